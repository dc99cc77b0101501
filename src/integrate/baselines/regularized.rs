//! The common engineering shortcut: friction smoothed as F tanh(w/eps), contacts as stiff
//! penalty springs (with a dashpot giving the restitution e), integrated by the adaptive
//! Dormand-Prince 5(4) Runge-Kutta method.

use crate::error::SimulationError;
use crate::integrate::stepping::{positive, Model, Observer};
use crate::integrate::{Integrator, Scenario};
use crate::response::Response;

/// Regularized friction and penalty contacts under Dormand-Prince 5(4).
#[derive(Debug, Clone)]
pub struct Regularized {
    /// Relative tolerance of the step control.
    pub rtol: f64,
    /// Absolute tolerance (m, m/s).
    pub atol: f64,
    /// Friction regularization velocity (m/s).
    pub eps: f64,
    /// Penalty stiffness per contact (N/m).
    pub stiffness: f64,
    /// Smallest step allowed before the run is declared stalled (s).
    pub min_step: f64,
}

impl Regularized {
    /// Tolerance rtol (atol = rtol x 1e-3), eps = 1e-4 m/s, stiffness 1e9 N/m.
    pub fn new(rtol: f64) -> Regularized {
        Regularized {
            rtol,
            atol: rtol * 1e-3,
            eps: 1e-4,
            stiffness: 1e9,
            min_step: 1e-12,
        }
    }
}

struct Rhs<'a> {
    m: &'a Model,
    eps: f64,
    k: f64,
    damping: &'a [f64],
    gone: &'a [bool],
}

impl Rhs<'_> {
    /// dy/dt for y = (u, v).
    fn eval(&self, ag: f64, y: &[f64], out: &mut [f64]) {
        let n = self.m.n;
        let (u, v) = y.split_at(n);
        for i in 0..n {
            out[i] = v[i];
            out[n + i] = if self.m.movable[i] && !self.gone[i] {
                -ag
            } else {
                0.0
            };
        }
        for j in &self.m.horizontal {
            if self.gone[j.upper] || j.lower_any.is_some_and(|l| self.gone[l]) {
                continue;
            }
            let f = j.capacity * (self.m.slip_velocity(j, v) / self.eps).tanh();
            out[n + j.upper] -= f / self.m.mass[j.upper];
            if let Some(l) = j.lower {
                out[n + l] += f / self.m.mass[l];
            }
        }
        for (kf, face) in self.m.vertical.iter().enumerate() {
            if self.gone[face.pair.0] || self.gone[face.pair.1] {
                continue;
            }
            let pen = -self.m.gap(face, u);
            if pen <= 0.0 {
                continue;
            }
            let closing = face.left.map_or(0.0, |l| v[l]) - face.right.map_or(0.0, |r| v[r]);
            let force = (self.k * pen + self.damping[kf] * closing).max(0.0);
            if let Some(l) = face.left {
                out[n + l] -= force / self.m.mass[l];
            }
            if let Some(r) = face.right {
                out[n + r] += force / self.m.mass[r];
            }
        }
    }
}

// Dormand-Prince 5(4) tableau.
const C: [f64; 7] = [0.0, 1.0 / 5.0, 3.0 / 10.0, 4.0 / 5.0, 8.0 / 9.0, 1.0, 1.0];
const A: [[f64; 6]; 7] = [
    [0.0; 6],
    [1.0 / 5.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.0 / 40.0, 9.0 / 40.0, 0.0, 0.0, 0.0, 0.0],
    [44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0, 0.0, 0.0, 0.0],
    [
        19372.0 / 6561.0,
        -25360.0 / 2187.0,
        64448.0 / 6561.0,
        -212.0 / 729.0,
        0.0,
        0.0,
    ],
    [
        9017.0 / 3168.0,
        -355.0 / 33.0,
        46732.0 / 5247.0,
        49.0 / 176.0,
        -5103.0 / 18656.0,
        0.0,
    ],
    [
        35.0 / 384.0,
        0.0,
        500.0 / 1113.0,
        125.0 / 192.0,
        -2187.0 / 6784.0,
        11.0 / 84.0,
    ],
];
// First same as last: the fifth-order weights are the last stage's row.
const B5: [f64; 7] = [A[6][0], A[6][1], A[6][2], A[6][3], A[6][4], A[6][5], 0.0];
const B4: [f64; 7] = [
    5179.0 / 57600.0,
    0.0,
    7571.0 / 16695.0,
    393.0 / 640.0,
    -92097.0 / 339200.0,
    187.0 / 2100.0,
    1.0 / 40.0,
];

