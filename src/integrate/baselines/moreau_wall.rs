//! Moreau-Jean time stepping of a whole wall with rotations, the scheme of LMGC90 and Siconos:
//! three degrees of freedom per free block (its centroid's x and y, its rotation), and
//! unilateral point-on-face contacts at the corners of every joint the graph knows, measured on
//! the moved and rotated blocks (a corner counts while it lies on the face it rests on or looks
//! at). Horizontal joints carry Coulomb friction and land plastically (Newton's e = 0, which
//! with friction holding is Housner's landing); vertical joints are frictionless and restitute
//! with the wall's e, as in the sliding model. At each step the impulses of the contacts
//! predicted closed solve the contact laws at velocity level, by projected Gauss-Seidel (rigid
//! contacts) or by Newton's method on the whole wall (stiff contacts, `wall_newton.rs`), the
//! velocities jump by them, and positions follow by the midpoint rule. Nothing is decided
//! exactly and every block carries three degrees of freedom at all times: it is the reference
//! the exact rocking engine converges to (a free-standing block, a wall of columns) and the
//! fallback for walls whose blocks may rock beyond it (docs/rocking-walls.md).

use super::release::released;
use super::set_down::{calm, set_down, SEATED_M, SEATED_STEPS};
use super::wall_dual::WallDual;
use super::wall_newton::{Contact, Part, Stall, StepProblem, WallNewton, COMPLIANCE};
use crate::error::SimulationError;
use crate::integrate::event::HandOff;
use crate::integrate::stepping::{lerp, outputs_in_step, time_step};
use crate::integrate::{AfterCollapse, Integrator, Scenario};
use crate::response::{Collapse, CollapseCause, EventKind, ModelUsed, Recorder, Response, Warning};
use crate::topology::{Base, JointRef, VerticalId};
use nalgebra::{Matrix2, Vector2, Vector3};

/// Per block: u of the base's middle (m), its velocity (m/s), theta (rad, clockwise positive),
/// omega (rad/s), w of the base's middle (m): what a history row holds.
type Outputs = (Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>, Vec<f64>);

/// Blocks named in the warning on unconverged steps: the few where Gauss-Seidel struggles.
const FASTEST_LISTED: usize = 3;

/// A block lifts (for the summary's uplift time) when its rotation moves a corner by this much
/// (m): Gauss-Seidel leaves rotations of round-off size on blocks that stay seated.
const UPLIFT_M: f64 = 1e-6;

/// Approach speed above which a vertical joint's closing counts as an impact (m/s), as in the
/// sliding Moreau-Jean model.
const IMPACT_SPEED_M_S: f64 = 1e-9;

/// A corner counts as on a face up to this fraction of the face's length beyond its ends, so
/// that corners of blocks whose edges line up are not lost to round-off.
const ON_FACE: f64 = 1e-9;

/// A contact whose gap, predicted at mid-step, is at most this (m) takes part in the step: the
/// faces of blocks stacked at rest meet in exact rationals but their float positions can leave
/// them 1e-16 m apart, and a block whose supports all looked open by that much would fall
/// freely for a step and land on them, a transient that Gauss-Seidel then spends thousands of
/// sweeps on.
const TOUCH_M: f64 = 1e-12;

/// Steps between two reports of the time reached. A request to stop is looked at every step:
/// a step of a wall of a thousand blocks takes 20 ms, and a step Gauss-Seidel takes over a
/// second, so 1,024 of them kept Ctrl-C waiting for minutes.
const PROGRESS_STEPS: u64 = 1024;

/// The `method` of a run the exact sliding engine handed over at its first uplift.
pub const HANDED_OFF: &str = "event+moreau";

/// Moreau-Jean with rotations, on a wall of any number of blocks.
#[derive(Debug, Clone)]
pub struct MoreauWall {
    /// Time step (s).
    pub dt_s: f64,
    /// How each step's contact problem is solved.
    pub solver: ContactSolver,
    /// Gauss-Seidel stops when no block's velocity (its corners' for the rotation) changes in a
    /// sweep by more than this fraction of g times the step.
    pub tolerance: f64,
    /// Gauss-Seidel sweeps allowed per step; steps that need more are counted in a warning.
    pub max_sweeps: usize,
    /// Newton's method on the whole wall stops when no block's velocity changes by more than
    /// this fraction of g times the step: 1e-10 by default, above the round-off of its stiff
    /// systems (about 1e-12), below the error its compliance itself makes (1e-8, `wall_newton.rs`).
    pub newton_tolerance: f64,
    /// A block released from a rotation (rad, clockwise positive): in a wall of one column the
    /// column's moving body, turned about the end of its base on that side; in any other wall
    /// the block with the blocks resting on it alone, turned as one (`release.rs`).
    pub initial_rotation: Option<(String, f64)>,
}

impl MoreauWall {
    /// Moreau-Jean with rotations, step dt, the usual settings, from rest.
    pub fn new(dt_s: f64) -> MoreauWall {
        MoreauWall {
            dt_s,
            solver: ContactSolver::GaussSeidel,
            tolerance: 1e-12,
            max_sweeps: 10_000,
            newton_tolerance: 1e-10,
            initial_rotation: None,
        }
    }
}

/// How the contact problem of a step is solved.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum ContactSolver {
    /// Projected Gauss-Seidel over the contacts, rigid: where a block rests on two others the
    /// split of its load is whichever the sweeps reach (docs/rocking-walls.md).
    #[default]
    GaussSeidel,
    /// Newton's method on every block's velocity at once, each contact stiff (the split of a
    /// block on two others that of springs of one stiffness per metre of joint): many times
    /// faster on tall walls.
    Newton,
}

/// A face of a block, by its outward normal in the block's own frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Face {
    Top,
    Bottom,
    Left,
    Right,
}

impl Face {
    fn normal(self) -> Vector2<f64> {
        match self {
            Face::Top => Vector2::new(0.0, 1.0),
            Face::Bottom => Vector2::new(0.0, -1.0),
            Face::Left => Vector2::new(-1.0, 0.0),
            Face::Right => Vector2::new(1.0, 0.0),
        }
    }
}

