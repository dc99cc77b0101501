//! Steps 1 and 3 of a regrouping: the component of an event (whole clusters joined through
//! joints whose sides move with equal velocities, those velocities made equal where they agree
//! within round-off), and its exact decision problem (masses, the friction of sliding joints as
//! external forces, the joints still undecided).

use super::scratch::{Equal, Local, SetVel};
use crate::exact::Q;
use crate::integrate::event::cluster::ClusterId;
use crate::integrate::event::cluster::Mode;
use crate::integrate::event::slip::Slip;
use crate::integrate::event::solver::BODY_FROM;
use crate::integrate::event::solver::{End, Problem};
use crate::integrate::event::Engine;
use crate::response::StuckGroup;

impl Engine<'_> {
    /// Velocity of block i with the given overrides.
    pub(super) fn vel_with(&self, i: usize, set_vel: &SetVel) -> f64 {
        set_vel.get(i).unwrap_or_else(|| self.block_vel(i))
    }

    /// Step 1 of [`Engine::regroup`]: the blocks of the component (whole clusters joined to
    /// `seeds` through joints whose sides move with equal velocities), in the order found, with
    /// their local indices, the old clusters they come from, and `queue` left empty.
    pub(super) fn gather(
        &self,
        seeds: &[usize],
        set_vel: &SetVel,
        local: &mut Local,
        blocks: &mut Vec<usize>,
        old_clusters: &mut Vec<ClusterId>,
        queue: &mut Vec<usize>,
    ) {
        let add = |b: usize,
                   this: &Engine,
                   local: &mut Local,
                   blocks: &mut Vec<usize>,
                   old: &mut Vec<ClusterId>,
                   queue: &mut Vec<usize>| {
            // Once per cluster: its first block brings in all the others.
            let members: &[usize] = match this.of[b] {
                ClusterId::NONE => std::slice::from_ref(&b),
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
            if !self.given.fixed[b] && !self.fallen[b] && !local.contains_key(&b) {
                add(b, self, local, blocks, old_clusters, queue);
            }
        }
        while let Some(i) = queue.pop() {
            let vi = self.vel_with(i, set_vel);
            for other in self.live_neighbours(i) {
                if let Some(o) = other.filter(|&o| !self.given.fixed[o]) {
                    if !local.contains_key(&o) && self.same_velocity(vi, self.vel_with(o, set_vel))
                    {
                        add(o, self, local, blocks, old_clusters, queue);
                    }
                }
            }
            for &j in &self.given.topo.sides[i] {
                if !self.live_vertical(j.0) || !self.is_touching(j.0) {
                    continue;
                }
                let o = self.across_vertical(j.0, i);
                if !self.given.fixed[o]
                    && !local.contains_key(&o)
                    && self.same_velocity(vi, self.vel_with(o, set_vel))
                {
                    add(o, self, local, blocks, old_clusters, queue);
                }
            }
        }
    }

    /// Step 3 of [`Engine::regroup`]: the decision problem of the component `blocks` (in
    /// `p`, empty): their masses, the friction of joints that slide as external forces, the
    /// joints and touching faces whose sides move with equal velocities as undecided.
    pub(super) fn problem_of(
        &self,
        p: &mut Problem,
        blocks: &[usize],
        local: &Local,
        set_vel: &SetVel,
        touched_horizontal: &[usize],
        touched_vertical: &[usize],
    ) {
        p.mass
            .extend(blocks.iter().map(|&i| self.given.mass_q[i].clone()));
        p.external.resize(blocks.len(), Q::zero());
        for &s in touched_horizontal {
            if !self.live_horizontal(s) {
                continue;
            }
            let (up, lo) = self.horizontal_ends(s);
            let (vu, vl) = (
                self.vel_with(up, set_vel),
                lo.map_or(0.0, |l| self.vel_with(l, set_vel)),
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
                p.friction.push((u, end, self.given.cap_q[s].clone()));
            } else {
                // Sliding: friction opposes the relative velocity (or, when the far side is
                // outside and moving with it, its recorded direction).
                let slip = if vu != vl {
                    Slip::of(vu.total_cmp(&vl))
                } else {
                    self.slip[s]
                };
                let f = slip.on_upper(&self.given.cap_q[s]);
                if let Some(k) = lu {
                    p.external[k] = &p.external[k] + &f;
                }
                if let Some(k) = ll {
                    p.external[k] = &p.external[k] - &f;
                }
            }
        }
        for &j in touched_vertical {
            if !self.live_vertical(j) || !self.is_touching(j) {
                continue;
            }
            let jt = &self.given.topo.vertical[j];
            let (l, r) = (jt.left.0, jt.right.0);
            let end = |b: usize| {
                if self.given.fixed[b] {
                    Some(End::Ground)
                } else {
                    local.get(&b).map(|&k| End::Node(k))
                }
            };
            let (vl, vr) = (self.vel_with(l, set_vel), self.vel_with(r, set_vel));
            if let (Some(el), Some(er)) = (end(l), end(r)) {
                if vl == vr {
                    p.contacts.push((el, er));
                }
            }
        }
    }

    /// Large clusters of the component that slid as one body until now (see `Problem::solve`),
    /// each cut by velocity: the blocks an impact hits leave with velocities of their own, and
    /// held to the rest they would fail the first try, which costs a cut over the body.
    pub(super) fn sliding_bodies(
        &self,
        old_clusters: &[ClusterId],
        local: &Local,
        set_vel: &SetVel,
    ) -> Vec<Vec<usize>> {
        let mut bodies: Vec<Vec<usize>> = Vec::new();
        for c in old_clusters.iter().map(|&k| &self.clusters[k]) {
            if c.slide().is_none() || c.blocks.len() < BODY_FROM {
                continue;
            }
            let mut by_velocity: Vec<(f64, Vec<usize>)> = Vec::new();
            for b in &c.blocks {
                let v = self.vel_with(*b, set_vel);
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
    pub(super) fn horizontal_ends(&self, s: usize) -> (usize, Option<usize>) {
        let up = self.given.topo.horizontal[s].upper.0;
        (up, self.lower_block(s).filter(|&l| !self.given.fixed[l]))
    }

    /// The largest of these clusters that is stuck to the ground, for the decision log.
    pub(super) fn largest_stuck(&self, clusters: &[ClusterId]) -> Option<StuckGroup> {
        clusters
            .iter()
            .filter_map(|&k| match &self.clusters[k].mode {
                Mode::Stuck {
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
                Mode::Sliding(_) => None,
            })
            .max_by_key(|g| g.blocks)
    }

    /// Velocities within round-off of each other are equal.
    pub(super) fn same_velocity(&self, a: f64, b: f64) -> bool {
        (a - b).abs() <= self.vel_tol(a, b)
    }

    /// Calls `f(k, other)` for each live horizontal joint and touching vertical joint of the component's
    /// block `blocks[k]`: `other` is the local index of the block on the other side, or `None`
    /// for the ground or an abutment; joints to blocks outside the component are left out.
    pub(super) fn for_each_pair(
        &self,
        blocks: &[usize],
        local: &Local,
        mut f: impl FnMut(usize, Option<usize>),
    ) {
        for (k, &b) in blocks.iter().enumerate() {
            for other in self.live_neighbours(b) {
                match other.filter(|&o| !self.given.fixed[o]) {
                    None => f(k, None),
                    Some(o) => {
                        if let Some(&m) = local.get(&o) {
                            f(k, Some(m));
                        }
                    }
                }
            }
            for &j in &self.given.topo.sides[b] {
                if !self.live_vertical(j.0) || !self.is_touching(j.0) {
                    continue;
                }
                let o = self.across_vertical(j.0, b);
                if self.given.fixed[o] {
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
    pub(super) fn equalize_velocities(
        &self,
        blocks: &[usize],
        local: &Local,
        set_vel: &mut SetVel,
        v: &mut Vec<f64>,
        equal: &mut Equal,
    ) {
        let n = blocks.len();
        v.clear();
        v.extend(blocks.iter().map(|&b| self.vel_with(b, set_vel)));
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
        let Equal {
            sets,
            grounded,
            by_set,
        } = equal;
        sets.reset(n);
        grounded.clear();
        grounded.resize(n, false);
        self.for_each_pair(blocks, local, |k, other| {
            if near(v[k], other_velocity(other)).0 {
                match other {
                    None => grounded[k] = true,
                    Some(m) => sets.join(k, m),
                }
            }
        });
        // The blocks of each set together, each set's in order.
        by_set.clear();
        by_set.extend((0..n).map(|k| (sets.find(k), k)));
        by_set.sort_unstable();
        for set in by_set.chunk_by(|a, b| a.0 == b.0) {
            let members = || set.iter().map(|&(_, k)| k);
            let first = v[set[0].1];
            let distinct = members().any(|k| v[k] != first);
            let on_ground = members().any(|k| grounded[k]);
            let needs = distinct || (on_ground && first != 0.0);
            if !needs {
                continue;
            }
            let common = if on_ground {
                0.0
            } else {
                let (p, m) = members().fold((0.0, 0.0), |(p, m), k| {
                    (
                        p + self.given.mass[blocks[k]] * v[k],
                        m + self.given.mass[blocks[k]],
                    )
                });
                p / m
            };
            for k in members() {
                set_vel.insert(blocks[k], common);
            }
        }
    }

    /// Faces of joint j touch (their gap is zero within round-off).
    pub(in crate::integrate::event) fn is_touching(&self, j: usize) -> bool {
        let jt = &self.given.topo.vertical[j];
        let (ul, ur) = (self.block_disp(jt.left.0), self.block_disp(jt.right.0));
        (self.given.gap0[j] + ur - ul).abs() <= self.len_tol(ul, ur)
    }
}
