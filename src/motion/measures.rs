//! A record at a glance: peak values, Arias intensity, significant duration, mean period
//! (Rathje et al. 1998), predominant period (peak of the 5 %-damped response spectrum), and the
//! Fourier amplitude spectrum.

use super::Record;
use serde::Serialize;

/// Intensity measures of a record, with units in the names.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Measures {
    /// Peak ground acceleration (m/s2).
    pub pga_m_s2: f64,
    /// Peak ground velocity (m/s), from the exact integral of the piecewise-linear record.
    pub pgv_m_s: f64,
    /// Peak ground displacement (m), likewise (no filtering: reflects the baseline).
    pub pgd_m: f64,
    /// Arias intensity pi/(2g) integral a^2 dt (m/s).
    pub arias_m_s: f64,
    /// Significant duration: time between 5 % and 95 % of the Arias intensity (s).
    pub d5_95_s: f64,
    /// Mean period (Rathje et al. 1998): sum(C^2/f)/sum(C^2) over 0.25-20 Hz (s).
    pub tm_s: f64,
    /// Period of the peak 5 %-damped pseudo-spectral acceleration (s).
    pub predominant_period_s: f64,
    /// Number of samples.
    pub npts: usize,
    /// Sample interval (s).
    pub dt_s: f64,
}

/// In-place radix-2 FFT of (re, im); the length must be a power of two.
fn fft(re: &mut [f64], im: &mut [f64]) {
    let n = re.len();
    let mut j = 0;
    for i in 1..n {
        let mut bit = n >> 1;
        while j & bit != 0 {
            j ^= bit;
            bit >>= 1;
        }
        j |= bit;
        if i < j {
            re.swap(i, j);
            im.swap(i, j);
        }
    }
    let mut len = 2;
    while len <= n {
        let angle = -2.0 * std::f64::consts::PI / len as f64;
        for start in (0..n).step_by(len) {
            for k in 0..len / 2 {
                let (s, c) = (angle * k as f64).sin_cos();
                let (a, b) = (start + k, start + k + len / 2);
                let (xr, xi) = (re[b] * c - im[b] * s, re[b] * s + im[b] * c);
                re[b] = re[a] - xr;
                im[b] = im[a] - xi;
                re[a] += xr;
                im[a] += xi;
            }
        }
        len <<= 1;
    }
}

/// Fourier amplitude spectrum |A(f)| dt (m/s) at frequencies k / (N dt), zero-padded to a power
/// of two, up to Nyquist.
pub fn fourier_amplitude(r: &Record) -> Vec<(f64, f64)> {
    let n = r.accel_m_s2.len().next_power_of_two();
    let mut re = vec![0.0; n];
    let mut im = vec![0.0; n];
    re[..r.accel_m_s2.len()].copy_from_slice(&r.accel_m_s2);
    fft(&mut re, &mut im);
    (1..=n / 2)
        .map(|k| {
            (
                k as f64 / (n as f64 * r.dt_s),
                (re[k] * re[k] + im[k] * im[k]).sqrt() * r.dt_s,
            )
        })
        .collect()
}

/// Peak |pseudo-spectral acceleration| (m/s2) of a damped oscillator of period `period_s`,
/// integrated exactly for piecewise-linear input (Nigam and Jennings 1969).
pub fn pseudo_acceleration(r: &Record, period_s: f64, damping: f64) -> f64 {
    let w = 2.0 * std::f64::consts::PI / period_s;
    let wd = w * (1.0 - damping * damping).sqrt();
    let dt = r.dt_s;
    let e = (-damping * w * dt).exp();
    let (s, c) = (wd * dt).sin_cos();
    let zr = damping / (1.0 - damping * damping).sqrt();
    let a11 = e * (zr * s + c);
    let a12 = e * s / wd;
    let a21 = -w / (1.0 - damping * damping).sqrt() * e * s;
    let a22 = e * (c - zr * s);
    let t1 = (2.0 * damping * damping - 1.0) / (w * w * dt);
    let t2 = 2.0 * damping / (w * w * w * dt);
    let b11 = e * (((t1 + damping / w) * s / wd) + (t2 + 1.0 / (w * w)) * c) - t2;
    let b12 = -e * ((t1 * s / wd) + t2 * c) - 1.0 / (w * w) + t2;
    let b21 = e
        * ((t1 + damping / w) * (c - zr * s) - (t2 + 1.0 / (w * w)) * (wd * s + damping * w * c))
        + 1.0 / (w * w * dt);
    let b22 = -e * (t1 * (c - zr * s) - t2 * (wd * s + damping * w * c)) - 1.0 / (w * w * dt);
    let (mut x, mut v) = (0.0f64, 0.0f64);
    let mut peak: f64 = 0.0;
    let a = &r.accel_m_s2;
    for k in 0..a.len() - 1 {
        // Relative motion under -a_g.
        let (p0, p1) = (-a[k], -a[k + 1]);
        let xn = a11 * x + a12 * v + b11 * p0 + b12 * p1;
        let vn = a21 * x + a22 * v + b21 * p0 + b22 * p1;
        x = xn;
        v = vn;
        peak = peak.max(x.abs());
    }
    peak * w * w
}

