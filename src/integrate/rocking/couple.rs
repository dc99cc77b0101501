//! Two rocking bodies in contact. Where an impact between two bodies, each rocking on a pivot
//! that stays on the ground without slipping, leaves no speed to part (no restitution, or
//! elastic bounces that accumulate to round-off), the corner of one stays on the face of the
//! other: two columns leaning together. They turn as one mechanism of one degree of freedom,
//! the contact (frictionless, as at every face between blocks) pushing them apart. This module
//! owns that mechanism's motion: both rotations and the contact's push as series over a step,
//! and the condition that ends it, the push falling to zero (the bodies part). The pivots'
//! conditions (slip, lift) are the rocking mode's, on the forces with the push; where the
//! corner reaches an end of the face, or another corner the face, is the pair's (`clearance`).
//! A landing of either body ends the couple; the engine takes its impulses one after the other
//! (the landing's, then the contact's) and may start another.
//!
//! With the push P along the face's normal n (into the corner's body), body k's equation about
//! its pivot is I_O,k theta_k'' = Q_k + J_k P, Q_k the rocking one (I_O theta'' = -m (G_y a_g +
//! dx g lambda)) and J_k the push's arm: J_1 = -(r_1 x n) for the corner's body, J_2 = r_2 x n
//! for the face's, r_k from pivot k to the corner. The same J_k give the rate at which the
//! corner leaves the face, J_1 theta_1' + J_2 theta_2', which stays zero: order by order in the
//! series, three linear equations in theta_1'', theta_2'' and P.

use super::body::RockingBody;
use super::clearance::Touch;
use super::modes::{
    arms, Constraint, Corner, Equations, Guard, Inputs, Mode, Scales, State, Trajectory,
};
use super::series::{mul_at, sin_cos_at, Coeffs, ORDER, ZERO};

/// Two bodies in contact, the corner of the first on a face of the second: the geometry in
/// each body's frame upright (theta = 0), from its pivot, which stays where it is meanwhile.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Couple {
    /// The contact as the impact that started the couple found it: the corner's block, then
    /// the face's, their pair, and what moves them.
    pub(super) touch: Touch,
    /// The corner's body, then the face's.
    pub(super) bodies: [usize; 2],
    /// Their pivots (m).
    pivots: [[f64; 2]; 2],
    /// The corner, from its body's pivot (m).
    corner: [f64; 2],
    /// The face's normal, pointing into the corner's body.
    normal: [f64; 2],
}

/// The clockwise rotation by theta of r: (r_x cos + r_y sin, -r_x sin + r_y cos).
fn turned(r: [f64; 2], (sin, cos): (f64, f64)) -> [f64; 2] {
    [r[0] * cos + r[1] * sin, -r[0] * sin + r[1] * cos]
}

