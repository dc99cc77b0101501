//! The exact event-driven integrator of rocking bodies: free-standing blocks that rest, slide,
//! rock and slide-rock on a moving base, land on their corners and overturn (Housner 1963,
//! Shenton 1996). Between events each body follows a Taylor series of its mode's equations
//! (`series`, `modes`); every contact condition is a series too, and the first to fall is
//! the next event, located to round-off. At an event the next mode is decided from the contact
//! conditions of both corners (`modes::decide`); landings follow `impact`; a series of
//! landings that accumulates (Zeno) is summed in closed form.
//!
//! Bodies are independent (the sections of a wall checked across its plane are run side by
//! side): they advance in lockstep so that every event of one is a history row of all.
//!
//! | event | found by | handled by |
//! |---|---|---|
//! | stick limit, uplift, stop, pivot slip or stick, flight | a `modes::Constraint` falls | `modes::decide` |
//! | landing (theta = 0) | the `Impact` constraint | `impact::land`, then `decide` |
//! | landing from free flight (a corner reaches the ground) | a `Land` constraint | `impact::land_from_flight`, then `decide` |
//! | overturning | theta reaches pi/2, or alpha with the ground at rest from then on | `Engine::overturn` |
//! | a column's held joint opens under the rocking body | its watch's condition falls | `chain`: the column's blocks rock on each other until it is one body again |
//! | the chain's lowest pivot, or a held joint below it, slips; the slip stops | its condition falls | `chain`: the blocks above the joint translate on it (`chain::Slide`) |
//! | a column's held joint below the rocking body slips | its watch's condition falls | `stack`: the blocks above it slide under the body until their slip stops |
//! | a sliding stack stops | its `Stop` constraint | `Engine::stack_stops`, then `decide` |
//! | the pivot slips on the sliding stack, or stops slipping on it | `PivotSlip`, `PivotStick` | `Engine::stack_parts`, `Engine::stack_rejoins` |
//! | a held joint inside or below the sliding stacks slips | its watch's condition falls | `Engine::stack_splits` |
//! | a stack stops slipping on the stack beneath it | `Stop`, `Beneath` | `Engine::stack_joins` (slipping back at once: `Engine::stack_splits`) |
//! | landing on the sliding stacks | the `Impact` constraint | `stack::landing`, `Engine::stack_lands` |
//! | extremes of theta, u, u' | roots of their derivatives | recorded, nothing decided |
//! | end of a ground-motion segment | the step stops there | `decide` if a_g jumps |

mod abutting;
#[cfg(test)]
mod abutting_tests;
mod body;
mod chain;
mod clearance;
#[cfg(test)]
mod clearance_tests;
mod collision;
mod column;
mod couple;
#[cfg(test)]
mod couple_tests;
#[cfg(test)]
mod enumeration;
mod frame;
#[cfg(test)]
mod handoff_tests;
mod impact;
mod layout;
mod lean;
mod lying;
#[cfg(test)]
mod lying_tests;
mod modes;
mod scenes;
mod series;
mod stack;
#[cfg(test)]
mod tie_tests;

pub use body::RockingBody;
pub use column::{columns, Column, JointLimit, Watch};
pub use frame::Trilith;
pub use modes::Equations;
pub use scenes::{
    can_lift, equations_name, free_standing, out_of_plane, released_body, rocks_in_plane,
    ModelChoice, Rocking,
};

use crate::error::SimulationError;
use crate::integrate::event::{HandOff, Turned};
use crate::integrate::{AfterCollapse, Settings};
use crate::motion::{Motion, Segment, Shape};
use crate::response::{Collapse, CollapseCause, EventKind, Recorder, Response, Warning};
use abutting::Abutting;
use clearance::{Clearance, Meeting, Seated, Side, Touch};
use couple::{Couple, Member};
use layout::Layout;
use lean::Lean;
use lying::{Decision, Lying};
use modes::{Corner, Guard, Inputs, Mode, Scales, Slip, State, Trajectory};
use series::Coeffs;
use stack::Displaced;

/// Stops at one instant (events that do not move the time) before a run is declared stuck; the
/// same number of stops in a row that each move it by less than [`CRAWL`] of the bodies'
/// shortest time scale is a run that crawls (events crowding in at the scale of round-off, which
/// would go on for ever, each a history row).
const STALL_STOPS: usize = 10_000;

/// See [`STALL_STOPS`]: well above the steps of any series of events the model sums or follows
/// (a series of landings is summed in closed form once a rise is below 1e-9 of alpha).
const CRAWL: f64 = 1e-6;

/// How many times a pair may part at one instant, its push falling at once, before a contact
/// whose push falls at once again stops the run: a pair that touches and parts again as it did
/// (alone, the bodies come back to the contact at the instant) would do so without end, where
/// other events of the instant may come between the first partings.
const PARTINGS: usize = 3;

/// A landing after which the body would rise by less than this fraction of alpha starts a series
/// of landings that is summed in closed form (Zeno). It must lie well above [`series::TIE`]: an
/// excursion that small is a tie to the mode decisions, which could no longer tell it from
/// rest. What the sum leaves out is rocking below 1e-9 alpha; its duration is computed as if
/// a_g stayed as it is over the tail (exact on a still base; otherwise the instant the body is
/// seated carries an error of about (da_g/dt / a_g) times the square of the tail's duration,
/// while the state is right to that rotation).
const ZENO_ROTATION: f64 = 1e-9;

/// What stops a body's step: the time from the step's start and the condition that falls there
/// (`None`: an extreme of theta, u or u', recorded and nothing decided).
type Stop = (f64, Option<Guard>);

/// A body's trajectory over a step and its first stop within it.
type Plan = (Trajectory, Option<Stop>);

/// One body as the engine carries it.
struct Track {
    mode: Mode,
    state: State,
    /// Where it lies once it has overturned (its trajectory at rest there); it moves no more.
    fallen: Option<Trajectory>,
    /// The end of the series of landings it is in (its time, the angular velocity after the
    /// landing that started it and the series' duration): it is taken as seated until then,
    /// when it comes to rest.
    settles: Option<(f64, f64, f64)>,
    /// It rests leaning on a fixed block, held still by their contact, until that lets go.
    leans: Option<Lean>,
    /// It turns in contact with another body, the two as one mechanism, or slides along a
    /// fixed block's face, until they part.
    couple: Option<Couple>,
    /// Its face lies on another body's, pressed at both ends of their overlap, until an end
    /// lets go.
    lies: Option<Lying>,
    /// Where its column's held blocks are, and the stack under it that slides, if one does.
    displaced: Displaced,
}

/// Bodies to run side by side, and how.
pub struct Scene<'a> {
    /// The bodies.
    pub bodies: &'a [RockingBody],
    /// Initial rotation of each (rad; 0: seated at rest). A body released from a rotation
    /// starts at rest on the corner of its sign.
    pub initial_rotation_rad: &'a [f64],
    /// The held joints of each body's column, one per body (empty: every body stands alone
    /// on the ground).
    pub watches: &'a [Watch],
    /// The wall whose columns the watches watch, and its graph: a run then lists its every
    /// block in its order (none: each body is one output).
    pub wall: Option<(&'a crate::wall::Wall, &'a crate::topology::Topology)>,
    /// The equations between events.
    pub equations: Equations,
    /// The ground motion.
    pub motion: &'a Motion,
    /// Duration, outputs, collapse policy.
    pub settings: &'a Settings,
}

/// Runs the bodies of a scene under its ground motion.
pub fn run(scene: &Scene) -> Result<Response, SimulationError> {
    check(scene)?;
    match Engine::new(scene, false).run()? {
        Finished::Ended(r) => Ok(*r),
        Finished::Stopped(..) => Err(SimulationError::Bug(
            "a rocking run not asked to hand over did".into(),
        )),
    }
}

/// The scene's settings, bodies and choices, as a run takes them.
fn check(scene: &Scene) -> Result<(), SimulationError> {
    scene.settings.validate(scene.bodies.len())?;
    for b in scene.bodies {
        b.validate()?;
    }
    if scene.initial_rotation_rad.len() != scene.bodies.len()
        || !(scene.watches.is_empty() || scene.watches.len() == scene.bodies.len())
        || scene.watches.is_empty() != scene.wall.is_none()
    {
        return Err(SimulationError::Bug(
            "one initial rotation per body and none or one watch per body (with the wall they \
             belong to) expected"
                .into(),
        ));
    }
    if scene.equations == Equations::Linearised && scene.motion.has_vertical() {
        return Err(SimulationError::Incompatible {
            asked: "the linearised rocking equations take no vertical ground motion",
            fix: "use --rocking exact",
        });
    }
    Ok(())
}

/// How a run of the exact model ended where it was asked to hand over ([`run_to_stop`]).
pub(crate) enum Finished {
    /// At its end (or where it was told to stop, or where a body fell and the run stops there):
    /// the answer.
    Ended(Box<Response>),
    /// Where the exact model stopped following the wall (a held joint gives way, a column's
    /// body or a trilith's frame would fly): every block's state there, with what was
    /// recorded up to then, for a model that follows every block; and why it stopped, in a few
    /// words (the run no longer carries its warning: it goes on).
    Stopped(Box<HandOff>, String),
}

/// Runs a scene as [`run`] does, but where the exact model stops before the end (only a
/// wall's columns or trilith can: what their watches hold gives way), hands over the state of
/// that instant instead of ending the run.
pub(crate) fn run_to_stop(scene: &Scene) -> Result<Finished, SimulationError> {
    check(scene)?;
    Engine::new(scene, true).run()
}

struct Engine<'a> {
    scene: &'a Scene<'a>,
    layout: Layout,
    tracks: Vec<Track>,
    rec: Recorder,
    t: f64,
    t_end: f64,
    /// Output times passed, and the next one.
    outputs: u64,
    next_out: f64,
    /// Where a run that ended in a chain of open joints left its blocks.
    chain_end: Option<ChainEnd>,
    /// Hand over where the exact model stops ([`run_to_stop`]), and why it stopped, once it has.
    hand_off: bool,
    stop: Option<String>,
    /// The blocks of different columns (or a column's and a fixed one) that stand apart.
    clearance: Clearance,
    /// Each body's mode and state as a step reached its stop, before that stop's events
    /// (kept between steps, not allocated anew).
    reached: Vec<(Mode, State)>,
    /// The landings due at a step's stop, per body (on its base: `Some(None)`; from flight, on
    /// a corner: `Some(Some(corner))`); a body of a couple taking both takes the other's.
    landings: Vec<Option<Option<Corner>>>,
    /// The pair whose couple last parted because its push fell to zero, when (s), and how
    /// many times it did at that instant.
    parted: Option<(usize, f64, usize)>,
}

/// Where a block is at a hand-over: its centroid's horizontal displacement (m) and velocity
/// (m/s), its rise and rotation.
type Placed = (f64, f64, Turned);

/// A held block a stack moved: its u (m), u' (m/s) and, while it slides, its acceleration
/// relative to the ground (m/s2).
type Moved = (f64, f64, Option<f64>);

/// Every output's state at one instant: u (m), u' (m/s), theta (rad), theta' (rad/s), the
/// rise w (m) and the absolute acceleration (m/s2; none for a body that lies fallen).
struct Row {
    u: Vec<f64>,
    v: Vec<f64>,
    theta: Vec<f64>,
    omega: Vec<f64>,
    w: Vec<f64>,
    accel: Vec<Option<f64>>,
}

impl Row {
    /// n outputs at rest relative to the ground, accelerating with it at a_g: what held blocks
    /// and abutments report.
    fn at_rest(n: usize, a_g: f64) -> Row {
        Row {
            u: vec![0.0; n],
            v: vec![0.0; n],
            theta: vec![0.0; n],
            omega: vec![0.0; n],
            w: vec![0.0; n],
            accel: vec![Some(a_g); n],
        }
    }
}

/// The end of a run in a column's chain of open joints: each output's u (m) and u' (m/s), and
/// the energy left in the blocks that still stand (J).
struct ChainEnd {
    u: Vec<f64>,
    v: Vec<f64>,
    kinetic_j: f64,
    potential_j: f64,
    placed: Vec<Placed>,
}

/// The event a change of mode is logged as (`start`: the first mode of the run, logged only
/// when the body starts on a corner).
fn transition(old: Mode, new: Mode, start: bool) -> Option<EventKind> {
    use Mode::*;
    match (old, new) {
        (_, Rock(_) | SlideRock(..)) if start => Some(EventKind::Uplift),
        _ if start || old == new => None,
        (Rest | Slide(_), Rock(_) | SlideRock(..)) => Some(EventKind::Uplift),
        (Rock(_), SlideRock(..)) => Some(EventKind::PivotSlip),
        (SlideRock(..), Rock(_) | SlideRock(..)) => Some(EventKind::PivotStick),
        (_, Flight(_)) => Some(EventKind::Flight),
        (Rest, Slide(_)) => Some(EventKind::Slip),
        (Slide(_), Rest | Slide(_)) => Some(EventKind::Stick),
        (Rock(_) | SlideRock(..), Rest | Slide(_)) => Some(EventKind::Rest),
        _ => None,
    }
}

/// A body's mode after an impact (`after`; its mode before, `mode`): rocking on the pivot it
/// had, or on either corner where both were on the ground through the impact (`seated`: a
/// seated body, or one landing on its base), stuck or slipping; or
/// in flight, its u and lift following the corner it rocked on (or its right one, as from
/// rest); else what it does instead, in words.
fn mode_after(after: &collision::After, mode: Mode, seated: bool) -> Result<Mode, &'static str> {
    let rocks = |corner, slips| match slips {
        true => Mode::SlideRock(corner, Slip::of_sign(after.v)),
        false => Mode::Rock(corner),
    };
    match (after.base, mode.pivot()) {
        (collision::Base::Pivot { corner, slips }, Some(c)) if corner == c => Ok(rocks(c, slips)),
        (collision::Base::Pivot { corner, slips }, _) if seated => Ok(rocks(corner, slips)),
        (collision::Base::Flies, _) => Ok(Mode::Flight(mode.corner().unwrap_or(Corner::Right))),
        (collision::Base::Pivot { .. }, _) => Err("turns on its other corner"),
        (collision::Base::Seated { .. }, _) => Err("stays seated"),
    }
}

/// Whether a body in `mode` rocks on its pivot a round-off from its seat (or on it) and turns
/// down onto it (where a blow left it as it was landing, or a contact's round-off closed by its
/// rotation turned it so at its seat): it lands now, as where its rotation reaches zero.
fn seats_by_round_off(body: &RockingBody, mode: Mode, st: &State) -> bool {
    mode.pivot().is_some_and(|c| st.omega * c.sign() < 0.0)
        && st.theta.abs() <= series::TIE * body.slenderness_rad()
}

/// The landing a body in `mode` is a round-off from, where another body meets it: on its base
/// (`Some(None)`) where it turns down onto its seat from a round-off, or is turned and turning
/// by round-off (a body that nothing meets settles there, [`Engine::decide`]; here the
/// landing's impulse takes what is left); from flight (`Some(Some(corner))`) where the corner
/// it follows is a round-off above the ground and coming down, or rising at a tie's rate (the
/// end of a series of blows that each lift it by less: it is on the ground).
fn lands_by_round_off(body: &RockingBody, mode: Mode, st: &State) -> Option<Option<Corner>> {
    match mode {
        Mode::Flight(c) => (st.lift <= series::TIE * body.size_m()
            && (st.lift_v < 0.0 || tie_speed(body, st.lift_v)))
        .then_some(Some(c)),
        Mode::Rock(_) | Mode::SlideRock(..) => {
            (seats_by_round_off(body, mode, st) || still_by_round_off(body, st)).then_some(None)
        }
        _ => None,
    }
}

/// A body's state as the mode decided for it just after an impact takes it: on the ground, a
/// rise (and a slip) at a tie's rate is the impact law's round-off, and a seated body does not
/// turn.
fn settled_in(body: &RockingBody, mode: Mode, state: State) -> State {
    let mut state = state;
    if !matches!(mode, Mode::Flight(_)) {
        (state.lift, state.lift_v) = (0.0, 0.0);
        if matches!(mode, Mode::Rock(_) | Mode::Rest) || tie_speed(body, state.v) {
            state.v = 0.0;
        }
    }
    if matches!(mode, Mode::Rest | Mode::Slide(_)) {
        (state.theta, state.omega) = (0.0, 0.0);
    }
    state
}

/// How far along the ground (m) a body in contact with other blocks (`contacts`: each point,
/// the face's normal pointing into the corner's block, and +1 where the body is the corner's
/// block, -1 where it is the face's), tilted by `theta` (rad) about its pivot (its home at rest
/// `home`, its base moved by `u`) as it lands, must be moved so that, turned back with the body
/// to theta = 0, no contact moves into the other block where a shift can keep them all out: of
/// the shifts that keep one contact where it was along its normal, the first that opens the
/// others most. For faces lying on each other (their overlap's two ends) one end stays and the
/// other opens, by at most the tilt times the overlap. None without a contact.
fn seat_shift_among_m(
    contacts: &[([f64; 2], [f64; 2], f64)],
    home: [f64; 2],
    theta: f64,
    u: f64,
) -> f64 {
    // The least any contact opens (m) with the base moved by `shift`.
    let least = |shift: f64| {
        (contacts.iter())
            .map(|&(point, normal, side)| {
                side * (shift - seat_shift_m(point, normal, home, theta, u)) * normal[0]
            })
            .fold(f64::INFINITY, f64::min)
    };
    let keeps = contacts
        .iter()
        .map(|&(point, normal, _)| seat_shift_m(point, normal, home, theta, u));
    keeps
        .fold(None, |best: Option<(f64, f64)>, shift| {
            let opens = least(shift);
            match best {
                Some((_, most)) if most >= opens => best,
                _ => Some((shift, opens)),
            }
        })
        .map_or(0.0, |(shift, _)| shift)
}

/// How far along the ground (m) a body that lands on its base, tilted by `theta` (rad) about
/// its pivot (its home at rest `home`, its base moved by `u`), must be moved so that the point
/// `point` of a contact with normal `normal`, turned back with the body to theta = 0, stays
/// where it was along the normal.
fn seat_shift_m(point: [f64; 2], normal: [f64; 2], home: [f64; 2], theta: f64, u: f64) -> f64 {
    let r = [point[0] - home[0] - u, point[1] - home[1]];
    let (sin, cos) = theta.sin_cos();
    // The body turns clockwise by theta from rest: back by theta, a point r goes to R(-theta) r.
    let back = [r[0] * cos - r[1] * sin, r[0] * sin + r[1] * cos];
    let moved = (back[0] - r[0]) * normal[0] + (back[1] - r[1]) * normal[1];
    -moved / normal[0]
}

/// Whether a body's corners, `half_base_m` from its base's middle, stand level to a tie of its
/// size: tilted so little that which one is lower is round-off.
fn level_by_round_off(body: &RockingBody, half_base_m: f64, theta: f64) -> bool {
    2.0 * half_base_m * theta.abs() <= series::TIE * body.size_m()
}

/// Whether a body's tilt and rotation rate are round-off: a tie of its slenderness, and of
/// the rate it would take to turn that far in its time scale.
fn upright_by_round_off(body: &RockingBody, state: &State) -> bool {
    let tie = series::TIE * body.slenderness_rad();
    state.theta.abs() <= tie && state.omega.abs() <= tie * body.frequency_parameter_rad_s()
}

/// Whether every coefficient of a trajectory's coordinates is a number.
fn finite(t: &Trajectory) -> bool {
    [&t.theta, &t.omega, &t.u, &t.v, &t.lift, &t.lift_v]
        .iter()
        .all(|c| c.iter().all(|x| x.is_finite()))
}

/// What a body does in `mode` from `state`, in words.
fn in_mode(mode: Mode, state: &State) -> String {
    match mode {
        Mode::Flight(_) => "in flight".into(),
        Mode::Rock(c) => format!("rocking on its {} corner", c.name()),
        Mode::SlideRock(c, _) => format!(
            "rocking on its {} corner, slipping at {:.6e} m/s",
            c.name(),
            state.v
        ),
        Mode::Rest => "seated".into(),
        Mode::Slide(_) => format!("seated, sliding at {:.6e} m/s", state.v),
    }
}

/// The sides of a couple just after an impact: each side's body (none for a fixed block),
/// its pivot's home, its state and mode.
struct Sides {
    bodies: [Option<usize>; 2],
    homes: [[f64; 2]; 2],
    states: [State; 2],
    modes: [Mode; 2],
}

/// How a blow on blocks in contact with others is taken.
enum AtOnce {
    /// Every contact's impulse at once, the modes after it set.
    Done,
    /// Not followed: the run stops, for this reason.
    Stops(String),
    /// By the sequential law instead: the blow first, then each contact that stayed.
    InTurn,
}

/// What gives a contact that stays through an impact its impulse.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Through {
    /// The blocks' own approach there.
    Approach,
    /// Body i landing on its base (or a corner) beside it, both at once (and the other
    /// body, where it lands at the same instant).
    Landing(usize, Option<usize>),
    /// A blow at another contact, both at once.
    Blow,
}

impl Through {
    /// Whether body i lands through it.
    fn lands(self, i: usize) -> bool {
        matches!(self, Through::Landing(a, b) if a == i || b == Some(i))
    }
}

/// The state of a body in flight followed by its other corner instead of `from` (its base's
/// half-width `bp`, m): that corner's displacement from its own place at rest, its height and
/// their rates. Turned clockwise by theta, it lies (dx cos, -dx sin) from the one followed, dx =
/// -2 s b (and dx (cos - 1) = -2 dx sin^2(theta / 2)).
fn refollowed(state: State, from: Corner, bp: f64) -> State {
    let dx = -2.0 * from.sign() * bp;
    let (sin, cos) = state.theta.sin_cos();
    let half = (0.5 * state.theta).sin();
    State {
        u: state.u - 2.0 * dx * half * half,
        lift: state.lift - dx * sin,
        v: state.v - state.omega * dx * sin,
        lift_v: state.lift_v - state.omega * dx * cos,
        ..state
    }
}

/// Is a speed of the body's (m/s) a tie at its scales: round-off of an impact's law, which a
/// contact may read as zero?
fn tie_speed(body: &RockingBody, speed_m_s: f64) -> bool {
    speed_m_s.abs() * body.time_scale_s() <= series::TIE * body.size_m()
}

/// Is the body turned and turning by round-off (|theta| within TIE of alpha, |theta'| within
/// TIE of alpha p): seated, to the decision's ties?
fn still_by_round_off(body: &RockingBody, st: &State) -> bool {
    let angle = body.slenderness_rad();
    st.theta.abs() <= series::TIE * angle
        && st.omega.abs() <= series::TIE * angle * body.frequency_parameter_rad_s()
}

/// What a body does where the condition `guard` of its mode falls, in words.
fn breaks(guard: Guard) -> &'static str {
    match guard {
        Guard::PivotSlip | Guard::StickLimit => "slip at its pivot",
        Guard::Land(_) => "land on a corner",
        Guard::PivotStick => "slip the other way",
        Guard::Flight => "leave the ground at its pivot",
        Guard::Overturn => "lie on its face",
        Guard::Impact => "land on its base",
        Guard::Indeterminate => "have its acceleration made indeterminate by friction",
        _ => "change its mode",
    }
}

/// Is the ground at rest from this segment on?
fn quiet(seg: &Segment) -> bool {
    seg.t1.is_infinite()
        && seg.shape
            == Shape::Linear {
                a0: 0.0,
                slope: 0.0,
            }
        && seg.lambda == (1.0, 0.0)
}

