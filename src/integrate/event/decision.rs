//! Re-deciding the mode around an event: gather the blocks whose joints became undecided, solve
//! their decision problem exactly, install the new clusters, and update the neighbours whose
//! friction forces changed.

use super::cluster::{Cluster, Motion, Slide};
use super::decide::{End, Group, Lex, Problem};
use super::flow;
use super::stuck::{stuck, Before, Limits};
use super::{Engine, NONE};
use crate::clock::ThreadClock;
use crate::error::SimulationError;
use crate::exact::Q;
use crate::response::{DecisionCause as Cause, DecisionRecord, EventKind, StuckGroup};
use crate::sets::DisjointSets;
use rustc_hash::FxHashMap;
use std::cell::OnceCell;

/// A ground acceleration within rounding of a breakpoint of the decision is snapped to it; the
/// snap can move the breakpoint that matters at most this many times.
const MAX_SNAPS: usize = 8;

/// Ground accelerations remembered per decision problem (the oldest is forgotten first): a
/// problem is met again at the few stick thresholds of its neighbourhood, or away from the
/// ground at none.
const THETAS_KEPT: usize = 16;

/// Sliding clusters of at least this many blocks are held together in a decision's first try
/// (`Problem::solve`); below it the general decision costs no more.
pub(super) const BODY_FROM: usize = 32;

/// The local index of each block in a decision problem (`NONE` outside it): a table over all
/// blocks, because a decision can take in most of a large wall.
pub(super) struct Local(Vec<usize>);

impl Local {
    /// The table over n blocks, in the memory of an earlier one (all `NONE`) if given.
    pub(super) fn reuse(mut table: Vec<usize>, n: usize) -> Local {
        if table.len() != n {
            table = vec![NONE; n];
        }
        Local(table)
    }

    /// Empties the entries of `used` and hands the memory back.
    pub(super) fn release(mut self, used: &[usize]) -> Vec<usize> {
        for &b in used {
            self.0[b] = NONE;
        }
        self.0
    }

    pub(super) fn get(&self, b: &usize) -> Option<&usize> {
        Some(&self.0[*b]).filter(|&&k| k != NONE)
    }

    fn contains_key(&self, b: &usize) -> bool {
        self.0[*b] != NONE
    }

    pub(super) fn insert(&mut self, b: usize, k: usize) {
        self.0[b] = k;
    }
}

/// Velocities set for the decision (m/s), over all blocks (NaN: none set): where a block stops,
/// where two clusters meet, after an impact, and where round-off was evened out.
struct Snap {
    vel: Vec<f64>,
    set: Vec<usize>,
}

impl Snap {
    /// The table over n blocks, in the memory of an earlier one (all NaN) if given.
    fn reuse(mut vel: Vec<f64>, mut set: Vec<usize>, n: usize) -> Snap {
        if vel.len() != n {
            vel = vec![f64::NAN; n];
        }
        set.clear();
        Snap { vel, set }
    }

    fn get(&self, b: usize) -> Option<f64> {
        Some(self.vel[b]).filter(|v| !v.is_nan())
    }

    fn insert(&mut self, b: usize, v: f64) {
        if self.vel[b].is_nan() {
            self.set.push(b);
        }
        self.vel[b] = v;
    }

