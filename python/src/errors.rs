//! pirqa's errors as Python exceptions: the classes live in `pirqa/errors.py` (a root
//! `PirqaError`; invalid walls, motions, sweeps and options also `ValueError`, files also
//! `OSError`), and the message is the command line's, word for word.

use pirqa::Error;
use pyo3::prelude::*;

/// The exception class of `pirqa.errors` that stands for `e`.
fn class_name(e: &Error) -> &'static str {
    match e {
        Error::Wall { .. } | Error::InvalidWall(_) | Error::Survey { .. } | Error::Moved { .. } => {
            "WallError"
        }
        Error::Motion { .. } | Error::InvalidMotion(_) | Error::Unit(_) => "MotionError",
        Error::Sweep { .. } => "SweepError",
        Error::Option { .. } => "OptionError",
        Error::Simulation(_) | Error::Stopped { .. } => "SimulationError",
        Error::Io { .. } => "FileError",
        Error::Table { .. } => "ResultsError",
    }
}

/// `e` as the Python exception of its class.
pub fn to_py(e: Error) -> PyErr {
    Python::attach(|py| {
        let class = py
            .import("pirqa.errors")
            .and_then(|m| m.getattr(class_name(&e)));
        match class {
            Ok(class) => PyErr::from_value(
                class
                    .call1((e.to_string(),))
                    .unwrap_or_else(|err| err.into_value(py).into_bound(py).into_any()),
            ),
            Err(err) => err,
        }
    })
}

/// An option's value that cannot be used, as `OptionError` (a `ValueError`).
pub fn option(option: &str, rule: impl Into<String>) -> PyErr {
    to_py(Error::Option {
        option: option.into(),
        rule: rule.into(),
    })
}

/// Results as Python results.
pub trait IntoPy<T> {
    /// The error as its Python exception.
    fn py(self) -> PyResult<T>;
}

impl<T, E: Into<Error>> IntoPy<T> for Result<T, E> {
    fn py(self) -> PyResult<T> {
        self.map_err(|e| to_py(e.into()))
    }
}
