//! Plain-text and CSV records: one column of accelerations at a given dt, or two columns of time
//! and acceleration. Units are never guessed: they come from a `# units: gal` header line or the
//! caller.

use super::{ReadOptions, Reads, RecordFormat};
use crate::error::MotionError;
use crate::motion::Record;
use crate::units::AccelUnit;

/// Plain text and CSV.
pub struct Plain;

impl RecordFormat for Plain {
    fn name(&self) -> &'static str {
        "plain"
    }

    fn detect(&self, _text: &str) -> bool {
        true
    }

    fn reads(&self) -> Reads {
        Reads {
            dt_s: true,
            units: true,
            component: true,
        }
    }

    fn read(&self, name: &str, text: &str, opts: &ReadOptions) -> Result<Record, MotionError> {
        read_plain(name, text, opts)
    }
}

/// Relative tolerance on the spacing of a time column: sample times written with a few decimals
/// are equally spaced to about 1e-9 relative, not exactly.
const SPACING_TOL: f64 = 1e-6;

/// Reads a plain-text or CSV record: one column of accelerations (with `dt_s`), or time in the
/// first column and accelerations in the others (`component` picks one, 1-based after time;
/// default the last).
pub fn read_plain(name: &str, text: &str, opts: &ReadOptions) -> Result<Record, MotionError> {
    let (mut units, mut dt) = (opts.units, opts.dt_s);
    // A file that says its units or interval twice is refused, not read by its last line.
    let (mut said_units, mut said_dt) = (false, false);
    let mut rows: Vec<(usize, Vec<f64>)> = Vec::new();
    for (k, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(comment) = line.strip_prefix('#') {
            let comment = comment.trim();
            if let Some((key, value)) = comment.split_once(':') {
                // What the file says and what was given beside it must agree.
                let disagree = |said: String, given: String, option: &str| MotionError::Line {
                    line: k + 1,
                    message: format!(
                        "the file says {said}, but {given} was given ({option}): leave the \
                         option out or correct the file"
                    ),
                };
                match key.trim().to_ascii_lowercase().as_str() {
                    "units" | "unit" => {
                        if std::mem::replace(&mut said_units, true) {
                            return Err(MotionError::Line {
                                line: k + 1,
                                message: "a second `# units:` line: give the units once".into(),
                            });
                        }
                        let said = AccelUnit::parse(value).ok_or_else(|| MotionError::Line {
                            line: k + 1,
                            message: format!(
                                "unknown units \"{}\": use gal, g or m/s2",
                                value.trim()
                            ),
                        })?;
                        match opts.units {
                            Some(u) if u != said => {
                                return Err(disagree(
                                    format!("units {}", said.name()),
                                    format!("units {}", u.name()),
                                    "--units",
                                ))
                            }
                            _ => units = Some(said),
                        }
                    }
                    "dt_s" | "dt" => {
                        if std::mem::replace(&mut said_dt, true) {
                            return Err(MotionError::Line {
                                line: k + 1,
                                message: "a second `# dt_s:` line: give the interval once".into(),
                            });
                        }
                        let said: f64 = value.trim().parse().map_err(|_| MotionError::Line {
                            line: k + 1,
                            message: format!("dt \"{}\" is not a number of seconds", value.trim()),
                        })?;
                        match opts.dt_s {
                            Some(d) if d != said => {
                                return Err(disagree(
                                    format!("dt {said} s"),
                                    format!("dt {d} s"),
                                    "--record-dt",
                                ))
                            }
                            _ => dt = Some(said),
                        }
                    }
                    _ => {}
                }
            }
            continue;
        }
        let fields: Vec<&str> = line
            .split(|c: char| c == ',' || c == ';' || c.is_whitespace())
            .filter(|f| !f.is_empty())
            .collect();
        let mut values = Vec::with_capacity(fields.len());
        for f in &fields {
            match f.parse::<f64>() {
                Ok(v) if v.is_finite() => values.push(v),
                Ok(_) => {
                    return Err(MotionError::Line {
                        line: k + 1,
                        message: format!("\"{f}\" is not a finite number"),
                    })
                }
                Err(_) if rows.is_empty() => {
                    // A header line such as "time,accel": skip it, but only before the data.
                    values.clear();
                    break;
                }
                Err(_) => {
                    return Err(MotionError::Line {
                        line: k + 1,
                        message: format!("expected numbers, found \"{f}\""),
                    })
                }
            }
        }
        if !values.is_empty() {
            if let Some((_, first)) = rows.first() {
                if first.len() != values.len() {
                    return Err(MotionError::Line {
                        line: k + 1,
                        message: format!(
                            "expected {} columns like the first data line, found {}",
                            first.len(),
                            values.len()
                        ),
                    });
                }
            }
            rows.push((k + 1, values));
        }
    }
    let units = units.ok_or(MotionError::Missing {
        missing: "the file does not say its units",
        fix: "add a line `# units: gal` (or g, m/s2) or pass --units",
    })?;
    if rows.len() < 2 {
        return Err(MotionError::TooFewSamples {
            found: rows.len(),
            counted: "data lines",
        });
    }
    let ncol = rows[0].1.len();
    let (dt, col) = if ncol == 1 {
        if let Some(c) = opts.component {
            return Err(MotionError::NoComponent {
                asked: format!("component {c} asked for"),
                available: "the file has one column of accelerations: leave --component out".into(),
            });
        }
        let dt = dt.ok_or(MotionError::Missing {
            missing: "one column of accelerations needs a time step",
            fix: "add `# dt_s: 0.01` or pass --record-dt",
        })?;
        (dt, 0)
    } else {
        let col = opts.component.unwrap_or(ncol - 1);
        if col == 0 || col >= ncol {
            return Err(MotionError::NoComponent {
                asked: format!("column {col}"),
                available: format!(
                    "not an acceleration column of this {ncol}-column file (column 0 is time; \
                     use 1..{})",
                    ncol - 1
                ),
            });
        }
        let t0 = rows[0].1[0];
        let step = rows[1].1[0] - t0;
        for (i, (line, r)) in rows.iter().enumerate() {
            let expect = t0 + i as f64 * step;
            if (r[0] - expect).abs()
                > SPACING_TOL * step.abs().max(f64::MIN_POSITIVE) * (i as f64 + 1.0)
            {
                return Err(MotionError::Line {
                    line: *line,
                    message: format!(
                        "time {} breaks the equal spacing of {} s (expected {})",
                        r[0], step, expect
                    ),
                });
            }
        }
        if let Some(d) = dt.filter(|d| (d - step).abs() > SPACING_TOL * step.abs()) {
            return Err(MotionError::Contradiction(format!(
                "a sample interval of {d} s was given (--record-dt or `# dt_s:`), but the time \
                 column is spaced {step} s: leave the interval out or correct it"
            )));
        }
        (step, col)
    };
    let scale = units.to_m_s2();
    let accel = rows.iter().map(|(_, r)| r[col] * scale).collect();
    Record::new(name, dt, accel)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_and_two_column_files() {
        let r = read_plain(
            "a",
            "# units: gal\n# dt_s: 0.02\n100\n-50\n25\n",
            &ReadOptions::default(),
        )
        .unwrap();
        assert_eq!(r.dt_s, 0.02);
        assert_eq!(r.accel_m_s2, vec![1.0, -0.5, 0.25]);
        let r = read_plain(
            "b",
            "time,acc\n0.0, 0.1\n0.01, 0.2\n0.02, 0.3\n",
            &ReadOptions {
                units: Some(AccelUnit::G),
                ..Default::default()
            },
        )
        .unwrap();
        assert!((r.dt_s - 0.01).abs() < 1e-15);
        assert!((r.accel_m_s2[1] - 0.2 * 9.81).abs() < 1e-12);
    }

    #[test]
    fn broken_files_name_the_line() {
        let e = read_plain("a", "1\n2\n", &ReadOptions::default()).unwrap_err();
        assert!(e.to_string().contains("units"), "{e}");
        let e = read_plain("a", "# units: g\n1\n2\n", &ReadOptions::default()).unwrap_err();
        assert!(e.to_string().contains("--record-dt"), "{e}");
        let e = read_plain(
            "a",
            "# units: g\n# dt_s: 0.1\n1\nx\n",
            &ReadOptions::default(),
        )
        .unwrap_err();
        assert_eq!(e.to_string(), "line 4: expected numbers, found \"x\"");
        let e = read_plain(
            "a",
            "# units: g\n0 1\n0.1 2\n0.25 3\n",
            &ReadOptions::default(),
        )
        .unwrap_err();
        assert!(e.to_string().starts_with("line 4: time 0.25"), "{e}");
        let e = read_plain(
            "a",
            "# units: g\n# dt_s: 0.1\n1\nNaN\n",
            &ReadOptions::default(),
        )
        .unwrap_err();
        assert!(e.to_string().contains("line 4"), "{e}");
    }
}
