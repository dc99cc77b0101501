//! pirqa's integration tests, one module per subject, in one test binary: a binary per file
//! would link the whole library (with the release profile's fat LTO) once per file.

mod allocations;
mod animate;
mod answers;
mod common;
mod engine;

mod baselines;
mod cli;
mod collapse;
mod differential;
mod docs;
mod event_driven;
mod fuzz;
mod generate;
mod hand_back;
mod hand_off;
mod hardening;
mod large_walls;
mod properties;
mod python;
mod records;
mod rocking;
mod rocking_walls;
mod shards;
mod survey;
mod sweep;
mod topology;
mod uplift_check;
mod vertical;
mod wall_input;
