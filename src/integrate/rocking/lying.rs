//! Two bodies whose faces lie on each other, pressed at both ends of the faces' overlap. Where a
//! face comes down flat on another and both ends of their overlap are left at rest on each
//! other, pressing (the contact problem at the level of accelerations says so), the faces move
//! together: the relative rotation is locked, the normal distance too, and the one relative
//! motion left is the faces sliding along each other (frictionless, as at every face between
//! blocks). This module owns that mechanism: the two contacts as couples ([`Couple`], the
//! corner of one block on the face of the other at each end of the overlap), both bodies'
//! motion with the two pushes as series over a step ([`couple::pushed`]: each order's pushes
//! solve a 2x2 system), and the conditions that end it, either push falling to zero (the
//! faces turn apart at that end, or part). Where an end of the overlap reaches a corner of
//! the other face (the faces slide along each other) is the pair's (`clearance`), and the
//! end passes to that corner. Bodies in flight only: a body on the ground takes its pivot's
//! friction into the decision of which ends press, which is not built; a landing of either
//! body takes the ground's impulses with both ends' at once (the engine's `lying_lands`), and
//! where both ends stay after it, the run stops.

use super::body::RockingBody;
use super::clearance::{Side, Touch};
use super::couple::{self, Couple, Member, Pushed};
use super::modes::{Constraint, Guard, Inputs, Scales, State};

/// Two faces lying on each other: the contact at each end of their overlap, the first's sides
/// giving the bodies' order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Lying {
    pub(super) ends: [Couple; 2],
}

impl Lying {
    /// The faces lying on each other at the contacts `ends` (each a corner of one body on the
    /// other's face), the bodies in flight (`bodies`, in the first contact's order, with their
    /// pivots' homes and their states); none where a contact's sides are not these bodies.
    /// A push moves a body in flight whatever its arm: no contact is refused for its arms.
    pub(super) fn new(
        ends: [&Touch; 2],
        bodies: [usize; 2],
        homes: [[f64; 2]; 2],
        states: [&State; 2],
    ) -> Option<Lying> {
        let couple = |t: &Touch| {
            let side = |s: Side| match s {
                Side::Body(k, _) => bodies.iter().position(|&b| b == k),
                _ => None,
            };
            let order = [side(t.sides[0])?, side(t.sides[1])?];
            let placed = order.map(|k| Some(states[k]));
            let (ids, homes) = (order.map(|k| Some(bodies[k])), order.map(|k| homes[k]));
            Couple::new(t, ids, homes, placed, 0.0)
        };
        Some(Lying {
            ends: [couple(ends[0])?, couple(ends[1])?],
        })
    }

    /// The bodies, in the first contact's order.
    pub(super) fn bodies(&self) -> [Option<usize>; 2] {
        self.ends[0].bodies
    }

    /// Both bodies' motion from their states in their modes (`members`, in the first
    /// contact's order), and the two pushes.
    pub(super) fn motion(&self, members: [Member; 2], inputs: &Inputs) -> Pushed {
        couple::pushed(&[&self.ends[0], &self.ends[1]], members, inputs)
    }

    /// Each end's contact where the bodies are in `states` (first contact's order), as touches
    /// of blocks that have not parted.
    pub(super) fn touches_at(&self, states: [&State; 2]) -> [Touch; 2] {
        self.ends.map(|end| {
            let order = end.bodies.map(|b| usize::from(b != self.bodies()[0]));
            end.touch_at(order.map(|k| Some(states[k])))
        })
    }

    /// The faces lie on each other while both pushes stay >= 0 (scaled by the weight of
    /// `body`, the first).
    pub(super) fn conditions(&self, body: &RockingBody, motion: &Pushed) -> [Constraint; 2] {
        motion.pushes.map(|push| Constraint {
            series: push,
            scale: Scales::of(body).force,
            guard: Guard::Parts,
            strict: false,
        })
    }
}
