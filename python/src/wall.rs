//! `pirqa.Wall`: a checked wall with its graph, from a RON file, RON text or numpy arrays of
//! block rectangles. It pickles as its RON text, so a worker process rebuilds the same wall.

use crate::errors::{option, IntoPy};
use crate::interrupt::Interrupt;
use pirqa::wall::{parse_description, to_ron_string, RectangleDescription, WallDescription};
use pirqa::Model;
use pyo3::prelude::*;
use pyo3::types::PyTuple;
use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

/// A wall and its support and contact graph, checked.
#[pyclass(frozen, module = "pirqa")]
pub struct Wall {
    pub model: Arc<Model>,
    /// RON text that builds it again (pickling).
    ron: String,
}

/// A wall from a description, named `name` when the description gives none.
fn build(mut d: WallDescription, name: Option<String>) -> PyResult<Wall> {
    if d.name.is_none() {
        d.name = name;
    }
    let wall = pirqa::Wall::from_description(&d).py()?;
    let model = Model::new(wall).py()?;
    Ok(Wall {
        model: Arc::new(model),
        ron: to_ron_string(&d),
    })
}

#[pymethods]
impl Wall {
    /// Reads a wall file (RON, docs/wall-format.md); errors name the file and the line.
    #[staticmethod]
    fn from_file(py: Python<'_>, path: PathBuf) -> PyResult<Wall> {
        let model = py.detach(|| Model::from_file(&path)).py()?;
        let text = std::fs::read_to_string(&path).map_err(|source| {
            crate::errors::to_py(pirqa::Error::Io {
                path: path.clone(),
                source,
            })
        })?;
        let d = parse_description(text.trim_start_matches('\u{feff}')).py()?;
        let mut wall = build(d, Some(model.wall().name.clone()))?;
        wall.model = Arc::new(model);
        Ok(wall)
    }

    /// A wall written in RON; `name` when the text gives none.
    #[staticmethod]
    #[pyo3(signature = (text, name = None))]
    fn from_ron(text: &str, name: Option<String>) -> PyResult<Wall> {
        build(parse_description(text).py()?, name)
    }

