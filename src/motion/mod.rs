//! Ground motion: horizontal ground acceleration a_g(t) in m/s2, its velocity V_g and
//! displacement D_g (from rest at t = 0), cut into segments on which each is known in closed form:
//! linear a_g on a record's sample interval, monotone sine arcs between a sine's peaks. The exact
//! integrator finds events segment by segment; time-stepping integrators just sample a_g.

pub mod formats;
pub mod measures;
mod process;
mod segment;
pub mod synthetic;

pub use formats::{read_companion, read_record, ReadOptions};
pub use process::{check_scale, process, Baseline, Processing};
pub use segment::{Segment, Shape};

use crate::bounds;
use crate::error::MotionError;
use crate::units::Shown;

/// A horizontal ground acceleration history.
#[derive(Debug, Clone, PartialEq)]
pub enum Motion {
    /// a_g = amplitude * sin(2 pi f t + phase) for 0 <= t <= duration, 0 after.
    Sine(Sine),
    /// Piecewise-linear between samples, 0 after the last sample (reached linearly over one step).
    Record(Record),
    /// a_g = amplitude for 0 <= t < duration, 0 after: a rectangular pulse, the classic test
    /// of rocking (amplitude 0: the ground at rest).
    Pulse(Pulse),
}

/// A rectangular pulse.
#[derive(Debug, Clone, PartialEq)]
pub struct Pulse {
    /// Amplitude (m/s2).
    pub amplitude_m_s2: f64,
    /// Duration (s).
    pub duration_s: f64,
}

impl Pulse {
    /// Checks the numbers: a finite amplitude, a positive duration.
    pub fn validate(&self) -> Result<(), MotionError> {
        let (a, d) = (self.amplitude_m_s2, self.duration_s);
        if !(a.abs() <= bounds::MAX_ACCEL_M_S2 && d > 0.0 && d <= bounds::MAX_DURATION_S) {
            return Err(MotionError::Parameter {
                what: format!("pulse of {a} m/s2 for {d} s"),
                rule: format!(
                    "a pulse needs an amplitude of at most {} m/s2 (about 100 g) and a positive \
                     duration of at most {} s",
                    bounds::MAX_ACCEL_M_S2,
                    bounds::MAX_DURATION_S
                ),
            });
        }
        Ok(())
    }

    /// The pulse, checked.
    pub fn checked(self) -> Result<Pulse, MotionError> {
        self.validate()?;
        Ok(self)
    }

    /// The ground at rest.
    pub fn rest() -> Pulse {
        Pulse {
            amplitude_m_s2: 0.0,
            duration_s: 0.0,
        }
    }
}

/// A sine, by its named numbers: `Sine { amplitude_m_s2: 4.0, frequency_hz: 1.0, duration_s:
/// 20.0, ..Sine::default() }` (phase 0), checked by [`Motion::sine`] or [`Sine::checked`].
#[derive(Debug, Clone, PartialEq)]
pub struct Sine {
    /// Amplitude (m/s2).
    pub amplitude_m_s2: f64,
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Phase at t = 0 (rad).
    pub phase_rad: f64,
    /// Duration (s).
    pub duration_s: f64,
}

/// The El Centro 1940 record (PEER IELC180, in records/) that the paper's figures, the
/// benchmarks and the command line's defaults use.
pub const EL_CENTRO: &str = "records/elcentro1940_IELC180_peer_dt0p01_g.AT2";

/// A phase given in degrees, in radians: reduced to [0, 360) first, where the remainder is exact
/// for any float, so 1e18 degrees is 280 degrees to the bit (reducing radians would lose the
/// digits, and 2 pi is not a float).
pub fn phase_rad(degrees: f64) -> f64 {
    degrees.rem_euclid(360.0).to_radians()
}

/// A sampled record, linear between samples. Its samples are read through methods: the
/// ground velocity and displacement it keeps are their integrals, and must not fall behind.
#[derive(Debug, Clone, PartialEq)]
pub struct Record {
    /// Where it came from (file name, or a description).
    pub name: String,
    dt_s: f64,
    accel_m_s2: Vec<f64>,
    lambda: Option<Vec<f64>>,
    // Ground velocity and displacement at each sample, from rest (compensated sums).
    velocity: Vec<f64>,
    displacement: Vec<f64>,
}

