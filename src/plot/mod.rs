//! Pictures: wall elevations (initial, displaced, collapsed) written as plain SVG, charts, the
//! chart of a run, and a run played back as an HTML page.

pub mod animation;
pub mod chart;
mod response_chart;
mod svg;
mod wall_drawing;

pub use response_chart::{response_charts, MOST_MOVED};
pub use svg::{Style, Svg};
pub use wall_drawing::{draw_wall, mechanism_pose, WallDrawing};
