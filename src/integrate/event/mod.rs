//! The exact event-driven integrator (design note `event-driven.md`).
//!
//! No time step: between events every cluster moves in closed form (`cluster`); events are
//! roots of closed-form functions, located to round-off ([`roots`]); at each event the new mode
//! is decided exactly ([`decide`]) and impacts are resolved exactly ([`impact`]). Work per event
//! touches only the clusters whose mode changed and their neighbours; a stuck cluster costs one
//! threshold check per segment of the ground motion.

mod cluster;
pub mod decide;
mod decision;
pub mod flow;
pub mod impact;
mod memo;
pub mod roots;
mod schedule;

use crate::error::SimulationError;
use crate::exact::Q;
use crate::integrate::{AfterCollapse, Integrator, Progress, Scenario};
use crate::motion::{Motion, Segment};
use crate::response::{Collapse, DecisionCause as Cause, EventKind, Recorder, Response};
use crate::topology::{Base, Topology};
use crate::wall::Wall;
use cluster::{Cluster, Motion as ClusterMotion};
use memo::Memo;
use roots::{Counter, Fun};
use std::cmp::{Ordering, Reverse};
use std::collections::{BinaryHeap, HashMap, VecDeque};

/// Settings of the event-driven integrator. None is a tolerance: the first two only stop a run
/// that would otherwise never end, with an error that says where; the others change the work,
/// never the answer.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// Events allowed at one instant.
    pub max_events_per_instant: usize,
    /// Pairwise collisions allowed in one impact chain.
    pub max_collisions_per_chain: usize,
    /// A stuck group of at least this many blocks that a decision leaves, forms or turns a
    /// joint of keeps the limits its change cannot have narrowed, as bounds, and works them out
    /// only when a_g reaches them (`usize::MAX`: always at once). Below it, working a limit out
    /// costs less than the event a bound may add.
    pub kept_limits_from: usize,
    /// A decision at the ground over a stuck group of at least this many blocks and a few
    /// blocks beside it decides those few with the group held at a_g, and the group from its
    /// stick interval, where that shows the answer (`usize::MAX`: never). Below it, the
    /// decision over the whole piece costs no more.
    pub beside_stuck_from: usize,
}

impl Default for Params {
    fn default() -> Params {
        Params {
            max_events_per_instant: 10_000,
            max_collisions_per_chain: 100_000,
            kept_limits_from: KEPT_LIMITS_FROM,
            beside_stuck_from: BESIDE_STUCK_FROM,
        }
    }
}

/// The default of [`Params::kept_limits_from`].
const KEPT_LIMITS_FROM: usize = 256;

/// The default of [`Params::beside_stuck_from`].
const BESIDE_STUCK_FROM: usize = 256;

/// The property tests' configuration: many cases (each is cheap), and no regression file, which
/// would sit at the top level.
#[cfg(test)]
pub(crate) fn many_cheap_cases() -> proptest::test_runner::Config {
    proptest::test_runner::Config {
        cases: 3000,
        failure_persistence: None,
        ..Default::default()
    }
}

/// The exact event-driven integrator.
#[derive(Debug, Clone, Default)]
pub struct EventDriven {
    /// Safeguards.
    pub params: Params,
}

impl Integrator for EventDriven {
    fn method(&self) -> &'static str {
        "event"
    }

    fn run(&self, scenario: &Scenario) -> Result<Response, SimulationError> {
        Engine::new(scenario, &self.params)?.run()
    }
}

/// Positions and velocities carry round-off of a few ulps of the largest magnitudes that enter
/// them (block coordinates, ground displacement, block displacement). Quantities within this many
/// ulps of zero are zero: a gap that closes to within it is touching, an approach speed within it
/// is a touch, not an impact.
const ROUNDOFF_ULPS: f64 = 1024.0;

/// Events closer together than this many ulps of time count as one instant for the progress
/// guard ([`Params::max_events_per_instant`]).
const PROGRESS_WINDOW_ULPS: f64 = 1e6;

/// Marks a block that belongs to no cluster (fixed or fallen).
const NONE: usize = usize::MAX;

/// The event queue is first rid of stale events when it reaches this size (see `push`).
const PURGE_FROM: usize = 1024;