impl Default for Sine {
    /// 1 Hz for 10 s from phase 0, of zero amplitude (give one).
    fn default() -> Sine {
        Sine {
            amplitude_m_s2: 0.0,
            frequency_hz: 1.0,
            phase_rad: 0.0,
            duration_s: 10.0,
        }
    }
}

impl Sine {
    /// Checks that the numbers make sense: a finite amplitude and phase, a frequency and a
    /// duration within the bounds of [`bounds`].
    pub fn validate(&self) -> Result<(), MotionError> {
        let (f, d) = (self.frequency_hz, self.duration_s);
        let ok = self.amplitude_m_s2.abs() <= bounds::MAX_ACCEL_M_S2
            && f >= bounds::FREQUENCY_HZ.0
            && f <= bounds::FREQUENCY_HZ.1
            && self.phase_rad.abs() <= bounds::MAX_PHASE_RAD
            && d > 0.0
            && d <= bounds::MAX_DURATION_S
            && f * d <= bounds::MAX_CYCLES;
        if !ok {
            return Err(MotionError::Parameter {
                what: format!(
                    "sine of {} m/s2, phase {} rad, {} Hz, {} s",
                    Shown(self.amplitude_m_s2),
                    Shown(self.phase_rad),
                    Shown(f),
                    Shown(d)
                ),
                rule: format!(
                    "a sine needs an amplitude of at most {} m/s2 (about 100 g), a frequency \
                     from {} to {} Hz, a phase within {} rad (reduce a larger one), a \
                     positive duration of at most {} s and at most {:e} cycles \
                     (docs/reliability.md: bounds)",
                    bounds::MAX_ACCEL_M_S2,
                    bounds::FREQUENCY_HZ.0,
                    bounds::FREQUENCY_HZ.1,
                    bounds::MAX_PHASE_RAD,
                    bounds::MAX_DURATION_S,
                    bounds::MAX_CYCLES
                ),
            });
        }
        Ok(())
    }

    /// The sine, checked.
    pub fn checked(self) -> Result<Sine, MotionError> {
        self.validate()?;
        Ok(self)
    }

    fn omega(&self) -> f64 {
        2.0 * std::f64::consts::PI * self.frequency_hz
    }
}

/// Compensated (Neumaier) running sum.
#[derive(Default, Clone, Copy)]
struct Sum {
    s: f64,
    c: f64,
}

impl Sum {
    fn add(&mut self, x: f64) {
        let t = self.s + x;
        self.c += if self.s.abs() >= x.abs() {
            (self.s - t) + x
        } else {
            (x - t) + self.s
        };
        self.s = t;
    }
    fn value(&self) -> f64 {
        self.s + self.c
    }
}

