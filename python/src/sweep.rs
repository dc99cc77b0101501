//! The Rust side of `pirqa.sweep`: what a sweep file holds (`sweep_info`), a batch of its cases
//! run in a worker (`run_batch`, plain strings back), and the store that keeps finished cases on
//! disk as the command line does (`SweepStore`), so that a sweep run from Python writes the
//! same files, resumes the same way and draws the same charts.

use crate::errors::{option, to_py, IntoPy};
use crate::interrupt::Interrupt;
use pirqa::study::sweep::analysis::analyse;
use pirqa::study::sweep::batch::Batch;
use pirqa::study::sweep::store::{Existing, Store};
use pirqa::study::sweep::Sweep;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex};

/// The sweep a worker process read last: the batches of one sweep come to the same workers,
/// and reading its walls and records again for each would cost more than a small batch's runs.
static LOADED: Mutex<Option<Arc<Sweep>>> = Mutex::new(None);

/// The sweep in `path`, read once per process and again when its files changed.
fn load(path: &Path, fingerprint: Option<&str>) -> Result<Arc<Sweep>, pirqa::Error> {
    let mut loaded = LOADED.lock().unwrap_or_else(|p| p.into_inner());
    if let Some(s) = loaded.as_ref() {
        if s.origin == path && fingerprint.is_some_and(|f| f == s.fingerprint) {
            return Ok(s.clone());
        }
    }
    let sweep = Arc::new(Sweep::load(path)?);
    if let Some(f) = fingerprint.filter(|f| *f != sweep.fingerprint) {
        return Err(pirqa::Error::Table {
            path: path.to_path_buf(),
            line: 0,
            message: format!(
                "the sweep changed while it ran (fingerprint {} now, {f} when it started): \
                 run it again",
                sweep.fingerprint
            ),
        });
    }
    *loaded = Some(sweep.clone());
    Ok(sweep)
}

/// For every case of the sweep finished in `out`, the limit at rest of its wall where its run
/// left it, beside the wall's as built (`pirqa sweep FILE --out DIR --residual`): residual.csv
/// and capacity-left.svg written into `out`. Runs without the GIL; an interrupt stops it,
/// keeping the rows done, and raises `KeyboardInterrupt`.
#[pyfunction]
pub fn sweep_residual(py: Python<'_>, path: PathBuf, out: PathBuf) -> PyResult<()> {
    let interrupt = Interrupt::new(py)?;
    let stop = interrupt.check();
    py.detach(|| {
        let sweep = load(&path, None)?;
        let rows = Store::finished(&out, &sweep)?;
        pirqa::study::sweep::residual::write(&sweep, &rows, &out, &|| {}, &stop)
    })
    .py()?;
    match interrupt.raised() {
        Some(signal) => Err(signal),
        None => Ok(()),
    }
}

/// What a sweep file holds: its name, number of cases, fingerprint and largest wall.
#[pyfunction]
pub fn sweep_info<'py>(py: Python<'py>, path: PathBuf) -> PyResult<Bound<'py, PyDict>> {
    let sweep = py.detach(|| load(&path, None)).py()?;
    let info = PyDict::new(py);
    info.set_item("name", &sweep.name)?;
    info.set_item("cases", sweep.len())?;
    info.set_item("fingerprint", &sweep.fingerprint)?;
    info.set_item(
        "max_blocks",
        sweep
            .walls
            .iter()
            .map(|w| w.wall.blocks.len())
            .max()
            .unwrap_or(0),
    )?;
    Ok(info)
}

/// Runs the cases `ids` of the sweep in `path` one after the other (a worker's share) and
/// returns their rows as CSV lines: (cases, blocks, timing). `fingerprint` is the sweep's when
/// the sweep started: a sweep file changed since is refused.
#[pyfunction]
pub fn run_batch(
    py: Python<'_>,
    path: PathBuf,
    fingerprint: String,
    ids: Vec<usize>,
) -> PyResult<(String, String, String)> {
    let batch = py
        .detach(|| load(&path, Some(&fingerprint))?.run_batch(&ids))
        .py()?;
    Ok((batch.cases, batch.blocks, batch.timing))
}

/// The output folder of a sweep: finished cases appended as they come, tables in case order
/// and the charts at the end.
#[pyclass(module = "pirqa")]
pub struct SweepStore {
    sweep: Arc<Sweep>,
    out: PathBuf,
    store: Option<Store>,
}

impl SweepStore {
    fn open(&mut self) -> PyResult<&mut Store> {
        self.store
            .as_mut()
            .ok_or_else(|| option("SweepStore", "finished already: open the folder again"))
    }
}

#[pymethods]
impl SweepStore {
    /// Opens `out` for the sweep in `path`; `existing` says what to do with results already
    /// there: "refuse", "resume" or "fresh".
    #[new]
    fn new(py: Python<'_>, out: PathBuf, path: PathBuf, existing: &str) -> PyResult<SweepStore> {
        let existing = match existing {
            "refuse" => Existing::Refuse,
            "resume" => Existing::Resume,
            "fresh" => Existing::Overwrite,
            _ => {
                return Err(option(
                    "existing",
                    format!("\"{existing}\": give refuse, resume or fresh"),
                ))
            }
        };
        let sweep = py.detach(|| load(&path, None)).py()?;
        let store = Store::open(&out, &sweep, existing).py()?;
        Ok(SweepStore {
            sweep,
            out,
            store: Some(store),
        })
    }

    /// The sweep's fingerprint.
    #[getter]
    fn fingerprint(&self) -> String {
        self.sweep.fingerprint.clone()
    }

    /// The cases not finished yet, in order.
    fn pending(&mut self) -> PyResult<Vec<usize>> {
        let sweep = self.sweep.clone();
        Ok(self.open()?.pending(&sweep))
    }

    /// Stores a batch that `run_batch` returned.
    fn append(&mut self, batch: (String, String, String)) -> PyResult<()> {
        let (cases, blocks, timing) = batch;
        self.open()?
            .append_batch(&Batch {
                cases,
                blocks,
                timing,
            })
            .py()
    }

    /// Runs the cases `ids` in this process on `threads` threads (default: every core),
    /// storing each as it finishes. Ctrl-C starts no more cases: those running finish and are
    /// stored, then the signal's exception is raised (a resumed sweep runs the rest).
    #[pyo3(signature = (ids, threads = None))]
    fn run(&mut self, py: Python<'_>, ids: Vec<usize>, threads: Option<usize>) -> PyResult<()> {
        let sweep = self.sweep.clone();
        let store = self.open()?;
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads.unwrap_or(0))
            .build()
            .map_err(|e| option("threads", e.to_string()))?;
        let interrupt = Interrupt::new(py)?;
        let ran = py.detach(|| {
            interrupt.around(|stop| {
                pool.install(|| {
                    sweep.run_ids_until(&ids, stop, |row, blocks| store.append(row, blocks))
                })
            })
        });
        match interrupt.raised() {
            Some(signal) => Err(signal),
            None => ran.py(),
        }
    }

    /// Writes the tables in case order, results.json and the charts; returns the folder.
    fn finish(&mut self, py: Python<'_>) -> PyResult<PathBuf> {
        let store = self
            .store
            .take()
            .ok_or_else(|| option("SweepStore", "finished already"))?;
        let (sweep, out) = (self.sweep.clone(), self.out.clone());
        py.detach(move || -> Result<(), pirqa::Error> {
            let (rows, _) = store.finish()?;
            analyse(&sweep, &rows).write(&out)
        })
        .map_err(to_py)?;
        Ok(self.out.clone())
    }
}
