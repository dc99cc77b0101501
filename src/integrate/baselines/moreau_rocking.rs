//! Moreau-Jean time stepping of a free-standing block with its rotation: three degrees of
//! freedom (the centroid's x and y, the rotation), the two base corners as unilateral contacts
//! with Coulomb friction, plastic at velocity level (Newton's e = 0: a corner that lands stays,
//! which with friction holding is Housner's landing). The scheme of LMGC90 and Siconos for one
//! body: velocities jump by impulses that solve the contact laws on the corners predicted
//! closed, by projected Gauss-Seidel; positions follow by the midpoint rule. The reference the
//! exact rocking engine is checked against as the step falls (docs/accuracy.md).

use crate::error::SimulationError;
use crate::integrate::rocking::{self, RockingBody};
use crate::integrate::stepping::time_step;
use crate::integrate::{Integrator, Scenario};
use crate::response::{Collapse, CollapseCause, Recorder, Response, Warning};
use nalgebra::{Matrix2, Matrix2x3, Vector2, Vector3};

/// Moreau-Jean with rotations, on a wall of one free-standing block.
#[derive(Debug, Clone)]
pub struct MoreauRocking {
    /// Time step (s).
    pub dt_s: f64,
    /// Gauss-Seidel stops when no impulse changes by more than this fraction of the weight
    /// times the step.
    pub tolerance: f64,
    /// Gauss-Seidel sweeps allowed per step; steps that need more are counted in a warning.
    pub max_sweeps: usize,
    /// Initial rotation (rad, clockwise positive as in the exact engine).
    pub initial_rotation_rad: f64,
}

impl MoreauRocking {
    /// Moreau-Jean with rotations, step dt, the usual settings.
    pub fn new(dt_s: f64) -> MoreauRocking {
        MoreauRocking {
            dt_s,
            tolerance: 1e-12,
            max_sweeps: 10_000,
            initial_rotation_rad: 0.0,
        }
    }
}

/// A corner's offset from the centroid at rotation phi (counter-clockwise), and the Jacobian
/// of its (normal, tangential) velocity: v_P = v_G + phi' x r.
fn corner(body: &RockingBody, sign: f64, phi: f64) -> (Vector2<f64>, Matrix2x3<f64>) {
    let (s, c) = phi.sin_cos();
    let (x, y) = (sign * body.half_base_m, -body.centroid_height_m);
    let r = Vector2::new(c * x - s * y, s * x + c * y);
    (r, Matrix2x3::new(0.0, 1.0, r.x, 1.0, 0.0, -r.y))
}

