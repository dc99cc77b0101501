//! What a run produces, whatever the integrator: the summary (`summary.json`), the history of
//! displacements and velocities (`history.csv`), the event log (`events.jsonl`), and, from the
//! event-driven integrator when asked, the log of its mode decisions (`decisions.jsonl`).
//! Integrators feed a recorder; nothing here knows how the numbers were computed.

mod history_file;
pub use history_file::{each_row, RowVisitor, Stream};
mod partial;
pub use partial::partial_name;
pub mod moved;
mod recorder;
pub mod saved;

#[doc(hidden)]
pub use recorder::{horizontal_joints, Recorder};

use crate::topology::{BlockId, HorizontalId, JointRef};
use serde::Serialize;

/// Kinds of logged events.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum EventKind {
    /// A horizontal joint starts to slide.
    Slip,
    /// A horizontal joint stops sliding.
    Stick,
    /// Two faces collide with a positive approach speed.
    Impact,
    /// Two faces come into contact with zero approach speed.
    Touch,
    /// Two touching faces move apart; a column turns away from the fixed block it rested
    /// against.
    Separation,
    /// A block falls.
    Collapse,
    /// A sequence of impacts with e < 1 accumulates; the faces stay in contact from here.
    Zeno,
    /// A seated block lifts off one corner and starts to rock (where a sliding run hands over
    /// to time stepping, the blocks the uplift check finds turning).
    Uplift,
    /// A rocking block lands on its other corner.
    RockingImpact,
    /// The corner a block rocks on stops slipping.
    PivotStick,
    /// The corner a block rocks on starts to slip (slide-rock).
    PivotSlip,
    /// A rocking block comes to rest seated on both corners (its impacts accumulated); after
    /// time stepping, the wall set down flat, with the blocks that rocked since the uplift
    /// (`--after-uplift moreau-while-rocking`).
    Rest,
    /// A block overturns: it passed the point of no return, or lies on its face.
    Overturning,
    /// A block leaves the ground on both corners (free flight): beyond the model, the run stops.
    Flight,
    /// A joint a column's rocking model holds would slip or open: beyond the model, the run
    /// stops.
    HeldJointGives,
    /// Blocks of two columns (or a column's and a fixed one) that stood apart meet where the
    /// model does not follow them (two corners, a body that does not rock on a pivot, blocks
    /// that stay in contact): the run stops.
    BlocksMeet,
    /// A corner of one block strikes a face of another (of another column, or fixed): the
    /// impact is resolved and the run goes on.
    BlocksImpact,
}

/// One logged event.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventRecord {
    /// Time (s).
    pub time_s: f64,
    /// What happened.
    pub kind: EventKind,
    /// Blocks involved, by name.
    pub blocks: Vec<String>,
    /// The same blocks by index (not written: the event log names them).
    #[serde(skip)]
    pub block_ids: Vec<BlockId>,
    /// The joint, `"upper/lower"` or `"left|right"`, when one is involved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
    /// The same joint by index (not written).
    #[serde(skip)]
    pub joint_id: Option<JointRef>,
    /// Approach speed of an impact (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub approach_speed_m_s: Option<f64>,
    /// Velocities of the two blocks (left, right) just before an impact (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub before_m_s: Option<[f64; 2]>,
    /// Velocities of the two blocks (left, right) just after an impact (m/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub after_m_s: Option<[f64; 2]>,
    /// A rocking block's angular velocity just before the event (rad/s, clockwise positive).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angular_velocity_before_rad_s: Option<f64>,
    /// Its angular velocity just after (rad/s).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub angular_velocity_after_rad_s: Option<f64>,
    /// The mode a rocking block goes on in ("rock on the left corner", ...).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mode: Option<String>,
}

