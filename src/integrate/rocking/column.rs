//! Columns: walls whose movable blocks stand in stacks, each block on one block (or the ground
//! or an abutment) touching nothing beside it (what stands apart is watched by `clearance`
//! until it meets). In a column the joint that gives way first under a
//! ground acceleration that grows from zero (the smallest of its friction coefficient and its
//! two tipping ratios, the part above taken as rigid) is the one the column moves on: the part
//! above it is one rocking body ([`RockingBody`]) on a base held to the ground, and the exact
//! engine runs it through rest, sliding, rocking, slide-rock, landings and overturning. Every
//! other joint is *held*: the blocks below move with the ground, those above with the body.
//! That holds while each held joint can carry what it must, so the [`Watch`] checks it as the
//! run goes: friction within its cone and the resultant of its normal force within its contact
//! (the block on it does not tip), both as series between events and as impulses through
//! every landing. The first of these conditions to fall ends the exact model at that instant,
//! the run with it, and says which joint gave way and how (docs/rocking-walls.md).

use super::body::RockingBody;
use super::frame::{trilith, Frame, Recognised};
use super::modes::{Constraint, Corner, Guard, Inputs, Mode, Slip, Trajectory, Velocity};
use super::series::{
    add_to, constant, derivative, plus, product, sin_cos_at, Coeffs, ORDER, TIE, ZERO,
};
use super::stack::{Displaced, Stack};
use crate::error::SimulationError;
use crate::exact::Q;
use crate::topology::{Base, BlockId, Topology};
use crate::wall::Wall;

/// One column of a wall, as the exact engine runs it.
#[derive(Debug, Clone)]
pub struct Column {
    /// The part above the joint the column moves on, named after its blocks (`B2+B3`).
    pub body: RockingBody,
    /// Each joint of the column, bottom first, and where it gives way.
    pub limits: Vec<JointLimit>,
    /// The held joints, checked as the body moves.
    pub watch: Watch,
    /// The blocks held to the ground below the body, bottom first.
    pub held: Vec<String>,
}

impl Column {
    /// Where the body's blocks are once it is turned by `theta_rad` (clockwise positive) about
    /// the end of its base on that side: each moving block's name, the displacement of its
    /// centroid (m, m) and its counter-clockwise rotation (rad), for a time-stepped model to
    /// start from.
    pub fn released(&self, theta_rad: f64) -> Vec<(String, f64, f64, f64)> {
        let w = &self.watch;
        if let Some(frame) = &w.frame {
            let name = |k: usize| w.outputs[k].name.clone();
            return frame
                .released(theta_rad)
                .into_iter()
                .map(|(k, dx, dy, phi)| (name(k), dx, dy, phi))
                .collect();
        }
        let s = if theta_rad > 0.0 { 1.0 } else { -1.0 };
        let (sin, cos) = theta_rad.sin_cos();
        w.pieces
            .iter()
            .zip(&w.outputs)
            .filter(|(p, _)| p.moving)
            .map(|(p, o)| {
                let (rx, ry) = (p.x0 - s * w.half_base_m, p.y0);
                let x = s * w.half_base_m + rx * cos + ry * sin;
                let y = -rx * sin + ry * cos;
                (o.name.clone(), x - p.x0, y - p.y0, -theta_rad)
            })
            .collect()
    }

    /// Whether block `name` moves with the body (rather than being held below it).
    pub fn moves(&self, name: &str) -> bool {
        self.watch
            .outputs
            .iter()
            .any(|o| o.moving && o.name == name)
            || self.body.name == name
    }
}

/// A block of a column as the watch sees it: in the frame whose origin is the middle of the
/// body's base at rest, on the level of its joint.
#[derive(Debug, Clone)]
pub(super) struct Piece {
    pub(super) mass_kg: f64,
    /// About its own centroid (kg m2).
    pub(super) inertia_kg_m2: f64,
    /// Its centroid at rest (m).
    pub(super) x0: f64,
    pub(super) y0: f64,
    /// Part of the body (moves with it) or held to the ground below it.
    moving: bool,
}

