//! What a rocking run reports, block by block: a body standing alone is one output; a run of a
//! wall's columns lists every block of the wall in the wall's order, as a sliding run does (a
//! column's body moves its blocks, its held blocks and the abutments stay put). This module owns
//! the map from bodies to outputs and each output block's motion as a series.

use super::body::RockingBody;
use super::modes::{Corner, Mode, State, Trajectory};
use super::series::{self, Coeffs, ORDER, ZERO};
use super::Watch;
use crate::integrate::event::Turned;
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
    /// Per body, half the width of the base its blocks turn on (m).
    pivot_half_base: Vec<f64>,
    /// Per output, whether it turns with its body (a trilith's lintel translates).
    turns: Vec<bool>,
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
                pivot_half_base: watches.iter().map(Watch::pivot_half_base_m).collect(),
                turns: {
                    let mut turns = vec![true; wall.blocks.len()];
                    for o in watches.iter().flat_map(|w| &w.outputs) {
                        turns[o.block] = o.turns;
                    }
                    turns
                },
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
                pivot_half_base: bodies.iter().map(|b| b.half_base_m).collect(),
                turns: vec![true; bodies.len()],
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

    /// Half the width of the base body i turns on (m).
    pub fn pivot_half_base_m(&self, i: usize) -> f64 {
        self.pivot_half_base[i]
    }

    /// Whether output k turns with its body.
    pub fn turns(&self, k: usize) -> bool {
        self.turns[k]
    }

    /// The output of block k (bottom first) of body i's column.
    pub fn column_output(&self, i: usize, k: usize) -> usize {
        self.column[i][k]
    }

    /// The vertical displacement of the middle of the base of each of body i's blocks, with
    /// its output, when the body is turned by `theta` about its pivot (`None`: seated): the
    /// point at (x0, y0) from the base's middle rises by -(x0 - s bp) sin theta + y0 (cos
    /// theta - 1); a block that does not turn follows the top corner it rests on, x0 = -s bp.
    pub fn lifts(&self, i: usize, pivot: Option<Corner>, theta: f64) -> Vec<(usize, f64)> {
        let bp = self.pivot_half_base[i];
        let Some(c) = pivot else {
            return self.moving[i].iter().map(|m| (m.0, 0.0)).collect();
        };
        let s = c.sign();
        let (sin, cos) = theta.sin_cos();
        self.moving[i]
            .iter()
            .map(|&(k, x0, y0)| {
                let x0 = if self.turns[k] { x0 } else { -s * bp };
                (k, -(x0 - s * bp) * sin + y0 * (cos - 1.0))
            })
            .collect()
    }

    /// Where each of body i's blocks is when the body is in `mode` and state `st`, with its
    /// output: its centroid's horizontal displacement and velocity and the
    /// rest of its motion (`half_height` of each output's block, m). A turning block's
    /// centroid, at (x0, y0 + half height) from the base's middle at rest, turns about the
    /// corner at (s bp, 0), which has moved by (u, lift) at (u', lift'): a point r from it goes
    /// to R r, R the clockwise rotation by theta, at theta' dR/dtheta r; a block that does not
    /// turn moves with the top corner it rests on (x0 = -s bp).
    pub fn placed(
        &self,
        i: usize,
        mode: Mode,
        st: &State,
        half_height: &dyn Fn(usize) -> f64,
    ) -> Vec<(usize, (f64, f64, Turned))> {
        let bp = self.pivot_half_base[i];
        let Some(c) = mode.corner() else {
            return self.moving[i]
                .iter()
                .map(|m| (m.0, (st.u, st.v, Turned::default())))
                .collect();
        };
        let s = c.sign();
        let (sin, cos) = st.theta.sin_cos();
        let (lift, lift_v) = match mode {
            Mode::Flight(_) => (st.lift, st.lift_v),
            _ => (0.0, 0.0),
        };
        self.moving[i]
            .iter()
            .map(|&(k, x0, y0)| {
                let turns = self.turns[k];
                let (x, y) = if turns {
                    (x0, y0 + half_height(k))
                } else {
                    (-s * bp, y0)
                };
                let (rx, ry) = (x - s * bp, y);
                let moved = (
                    st.u + rx * (cos - 1.0) + ry * sin,
                    lift - rx * sin + ry * (cos - 1.0),
                );
                let rate = (
                    st.v + st.omega * (-rx * sin + ry * cos),
                    lift_v - st.omega * (rx * cos + ry * sin),
                );
                let (phi, omega) = if turns {
                    (-st.theta, -st.omega)
                } else {
                    (0.0, 0.0)
                };
                let turned = Turned {
                    rise_m: moved.1,
                    phi_rad: phi,
                    rise_m_s: rate.1,
                    omega_rad_s: omega,
                };
                (k, (moved.0, rate.0, turned))
            })
            .collect()
    }

    /// The horizontal displacement of the middle of the base of each of body i's blocks, with
    /// its output, as series along `traj`.
    pub fn series(&self, i: usize, body: &RockingBody, traj: &Trajectory) -> Vec<(usize, Coeffs)> {
        let bp = self.pivot_half_base[i];
        self.moving[i]
            .iter()
            .map(|&(k, x0, y0)| (k, block_series(body, traj, bp, x0, y0, self.turns[k])))
            .collect()
    }
}