impl<'a> Engine<'a> {
    fn new(scene: &'a Scene<'a>, hand_off: bool) -> Engine<'a> {
        let layout = Layout::new(scene.bodies, scene.watches, scene.wall);
        let s = scene.settings;
        // A wall's columns report its every block and joint, the vertical joints between
        // blocks that stand apart too (where time stepping goes on after they meet, it logs
        // their impacts).
        let rec = match scene.wall.filter(|_| !scene.watches.is_empty()) {
            Some((wall, topo)) => Recorder::new(wall, topo, s.history_to(), s.events_to()),
            None => Recorder::for_bodies(
                layout.names.clone(),
                layout.horizontal.clone(),
                s.history_to(),
                s.events_to(),
            ),
        };
        let tracks = scene
            .initial_rotation_rad
            .iter()
            .map(|&theta| Track {
                mode: Mode::Rest,
                state: State {
                    theta,
                    ..State::default()
                },
                fallen: None,
                settles: None,
                leans: None,
                couple: None,
                lies: None,
                displaced: Displaced::default(),
            })
            .collect();
        Engine {
            scene,
            layout,
            tracks,
            rec,
            t: 0.0,
            t_end: s.duration_s,
            outputs: 0,
            next_out: s.output_dt_s.unwrap_or(f64::INFINITY),
            chain_end: None,
            hand_off,
            stop: None,
            clearance: scene
                .wall
                .map(|(wall, topo)| Clearance::of(wall, topo, scene.watches))
                .unwrap_or_default(),
            reached: Vec::new(),
            landings: Vec::new(),
            parted: None,
        }
    }

    /// Two bodies whose blocks touch face on face, seated at rest, where the run starts or where
    /// they are set down ([`Engine::sets_down`]; `ends`: the contacts at the ends of their
    /// overlap), lie on each other from there; returns the first body. A body released from a
    /// tilt cannot start so.
    fn abut(&mut self, ends: [Touch; 2]) -> Result<usize, SimulationError> {
        let sides = ends[0].sides.map(|side| match side {
            Side::Body(k, origin) => (k, origin),
            _ => unreachable!("blocks face on face from the start are moved by bodies"),
        });
        let [a, b] = sides.map(|(k, _)| k);
        let moved = |k: usize| {
            let st = self.tracks[k].state;
            (st.theta, st.omega, st.v, st.lift) != (0.0, 0.0, 0.0, 0.0)
        };
        if let Some(k) = [a, b].into_iter().find(|&k| moved(k)) {
            return Err(SimulationError::NotApplicable(format!(
                "{} starts turned while its face lies on {}'s: blocks face on face are followed \
                 from rest",
                self.body(k).name,
                self.body(a + b - k).name
            )));
        }
        // A seated body's pivot is the corner the push would turn it on: away from the other.
        let homes = [0, 1].map(|k| {
            let push_x = [1.0, -1.0][k] * ends[0].normal[0];
            self.home(sides[k].0, sides[k].1, Corner::of_sign(push_x))
        });
        let states = [a, b].map(|k| self.tracks[k].state);
        let lying = Lying::new(ends.each_ref(), [a, b], homes, states.each_ref());
        for k in [a, b] {
            (self.tracks[k].mode, self.tracks[k].lies) = (Mode::Rest, Some(lying));
        }
        Ok(a)
    }

    /// The exact model stops following the scene here, for the reason `w` says: the run ends,
    /// or is handed over.
    fn stops(&mut self, w: Warning) {
        self.stop = Some(match &w {
            Warning::HeldJointGives { joint, how, .. } => format!("the joint {joint} {how}"),
            Warning::Flight { body, .. } => format!("{body} would leave what it stands on"),
            Warning::BlocksMeet { first, second, .. } => format!("{first} meets {second}"),
            other => other.to_string(),
        });
        self.rec.warnings.push(w);
        self.t_end = self.t;
    }

    fn body(&self, i: usize) -> &'a RockingBody {
        &self.scene.bodies[i]
    }

    fn inputs_at(&self, t: f64) -> (Segment, Inputs) {
        let seg = self.scene.motion.segment_at(t);
        let inputs = modes::inputs(&seg, t - seg.t0);
        (seg, inputs)
    }

    fn trajectory(&self, i: usize, inputs: &Inputs) -> Trajectory {
        let tr = &self.tracks[i];
        if let Some(lying) = &tr.lies {
            let [first, second] = lying.motion(self.members(&lying.ends[0]), inputs).bodies;
            return if lying.bodies()[0] == Some(i) {
                first
            } else {
                second
            };
        }
        if let Some(couple) = &tr.couple {
            let [first, second] = self.coupled(couple, inputs).bodies;
            return if couple.bodies[0] == Some(i) {
                first
            } else {
                second
            };
        }
        if tr.displaced.sliding.is_some() {
            if let Some(t) = stack::on(self.body(i), &tr.displaced, tr.mode, &tr.state, inputs) {
                return t;
            }
        }
        let mut t = modes::trajectory(
            self.body(i),
            self.scene.equations,
            tr.mode,
            &tr.state,
            inputs,
        );
        if let Some(lean) = &tr.leans {
            lean.hold(self.body(i), &mut t, inputs);
        }
        t
    }

    /// The sides of a couple: its bodies in their modes and states, or a fixed block.
    fn members(&self, couple: &Couple) -> [Member<'_>; 2] {
        couple.bodies.map(|b| match b {
            Some(i) => Member::Moves(self.body(i), self.tracks[i].mode, &self.tracks[i].state),
            None => Member::Fixed,
        })
    }

    /// The motion of a couple's bodies and their contact's push.
    fn coupled(&self, couple: &Couple, inputs: &Inputs) -> couple::Motion {
        couple.motion(self.members(couple), inputs)
    }

    /// Whether body i rocks on its pivot a round-off from its seat and turns down onto it
    /// (where a blow left it as it was landing): it lands now, as where its rotation reaches
    /// zero.
    fn seats_by_round_off(&self, i: usize) -> bool {
        seats_by_round_off(self.body(i), self.tracks[i].mode, &self.tracks[i].state)
    }

    /// The landing body i is a round-off from ([`lands_by_round_off`]).
    fn lands_by_round_off(&self, i: usize) -> Option<Option<Corner>> {
        lands_by_round_off(self.body(i), self.tracks[i].mode, &self.tracks[i].state)
    }

    /// Decides body i's mode now, from its state and the pivot it rocks on, and logs the
    /// change (`start`: the first decision of the run).
    fn decide(&mut self, i: usize, inputs: &Inputs, start: bool) -> Result<(), SimulationError> {
        if let Mode::Flight(_) = self.tracks[i].mode {
            // Nothing touches a body in flight: a jump of the ground changes its motion only
            // through its trajectory, and it leaves flight by landing.
            return Ok(());
        }
        let tr = &self.tracks[i];
        if tr.leans.is_some() || tr.couple.is_some() || tr.lies.is_some() {
            // A body resting against a block, or turning in contact with another body, stays
            // so while the contact's push and its pivot's forces allow, which its conditions
            // watch from every instant on.
            return Ok(());
        }
        let body = self.body(i);
        let st = self.tracks[i].state;
        if self.seats_by_round_off(i) {
            return self.land(i, inputs);
        }
        let mut settled = st;
        if still_by_round_off(body, &st) {
            // Turned and turning by round-off: the body touched its uplift threshold (a ground
            // acceleration that peaks on it to the last bit) and came back, or a blow at a
            // rate of round-off left it so. It is seated.
            (settled.theta, settled.omega) = (0.0, 0.0);
        }
        if st.v != 0.0 && tie_speed(body, st.v) {
            // Slipping at a rate that is round-off (what a landing at a rate of round-off
            // leaves): the contact decides as one at rest in slip, as a slide's own stop
            // condition reads that rate.
            settled.v = 0.0;
        }
        if settled != st {
            // What it had of kinetic and potential energy beyond the state it settles to
            // counts as lost.
            let energy = |engine: &Self| {
                let t = engine.trajectory(i, inputs);
                modes::kinetic_j(body, &t, 0.0) + modes::potential_j(body, &t, 0.0)
            };
            let before = energy(self);
            self.tracks[i].state = settled;
            self.rec.energy.impact_loss_j += before - energy(self);
        }
        let tr = &self.tracks[i];
        let old = tr.mode;
        let seated = tr.state.theta == 0.0 && tr.state.omega == 0.0;
        let pivot = if seated {
            None
        } else {
            old.pivot().or(Some(Corner::of_sign(tr.state.theta)))
        };
        let next = modes::decide(body, self.scene.equations, &tr.state, pivot, inputs, self.t)?;
        self.rec.stats.mode_decisions += 1;
        let new = next.mode;
        let watched = self.scene.watches.get(i);
        if let (Mode::Flight(_), Some(false)) = (new, watched.map(Watch::holds_nothing)) {
            // A column's body leaving its held base, or a trilith's frame its feet: what the
            // watch holds no longer holds, and the exact model of those ends. A column that
            // holds nothing flies as a body standing alone does.
            self.rec.rocking_event(
                self.t,
                EventKind::Flight,
                &self.layout.outputs(i),
                None,
                new.name(),
            );
            // The run ends here; the body keeps the mode it had, whose trajectory gives the
            // energies and the pose of its state now (a flight's would seat it).
            self.stops(Warning::Flight {
                body: body.name.clone(),
                time_s: self.t,
            });
            return Ok(());
        }
        if let Some(k) = self.scene.watches.get(i).and_then(|w| w.forbids(new)) {
            self.gives(i, k, false);
            return Ok(());
        }
        let kind = transition(old, new, start);
        match kind {
            Some(EventKind::Uplift) => {
                for k in self.layout.outputs(i) {
                    self.rec.uplift(k, self.t);
                }
            }
            Some(EventKind::Slip | EventKind::Stick) => self.rec.transitions += 1,
            _ => {}
        }
        if let Some(kind) = kind {
            self.rec
                .rocking_event(self.t, kind, &self.layout.outputs(i), None, new.name());
        }
        let tr = &mut self.tracks[i];
        tr.mode = new;
        if matches!(new, Mode::Rest | Mode::Rock(_)) {
            // A contact that sticks does so from exactly zero slip.
            tr.state.v = 0.0;
        }
        Ok(())
    }

    fn run(mut self) -> Result<Finished, SimulationError> {
        let (_, inputs) = self.inputs_at(0.0);
        for i in 0..self.tracks.len() {
            self.decide(i, &inputs, true)?;
            let traj = self.trajectory(i, &inputs);
            let body = self.body(i);
            self.rec.energy.initial_j +=
                modes::kinetic_j(body, &traj, 0.0) + modes::potential_j(body, &traj, 0.0);
        }
        // Where the bodies start, which blocks stand apart and which lie face on face: a pair
        // seated so is decided again as one, its first mode as its rest's limits say.
        if !self.clearance.is_empty() {
            let trajs: Vec<Trajectory> = (0..self.tracks.len())
                .map(|i| self.trajectory(i, &inputs))
                .collect();
            let trajs: Vec<Option<&Trajectory>> = trajs.iter().map(Some).collect();
            let names = &self.layout.names;
            for ends in self.clearance.start(self.scene.bodies, &trajs, names)? {
                let i = self.abut(ends)?;
                self.relie(i, Guard::StickLimit, &inputs)?;
            }
        }
        let dt = self.scene.settings.output_dt_s;
        // A history row at each stop that is an event or an output time (and at the start).
        let mut row = true;
        let (mut stalled, mut crawled) = (0usize, 0usize);
        // The last two blocks to meet, and when; since when the steps have crawled.
        let mut met: Option<((usize, usize), f64)> = None;
        let mut crawl_from = self.t;
        let crawl_s = CRAWL
            * (self.scene.bodies.iter())
                .map(RockingBody::time_scale_s)
                .fold(f64::INFINITY, f64::min);
        while self.t < self.t_end {
            let (seg, inputs) = self.inputs_at(self.t);
            let limit = seg.t1.min(self.t_end);
            let span = limit - self.t;
            let is_quiet = quiet(&seg);
            // Each body's trajectory and its first event within the step.
            let mut plans = Vec::with_capacity(self.tracks.len());
            let mut tau = span;
            for i in 0..self.tracks.len() {
                if self.tracks[i].fallen.is_some() {
                    plans.push(None);
                    continue;
                }
                let traj = self.trajectory(i, &inputs);
                // A motion that is not a number would send every search for its events down to
                // round-off everywhere at once (the clearance's subdivision never rules a
                // subinterval out): the run stops here instead, naming the body.
                if !finite(&traj) {
                    return Err(SimulationError::Bug(format!(
                        "{}'s motion {} at t = {} s is not a number",
                        self.body(i).name,
                        in_mode(traj.mode, &self.tracks[i].state),
                        self.t
                    )));
                }
                if let Some((until, ..)) = self.tracks[i].settles {
                    // Seated through the rest of its series of landings.
                    let x = until - self.t;
                    tau = tau.min(x);
                    plans.push(Some((traj, Some((x, Some(Guard::Settled))))));
                    continue;
                }
                let (h, event) = self.first_event(i, &traj, &inputs, span, is_quiet);
                tau = tau.min(event.map_or(h, |(x, _)| x));
                plans.push(Some((traj, event)));
            }
            // Where two blocks kept apart first meet within the step.
            let mut meet = None;
            if !self.clearance.is_empty() {
                let trajs: Vec<Option<&Trajectory>> =
                    plans.iter().map(|p| p.as_ref().map(|(t, _)| t)).collect();
                meet = self
                    .clearance
                    .follow(self.scene.bodies, &trajs, self.t, tau)?;
                if let Some((x, ..)) = meet {
                    tau = x;
                }
            }
            self.note(&plans, 0.0, self.t, inputs.accel[0], row);
            self.rec.stats.steps += 1;
            if !self.keep_going() {
                break;
            }
            let t_new = if tau >= span { limit } else { self.t + tau };
            // Blocks that meet again and again without time passing, or crawling on, rattle
            // against each other at the scale of round-off: the run stops at their meeting (and
            // may be handed over), where any other stall is an error.
            let rattle = |pair: Option<((usize, usize), f64)>, since: f64| {
                pair.filter(|&(_, t)| t >= since).map(|(blocks, _)| blocks)
            };
            if t_new > self.t {
                stalled = 0;
            } else {
                stalled += 1;
                if let (true, Some(blocks)) = (stalled > STALL_STOPS, rattle(met, self.t)) {
                    let why = format!(
                        "they meet again {stalled} times at one instant: blocks that rattle \
                         against each other at the scale of round-off are beyond the exact model"
                    );
                    self.stops_meeting(blocks, why);
                    break;
                }
                if stalled > STALL_STOPS {
                    return Err(SimulationError::TooManyEvents {
                        time_s: self.t,
                        count: stalled,
                        detail: "a rocking body's events".into(),
                        limit: "a body that changes its mode this often without time passing is \
                                beyond the rocking model; please report the body and the motion",
                    });
                }
            }
            crawled = if t_new - self.t < crawl_s {
                crawled + 1
            } else {
                crawl_from = t_new;
                0
            };
            if let (true, Some(blocks)) = (crawled > STALL_STOPS, rattle(met, crawl_from)) {
                let why = format!(
                    "they meet again and again, {crawled} steps in a row each shorter than \
                     {crawl_s:.3e} s: blocks that rattle against each other at the scale of \
                     round-off are beyond the exact model"
                );
                self.stops_meeting(blocks, why);
                break;
            }
            if crawled > STALL_STOPS {
                return Err(SimulationError::EventsCrowd {
                    time_s: self.t,
                    count: crawled,
                    step_s: crawl_s,
                });
            }
            // History rows inside the step, from the series (dense output).
            while self.next_out < t_new {
                let tau_out = self.next_out - self.t;
                let a_g = series::eval(&inputs.accel, tau_out);
                self.note(&plans, tau_out, self.next_out, a_g, true);
                self.outputs += 1;
                self.next_out = (self.outputs + 1) as f64 * dt.unwrap_or(f64::INFINITY);
            }
            // Advance every body to the stop.
            for (i, plan) in plans.iter().enumerate() {
                let Some((traj, _)) = plan else { continue };
                let body = self.body(i);
                let displaced = &self.tracks[i].displaced;
                let (input, friction) = match displaced.sliding {
                    Some(_) => stack::power_series(body, displaced, traj, &inputs),
                    None => modes::power_series(body, traj, &inputs),
                };
                self.rec.energy.input_j += series::integral(&input, tau);
                self.rec.energy.friction_j += series::integral(&friction, tau);
                let displaced = &mut self.tracks[i].displaced;
                if let (Some(stack), Some([u_s, v_s])) = (&mut displaced.sliding, &traj.stack) {
                    stack.apart = Some([series::eval(u_s, tau), series::eval(v_s, tau)]);
                }
                for (st, [u_s, v_s]) in displaced.beneath.iter_mut().zip(&traj.beneath) {
                    st.apart = Some([series::eval(u_s, tau), series::eval(v_s, tau)]);
                }
                let st = &mut self.tracks[i].state;
                st.theta = series::eval(&traj.theta, tau);
                st.omega = series::eval(&traj.omega, tau);
                st.u = series::eval(&traj.u, tau);
                st.v = series::eval(&traj.v, tau);
                if let Mode::Flight(_) = traj.mode {
                    st.lift = series::eval(&traj.lift, tau);
                    st.lift_v = series::eval(&traj.lift_v, tau);
                }
            }
            self.t = t_new;
            let (_, now) = self.inputs_at(self.t);
            // The events of the bodies whose first event is this stop. A body that an earlier
            // one's event at this stop decided anew (a contact that ends, a blow) has left the
            // trajectory its guard was found on: its new mode's conditions were checked from
            // now, and its next step finds its events again. A landing that a body of a couple
            // took with the other's at this instant is not taken again.
            row = false;
            self.reached.clear();
            self.reached
                .extend(self.tracks.iter().map(|tr| (tr.mode, tr.state)));
            self.landings.clear();
            self.landings.extend(plans.iter().map(|plan| match plan {
                Some((_, Some((x, Some(Guard::Impact))))) if *x == tau => Some(None),
                Some((_, Some((x, Some(Guard::Land(c)))))) if *x == tau => Some(Some(*c)),
                _ => None,
            }));
            // What holds bodies together as the meeting was found.
            let bound: Vec<_> = match meet {
                Some(_) => self.tracks.iter().map(|tr| (tr.couple, tr.lies)).collect(),
                None => Vec::new(),
            };
            for (i, plan) in plans.into_iter().enumerate() {
                let Some((traj, Some((x, guard)))) = plan else {
                    continue;
                };
                if x != tau || self.tracks[i].fallen.is_some() {
                    continue;
                }
                if (self.tracks[i].mode, self.tracks[i].state) != self.reached[i] {
                    continue;
                }
                if matches!(guard, Some(Guard::Impact | Guard::Land(_)))
                    && self.landings[i].is_none()
                {
                    continue;
                }
                if guard.is_some() {
                    self.rec.stats.events += 1;
                    row = true;
                }
                self.handle(i, guard, &traj, tau, &now)?;
            }
            // A couple or faces lying on each other that a body's event at this instant ended
            // or began leave the meeting found before it stale (read as if they held, or not):
            // the next step finds it again, from the state after that event.
            let stale = (self.tracks.iter().zip(&bound)).any(|(tr, b)| (tr.couple, tr.lies) != *b);
            if let Some((_, outputs, touch)) = meet {
                if self.t < self.t_end && !stale {
                    self.rec.stats.events += 1;
                    row = true;
                    met = Some((outputs, self.t));
                    self.meet(outputs, touch, &now)?;
                }
            }
            if self.t >= self.next_out {
                row = true;
                self.outputs += 1;
                self.next_out = (self.outputs + 1) as f64 * dt.unwrap_or(f64::INFINITY);
            }
            if self.t == seg.t1 && self.t < self.t_end {
                self.rec.stats.segments += 1;
                // A jump of the ground motion (a pulse's end) is a new situation for every body.
                let before = series::eval(&inputs.accel, tau);
                let lam_before = series::eval(&inputs.lambda, tau);
                let g = self.scene.bodies.first().map_or(9.81, |b| b.g_m_s2);
                if (before - now.accel[0]).abs() > series::TIE * g
                    || (lam_before - now.lambda[0]).abs() > series::TIE
                {
                    for i in 0..self.tracks.len() {
                        if self.tracks[i].fallen.is_none() {
                            self.decide(i, &now, false)?;
                        }
                    }
                }
            }
        }
        self.finish(row)
    }

    /// Tells the progress the time reached; false (the run ends here, the summary saying
    /// when) once the caller asked it to stop.
    fn keep_going(&mut self) -> bool {
        let Some(p) = &self.scene.settings.progress else {
            return true;
        };
        if p.at(self.t.min(self.t_end)) {
            return true;
        }
        self.rec.interrupted_at_s = Some(self.t);
        self.t_end = self.t;
        false
    }

    /// Body i's step within `span` and its first event: the first condition of its mode to
    /// fall, or the first extreme of theta, u or u' (recorded exactly, nothing decided).
    fn first_event(
        &self,
        i: usize,
        traj: &Trajectory,
        inputs: &Inputs,
        span: f64,
        is_quiet: bool,
    ) -> (f64, Option<Stop>) {
        let body = self.body(i);
        let sc = Scales::of(body);
        let p = body.frequency_parameter_rad_s();
        let ts = body.time_scale_s();
        let mut h = series::step_size(&[
            (&traj.theta, 1.0),
            (&traj.omega, p),
            (&traj.u, body.size_m()),
            (&traj.v, sc.velocity),
        ]);
        for [u_s, v_s] in traj.stack.iter().chain(&traj.beneath) {
            // A stack that moves on its own is followed to round-off too.
            h = h.min(series::step_size(&[
                (u_s, body.size_m()),
                (v_s, sc.velocity),
            ]));
        }
        let h = h.min(span);
        let mut best: Option<Stop> = None;
        let mut consider = |x: Option<f64>, what: Option<Guard>| {
            if let Some(x) = x {
                if best.is_none_or(|(b, _)| x < b) {
                    best = Some((x, what));
                }
            }
        };
        let mut conditions = modes::constraints(body, self.scene.equations, traj);
        if let Some(watch) = self.scene.watches.get(i) {
            conditions.extend(watch.conditions(traj, inputs, &self.tracks[i].displaced));
        }
        stack::conditions(body, &self.tracks[i].displaced, traj, &mut conditions);
        if let Some(lean) = &self.tracks[i].leans {
            conditions.push(lean.condition(body, inputs));
        }
        if let Some(couple) = self.tracks[i]
            .couple
            .filter(|c| c.moving().next() == Some(i))
        {
            // The couple's own condition, once: on its first body.
            conditions.push(couple.condition(body, &self.coupled(&couple, inputs)));
        }
        if let Some(lying) = &self.tracks[i].lies {
            let members = self.members(&lying.ends[0]);
            if lying.abutting(members).is_some() {
                // Seated face on face, the bodies rest or slide as one on the pair's conditions
                // (their own are those of a block alone), the first's stop the pair's.
                let first = lying.bodies()[0] == Some(i);
                conditions.retain(|c| first && c.guard == Guard::Stop);
            }
            if lying.bodies()[0] == Some(i) {
                let motion = lying.motion(members, inputs);
                conditions.extend(lying.conditions(members, &motion, inputs));
            }
        }
        // A body that may run into a block beside it is followed until it lies on its face or
        // strikes: a block can stop its fall.
        if is_quiet && !self.clearance.watches(i) {
            if let Some(c) = traj.mode.pivot() {
                let s = c.sign();
                let inside = s * traj.theta[0] <= body.slenderness_rad();
                if inside {
                    // Past alpha with the ground at rest for good: it can only fall.
                    let mut past = traj.theta.map(|x| -s * x);
                    past[0] += body.slenderness_rad();
                    conditions.push(modes::Constraint {
                        series: past,
                        scale: sc.angle,
                        guard: Guard::Overturn,
                        strict: false,
                    });
                } else {
                    // Beyond alpha and coming back: if it stops before alpha, it falls.
                    conditions.push(modes::Constraint {
                        series: traj.omega.map(|x| -s * x),
                        scale: sc.angle * p,
                        guard: Guard::Overturn,
                        strict: false,
                    });
                }
            }
        }
        for c in &conditions {
            consider(series::first_fall(&c.series, c.scale, ts, h), Some(c.guard));
        }
        // Extremes: where the derivatives of theta and of each block's u and u' vanish.
        let mut extreme = |d: &Coeffs, scale: f64| {
            let sign = series::sign_after(d, scale, ts);
            if sign != 0 {
                let mut f = *d;
                f.iter_mut().for_each(|x| *x *= f64::from(sign));
                consider(series::first_fall(&f, scale, ts, h), None);
            }
        };
        extreme(&traj.omega, sc.angle * p);
        for (_, u) in self.layout.series(i, body, traj) {
            let v = series::derivative(&u);
            extreme(&v, sc.velocity);
            extreme(&series::derivative(&v), sc.velocity * p);
        }
        if self.tracks[i].displaced.sliding.is_some() {
            // A stack's displacement peaks where it stops (an event); its velocity here.
            let v_s = traj.stack.as_ref().map_or(&traj.v, |[_, v]| v);
            extreme(&series::derivative(v_s), sc.velocity * p);
            for [_, v] in &traj.beneath {
                extreme(&series::derivative(v), sc.velocity * p);
            }
        }
        (h, best.filter(|(x, _)| *x <= h))
    }

    /// Handles body i's event `guard` (None: an extreme) reached after tau on `traj`.
    fn handle(
        &mut self,
        i: usize,
        guard: Option<Guard>,
        traj: &Trajectory,
        tau: f64,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let Some(guard) = guard else {
            return Ok(());
        };
        if self.tracks[i].displaced.sliding.is_some() {
            let beneath = !self.tracks[i].displaced.beneath.is_empty();
            return match guard {
                Guard::Stop if beneath => {
                    self.stack_joins(i, None, now);
                    Ok(())
                }
                Guard::Beneath(k) => {
                    self.stack_joins(i, Some(k), now);
                    Ok(())
                }
                Guard::Held(k) => {
                    if !self.stack_splits(i, k, now) {
                        self.gives(i, k, false);
                    }
                    Ok(())
                }
                Guard::Stop => self.stack_stops(i, now),
                Guard::PivotSlip => {
                    self.stack_parts(i, now);
                    Ok(())
                }
                Guard::PivotStick => {
                    self.stack_rejoins(i, now);
                    Ok(())
                }
                Guard::Overturn => self.overturn(i, traj, tau),
                Guard::Impact => self.stack_lands(i, now),
                _ => {
                    self.stack_gives(i, guard);
                    Ok(())
                }
            };
        }
        if self.tracks[i].lies.is_some() {
            if self.stop.is_some() {
                // The other body stopped the run at this instant.
                return Ok(());
            }
            return match guard {
                Guard::Parts
                | Guard::PivotSlip
                | Guard::PivotStick
                | Guard::Flight
                | Guard::StickLimit
                | Guard::Stop
                | Guard::Uplift => self.relie(i, guard, now),
                Guard::Impact => self.lying_lands(i, None, now),
                Guard::Land(corner) => self.lying_lands(i, Some(corner), now),
                _ => self.lying_gives(i, guard, now),
            };
        }
        if self.tracks[i].couple.is_some() {
            if self.stop.is_some() {
                // The other body of the couple stopped the run at this instant.
                return Ok(());
            }
            return match guard {
                Guard::Parts => self.part(i, now, false),
                Guard::Impact => self.couple_lands(i, None, now),
                Guard::Land(corner) => self.couple_lands(i, Some(corner), now),
                Guard::PivotSlip
                | Guard::PivotStick
                | Guard::Flight
                | Guard::StickLimit
                | Guard::Stop
                | Guard::Uplift => self.recouple(i, guard, now),
                Guard::Overturn => self.couple_overturns(i, traj, tau, now),
                _ => self.couple_gives(i, guard, now),
            };
        }
        match guard {
            Guard::Parts => self.lets_go(i, now),
            Guard::PivotSlip | Guard::Flight if self.tracks[i].leans.is_some() => {
                self.lean_moves(i, now)
            }
            Guard::Overturn => self.overturn(i, traj, tau),
            Guard::Impact => self.land(i, now),
            Guard::Land(corner) => self.land_from_flight(i, corner, now),
            Guard::Stop | Guard::PivotStick => {
                self.stills([Some(i), None], |_| true, now);
                self.decide(i, now, false)
            }
            Guard::StickLimit | Guard::Uplift | Guard::PivotSlip | Guard::Flight => {
                self.decide(i, now, false)
            }
            Guard::Held(k) if self.chain_can_follow(i, k) => self.open_chain(k),
            Guard::Held(k) => {
                if !self.stack_slides(i, k, now) && !self.slips_as_chain(k, now)? {
                    self.gives(i, k, false);
                }
                Ok(())
            }
            Guard::Indeterminate => Err(self.indeterminate(i)),
            Guard::Beneath(_) => Err(SimulationError::Bug(
                "a stack beneath another's stop met by a body on no sliding stack".into(),
            )),
            Guard::Settled => {
                let (_, after, tail) = self.tracks[i].settles.take().expect("a series of landings");
                self.settled(i, after, tail);
                self.decide(i, now, false)
            }
        }
    }

    /// Body i slide-rocks and the effective mass of its slipping corner falls to zero: from
    /// here friction makes its acceleration indeterminate (Painleve's paradox), as a decision
    /// refuses a slide-rock whose denominator starts not positive ([`modes::decide`]).
    fn indeterminate(&self, i: usize) -> SimulationError {
        let body = self.body(i);
        let st = &self.tracks[i].state;
        SimulationError::RigidModel {
            at: format!(
                "{} at t = {} s (theta = {} rad, theta' = {} rad/s, slip velocity {} m/s)",
                body.name, self.t, st.theta, st.omega, st.v
            ),
            why: format!(
                "Painleve's paradox: in {}, friction {} makes the effective mass of its \
                 slipping corner fall to zero (I_G + m dx^2 - m mu sigma G_y dx = 0); the rigid \
                 model with Coulomb friction cannot go on",
                self.tracks[i].mode.name(),
                body.friction
            ),
        }
    }

    /// Blocks of two columns (or a column's and a fixed one) meet. Where a corner strikes a
    /// face, each block fixed or moved by a body that stands alone (its column holding no
    /// joint), the impact is resolved ([`collision`]) and the run goes on, the column perhaps
    /// at rest against a fixed block from there ([`lean`]), or two columns turning together
    /// ([`couple`]); at any other meeting the run ends here, the state the one just before,
    /// and says why.
    fn meet(
        &mut self,
        (a, b): (usize, usize),
        meeting: Meeting,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let lying = self.tracks.iter().find_map(|tr| {
            let l = tr.lies?;
            let blocks = l.ends[0].touch.blocks;
            (blocks == [a, b] || blocks == [b, a]).then_some(l)
        });
        if let Some(lying) = lying {
            return self.lying_meets(lying, meeting, now);
        }
        // A body of theirs and the blocks' names, the corner's first, where they move together.
        let together = self.tracks.iter().enumerate().find_map(|(i, tr)| {
            let c = tr.couple?;
            let names = c.touch.blocks.map(|k| self.layout.names[k].clone());
            (c.touch.blocks == [a, b] || c.touch.blocks == [b, a]).then_some((i, names))
        });
        let why = match (meeting, together) {
            (Meeting::Strikes(t), _) => match self.strike(&t, now)? {
                None => return Ok(()),
                Some(why) => why,
            },
            // The corner they move on goes past an end of the face, along the face's line:
            // the blocks, each convex, touch there corner on corner with no room to press on
            // each other beyond it, so the push ends at once (no impulse) and they part; the
            // clearance finds the edge that keeps them apart from there, or stops the run where
            // none does.
            (Meeting::Corners, Some((i, _))) => return self.part(i, now, true),
            (Meeting::Flat(Some(t)), Some((i, _))) => match self.flat(i, &t, now)? {
                None => return Ok(()),
                Some(why) => why,
            },
            (Meeting::Flat(_), Some((_, [corner, face]))) => {
                format!("{corner}'s face comes down flat on {face}'s, the two moving together")
            }
            (Meeting::Corners, None) => "two corners meet".into(),
            (Meeting::Flat(_), None) => "a face comes down flat on a face".into(),
            (Meeting::Faces(ends), _) => match self.lies_flat(ends, None, now)? {
                None => return Ok(()),
                Some(why) => why,
            },
        };
        self.meeting_not_followed((a, b), why, now)
    }

    /// The face beside the corner of body i's couple comes down flat on the face the corner
    /// is on: the other end of the faces' overlap strikes (`t`) while the corner stays
    /// ([`Engine::lies_flat`]).
    fn flat(
        &mut self,
        i: usize,
        t: &Touch,
        now: &Inputs,
    ) -> Result<Option<String>, SimulationError> {
        let couple = self.tracks[i].couple.expect("a body of a couple");
        if self.other_end_opens(&couple, t, now) {
            // The face is flat on the other only at this instant, its other end leaving it:
            // what met is the held corner, at an end of the face (as where two blocks' bottom
            // corners are together), sliding off it.
            self.part(i, now, true)?;
            return Ok(None);
        }
        let held = Touch {
            stays: true,
            ..couple.touch_at(couple.bodies.map(|b| b.map(|k| &self.tracks[k].state)))
        };
        self.lies_flat([*t, held], Some(i), now)
    }

    /// Whether the other end `t` of the faces of `couple` leaves its face just after now, the
    /// bodies moving as the couple moves them.
    fn other_end_opens(&self, couple: &Couple, t: &Touch, now: &Inputs) -> bool {
        let slot = |s: Side| match s {
            Side::Body(k, _) => couple.bodies.iter().position(|&b| b == Some(k)),
            _ => None,
        };
        let Some(order) = [slot(t.sides[0]), slot(t.sides[1])]
            .into_iter()
            .collect::<Option<Vec<usize>>>()
        else {
            return false;
        };
        let bodies = [order[0], order[1]].map(|k| couple.bodies[k]);
        let states = bodies.map(|b| b.map(|k| self.tracks[k].state));
        let placed = Couple::placed(
            t,
            bodies,
            [order[0], order[1]].map(|k| couple.home(k)),
            states.each_ref().map(Option::as_ref),
        );
        let trajs = bodies.map(|b| match b {
            Some(k) => self.trajectory(k, now),
            None => Trajectory::start(Mode::Rest, Equations::Exact, &State::default()),
        });
        let (size, scale_t) = t.scales;
        series::sign_after(&placed.approach(&trajs), size, scale_t) > 0
    }

    /// A face comes down flat on a face, and the two ends of their overlap (`ends`) take their
    /// impulses at once ([`collision::resolve_all`], each free to open). Where the pair was held
    /// in contact (`couple`: a body of their couple), `ends[1]` is the corner it moved on, which
    /// takes no restitution, while `ends[0]` strikes; where the pair was apart, both strike with
    /// the wall's restitution (none for an end that has not parted since the last impact).
    /// Where one end stays and the other opens (Housner's law between two blocks: the face
    /// rocks on over one end), the blocks turn on together on the one that stays; where both
    /// open, they part. Where both are left at rest on each other, which ends press and how
    /// each body's pivot moves is decided from the accelerations ([`Engine::pressed_ends`]);
    /// where both press, the faces lie on each other from there ([`Engine::lie`]). Where the
    /// decision or the law has no outcome or several, where one side is a block that does not
    /// move (a face lying on it is not followed), or where a column holds joints the impulse
    /// would pass through, the reason is returned; nothing has changed then.
    fn lies_flat(
        &mut self,
        ends: [Touch; 2],
        couple: Option<usize>,
        now: &Inputs,
    ) -> Result<Option<String>, SimulationError> {
        let [t, held] = &ends;
        // Each end's blocks' names, the corner's first.
        let named = ends
            .each_ref()
            .map(|t| t.blocks.map(|b| self.layout.names[b].clone()));
        let [corner, face] = named[usize::from(couple.is_some())].clone();
        let comes = format!("{corner}'s face comes down flat on {face}'s");
        let ids: Vec<(usize, [f64; 2])> = (held.sides.iter())
            .filter_map(|side| match *side {
                Side::Body(k, origin) => Some((k, origin)),
                _ => None,
            })
            .collect();
        if let Some(&(k, _)) = (ids.iter())
            .find(|&&(k, _)| !self.scene.watches.get(k).is_none_or(Watch::holds_nothing))
        {
            return Ok(Some(format!(
                "{comes}, and {}'s column holds joints the impulse would pass through",
                self.body(k).name
            )));
        }
        if couple.is_none() {
            // From apart, a block held in its column, or a body in contact with a third block,
            // would take the impulses elsewhere too.
            if let Some(k) = (0..2).find(|&k| held.sides[k] == Side::Held) {
                return Ok(Some(format!(
                    "{comes}, and {} stands held in its column under a joint that opened: an \
                     impulse on it is not followed",
                    named[1][k]
                )));
            }
            if let Some(busy) = self.in_contact_elsewhere(&held.sides) {
                return Ok(Some(format!("{comes}, and {busy}")));
            }
        }
        let index = |side: Side| match side {
            Side::Body(k, _) => ids.iter().position(|&(j, _)| j == k),
            _ => None,
        };
        // An end that has not parted since the pair's last impact rattles at the scale of
        // round-off: it takes up what is left of its approach without a rebound.
        let wall = self.scene.wall.map_or(1.0, |(w, _)| w.restitution.to_f64());
        let restitution_of = |t: &Touch| if t.stays { 0.0 } else { wall };
        let restitution = restitution_of(t);
        let links = [
            collision::Link {
                sides: t.sides.map(index),
                contact: collision::Contact {
                    point: t.point,
                    normal: t.normal,
                    restitution,
                },
            },
            collision::Link {
                sides: held.sides.map(index),
                contact: match couple {
                    Some(_) => self.staying(held).1,
                    None => collision::Contact {
                        point: held.point,
                        normal: held.normal,
                        restitution: restitution_of(held),
                    },
                },
            },
        ];
        // A body that rocks upright to a round-off as its face comes flat on a seated block's
        // has both corners of its base on the ground where it turns down onto its seat, or has
        // just landed there and turns on into the face (an end of the faces approaching): they
        // take their impulses with the faces' at once, as a landing while lying does
        // ([`Engine::lying_lands`]).
        let turning: Vec<collision::Turning> = (ids.iter())
            .map(|&(k, origin)| self.turning(k, origin))
            .collect();
        let strikes = ends.iter().any(|t| {
            let contact = collision::Contact {
                point: t.point,
                normal: t.normal,
                restitution: 0.0,
            };
            let sides = t.sides.map(|side| index(side).map(|j| &turning[j]));
            collision::approach(sides, &contact).0 < -t.tie_m_s()
        });
        // What the faces' impulses alone leave of each body's velocities: a body in flight a
        // tie above the ground that they leave coming down lands with them.
        let alone = collision::resolve_all(&turning, &links).ok();
        let pressed_down = |k: usize| {
            let (body, lift) = (self.body(k), self.tracks[k].state.lift);
            let j = ids.iter().position(|&(b, _)| b == k);
            let after = j.zip(alone.as_ref()).map(|(j, all)| all.after[j].lift_v);
            after.is_some_and(|w| {
                lift <= series::TIE * body.size_m() && (w < 0.0 || tie_speed(body, w))
            })
        };
        let upright = |k: usize| {
            let tie = series::TIE * self.body(k).slenderness_rad();
            self.tracks[k].mode.pivot().is_some() && self.tracks[k].state.theta.abs() <= tie
        };
        // Both bodies, where both are upright so (a couple turning together onto both seats),
        // and a body in flight a round-off above the ground, coming down before the impact or
        // after it: each with the corner it lands on from flight (none: on its base).
        let lands = |k: usize| match (self.lands_by_round_off(k), self.tracks[k].mode) {
            (None, _) if strikes && upright(k) => Some(None),
            (None, Mode::Flight(c)) if pressed_down(k) => Some(Some(c)),
            (found, _) => found,
        };
        let mut landing = (ids.iter()).filter_map(|&(k, _)| Some((k, lands(k)?)));
        let landing = [landing.next(), landing.next()];
        let comes = match landing {
            [Some((k, corner)), second] => {
                let why = match () {
                    _ if self.scene.equations != Equations::Exact => {
                        Some("the linearised equations do not follow blocks in contact")
                    }
                    _ if landing
                        .iter()
                        .flatten()
                        .any(|&(j, _)| self.body(j).restitution_factor != 1.0) =>
                    {
                        Some(
                            "a landing that keeps less than Housner's rate (a restitution factor \
                             below one) with the faces' contacts is not followed",
                        )
                    }
                    _ => None,
                };
                let on = |k: usize, corner: Option<Corner>| match corner {
                    None => format!("{} upright on its base", self.body(k).name),
                    Some(c) => format!(
                        "{} landing from free flight on its {} corner",
                        self.body(k).name,
                        c.name()
                    ),
                };
                let comes = match second {
                    None => format!("{comes}, {}", on(k, corner)),
                    Some((j, None)) if corner.is_none() => format!(
                        "{comes}, {} and {} upright on their bases",
                        self.body(k).name,
                        self.body(j).name
                    ),
                    Some((j, other)) => format!("{comes}, {} and {}", on(k, corner), on(j, other)),
                };
                if let Some(why) = why {
                    return Ok(Some(format!("{comes}, and {why}")));
                }
                comes
            }
            _ => comes,
        };
        let through = match landing {
            [Some((k, _)), second] => Through::Landing(k, second.map(|(j, _)| j)),
            _ => Through::Approach,
        };
        // The landing bodies' rotation rates before, and their bases' contacts with the ground
        // (where a refusal below stops the run, their tilts of round-off stay set to zero).
        let mut landed = [None, None];
        for (n, &(k, corner)) in landing.iter().flatten().enumerate() {
            let theta = self.tracks[k].state.theta;
            let pivot = corner.or(self.tracks[k].mode.pivot());
            landed[n] = Some((
                k,
                self.tracks[k].state.omega,
                self.grounded(k, corner, now)?,
            ));
            if let (Some(p), Some(&(_, origin))) = (pivot, ids.iter().find(|&&(j, _)| j == k)) {
                self.set_upright_clear(k, (origin, p), theta, [t, held]);
            }
        }
        let mut bodies: Vec<collision::Turning> = (ids.iter())
            .map(|&(k, origin)| self.turning(k, origin))
            .collect();
        let landed = landed.map(|l| {
            l.map(|(k, before, ground)| {
                let j = ids
                    .iter()
                    .position(|&(b, _)| b == k)
                    .expect("the landing body's side");
                bodies[j].ground = ground;
                (k, j, before)
            })
        });
        let all = match collision::resolve_all(&bodies, &links) {
            Ok(all) => all,
            Err(refusal) => return Ok(Some(format!("{comes}, and {refusal}"))),
        };
        // The landing's event, logged where the run goes on from the impact.
        let bases = match landed {
            [_, Some(_)] => "their bases'",
            _ => "its base's",
        };
        let log_landing = |e: &mut Self| {
            for &(k, j, before) in landed.iter().flatten() {
                let what = format!("{comes}, {bases} contacts and the faces' plastic at once");
                e.logs_landing(k, (before, all.after[j].omega), &what);
            }
        };
        let sides_of = |l: &collision::Link| l.sides.map(|k| k.map(|j| &bodies[j]));
        let (_, speed, _) = collision::approach(sides_of(&links[1]), &links[1].contact);
        let mut stays = [
            all.normal_m_s[0].1 <= t.tie_m_s(),
            all.normal_m_s[1].1
                <= match couple {
                    Some(_) => series::TIE * speed,
                    None => held.tie_m_s(),
                },
        ];
        // Where both ends are left at rest on each other, the words saying so and that the
        // faces turn apart at an end, for the end (or both) that opens all the same.
        let mut at_rest = None;
        if stays == [true, true] && ids.len() < 2 {
            // What the impact leaves of the body's base says which motion would follow: a base
            // that stays as it was, stuck, leaves the blocks no motion (locked face on face);
            // one that lifts or slips leaves a face sliding along the fixed block's.
            let (k, _) = ids[0];
            let (old, after) = (self.tracks[k].mode, &all.after[0]);
            let seated = matches!(old, Mode::Rest | Mode::Slide(_));
            let what = match (after.base, mode_after(after, old, seated)) {
                (collision::Base::Seated { slips: false }, _) => None,
                (collision::Base::Seated { slips: true }, _) => Some("slides on its base"),
                (_, Ok(Mode::Rock(_))) if !seated => None,
                (_, Ok(Mode::Rock(_))) => Some("turns onto a corner"),
                (_, Ok(Mode::Flight(_))) if tie_speed(self.body(k), after.lift_v) => {
                    Some("rises off the ground at a tie's rate")
                }
                (_, Ok(Mode::Flight(_))) => Some("leaves the ground"),
                (_, Ok(_)) => Some("slips at its pivot"),
                (_, Err(what)) => Some(what),
            };
            let how = match what {
                None => {
                    "its base stays, stuck: blocks locked face on face are not followed".to_string()
                }
                Some(what) => format!(
                    "{} {what} through it: a face that moves along a face it lies on is not \
                     followed",
                    self.body(k).name
                ),
            };
            return Ok(Some(format!(
                "{comes}, and both ends of their contact stay on it (impulses {:.6e} and {:.6e} N \
                 s), and {how}",
                all.impulse_n_s[0], all.impulse_n_s[1]
            )));
        }
        if stays == [true, true] {
            let after = links[0].sides.map(|k| k.map(|j| all.after[j]));
            match self.pressed_ends([t, held], &after, through, now) {
                Ok((decision, lying, sides)) if decision.pressed == [true, true] => {
                    if let Some(i) = couple {
                        self.uncouple(i);
                    }
                    log_landing(self);
                    self.rec.energy.impact_loss_j += all.loss_j;
                    self.rec.impacts += 1;
                    self.struck(t);
                    let (bodies, omega) = self.lie(&ends, lying, &decision, &sides, now);
                    let [(b0, a0), (b1, a1)] = [all.normal_m_s[0], all.normal_m_s[1]];
                    let what = format!(
                        "{comes} at the ends of their overlap, their normal velocities {b0:.6e} \
                         and {b1:.6e} m/s before and {a0:.6e} and {a1:.6e} m/s after (impulses \
                         {:.6e} and {:.6e} N s), and both ends press: the faces lie on each \
                         other{bodies}",
                        all.impulse_n_s[0], all.impulse_n_s[1]
                    );
                    let blocks = &t.blocks;
                    let kind = EventKind::BlocksImpact;
                    self.rec
                        .rocking_event(self.t, kind, blocks, Some(omega), what);
                    return Ok(None);
                }
                Ok((decision, ..)) => {
                    let impulses = match couple {
                        Some(_) => format!(
                            " (impulses {:.6e} and {:.6e} N s)",
                            all.impulse_n_s[0], all.impulse_n_s[1]
                        ),
                        None => String::new(),
                    };
                    at_rest = Some(format!(
                        "both ends of their contact at rest on it after the impact{impulses}"
                    ));
                    stays = decision.pressed;
                }
                Err(why) => {
                    return Ok(Some(format!(
                        "{comes}, and both ends of their contact stay on it (impulses {:.6e} and \
                         {:.6e} N s), and {why}",
                        all.impulse_n_s[0], all.impulse_n_s[1]
                    )))
                }
            }
        }
        if let Some(i) = couple {
            self.uncouple(i);
        }
        let [c, f] = &named[0];
        let strikes = format!("{comes}, {c}'s corner striking {f}'s face at its other end");
        // Each side's velocities after, and the impact as one contact's.
        let one = |l: usize, loss_j: f64| {
            let link = &links[l];
            (
                link.sides.map(|k| k.map(|j| bodies[j])),
                collision::Outcome {
                    after: link.sides.map(|k| k.map(|j| all.after[j])),
                    impulse_n_s: all.impulse_n_s[l],
                    normal_m_s: all.normal_m_s[l],
                    loss_j,
                },
            )
        };
        let blow = |e: usize| {
            format!(
                "at {:.6e} m/s, parting at {:.6e} m/s (impulse {:.6e} N s)",
                -all.normal_m_s[e].0, all.normal_m_s[e].1, all.impulse_n_s[e]
            )
        };
        let strike = format!("{strikes} {}", blow(0));
        // From apart: where one end stays, they turn on together on it, the other leaving.
        if let (None, Some(e)) = (couple, stays.iter().position(|&s| s)) {
            let (turning, out) = one(e, all.loss_j);
            let [c, f] = &named[1 - e];
            let why = match &at_rest {
                None => format!(
                    "they stay in contact after the impact (coefficient of restitution {}), \
                     {comes} and {c}'s corner leaves {f}'s face, its normal velocity {:.6e} m/s \
                     before and {:.6e} m/s after (impulse {:.6e} N s)",
                    restitution_of(&ends[e]),
                    all.normal_m_s[1 - e].0,
                    all.normal_m_s[1 - e].1,
                    all.impulse_n_s[1 - e]
                ),
                Some(rest) => format!(
                    "they stay in contact after the impact, {comes}, {rest}, and {c}'s corner \
                     leaves {f}'s face as the faces turn apart there"
                ),
            };
            let stop = self.rests_against(&ends[e], &turning, &out, now, why, through)?;
            if stop.is_none() {
                log_landing(self);
            }
            return Ok(stop);
        }
        if stays[0] {
            // The corner's contact took no impulse: the strike's is the whole impact.
            let (turning, out) = one(0, all.loss_j);
            let why = match &at_rest {
                None => format!(
                    "they stay in contact after the impact (coefficient of restitution \
                     {restitution}), {comes} and {corner}'s corner leaves {face}'s face"
                ),
                Some(rest) => format!(
                    "they stay in contact after the impact, {comes}, {rest}, and {corner}'s \
                     corner leaves {face}'s face as the faces turn apart there"
                ),
            };
            let stop = self.rests_against(t, &turning, &out, now, why, through)?;
            if stop.is_none() {
                log_landing(self);
            }
            return Ok(stop);
        }
        if stays[1] {
            // The strike parts at once: the corner's contact carries the whole impact.
            let (turning, out) = one(1, all.loss_j);
            let why = match &at_rest {
                None => format!("they stay in contact as {strike}"),
                Some(rest) => format!(
                    "they stay in contact as {strike}, {rest}, and the faces turn apart at that \
                     end"
                ),
            };
            // A body landing with the faces lands through it all the same.
            let through = match through {
                Through::Landing(..) => through,
                _ => Through::Blow,
            };
            let stop = self.rests_against(held, &turning, &out, now, why, through)?;
            if stop.is_none() {
                log_landing(self);
                self.clearance.strike(t.pair);
                // The contact that stays counts the impact where it takes an impulse.
                if all.impulse_n_s[1] <= 0.0 {
                    self.rec.impacts += 1;
                    self.struck(t);
                }
            }
            return Ok(stop);
        }
        let apart = match &at_rest {
            None => String::new(),
            Some(rest) => format!(", {rest}, and the faces turn apart from both ends"),
        };
        let mut what = match couple {
            Some(_) => {
                let leaves = format!("{corner}'s corner leaves {face}'s face as {strikes}{apart}");
                self.rec
                    .rocking_event(self.t, EventKind::Separation, &held.blocks, None, leaves);
                strike
            }
            None => {
                let [c1, f1] = &named[1];
                let [(b0, a0), (b1, a1)] = [all.normal_m_s[0], all.normal_m_s[1]];
                format!(
                    "{comes} at the ends of their overlap, {c}'s corner on {f}'s face and {c1}'s \
                     on {f1}'s, their normal velocities {b0:.6e} and {b1:.6e} m/s before and \
                     {a0:.6e} and {a1:.6e} m/s after (impulses {:.6e} and {:.6e} N s){apart}",
                    all.impulse_n_s[0], all.impulse_n_s[1]
                )
            }
        };
        self.clearance.strike(t.pair);
        self.rec.energy.impact_loss_j += all.loss_j;
        self.rec.impacts += 1;
        self.struck(t);
        log_landing(self);
        let mut omega = None;
        let mut decide = Vec::new();
        for (j, &(k, _)) in ids.iter().enumerate() {
            let before = self.tracks[k].state.omega;
            omega.get_or_insert((before, all.after[j].omega));
            let (how, decides) = self.take(k, &all.after[j]);
            what += &format!(
                "; {}: theta' {before:.6e} -> {:.6e} rad/s, {how}",
                self.body(k).name,
                all.after[j].omega
            );
            if decides {
                decide.push(k);
            }
        }
        self.rec
            .rocking_event(self.t, EventKind::BlocksImpact, &t.blocks, omega, what);
        for k in decide {
            self.decide(k, now, false)?;
        }
        Ok(None)
    }

    /// Which ends of two faces lying on each other press just after an impact that left both
    /// at rest on each other, and each body's mode ([`Lying::decide`]); `ends`: the strike's
    /// contact, then the other end's; `after`: the velocities of the first end's sides;
    /// `through`: what gave the impulses. With the decision, the faces' two contacts and the
    /// bodies' states after the impact (in the first end's order); else why not, in words.
    fn pressed_ends(
        &self,
        ends: [&Touch; 2],
        after: &[Option<collision::After>; 2],
        through: Through,
        now: &Inputs,
    ) -> Result<(Decision, Lying, Sides), String> {
        let sides = self.sides_after(ends[0], after, through).map_err(|what| {
            format!(
                "{what}: faces lying on each other are followed only while each body is seated, \
                 rocks on a pivot or flies"
            )
        })?;
        let [Some(a), Some(b)] = sides.bodies else {
            return Err(
                "a face lying on the face of a block that does not move is not followed".into(),
            );
        };
        // Both ends are between the pair's blocks, the sides' bodies.
        let lying = Lying::new(ends, [a, b], sides.homes, sides.states.each_ref());
        let members = [a, b].map(|i| self.body(i));
        let members = [0, 1].map(|k| Member::Moves(members[k], sides.modes[k], &sides.states[k]));
        let decision = lying.decide(members, now)?;
        Ok((decision, lying, sides))
    }

    /// Where a body on `sides` is in contact with a third block (turning with it or resting
    /// against it), why the exact model does not follow the contact of `sides` besides.
    fn in_contact_elsewhere(&self, sides: &[Side; 2]) -> Option<String> {
        let (k, blocks) = sides.iter().find_map(|side| match *side {
            Side::Body(k, _) => {
                let tr = &self.tracks[k];
                let other = (tr.couple.map(|c| c.touch.blocks))
                    .or(tr.leans.map(|l| l.touch.blocks))
                    .or(tr.lies.map(|l| l.ends[0].touch.blocks));
                other.map(|blocks| (k, blocks))
            }
            _ => None,
        })?;
        let [corner, face] = blocks.map(|b| self.layout.names[b].as_str());
        Some(format!(
            "{} is in contact with another block too ({corner}'s corner on {face}'s face): blocks \
             in contact on two sides at once are not followed",
            self.body(k).name
        ))
    }

    /// The faces of `lying` lie on each other from here, both ends pressing (`ends`, as the
    /// clearance watches them), each body in the mode `decision` gives it from its state after
    /// an impact (`sides`, in the first end's order; what that settles of the impact law's
    /// round-off goes with the impact's loss). Returns the words of each body's change and of
    /// the pushes, and the first body's rotation rate before and after.
    fn lie(
        &mut self,
        ends: &[Touch; 2],
        lying: Lying,
        decision: &Decision,
        sides: &Sides,
        now: &Inputs,
    ) -> (String, (f64, f64)) {
        let bodies = sides.bodies;
        let mut settled = [0, 1].map(|k| match bodies[k] {
            Some(i) => settled_in(self.body(i), decision.modes[k], sides.states[k]),
            None => sides.states[k],
        });
        // Side faces lying on each other keep the bodies' rotations equal: on a seated body's
        // face, the other stands upright, what the impact law leaves of its tilt and turning
        // a round-off.
        let seated = decision
            .modes
            .map(|m| matches!(m, Mode::Rest | Mode::Slide(_)));
        for k in 0..2 {
            if let (true, Some(i)) = (seated[1 - k], bodies[k]) {
                if upright_by_round_off(self.body(i), &settled[k]) {
                    (settled[k].theta, settled[k].omega) = (0.0, 0.0);
                }
            }
        }
        let (before, after) = (
            self.energies_j(bodies, sides.modes, &sides.states, now),
            self.energies_j(bodies, decision.modes, &settled, now),
        );
        self.rec.energy.impact_loss_j += (before.0 - after.0) + (before.1 - after.1);
        let mut what = String::new();
        let mut omega = (0.0, 0.0);
        for k in 0..2 {
            let i = bodies[k].expect("the sides of lying faces are bodies");
            let (mode, state) = (decision.modes[k], settled[k]);
            let tr = &mut self.tracks[i];
            let before = tr.state.omega;
            if k == 0 {
                omega = (before, state.omega);
            }
            (tr.mode, tr.state, tr.lies) = (mode, state, Some(lying));
            what += &format!(
                "; {}: theta' {before:.6e} -> {:.6e} rad/s, {}",
                self.body(i).name,
                state.omega,
                in_mode(mode, &state)
            );
        }
        self.clearance.lie(ends[0].pair, Some(ends));
        self.close_contacts(&self.lying_touches(&lying), None, now);
        let [p0, p1] = lying.motion(self.members(&lying.ends[0]), now).pushes;
        what += &format!("; pushed by {:.6e} and {:.6e} N", p0[0], p1[0]);
        (what, omega)
    }

    /// The contacts `touches` stay closed from here (a couple's one contact, or both ends of
    /// faces lying on each other): their normal velocities, round-off where a decision made a
    /// rate at a tie zero (a slip, a rise), are made zero, each body changing the velocities its
    /// mode leaves free by the least that does it ([`collision::closing_all`]; the slip of the
    /// body `stuck`, whose pivot has just stuck, stays zero), so that the pushes do no work; what
    /// that changes of the kinetic energy goes with the impacts' loss.
    fn close_contacts(&mut self, touches: &[Touch], stuck: Option<usize>, now: &Inputs) {
        let sides = touches[0].sides.map(|side| match side {
            Side::Body(k, origin) => Some((k, origin)),
            _ => None,
        });
        let moving: Vec<(usize, [f64; 2])> = sides.into_iter().flatten().collect();
        let turning: Vec<collision::Turning> = (moving.iter())
            .map(|&(k, origin)| self.turning(k, origin))
            .collect();
        let index = |side: Side| match side {
            Side::Body(k, _) => moving.iter().position(|&(j, _)| j == k),
            _ => None,
        };
        let links: Vec<collision::Link> = (touches.iter())
            .map(|t| collision::Link {
                sides: t.sides.map(index),
                contact: collision::Contact {
                    point: t.point,
                    normal: t.normal,
                    restitution: 0.0,
                },
            })
            .collect();
        let free: Vec<[bool; 3]> = (moving.iter())
            .map(|&(k, _)| {
                let slips = stuck != Some(k);
                match self.tracks[k].mode {
                    Mode::Rest => [false; 3],
                    Mode::Slide(_) => [slips, false, false],
                    Mode::Rock(_) => [false, true, false],
                    Mode::SlideRock(..) => [slips, true, false],
                    Mode::Flight(_) => [true; 3],
                }
            })
            .collect();
        let Some(change) = collision::closing_all(&turning, &links, &free) else {
            return;
        };
        let bodies = sides.map(|side| side.map(|(k, _)| k));
        let modes = bodies.map(|b| b.map_or(Mode::Rest, |k| self.tracks[k].mode));
        let (was, _) = self.energies_j(bodies, modes, &self.states_of(bodies), now);
        for (&(k, _), [dv, domega, dw]) in moving.iter().zip(change) {
            let st = &mut self.tracks[k].state;
            (st.v, st.omega, st.lift_v) = (st.v + dv, st.omega + domega, st.lift_v + dw);
        }
        let (is, _) = self.energies_j(bodies, modes, &self.states_of(bodies), now);
        self.rec.energy.impact_loss_j += was - is;
    }

    /// Both ends of `lying` where its bodies are now, as touches.
    fn lying_touches(&self, lying: &Lying) -> [Touch; 2] {
        let bodies = lying
            .bodies()
            .map(|b| b.expect("the sides of lying faces are bodies"));
        lying.touches_at(bodies.map(|k| &self.tracks[k].state))
    }

    /// The states of `bodies` (a fixed block's side: at rest).
    fn states_of(&self, bodies: [Option<usize>; 2]) -> [State; 2] {
        bodies.map(|b| b.map_or_else(State::default, |k| self.tracks[k].state))
    }

    /// The bodies' kinetic and potential energies (J) in `modes` and `states` (none for a
    /// fixed block's side), each body's trajectory formed once for both.
    fn energies_j(
        &self,
        bodies: [Option<usize>; 2],
        modes: [Mode; 2],
        states: &[State; 2],
        now: &Inputs,
    ) -> (f64, f64) {
        (0..2)
            .filter_map(|k| {
                let body = self.body(bodies[k]?);
                let traj = modes::trajectory(body, Equations::Exact, modes[k], &states[k], now);
                Some((
                    modes::kinetic_j(body, &traj, 0.0),
                    modes::potential_j(body, &traj, 0.0),
                ))
            })
            .fold((0.0, 0.0), |(k, p), (dk, dp)| (k + dk, p + dp))
    }

    /// The slips of the bodies `which` picks among `bodies` stop: each slip located to
    /// round-off, set to zero. What it carried of kinetic energy (with a turning body a term of
    /// first order in it, m v omega G_y) counts as lost, so the balance closes to round-off.
    fn stills(&mut self, bodies: [Option<usize>; 2], which: impl Fn(usize) -> bool, now: &Inputs) {
        let modes = bodies.map(|b| b.map_or(Mode::Rest, |k| self.tracks[k].mode));
        let was = self.states_of(bodies);
        for k in bodies.into_iter().flatten().filter(|&k| which(k)) {
            self.tracks[k].state.v = 0.0;
        }
        let is = self.states_of(bodies);
        let ((before, _), (after, _)) = (
            self.energies_j(bodies, modes, &was, now),
            self.energies_j(bodies, modes, &is, now),
        );
        self.rec.energy.impact_loss_j += before - after;
    }

    /// A seated body (i) lifts off the corner whose share of the load fell to zero: the corner
    /// it turns on.
    fn lifts_on(&self, i: usize, now: &Inputs) -> Corner {
        let (left, _) = self
            .trajectory(i, now)
            .corners
            .expect("a seated body's corners");
        let body = self.body(i);
        let force = modes::Scales::of(body).force;
        if series::sign_after(&left, force, body.time_scale_s()) > 0 {
            Corner::Left
        } else {
            Corner::Right
        }
    }

    /// Body i, whose face lies on another's, reaches a change of their mechanism (`guard`): a
    /// push falls to zero, or a condition of a body's pivot (to slip, to stick, to leave the
    /// ground; a seated body's, to lift). Which ends press and each body's mode are decided
    /// again ([`Lying::decide`]; a seated body that lifts, on the corner that keeps its load).
    /// Where both ends press, the faces lie on each other on, in the modes decided; where one
    /// does, the bodies turn on together on it (a couple); where none does, they part, each in
    /// its mode alone; where the decision fails, the run stops, saying why. At a pivot's
    /// change, a body a round-off from landing lands now instead ([`Engine::lying_lands`]).
    fn relie(&mut self, i: usize, guard: Guard, now: &Inputs) -> Result<(), SimulationError> {
        let mut lying = self.tracks[i].lies.expect("a body of lying faces");
        let mut bodies = lying
            .bodies()
            .map(|b| b.expect("the sides of lying faces are bodies"));
        let abutting = lying.abutting(self.members(&lying.ends[0])).is_some();
        if matches!(guard, Guard::PivotStick | Guard::Stop) {
            // Seated face on face, the two slide as one and stop together.
            self.stills(bodies.map(Some), |k| k == i || abutting, now);
        }
        if guard != Guard::Parts {
            let round_off = |j: usize| Some((j, self.lands_by_round_off(j)?));
            if let Some((j, corner)) = bodies.into_iter().find_map(round_off) {
                return self.lying_lands(j, corner, now);
            }
        }
        let states = bodies.map(|k| self.tracks[k].state);
        let mut touches = lying.touches_at(states.each_ref());
        let names = |t: &Touch| t.blocks.map(|b| self.layout.names[b].clone());
        let [a, b] = names(&touches[0]);
        let blocks = (touches[0].blocks[0], touches[0].blocks[1]);
        if guard == Guard::Uplift && abutting {
            // Both turn, if at all, toward where the ground's inertial force on them points;
            // where their bottom corners are together, the contact there is the corner of the
            // block that would lift it on the other's face.
            let absolute = now.accel[0] + self.trajectory(i, now).v[1];
            let pivot = Abutting::tipping_corner(absolute);
            for t in touches.iter_mut() {
                *t = abutting::lifting_corner(t, pivot);
            }
            let homes = [0, 1].map(|s| {
                let Side::Body(k, origin) = lying.ends[0].touch.sides[s] else {
                    unreachable!("a body's side of lying faces");
                };
                self.home(k, origin, pivot)
            });
            lying = Lying::new(touches.each_ref(), bodies, homes, states.each_ref());
            bodies = lying
                .bodies()
                .map(|b| b.expect("the sides of lying faces are bodies"));
        } else if guard == Guard::Uplift {
            // A seated body lifts off the corner whose share of the load fell to zero.
            let pivot = self.lifts_on(i, now);
            let k = usize::from(bodies[1] == i);
            if lying.ends[0].pivots[k] != pivot {
                let Side::Body(_, origin) = lying.ends[0].touch.sides[k] else {
                    unreachable!("a body's side of lying faces");
                };
                let homes = [0, 1].map(|s| match s == k {
                    true => self.home(i, origin, pivot),
                    false => lying.ends[0].home(s),
                });
                lying = Lying::new(touches.each_ref(), bodies, homes, states.each_ref());
            }
        }
        let decision = match lying.decide(self.members(&lying.ends[0]), now) {
            Ok(decision) => decision,
            Err(why) => {
                return self.meeting_not_followed(
                    blocks,
                    format!("{a}'s face lies on {b}'s, and {why}"),
                    now,
                );
            }
        };
        self.rec.stats.mode_decisions += 1;
        let within = format!(", in the faces of {a} and {b} lying on each other");
        let modes = decision.modes.map(Some);
        if decision.pressed == [true, true] {
            // The push touched zero and presses on, or the pivots change under both pushes.
            for k in bodies {
                self.tracks[k].lies = Some(lying);
            }
            if abutting {
                // Its ends as the decision took them.
                self.clearance.lie(touches[0].pair, Some(&touches));
            }
            self.retake(bodies.map(Some), modes, &within);
            self.close_contacts(&self.lying_touches(&lying), None, now);
            return Ok(());
        }
        for k in bodies {
            self.tracks[k].lies = None;
        }
        self.clearance.lie(touches[0].pair, None);
        let how = match decision.pressed.iter().position(|&p| p) {
            Some(e) => {
                let couple = lying.ends[e];
                for k in bodies {
                    self.tracks[k].couple = Some(couple);
                }
                self.clearance.hold(touches[e].pair, Some(&couple.touch));
                let [c, f] = names(&touches[1 - e]);
                format!(
                    "{c}'s corner leaves {f}'s face, which no longer pushes on it: the faces that \
                     lay on each other turn apart at that end, the bodies turning on together on \
                     the other"
                )
            }
            None => format!("{a}'s and {b}'s faces, which lay on each other, part at both ends"),
        };
        self.rec
            .rocking_event(self.t, EventKind::Separation, &touches[0].blocks, None, how);
        self.retake(bodies.map(Some), modes, &within);
        Ok(())
    }

    /// Body i, whose face lies on another's, lands (on its base, or from flight on `corner`):
    /// the landing's impulses and both ends' at once, plastic ([`collision::resolve_all`], the
    /// law of a landing in a couple with one more contact). Where both ends stay, which press
    /// is decided from the accelerations ([`Engine::pressed_ends`]); where both do, the faces
    /// lie on each other on, in the modes decided. Where both ends open (or none presses), the
    /// bodies part; where one stays (or presses), they turn on together on it (or the body
    /// rests against the other, as after any impact that leaves a contact). The other body,
    /// where its landing is due at this instant too or it is a round-off from landing, lands
    /// with it: the law takes both bodies' ground contacts with both ends. Where the law or the
    /// decision has no outcome, the run stops, saying why.
    fn lying_lands(
        &mut self,
        i: usize,
        corner: Option<Corner>,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let lying = self.tracks[i].lies.expect("a body of lying faces");
        if let Some(due) = self.landings.get_mut(i) {
            // Taken here, wherever it was found: not again at this stop.
            *due = None;
        }
        let bodies = lying
            .bodies()
            .map(|b| b.expect("the sides of lying faces are bodies"));
        let ends = self.lying_touches(&lying);
        let [a, b] = ends[0].blocks.map(|k| self.layout.names[k].clone());
        let landing = |name: &str, c: Option<Corner>| match c {
            None => format!("{name} lands on its base"),
            Some(c) => format!("{name} lands from free flight on its {} corner", c.name()),
        };
        let j = bodies[usize::from(bodies[0] == i)];
        // Due on the trajectory it had at this stop, where nothing has moved it since.
        let due =
            self.landings.get(j).copied().flatten().filter(|_| {
                self.reached.get(j) == Some(&(self.tracks[j].mode, self.tracks[j].state))
            });
        let partner = due.or(self.lands_by_round_off(j));
        let lands = match partner {
            None => landing(&self.body(i).name, corner),
            Some(c) => format!(
                "{} and {}",
                landing(&self.body(i).name, corner),
                landing(&self.body(j).name, c)
            ),
        };
        let comes = format!("{lands} while {a}'s face lies on {b}'s");
        let pair = (ends[0].blocks[0], ends[0].blocks[1]);
        let housner = |k: usize| self.body(k).restitution_factor == 1.0;
        let why = match () {
            _ if self.scene.equations != Equations::Exact => {
                Some("the linearised equations do not follow blocks in contact")
            }
            _ if !housner(i) || (partner.is_some() && !housner(j)) => Some(
                "a landing that keeps less than Housner's rate (a restitution factor below one) \
                 with two contacts is not followed",
            ),
            _ => None,
        };
        if let Some(why) = why {
            return self.meeting_not_followed(pair, format!("{comes}, and {why}"), now);
        }
        if partner.is_some() {
            if let Some(due) = self.landings.get_mut(j) {
                *due = None;
            }
        }
        for k in bodies {
            self.tracks[k].lies = None;
        }
        self.clearance.lie(ends[0].pair, None);
        let landed = [Some((i, corner)), partner.map(|c| (j, c))];
        let before = landed.map(|l| l.map(|(k, _)| self.tracks[k].state.omega));
        let ids = ends[0].sides.map(|side| match side {
            Side::Body(k, origin) => (k, origin),
            _ => unreachable!("the sides of lying faces are bodies"),
        });
        let mut grounds = [None, None];
        for (n, &(k, c)) in landed.iter().flatten().enumerate() {
            let (theta, pivot) = (
                self.tracks[k].state.theta,
                c.or(self.tracks[k].mode.pivot()),
            );
            grounds[n] = Some((k, self.grounded(k, c, now)?));
            if let Some(p) = pivot {
                let origin = ids[usize::from(ids[0].0 != k)].1;
                self.set_upright_clear(k, (origin, p), theta, ends.each_ref());
            }
        }
        let mut turning = ids.map(|(k, origin)| self.turning(k, origin));
        for (k, ground) in grounds.into_iter().flatten() {
            turning[usize::from(ids[0].0 != k)].ground = ground;
        }
        let index = |side: Side| match side {
            Side::Body(k, _) => ids.iter().position(|&(b, _)| b == k),
            _ => None,
        };
        let links = ends.each_ref().map(|t| collision::Link {
            sides: t.sides.map(index),
            contact: collision::Contact {
                point: t.point,
                normal: t.normal,
                restitution: 0.0,
            },
        });
        let all = match collision::resolve_all(&turning, &links) {
            Ok(all) => all,
            Err(refusal) => {
                return self.meeting_not_followed(pair, format!("{comes}, and {refusal}"), now);
            }
        };
        let mut stays = [0, 1].map(|e| all.normal_m_s[e].1 <= ends[e].tie_m_s());
        // Where both ends stay, which press decides how the faces go on.
        let mut pressed = None;
        if stays == [true, true] {
            let after = links[0].sides.map(|k| k.map(|n| all.after[n]));
            let through = Through::Landing(i, partner.map(|_| j));
            match self.pressed_ends([&ends[0], &ends[1]], &after, through, now) {
                Ok(decided) => {
                    stays = decided.0.pressed;
                    pressed = Some(decided);
                }
                Err(why) => {
                    let why = format!(
                        "{comes}, and both ends of their contact stay on it (impulses {:.6e} and \
                         {:.6e} N s), and {why}",
                        all.impulse_n_s[0], all.impulse_n_s[1]
                    );
                    return self.meeting_not_followed(pair, why, now);
                }
            }
        }
        let contacts = if partner.is_some() {
            "the four"
        } else {
            "the three"
        };
        for (&(k, _), before) in landed.iter().flatten().zip(before.into_iter().flatten()) {
            let after = all.after[usize::from(ids[0].0 != k)].omega;
            let what = format!("{comes}, {contacts} contacts plastic at once");
            self.logs_landing(k, (before, after), &what);
        }
        if let Some((decision, lying, sides)) = pressed.filter(|d| d.0.pressed == [true, true]) {
            self.rec.energy.impact_loss_j += all.loss_j;
            if all.impulse_n_s.iter().any(|&j| j > 0.0) {
                self.rec.impacts += 1;
                self.struck(&ends[0]);
            }
            let (bodies, omega) = self.lie(&ends, lying, &decision, &sides, now);
            let what = format!(
                "both ends of the contact of {a}'s face with {b}'s stay on it as {lands} \
                 (impulses {:.6e} and {:.6e} N s), and both press: the faces lie on each other \
                 on{bodies}",
                all.impulse_n_s[0], all.impulse_n_s[1]
            );
            let kind = EventKind::BlocksImpact;
            self.rec
                .rocking_event(self.t, kind, &ends[0].blocks, Some(omega), what);
            return Ok(());
        }
        match stays.iter().position(|&s| s) {
            None => {
                // Both ends open: each body on in the mode its velocities give.
                self.rec.energy.impact_loss_j += all.loss_j;
                self.rec.rocking_event(
                    self.t,
                    EventKind::Separation,
                    &ends[0].blocks,
                    None,
                    format!(
                        "{a}'s and {b}'s faces, which lay on each other, part at both ends as \
                         {lands}, at {:.6e} and {:.6e} m/s",
                        all.normal_m_s[0].1, all.normal_m_s[1].1
                    ),
                );
                for (n, &(k, _)) in ids.iter().enumerate() {
                    let (_, decides) = self.take(k, &all.after[n]);
                    if decides {
                        self.decide(k, now, false)?;
                    }
                }
            }
            Some(e) => {
                let t = &ends[e];
                let [c, f] = ends[1 - e].blocks.map(|k| self.layout.names[k].clone());
                let sides = links[e].sides.map(|k| k.map(|n| turning[n]));
                let out = collision::Outcome {
                    after: links[e].sides.map(|k| k.map(|n| all.after[n])),
                    impulse_n_s: all.impulse_n_s[e],
                    normal_m_s: all.normal_m_s[e],
                    loss_j: all.loss_j,
                };
                let why = format!(
                    "they stay in contact as {lands}, {c}'s corner leaving {f}'s face at the other \
                     end of the faces that lay on each other"
                );
                let through = Through::Landing(i, partner.map(|_| j));
                if let Some(why) = self.rests_against(t, &sides, &out, now, why, through)? {
                    self.meeting_not_followed(pair, why, now)?;
                }
            }
        }
        Ok(())
    }

    /// Body i, whose face lies on another's, would change its mode otherwise than by a landing
    /// (`guard`: lie on its face): the exact model does not follow that; the run ends here and
    /// says so, unless both bodies are a billionth of their alpha from rest and are set down
    /// ([`Engine::meeting_not_followed`]).
    fn lying_gives(&mut self, i: usize, guard: Guard, now: &Inputs) -> Result<(), SimulationError> {
        let lying = self.tracks[i].lies.expect("a body of lying faces");
        let blocks = lying.ends[0].touch.blocks;
        let [a, b] = blocks.map(|k| self.layout.names[k].as_str());
        let why = format!(
            "{a}'s face lies on {b}'s, pressed at both ends of their overlap, and {} would {}: \
             a change of such a mechanism is not followed",
            self.body(i).name,
            breaks(guard)
        );
        self.meeting_not_followed((blocks[0], blocks[1]), why, now)
    }

    /// The pair of faces lying on each other (`lying`) meets: an end of their overlap reaches
    /// an end of the face it is on (`Meeting::Faces`, the ends from there: the faces slide
    /// along each other, and the end passes to the other face's corner, the pushes going on),
    /// or the overlap is gone (the faces slide off each other, corner on corner: they part).
    fn lying_meets(
        &mut self,
        lying: Lying,
        meeting: Meeting,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let bodies = lying
            .bodies()
            .map(|b| b.expect("the sides of lying faces are bodies"));
        let old = self.lying_touches(&lying);
        let [a, b] = old[0].blocks.map(|k| self.layout.names[k].clone());
        let ends = match meeting {
            Meeting::Faces(ends) => ends,
            Meeting::Corners => {
                for k in bodies {
                    self.tracks[k].lies = None;
                }
                self.clearance.lie(old[0].pair, None);
                self.rec.rocking_event(
                    self.t,
                    EventKind::Separation,
                    &old[0].blocks,
                    None,
                    format!(
                        "{a}'s and {b}'s faces, which lay on each other, slide off each other's \
                         ends, corner on corner: they part"
                    ),
                );
                for k in bodies {
                    self.decide(k, now, false)?;
                }
                return Ok(());
            }
            _ => unreachable!("lying faces meet only where their overlap's ends move"),
        };
        // Each body's pivot's home, from the contacts it had; the first new end's order.
        let home = |k: usize| {
            let side = usize::from(lying.ends[0].bodies[0] != Some(k));
            lying.ends[0].home(side)
        };
        let order = ends[0].sides.map(|s| match s {
            Side::Body(k, _) => k,
            _ => unreachable!("the sides of lying faces are bodies"),
        });
        let states = order.map(|k| self.tracks[k].state);
        let new = Lying::new(ends.each_ref(), order, order.map(home), states.each_ref());
        if !new.turns(self.members(&new.ends[0])) {
            return self.meeting_not_followed(
                (old[0].blocks[0], old[0].blocks[1]),
                format!(
                    "{a}'s and {b}'s faces lie on each other, and an end of their overlap passes \
                     to a corner that is both bodies' pivots: its push would turn neither body"
                ),
                now,
            );
        }
        for k in bodies {
            self.tracks[k].lies = Some(new);
        }
        self.clearance.lie(ends[0].pair, Some(&ends));
        let moved = (ends.iter())
            .find(|t| {
                !old.iter()
                    .any(|o| o.blocks == t.blocks && o.corner == t.corner)
            })
            .unwrap_or(&ends[0]);
        let [c, f] = moved.blocks.map(|k| self.layout.names[k].as_str());
        let how = format!(
            "the faces lying on each other slide along each other: an end of their overlap \
             passes to {c}'s corner, on {f}'s face"
        );
        self.rec
            .rocking_event(self.t, EventKind::Touch, &moved.blocks, None, how);
        Ok(())
    }

    /// Counts an impact at `t` for each of its blocks that moves.
    fn struck(&mut self, t: &Touch) {
        for (side, &block) in t.sides.iter().zip(&t.blocks) {
            if let Side::Body(..) = side {
                self.rec.rocking_impact(block);
            }
        }
    }

    /// Logs body k's landing, `what` it was, with its theta' before and after (rad/s).
    fn logs_landing(&mut self, k: usize, (before, after): (f64, f64), what: &str) {
        self.rec.rocking_event(
            self.t,
            EventKind::RockingImpact,
            &self.layout.outputs(k),
            Some((before, after)),
            format!("{what}: theta' {before:.6e} -> {after:.6e} rad/s"),
        );
    }

    /// Where blocks a and b meet (or touch) and the exact model has no way on (`why`): both
    /// bodies set down seated where both are within [`ZENO_ROTATION`] of their alpha from it
    /// ([`Engine::sets_down`]), else the run stops there.
    fn meeting_not_followed(
        &mut self,
        blocks: (usize, usize),
        why: String,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        if !self.sets_down(blocks, &why, now)? {
            self.stops_meeting(blocks, why);
        }
        Ok(())
    }

    /// Whether body i's motion is below what the model follows: what it has of kinetic and
    /// potential energy beyond rest would turn it, against gravity alone, by at most
    /// [`ZENO_ROTATION`] of its alpha (m g b ZENO_ROTATION alpha), and it is in contact with no
    /// block but those of `other`'s body.
    fn nearly_seated(&self, i: usize, other: usize, now: &Inputs) -> bool {
        let (tr, body) = (&self.tracks[i], self.body(i));
        let alone = |k: usize| k == i || k == other;
        let contacts = tr.leans.is_none()
            && tr.couple.is_none_or(|c| c.moving().all(alone))
            && tr
                .lies
                .is_none_or(|l| l.bodies().into_iter().flatten().all(alone));
        let free =
            tr.fallen.is_none() && self.scene.watches.get(i).is_none_or(Watch::holds_nothing);
        if !(contacts && free) {
            return false;
        }
        let traj = modes::trajectory(body, Equations::Exact, tr.mode, &tr.state, now);
        let energy = modes::kinetic_j(body, &traj, 0.0) + modes::potential_j(body, &traj, 0.0);
        let zeno =
            body.mass_kg * body.g_m_s2 * body.half_base_m * ZENO_ROTATION * body.slenderness_rad();
        energy <= zeno
    }

    /// Where blocks a and b meet and the exact model has no way on (`why`), each moved by a
    /// body within [`ZENO_ROTATION`] of its alpha from seated ([`Engine::nearly_seated`]), one
    /// of them not seated yet: both are set down seated, at rest, and go on from there, lying
    /// face on face where they touch so (decided as a pair at rest is, [`Engine::relie`]), else
    /// each on its own. What they had of kinetic and potential energy beyond it counts as lost,
    /// as what a body's series of landings leaves out does; counted with those series (`zeno`).
    /// Where they would touch otherwise, or another block touches them, nothing is done: false.
    fn sets_down(
        &mut self,
        blocks: (usize, usize),
        why: &str,
        now: &Inputs,
    ) -> Result<bool, SimulationError> {
        let Some((pair, [Some(a), Some(b)])) = self.clearance.pair_of(blocks) else {
            return Ok(false);
        };
        let seated = |e: &Self, k: usize| {
            let st = &e.tracks[k].state;
            matches!(e.tracks[k].mode, Mode::Rest | Mode::Slide(_)) && st.v == 0.0
        };
        if a == b
            || self.scene.equations != Equations::Exact
            || !self.nearly_seated(a, b, now)
            || !self.nearly_seated(b, a, now)
            || (seated(self, a) && seated(self, b))
        {
            return Ok(false);
        }
        let pair_bodies = [a, b];
        let down = pair_bodies.map(|k| State {
            u: self.tracks[k].state.u,
            ..State::default()
        });
        let trajs: Vec<Option<Trajectory>> = (0..self.tracks.len())
            .map(|k| match pair_bodies.iter().position(|&j| j == k) {
                Some(n) => Some(modes::trajectory(
                    self.body(k),
                    Equations::Exact,
                    Mode::Rest,
                    &down[n],
                    now,
                )),
                None => (self.tracks[k].fallen.is_none()).then(|| self.trajectory(k, now)),
            })
            .collect();
        let trajs: Vec<Option<&Trajectory>> = trajs.iter().map(Option::as_ref).collect();
        let bodies = self.scene.bodies;
        let elsewhere = pair_bodies
            .iter()
            .any(|&k| (self.clearance.touching(k, bodies, &trajs).iter()).any(|t| t.pair != pair));
        if elsewhere {
            return Ok(false);
        }
        let modes = pair_bodies.map(|k| self.tracks[k].mode);
        let states = pair_bodies.map(|k| self.tracks[k].state);
        let Some(lies) = self.clearance.set_down(pair, bodies, &trajs) else {
            return Ok(false);
        };
        let ids = pair_bodies.map(Some);
        let before = self.energies_j(ids, modes, &states, now);
        let after = self.energies_j(ids, [Mode::Rest; 2], &down, now);
        self.rec.energy.impact_loss_j += (before.0 - after.0) + (before.1 - after.1);
        self.rec.zeno += 1;
        for (n, &k) in pair_bodies.iter().enumerate() {
            let other = self.body(pair_bodies[1 - n]).name.clone();
            let tr = &mut self.tracks[k];
            (tr.mode, tr.state, tr.couple, tr.lies) = (Mode::Rest, down[n], None, None);
            tr.settles = None;
            if let Some(due) = self.landings.get_mut(k) {
                *due = None;
            }
            let st = &states[n];
            self.rec.rocking_event(
                self.t,
                EventKind::Rest,
                &self.layout.outputs(k),
                Some((st.omega, 0.0)),
                format!(
                    "set down seated beside {other} (tilt {:.6e} rad, rate {:.6e} rad/s: what it \
                     had beyond rest would turn it by less than {ZENO_ROTATION:e} of its alpha), \
                     where {why}",
                    st.theta, st.omega
                ),
            );
        }
        match lies {
            Seated::FaceOnFace(ends) => {
                let i = self.abut(*ends)?;
                self.relie(i, Guard::StickLimit, now)?;
            }
            _ => {
                for k in pair_bodies {
                    self.decide(k, now, false)?;
                }
            }
        }
        Ok(true)
    }

    /// The exact model stops where blocks a and b meet (or touch), for the reason `why`.
    fn stops_meeting(&mut self, (a, b): (usize, usize), why: String) {
        let (first, second) = (self.layout.names[a].clone(), self.layout.names[b].clone());
        self.rec.rocking_event(
            self.t,
            EventKind::BlocksMeet,
            &[a, b],
            None,
            format!("{first} meets {second}: {why}"),
        );
        self.stops(Warning::BlocksMeet {
            first,
            second,
            why,
            time_s: self.t,
        });
    }

    /// The fixed block body i rests against lets go of it: the body turns away, in the mode
    /// its state now gives, and its pair must part before it may strike again.
    fn lets_go(&mut self, i: usize, now: &Inputs) -> Result<(), SimulationError> {
        let lean = self.tracks[i]
            .leans
            .take()
            .expect("a body resting against a block");
        self.clearance.lean(lean.touch.pair, false);
        let [own, other] = lean.blocks.map(|k| self.layout.names[k].clone());
        self.rec.rocking_event(
            self.t,
            EventKind::Separation,
            &lean.blocks,
            None,
            format!("{own} turns away from {other}'s face, which no longer pushes on it"),
        );
        self.decide(i, now, false)
    }

    /// Ends body i's couple: its bodies move each on its own from here, and their pair must
    /// part before it may strike again.
    fn uncouple(&mut self, i: usize) -> Couple {
        let couple = self.tracks[i].couple.expect("a body of a couple");
        for k in couple.moving() {
            self.tracks[k].couple = None;
        }
        self.clearance.hold(couple.touch.pair, None);
        couple
    }

    /// The bodies of body i's couple part: the push between them falls to zero, or (`off_end`)
    /// the corner slides off an end of the face. Each turns on in the mode its state now
    /// gives, and the pair must part before it may strike again.
    fn part(&mut self, i: usize, now: &Inputs, off_end: bool) -> Result<(), SimulationError> {
        let couple = self.uncouple(i);
        if !off_end {
            let (pair, t) = (couple.touch.pair, self.t);
            let again = match self.parted {
                Some((p, at, n)) if (p, at) == (pair, t) => n,
                _ => 0,
            };
            self.parted = Some((pair, t, again + 1));
        }
        let [corner, face] = couple.touch.blocks.map(|k| self.layout.names[k].clone());
        let how = match off_end {
            true => format!("{corner}'s corner slides off an end of {face}'s face: the two part"),
            false => {
                format!("{corner}'s corner leaves {face}'s face, which no longer pushes on it")
            }
        };
        self.rec.rocking_event(
            self.t,
            EventKind::Separation,
            &couple.touch.blocks,
            None,
            how,
        );
        for k in couple.moving() {
            self.decide(k, now, false)?;
        }
        Ok(())
    }

    /// Body i of a couple lands on its base (or, in flight, on `corner`), the other body's
    /// corner on its face or its corner on the other's face. Both contacts take their impulses
    /// at once, plastic ([`collision::resolve_landing`], the time-stepped model's law solved
    /// exactly), and the other body's ground contacts with them where it lands at this instant
    /// too: the bodies turn together again, or part where the contact opens, or the run stops
    /// there, saying why. Where that law is not the landing's (a restitution factor
    /// below one, a column holding joints, the linearised equations), the impulses are taken
    /// one after the other ([`Engine::lands_in_turn`]).
    fn couple_lands(
        &mut self,
        i: usize,
        corner: Option<Corner>,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let couple = self.uncouple(i);
        if let Some(due) = self.landings.get_mut(i) {
            // Taken here, wherever it was found: not again at this stop.
            *due = None;
        }
        let plain = |k: usize| self.scene.watches.get(k).is_none_or(Watch::holds_nothing);
        if self.scene.equations != Equations::Exact
            || self.body(i).restitution_factor != 1.0
            || !couple.moving().all(plain)
        {
            return self.lands_in_turn(i, &couple, corner, now);
        }
        // The other body, where its landing is due at this instant too or it is a round-off
        // from landing (and its wall keeps Housner's factor of one), lands with it: the law
        // takes both bodies' ground contacts with the contact between them.
        let k = usize::from(couple.bodies[1] == Some(i));
        let mut partner = None;
        if let Some(j) = couple.bodies[1 - k] {
            if self.body(j).restitution_factor == 1.0 {
                // Due on the trajectory it had at this stop, where nothing has moved it since.
                let due = self.landings.get_mut(j).and_then(Option::take).filter(|_| {
                    self.reached.get(j) == Some(&(self.tracks[j].mode, self.tracks[j].state))
                });
                partner = due.or(self.lands_by_round_off(j)).map(|c| (j, c));
            }
        }
        let before = [Some(i), partner.map(|(j, _)| j)].map(|b| b.map(|b| self.tracks[b].state));
        let held = couple.touch_at(couple.bodies.map(|b| b.map(|k| &self.tracks[k].state)));
        let ground = self.grounded(i, corner, now)?;
        let partner_ground = match partner {
            Some((j, c)) => Some(self.grounded(j, c, now)?),
            None => None,
        };
        // A body that lands on its base a tie from its seat has that tilt set to zero, which
        // would move the contact along its normal by up to the tie times the body's height:
        // the blocks would overlap or part by that much. That round-off goes into where the
        // body's base stands on the ground instead (a side face's normal is near horizontal;
        // along a top face, which a tilt moves sideways only, nothing is moved).
        for (n, (b, c)) in std::iter::once((i, corner)).chain(partner).enumerate() {
            let s = usize::from(couple.bodies[1] == Some(b));
            let theta = before[n].map_or(0.0, |st| st.theta);
            if c.is_none() && held.normal[0].abs() > std::f64::consts::FRAC_1_SQRT_2 {
                let st = &mut self.tracks[b].state;
                st.u += seat_shift_m(held.point, held.normal, couple.home(s), theta, st.u);
            }
        }
        let touch = Touch {
            stays: true,
            ..couple.touch_at(couple.bodies.map(|b| b.map(|k| &self.tracks[k].state)))
        };
        let (mut sides, contact) = self.staying(&touch);
        for (s, g) in [(k, Some(ground)), (1 - k, partner_ground)] {
            if let (Some(turns), Some(g)) = (sides[s].as_mut(), g) {
                turns.ground = g;
            }
        }
        let [own, other] = [k, 1 - k].map(|s| self.layout.names[touch.blocks[s]].clone());
        let landing = |name: &str, c: Option<Corner>| match c {
            None => format!("{name} lands on its base"),
            Some(c) => format!("{name} lands from free flight on its {} corner", c.name()),
        };
        let (lands, with, contacts) = match partner {
            None => (
                landing(&own, corner),
                format!("in contact with {other}"),
                "both",
            ),
            Some((_, c)) => (
                format!("{} and {}", landing(&own, corner), landing(&other, c)),
                "in contact".to_string(),
                "the three",
            ),
        };
        let out = match collision::resolve_landing([sides[0].as_ref(), sides[1].as_ref()], &contact)
        {
            Ok(out) => out,
            Err(refusal) => {
                let why = format!("{lands} {with}, and {refusal}");
                return self.meeting_not_followed((touch.blocks[0], touch.blocks[1]), why, now);
            }
        };
        let (_, speed, _) = collision::approach([sides[0].as_ref(), sides[1].as_ref()], &contact);
        // The landing may turn the body away from the other: the contact opens, its impulse
        // zero, and the other side moves on as it was (or lands by its own law).
        let opens = out.normal_m_s.1 > series::TIE * speed;
        if opens {
            self.rec.energy.impact_loss_j += out.loss_j;
        }
        let landed = [(k, Some(i)), (1 - k, partner.map(|(j, _)| j))];
        for ((s, b), before) in landed.into_iter().zip(before) {
            let (Some(b), Some(before)) = (b, before) else {
                continue;
            };
            let after = out.after[s].expect("a landing body's side moves");
            let mut what = format!(
                "{lands} {with}, {contacts} contacts plastic at once: theta' {:.6e} -> {:.6e} \
                 rad/s",
                before.omega, after.omega
            );
            if opens {
                let (how, _) = self.take(b, &after);
                what += &format!(", {how}; the contact opens at {:.6e} m/s", out.normal_m_s.1);
            }
            self.rec.rocking_event(
                self.t,
                EventKind::RockingImpact,
                &self.layout.outputs(b),
                Some((before.omega, after.omega)),
                what,
            );
        }
        if opens {
            let [corner_name, face_name] = touch.blocks.map(|b| self.layout.names[b].clone());
            self.rec.rocking_event(
                self.t,
                EventKind::Separation,
                &touch.blocks,
                None,
                format!("{corner_name}'s corner leaves {face_name}'s face as {lands}"),
            );
            for j in couple.moving() {
                self.decide(j, now, false)?;
            }
            return Ok(());
        }
        let stays = format!("they stay in contact as {lands}");
        let through = Through::Landing(i, partner.map(|(j, _)| j));
        if let Some(why) = self.rests_against(&touch, &sides, &out, now, stays, through)? {
            self.meeting_not_followed((touch.blocks[0], touch.blocks[1]), why, now)?;
        }
        Ok(())
    }

    /// Body i as a landing's law takes it (`corner`: from flight, on that corner; else on its
    /// base): seated at theta = 0, or followed by the corner it lands on, on the ground (what
    /// height it had there, a tie, goes with the loss); its ground contacts for the law.
    fn grounded(
        &mut self,
        i: usize,
        corner: Option<Corner>,
        now: &Inputs,
    ) -> Result<[Option<(Corner, f64)>; 2], SimulationError> {
        let body = self.body(i);
        let traj = self.trajectory(i, now);
        let dropped = modes::potential_j(body, &traj, 0.0);
        let bp = self.layout.pivot_half_base_m(i);
        let tr = &mut self.tracks[i];
        let (yg, omega) = (
            tr.state.lift_v + traj.dx[0] * tr.state.omega,
            tr.state.omega,
        );
        let ground = match corner {
            None => {
                tr.state.theta = 0.0;
                let c = tr
                    .mode
                    .pivot()
                    .expect("only a rocking body lands on its base");
                [Some((c, 0.0)), Some((c.other(), -2.0 * c.sign() * bp))]
            }
            Some(c) => {
                let Mode::Flight(followed) = tr.mode else {
                    return Err(SimulationError::Bug(
                        "only a body in flight lands from it".into(),
                    ));
                };
                if c != followed {
                    tr.state = refollowed(tr.state, followed, bp);
                }
                tr.state.lift = 0.0;
                tr.mode = Mode::Flight(c);
                let both = [Some((c, 0.0)), Some((c.other(), -2.0 * c.sign() * bp))];
                if upright_by_round_off(body, &tr.state) {
                    // Upright but for round-off, it comes down on both corners at once.
                    tr.state.theta = 0.0;
                    both
                } else if c.sign() * tr.state.theta < 0.0
                    && level_by_round_off(body, bp, tr.state.theta)
                {
                    // Tilted to the side its corner cannot rock on, its corners level to a
                    // tie: the tilt's sign is round-off, and it lands upright, on both corners
                    // where the other comes down too.
                    tr.state.theta = 0.0;
                    let other = c.other();
                    let rises = impact::rise_m_s(body, 0.0, other, (yg, omega)) > 0.0
                        || impact::touches(body, 0.0, other, (yg, omega));
                    if rises {
                        [Some((c, 0.0)), None]
                    } else {
                        both
                    }
                } else {
                    [Some((c, 0.0)), None]
                }
            }
        };
        self.rec.energy.impact_loss_j +=
            dropped - modes::potential_j(body, &self.trajectory(i, now), 0.0);
        Ok(ground)
    }

    /// Body i of `couple` lands on its base (or, in flight, on `corner`), the impulses taken
    /// one after the other: the landing first, as the body's alone (Housner's), then at the
    /// contact between the bodies what is left of their approach, without restitution
    /// ([`Engine::strike`]): they turn together again, or the run stops there, saying why;
    /// where the landing turns the body away from the other, they part.
    fn lands_in_turn(
        &mut self,
        i: usize,
        couple: &Couple,
        corner: Option<Corner>,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        match corner {
            Some(corner) => self.land_from_flight(i, corner, now)?,
            None => self.land(i, now)?,
        }
        if self.stop.is_some() {
            return Ok(());
        }
        let touch = couple.touch_at(couple.bodies.map(|b| b.map(|k| &self.tracks[k].state)));
        let cause = format!("{} lands", self.body(i).name);
        self.rejoin(&touch, &cause, &[i], now)
    }

    /// What is left of the approach at a contact `touch` that stayed until an impulse
    /// elsewhere at this instant (`cause` says which; the bodies `moved` took it and have
    /// their modes): where the blocks now move apart, they part (a `separation` event, the
    /// other bodies' modes decided); else the approach is taken up without restitution
    /// ([`Engine::strike`]), which may leave them in contact again or stop the run, saying why.
    fn rejoin(
        &mut self,
        touch: &Touch,
        cause: &str,
        moved: &[usize],
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let (sides, contact) = self.staying(touch);
        let (approach, speed, _) =
            collision::approach([sides[0].as_ref(), sides[1].as_ref()], &contact);
        if approach > series::TIE * speed {
            let [corner, face] = touch.blocks.map(|k| self.layout.names[k].clone());
            self.rec.rocking_event(
                self.t,
                EventKind::Separation,
                &touch.blocks,
                None,
                format!("{corner}'s corner leaves {face}'s face as {cause}"),
            );
            for side in touch.sides {
                if let Side::Body(k, _) = side {
                    if !moved.contains(&k) {
                        self.decide(k, now, false)?;
                    }
                }
            }
            return Ok(());
        }
        let touch = Touch {
            stays: true,
            ..*touch
        };
        // The impulse elsewhere may have left a body of this contact in contact with a third
        // block: a chain of three in contact is beyond the model (and taking each contact in
        // turn would not end).
        if let Some(busy) = self.in_contact_elsewhere(&touch.sides) {
            let why = format!("they stay in contact as {cause}, and {busy}");
            return self.meeting_not_followed((touch.blocks[0], touch.blocks[1]), why, now);
        }
        if let Some(why) = self.strike(&touch, now)? {
            self.meeting_not_followed((touch.blocks[0], touch.blocks[1]), why, now)?;
        }
        Ok(())
    }

    /// The sides of a contact `touch` that stays, as the impact law takes them, and the
    /// contact, without restitution.
    fn staying(&self, touch: &Touch) -> ([Option<collision::Turning>; 2], collision::Contact) {
        let sides = touch.sides.map(|side| match side {
            Side::Body(k, origin) => Some(self.turning(k, origin)),
            Side::Fixed | Side::Held => None,
        });
        let contact = collision::Contact {
            point: touch.point,
            normal: touch.normal,
            restitution: 0.0,
        };
        (sides, contact)
    }

    /// Body i of a couple would fall flat (`guard`): the mechanism changes in a way the exact
    /// model does not follow.
    fn couple_gives(
        &mut self,
        i: usize,
        guard: Guard,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let couple = self.tracks[i].couple.expect("a body of a couple");
        let [corner, face] = couple.touch.blocks.map(|k| self.layout.names[k].as_str());
        let why = format!(
            "{corner}'s corner turns on {face}'s face, the two bodies in contact, and {} would \
             {}: a change of such a mechanism is not followed",
            self.body(i).name,
            breaks(guard)
        );
        self.meeting_not_followed((couple.touch.blocks[0], couple.touch.blocks[1]), why, now)
    }

    /// Body i of a couple lies on its face: it has overturned, as a body alone does
    /// ([`Engine::overturn`]), and drops out of the contact; the other body turns on alone, in
    /// the mode its state gives (where the run goes on after a collapse).
    fn couple_overturns(
        &mut self,
        i: usize,
        traj: &Trajectory,
        tau: f64,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let couple = self.uncouple(i);
        self.overturn(i, traj, tau)?;
        for k in couple.moving().filter(|&k| k != i) {
            if self.t < self.t_end {
                self.decide(k, now, false)?;
            }
        }
        Ok(())
    }

    /// Body i of a couple reaches the limit of its pivot's friction, its slipping pivot stops,
    /// or the ground's push on its pivot falls to zero (`guard`): the couple's modes are
    /// decided again, each change logged (after the landing of a body a round-off from one,
    /// [`Engine::couple_lands`]); a body sliding along a fixed block's face whose pivot sticks
    /// rests there ([`lean`]); where no one mode holds, the run stops, saying why.
    fn recouple(&mut self, i: usize, guard: Guard, now: &Inputs) -> Result<(), SimulationError> {
        let mut couple = self.tracks[i].couple.expect("a body of a couple");
        if matches!(guard, Guard::PivotStick | Guard::Stop) {
            self.stills(couple.bodies, |k| k == i, now);
            // The contact's normal rate, left at the slip's round-off, closes.
            let states = couple.bodies.map(|b| b.map(|k| &self.tracks[k].state));
            self.close_contacts(&[couple.touch_at(states)], Some(i), now);
        }
        if let Some((j, corner)) = couple
            .moving()
            .find_map(|j| Some((j, self.lands_by_round_off(j)?)))
        {
            // A body a round-off from landing (a flight of round-off after a blow) lands now,
            // the couple's modes decided after it.
            return self.couple_lands(j, corner, now);
        }
        if guard == Guard::Uplift {
            // It turns on the corner that keeps its load, its pivot's home there.
            let pivot = self.lifts_on(i, now);
            let k = usize::from(couple.bodies[1] == Some(i));
            if couple.pivots[k] != pivot {
                let Side::Body(_, origin) = couple.touch.sides[k] else {
                    unreachable!("a body's side of its couple");
                };
                let homes = [0, 1].map(|s| match couple.bodies[s] {
                    Some(j) if j == i => self.home(i, origin, pivot),
                    Some(_) => couple.home(s),
                    None => couple.touch.point,
                });
                let states = couple.bodies.map(|b| b.map(|j| self.tracks[j].state));
                let touch = couple.touch_at(states.each_ref().map(Option::as_ref));
                let size = self.body(i).size_m();
                let Some(again) = Couple::new(
                    &touch,
                    couple.bodies,
                    homes,
                    states.each_ref().map(Option::as_ref),
                    series::TIE * size,
                ) else {
                    let [corner, face] = couple.touch.blocks.map(|b| self.layout.names[b].clone());
                    let why = format!(
                        "{corner}'s corner turns on {face}'s face, and {} would lift onto a corner \
                         about which the push has no moment",
                        self.body(i).name
                    );
                    return self.meeting_not_followed(
                        (couple.touch.blocks[0], couple.touch.blocks[1]),
                        why,
                        now,
                    );
                };
                couple = again;
                for j in couple.moving() {
                    self.tracks[j].couple = Some(couple);
                }
            }
        }
        let modes = match couple.decide(self.members(&couple), now) {
            Ok(modes) => modes,
            Err(why) => {
                let [corner, face] = couple.touch.blocks.map(|k| self.layout.names[k].as_str());
                let why = format!("{corner}'s corner turns on {face}'s face, and {why}");
                return self.meeting_not_followed(
                    (couple.touch.blocks[0], couple.touch.blocks[1]),
                    why,
                    now,
                );
            }
        };
        self.rec.stats.mode_decisions += 1;
        let [corner, face] = couple.touch.blocks.map(|b| &self.layout.names[b]);
        let within = format!(", in the contact of {corner}'s corner with {face}'s face");
        self.retake(couple.bodies, modes, &within);
        if couple.bodies.contains(&None) && matches!(self.tracks[i].mode, Mode::Rock(_)) {
            self.rests_still(i, now);
        }
        Ok(())
    }

    /// The bodies of a mechanism of contacts (`bodies`, none for a fixed block) take the modes
    /// decided for them again (none: a fixed block's), each change logged; a seated body that
    /// lifts says in which contacts (`within`), for no swept scene has reached it yet
    /// (docs/rocking/scans). A pivot that sticks does so from exactly zero slip, and a body
    /// that leaves the ground leaves it from its pivot, at rest there.
    fn retake(&mut self, bodies: [Option<usize>; 2], modes: [Option<Mode>; 2], within: &str) {
        for (k, new) in bodies.into_iter().zip(modes) {
            let (Some(k), Some(new)) = (k, new) else {
                continue;
            };
            let old = self.tracks[k].mode;
            if let Some(kind) = transition(old, new, false) {
                if matches!(kind, EventKind::Slip | EventKind::Stick) {
                    self.rec.transitions += 1;
                }
                let blocks = self.layout.outputs(k);
                let mut mode = new.name();
                if kind == EventKind::Uplift {
                    mode += within;
                }
                self.rec.rocking_event(self.t, kind, &blocks, None, mode);
            }
            let tr = &mut self.tracks[k];
            tr.mode = new;
            match new {
                Mode::Rock(_) => tr.state.v = 0.0,
                Mode::Flight(_) if old != new => (tr.state.lift, tr.state.lift_v) = (0.0, 0.0),
                _ => {}
            }
        }
    }

    /// Body i slides along a fixed block's face and its pivot sticks: the contact leaves it no
    /// motion, and it rests against the block from here ([`lean`]), what it had of kinetic
    /// energy (round-off: the contact ties its rotation to its slip) counted as lost. (Where
    /// the push has no moment about the pivot at all, it stays in the couple, its pivot stuck.)
    fn rests_still(&mut self, i: usize, now: &Inputs) {
        let couple = self.tracks[i].couple.expect("a body of a couple");
        let k = usize::from(couple.bodies[1] == Some(i));
        let touch = couple.touch_at([0, 1].map(|s| (s == k).then_some(&self.tracks[i].state)));
        let Side::Body(_, origin) = touch.sides[k] else {
            unreachable!("the body's side of its couple");
        };
        let turns = self.turning(i, origin);
        let Some(lean) = Lean::new(&touch, k, turns.pivot, turns.centroid, 0.0) else {
            return;
        };
        self.uncouple(i);
        let body = self.body(i);
        let before = modes::kinetic_j(body, &self.trajectory(i, now), 0.0);
        let tr = &mut self.tracks[i];
        tr.state.omega = 0.0;
        tr.leans = Some(lean);
        self.rec.energy.impact_loss_j += before;
        self.clearance.lean(touch.pair, true);
    }

    /// Body i, at rest against a fixed block, reaches the limit of its pivot's friction, or the
    /// ground's push on its pivot falls to zero: it slides along the block's face, or leaves
    /// the ground, the contact staying, as a couple with the block ([`couple`]) in the mode the
    /// contact conditions allow; or the run stops, saying why.
    fn lean_moves(&mut self, i: usize, now: &Inputs) -> Result<(), SimulationError> {
        let lean = self.tracks[i]
            .leans
            .expect("a body resting against a block");
        let touch = lean.touch;
        let k = usize::from(matches!(touch.sides[1], Side::Body(..)));
        let Side::Body(_, origin) = touch.sides[k] else {
            unreachable!("the body's side of its lean");
        };
        let c = self.tracks[i]
            .mode
            .pivot()
            .expect("a leaning body rocks on a pivot");
        let mut homes = [touch.point; 2];
        homes[k] = self.home(i, origin, c);
        let bodies = [0, 1].map(|s| (s == k).then_some(i));
        let state = self.tracks[i].state;
        let placed = [0, 1].map(|s| (s == k).then_some(&state));
        let tie_m = series::TIE * self.body(i).size_m();
        let [own, other] = lean.blocks.map(|b| self.layout.names[b].clone());
        let Some(couple) = Couple::new(&touch, bodies, homes, placed, tie_m) else {
            let why = format!(
                "{own} rests against {other}'s face, its pivot would move, and the face's push \
                 has no moment about it to move it by"
            );
            return self.meeting_not_followed((lean.blocks[0], lean.blocks[1]), why, now);
        };
        let members = [0, 1].map(|s| match s == k {
            true => Member::Moves(self.body(i), self.tracks[i].mode, &state),
            false => Member::Fixed,
        });
        match couple.decide(members, now) {
            Ok(modes) if modes[k] != Some(Mode::Rock(c)) => {
                let mode = modes[k].expect("the body's side has a mode");
                self.rec.stats.mode_decisions += 1;
                let (kind, along) = match mode {
                    Mode::Flight(_) => (EventKind::Flight, "its corner on"),
                    _ => (EventKind::PivotSlip, "sliding along"),
                };
                self.rec.rocking_event(
                    self.t,
                    kind,
                    &self.layout.outputs(i),
                    None,
                    format!("{}, {along} {other}'s face", mode.name()),
                );
                self.clearance.lean(touch.pair, false);
                self.clearance.hold(touch.pair, Some(&touch));
                let tr = &mut self.tracks[i];
                tr.leans = None;
                tr.mode = mode;
                tr.couple = Some(couple);
            }
            // Its friction holds after all: the margin touched zero and turns back.
            Ok(_) => {}
            Err(why) => {
                let why = format!("{own} rests against {other}'s face, and {why}");
                self.meeting_not_followed((lean.blocks[0], lean.blocks[1]), why, now)?;
            }
        }
        Ok(())
    }

    /// The impact where a corner strikes a face (`t`), then the modes after it; or why it is
    /// not followed (nothing changed then, but where a struck body had a contact besides: the
    /// blow is refused after that contact was let go, and the run stops there anyway). A struck
    /// body resting against a block or turning with another takes the blow first, then what is
    /// left at that contact ([`Engine::rejoin`]); one seated through the rest of a series of
    /// landings takes it seated, the series ending there.
    fn strike(&mut self, t: &Touch, now: &Inputs) -> Result<Option<String>, SimulationError> {
        let lies = t.sides.iter().find_map(|side| match *side {
            Side::Body(i, _) => self.tracks[i].lies.map(|l| (i, l)),
            _ => None,
        });
        if let Some((i, lying)) = lies {
            let [a, b] = lying.ends[0]
                .touch
                .blocks
                .map(|k| self.layout.names[k].as_str());
            return Ok(Some(format!(
                "{}'s face lies on another's ({a}'s on {b}'s): a blow on faces lying on each \
                 other is not followed",
                self.body(i).name
            )));
        }
        for k in 0..2 {
            let name = &self.layout.names[t.blocks[k]];
            let i = match t.sides[k] {
                Side::Fixed => continue,
                Side::Held => {
                    return Ok(Some(format!(
                        "{name} stands held in its column under a joint that opened, and an \
                         impulse on it is not followed"
                    )))
                }
                Side::Body(i, _) => i,
            };
            if !self.scene.watches.get(i).is_none_or(Watch::holds_nothing) {
                return Ok(Some(format!(
                    "{name}'s column holds joints the impulse would pass through"
                )));
            }
        }
        // A body seated through the rest of a series of landings rocks below ZENO_ROTATION of
        // its alpha there (the series summed as rest, its energy booked with the landing's
        // loss): it takes the blow seated, and the series ends here.
        for side in t.sides {
            if let Side::Body(i, _) = side {
                if let Some((until, after, _)) = self.tracks[i].settles.take() {
                    self.rec.rocking_event(
                        self.t,
                        EventKind::Rest,
                        &self.layout.outputs(i),
                        Some((after, 0.0)),
                        format!(
                            "its landings accumulate, ended {:e} s before their series' end by \
                             a blow",
                            until - self.t
                        ),
                    );
                }
            }
        }
        // A body alone in flight a round-off from landing (a flight of round-off that an
        // impact at this contact left, a round-off ago) lands first, as it would have; the
        // blow takes it as it then moves. (One on its pivot a round-off from its seat is struck
        // as it is: landing it first could start a series of landings the blow would break.)
        for side in t.sides {
            let Side::Body(i, _) = side else { continue };
            if self.tracks[i].leans.is_some() || self.tracks[i].couple.is_some() {
                continue;
            }
            if let Some(Some(corner)) = self.lands_by_round_off(i) {
                self.land_from_flight(i, corner, now)?;
                if self.stop.is_some() {
                    return Ok(None);
                }
            }
        }
        // A struck body that rests against a block or moves in contact with another takes the
        // blow first, as if alone; then what is left of the approach at the contact it had
        // (a sequential law, as for a landing in contact).
        let mut held = Vec::new();
        for side in t.sides {
            let Side::Body(i, _) = side else { continue };
            if let Some(lean) = self.tracks[i].leans.take() {
                self.clearance.lean(lean.touch.pair, false);
                held.push(lean.touch);
            }
            if let Some(couple) = self.tracks[i].couple {
                held.push(couple.touch_at(couple.bodies.map(|b| b.map(|k| &self.tracks[k].state))));
                self.uncouple(i);
            }
        }
        if !held.is_empty() {
            match self.blow_at_once(t, &held, now)? {
                AtOnce::Done => return Ok(None),
                AtOnce::Stops(why) => return Ok(Some(why)),
                AtOnce::InTurn => {}
            }
        }
        if let Some(why) = self.blow(t, now)? {
            return Ok(Some(why));
        }
        let [corner, face] = t.blocks.map(|k| self.layout.names[k].clone());
        let cause = format!("{corner}'s corner meets {face}'s face");
        let moved: Vec<usize> = (t.sides.iter())
            .filter_map(|s| match s {
                Side::Body(i, _) => Some(*i),
                _ => None,
            })
            .collect();
        for touch in held {
            if self.stop.is_some() {
                break;
            }
            self.rejoin(&touch, &cause, &moved, now)?;
        }
        Ok(None)
    }

    /// A blow `t` on blocks in contact with others (`held`, the contacts that stayed until
    /// now): every contact takes its impulse at once ([`collision::resolve_all`]: Moreau's law,
    /// the blow's with the wall's restitution, the others' without, each free to open). Where
    /// the blow parts its blocks, the contacts that open part theirs (`separation` events) and
    /// those that stay go on as a couple or a rest against a fixed block; where the blow's own
    /// contact stays, or the blocks rattle, or a side is held in its column, the impulses are
    /// taken in turn instead ([`AtOnce::InTurn`]).
    fn blow_at_once(
        &mut self,
        t: &Touch,
        held: &[Touch],
        now: &Inputs,
    ) -> Result<AtOnce, SimulationError> {
        let all_sides = || std::iter::once(t).chain(held).flat_map(|h| h.sides);
        if t.stays
            || self.scene.equations != Equations::Exact
            || all_sides().any(|side| side == Side::Held)
        {
            return Ok(AtOnce::InTurn);
        }
        // The bodies of every contact, each once, and each contact's sides among them.
        let mut ids: Vec<(usize, [f64; 2])> = Vec::new();
        for side in all_sides() {
            if let Side::Body(i, origin) = side {
                if !ids.iter().any(|&(j, _)| j == i) {
                    ids.push((i, origin));
                }
            }
        }
        let index = |side: Side| match side {
            Side::Body(i, _) => ids.iter().position(|&(j, _)| j == i),
            _ => None,
        };
        let restitution = self.scene.wall.map_or(1.0, |(w, _)| w.restitution.to_f64());
        let mut links = vec![collision::Link {
            sides: t.sides.map(index),
            contact: collision::Contact {
                point: t.point,
                normal: t.normal,
                restitution,
            },
        }];
        for h in held {
            links.push(collision::Link {
                sides: h.sides.map(index),
                contact: self.staying(h).1,
            });
        }
        let bodies: Vec<collision::Turning> = (ids.iter())
            .map(|&(i, origin)| self.turning(i, origin))
            .collect();
        let sides_of = |l: &collision::Link| l.sides.map(|k| k.map(|j| &bodies[j]));
        let (approach, speed, _) = collision::approach(sides_of(&links[0]), &links[0].contact);
        if approach >= -series::TIE * speed {
            return Ok(AtOnce::InTurn);
        }
        let all = match collision::resolve_all(&bodies, &links) {
            Ok(all) => all,
            Err(refusal) => return Ok(AtOnce::Stops(refusal.to_string())),
        };
        if all.normal_m_s[0].1 <= t.tie_m_s() {
            return Ok(AtOnce::InTurn);
        }
        // The contacts that stay, and no body in two of them: taking each in turn would not end.
        let stays: Vec<usize> = (1..links.len())
            .filter(|&l| {
                let (_, speed, _) = collision::approach(sides_of(&links[l]), &links[l].contact);
                all.normal_m_s[l].1 <= series::TIE * speed
            })
            .collect();
        for (j, &(i, _)) in ids.iter().enumerate() {
            let count = (stays.iter())
                .filter(|&&l| links[l].sides.contains(&Some(j)))
                .count();
            if count > 1 {
                return Ok(AtOnce::Stops(format!(
                    "{} stays in contact on two sides at once: blocks in contact on two sides \
                     are not followed",
                    self.body(i).name
                )));
            }
        }
        self.clearance.strike(t.pair);
        self.rec.energy.impact_loss_j += all.loss_j;
        self.rec.impacts += 1;
        let [corner, face] = t.blocks.map(|b| self.layout.names[b].clone());
        let mut what = format!(
            "{corner}'s corner strikes {face}'s face at {:.6e} m/s, parting at {:.6e} m/s \
             (impulse {:.6e} N s), every contact it touches taking its impulse at once",
            -all.normal_m_s[0].0, all.normal_m_s[0].1, all.impulse_n_s[0]
        );
        let mut omega = None;
        for k in 0..2 {
            if let (Side::Body(i, _), Some(j)) = (t.sides[k], links[0].sides[k]) {
                self.rec.rocking_impact(t.blocks[k]);
                omega.get_or_insert((self.tracks[i].state.omega, all.after[j].omega));
            }
        }
        // Bodies in no contact that stays take their velocities now; the others through it.
        let mut decide = Vec::new();
        for (j, &(i, _)) in ids.iter().enumerate() {
            if stays.iter().any(|&l| links[l].sides.contains(&Some(j))) {
                continue;
            }
            let after = all.after[j];
            let before = self.tracks[i].state.omega;
            let (how, decides) = self.take(i, &after);
            what += &format!(
                "; {}: theta' {before:.6e} -> {:.6e} rad/s, {how}",
                self.body(i).name,
                after.omega
            );
            if decides {
                decide.push(i);
            }
        }
        self.rec
            .rocking_event(self.t, EventKind::BlocksImpact, &t.blocks, omega, what);
        for (l, h) in held.iter().enumerate().map(|(k, h)| (k + 1, h)) {
            let [c, f] = h.blocks.map(|b| self.layout.names[b].clone());
            if !stays.contains(&l) {
                self.rec.rocking_event(
                    self.t,
                    EventKind::Separation,
                    &h.blocks,
                    None,
                    format!("{c}'s corner leaves {f}'s face as {corner}'s corner strikes {face}'s"),
                );
                continue;
            }
            let pair = links[l].sides.map(|k| k.map(|j| all.after[j]));
            let out = collision::Outcome {
                after: pair,
                impulse_n_s: all.impulse_n_s[l],
                normal_m_s: all.normal_m_s[l],
                loss_j: 0.0,
            };
            let turning = links[l].sides.map(|k| k.map(|j| bodies[j]));
            let stays = format!("they stay in contact as {corner}'s corner strikes {face}'s face");
            let touch = Touch { stays: true, ..*h };
            if let Some(why) =
                self.rests_against(&touch, &turning, &out, now, stays, Through::Blow)?
            {
                self.meeting_not_followed((h.blocks[0], h.blocks[1]), why, now)?;
                return Ok(AtOnce::Done);
            }
        }
        for i in decide {
            self.decide(i, now, false)?;
        }
        Ok(AtOnce::Done)
    }

    /// The impact where a corner strikes a face (`t`), each body on its side taken as it
    /// stands (on the ground alone), then the modes after it; or why it is not followed.
    fn blow(&mut self, t: &Touch, now: &Inputs) -> Result<Option<String>, SimulationError> {
        let mut turning = [None; 2];
        for (k, turns) in turning.iter_mut().enumerate() {
            if let Side::Body(i, origin) = t.sides[k] {
                *turns = Some(self.turning(i, origin));
            }
        }
        // Blocks that have not parted since their last impact rattle at the scale of
        // round-off: what is left of their approach is taken up without a rebound.
        let restitution = if t.stays {
            0.0
        } else {
            self.scene.wall.map_or(1.0, |(w, _)| w.restitution.to_f64())
        };
        let contact = collision::Contact {
            point: t.point,
            normal: t.normal,
            restitution,
        };
        let stays = if t.stays {
            "they stay in contact (since their last impact they have not parted by more than \
             round-off)"
                .to_string()
        } else {
            format!(
                "they stay in contact after the impact (coefficient of restitution {restitution})"
            )
        };
        let out = match collision::resolve([turning[0].as_ref(), turning[1].as_ref()], &contact) {
            Ok(out) => out,
            Err(collision::Refusal::Grazing) => {
                // What is left of the blocks' approach is round-off (a graze, or a body's
                // bounces on a block accumulated): no impulse, and they stay in contact.
                let out = collision::Outcome {
                    after: [0, 1].map(|k| Some(self.unchanged(t.sides[k], turning[k].as_ref()?))),
                    impulse_n_s: 0.0,
                    normal_m_s: (0.0, 0.0),
                    loss_j: 0.0,
                };
                let why = "they touch without approaching faster than round-off";
                return self.rests_against(t, &turning, &out, now, why.into(), Through::Approach);
            }
            Err(refusal) => return Ok(Some(refusal.to_string())),
        };
        if t.stays || out.normal_m_s.1 <= t.tie_m_s() {
            return self.rests_against(t, &turning, &out, now, stays, Through::Approach);
        }
        self.clearance.strike(t.pair);
        self.rec.energy.impact_loss_j += out.loss_j;
        self.rec.impacts += 1;
        let [corner, face] = t.blocks.map(|k| self.layout.names[k].clone());
        let mut what = format!(
            "{corner}'s corner strikes {face}'s face at {:.6e} m/s, parting at {:.6e} m/s \
             (impulse {:.6e} N s)",
            -out.normal_m_s.0, out.normal_m_s.1, out.impulse_n_s
        );
        let mut omega = None;
        let mut decide = Vec::new();
        for k in 0..2 {
            let (Side::Body(i, _), Some(after)) = (t.sides[k], out.after[k]) else {
                continue;
            };
            self.rec.rocking_impact(t.blocks[k]);
            let before = self.tracks[i].state.omega;
            omega.get_or_insert((before, after.omega));
            let (how, decides) = self.take(i, &after);
            what += &format!(
                "; {}: theta' {before:.6e} -> {:.6e} rad/s, {how}",
                self.layout.names[t.blocks[k]], after.omega,
            );
            if decides {
                decide.push(i);
            }
        }
        self.rec
            .rocking_event(self.t, EventKind::BlocksImpact, &t.blocks, omega, what);
        for i in decide {
            self.decide(i, now, false)?;
        }
        Ok(None)
    }

    /// Body i comes out of an impulse with the velocities `after`, in the mode its base gives:
    /// rocking on a pivot or seated (to be decided again: true), or in flight. The words say
    /// how it goes on.
    fn take(&mut self, i: usize, after: &collision::After) -> (String, bool) {
        let tr = &mut self.tracks[i];
        let flying = matches!(tr.mode, Mode::Flight(_));
        let slipping = |slips: bool| {
            if slips {
                format!(", slipping at {:.6e} m/s", after.v)
            } else {
                String::new()
            }
        };
        let how = match after.base {
            collision::Base::Seated { slips } => format!("stays seated{}", slipping(slips)),
            collision::Base::Pivot { corner, slips } => {
                format!("rocks on its {} corner{}", corner.name(), slipping(slips))
            }
            collision::Base::Flies if flying => "flies on".into(),
            collision::Base::Flies => format!("leaves the ground at {:.6e} m/s", after.lift_v),
        };
        tr.state.omega = after.omega;
        tr.state.v = after.v;
        let decides = match after.base {
            collision::Base::Flies => {
                // A seated body leaves with its right corner followed, as from rest.
                let c = tr.mode.corner().unwrap_or(Corner::Right);
                if !flying {
                    tr.state.lift = 0.0;
                }
                tr.state.lift_v = after.lift_v;
                tr.mode = Mode::Flight(c);
                false
            }
            // On the ground, whatever rise it had (landing from flight) is gone.
            collision::Base::Pivot { corner, .. } => {
                tr.state.lift_v = 0.0;
                tr.mode = Mode::Rock(corner);
                true
            }
            collision::Base::Seated { .. } => {
                tr.state.lift_v = 0.0;
                tr.mode = Mode::Rest;
                true
            }
        };
        (how, decides)
    }

    /// Where body i's corner c stands while its u is zero, its base's middle at rest at
    /// `origin` (m).
    fn home(&self, i: usize, origin: [f64; 2], c: Corner) -> [f64; 2] {
        [
            origin[0] + c.sign() * self.layout.pivot_half_base_m(i),
            origin[1],
        ]
    }

    /// Body i as the impact law takes it, its base's middle at rest at `origin` (m).
    fn turning(&self, i: usize, origin: [f64; 2]) -> collision::Turning {
        let (tr, body) = (&self.tracks[i], self.body(i));
        // The corner the law takes the velocities of (a seated body's right one), and the
        // corners on the ground.
        let bp = self.layout.pivot_half_base_m(i);
        let (c, ground) = match tr.mode {
            Mode::Rock(c) | Mode::SlideRock(c, _) => (c, [Some((c, 0.0)), None]),
            Mode::Flight(c) => (c, [None, None]),
            Mode::Rest | Mode::Slide(_) => (
                Corner::Right,
                [Some((Corner::Right, 0.0)), Some((Corner::Left, -2.0 * bp))],
            ),
        };
        let s = c.sign();
        let flying = matches!(tr.mode, Mode::Flight(_));
        let lift = if flying { tr.state.lift } else { 0.0 };
        let home = self.home(i, origin, c);
        let pivot = [home[0] + tr.state.u, home[1] + lift];
        // The centroid, at (0, h_c) from the base's middle, turned clockwise about the pivot.
        let (sin, cos) = tr.state.theta.sin_cos();
        let (rx, ry) = (-s * bp, body.centroid_height_m);
        collision::Turning {
            mass_kg: body.mass_kg,
            inertia_kg_m2: body.inertia_kg_m2,
            friction: body.friction,
            pivot,
            centroid: [
                pivot[0] + rx * cos + ry * sin,
                pivot[1] - rx * sin + ry * cos,
            ],
            omega: tr.state.omega,
            v: tr.state.v,
            w: if flying { tr.state.lift_v } else { 0.0 },
            ground,
        }
    }

    /// The velocities of a body that a contact leaves as they are (`turns`, on `side`), and
    /// where it stands.
    fn unchanged(&self, side: Side, turns: &collision::Turning) -> collision::After {
        let Side::Body(i, _) = side else {
            unreachable!("a side that moves is a body's");
        };
        let base = match self.tracks[i].mode {
            Mode::Rock(corner) => collision::Base::Pivot {
                corner,
                slips: false,
            },
            Mode::SlideRock(corner, _) => collision::Base::Pivot {
                corner,
                slips: true,
            },
            Mode::Rest => collision::Base::Seated { slips: false },
            Mode::Slide(_) => collision::Base::Seated { slips: true },
            Mode::Flight(_) => collision::Base::Flies,
        };
        collision::After {
            omega: turns.omega,
            v: turns.v,
            lift_v: turns.w,
            base,
        }
    }

    /// Where the blocks of an impact `t` stay in contact after it (`out`, the bodies' states
    /// before it `turning`; `stays` says how, and `through` what gave the contact its
    /// impulse): a body whose pivot stays on the ground, stuck, against a fixed block comes to
    /// rest there ([`lean`]); any other contact that stays stops the run, and the reason is
    /// returned.
    fn rests_against(
        &mut self,
        t: &Touch,
        turning: &[Option<collision::Turning>; 2],
        out: &collision::Outcome,
        now: &Inputs,
        stays: String,
        through: Through,
    ) -> Result<Option<String>, SimulationError> {
        let k = match t.sides {
            [Side::Body(..), Side::Fixed] => 0,
            [Side::Fixed, Side::Body(..)] => 1,
            [Side::Body(..), Side::Body(..)] => return self.couples(t, out, now, stays, through),
            _ => unreachable!("an impact's sides move, at least one of them"),
        };
        let (Side::Body(i, origin), Some(turns), Some(after)) =
            (t.sides[k], turning[k], out.after[k])
        else {
            unreachable!("a body's side of an impact has its velocities");
        };
        let name = self.layout.names[t.blocks[k]].clone();
        let body = self.body(i);
        if self.scene.equations != Equations::Exact {
            return Ok(Some(format!(
                "{stays}, and the linearised equations do not follow a body resting against a \
                 block"
            )));
        }
        let c = match mode_after(&after, self.tracks[i].mode, through.lands(i)) {
            Ok(Mode::Rock(c)) => c,
            // Its pivot slipping, or off the ground, it moves along the face, the corner on it.
            Ok(_) => return self.couples(t, out, now, stays, through),
            Err(what) => {
                return Ok(Some(format!(
                    "{stays}, and {name} {what} against it: a contact that stays on a body \
                     that is not rocking on a pivot or in flight is not followed"
                )))
            }
        };
        let tie_m = series::TIE * body.size_m();
        // Its pivot on the ground (the corner it landed on, for a body landing on its base).
        let pivot = self.home(i, origin, c);
        let pivot = [pivot[0] + self.tracks[i].state.u, pivot[1]];
        let Some(lean) = Lean::new(t, k, pivot, turns.centroid, tie_m) else {
            return Ok(Some(format!(
                "{stays}, and the contact's push has no moment about {name}'s pivot to hold it by"
            )));
        };
        // What the impact leaves of the body's motion is round-off: it rests, and that goes
        // with the impact's loss.
        let before = self.tracks[i].state.omega;
        self.tracks[i].state.omega = after.omega;
        self.tracks[i].state.v = after.v;
        let left = modes::kinetic_j(body, &self.trajectory(i, now), 0.0);
        self.rec.energy.impact_loss_j += out.loss_j + left;
        let meeting = self.stays_in_contact(t, out, &stays, through);
        if out.impulse_n_s > 0.0 {
            self.rec.rocking_impact(t.blocks[k]);
        }
        self.clearance.lean(t.pair, true);
        let tr = &mut self.tracks[i];
        tr.state.omega = 0.0;
        tr.state.v = 0.0;
        tr.mode = Mode::Rock(c);
        tr.leans = Some(lean);
        let what = format!(
            "{meeting}; {name}: theta' {before:.6e} -> 0 rad/s, at rest against {} at theta = \
             {:.6e} rad, pushed by {:.6e} N",
            self.layout.names[t.blocks[1 - k]],
            tr.state.theta,
            lean.push_n(body, now),
        );
        self.rec.rocking_event(
            self.t,
            EventKind::BlocksImpact,
            &t.blocks,
            Some((before, 0.0)),
            what,
        );
        Ok(None)
    }

    /// The words of an impact `t` (`out`) after which the blocks stay in contact (`stays` says
    /// how), counted among the impacts where it has an impulse.
    fn stays_in_contact(
        &mut self,
        t: &Touch,
        out: &collision::Outcome,
        stays: &str,
        through: Through,
    ) -> String {
        let [corner, face] = t.blocks.map(|b| &self.layout.names[b]);
        if through != Through::Approach {
            // The contact's impulse comes from an impact elsewhere, not from an approach.
            if out.impulse_n_s > 0.0 {
                self.rec.impacts += 1;
            }
            format!(
                "{corner}'s corner stays on {face}'s face, its impulse {:.6e} N s: {stays}",
                out.impulse_n_s
            )
        } else if out.impulse_n_s > 0.0 {
            self.rec.impacts += 1;
            format!(
                "{corner}'s corner strikes {face}'s face at {:.6e} m/s and {stays}",
                -out.normal_m_s.0
            )
        } else {
            format!("{corner}'s corner touches {face}'s face: {stays}")
        }
    }

    /// The sides of a couple on `t` where an impact leaves the blocks there with the velocities
    /// `after` (each body's, `through` what): each body's mode just after it (on the pivot it
    /// had, or a seated one, or one landing on its base, on the corner the impact turns it on;
    /// stuck or slipping; or in flight), its state in that mode and its pivot's home; else what
    /// a body does instead, in words.
    fn sides_after(
        &self,
        t: &Touch,
        after: &[Option<collision::After>; 2],
        through: Through,
    ) -> Result<Sides, String> {
        let mut bodies = [None; 2];
        let mut homes = [t.point; 2];
        let mut states = [State::default(); 2];
        let mut modes = [Mode::Rest; 2];
        for k in 0..2 {
            let (i, origin, a) = match (t.sides[k], after[k]) {
                (Side::Body(i, origin), Some(a)) => (i, origin, a),
                (Side::Fixed, _) => continue,
                _ => unreachable!("a side of a contact that moves has its velocities"),
            };
            let (old, state) = (self.tracks[i].mode, self.tracks[i].state);
            let seated = matches!(old, Mode::Rest | Mode::Slide(_)) || through.lands(i);
            let mode = match (a.base, mode_after(&a, old, seated)) {
                (collision::Base::Seated { slips: true }, _) => Mode::Slide(Slip::of_sign(a.v)),
                (collision::Base::Seated { slips: false }, _) => Mode::Rest,
                (_, Ok(mode)) => mode,
                (_, Err(what)) => return Err(format!("{} {what}", self.body(i).name)),
            };
            // A seated body's pivot is the corner the push would turn it on.
            let push_x = if k == 0 { t.normal[0] } else { -t.normal[0] };
            let c = mode.corner().unwrap_or(Corner::of_sign(push_x));
            bodies[k] = Some(i);
            homes[k] = self.home(i, origin, c);
            let flies = matches!(mode, Mode::Flight(_));
            let seated = matches!(mode, Mode::Rest | Mode::Slide(_));
            states[k] = State {
                theta: if seated { 0.0 } else { state.theta },
                omega: if seated { 0.0 } else { a.omega },
                v: if matches!(mode, Mode::Rock(_) | Mode::Rest) {
                    0.0
                } else {
                    a.v
                },
                // A body that leaves the ground here leaves it from its pivot.
                lift: if flies { state.lift } else { 0.0 },
                lift_v: if flies { a.lift_v } else { 0.0 },
                ..state
            };
            modes[k] = mode;
        }
        Ok(Sides {
            bodies,
            homes,
            states,
            modes,
        })
    }

    /// Where the blocks of an impact `t` stay in contact (`out`; `stays` says how), each body
    /// rocking on the pivot it had (or a seated one, or one landing on its base `through` it,
    /// on the corner the impact turns it on), stuck or slipping: two bodies move on together,
    /// or one slides along a fixed block's face, its pivot slipping ([`couple`]), in the one
    /// mode of their pivots the contact conditions allow; any other contact that stays stops
    /// the run, and the reason is returned.
    fn couples(
        &mut self,
        t: &Touch,
        out: &collision::Outcome,
        now: &Inputs,
        stays: String,
        through: Through,
    ) -> Result<Option<String>, SimulationError> {
        if self.scene.equations != Equations::Exact {
            return Ok(Some(format!(
                "{stays}, and the linearised equations do not follow two blocks in contact"
            )));
        }
        let Sides {
            bodies,
            homes,
            mut states,
            modes,
        } = match self.sides_after(t, &out.after, through) {
            Ok(sides) => sides,
            Err(what) => {
                return Ok(Some(format!(
                    "{stays}, and {what}: blocks in contact are followed only while each body is \
                     seated, rocks on a pivot or flies"
                )))
            }
        };
        let size = bodies.map(|b| b.map_or(0.0, |i| self.body(i).size_m()));
        let tie_m = series::TIE * size[0].max(size[1]);
        let placed = [0, 1].map(|k| bodies[k].map(|_| &states[k]));
        let couple = Couple::placed(t, bodies, homes, placed);
        let members = [0, 1].map(|k| match bodies[k] {
            Some(i) => Member::Moves(self.body(i), modes[k], &states[k]),
            None => Member::Fixed,
        });
        // A push that moves neither body can hold a contact the bodies alone do not close;
        // where they close it, only a way that slips or lifts a pivot can (decided below).
        if !couple.moves(members, tie_m) && !couple.closed_alone(members, now) {
            let sides = Sides {
                bodies,
                homes,
                states,
                modes,
            };
            self.holds_nothing(t, out, now, stays, through, sides);
            return Ok(None);
        }
        let given = (modes, states);
        // A body the impact leaves a round-off from landing (its pivot a round-off above the
        // ground, or its tilt a round-off from its seat and closing) breaks every way at once:
        // it keeps the mode the impact left it in, and lands with the contact at once after it
        // (not after a landing's own law, which took every landing due).
        let (modes, lands) = match couple.decide(members, now) {
            Ok(modes) => (modes, None),
            Err(why) => {
                let landing = matches!(through, Through::Landing(..));
                let lands = (0..2).filter(|_| !landing).find_map(|k| {
                    let i = bodies[k]?;
                    Some((
                        i,
                        lands_by_round_off(self.body(i), given.0[k], &given.1[k])?,
                    ))
                });
                // Both pivots at one point, the contact there: where the bodies alone keep it,
                // it carries nothing, and each goes on alone.
                let unpushed = (lands.is_none())
                    .then(|| couple.unpushed(members, now))
                    .flatten();
                if let Some(unpushed) = unpushed {
                    let sides = Sides {
                        bodies,
                        homes,
                        states: given.1,
                        modes: unpushed.map(|m| m.unwrap_or(Mode::Rest)),
                    };
                    self.holds_nothing(t, out, now, stays, through, sides);
                    return Ok(None);
                }
                match lands {
                    Some(lands) => ([0, 1].map(|k| bodies[k].map(|_| given.0[k])), Some(lands)),
                    None => return Ok(Some(format!("{stays}, and {why}"))),
                }
            }
        };
        for k in 0..2 {
            if let (Some(i), Some(mode)) = (bodies[k], modes[k]) {
                states[k] = settled_in(self.body(i), mode, states[k]);
            }
        }
        // A push that falls at once parts the pair at this instant; where it parted so at
        // this instant again and again, alone the bodies coming back to the contact each time,
        // the pair would touch and part without end.
        if self.parted == Some((t.pair, self.t, PARTINGS)) {
            let members = [0, 1].map(|k| match (bodies[k], modes[k]) {
                (Some(i), Some(mode)) => Member::Moves(self.body(i), mode, &states[k]),
                _ => Member::Fixed,
            });
            let push = couple.motion(members, now).push;
            let body = self.body(bodies.into_iter().flatten().next().expect("a moving side"));
            let force = modes::Scales::of(body).force;
            if series::sign_after(&push, force, body.time_scale_s()) < 0 {
                return Ok(Some(format!(
                    "{stays}, and the one mode of the pivots that holds with the contact has a \
                     push that falls at once ({:.6e} N), where they parted {PARTINGS} times at \
                     this instant and alone came back to it each time: the rigid model with \
                     Coulomb friction has no motion here",
                    push[0]
                )));
            }
        }
        self.rec.energy.impact_loss_j += out.loss_j;
        let mut what = self.stays_in_contact(t, out, &stays, through);
        let mut omega = None;
        for k in 0..2 {
            let (Some(i), Some(mode)) = (bodies[k], modes[k]) else {
                continue;
            };
            if out.impulse_n_s > 0.0 {
                self.rec.rocking_impact(t.blocks[k]);
            }
            let tr = &mut self.tracks[i];
            omega.get_or_insert((tr.state.omega, states[k].omega));
            let slipping = match mode {
                Mode::SlideRock(..) => format!(", slipping at {:.6e} m/s", states[k].v),
                Mode::Rest => ", seated".to_string(),
                Mode::Slide(_) => format!(", seated, sliding at {:.6e} m/s", states[k].v),
                Mode::Flight(_) => format!(", leaving the ground at {:.6e} m/s", states[k].lift_v),
                _ => String::new(),
            };
            what += &format!(
                "; {}: theta' {:.6e} -> {:.6e} rad/s{slipping}",
                self.layout.names[t.blocks[k]], tr.state.omega, states[k].omega
            );
            tr.state = states[k];
            tr.mode = mode;
            tr.couple = Some(couple);
        }
        // A rise or a slip read as zero, and the tie an impulse leaves at the contact, leave
        // round-off in the corner's normal velocity: one body's rotation closes it, so that
        // the corner stays on the face to round-off. What that changes of the kinetic energy
        // goes with the impact's loss.
        let (sides, contact) = self.staying(t);
        // A seated body does not turn.
        let turns = modes.map(|m| !m.is_some_and(|m| matches!(m, Mode::Rest | Mode::Slide(_))));
        if let Some((k, d_omega)) =
            collision::closing([sides[0].as_ref(), sides[1].as_ref()], &contact, turns)
        {
            let i = bodies[k].expect("a side that turns is a body's");
            self.tracks[i].state.omega += d_omega;
        }
        let now_states =
            [0, 1].map(|k| bodies[k].map_or(State::default(), |i| self.tracks[i].state));
        let now_modes = [0, 1].map(|k| bodies[k].map_or(Mode::Rest, |i| self.tracks[i].mode));
        let (was, _) = self.energies_j(bodies, given.0, &given.1, now);
        let (is, _) = self.energies_j(bodies, now_modes, &now_states, now);
        self.rec.energy.impact_loss_j += was - is;
        self.clearance.hold(t.pair, Some(t));
        // A body against a fixed face whose pivot stays on the ground, stuck, rests there
        // (where the push has a moment about its pivot to hold it by).
        let resting = (bodies.iter().flatten().copied())
            .find(|&i| bodies.contains(&None) && matches!(self.tracks[i].mode, Mode::Rock(_)));
        if let Some(i) = resting {
            self.rests_still(i, now);
        }
        let leaning = resting.and_then(|i| Some((i, self.tracks[i].leans?)));
        what += &match (leaning, bodies.contains(&None)) {
            (Some((i, lean)), _) => format!(
                "; it rests against the face, pushed by {:.6e} N",
                lean.push_n(self.body(i), now)
            ),
            (None, fixed) => {
                let push = self.coupled(&couple, now).push[0];
                match fixed {
                    true => format!("; it slides along the face, pushed by {push:.6e} N"),
                    false => format!("; they turn on together, pushed apart by {push:.6e} N"),
                }
            }
        };
        self.rec
            .rocking_event(self.t, EventKind::BlocksImpact, &t.blocks, omega, what);
        if let Some((i, corner)) = lands {
            self.couple_lands(i, corner, now)?;
        }
        Ok(None)
    }

    /// An impact `t` whose contact stays (`out`; `stays` says how) where its push has no moment
    /// about either body's pivot (`sides`, as the impact leaves them) and each body alone does
    /// not close it ([`Couple::closed_alone`]): a corner both bodies turn about, or that
    /// neither's motion moves, as where two blocks' bottom corners are together. It holds no
    /// push: each goes on alone, the pair struck (they must part before they may strike again).
    fn holds_nothing(
        &mut self,
        t: &Touch,
        out: &collision::Outcome,
        now: &Inputs,
        stays: String,
        through: Through,
        sides: Sides,
    ) {
        let Sides {
            bodies,
            states,
            modes,
            ..
        } = sides;
        self.rec.energy.impact_loss_j += out.loss_j;
        let mut what = self.stays_in_contact(t, out, &stays, through);
        let mut omega = None;
        let mut settled = states;
        for k in 0..2 {
            let Some(i) = bodies[k] else {
                continue;
            };
            settled[k] = settled_in(self.body(i), modes[k], states[k]);
            if out.impulse_n_s > 0.0 {
                self.rec.rocking_impact(t.blocks[k]);
            }
            let tr = &mut self.tracks[i];
            omega.get_or_insert((tr.state.omega, settled[k].omega));
            what += &format!(
                "; {}: theta' {:.6e} -> {:.6e} rad/s, {}",
                self.layout.names[t.blocks[k]],
                tr.state.omega,
                settled[k].omega,
                in_mode(modes[k], &settled[k])
            );
            (tr.mode, tr.state) = (modes[k], settled[k]);
        }
        // What settling the impact law's round-off changes of the energies goes with its loss.
        let (was, _) = self.energies_j(bodies, modes, &states, now);
        let (is, _) = self.energies_j(bodies, modes, &settled, now);
        self.rec.energy.impact_loss_j += was - is;
        self.clearance.strike(t.pair);
        what += "; their contact is at a corner both turn about, where it holds no push: each \
                 goes on alone";
        self.rec
            .rocking_event(self.t, EventKind::BlocksImpact, &t.blocks, omega, what);
    }

    /// Condition k of body i's watch falls (`at_landing`: under a landing's impulse): a held
    /// joint of its column gives way, which the exact model does not follow; the run ends here
    /// and says so.
    fn gives(&mut self, i: usize, k: usize, at_landing: bool) {
        let (joint, how, upper) = self.scene.watches[i].describe(k);
        // The block on the joint first (the event names its joint), then the body's.
        let on = self.layout.column_output(i, upper);
        let mut blocks = vec![on];
        blocks.extend(self.layout.outputs(i).into_iter().filter(|&b| b != on));
        self.held_joint_gives(i, &blocks, joint, how, at_landing);
    }

    /// The joint named `joint` under body i gives way as `how` says (`at_landing`: under a
    /// landing's impulse, the state given being the one just before the impact, which the exact
    /// model cannot resolve): the event, on `blocks`, and the warning that the run stops here.
    fn held_joint_gives(
        &mut self,
        i: usize,
        blocks: &[usize],
        joint: String,
        how: &str,
        at_landing: bool,
    ) {
        let how = if at_landing {
            format!(
                "{how}, under the impulse of the landing at this instant (the state given is \
                 the one just before it)"
            )
        } else {
            how.to_string()
        };
        self.rec
            .rocking_event(self.t, EventKind::HeldJointGives, blocks, None, how.clone());
        self.stops(Warning::HeldJointGives {
            body: self.body(i).name.clone(),
            joint,
            how,
            time_s: self.t,
        });
    }

    fn overturn(&mut self, i: usize, traj: &Trajectory, tau: f64) -> Result<(), SimulationError> {
        let body = self.body(i);
        // Its last motion, at the instant it falls: after this it is drawn lying still.
        for (k, u) in self.layout.series(i, body, traj) {
            self.rec.block_extremes(
                k,
                series::eval(&u, tau).abs(),
                series::eval(&series::derivative(&u), tau).abs(),
            );
        }
        let (_, now) = self.inputs_at(self.t);
        let at_rest = State {
            omega: 0.0,
            v: 0.0,
            lift: 0.0,
            lift_v: 0.0,
            ..self.tracks[i].state
        };
        let tr = &mut self.tracks[i];
        // A body that turns to a face in flight lies where it would land, on the corner it
        // left (drawn on the ground).
        let lying = match tr.mode {
            Mode::Flight(c) => Mode::Rock(c),
            other => other,
        };
        tr.fallen = Some(modes::trajectory(
            body,
            self.scene.equations,
            lying,
            &at_rest,
            &now,
        ));
        for k in self.layout.outputs(i) {
            self.rec.fell(k);
        }
        self.rec.energy.fallen_j +=
            modes::kinetic_j(body, traj, tau) + modes::potential_j(body, traj, tau);
        self.rec.rocking_event(
            self.t,
            EventKind::Overturning,
            &self.layout.outputs(i),
            None,
            format!("overturned at theta = {} rad", tr.state.theta),
        );
        if self.rec.collapse.is_none() {
            self.rec.collapse = Some(Collapse {
                time_s: self.t,
                block: body.name.clone(),
                cause: CollapseCause::Overturning,
            });
        }
        if self.scene.settings.after_collapse == AfterCollapse::Stop
            || self.tracks.iter().all(|t| t.fallen.is_some())
        {
            self.t_end = self.t;
        }
        Ok(())
    }

    /// A landing on the other corner, then the mode after it; a series of landings that
    /// accumulates is summed.
    fn land(&mut self, i: usize, now: &Inputs) -> Result<(), SimulationError> {
        let body = self.body(i);
        let eq = self.scene.equations;
        let tr = &self.tracks[i];
        let pivot = tr.mode.pivot().expect("only a rocking body lands");
        let (omega, v, u) = (tr.state.omega, tr.state.v, tr.state.u);
        let landing = impact::land(body, eq, pivot, omega, v, self.t)?;
        let after = landing.state.omega;
        let breaks = self.scene.watches.get(i).and_then(|w| {
            w.landing(
                u,
                (Some(pivot), omega, v),
                (landing.pivot, after, landing.state.v),
                &self.tracks[i].displaced,
                &self.tracks[i].displaced,
            )
        });
        if let Some(k) = breaks {
            // The landing's impulse would break a held joint, so the impact is not the one the
            // body's law has: the chain's law takes it, or the run stops at the instant before
            // it (where a hand-off's time stepping resolves it), not after an impact it does not
            // believe.
            if !self.lands_as_chain(now)? {
                self.gives(i, k, true);
            }
            return Ok(());
        }
        // A landing is found where theta is zero to a tie (series::TIE of alpha), and the body
        // is then seated at theta = 0: what potential energy it had there (m g b theta, up to
        // 5e-9 J for a 0.4 m block) goes with the landing's loss, or the balance would lose it.
        let dropped = modes::potential_j(body, &self.trajectory(i, now), 0.0);
        let u = u + self.seat_shift_touching_m(i, pivot, now);
        self.install(i, &landing, u, dropped);
        let mut what = landing
            .pivot
            .map_or("seated".into(), |c| format!("on the {} corner", c.name()));
        if let Some(contacts) = self.scene.watches.get(i).and_then(Watch::landing_contacts) {
            what = format!("{what}: {contacts}");
        }
        self.rec.rocking_event(
            self.t,
            EventKind::RockingImpact,
            &self.layout.outputs(i),
            Some((omega, after)),
            what,
        );
        if let (Some(c), false) = (landing.pivot, landing.slipped) {
            if let Some(tail) = self.zeno_tail(i, c, omega, after, now) {
                let kinetic = {
                    let t = self.trajectory(i, now);
                    modes::kinetic_j(body, &t, 0.0)
                };
                self.rec.energy.impact_loss_j += kinetic;
                self.rec.zeno += 1;
                let tr = &mut self.tracks[i];
                tr.state = State {
                    u,
                    ..State::default()
                };
                tr.mode = Mode::Rest;
                // Seated through the series' duration (what the series leaves is below 1e-9
                // alpha), the body comes to rest at its end, an event of its own; the steps
                // meanwhile write the history's rows (the landing's, the output times') and
                // move the other bodies.
                tr.settles = Some((self.t + tail, after, tail));
                return Ok(());
            }
        }
        self.decide(i, now, false)
    }

    /// Body k, whose tilt of a tie `theta` about `pivot` has just been set to zero, its base's
    /// middle at rest at `origin`: where it touches the other body at `ends` sideways, that
    /// tilt turned its face under the other's, and its base moves along the ground so that
    /// neither end goes into the other ([`seat_shift_among_m`]).
    fn set_upright_clear(
        &mut self,
        k: usize,
        (origin, pivot): ([f64; 2], Corner),
        theta: f64,
        ends: [&Touch; 2],
    ) {
        let sideways = (ends.iter()).all(|t| t.normal[0].abs() > std::f64::consts::FRAC_1_SQRT_2);
        if !sideways || self.tracks[k].state.theta != 0.0 {
            return;
        }
        let home = self.home(k, origin, pivot);
        let side = |t: &Touch| match t.sides[0] {
            Side::Body(b, _) if b == k => 1.0,
            _ => -1.0,
        };
        let at = ends.map(|t| (t.point, t.normal, side(t)));
        let st = &mut self.tracks[k].state;
        st.u += seat_shift_among_m(&at, home, theta, st.u);
    }

    /// How far along the ground (m) body i, landing alone from its tilt of a tie about `pivot`,
    /// is moved so that no block touching one of its side faces at the instant (a corner just
    /// struck on it, or one of its corners on another's face) is moved into as the tilt is set
    /// to zero ([`seat_shift_among_m`]): setting down a tilt of 1e-11 rad moves the top of a
    /// block 1.2 m high by about as much. None where nothing touches its sides.
    fn seat_shift_touching_m(&self, i: usize, pivot: Corner, now: &Inputs) -> f64 {
        let st = &self.tracks[i].state;
        if st.theta == 0.0 || !self.clearance.watches(i) {
            return 0.0;
        }
        let trajs: Vec<Option<Trajectory>> = (0..self.tracks.len())
            .map(|k| (self.tracks[k].fallen.is_none()).then(|| self.trajectory(k, now)))
            .collect();
        let trajs: Vec<Option<&Trajectory>> = trajs.iter().map(Option::as_ref).collect();
        let touching = self.clearance.touching(i, self.scene.bodies, &trajs);
        let sideways = |t: &&Touch| t.normal[0].abs() > std::f64::consts::FRAC_1_SQRT_2;
        let is_i = |s: Side| matches!(s, Side::Body(b, _) if b == i);
        let (mut contacts, mut origin) = (Vec::new(), None);
        for t in touching.iter().filter(sideways) {
            // Body i is the corner's side (+1) or the face's (-1).
            let k = usize::from(!is_i(t.sides[0]));
            if let Side::Body(_, o) = t.sides[k] {
                origin = Some(o);
            }
            contacts.push((t.point, t.normal, if k == 0 { 1.0 } else { -1.0 }));
        }
        let Some(origin) = origin else {
            return 0.0;
        };
        seat_shift_among_m(&contacts, self.home(i, origin, pivot), st.theta, st.u)
    }

    /// Body i comes to rest, now, at the end of the series of landings a landing at `after`
    /// rad/s started, `tail` s long.
    fn settled(&mut self, i: usize, after: f64, tail: f64) {
        self.rec.rocking_event(
            self.t,
            EventKind::Rest,
            &self.layout.outputs(i),
            Some((after, 0.0)),
            format!("its landings accumulate after {tail:e} s"),
        );
    }

    /// Body i after `landing`, its pivot (or base) at `u`: the landing's loss booked with
    /// `dropped` (the potential energy of what the landing found at a tie), the impact counted.
    fn install(&mut self, i: usize, landing: &impact::Landing, u: f64, dropped: f64) {
        self.rec.energy.impact_loss_j += landing.loss_j + dropped;
        for k in self.layout.outputs(i) {
            self.rec.rocking_impact(k);
        }
        self.rec.impacts += 1;
        let tr = &mut self.tracks[i];
        tr.state = State { u, ..landing.state };
        tr.mode = match landing.pivot {
            Some(c) => Mode::Rock(c),
            None => Mode::Rest,
        };
    }

    /// A body in free flight lands on `corner` ([`impact::land_from_flight`]), then the mode
    /// after it. Tilted by a round-off the other way, its corners level to a tie of angle, it
    /// lands on the one that is lower to the bit; tilted to the side `corner` cannot rock on,
    /// its corners level to a tie of its size, the landing is decided upright.
    fn land_from_flight(
        &mut self,
        i: usize,
        corner: Corner,
        now: &Inputs,
    ) -> Result<(), SimulationError> {
        let body = self.body(i);
        let traj = self.trajectory(i, now);
        let Mode::Flight(followed) = traj.mode else {
            return Err(SimulationError::Bug(
                "only a body in flight lands from it".into(),
            ));
        };
        let st = self.tracks[i].state;
        let (xg, yg) = (
            st.v + traj.gy[0] * st.omega,
            st.lift_v + traj.dx[0] * st.omega,
        );
        let level = st.theta.abs() <= series::TIE * body.slenderness_rad();
        let other = corner.other();
        let rise = |c: Corner| impact::rise_m_s(body, st.theta, c, (yg, st.omega));
        let falls =
            |c: Corner| rise(c) < 0.0 && !impact::touches(body, st.theta, c, (yg, st.omega));
        let lower = corner.sign() * st.theta < 0.0 && falls(other);
        // Upright, the corner that comes down lands, not the one that rises.
        let upright = st.theta == 0.0 && falls(other) && rise(corner) > 0.0;
        let corner = if (level && lower) || upright {
            other
        } else {
            corner
        };
        // Tilted to the side its corner cannot rock on, by a tilt that leaves the corners level
        // to a tie: the tilt's sign is round-off, and the landing is decided upright (on the
        // corner that comes down where the other rises, else flat, else on one corner alone).
        // It keeps its tilt where it rocks on the corner the tilt lowers; else it is set upright
        // (its height's change going with the loss below).
        let wrong_side =
            corner.sign() * st.theta < 0.0 && level_by_round_off(body, body.half_base_m, st.theta);
        let landing = if wrong_side {
            let mut upright =
                impact::land_from_flight(body, 0.0, corner, (xg, yg, st.omega), self.t)?;
            if upright.pivot.is_some_and(|c| c.sign() * st.theta >= 0.0) {
                upright.state.theta = st.theta;
            }
            upright
        } else {
            impact::land_from_flight(body, st.theta, corner, (xg, yg, st.omega), self.t)?
        };
        let corner = landing.pivot.unwrap_or(corner);
        // The landing corner's displacement: the other corner lies 2 s b cos theta from the
        // one followed, 2 s b apart at rest (2 s b (1 - cos) = 4 s b sin^2(theta / 2)).
        let mut u = if corner == followed {
            st.u
        } else {
            let half = (0.5 * st.theta).sin();
            st.u + 4.0 * followed.sign() * body.half_base_m * half * half
        };
        if landing.state.theta != st.theta {
            // Set upright, it moves clear of what touches its sides, as a landing from rocking.
            u += self.seat_shift_touching_m(i, corner, now);
        }
        // Its height, zero to a tie where the landing was found, goes with the landing's loss
        // as a landing from rocking's tilt does.
        let dropped = modes::potential_j(body, &traj, 0.0)
            - modes::potential_j(
                body,
                &modes::trajectory(
                    body,
                    self.scene.equations,
                    Mode::Rock(corner),
                    &State { u, ..landing.state },
                    now,
                ),
                0.0,
            );
        self.install(i, &landing, u, dropped);
        let what = match landing.pivot {
            Some(c) if impact::touches(body, st.theta, corner, (yg, st.omega)) => {
                format!(
                    "from free flight on the {} corner, touching without speed: no impulse",
                    c.name()
                )
            }
            Some(c) => format!("from free flight on the {} corner", c.name()),
            None => "from free flight, flat on both corners".into(),
        };
        self.rec.rocking_event(
            self.t,
            EventKind::RockingImpact,
            &self.layout.outputs(i),
            Some((st.omega, landing.state.omega)),
            what,
        );
        self.decide(i, now, false)
    }

    /// The time left in a series of landings, if the landing leaves the body rising by less
    /// than [`ZENO_ROTATION`] alpha (w^2 / (2 kappa)), the rocking stays pure (friction holds on
    /// both corners) and returns on both sides; it ends at the end of the segment or run at
    /// the latest. Near theta = 0
    /// a body is a ball bouncing under the constant angular deceleration kappa of each side:
    /// a half-cycle on side c lasts 2 w / kappa_c and the next starts at r w, so the rest of
    /// the series lasts 2 w (1 / kappa_c + r / kappa_other) / (1 - r^2).
    fn zeno_tail(&self, i: usize, c: Corner, before: f64, after: f64, now: &Inputs) -> Option<f64> {
        let body = self.body(i);
        let r = (after / before).abs();
        if r >= 1.0 || after == 0.0 {
            return None;
        }
        let seated = State {
            u: self.tracks[i].state.u,
            ..State::default()
        };
        let side = |corner: Corner| -> Option<f64> {
            let t = modes::trajectory(body, self.scene.equations, Mode::Rock(corner), &seated, now);
            let kappa = -corner.sign() * 2.0 * t.theta[2];
            let holds = self.scene.equations == Equations::Linearised
                || (t.normal[0] > 0.0 && t.tangential[0].abs() < body.friction * t.normal[0]);
            (kappa > 0.0 && holds).then_some(kappa)
        };
        let (k_this, k_other) = (side(c)?, side(c.other())?);
        if after * after / (2.0 * k_this) > ZENO_ROTATION * body.slenderness_rad() {
            return None;
        }
        let tail = 2.0 * after.abs() * (1.0 / k_this + r / k_other) / (1.0 - r * r);
        let (seg, _) = self.inputs_at(self.t);
        Some(tail.min(seg.t1.min(self.t_end) - self.t))
    }

    /// Notes at `t` every body's extremes and, when `row`, a history row, read off each body's
    /// trajectory `tau` after the step's start (a body that fell, where it fell); `a_g` is the
    /// ground acceleration then.
    fn note(&mut self, plans: &[Option<Plan>], tau: f64, t: f64, a_g: f64, row: bool) {
        let mut r = Row::at_rest(self.layout.len(), a_g);
        let Row {
            u,
            v,
            theta,
            omega,
            w,
            accel,
        } = &mut r;
        for (i, plan) in plans.iter().enumerate() {
            let body = self.body(i);
            let (traj, at) = match (plan, &self.tracks[i].fallen) {
                (Some((traj, _)), _) => (traj, tau),
                (None, Some(fallen)) => (fallen, 0.0),
                (None, None) => unreachable!("a body without a step has fallen"),
            };
            for (k, base) in self.layout.series(i, body, traj) {
                let base_v = series::derivative(&base);
                u[k] = series::eval(&base, at);
                v[k] = series::eval(&base_v, at);
                if self.layout.turns(k) {
                    theta[k] = series::eval(&traj.theta, at);
                    omega[k] = series::eval(&traj.omega, at);
                }
                accel[k] = plan
                    .is_some()
                    .then(|| a_g + series::eval(&series::derivative(&base_v), at));
            }
            for (k, (du, dv, da)) in self.held_moved(i, traj, at, plan.is_none()) {
                u[k] = du;
                v[k] = dv;
                if let Some(da) = da {
                    accel[k] = Some(a_g + da);
                }
            }
            if row {
                let pivot = traj.mode.corner();
                let theta = series::eval(&traj.theta, at);
                let flying = match traj.mode {
                    Mode::Flight(_) => Some(series::eval(&traj.lift, at)),
                    _ => None,
                };
                for (k, lift) in self.layout.lifts(i, pivot, theta) {
                    w[k] = flying.map_or(lift, |corner| lift + corner);
                }
            }
        }
        self.record(&r, t, row);
    }

    /// The held blocks of body i's column that a stack moved or moves, each with its output
    /// and where it is `tau` along `traj` (`fallen`: the body lies fallen, the stack where the
    /// body's state left it).
    fn held_moved(
        &self,
        i: usize,
        traj: &Trajectory,
        tau: f64,
        fallen: bool,
    ) -> Vec<(usize, Moved)> {
        let tr = &self.tracks[i];
        let Some(watch) = self
            .scene
            .watches
            .get(i)
            .filter(|_| !tr.displaced.is_still())
        else {
            return Vec::new();
        };
        watch
            .held_blocks()
            .map(|p| {
                let k = self.layout.column_output(i, p);
                let (x, slides) = tr.displaced.block(p, traj);
                if fallen {
                    let v = tr.displaced.velocity_m_s(p, tr.state.v);
                    return (k, (x[0], v, None));
                }
                let xv = series::derivative(&x);
                let xa = series::derivative(&xv);
                let acc = slides.then(|| series::eval(&xa, tau));
                (k, (series::eval(&x, tau), series::eval(&xv, tau), acc))
            })
            .collect()
    }

    /// Notes every output's extremes from `r` and, when `row`, writes it as the history row
    /// at t.
    fn record(&mut self, r: &Row, t: f64, row: bool) {
        for i in 0..r.u.len() {
            self.rec.block_extremes(i, r.u[i].abs(), r.v[i].abs());
            self.rec.rotation_extreme(i, r.theta[i].abs());
            if let Some(a) = r.accel[i] {
                self.rec.block_accel(i, a.abs());
            }
        }
        self.rec.joint_extremes(&r.u);
        if row {
            self.rec
                .sample_rotating(t, [&r.u, &r.v, &r.theta, &r.omega, &r.w]);
        }
    }

    /// The end of the run: the last extremes and history row (`row`: the last stop was an
    /// event or an output time; the end is a row in any case), the energy left, the summary;
    /// or, where the exact model stopped and the run is to be handed over, the state there.
    fn finish(mut self, row: bool) -> Result<Finished, SimulationError> {
        if let Some(end) = self.chain_end.take() {
            self.rec.energy.kinetic_j += end.kinetic_j;
            self.rec.energy.potential_j += end.potential_j;
            return Ok(self.summary(&end.u, &end.v, end.placed));
        }
        let (_, now) = self.inputs_at(self.t);
        let n = self.tracks.len();
        let plans: Vec<Option<Plan>> = (0..n)
            .map(|i| {
                self.tracks[i]
                    .fallen
                    .is_none()
                    .then(|| (self.trajectory(i, &now), None))
            })
            .collect();
        let last_row = self.rec.last_row_time();
        self.note(
            &plans,
            0.0,
            self.t,
            now.accel[0],
            row || last_row.is_some_and(|r| r < self.t),
        );
        let mut u = vec![0.0; self.layout.len()];
        let mut v = u.clone();
        let mut placed = vec![(0.0, 0.0, Turned::default()); self.layout.len()];
        for (i, plan) in plans.iter().enumerate() {
            let body = self.body(i);
            let traj = match (plan, &self.tracks[i].fallen) {
                (Some((traj, _)), _) => traj,
                (None, Some(fallen)) => fallen,
                (None, None) => unreachable!("a body without a step has fallen"),
            };
            for (k, base) in self.layout.series(i, body, traj) {
                u[k] = base[0];
                v[k] = base[1];
            }
            for (k, (du, dv, _)) in self.held_moved(i, traj, 0.0, plan.is_none()) {
                u[k] = du;
                v[k] = dv;
                placed[k] = (du, dv, Turned::default());
            }
            let tr = &self.tracks[i];
            for stack in tr.displaced.sliding.iter().chain(&tr.displaced.beneath) {
                let v = stack.velocity_m_s(tr.state.v);
                self.rec.energy.kinetic_j += 0.5 * stack.mass_kg * v * v;
            }
            if plan.is_some() {
                self.rec.energy.kinetic_j += modes::kinetic_j(body, traj, 0.0);
                self.rec.energy.potential_j += modes::potential_j(body, traj, 0.0);
                if let (true, Some((wall, _))) = (self.hand_off, self.scene.wall) {
                    let tr = &self.tracks[i];
                    let half_height = |k: usize| 0.5 * wall.blocks[k].height.to_f64();
                    for (k, p) in self.layout.placed(i, tr.mode, &tr.state, &half_height) {
                        placed[k] = p;
                    }
                }
            }
        }
        Ok(self.summary(&u, &v, placed))
    }

    /// The run's response, every output's final u (m) and u' (m/s) given; or, where the exact
    /// model stopped before the end and is to hand over, the state there, every output
    /// `placed` (the last row and the energies are written: the energies go to the balance of
    /// what follows, which counts the blocks' own again at its end).
    fn summary(mut self, u: &[f64], v: &[f64], placed: Vec<Placed>) -> Finished {
        let stopped = self.stop.is_some();
        if let (true, Some(why)) = (self.hand_off, self.stop.take()) {
            let e = &mut self.rec.energy;
            let mechanical_j = e.kinetic_j + e.potential_j;
            (e.kinetic_j, e.potential_j) = (0.0, 0.0);
            // The run goes on: the stop is an event, not a warning of where the run ended.
            self.rec.warnings.retain(|w| !w.stops_exact_model());
            let mut fallen = vec![false; self.layout.len()];
            for i in (0..self.tracks.len()).filter(|&i| self.tracks[i].fallen.is_some()) {
                for k in self.layout.outputs(i) {
                    fallen[k] = true;
                }
            }
            return Finished::Stopped(
                Box::new(HandOff {
                    t_s: self.t,
                    u_m: placed.iter().map(|p| p.0).collect(),
                    v_m_s: placed.iter().map(|p| p.1).collect(),
                    turned: placed.iter().map(|p| p.2).collect(),
                    fallen,
                    mechanical_j,
                    rec: self.rec,
                    next_output: self.outputs + 1,
                }),
                why,
            );
        }
        let motion = self.scene.motion.describe();
        let t = self.t;
        if stopped {
            self.rec.stopped_at_s = Some(t);
        }
        let name = self
            .scene
            .bodies
            .iter()
            .map(|b| b.name.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        Finished::Ended(Box::new(self.rec.finish("event", &name, motion, t, u, v)))
    }
}
