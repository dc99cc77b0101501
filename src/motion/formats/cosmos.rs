//! COSMOS V2 (processed) files: a text header (its first line says how many lines), an integer
//! header and a real header (each introduced by a line giving its count and Fortran format), a
//! comment block, then per channel the acceleration, velocity and displacement series in
//! fixed-width fields, where values may touch. The sample interval is real header value 62 (ms),
//! the data's units the code in the acceleration line (`units=cm/sec2 (04)`).

use super::numbers::{free_format, FixedFormat};
use super::{ReadOptions, Reads, RecordFormat};
use crate::error::MotionError;
use crate::motion::Record;

/// The COSMOS V2 format.
pub struct Cosmos;

fn line_err(line: usize, message: impl Into<String>) -> MotionError {
    MotionError::Line {
        line,
        message: message.into(),
    }
}

/// The count and format of a block introduced by a line such as
/// `  100 Integer-header values follow on  10 lines, Format= (10I8)`.
fn block_header(line: &str, n: usize, what: &str) -> Result<(usize, FixedFormat), MotionError> {
    let count = line
        .split_whitespace()
        .next()
        .and_then(|w| w.parse().ok())
        .ok_or_else(|| {
            line_err(
                n,
                format!(
                    "expected the {what} line (a count first), found \"{}\"",
                    line.trim()
                ),
            )
        })?;
    let from = line.to_ascii_lowercase().find("format").unwrap_or(0);
    let fmt = line[from..]
        .find('(')
        .and_then(|i| FixedFormat::parse(line[from + i..].split(')').next()?))
        .ok_or_else(|| {
            line_err(
                n,
                format!("the {what} line has no Fortran format such as `Format=(8F10.5)`"),
            )
        })?;
    Ok((count, fmt))
}

/// Reads `count` fixed-width values starting at line index `start`; returns them and the index
/// of the line after them.
fn fixed_values(
    lines: &[&str],
    start: usize,
    count: usize,
    fmt: FixedFormat,
    what: &str,
) -> Result<(Vec<f64>, usize), MotionError> {
    // Sized by the lines left (a fixed-width line holds a few values), not by the header.
    let mut out = Vec::with_capacity(count.min(lines.len().saturating_sub(start) * 10));
    let mut k = start;
    while out.len() < count {
        let line = lines.get(k).ok_or_else(|| {
            line_err(
                k,
                format!("the file ends after {} of {count} {what} values", out.len()),
            )
        })?;
        let v = fmt.values(line).map_err(|e| {
            line_err(
                k + 1,
                format!(
                    "{e} ({what}, format {} x {} characters)",
                    fmt.per_line, fmt.width
                ),
            )
        })?;
        out.extend(v);
        k += 1;
    }
    out.truncate(count);
    Ok((out, k))
}

/// m/s2 per data unit, from the COSMOS physical-parameter code.
fn unit_scale(code: i64) -> Option<f64> {
    match code {
        2 => Some(crate::units::G_UNIT_M_S2),
        4 | 10 => Some(0.01),
        11 => Some(crate::units::G_UNIT_M_S2 * 1e-3),
        _ => None,
    }
}

impl RecordFormat for Cosmos {
    fn name(&self) -> &'static str {
        "cosmos"
    }

    fn detect(&self, text: &str) -> bool {
        text.lines()
            .next()
            .is_some_and(|l| l.to_ascii_lowercase().contains("(format v"))
    }

    fn reads(&self) -> Reads {
        Reads {
            component: true,
            ..Reads::default()
        }
    }

    fn read(&self, name: &str, text: &str, opts: &ReadOptions) -> Result<Record, MotionError> {
        let lines: Vec<&str> = text.lines().collect();
        let mut channels = Vec::new();
        let mut k = 0;
        while k < lines.len() {
            if lines[k].trim().is_empty() {
                k += 1;
                continue;
            }
            let (record, next) = read_channel(name, &lines, k)?;
            channels.push(record);
            k = next;
        }
        let which = opts.component.unwrap_or(0);
        let count = channels.len();
        channels
            .into_iter()
            .nth(which)
            .ok_or_else(|| MotionError::NoComponent {
                asked: format!("channel {which} asked for"),
                available: format!("the file has {count} (numbered from 0)"),
            })
    }
}