/// What brought the event-driven integrator to decide the mode again.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum DecisionCause {
    /// The wall at rest at t = 0.
    Start,
    /// The ground acceleration reached a limit of a cluster stuck to the ground.
    StickLimit,
    /// A sliding cluster came to rest relative to the ground.
    Stop,
    /// Two sliding clusters reached the same velocity.
    Meet,
    /// Faces closed at zero approach speed.
    Touch,
    /// Faces collided.
    Impact,
    /// A series of impacts with e < 1 accumulated.
    Zeno,
    /// A sliding cluster whose friction forces a decision next to it changed.
    Split,
    /// A block fell (`--after-collapse continue`).
    Fall,
}

/// A cluster stuck to the ground, with the limits of the ground acceleration it holds within
/// (m/s2, at unit vertical load factor; `None`: no ground acceleration that way moves it).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct StuckGroup {
    /// Its blocks.
    pub blocks: usize,
    /// Lower limit of a_g (m/s2).
    pub a_g_lo_m_s2: Option<f64>,
    /// Upper limit of a_g (m/s2).
    pub a_g_hi_m_s2: Option<f64>,
    /// The lower limit is only a bound from inside, kept from a larger group and worked out
    /// when a_g reaches it (the limit itself lies at it or beyond).
    pub lo_is_bound: bool,
    /// The same for the upper limit.
    pub hi_is_bound: bool,
}

/// One mode decision of the event-driven integrator: what it took in, what it cost, what it
/// made. Its counts add up to the run's `stats` (`mode_decisions`, `decision_blocks`,
/// `flow_nodes`); `cpu_s` is measured, so it differs from run to run.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct DecisionRecord {
    /// Time (s).
    pub time_s: f64,
    /// What brought it.
    pub cause: DecisionCause,
    /// Ground acceleration (m/s2).
    pub a_g_m_s2: f64,
    /// Vertical load factor 1 + a_v/g (1 without a vertical component): the limits of a stuck
    /// group are at unit load factor, so it holds while a_g / load_factor lies within them.
    pub load_factor: f64,
    /// Blocks it took in: the clusters joined to the event by joints at equal velocities.
    pub blocks: usize,
    /// The largest cluster stuck to the ground among those it took in, as it was.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stuck_taken_in: Option<StuckGroup>,
    /// Clusters it formed.
    pub clusters: usize,
    /// The largest cluster stuck to the ground it formed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stuck_formed: Option<StuckGroup>,
    /// Nodes of its maximum-flow passes, summed over passes.
    pub flow_nodes: u64,
    /// CPU time of the calling thread (s), from gathering the blocks to scheduling the new
    /// clusters' events; the decisions it sets off for split clusters are records of their own.
    pub cpu_s: f64,
}

/// Per-block results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BlockSummary {
    /// The block (its index in the wall; not written, the name is).
    #[serde(skip)]
    pub id: BlockId,
    /// Name.
    pub name: String,
    /// Largest |u| relative to the ground (m).
    pub max_abs_displacement_m: f64,
    /// u at the end (m).
    pub final_displacement_m: f64,
    /// Largest |v| relative to the ground (m/s).
    pub max_abs_velocity_m_s: f64,
    /// Largest absolute acceleration (m/s2), for the rocking check (sliding model; with
    /// rocking, the largest at its events and history samples).
    pub max_abs_accel_m_s2: f64,
    /// Largest |theta| (rad): 0 when it never lifted (or the model slides only).
    pub max_abs_rotation_rad: f64,
    /// When it first lifted off a corner (s); `null` if never.
    pub uplift_time_s: Option<f64>,
    /// Landings on a corner while rocking (an accumulated series counts once).
    pub rocking_impacts: u64,
    /// The block fell.
    pub fell: bool,
}

/// Per horizontal joint results.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct HorizontalJointSummary {
    /// Which joint (not written, the names are).
    #[serde(skip)]
    pub joint: HorizontalId,
    /// Upper block.
    pub upper: String,
    /// Lower block or `ground`.
    pub lower: String,
    /// Largest |u_upper - u_lower| (m).
    pub max_abs_relative_displacement_m: f64,
    /// u_upper - u_lower at the end (m).
    pub final_relative_displacement_m: f64,
}

