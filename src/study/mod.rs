//! Studies: many runs and what they show. Each module owns one kind of study.

pub mod failures;
pub mod overturning;
pub mod paper;
pub mod stats;
pub mod sweep;
pub mod work_precision;