/// y' = f(t, y), written into its third argument.
pub(crate) type Derivative<'a> = dyn FnMut(f64, &[f64], &mut [f64]) + 'a;

/// The stages of Dormand-Prince 5(4) steps of y' = f(t, y). The last stage of a step is the
/// derivative at its fifth-order end point (first same as last), so an accepted step hands it
/// to the next as its first: six evaluations a step, not seven; a rejected step keeps its
/// first stage too.
pub(crate) struct Stages {
    k: Vec<Vec<f64>>,
    /// k[0] holds f at the current (t, y).
    first_known: bool,
    scratch: Vec<f64>,
    /// The fifth-order solution of the last step.
    pub y5: Vec<f64>,
    /// Fifth- minus fourth-order solution of the last step (the error estimate).
    pub difference: Vec<f64>,
    /// Evaluations of f so far.
    pub evaluations: u64,
}

impl Stages {
    pub(crate) fn new(dim: usize) -> Stages {
        Stages {
            k: vec![vec![0.0; dim]; 7],
            first_known: false,
            scratch: vec![0.0; dim],
            y5: vec![0.0; dim],
            difference: vec![0.0; dim],
            evaluations: 0,
        }
    }

    /// One step from (t, y) over h: `y5` and `difference`.
    pub(crate) fn step(&mut self, f: &mut Derivative, t: f64, y: &[f64], h: f64) {
        if !self.first_known {
            f(t, y, &mut self.k[0]);
            self.evaluations += 1;
            self.first_known = true;
        }
        for s in 1..7 {
            for (i, x) in self.scratch.iter_mut().enumerate() {
                *x = y[i] + h * (0..s).map(|j| A[s][j] * self.k[j][i]).sum::<f64>();
            }
            f(t + C[s] * h, &self.scratch, &mut self.k[s]);
            self.evaluations += 1;
        }
        for (i, &yi) in y.iter().enumerate() {
            self.y5[i] = yi + h * (0..7).map(|s| B5[s] * self.k[s][i]).sum::<f64>();
            let y4 = yi + h * (0..7).map(|s| B4[s] * self.k[s][i]).sum::<f64>();
            self.difference[i] = self.y5[i] - y4;
        }
    }

    /// Takes the step: y becomes its fifth-order solution, whose derivative (the last stage,
    /// evaluated at exactly that point) is the next step's first stage.
    pub(crate) fn accept(&mut self, y: &mut Vec<f64>) {
        std::mem::swap(y, &mut self.y5);
        self.k.swap(0, 6);
    }

    /// The right-hand side changed: the next step evaluates its first stage afresh.
    pub(crate) fn forget(&mut self) {
        self.first_known = false;
    }
}

