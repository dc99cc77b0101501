//! Synthetic ground motions, sampled into records: sines with a ramp-in and taper, sweeps,
//! pulses, and Kanai-Tajimi filtered white noise under an envelope (a stand-in for records that
//! cannot be redistributed, such as the paper's 1978 Miyagi-ken-oki record).

use super::Record;
use crate::error::MotionError;
use crate::rng::Rng;
use std::f64::consts::PI;

/// A synthetic motion. Accelerations in m/s2, times in s, frequencies in Hz.
#[derive(Debug, Clone, PartialEq)]
pub enum Synthetic {
    /// amplitude sin(2 pi f t + phase), raised over `ramp_s` and lowered over `taper_s` by
    /// half-cosine windows.
    Sine {
        /// Amplitude.
        amplitude: f64,
        /// Frequency.
        frequency: f64,
        /// Phase at t = 0 (rad).
        phase: f64,
        /// Length.
        duration: f64,
        /// Ramp-in length.
        ramp_s: f64,
        /// Taper length.
        taper_s: f64,
    },
    /// A linear sweep from `f0` to `f1` Hz (instantaneous frequency), with ramp and taper.
    Chirp {
        /// Amplitude.
        amplitude: f64,
        /// Start frequency.
        f0: f64,
        /// End frequency.
        f1: f64,
        /// Length.
        duration: f64,
        /// Ramp-in length.
        ramp_s: f64,
        /// Taper length.
        taper_s: f64,
    },
    /// Ricker wavelet amplitude (1 - 2 (pi f tau)^2) exp(-(pi f tau)^2), tau = t - center.
    Ricker {
        /// Peak acceleration.
        amplitude: f64,
        /// Peak frequency.
        frequency: f64,
        /// Time of the peak.
        center: f64,
        /// Length.
        duration: f64,
    },
    /// One cycle of amplitude sin(2 pi f (t - delay)), zero elsewhere.
    SinePulse {
        /// Amplitude.
        amplitude: f64,
        /// Frequency.
        frequency: f64,
        /// Start of the pulse.
        delay: f64,
        /// Length of the record.
        duration: f64,
    },
    /// Kanai-Tajimi: white noise through a ground filter of frequency `fg` and damping
    /// `zeta_g`, under a rise-hold-decay envelope, baseline-corrected, scaled to `pga`.
    KanaiTajimi {
        /// Target peak acceleration.
        pga: f64,
        /// Ground filter frequency.
        fg: f64,
        /// Ground filter damping (0 < zeta_g < 1).
        zeta_g: f64,
        /// Length.
        duration: f64,
        /// Random seed.
        seed: u64,
    },
}

fn window(t: f64, duration: f64, ramp: f64, taper: f64) -> f64 {
    let rise = if ramp > 0.0 && t < ramp {
        0.5 * (1.0 - (PI * t / ramp).cos())
    } else {
        1.0
    };
    let fall = if taper > 0.0 && t > duration - taper {
        0.5 * (1.0 - (PI * (duration - t) / taper).cos())
    } else {
        1.0
    };
    rise * fall
}

/// The envelope of the Kanai-Tajimi motion: quadratic rise over the first 10 %, strong phase to
/// 40 %, exponential decay to 5 % at the end.
fn envelope(t: f64, duration: f64) -> f64 {
    let (t1, t2) = (0.1 * duration, 0.4 * duration);
    if t < t1 {
        (t / t1).powi(2)
    } else if t <= t2 {
        1.0
    } else {
        (20f64.ln() * -(t - t2) / (duration - t2)).exp()
    }
}

fn positive(what: &str, x: f64) -> Result<(), MotionError> {
    if x.is_finite() && x > 0.0 {
        Ok(())
    } else {
        Err(MotionError::Parameter {
            what: format!("{what} = {}", crate::units::Shown(x)),
            rule: "it must be positive and finite".into(),
        })
    }
}