/// Energy balance (J), relative to the moving ground.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Energy {
    /// Mechanical energy at the start (a block released from a rotation holds potential
    /// energy; 0 for a wall at rest).
    pub initial_j: f64,
    /// Work of the inertial forces -m a_g on the blocks.
    pub input_j: f64,
    /// Dissipated by friction.
    pub friction_j: f64,
    /// Lost in impacts.
    pub impact_loss_j: f64,
    /// Kinetic energy at the end.
    pub kinetic_j: f64,
    /// Potential energy at the end, above the seated position (rocking blocks lift their
    /// centroid; 0 for sliding).
    pub potential_j: f64,
    /// Kinetic energy carried away by blocks that fell.
    pub fallen_j: f64,
    /// initial + input - friction - impact loss - kinetic - potential - fallen: zero up to
    /// round-off for an exact integrator.
    pub residual_j: f64,
}

/// A collapse.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Collapse {
    /// When (s).
    pub time_s: f64,
    /// Which block fell first.
    pub block: String,
    /// How it fell.
    pub cause: CollapseCause,
}

/// How a block fell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum CollapseCause {
    /// Its centroid left the span its supports give it.
    #[serde(rename = "sliding off")]
    SlidingOff,
    /// It rocked past the point of no return, or onto its face.
    #[serde(rename = "overturning")]
    Overturning,
}

/// Which model ran, and why (`--model auto` chooses).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModelUsed {
    /// `"slide"` (blocks slide, one degree of freedom each) or `"slide-rock"` (they may also
    /// lift, rock and overturn).
    pub name: String,
    /// The rocking equations (`"exact"` or `"linearised"`); absent for `"slide"`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub equations: Option<String>,
    /// `"in-plane"` (the wall's own plane) or `"out-of-plane"` (across it).
    pub direction: String,
    /// Why this model.
    pub why: String,
}

impl Default for ModelUsed {
    fn default() -> ModelUsed {
        ModelUsed {
            name: "slide".into(),
            equations: None,
            direction: "in-plane".into(),
            why: "asked for (--model slide)".into(),
        }
    }
}

/// Work counters of a run.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize)]
pub struct Stats {
    /// Events handled (or steps taken, for time stepping).
    pub events: u64,
    /// Mode decisions solved.
    pub mode_decisions: u64,
    /// Segments of the ground motion crossed.
    pub segments: u64,
    /// Root refinements (function evaluations in root finding).
    pub root_evaluations: u64,
    /// Time steps (time-stepping methods).
    pub steps: u64,
    /// Blocks in the mode decisions, summed over decisions: the size of the rigid groups the
    /// events touched (event-driven).
    pub decision_blocks: u64,
    /// Nodes of the maximum-flow passes of the exact decisions, summed over passes (minimum
    /// cuts over at most six blocks try every set and run none; event-driven).
    pub flow_nodes: u64,
    /// Pairs of sliding clusters whose events were found, summed over the times they were
    /// (event-driven): the scheduling work, which a decision beside a large sliding body
    /// keeps to the pairs it changed.
    pub pair_schedules: u64,
    /// Steps whose Gauss-Seidel stopped at its sweep limit (Moreau-Jean; written only when
    /// not zero).
    #[serde(skip_serializing_if = "is_zero")]
    pub unconverged_steps: u64,
}

fn is_zero(x: &u64) -> bool {
    *x == 0
}

