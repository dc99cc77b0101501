//! Studies: many runs and what they show. Each module owns one kind of study.

pub mod failures;
pub mod work_precision;
