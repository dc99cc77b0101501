//! Reference cases with answers known independently of the integrator: small walls built in
//! code, and the closed-form stick-slip motion of one block on the ground under a sine. Tests and
//! benches share them.

use crate::wall::{BlockDescription, RectangleDescription, RowDescription, Wall, WallDescription};
use std::collections::BTreeMap;

fn description(friction: f64) -> WallDescription {
    WallDescription {
        version: crate::wall::WALL_FORMAT_VERSION,
        name: None,
        thickness_m: 1.0,
        density_kg_m3: Some(2000.0),
        unit_weight_kn_m3: None,
        friction,
        restitution: 1.0,
        rocking_restitution_factor: 1.0,
        g_m_s2: 9.81,
        rows: Vec::new(),
        rectangles: Vec::new(),
        joint_friction: BTreeMap::new(),
    }
}

fn block(width_m: f64, gap_m: f64) -> BlockDescription {
    BlockDescription {
        width_m,
        gap_m,
        name: None,
        height_m: None,
        density_kg_m3: None,
        fixed: false,
    }
}

fn build(d: WallDescription, name: &str) -> Wall {
    let mut w = Wall::from_description(&d).expect("sample walls are valid");
    w.name = name.to_string();
    w
}

/// One 1 m x 1 m block on the ground.
pub fn one_block(friction: f64) -> Wall {
    let mut d = description(friction);
    d.rows.push(RowDescription {
        height_m: 1.0,
        x_m: 0.0,
        blocks: vec![block(1.0, 0.0)],
    });
    build(d, "one block")
}

/// B2 (1 m wide, 0.5 m high) on B1 (1 m x 0.5 m) on the ground.
pub fn stacked_pair(friction_bottom: f64, friction_top: f64) -> Wall {
    let mut d = description(friction_bottom);
    for _ in 0..2 {
        d.rows.push(RowDescription {
            height_m: 0.5,
            x_m: 0.0,
            blocks: vec![block(1.0, 0.0)],
        });
    }
    d.joint_friction.insert("B2/B1".into(), friction_top);
    build(d, "stacked pair")
}

/// Blocks in one course on the ground with the given frictions and gaps before each block.
pub fn course(frictions: &[f64], gaps_m: &[f64], restitution: f64) -> Wall {
    let mut d = description(frictions[0]);
    d.restitution = restitution;
    d.rows.push(RowDescription {
        height_m: 0.5,
        x_m: 0.0,
        blocks: gaps_m.iter().map(|&g| block(1.0, g)).collect(),
    });
    for (k, &mu) in frictions.iter().enumerate() {
        d.joint_friction.insert(format!("B{}/ground", k + 1), mu);
    }
    build(d, "course")
}

/// An abutment (fixed, at x < 0) and one block on the ground at `gap_m` to its right.
pub fn block_and_abutment(friction: f64, gap_m: f64, restitution: f64) -> Wall {
    let mut d = description(friction);
    d.restitution = restitution;
    d.rectangles.push(RectangleDescription {
        x_m: -1.0,
        y_m: 0.0,
        width_m: 1.0,
        height_m: 1.0,
        name: Some("Abutment".into()),
        density_kg_m3: None,
        fixed: true,
    });
    d.rectangles.push(RectangleDescription {
        x_m: gap_m,
        y_m: 0.0,
        width_m: 1.0,
        height_m: 0.5,
        name: Some("Block".into()),
        density_kg_m3: None,
        fixed: false,
    });
    build(d, "block and abutment")
}

/// The stick-slip motion of one block on the ground (friction mu) under
/// a_g = amplitude sin(omega t + phase), from rest, computed phase by phase from the closed-form
/// ground velocity and displacement, with stop times found by bisection to the last bit.
pub struct SlidingBlockReference {
    mu_g: f64,
    amplitude: f64,
    omega: f64,
    phase: f64,
    /// Phases: (start time, displacement at start, direction: 0 stuck, +1/-1 sliding).
    phases: Vec<(f64, f64, i8)>,
}

