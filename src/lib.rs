//! pirqa computes how dry-stone block walls slide, rock, collide and fail in earthquakes.
//!
//! A run: the paper's five-block wall with variable friction under a 400 gal, 1 Hz sine for
//! 20 s, on the exact event-driven integrator.
//!
//! ```
//! use pirqa::{Model, Motion, RunSettings, Sine};
//!
//! let model = Model::from_file("walls/five-block-variable.ron")?;
//! let sine = Sine { amplitude_m_s2: 4.0, frequency_hz: 1.0, duration_s: 20.0, ..Sine::default() };
//! let result = pirqa::run(&model, &Motion::sine(sine)?, &RunSettings::default())?;
//! for block in &result.summary.blocks {
//!     println!("{}: max |u| = {:.4} m", block.name, block.max_abs_displacement_m);
//! }
//! assert!(result.summary.energy.residual_j.abs() < 1e-9 * result.summary.energy.input_j);
//! # Ok::<(), pirqa::Error>(())
//! ```
//!
//! What to reach for: [`Model`] (a wall with its graph, from a file or RON text), [`Motion`]
//! (a [`Sine`], a rectangular [`Pulse`], a [`Record`] read by [`motion::read_record`]),
//! [`RunSettings`] (method, model, history, logs; `Default` for the exact integrator with the
//! model chosen by the motion) and [`run()`], which returns a [`Response`]: the [`Summary`]
//! (`summary.json`), the history and the event log. Sweeps: [`study::sweep`]. More in
//! `examples/` (`cargo run --release --example paper_wall`, `record`, `sweep`).
//!
//! Data flows one way: a wall description ([`wall`]) becomes a support and contact graph
//! ([`topology`]); a ground motion drives it; the integrator finds every stick-slip transition
//! and impact; the response is summarised, swept and drawn. The model and its equations are in
//! `docs/model.md`.

#![warn(missing_docs)]

pub mod bounds;
pub mod clock;
pub mod error;
pub mod estimate;
pub mod exact;
pub mod integrate;
pub mod limit;
pub mod model;
pub mod motion;
pub mod plot;
pub mod response;
pub mod rng;
pub mod run;
pub mod samples;
pub mod sets;
pub mod study;
mod table;
pub mod text;
pub mod topology;
pub mod units;
pub mod validity;
pub mod wall;

pub use error::{Error, MotionError, Result, SimulationError, SweepError, WallError};
pub use estimate::{estimate, Estimate};
pub use exact::Q;
pub use integrate::baselines::ContactSolver;
pub use integrate::rocking::{Equations, ModelChoice};
pub use integrate::AfterCollapse;
pub use model::Model;
pub use motion::{Motion, Pulse, Record, Sine};
pub use response::{Response, Summary, Warning};
pub use run::{run, AfterStop, AfterUplift, Direction, Method, RunSettings};
pub use topology::{Base, BlockId, HorizontalId, JointRef, Topology, VerticalId};
pub use wall::Wall;