impl Synthetic {
    /// The 1978 Miyagi-ken-oki stand-in used for the paper's Fig. 5 and 6: Kanai-Tajimi with
    /// PGA 258 gal (the Tohoku University N-S record's peak), a 1.5 Hz, 0.4-damped ground
    /// filter (a soft site with long-period content), 40 s, seed 1978. Representative, not a
    /// reproduction.
    pub fn miyagi_like() -> Synthetic {
        Synthetic::KanaiTajimi {
            pga: 2.58,
            fg: 1.5,
            zeta_g: 0.4,
            duration: 40.0,
            seed: 1978,
        }
    }

    /// A short description for file headers and summaries.
    pub fn describe(&self) -> String {
        match self {
            Synthetic::Sine { amplitude, frequency, duration, ramp_s, taper_s, .. } => format!("sine {amplitude} m/s2, {frequency} Hz, {duration} s, ramp {ramp_s} s, taper {taper_s} s"),
            Synthetic::Chirp { amplitude, f0, f1, duration, .. } => format!("sweep {amplitude} m/s2, {f0}-{f1} Hz, {duration} s"),
            Synthetic::Ricker { amplitude, frequency, center, .. } => format!("Ricker pulse {amplitude} m/s2, {frequency} Hz, peak at {center} s"),
            Synthetic::SinePulse { amplitude, frequency, delay, .. } => format!("one-cycle sine pulse {amplitude} m/s2, {frequency} Hz, from {delay} s"),
            Synthetic::KanaiTajimi { pga, fg, zeta_g, duration, seed } => format!("Kanai-Tajimi PGA {pga} m/s2, fg {fg} Hz, zeta_g {zeta_g}, {duration} s, seed {seed}"),
        }
    }

    /// Samples the motion every `dt` seconds.
    pub fn record(&self, dt: f64) -> Result<Record, MotionError> {
        positive("dt", dt)?;
        let samples = |duration: f64| -> Result<Vec<f64>, MotionError> {
            positive("duration", duration)?;
            let n = (duration / dt).round() as usize + 1;
            Ok((0..n).map(|k| k as f64 * dt).collect())
        };
        let values: Vec<f64> = match *self {
            Synthetic::Sine {
                amplitude,
                frequency,
                phase,
                duration,
                ramp_s,
                taper_s,
            } => {
                positive("frequency", frequency)?;
                samples(duration)?
                    .iter()
                    .map(|&t| {
                        amplitude
                            * window(t, duration, ramp_s, taper_s)
                            * (2.0 * PI * frequency * t + phase).sin()
                    })
                    .collect()
            }
            Synthetic::Chirp {
                amplitude,
                f0,
                f1,
                duration,
                ramp_s,
                taper_s,
            } => {
                positive("start frequency", f0)?;
                positive("end frequency", f1)?;
                let rate = (f1 - f0) / duration;
                samples(duration)?
                    .iter()
                    .map(|&t| {
                        amplitude
                            * window(t, duration, ramp_s, taper_s)
                            * (2.0 * PI * (f0 * t + 0.5 * rate * t * t)).sin()
                    })
                    .collect()
            }
            Synthetic::Ricker {
                amplitude,
                frequency,
                center,
                duration,
            } => {
                positive("frequency", frequency)?;
                samples(duration)?
                    .iter()
                    .map(|&t| {
                        let x = (PI * frequency * (t - center)).powi(2);
                        amplitude * (1.0 - 2.0 * x) * (-x).exp()
                    })
                    .collect()
            }
            Synthetic::SinePulse {
                amplitude,
                frequency,
                delay,
                duration,
            } => {
                positive("frequency", frequency)?;
                samples(duration)?
                    .iter()
                    .map(|&t| {
                        let s = t - delay;
                        if (0.0..=1.0 / frequency).contains(&s) {
                            amplitude * (2.0 * PI * frequency * s).sin()
                        } else {
                            0.0
                        }
                    })
                    .collect()
            }
            Synthetic::KanaiTajimi {
                pga,
                fg,
                zeta_g,
                duration,
                seed,
            } => {
                positive("PGA", pga)?;
                positive("ground frequency", fg)?;
                if !(zeta_g > 0.0 && zeta_g < 1.0) {
                    return Err(MotionError::Parameter {
                        what: format!("ground damping {zeta_g}"),
                        rule: "it must lie in (0, 1)".into(),
                    });
                }
                kanai_tajimi(&samples(duration)?, dt, pga, fg, zeta_g, duration, seed)
            }
        };
        Record::new(format!("synthetic: {}", self.describe()), dt, values)
    }
}