    /// A wall from arrays of block rectangles (m): left edge, bottom edge (0 on the ground),
    /// width and height of each block. Blocks are named B1, B2, ... unless `names` are given;
    /// `fixed` marks abutments that move with the ground.
    #[staticmethod]
    #[pyo3(signature = (x_m, y_m, width_m, height_m, *, thickness_m, friction, density_kg_m3,
        names = None, fixed = None, restitution = 1.0, g_m_s2 = 9.81, joint_friction = None,
        name = None))]
    #[allow(clippy::too_many_arguments)]
    fn from_rectangles(
        x_m: Vec<f64>,
        y_m: Vec<f64>,
        width_m: Vec<f64>,
        height_m: Vec<f64>,
        thickness_m: f64,
        friction: f64,
        density_kg_m3: f64,
        names: Option<Vec<String>>,
        fixed: Option<Vec<bool>>,
        restitution: f64,
        g_m_s2: f64,
        joint_friction: Option<BTreeMap<String, f64>>,
        name: Option<String>,
    ) -> PyResult<Wall> {
        let n = x_m.len();
        for (what, len) in [
            ("y_m", y_m.len()),
            ("width_m", width_m.len()),
            ("height_m", height_m.len()),
            ("names", names.as_ref().map_or(n, Vec::len)),
            ("fixed", fixed.as_ref().map_or(n, Vec::len)),
        ] {
            if len != n {
                return Err(option(
                    what,
                    format!("{len} values for {n} blocks (x_m has {n}): give one per block"),
                ));
            }
        }
        let rectangles = (0..n)
            .map(|k| RectangleDescription {
                x_m: x_m[k],
                y_m: y_m[k],
                width_m: width_m[k],
                height_m: height_m[k],
                name: names.as_ref().map(|v| v[k].clone()),
                density_kg_m3: None,
                fixed: fixed.as_ref().is_some_and(|v| v[k]),
            })
            .collect();
        let d = WallDescription {
            version: pirqa::wall::WALL_FORMAT_VERSION,
            name: None,
            thickness_m,
            density_kg_m3: Some(density_kg_m3),
            unit_weight_kn_m3: None,
            friction,
            restitution,
            rocking_restitution_factor: 1.0,
            g_m_s2,
            rows: Vec::new(),
            rectangles,
            joint_friction: joint_friction.unwrap_or_default(),
        };
        build(d, Some(name.unwrap_or_else(|| "wall".into())))
    }

    /// The wall's name.
    #[getter]
    fn name(&self) -> String {
        self.model.wall().name.clone()
    }

    /// The blocks' names, bottom course first.
    #[getter]
    fn blocks(&self) -> Vec<String> {
        self.model
            .wall()
            .blocks
            .iter()
            .map(|b| b.name.clone())
            .collect()
    }

    /// The wall's limit at rest in its plane (`pirqa check --limit`, docs/rocking-walls.md): a
    /// dict with `towards_plus_x` and `towards_minus_x`, each `{"kind": "holds", "accel_g",
    /// "accel_m_s2", "exact_g" (a fraction), "mechanism": [{"block", "how", "u", "v",
    /// "omega_rad_s"}, ...], "mechanism_uniqueness": "unique", "one_of_several" or "undecided",
    /// "moving_in_every_mechanism" and "turning_in_every_mechanism": block names, or None where
    /// not decided}` or `{"kind": "unlimited"}`. With `displacement_m` (one per block, in the
    /// order of `blocks`: a run's final displacements or a history row), the limit of the wall
    /// with its blocks so moved, the `fallen` ones (booleans) taken out, as `pirqa check --run`
    /// gives it, and `moved` saying what moving it changed. The exact programs run without the
    /// GIL; Ctrl-C (a notebook's interrupt) stops them, raising `KeyboardInterrupt` (a large
    /// wall's take minutes).
    #[pyo3(signature = (*, displacement_m = None, fallen = None))]
    fn limit_at_rest<'py>(
        &self,
        py: Python<'py>,
        displacement_m: Option<Vec<f64>>,
        fallen: Option<Vec<bool>>,
    ) -> PyResult<Bound<'py, PyAny>> {
        let n = self.model.wall().blocks.len();
        let moved = match (displacement_m, fallen) {
            (None, None) => None,
            (None, Some(_)) => {
                return Err(option(
                    "fallen",
                    "give it with displacement_m: the blocks that fell of a moved wall",
                ))
            }
            (Some(u), fallen) => {
                let fallen = fallen.unwrap_or_else(|| vec![false; n]);
                for (name, len) in [("displacement_m", u.len()), ("fallen", fallen.len())] {
                    if len != n {
                        return Err(option(
                            name,
                            format!(
                                "{len} values for {n} blocks: one per block, in the order of \
                                 Wall.blocks"
                            ),
                        ));
                    }
                }
                let state = pirqa::response::saved::SavedState {
                    time_s: 0.0,
                    displacement_m: u,
                    fallen,
                    pose: None,
                };
                let model = &self.model;
                let moved = pirqa::response::moved::moved(model.wall(), model.topology(), &state)
                    .map_err(pirqa::Error::InvalidWall)
                    .py()?;
                Some(moved)
            }
        };
        let model = Arc::clone(&self.model);
        let interrupt = Interrupt::new(py)?;
        let stop = interrupt.check();
        let (limits, moves) = py.detach(move || {
            let limits = match &moved {
                Some((wall, topo, _)) => pirqa::limit::at_rest_until(wall, topo, &stop),
                None => pirqa::limit::at_rest_until(model.wall(), model.topology(), &stop),
            };
            (limits, moved.map(|(_, _, moves)| moves))
        });
        let limits = limits.map_err(pirqa::Error::from).py()?;
        /// The limits, and what moving the wall changed where it was moved.
        #[derive(serde::Serialize)]
        struct Report {
            #[serde(flatten)]
            limits: pirqa::limit::Limits,
            #[serde(skip_serializing_if = "Option::is_none")]
            moved: Option<pirqa::response::moved::Moves>,
        }
        match (limits, interrupt.raised()) {
            (_, Some(signal)) => Err(signal),
            (Some(limits), None) => crate::to_python::to_python(
                py,
                &Report {
                    limits,
                    moved: moves,
                },
            ),
            // The stop is set only where a signal's handler raised, so this is not met.
            (None, None) => Err(pyo3::exceptions::PyKeyboardInterrupt::new_err(
                "the limit at rest was stopped",
            )),
        }
    }

    /// The wall as RON text (what `from_ron` reads back).
    #[getter]
    fn ron(&self) -> String {
        self.ron.clone()
    }

    fn __len__(&self) -> usize {
        self.model.wall().blocks.len()
    }

    fn __repr__(&self) -> String {
        format!(
            "Wall({:?}, {} blocks, {} horizontal joints)",
            self.model.wall().name,
            self.model.wall().blocks.len(),
            self.model.topology().horizontal.len()
        )
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let from_ron = py.get_type::<Wall>().getattr("from_ron")?;
        let me = slf.get();
        (from_ron, (me.ron.clone(), me.model.wall().name.clone())).into_pyobject(py)
    }
}
