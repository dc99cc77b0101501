//! The decisions' working memory, kept from one event to the next: the tables that give each
//! block its place in a decision problem and its set velocity ([`Local`], [`SetVel`]), the
//! buffers of a decision ([`Buffers`]), the groups it found ([`Decided`]), and what it changed
//! and installs ([`Before`], [`After`]).

use crate::exact::Q;
use crate::integrate::event::cluster::{ClusterId, Limits};
use crate::integrate::event::slip::Slip;
use crate::integrate::event::solver::{Group, Pieces, Problem};
use crate::sets::DisjointSets;
use rustc_hash::FxHashMap;

/// No local index: a block outside the decision problem.
pub(in crate::integrate::event) const NONE: usize = usize::MAX;

/// The local index of each block in a decision problem (`NONE` outside it): a table over all
/// blocks, because a decision can take in most of a large wall.
pub(in crate::integrate::event) struct Local(Vec<usize>);

impl Local {
    /// The table over n blocks, in the memory of an earlier one (all `NONE`) if given.
    pub(in crate::integrate::event) fn reuse(mut table: Vec<usize>, n: usize) -> Local {
        if table.len() != n {
            table = vec![NONE; n];
        }
        Local(table)
    }

    /// Empties the entries of `used` and hands the memory back.
    pub(in crate::integrate::event) fn release(mut self, used: &[usize]) -> Vec<usize> {
        for &b in used {
            self.0[b] = NONE;
        }
        self.0
    }

    pub(in crate::integrate::event) fn get(&self, b: &usize) -> Option<&usize> {
        Some(&self.0[*b]).filter(|&&k| k != NONE)
    }

    pub(super) fn contains_key(&self, b: &usize) -> bool {
        self.0[*b] != NONE
    }

    pub(in crate::integrate::event) fn insert(&mut self, b: usize, k: usize) {
        self.0[b] = k;
    }
}

/// Velocities set for the decision (m/s), over all blocks (NaN: none set): where a block stops,
/// where two clusters meet, after an impact, and where round-off was evened out.
pub(super) struct SetVel {
    vel: Vec<f64>,
    set: Vec<usize>,
}

impl SetVel {
    /// The table over n blocks, in the memory of an earlier one (all NaN) if given.
    pub(super) fn reuse(mut vel: Vec<f64>, mut set: Vec<usize>, n: usize) -> SetVel {
        if vel.len() != n {
            vel = vec![f64::NAN; n];
        }
        set.clear();
        SetVel { vel, set }
    }

    pub(super) fn get(&self, b: usize) -> Option<f64> {
        Some(self.vel[b]).filter(|v| !v.is_nan())
    }

    pub(super) fn insert(&mut self, b: usize, v: f64) {
        if self.vel[b].is_nan() {
            self.set.push(b);
        }
        self.vel[b] = v;
    }

    /// Empties the table and hands the memory back.
    pub(super) fn release(mut self) -> (Vec<f64>, Vec<usize>) {
        for &b in &self.set {
            self.vel[b] = f64::NAN;
        }
        (self.vel, self.set)
    }
}

impl std::ops::Index<&usize> for Local {
    type Output = usize;

    fn index(&self, b: &usize) -> &usize {
        self.get(b).expect("block in the problem")
    }
}

/// Working memory of the decisions, kept from one event to the next (allocated afresh at every
/// decision it cost the paper's wall about 5 % of its run). Between decisions every vector is
/// empty and `local` is all `NONE`.
#[derive(Default)]
pub(in crate::integrate::event) struct Buffers {
    /// The table of [`Local`].
    pub(in crate::integrate::event) local: Vec<usize>,
    /// The table of [`SetVel`] and the blocks set in it.
    pub(super) set_vel: Vec<f64>,
    pub(super) set_vel_blocks: Vec<usize>,
    /// The component's blocks, and the queue that gathers them.
    pub(in crate::integrate::event) blocks: Vec<usize>,
    pub(super) queue: Vec<usize>,
    /// The clusters the component's blocks belonged to.
    pub(super) old: Vec<ClusterId>,
    /// The horizontal and vertical joints at the component's blocks.
    pub(super) horizontal: Vec<usize>,
    pub(super) vertical: Vec<usize>,
    /// The decision problem.
    pub(in crate::integrate::event) problem: Problem,
    /// The blocks' displacements and velocities (m, m/s), and the new group of each.
    pub(super) u: Vec<f64>,
    pub(super) v: Vec<f64>,
    pub(super) group_of: Vec<usize>,
    /// What the decision found.
    pub(super) decided: Decided,
    /// Of the velocities made equal.
    pub(super) equal: Equal,
}