    /// Empties the table and hands the memory back.
    fn release(mut self) -> (Vec<f64>, Vec<usize>) {
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
pub(super) struct Buffers {
    /// The table of [`Local`].
    pub(super) local: Vec<usize>,
    /// The table of [`Snap`] and the blocks set in it.
    snap: Vec<f64>,
    snapped: Vec<usize>,
    /// The component's blocks, and the queue that gathers them.
    blocks: Vec<usize>,
    queue: Vec<usize>,
    /// The clusters the component's blocks belonged to.
    old: Vec<usize>,
    /// The supports and vertical joints at the component's blocks.
    supports: Vec<usize>,
    joints: Vec<usize>,
    /// The decision problem.
    problem: Problem,
    /// The blocks' displacements and velocities (m, m/s), and the new group of each.
    u: Vec<f64>,
    v: Vec<f64>,
    group_of: Vec<usize>,
}

impl Engine<'_> {
    /// Velocity of block i with the given overrides.
    fn vel_with(&self, i: usize, snap: &Snap) -> f64 {
        snap.get(i).unwrap_or_else(|| self.block_vel(i))
    }

    /// The ground acceleration just after now, divided by the vertical load factor (every
    /// friction force scales with it, so the decision at lambda is the decision at 1 with
    /// a_g/lambda): exact value (or `snap`, already divided) with its derivatives.
    fn ground_lex(&self, snap: Option<Q>) -> Lex {
        let s = self.s();
        let q = |x: f64| Q::from_f64_exact(x).expect("finite value");
        let (a, (r1, r2)) = (self.seg.accel(s), self.seg.accel_rates(s));
        let (l, dl) = (self.seg.lambda_at(s), self.seg.lambda.1);
        if !self.seg.has_vertical() {
            let a0 = snap.unwrap_or_else(|| q(a));
            return Lex([a0, q(r1), q(r2)]);
        }
        // (a/l)' = (a' l - a l')/l^2; (a/l)'' = -2 l' (a' l - a l')/l^3 (a'' = l'' = 0).
        let a0 = snap.unwrap_or_else(|| q(a) / q(l));
        let num = r1 * l - a * dl;
        Lex([a0, q(num / (l * l)), q(-2.0 * dl * num / (l * l * l))])
    }

    /// Re-decides the mode of the clusters of `seeds` and of every cluster joined to them by a
    /// joint with zero relative velocity. `snap` overrides block velocities (set to exactly zero at
    /// a stop, to a common value where two clusters meet, after an impact); `theta` is the exact
    /// ground acceleration when the event is a stick threshold; `cause` goes into the decision
    /// log.
    pub(super) fn decide_from(
        &mut self,
        seeds: &[usize],
        snap: &[(usize, f64)],
        theta: Option<Q>,
        cause: Cause,
    ) -> Result<(), SimulationError> {
        self.rec.stats.mode_decisions += 1;
        let log_from = self
            .rec
            .decisions
            .is_some()
            .then(|| (ThreadClock::start(), flow::pass_nodes()));
        let t = self.t;

        // 1. The component: whole clusters joined through joints with equal velocities.
        let mut buf = std::mem::take(&mut self.buffers);
        let mut snap = {
            let (vel, set) = (
                std::mem::take(&mut buf.snap),
                std::mem::take(&mut buf.snapped),
            );
            let mut table = Snap::reuse(vel, set, self.n);
            for &(i, v) in snap {
                table.insert(i, v);
            }
            table
        };
        let mut local = Local::reuse(std::mem::take(&mut buf.local), self.n);
        let mut blocks = std::mem::take(&mut buf.blocks);
        let mut old_clusters = std::mem::take(&mut buf.old);
        let mut queue = std::mem::take(&mut buf.queue);
        self.gather(
            seeds,
            &snap,
            &mut local,
            &mut blocks,
            &mut old_clusters,
            &mut queue,
        );

        // Canonical order (by block index), so a configuration met again is the same problem.
        blocks.sort_unstable();
        self.rec.stats.decision_blocks += blocks.len() as u64;
        old_clusters.sort_unstable();
        let taken_in = log_from
            .as_ref()
            .map(|_| (blocks.len(), self.largest_stuck(&old_clusters)));
        for (k, &b) in blocks.iter().enumerate() {
            local.insert(b, k);
        }
        self.equalize_velocities(&blocks, &local, &mut snap, &mut buf.v);

        // 2. Account what the old clusters did up to now, and the joints around them.
        for &k in &old_clusters {
            self.account(k, t);
        }
        let mut touched_supports = std::mem::take(&mut buf.supports);
        let mut touched_joints = std::mem::take(&mut buf.joints);
        for &i in &blocks {
            touched_supports.extend(
                self.topo.below[i]
                    .iter()
                    .chain(&self.topo.above[i])
                    .map(|s| s.0),
            );
            touched_joints.extend(self.topo.sides[i].iter().map(|j| j.0));
        }
        for touched in [&mut touched_supports, &mut touched_joints] {
            touched.sort_unstable();
            touched.dedup();
        }
        for &s in &touched_supports {
            self.account_support(s);
        }
        let (u_now, v_now) = (&mut buf.u, &mut buf.v);
        u_now.extend(blocks.iter().map(|&i| self.block_disp(i)));
        v_now.clear();
        v_now.extend(blocks.iter().map(|&i| self.vel_with(i, &snap)));

        // 3. The decision problem.
        let mut p = std::mem::take(&mut buf.problem);
        self.problem_of(
            &mut p,
            &blocks,
            &local,
            &snap,
            &touched_supports,
            &touched_joints,
        );
        let p = p.canonical();

        // 4. Solve: stuck pieces by their stick intervals, the rest by the general decision.
        let (groups, intervals, theta_lex) =
            self.solve_component(&p, &blocks, &old_clusters, &local, &snap, theta.as_ref());

        // 5. Install the new clusters, keeping what the intervals after it may need.
        let mut before = Before::default();
        if blocks.len() >= self.params.kept_limits_from {
            for &b in &blocks {
                before.of.insert(b, self.of[b]);
            }
            for &k in &old_clusters {
                let limits = match &self.clusters[k].motion {
                    Motion::Stuck { lo_q, hi_q, .. } => Some([lo_q.clone(), hi_q.clone()]),
                    Motion::Sliding(_) => None,
                };
                before.limits.insert(k, limits);
            }
        }
        for &k in &old_clusters {
            self.record_extremes(k);
            self.clusters[k].blocks.clear();
            self.clusters[k].version = self.new_version();
            self.free.push(k);
        }
        let group_of = &mut buf.group_of;
        group_of.resize(blocks.len(), usize::MAX);
        let mut new_clusters = Vec::with_capacity(groups.len());
        let mut needs_interval = Vec::new();
        for (g_idx, g) in groups.iter().enumerate() {
            // The member list is built in the emptied list of the slot `alloc` will give.
            let mut members = self
                .free
                .last()
                .map_or_else(Vec::new, |&k| std::mem::take(&mut self.clusters[k].blocks));
            members.extend(g.nodes.iter().map(|&k| blocks[k]));
            for (&i, &node) in members.iter().zip(&g.nodes) {
                group_of[node] = g_idx;
                self.u_ref[i] = u_now[node];
            }
            let mass_q: Q = members.iter().map(|&i| self.mass_q[i].clone()).sum();
            let motion = if g.grounded {
                stuck(intervals[g_idx].clone().unwrap_or_default())
            } else {
                let v = v_now[g.nodes[0]];
                Motion::Sliding(Slide::formed(&self.seg, self.t, v, g.accel.clone()))
            };
            let k = self.alloc(Cluster {
                mass: mass_q.to_f64(),
                mass_q,
                blocks: members,
                version: 0,
                ground_version: 0,
                motion,
                accounted_to: t,
                roots: None,
                ground_hits: None,
                extremes: Default::default(),
                boundary: OnceCell::new(),
            });
            for &i in &self.clusters[k].blocks {
                self.of[i] = k;
            }
            if g.grounded && intervals[g_idx].is_none() {
                needs_interval.push(k);
            }
            new_clusters.push(k);
        }

        // 6. Joint directions, stick-slip transitions and separations.
        let accel_of = |b: Option<usize>| -> Lex {
            match b.and_then(|b| local.get(&b)) {
                Some(&k) if !groups[group_of[k]].grounded => {
                    Lex::constant(groups[group_of[k]].accel.clone())
                }
                _ => theta_lex.clone(),
            }
        };
        let (mut neighbours, mut pushed) = self.turn_joints(
            &touched_supports,
            &touched_joints,
            &local,
            &snap,
            &accel_of,
            &mut before,
        );
        // The working memory goes back before anything below decides again.
        buf.local = local.release(&blocks);
        buf.problem = p.cleared();
        (buf.snap, buf.snapped) = snap.release();
        for (v, kept) in [
            (blocks, &mut buf.blocks),
            (queue, &mut buf.queue),
            (old_clusters, &mut buf.old),
            (touched_supports, &mut buf.supports),
            (touched_joints, &mut buf.joints),
        ] {
            *kept = v;
            kept.clear();
        }
        buf.u.clear();
        buf.v.clear();
        buf.group_of.clear();
        self.buffers = buf;
        // Neighbours hold blocks outside the component only, so none is a new cluster.
        for set in [&mut neighbours, &mut pushed] {
            set.sort_unstable();
            set.dedup();
        }
        // A stuck neighbour none of whose joints turned keeps its problem, so its interval and
        // events stand. A sliding one keeps its motion and its events with the sliding clusters
        // that did not change (those with the new ones come with theirs); what it slides
        // against has changed, so its events against the ground side are found again. A large
        // body beside a small decision then costs a pass over its own blocks, not one over every
        // sliding cluster along it.
        let quiet: Vec<usize> = neighbours
            .into_iter()
            .filter(|k| pushed.binary_search(k).is_err() && self.clusters[*k].slide().is_some())
            .collect();

        // 7. Stuck clusters get their threshold interval; neighbours whose friction changed move
        //    on with their new forces.
        for &k in &needs_interval {
            self.set_thresholds(k, Some(&before));
        }
        for &k in &new_clusters {
            self.clusters[k].version = self.new_version();
        }
        for &k in &pushed {
            self.refresh(k, &before);
        }
        for &k in &quiet {
            self.clusters[k].ground_version = self.new_version();
            self.schedule_segment(k);
        }
        self.schedule(new_clusters.iter().chain(&pushed).copied());
        if let (Some((clock, nodes_from)), Some((blocks, stuck_taken_in))) = (log_from, taken_in) {
            let record = DecisionRecord {
                time_s: t,
                cause,
                a_g_m_s2: self.seg.accel(self.s()),
                load_factor: self.seg.lambda_at(self.s()),
                blocks,
                stuck_taken_in,
                clusters: new_clusters.len(),
                stuck_formed: self.largest_stuck(&new_clusters),
                flow_nodes: flow::pass_nodes() - nodes_from,
                cpu_s: clock.seconds(),
            };
            if let Some(log) = &mut self.rec.decisions {
                log.push(record);
            }
        }

        // 8. A sliding cluster of several blocks whose friction forces changed may have to split:
        //    re-decide it (a stuck one has its new stick interval, which is checked at once).
        for k in pushed {
            let blocks = &self.clusters[k].blocks;
            if blocks.len() > 1 && self.clusters[k].slide().is_some() {
                let seeds = blocks.clone();
                self.decide_from(&seeds, &[], None, Cause::Split)?;
            }
        }
        Ok(())
    }

    /// Step 6 of [`Engine::decide_from`]: each joint of the component takes its new direction
    /// (`accel_of`: a block's acceleration after the decision, the ground's for `None`), with
    /// its stick-slip transition and the faces that separate logged. Returns the clusters
    /// outside the component beside it, and those of them one of whose joints turned: their
    /// friction forces changed (only an impact turns a sliding joint without a re-decision of
    /// both sides).
    fn turn_joints(
        &mut self,
        touched_supports: &[usize],
        touched_joints: &[usize],
        local: &Local,
        snap: &Snap,
        accel_of: &dyn Fn(Option<usize>) -> Lex,
        before: &mut Before,
    ) -> (Vec<usize>, Vec<usize>) {
        let mut neighbours: Vec<usize> = Vec::new();
        let mut pushed: Vec<usize> = Vec::new();
        for &s in touched_supports {
            if !self.live_support(s) {
                continue;
            }
            let (up, lo) = self.support_ends(s);
            for b in std::iter::once(up).chain(lo) {
                if !local.contains_key(&b) && self.of[b] != NONE {
                    neighbours.push(self.of[b]);
                }
            }
            let same = lo.is_some_and(|l| self.of[l] == self.of[up]);
            let (vu, vl) = (
                self.vel_with(up, snap),
                lo.map_or(0.0, |l| self.vel_with(l, snap)),
            );
            let new_dir: i8 = if same || (lo.is_none() && self.grounded(up)) {
                0
            } else if vu != vl {
                if vu > vl {
                    1
                } else {
                    -1
                }
            } else {
                match accel_of(Some(up)).cmp(&accel_of(lo)) {
                    std::cmp::Ordering::Greater => 1,
                    std::cmp::Ordering::Less => -1,
                    std::cmp::Ordering::Equal => self.dir[s],
                }
            };
            let old_dir = self.dir[s];
            self.dir[s] = new_dir;
            if old_dir != new_dir {
                before.dir.insert(s, old_dir);
                for b in std::iter::once(up).chain(lo) {
                    if !local.contains_key(&b) && self.of[b] != NONE {
                        pushed.push(self.of[b]);
                    }
                }
            }
            if (old_dir == 0) != (new_dir == 0) {
                self.rec.transitions += 1;
                let kind = if new_dir == 0 {
                    EventKind::Stick
                } else {
                    EventKind::Slip
                };
                let who: &[usize] = match lo {
                    Some(l) => &[up, l],
                    None => &[up],
                };
                self.rec.support_event(self.t, kind, s, who);
            }
        }
        for &j in touched_joints {
            if !self.live_joint(j) {
                continue;
            }
            let jt = &self.topo.joints[j];
            let (l, r) = (jt.left.0, jt.right.0);
            for b in [l, r] {
                if !local.contains_key(&b) && self.of[b] != NONE {
                    neighbours.push(self.of[b]);
                }
            }
            let together = (self.of[l] == self.of[r] && self.of[l] != NONE)
                || (self.grounded(l) && self.grounded(r));
            if self.touching[j] && !together && self.is_touching(j) {
                self.touching[j] = false;
                self.rec.event(
                    self.t,
                    EventKind::Separation,
                    &[l, r],
                    Some(self.joint_label(j)),
                    None,
                );
            } else if together && self.is_touching(j) {
                self.touching[j] = true;
            }
        }
        (neighbours, pushed)
    }

    /// Step 1 of [`Engine::decide_from`]: the blocks of the component (whole clusters joined to
    /// `seeds` through joints whose sides move with equal velocities), in the order found, with
    /// their local indices, the old clusters they come from, and `queue` left empty.
    fn gather(
        &self,
        seeds: &[usize],
        snap: &Snap,
        local: &mut Local,
        blocks: &mut Vec<usize>,
        old_clusters: &mut Vec<usize>,
        queue: &mut Vec<usize>,
    ) {
        let add = |b: usize,
                   this: &Engine,
                   local: &mut Local,
                   blocks: &mut Vec<usize>,
                   old: &mut Vec<usize>,
                   queue: &mut Vec<usize>| {
            // Once per cluster: its first block brings in all the others.
            let members: &[usize] = match this.of[b] {
                NONE => std::slice::from_ref(&b),
                k => {
                    old.push(k);
                    &this.clusters[k].blocks
                }
            };
            for &m in members {
                if !local.contains_key(&m) {
                    local.insert(m, blocks.len());
                    blocks.push(m);
                    queue.push(m);
                }
            }
        };
        for &b in seeds {
            if !self.fixed[b] && !self.fallen[b] && !local.contains_key(&b) {
                add(b, self, local, blocks, old_clusters, queue);
            }
        }
        let mut next = Vec::new();
        while let Some(i) = queue.pop() {
            let vi = self.vel_with(i, snap);
            next.clear();
            for other in self.live_neighbours(i) {
                if let Some(o) = other.filter(|&o| !self.fixed[o]) {
                    if !local.contains_key(&o) && self.same_velocity(vi, self.vel_with(o, snap)) {
                        next.push(o);
                    }
                }
            }
            for &j in &self.topo.sides[i] {
                if !self.live_joint(j.0) || !self.is_touching(j.0) {
                    continue;
                }
                let o = self.across_joint(j.0, i);
                if !self.fixed[o]
                    && !local.contains_key(&o)
                    && self.same_velocity(vi, self.vel_with(o, snap))
                {
                    next.push(o);
                }
            }
            for &o in &next {
                if !local.contains_key(&o) {
                    add(o, self, local, blocks, old_clusters, queue);
                }
            }
        }
    }

    /// Step 3 of [`Engine::decide_from`]: the decision problem of the component `blocks` (in
    /// `p`, empty): their masses, the friction of joints that slide as external forces, the
    /// joints and touching faces whose sides move with equal velocities as undecided.
    fn problem_of(
        &self,
        p: &mut Problem,
        blocks: &[usize],
        local: &Local,
        snap: &Snap,
        touched_supports: &[usize],
        touched_joints: &[usize],
    ) {
        p.mass
            .extend(blocks.iter().map(|&i| self.mass_q[i].clone()));
        p.external.resize(blocks.len(), Q::zero());
        for &s in touched_supports {
            if !self.live_support(s) {
                continue;
            }
            let (up, lo) = self.support_ends(s);
            let (vu, vl) = (
                self.vel_with(up, snap),
                lo.map_or(0.0, |l| self.vel_with(l, snap)),
            );
            let (lu, ll) = (
                local.get(&up).copied(),
                lo.and_then(|l| local.get(&l).copied()),
            );
            let lower_is_ground = lo.is_none();
            let undecided = match lu {
                Some(u) if vu == vl && (ll.is_some() || lower_is_ground) => Some(u),
                _ => None,
            };
            if let Some(u) = undecided {
                let end = ll.map_or(End::Ground, End::Node);
                p.friction.push((u, end, self.cap_q[s].clone()));
            } else {
                // Sliding: friction opposes the relative velocity (or, when the far side is
                // outside and moving with it, its recorded direction).
                let dir = if vu != vl {
                    if vu > vl {
                        1
                    } else {
                        -1
                    }
                } else {
                    self.dir[s]
                };
                let f = &self.cap_q[s];
                if let Some(k) = lu {
                    p.external[k] = if dir > 0 {
                        &p.external[k] - f
                    } else {
                        &p.external[k] + f
                    };
                }
                if let Some(k) = ll {
                    p.external[k] = if dir > 0 {
                        &p.external[k] + f
                    } else {
                        &p.external[k] - f
                    };
                }
            }
        }
        for &j in touched_joints {
            if !self.live_joint(j) || !self.is_touching(j) {
                continue;
            }
            let jt = &self.topo.joints[j];
            let (l, r) = (jt.left.0, jt.right.0);
            let end = |b: usize| {
                if self.fixed[b] {
                    Some(End::Ground)
                } else {
                    local.get(&b).map(|&k| End::Node(k))
                }
            };
            let (vl, vr) = (self.vel_with(l, snap), self.vel_with(r, snap));
            if let (Some(el), Some(er)) = (end(l), end(r)) {
                if vl == vr {
                    p.contacts.push((el, er));
                }
            }
        }
    }

    /// Step 4 of [`Engine::decide_from`]: the groups of the component's problem `p`, the stick
    /// intervals of those found stuck by their pieces (`None` for the others), and the ground
    /// acceleration they were decided at. Pieces joined to the ground with the ground
    /// acceleration strictly inside their stick intervals stay stuck (the common case); the
    /// other pieces get the general decision. Pieces meet only through the ground, whose motion
    /// is given, so each is decided on its own: a block knocked out of a large stuck cluster
    /// costs that cluster a stick interval, not a general decision over all of it.
    fn solve_component(
        &mut self,
        p: &Problem,
        blocks: &[usize],
        old_clusters: &[usize],
        local: &Local,
        snap: &Snap,
        theta: Option<&Q>,
    ) -> (Vec<Group>, Vec<Option<Limits>>, Lex) {
        let mut theta_lex = self.ground_lex(theta.cloned());
        let (mut groups, mut intervals, rest) =
            self.stuck_pieces(p, blocks, &theta_lex, theta.is_some());
        if !rest.is_empty() {
            let bodies = self.sliding_bodies(old_clusters, local, snap);
            if rest.len() == blocks.len() {
                groups = self.decide_general(p, &mut theta_lex, theta.is_some(), &bodies);
            } else {
                let mut index = vec![NONE; blocks.len()];
                for (k, &i) in rest.iter().enumerate() {
                    index[i] = k;
                }
                // What is left of each body in the rest (an impact can have knocked some of
                // its blocks into other pieces).
                let rest_bodies: Vec<Vec<usize>> = bodies
                    .iter()
                    .map(|b| {
                        b.iter()
                            .filter(|&&i| index[i] != NONE)
                            .map(|&i| index[i])
                            .collect::<Vec<usize>>()
                    })
                    .filter(|b| !b.is_empty())
                    .collect();
                let q = p.restrict(&rest);
                let before = theta_lex.clone();
                let found = self.decide_general(&q, &mut theta_lex, theta.is_some(), &rest_bodies);
                if theta_lex == before {
                    groups.extend(found.into_iter().map(|g| Group {
                        nodes: g.nodes.iter().map(|&k| rest[k]).collect(),
                        ..g
                    }));
                } else {
                    // A hidden breakpoint moved the ground acceleration, at which the stuck
                    // pieces were not decided: decide everything there (rare).
                    theta_lex = before;
                    groups = self.decide_general(p, &mut theta_lex, theta.is_some(), &bodies);
                    intervals.clear();
                }
            }
            intervals.resize(groups.len(), None);
        }
        (groups, intervals, theta_lex)
    }

    /// Large clusters of the component that slid as one body until now (see `Problem::solve`),
    /// each cut by velocity: the blocks an impact hits leave with velocities of their own, and
    /// held to the rest they would fail the first try, which costs a cut over the body.
    fn sliding_bodies(
        &self,
        old_clusters: &[usize],
        local: &Local,
        snap: &Snap,
    ) -> Vec<Vec<usize>> {
        let mut bodies: Vec<Vec<usize>> = Vec::new();
        for c in old_clusters.iter().map(|&k| &self.clusters[k]) {
            if c.slide().is_none() || c.blocks.len() < BODY_FROM {
                continue;
            }
            let mut by_velocity: Vec<(f64, Vec<usize>)> = Vec::new();
            for b in &c.blocks {
                let v = self.vel_with(*b, snap);
                match by_velocity.iter_mut().find(|(w, _)| *w == v) {
                    Some((_, nodes)) => nodes.push(local[b]),
                    None => by_velocity.push((v, vec![local[b]])),
                }
            }
            for (_, mut nodes) in by_velocity {
                if nodes.len() >= 2 {
                    nodes.sort_unstable();
                    bodies.push(nodes);
                }
            }
        }
        bodies
    }

    /// Support s's upper block, and its lower block where that can move (`None`: the ground or
    /// an abutment).
    fn support_ends(&self, s: usize) -> (usize, Option<usize>) {
        let up = self.topo.supports[s].upper.0;
        (up, self.lower_block(s).filter(|&l| !self.fixed[l]))
    }

    /// The largest of these clusters that is stuck to the ground, for the decision log.
    fn largest_stuck(&self, clusters: &[usize]) -> Option<StuckGroup> {
        clusters
            .iter()
            .filter_map(|&k| match &self.clusters[k].motion {
                Motion::Stuck {
                    lo_q,
                    hi_q,
                    bound_only,
                    ..
                } => Some(StuckGroup {
                    blocks: self.clusters[k].blocks.len(),
                    a_g_lo_m_s2: lo_q.as_ref().map(Q::to_f64),
                    a_g_hi_m_s2: hi_q.as_ref().map(Q::to_f64),
                    lo_is_bound: bound_only[0],
                    hi_is_bound: bound_only[1],
                }),
                Motion::Sliding(_) => None,
            })
            .max_by_key(|g| g.blocks)
    }

    /// Velocities within round-off of each other are equal.
    fn same_velocity(&self, a: f64, b: f64) -> bool {
        (a - b).abs() <= self.vel_tol(a, b)
    }

    /// Calls `f(k, other)` for each live support and touching vertical joint of the component's
    /// block `blocks[k]`: `other` is the local index of the block on the other side, or `None`
    /// for the ground or an abutment; joints to blocks outside the component are left out.
    fn for_each_pair(
        &self,
        blocks: &[usize],
        local: &Local,
        mut f: impl FnMut(usize, Option<usize>),
    ) {
        for (k, &b) in blocks.iter().enumerate() {
            for other in self.live_neighbours(b) {
                match other.filter(|&o| !self.fixed[o]) {
                    None => f(k, None),
                    Some(o) => {
                        if let Some(&m) = local.get(&o) {
                            f(k, Some(m));
                        }
                    }
                }
            }
            for &j in &self.topo.sides[b] {
                if !self.live_joint(j.0) || !self.is_touching(j.0) {
                    continue;
                }
                let o = self.across_joint(j.0, b);
                if self.fixed[o] {
                    f(k, None);
                } else if let Some(&m) = local.get(&o) {
                    f(k, Some(m));
                }
            }
        }
    }

    /// Joints whose two sides move with velocities equal within round-off are undecided: give
    /// each group of blocks so joined one velocity, their momentum-weighted mean (zero if the
    /// group is joined to the ground), so the decision sees exact equality. Without this, a
    /// block resting on two supports whose velocities differ by round-off meets each in turn,
    /// one ulp apart, for ever.
    fn equalize_velocities(
        &self,
        blocks: &[usize],
        local: &Local,
        snap: &mut Snap,
        v: &mut Vec<f64>,
    ) {
        let n = blocks.len();
        v.clear();
        v.extend(blocks.iter().map(|&b| self.vel_with(b, snap)));
        // Velocities a and b count as equal; the second flag: only within round-off.
        let near = |a: f64, b: f64| (self.same_velocity(a, b), a != b);
        let other_velocity = |other: Option<usize>| other.map_or(0.0, |m| v[m]);
        // Whether some velocities are equal within round-off but not exactly (else: done).
        let mut inexact = false;
        self.for_each_pair(blocks, local, |k, other| {
            let (same, off) = near(v[k], other_velocity(other));
            inexact |= same && off;
        });
        if !inexact {
            return;
        }
        let mut sets = DisjointSets::new(n);
        let mut grounded = vec![false; n];
        self.for_each_pair(blocks, local, |k, other| {
            if near(v[k], other_velocity(other)).0 {
                match other {
                    None => grounded[k] = true,
                    Some(m) => sets.join(k, m),
                }
            }
        });
        let mut groups: FxHashMap<usize, Vec<usize>> = FxHashMap::default();
        for k in 0..n {
            let r = sets.find(k);
            groups.entry(r).or_default().push(k);
        }
        for members in groups.values() {
            let distinct = members.iter().any(|&k| v[k] != v[members[0]]);
            let on_ground = members.iter().any(|&k| grounded[k]);
            let needs = distinct || (on_ground && v[members[0]] != 0.0);
            if !needs {
                continue;
            }
            let common = if on_ground {
                0.0
            } else {
                let (p, m) = members.iter().fold((0.0, 0.0), |(p, m), &k| {
                    (p + self.mass[blocks[k]] * v[k], m + self.mass[blocks[k]])
                });
                p / m
            };
            for &k in members {
                snap.insert(blocks[k], common);
            }
        }
    }

    /// Faces of joint j touch (their gap is zero within round-off).
    pub(super) fn is_touching(&self, j: usize) -> bool {
        let jt = &self.topo.joints[j];
        let (ul, ur) = (self.block_disp(jt.left.0), self.block_disp(jt.right.0));
        (self.gap0[j] + ur - ul).abs() <= self.len_tol(ul, ur)
    }

    fn alloc(&mut self, c: Cluster) -> usize {
        match self.free.pop() {
            Some(k) => {
                self.clusters[k] = c;
                k
            }
            None => {
                self.clusters.push(c);
                self.clusters.len() - 1
            }
        }
    }

    /// Constant external friction on each block of cluster k from joints that slide.
    pub(super) fn external_forces(&self, k: usize) -> Vec<Q> {
        self.clusters[k]
            .blocks
            .iter()
            .map(|&i| self.external_force(i))
            .collect()
    }

    /// Constant friction on block i from its joints that slide, by their recorded directions.
    fn external_force(&self, i: usize) -> Q {
        self.external_force_by(i, |s| self.dir[s])
    }

    /// The same with each support's direction given by `dir`.
    pub(super) fn external_force_by(&self, i: usize, dir: impl Fn(usize) -> i8) -> Q {
        let mut e = Q::zero();
        for &s in &self.topo.below[i] {
            let d = dir(s.0);
            if self.live_support(s.0) && d != 0 {
                e = if d > 0 {
                    e - &self.cap_q[s.0]
                } else {
                    e + &self.cap_q[s.0]
                };
            }
        }
        for &s in &self.topo.above[i] {
            let d = dir(s.0);
            if self.live_support(s.0) && d != 0 {
                e = if d > 0 {
                    e + &self.cap_q[s.0]
                } else {
                    e - &self.cap_q[s.0]
                };
            }
        }
        e
    }

    /// The general decision. Only the signs of the ground acceleration's derivatives matter
    /// (they order ties, and every tie compares the same mass combination), so theta is
    /// normalised to them; decisions away from the ground, or at a stick threshold (an exact
    /// value met again cycle after cycle), are remembered per run ([`Memo`](super::memo::Memo)).
    fn solve(
        &mut self,
        p: &Problem,
        theta: &Lex,
        remember: bool,
        bodies: &[Vec<usize>],
    ) -> Vec<Group> {
        let sign = |q: &Q| Q::int(i64::from(q.signum()));
        let theta = if p.touches_ground() {
            let second = if theta.0[1].is_zero() {
                sign(&theta.0[2])
            } else {
                Q::zero()
            };
            Lex([theta.0[0].clone(), sign(&theta.0[1]), second])
        } else {
            Lex::zero()
        };
        if !remember && p.touches_ground() {
            return self.solve_anew(p, &theta, bodies);
        }
        let known = self.free_memo.get(p);
        if let Some((_, found)) = known.and_then(|k| k.iter().find(|(at, _)| *at == theta)) {
            return found.clone();
        }
        let found = self.solve_anew(p, &theta, bodies);
        match self.free_memo.get_mut(p) {
            Some(known) => {
                if known.len() == THETAS_KEPT {
                    known.remove(0);
                }
                known.push((theta, found.clone()));
            }
            None => self
                .free_memo
                .insert(p.clone(), vec![(theta, found.clone())], p.mass.len()),
        }
        found
    }

    /// Problem p decided at `theta`; at a limit of its own remembered stick interval (a stuck
    /// cluster reaching it), without the two cuts at the ground ([`Problem::solve_past_limit`]).
    fn solve_anew(&self, p: &Problem, theta: &Lex, bodies: &[Vec<usize>]) -> Vec<Group> {
        p.touches_ground()
            .then(|| self.stick_memo.get(p))
            .flatten()
            .and_then(|stick| p.solve_past_limit(theta, bodies, stick))
            .unwrap_or_else(|| p.solve(theta, bodies))
    }

    /// The general decision of problem p at the ground acceleration `theta`, snapping theta to
    /// a breakpoint that rounding hides: the motion will start from the float c lambda - a_g
    /// (`Slide::formed`), and if rounding gives it no sign, or the wrong one, the group's
    /// breakpoint is in fact where the ground is. `theta` comes back snapped.
    pub(super) fn decide_general(
        &mut self,
        p: &Problem,
        theta: &mut Lex,
        remember: bool,
        bodies: &[Vec<usize>],
    ) -> Vec<Group> {
        let mut groups = self.solve(p, theta, remember, bodies);
        for _ in 0..MAX_SNAPS {
            let (lambda, ag) = (self.seg.lambda_at(self.s()), self.seg.accel(self.s()));
            let hidden = groups.iter().find(|g| {
                let rel = g.accel.to_f64() * lambda - ag;
                let exact = (&g.accel - &theta.0[0]).signum();
                !g.grounded
                    && exact != 0
                    && (rel == 0.0 || (rel > 0.0) != (exact > 0))
                    && touches_ground(p, &groups, g)
            });
            match hidden {
                Some(g) => {
                    theta.0[0] = g.accel.clone();
                    groups = self.solve(p, theta, false, bodies);
                }
                None => break,
            }
        }
        groups
    }

    /// A neighbour of the re-decided clusters one of whose joints the decision turned (after an
    /// impact): its friction forces have changed; it gets a new version and fresh events.
    fn refresh(&mut self, k: usize, before: &Before) {
        let t = self.t;
        match &self.clusters[k].motion {
            Motion::Stuck { .. } => self.set_thresholds(k, Some(before)),
            Motion::Sliding(sl) => {
                let force: Q = self.external_forces(k).into_iter().sum();
                let c_q = force / &self.clusters[k].mass_q;
                if c_q != sl.c_q {
                    self.account(k, t);
                    self.record_extremes(k);
                    let v = self.cluster_vel(k);
                    let members = self.clusters[k].blocks.clone();
                    for &i in &members {
                        self.u_ref[i] = self.block_disp(i);
                    }
                    self.clusters[k].motion =
                        Motion::Sliding(Slide::formed(&self.seg, self.t, v, c_q));
                    self.clusters[k].roots = None;
                    self.clusters[k].ground_hits = None;
                }
            }
        }
        self.clusters[k].version = self.new_version();
    }

    /// Block i has fallen (`--after-collapse continue`): remove it and its load, let whatever
    /// rested only on it fall too, and re-decide the whole wall.
    pub(super) fn remove_fallen(&mut self, first: usize) -> Result<(), SimulationError> {
        let mut falling = vec![first];
        while let Some(i) = falling.pop() {
            if self.fallen[i] {
                continue;
            }
            let v = self.block_vel(i);
            self.rec.energy.fallen_j += 0.5 * self.mass[i] * v * v;
            for s in self.topo.below[i].iter().chain(&self.topo.above[i]) {
                self.account_support(s.0);
            }
            if self.of[i] != NONE {
                let k = self.of[i];
                self.account(k, self.t);
                self.record_extremes(k);
            }
            self.u_ref[i] = self.block_disp(i);
            self.fallen[i] = true;
            self.rec.fell(i);
            for &s in &self.topo.above[i] {
                let up = self.topo.supports[s.0].upper.0;
                if !self.fallen[up] && !self.stands(up) {
                    self.rec
                        .event(self.t, EventKind::Collapse, &[up], None, None);
                    falling.push(up);
                }
            }
        }
        // Capacities change with the loads: friction work so far is owed at the old ones.
        for s in 0..self.topo.supports.len() {
            self.account_support(s);
        }
        let loads = self.topo.loads_without(self.wall, &self.fallen);
        for (s, load) in loads.into_iter().enumerate() {
            self.cap_q[s] = &self.topo.supports[s].friction * &load;
            self.cap[s] = self.cap_q[s].to_f64();
        }
        // Dissolve every cluster; blocks keep their velocities.
        let live: Vec<usize> = (0..self.n)
            .filter(|&i| !self.fixed[i] && !self.fallen[i])
            .collect();
        let snap: Vec<(usize, f64)> = live.iter().map(|&i| (i, self.block_vel(i))).collect();
        for k in 0..self.clusters.len() {
            if self.clusters[k].blocks.is_empty() {
                continue;
            }
            self.account(k, self.t);
            self.record_extremes(k);
            let moved = self.cluster_disp(k);
            let members = std::mem::take(&mut self.clusters[k].blocks);
            for i in members {
                self.u_ref[i] += moved;
                self.of[i] = NONE;
            }
            self.clusters[k].version = self.new_version();
            self.free.push(k);
        }
        for &(i, v) in &snap {
            // Each block alone for a moment, with its own velocity, until the decision regroups.
            let k = self.alloc(Cluster {
                mass: self.mass[i],
                mass_q: self.mass_q[i].clone(),
                blocks: vec![i],
                version: 0,
                ground_version: 0,
                motion: Motion::Sliding(Slide::formed(&self.seg, self.t, v, Q::zero())),
                accounted_to: self.t,
                roots: None,
                ground_hits: None,
                extremes: Default::default(),
                boundary: OnceCell::new(),
            });
            self.of[i] = k;
        }
        for s in 0..self.dir.len() {
            if !self.live_support(s) {
                self.dir[s] = 0;
            }
        }
        self.decide_from(&live, &snap, None, Cause::Fall)
    }
}

/// Does group g share an undecided joint with the ground or a stuck group?
fn touches_ground(p: &Problem, groups: &[Group], g: &Group) -> bool {
    let grounded_node = |n: usize| groups.iter().any(|h| h.grounded && h.nodes.contains(&n));
    let inside = |n: usize| g.nodes.contains(&n);
    p.friction.iter().any(|(i, j, _)| match j {
        End::Ground => inside(*i),
        End::Node(j) => (inside(*i) && grounded_node(*j)) || (inside(*j) && grounded_node(*i)),
    }) || p.contacts.iter().any(|(l, r)| match (l, r) {
        (End::Ground, End::Node(n)) | (End::Node(n), End::Ground) => inside(*n),
        (End::Node(a), End::Node(b)) => {
            (inside(*a) && grounded_node(*b)) || (inside(*b) && grounded_node(*a))
        }
        _ => false,
    })
}
