//! Reading acceleration records in the formats strong-motion databases distribute: PEER NGA
//! AT2, K-NET/KiK-net ASCII, COSMOS V2, and plain text or CSV. One module per format behind
//! [`RecordFormat`]; the format is recognised from the content, or forced.

mod at2;
mod cosmos;
mod knet;
mod numbers;
mod plain;

pub use at2::At2;
pub use cosmos::Cosmos;
pub use knet::Knet;
pub use numbers::{free_format, FixedFormat};
pub use plain::{read_plain, Plain};

use super::Record;
use crate::error::{Error, MotionError};
use crate::units::AccelUnit;
use std::path::Path;

/// What the caller knows beyond the file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReadOptions {
    /// Sample interval (s) for one-column plain files without a `# dt_s:` line.
    pub dt_s: Option<f64>,
    /// Units of plain files without a `# units:` line.
    pub units: Option<AccelUnit>,
    /// Which component: the column after time in a plain multi-column file (1-based), the
    /// channel in a multi-channel COSMOS file (0-based).
    pub component: Option<usize>,
}

/// Which of the [`ReadOptions`] a format reads; a file in it gives the others itself.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Reads {
    /// [`ReadOptions::dt_s`].
    pub dt_s: bool,
    /// [`ReadOptions::units`].
    pub units: bool,
    /// [`ReadOptions::component`].
    pub component: bool,
}

/// A record file format.
pub trait RecordFormat {
    /// Name used by `--format`.
    fn name(&self) -> &'static str;
    /// Does this text look like this format?
    fn detect(&self, text: &str) -> bool;
    /// The options this format reads (default: none, its header says everything).
    fn reads(&self) -> Reads {
        Reads::default()
    }
    /// Reads the record; accelerations come back in m/s2.
    fn read(&self, name: &str, text: &str, opts: &ReadOptions) -> Result<Record, MotionError>;
}

/// Refuses options a format does not read: the file gives them itself, and an option that
/// would be ignored is a mistake to report, not to pass over.
fn refuse_unread(
    fmt: &dyn RecordFormat,
    opts: &ReadOptions,
    component_option: &str,
) -> Result<(), MotionError> {
    let reads = fmt.reads();
    let unread = [
        (
            opts.dt_s.is_some() && !reads.dt_s,
            "gives its sample interval in its header",
            "--record-dt",
        ),
        (
            opts.units.is_some() && !reads.units,
            "gives its units in its header",
            "--units",
        ),
        (
            opts.component.is_some() && !reads.component,
            "holds one component",
            component_option,
        ),
    ];
    match unread.iter().find(|(given, _, _)| *given) {
        Some((_, says, option)) => Err(MotionError::Contradiction(format!(
            "a record in the {} format {says}: leave {option} out",
            fmt.name()
        ))),
        None => Ok(()),
    }
}

/// Every format, most specific first; plain text matches anything and comes last.
pub const FORMATS: [&dyn RecordFormat; 4] = [&Knet, &Cosmos, &At2, &Plain];

/// The format called `name` (`at2`, `knet`, `cosmos`, `plain`).
pub fn format_named(name: &str) -> Option<&'static dyn RecordFormat> {
    let name = name.to_ascii_lowercase();
    let name = if name == "csv" || name == "txt" {
        "plain".to_string()
    } else {
        name
    };
    FORMATS.iter().copied().find(|f| f.name() == name)
}

/// The format this text is in.
pub fn detect(text: &str) -> &'static dyn RecordFormat {
    FORMATS
        .iter()
        .copied()
        .find(|f| f.detect(text))
        .unwrap_or(&Plain)
}

/// Reads a record file, detecting its format unless one is given; options the format does not
/// read are refused. Errors name the file.
pub fn read_record(path: &Path, format: Option<&str>, opts: &ReadOptions) -> Result<Record, Error> {
    read_file(path, format, opts, None)
}

/// Reads a record that comes with another and shares its sample interval and units options (a
/// vertical component beside its horizontal record): where its format gives those itself they
/// were meant for the other record, and are left aside instead of refused. Its component is
/// its own (given as `component_option`), refused where the format has one.
pub fn read_companion(
    path: &Path,
    format: Option<&str>,
    opts: &ReadOptions,
    component_option: &str,
) -> Result<Record, Error> {
    read_file(path, format, opts, Some(component_option))
}

/// A record read alone (`companion` = `None`) or beside another, its component given by the
/// option `companion` names.
fn read_file(
    path: &Path,
    format: Option<&str>,
    opts: &ReadOptions,
    companion: Option<&str>,
) -> Result<Record, Error> {
    let text = crate::text::read(path, "record")?;
    let fmt = match format {
        Some(f) => format_named(f).ok_or_else(|| Error::Motion {
            path: path.to_path_buf(),
            source: MotionError::Unknown {
                what: "format",
                given: f.into(),
                choices: "at2, knet, cosmos or plain",
            },
        })?,
        None => detect(&text),
    };
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |f| f.to_string_lossy().into_owned(),
    );
    let reads = fmt.reads();
    let used = ReadOptions {
        dt_s: opts.dt_s.filter(|_| reads.dt_s),
        units: opts.units.filter(|_| reads.units),
        component: opts.component.filter(|_| reads.component),
    };
    let own = ReadOptions {
        component: opts.component,
        ..ReadOptions::default()
    };
    let checked = match companion {
        None => refuse_unread(fmt, opts, "--component"),
        Some(option) => refuse_unread(fmt, &own, option),
    };
    checked
        .and_then(|()| fmt.read(&name, &text, &used))
        .map_err(|source| Error::Motion {
            path: path.to_path_buf(),
            source,
        })
}
