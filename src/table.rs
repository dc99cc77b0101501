//! The CSV tables pirqa writes and reads back (history.csv, a sweep's cases.csv and blocks.csv,
//! the data of every chart), through the csv crate: a name with a comma, a quote or a line
//! break in it is quoted and comes back as it was, and a table is read by its column names,
//! not by position. Numbers keep the forms they always had: the shortest decimal that reads
//! back to the same float (`plain`), or the same in scientific notation (`sci`).

use crate::error::Error;
use serde::de::DeserializeOwned;
use serde::Serializer;
use std::path::Path;

/// A float as the shortest decimal that reads back to it (`0.2`, `200`, `1e-7`).
pub(crate) fn plain<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(x)
}

/// A float in scientific notation, shortest mantissa that reads back to it (`2.0653e-3`).
pub(crate) fn sci<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    s.collect_str(&format_args!("{x:e}"))
}

/// An optional float as [`sci`], or an empty field.
pub(crate) fn sci_opt<S: Serializer>(x: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
    match x {
        Some(x) => sci(x, s),
        None => s.serialize_str(""),
    }
}

/// An optional float as [`plain`], or an empty field.
pub(crate) fn plain_opt<S: Serializer>(x: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
    match x {
        Some(x) => s.collect_str(x),
        None => s.serialize_str(""),
    }
}

/// A writer of CSV text into memory (fields quoted only where they must be).
pub(crate) fn writer() -> csv::Writer<Vec<u8>> {
    csv::WriterBuilder::new()
        .has_headers(false)
        .buffer_capacity(BUFFER_BYTES)
        .from_writer(Vec::new())
}

/// The bytes a writer gathers before it hands them to its vector. Most writers here write one
/// line (a sweep writes a dozen per case, each with a writer of its own), and the crate's
/// default of 8 KB, cleared at every writer's making, cost as much as the line.
const BUFFER_BYTES: usize = 512;

/// One field as a writer that quotes every field but numbers (`csv::QuoteStyle::NonNumeric`)
/// writes it, without its line's end.
pub(crate) fn non_numeric(field: &str) -> String {
    let mut w = csv::WriterBuilder::new()
        .quote_style(csv::QuoteStyle::NonNumeric)
        .from_writer(Vec::new());
    w.write_record([field])
        .unwrap_or_else(|e| unreachable!("memory takes every write: {e}"));
    let mut line = text(w);
    line.pop();
    line
}

/// The text a writer made.
pub(crate) fn text(w: csv::Writer<Vec<u8>>) -> String {
    let bytes = w
        .into_inner()
        .unwrap_or_else(|e| unreachable!("memory takes every write: {}", e.error()));
    String::from_utf8(bytes)
        .unwrap_or_else(|e| unreachable!("every field is a Rust string or a number: {e}"))
}

/// One record as a CSV line (with its newline).
pub(crate) fn line<T: serde::Serialize>(record: &T) -> String {
    let mut w = writer();
    // Writing into memory fails only for a record that is not flat, and every record here is.
    w.serialize(record)
        .unwrap_or_else(|e| unreachable!("a flat record serialises: {e}"));
    text(w)
}

/// A header line from column names.
pub(crate) fn header(columns: &[&str]) -> String {
    let mut w = writer();
    w.write_record(columns)
        .unwrap_or_else(|e| unreachable!("names serialise: {e}"));
    text(w)
}

fn table_error(path: &Path, line: usize, message: String) -> Error {
    Error::Table {
        path: path.to_path_buf(),
        line,
        message,
    }
}

