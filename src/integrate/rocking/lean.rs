//! A body resting against a fixed block. Where a rocking body strikes a fixed block and its
//! pivot stays on the ground without slipping, an impact that leaves no speed to part (no
//! restitution, or elastic bounces that accumulate to round-off) leaves it still: turning
//! about its stuck pivot is its one motion, and the contact forbids the sense towards the
//! block (a column that fell past its alpha onto a neighbour or an abutment, and stays
//! there). This module owns the forces that hold it: the contact's push from the moment
//! balance about the pivot, and the ground's reaction at the pivot, as series over a step,
//! and the condition that ends the rest, the push falling to zero (the ground acceleration
//! turning the body away). The pivot's own conditions (slip, lift) are the rocking mode's,
//! on these forces; where the pivot slips, the body slides along the face, a `couple` with
//! the fixed block, and rests here again where the slip stops.

use super::body::RockingBody;
use super::clearance::Touch;
use super::modes::{Constraint, Guard, Inputs, Scales, Trajectory};
use super::series::{constant, Coeffs, ZERO};

/// A body at rest against a fixed block: the blocks in contact and the geometry of the contact
/// from the body's pivot, which stays where it is while the body rests.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Lean {
    /// The contact, as the body came to rest against the block (it stays there).
    pub(super) touch: Touch,
    /// The body's block, then the fixed block (outputs).
    pub(super) blocks: [usize; 2],
    /// From the pivot to the body's centroid and to the contact point (m).
    pub(super) centroid: [f64; 2],
    pub(super) contact: [f64; 2],
    /// The unit direction in which the fixed block pushes on the body.
    pub(super) push: [f64; 2],
}

impl Lean {
    /// The lean of the body on side k of `touch` (0: its corner on the fixed block's face, 1:
    /// its face on the block's corner), whose pivot is at `pivot` and centroid at `centroid`
    /// (positions in the wall's frame, m); none where the push has no moment about the pivot
    /// to hold the body by (to a tie of the arm).
    pub(super) fn new(
        touch: &Touch,
        k: usize,
        pivot: [f64; 2],
        centroid: [f64; 2],
        tie_m: f64,
    ) -> Option<Lean> {
        let from = |p: [f64; 2]| [p[0] - pivot[0], p[1] - pivot[1]];
        // The face's normal points into the corner's block.
        let push = if k == 0 {
            touch.normal
        } else {
            touch.normal.map(|x| -x)
        };
        let lean = Lean {
            touch: *touch,
            blocks: [touch.blocks[k], touch.blocks[1 - k]],
            centroid: from(centroid),
            contact: from(touch.point),
            push,
        };
        (lean.arm().abs() > tie_m).then_some(lean)
    }

    /// The push's moment arm about the pivot (m, counter-clockwise positive).
    fn arm(&self) -> f64 {
        self.contact[0] * self.push[1] - self.contact[1] * self.push[0]
    }

    /// The push P (N) and the ground's horizontal and vertical forces on the pivot (N) that
    /// keep the body still under the ground's motion: with the inertial load -m a_g and the
    /// weight -m g lambda at the centroid (arm r_G), the moments about the pivot balance,
    /// m (r_Gy a_g - g lambda r_Gx) + P (r_C x n) = 0, and the forces do.
    fn forces(&self, body: &RockingBody, inputs: &Inputs) -> (Coeffs, Coeffs, Coeffs) {
        let (m, g) = (body.mass_kg, body.g_m_s2);
        let arm = self.arm();
        let (mut push, mut horizontal, mut vertical) = (ZERO, ZERO, ZERO);
        for k in 0..push.len() {
            let (a, lam) = (inputs.accel[k], inputs.lambda[k]);
            push[k] = -m * (self.centroid[1] * a - g * lam * self.centroid[0]) / arm;
            horizontal[k] = m * a - push[k] * self.push[0];
            vertical[k] = m * g * lam - push[k] * self.push[1];
        }
        (push, horizontal, vertical)
    }

    /// The body's trajectory `t`, in its rocking mode on the pivot, held still: its state
    /// kept, the ground's forces those that hold it.
    pub(super) fn hold(&self, body: &RockingBody, t: &mut Trajectory, inputs: &Inputs) {
        let (_, horizontal, vertical) = self.forces(body, inputs);
        for c in [&mut t.theta, &mut t.u, &mut t.gy, &mut t.dx] {
            *c = constant(c[0]);
        }
        t.omega = ZERO;
        t.v = ZERO;
        t.tangential = horizontal;
        t.normal = vertical;
    }

    /// The rest lasts while the push stays >= 0.
    pub(super) fn condition(&self, body: &RockingBody, inputs: &Inputs) -> Constraint {
        Constraint {
            series: self.forces(body, inputs).0,
            scale: Scales::of(body).force,
            guard: Guard::Parts,
            strict: false,
        }
    }

    /// The push now (N).
    pub(super) fn push_n(&self, body: &RockingBody, inputs: &Inputs) -> f64 {
        self.forces(body, inputs).0[0]
    }
}
