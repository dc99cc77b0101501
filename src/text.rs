//! Reading the text files pirqa takes (walls, records, sweep files): UTF-8 with a byte-order
//! mark dropped (spreadsheets and Windows editors write one), and a file that is empty or not
//! text at all said to be so, instead of failing later on its first line with another name.

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

#[cfg(test)]
mod tests {
    use super::read;

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