/// A joint of a column: its name (`upper/lower`), friction, the ends of its contact at rest (in
/// the watch's frame, on its level), whether it lies inside the body (and moves with it), and
/// the pieces above it.
#[derive(Debug, Clone)]
pub(super) struct Held {
    pub(super) name: String,
    /// The block on it (index in the column, bottom first).
    pub(super) upper: usize,
    pub(super) friction: f64,
    pub(super) ends: [(f64, f64); 2],
    inside: bool,
    above: Vec<usize>,
    /// Whether each end is a corner of the block on it (else of the block or ground below):
    /// a block that turns on that end presses its corner on the face below, or the face
    /// below's corner on its own face, and the contact's normal is that face's.
    pub(super) upper_corner: [bool; 2],
}

/// A joint of a column and the ground accelerations, in g (at unit vertical load factor),
/// at which it gives way with the part above it rigid and moving with the ground.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct JointLimit {
    /// `upper/lower`.
    pub joint: String,
    /// |a_g| / g at which it slips: its friction coefficient.
    pub slip_g: f64,
    /// a_g / g at or above which the part above tips about the joint's left end, (x_G - x_l) / h.
    pub tips_left_g: f64,
    /// -a_g / g at or above which it tips about the right end, (x_r - x_G) / h.
    pub tips_right_g: f64,
    /// The joint gives way first (the smallest of the three, the lowest joint of equal ones):
    /// the column moves on it.
    pub moves: bool,
}

/// A block of a column as a run reports it.
#[derive(Debug, Clone)]
pub struct Output {
    /// Its name.
    pub name: String,
    /// Its place in the wall.
    pub block: usize,
    /// The middle of its base at rest, in the watch's frame (m); a trilith's blocks each from
    /// the middle of their own base (0, and the lintel's `y0` as `turns` says).
    pub x0: f64,
    /// The same, height.
    pub y0: f64,
    /// Moves with the body (or is held).
    pub moving: bool,
    /// Turns with the body; a trilith's lintel translates, following the corner of the
    /// columns' tops opposite their feet, at height `y0`.
    pub turns: bool,
}

/// The conditions of a column's held joints.
#[derive(Debug, Clone)]
pub struct Watch {
    /// What the body stands on (`ground` or a block's name).
    pub base: String,
    /// The column's blocks, bottom first.
    pub outputs: Vec<Output>,
    pub(super) pieces: Vec<Piece>,
    joints: Vec<Held>,
    /// The joint the body moves on (none for a trilith).
    pub(super) moving: Option<Held>,
    pub(super) half_base_m: f64,
    pub(super) g_m_s2: f64,
    /// Forces (N) and moments (N m) are measured against the column's weight and its weight
    /// times its height.
    pub(super) force_scale: f64,
    pub(super) moment_scale: f64,
    /// A trilith's joints, watched instead of a column's.
    frame: Option<Frame>,
}

/// How a held joint gives way; four conditions per joint, in this order.
const HOW: [&str; 4] = [
    "would slip, the block on it towards -x (it needs more friction towards +x than the \
     joint holds)",
    "would slip, the block on it towards +x (it needs more friction towards -x than the \
     joint holds)",
    "would open at its right end (the block on it would tip about its left end)",
    "would open at its left end (the block on it would tip about its right end)",
];

impl Watch {
    /// The watch of a trilith: its blocks, and the half width of a column's foot.
    pub(super) fn of_frame(frame: Frame, outputs: Vec<Output>, half_base_m: f64) -> Watch {
        Watch {
            base: "ground".into(),
            outputs,
            pieces: Vec::new(),
            joints: Vec::new(),
            moving: None,
            half_base_m,
            g_m_s2: frame.g_m_s2,
            force_scale: frame.force_scale,
            moment_scale: frame.moment_scale,
            frame: Some(frame),
        }
    }

    /// Half the width of the base each moving block turns on (a column's foot in a trilith).
    pub(super) fn pivot_half_base_m(&self) -> f64 {
        self.half_base_m
    }

    /// Every joint of the column, the one the body moves on too, bottom first (none for a
    /// trilith).
    pub(super) fn all_joints(&self) -> Vec<&Held> {
        let mut all: Vec<&Held> = self.joints.iter().chain(&self.moving).collect();
        all.sort_by_key(|j| j.upper);
        all
    }

