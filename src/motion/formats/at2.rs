//! PEER NGA `.AT2`: four header lines (the fourth gives the number of points and the step, as
//! `NPTS=  4000, DT= .0100 SEC` or `4164  0.0100  NPTS, DT`), then accelerations in g, several
//! per line, in free format.

use super::numbers::{free_format, free_format_into};
use super::{ReadOptions, RecordFormat};
use crate::error::MotionError;
use crate::motion::Record;
use crate::units::AccelUnit;

/// The PEER NGA AT2 format.
pub struct At2;

fn line_err(line: usize, message: impl Into<String>) -> MotionError {
    MotionError::Line {
        line,
        message: message.into(),
    }
}

/// NPTS and DT from the fourth header line, in either layout.
fn npts_dt(line: &str, n: usize) -> Result<(usize, f64), MotionError> {
    let upper = line.to_ascii_uppercase();
    let expected = "the PEER header `NPTS=  4000, DT= .0100 SEC` (or `4000  0.0100  NPTS, DT`)";
    let after = |key: &str| -> Option<f64> {
        let i = upper.find(key)? + key.len();
        let rest = upper[i..].trim_start_matches([' ', '=']);
        let end = rest
            .find(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == '+' || c == 'E'))
            .unwrap_or(rest.len());
        rest[..end].parse().ok()
    };
    let (npts, dt) = if upper.contains("NPTS=") || upper.contains("NPTS =") {
        let npts = after("NPTS")
            .ok_or_else(|| line_err(n, format!("no number after NPTS: expected {expected}")))?;
        let dt = after("DT")
            .ok_or_else(|| line_err(n, format!("no number after DT: expected {expected}")))?;
        (npts, dt)
    } else if upper.contains("NPTS") {
        let head = &upper[..upper.find("NPTS").expect("checked")];
        let v = free_format(head).map_err(|e| line_err(n, format!("{e}: expected {expected}")))?;
        match v[..] {
            [npts, dt, ..] => (npts, dt),
            _ => return Err(line_err(n, format!("expected {expected}"))),
        }
    } else {
        return Err(line_err(
            n,
            format!("expected {expected}, found \"{}\"", line.trim()),
        ));
    };
    if !(npts >= 2.0 && npts.fract() == 0.0) {
        return Err(line_err(
            n,
            format!("NPTS = {npts}: a record needs a whole number of at least 2 points"),
        ));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(line_err(
            n,
            format!("DT = {dt}: the time step must be positive and finite"),
        ));
    }
    Ok((npts as usize, dt))
}

impl RecordFormat for At2 {
    fn name(&self) -> &'static str {
        "at2"
    }

    fn detect(&self, text: &str) -> bool {
        // The NPTS line, or (for a file cut before it) the PEER title line that opens the
        // format: then the reader says the file is cut short, not that a plain file lacks units.
        let mut lines = text.lines();
        let first = lines.next().unwrap_or_default().to_ascii_uppercase();
        (first.starts_with("PEER") && first.contains("RECORD"))
            || text
                .lines()
                .take(6)
                .any(|l| l.to_ascii_uppercase().contains("NPTS"))
    }

    fn read(&self, name: &str, text: &str, _opts: &ReadOptions) -> Result<Record, MotionError> {
        let lines: Vec<&str> = text.lines().collect();
        if lines.len() < 5 {
            return Err(MotionError::Truncated {
                format: "AT2",
                header: 4,
                lines: lines.len(),
            });
        }
        let header = lines[..3].join(" ").to_ascii_uppercase();
        // The format is defined in g; a header saying otherwise is followed.
        let unit = if header.contains("CM/S") || header.contains("GAL") {
            AccelUnit::Gal
        } else if header.contains("M/S") {
            AccelUnit::Ms2
        } else {
            AccelUnit::G
        };
        let (npts, dt) = npts_dt(lines[3], 4)?;
        // Sized by what the file can hold (a value takes two bytes at least), never by the
        // header's claim: `NPTS= 1e30` must not allocate before one sample is read.
        let mut values = Vec::with_capacity(npts.min(text.len() / 2));
        let mut last_line = 4;
        for (k, line) in lines.iter().enumerate().skip(4) {
            if values.len() >= npts {
                break;
            }
            free_format_into(line, &mut values)
                .map_err(|e| line_err(k + 1, format!("{e}: expected accelerations")))?;
            last_line = k + 1;
        }
        if values.len() < npts {
            return Err(line_err(
                last_line,
                format!(
                    "the data end after {} values; NPTS on line 4 says {npts}",
                    values.len()
                ),
            ));
        }
        values.truncate(npts);
        let scale = unit.to_m_s2();
        Record::new(name, dt, values.into_iter().map(|a| a * scale).collect())
    }
}