/// A block as a rigid body: at rest its centroid is at `rest`.
struct Body {
    mass: f64,
    inertia: f64,
    half: Vector2<f64>,
    rest: Vector2<f64>,
    free: bool,
}

/// Rotation by phi (counter-clockwise) of v.
fn rotate(phi: f64, v: Vector2<f64>) -> Vector2<f64> {
    let (s, c) = phi.sin_cos();
    Vector2::new(c * v.x - s * v.y, s * v.x + c * v.y)
}

/// A possible contact: the corner `corner` (signs of its offset from the centroid) of block
/// `point` against face `face` of block `on` (`None`: the ground, the line y = 0).
struct Candidate {
    point: usize,
    corner: Vector2<f64>,
    on: Option<usize>,
    face: Face,
    friction: f64,
    restitution: f64,
    joint: JointRef,
    /// The length of the joint's contact (m): each corner stands for half of it.
    length_m: f64,
    /// Counts only strictly inside the face: the corner at an end of it is the other block's
    /// candidate already (edges that line up), and one contact twice would make the contact
    /// problem degenerate.
    strict: bool,
}

/// Where a candidate stands this step: its gap, and the rows of its (normal, tangential)
/// relative velocity for the corner's block and the face's block.
struct Geometry {
    gap: f64,
    point_row: [Vector3<f64>; 2],
    on_row: Option<[Vector3<f64>; 2]>,
}

impl Geometry {
    /// The contact's (normal, tangential) relative velocity when the blocks move at `v`.
    fn velocity(&self, c: &Candidate, v: &[Vector3<f64>]) -> Vector2<f64> {
        let rows = |r: &[Vector3<f64>; 2], w: &Vector3<f64>| Vector2::new(r[0].dot(w), r[1].dot(w));
        let mut u = rows(&self.point_row, &v[c.point]);
        if let (Some(f), Some(r)) = (c.on, &self.on_row) {
            u += rows(r, &v[f]);
        }
        u
    }
}

/// The rows of a point's velocity along n and t for a body whose centroid is r away.
fn rows(n: Vector2<f64>, t: Vector2<f64>, r: Vector2<f64>) -> [Vector3<f64>; 2] {
    let row = |d: Vector2<f64>| Vector3::new(d.x, d.y, r.x * d.y - r.y * d.x);
    [row(n), row(t)]
}

/// A candidate on the moved blocks (`q`: each block's centroid displacement and rotation), or
/// `None` when its corner is off the face.
fn geometry(c: &Candidate, bodies: &[Body], q: &[Vector3<f64>]) -> Option<Geometry> {
    let centre = |i: usize| bodies[i].rest + q[i].xy();
    let p_body = &bodies[c.point];
    let p = centre(c.point) + rotate(q[c.point].z, c.corner.component_mul(&p_body.half));
    let (n, t, face_point, half_length, on_row) = match c.on {
        None => (
            Vector2::new(0.0, 1.0),
            Vector2::new(1.0, 0.0),
            p.x * Vector2::x(),
            f64::INFINITY,
            None,
        ),
        Some(f) => {
            let (body, phi) = (&bodies[f], q[f].z);
            let n = rotate(phi, c.face.normal());
            let t = Vector2::new(n.y, -n.x);
            let local = c.face.normal().component_mul(&body.half);
            let face_point = centre(f) + rotate(phi, local);
            let along = Vector2::new(c.face.normal().y, -c.face.normal().x);
            let half_length = along.component_mul(&body.half).abs().sum();
            let r = p - centre(f);
            (
                n,
                t,
                face_point,
                half_length,
                Some(rows(n, t, r).map(|row| -row)),
            )
        }
    };
    let s = (p - face_point).dot(&t);
    let reach = if c.strict {
        1.0 - ON_FACE
    } else {
        1.0 + ON_FACE
    };
    if s.abs() > half_length * reach {
        return None;
    }
    Some(Geometry {
        gap: (p - face_point).dot(&n),
        point_row: rows(n, t, p - centre(c.point)),
        on_row,
    })
}

/// The candidates of a wall: the corners at the ends of every horizontal joint (the upper
/// block's on the lower's top, the lower's on the upper's bottom) and of every vertical joint
/// (each block's corners on the other's face).
fn candidates(sc: &Scenario) -> Vec<Candidate> {
    let (topo, e) = (sc.topology, sc.wall.restitution.to_f64());
    let mut out = Vec::new();
    for (k, j) in topo.horizontal.iter().enumerate() {
        let (upper, mu, length_m) = (j.upper.0, j.friction.to_f64(), j.overlap_m.to_f64());
        let joint = JointRef::Horizontal(crate::topology::HorizontalId(k));
        let lower = match j.lower {
            Base::Ground => None,
            Base::Block(b) => Some(b.0),
        };
        for sx in [-1.0, 1.0] {
            out.push(Candidate {
                point: upper,
                corner: Vector2::new(sx, -1.0),
                on: lower,
                face: Face::Top,
                friction: mu,
                restitution: 0.0,
                joint,
                length_m,
                strict: false,
            });
            if let Some(l) = lower {
                out.push(Candidate {
                    point: l,
                    corner: Vector2::new(sx, 1.0),
                    on: Some(upper),
                    face: Face::Bottom,
                    friction: mu,
                    restitution: 0.0,
                    joint,
                    length_m,
                    strict: true,
                });
            }
        }
    }
    for (k, j) in topo.vertical.iter().enumerate() {
        let joint = JointRef::Vertical(VerticalId(k));
        let length_m = j.height_m.to_f64();
        for sy in [-1.0, 1.0] {
            for (point, corner, on, face, strict) in [
                (
                    j.left.0,
                    Vector2::new(1.0, sy),
                    j.right.0,
                    Face::Left,
                    false,
                ),
                (
                    j.right.0,
                    Vector2::new(-1.0, sy),
                    j.left.0,
                    Face::Right,
                    true,
                ),
            ] {
                out.push(Candidate {
                    point,
                    corner,
                    on: Some(on),
                    face,
                    friction: 0.0,
                    restitution: e,
                    joint,
                    length_m,
                    strict,
                });
            }
        }
    }
    out
}

