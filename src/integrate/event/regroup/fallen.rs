//! A fallen block under `--after-collapse continue`: it leaves the wall with its load, whatever
//! rested only on it falls too, and the whole wall is decided again.

use crate::error::SimulationError;
use crate::exact::Q;
use crate::integrate::event::cluster::ClusterId;
use crate::integrate::event::cluster::{Cluster, Mode, Slide};
use crate::integrate::event::slip::Slip;
use crate::integrate::event::Engine;
use crate::response::{DecisionCause as Cause, EventKind};
use std::cell::OnceCell;

impl Engine<'_> {
    /// Block i has fallen (`--after-collapse continue`): remove it and its load, let whatever
    /// rested only on it fall too, and re-decide the whole wall.
    pub(in crate::integrate::event) fn remove_fallen(
        &mut self,
        first: usize,
    ) -> Result<(), SimulationError> {
        let mut falling = vec![first];
        while let Some(i) = falling.pop() {
            if self.fallen[i] {
                continue;
            }
            let v = self.block_vel(i);
            self.rec.energy.fallen_j += 0.5 * self.given.mass[i] * v * v;
            for s in self.given.topo.below[i]
                .iter()
                .chain(&self.given.topo.above[i])
            {
                self.account_horizontal(s.0);
            }
            if self.of[i] != ClusterId::NONE {
                let k = self.of[i];
                self.account(k, self.t);
                self.record_extremes(k);
            }
            self.u_ref[i] = self.block_disp(i);
            self.fallen[i] = true;
            self.rec.fell(i);
            for &s in &self.given.topo.above[i] {
                let up = self.given.topo.horizontal[s.0].upper.0;
                if !self.fallen[up] && !self.stands(up) {
                    self.rec
                        .event(self.t, EventKind::Collapse, &[up], None, None);
                    falling.push(up);
                }
            }
        }
        // Capacities change with the loads: friction work so far is owed at the old ones.
        for s in 0..self.given.topo.horizontal.len() {
            self.account_horizontal(s);
        }
        let loads = self.given.topo.loads_without(self.given.wall, &self.fallen);
        for (s, load) in loads.into_iter().enumerate() {
            self.given.cap_q[s] = &self.given.topo.horizontal[s].friction * &load;
            self.given.cap[s] = self.given.cap_q[s].to_f64();
        }
        // Dissolve every cluster; blocks keep their velocities.
        let live: Vec<usize> = (0..self.given.n)
            .filter(|&i| !self.given.fixed[i] && !self.fallen[i])
            .collect();
        let set_vel: Vec<(usize, f64)> = live.iter().map(|&i| (i, self.block_vel(i))).collect();
        for k in self.clusters.ids() {
            if self.clusters[k].blocks.is_empty() {
                continue;
            }
            self.account(k, self.t);
            self.record_extremes(k);
            let moved = self.cluster_disp(k);
            let members = std::mem::take(&mut self.clusters[k].blocks);
            for i in members {
                self.u_ref[i] += moved;
                self.of[i] = ClusterId::NONE;
            }
            self.clusters[k].version = self.new_version();
            self.free.push(k);
        }
        for &(i, v) in &set_vel {
            // Each block alone for a moment, with its own velocity, until the decision regroups.
            let k = self.alloc(Cluster {
                mass: self.given.mass[i],
                mass_q: self.given.mass_q[i].clone(),
                blocks: vec![i],
                version: 0,
                ground_version: 0,
                mode: Mode::Sliding(Slide::formed(&self.seg, self.t, v, Q::zero())),
                accounted_to: self.t,
                roots: None,
                ground_hits: None,
                extremes: Default::default(),
                boundary: OnceCell::new(),
            });
            self.of[i] = k;
        }
        for s in 0..self.slip.len() {
            if !self.live_horizontal(s) {
                self.slip[s] = Slip::Stuck;
            }
        }
        self.regroup(&live, &set_vel, None, Cause::Fall)
    }
}
