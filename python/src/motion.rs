//! `pirqa.Motion`: a ground motion from a numpy array of accelerations (with its sample interval
//! and units), a record file, or a sine. It pickles as its samples or its sine's numbers.

use crate::errors::{option, IntoPy};
use numpy::{PyArray1, PyReadonlyArray1};
use pirqa::motion::{read_record, ReadOptions};
use pirqa::units::{parse_acceleration, AccelUnit, ACCELERATION_UNITS};
use pirqa::{Record, Sine};
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::path::PathBuf;
use std::sync::Arc;

/// A horizontal ground acceleration history.
#[pyclass(frozen, module = "pirqa")]
pub struct Motion {
    pub motion: Arc<pirqa::Motion>,
}

/// Accelerations as float64 values: a numpy array read in place, or any sequence of numbers.
fn samples(values: &Bound<'_, PyAny>) -> PyResult<Vec<f64>> {
    match values.extract::<PyReadonlyArray1<'_, f64>>() {
        Ok(a) => Ok(a
            .as_slice()
            .map_or_else(|_| a.as_array().to_vec(), <[f64]>::to_vec)),
        Err(_) => values.extract::<Vec<f64>>().map_err(|_| {
            option(
                "accel_m_s2",
                "expected a one-dimensional array (or sequence) of numbers",
            )
        }),
    }
}

fn unit(units: &str) -> PyResult<AccelUnit> {
    AccelUnit::parse(units).ok_or_else(|| {
        option(
            "units",
            format!("\"{units}\": give one of gal, g, m/s2 ({ACCELERATION_UNITS})"),
        )
    })
}

/// A record from samples in m/s2.
fn record(name: String, dt_s: f64, accel_m_s2: Vec<f64>) -> PyResult<Motion> {
    let r = Record::new(name, dt_s, accel_m_s2).py()?;
    Ok(Motion {
        motion: Arc::new(pirqa::Motion::Record(r)),
    })
}

#[pymethods]
impl Motion {
    /// A record from an array of ground accelerations, the first at t = 0, `dt_s` apart, in
    /// `units` (m/s2, gal or g), linear between samples.
    #[staticmethod]
    #[pyo3(signature = (accel_m_s2, *, dt_s, units = "m/s2", name = "array"))]
    fn from_array(
        accel_m_s2: &Bound<'_, PyAny>,
        dt_s: f64,
        units: &str,
        name: &str,
    ) -> PyResult<Motion> {
        let factor = unit(units)?.to_m_s2();
        let mut a = samples(accel_m_s2)?;
        if factor != 1.0 {
            a.iter_mut().for_each(|x| *x *= factor);
        }
        record(name.into(), dt_s, a)
    }

    /// A record file (PEER AT2, COSMOS, plain columns: docs/motion.md), scaled by `scale` or to
    /// the peak `pga` (`"400gal"`, `"0.4g"`); `dt_s` and `units` for plain files that do not
    /// say them.
    #[staticmethod]
    #[pyo3(signature = (path, *, scale = None, pga = None, dt_s = None, units = None, format = None))]
    fn from_file(
        path: PathBuf,
        scale: Option<f64>,
        pga: Option<&str>,
        dt_s: Option<f64>,
        units: Option<&str>,
        format: Option<&str>,
    ) -> PyResult<Motion> {
        let opts = ReadOptions {
            dt_s,
            units: units.map(unit).transpose()?,
            component: None,
        };
        let r = read_record(&path, format, &opts).py()?;
        let factor = match (scale, pga) {
            (Some(_), Some(_)) => return Err(option("pga", "give scale or pga, not both")),
            (Some(s), None) => s,
            (None, Some(p)) => parse_acceleration(p).py()? / r.pga_m_s2(),
            (None, None) => 1.0,
        };
        let r = if factor == 1.0 {
            r
        } else {
            r.scaled(factor).py()?
        };
        Ok(Motion {
            motion: Arc::new(pirqa::Motion::Record(r)),
        })
    }

    /// A sine a = amplitude sin(2 pi f t + phase) for 0 <= t <= duration_s; the amplitude with
    /// its units (`"400gal"`, `"0.41g"`, `"4m/s2"`).
    #[staticmethod]
    #[pyo3(signature = (amplitude, *, frequency_hz, duration_s, phase_deg = 0.0))]
    fn sine(
        amplitude: &str,
        frequency_hz: f64,
        duration_s: f64,
        phase_deg: f64,
    ) -> PyResult<Motion> {
        let s = Sine {
            amplitude_m_s2: parse_acceleration(amplitude).py()?,
            frequency_hz,
            duration_s,
            phase_rad: pirqa::motion::phase_rad(phase_deg),
        };
        Ok(Motion {
            motion: Arc::new(pirqa::Motion::sine(s).py()?),
        })
    }

