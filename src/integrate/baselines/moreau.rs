//! Moreau-Jean time stepping, the scheme of the nonsmooth contact dynamics codes used for
//! masonry (LMGC90, Siconos): velocities jump at each step by impulses solving the Coulomb and
//! contact laws at velocity level (a complementarity problem, by projected Gauss-Seidel),
//! positions follow by the theta method. Impacts obey Newton's law at velocity level on the
//! contacts predicted closed.

use crate::error::SimulationError;
use crate::integrate::stepping::{time_step, Model, Observer};
use crate::integrate::{Integrator, Scenario};
use crate::response::{Response, Warning};

/// Approach speed above which a contact impulse counts as an impact in the log (m/s).
const IMPACT_SPEED_M_S: f64 = 1e-9;

/// Moreau-Jean with a fixed step.
#[derive(Debug, Clone)]
pub struct Moreau {
    /// Time step (s).
    pub dt_s: f64,
    /// Theta of the position update and force evaluation (0.5 by default).
    pub theta: f64,
    /// Gauss-Seidel stops when no impulse changes by more than this fraction of the largest
    /// impulse scale (friction capacity x step).
    pub tolerance: f64,
    /// Gauss-Seidel sweeps allowed per step.
    pub max_sweeps: usize,
}

impl Moreau {
    /// Moreau-Jean with step dt and the usual settings.
    pub fn new(dt_s: f64) -> Moreau {
        Moreau {
            dt_s,
            theta: 0.5,
            tolerance: 1e-12,
            max_sweeps: 10_000,
        }
    }
}

impl Integrator for Moreau {
    fn method(&self) -> &'static str {
        "moreau"
    }

    fn run(&self, sc: &Scenario) -> Result<Response, SimulationError> {
        let h = self.dt_s;
        time_step(sc, h)?;
        let m = Model::new(sc);
        let mut obs = Observer::new(sc, &m, sc.motion);
        let n = m.n;
        let inv: Vec<f64> = (0..n)
            .map(|i| if m.movable[i] { 1.0 / m.mass[i] } else { 0.0 })
            .collect();
        let (mut u, mut v, mut v_old) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let mut p_joint = vec![0.0; m.horizontal.len()];
        let mut p_face = vec![0.0; m.vertical.len()];
        let scale = m.horizontal.iter().map(|j| j.capacity).fold(1.0, f64::max) * h;
        let steps = (sc.settings.duration_s / h).ceil() as u64;
        let th = self.theta;
        let mut unconverged = 0u64;
        for k in 1..=steps {
            let t0 = (k - 1) as f64 * h;
            let t = (k as f64 * h).min(sc.settings.duration_s);
            let ag = (1.0 - th) * sc.motion.accel(t0) + th * sc.motion.accel(t);
            v_old.copy_from_slice(&v);
            for ((vi, &movable), &gone) in v.iter_mut().zip(&m.movable).zip(&obs.gone) {
                if movable && !gone {
                    *vi -= h * ag;
                }
            }
            // Contacts predicted closed, with their approach speed at the start of the step.
            let active: Vec<(usize, f64)> = m
                .vertical
                .iter()
                .enumerate()
                .filter(|(_, f)| !obs.gone[f.pair.0] && !obs.gone[f.pair.1])
                .filter_map(|(kf, f)| {
                    let un = f.right.map_or(0.0, |r| v_old[r]) - f.left.map_or(0.0, |l| v_old[l]);
                    (m.gap(f, &u) + th * h * un <= 0.0).then_some((kf, un))
                })
                .collect();
            p_joint.iter_mut().for_each(|p| *p = 0.0);
            p_face.iter_mut().for_each(|p| *p = 0.0);
            let mut converged = false;
            for _ in 0..self.max_sweeps {
                let mut change: f64 = 0.0;
                for (kj, j) in m.horizontal.iter().enumerate() {
                    if obs.gone[j.upper] || j.lower_any.is_some_and(|l| obs.gone[l]) {
                        continue;
                    }
                    let w = m.slip_velocity(j, &v);
                    let il = j.lower.map_or(0.0, |l| inv[l]);
                    let meff = 1.0 / (inv[j.upper] + il);
                    let cap = j.capacity * h;
                    let new = (p_joint[kj] - w * meff).clamp(-cap, cap);
                    let dp = new - p_joint[kj];
                    if dp != 0.0 {
                        p_joint[kj] = new;
                        v[j.upper] += dp * inv[j.upper];
                        if let Some(l) = j.lower {
                            v[l] -= dp * il;
                        }
                        change = change.max(dp.abs());
                    }
                }
                for &(kf, un_old) in &active {
                    let f = &m.vertical[kf];
                    let (il, ir) = (
                        f.left.map_or(0.0, |b| inv[b]),
                        f.right.map_or(0.0, |b| inv[b]),
                    );
                    let un = f.right.map_or(0.0, |r| v[r]) - f.left.map_or(0.0, |l| v[l]);
                    let target = -m.restitution * un_old.min(0.0);
                    let new = (p_face[kf] + (target - un) / (il + ir)).max(0.0);
                    let dp = new - p_face[kf];
                    if dp != 0.0 {
                        p_face[kf] = new;
                        if let Some(r) = f.right {
                            v[r] += dp * ir;
                        }
                        if let Some(l) = f.left {
                            v[l] -= dp * il;
                        }
                        change = change.max(dp.abs());
                    }
                }
                if change <= self.tolerance * scale {
                    converged = true;
                    break;
                }
            }
            if !converged {
                unconverged += 1;
            }
            for &(kf, un_old) in &active {
                // Pressing faces carry an impulse every step; an impact is a face that was
                // approaching at more than round-off speed.
                if p_face[kf] > 0.0 && un_old < -IMPACT_SPEED_M_S {
                    let f = &m.vertical[kf];
                    let side = |b: Option<usize>, vv: &[f64]| b.map_or(0.0, |b| vv[b]);
                    obs.impact(
                        t,
                        kf,
                        [side(f.left, &v_old), side(f.right, &v_old)],
                        [side(f.left, &v), side(f.right, &v)],
                    );
                }
            }
            for i in 0..n {
                u[i] += h * (th * v[i] + (1.0 - th) * v_old[i]);
            }
            obs.step(t, &u, &v);
            if obs.stopped {
                break;
            }
        }
        let mut r = obs.finish("moreau", sc, steps);
        r.summary.stats.unconverged_steps = unconverged;
        if unconverged > 0 {
            r.summary.warnings.push(Warning::Unconverged {
                steps: unconverged,
                sweeps: self.max_sweeps,
                first_s: None,
                blocks: Vec::new(),
            });
        }
        Ok(r)
    }
}