impl Record {
    /// A record from samples; checks dt and the values.
    pub fn new(
        name: impl Into<String>,
        dt_s: f64,
        accel_m_s2: Vec<f64>,
    ) -> Result<Record, MotionError> {
        if !bounds::within(dt_s, bounds::RECORD_DT_S) {
            return Err(MotionError::Parameter {
                what: format!("time step dt = {} s", Shown(dt_s)),
                rule: format!(
                    "it must lie from {} to {} s",
                    bounds::RECORD_DT_S.0,
                    bounds::RECORD_DT_S.1
                ),
            });
        }
        if accel_m_s2.len() as f64 * dt_s > bounds::MAX_DURATION_S {
            return Err(MotionError::Parameter {
                what: format!("{} samples at {} s", accel_m_s2.len(), Shown(dt_s)),
                rule: format!("a record may last {} s at most", bounds::MAX_DURATION_S),
            });
        }
        if accel_m_s2.len() < 2 {
            return Err(MotionError::TooFewSamples {
                found: accel_m_s2.len(),
                counted: "samples",
            });
        }
        if let Some(k) = accel_m_s2
            .iter()
            .position(|a| a.is_nan() || a.abs() > bounds::MAX_ACCEL_M_S2)
        {
            return Err(MotionError::Parameter {
                what: format!(
                    "sample {} (t = {} s) = {} m/s2",
                    k + 1,
                    k as f64 * dt_s,
                    Shown(accel_m_s2[k])
                ),
                rule: format!(
                    "a ground acceleration must be a number of at most {} m/s2 (about 100 g)",
                    bounds::MAX_ACCEL_M_S2
                ),
            });
        }
        // Exact integrals of the piecewise-linear acceleration, summed with compensation so that
        // D_g stays accurate to a few ulps over tens of thousands of samples.
        let n = accel_m_s2.len();
        let mut velocity = Vec::with_capacity(n + 1);
        let mut displacement = Vec::with_capacity(n + 1);
        let (mut v, mut d) = (Sum::default(), Sum::default());
        velocity.push(0.0);
        displacement.push(0.0);
        let mut vk = 0.0;
        for k in 0..n {
            let a0 = accel_m_s2[k];
            let a1 = accel_m_s2.get(k + 1).copied().unwrap_or(0.0);
            d.add(vk * dt_s + dt_s * dt_s * (a0 / 3.0 + a1 / 6.0));
            v.add(0.5 * (a0 + a1) * dt_s);
            vk = v.value();
            velocity.push(vk);
            displacement.push(d.value());
        }
        Ok(Record {
            name: name.into(),
            dt_s,
            accel_m_s2,
            lambda: None,
            velocity,
            displacement,
        })
    }

    /// Sample interval (s).
    pub fn dt_s(&self) -> f64 {
        self.dt_s
    }

    /// Accelerations (m/s2), the first at t = 0.
    pub fn accel_m_s2(&self) -> &[f64] {
        &self.accel_m_s2
    }

    /// Vertical load factor 1 + a_v/g at each sample, when a vertical component is given.
    pub fn lambda(&self) -> Option<&[f64]> {
        self.lambda.as_deref()
    }

    /// Time of the last sample (s).
    pub fn duration_s(&self) -> f64 {
        (self.accel_m_s2.len() - 1) as f64 * self.dt_s
    }

    /// The same record scaled by a factor (the vertical component, if any, is kept).
    pub fn scaled(&self, factor: f64) -> Result<Record, MotionError> {
        let mut r = Record::new(
            self.name.clone(),
            self.dt_s,
            self.accel_m_s2.iter().map(|a| a * factor).collect(),
        )?;
        r.lambda = self.lambda.clone();
        Ok(r)
    }

    /// Adds a vertical component: every normal load is multiplied by 1 + a_v/g. It must share
    /// the time step; a shorter one is extended with zeros. Where 1 + a_v/g <= 0 the blocks would
    /// lift off, which the sliding model cannot represent: an error names the time.
    pub fn with_vertical(&self, vertical: &Record, g: f64) -> Result<Record, MotionError> {
        if (vertical.dt_s - self.dt_s).abs() > 1e-9 * self.dt_s {
            return Err(MotionError::Contradiction(format!(
                "the vertical component's time step {} s differs from the horizontal one's {} s: \
                 resample one of them",
                Shown(vertical.dt_s),
                Shown(self.dt_s)
            )));
        }
        let n = self.accel_m_s2.len();
        let lambda: Vec<f64> = (0..n)
            .map(|k| 1.0 + vertical.accel_m_s2.get(k).copied().unwrap_or(0.0) / g)
            .collect();
        if let Some(k) = lambda.iter().position(|&l| l <= 0.0) {
            return Err(MotionError::Contradiction(format!(
                "at t = {} s the vertical acceleration {:.4} m/s2 exceeds g downwards (1 + a_v/g = {:.4} <= 0): the blocks would lift off, which this sliding model cannot represent",
                k as f64 * self.dt_s,
                vertical.accel_m_s2[k],
                lambda[k]
            )));
        }
        let mut r = self.clone();
        r.lambda = Some(lambda);
        Ok(r)
    }

    /// Peak absolute acceleration (m/s2).
    pub fn pga_m_s2(&self) -> f64 {
        self.accel_m_s2.iter().fold(0.0, |m, a| m.max(a.abs()))
    }
}

