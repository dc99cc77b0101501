//! `pirqa.run`: one run of a wall under a motion, the GIL released while it runs and Ctrl-C
//! heard (`interrupt`). It returns plain data (summary.json's values as a dict, the history as
//! numpy arrays moved out of Rust, the event log as dicts) that the Python `Result` wraps, so a
//! result pickles as it is.

use crate::errors::{option, IntoPy};
use crate::interrupt::Interrupt;
use crate::motion::Motion;
use crate::to_python::to_python;
use crate::wall::Wall;
use numpy::ndarray::Array2;
use numpy::IntoPyArray;
use pirqa::integrate::Progress;
use pirqa::{AfterStop, AfterUplift, ContactSolver, Direction, Method, ModelChoice, RunSettings};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Rows of per-block values as a (rows x blocks) array: one contiguous copy, then handed to
/// numpy without another.
fn matrix<'py>(py: Python<'py>, rows: Vec<Vec<f64>>) -> PyResult<Bound<'py, PyAny>> {
    let (n, columns) = (rows.len(), rows.first().map_or(0, Vec::len));
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    let array = Array2::from_shape_vec((n, columns), flat).map_err(|_| {
        crate::errors::to_py(pirqa::Error::Simulation(pirqa::SimulationError::Bug(
            "history rows of unequal lengths".into(),
        )))
    })?;
    Ok(array.into_pyarray(py).into_any())
}

fn method(name: &str, dt_s: Option<f64>) -> PyResult<Method> {
    let step =
        || dt_s.ok_or_else(|| option("dt_s", format!("method \"{name}\" needs a time step dt_s")));
    match name {
        "event" if dt_s.is_none() => Ok(Method::Event),
        "event" => Err(option(
            "dt_s",
            "the exact method takes no time step: leave dt_s out",
        )),
        "moreau" => Ok(Method::Moreau { dt_s: step()? }),
        "paper" => Ok(Method::Paper { dt_s: step()? }),
        _ => Err(option(
            "method",
            format!("\"{name}\": give event (exact), moreau or paper"),
        )),
    }
}

/// The integrator, what follows a first uplift and what follows where the exact rocking model
/// stops: with "moreau" (or "moreau-while-rocking") after either, `dt_s` is the step of the time
/// stepping that takes over, and the exact method runs up to there (and again, after an
/// uplift, wherever every block is seated and calm).
fn method_after(
    method: &str,
    after_uplift: &str,
    after_stop: &str,
    dt_s: Option<f64>,
) -> PyResult<(Method, AfterUplift, AfterStop)> {
    let handed = |option_name: &str, asked: &str| {
        dt_s.ok_or_else(|| {
            option(
                "dt_s",
                format!(
                    "{option_name} \"{asked}\" needs the time step dt_s of the stepping that \
                     takes over"
                ),
            )
        })
    };
    let after_uplift = match after_uplift {
        "slide" => AfterUplift::Slide,
        "moreau" => AfterUplift::Moreau {
            dt_s: handed("after_uplift", after_uplift)?,
        },
        "moreau-while-rocking" => AfterUplift::MoreauWhileRocking {
            dt_s: handed("after_uplift", after_uplift)?,
        },
        _ => {
            return Err(option(
                "after_uplift",
                format!("\"{after_uplift}\": give slide, moreau or moreau-while-rocking"),
            ))
        }
    };
    let after_stop = match after_stop {
        "end" => AfterStop::End,
        "moreau" => AfterStop::Moreau {
            dt_s: handed("after_stop", after_stop)?,
        },
        _ => {
            return Err(option(
                "after_stop",
                format!("\"{after_stop}\": give end or moreau"),
            ))
        }
    };
    // The step belongs to the stepping that takes over; the exact method takes none.
    let taken = after_uplift != AfterUplift::Slide || after_stop != AfterStop::End;
    let own = if taken && method == "event" {
        None
    } else {
        dt_s
    };
    Ok((self::method(method, own)?, after_uplift, after_stop))
}

fn model(name: &str) -> PyResult<ModelChoice> {
    match name {
        "auto" => Ok(ModelChoice::Auto),
        "slide" => Ok(ModelChoice::Slide),
        "slide-rock" => Ok(ModelChoice::SlideRock),
        _ => Err(option(
            "model",
            format!("\"{name}\": give auto, slide or slide-rock"),
        )),
    }
}

fn contact_solver(name: &str) -> PyResult<ContactSolver> {
    match name {
        "gauss-seidel" => Ok(ContactSolver::GaussSeidel),
        "newton" => Ok(ContactSolver::Newton),
        _ => Err(option(
            "contact_solver",
            format!("\"{name}\": give gauss-seidel or newton"),
        )),
    }
}

fn direction(name: &str) -> PyResult<Direction> {
    match name {
        "in-plane" => Ok(Direction::InPlane),
        "out-of-plane" => Ok(Direction::OutOfPlane),
        _ => Err(option(
            "direction",
            format!("\"{name}\": give in-plane or out-of-plane"),
        )),
    }
}

