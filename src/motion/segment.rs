//! One piece of a ground motion on which a_g, its integrals and its derivatives are closed-form
//! functions of s = t - t0, and a_g is monotone.

use std::cell::Cell;

/// The closed form of a_g on a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Shape {
    /// a_g = a0 + slope * s.
    Linear {
        /// a_g at the start (m/s2).
        a0: f64,
        /// Rate (m/s3).
        slope: f64,
    },
    /// a_g = amplitude * sin(theta0 + omega * s), monotone on the segment.
    Sine {
        /// Amplitude (m/s2).
        amplitude: f64,
        /// Angular frequency (rad/s).
        omega: f64,
        /// Phase at the start (rad).
        theta0: f64,
        /// sin(theta0), cached: every evaluation needs it.
        sin0: f64,
        /// cos(theta0), cached.
        cos0: f64,
    },
}

impl Shape {
    /// A sine arc starting at phase theta0.
    pub fn sine(amplitude: f64, omega: f64, theta0: f64) -> Shape {
        let (sin0, cos0) = sin_cos(theta0);
        Shape::Sine {
            amplitude,
            omega,
            theta0,
            sin0,
            cos0,
        }
    }

    /// a_g at s from the start (m/s2).
    pub fn accel(&self, s: f64) -> f64 {
        match *self {
            Shape::Linear { a0, slope } => a0 + slope * s,
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                let (sn, cs) = sin_cos(omega * s);
                amplitude * (sin0 * cs + cos0 * sn)
            }
        }
    }
}

/// A segment [t0, t1) of a ground motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// Start (s).
    pub t0: f64,
    /// End (s); infinite for the quiet tail after the motion.
    pub t1: f64,
    /// Ground velocity at t0 (m/s).
    pub v0: f64,
    /// Ground displacement at t0 (m).
    pub d0: f64,
    /// Vertical load factor 1 + a_v/g at t0 and its rate (1/s): every normal load, hence every
    /// friction capacity, is multiplied by lambda0 + lambda1 s. (1, 0) without vertical shaking.
    pub lambda: (f64, f64),
    /// a_g on the segment.
    pub shape: Shape,
}

/// The memo of `sin_cos` has 2^TRIG_BITS slots.
const TRIG_BITS: u32 = 5;
const TRIG_SLOTS: usize = 1 << TRIG_BITS;

thread_local! {
    /// The latest arguments of `sin_cos` (bits) with their sine and cosine, direct-mapped.
    static TRIG: [Cell<(u64, f64, f64)>; TRIG_SLOTS] =
        const { [const { Cell::new((NAN_BITS, f64::NAN, f64::NAN)) }; TRIG_SLOTS] };
}

/// An empty slot: a NaN argument, whose sine and cosine are NaN anyway.
const NAN_BITS: u64 = 0x7ff8_0000_0000_0000;

/// The slot of an argument (bits). Fibonacci hashing: the top bits of the product depend on
/// every bit of the argument.
fn trig_slot(bits: u64) -> usize {
    (bits.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - TRIG_BITS)) as usize
}

/// sin(x) and cos(x), remembered for recent arguments. Why: the event-driven integrator
/// evaluates a sliding cluster many times at one instant (its displacement, velocity and
/// acceleration, each block's, each joint's), and a root finder a function and its derivative
/// at one point; on the paper's wall four calls in five repeat one of the last few arguments.
/// The values are those of `f64::sin_cos`, bit for bit.
fn sin_cos(x: f64) -> (f64, f64) {
    let bits = x.to_bits();
    TRIG.with(|memo| {
        let slot = &memo[trig_slot(bits)];
        let (key, s, c) = slot.get();
        if key == bits {
            (s, c)
        } else {
            let (s, c) = x.sin_cos();
            slot.set((bits, s, c));
            (s, c)
        }
    })
}