/// `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Integrator.
    pub method: String,
    /// Model: sliding only, or sliding and rocking, and why.
    pub model: ModelUsed,
    /// Wall name.
    pub wall: String,
    /// Ground motion.
    pub motion: String,
    /// What was done to the record before the run (window, baseline, scaling).
    pub motion_processing: Vec<String>,
    /// Simulated time (s).
    pub duration_s: f64,
    /// The run was asked to stop (Ctrl-C) and ended at this time (s), before its duration:
    /// every number here is of the motion up to it. Absent for a run that went to its end.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub interrupted_at_s: Option<f64>,
    /// The exact model stopped following the wall at this time (s), before the run's duration,
    /// and the run ended there (a warning says why): every number here is of the motion up to
    /// it. Absent for a run that went to its end, and for one that time stepping carried on
    /// from the stop (`--after-stop moreau`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stopped_at_s: Option<f64>,
    /// Per block.
    pub blocks: Vec<BlockSummary>,
    /// Per horizontal joint (`joints` in summary.json, its name there since the first release).
    #[serde(rename = "joints")]
    pub horizontal_joints: Vec<HorizontalJointSummary>,
    /// Impacts (positive approach speed).
    pub impacts: u64,
    /// Contacts made at zero approach speed.
    pub touches: u64,
    /// Infinite series of impacts (e < 1) summed in closed form; each counts once in `impacts`.
    /// With them, pairs of rocking blocks set down seated where the exact model had no way on
    /// and both were within 1e-9 of their alpha from rest (docs/rocking-walls.md).
    pub zeno_accumulations: u64,
    /// Horizontal joints changing between sticking and slipping.
    pub stick_slip_transitions: u64,
    /// First collapse, if any.
    pub collapse: Option<Collapse>,
    /// Energy balance.
    pub energy: Energy,
    /// Work counters.
    pub stats: Stats,
    /// The largest share of a joint's overlap at rest (where a block rests on another) that
    /// sliding took away, 0 to 1: the sliding model keeps the loads and capacities of the
    /// overlaps at rest, so its answer is one of small displacements while this is small
    /// (a warning from [`crate::validity::SMALL_OVERLAP_LOSS`]). Absent for runs with rotations,
    /// whose geometry moves.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub max_overlap_loss: Option<f64>,
    /// Warnings about the validity of the model for this run.
    pub warnings: Vec<Warning>,
    /// Across the wall's plane: the section nearest to overturning (absent when none lifted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst: Option<Worst>,
    /// Whether every block could stay seated along the sliding run (`--check-uplift`), and the
    /// first instant one could not; absent when not asked.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub uplift_check: Option<UpliftCheck>,
}

/// The uplift check of a sliding run: at every instant, whether contact forces exist that give
/// each block its sliding acceleration with no block turning (`limit::seated`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct UpliftCheck {
    /// Checked from t = 0 up to this time (s): the run's end, or the first uplift.
    pub checked_until_s: f64,
    /// The first instant some block must start to turn; `None`: every block stayed seated.
    pub first_uplift: Option<Uplift>,
}

/// The first instant of a sliding run at which no contact forces keep every block seated.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Uplift {
    /// When (s).
    pub time_s: f64,
    /// The ground's acceleration then (m/s2).
    pub ground_accel_m_s2: f64,
    /// The blocks that start to turn, each with how (`F1 turns counterclockwise about its
    /// bottom-left corner`), from the mechanism of the seated program's multipliers.
    pub turning: Vec<String>,
    /// Whether the mechanism `turning` comes from is the only one past that instant, decided
    /// as the limit at rest's is.
    pub mechanism_uniqueness: crate::limit::Uniqueness,
    /// The blocks that turn in every mechanism that holds then (every block of `turning` where
    /// the mechanism is unique; where the state keeps no block seated whatever the ground does,
    /// in every certificate of that); `None` where not decided.
    pub turning_in_every_mechanism: Option<Vec<String>>,
}

/// The body of a run nearest to overturning: the first to overturn, or the one whose largest
/// rotation came nearest its slenderness alpha.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Worst {
    /// Its name.
    pub block: String,
    /// Largest |theta| / alpha.
    pub rotation_over_alpha: f64,
    /// It overturned.
    pub overturned: bool,
}