impl Measures {
    /// Measures of a record.
    pub fn of(r: &Record) -> Measures {
        let motion = super::Motion::Record(r.clone());
        let dt = r.dt_s;
        let n = r.accel_m_s2.len();
        let (mut pgv, mut pgd) = (0.0f64, 0.0f64);
        for k in 0..n {
            let t = k as f64 * dt;
            pgv = pgv.max(motion.velocity(t).abs());
            pgd = pgd.max(motion.displacement(t).abs());
        }
        // Cumulative Arias: exact integral of the square of each linear piece.
        let a = &r.accel_m_s2;
        let mut cumulative = vec![0.0; n];
        for k in 1..n {
            let (x, y) = (a[k - 1], a[k]);
            cumulative[k] = cumulative[k - 1] + dt * (x * x + x * y + y * y) / 3.0;
        }
        let total = cumulative[n - 1];
        let arias = std::f64::consts::PI / (2.0 * crate::units::G_UNIT_M_S2) * total;
        let time_at = |fraction: f64| -> f64 {
            let target = fraction * total;
            let k = cumulative.partition_point(|&c| c < target).clamp(1, n - 1);
            let (c0, c1) = (cumulative[k - 1], cumulative[k]);
            let f = if c1 > c0 {
                (target - c0) / (c1 - c0)
            } else {
                0.0
            };
            (k as f64 - 1.0 + f) * dt
        };
        let d5_95 = if total > 0.0 {
            time_at(0.95) - time_at(0.05)
        } else {
            0.0
        };
        let fas = fourier_amplitude(r);
        let (mut num, mut den) = (0.0, 0.0);
        for &(f, c) in &fas {
            if (0.25..=20.0).contains(&f) {
                num += c * c / f;
                den += c * c;
            }
        }
        let tm = if den > 0.0 { num / den } else { 0.0 };
        let periods = spectrum_periods();
        let predominant = periods
            .iter()
            .map(|&p| (p, pseudo_acceleration(r, p, 0.05)))
            .fold(
                (0.0, -1.0),
                |best, (p, sa)| if sa > best.1 { (p, sa) } else { best },
            )
            .0;
        Measures {
            pga_m_s2: r.pga_m_s2(),
            pgv_m_s: pgv,
            pgd_m: pgd,
            arias_m_s: arias,
            d5_95_s: d5_95,
            tm_s: tm,
            predominant_period_s: predominant,
            npts: n,
            dt_s: dt,
        }
    }
}

/// Periods at which response spectra are evaluated: 100 log-spaced from 0.05 to 5 s.
pub fn spectrum_periods() -> Vec<f64> {
    (0..100)
        .map(|k| 0.05 * 100f64.powf(k as f64 / 99.0))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sine_record(amp: f64, f: f64, seconds: f64, dt: f64) -> Record {
        let n = (seconds / dt).round() as usize + 1;
        let w = 2.0 * std::f64::consts::PI * f;
        Record::new(
            "sine",
            dt,
            (0..n).map(|k| amp * (w * k as f64 * dt).sin()).collect(),
        )
        .unwrap()
    }

    #[test]
    fn measures_of_a_sine() {
        let r = sine_record(2.0, 2.0, 10.0, 0.001);
        let m = Measures::of(&r);
        assert!((m.pga_m_s2 - 2.0).abs() < 1e-9);
        // Arias of A sin over T: pi/(2g) A^2 T / 2.
        let expect = std::f64::consts::PI / (2.0 * 9.81) * 4.0 * 10.0 / 2.0;
        assert!((m.arias_m_s - expect).abs() < 1e-3 * expect);
        // A steady sine: 90 % of its energy in 90 % of its length.
        assert!((m.d5_95_s - 9.0).abs() < 0.01, "{}", m.d5_95_s);
        assert!((m.tm_s - 0.5).abs() < 0.02, "Tm {}", m.tm_s);
        assert!(
            (m.predominant_period_s - 0.5).abs() < 0.03,
            "Tp {}",
            m.predominant_period_s
        );
        // PGV of A sin(w t) from rest: 2A/w, up to the sampled sine's piecewise-linear error,
        // (w dt)^2 / 12 relative.
        let expect = 2.0 * 2.0 / (4.0 * std::f64::consts::PI);
        let tol = (4.0 * std::f64::consts::PI * 0.001f64).powi(2) / 12.0;
        assert!(
            (m.pgv_m_s - expect).abs() < 1.5 * tol * expect,
            "{} vs {expect}",
            m.pgv_m_s
        );
    }

    #[test]
    fn resonant_oscillator_amplification() {
        // A 5 %-damped oscillator at resonance with a long sine: PSA -> A / (2 zeta) = 10 A.
        let r = sine_record(1.0, 1.0, 60.0, 0.002);
        let sa = pseudo_acceleration(&r, 1.0, 0.05);
        assert!((sa - 10.0).abs() < 0.2, "{sa}");
        // Far above resonance (stiff): PSA -> PGA.
        let sa = pseudo_acceleration(&r, 0.02, 0.05);
        assert!((sa - 1.0).abs() < 0.02, "{sa}");
    }
}