/// sin theta and cos theta of a body rocking on (or flying from) the corner of sign s, as
/// series, from the body's arms: h_c G_y + s b dx = R^2 cos theta, s b G_y - h_c dx = R^2 sin
/// theta.
fn turn_series(body: &RockingBody, t: &Trajectory, s: f64) -> (Coeffs, Coeffs) {
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    let r2 = b * b + h * h;
    let (mut sin, mut cos) = (ZERO, ZERO);
    for (k, (gy, dx)) in t.gy.iter().zip(&t.dx).enumerate() {
        cos[k] = (h * gy + s * b * dx) / r2;
        sin[k] = (s * b * gy - h * dx) / r2;
    }
    (sin, cos)
}

/// The horizontal displacement of the middle of a base of half width `bp` that turns with the
/// body, as a series: the pivot's u while seated, u + s bp (1 - cos theta) while rocking on (or
/// flying from) the corner of sign s. A column's body turns on its own base (bp = b); a
/// trilith's on its columns' feet.
fn base_series(body: &RockingBody, t: &Trajectory, bp: f64) -> Coeffs {
    let Some(c) = t.mode.corner() else {
        return t.u;
    };
    let s = c.sign();
    let (_, cos) = turn_series(body, t, s);
    let mut out = t.u;
    for (k, (x, cos)) in out.iter_mut().zip(cos).enumerate() {
        *x += s * bp * (if k == 0 { 1.0 } else { 0.0 } - cos);
    }
    out
}

/// The same for a point that lies at (x0, y0) of the base middle at rest: the base's
/// displacement plus x0 (cos theta - 1) + y0 sin theta. A block that does not turn (a
/// trilith's lintel) moves with the point it rests on, the top corner opposite the pivot:
/// x0 = -s bp.
fn block_series(
    body: &RockingBody,
    t: &Trajectory,
    bp: f64,
    x0: f64,
    y0: f64,
    turns: bool,
) -> Coeffs {
    let mut out = base_series(body, t, bp);
    let Some(c) = t.mode.corner().filter(|_| x0 != 0.0 || y0 != 0.0) else {
        return out;
    };
    let s = c.sign();
    let x0 = if turns { x0 } else { -s * bp };
    let (sin, cos) = turn_series(body, t, s);
    for (k, (x, (sin, cos))) in out.iter_mut().zip(sin.iter().zip(cos)).enumerate() {
        *x += x0 * (cos - if k == 0 { 1.0 } else { 0.0 }) + y0 * sin;
    }
    out
}

/// How a point of a body that turns moves, as series along `t`: its horizontal and vertical
/// displacement from rest, the point at (x, y) from the middle of the body's base at rest, the
/// body turning on a base of half width `bp`. It turns with the corner at (s bp, 0), moved by
/// (u, lift): r = (x - s bp, y) goes to R r, R the clockwise rotation by theta. With it, the
/// rotation's sine and cosine (0 and 1 while seated).
pub(super) fn point_series(
    body: &RockingBody,
    t: &Trajectory,
    bp: f64,
    x: f64,
    y: f64,
) -> ([Coeffs; 2], (Coeffs, Coeffs)) {
    let Some(c) = t.mode.corner() else {
        return ([t.u, ZERO], (ZERO, series::constant(1.0)));
    };
    let s = c.sign();
    let (sin, cos) = turn_series(body, t, s);
    let rx = x - s * bp;
    let lift = if matches!(t.mode, Mode::Flight(_)) {
        t.lift
    } else {
        ZERO
    };
    let (mut dx, mut dy) = (t.u, lift);
    for k in 0..=ORDER {
        let one = if k == 0 { 1.0 } else { 0.0 };
        dx[k] += rx * (cos[k] - one) + y * sin[k];
        dy[k] += -rx * sin[k] + y * (cos[k] - one);
    }
    ([dx, dy], (sin, cos))
}