    /// Whether it watches a trilith.
    pub fn is_frame(&self) -> bool {
        self.frame.is_some()
    }

    /// The condition a new mode of the body breaks, if the watched blocks cannot follow it.
    pub(crate) fn forbids(&self, mode: Mode) -> Option<usize> {
        self.frame.as_ref().and_then(|f| f.forbids(mode))
    }

    /// Whether the column holds no joint (its body stands alone on the ground or a fixed
    /// block): nothing but the body's own base takes its impulses, and it may leave that base
    /// as a body standing alone does.
    pub(crate) fn holds_nothing(&self) -> bool {
        self.frame.is_none() && self.joints.is_empty()
    }

    /// The contacts a landing strikes at once, when more than the body's own corner (a
    /// trilith's feet and lintel).
    pub(crate) fn landing_contacts(&self) -> Option<String> {
        self.frame.as_ref().map(Frame::landing_contacts)
    }

    /// The held joint, how it gives way and the block on it (index in the column, bottom
    /// first), for the condition `k` of [`Watch::conditions`].
    pub(crate) fn describe(&self, k: usize) -> (String, &'static str, usize) {
        if let Some(frame) = &self.frame {
            return frame.describe(k);
        }
        let joint = &self.joints[k / 4];
        (joint.name.clone(), HOW[k % 4], joint.upper)
    }

    /// The stack that slides where condition `k` falls, if it is a slip of a held joint below
    /// the body: the blocks from the one on that joint up to the body's, moving as one
    /// (`u_start_m`: the body's u now).
    pub(crate) fn stack_on(&self, k: usize, u_start_m: f64) -> Option<Stack> {
        if self.frame.is_some() || k % 4 >= 2 {
            return None;
        }
        let joint = self.joints.get(k / 4).filter(|j| !j.inside)?;
        let held = self.pieces[joint.upper..].iter().filter(|p| !p.moving);
        Some(Stack {
            joint: k / 4,
            first: joint.upper,
            mass_kg: held.map(|p| p.mass_kg).sum(),
            friction: joint.friction,
            // Condition 4 j slips the block on the joint towards -x, 4 j + 1 towards +x.
            slip: if k.is_multiple_of(4) {
                Slip::Backward
            } else {
                Slip::Forward
            },
            u_start_m,
            apart: None,
        })
    }