/// What limits a cluster's displacement relative to a neighbour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Constraint {
    /// A vertical joint closing.
    Gap(usize),
    /// A support's relative displacement crossing a collapse threshold.
    Collapse(usize),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Ev {
    Threshold {
        k: usize,
        ver: u64,
        upper: bool,
    },
    Stop {
        k: usize,
        ver: u64,
        ground: u64,
    },
    GroundBound {
        k: usize,
        ver: u64,
        ground: u64,
        c: Constraint,
    },
    Meet {
        a: usize,
        va: u64,
        b: usize,
        vb: u64,
    },
    PairBound {
        a: usize,
        va: u64,
        b: usize,
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

#[derive(Debug, Clone, Copy)]
struct Pending {
    t: f64,
    seq: u64,
    ev: Ev,
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

/// The blocks an impact reaches through touching faces ([`impact::resolve`]'s input).
struct Chain {
    /// Each block with its mass and velocity; the ground and abutments have no mass.
    bodies: Vec<(usize, impact::Body)>,
    /// Touching faces (left body, right body, joint), left to right.
    faces: Vec<(usize, usize, usize)>,
}

pub(crate) struct Engine<'a> {
    wall: &'a Wall,
    topo: &'a Topology,
    motion: &'a Motion,
    after_collapse: AfterCollapse,
    params: &'a Params,
    n: usize,
    mass: Vec<f64>,
    mass_q: Vec<Q>,
    cap: Vec<f64>,
    cap_q: Vec<Q>,
    fixed: Vec<bool>,
    fallen: Vec<bool>,
    xl: Vec<f64>,
    xr: Vec<f64>,
    xc: Vec<f64>,
    gap0: Vec<f64>,
    restitution: Q,
    t: f64,
    t_end: f64,
    progress: Option<Progress>,
    seg: Segment,
    of: Vec<usize>,
    clusters: Vec<Cluster>,
    free: Vec<usize>,
    u_ref: Vec<f64>,
    /// Per support: sliding direction of the upper block relative to the lower (+1, -1), 0 = stuck.
    dir: Vec<i8>,
    /// Per vertical joint: the faces touch.
    touching: Vec<bool>,
    /// Per support: relative displacement when friction work was last accounted.
    d_last: Vec<f64>,
    /// Per support: when friction work was last accounted (s).
    t_fric: Vec<f64>,
    heap: BinaryHeap<Reverse<Pending>>,
    /// The queue's size at which its stale events are next purged.
    purge_at: usize,
    seq: u64,
    version: u64,
    rec: Recorder,
    output_dt: Option<f64>,
    output_k: u64,
    instant: (f64, usize),
    len_scale: f64,
    vel_scale: f64,
    count: Counter,
    stopped: bool,
    /// Stick intervals already worked out, by problem, with the blocks that leave at each limit.
    stick_memo: Memo<decide::Problem, decide::Stick>,
    /// Sets of blocks (global indices, sorted) that broke away at recent stick limits, newest
    /// first: hints for the next stick intervals.
    breaking: VecDeque<Vec<usize>>,
    /// Decisions already worked out, by problem, and under it by ground acceleration (a
    /// problem meets few: it is looked up without building a key).
    free_memo: Memo<decide::Problem, Vec<(decide::Lex, Vec<decide::Group>)>>,
    /// Working memory of the decisions.
    buffers: decision::Buffers,
    /// Working memory of the scheduling: pairs of sliding clusters (empty between calls).
    pairs: Vec<(usize, usize)>,
}

impl<'a> Engine<'a> {
    fn new(sc: &Scenario<'a>, params: &'a Params) -> Result<Engine<'a>, SimulationError> {
        let (wall, topo) = (sc.wall, sc.topology);
        let n = wall.blocks.len();
        let t_end = sc.settings.duration_s;
        if !(t_end.is_finite() && t_end > 0.0) {
            return Err(SimulationError::Invalid(format!(
                "duration {t_end} s: it must be positive"
            )));
        }
        if let Some(dt) = sc.settings.output_dt_s {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(SimulationError::Invalid(format!(
                    "output interval {dt} s: it must be positive"
                )));
            }
        }
        let mass_q: Vec<Q> = topo.blocks.iter().map(|b| b.mass_kg.clone()).collect();
        let cap_q: Vec<Q> = topo.supports.iter().map(|s| s.capacity_n.clone()).collect();
        let f = |v: &[Q]| v.iter().map(Q::to_f64).collect::<Vec<f64>>();
        // Over the whole motion, so a run's round-off scales, and with them its answer up to any
        // instant, do not depend on how long it is asked to run.
        let (v_max, d_max) = motion_bounds(sc.motion, t_end.max(sc.motion.duration_s()));
        let extent: f64 = wall
            .blocks
            .iter()
            .map(|b| b.right().to_f64().abs().max(b.top().to_f64()))
            .fold(1.0, f64::max);
        let seg = sc.motion.segment_at(0.0);
        let mut rec = Recorder::new(
            wall,
            topo,
            sc.settings.output_dt_s.is_some(),
            sc.settings.log_events,
        );
        rec.decisions = sc.settings.log_decisions.then(Vec::new);
        Ok(Engine {
            wall,
            topo,
            motion: sc.motion,
            after_collapse: sc.settings.after_collapse,
            params,
            n,
            mass: f(&mass_q),
            mass_q,
            cap: f(&cap_q),
            cap_q,
            fixed: wall.blocks.iter().map(|b| b.fixed).collect(),
            fallen: vec![false; n],
            xl: wall.blocks.iter().map(|b| b.x.to_f64()).collect(),
            xr: wall.blocks.iter().map(|b| b.right().to_f64()).collect(),
            xc: wall
                .blocks
                .iter()
                .map(|b| b.centroid_x().to_f64())
                .collect(),
            gap0: topo.joints.iter().map(|j| j.gap_m.to_f64()).collect(),
            restitution: wall.restitution.clone(),
            t: 0.0,
            t_end,
            progress: sc.settings.progress.clone(),
            seg,
            of: vec![NONE; n],
            clusters: Vec::new(),
            free: Vec::new(),
            u_ref: vec![0.0; n],
            dir: vec![0; topo.supports.len()],
            touching: topo.joints.iter().map(|j| j.gap_m.is_zero()).collect(),
            d_last: vec![0.0; topo.supports.len()],
            t_fric: vec![0.0; topo.supports.len()],
            heap: BinaryHeap::new(),
            purge_at: PURGE_FROM,
            seq: 0,
            version: 0,
            rec,
            output_dt: sc.settings.output_dt_s,
            output_k: 0,
            instant: (f64::NEG_INFINITY, 0),
            len_scale: extent + d_max,
            vel_scale: v_max + 1e-3,
            count: Counter::default(),
            stopped: false,
            stick_memo: Memo::new(),
            breaking: VecDeque::new(),
            free_memo: Memo::new(),
            buffers: decision::Buffers::default(),
            pairs: Vec::new(),
        })
    }

    fn run(mut self) -> Result<Response, SimulationError> {
        // The flow passes counted from here on are this run's (a failed run on this thread
        // may have left some).
        flow::take_pass_nodes();
        // At rest at t = 0: every block is undecided against the ground.
        let seeds: Vec<usize> = (0..self.n).filter(|&i| !self.fixed[i]).collect();
        self.decide_from(&seeds, &[], None, Cause::Start)?;
        loop {
            let seg_end = self.seg.t1.min(self.t_end);
            match self.pop_until(seg_end) {
                Some(p) => {
                    self.output_until(p.t);
                    self.t = p.t;
                    self.rec.stats.events += 1;
                    self.progress_guard(&p)?;
                    self.handle(p.ev)?;
                    if self.stopped {
                        break;
                    }
                }
                None => {
                    self.output_until(seg_end);
                    self.t = seg_end;
                    if let Some(p) = &self.progress {
                        p.at(seg_end);
                    }
                    if seg_end >= self.t_end {
                        break;
                    }
                    self.enter_segment(seg_end);
                }
            }
        }
        Ok(self.finish())
    }

    /// Events piling up at one instant, or creeping forward by a few ulps, mean the run would
    /// never end: stop with an error that says where. Within `PROGRESS_WINDOW_ULPS` ulps of
    /// time counts as the same instant.
    fn progress_guard(&mut self, p: &Pending) -> Result<(), SimulationError> {
        let window = PROGRESS_WINDOW_ULPS * f64::EPSILON * self.instant.0.abs().max(1.0);
        // The first event opens the first instant (before it, `instant` is -inf).
        if self.instant.0.is_finite() && p.t - self.instant.0 <= window {
            self.instant.1 += 1;
            if self.instant.1 > self.params.max_events_per_instant {
                return Err(SimulationError::NoProgress {
                    time_s: p.t,
                    count: self.instant.1,
                    detail: format!("{:?}", p.ev),
                });
            }
        } else {
            self.instant = (p.t, 1);
        }
        Ok(())
    }

    fn pop_until(&mut self, limit: f64) -> Option<Pending> {
        while let Some(Reverse(p)) = self.heap.peek().copied() {
            if p.t > limit {
                return None;
            }
            self.heap.pop();
            if self.is_current(&p.ev) {
                return Some(p);
            }
        }
        None
    }

    fn is_current(&self, ev: &Ev) -> bool {
        let ok = |k: usize, v: u64| {
            self.clusters
                .get(k)
                .is_some_and(|c| c.version == v && !c.blocks.is_empty())
        };
        match *ev {
            Ev::Threshold { k, ver, .. } => ok(k, ver),
            Ev::Stop { k, ver, ground } | Ev::GroundBound { k, ver, ground, .. } => {
                ok(k, ver) && self.clusters[k].ground_version == ground
            }
            Ev::Meet { a, va, b, vb } | Ev::PairBound { a, va, b, vb, .. } => {
                ok(a, va) && ok(b, vb)
            }
        }
    }

    /// Queues an event. Events of clusters that have changed since go stale and are skipped
    /// when popped; on a large wall far more go stale than are popped (a pair's events are found
    /// up to the end of the run), so the queue is purged of them whenever it has doubled. The
    /// order of the events kept does not change.
    fn push(&mut self, t: f64, ev: Ev) {
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
                .filter(|Reverse(p)| self.is_current(&p.ev))
                .collect();
            self.purge_at = (2 * self.heap.len()).max(PURGE_FROM);
        }
    }

    fn s(&self) -> f64 {
        self.t - self.seg.t0
    }

    /// Displacement gained by cluster k since it formed (m), at the current time.
    fn cluster_disp(&self, k: usize) -> f64 {
        self.clusters[k].slide().map_or(0.0, |sl| sl.disp(self.t))
    }

    /// Velocity of cluster k relative to the ground (m/s), at the current time.
    fn cluster_vel(&self, k: usize) -> f64 {
        self.clusters[k].slide().map_or(0.0, |sl| sl.vel(self.t))
    }

    fn block_disp(&self, i: usize) -> f64 {
        match self.of[i] {
            NONE => self.u_ref[i],
            k => self.u_ref[i] + self.cluster_disp(k),
        }
    }

    fn block_vel(&self, i: usize) -> f64 {
        match self.of[i] {
            NONE => 0.0,
            k => self.cluster_vel(k),
        }
    }

    /// True for the ground side of a joint: the ground, an abutment, or a block stuck to the
    /// ground.
    fn grounded(&self, i: usize) -> bool {
        self.of[i] == NONE
            || matches!(
                self.clusters[self.of[i]].motion,
                ClusterMotion::Stuck { .. }
            )
    }

    fn len_tol(&self, a: f64, b: f64) -> f64 {
        ROUNDOFF_ULPS * f64::EPSILON * (self.len_scale + a.abs() + b.abs())
    }

    fn vel_tol(&self, a: f64, b: f64) -> f64 {
        ROUNDOFF_ULPS * f64::EPSILON * (self.vel_scale + a.abs() + b.abs())
    }

    /// The lower block of a support, if it is a block that can move.
    fn lower_block(&self, s: usize) -> Option<usize> {
        match self.topo.supports[s].lower {
            Base::Ground => None,
            Base::Block(b) => Some(b.0),
        }
    }

    /// A support still in the model (neither end fell).
    fn live_support(&self, s: usize) -> bool {
        let sup = &self.topo.supports[s];
        !self.fallen[sup.upper.0] && self.lower_block(s).is_none_or(|l| !self.fallen[l])
    }

    /// The blocks of cluster k that have a support or a face to the ground or to a block
    /// outside it ([`Cluster::boundary`](cluster::Cluster)): a large body's contacts with the
    /// rest of the wall, found from a fraction of its blocks.
    fn boundary(&self, k: usize) -> &[usize] {
        self.clusters[k].boundary.get_or_init(|| {
            let outside = |o: usize| self.of[o] != k;
            self.clusters[k]
                .blocks
                .iter()
                .copied()
                .filter(|&i| {
                    let supports = self.topo.below[i].iter().chain(&self.topo.above[i]);
                    let across_support = supports.map(|s| self.across_support(s.0, i));
                    let faces = self.topo.sides[i].iter().map(|j| self.across_joint(j.0, i));
                    across_support
                        .chain(faces.map(Some))
                        .any(|o| o.is_none_or(outside))
                })
                .collect()
        })
    }

    /// The other ends of block `b`'s live supports (under and over it); `None` is the ground.
    fn live_neighbours(&self, b: usize) -> impl Iterator<Item = Option<usize>> + '_ {
        self.topo.below[b]
            .iter()
            .chain(&self.topo.above[b])
            .filter(|s| self.live_support(s.0))
            .map(move |s| self.across_support(s.0, b))
    }

    /// The block across support s from block b; `None` is the ground.
    fn across_support(&self, s: usize, b: usize) -> Option<usize> {
        let upper = self.topo.supports[s].upper.0;
        if upper == b {
            self.lower_block(s)
        } else {
            Some(upper)
        }
    }

    /// The block across vertical joint j from block b.
    fn across_joint(&self, j: usize, b: usize) -> usize {
        let jt = &self.topo.joints[j];
        if jt.left.0 == b {
            jt.right.0
        } else {
            jt.left.0
        }
    }

    fn live_joint(&self, j: usize) -> bool {
        let jt = &self.topo.joints[j];
        !self.fallen[jt.left.0] && !self.fallen[jt.right.0]
    }

    fn gap(&self, j: usize) -> f64 {
        let jt = &self.topo.joints[j];
        self.gap0[j] + self.block_disp(jt.right.0) - self.block_disp(jt.left.0)
    }

    fn support_d(&self, s: usize) -> f64 {
        let sup = &self.topo.supports[s];
        self.block_disp(sup.upper.0) - self.lower_block(s).map_or(0.0, |l| self.block_disp(l))
    }

    fn new_version(&mut self) -> u64 {
        self.version += 1;
        self.version
    }

    fn enter_segment(&mut self, t: f64) {
        if self.seg.has_vertical() {
            // Friction work with a varying capacity is integrated segment by segment.
            for s in 0..self.topo.supports.len() {
                self.account_support(s);
            }
        }
        // A sliding cluster's closed form is rebased on the new segment: what it did on this
        // one is booked first. A stuck one moves with the ground, whatever the segment, and is
        // booked when it dissolves (a stuck wall costs nothing per block and segment).
        for k in 0..self.clusters.len() {
            if !self.clusters[k].blocks.is_empty() && self.clusters[k].slide().is_some() {
                self.account(k, t);
            }
        }
        self.seg = self.motion.segment_at(t);
        self.rec.stats.segments += 1;
        let seg = self.seg;
        for c in &mut self.clusters {
            if let ClusterMotion::Sliding(sl) = &mut c.motion {
                if !c.blocks.is_empty() {
                    sl.rebase(&seg);
                    c.roots = None;
                    c.ground_hits = None;
                }
            }
        }
        if self.motion.has_vertical() {
            // Relative motion of sliding clusters involves lambda(t): re-found per segment.
            let live: Vec<usize> = (0..self.clusters.len())
                .filter(|&k| !self.clusters[k].blocks.is_empty())
                .collect();
            self.schedule(live);
        } else {
            for k in 0..self.clusters.len() {
                if !self.clusters[k].blocks.is_empty() {
                    self.schedule_segment(k);
                }
            }
        }
    }

    /// Energy input and displacement/velocity extremes of every sliding cluster up to t.
    fn account_all(&mut self, t: f64) {
        for k in 0..self.clusters.len() {
            if !self.clusters[k].blocks.is_empty() {
                self.account(k, t);
            }
        }
    }

    /// Energy input and extremes of cluster k from where it was accounted to t (same segment).
    fn account(&mut self, k: usize, t: f64) {
        let t_a = self.clusters[k].accounted_to;
        self.clusters[k].accounted_to = t;
        let Some(sl) = self.clusters[k].slide().cloned() else {
            // Stuck blocks move with the ground.
            if t > t_a {
                let (lo, hi) = self.motion.accel_range(t_a, t);
                let peak = &mut self.clusters[k].extremes.accel_m_s2;
                *peak = peak.max(lo.abs().max(hi.abs()));
            }
            return;
        };
        let peak = sl.absolute_accel(t_a).abs().max(sl.absolute_accel(t).abs());
        let accel = &mut self.clusters[k].extremes.accel_m_s2;
        *accel = accel.max(peak);
        if t <= t_a {
            return;
        }
        self.rec.energy.input_j += self.clusters[k].mass * sl.input_work_per_kg(t_a, t);
        // The cluster's zeros, found when it was scheduled on this segment (kept for later
        // accounts), or found now.
        let cached = self.clusters[k].roots.take();
        let fresh = match &cached {
            Some(r) if r.from <= t_a && t <= r.to => None,
            _ => Some(self.zeros(&sl, t_a, t)),
        };
        let roots = fresh.as_ref().or(cached.as_ref()).expect("found or cached");
        let inside = |x: &&f64| **x > t_a && **x < t;
        let vel = |x: f64| sl.vel(x);
        let (d_a, d_t) = (sl.disp(t_a), sl.disp(t));
        let (mut lo, mut hi) = (d_a.min(d_t), d_a.max(d_t));
        for &r in roots.v_zero.iter().filter(inside) {
            let x = sl.disp(r);
            lo = lo.min(x);
            hi = hi.max(x);
        }
        let mut vmax = vel(t_a).abs().max(vel(t).abs());
        for &r in roots.a_zero.iter().filter(inside) {
            vmax = vmax.max(vel(r).abs());
        }
        self.clusters[k].roots = cached;
        let e = &mut self.clusters[k].extremes;
        e.disp_m = Some(e.disp_m.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))));
        e.vel_m_s = e.vel_m_s.max(vmax);
    }

    /// Hands cluster k's extremes to its blocks: before their references change, and at the end.
    fn record_extremes(&mut self, k: usize) {
        let e = std::mem::take(&mut self.clusters[k].extremes);
        for &i in &self.clusters[k].blocks {
            self.rec.block_accel(i, e.accel_m_s2);
            if let Some((lo, hi)) = e.disp_m {
                let u = (self.u_ref[i] + lo).abs().max((self.u_ref[i] + hi).abs());
                self.rec.block_extremes(i, u, e.vel_m_s);
            }
        }
    }

    /// Zeros of a sliding cluster's relative acceleration and velocity in [t_a, t_b], to the last
    /// bit (they are split points of its event functions).
    fn zeros(&mut self, sl: &cluster::Slide, t_a: f64, t_b: f64) -> cluster::Roots {
        let acc = |x: f64| sl.acc(x);
        let vel = |x: f64| sl.vel(x);
        let vel_acc = |x: f64| {
            let (_, v, a) = sl.state(x);
            (v, a)
        };
        // The relative acceleration c - a_g vanishes where a_g = c: closed form on the
        // monotone arc, then the exact float.
        let (fa, fb) = (acc(t_a), acc(t_b));
        let mut a_zero = Vec::new();
        if (fa > 0.0 && fb <= 0.0) || (fa < 0.0 && fb >= 0.0) {
            let seg = &sl.anchor;
            let guess = seg
                .time_of_ratio(sl.c, t_a - seg.t0, t_b - seg.t0)
                .map_or(0.5 * (t_a + t_b), |s| seg.t0 + s);
            let t = if fa > 0.0 {
                roots::polish(&acc, guess, t_a, t_b, &mut self.count)
            } else {
                roots::polish(&|x| -acc(x), guess, t_a, t_b, &mut self.count)
            };
            if t < t_b {
                a_zero.push(t);
            }
        }
        let v_zero = roots::sign_changes(
            Fun::with(&vel, &vel_acc),
            t_a,
            t_b,
            &a_zero,
            0.0,
            &mut self.count,
        );
        cluster::Roots {
            from: t_a,
            to: t_b,
            a_zero,
            v_zero,
        }
    }

    /// Friction work on support s since it was last accounted, and its displacement extreme.
    /// With vertical shaking the capacity is F lambda(t): the work is F sigma (lambda d |_a^b -
    /// lambda' integral d dt) over the stretch (within one segment).
    fn account_support(&mut self, s: usize) {
        if !self.live_support(s) {
            return;
        }
        let d = self.support_d(s);
        let t_a = self.t_fric[s];
        if self.seg.has_vertical() && self.dir[s] != 0 {
            let seg = self.seg;
            let (la, lb) = (seg.lambda_at(t_a - seg.t0), seg.lambda_at(self.t - seg.t0));
            let integral = self.block_disp_integral(self.topo.supports[s].upper.0, t_a)
                - self
                    .lower_block(s)
                    .map_or(0.0, |l| self.block_disp_integral(l, t_a));
            let work =
                f64::from(self.dir[s]) * (lb * d - la * self.d_last[s] - seg.lambda.1 * integral);
            self.rec.energy.friction_j += self.cap[s] * work;
        } else {
            self.rec.energy.friction_j += self.cap[s] * (d - self.d_last[s]).abs();
        }
        self.d_last[s] = d;
        self.t_fric[s] = self.t;
        self.rec.joint_extreme(s, d.abs());
    }

    /// Integral of block i's displacement from t_a to now (m s), within the current segment.
    fn block_disp_integral(&self, i: usize, t_a: f64) -> f64 {
        let span = self.t - t_a;
        match self.of[i] {
            NONE => self.u_ref[i] * span,
            k => {
                self.u_ref[i] * span
                    + self.clusters[k]
                        .slide()
                        .map_or(0.0, |sl| sl.disp_integral(t_a, self.t))
            }
        }
    }

    fn output_until(&mut self, t: f64) {
        let Some(dt) = self.output_dt else { return };
        loop {
            let tk = self.output_k as f64 * dt;
            if tk > t || tk > self.t_end {
                return;
            }
            let saved = self.t;
            self.t = tk;
            self.sample();
            self.t = saved;
            self.output_k += 1;
        }
    }

    fn sample(&mut self) {
        if !self.rec.wants_history() {
            return;
        }
        let u: Vec<f64> = (0..self.n).map(|i| self.block_disp(i)).collect();
        let v: Vec<f64> = (0..self.n)
            .map(|i| {
                if self.fallen[i] {
                    0.0
                } else {
                    self.block_vel(i)
                }
            })
            .collect();
        self.rec.sample(self.t, &u, &v);
    }

    fn handle(&mut self, ev: Ev) -> Result<(), SimulationError> {
        match ev {
            Ev::Threshold { k, upper, .. } => {
                let side = usize::from(upper);
                let limit = |motion: &ClusterMotion| match motion {
                    ClusterMotion::Stuck { lo_q, hi_q, .. } => [lo_q, hi_q][side].clone(),
                    ClusterMotion::Sliding(_) => None,
                };
                let bound = limit(&self.clusters[k].motion);
                if matches!(&self.clusters[k].motion, ClusterMotion::Stuck { bound_only, .. } if bound_only[side])
                {
                    // a_g has reached a bound: the exact limit is at it or beyond. Beyond it,
                    // nothing happens (no history row either: the run is the same as if the
                    // limit had been worked out at once).
                    self.set_exact_thresholds(k);
                    if limit(&self.clusters[k].motion) != bound {
                        self.clusters[k].version = self.new_version();
                        self.schedule([k]);
                        return Ok(());
                    }
                }
                let limit = bound;
                // Snap a_g to the limit only when it is there. A stuck cluster whose neighbours
                // changed gets a new interval that a_g may already lie beyond; it is decided
                // with the a_g it has (snapping would keep it stuck and fire again, forever).
                let (ag, lambda) = (self.seg.accel(self.s()), self.seg.lambda_at(self.s()));
                let snap = limit.filter(|q| {
                    let at = q.to_f64() * lambda;
                    (ag - at).abs() <= ROUNDOFF_ULPS * f64::EPSILON * (ag.abs() + at.abs())
                });
                let seeds = self.clusters[k].blocks.clone();
                self.decide_from(&seeds, &[], snap, Cause::StickLimit)?;
            }
            Ev::Stop { k, .. } => {
                let seeds = self.clusters[k].blocks.clone();
                let snap: Vec<(usize, f64)> = seeds.iter().map(|&i| (i, 0.0)).collect();
                self.decide_from(&seeds, &snap, None, Cause::Stop)?;
            }
            Ev::Meet { a, b, .. } => {
                let (ma, mb) = (self.clusters[a].mass, self.clusters[b].mass);
                let v = (ma * self.cluster_vel(a) + mb * self.cluster_vel(b)) / (ma + mb);
                let seeds: Vec<usize> = self.clusters[a]
                    .blocks
                    .iter()
                    .chain(&self.clusters[b].blocks)
                    .copied()
                    .collect();
                let snap: Vec<(usize, f64)> = seeds.iter().map(|&i| (i, v)).collect();
                self.decide_from(&seeds, &snap, None, Cause::Meet)?;
            }
            Ev::GroundBound { k, c, .. } => self.constraint_reached(k, None, c)?,
            Ev::PairBound { a, b, c, .. } => self.constraint_reached(a, Some(b), c)?,
        }
        if self.rec.wants_history() {
            self.sample();
        }
        Ok(())
    }

    fn constraint_reached(
        &mut self,
        a: usize,
        b: Option<usize>,
        c: Constraint,
    ) -> Result<(), SimulationError> {
        match c {
            Constraint::Gap(j) => self.faces_meet(j),
            Constraint::Collapse(s) => {
                let upper = self.topo.supports[s].upper.0;
                if self.stands(upper) {
                    // A threshold of the support span passed without toppling: look further.
                    for k in std::iter::once(a).chain(b) {
                        let v = self.new_version();
                        self.clusters[k].version = v;
                    }
                    self.schedule(std::iter::once(a).chain(b));
                    Ok(())
                } else {
                    self.collapse(upper)
                }
            }
        }
    }

    /// A vertical joint closes: an impact if the faces approach, a touch otherwise.
    fn faces_meet(&mut self, j: usize) -> Result<(), SimulationError> {
        let (l, r) = (self.topo.joints[j].left.0, self.topo.joints[j].right.0);
        self.touching[j] = true;
        if self.approaching(j) {
            return self.impact(j);
        }
        let (vl, vr) = (self.block_vel(l), self.block_vel(r));
        self.rec.touches += 1;
        self.rec.event(
            self.t,
            EventKind::Touch,
            &[l, r],
            Some(self.joint_label(j)),
            None,
        );
        let v = match (self.grounded(l), self.grounded(r)) {
            (true, _) | (_, true) => 0.0,
            _ => {
                let (ml, mr) = (
                    self.clusters[self.of[l]].mass,
                    self.clusters[self.of[r]].mass,
                );
                (ml * vl + mr * vr) / (ml + mr)
            }
        };
        let mut seeds = Vec::new();
        for i in [l, r] {
            if self.of[i] != NONE {
                seeds.extend(self.clusters[self.of[i]].blocks.iter().copied());
            }
        }
        let snap: Vec<(usize, f64)> = seeds
            .iter()
            .filter(|&&i| !self.grounded(i))
            .map(|&i| (i, v))
            .collect();
        self.decide_from(&seeds, &snap, None, Cause::Touch)
    }

    fn joint_label(&self, j: usize) -> String {
        let jt = &self.topo.joints[j];
        format!(
            "{}|{}",
            self.wall.blocks[jt.left.0].name, self.wall.blocks[jt.right.0].name
        )
    }

    /// The chain of an impact at joint j: the blocks reachable from it through touching faces
    /// (joints already `seen` are left out, and the chain's are marked).
    fn chain(&self, j: usize, seen: &mut [bool]) -> Chain {
        let mut bodies_of = HashMap::new();
        let mut chain = Chain {
            bodies: Vec::new(),
            faces: Vec::new(),
        };
        let mut queue = vec![j];
        seen[j] = true;
        while let Some(jj) = queue.pop() {
            let jt = &self.topo.joints[jj];
            let mut ids = [0usize; 2];
            for (slot, blk) in [jt.left.0, jt.right.0].into_iter().enumerate() {
                let key = if self.fixed[blk] {
                    usize::MAX - blk
                } else {
                    blk
                };
                let id = *bodies_of.entry(key).or_insert_with(|| {
                    chain.bodies.push((
                        blk,
                        impact::Body {
                            mass: (!self.fixed[blk]).then(|| self.mass_q[blk].clone()),
                            velocity: Q::from_f64_exact(self.block_vel(blk))
                                .expect("velocities are finite"),
                        },
                    ));
                    chain.bodies.len() - 1
                });
                ids[slot] = id;
                if !self.fixed[blk] {
                    for &side in &self.topo.sides[blk] {
                        if !seen[side.0] && self.closed(side.0, blk) {
                            seen[side.0] = true;
                            queue.push(side.0);
                        }
                    }
                }
            }
            chain.faces.push((ids[0], ids[1], jj));
        }
        chain.faces.sort_by(|p, q| {
            self.xl[self.topo.joints[p.2].right.0]
                .total_cmp(&self.xl[self.topo.joints[q.2].right.0])
        });
        chain
    }

    /// Joint j, a side of block `blk`, is live and its faces touch.
    fn closed(&self, j: usize, blk: usize) -> bool {
        self.live_joint(j) && self.gap(j).abs() <= self.len_tol(self.block_disp(blk), 0.0)
    }

    /// The faces of joint j approach: closed, they collide.
    fn approaching(&self, j: usize) -> bool {
        let (vl, vr) = (
            self.block_vel(self.topo.joints[j].left.0),
            self.block_vel(self.topo.joints[j].right.0),
        );
        vl - vr > self.vel_tol(vl, vr)
    }

    /// Resolves a chain exactly: its collisions, the kinetic energy they lose (J) and the
    /// bodies' velocities after.
    fn resolve_chain(
        &self,
        chain: &Chain,
    ) -> Result<(Vec<impact::Collision>, Q, Vec<impact::Body>), SimulationError> {
        let pairs: Vec<(usize, usize)> = chain.faces.iter().map(|f| (f.0, f.1)).collect();
        let mut exact: Vec<impact::Body> = chain.bodies.iter().map(|b| b.1.clone()).collect();
        let scale = chain
            .bodies
            .iter()
            .map(|b| b.1.velocity.abs().to_f64())
            .fold(0.0, f64::max);
        let negligible = Q::from_f64_exact(self.vel_tol(scale, 0.0)).expect("finite tolerance");
        let Some((collisions, loss)) = impact::resolve(
            &mut exact,
            &pairs,
            &self.restitution,
            &negligible,
            self.params.max_collisions_per_chain,
        ) else {
            let names: Vec<&str> = chain
                .bodies
                .iter()
                .map(|b| self.wall.blocks[b.0].name.as_str())
                .collect();
            return Err(SimulationError::ImpactChain {
                time_s: self.t,
                blocks: names.join(", "),
                count: self.params.max_collisions_per_chain,
            });
        };
        Ok((collisions, loss, exact))
    }

    /// Other chains that collide at this instant on the clusters of `chains`' blocks, resolved
    /// (and marked `seen`): where a body hits its neighbours along several courses at once, one
    /// scheduled pair of clusters gives one face, and the others would each be found only after
    /// a decision over the whole body, with a transition at zero duration in between. A chain of
    /// one collision between two blocks each sliding alone is left to its own event: it may
    /// start a Zeno series ([`Engine::zeno_accumulation`]).
    fn simultaneous_chains(
        &self,
        chains: &mut Vec<(Chain, Vec<impact::Collision>, Q, Vec<impact::Body>)>,
        seen: &mut [bool],
    ) -> Result<(), SimulationError> {
        let mut scanned: Vec<usize> = Vec::new();
        let mut next = 0;
        while next < chains.len() {
            let hit: Vec<usize> = chains[next]
                .0
                .bodies
                .iter()
                .map(|b| b.0)
                .filter(|&b| !self.fixed[b])
                .collect();
            next += 1;
            for b in hit {
                let k = self.of[b];
                let members = match k {
                    NONE => std::slice::from_ref(&b),
                    k if scanned.contains(&k) => continue,
                    k => {
                        scanned.push(k);
                        &self.clusters[k].blocks[..]
                    }
                };
                for &m in members {
                    for &side in &self.topo.sides[m] {
                        let jj = side.0;
                        if seen[jj] || !self.closed(jj, m) || !self.approaching(jj) {
                            continue;
                        }
                        let chain = self.chain(jj, seen);
                        let (collisions, loss, exact) = self.resolve_chain(&chain)?;
                        if collisions.len() == 1 && self.alone_sliding(jj).is_some() {
                            continue;
                        }
                        chains.push((chain, collisions, loss, exact));
                    }
                }
            }
        }
        Ok(())
    }

    /// Resolves the impact at joint j and the chain of touching blocks around it, exactly, with
    /// every other chain that collides at this instant on the clusters they hit
    /// ([`Engine::simultaneous_chains`]); then one decision follows them all.
    fn impact(&mut self, j: usize) -> Result<(), SimulationError> {
        let mut seen = vec![false; self.topo.joints.len()];
        let first = self.chain(j, &mut seen);
        let (collisions, loss, exact) = self.resolve_chain(&first)?;
        if let Some(single) = (collisions.len() == 1).then(|| first.faces[collisions[0].face]) {
            if let Some(t_acc) = self.zeno_accumulation(single.2, &collisions[0].approach) {
                self.record_collisions(&first, &collisions);
                // Every bounce of the series happens within (t, t_acc) under the same forces: the
                // pair's centre of mass moves as if they had stuck now, and from t_acc on they
                // do. Merge them now with their common velocity; all of the relative kinetic
                // energy is lost to the series.
                let (bl, br, jj) = single;
                let (ml, mr) = (
                    first.bodies[bl].1.mass.clone().expect("sliding"),
                    first.bodies[br].1.mass.clone().expect("sliding"),
                );
                let c = &collisions[0];
                let common = (&ml * &c.before[0] + &mr * &c.before[1]) / (&ml + &mr);
                let total_loss =
                    Q::frac(1, 2) * &ml * &mr / (&ml + &mr) * &c.approach * &c.approach;
                self.rec.energy.impact_loss_j += total_loss.to_f64();
                let (l, r) = (self.topo.joints[jj].left.0, self.topo.joints[jj].right.0);
                self.rec.event(
                    t_acc,
                    EventKind::Zeno,
                    &[l, r],
                    Some(self.joint_label(jj)),
                    None,
                );
                self.rec.zeno += 1;
                let v = common.to_f64();
                return self.decide_from(&[l, r], &[(l, v), (r, v)], None, Cause::Zeno);
            }
        }
        let mut chains = vec![(first, collisions, loss, exact)];
        self.simultaneous_chains(&mut chains, &mut seen)?;
        let mut seeds = Vec::new();
        let mut snap = Vec::new();
        for (chain, collisions, loss, exact) in &chains {
            self.record_collisions(chain, collisions);
            self.rec.energy.impact_loss_j += loss.to_f64();
            for (k, (blk, _)) in chain.bodies.iter().enumerate() {
                if self.fixed[*blk] {
                    continue;
                }
                let v = exact[k].velocity.to_f64();
                if v != self.block_vel(*blk) {
                    snap.push((*blk, v));
                }
                seeds.push(*blk);
            }
        }
        self.decide_from(&seeds, &snap, None, Cause::Impact)
    }

    /// Logs a chain's collisions; their faces touch from now on.
    fn record_collisions(&mut self, chain: &Chain, collisions: &[impact::Collision]) {
        for c in collisions {
            let jj = chain.faces[c.face].2;
            let (l, r) = (self.topo.joints[jj].left.0, self.topo.joints[jj].right.0);
            self.touching[jj] = true;
            let pair = |v: &[Q; 2]| [v[0].to_f64(), v[1].to_f64()];
            self.rec.impact(
                self.t,
                l,
                r,
                self.joint_label(jj),
                pair(&c.before),
                pair(&c.after),
            );
        }
    }

    /// Zeno: after an impact with 0 < e < 1 between two blocks that slide alone under forces the
    /// impact does not change (no joint reverses within the bounces), the relative acceleration
    /// is a constant a pushing them together, the rebound speeds are e^k v_r and the bounces
    /// accumulate at t + 2 v_r / (|a| (1 - e)) (design note, section 5). Returns that time when
    /// the conditions hold, nothing else happens before it, and the rest of the series is
    /// invisible: its widest opening, v_r^2 / (2 |a|), is within the round-off of the
    /// displacements. Until then each bounce is an ordinary impact, so the history between
    /// bounces is the exact one, not that of blocks merged early.
    fn zeno_accumulation(&self, j: usize, approach: &Q) -> Option<f64> {
        let e = &self.restitution;
        let (l, r) = (self.topo.joints[j].left.0, self.topo.joints[j].right.0);
        let (sl, sr) = self.alone_sliding(j)?;
        let closing = &sr.c_q - &sl.c_q;
        if !closing.is_negative() {
            return None;
        }
        let rebound = e * approach;
        let opening = (&rebound * &rebound / (Q::int(-2) * &closing)).to_f64();
        if opening > self.len_tol(self.block_disp(l), self.block_disp(r)) {
            return None;
        }
        let dt = (Q::int(2) * &rebound / (-&closing * (Q::one() - e))).to_f64();
        let t_acc = self.t + dt;
        // No joint of either block may reverse within the bounces, whatever the ground does:
        // the series changes a velocity by at most (1 + e) v0 <= 2 v0 (the first bounce), and
        // in dt a relative velocity drifts towards zero by at most its worst-case acceleration
        // that way times dt.
        let v0 = approach.to_f64();
        let (a_min, a_max) = self.motion.accel_range(self.t, t_acc);
        for b in [l, r] {
            let vb = self.block_vel(b);
            let cb = self.clusters[self.of[b]].slide()?.c;
            for other in self.live_neighbours(b) {
                let w = vb - other.map_or(0.0, |o| self.block_vel(o));
                let (dw_lo, dw_hi) = match other
                    .filter(|&o| self.of[o] != NONE)
                    .and_then(|o| self.clusters[self.of[o]].slide())
                {
                    Some(so) => (cb - so.c, cb - so.c),
                    None => (cb - a_max, cb - a_min),
                };
                let drift = if w < 0.0 {
                    dw_hi.max(0.0)
                } else {
                    (-dw_lo).max(0.0)
                } * dt;
                if w.abs() <= 2.0 * v0 + drift {
                    return None;
                }
            }
        }
        let earliest = self
            .heap
            .iter()
            .filter(|p| self.is_current(&p.0.ev))
            .map(|p| p.0.t)
            .fold(f64::INFINITY, f64::min);
        (t_acc < earliest && t_acc < self.t_end).then_some(t_acc)
    }

    /// The slides of the two blocks of joint j where a Zeno series is possible between them: 0 <
    /// e < 1, no vertical shaking, and each block sliding alone.
    fn alone_sliding(&self, j: usize) -> Option<(&cluster::Slide, &cluster::Slide)> {
        let e = &self.restitution;
        if !(e.is_positive() && *e < Q::one()) || self.motion.has_vertical() {
            return None;
        }
        let (l, r) = (self.topo.joints[j].left.0, self.topo.joints[j].right.0);
        let (kl, kr) = (self.of[l], self.of[r]);
        if kl == NONE
            || kr == NONE
            || self.clusters[kl].blocks.len() != 1
            || self.clusters[kr].blocks.len() != 1
        {
            return None;
        }
        Some((self.clusters[kl].slide()?, self.clusters[kr].slide()?))
    }

    /// Does block i still stand on its supports? Its centroid must lie in the span from the
    /// leftmost to the rightmost point where its bottom face touches a support's top face; on the
    /// edge of the span, it falls if it is moving out (velocity, then acceleration).
    fn stands(&self, i: usize) -> bool {
        let state = |b: usize| -> [f64; 3] {
            if self.of[b] == NONE {
                return [self.u_ref[b], 0.0, 0.0];
            }
            let k = self.of[b];
            match self.clusters[k].slide() {
                Some(sl) => [
                    self.u_ref[b] + sl.disp(self.t),
                    sl.vel(self.t),
                    sl.acc(self.t),
                ],
                None => [self.u_ref[b], 0.0, 0.0],
            }
        };
        let add = |p: [f64; 3], x: f64| [p[0] + x, p[1], p[2]];
        let tol = self.len_tol(self.block_disp(i), 0.0);
        let cmp = |a: [f64; 3], b: [f64; 3]| -> Ordering {
            if (a[0] - b[0]).abs() > tol {
                return a[0].total_cmp(&b[0]);
            }
            a[1].total_cmp(&b[1]).then(a[2].total_cmp(&b[2]))
        };
        let lex_max = |a: [f64; 3], b: [f64; 3]| if cmp(a, b) == Ordering::Less { b } else { a };
        let lex_min = |a: [f64; 3], b: [f64; 3]| if cmp(a, b) == Ordering::Greater { b } else { a };
        let ui = state(i);
        let centroid = add(ui, self.xc[i]);
        let mut hull: Option<([f64; 3], [f64; 3])> = None;
        for &s in &self.topo.below[i] {
            if !self.live_support(s.0) {
                continue;
            }
            let Some(j) = self.lower_block(s.0) else {
                return true;
            };
            let uj = state(j);
            let lo = lex_max(add(ui, self.xl[i]), add(uj, self.xl[j]));
            let hi = lex_min(add(ui, self.xr[i]), add(uj, self.xr[j]));
            if cmp(hi, lo) == Ordering::Greater {
                hull = Some(match hull {
                    None => (lo, hi),
                    Some((a, b)) => (lex_min(a, lo), lex_max(b, hi)),
                });
            }
        }
        match hull {
            None => false,
            Some((lo, hi)) => {
                cmp(centroid, lo) != Ordering::Less && cmp(centroid, hi) != Ordering::Greater
            }
        }
    }

    fn collapse(&mut self, i: usize) -> Result<(), SimulationError> {
        if self.rec.collapse.is_none() {
            self.rec.collapse = Some(Collapse {
                time_s: self.t,
                block: self.wall.blocks[i].name.clone(),
            });
        }
        self.rec
            .event(self.t, EventKind::Collapse, &[i], None, None);
        self.rec.fell(i);
        if self.after_collapse == AfterCollapse::Stop {
            self.stopped = true;
            return Ok(());
        }
        self.remove_fallen(i)
    }

    fn finish(mut self) -> Response {
        let t = self.t.min(self.t_end);
        self.t = t;
        self.account_all(t);
        for k in 0..self.clusters.len() {
            self.record_extremes(k);
        }
        for s in 0..self.topo.supports.len() {
            self.account_support(s);
        }
        let u: Vec<f64> = (0..self.n).map(|i| self.block_disp(i)).collect();
        let v: Vec<f64> = (0..self.n)
            .map(|i| {
                if self.fallen[i] {
                    0.0
                } else {
                    self.block_vel(i)
                }
            })
            .collect();
        self.rec.energy.kinetic_j = (0..self.n)
            .filter(|&i| !self.fallen[i])
            .map(|i| 0.5 * self.mass[i] * v[i] * v[i])
            .sum();
        self.rec.stats.root_evaluations = self.count.0;
        self.rec.stats.flow_nodes = flow::take_pass_nodes();
        self.rec.warnings =
            crate::validity::rocking_warnings(self.wall, self.topo, self.rec.peak_accel());
        let motion = self.motion.describe();
        self.rec.finish("event", self.wall, motion, t, &u, &v)
    }
}