impl Motion {
    /// A sine, checked.
    pub fn sine(sine: Sine) -> Result<Motion, MotionError> {
        Ok(Motion::Sine(sine.checked()?))
    }

    /// A rectangular pulse, checked.
    pub fn pulse(pulse: Pulse) -> Result<Motion, MotionError> {
        Ok(Motion::Pulse(pulse.checked()?))
    }

    /// Natural length of the motion (s): the sine's duration or the record's last sample.
    pub fn duration_s(&self) -> f64 {
        match self {
            Motion::Sine(s) => s.duration_s,
            Motion::Record(r) => r.duration_s(),
            Motion::Pulse(p) => p.duration_s,
        }
    }

    /// True when a vertical component scales the normal loads.
    pub fn has_vertical(&self) -> bool {
        matches!(self, Motion::Record(r) if r.lambda.is_some())
    }

    /// Peak absolute ground acceleration (m/s2).
    pub fn peak_accel_m_s2(&self) -> f64 {
        match self {
            Motion::Sine(s) => s.amplitude_m_s2.abs(),
            Motion::Record(r) => r.pga_m_s2(),
            Motion::Pulse(p) => p.amplitude_m_s2.abs(),
        }
    }

    /// Smallest and largest ground acceleration over [t0, t1] (m/s2).
    pub fn accel_range(&self, t0: f64, t1: f64) -> (f64, f64) {
        let (mut lo, mut hi) = {
            let (a, b) = (self.accel(t0), self.accel(t1));
            (a.min(b), a.max(b))
        };
        // Extremes inside lie on segment boundaries: sample peaks, sine crests.
        match self {
            Motion::Record(r) => {
                // The samples themselves (zero past the last), read in place: a cluster stuck
                // through a long record asks for its peak once, over all of it.
                let n = r.accel_m_s2.len();
                for j in record_index(r, t0) + 1..=n {
                    if j as f64 * r.dt_s >= t1 {
                        break;
                    }
                    let a = r.accel_m_s2.get(j).copied().unwrap_or(0.0);
                    lo = lo.min(a);
                    hi = hi.max(a);
                }
            }
            Motion::Sine(s) => {
                // The crests between arcs, and the end of the sine (0 after it).
                let mut end = sine_arc(s, t0).map_or(f64::INFINITY, |(_, t)| t);
                while end < t1 {
                    let a = sine_accel(s, end);
                    lo = lo.min(a);
                    hi = hi.max(a);
                    end = sine_arc(s, end).map_or(f64::INFINITY, |(_, t)| t);
                }
            }
            // Constant, then zero: the ends hold both.
            Motion::Pulse(_) => {}
        }
        (lo, hi)
    }

    /// Short description for summaries.
    pub fn describe(&self) -> String {
        match self {
            Motion::Sine(s) => format!(
                "sine {} m/s2 ({:.1} gal), {} Hz, phase {} deg, {} s",
                s.amplitude_m_s2,
                s.amplitude_m_s2 * 100.0,
                s.frequency_hz,
                // To 1e-9 degree: the phase was given in degrees and is kept in radians, and
                // the way back shows rounding noise (29.999999999999996 for 30).
                (s.phase_rad.to_degrees() * 1e9).round() / 1e9,
                s.duration_s
            ),
            Motion::Record(r) => format!(
                "record {} ({} samples at {} s, PGA {:.4} m/s2)",
                r.name,
                r.accel_m_s2.len(),
                r.dt_s,
                r.pga_m_s2()
            ),
            Motion::Pulse(p) if p.amplitude_m_s2 == 0.0 => "ground at rest".into(),
            Motion::Pulse(p) => format!(
                "rectangular pulse {} m/s2 ({:.1} gal) for {} s",
                p.amplitude_m_s2,
                p.amplitude_m_s2 * 100.0,
                p.duration_s
            ),
        }
    }