/// A warning about a run: where the model stops being valid, or a method's own trouble. Written
/// into `summary.json` as its text (the same words as the terminal's).
#[derive(Debug, Clone, PartialEq)]
pub enum Warning {
    /// A block's peak absolute acceleration reached Housner's g b/h: as a free block it could
    /// rock, which the sliding model leaves out.
    CouldRock {
        /// The block.
        block: crate::topology::BlockId,
        /// Its name.
        name: String,
        /// Its peak absolute acceleration (m/s2).
        peak_accel_m_s2: f64,
        /// g b/h (m/s2).
        limit_m_s2: f64,
        /// The lowest friction coefficient under it.
        friction: f64,
        /// b/h.
        ratio: f64,
    },
    /// More blocks could rock than the warnings list.
    MoreCouldRock {
        /// How many more.
        more: usize,
    },
    /// A joint of a sliding run lost a share of its overlap at rest that is no longer small
    /// ([`crate::validity::SMALL_OVERLAP_LOSS`]): the model keeps the loads and capacities of
    /// the overlaps at rest.
    OverlapLost {
        /// The block on top.
        upper: String,
        /// What it rests on.
        lower: String,
        /// The joint's overlap at rest (m).
        at_rest_m: f64,
        /// Its least overlap along the run (m).
        least_m: f64,
        /// u_upper - u_lower there (m).
        slip_m: f64,
    },
    /// The uplift check found an instant from which the sliding answer leaves rocking out.
    Lifts {
        /// When (s).
        time_s: f64,
        /// The blocks that start to turn, each with how.
        turning: Vec<String>,
    },
    /// A rocking body left the ground on both corners: the run stopped there.
    Flight {
        /// The body.
        body: String,
        /// When (s).
        time_s: f64,
    },
    /// A joint that the column model holds (or a trilith's mechanism) would slip or open under
    /// the moving body: the run stopped there.
    HeldJointGives {
        /// The body that moves.
        body: String,
        /// The joint, `upper/lower` (`A/B and C/D` where a pair is watched together).
        joint: String,
        /// How it gives way.
        how: String,
        /// When (s).
        time_s: f64,
    },
    /// Blocks of two columns (or a column's block and a fixed one) that the rocking model
    /// follows apart met: the run stopped there.
    BlocksMeet {
        /// One block.
        first: String,
        /// The other.
        second: String,
        /// Why the meeting is not followed.
        why: String,
        /// When (s).
        time_s: f64,
    },
    /// A level of the wall was not checked across its plane.
    LevelSkipped {
        /// Its height (m).
        level_m: f64,
        /// Why.
        why: String,
    },
    /// Blocks that rest on two or more blocks, run with rotations (Moreau-Jean): how their load
    /// splits among their supports is statically indeterminate for rigid blocks.
    IndeterminateSupport {
        /// Their names (the first few).
        blocks: Vec<String>,
        /// How many there are.
        count: usize,
        /// The whole-wall Newton solver decided the split (that of contact springs of one
        /// stiffness per metre of joint) rather than Gauss-Seidel's sweeps.
        elastic: bool,
    },
    /// Gauss-Seidel stopped at its sweep limit in some steps (Moreau-Jean).
    Unconverged {
        /// Steps that ended unconverged.
        steps: u64,
        /// The sweep limit.
        sweeps: usize,
        /// With rotations: the end of the first such step (s).
        first_s: Option<f64>,
        /// With rotations: the blocks whose velocity changed most in such a step's last sweep,
        /// with how many steps each (the first few, most often first).
        blocks: Vec<(String, u64)>,
    },
    /// Newton's method on the whole wall (Moreau-Jean with rotations, `--contact-solver
    /// newton`) stopped at its iteration limit in some steps, which were given to Gauss-Seidel
    /// instead (where Gauss-Seidel does not settle them either, [`Warning::Unconverged`] counts
    /// them too).
    NewtonFellBack {
        /// Those steps.
        steps: u64,
        /// The end of the first of them (s).
        first_s: f64,
    },
    /// Newton's method on the whole wall did not converge in the blocks' velocities in some
    /// steps, which the same problem in the contacts' impulses solved.
    NewtonInImpulses {
        /// Those steps.
        steps: u64,
        /// The end of the first of them (s).
        first_s: f64,
    },
    /// Newton's method on the whole wall converged neither in the blocks' velocities nor in
    /// the contacts' impulses in some steps, which an interior point in the velocities solved;
    /// it was then given some of the steps after them first.
    NewtonByInteriorPoint {
        /// Those steps.
        steps: u64,
        /// The end of the first of them (s).
        first_s: f64,
        /// Steps after them that the interior point was given first, and solved.
        given_first: u64,
    },
}