/// White noise, constant over each step, through the ground filter x'' + 2 z w x' + w^2 x = -n
/// (solved exactly step by step); the ground acceleration is 2 z w x' + w^2 x. Enveloped,
/// baseline-corrected (linear), scaled to the peak.
fn kanai_tajimi(
    times: &[f64],
    dt: f64,
    pga: f64,
    fg: f64,
    zeta: f64,
    duration: f64,
    seed: u64,
) -> Vec<f64> {
    let w = 2.0 * PI * fg;
    let wd = w * (1.0 - zeta * zeta).sqrt();
    let e = (-zeta * w * dt).exp();
    let (s, c) = (wd * dt).sin_cos();
    // Free-response transition over one step.
    let f11 = e * (c + zeta * w / wd * s);
    let f12 = e * s / wd;
    let f21 = -e * w * w / wd * s;
    let f22 = e * (c - zeta * w / wd * s);
    let mut rng = Rng::new(seed);
    let (mut x, mut v) = (0.0f64, 0.0f64);
    let mut out = Vec::with_capacity(times.len());
    for &t in times {
        out.push(envelope(t, duration) * (2.0 * zeta * w * v + w * w * x));
        let noise = rng.normal();
        // Under a constant load -noise the equilibrium is x* = -noise / w^2.
        let xs = -noise / (w * w);
        let (dx, dv) = (x - xs, v);
        x = xs + f11 * dx + f12 * dv;
        v = f21 * dx + f22 * dv;
    }
    let record = Record::new("kt", dt, out).expect("finite noise");
    let (corrected, _) = record.baseline_corrected(super::Baseline::Linear);
    let peak = corrected.pga_m_s2();
    corrected
        .accel_m_s2
        .iter()
        .map(|a| a * pga / peak)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::measures::Measures;

    #[test]
    fn pulses_and_sweeps_have_the_stated_shape() {
        let r = Synthetic::Ricker {
            amplitude: 3.0,
            frequency: 2.0,
            center: 1.0,
            duration: 2.0,
        }
        .record(0.001)
        .unwrap();
        assert!((r.pga_m_s2() - 3.0).abs() < 1e-12);
        let p = Synthetic::SinePulse {
            amplitude: 2.0,
            frequency: 1.0,
            delay: 0.5,
            duration: 3.0,
        }
        .record(0.001)
        .unwrap();
        assert_eq!(p.accel_m_s2[400], 0.0);
        assert!((p.accel_m_s2[750] - 2.0).abs() < 1e-9);
        let s = Synthetic::Sine {
            amplitude: 1.0,
            frequency: 1.0,
            phase: 0.0,
            duration: 10.0,
            ramp_s: 2.0,
            taper_s: 2.0,
        }
        .record(0.01)
        .unwrap();
        assert!(s.accel_m_s2[25].abs() < 0.5 && (s.accel_m_s2[525] - 1.0).abs() < 1e-9);
        assert_eq!(*s.accel_m_s2.last().unwrap(), 0.0);
    }

    #[test]
    fn kanai_tajimi_is_seeded_scaled_and_centred_on_its_ground_frequency() {
        let m = Synthetic::miyagi_like();
        let a = m.record(0.01).unwrap();
        let b = m.record(0.01).unwrap();
        assert_eq!(a, b, "same seed, same record");
        assert!((a.pga_m_s2() - 2.58).abs() < 1e-12);
        let other = Synthetic::KanaiTajimi {
            pga: 2.58,
            fg: 1.5,
            zeta_g: 0.4,
            duration: 40.0,
            seed: 1979,
        }
        .record(0.01)
        .unwrap();
        assert_ne!(a, other);
        let measures = Measures::of(&a);
        assert!(
            measures.predominant_period_s > 0.3 && measures.predominant_period_s < 1.2,
            "{measures:?}"
        );
        assert!(Synthetic::KanaiTajimi {
            pga: 1.0,
            fg: 1.0,
            zeta_g: 1.5,
            duration: 1.0,
            seed: 1
        }
        .record(0.01)
        .is_err());
    }
}