    /// Ground acceleration at time t (m/s2).
    pub fn accel(&self, t: f64) -> f64 {
        match self {
            Motion::Sine(s) => sine_accel(s, t),
            Motion::Pulse(p) => {
                if t < p.duration_s {
                    p.amplitude_m_s2
                } else {
                    0.0
                }
            }
            Motion::Record(_) => {
                let s = self.segment_at(t);
                s.accel(t - s.t0)
            }
        }
    }

    /// The segment containing time t (the later one at a boundary); t >= 0.
    pub fn segment_at(&self, t: f64) -> Segment {
        match self {
            Motion::Sine(s) => sine_segment(s, t),
            Motion::Record(r) => record_segment(r, t),
            Motion::Pulse(p) => pulse_segment(p, t),
        }
    }

    /// Ground velocity at t (m/s), from rest at t = 0.
    pub fn velocity(&self, t: f64) -> f64 {
        self.velocity_displacement(t).0
    }

    /// Ground displacement at t (m), from rest at t = 0.
    pub fn displacement(&self, t: f64) -> f64 {
        self.velocity_displacement(t).1
    }

    /// Ground velocity (m/s) and displacement (m) at t, from rest at t = 0, from one lookup of
    /// the segment holding t (a record's is a search of its samples).
    pub fn velocity_displacement(&self, t: f64) -> (f64, f64) {
        let s = self.segment_at(t);
        let x = t - s.t0;
        (s.v0 + s.dv(x), s.d0 + s.v0 * x + s.dd(x))
    }
}

fn sine_segment(s: &Sine, t: f64) -> Segment {
    let Some((t0, t1)) = sine_arc(s, t) else {
        let (v_end, d_end) = sine_state(s, s.duration_s);
        return Segment {
            t0: s.duration_s,
            t1: f64::INFINITY,
            v0: v_end,
            d0: d_end,
            lambda: (1.0, 0.0),
            shape: Shape::Linear {
                a0: 0.0,
                slope: 0.0,
            },
        };
    };
    let (v0, d0) = sine_state(s, t0);
    Segment {
        t0,
        t1,
        v0,
        d0,
        lambda: (1.0, 0.0),
        shape: sine_shape(s, t0),
    }
}

/// The arc [t0, t1) of a sine holding t (the later one at a boundary): a_g is monotone
/// between the instants where the phase w t + phi passes pi/2 + k pi. `None` from the end of
/// the sine on.
fn sine_arc(s: &Sine, t: f64) -> Option<(f64, f64)> {
    if t >= s.duration_s {
        return None;
    }
    let (w, phi) = (s.omega(), s.phase_rad);
    let k = ((w * t + phi - std::f64::consts::FRAC_PI_2) / std::f64::consts::PI).floor();
    let boundary = |k: f64| (std::f64::consts::FRAC_PI_2 + k * std::f64::consts::PI - phi) / w;
    let mut t0 = boundary(k).max(0.0);
    let mut t1 = boundary(k + 1.0).min(s.duration_s);
    // Guard against round-off placing t just outside [t0, t1).
    if t < t0 {
        t1 = t0;
        t0 = boundary(k - 1.0).max(0.0);
    } else if t >= t1 && t1 < s.duration_s {
        t0 = t1;
        t1 = boundary(k + 2.0).min(s.duration_s);
    }
    Some((t0, t1))
}

/// a_g on the sine's arc that starts at t0.
fn sine_shape(s: &Sine, t0: f64) -> Shape {
    let w = s.omega();
    Shape::sine(s.amplitude_m_s2, w, w * t0 + s.phase_rad)
}

/// a_g of a sine at t, bit for bit what its segment at t gives, without the segment's
/// velocity and displacement.
fn sine_accel(s: &Sine, t: f64) -> f64 {
    match sine_arc(s, t) {
        Some((t0, _)) => sine_shape(s, t0).accel(t - t0),
        None => 0.0,
    }
}

/// Ground velocity and displacement of a sine at t <= duration, from rest at 0.
fn sine_state(s: &Sine, t: f64) -> (f64, f64) {
    let seg = Segment {
        t0: 0.0,
        t1: s.duration_s,
        v0: 0.0,
        d0: 0.0,
        lambda: (1.0, 0.0),
        shape: Shape::sine(s.amplitude_m_s2, s.omega(), s.phase_rad),
    };
    (seg.dv(t), seg.dd(t))
}