/// An active contact of one step: its candidate, geometry, Delassus block and the velocity
/// change one unit of impulse gives each of its two bodies.
struct Active {
    candidate: usize,
    geometry: Geometry,
    delassus: Matrix2<f64>,
    approach_m_s: f64,
}

impl Integrator for MoreauWall {
    fn method(&self) -> &'static str {
        "moreau"
    }

    fn run(&self, sc: &Scenario) -> Result<Response, SimulationError> {
        match self.stepped(sc, None, None)? {
            Stepped::Ended(r) => Ok(*r),
            Stepped::Seated(_) => Err(SimulationError::Bug(
                "a stepper not asked to set the wall down did".into(),
            )),
        }
    }
}

impl MoreauWall {
    /// Goes on from an uplift the exact sliding run found: its blocks where the sliding model
    /// had them, seated and unturned, with its velocities, recorder and energy terms; to the
    /// end, or, `until_seated`, until every block is seated again and calm
    /// ([`set_down::SEATED_STEPS`] steps in a row) and the check given keeps the wall set down
    /// there seated, where it sets the wall down.
    pub(crate) fn run_from(
        &self,
        sc: &Scenario,
        start: HandOff,
        until_seated: Option<KeepsSeated>,
    ) -> Result<Stepped, SimulationError> {
        self.stepped(sc, Some(start), until_seated)
    }

