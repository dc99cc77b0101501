//! Generated walls: one overall size cut into running-bond courses, so that the same wall can be
//! studied as 5, 20, 100, 1,000 or 10,000 blocks. Two courses of two blocks over 2.4 m x 1.2 m is
//! the paper's five-block wall.

use super::description::{BlockDescription, RowDescription, WallDescription, WALL_FORMAT_VERSION};
use crate::error::WallError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Block edges are placed on a grid of this many per metre (0.1 mm), so that every width is an
/// exact decimal and each course spans the wall exactly.
const GRID_PER_M: f64 = 1e4;

/// A running-bond wall: `courses` courses over `width_m` x `height_m`. Even courses (the first is
/// course 0, on the ground) hold `blocks_per_course` equal blocks; odd courses are offset by half
/// a block and so start and end with half blocks (`blocks_per_course + 1` pieces).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunningBond {
    /// Number of courses.
    pub courses: usize,
    /// Whole blocks per even course.
    pub blocks_per_course: usize,
    /// Overall width (m).
    pub width_m: f64,
    /// Overall height (m).
    pub height_m: f64,
    /// Out-of-plane thickness (m).
    pub thickness_m: f64,
    /// Density (kg/m3).
    pub density_kg_m3: f64,
    /// Friction coefficient of every horizontal joint.
    pub friction: f64,
    /// Coefficient of restitution (default 1).
    #[serde(default = "one")]
    pub restitution: f64,
}

fn one() -> f64 {
    1.0
}

impl RunningBond {
    /// The paper's wall (2.4 m x 1.2 m, 0.8 m thick, 2650 kg/m3, mu 0.3, e = 1) cut into about
    /// `target` blocks with the paper's block proportions: as many courses as blocks per course.
    pub fn paper_wall(target: usize) -> RunningBond {
        // n blocks per course over n courses give n^2 + floor(n / 2) pieces.
        let count = |n: usize| n * n + n / 2;
        let n = (2..=(target as f64).sqrt() as usize + 2)
            .min_by_key(|&n| count(n).abs_diff(target))
            .expect("a non-empty range");
        RunningBond {
            courses: n,
            blocks_per_course: n,
            width_m: 2.4,
            height_m: 1.2,
            thickness_m: 0.8,
            density_kg_m3: 2650.0,
            friction: 0.3,
            restitution: 1.0,
        }
    }

    /// Number of blocks the wall will have.
    pub fn block_count(&self) -> usize {
        self.courses * self.blocks_per_course + self.courses / 2
    }

    /// The wall description (courses of blocks; edges on a 0.1 mm grid).
    pub fn description(&self) -> Result<WallDescription, WallError> {
        let positive = |field: &str, x: f64| {
            if x.is_finite() && x > 0.0 {
                Ok(())
            } else {
                Err(WallError::Field {
                    field: field.into(),
                    value: x,
                    rule: "must be positive and finite",
                })
            }
        };
        for (field, x) in [
            ("courses", self.courses as f64),
            ("blocks_per_course", self.blocks_per_course as f64),
            ("width_m", self.width_m),
            ("height_m", self.height_m),
        ] {
            positive(field, x)?;
        }
        let grid = |x: f64| (x * GRID_PER_M).round() as i64;
        let (w, h) = (grid(self.width_m), grid(self.height_m));
        let (b, c) = (self.blocks_per_course as i64, self.courses as i64);
        // The smallest piece is a half block of an odd course: it must span at least one cell.
        if w < 2 * b || h < c {
            return Err(WallError::Field {
                field: "blocks_per_course".into(),
                value: self.blocks_per_course as f64,
                rule:
                    "too many blocks or courses for the wall's size: pieces would be under 0.1 mm",
            });
        }
        let metres = |cells: i64| cells as f64 / GRID_PER_M;
        let rows = (0..c)
            .map(|k| {
                // Edges at multiples of w / b, shifted by half a block on odd courses.
                let edges: Vec<i64> = if k % 2 == 0 {
                    (0..=b).map(|j| (j * w + b / 2) / b).collect()
                } else {
                    std::iter::once(0)
                        .chain((0..b).map(|j| ((2 * j + 1) * w + b) / (2 * b)))
                        .chain(std::iter::once(w))
                        .collect()
                };
                RowDescription {
                    height_m: metres((k + 1) * h / c - k * h / c),
                    x_m: 0.0,
                    blocks: edges
                        .windows(2)
                        .map(|e| BlockDescription {
                            width_m: metres(e[1] - e[0]),
                            gap_m: 0.0,
                            name: None,
                            height_m: None,
                            density_kg_m3: None,
                            fixed: false,
                        })
                        .collect(),
                }
            })
            .collect();
        Ok(WallDescription {
            version: WALL_FORMAT_VERSION,
            name: Some(format!(
                "Running bond, {} courses x {} blocks ({} blocks), {} m x {} m",
                self.courses,
                self.blocks_per_course,
                self.block_count(),
                self.width_m,
                self.height_m
            )),
            thickness_m: self.thickness_m,
            density_kg_m3: Some(self.density_kg_m3),
            unit_weight_kn_m3: None,
            friction: self.friction,
            restitution: self.restitution,
            rocking_restitution_factor: 1.0,
            g_m_s2: 9.81,
            rows,
            rectangles: Vec::new(),
            joint_friction: BTreeMap::new(),
        })
    }
}
