//! Blocks that lose their support: a support's relative displacement reaching a threshold of
//! its span is checked against the block's centroid (does it still stand?), and a block that
//! no longer stands falls, ending the run or leaving it (`AfterCollapse`).

use super::cluster::ClusterId;
use super::queue::Constraint;
use super::Engine;
use crate::error::SimulationError;
use crate::integrate::AfterCollapse;
use crate::response::{Collapse, CollapseCause, EventKind};
use std::cmp::Ordering;

impl Engine<'_> {
    pub(super) fn constraint_reached(
        &mut self,
        a: ClusterId,
        b: Option<ClusterId>,
        c: Constraint,
    ) -> Result<(), SimulationError> {
        match c {
            Constraint::Gap(j) => self.faces_meet(j),
            Constraint::Collapse(s) => {
                let upper = self.given.topo.horizontal[s].upper.0;
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

    /// Does block i still stand on its supports? Its centroid must lie in the span from the
    /// leftmost to the rightmost point where its bottom face touches a support's top face; on the
    /// edge of the span, it falls if it is moving out (velocity, then acceleration).
    pub(super) fn stands(&self, i: usize) -> bool {
        let state = |b: usize| -> [f64; 3] {
            if self.of[b] == ClusterId::NONE {
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
        let centroid = add(ui, self.given.xc[i]);
        let mut hull: Option<([f64; 3], [f64; 3])> = None;
        for &s in &self.given.topo.below[i] {
            if !self.live_horizontal(s.0) {
                continue;
            }
            let Some(j) = self.lower_block(s.0) else {
                return true;
            };
            let uj = state(j);
            let lo = lex_max(add(ui, self.given.xl[i]), add(uj, self.given.xl[j]));
            let hi = lex_min(add(ui, self.given.xr[i]), add(uj, self.given.xr[j]));
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

    pub(super) fn collapse(&mut self, i: usize) -> Result<(), SimulationError> {
        if self.rec.collapse.is_none() {
            self.rec.collapse = Some(Collapse {
                time_s: self.t,
                block: self.given.wall.blocks[i].name.clone(),
                cause: CollapseCause::SlidingOff,
            });
        }
        self.rec
            .event(self.t, EventKind::Collapse, &[i], None, None);
        self.rec.fell(i);
        if self.given.after_collapse == AfterCollapse::Stop {
            self.stopped = true;
            return Ok(());
        }
        self.remove_fallen(i)
    }
}
