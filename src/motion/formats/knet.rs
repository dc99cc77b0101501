//! K-NET and KiK-net ASCII (NIED): 17 header lines, each a label in columns 1-18 and a value
//! from column 19, then integer counts. Acceleration in gal = count x scale factor
//! (`3920(gal)/6182761`), with the record mean removed as NIED prescribes.

use super::numbers::free_format;
use super::{ReadOptions, RecordFormat};
use crate::error::MotionError;
use crate::motion::Record;

/// The K-NET / KiK-net ASCII format.
pub struct Knet;

const LABELS: [&str; 17] = [
    "Origin Time",
    "Lat.",
    "Long.",
    "Depth. (km)",
    "Mag.",
    "Station Code",
    "Station Lat.",
    "Station Long.",
    "Station Height(m)",
    "Record Time",
    "Sampling Freq(Hz)",
    "Duration Time(s)",
    "Dir.",
    "Scale Factor",
    "Max. Acc. (gal)",
    "Last Correction",
    "Memo.",
];

fn line_err(line: usize, message: impl Into<String>) -> MotionError {
    MotionError::Line {
        line,
        message: message.into(),
    }
}

fn value_of(line: &str) -> &str {
    line.get(18..).unwrap_or("").trim()
}

impl RecordFormat for Knet {
    fn name(&self) -> &'static str {
        "knet"
    }

    fn detect(&self, text: &str) -> bool {
        text.lines()
            .next()
            .is_some_and(|l| l.starts_with("Origin Time"))
    }

    fn read(&self, name: &str, text: &str, _opts: &ReadOptions) -> Result<Record, MotionError> {
        let lines: Vec<&str> = text.lines().collect();
        for (k, label) in LABELS.iter().enumerate() {
            let line = lines.get(k).copied().unwrap_or("");
            if !line.trim_start().starts_with(label) {
                return Err(line_err(
                    k + 1,
                    format!(
                        "expected the K-NET header field `{label}` in columns 1-18, found \"{}\"",
                        line.trim()
                    ),
                ));
            }
        }
        let freq_text = value_of(lines[10]);
        let freq: f64 = freq_text
            .trim_end_matches(|c: char| c.is_ascii_alphabetic())
            .trim()
            .parse()
            .map_err(|_| line_err(11, format!("sampling frequency \"{freq_text}\": expected a number of Hz such as `100Hz`")))?;
        if !(freq.is_finite() && freq > 0.0) {
            return Err(line_err(
                11,
                format!("sampling frequency {freq} Hz: it must be positive and finite"),
            ));
        }
        let scale_text = value_of(lines[13]);
        let factor = scale_text
            .split_once('/')
            .and_then(|(num, den)| {
                let num: f64 = num.split('(').next()?.trim().parse().ok()?;
                let den: f64 = den.trim().parse().ok()?;
                (num.is_finite() && den.is_finite() && den != 0.0).then_some(num / den)
            })
            .ok_or_else(|| {
                line_err(
                    14,
                    format!("scale factor \"{scale_text}\": expected the form `3920(gal)/6182761`"),
                )
            })?;
        let mut counts = Vec::new();
        for (k, line) in lines.iter().enumerate().skip(17) {
            let v = free_format(line)
                .map_err(|e| line_err(k + 1, format!("{e}: expected integer counts")))?;
            if let Some(x) = v.iter().find(|x| x.fract() != 0.0) {
                return Err(line_err(k + 1, format!("{x} is not an integer count")));
            }
            counts.extend(v);
        }
        if counts.len() < 2 {
            return Err(MotionError::TooFewSamples {
                found: counts.len(),
                counted: "data values after the 17 header lines",
            });
        }
        let gal: Vec<f64> = counts.iter().map(|c| c * factor).collect();
        let mean = gal.iter().sum::<f64>() / gal.len() as f64;
        let component = value_of(lines[12]);
        let label = if component.is_empty() {
            name.to_string()
        } else {
            format!("{name} ({component})")
        };
        Record::new(
            label,
            1.0 / freq,
            gal.iter().map(|a| (a - mean) * 0.01).collect(),
        )
    }
}
