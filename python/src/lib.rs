//! `pirqa._pirqa`: the Rust half of the Python package. It wraps the curated library API
//! (`pirqa::Model`, `pirqa::Motion`, `pirqa::run`, the sweep's batches and store) and nothing of
//! the command line; the Python half (`pirqa/`) adds the sweeps over executors, the exception
//! classes and the type stubs. Every solver call releases the GIL.

mod errors;
mod interrupt;
mod motion;
mod run;
mod sweep;
mod to_python;
mod wall;

use pyo3::prelude::*;

#[pymodule]
fn _pirqa(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<wall::Wall>()?;
    m.add_class::<motion::Motion>()?;
    m.add_class::<sweep::SweepStore>()?;
    m.add_function(wrap_pyfunction!(run::run, m)?)?;
    m.add_function(wrap_pyfunction!(run::_time_runs, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_info, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::run_batch, m)?)?;
    m.add_function(wrap_pyfunction!(sweep::sweep_residual, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