impl SlidingBlockReference {
    fn ag(&self, t: f64) -> f64 {
        self.amplitude * (self.omega * t + self.phase).sin()
    }
    fn vg(&self, t: f64) -> f64 {
        self.amplitude / self.omega * (self.phase.cos() - (self.omega * t + self.phase).cos())
    }
    fn dg(&self, t: f64) -> f64 {
        let (a, w, p) = (self.amplitude, self.omega, self.phase);
        a / w * p.cos() * t - a / (w * w) * ((w * t + p).sin() - p.sin())
    }
    /// Velocity at t of a slide that started from rest at t0 in direction dir.
    fn slide_v(&self, t0: f64, dir: i8, t: f64) -> f64 {
        -f64::from(dir) * self.mu_g * (t - t0) - (self.vg(t) - self.vg(t0))
    }
    fn slide_u(&self, t0: f64, u0: f64, dir: i8, t: f64) -> f64 {
        let tau = t - t0;
        u0 - 0.5 * f64::from(dir) * self.mu_g * tau * tau
            - (self.dg(t) - self.dg(t0) - self.vg(t0) * tau)
    }

    /// Solves the motion up to `duration` s.
    pub fn new(
        mu: f64,
        g: f64,
        amplitude: f64,
        frequency_hz: f64,
        phase_rad: f64,
        duration: f64,
    ) -> Self {
        let mut r = SlidingBlockReference {
            mu_g: mu * g,
            amplitude,
            omega: 2.0 * std::f64::consts::PI * frequency_hz,
            phase: phase_rad,
            phases: vec![(0.0, 0.0, 0)],
        };
        let step = 1e-3 / frequency_hz;
        let bisect = |f: &dyn Fn(f64) -> bool, mut lo: f64, mut hi: f64| {
            // f(lo) false, f(hi) true: the first time it turns true.
            while hi > lo.next_up() {
                let m = 0.5 * (lo + hi);
                if m <= lo || m >= hi {
                    break;
                }
                if f(m) {
                    hi = m;
                } else {
                    lo = m;
                }
            }
            hi
        };
        loop {
            let &(t0, u0, dir) = r.phases.last().expect("phases start non-empty");
            if t0 >= duration {
                break;
            }
            let next = if dir == 0 {
                // Stuck until |a_g| exceeds mu g.
                let slips = |t: f64| r.ag(t).abs() > r.mu_g;
                let mut t = t0;
                loop {
                    if t >= duration {
                        break None;
                    }
                    let t1 = (t + step).min(duration);
                    if slips(t1) {
                        let ts = bisect(&slips, t, t1);
                        break Some((ts, u0, if r.ag(ts) > 0.0 { -1 } else { 1 }));
                    }
                    t = t1;
                }
            } else {
                let stopped = |t: f64| f64::from(dir) * r.slide_v(t0, dir, t) <= 0.0;
                let mut t = t0 + step;
                loop {
                    if t >= duration {
                        break None;
                    }
                    let t1 = (t + step).min(duration);
                    if stopped(t1) {
                        let ts = bisect(&stopped, t, t1);
                        let us = r.slide_u(t0, u0, dir, ts);
                        let a = r.ag(ts);
                        let new_dir = if a.abs() > r.mu_g {
                            if a > 0.0 {
                                -1
                            } else {
                                1
                            }
                        } else {
                            0
                        };
                        break Some((ts, us, new_dir));
                    }
                    t = t1;
                }
            };
            match next {
                Some(p) => r.phases.push(p),
                None => break,
            }
        }
        r
    }

    /// Displacement relative to the ground at t (m).
    pub fn displacement(&self, t: f64) -> f64 {
        let k = self.phases.partition_point(|p| p.0 <= t).saturating_sub(1);
        let (t0, u0, dir) = self.phases[k];
        if dir == 0 {
            u0
        } else {
            self.slide_u(t0, u0, dir, t)
        }
    }

    /// Largest |u| up to `duration` (it is reached where a slide stops).
    pub fn max_abs_displacement(&self) -> f64 {
        self.phases.iter().map(|p| p.1.abs()).fold(0.0, f64::max)
    }

    /// Number of stick-slip phases found.
    pub fn phase_count(&self) -> usize {
        self.phases.len()
    }
}

