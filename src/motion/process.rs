//! Preparing a record for a run: a time window, baseline correction, scaling to a target peak
//! and by a factor. Every step is logged in words for the summary.

use super::Record;
use crate::error::MotionError;

/// Baseline correction.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Baseline {
    /// Leave the record as it is.
    #[default]
    None,
    /// Subtract the mean acceleration.
    Mean,
    /// Subtract the least-squares straight line through the accelerations.
    Linear,
}

/// The processing asked for, applied in this order: window, baseline, peak, scale.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Processing {
    /// Keep samples from this time (s).
    pub start_s: Option<f64>,
    /// Keep samples up to this time (s).
    pub end_s: Option<f64>,
    /// Baseline correction.
    pub baseline: Baseline,
    /// Scale to this peak absolute acceleration (m/s2).
    pub pga_m_s2: Option<f64>,
    /// Then multiply by this factor.
    pub scale: Option<f64>,
}

impl Record {
    /// The samples between `start` and `end` (s), re-timed to start at 0.
    pub fn window(&self, start: f64, end: f64) -> Result<Record, MotionError> {
        let n = self.accel_m_s2.len();
        let last = self.duration_s();
        if !(start.is_finite() && end.is_finite() && start >= 0.0 && end > start && start < last) {
            return Err(MotionError::Parameter {
                what: format!("window {start}..{end} s"),
                rule: format!("it is not inside the record (0..{last} s)"),
            });
        }
        let i0 = (start / self.dt_s).round() as usize;
        let i1 = ((end / self.dt_s).round() as usize).min(n - 1);
        Record::new(
            self.name.clone(),
            self.dt_s,
            self.accel_m_s2[i0..=i1].to_vec(),
        )
    }

    /// The record with its mean, or its least-squares line, removed; and what was removed.
    pub fn baseline_corrected(&self, mode: Baseline) -> (Record, Option<String>) {
        let a = &self.accel_m_s2;
        let n = a.len() as f64;
        let mean = a.iter().sum::<f64>() / n;
        let (fixed, note): (Vec<f64>, Option<String>) = match mode {
            Baseline::None => return (self.clone(), None),
            Baseline::Mean => (
                a.iter().map(|x| x - mean).collect(),
                Some(format!("baseline: mean {mean:.6e} m/s2 removed")),
            ),
            Baseline::Linear => {
                let tm = (n - 1.0) / 2.0;
                let (mut sxy, mut sxx) = (0.0, 0.0);
                for (i, x) in a.iter().enumerate() {
                    let d = i as f64 - tm;
                    sxy += d * (x - mean);
                    sxx += d * d;
                }
                let slope = if sxx > 0.0 { sxy / sxx } else { 0.0 };
                (
                    a.iter()
                        .enumerate()
                        .map(|(i, x)| x - mean - slope * (i as f64 - tm))
                        .collect(),
                    Some(format!(
                        "baseline: line {mean:.6e} m/s2 + {:.6e} m/s3 (t - t_mid) removed",
                        slope / self.dt_s
                    )),
                )
            }
        };
        (
            Record::new(self.name.clone(), self.dt_s, fixed)
                .expect("a corrected record stays valid"),
            note,
        )
    }
}

/// Applies the processing; returns the record and a log of what was done.
pub fn process(record: &Record, p: &Processing) -> Result<(Record, Vec<String>), MotionError> {
    let mut notes = Vec::new();
    let mut r = record.clone();
    if p.start_s.is_some() || p.end_s.is_some() {
        let (s, e) = (p.start_s.unwrap_or(0.0), p.end_s.unwrap_or(r.duration_s()));
        r = r.window(s, e)?;
        notes.push(format!(
            "window {s}..{e} s of the record, re-timed to start at 0"
        ));
    }
    let (corrected, note) = r.baseline_corrected(p.baseline);
    r = corrected;
    notes.extend(note);
    if let Some(target) = p.pga_m_s2 {
        let peak = r.pga_m_s2();
        if !(target.is_finite() && target > 0.0) || peak == 0.0 {
            return Err(MotionError::Parameter {
                what: format!("peak {target} m/s2"),
                rule: format!("cannot scale a record of peak {peak} m/s2 to it"),
            });
        }
        r = r.scaled(target / peak)?;
        notes.push(format!(
            "scaled to PGA {target} m/s2 (factor {:.6})",
            target / peak
        ));
    }
    if let Some(k) = p.scale {
        check_scale(k)?;
        if k != 1.0 {
            r = r.scaled(k)?;
            notes.push(format!("scaled by {k}"));
        }
    }
    Ok((r, notes))
}

/// A factor a motion may be multiplied by: finite and not zero (zero leaves no motion; a
/// negative factor reverses the motion's direction, which an asymmetric wall feels).
pub fn check_scale(k: f64) -> Result<(), MotionError> {
    if k.is_finite() && k != 0.0 {
        Ok(())
    } else {
        Err(MotionError::Parameter {
            what: format!("scale factor {k}"),
            rule: "it must be a finite number other than 0 (a negative one reverses the motion)"
                .into(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_baseline_and_scaling() {
        let r = Record::new("r", 0.1, vec![1.0, 2.0, 3.0, 4.0, 5.0]).unwrap();
        let w = r.window(0.1, 0.3).unwrap();
        assert_eq!(w.accel_m_s2, vec![2.0, 3.0, 4.0]);
        let (m, note) = r.baseline_corrected(Baseline::Mean);
        assert_eq!(m.accel_m_s2, vec![-2.0, -1.0, 0.0, 1.0, 2.0]);
        assert!(note.unwrap().contains("mean 3"));
        let (l, _) = r.baseline_corrected(Baseline::Linear);
        assert!(l.accel_m_s2.iter().all(|x| x.abs() < 1e-12));
        let p = Processing {
            pga_m_s2: Some(2.58),
            scale: Some(5.0),
            ..Default::default()
        };
        let (s, notes) = process(&r, &p).unwrap();
        assert!((s.pga_m_s2() - 12.9).abs() < 1e-12);
        assert_eq!(notes.len(), 2);
        assert!(r.window(0.5, 0.2).is_err());
        // A factor of zero leaves no motion and is refused; a negative one reverses it.
        for k in [0.0, f64::NAN, f64::INFINITY] {
            let p = Processing {
                scale: Some(k),
                ..Default::default()
            };
            let e = process(&r, &p).unwrap_err().to_string();
            assert!(e.contains(&format!("scale factor {k}")), "{e}");
        }
        let p = Processing {
            scale: Some(-1.0),
            ..Default::default()
        };
        let (reversed, _) = process(&r, &p).unwrap();
        assert_eq!(reversed.accel_m_s2, vec![-1.0, -2.0, -3.0, -4.0, -5.0]);
    }
}