impl Integrator for MoreauRocking {
    fn method(&self) -> &'static str {
        "moreau"
    }

    fn run(&self, sc: &Scenario) -> Result<Response, SimulationError> {
        let dt = self.dt_s;
        time_step(sc, dt)?;
        let body = rocking::free_standing(sc.wall, sc.topology)?;
        let (m, ig, mu, g, hc) = (
            body.mass_kg,
            body.inertia_kg_m2,
            body.friction,
            body.g_m_s2,
            body.centroid_height_m,
        );
        let inv_mass = Vector3::new(1.0 / m, 1.0 / m, 1.0 / ig);
        let settings = sc.settings;
        let mut rec = Recorder::for_bodies(
            vec![body.name.clone()],
            vec![(0, None, body.name.clone(), "ground".to_string())],
            settings.history_to(),
            settings.log_events,
        );
        // The centroid relative to the base centre's place at rest; phi counter-clockwise.
        let phi0 = -self.initial_rotation_rad;
        let mut q = Vector3::new(0.0, hc, 0.0);
        if phi0 != 0.0 {
            // Resting on the corner it leans on.
            let (r, _) = corner(&body, -phi0.signum(), phi0);
            q = Vector3::new(-phi0.signum() * body.half_base_m - r.x, -r.y, phi0);
        }
        let mut v = Vector3::<f64>::zeros();
        let energy = |q: &Vector3<f64>, v: &Vector3<f64>| {
            0.5 * m * (v.x * v.x + v.y * v.y) + 0.5 * ig * v.z * v.z + m * g * (q.y - hc)
        };
        rec.energy.initial_j = energy(&q, &v);
        let base =
            |q: &Vector3<f64>, v: &Vector3<f64>| (q.x + hc * q.z.sin(), v.x + hc * q.z.cos() * v.z);
        let record = |rec: &mut Recorder, t: f64, q: &Vector3<f64>, v: &Vector3<f64>, row: bool| {
            let (u, uv) = base(q, v);
            rec.block_extremes(0, u.abs(), uv.abs());
            rec.rotation_extreme(0, q.z.abs());
            rec.joint_extremes(&[u]);
            if row {
                rec.sample_rotating(t, &[u], &[uv], &[-q.z], &[-v.z]);
            }
        };
        record(&mut rec, 0.0, &q, &v, true);
        let steps = (settings.duration_s / dt).ceil() as u64;
        let every = settings
            .output_dt_s
            .map_or(u64::MAX, |o| ((o / dt).round() as u64).max(1));
        let scale = m * g * dt;
        let mut unconverged = 0u64;
        let mut impulses = [Vector2::<f64>::zeros(); 2];
        let mut t = 0.0;
        for k in 1..=steps {
            let t_mid = (k as f64 - 0.5) * dt;
            let seg = sc.motion.segment_at(t_mid);
            let s = t_mid - seg.t0;
            let (a, lambda) = (seg.accel(s), seg.lambda.0 + seg.lambda.1 * s);
            let force = Vector3::new(-m * a, -m * g * lambda, 0.0);
            let v_free = v + dt * force.component_mul(&inv_mass);
            // The corners predicted closed at mid-step take part.
            let mut active: Vec<(usize, Matrix2x3<f64>)> = Vec::with_capacity(2);
            for (slot, sign) in [(0usize, -1.0), (1, 1.0)] {
                let (r, h) = corner(&body, sign, q.z);
                if q.y + r.y + 0.5 * dt * (h * v)[0] <= 0.0 {
                    active.push((slot, h));
                } else {
                    impulses[slot] = Vector2::zeros();
                }
            }
            // M^-1 H^T of each active corner, and its diagonal Delassus block H M^-1 H^T.
            let spread: Vec<nalgebra::Matrix3x2<f64>> = active
                .iter()
                .map(|(_, h)| {
                    let mut ht = h.transpose();
                    for (row, w) in inv_mass.iter().enumerate() {
                        ht.row_mut(row).scale_mut(*w);
                    }
                    ht
                })
                .collect();
            let diag: Vec<Matrix2<f64>> = active
                .iter()
                .zip(&spread)
                .map(|((_, h), mh)| h * mh)
                .collect();
            let velocity = |imp: &[Vector2<f64>; 2]| {
                active
                    .iter()
                    .zip(&spread)
                    .fold(v_free, |acc, ((slot, _), mh)| acc + mh * imp[*slot])
            };
            let mut converged = active.is_empty();
            for _ in 0..self.max_sweeps {
                if converged {
                    break;
                }
                let mut change: f64 = 0.0;
                for (i, (slot, h)) in active.iter().enumerate() {
                    let u = h * velocity(&impulses);
                    let w = &diag[i];
                    let p = impulses[*slot];
                    // Plastic normal law (e = 0), then Coulomb with the new normal impulse.
                    let pn = (p.x - u.x / w[(0, 0)]).max(0.0);
                    let ut = u.y + w[(1, 0)] * (pn - p.x);
                    let pt = (p.y - ut / w[(1, 1)]).clamp(-mu * pn, mu * pn);
                    change = change.max((pn - p.x).abs()).max((pt - p.y).abs());
                    impulses[*slot] = Vector2::new(pn, pt);
                }
                converged = change <= self.tolerance * scale;
            }
            if !converged {
                unconverged += 1;
            }
            let v_new = velocity(&impulses);
            let dq = 0.5 * dt * (v + v_new);
            // Work of the ground's inertial force and of the vertical motion's extra weight.
            rec.energy.input_j += -m * a * dq.x - m * g * (lambda - 1.0) * dq.y;
            q += dq;
            v = v_new;
            t = k as f64 * dt;
            rec.stats.steps += 1;
            if q.z.abs() > 0.0 {
                rec.uplift(0, t - dt);
            }
            if q.z.abs() >= std::f64::consts::FRAC_PI_2 {
                rec.fell(0);
                rec.collapse = Some(Collapse {
                    time_s: t,
                    block: body.name.clone(),
                    cause: CollapseCause::Overturning,
                });
                rec.energy.fallen_j = energy(&q, &v);
                record(&mut rec, t, &q, &v, true);
                break;
            }
            record(&mut rec, t, &q, &v, k % every == 0);
        }
        if rec.collapse.is_none() {
            rec.energy.kinetic_j = 0.5 * m * (v.x * v.x + v.y * v.y) + 0.5 * ig * v.z * v.z;
            rec.energy.potential_j = m * g * (q.y - hc);
        }
        // What the contacts took: the rest of the balance (Moreau-Jean has no event to
        // attribute it to friction or landings one by one).
        let e = &mut rec.energy;
        e.friction_j = e.initial_j + e.input_j - e.kinetic_j - e.potential_j - e.fallen_j;
        rec.stats.unconverged_steps = unconverged;
        if unconverged > 0 {
            rec.warnings.push(Warning::Unconverged {
                steps: unconverged,
                sweeps: self.max_sweeps,
            });
        }
        let (u, uv) = base(&q, &v);
        let motion = sc.motion.describe();
        let mut r = rec.finish("moreau", &sc.wall.name, motion, t, &[u], &[uv]);
        r.summary.model = crate::response::ModelUsed {
            name: "slide-rock".into(),
            equations: Some("moreau-jean".into()),
            direction: "in-plane".into(),
            why: "asked for (--model slide-rock --method moreau)".into(),
        };
        Ok(r)
    }
}