    /// The slip conditions (numbered as [`Watch::conditions`] numbers them) of the held joints
    /// under the column's blocks `blocks` (bottom first): each joint's two, towards -x and
    /// towards +x.
    pub(crate) fn slips_under(
        &self,
        blocks: std::ops::Range<usize>,
    ) -> impl Iterator<Item = usize> + '_ {
        (self.joints.iter().enumerate())
            .filter(move |(_, joint)| !joint.inside && blocks.contains(&joint.upper))
            .flat_map(|(j, _)| [4 * j, 4 * j + 1])
    }

    /// The column's held blocks (indices in the column, bottom first).
    pub(crate) fn held_blocks(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.pieces.len()).filter(|&p| !self.pieces[p].moving)
    }

    /// The held joints' conditions along a trajectory of the body: each series must stay
    /// non-negative, with guard `Guard::Held` naming it. Held blocks stand where `shift` has
    /// them; the joint a stack slides on keeps its two tipping conditions (its slip is the
    /// stack's own).
    pub(crate) fn conditions(
        &self,
        traj: &Trajectory,
        inputs: &Inputs,
        shift: &Displaced,
    ) -> Vec<Constraint> {
        if let Some(frame) = &self.frame {
            return frame.conditions(traj, inputs);
        }
        if self.joints.is_empty() {
            return Vec::new();
        }
        let s = traj.mode.pivot().map_or(0.0, Corner::sign);
        let (mut sin, mut cos) = (ZERO, ZERO);
        for k in 0..=ORDER {
            sin_cos_at(&traj.theta, &mut sin, &mut cos, k);
        }
        let alpha = derivative(&traj.omega);
        let w2 = product(&traj.omega, &traj.omega);
        let mut base_acc = derivative(&traj.v);
        add_to(&mut base_acc, &inputs.accel, 1.0);

        let pivot_x = plus(&traj.u, s * self.half_base_m);
        // Where a point of the body that lies at (x0, y0) at rest is now: the pivot (or the
        // base's middle) plus the turned offset (theta > 0 turns clockwise).
        let place = |x0: f64, y0: f64| -> (Coeffs, Coeffs) {
            let (rx0, ry0) = (x0 - s * self.half_base_m, y0);
            let mut rx = ZERO;
            let mut ry = ZERO;
            add_to(&mut rx, &cos, rx0);
            add_to(&mut rx, &sin, ry0);
            add_to(&mut ry, &sin, -rx0);
            add_to(&mut ry, &cos, ry0);
            (rx, ry)
        };
        // Each piece: position and absolute acceleration as series.
        let motion: Vec<Kinematics> = self
            .pieces
            .iter()
            .enumerate()
            .map(|(k, p)| {
                if !p.moving {
                    let (mut x, slides) = shift.block(k, traj);
                    x[0] += p.x0;
                    return Kinematics {
                        x,
                        y: constant(p.y0),
                        // A stack that moves on its own by its own acceleration.
                        ax: match (slides, shift.acceleration(k, traj, inputs)) {
                            (true, Some(acc)) => acc,
                            (true, None) => base_acc,
                            (false, _) => inputs.accel,
                        },
                        ay: ZERO,
                    };
                }
                let (rx, ry) = place(p.x0, p.y0);
                let mut ax = base_acc;
                add_to(&mut ax, &product(&alpha, &ry), 1.0);
                add_to(&mut ax, &product(&w2, &rx), -1.0);
                let mut ay = product(&alpha, &rx);
                ay.iter_mut().for_each(|c| *c = -*c);
                add_to(&mut ay, &product(&w2, &ry), -1.0);
                let mut x = pivot_x;
                add_to(&mut x, &rx, 1.0);
                Kinematics { x, y: ry, ax, ay }
            })
            .collect();
        let mut glam = inputs.lambda;
        glam.iter_mut().for_each(|c| *c *= self.g_m_s2);
        let mut out = Vec::with_capacity(4 * self.joints.len());
        for (j, joint) in self.joints.iter().enumerate() {
            let (mut h, mut v) = (ZERO, ZERO);
            for &i in &joint.above {
                let (p, k) = (&self.pieces[i], &motion[i]);
                add_to(&mut h, &k.ax, p.mass_kg);
                add_to(&mut v, &glam, p.mass_kg);
                add_to(&mut v, &k.ay, p.mass_kg);
            }
            let ends = joint.ends.map(|(x0, y0)| {
                if joint.inside {
                    let (rx, ry) = place(x0, y0);
                    let mut x = pivot_x;
                    add_to(&mut x, &rx, 1.0);
                    (x, ry)
                } else {
                    // The contact moves with the block on it.
                    let (mut x, _) = shift.block(joint.upper, traj);
                    x[0] += x0;
                    (x, constant(y0))
                }
            });
            // Moments about each end of the forces the joint passes up: the d'Alembert
            // balance of the pieces above, m g lambda (x - E_x) + m ((x - E_x) a_y - (y - E_y)
            // a_x) - I theta'' for each (theta'' only for the body's pieces).
            let moments = ends.map(|(ex, ey)| {
                let mut m = ZERO;
                for &i in &joint.above {
                    let (p, k) = (&self.pieces[i], &motion[i]);
                    let mut dx = k.x;
                    add_to(&mut dx, &ex, -1.0);
                    let mut dy = k.y;
                    add_to(&mut dy, &ey, -1.0);
                    let mut ay = k.ay;
                    add_to(&mut ay, &glam, 1.0);
                    add_to(&mut m, &product(&dx, &ay), p.mass_kg);
                    add_to(&mut m, &product(&dy, &k.ax), -p.mass_kg);
                    if p.moving {
                        add_to(&mut m, &alpha, -p.inertia_kg_m2);
                    }
                }
                m
            });
            // Normal and tangential components on the joint's own (turned) faces.
            let (n, t) = if joint.inside {
                let mut n = product(&h, &sin);
                add_to(&mut n, &product(&v, &cos), 1.0);
                let mut t = product(&h, &cos);
                add_to(&mut t, &product(&v, &sin), -1.0);
                (n, t)
            } else {
                (v, h)
            };
            let mu = joint.friction;
            let mut forward = ZERO;
            add_to(&mut forward, &n, mu);
            let mut backward = forward;
            add_to(&mut forward, &t, -1.0);
            add_to(&mut backward, &t, 1.0);
            let mut right = moments[1];
            right.iter_mut().for_each(|c| *c = -*c);
            let series = [forward, backward, moments[0], right];
            let slides = shift.slides_on(j);
            for (c, series) in series
                .into_iter()
                .enumerate()
                .skip(if slides { 2 } else { 0 })
            {
                let scale = if c < 2 {
                    self.force_scale
                } else {
                    self.moment_scale
                };
                out.push(Constraint {
                    series,
                    scale,
                    guard: Guard::Held(4 * j + c),
                    strict: false,
                });
            }
        }
        out
    }

    /// The first held joint's condition that the impulses of a landing break, if any: every
    /// piece's velocity jumps from `before` (pivot, angular velocity, pivot slip velocity) to
    /// `after` (the new pivot or none, and the same), at theta = 0, with the body displaced
    /// by `u`, and the blocks of sliding stacks from their velocities in `shift` to those in
    /// `shifted` (the stacks after the landing). The impulses passed through a held joint must
    /// lie in its friction cone and their resultant within its contact, as the forces must
    /// between events.
    pub(crate) fn landing(
        &self,
        u: f64,
        before: Velocity,
        after: Velocity,
        shift: &Displaced,
        shifted: &Displaced,
    ) -> Option<usize> {
        if let Some(frame) = &self.frame {
            return frame.landing(before, after);
        }
        // Ties are measured against the largest impulse the landing could pass (N s) and its
        // moment over the column's height.
        let height = self.moment_scale / self.force_scale;
        let mass: f64 = self.pieces.iter().map(|p| p.mass_kg).sum();
        let impulse =
            mass * ((before.1.abs() + after.1.abs()) * height + before.2.abs() + after.2.abs());
        let tol = [1.0, 1.0, height, height].map(|k| TIE * impulse * k);
        self.joints.iter().enumerate().find_map(|(j, joint)| {
            let margins = self.impulse_margins(joint, u, (before, after), (shift, shifted));
            // The joint a stack slides on keeps its tipping conditions alone.
            let slides = shift.slides_on(j);
            (if slides { 2 } else { 0 }..4)
                .find(|&c| margins[c] < -tol[c])
                .map(|c| 4 * j + c)
        })
    }

    /// What a joint has to spare through a landing, as [`Watch::conditions`] orders them:
    /// mu J_n -+ J_t and the moments of the impulses about its two ends.
    fn impulse_margins(
        &self,
        joint: &Held,
        u: f64,
        (before, after): (Velocity, Velocity),
        (shift, shifted): (&Displaced, &Displaced),
    ) -> [f64; 4] {
        let velocity = |(pivot, omega, v): Velocity, p: &Piece| {
            let s = pivot.map_or(0.0, Corner::sign);
            (v + omega * p.y0, -omega * (p.x0 - s * self.half_base_m))
        };
        let spin = after.1 - before.1;
        let (mut jx, mut jy) = (0.0, 0.0);
        let mut moments = [0.0; 2];
        let ends = joint.ends.map(|(ex, ey)| {
            let moved = if joint.inside {
                u
            } else {
                shift.at(joint.upper, u)
            };
            (ex + moved, ey)
        });
        for &i in &joint.above {
            let p = &self.pieces[i];
            // The body's blocks jump with its velocities; a sliding stack's with the stack's.
            let (dvx, dvy, turn, x) = if p.moving {
                let (a, b) = (velocity(after, p), velocity(before, p));
                (a.0 - b.0, a.1 - b.1, spin, p.x0 + u)
            } else if shift.slides(i) {
                let jump = shifted.velocity_m_s(i, after.2) - shift.velocity_m_s(i, before.2);
                (jump, 0.0, 0.0, p.x0 + shift.at(i, u))
            } else {
                continue;
            };
            jx += p.mass_kg * dvx;
            jy += p.mass_kg * dvy;
            for (m, &(ex, ey)) in moments.iter_mut().zip(&ends) {
                *m += p.mass_kg * ((x - ex) * dvy - (p.y0 - ey) * dvx) - p.inertia_kg_m2 * turn;
            }
        }
        let mu = joint.friction;
        [mu * jy - jx, mu * jy + jx, moments[0], -moments[1]]
    }
}