    /// Steps from rest at t = 0 (a released block turned), or from `start`.
    fn stepped(
        &self,
        sc: &Scenario,
        start: Option<HandOff>,
        until_seated: Option<KeepsSeated>,
    ) -> Result<Stepped, SimulationError> {
        let dt = self.dt_s;
        time_step(sc, dt)?;
        let (wall, topo, settings) = (sc.wall, sc.topology, sc.settings);
        let g = wall.g_m_s2.to_f64();
        let bodies: Vec<Body> = wall
            .blocks
            .iter()
            .zip(&topo.blocks)
            .map(|(b, data)| {
                let (w, h) = (b.width.to_f64(), b.height.to_f64());
                let mass = data.mass_kg.to_f64();
                Body {
                    mass,
                    inertia: mass * (w * w + h * h) / 12.0,
                    half: Vector2::new(0.5 * w, 0.5 * h),
                    rest: Vector2::new(b.x.to_f64() + 0.5 * w, b.y.to_f64() + 0.5 * h),
                    free: !b.fixed,
                }
            })
            .collect();
        let n = bodies.len();
        let candidates = candidates(sc);
        let (handed, t0) = (start.is_some(), start.as_ref().map_or(0.0, |h| h.t_s));
        let (mut q, mut v) = (
            vec![Vector3::<f64>::zeros(); n],
            vec![Vector3::<f64>::zeros(); n],
        );
        let mut gone = vec![false; n];
        // The energy terms at the start, for the balance of the steps (friction and landings).
        let mut before = Before::default();
        let mut next_output = 1;
        let mut rec = match start {
            Some(h) => {
                // The model before wrote the rows up to the hand-off and one at it.
                next_output = h.next_output;
                for i in 0..n {
                    q[i].x = h.u_m[i];
                    v[i].x = h.v_m_s[i];
                }
                for (i, t) in h.turned.iter().enumerate() {
                    (q[i].y, q[i].z) = (t.rise_m, t.phi_rad);
                    (v[i].y, v[i].z) = (t.rise_m_s, t.omega_rad_s);
                }
                gone = h.fallen;
                before = Before {
                    mechanical_j: h.mechanical_j,
                    input_j: h.rec.energy.input_j,
                    fallen_j: h.rec.energy.fallen_j,
                    friction_j: h.rec.energy.friction_j,
                };
                h.rec
            }
            None => Recorder::new(wall, topo, settings.history_to(), settings.events_to()),
        };
        let on_several: Vec<String> = (0..n)
            .filter(|&i| {
                topo.horizontal
                    .iter()
                    .filter(|j| j.upper.0 == i && matches!(j.lower, Base::Block(_)))
                    .count()
                    > 1
            })
            .map(|i| wall.blocks[i].name.clone())
            .collect();
        let warned = |w: &Warning| matches!(w, Warning::IndeterminateSupport { .. });
        if !on_several.is_empty() && !rec.warnings.iter().any(warned) {
            rec.warnings.push(Warning::IndeterminateSupport {
                count: on_several.len(),
                blocks: on_several.into_iter().take(5).collect(),
                elastic: self.solver == ContactSolver::Newton,
            });
        }
        if let Some((name, theta)) = &self.initial_rotation {
            for (i, moved) in released(wall, topo, name, *theta)? {
                q[i] = moved;
            }
        }
        let moves = |i: usize, gone: &[bool]| bodies[i].free && !gone[i];
        let energy_of = |i: usize, q: &[Vector3<f64>], v: &[Vector3<f64>]| {
            let b = &bodies[i];
            0.5 * b.mass * (v[i].x * v[i].x + v[i].y * v[i].y)
                + 0.5 * b.inertia * v[i].z * v[i].z
                + b.mass * g * q[i].y
        };
        if self.initial_rotation.is_some() {
            // A released body starts with the potential energy of its raised blocks.
            rec.energy.initial_j = (0..n).map(|i| energy_of(i, &q, &v)).sum();
        }
        // The base centre's horizontal displacement and velocity (what the sliding model calls
        // u), the rotation clockwise positive as the exact rocking engine writes it, and the
        // base centre's vertical displacement.
        let outputs = |q: &[Vector3<f64>], v: &[Vector3<f64>]| {
            let mut u = Vec::with_capacity(n);
            let mut uv = Vec::with_capacity(n);
            let mut w = Vec::with_capacity(n);
            for i in 0..n {
                let h = bodies[i].half.y;
                u.push(q[i].x + h * q[i].z.sin());
                uv.push(v[i].x + h * q[i].z.cos() * v[i].z);
                w.push(q[i].y + h * (1.0 - q[i].z.cos()));
            }
            let theta: Vec<f64> = q.iter().map(|s| -s.z).collect();
            let omega: Vec<f64> = v.iter().map(|s| -s.z).collect();
            (u, uv, theta, omega, w)
        };
        // Extremes at every step; history rows at the output times, between steps by linear
        // interpolation (as every time stepper writes them), and at a fall.
        let extremes = |rec: &mut Recorder, out: &Outputs| {
            let (u, uv, theta, _, _) = out;
            for i in 0..n {
                rec.block_extremes(i, u[i].abs(), uv[i].abs());
                rec.rotation_extreme(i, theta[i].abs());
            }
            rec.joint_extremes(u);
        };
        // Overturned, or dropped by half its height: block i left what carried it at t (the
        // first to fall is the collapse).
        let falls = |rec: &mut Recorder,
                     gone: &mut [bool],
                     i: usize,
                     t: f64,
                     q: &[Vector3<f64>],
                     v: &[Vector3<f64>]| {
            let b = &bodies[i];
            if q[i].z.abs() < std::f64::consts::FRAC_PI_2 && q[i].y >= -b.half.y {
                return false;
            }
            let tipped = q[i].z.abs() >= b.half.x.atan2(b.half.y);
            rec.fell(i);
            rec.energy.fallen_j += energy_of(i, q, v);
            gone[i] = true;
            if rec.collapse.is_none() {
                rec.collapse = Some(Collapse {
                    time_s: t,
                    block: wall.blocks[i].name.clone(),
                    cause: if tipped {
                        CollapseCause::Overturning
                    } else {
                        CollapseCause::SlidingOff
                    },
                });
            }
            true
        };
        let mut previous = outputs(&q, &v);
        extremes(&mut rec, &previous);
        if !handed {
            let (u0, uv0, theta0, omega0, w0) = &previous;
            rec.sample_rotating(0.0, [u0, uv0, theta0, omega0, w0]);
        }
        // A state handed over may have left what carried it by this criterion already (the
        // model before has its own, a body turned to a right angle): it falls at the hand-off,
        // whatever the step, not at the end of the first.
        let mut fell_at_start = false;
        for i in 0..n {
            if handed && moves(i, &gone) {
                fell_at_start |= falls(&mut rec, &mut gone, i, t0, &q, &v);
            }
        }
        let steps = if fell_at_start && settings.after_collapse == AfterCollapse::Stop {
            0
        } else {
            ((settings.duration_s - t0) / dt).ceil() as u64
        };
        let at = |k: u64| t0 + k as f64 * dt;
        let scale = g * dt;
        let inv = |i: usize| {
            Vector3::new(
                1.0 / bodies[i].mass,
                1.0 / bodies[i].mass,
                1.0 / bodies[i].inertia,
            )
        };
        // Impulses of the last step, per candidate (warm start).
        let mut impulses = vec![Vector2::<f64>::zeros(); candidates.len()];
        let mut struggles = Struggles {
            fastest: vec![0; n],
            ..Struggles::default()
        };
        // Steps in a row with every block seated (`--after-uplift moreau-while-rocking`), and
        // the blocks that rocked since the start.
        let mut seated_steps = 0;
        let mut rocked = vec![false; n];
        let mut newton =
            (self.solver == ContactSolver::Newton).then(|| NewtonStep::new(&bodies, &candidates));
        let mut t = t0;
        for k in 1..=steps {
            let t_prev = t;
            if let Some(p) = &settings.progress {
                let go_on = if k % PROGRESS_STEPS == 0 {
                    p.at(t)
                } else {
                    !p.stop_requested()
                };
                if !go_on {
                    rec.interrupted_at_s = Some(t);
                    break;
                }
            }
            // After a hand-off the grid starts at the uplift, and its last step is cut to end at
            // the duration.
            let last = handed && k == steps;
            let h = if last {
                settings.duration_s - t_prev
            } else {
                dt
            };
            let t_mid = if last {
                t_prev + 0.5 * h
            } else {
                t0 + (k as f64 - 0.5) * dt
            };
            let seg = sc.motion.segment_at(t_mid);
            let s = t_mid - seg.t0;
            let (a, lambda) = (seg.accel(s), seg.lambda.0 + seg.lambda.1 * s);
            let v_start = v.clone();
            for (i, vi) in v.iter_mut().enumerate() {
                if moves(i, &gone) {
                    *vi += h * Vector3::new(-a, -g * lambda, 0.0);
                }
            }
            // The contacts predicted closed at mid-step, on the blocks where they were at its
            // start; the others lose their impulse.
            let mut active = Vec::new();
            // Some corner of a horizontal joint stands off its face.
            let mut open = false;
            for (ci, c) in candidates.iter().enumerate() {
                let live = |i: usize| !gone[i];
                let involved_move = moves(c.point, &gone) || c.on.is_some_and(|f| moves(f, &gone));
                let found = (live(c.point) && c.on.is_none_or(live) && involved_move)
                    .then(|| geometry(c, &bodies, &q))
                    .flatten();
                let Some(geometry) = found else {
                    impulses[ci] = Vector2::zeros();
                    continue;
                };
                open |= matches!(c.joint, JointRef::Horizontal(_)) && geometry.gap > SEATED_M;
                let before = geometry.velocity(c, &v_start);
                if geometry.gap + 0.5 * h * before.x > TOUCH_M {
                    impulses[ci] = Vector2::zeros();
                    continue;
                }
                let mut delassus = Matrix2::zeros();
                let mut add = |body: usize, r: &[Vector3<f64>; 2]| {
                    if moves(body, &gone) {
                        let m = inv(body);
                        for a in 0..2 {
                            for b in 0..2 {
                                delassus[(a, b)] += r[a].component_mul(&m).dot(&r[b]);
                            }
                        }
                    }
                };
                add(c.point, &geometry.point_row);
                if let (Some(f), Some(r)) = (c.on, &geometry.on_row) {
                    add(f, r);
                }
                active.push(Active {
                    candidate: ci,
                    geometry,
                    delassus,
                    approach_m_s: before.x,
                });
            }
            // Newton where asked; where it does not converge, its last iterate can be far off
            // (on the 976-block running bond such steps followed one another until blocks flew
            // off at km/s), so Gauss-Seidel solves that step instead, from the free velocities.
            let by_newton = newton.as_mut().is_some_and(|newton| {
                let solved = newton.solve(
                    &candidates,
                    &active,
                    |i| moves(i, &gone),
                    &v_start,
                    &mut v,
                    &mut impulses,
                    self.newton_tolerance * scale,
                );
                match solved {
                    Solved::InVelocities => {}
                    Solved::InImpulses => {
                        struggles.in_impulses += 1;
                        struggles.first_in_impulses.get_or_insert(at(k));
                    }
                    Solved::ByInteriorPoint => {
                        struggles.by_interior += 1;
                        struggles.first_by_interior.get_or_insert(at(k));
                    }
                    Solved::InteriorFirst => struggles.interior_first += 1,
                    Solved::Neither => {
                        struggles.fell_back += 1;
                        struggles.first_fell_back.get_or_insert(at(k));
                    }
                }
                solved != Solved::Neither
            });
            let converged = by_newton || {
                // Warm start: the last step's impulses of the contacts still active.
                let apply = |v: &mut [Vector3<f64>], act: &Active, p: Vector2<f64>| {
                    let c = &candidates[act.candidate];
                    if moves(c.point, &gone) {
                        let r = &act.geometry.point_row;
                        v[c.point] += (r[0] * p.x + r[1] * p.y).component_mul(&inv(c.point));
                    }
                    if let (Some(f), Some(r)) = (c.on, &act.geometry.on_row) {
                        if moves(f, &gone) {
                            v[f] += (r[0] * p.x + r[1] * p.y).component_mul(&inv(f));
                        }
                    }
                };
                for act in &active {
                    apply(&mut v, act, impulses[act.candidate]);
                }
                let mut converged = active.is_empty();
                let mut sweep_start = v.clone();
                let mut changing = None;
                for _ in 0..self.max_sweeps {
                    if converged {
                        break;
                    }
                    sweep_start.copy_from_slice(&v);
                    for act in &active {
                        let c = &candidates[act.candidate];
                        let u = act.geometry.velocity(c, &v);
                        let w = &act.delassus;
                        let p = impulses[act.candidate];
                        // Newton's law at velocity level (u_n after >= -e u_n before), then Coulomb
                        // with the new normal impulse.
                        let target = -c.restitution * act.approach_m_s.min(0.0);
                        let pn = (p.x - (u.x - target) / w[(0, 0)]).max(0.0);
                        let ut = u.y + w[(1, 0)] * (pn - p.x);
                        let pt = if c.friction > 0.0 {
                            (p.y - ut / w[(1, 1)]).clamp(-c.friction * pn, c.friction * pn)
                        } else {
                            0.0
                        };
                        let new = Vector2::new(pn, pt);
                        apply(&mut v, act, new - p);
                        impulses[act.candidate] = new;
                    }
                    // The blocks' velocities, not the impulses: those of redundant contacts (a
                    // block on two others, two corners at one point) may trade load among
                    // themselves without end once the velocities have converged.
                    let (block, change) = v
                        .iter()
                        .zip(&sweep_start)
                        .zip(&bodies)
                        .map(|((a, b), body)| {
                            let d = a - b;
                            d.x.abs().max(d.y.abs()).max(d.z.abs() * body.half.norm())
                        })
                        .enumerate()
                        .fold(
                            (0, 0.0),
                            |best, (i, c)| if c > best.1 { (i, c) } else { best },
                        );
                    changing = Some(block);
                    converged = change <= self.tolerance * scale;
                }
                if let (false, Some(block)) = (converged, changing) {
                    struggles.fastest[block] += 1;
                }
                converged
            };
            if !converged {
                struggles.unconverged += 1;
                struggles.first_unconverged.get_or_insert(at(k));
            }
            // A vertical joint whose faces met approaching (one impact, however many of its
            // corners took part).
            let mut struck: Vec<VerticalId> = Vec::new();
            for act in &active {
                let c = &candidates[act.candidate];
                if let JointRef::Vertical(j) = c.joint {
                    if act.approach_m_s < -IMPACT_SPEED_M_S
                        && impulses[act.candidate].x > 0.0
                        && !struck.contains(&j)
                    {
                        struck.push(j);
                    }
                }
            }
            for j in struck {
                let (l, r) = (topo.vertical[j.0].left.0, topo.vertical[j.0].right.0);
                rec.impact(t, j, [v_start[l].x, v_start[r].x], [v[l].x, v[r].x]);
            }
            for i in 0..n {
                if !moves(i, &gone) {
                    v[i] = Vector3::zeros();
                    continue;
                }
                let dq = 0.5 * h * (v_start[i] + v[i]);
                let m = bodies[i].mass;
                // Work of the ground's inertial force and of the vertical motion's extra weight.
                rec.energy.input_j += -m * a * dq.x - m * g * (lambda - 1.0) * dq.y;
                q[i] += dq;
            }
            t = if last { settings.duration_s } else { at(k) };
            rec.stats.steps += 1;
            let mut fell_now = false;
            for i in 0..n {
                if !moves(i, &gone) {
                    continue;
                }
                let b = &bodies[i];
                if q[i].z.abs() * b.half.x.max(b.half.y) > UPLIFT_M {
                    rec.uplift(i, t - h);
                    rocked[i] = true;
                }
                fell_now |= falls(&mut rec, &mut gone, i, t, &q, &v);
            }
            let now = outputs(&q, &v);
            extremes(&mut rec, &now);
            let mut last_row = None;
            if let Some(o) = settings.output_dt_s {
                outputs_in_step(&mut next_output, o, t_prev, t, |tk, f| {
                    let (a, b) = (&previous, &now);
                    rec.sample_rotating(
                        tk,
                        [
                            &lerp(&a.0, &b.0, f),
                            &lerp(&a.1, &b.1, f),
                            &lerp(&a.2, &b.2, f),
                            &lerp(&a.3, &b.3, f),
                            &lerp(&a.4, &b.4, f),
                        ],
                    );
                    last_row = Some(tk);
                });
            }
            if fell_now && last_row != Some(t) {
                rec.sample_rotating(t, [&now.0, &now.1, &now.2, &now.3, &now.4]);
            }
            previous = now;
            if fell_now && settings.after_collapse == AfterCollapse::Stop {
                break;
            }
            if let Some(keeps_seated) = until_seated.filter(|_| t < settings.duration_s) {
                // The step's mean velocities, which its positions moved at: at a closed contact
                // with e = 1 Moreau-Jean's velocities can flip sign at every step with the pose
                // frozen, and the flips cancel in the mean.
                let mean = |i: usize| 0.5 * (v_start[i] + v[i]);
                let calm_now = |i: usize| {
                    let b = &bodies[i];
                    calm(b.half, b.inertia / b.mass, q[i].z, &mean(i), g)
                };
                let all = !open && (0..n).all(|i| !moves(i, &gone) || calm_now(i));
                seated_steps = if all { seated_steps + 1 } else { 0 };
                if seated_steps >= SEATED_STEPS {
                    let live: Vec<bool> = (0..n).map(|i| moves(i, &gone)).collect();
                    let mean: Vec<Vector3<f64>> = (0..n).map(mean).collect();
                    let (_, mean_vx, ..) = outputs(&q, &mean);
                    let free: Vec<bool> = bodies.iter().map(|b| b.free).collect();
                    let (u, vx) = set_down(topo, &previous.0, &mean_vx, &free, &gone);
                    // Where the exact model would lift a block again at once, the rocking
                    // called calm is the ground's doing: stepping goes on, and asks again ten
                    // steps on.
                    if !keeps_seated((t, &u, &vx, &gone))? {
                        seated_steps = 0;
                        continue;
                    }
                    let kinetic_j: f64 = (0..n)
                        .filter(|&i| live[i])
                        .map(|i| 0.5 * bodies[i].mass * vx[i] * vx[i])
                        .sum();
                    // Setting down takes the rest of the rotation, the vertical motion and the
                    // velocities made one: with the contacts' share, as at the end.
                    rec.energy.friction_j = before.friction_after(&rec.energy, kinetic_j, 0.0);
                    struggles.report(&mut rec, wall, self.max_sweeps);
                    let rested: Vec<usize> = (0..n).filter(|&i| rocked[i] && !gone[i]).collect();
                    rec.event(t, EventKind::Rest, &rested, None, None);
                    return Ok(Stepped::Seated(Box::new(HandOff {
                        t_s: t,
                        u_m: u,
                        v_m_s: vx,
                        turned: Vec::new(),
                        fallen: gone,
                        mechanical_j: kinetic_j,
                        rec,
                        next_output,
                    })));
                }
            }
        }
        if let (Some(p), None) = (&settings.progress, rec.interrupted_at_s) {
            // The end reached: a bar shows it full (nothing is left to stop).
            p.at(t);
        }
        for i in (0..n).filter(|&i| moves(i, &gone)) {
            let b = &bodies[i];
            rec.energy.kinetic_j += 0.5 * b.mass * (v[i].x * v[i].x + v[i].y * v[i].y)
                + 0.5 * b.inertia * v[i].z * v[i].z;
            rec.energy.potential_j += b.mass * g * q[i].y;
        }
        // What the contacts took: the rest of the balance (friction and landings together,
        // which time stepping does not tell apart); after a hand-off, the rest of the steps'
        // balance added to what the sliding run lost, whose own balance stays as it closed.
        let e = &mut rec.energy;
        e.friction_j = if !handed {
            e.initial_j + e.input_j - e.kinetic_j - e.potential_j - e.fallen_j
        } else {
            before.friction_after(e, e.kinetic_j, e.potential_j)
        };
        struggles.report(&mut rec, wall, self.max_sweeps);
        let (u, uv, _, _, _) = outputs(&q, &v);
        let motion = sc.motion.describe();
        let method = if handed { HANDED_OFF } else { "moreau" };
        let mut r = rec.finish(method, &wall.name, motion, t, &u, &uv);
        r.summary.model = self.model_used("asked for (--model slide-rock --method moreau)");
        Ok(Stepped::Ended(Box::new(r)))
    }

