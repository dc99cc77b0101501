//! The text files pirqa reads and writes. Reading (walls, records, sweep files): UTF-8 with a
//! byte-order mark dropped (spreadsheets and Windows editors write one), and a file that is
//! empty or not text at all said to be so, instead of failing later on its first line with
//! another name. Writing (every result file): whole or not at all, so a killed run never leaves
//! a truncated summary or table that a later run would trust.

use crate::error::Error;
use std::path::Path;

const BOM: &str = "\u{feff}";

/// The text of the file at `path` (`what`: "record", "wall", ... for the messages).
pub fn read(path: &Path, what: &str) -> Result<String, Error> {
    let bytes = std::fs::read(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let invalid = |message: String| Error::Io {
        path: path.to_path_buf(),
        source: std::io::Error::new(std::io::ErrorKind::InvalidData, message),
    };
    let text = String::from_utf8(bytes).map_err(|e| {
        invalid(format!(
            "not a text file (byte {} is not UTF-8): a {what} is text",
            e.utf8_error().valid_up_to() + 1
        ))
    })?;
    let text = text.strip_prefix(BOM).map(str::to_string).unwrap_or(text);
    if text.trim().is_empty() {
        return Err(invalid(format!("the file is empty: it holds no {what}")));
    }
    Ok(text)
}

/// Writes `contents` to `path` atomically: into a temporary file beside it, then renamed over
/// it (a rename within a folder replaces the file at once), creating the folder if needed.
pub fn write(path: &Path, contents: &str) -> Result<(), Error> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| Error::Io { path, source }
    };
    let dir = path.parent().filter(|d| !d.as_os_str().is_empty());
    if let Some(dir) = dir {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
    }
    let name = path
        .file_name()
        .map_or_else(|| "out".into(), |n| n.to_string_lossy().into_owned());
    let tmp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    std::fs::write(&tmp, contents).map_err(|e| {
        // A disk that filled up part-way leaves a cut temporary file: take it away, so that
        // nothing but whole results is ever left.
        let _ = std::fs::remove_file(&tmp);
        io(path)(e)
    })?;
    std::fs::rename(&tmp, path).map_err(|e| {
        // Leave nothing behind: the error is about the rename.
        let _ = std::fs::remove_file(&tmp);
        io(path)(e)
    })
}

#[cfg(test)]
mod tests {
    use super::{read, write};

    #[test]
    fn a_write_replaces_the_file_whole_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("deep").join("summary.json");
        write(&path, "first").unwrap();
        write(&path, "second").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "second");
        let left: Vec<_> = std::fs::read_dir(path.parent().unwrap()).unwrap().collect();
        assert_eq!(left.len(), 1);
        let e = write(&dir.path().join("deep"), "x")
            .unwrap_err()
            .to_string();
        assert!(e.contains("deep"), "{e}");
    }

    #[test]
    fn a_byte_order_mark_is_dropped_and_empty_or_binary_files_are_named() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("r.txt");
        std::fs::write(&path, "\u{feff}# units: gal\n").unwrap();
        assert_eq!(read(&path, "record").unwrap(), "# units: gal\n");
        std::fs::write(&path, " \n\n").unwrap();
        let e = read(&path, "record").unwrap_err().to_string();
        assert!(
            e.contains("r.txt: the file is empty: it holds no record"),
            "{e}"
        );
        std::fs::write(&path, [b'a', b'b', 0xff, 0xfe]).unwrap();
        let e = read(&path, "record").unwrap_err().to_string();
        assert!(e.contains("not a text file (byte 3 is not UTF-8)"), "{e}");
    }
}