impl Warning {
    /// Whether the exact model stopped following the wall here (the run ends, or a hand-off
    /// goes on from here).
    pub fn stops_exact_model(&self) -> bool {
        matches!(
            self,
            Warning::HeldJointGives { .. } | Warning::Flight { .. } | Warning::BlocksMeet { .. }
        )
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::CouldRock {
                name,
                peak_accel_m_s2,
                limit_m_s2,
                friction,
                ratio,
                ..
            } => {
                let order = if friction > ratio {
                    format!("its friction {friction} exceeds b/h = {ratio:.3}, so it would rock before sliding (Shenton 1996)")
                } else {
                    format!("with friction {friction} <= b/h = {ratio:.3} it slides first, but may slide and rock (Shenton 1996)")
                };
                write!(
                    f,
                    "{name}: peak absolute acceleration {peak_accel_m_s2:.3} m/s2 reaches g b/h = {limit_m_s2:.3} m/s2 (Housner): as a free block it could rock; {order}. The sliding-only answer is not reliable for it."
                )
            }
            Warning::MoreCouldRock { more } => write!(f, "... and {more} more blocks could rock"),
            Warning::OverlapLost {
                upper,
                lower,
                at_rest_m,
                least_m,
                slip_m,
            } => write!(
                f,
                "{upper} on {lower}: at u_{upper} - u_{lower} = {slip_m:.4} m their overlap was \
                 {least_m:.4} m, {:.0} % less than its {at_rest_m:.4} m at rest{}; the sliding \
                 model (and the uplift check) keeps the loads and friction capacities of the \
                 overlaps at rest (eq. 3: small displacements), so its answer is approximate \
                 once a joint has slid that far",
                100.0 * (at_rest_m - least_m) / at_rest_m,
                if *least_m == 0.0 {
                    format!(", and {upper} no longer rested on {lower}")
                } else {
                    String::new()
                }
            ),
            Warning::Lifts { time_s, turning } => write!(
                f,
                "at t = {time_s} s no contact forces keep every block seated ({}): from there \
                 the sliding answer leaves out rocking that the motion causes (run the wall \
                 with --model slide-rock --method moreau --dt S to follow it)",
                turning.join(", ")
            ),
            Warning::Flight { body, time_s } => write!(
                f,
                "{body} leaves the ground on both corners at t = {time_s} s (free flight): the \
                 model stops there, and the run with it (run the wall with --after-stop moreau \
                 --dt S to go on from there by time stepping every block)"
            ),
            Warning::BlocksMeet {
                first,
                second,
                why,
                time_s,
            } => write!(
                f,
                "{first} meets {second} at t = {time_s} s, and {why}: the exact model follows \
                 blocks of different columns while they stand apart, and through the impact \
                 where a corner of one strikes a face of the other, each block fixed or moved by \
                 a column that holds no joint, and while such a column rests against or slides \
                 along a fixed block or two such columns turn together, their pivots stuck, \
                 slipping or off the ground; it stops at any other meeting, and the run with it \
                 (run the wall with --after-stop moreau --dt S to go on from there by time \
                 stepping every block)"
            ),
            Warning::HeldJointGives {
                body,
                joint,
                how,
                time_s,
            } => write!(
                f,
                "at t = {time_s} s the joint {joint} {how} under {body}'s motion: the exact \
                 model follows {body} only while its joints hold as the model has them (a \
                 column's held joints, a trilith's mechanism), so it stops there, and the run \
                 with it (run the wall with --after-stop moreau --dt S to go on from there by \
                 time stepping every block, or with --model slide-rock --method moreau --dt S to \
                 time step it whole)"
            ),
            Warning::LevelSkipped { level_m, why } => {
                write!(f, "level {level_m} m not checked across the plane: {why}")
            }
            Warning::IndeterminateSupport {
                blocks,
                count,
                elastic,
            } => write!(
                f,
                "{}{} {} on two or more blocks: for rigid blocks the split of the load among \
                 the supports is statically indeterminate, and {} (not the tributary one of \
                 eq. 3) sets the friction capacities below; where those joints differ in \
                 friction the answer depends on {} (docs/rocking-walls.md)",
                blocks.join(", "),
                if *count > blocks.len() {
                    format!(" and {} more", count - blocks.len())
                } else {
                    String::new()
                },
                if *count == 1 { "rests" } else { "rest" },
                if *elastic {
                    "the split of contact springs of one stiffness per metre of joint"
                } else {
                    "the solver's split"
                },
                if *elastic {
                    "that rule"
                } else {
                    "the step and the solver"
                }
            ),
            Warning::Unconverged {
                steps,
                sweeps,
                first_s,
                blocks,
            } => {
                write!(
                    f,
                    "Gauss-Seidel did not converge within {sweeps} sweeps in {steps} steps"
                )?;
                if let Some(t) = first_s {
                    write!(f, " (the first ending at {} s", to_the_nanosecond(*t))?;
                    if !blocks.is_empty() {
                        let most: Vec<String> = blocks
                            .iter()
                            .enumerate()
                            .map(|(k, (name, n))| {
                                let unit = if k == 0 { " steps" } else { "" };
                                format!("{name} in {n}{unit}")
                            })
                            .collect();
                        write!(
                            f,
                            "; changing fastest at the last sweep: {}",
                            most.join(", ")
                        )?;
                    }
                    write!(f, ")")?;
                }
                Ok(())
            }
            Warning::NewtonFellBack { steps, first_s } => write!(
                f,
                "Newton's method did not converge within its iterations in {steps} steps (the \
                 first ending at {} s); they were given to Gauss-Seidel instead (a warning \
                 on Gauss-Seidel counts those it did not settle either)",
                to_the_nanosecond(*first_s)
            ),
            Warning::NewtonInImpulses { steps, first_s } => write!(
                f,
                "Newton's method did not converge in the blocks' velocities in {steps} steps (the \
                 first ending at {} s); the same problem in the contacts' impulses solved them \
                 (docs/rocking-walls.md)",
                to_the_nanosecond(*first_s)
            ),
            Warning::NewtonByInteriorPoint {
                steps,
                first_s,
                given_first,
            } => {
                write!(
                    f,
                    "Newton's method converged neither in the blocks' velocities nor in the \
                     contacts' impulses in {steps} steps (the first ending at {} s); an \
                     interior point in the velocities solved them",
                    to_the_nanosecond(*first_s)
                )?;
                if *given_first > 0 {
                    write!(
                        f,
                        ", and {given_first} steps after them that it was given first"
                    )?;
                }
                write!(f, " (docs/rocking-walls.md)")
            }
        }
    }
}

