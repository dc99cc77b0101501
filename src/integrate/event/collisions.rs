//! Impacts in the engine: faces that meet, the chain of touching blocks an impact reaches
//! (resolved exactly by [`impact::resolve`]), other chains that collide at the same instant on
//! the same clusters, and Zeno series of bounces summed in closed form.

use super::cluster::ClusterId;
use super::{cluster, impact, Engine};
use crate::error::{name_list, SimulationError};
use crate::exact::Q;
use crate::response::{DecisionCause as Cause, EventKind};
use crate::topology::{JointRef, VerticalId};
use std::collections::HashMap;

/// The blocks an impact reaches through touching faces ([`impact::resolve`]'s input).
struct Chain {
    /// Each block with its mass and velocity; the ground and abutments have no mass.
    bodies: Vec<(usize, impact::Body)>,
    /// Touching faces (left body, right body, joint), left to right.
    faces: Vec<(usize, usize, usize)>,
}

impl Engine<'_> {
    /// A vertical joint closes: an impact if the faces approach, a touch otherwise.
    pub(super) fn faces_meet(&mut self, j: usize) -> Result<(), SimulationError> {
        let (l, r) = (
            self.given.topo.vertical[j].left.0,
            self.given.topo.vertical[j].right.0,
        );
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
            Some(JointRef::Vertical(VerticalId(j))),
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
            if self.of[i] != ClusterId::NONE {
                seeds.extend(self.clusters[self.of[i]].blocks.iter().copied());
            }
        }
        let set_vel: Vec<(usize, f64)> = seeds
            .iter()
            .filter(|&&i| !self.grounded(i))
            .map(|&i| (i, v))
            .collect();
        self.regroup(&seeds, &set_vel, None, Cause::Touch)
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
            let jt = &self.given.topo.vertical[jj];
            let mut ids = [0usize; 2];
            for (slot, blk) in [jt.left.0, jt.right.0].into_iter().enumerate() {
                let key = if self.given.fixed[blk] {
                    usize::MAX - blk
                } else {
                    blk
                };
                let id = *bodies_of.entry(key).or_insert_with(|| {
                    chain.bodies.push((
                        blk,
                        impact::Body {
                            mass: (!self.given.fixed[blk]).then(|| self.given.mass_q[blk].clone()),
                            velocity: Q::from_f64_exact(self.block_vel(blk))
                                .expect("velocities are finite"),
                        },
                    ));
                    chain.bodies.len() - 1
                });
                ids[slot] = id;
                if !self.given.fixed[blk] {
                    for &side in &self.given.topo.sides[blk] {
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
            self.given.xl[self.given.topo.vertical[p.2].right.0]
                .total_cmp(&self.given.xl[self.given.topo.vertical[q.2].right.0])
        });
        chain
    }

    /// Joint j, a side of block `blk`, is live and its faces touch.
    fn closed(&self, j: usize, blk: usize) -> bool {
        self.live_vertical(j) && self.gap(j).abs() <= self.len_tol(self.block_disp(blk), 0.0)
    }

    /// The faces of joint j approach: closed, they collide.
    fn approaching(&self, j: usize) -> bool {
        let (vl, vr) = (
            self.block_vel(self.given.topo.vertical[j].left.0),
            self.block_vel(self.given.topo.vertical[j].right.0),
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
        let n = chain.bodies.len();
        let most = self
            .given
            .params
            .max_collisions_per_chain
            .unwrap_or(100_000 + n * n);
        let names = || {
            name_list(
                chain
                    .bodies
                    .iter()
                    .map(|b| self.given.wall.blocks[b.0].name.as_str()),
                6,
            )
        };
        let (collisions, loss) = match impact::resolve(
            &mut exact,
            &pairs,
            &self.given.restitution,
            &negligible,
            most,
        ) {
            Ok(done) => done,
            Err((impact::Unsettled::Cycle { period }, count)) => {
                return Err(SimulationError::ImpactCycle {
                    time_s: self.t,
                    blocks: names(),
                    count,
                    period,
                })
            }
            Err((impact::Unsettled::Backstop, count)) => {
                return Err(SimulationError::ImpactChain {
                    time_s: self.t,
                    blocks: names(),
                    count,
                })
            }
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
        let mut scanned: Vec<ClusterId> = Vec::new();
        let mut next = 0;
        while next < chains.len() {
            let hit: Vec<usize> = chains[next]
                .0
                .bodies
                .iter()
                .map(|b| b.0)
                .filter(|&b| !self.given.fixed[b])
                .collect();
            next += 1;
            for b in hit {
                let k = self.of[b];
                let members = match k {
                    ClusterId::NONE => std::slice::from_ref(&b),
                    k if scanned.contains(&k) => continue,
                    k => {
                        scanned.push(k);
                        &self.clusters[k].blocks[..]
                    }
                };
                for &m in members {
                    for &side in &self.given.topo.sides[m] {
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
        let mut seen = vec![false; self.given.topo.vertical.len()];
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
                let (l, r) = (
                    self.given.topo.vertical[jj].left.0,
                    self.given.topo.vertical[jj].right.0,
                );
                self.rec.event(
                    t_acc,
                    EventKind::Zeno,
                    &[l, r],
                    Some(JointRef::Vertical(VerticalId(jj))),
                    None,
                );
                self.rec.zeno += 1;
                let v = common.to_f64();
                return self.regroup(&[l, r], &[(l, v), (r, v)], None, Cause::Zeno);
            }
        }
        let mut chains = vec![(first, collisions, loss, exact)];
        self.simultaneous_chains(&mut chains, &mut seen)?;
        let mut seeds = Vec::new();
        let mut set_vel = Vec::new();
        for (chain, collisions, loss, exact) in &chains {
            self.record_collisions(chain, collisions);
            self.rec.energy.impact_loss_j += loss.to_f64();
            for (k, (blk, _)) in chain.bodies.iter().enumerate() {
                if self.given.fixed[*blk] {
                    continue;
                }
                let v = exact[k].velocity.to_f64();
                if v != self.block_vel(*blk) {
                    set_vel.push((*blk, v));
                }
                seeds.push(*blk);
            }
        }
        self.regroup(&seeds, &set_vel, None, Cause::Impact)
    }

    /// Logs a chain's collisions; their faces touch from now on.
    fn record_collisions(&mut self, chain: &Chain, collisions: &[impact::Collision]) {
        for c in collisions {
            let jj = chain.faces[c.face].2;
            self.touching[jj] = true;
            let pair = |v: &[Q; 2]| [v[0].to_f64(), v[1].to_f64()];
            self.rec
                .impact(self.t, VerticalId(jj), pair(&c.before), pair(&c.after));
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
        let e = &self.given.restitution;
        let (l, r) = (
            self.given.topo.vertical[j].left.0,
            self.given.topo.vertical[j].right.0,
        );
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
        let (a_min, a_max) = self.given.motion.accel_range(self.t, t_acc);
        for b in [l, r] {
            let vb = self.block_vel(b);
            let cb = self.clusters[self.of[b]].slide()?.c;
            for other in self.live_neighbours(b) {
                let w = vb - other.map_or(0.0, |o| self.block_vel(o));
                let (dw_lo, dw_hi) = match other
                    .filter(|&o| self.of[o] != ClusterId::NONE)
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
        let earliest = self.queue.earliest(&self.clusters);
        (t_acc < earliest && t_acc < self.given.t_end).then_some(t_acc)
    }

    /// The slides of the two blocks of joint j where a Zeno series is possible between them: 0 <
    /// e < 1, no vertical shaking, and each block sliding alone.
    fn alone_sliding(&self, j: usize) -> Option<(&cluster::Slide, &cluster::Slide)> {
        let e = &self.given.restitution;
        if !(e.is_positive() && *e < Q::one()) || self.given.motion.has_vertical() {
            return None;
        }
        let (l, r) = (
            self.given.topo.vertical[j].left.0,
            self.given.topo.vertical[j].right.0,
        );
        let (kl, kr) = (self.of[l], self.of[r]);
        if kl == ClusterId::NONE
            || kr == ClusterId::NONE
            || self.clusters[kl].blocks.len() != 1
            || self.clusters[kr].blocks.len() != 1
        {
            return None;
        }
        Some((self.clusters[kl].slide()?, self.clusters[kr].slide()?))
    }
}