    /// The model summary.json names for a run of this stepper, chosen for `why`.
    pub(crate) fn model_used(&self, why: &str) -> ModelUsed {
        ModelUsed {
            name: "slide-rock".into(),
            equations: Some(
                match self.solver {
                    ContactSolver::GaussSeidel => "moreau-jean",
                    ContactSolver::Newton => "moreau-jean-newton",
                }
                .into(),
            ),
            direction: "in-plane".into(),
            why: why.into(),
        }
    }
}

/// Whether the exact sliding model, set going at an instant (s) from blocks seated at these
/// displacements (m) with these velocities (m/s), the fallen ones gone, keeps every block seated
/// there: what a stepper asks before it sets a wall down.
pub(crate) type KeepsSeated<'a> =
    &'a dyn Fn((f64, &[f64], &[f64], &[bool])) -> Result<bool, SimulationError>;

/// How a stretch of stepping ended.
pub(crate) enum Stepped {
    /// At the run's end (or where it stopped): the answer.
    Ended(Box<Response>),
    /// Every block seated again and set down, for the exact sliding engine to go on.
    Seated(Box<HandOff>),
}

/// Where the contact solvers struggled: how many steps each way and when first, and which
/// block each unconverged step left changing fastest (counted per block): what the warnings
/// say of where.
#[derive(Default)]
struct Struggles {
    unconverged: u64,
    first_unconverged: Option<f64>,
    fastest: Vec<u64>,
    fell_back: u64,
    first_fell_back: Option<f64>,
    in_impulses: u64,
    first_in_impulses: Option<f64>,
    by_interior: u64,
    first_by_interior: Option<f64>,
    interior_first: u64,
}

