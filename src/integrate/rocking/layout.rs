//! What a rocking run reports, block by block: a body standing alone is one output; a run of a
//! wall's columns lists every block of the wall in the wall's order, as a sliding run does (a
//! column's body moves its blocks, its held blocks and the abutments stay put). This module owns
//! the map from bodies to outputs and each output block's motion as a series.

use super::body::RockingBody;
use super::modes::Trajectory;
use super::series::Coeffs;
use super::Watch;
use crate::response::horizontal_joints;
use crate::topology::Topology;
use crate::wall::Wall;

/// The outputs of a scene and the bodies that move them.
pub struct Layout {
    /// Output names (blocks, or bodies standing alone).
    pub names: Vec<String>,
    /// Per output, its horizontal joint: (output, output below it, its name, its base's name).
    pub horizontal: Vec<(usize, Option<usize>, String, String)>,
    /// Per body, its outputs with the middle of their base at rest in the body's frame (the
    /// middle of the body's base at its level, m); the first is the body's lowest block.
    moving: Vec<Vec<(usize, f64, f64)>>,
    /// Per body, the output of each block of its column, bottom first.
    column: Vec<Vec<usize>>,
}

impl Layout {
    /// The outputs of `bodies`: the blocks of `wall` when the bodies are its columns (one
    /// watch each), else one per body.
    pub fn new(
        bodies: &[RockingBody],
        watches: &[Watch],
        wall: Option<(&Wall, &Topology)>,
    ) -> Layout {
        match wall.filter(|_| !watches.is_empty()) {
            Some((wall, topo)) => Layout {
                names: wall.blocks.iter().map(|b| b.name.clone()).collect(),
                horizontal: horizontal_joints(wall, topo),
                moving: watches
                    .iter()
                    .map(|w| {
                        let moving = w.outputs.iter().filter(|o| o.moving);
                        moving.map(|o| (o.block, o.x0, o.y0)).collect()
                    })
                    .collect(),
                column: watches
                    .iter()
                    .map(|w| w.outputs.iter().map(|o| o.block).collect())
                    .collect(),
            },
            None => Layout {
                names: bodies.iter().map(|b| b.name.clone()).collect(),
                horizontal: bodies
                    .iter()
                    .enumerate()
                    .map(|(i, b)| (i, None, b.name.clone(), "ground".to_string()))
                    .collect(),
                moving: (0..bodies.len()).map(|i| vec![(i, 0.0, 0.0)]).collect(),
                column: (0..bodies.len()).map(|i| vec![i]).collect(),
            },
        }
    }

    /// How many outputs.
    pub fn len(&self) -> usize {
        self.names.len()
    }

    /// Body i's outputs, its lowest block first.
    pub fn outputs(&self, i: usize) -> Vec<usize> {
        self.moving[i].iter().map(|m| m.0).collect()
    }

    /// The output of block k (bottom first) of body i's column.
    pub fn column_output(&self, i: usize, k: usize) -> usize {
        self.column[i][k]
    }

    /// The horizontal displacement of the middle of the base of each of body i's blocks, with
    /// its output, as series along `traj`.
    pub fn series(&self, i: usize, body: &RockingBody, traj: &Trajectory) -> Vec<(usize, Coeffs)> {
        self.moving[i]
            .iter()
            .map(|&(k, x0, y0)| (k, block_series(body, traj, x0, y0)))
            .collect()
    }
}

/// The horizontal displacement of the middle of the body's base, as a series: the pivot's u
/// while seated, u + s b (1 - cos theta) while rocking on the corner of sign s (cos theta from
/// the arms: h_c G_y + s b dx = R^2 cos theta).
fn base_series(body: &RockingBody, t: &Trajectory) -> Coeffs {
    let Some(c) = t.mode.pivot() else {
        return t.u;
    };
    let s = c.sign();
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    let r2 = b * b + h * h;
    let mut out = t.u;
    for (k, (x, (gy, dx))) in out.iter_mut().zip(t.gy.iter().zip(&t.dx)).enumerate() {
        let cos = (h * gy + s * b * dx) / r2;
        *x += s * b * (if k == 0 { 1.0 } else { 0.0 } - cos);
    }
    out
}

/// The same for a point that lies at (x0, y0) of the body's base middle at rest: the base's
/// displacement plus x0 (cos theta - 1) + y0 sin theta (sin theta from the arms too:
/// s b G_y - h_c dx = R^2 sin theta).
fn block_series(body: &RockingBody, t: &Trajectory, x0: f64, y0: f64) -> Coeffs {
    let mut out = base_series(body, t);
    let Some(c) = t.mode.pivot().filter(|_| x0 != 0.0 || y0 != 0.0) else {
        return out;
    };
    let s = c.sign();
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    let r2 = b * b + h * h;
    for (k, (x, (gy, dx))) in out.iter_mut().zip(t.gy.iter().zip(&t.dx)).enumerate() {
        let cos = (h * gy + s * b * dx) / r2;
        let sin = (s * b * gy - h * dx) / r2;
        *x += x0 * (cos - if k == 0 { 1.0 } else { 0.0 }) + y0 * sin;
    }
    out
}