/// A piece's position and absolute acceleration, as series.
struct Kinematics {
    x: Coeffs,
    y: Coeffs,
    ax: Coeffs,
    ay: Coeffs,
}

/// A block of a column: its mass and extent, exact.
struct Stacked {
    id: usize,
    mass: Q,
    x: Q,
    right: Q,
    bottom: Q,
    top: Q,
}

/// The columns of a wall, or why it is not made of columns: every movable block rests on one
/// block (or the ground) and carries at most one, touching no block beside it (blocks that
/// stand apart are watched, and their impacts resolved, by `clearance` and `collision`) but
/// for two blocks each alone in its column that touch face on face (seated face on face from
/// the start, `abutting`); the body of each column must have its centroid over the middle of
/// the contact it moves on (the rocking body's equations take it there). A trilith is one
/// column whose body is its frame ([`Trilith`](super::Trilith)).
pub fn columns(wall: &Wall, topo: &Topology) -> Result<Vec<Column>, SimulationError> {
    let not = |why: String| {
        SimulationError::NotApplicable(format!(
            "{why}: the exact rocking model runs walls whose movable blocks stand in free \
             columns (each on one block, carrying at most one, nothing touching it beside it \
             but, face on face, one other block alone in its column like it); \
             run this \
             wall's blocks with rotations on time stepping (--model slide-rock --method moreau \
             --dt S), sliding exactly (--model slide), or across its plane (--direction \
             out-of-plane)"
        ))
    };
    if let Some(t) = trilith(wall, topo)? {
        return Ok(vec![of_trilith(wall, t)]);
    }
    let movable = |b: usize| !wall.blocks[b].fixed;
    let touching = |b: usize| {
        (topo.sides[b].iter())
            .map(|v| &topo.vertical[v.0])
            .filter(|j| j.gap_m.is_zero())
            .map(move |j| if j.left.0 == b { j.right.0 } else { j.left.0 })
    };
    // Alone in its column: on the ground or a fixed block, carrying nothing.
    let alone = |b: usize| {
        topo.above[b].is_empty()
            && matches!(topo.below[b][..], [s] if match topo.horizontal[s.0].lower {
                Base::Ground => true,
                Base::Block(BlockId(l)) => !movable(l),
            })
    };
    let mut bottoms = Vec::new();
    for b in (0..wall.blocks.len()).filter(|&b| movable(b)) {
        let name = &wall.blocks[b].name;
        let beside: Vec<usize> = touching(b).collect();
        if let Some(&other) = beside.first() {
            let face_on_face = beside.len() == 1
                && movable(other)
                && touching(other).count() == 1
                && alone(b)
                && alone(other);
            if !face_on_face {
                return Err(not(format!(
                    "{name} touches {} beside it",
                    wall.blocks[other].name
                )));
            }
        }
        let [below] = topo.below[b] else {
            return Err(not(format!(
                "{name} rests on {} blocks",
                topo.below[b].len()
            )));
        };
        let above = &topo.above[b];
        if above.len() > 1 {
            return Err(not(format!("{name} carries {} blocks", above.len())));
        }
        if let Some(a) = above.first() {
            if !movable(topo.horizontal[a.0].upper.0) {
                return Err(not(format!("{name} carries an abutment")));
            }
        }
        let lower = topo.horizontal[below.0].lower;
        if matches!(lower, Base::Ground) || matches!(lower, Base::Block(BlockId(l)) if !movable(l))
        {
            bottoms.push(b);
        }
    }
    if bottoms.is_empty() {
        return Err(not(format!("{} has no movable block", wall.name)));
    }
    bottoms.into_iter().map(|b| column(wall, topo, b)).collect()
}