/// Bounds on |V_g| and |D_g| over [0, t_end], for round-off scales.
fn motion_bounds(m: &Motion, t_end: f64) -> (f64, f64) {
    match m {
        Motion::Sine(s) => {
            let w = 2.0 * std::f64::consts::PI * s.frequency_hz;
            let a = s.amplitude_m_s2.abs();
            (2.0 * a / w, a / w * t_end + 2.0 * a / (w * w))
        }
        Motion::Record(_) => {
            let mut v: f64 = 0.0;
            let mut d: f64 = 0.0;
            let steps = 2000;
            for k in 0..=steps {
                let t = t_end * k as f64 / steps as f64;
                v = v.max(m.velocity(t).abs());
                d = d.max(m.displacement(t).abs());
            }
            (2.0 * v, 2.0 * d + v * t_end / steps as f64)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::Settings;
    use crate::motion::Sine;
    use crate::wall::RunningBond;

    /// A running-bond wall at rest is one stuck cluster, which meets nothing but the ground
    /// under its bottom course: that course is its boundary. (Clusters that meet other
    /// clusters are covered by the runs whose event logs and energy balances the integration
    /// tests check: leaving out the supports above a block fails three of them.)
    #[test]
    fn a_cluster_meets_the_rest_of_the_wall_only_at_its_boundary() {
        let spec = RunningBond {
            courses: 4,
            blocks_per_course: 6,
            ..RunningBond::paper_wall(5)
        };
        let wall = Wall::from_description(&spec.description().unwrap()).unwrap();
        let topology = Topology::new(&wall).unwrap();
        let motion = Motion::Sine(Sine::new(1.0, 1.0, 0.0, 1.0).unwrap());
        let settings = Settings::summary_only(1.0);
        let params = Params::default();
        let scenario = Scenario {
            wall: &wall,
            topology: &topology,
            motion: &motion,
            settings: &settings,
        };
        let mut engine = Engine::new(&scenario, &params).unwrap();
        let all: Vec<usize> = (0..wall.blocks.len()).collect();
        engine.decide_from(&all, &[], None, Cause::Start).unwrap();
        let k = engine.of[0];
        assert!(all.iter().all(|&i| engine.of[i] == k), "one cluster");
        let bottom: Vec<usize> = all
            .iter()
            .copied()
            .filter(|&i| wall.blocks[i].y.is_zero())
            .collect();
        assert!(bottom.len() >= 6 && bottom.len() < all.len());
        assert_eq!(engine.boundary(k), bottom.as_slice());
    }
}
