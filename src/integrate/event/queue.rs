//! The event queue: events ordered by time, then by kind (contacts and collapse first, then
//! joints stopping, then thresholds), then by the order they were found; stale events (of
//! clusters that changed since) are skipped when popped and purged when they pile up.

use super::cluster::{ClusterId, Clusters};
use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

/// The event queue is first rid of stale events when it reaches this size (see `push`).
const PURGE_FROM: usize = 1024;

/// What limits a cluster's displacement relative to a neighbour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Constraint {
    /// A vertical joint closing.
    Gap(usize),
    /// A horizontal joint's relative displacement crossing a collapse threshold.
    Collapse(usize),
}

/// An event of the queue, with the versions of the clusters it was found for: a cluster that
/// changed since makes it stale.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Ev {
    Threshold {
        k: ClusterId,
        ver: u64,
        upper: bool,
    },
    Stop {
        k: ClusterId,
        ver: u64,
        ground: u64,
    },
    GroundBound {
        k: ClusterId,
        ver: u64,
        ground: u64,
        c: Constraint,
    },
    Meet {
        a: ClusterId,
        va: u64,
        b: ClusterId,
        vb: u64,
    },
    PairBound {
        a: ClusterId,
        va: u64,
        b: ClusterId,
        vb: u64,
        c: Constraint,
    },
}

impl Ev {
    /// Simultaneous events are handled contacts and collapse first, then joints stopping, then
    /// thresholds, then in the order they were found.
    fn priority(&self) -> u8 {
        match self {
            Ev::GroundBound { .. } | Ev::PairBound { .. } => 0,
            Ev::Stop { .. } | Ev::Meet { .. } => 1,
            Ev::Threshold { .. } => 2,
        }
    }
}

/// A queued event: its time, and the order it was found in (ties keep it).
#[derive(Debug, Clone, Copy)]
pub(super) struct Pending {
    pub(super) t: f64,
    seq: u64,
    pub(super) ev: Ev,
}

impl PartialEq for Pending {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Pending {}
impl PartialOrd for Pending {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Pending {
    fn cmp(&self, o: &Self) -> Ordering {
        self.t
            .total_cmp(&o.t)
            .then(self.ev.priority().cmp(&o.ev.priority()))
            .then(self.seq.cmp(&o.seq))
    }
}

/// Is the event still one of the current clusters (their versions unchanged)?
pub(super) fn is_current(clusters: &Clusters, ev: &Ev) -> bool {
    let ok = |k: ClusterId, v: u64| {
        clusters
            .get(k)
            .is_some_and(|c| c.version == v && !c.blocks.is_empty())
    };
    match *ev {
        Ev::Threshold { k, ver, .. } => ok(k, ver),
        Ev::Stop { k, ver, ground } | Ev::GroundBound { k, ver, ground, .. } => {
            ok(k, ver) && clusters[k].ground_version == ground
        }
        Ev::Meet { a, va, b, vb } | Ev::PairBound { a, va, b, vb, .. } => ok(a, va) && ok(b, vb),
    }
}

/// The queue of pending events.
pub(super) struct Queue {
    heap: BinaryHeap<Reverse<Pending>>,
    /// The queue's size at which its stale events are next purged.
    purge_at: usize,
    seq: u64,
}

impl Default for Queue {
    fn default() -> Queue {
        Queue {
            heap: BinaryHeap::new(),
            purge_at: PURGE_FROM,
            seq: 0,
        }
    }
}

impl Queue {
    /// The first current event at or before `limit`, taken off the queue (the stale ones
    /// before it are dropped).
    pub(super) fn pop_until(&mut self, limit: f64, clusters: &Clusters) -> Option<Pending> {
        while let Some(Reverse(p)) = self.heap.peek().copied() {
            if p.t > limit {
                return None;
            }
            self.heap.pop();
            if is_current(clusters, &p.ev) {
                return Some(p);
            }
        }
        None
    }

    /// The time of the earliest current event (infinite if none).
    pub(super) fn earliest(&self, clusters: &Clusters) -> f64 {
        self.heap
            .iter()
            .filter(|p| is_current(clusters, &p.0.ev))
            .map(|p| p.0.t)
            .fold(f64::INFINITY, f64::min)
    }

    /// Queues an event. Events of clusters that have changed since go stale and are skipped
    /// when popped; on a large wall far more go stale than are popped (a pair's events are found
    /// up to the end of the run), so the queue is purged of them whenever it has doubled. The
    /// order of the events kept does not change.
    pub(super) fn push(&mut self, t: f64, ev: Ev, clusters: &Clusters) {
        self.seq += 1;
        self.heap.push(Reverse(Pending {
            t,
            seq: self.seq,
            ev,
        }));
        if self.heap.len() >= self.purge_at {
            let all = std::mem::take(&mut self.heap).into_vec();
            self.heap = all
                .into_iter()
                .filter(|Reverse(p)| is_current(clusters, &p.ev))
                .collect();
            self.purge_at = (2 * self.heap.len()).max(PURGE_FROM);
        }
    }
}
