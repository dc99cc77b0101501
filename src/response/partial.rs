//! A file a run writes as it goes: under a partial name (`.NAME.partial` beside its final name)
//! until the run ends, so a run that is killed or fails leaves a file that says it is partial,
//! never a final file cut short, and keeps what it had written up to then: the file is flushed
//! at least once a second, so a run killed outright loses at most its last second.

use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

/// How long written lines may wait in memory.
const FLUSH_EVERY: Duration = Duration::from_secs(1);

/// Lines appended to a partial file, opened at the first line.
#[derive(Debug)]
pub(crate) struct PartialFile {
    path: PathBuf,
    partial: PathBuf,
    file: Option<std::io::BufWriter<std::fs::File>>,
    /// When the file was last flushed.
    flushed: Instant,
    /// The first failure, kept until the run ends (a run does not stop for its files).
    failed: Option<std::io::Error>,
}

impl PartialFile {
    /// A file that will be named `path` when the run ends.
    pub(crate) fn new(path: &Path) -> PartialFile {
        PartialFile {
            partial: partial_name(path),
            path: path.to_path_buf(),
            file: None,
            flushed: Instant::now(),
            failed: None,
        }
    }

    /// Has the first line been written (the file opened)?
    pub(crate) fn opened(&self) -> bool {
        self.file.is_some()
    }

    /// Whether writing has failed (nothing more is written).
    pub(crate) fn failed(&self) -> bool {
        self.failed.is_some()
    }

    /// Appends `text`, opening the file (and its folder) first if needed.
    pub(crate) fn write(&mut self, text: &str) {
        if self.failed.is_some() {
            return;
        }
        if self.file.is_none() {
            let opened = self
                .partial
                .parent()
                .filter(|d| !d.as_os_str().is_empty())
                .map_or(Ok(()), std::fs::create_dir_all)
                .and_then(|()| std::fs::File::create(&self.partial));
            match opened {
                Ok(f) => self.file = Some(std::io::BufWriter::with_capacity(1 << 20, f)),
                Err(e) => {
                    self.failed = Some(e);
                    return;
                }
            }
        }
        let file = self.file.as_mut().expect("opened above");
        let mut written = file.write_all(text.as_bytes());
        if written.is_ok() && self.flushed.elapsed() >= FLUSH_EVERY {
            written = file.flush();
            self.flushed = Instant::now();
        }
        if let Err(e) = written {
            self.failed = Some(e);
        }
    }

    /// Ends the file: flushed and given its final name; on a failure the partial file is taken
    /// away and the error returned with the final name.
    pub(crate) fn finish(mut self) -> Result<PathBuf, (PathBuf, std::io::Error)> {
        let done = match (self.failed.take(), self.file.take()) {
            (Some(e), _) => Err(e),
            (None, Some(mut f)) => f
                .flush()
                .and_then(|()| f.get_ref().sync_all())
                .and_then(|()| std::fs::rename(&self.partial, &self.path)),
            (None, None) => Ok(()),
        };
        done.map(|()| self.path.clone()).map_err(|e| {
            let _ = std::fs::remove_file(&self.partial);
            (self.path.clone(), e)
        })
    }

    /// Ends the file without keeping it: the run ended and its caller writes the final file.
    pub(crate) fn discard(mut self) {
        if self.file.take().is_some() {
            let _ = std::fs::remove_file(&self.partial);
        }
    }
}

/// `.NAME.partial` beside `path`.
pub fn partial_name(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map_or_else(|| "file".into(), |n| n.to_string_lossy().into_owned());
    path.with_file_name(format!(".{name}.partial"))
}