fn pulse_segment(p: &Pulse, t: f64) -> Segment {
    let (a, d) = (p.amplitude_m_s2, p.duration_s);
    let flat = |a0: f64| Shape::Linear { a0, slope: 0.0 };
    if t < d {
        Segment {
            t0: 0.0,
            t1: d,
            v0: 0.0,
            d0: 0.0,
            lambda: (1.0, 0.0),
            shape: flat(a),
        }
    } else {
        Segment {
            t0: d,
            t1: f64::INFINITY,
            v0: a * d,
            d0: 0.5 * a * d * d,
            lambda: (1.0, 0.0),
            shape: flat(0.0),
        }
    }
}

/// The sample interval [k dt, (k + 1) dt) holding t; n (the record's length) past its end.
fn record_index(r: &Record, t: f64) -> usize {
    let n = r.accel_m_s2.len();
    // A float-to-integer cast rounds towards zero and takes negatives and NaN to 0: the floor's
    // index for every t, without the call to floor (a library function on this target).
    let k = ((t / r.dt_s) as usize).min(n);
    // Round-off in t / dt can land one step off; correct it.
    if k > 0 && t < k as f64 * r.dt_s {
        k - 1
    } else if k < n && t >= (k + 1) as f64 * r.dt_s {
        k + 1
    } else {
        k
    }
}

