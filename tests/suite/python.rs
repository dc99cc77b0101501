//! The Python package, built and tested from the README's test command: a virtual environment
//! in target/python (made once, with maturin, numpy, pandas, pytest, Dask and matplotlib from
//! PyPI), the wheel built from python/ and installed, then python/tests run by pytest against
//! the command line this test suite built. pytest's own report (its skips say why: MPI and Ray
//! run only where they are installed) goes to the terminal.

use std::path::{Path, PathBuf};
use std::process::Command;

/// What the tests need from PyPI.
const REQUIREMENTS: &[&str] = &[
    "maturin>=1.9,<2",
    "numpy>=1.22",
    "pandas>=1.5",
    "pytest>=7",
    "dask[distributed]>=2023.1",
    "matplotlib>=3.5",
];

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Runs `command`, failing the test with what it printed when it fails.
fn run(what: &str, command: &mut Command) -> String {
    let out = command
        .output()
        .unwrap_or_else(|e| panic!("{what}: cannot start {command:?}: {e}"));
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{what} failed ({command:?}):\n{text}");
    text
}

/// The virtual environment, made and filled once (again when the requirements change).
fn venv(dir: &Path) -> PathBuf {
    let venv = dir.join("venv");
    let python = venv.join("bin/python");
    let marker = venv.join("pirqa-requirements.txt");
    let wanted = REQUIREMENTS.join("\n");
    if std::fs::read_to_string(&marker).ok().as_deref() == Some(wanted.as_str()) {
        return python;
    }
    let _ = std::fs::remove_dir_all(&venv);
    run(
        "making a virtual environment (python3 -m venv)",
        Command::new("python3").arg("-m").arg("venv").arg(&venv),
    );
    run(
        "installing the test requirements from PyPI",
        Command::new(&python)
            .args(["-m", "pip", "install", "-q", "--disable-pip-version-check"])
            .args(REQUIREMENTS),
    );
    std::fs::write(&marker, wanted).expect("a file in target/");
    python
}

/// Builds the wheel (abi3, the tests' optimisation) and installs it in the environment.
fn install_wheel(dir: &Path, python: &Path) {
    let wheels = dir.join("wheels");
    let _ = std::fs::remove_dir_all(&wheels);
    run(
        "building the wheel (maturin)",
        Command::new(python)
            .args([
                "-m",
                "maturin",
                "build",
                "--quiet",
                "--profile",
                "tests",
                "-m",
            ])
            .arg(root().join("python/Cargo.toml"))
            .arg("--out")
            .arg(&wheels)
            // Its own target folder: the one of this `cargo test` is locked while it runs.
            .env("CARGO_TARGET_DIR", dir.join("cargo")),
    );
    let wheel = std::fs::read_dir(&wheels)
        .expect("maturin wrote its wheel")
        .map(|e| e.unwrap().path())
        .find(|p| p.extension().is_some_and(|x| x == "whl"))
        .expect("a wheel");
    run(
        "installing the wheel",
        Command::new(python)
            .args(["-m", "pip", "install", "-q", "--disable-pip-version-check"])
            .args(["--force-reinstall", "--no-deps"])
            .arg(&wheel),
    );
}

#[test]
fn the_python_package_builds_and_its_tests_pass() {
    let dir = root().join("target/python");
    std::fs::create_dir_all(&dir).expect("target/ is writable");
    let python = venv(&dir);
    install_wheel(&dir, &python);
    let status = Command::new(&python)
        .args(["-m", "pytest", "-q", "-rs", "-p", "no:cacheprovider"])
        .arg(root().join("python/tests"))
        .current_dir(root())
        .env("PIRQA_BIN", env!("CARGO_BIN_EXE_pirqa"))
        .env("PYTHONDONTWRITEBYTECODE", "1")
        .status()
        .expect("pytest starts");
    assert!(
        status.success(),
        "the Python tests failed: their report is above"
    );
}