/// Its inverse.
fn upright(r: [f64; 2], (sin, cos): (f64, f64)) -> [f64; 2] {
    turned(r, (-sin, cos))
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The rotations' sines and cosines over a step, the corner from each pivot, the face's
/// normal and the push's arms J_1, J_2, as series.
#[derive(Default)]
struct Geometry {
    sin: [Coeffs; 2],
    cos: [Coeffs; 2],
    r1: [Coeffs; 2],
    r2: [Coeffs; 2],
    n: [Coeffs; 2],
    arm: [Coeffs; 2],
}

impl Geometry {
    /// Order j, the rotations known to order j.
    fn place(&mut self, couple: &Couple, t: &[Trajectory; 2], j: usize) {
        for (k, body) in t.iter().enumerate() {
            sin_cos_at(&body.theta, &mut self.sin[k], &mut self.cos[k], j);
        }
        let one = if j == 0 { 1.0 } else { 0.0 };
        let (c, q) = (couple.corner, couple.normal);
        let (sin, cos) = (&self.sin, &self.cos);
        self.r1[0][j] = c[0] * cos[0][j] + c[1] * sin[0][j];
        self.r1[1][j] = -c[0] * sin[0][j] + c[1] * cos[0][j];
        self.n[0][j] = q[0] * cos[1][j] + q[1] * sin[1][j];
        self.n[1][j] = -q[0] * sin[1][j] + q[1] * cos[1][j];
        let [p1, p2] = couple.pivots;
        for x in 0..2 {
            self.r2[x][j] = self.r1[x][j] + (p1[x] - p2[x]) * one;
        }
        let n = &self.n;
        let crossed = |r: &[Coeffs; 2]| mul_at(&r[0], &n[1], j) - mul_at(&r[1], &n[0], j);
        self.arm[0][j] = -crossed(&self.r1);
        self.arm[1][j] = crossed(&self.r2);
    }
}

/// Each body of a couple over a step, and the push (N).
pub(super) struct Motion {
    pub(super) bodies: [Trajectory; 2],
    pub(super) push: Coeffs,
}

impl Couple {
    /// The couple of the bodies whose pivots are at `pivots` and rotations `theta` (the
    /// corner's body first) in contact at `touch`; none where the push would turn neither body
    /// (to a tie of the arms).
    pub(super) fn new(
        touch: &Touch,
        bodies: [usize; 2],
        pivots: [[f64; 2]; 2],
        theta: [f64; 2],
        tie_m: f64,
    ) -> Option<Couple> {
        let (point, normal) = (touch.point, touch.normal);
        let p1 = pivots[0];
        let couple = Couple {
            touch: Touch {
                stays: true,
                ..*touch
            },
            bodies,
            pivots,
            corner: upright([point[0] - p1[0], point[1] - p1[1]], theta[0].sin_cos()),
            normal: upright(normal, theta[1].sin_cos()),
        };
        let reach = pivots.map(|p| cross([point[0] - p[0], point[1] - p[1]], normal));
        reach.iter().any(|a| a.abs() > tie_m).then_some(couple)
    }

    /// The contact where the bodies are turned by `theta`, as a touch of blocks that have not
    /// parted.
    pub(super) fn touch_at(&self, theta: [f64; 2]) -> Touch {
        let (r, p) = (turned(self.corner, theta[0].sin_cos()), self.pivots[0]);
        Touch {
            point: [p[0] + r[0], p[1] + r[1]],
            normal: turned(self.normal, theta[1].sin_cos()),
            ..self.touch
        }
    }

    /// Both bodies' motion from their states (rocking on the corners `corners`) under
    /// `inputs`, to order [`ORDER`], and the push.
    pub(super) fn motion(
        &self,
        bodies: [&RockingBody; 2],
        corners: [Corner; 2],
        states: [&State; 2],
        inputs: &Inputs,
    ) -> Motion {
        let (a, lam) = (&inputs.accel, &inputs.lambda);
        let mut t =
            [0, 1].map(|k| Trajectory::start(Mode::Rock(corners[k]), Equations::Exact, states[k]));
        let io = bodies.map(RockingBody::corner_inertia_kg_m2);
        let mut at = Geometry::default();
        let (mut acc, mut w, mut push) = ([ZERO; 2], [ZERO; 2], ZERO);
        at.place(self, &t, 0);
        for k in 0..=ORDER {
            if k < ORDER {
                for tk in t.iter_mut() {
                    tk.theta[k + 1] = tk.omega[k] / (k + 1) as f64;
                }
                at.place(self, &t, k + 1);
            }
            let mut rest = [0.0; 2];
            for b in 0..2 {
                let (m, g) = (bodies[b].mass_kg, bodies[b].g_m_s2);
                (t[b].gy[k], t[b].dx[k]) =
                    arms(bodies[b], corners[b].sign(), &at.sin[b], &at.cos[b], k);
                let q = -m * (mul_at(&t[b].gy, a, k) + g * mul_at(&t[b].dx, lam, k));
                let earlier: f64 = (1..=k).map(|j| at.arm[b][j] * push[k - j]).sum();
                rest[b] = q + earlier;
            }
            // The rate at which the corner leaves the face, at order k + 1, but for the
            // accelerations at order k: J_1 theta_1'' + J_2 theta_2'' = c (at the last order,
            // whose accelerations give only forces, the rate's term lies beyond the series).
            let c = if k < ORDER {
                let known: f64 = (1..=k + 1)
                    .map(|j| {
                        at.arm[0][j] * t[0].omega[k + 1 - j] + at.arm[1][j] * t[1].omega[k + 1 - j]
                    })
                    .sum();
                -((k + 1) as f64) * known
            } else {
                0.0
            };
            let (j1, j2) = (at.arm[0][0], at.arm[1][0]);
            push[k] = (c - j1 * rest[0] / io[0] - j2 * rest[1] / io[1])
                / (j1 * j1 / io[0] + j2 * j2 / io[1]);
            for b in 0..2 {
                acc[b][k] = (rest[b] + at.arm[b][0] * push[k]) / io[b];
                w[b][k] = mul_at(&t[b].omega, &t[b].omega, k);
                // The ground's forces as the rocking mode's, less the push on the body (+n on
                // the corner's, -n on the face's).
                let (m, g) = (bodies[b].mass_kg, bodies[b].g_m_s2);
                let on = if b == 0 { 1.0 } else { -1.0 };
                let (tb, ab, wb) = (&t[b], &acc[b], &w[b]);
                let fx = m * (mul_at(&tb.gy, ab, k) + mul_at(&tb.dx, wb, k) + a[k]);
                let fy = m * (mul_at(&tb.dx, ab, k) - mul_at(&tb.gy, wb, k) + g * lam[k]);
                t[b].tangential[k] = fx - on * mul_at(&push, &at.n[0], k);
                t[b].normal[k] = fy - on * mul_at(&push, &at.n[1], k);
            }
            if k < ORDER {
                for b in 0..2 {
                    t[b].omega[k + 1] = acc[b][k] / (k + 1) as f64;
                }
            }
        }
        Motion { bodies: t, push }
    }

    /// The contact lasts while the push stays >= 0.
    pub(super) fn condition(&self, body: &RockingBody, motion: &Motion) -> Constraint {
        Constraint {
            series: motion.push,
            scale: Scales::of(body).force,
            guard: Guard::Parts,
            strict: false,
        }
    }
}