/// The first two movable blocks of a wall that touch face on face (their names), if any: the
/// columns the exact model takes seated side by side from the start ([`columns`]).
pub(super) fn face_on_face(wall: &Wall, topo: &Topology) -> Option<(String, String)> {
    (topo.vertical.iter())
        .filter(|j| j.gap_m.is_zero())
        .map(|j| [j.left.0, j.right.0])
        .find(|ends| ends.iter().all(|&b| !wall.blocks[b].fixed))
        .map(|[l, r]| (wall.blocks[l].name.clone(), wall.blocks[r].name.clone()))
}

/// A trilith as the column model runs it: one column whose body is its frame, every joint
/// watched by the frame.
fn of_trilith(wall: &Wall, t: Recognised) -> Column {
    let limits = t
        .limits
        .into_iter()
        .map(|(joint, slip_g, [left, right], moves)| JointLimit {
            joint,
            slip_g,
            tips_left_g: left,
            tips_right_g: right,
            moves,
        })
        .collect();
    let outputs = t
        .blocks
        .into_iter()
        .map(|(block, y0, turns)| Output {
            name: wall.blocks[block].name.clone(),
            block,
            x0: 0.0,
            y0,
            moving: true,
            turns,
        })
        .collect();
    Column {
        watch: Watch::of_frame(t.frame, outputs, t.half_base_m),
        body: t.body,
        limits,
        held: Vec::new(),
    }
}

