//! Re-deciding the mode around an event: gather the blocks whose joints became undecided, solve
//! their decision problem exactly, install the new clusters, and update the neighbours whose
//! friction forces changed.

mod component;
mod fallen;
pub(super) mod scratch;
mod solving;

use super::cluster::ClusterId;
use scratch::SetVel;
pub(super) use scratch::{After, Before, Buffers, Local};

use super::cluster::{Cluster, Mode, Slide};
use super::flow;
use super::slip::Slip;
use super::solver::Lex;
use super::stuck::stuck;
use super::Engine;
use crate::clock::ThreadClock;
use crate::error::SimulationError;
use crate::exact::Q;
use crate::response::{DecisionCause as Cause, DecisionRecord, EventKind};
use crate::topology::{HorizontalId, JointRef, VerticalId};
use std::cell::OnceCell;

impl Engine<'_> {
    /// Re-decides the mode of the clusters of `seeds` and of every cluster joined to them by a
    /// joint with zero relative velocity. `set_vel` overrides block velocities (set to exactly zero at
    /// a stop, to a common value where two clusters meet, after an impact); `theta` is the exact
    /// ground acceleration when the event is a stick threshold; `cause` goes into the decision
    /// log.
    pub(super) fn regroup(
        &mut self,
        seeds: &[usize],
        set_vel: &[(usize, f64)],
        theta: Option<Q>,
        cause: Cause,
    ) -> Result<(), SimulationError> {
        self.rec.stats.mode_decisions += 1;
        let log_from = self
            .rec
            .logs_decisions()
            .then(|| (ThreadClock::start(), flow::pass_nodes()));
        let t = self.t;

        // 1. The component: whole clusters joined through joints with equal velocities.
        let mut buf = std::mem::take(&mut self.scratch.decisions);
        let mut set_vel = {
            let (vel, set) = (
                std::mem::take(&mut buf.set_vel),
                std::mem::take(&mut buf.set_vel_blocks),
            );
            let mut table = SetVel::reuse(vel, set, self.given.n);
            for &(i, v) in set_vel {
                table.insert(i, v);
            }
            table
        };
        let mut local = Local::reuse(std::mem::take(&mut buf.local), self.given.n);
        let mut blocks = std::mem::take(&mut buf.blocks);
        let mut old_clusters = std::mem::take(&mut buf.old);
        let mut queue = std::mem::take(&mut buf.queue);
        self.gather(
            seeds,
            &set_vel,
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
        self.equalize_velocities(&blocks, &local, &mut set_vel, &mut buf.v, &mut buf.equal);

        // 2. Account what the old clusters did up to now, and the joints around them.
        for &k in &old_clusters {
            self.account(k, t);
        }
        let mut touched_horizontal = std::mem::take(&mut buf.horizontal);
        let mut touched_vertical = std::mem::take(&mut buf.vertical);
        for &i in &blocks {
            touched_horizontal.extend(
                self.given.topo.below[i]
                    .iter()
                    .chain(&self.given.topo.above[i])
                    .map(|s| s.0),
            );
            touched_vertical.extend(self.given.topo.sides[i].iter().map(|j| j.0));
        }
        for touched in [&mut touched_horizontal, &mut touched_vertical] {
            touched.sort_unstable();
            touched.dedup();
        }
        for &s in &touched_horizontal {
            self.account_horizontal(s);
        }
        let (u_now, v_now) = (&mut buf.u, &mut buf.v);
        u_now.extend(blocks.iter().map(|&i| self.block_disp(i)));
        v_now.clear();
        v_now.extend(blocks.iter().map(|&i| self.vel_with(i, &set_vel)));

        // 3. The decision problem.
        let mut p = std::mem::take(&mut buf.problem);
        self.problem_of(
            &mut p,
            &blocks,
            &local,
            &set_vel,
            &touched_horizontal,
            &touched_vertical,
        );
        let p = p.canonical();

        // 4. Solve: stuck pieces by their stick intervals, the rest by the general decision.
        let mut decided = std::mem::take(&mut buf.decided);
        let bodies = |e: &Self| e.sliding_bodies(&old_clusters, &local, &set_vel);
        let theta_lex = self.solve_component(&p, &blocks, bodies, theta.as_ref(), &mut decided);
        let (groups, intervals) = (&decided.groups, &decided.intervals);

        // 5. Install the new clusters, keeping what the intervals after it may need.
        let mut after = std::mem::take(&mut self.scratch.after);
        if blocks.len() >= self.given.params.kept_limits_from {
            for &b in &blocks {
                after.before.of.insert(b, self.of[b]);
            }
            for &k in &old_clusters {
                let limits = match &self.clusters[k].mode {
                    Mode::Stuck { lo_q, hi_q, .. } => Some([lo_q.clone(), hi_q.clone()]),
                    Mode::Sliding(_) => None,
                };
                after.before.limits.insert(k, limits);
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
            let mass_q: Q = members.iter().map(|&i| self.given.mass_q[i].clone()).sum();
            let mode = if g.grounded {
                stuck(intervals[g_idx].clone().unwrap_or_default())
            } else {
                let v = v_now[g.nodes[0]];
                Mode::Sliding(Slide::formed(&self.seg, self.t, v, g.accel.clone()))
            };
            let k = self.alloc(Cluster {
                mass: mass_q.to_f64(),
                mass_q,
                blocks: members,
                version: 0,
                ground_version: 0,
                mode,
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
                after.needs_interval.push(k);
            }
            after.new_clusters.push(k);
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
        self.turn_joints(
            &touched_horizontal,
            &touched_vertical,
            &local,
            &set_vel,
            &accel_of,
            &mut after,
        );
        // The working memory goes back before anything below decides again.
        buf.local = local.release(&blocks);
        buf.problem = p.cleared();
        (buf.set_vel, buf.set_vel_blocks) = set_vel.release();
        for (v, kept) in [
            (blocks, &mut buf.blocks),
            (queue, &mut buf.queue),
            (touched_horizontal, &mut buf.horizontal),
            (touched_vertical, &mut buf.vertical),
        ] {
            *kept = v;
            kept.clear();
        }
        buf.old = old_clusters;
        buf.old.clear();
        buf.u.clear();
        buf.v.clear();
        buf.group_of.clear();
        decided.clear();
        buf.decided = decided;
        self.scratch.decisions = buf;
        // Neighbours hold blocks outside the component only, so none is a new cluster.
        for set in [&mut after.neighbours, &mut after.pushed] {
            set.sort_unstable();
            set.dedup();
        }
        // A stuck neighbour none of whose joints turned keeps its problem, so its interval and
        // events stand. A sliding one keeps its motion and its events with the sliding clusters
        // that did not change (those with the new ones come with theirs); what it slides
        // against has changed, so its events against the ground side are found again. A large
        // body beside a small decision then costs a pass over its own blocks, not one over every
        // sliding cluster along it.
        let After {
            neighbours,
            pushed,
            quiet,
            ..
        } = &mut after;
        quiet.extend(
            neighbours.iter().copied().filter(|k| {
                pushed.binary_search(k).is_err() && self.clusters[*k].slide().is_some()
            }),
        );

        // 7. Stuck clusters get their threshold interval; neighbours whose friction changed move
        //    on with their new forces.
        for &k in &after.needs_interval {
            self.set_thresholds(k, Some(&after.before));
        }
        for &k in &after.new_clusters {
            self.clusters[k].version = self.new_version();
        }
        for &k in &after.pushed {
            self.refresh(k, &after.before);
        }
        for &k in &after.quiet {
            self.clusters[k].ground_version = self.new_version();
            self.schedule_segment(k);
        }
        self.schedule(after.new_clusters.iter().chain(&after.pushed).copied());
        if let (Some((clock, nodes_from)), Some((blocks, stuck_taken_in))) = (log_from, taken_in) {
            let record = DecisionRecord {
                time_s: t,
                cause,
                a_g_m_s2: self.seg.accel(self.s()),
                load_factor: self.seg.lambda_at(self.s()),
                blocks,
                stuck_taken_in,
                clusters: after.new_clusters.len(),
                stuck_formed: self.largest_stuck(&after.new_clusters),
                flow_nodes: flow::pass_nodes() - nodes_from,
                cpu_s: clock.seconds(),
            };
            self.rec.decision(record);
        }

        // 8. A sliding cluster of several blocks whose friction forces changed may have to split:
        //    re-decide it (a stuck one has its new stick interval, which is checked at once).
        let pushed = std::mem::take(&mut after.pushed);
        self.scratch.after = after.cleared();
        for &k in &pushed {
            let blocks = &self.clusters[k].blocks;
            if blocks.len() > 1 && self.clusters[k].slide().is_some() {
                let seeds = blocks.clone();
                self.regroup(&seeds, &[], None, Cause::Split)?;
            }
        }
        let mut pushed = pushed;
        pushed.clear();
        self.scratch.after.pushed = pushed;
        Ok(())
    }

    /// Step 6 of [`Engine::regroup`]: each joint of the component takes its new direction
    /// (`accel_of`: a block's acceleration after the decision, the ground's for `None`), with
    /// its stick-slip transition and the faces that separate logged. Returns the clusters
    /// outside the component beside it, and those of them one of whose joints turned: their
    /// friction forces changed (only an impact turns a sliding joint without a re-decision of
    /// both sides).
    fn turn_joints(
        &mut self,
        touched_horizontal: &[usize],
        touched_vertical: &[usize],
        local: &Local,
        set_vel: &SetVel,
        accel_of: &dyn Fn(Option<usize>) -> Lex,
        after: &mut After,
    ) {
        let After {
            before,
            neighbours,
            pushed,
            ..
        } = after;
        for &s in touched_horizontal {
            if !self.live_horizontal(s) {
                continue;
            }
            let (up, lo) = self.horizontal_ends(s);
            for b in std::iter::once(up).chain(lo) {
                if !local.contains_key(&b) && self.of[b] != ClusterId::NONE {
                    neighbours.push(self.of[b]);
                }
            }
            let same = lo.is_some_and(|l| self.of[l] == self.of[up]);
            let (vu, vl) = (
                self.vel_with(up, set_vel),
                lo.map_or(0.0, |l| self.vel_with(l, set_vel)),
            );
            let new = if same || (lo.is_none() && self.grounded(up)) {
                Slip::Stuck
            } else if vu != vl {
                Slip::of(vu.total_cmp(&vl))
            } else {
                match accel_of(Some(up)).cmp(&accel_of(lo)) {
                    std::cmp::Ordering::Equal => self.slip[s],
                    o => Slip::of(o),
                }
            };
            let old = self.slip[s];
            self.slip[s] = new;
            if old != new {
                before.slip.insert(s, old);
                for b in std::iter::once(up).chain(lo) {
                    if !local.contains_key(&b) && self.of[b] != ClusterId::NONE {
                        pushed.push(self.of[b]);
                    }
                }
            }
            if old.is_stuck() != new.is_stuck() {
                self.rec.transitions += 1;
                let kind = if new.is_stuck() {
                    EventKind::Stick
                } else {
                    EventKind::Slip
                };
                let who: &[usize] = match lo {
                    Some(l) => &[up, l],
                    None => &[up],
                };
                self.rec.event(
                    self.t,
                    kind,
                    who,
                    Some(JointRef::Horizontal(HorizontalId(s))),
                    None,
                );
            }
        }
        for &j in touched_vertical {
            if !self.live_vertical(j) {
                continue;
            }
            let jt = &self.given.topo.vertical[j];
            let (l, r) = (jt.left.0, jt.right.0);
            for b in [l, r] {
                if !local.contains_key(&b) && self.of[b] != ClusterId::NONE {
                    neighbours.push(self.of[b]);
                }
            }
            let together = (self.of[l] == self.of[r] && self.of[l] != ClusterId::NONE)
                || (self.grounded(l) && self.grounded(r));
            if self.touching[j] && !together && self.is_touching(j) {
                self.touching[j] = false;
                self.rec.event(
                    self.t,
                    EventKind::Separation,
                    &[l, r],
                    Some(JointRef::Vertical(VerticalId(j))),
                    None,
                );
            } else if together && self.is_touching(j) {
                self.touching[j] = true;
            }
        }
    }

    fn alloc(&mut self, c: Cluster) -> ClusterId {
        match self.free.pop() {
            Some(k) => {
                self.clusters[k] = c;
                k
            }
            None => self.clusters.push(c),
        }
    }

    /// A neighbour of the re-decided clusters one of whose joints the decision turned (after an
    /// impact): its friction forces have changed; it gets a new version and fresh events.
    fn refresh(&mut self, k: ClusterId, before: &Before) {
        let t = self.t;
        match &self.clusters[k].mode {
            Mode::Stuck { .. } => self.set_thresholds(k, Some(before)),
            Mode::Sliding(sl) => {
                let blocks = &self.clusters[k].blocks;
                let force: Q = blocks.iter().map(|&i| self.external_force(i)).sum();
                let c_q = force / &self.clusters[k].mass_q;
                if c_q != sl.c_q {
                    self.account(k, t);
                    if self.seg.has_vertical() {
                        // A joint's friction work under a varying capacity follows the path of
                        // its blocks, which changes here: what it did so far is booked first
                        // (without vertical shaking it depends only on where they are).
                        self.account_joints_of(k);
                    }
                    self.record_extremes(k);
                    let v = self.cluster_vel(k);
                    let members = self.clusters[k].blocks.clone();
                    for &i in &members {
                        self.u_ref[i] = self.block_disp(i);
                    }
                    self.clusters[k].mode = Mode::Sliding(Slide::formed(&self.seg, self.t, v, c_q));
                    self.clusters[k].roots = None;
                    self.clusters[k].ground_hits = None;
                }
            }
        }
        self.clusters[k].version = self.new_version();
    }
}
