//! Pictures: wall elevations (initial, displaced, collapsed) written as plain SVG, and charts.

pub mod chart;
mod svg;
mod wall_drawing;

pub use svg::{Style, Svg};
pub use wall_drawing::{draw_wall, WallDrawing};
