//! Scratch space for the integration tests: every path lives in a directory of its own under the
//! system's temporary directory, removed with everything in it when the test ends, pass or fail
//! (the tests write histories and charts; left behind, they filled /tmp run after run).

use std::ops::Deref;
use std::path::{Path, PathBuf};

/// Runs the command line with `args` and the extra environment `env`: (exit code, stdout,
/// stderr).
pub fn pirqa(args: &[&str], env: &[(&str, &str)]) -> (i32, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_pirqa"))
        .args(args)
        .envs(env.iter().copied())
        .output()
        .expect("pirqa runs");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// A path in a temporary directory that is removed when this is dropped.
pub struct Scratch {
    _dir: tempfile::TempDir,
    path: PathBuf,
}

impl Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.path
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.path
    }
}

/// A path named `name` that does not exist yet (commands create what they write).
pub fn scratch(name: &str) -> Scratch {
    let dir = tempfile::Builder::new()
        .prefix("pirqa-test-")
        .tempdir()
        .expect("a temporary directory");
    let path = dir.path().join(name);
    Scratch { _dir: dir, path }
}

/// A file named `name` holding `text` (error messages name it, so tests choose the name).
pub fn file(name: &str, text: &str) -> Scratch {
    let f = scratch(name);
    std::fs::write(&*f, text).expect("a temporary file");
    f
}

/// Asserts that two sweep output folders hold the same results byte for byte: every file of
/// `expected` but timing.csv (CPU times, measured) and the shards' `parts/` is in `found` with the
/// same bytes, and `found` has no other result file. Returns how many files were compared.
pub fn same_sweep_files(expected: &Path, found: &Path) -> usize {
    let names = |dir: &Path| -> std::collections::BTreeSet<String> {
        std::fs::read_dir(dir)
            .expect("a sweep's output folder")
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n != "timing.csv" && n != "parts")
            .collect()
    };
    let files = names(expected);
    assert_eq!(
        files,
        names(found),
        "{} against {}",
        expected.display(),
        found.display()
    );
    for name in &files {
        let (a, b) = (
            std::fs::read(expected.join(name)).unwrap(),
            std::fs::read(found.join(name)).unwrap(),
        );
        assert!(
            a == b,
            "{name} differs: {} against {}",
            expected.display(),
            found.display()
        );
    }
    files.len()
}