impl Struggles {
    /// Counts the unconverged steps and warns of each struggle, into the warnings of an
    /// earlier stretch of the run where it left one of the kind (a run handed back and forth
    /// between models steps in stretches).
    fn report(self, rec: &mut Recorder, wall: &crate::wall::Wall, max_sweeps: usize) {
        rec.stats.unconverged_steps += self.unconverged;
        let mut warnings = Vec::new();
        if let Some(first_s) = self.first_unconverged {
            let blocks: Vec<(String, u64)> = (0..self.fastest.len())
                .filter(|&i| self.fastest[i] > 0)
                .map(|i| (wall.blocks[i].name.clone(), self.fastest[i]))
                .collect();
            warnings.push(Warning::Unconverged {
                steps: self.unconverged,
                sweeps: max_sweeps,
                first_s: Some(first_s),
                blocks,
            });
        }
        if let Some(first_s) = self.first_in_impulses {
            warnings.push(Warning::NewtonInImpulses {
                steps: self.in_impulses,
                first_s,
            });
        }
        if let Some(first_s) = self.first_by_interior {
            warnings.push(Warning::NewtonByInteriorPoint {
                steps: self.by_interior,
                first_s,
                given_first: self.interior_first,
            });
        }
        if let Some(first_s) = self.first_fell_back {
            warnings.push(Warning::NewtonFellBack {
                steps: self.fell_back,
                first_s,
            });
        }
        for w in warnings {
            merge_warning(&mut rec.warnings, w);
        }
    }
}