/// The releases of a dict {name: rotation in rad}, in its order.
fn releases(given: Option<&Bound<'_, PyDict>>) -> PyResult<Vec<(String, f64)>> {
    let Some(given) = given else {
        return Ok(Vec::new());
    };
    given
        .iter()
        .map(|(name, theta)| {
            let bad = || {
                option(
                    "initial_rotation",
                    "give a dict of block (or section) names to rotations in rad, \
                     {\"B17\": 0.1}",
                )
            };
            Ok((
                name.extract::<String>().map_err(|_| bad())?,
                theta.extract::<f64>().map_err(|_| bad())?,
            ))
        })
        .collect()
}

/// Runs `wall` under `motion`; see `pirqa.run`.
#[pyfunction]
#[pyo3(signature = (wall, motion, *, duration_s = None, output_dt_s = None, method = "event",
    dt_s = None, model = "auto", contact_solver = "gauss-seidel", direction = "in-plane",
    initial_rotation = None, log_events = false, check_uplift = false, after_uplift = "slide",
    after_stop = "end"))]
#[allow(clippy::too_many_arguments)]
pub fn run<'py>(
    py: Python<'py>,
    wall: &Wall,
    motion: &Motion,
    duration_s: Option<f64>,
    output_dt_s: Option<f64>,
    method: &str,
    dt_s: Option<f64>,
    model: &str,
    contact_solver: &str,
    direction: &str,
    initial_rotation: Option<&Bound<'_, PyDict>>,
    log_events: bool,
    check_uplift: bool,
    after_uplift: &str,
    after_stop: &str,
) -> PyResult<Bound<'py, PyDict>> {
    if motion.is_rest() && duration_s.is_none() {
        return Err(option(
            "duration_s",
            "a block released on still ground (Motion.rest()) needs duration_s",
        ));
    }
    let interrupt = Interrupt::new(py)?;
    let (method, after_uplift, after_stop) = method_after(method, after_uplift, after_stop, dt_s)?;
    let settings = RunSettings {
        duration_s,
        output_dt_s,
        log_events,
        method,
        after_uplift,
        after_stop,
        model: self::model(model)?,
        contact_solver: self::contact_solver(contact_solver)?,
        direction: self::direction(direction)?,
        initial_rotation: releases(initial_rotation)?,
        check_uplift,
        progress: Some(Progress::new(|_| {}).with_stop_when(interrupt.check())),
        ..RunSettings::default()
    };
    let (m, g) = (wall.model.clone(), motion.motion.clone());
    let response = py.detach(move || pirqa::run(&m, &g, &settings)).py()?;
    let out = result(py, response)?;
    match interrupt.raised() {
        // What the run reached goes with the exception, as the command line writes it.
        Some(signal) => {
            signal.value(py).setattr("partial", out)?;
            Err(signal)
        }
        None => Ok(out),
    }
}

/// A run's response as the plain data `pirqa.Result` wraps.
fn result(py: Python<'_>, response: pirqa::Response) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("summary", to_python(py, &response.summary)?)?;
    out.set_item("events", to_python(py, &response.events)?)?;
    // The history's columns are the summary's blocks: the wall's blocks in a run in the wall's
    // plane, its sections in a run across it.
    let names = response
        .summary
        .blocks
        .iter()
        .map(|b| b.name.clone())
        .collect::<Vec<_>>();
    out.set_item("blocks", names)?;
    match response.history {
        Some(h) => {
            let history = PyDict::new(py);
            history.set_item("time_s", h.time_s.into_pyarray(py))?;
            history.set_item("displacement_m", matrix(py, h.displacement_m)?)?;
            history.set_item("velocity_m_s", matrix(py, h.velocity_m_s)?)?;
            if !h.rotation_rad.is_empty() {
                history.set_item("rotation_rad", matrix(py, h.rotation_rad)?)?;
                history.set_item(
                    "angular_velocity_rad_s",
                    matrix(py, h.angular_velocity_rad_s)?,
                )?;
                history.set_item("lift_m", matrix(py, h.lift_m)?)?;
            }
            out.set_item("history", history)?;
        }
        None => out.set_item("history", py.None())?,
    }
    Ok(out)
}

/// The Rust library's own time for `repeats` runs of `wall` under `motion` (summary only, as
/// `run` with its defaults), each in seconds, with no Python in the loop: what
/// benches/python_sweeps.py sets the Python call against.
#[pyfunction]
pub fn _time_runs(
    py: Python<'_>,
    wall: &Wall,
    motion: &Motion,
    repeats: usize,
) -> PyResult<Vec<f64>> {
    let (m, g) = (wall.model.clone(), motion.motion.clone());
    py.detach(move || {
        (0..repeats)
            .map(|_| {
                let start = std::time::Instant::now();
                pirqa::run(&m, &g, &RunSettings::default())?;
                Ok(start.elapsed().as_secs_f64())
            })
            .collect::<Result<Vec<f64>, pirqa::Error>>()
    })
    .py()
}
