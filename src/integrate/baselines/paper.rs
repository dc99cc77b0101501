//! The paper's scheme as written (eqs. 1-5): Newmark updates of d, v, a with the friction
//! vector f of eq. (2), F_ij sgn(relative velocity), and its rule that friction acts only once
//! the input exceeds mu g; elastic impacts by velocity exchange when a gap closes.
//!
//! Where the paper is ambiguous, the most literal reading:
//! - f at step i+1 needs v at i+1, which eq. (5) computes from a at i+1: the sign is taken from
//!   the explicit prediction v_i + dt a_i (the scheme stays explicit, as eq. 5 reads);
//! - "friction acts only when the input exceeds mu g": the wall stays at rest until
//!   |a_g| first exceeds mu g (the smallest mu of the wall); from then on eq. (2) applies;
//! - impacts: when a gap has closed (is negative) and the faces approach, the two blocks exchange
//!   velocities (Newton's law with the wall's e, which is exchange for e = 1 and equal masses);
//!   positions are not corrected.

use super::collide;
use crate::error::SimulationError;
use crate::integrate::stepping::{time_step, Model, Observer};
use crate::integrate::{Integrator, Scenario};
use crate::response::Response;

/// The paper's Newmark scheme with a fixed step.
#[derive(Debug, Clone)]
pub struct PaperNewmark {
    /// Time step (s).
    pub dt_s: f64,
}

fn sgn(x: f64) -> f64 {
    if x > 0.0 {
        1.0
    } else if x < 0.0 {
        -1.0
    } else {
        0.0
    }
}

/// Relative accelerations from eq. (5): a = (-m a_g - f) / m, f from eq. (2) with signs of w.
fn accelerations(m: &Model, gone: &[bool], ag: f64, v_sign: &[f64], out: &mut [f64]) {
    for i in 0..m.n {
        out[i] = if m.movable[i] && !gone[i] { -ag } else { 0.0 };
    }
    for j in &m.horizontal {
        if gone[j.upper] || j.lower_any.is_some_and(|l| gone[l]) {
            continue;
        }
        let f = j.capacity * sgn(m.slip_velocity(j, v_sign));
        out[j.upper] -= f / m.mass[j.upper];
        if let Some(l) = j.lower {
            out[l] += f / m.mass[l];
        }
    }
}

impl Integrator for PaperNewmark {
    fn method(&self) -> &'static str {
        "paper"
    }

    fn run(&self, sc: &Scenario) -> Result<Response, SimulationError> {
        let h = self.dt_s;
        time_step(sc, h)?;
        let m = Model::new(sc);
        let mut obs = Observer::new(sc, &m, sc.motion);
        let n = m.n;
        let (mut d, mut v, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
        let (mut a1, mut pred) = (vec![0.0; n], vec![0.0; n]);
        let mu_min = m
            .horizontal
            .iter()
            .map(|j| j.mu)
            .fold(f64::INFINITY, f64::min);
        let mut started = false;
        let steps = (sc.settings.duration_s / h).ceil() as u64;
        for k in 1..=steps {
            let t = (k as f64 * h).min(sc.settings.duration_s);
            let ag = sc.motion.accel(t);
            if !started && ag.abs() <= mu_min * m.g {
                obs.step(t, &d, &v);
                if obs.stopped {
                    break;
                }
                continue;
            }
            started = true;
            for i in 0..n {
                d[i] += h * v[i] + 0.5 * h * h * a[i];
                pred[i] = v[i] + h * a[i];
            }
            accelerations(&m, &obs.gone, ag, &pred, &mut a1);
            for i in 0..n {
                v[i] += 0.5 * h * (a[i] + a1[i]);
            }
            std::mem::swap(&mut a, &mut a1);
            for (kf, f) in m.vertical.iter().enumerate() {
                let (l, r) = f.pair;
                if obs.gone[l] || obs.gone[r] || m.gap(f, &d) >= 0.0 {
                    continue;
                }
                let (vl, vr) = (f.left.map_or(0.0, |b| v[b]), f.right.map_or(0.0, |b| v[b]));
                if vl > vr {
                    let (nl, nr) = collide(
                        vl,
                        vr,
                        f.left.map(|b| m.mass[b]),
                        f.right.map(|b| m.mass[b]),
                        m.restitution,
                    );
                    if let Some(b) = f.left {
                        v[b] = nl;
                    }
                    if let Some(b) = f.right {
                        v[b] = nr;
                    }
                    obs.impact(t, kf, [vl, vr], [nl, nr]);
                }
            }
            obs.step(t, &d, &v);
            if obs.stopped {
                break;
            }
        }
        Ok(obs.finish("paper", sc, steps))
    }
}