/// Adds `w` to the warning of its kind in `warnings` (steps added, the first instant kept, the
/// blocks each stretch listed counted together and the most often fastest kept), or after them
/// where there is none.
fn merge_warning(warnings: &mut Vec<Warning>, mut w: Warning) {
    for old in warnings.iter_mut() {
        match (old, &mut w) {
            (
                Warning::Unconverged { steps, blocks, .. },
                Warning::Unconverged {
                    steps: more,
                    blocks: others,
                    ..
                },
            ) => {
                *steps += *more;
                for (name, count) in others.drain(..) {
                    match blocks.iter_mut().find(|b| b.0 == name) {
                        Some(b) => b.1 += count,
                        None => blocks.push((name, count)),
                    }
                }
                // Most often first; a stable sort keeps the wall's order among equals.
                blocks.sort_by_key(|b| std::cmp::Reverse(b.1));
                blocks.truncate(FASTEST_LISTED);
                return;
            }
            (
                Warning::NewtonInImpulses { steps, .. },
                Warning::NewtonInImpulses { steps: more, .. },
            )
            | (
                Warning::NewtonFellBack { steps, .. },
                Warning::NewtonFellBack { steps: more, .. },
            ) => {
                *steps += *more;
                return;
            }
            (
                Warning::NewtonByInteriorPoint {
                    steps, given_first, ..
                },
                Warning::NewtonByInteriorPoint {
                    steps: more,
                    given_first: given,
                    ..
                },
            ) => {
                *steps += *more;
                *given_first += *given;
                return;
            }
            _ => {}
        }
    }
    if let Warning::Unconverged { blocks, .. } = &mut w {
        blocks.sort_by_key(|b| std::cmp::Reverse(b.1));
        blocks.truncate(FASTEST_LISTED);
    }
    warnings.push(w);
}

/// Energy terms where the steps start (J).
#[derive(Default)]
struct Before {
    /// Kinetic and potential energy.
    mechanical_j: f64,
    /// Work put in by the ground.
    input_j: f64,
    /// Energy of the blocks fallen.
    fallen_j: f64,
    /// Friction's work (the sliding run's impacts keep their own term).
    friction_j: f64,
}

impl Before {
    /// Friction's work by the end of the steps, where the blocks have `kinetic_j` and
    /// `potential_j`: what the steps' contacts took (friction and landings, which time stepping
    /// does not tell apart) added to what was lost before them.
    fn friction_after(&self, e: &crate::response::Energy, kinetic_j: f64, potential_j: f64) -> f64 {
        let stepped = (e.input_j - self.input_j) + self.mechanical_j
            - kinetic_j
            - potential_j
            - (e.fallen_j - self.fallen_j);
        self.friction_j + stepped
    }
}

/// Newton's method on the whole wall, with what a run prepares once: the sparsity of the
/// wall's contacts, each candidate's compliance, the blocks' masses and reaches.
struct NewtonStep {
    solver: WallNewton,
    compliance: Vec<f64>,
    mass: Vec<Vector3<f64>>,
    reach: Vec<Vector3<f64>>,
    contacts: Vec<Contact>,
    impulses: Vec<Vector2<f64>>,
    v_free: Vec<Vector3<f64>>,
    /// The last resort where Newton in the blocks' velocities fails: the step in the
    /// contacts' impulses, from the last step's.
    dual: WallDual,
    last_impulses: Vec<Vector2<f64>>,
    /// Steps still to try the interior point first: after a step only it solved, the next
    /// [`INTERIOR_FIRST`] - 1 try it first, then one goes through the usual order again.
    interior_first_left: usize,
}

/// Where the interior point solved a step the others could not, it is tried first in the
/// steps that follow, for this many steps at a time: the three solvers before it fail
/// there at several times its cost (docs/rocking-walls.md), and one step in this many tries
/// them again to find where the wall has become easy.
const INTERIOR_FIRST: usize = 8;