/// A step's end k dt, rounded to the nanosecond for reading: 0.564, not 0.5640000000000001.
fn to_the_nanosecond(t_s: f64) -> f64 {
    (t_s * 1e9).round() / 1e9
}

impl Serialize for Warning {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_str(self)
    }
}

/// Time histories sampled at output times and at every event.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct History {
    /// Times (s).
    pub time_s: Vec<f64>,
    /// u per row, per block (m).
    pub displacement_m: Vec<Vec<f64>>,
    /// v per row, per block (m/s).
    pub velocity_m_s: Vec<Vec<f64>>,
    /// theta per row, per block (rad); empty when the model does not rotate blocks.
    pub rotation_rad: Vec<Vec<f64>>,
    /// theta' per row, per block (rad/s); empty likewise.
    pub angular_velocity_rad_s: Vec<Vec<f64>>,
    /// w per row, per block: the vertical displacement of the middle of its base (m), which
    /// rotations bring (a block rocking on a corner lifts it, a lintel on turning columns rises
    /// and falls with them); empty likewise.
    pub lift_m: Vec<Vec<f64>>,
}

/// Where a run keeps its history.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum HistoryTo {
    /// No history.
    #[default]
    Nowhere,
    /// In the response ([`Response::history`]).
    Memory,
    /// Written to this CSV file as the run goes ([`Response::history_file`]).
    File(std::path::PathBuf),
}

