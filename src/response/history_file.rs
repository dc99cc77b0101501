//! history.csv: its header and rows, written whole from a history kept in memory or row by row
//! to disk as a run goes (bounded memory: a history of gigabytes never sits in memory). A
//! streamed file is named `.history.csv.partial` beside its final name until the run ends, so a
//! killed run leaves a file that says it is partial, never a history.csv cut short.

use super::partial::PartialFile;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// The header: time, then u and v of every block (and theta, omega and w, the vertical
/// displacement of the middle of its base, when blocks rotate), with units in the names;
/// through the CSV writer, since a block name may hold a comma or a quote.
pub(crate) fn header(names: &[&str], rotating: bool) -> String {
    let quantities: &[(&str, &str)] = if rotating {
        &[
            ("u", "m"),
            ("v", "m_s"),
            ("theta", "rad"),
            ("omega", "rad_s"),
            ("w", "m"),
        ]
    } else {
        &[("u", "m"), ("v", "m_s")]
    };
    let mut columns = vec!["time_s".to_string()];
    for (q, unit) in quantities {
        columns.extend(names.iter().map(|n| format!("{q}_{n}_{unit}")));
    }
    let columns: Vec<&str> = columns.iter().map(String::as_str).collect();
    crate::table::header(&columns)
}

/// One row, numbers only: the time as the shortest decimal that reads back, the rest in
/// scientific notation.
pub(crate) fn push_row(out: &mut String, t: f64, parts: [&[f64]; 5]) {
    let _ = write!(out, "{t}");
    for x in parts.into_iter().flatten() {
        let _ = write!(out, ",{x:e}");
    }
    out.push('\n');
}

/// A history written to disk as it comes.
#[derive(Debug)]
pub struct Stream {
    file: PartialFile,
    names: Vec<String>,
    line: String,
    rows: u64,
}

impl Stream {
    /// A history for blocks `names`, to be written at `path`.
    pub fn new(path: &Path, names: &[String]) -> Stream {
        Stream {
            file: PartialFile::new(path),
            names: names.to_vec(),
            line: String::new(),
            rows: 0,
        }
    }

    /// Writes one row (the header before the first, rotating or not as the first row is).
    pub fn row(&mut self, t: f64, parts: [&[f64]; 5]) {
        if self.file.failed() {
            return;
        }
        self.line.clear();
        if !self.file.opened() {
            let names: Vec<&str> = self.names.iter().map(String::as_str).collect();
            self.line = header(&names, !parts[2].is_empty());
        }
        push_row(&mut self.line, t, parts);
        self.rows += 1;
        self.file.write(&self.line);
    }

    /// Rows written.
    pub fn rows(&self) -> u64 {
        self.rows
    }

    /// Ends the file: flushed and given its name; on a failure the partial file is taken away
    /// and the error returned with the final name.
    pub fn finish(self) -> Result<PathBuf, (PathBuf, std::io::Error)> {
        self.file.finish()
    }
}

/// What is done with each row of a history read back: its time, u of every block, and theta of
/// every block (empty when no block rotates).
pub type RowVisitor<'a> = dyn FnMut(f64, &[f64], &[f64]) + 'a;

/// Reads a history.csv of `blocks` blocks back row by row. Memory holds one row.
pub fn each_row(path: &Path, blocks: usize, f: &mut RowVisitor) -> Result<(), crate::Error> {
    use std::io::BufRead;
    let io = |source| crate::Error::Io {
        path: path.to_path_buf(),
        source,
    };
    let bad = |line: usize, what: &str| {
        io(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            format!("line {line}: {what}"),
        ))
    };
    let mut lines = std::io::BufReader::new(std::fs::File::open(path).map_err(io)?).lines();
    let header = lines.next().transpose().map_err(io)?.unwrap_or_default();
    let rotating = header.contains(",theta_");
    let per_row = 1 + blocks * if rotating { 5 } else { 2 };
    let mut row = Vec::with_capacity(per_row);
    for (k, line) in lines.enumerate() {
        let line = line.map_err(io)?;
        row.clear();
        for field in line.split(',') {
            row.push(
                field
                    .parse::<f64>()
                    .map_err(|_| bad(k + 2, "not a number"))?,
            );
        }
        if row.len() != per_row {
            return Err(bad(k + 2, "a row of another length than the header"));
        }
        let theta = if rotating {
            &row[1 + 2 * blocks..1 + 3 * blocks]
        } else {
            &[]
        };
        f(row[0], &row[1..1 + blocks], theta);
    }
    Ok(())
}