/// sin(x) - x without cancellation for small x.
fn sin_minus_x(x: f64) -> f64 {
    if x.abs() < 0.25 {
        let x2 = x * x;
        // Taylor series to x^13: the next term is below 1e-17 relative for |x| < 0.25.
        -x * x2
            * (1.0 / 6.0
                - x2 * (1.0 / 120.0
                    - x2 * (1.0 / 5040.0
                        - x2 * (1.0 / 362_880.0
                            - x2 * (1.0 / 39_916_800.0 - x2 / 6_227_020_800.0)))))
    } else {
        x.sin() - x
    }
}

/// sin(x) - x given sin(x/2) and cos(x/2), which callers have already computed.
fn sin_minus_x_from_half(x: f64, h: f64, ch: f64) -> f64 {
    if x.abs() < 0.25 {
        sin_minus_x(x)
    } else {
        2.0 * h * ch - x
    }
}

/// cos(x) - 1 + x^2/2 without cancellation for small x.
fn cos_minus_1_plus_half_x2(x: f64) -> f64 {
    if x.abs() < 0.25 {
        let x2 = x * x;
        x2 * x2
            * (1.0 / 24.0
                - x2 * (1.0 / 720.0
                    - x2 * (1.0 / 40_320.0 - x2 * (1.0 / 3_628_800.0 - x2 / 479_001_600.0))))
    } else {
        x.cos() - 1.0 + 0.5 * x * x
    }
}

impl Segment {
    /// The same motion described from time t on: a segment starting exactly at t (not at
    /// t0 + (t - t0), which can differ by an ulp). Closed forms measured from the new start stay
    /// free of cancellation near it.
    pub fn anchored(&self, t: f64) -> Segment {
        let s_a = t - self.t0;
        let shape = match self.shape {
            Shape::Linear { slope, .. } => Shape::Linear {
                a0: self.accel(s_a),
                slope,
            },
            Shape::Sine {
                amplitude,
                omega,
                theta0,
                sin0,
                cos0,
            } => {
                // Rotate exactly as `accel` does, so the new start's a_g is bit for bit the
                // value the parent gives at s_a: decisions made with one and motion computed
                // with the other must agree on ties.
                let (sn, cs) = sin_cos(omega * s_a);
                Shape::Sine {
                    amplitude,
                    omega,
                    theta0: theta0 + omega * s_a,
                    sin0: sin0 * cs + cos0 * sn,
                    cos0: cos0 * cs - sin0 * sn,
                }
            }
        };
        Segment {
            t0: t,
            t1: self.t1,
            lambda: (self.lambda_at(s_a), self.lambda.1),
            v0: self.v0 + self.dv(s_a),
            d0: self.d0 + self.v0 * s_a + self.dd(s_a),
            shape,
        }
    }