impl NewtonStep {
    fn new(bodies: &[Body], candidates: &[Candidate]) -> NewtonStep {
        // One stiffness per metre of joint for the whole wall, scaled so that a contact of the
        // mean length has COMPLIANCE times the mean inverse mass.
        let free: Vec<&Body> = bodies.iter().filter(|b| b.free).collect();
        let mean_inverse_mass =
            free.iter().map(|b| 1.0 / b.mass).sum::<f64>() / free.len().max(1) as f64;
        let mean_length =
            candidates.iter().map(|c| c.length_m).sum::<f64>() / candidates.len().max(1) as f64;
        NewtonStep {
            solver: WallNewton::new(
                bodies.len(),
                candidates.iter().filter_map(|c| c.on.map(|f| (c.point, f))),
            ),
            compliance: candidates
                .iter()
                .map(|c| COMPLIANCE * mean_inverse_mass * mean_length / c.length_m)
                .collect(),
            mass: bodies
                .iter()
                .map(|b| Vector3::new(b.mass, b.mass, b.inertia))
                .collect(),
            reach: bodies
                .iter()
                .map(|b| Vector3::new(1.0, 1.0, b.half.norm()))
                .collect(),
            contacts: Vec::new(),
            impulses: Vec::new(),
            v_free: Vec::new(),
            dual: WallDual::default(),
            last_impulses: Vec::new(),
            interior_first_left: 0,
        }
    }

    /// Solves a step's contacts from the free velocities `v` (left with the solution, and
    /// each active candidate's impulse in `impulses`), starting from the velocities at the
    /// step's start, or, where that fails, in the impulses from the last step's (`impulses`
    /// as they come); `v` and `impulses` as they came if neither converged.
    #[allow(clippy::too_many_arguments)]
    fn solve(
        &mut self,
        candidates: &[Candidate],
        active: &[Active],
        moves: impl Fn(usize) -> bool,
        v_start: &[Vector3<f64>],
        v: &mut [Vector3<f64>],
        impulses: &mut [Vector2<f64>],
        tolerance_m_s: f64,
    ) -> Solved {
        self.contacts.clear();
        for act in active {
            let c = &candidates[act.candidate];
            let point = moves(c.point).then_some(Part {
                body: c.point,
                rows: act.geometry.point_row,
            });
            let on = match (c.on, act.geometry.on_row) {
                (Some(f), Some(rows)) if moves(f) => Some(Part { body: f, rows }),
                _ => None,
            };
            self.contacts.push(Contact {
                parts: [point, on],
                target_m_s: -c.restitution * act.approach_m_s.min(0.0),
                friction: c.friction,
                compliance: self.compliance[act.candidate],
            });
        }
        self.last_impulses.clear();
        self.last_impulses
            .extend(active.iter().map(|act| impulses[act.candidate]));
        self.impulses.resize(active.len(), Vector2::zeros());
        self.v_free.clear();
        self.v_free.extend_from_slice(v);
        for (i, vi) in v.iter_mut().enumerate() {
            if moves(i) {
                *vi = v_start[i];
            }
        }
        let step = StepProblem {
            mass: &self.mass,
            reach: &self.reach,
            v_free: &self.v_free,
            contacts: &self.contacts,
            tolerance_m_s,
        };
        let restart = |v: &mut [Vector3<f64>]| {
            for (i, vi) in v.iter_mut().enumerate() {
                if moves(i) {
                    *vi = v_start[i];
                }
            }
        };
        let interior_first = self.interior_first_left > 0;
        let mut solved = Solved::InteriorFirst;
        let mut outcome = Err(Stall::Iterations);
        if interior_first {
            self.interior_first_left -= 1;
            outcome = self.solver.solve_interior(&step, v, &mut self.impulses);
            if outcome.is_err() {
                self.interior_first_left = 0;
                restart(v);
            }
        }
        if outcome.is_err() {
            solved = Solved::InVelocities;
            outcome = self.solver.solve(&step, v, &mut self.impulses);
        }
        if outcome.is_err() {
            solved = Solved::InImpulses;
            self.impulses.clone_from(&self.last_impulses);
            outcome = self.dual.solve(&step, v, &mut self.impulses);
        }
        if outcome.is_err() && !interior_first {
            solved = Solved::ByInteriorPoint;
            restart(v);
            outcome = self.solver.solve_interior(&step, v, &mut self.impulses);
            if outcome.is_ok() {
                self.interior_first_left = INTERIOR_FIRST - 1;
            }
        }
        if outcome.is_err() {
            // Back to the free velocities, the last step's impulses left for Gauss-Seidel's
            // warm start.
            v.copy_from_slice(&self.v_free);
            return Solved::Neither;
        }
        for (act, p) in active.iter().zip(&self.impulses) {
            impulses[act.candidate] = *p;
        }
        solved
    }
}

/// How a step's contacts were solved by [`NewtonStep::solve`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Solved {
    /// By Newton's method in the blocks' velocities.
    InVelocities,
    /// In the contacts' impulses, where that failed.
    InImpulses,
    /// By the interior point in the blocks' velocities, where both failed.
    ByInteriorPoint,
    /// By the interior point, tried first after a step only it solved ([`INTERIOR_FIRST`]).
    InteriorFirst,
    /// By neither: Gauss-Seidel's turn.
    Neither,
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Two stretches' warnings of unconverged steps make one: steps added, the first instant
    /// the first stretch's, blocks counted together; a kind met once is added as it comes.
    #[test]
    fn warnings_of_two_stretches_are_one() {
        let unconverged = |steps, first_s, blocks: &[(&str, u64)]| Warning::Unconverged {
            steps,
            sweeps: 10,
            first_s: Some(first_s),
            blocks: blocks.iter().map(|(b, c)| (b.to_string(), *c)).collect(),
        };
        let mut warnings = Vec::new();
        merge_warning(&mut warnings, unconverged(5, 1.0, &[("A", 3), ("B", 2)]));
        merge_warning(
            &mut warnings,
            unconverged(7, 4.0, &[("B", 4), ("C", 2), ("D", 1)]),
        );
        merge_warning(
            &mut warnings,
            Warning::NewtonFellBack {
                steps: 2,
                first_s: 5.0,
            },
        );
        let blocks = [("B", 6), ("A", 3), ("C", 2)].map(|(b, c)| (b.to_string(), c));
        assert_eq!(
            warnings,
            [
                Warning::Unconverged {
                    steps: 12,
                    sweeps: 10,
                    first_s: Some(1.0),
                    blocks: blocks.to_vec(),
                },
                Warning::NewtonFellBack {
                    steps: 2,
                    first_s: 5.0,
                },
            ]
        );
    }
}