    /// The ground at rest, for a block released from a rotation (`pirqa.run` with
    /// `initial_rotation` and `duration_s`).
    #[staticmethod]
    fn rest() -> Motion {
        Motion {
            motion: Arc::new(pirqa::Motion::Pulse(pirqa::Pulse::rest())),
        }
    }

    /// Length of the motion (s).
    #[getter]
    fn duration_s(&self) -> f64 {
        self.motion.duration_s()
    }

    /// Peak ground acceleration (m/s2).
    #[getter]
    fn pga_m_s2(&self) -> f64 {
        self.motion.peak_accel_m_s2()
    }

    /// Sample interval (s) of a record; None for a sine.
    #[getter]
    fn dt_s(&self) -> Option<f64> {
        match &*self.motion {
            pirqa::Motion::Record(r) => Some(r.dt_s()),
            _ => None,
        }
    }

    /// The samples of a record (m/s2, a copy); None for a sine.
    #[getter]
    fn accel_m_s2<'py>(&self, py: Python<'py>) -> Option<Bound<'py, PyArray1<f64>>> {
        match &*self.motion {
            pirqa::Motion::Record(r) => Some(PyArray1::from_slice(py, r.accel_m_s2())),
            _ => None,
        }
    }

    fn __repr__(&self) -> String {
        match &*self.motion {
            pirqa::Motion::Record(r) => format!(
                "Motion.record({:?}, {} samples, dt {} s, peak {} m/s2)",
                r.name,
                r.accel_m_s2().len(),
                r.dt_s(),
                r.pga_m_s2()
            ),
            pirqa::Motion::Sine(s) => format!(
                "Motion.sine({} m/s2, {} Hz, {} s)",
                s.amplitude_m_s2, s.frequency_hz, s.duration_s
            ),
            pirqa::Motion::Pulse(p) if *p == pirqa::Pulse::rest() => "Motion.rest()".into(),
            pirqa::Motion::Pulse(p) => format!(
                "Motion.pulse({} m/s2, {} s)",
                p.amplitude_m_s2, p.duration_s
            ),
        }
    }

    /// A record from samples in m/s2 (pickling).
    #[staticmethod]
    fn _from_samples(accel_m_s2: &Bound<'_, PyAny>, dt_s: f64, name: String) -> PyResult<Motion> {
        record(name, dt_s, samples(accel_m_s2)?)
    }

    /// A sine from its numbers as kept (pickling: the phase in radians, to the bit).
    #[staticmethod]
    fn _from_sine(
        amplitude_m_s2: f64,
        frequency_hz: f64,
        duration_s: f64,
        phase_rad: f64,
    ) -> PyResult<Motion> {
        let s = Sine {
            amplitude_m_s2,
            frequency_hz,
            duration_s,
            phase_rad,
        };
        Ok(Motion {
            motion: Arc::new(pirqa::Motion::sine(s).py()?),
        })
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let class = py.get_type::<Motion>();
        match &*slf.get().motion {
            pirqa::Motion::Record(r) if r.lambda().is_none() => (
                class.getattr("_from_samples")?,
                (
                    PyArray1::from_slice(py, r.accel_m_s2()),
                    r.dt_s(),
                    r.name.clone(),
                ),
            )
                .into_pyobject(py),
            pirqa::Motion::Sine(s) => (
                class.getattr("_from_sine")?,
                (s.amplitude_m_s2, s.frequency_hz, s.duration_s, s.phase_rad),
            )
                .into_pyobject(py),
            pirqa::Motion::Pulse(p) if *p == pirqa::Pulse::rest() => {
                (class.getattr("rest")?, ()).into_pyobject(py)
            }
            // The Python API makes neither.
            pirqa::Motion::Record(_) | pirqa::Motion::Pulse(_) => Err(option(
                "motion",
                "only records without a vertical component, sines and the ground at rest pickle",
            )),
        }
    }
}

impl Motion {
    /// Whether this is the ground at rest ([`Motion::rest`]), whose run needs a duration.
    pub fn is_rest(&self) -> bool {
        matches!(&*self.motion, pirqa::Motion::Pulse(p) if *p == pirqa::Pulse::rest())
    }
}