    /// a_g(s) - a_g(0), dv_beyond(s) and dd_beyond(s) together, from one sine evaluation.
    pub fn beyond(&self, s: f64) -> (f64, f64, f64) {
        match self.shape {
            Shape::Linear { slope, .. } => {
                (slope * s, 0.5 * slope * s * s, slope * s * s * s / 6.0)
            }
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                let x = omega * s;
                let (h, ch) = sin_cos(0.5 * x);
                let smx = sin_minus_x_from_half(x, h, ch);
                let cos_part = if x.abs() < 0.25 {
                    cos_minus_1_plus_half_x2(x)
                } else {
                    0.5 * x * x - 2.0 * h * h
                };
                (
                    2.0 * amplitude * (cos0 * ch - sin0 * h) * h,
                    amplitude / omega * (2.0 * cos0 * h * h + sin0 * smx),
                    -amplitude / (omega * omega) * (sin0 * cos_part + cos0 * smx),
                )
            }
        }
    }

    /// Where on [s_a, s_b] a_g equals `target`, in closed form (a_g is monotone on a segment):
    /// `None` if it does not. Accurate to a few ulps; callers polish it to the exact float.
    pub fn time_of_accel(&self, target: f64, s_a: f64, s_b: f64) -> Option<f64> {
        let (fa, fb) = (self.accel(s_a) - target, self.accel(s_b) - target);
        if (fa > 0.0) == (fb > 0.0) && fa != 0.0 && fb != 0.0 {
            return None;
        }
        let s = match self.shape {
            Shape::Linear { a0, slope } => (target - a0) / slope,
            Shape::Sine {
                amplitude,
                omega,
                theta0,
                ..
            } => {
                // The arc runs between crests at pi/2 + k pi: rising for odd k... pick the
                // solution of sin(theta) = target/A on the arc containing [s_a, s_b], found
                // from its middle (a segment starts at a crest, where rounding of theta0 can
                // fall on either arc).
                let y = (target / amplitude).clamp(-1.0, 1.0).asin();
                let mid = theta0 + omega * 0.5 * (s_a + s_b);
                let k = ((mid - std::f64::consts::FRAC_PI_2) / std::f64::consts::PI).floor();
                let base = std::f64::consts::FRAC_PI_2 + k * std::f64::consts::PI;
                let rising = (k as i64).rem_euclid(2) == 1;
                // On a rising arc theta - 2m pi = y; on a falling one theta - 2m pi = pi - y.
                let principal = if rising { y } else { std::f64::consts::PI - y };
                let turns = ((base - principal) / (2.0 * std::f64::consts::PI)).ceil();
                let theta = principal + turns * 2.0 * std::f64::consts::PI;
                (theta - theta0) / omega
            }
        };
        s.is_finite().then(|| s.clamp(s_a, s_b))
    }

    /// The vertical load factor at s.
    pub fn lambda_at(&self, s: f64) -> f64 {
        self.lambda.0 + self.lambda.1 * s
    }

    /// True when the vertical load factor varies on this segment.
    pub fn has_vertical(&self) -> bool {
        self.lambda != (1.0, 0.0)
    }

    /// Integral of a_g(sigma) sigma^2 / 2 from 0 to s (the work of inertial forces on a cluster
    /// whose friction varies linearly). Only linear segments carry a vertical component.
    pub fn moment2(&self, s: f64) -> f64 {
        match self.shape {
            Shape::Linear { a0, slope } => s * s * s * (a0 / 6.0 + slope * s / 8.0),
            Shape::Sine { .. } => 0.0,
        }
    }

    /// Where on [s_a, s_b] a_g(s) equals k lambda(s), in closed form: `None` if it does not.
    pub fn time_of_ratio(&self, k: f64, s_a: f64, s_b: f64) -> Option<f64> {
        if !self.has_vertical() {
            return self.time_of_accel(k, s_a, s_b);
        }
        let Shape::Linear { a0, slope } = self.shape else {
            return None;
        };
        let (fa, fb) = (
            a0 + slope * s_a - k * self.lambda_at(s_a),
            a0 + slope * s_b - k * self.lambda_at(s_b),
        );
        if (fa > 0.0) == (fb > 0.0) && fa != 0.0 && fb != 0.0 {
            return None;
        }
        let s = (k * self.lambda.0 - a0) / (slope - k * self.lambda.1);
        s.is_finite().then(|| s.clamp(s_a, s_b))
    }

    /// a_g(s) - a_g(0) (m/s2), without cancellation.
    pub fn da(&self, s: f64) -> f64 {
        match self.shape {
            Shape::Linear { slope, .. } => slope * s,
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                let (sh, ch) = sin_cos(0.5 * omega * s);
                2.0 * amplitude * (cos0 * ch - sin0 * sh) * sh
            }
        }
    }

    /// Ground velocity gained beyond the tangent: dv(s) - a_g(0) s (m/s), without cancellation.
    pub fn dv_beyond(&self, s: f64) -> f64 {
        match self.shape {
            Shape::Linear { slope, .. } => 0.5 * slope * s * s,
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                let x = omega * s;
                let (h, ch) = sin_cos(0.5 * x);
                amplitude / omega * (2.0 * cos0 * h * h + sin0 * sin_minus_x_from_half(x, h, ch))
            }
        }
    }

    /// Ground displacement gained beyond the tangent parabola: dd(s) - a_g(0) s^2/2 (m).
    pub fn dd_beyond(&self, s: f64) -> f64 {
        match self.shape {
            Shape::Linear { slope, .. } => slope * s * s * s / 6.0,
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                let x = omega * s;
                let (h, ch) = sin_cos(0.5 * x);
                let cos_part = if x.abs() < 0.25 {
                    cos_minus_1_plus_half_x2(x)
                } else {
                    0.5 * x * x - 2.0 * h * h
                };
                -amplitude / (omega * omega)
                    * (sin0 * cos_part + cos0 * sin_minus_x_from_half(x, h, ch))
            }
        }
    }

    /// a_g at s (m/s2).
    pub fn accel(&self, s: f64) -> f64 {
        self.shape.accel(s)
    }

    /// a_g at the start, bit for bit `accel(0.0)`: sin 0 = 0 and cos 0 = 1 exactly, so no sine
    /// is evaluated. Why not `accel(0.0)`: inside a loop over clusters the compiler hoisted
    /// that call's sine (a pure function to it) out of the loop and ahead of the test for the
    /// shape, evaluating it once per segment even of a record.
    pub fn start_accel(&self) -> f64 {
        match self.shape {
            Shape::Linear { a0, slope } => a0 + slope * 0.0,
            Shape::Sine {
                amplitude,
                sin0,
                cos0,
                ..
            } => amplitude * (sin0 * 1.0 + cos0 * 0.0),
        }
    }

    /// First and second time derivatives of a_g at s, from the right.
    pub fn accel_rates(&self, s: f64) -> (f64, f64) {
        match self.shape {
            Shape::Linear { slope, .. } => (slope, 0.0),
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                let (sn, cs) = sin_cos(omega * s);
                let (sin_th, cos_th) = (sin0 * cs + cos0 * sn, cos0 * cs - sin0 * sn);
                (
                    amplitude * omega * cos_th,
                    -amplitude * omega * omega * sin_th,
                )
            }
        }
    }

    /// Ground velocity gained since t0: V_g(t0 + s) - V_g(t0) (m/s).
    pub fn dv(&self, s: f64) -> f64 {
        match self.shape {
            Shape::Linear { a0, slope } => s * (a0 + 0.5 * slope * s),
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                // cos a - cos b = 2 sin((a+b)/2) sin((b-a)/2), free of cancellation.
                let (sh, ch) = sin_cos(0.5 * omega * s);
                2.0 * amplitude / omega * (sin0 * ch + cos0 * sh) * sh
            }
        }
    }

    /// Ground displacement since t0 beyond moving on at V_g(t0):
    /// D_g(t0 + s) - D_g(t0) - V_g(t0) s (m).
    pub fn dd(&self, s: f64) -> f64 {
        match self.shape {
            Shape::Linear { a0, slope } => s * s * (0.5 * a0 + slope * s / 6.0),
            Shape::Sine {
                amplitude,
                omega,
                sin0,
                cos0,
                ..
            } => {
                // A/w^2 [w s cos th0 - sin(th0 + w s) + sin th0]
                //   = A/w^2 [2 sin th0 sin^2(w s / 2) - cos th0 (sin(w s) - w s)].
                let x = omega * s;
                let (h, ch) = sin_cos(0.5 * x);
                amplitude / (omega * omega)
                    * (2.0 * sin0 * h * h - cos0 * sin_minus_x_from_half(x, h, ch))
            }
        }
    }

    /// Integral of a_g times s from 0 to s: s dv(s) - (displacement gained beyond v0), used for
    /// the work of inertial forces.
    pub fn moment(&self, s: f64) -> f64 {
        s * self.dv(s) - self.dd(s)
    }

    /// Length of the segment (s); infinite for the tail.
    pub fn len(&self) -> f64 {
        self.t1 - self.t0
    }

    /// True when a_g is identically zero here (the quiet tail after the motion).
    pub fn is_quiet(&self) -> bool {
        matches!(self.shape, Shape::Linear { a0, slope } if a0 == 0.0 && slope == 0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn remembered_sines_are_the_sines_bit_for_bit() {
        let same = |x: f64| {
            let ((s, c), (s0, c0)) = (sin_cos(x), x.sin_cos());
            assert_eq!(
                (s.to_bits(), c.to_bits()),
                (s0.to_bits(), c0.to_bits()),
                "{x}"
            );
        };
        // Arguments that share a slot and differ only in their last bits, asked for in turn:
        // each must get its own values, not its neighbour's.
        for k in 0..200 {
            let x = (k as f64 * 0.618_033_988_749_895).fract() * 7.0 - 0.5;
            let rivals: Vec<f64> = (1..200u64)
                .map(|d| f64::from_bits(x.to_bits() + d))
                .filter(|y| trig_slot(y.to_bits()) == trig_slot(x.to_bits()))
                .take(3)
                .collect();
            assert!(!rivals.is_empty());
            for &y in &rivals {
                for z in [x, y, x, y, y] {
                    same(z);
                }
            }
        }
        for z in [0.0, -0.0, 1e-300, f64::MIN_POSITIVE, 3.0, 3.0] {
            same(z);
        }
        let (s, c) = sin_cos(f64::NAN);
        assert!(s.is_nan() && c.is_nan());
    }

    #[test]
    fn acceleration_at_the_start_is_read_without_a_sine() {
        // Signed zeros included: -0 + 0 is +0, so the formula cannot be shortened to sin0 or a0.
        let at_zero = |cos0: f64| Shape::Sine {
            amplitude: 3.0,
            omega: 2.0,
            theta0: 0.0,
            sin0: -0.0,
            cos0,
        };
        let line = |a0: f64, slope: f64| Shape::Linear { a0, slope };
        let shapes = [
            Shape::sine(4.0, 6.2, 0.7),
            Shape::sine(-2.5, 1.3, 2.0),
            at_zero(1.0),
            at_zero(-1.0),
            line(-0.0, 2.0),
            line(-0.0, -2.0),
            line(1.5, 3.0),
        ];
        for shape in shapes {
            let seg = Segment {
                t0: 1.0,
                t1: 2.0,
                v0: 0.0,
                d0: 0.0,
                lambda: (1.0, 0.0),
                shape,
            };
            assert_eq!(
                seg.start_accel().to_bits(),
                seg.accel(0.0).to_bits(),
                "{shape:?}"
            );
        }
    }

    #[test]
    fn sine_increments_match_direct_formulas() {
        let seg = Segment {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            d0: 0.0,
            lambda: (1.0, 0.0),
            shape: Shape::sine(3.0, 5.0, 0.4),
        };
        for s in [1e-7f64, 1e-3, 0.1, 0.3] {
            let dv = 3.0 / 5.0 * (0.4f64.cos() - (0.4 + 5.0 * s).cos());
            let dd = 3.0 / 25.0 * (5.0 * s * 0.4f64.cos() - (0.4 + 5.0 * s).sin() + 0.4f64.sin());
            assert_relative_eq!(seg.dv(s), dv, max_relative = 1e-12);
            assert_relative_eq!(seg.dd(s), dd, max_relative = 1e-6, epsilon = 1e-18);
        }
        // Small s: dd ~ a(0) s^2 / 2 to leading order, computed without cancellation.
        let s = 1e-6;
        assert_relative_eq!(seg.dd(s), 0.5 * seg.accel(0.0) * s * s, max_relative = 1e-5);
    }

    /// A sine arc of 3 m/s2 at 2 rad/s starting at phase theta0.
    fn sine_from(theta0: f64) -> Segment {
        Segment {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            d0: 0.0,
            lambda: (1.0, 0.0),
            shape: Shape::sine(3.0, 2.0, theta0),
        }
    }

    #[test]
    fn closed_form_time_of_an_acceleration() {
        for theta0 in [-1.5, -0.2, 1.6, 2.0, 4.0, 7.9] {
            let seg = sine_from(theta0);
            // Monotone arc: from theta0 to the next crest.
            let k = ((theta0 - std::f64::consts::FRAC_PI_2) / std::f64::consts::PI).floor();
            let end =
                (std::f64::consts::FRAC_PI_2 + (k + 1.0) * std::f64::consts::PI - theta0) / 2.0;
            let target = 0.5 * (seg.accel(0.0) + seg.accel(end));
            let s = seg.time_of_accel(target, 0.0, end).unwrap();
            assert!((seg.accel(s) - target).abs() < 1e-12, "theta0 {theta0}");
        }
        // Segments start at crests, where theta0 may round to either side of pi/2 + k pi: the
        // arc is the one the segment runs on, whatever the side.
        for k in 0..40 {
            let crest = std::f64::consts::FRAC_PI_2 + f64::from(k) * std::f64::consts::PI;
            for theta0 in [crest.next_down(), crest, crest.next_up()] {
                let seg = sine_from(theta0);
                let end = std::f64::consts::PI / 2.0;
                let target = 0.3 * seg.accel(0.0) + 0.7 * seg.accel(end);
                let s = seg.time_of_accel(target, 0.0, end).unwrap();
                assert!((seg.accel(s) - target).abs() < 1e-12, "theta0 {theta0}");
            }
        }
        let lin = Segment {
            t0: 0.0,
            t1: 1.0,
            v0: 0.0,
            d0: 0.0,
            lambda: (1.0, 0.0),
            shape: Shape::Linear {
                a0: 1.0,
                slope: -2.0,
            },
        };
        assert_eq!(lin.time_of_accel(0.0, 0.0, 1.0), Some(0.5));
        assert_eq!(lin.time_of_accel(5.0, 0.0, 1.0), None);
    }

    #[test]
    fn increments_beyond_the_tangent() {
        let seg = Segment {
            t0: 2.0,
            t1: 3.0,
            v0: 0.1,
            d0: 0.2,
            lambda: (1.0, 0.0),
            shape: Shape::sine(3.0, 5.0, 0.4),
        };
        let b = seg.anchored(2.3);
        assert_eq!(b.t0, 2.3);
        // Bit for bit what the parent gives at that instant (s = t - t0, as the engine computes it).
        assert_eq!(b.accel(0.0), seg.accel(2.3 - 2.0));
        for s in [0.05f64, 0.2] {
            assert_relative_eq!(b.accel(s), seg.accel(0.3 + s), max_relative = 1e-14);
            assert_relative_eq!(b.da(s), b.accel(s) - b.accel(0.0), max_relative = 1e-12);
            assert_relative_eq!(
                b.dv_beyond(s),
                b.dv(s) - b.accel(0.0) * s,
                max_relative = 1e-9
            );
            assert_relative_eq!(
                b.dd_beyond(s),
                b.dd(s) - 0.5 * b.accel(0.0) * s * s,
                max_relative = 1e-8
            );
        }
        // Tiny s: the leading terms A w cos(th) s^2 / 2 and A w cos(th) s^3 / 6.
        let (s, rate) = (1e-9, 3.0 * 5.0 * (0.4f64 + 1.5).cos());
        assert_relative_eq!(b.dv_beyond(s), 0.5 * rate * s * s, max_relative = 1e-6);
        assert_relative_eq!(b.dd_beyond(s), rate * s * s * s / 6.0, max_relative = 1e-6);
    }
}