/// The rows of a table written earlier, read by column name. Every column of `columns` must be
/// in its header (others are left alone); a last line without its newline was cut off by an
/// interruption and is dropped. Errors name the file and the line.
pub(crate) fn read_rows<T: DeserializeOwned>(
    path: &Path,
    text: &str,
    columns: &[&str],
) -> Result<Vec<T>, Error> {
    let complete = match text.rfind('\n') {
        Some(end) => &text[..=end],
        None => "",
    };
    let mut reader = csv::ReaderBuilder::new().from_reader(complete.as_bytes());
    let found = reader
        .headers()
        .map_err(|e| table_error(path, 1, e.to_string()))?
        .clone();
    if let Some(missing) = columns.iter().find(|c| !found.iter().any(|h| h == **c)) {
        return Err(table_error(
            path,
            1,
            format!(
                "no column `{missing}`: expected the columns `{}` (a table written by another \
                 version of pirqa cannot be read back: rerun with --fresh)",
                columns.join(",")
            ),
        ));
    }
    reader
        .deserialize()
        .map(|row| {
            row.map_err(|e| {
                let line = e.position().map_or(0, |p| p.line() as usize);
                let message = match e.kind() {
                    csv::ErrorKind::UnequalLengths {
                        expected_len, len, ..
                    } => format!("expected {expected_len} fields, found {len}"),
                    csv::ErrorKind::Deserialize { err, .. } => match err.field() {
                        Some(k) => format!("column `{}`: {err}", &found[k as usize]),
                        None => err.to_string(),
                    },
                    _ => e.to_string(),
                };
                table_error(path, line, message)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    struct Row {
        name: String,
        #[serde(serialize_with = "sci")]
        u_m: f64,
        #[serde(serialize_with = "plain_opt")]
        scale: Option<f64>,
    }

    /// Names with the CSV's own separators round-trip; columns are found by name in any order;
    /// a line cut off by an interruption is dropped; numbers keep their forms.
    #[test]
    fn rows_round_trip_with_awkward_names_and_columns_in_any_order() {
        let rows = [
            Row {
                name: "B1, \"the big one\"\nsecond line".into(),
                u_m: 2.065e-3,
                scale: Some(200.0),
            },
            Row {
                name: "plain".into(),
                u_m: -0.0,
                scale: None,
            },
        ];
        let mut text = header(&["name", "u_m", "scale"]);
        for r in &rows {
            text.push_str(&line(r));
        }
        assert!(text.contains(",2.065e-3,200\n"), "{text}");
        assert!(text.ends_with("plain,-0e0,\n"), "{text}");
        let path = Path::new("t.csv");
        let back: Vec<Row> = read_rows(path, &text, &["name", "u_m", "scale"]).unwrap();
        assert_eq!(back, rows);
        let cut = format!("{text}more,1e0");
        let back: Vec<Row> = read_rows(path, &cut, &["name", "u_m", "scale"]).unwrap();
        assert_eq!(back, rows);
        let swapped = "scale,name,u_m\n3,a,1e0\n";
        let back: Vec<Row> = read_rows(path, swapped, &["name", "u_m", "scale"]).unwrap();
        assert_eq!(back[0].scale, Some(3.0));
        let e = read_rows::<Row>(path, "name,scale\na,1\n", &["name", "u_m", "scale"]);
        assert!(e.unwrap_err().to_string().contains("no column `u_m`"));
        let e = read_rows::<Row>(path, "name,u_m,scale\na,x,1\n", &["name", "u_m", "scale"]);
        let e = e.unwrap_err().to_string();
        assert!(e.contains("line 2") && e.contains("column `u_m`"), "{e}");
    }

    /// A line longer than a writer's buffer leaves it in pieces and reads as the line the
    /// crate's default buffer writes: a name of 5,000 characters with quotes and commas.
    #[test]
    fn a_line_longer_than_the_buffer_is_the_same_line() {
        let row = Row {
            name: "a, \"b\"\n".repeat(700),
            u_m: 1.5e-300,
            scale: Some(2.0),
        };
        let mut w = csv::WriterBuilder::new()
            .has_headers(false)
            .from_writer(Vec::new());
        w.serialize(&row).unwrap();
        let long = line(&row);
        assert!(long.len() > 10 * BUFFER_BYTES);
        assert_eq!(long, text(w));
    }
}