/// Where a run keeps its event log.
#[derive(Debug, Clone, PartialEq, Default)]
pub enum EventsTo {
    /// No event log.
    #[default]
    Nowhere,
    /// In the response ([`Response::events`]).
    Memory,
    /// In the response, and written to this JSON-lines file as the run goes, under its partial
    /// name until the run ends, which takes it away (the caller writes the final file from
    /// the response, in time order): a run that fails or is killed keeps the events it met.
    File(std::path::PathBuf),
}

/// A history written to a file as the run went.
#[derive(Debug, Clone, PartialEq)]
pub struct HistoryFile {
    /// The file.
    pub path: std::path::PathBuf,
    /// Rows written.
    pub rows: u64,
    /// Why the file could not be written whole (the run itself went on): what kind of
    /// failure, and the system's words.
    pub failed: Option<(std::io::ErrorKind, String)>,
}

/// Everything a run returns.
#[derive(Debug, Clone, PartialEq)]
pub struct Response {
    /// The summary.
    pub summary: Summary,
    /// The history, when asked for in memory.
    pub history: Option<History>,
    /// The history, when asked for in a file.
    pub history_file: Option<HistoryFile>,
    /// Logged events.
    pub events: Vec<EventRecord>,
    /// Logged mode decisions (event-driven, when asked for; otherwise empty).
    pub decisions: Vec<DecisionRecord>,
    /// Final displacement of each block (m), fallen ones at their last position.
    pub final_displacement_m: Vec<f64>,
}

/// One JSON object per line (the records hold only numbers, strings and flags, so each
/// serialises).
fn jsonl<T: Serialize>(records: &[T]) -> String {
    let mut s = String::new();
    for r in records {
        s.push_str(&serde_json::to_string(r).expect("record serialises"));
        s.push('\n');
    }
    s
}

impl Response {
    /// `summary.json` text.
    pub fn summary_json(&self) -> String {
        serde_json::to_string_pretty(&self.summary).expect("summary serialises") + "\n"
    }

    /// `events.jsonl` text: one JSON object per line.
    pub fn events_jsonl(&self) -> String {
        jsonl(&self.events)
    }

    /// `decisions.jsonl` text: one JSON object per mode decision.
    pub fn decisions_jsonl(&self) -> String {
        jsonl(&self.decisions)
    }

    /// `history.csv` text, or `None` without a history kept in memory.
    pub fn history_csv(&self) -> Option<String> {
        let h = self.history.as_ref()?;
        let names: Vec<&str> = self
            .summary
            .blocks
            .iter()
            .map(|b| b.name.as_str())
            .collect();
        let rotating = !h.rotation_rad.is_empty();
        let mut s = history_file::header(&names, rotating);
        let none: &[f64] = &[];
        for (k, &t) in h.time_s.iter().enumerate() {
            let (theta, omega, w) = if rotating {
                (
                    &h.rotation_rad[k][..],
                    &h.angular_velocity_rad_s[k][..],
                    &h.lift_m[k][..],
                )
            } else {
                (none, none, none)
            };
            history_file::push_row(
                &mut s,
                t,
                [&h.displacement_m[k], &h.velocity_m_s[k], theta, omega, w],
            );
        }
        Some(s)
    }
}