/// A deterministic broadband record for benchmarks and tests: a sum of 40 sines with
/// frequencies between 0.3 and 12 Hz and fixed pseudo-random phases, under a rise-hold-decay
/// envelope, scaled to the given peak (m/s2), sampled at `dt_s` for `duration_s`.
pub fn broadband_record(duration_s: f64, dt_s: f64, pga_m_s2: f64) -> crate::motion::Record {
    let n = (duration_s / dt_s).round() as usize + 1;
    let mut state: u64 = 0x9e37_79b9_7f4a_7c15;
    let mut next = || {
        state ^= state << 13;
        state ^= state >> 7;
        state ^= state << 17;
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let waves: Vec<(f64, f64)> = (0..40)
        .map(|k| {
            let f = 0.3 * (40.0f64).powf(k as f64 / 39.0);
            (
                2.0 * std::f64::consts::PI * f,
                2.0 * std::f64::consts::PI * next(),
            )
        })
        .collect();
    let mut a: Vec<f64> = (0..n)
        .map(|i| {
            let t = i as f64 * dt_s;
            let envelope = (t / 2.0).min(1.0)
                * (-((t - 0.5 * duration_s).max(0.0)) / (0.2 * duration_s)).exp();
            envelope * waves.iter().map(|(w, p)| (w * t + p).sin()).sum::<f64>()
        })
        .collect();
    let peak = a.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for x in &mut a {
        *x *= pga_m_s2 / peak;
    }
    crate::motion::Record::new("broadband", dt_s, a).expect("finite samples")
}

/// Carlson's symmetric elliptic integral R_F(x, y, z) (x, y, z >= 0, at most one zero), by
/// duplication to round-off (Carlson 1995, Numer. Algorithms 10).
pub fn carlson_rf(mut x: f64, mut y: f64, mut z: f64) -> f64 {
    loop {
        let mean = (x + y + z) / 3.0;
        let dx = 1.0 - x / mean;
        let dy = 1.0 - y / mean;
        let dz = 1.0 - z / mean;
        if dx.abs().max(dy.abs()).max(dz.abs()) < 1e-4 {
            // Fifth-order series in the deviations: the error is below 1e-20 here.
            let e2 = dx * dy - dz * dz;
            let e3 = dx * dy * dz;
            return (1.0 - e2 / 10.0 + e3 / 14.0 + e2 * e2 / 24.0 - 3.0 * e2 * e3 / 44.0)
                / mean.sqrt();
        }
        let (sx, sy, sz) = (x.sqrt(), y.sqrt(), z.sqrt());
        let lambda = sx * sy + sy * sz + sz * sx;
        x = 0.25 * (x + lambda);
        y = 0.25 * (y + lambda);
        z = 0.25 * (z + lambda);
    }
}

/// Legendre's incomplete elliptic integral of the first kind F(phi, k), |phi| <= pi/2.
pub fn elliptic_f(phi: f64, k: f64) -> f64 {
    let (s, c) = phi.sin_cos();
    s * carlson_rf(c * c, 1.0 - k * k * s * s, 1.0)
}

/// Time for a block released at rest from theta0 (0 < theta0 < alpha) on a still base to fall
/// back to theta = 0, from the exact equations: the pendulum psi'' = -p^2 sin psi with
/// psi = pi - (alpha - theta) gives t = [K(k) - F(phi1, k)] / p with k = cos((alpha - theta0)
/// / 2), sin phi1 = cos(alpha / 2) / k (Housner 1963). The difference is written as one integral,
/// F(phi2, k) with tan phi1 tan phi2 = 1 / k' (Legendre's addition), and tan phi2 from
/// cos^2 A - cos^2 B = sin(B + A) sin(B - A), so that it keeps its digits for small theta0.
pub fn free_rocking_quarter_s(alpha: f64, p: f64, theta0: f64) -> f64 {
    let k = ((alpha - theta0) / 2.0).cos();
    let k_prime = ((alpha - theta0) / 2.0).sin();
    let spread = ((alpha - theta0 / 2.0).sin() * (theta0 / 2.0).sin()).sqrt();
    let phi2 = (spread / (k_prime * (alpha / 2.0).cos())).atan();
    elliptic_f(phi2, k) / p
}

/// The same for the linearised equations: acosh(1 / (1 - theta0 / alpha)) / p.
pub fn linear_free_rocking_quarter_s(alpha: f64, p: f64, theta0: f64) -> f64 {
    (1.0 / (1.0 - theta0 / alpha)).acosh() / p
}

/// The amplitude a block reaches after landing from amplitude theta_n (exact equations,
/// Housner's r): E(theta_{n+1}) = r^2 E(theta_n) with E(theta) = cos(alpha - theta) - cos(alpha)
/// = 2 sin(alpha - theta/2) sin(theta/2), solved by Newton's method (E' = sin(alpha - theta))
/// in that form, which keeps its digits for small amplitudes.
pub fn amplitude_after_landing(alpha: f64, r: f64, theta_n: f64) -> f64 {
    let e = |x: f64| 2.0 * (alpha - x / 2.0).sin() * (x / 2.0).sin();
    let target = r * r * e(theta_n);
    let mut x = target / alpha.sin();
    for _ in 0..50 {
        let step = (e(x) - target) / (alpha - x).sin();
        x -= step;
        if step.abs() <= 1e-17 * x {
            break;
        }
    }
    x
}