fn read_channel(name: &str, lines: &[&str], start: usize) -> Result<(Record, usize), MotionError> {
    let first = lines[start].to_ascii_lowercase();
    let text_lines = first
        .find("with")
        .and_then(|i| {
            free_format(first[i + 4..].split("text").next()?)
                .ok()?
                .first()
                .copied()
        })
        .map_or(13, |n| n as usize);
    let mut k = start + text_lines;
    let (n_int, int_fmt) =
        block_header(lines.get(k).copied().unwrap_or(""), k + 1, "integer-header")?;
    let (ints, next) = fixed_values(lines, k + 1, n_int, int_fmt, "integer-header")?;
    k = next;
    let (n_real, real_fmt) =
        block_header(lines.get(k).copied().unwrap_or(""), k + 1, "real-header")?;
    let real_line = k + 1;
    let (reals, next) = fixed_values(lines, k + 1, n_real, real_fmt, "real-header")?;
    k = next;
    let comments: usize = lines
        .get(k)
        .and_then(|l| l.split_whitespace().next()?.parse().ok())
        .ok_or_else(|| {
            line_err(
                k + 1,
                "expected the comment-count line (`  4 Comment line(s) follow...`)",
            )
        })?;
    k += 1 + comments;
    let dt_ms = *reals.get(61).ok_or_else(|| {
        line_err(
            real_line,
            format!(
                "the real header has {} values; value 62 (sample interval, ms) is missing",
                reals.len()
            ),
        )
    })?;
    if !(dt_ms.is_finite() && dt_ms > 0.0) {
        return Err(line_err(
            real_line,
            format!("real-header value 62 (sample interval) is {dt_ms} ms: it must be positive and finite"),
        ));
    }
    if ints.get(1).is_some_and(|&kind| kind != 1.0) {
        return Err(MotionError::Contradiction(format!(
            "integer-header value 2 is {}: this channel is not an acceleration record",
            ints[1]
        )));
    }
    let data_line = lines.get(k).copied().unwrap_or("");
    let data_n = k + 1;
    if !data_line.to_ascii_lowercase().contains("accel") {
        return Err(line_err(
            data_n,
            format!(
                "expected the acceleration data line (`4000 acceleration pts, ...`), found \"{}\"",
                data_line.trim()
            ),
        ));
    }
    let (npts, data_fmt) = block_header(data_line, data_n, "acceleration data")?;
    // Units: the code in parentheses after `units=`, else integer-header value 3.
    let code = data_line
        .to_ascii_lowercase()
        .find("units")
        .and_then(|i| {
            let rest = &data_line[i..];
            let open = rest.find('(')?;
            let close = rest[open..].find(')')? + open;
            rest[open + 1..close].trim().parse::<i64>().ok()
        })
        .or_else(|| ints.get(2).map(|&c| c as i64));
    let scale = code.and_then(unit_scale).ok_or_else(|| {
        line_err(data_n, format!("acceleration units code {code:?} not understood: expected 04 (cm/s2), 10 (gal), 02 (g) or 11 (mg)"))
    })?;
    let (acc, mut k) = fixed_values(lines, k + 1, npts, data_fmt, "acceleration")?;
    // Skip the velocity and displacement series and the end-of-data line.
    while k < lines.len() && !lines[k].to_ascii_lowercase().contains("end-of-data") {
        k += 1;
    }
    let record = Record::new(name, dt_ms * 1e-3, acc.iter().map(|a| a * scale).collect())?;
    Ok((record, k + 1))
}