/// Working memory of `Engine::equalize_velocities`: the sets of blocks whose velocities are
/// equal within round-off, which of them touch the ground, and each block by its set.
#[derive(Default)]
pub(in crate::integrate::event) struct Equal {
    pub(super) sets: DisjointSets,
    pub(super) grounded: Vec<bool>,
    pub(super) by_set: Vec<(usize, usize)>,
}

/// What a component's decision found (step 4 of `Engine::regroup`): its groups (local block
/// indices), the stick interval of each group shown stuck by its piece (`None` for the
/// others), and while it is being found, the pieces of the problem and the blocks left to the
/// general decision. The node lists of earlier groups are kept for the next, so a decision met
/// again allocates nothing.
#[derive(Default)]
pub(in crate::integrate::event) struct Decided {
    pub(in crate::integrate::event) groups: Vec<Group>,
    pub(in crate::integrate::event) intervals: Vec<Option<Limits>>,
    pub(in crate::integrate::event) pieces: Pieces,
    pub(in crate::integrate::event) rest: Vec<usize>,
    spare: Vec<Vec<usize>>,
}

impl Decided {
    /// Empties every part, keeping the memory.
    pub(in crate::integrate::event) fn clear(&mut self) {
        for g in self.groups.drain(..) {
            let mut nodes = g.nodes;
            nodes.clear();
            self.spare.push(nodes);
        }
        self.intervals.clear();
        self.rest.clear();
    }

    /// The groups of a general decision (no interval: they were not shown stuck by a piece).
    pub(in crate::integrate::event) fn push_decided(&mut self, groups: &[Group]) {
        for g in groups {
            self.push(g.nodes.iter().copied(), g.accel.clone(), g.grounded, None);
        }
    }

    /// One more group, with its stick interval if its piece showed it stuck.
    pub(in crate::integrate::event) fn push(
        &mut self,
        nodes: impl IntoIterator<Item = usize>,
        accel: Q,
        grounded: bool,
        interval: Option<Limits>,
    ) {
        let mut list = self.spare.pop().unwrap_or_default();
        list.extend(nodes);
        self.groups.push(Group {
            nodes: list,
            accel,
            grounded,
        });
        self.intervals.push(interval);
    }
}

/// The state a decision changed, for the stick intervals worked out after it
/// (`Engine::kept_limits`): the cluster each block of the component was in, the limits of
/// those clusters (`None`: it slid), and the joints whose direction it turned. Everything else
/// is as it was.
#[derive(Debug, Default)]
pub(in crate::integrate::event) struct Before {
    pub(in crate::integrate::event) of: FxHashMap<usize, ClusterId>,
    pub(in crate::integrate::event) limits: FxHashMap<ClusterId, Option<[Option<Q>; 2]>>,
    pub(in crate::integrate::event) slip: FxHashMap<usize, Slip>,
}

/// Working memory of what a decision installs and updates after its [`Buffers`] went back
/// (those serve the decisions this part may start): the state it changed, its new clusters,
/// those of them that need a stick interval, the clusters beside it, those of them whose
/// friction changed, and the sliding ones left as they were. Empty between decisions; a
/// decision started from inside another finds them taken and works in fresh memory.
#[derive(Default)]
pub(in crate::integrate::event) struct After {
    pub(super) before: Before,
    pub(super) new_clusters: Vec<ClusterId>,
    pub(super) needs_interval: Vec<ClusterId>,
    pub(super) neighbours: Vec<ClusterId>,
    pub(super) pushed: Vec<ClusterId>,
    pub(super) quiet: Vec<ClusterId>,
}

impl After {
    /// Empties every part, keeping the memory.
    pub(super) fn cleared(mut self) -> After {
        self.before.of.clear();
        self.before.limits.clear();
        self.before.slip.clear();
        for v in [
            &mut self.new_clusters,
            &mut self.needs_interval,
            &mut self.neighbours,
            &mut self.pushed,
            &mut self.quiet,
        ] {
            v.clear();
        }
        self
    }
}