/// The column standing on block `bottom`'s joint.
fn column(wall: &Wall, topo: &Topology, bottom: usize) -> Result<Column, SimulationError> {
    let mut stack = vec![bottom];
    while let Some(a) = topo.above[*stack.last().expect("a column has a block")].first() {
        stack.push(topo.horizontal[a.0].upper.0);
    }
    let blocks: Vec<Stacked> = stack
        .iter()
        .map(|&id| {
            let b = &wall.blocks[id];
            Stacked {
                id,
                mass: wall.mass_kg(id),
                x: b.x.clone(),
                right: b.right(),
                bottom: b.y.clone(),
                top: b.top(),
            }
        })
        .collect();
    let name = |i: usize| wall.blocks[blocks[i].id].name.clone();
    let base_name = |i: usize| -> String {
        let joint = topo.below[blocks[i].id][0];
        topo.base_name(wall, topo.horizontal[joint.0].lower)
            .to_string()
    };
    // Each joint's contact, the part above it (mass, centroid) and the ratio at which it gives
    // way: the smallest of its friction and its tipping ratios (x_G - x_l) / h, (x_r - x_G) / h.
    let two = Q::int(2);
    let mut best: Option<(usize, Q)> = None;
    let mut contacts = Vec::new();
    let mut centroids = Vec::new();
    let mut limits = Vec::new();
    for i in 0..blocks.len() {
        let joint = &topo.horizontal[topo.below[blocks[i].id][0].0];
        let (lo, hi) = match joint.lower {
            Base::Ground => (blocks[i].x.clone(), blocks[i].right.clone()),
            Base::Block(BlockId(l)) => {
                let under = &wall.blocks[l];
                (
                    blocks[i].x.clone().max(under.x.clone()),
                    blocks[i].right.clone().min(under.right()),
                )
            }
        };
        let part = &blocks[i..];
        let mass: Q = part.iter().map(|b| b.mass.clone()).sum();
        let xg: Q = part
            .iter()
            .map(|b| &b.mass * &(&b.x + &b.right) / &two)
            .sum::<Q>()
            / &mass;
        let yg: Q = part
            .iter()
            .map(|b| &b.mass * &(&b.bottom + &b.top) / &two)
            .sum::<Q>()
            / &mass;
        let h = &yg - &blocks[i].bottom;
        let (left, right) = ((&xg - &lo) / &h, (&hi - &xg) / &h);
        limits.push(JointLimit {
            joint: format!("{}/{}", name(i), base_name(i)),
            slip_g: joint.friction.to_f64(),
            tips_left_g: left.to_f64(),
            tips_right_g: right.to_f64(),
            moves: false,
        });
        let ratio = joint.friction.clone().min(left).min(right);
        if best.as_ref().is_none_or(|(_, r)| ratio < *r) {
            best = Some((i, ratio));
        }
        let corners = [lo == blocks[i].x, hi == blocks[i].right];
        contacts.push((lo, hi, joint.friction.to_f64(), corners));
        centroids.push((mass, xg, yg));
    }
    let (k, _) = best.expect("a column has a joint");
    limits[k].moves = true;
    let (lo, hi, friction, _) = contacts[k].clone();
    let (mass, xg, yg) = centroids[k].clone();
    let middle = (&lo + &hi) / &two;
    let names: Vec<String> = (k..blocks.len()).map(name).collect();
    let body_name = names.join("+");
    if xg != middle {
        return Err(SimulationError::NotApplicable(format!(
            "{body_name} moves on its joint with {} but its centroid (x = {} m) is not over the \
             middle of that contact (x = {} m): the exact rocking model takes bodies centred on \
             their base; run the wall on time stepping (--model slide-rock --method moreau --dt \
             S)",
            base_name(k),
            xg.to_f64(),
            middle.to_f64()
        )));
    }
    let level = blocks[k].bottom.clone();
    let (x_origin, y_origin) = (middle.to_f64(), level.to_f64());
    let pieces: Vec<Piece> = blocks
        .iter()
        .enumerate()
        .map(|(i, b)| {
            let (w, hgt) = ((&b.right - &b.x).to_f64(), (&b.top - &b.bottom).to_f64());
            let m = b.mass.to_f64();
            Piece {
                mass_kg: m,
                inertia_kg_m2: m * (w * w + hgt * hgt) / 12.0,
                x0: ((&b.x + &b.right) / &two).to_f64() - x_origin,
                y0: ((&b.bottom + &b.top) / &two).to_f64() - y_origin,
                moving: i >= k,
            }
        })
        .collect();
    let (xg_f, yg_f) = (xg.to_f64() - x_origin, yg.to_f64() - y_origin);
    let inertia: f64 = pieces[k..]
        .iter()
        .map(|p| {
            let d2 = (p.x0 - xg_f).powi(2) + (p.y0 - yg_f).powi(2);
            p.inertia_kg_m2 + p.mass_kg * d2
        })
        .sum();
    let g = wall.g_m_s2.to_f64();
    let body = RockingBody {
        name: body_name,
        mass_kg: mass.to_f64(),
        inertia_kg_m2: inertia,
        half_base_m: ((&hi - &lo) / &two).to_f64(),
        centroid_height_m: yg_f,
        friction,
        restitution_factor: wall.rocking_restitution_factor,
        g_m_s2: g,
    };
    let joint = |i: usize| {
        let (lo, hi, friction, upper_corner) = &contacts[i];
        let y = blocks[i].bottom.to_f64() - y_origin;
        Held {
            name: format!("{}/{}", name(i), base_name(i)),
            upper: i,
            friction: *friction,
            ends: [(lo.to_f64() - x_origin, y), (hi.to_f64() - x_origin, y)],
            inside: i > k,
            above: (i..blocks.len()).collect(),
            upper_corner: *upper_corner,
        }
    };
    let joints = (0..blocks.len()).filter(|&i| i != k).map(&joint).collect();
    let total: f64 = pieces.iter().map(|p| p.mass_kg).sum();
    let height = (&blocks[blocks.len() - 1].top - &blocks[0].bottom).to_f64();
    let outputs = (0..blocks.len())
        .map(|i| {
            let b = &blocks[i];
            Output {
                name: name(i),
                block: b.id,
                x0: ((&b.x + &b.right) / &two).to_f64() - x_origin,
                y0: b.bottom.to_f64() - y_origin,
                moving: i >= k,
                turns: true,
            }
        })
        .collect();
    Ok(Column {
        watch: Watch {
            base: base_name(k),
            outputs,
            pieces,
            joints,
            moving: Some(joint(k)),
            half_base_m: body.half_base_m,
            g_m_s2: g,
            force_scale: total * g,
            moment_scale: total * g * height,
            frame: None,
        },
        held: (0..k).map(name).collect(),
        body,
        limits,
    })
}

#[cfg(test)]
#[path = "column_tests.rs"]
mod tests;
