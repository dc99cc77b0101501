//! pirqa computes how dry-stone block walls slide, collide and fail in earthquakes.
//!
//! Data flows one way: a wall description ([`wall`]) becomes a support and contact graph
//! ([`topology`]); a ground motion drives it; the integrator finds every stick-slip transition
//! and impact; the response is summarised, swept and drawn. The model and its equations are in
//! `docs/model.md`.

#![warn(missing_docs)]

pub mod clock;
pub mod error;
pub mod exact;
pub mod integrate;
pub mod motion;
pub mod plot;
pub mod response;
pub mod rng;
pub mod samples;
pub mod sets;
pub mod study;
pub mod topology;
pub mod units;
pub mod validity;
pub mod wall;

pub use error::{Error, Result};
pub use exact::Q;
pub use topology::{Base, BlockId, JointId, SupportId, Topology};
pub use wall::Wall;