impl Integrator for Regularized {
    fn method(&self) -> &'static str {
        "regularized"
    }

    fn run(&self, sc: &Scenario) -> Result<Response, SimulationError> {
        sc.settings.validate(sc.wall.blocks.len())?;
        positive("rtol", self.rtol, "")?;
        positive("eps", self.eps, " m/s")?;
        positive("stiffness", self.stiffness, " N/m")?;
        let m = Model::new(sc);
        let mut obs = Observer::new(sc, &m, sc.motion);
        let n = m.n;
        // Dashpot for restitution e: damping ratio z = -ln e / sqrt(pi^2 + ln^2 e).
        let z = if m.restitution >= 1.0 {
            0.0
        } else if m.restitution <= 0.0 {
            1.0
        } else {
            let l = m.restitution.ln();
            -l / (std::f64::consts::PI.powi(2) + l * l).sqrt()
        };
        let damping: Vec<f64> = m
            .vertical
            .iter()
            .map(|f| {
                let inv = f.left.map_or(0.0, |b| 1.0 / m.mass[b])
                    + f.right.map_or(0.0, |b| 1.0 / m.mass[b]);
                2.0 * z * (self.stiffness / inv).sqrt()
            })
            .collect();
        let mut y = vec![0.0; 2 * n];
        let mut t = 0.0;
        let t_end = sc.settings.duration_s;
        let mut h = 1e-4f64.min(t_end);
        let mut stages = Stages::new(2 * n);
        let mut steps = 0u64;
        let mut touching = vec![false; m.vertical.len()];
        while t < t_end && !obs.stopped {
            h = h.min(t_end - t);
            let rhs = Rhs {
                m: &m,
                eps: self.eps,
                k: self.stiffness,
                damping: &damping,
                gone: &obs.gone,
            };
            let mut f = |t: f64, y: &[f64], out: &mut [f64]| rhs.eval(sc.motion.accel(t), y, out);
            stages.step(&mut f, t, &y, h);
            let mut err: f64 = 0.0;
            for (&y0, (&y5, &d)) in y.iter().zip(stages.y5.iter().zip(&stages.difference)) {
                let scale = self.atol + self.rtol * y0.abs().max(y5.abs());
                err = err.max((d / scale).abs());
            }
            if err <= 1.0 {
                t += h;
                stages.accept(&mut y);
                steps += 1;
                let fallen = obs.gone.iter().filter(|&&g| g).count();
                let (u, v) = y.split_at(n);
                for (kf, f) in m.vertical.iter().enumerate() {
                    let now = m.gap(f, u) < 0.0;
                    if now && !touching[kf] {
                        let side = |b: Option<usize>| b.map_or(0.0, |b| v[b]);
                        obs.impact(
                            t,
                            kf,
                            [side(f.left), side(f.right)],
                            [side(f.left), side(f.right)],
                        );
                    }
                    touching[kf] = now;
                }
                if touching.iter().any(|&x| x) {
                    obs.impulsive();
                }
                obs.step(t, u, v);
                if obs.gone.iter().filter(|&&g| g).count() != fallen {
                    // A block fell: the right-hand side changed, the last stage is stale.
                    stages.forget();
                }
            }
            let factor = if err == 0.0 {
                5.0
            } else {
                (0.9 * err.powf(-0.2)).clamp(0.2, 5.0)
            };
            h *= factor;
            if h < self.min_step {
                return Err(SimulationError::StepTooSmall {
                    method: "regularized",
                    min_step_s: self.min_step,
                    time_s: t,
                    detail: format!("stiffness {} N/m, eps {} m/s", self.stiffness, self.eps),
                });
            }
        }
        Ok(obs.finish("regularized", sc, steps))
    }
}

#[cfg(test)]
mod tests {
    use super::Stages;

    /// Dormand-Prince is fifth order: on y'' = -y over [0, 1] with fixed steps, halving the
    /// step divides the error of the solution by about 2^5 and that of the embedded
    /// fourth-order estimate's difference by about 2^5 too (it is the local error of the fourth
    /// order, h^5); and every step after the first costs six evaluations.
    #[test]
    fn dormand_prince_converges_at_fifth_order_with_six_evaluations_a_step() {
        let error = |steps: usize| {
            let h = 1.0 / steps as f64;
            let mut y = vec![1.0, 0.0];
            let mut stages = Stages::new(2);
            let mut f = |_t: f64, y: &[f64], out: &mut [f64]| {
                out[0] = y[1];
                out[1] = -y[0];
            };
            for k in 0..steps {
                stages.step(&mut f, k as f64 * h, &y, h);
                stages.accept(&mut y);
            }
            assert_eq!(stages.evaluations, 1 + 6 * steps as u64);
            (y[0] - 1f64.cos()).abs().max((y[1] + 1f64.sin()).abs())
        };
        let (coarse, fine) = (error(10), error(20));
        let order = (coarse / fine).log2();
        assert!(
            (order - 5.0).abs() < 0.3,
            "order {order} ({coarse:e}, {fine:e})"
        );
    }
}