fn record_segment(r: &Record, t: f64) -> Segment {
    let n = r.accel_m_s2.len();
    let k = record_index(r, t);
    if k >= n {
        let t0 = n as f64 * r.dt_s;
        return Segment {
            t0,
            t1: f64::INFINITY,
            v0: r.velocity[n],
            d0: r.displacement[n],
            lambda: (1.0, 0.0),
            shape: Shape::Linear {
                a0: 0.0,
                slope: 0.0,
            },
        };
    }
    let a0 = r.accel_m_s2[k];
    let a1 = r.accel_m_s2.get(k + 1).copied().unwrap_or(0.0);
    let lambda = match &r.lambda {
        Some(l) => {
            let (l0, l1) = (l[k], l.get(k + 1).copied().unwrap_or(1.0));
            (l0, (l1 - l0) / r.dt_s)
        }
        None => (1.0, 0.0),
    };
    Segment {
        t0: k as f64 * r.dt_s,
        t1: (k + 1) as f64 * r.dt_s,
        v0: r.velocity[k],
        d0: r.displacement[k],
        lambda,
        shape: Shape::Linear {
            a0,
            slope: (a1 - a0) / r.dt_s,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn sine_integrals_are_closed_form() {
        let s = Sine {
            amplitude_m_s2: 4.0,
            frequency_hz: 1.3,
            phase_rad: 0.7,
            duration_s: 10.0,
        }
        .checked()
        .unwrap();
        let m = Motion::Sine(s.clone());
        let w = s.omega();
        for &t in &[0.0, 0.01, 0.3, 1.234, 5.0, 9.99] {
            let v = 4.0 / w * (0.7f64.cos() - (w * t + 0.7).cos());
            let d =
                4.0 / w * 0.7f64.cos() * t - 4.0 / (w * w) * ((w * t + 0.7).sin() - 0.7f64.sin());
            assert_relative_eq!(m.accel(t), 4.0 * (w * t + 0.7).sin(), epsilon = 1e-12);
            assert_relative_eq!(m.velocity(t), v, epsilon = 1e-12);
            assert_relative_eq!(m.displacement(t), d, epsilon = 1e-12);
            let seg = m.segment_at(t);
            assert!(
                seg.t0 <= t && t < seg.t1,
                "{t} not in [{}, {})",
                seg.t0,
                seg.t1
            );
        }
    }

    #[test]
    fn sine_segments_are_monotone_arcs() {
        let m = Motion::sine(Sine {
            amplitude_m_s2: 1.0,
            frequency_hz: 2.0,
            phase_rad: 0.0,
            duration_s: 3.0,
        })
        .unwrap();
        let mut t = 0.0;
        let mut count = 0;
        while t < 3.0 {
            let seg = m.segment_at(t);
            let (a0, a1) = (seg.accel(0.0), seg.accel(seg.t1 - seg.t0));
            let mid = seg.accel((seg.t1 - seg.t0) / 2.0);
            assert!((a0 <= mid && mid <= a1) || (a0 >= mid && mid >= a1));
            t = seg.t1;
            count += 1;
        }
        assert_eq!(count, 13); // 0..0.125, then every 0.25 s, then the tail to 3.0
    }

    #[test]
    fn record_integrals_are_exact_for_linear_pieces() {
        let r = Record::new("ramp", 0.5, vec![0.0, 1.0, -1.0]).unwrap();
        let m = Motion::Record(r);
        // a = 2t on [0, .5]: v = t^2, d = t^3/3.
        assert_relative_eq!(m.velocity(0.25), 0.0625, epsilon = 1e-15);
        assert_relative_eq!(m.displacement(0.5), 0.125 / 3.0, epsilon = 1e-15);
        // After the last sample the acceleration returns to zero over one step.
        assert_relative_eq!(m.accel(1.25), -0.5, epsilon = 1e-15);
        assert_eq!(m.accel(2.0), 0.0);
        assert!(Record::new("x", 0.0, vec![1.0, 2.0]).is_err());
        assert!(Record::new("x", 0.1, vec![1.0, f64::NAN]).is_err());
    }

    #[test]
    fn acceleration_range_of_a_record_is_its_extreme_samples() {
        // dt = 0.01 s: sample times are not exact in binary, so intervals that start or end
        // on a sample, just before or just after it, all occur.
        let a: Vec<f64> = (0..200)
            .map(|k| ((k * 37 % 101) as f64 - 50.0) / 7.0)
            .collect();
        let m = Motion::Record(Record::new("zigzag", 0.01, a).unwrap());
        let ends: Vec<f64> = (0..=205)
            .flat_map(|k| {
                let t = k as f64 * 0.01;
                [t.next_down(), t, t.next_up(), t + 0.004]
            })
            .filter(|&t| t >= 0.0)
            .collect();
        for (i, &t0) in ends.iter().enumerate().step_by(7) {
            for &t1 in ends[i..].iter().step_by(5) {
                assert_eq!(m.accel_range(t0, t1), range_by_segments(&m, t0, t1));
            }
        }
    }

    /// The extremes of a_g over [t0, t1] by definition: a_g is monotone on a segment, so they
    /// are among the ends and the starts of the segments inside, each read through its segment.
    fn range_by_segments(m: &Motion, t0: f64, t1: f64) -> (f64, f64) {
        let at = |t: f64| {
            let seg = m.segment_at(t);
            seg.accel(t - seg.t0)
        };
        let (a0, a1) = (at(t0), at(t1));
        let mut want = (a0.min(a1), a0.max(a1));
        let mut seg = m.segment_at(t0);
        while seg.t1 < t1 {
            seg = m.segment_at(seg.t1);
            let x = seg.accel(0.0);
            want = (want.0.min(x), want.1.max(x));
        }
        want
    }

    #[test]
    fn a_pulse_is_constant_then_zero_with_exact_integrals() {
        let m = Motion::Pulse(
            Pulse {
                amplitude_m_s2: -3.0,
                duration_s: 0.5,
            }
            .checked()
            .unwrap(),
        );
        assert_eq!(m.accel(0.49), -3.0);
        assert_eq!(m.accel(0.5), 0.0);
        assert_relative_eq!(m.velocity(0.25), -0.75, epsilon = 1e-15);
        assert_relative_eq!(m.displacement(2.0), -0.375 - 1.5 * 1.5, epsilon = 1e-15);
        assert_eq!(m.accel_range(0.1, 0.7), (-3.0, 0.0));
        assert!(
            Pulse {
                amplitude_m_s2: 1.0,
                duration_s: 0.0
            }
            .checked()
            .is_err()
                && Pulse {
                    amplitude_m_s2: f64::NAN,
                    duration_s: 1.0
                }
                .checked()
                .is_err()
        );
        let rest = Motion::Pulse(Pulse::rest());
        assert_eq!(
            (rest.accel(0.0), rest.describe().as_str()),
            (0.0, "ground at rest")
        );
    }

    #[test]
    fn a_sine_is_described_with_the_phase_in_degrees_as_given() {
        for (deg, shown) in [
            (30.0, "phase 30 deg"),
            (135.0, "phase 135 deg"),
            (0.1, "phase 0.1 deg"),
        ] {
            let m = Motion::sine(Sine {
                amplitude_m_s2: 4.0,
                frequency_hz: 1.0,
                phase_rad: f64::to_radians(deg),
                duration_s: 20.0,
            })
            .unwrap();
            assert!(m.describe().contains(shown), "{}", m.describe());
        }
    }

    #[test]
    fn a_sine_is_read_as_its_segments_and_peaks_at_its_crests() {
        // Crests at t = (pi/2 + k pi - 0.7) / (2 pi 1.3); the sine ends between two of them.
        let m = Motion::sine(Sine {
            amplitude_m_s2: 4.0,
            frequency_hz: 1.3,
            phase_rad: 0.7,
            duration_s: 4.9,
        })
        .unwrap();
        let w = 2.0 * std::f64::consts::PI * 1.3;
        let times: Vec<f64> = (0..14)
            .map(|k| (std::f64::consts::FRAC_PI_2 + k as f64 * std::f64::consts::PI - 0.7) / w)
            .chain([0.0, 4.9, 0.123, 2.5, 5.5])
            .filter(|&t| t >= 0.0)
            .flat_map(|t| [t.next_down(), t, t.next_up(), t + 0.05])
            .filter(|&t| t >= 0.0)
            .collect();
        for &t in &times {
            let seg = m.segment_at(t);
            assert_eq!(m.accel(t).to_bits(), seg.accel(t - seg.t0).to_bits(), "{t}");
        }
        for (i, &t0) in times.iter().enumerate() {
            for &t1 in times[i..].iter().filter(|&&t1| t1 >= t0) {
                let (lo, hi) = m.accel_range(t0, t1);
                assert_eq!((lo, hi), range_by_segments(&m, t0, t1), "[{t0}, {t1}]");
                for k in 0..=50 {
                    let a = m.accel(t0 + (t1 - t0) * k as f64 / 50.0);
                    assert!(lo <= a && a <= hi, "[{t0}, {t1}]: {a} outside [{lo}, {hi}]");
                }
            }
        }
        // Over a whole cycle the range is the amplitude, to round-off.
        let (lo, hi) = m.accel_range(0.0, 1.0);
        assert!(
            (lo + 4.0).abs() < 1e-14 && (hi - 4.0).abs() < 1e-14,
            "{lo} {hi}"
        );
    }

    #[test]
    fn a_record_time_is_in_the_sample_interval_that_holds_it() {
        // The index is the floor of t / dt, corrected where that quotient rounds across a
        // sample: the segment holding t starts at or before it and ends after it, at every
        // sample time, a float either side of it and between samples; before the record it
        // is the first, from its end on the last.
        let dt = 0.01;
        let r = Record::new("r", dt, (0..400).map(|k| (k as f64 * 0.37).sin()).collect()).unwrap();
        let n = r.accel_m_s2.len();
        for k in 0..n {
            let t = k as f64 * dt;
            for x in [t.next_down(), t, t.next_up(), t + 0.3 * dt, t + 0.999 * dt] {
                let i = record_index(&r, x);
                if x < 0.0 {
                    assert_eq!(i, 0, "{x}");
                    continue;
                }
                assert!(i <= n, "{x}");
                if i < n {
                    assert!(i as f64 * dt <= x && x < (i + 1) as f64 * dt, "{x}: {i}");
                } else {
                    assert!(x >= n as f64 * dt, "{x}: {i}");
                }
            }
        }
        for x in [-1.0, -1e-300, -0.0, f64::NAN] {
            assert_eq!(record_index(&r, x), 0, "{x}");
        }
        assert_eq!(record_index(&r, 1e300), n);
    }
}
