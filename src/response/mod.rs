//! What a run produces, whatever the integrator: the summary (`summary.json`), the history of
//! displacements and velocities (`history.csv`), the event log (`events.jsonl`), and, from the
//! event-driven integrator when asked, the log of its mode decisions (`decisions.jsonl`).
//! Integrators feed a [`Recorder`]; nothing here knows how the numbers were computed.

pub mod saved;

use crate::topology::{Base, Topology};
use crate::wall::Wall;
use serde::Serialize;
use std::fmt::Write;

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
    /// Two touching faces move apart.
    Separation,
    /// A block falls.
    Collapse,
    /// A sequence of impacts with e < 1 accumulates; the faces stay in contact from here.
    Zeno,
    /// A seated block lifts off one corner and starts to rock.
    Uplift,
    /// A rocking block lands on its other corner.
    RockingImpact,
    /// The corner a block rocks on stops slipping.
    PivotStick,
    /// The corner a block rocks on starts to slip (slide-rock).
    PivotSlip,
    /// A rocking block comes to rest seated on both corners (its impacts accumulated).
    Rest,
    /// A block overturns: it passed the point of no return, or lies on its face.
    Overturning,
    /// A block leaves the ground on both corners (free flight): beyond the model, the run stops.
    Flight,
}

/// One logged event.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct EventRecord {
    /// Time (s).
    pub time_s: f64,
    /// What happened.
    pub kind: EventKind,
    /// Blocks involved.
    pub blocks: Vec<String>,
    /// The joint, `"upper/lower"` or `"left|right"`, when one is involved.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint: Option<String>,
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
pub struct JointSummary {
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
    /// Per block.
    pub blocks: Vec<BlockSummary>,
    /// Per horizontal joint.
    pub joints: Vec<JointSummary>,
    /// Impacts (positive approach speed).
    pub impacts: u64,
    /// Contacts made at zero approach speed.
    pub touches: u64,
    /// Infinite series of impacts (e < 1) summed in closed form; each counts once in `impacts`.
    pub zeno_accumulations: u64,
    /// Horizontal joints changing between sticking and slipping.
    pub stick_slip_transitions: u64,
    /// First collapse, if any.
    pub collapse: Option<Collapse>,
    /// Energy balance.
    pub energy: Energy,
    /// Work counters.
    pub stats: Stats,
    /// Warnings about the validity of the model for this run.
    pub warnings: Vec<Warning>,
    /// Across the wall's plane: the section nearest to overturning (absent when none lifted).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub worst: Option<Worst>,
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
    /// A rocking body left the ground on both corners: the run stopped there.
    Flight {
        /// The body.
        body: String,
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
    /// Gauss-Seidel stopped at its sweep limit in some steps (Moreau-Jean).
    Unconverged {
        /// Steps that ended unconverged.
        steps: u64,
        /// The sweep limit.
        sweeps: usize,
    },
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
            Warning::Flight { body, time_s } => write!(
                f,
                "{body} leaves the ground on both corners at t = {time_s} s (free flight): the \
                 model stops there, and the run with it"
            ),
            Warning::LevelSkipped { level_m, why } => {
                write!(f, "level {level_m} m not checked across the plane: {why}")
            }
            Warning::Unconverged { steps, sweeps } => write!(
                f,
                "Gauss-Seidel did not converge within {sweeps} sweeps in {steps} steps"
            ),
        }
    }
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
}

/// Everything a run returns.
#[derive(Debug, Clone, PartialEq)]
pub struct Response {
    /// The summary.
    pub summary: Summary,
    /// The history, when asked for.
    pub history: Option<History>,
    /// Logged events.
    pub events: Vec<EventRecord>,
    /// Logged mode decisions (event-driven, when asked for; otherwise empty).
    pub decisions: Vec<DecisionRecord>,
    /// Final displacement of each block (m), fallen ones at their last position.
    pub final_displacement_m: Vec<f64>,
}

/// Collects results as an integrator runs.
pub struct Recorder {
    names: Vec<String>,
    joints: Vec<(usize, Option<usize>, String, String)>,
    max_u: Vec<f64>,
    max_v: Vec<f64>,
    max_d: Vec<f64>,
    max_a: Vec<f64>,
    max_theta: Vec<f64>,
    uplift: Vec<Option<f64>>,
    rocking_impacts: Vec<u64>,
    fell: Vec<bool>,
    history: Option<History>,
    /// Logged events.
    pub events: Vec<EventRecord>,
    log_events: bool,
    /// Logged mode decisions, when the integrator keeps them.
    pub decisions: Option<Vec<DecisionRecord>>,
    /// Impacts counted.
    pub impacts: u64,
    /// Touches counted.
    pub touches: u64,
    /// Zeno accumulations (infinite impact series summed in closed form).
    pub zeno: u64,
    /// Stick-slip transitions counted.
    pub transitions: u64,
    /// First collapse.
    pub collapse: Option<Collapse>,
    /// Energy terms accumulated by the integrator.
    pub energy: Energy,
    /// Work counters.
    pub stats: Stats,
    /// Model-validity warnings.
    pub warnings: Vec<Warning>,
    /// The model that ran.
    pub model: ModelUsed,
}

impl Recorder {
    /// A recorder for this wall; `history` keeps sampled rows, `log_events` keeps the event log.
    pub fn new(wall: &Wall, topo: &Topology, history: bool, log_events: bool) -> Recorder {
        let joints = topo
            .supports
            .iter()
            .map(|s| {
                let lower = match s.lower {
                    Base::Ground => None,
                    Base::Block(b) => Some(b.0),
                };
                (
                    s.upper.0,
                    lower,
                    wall.blocks[s.upper.0].name.clone(),
                    topo.base_name(wall, s.lower).to_string(),
                )
            })
            .collect();
        let names = wall.blocks.iter().map(|b| b.name.clone()).collect();
        Recorder::for_bodies(names, joints, history, log_events)
    }

    /// A recorder for bodies named `names`, with horizontal joints (upper body, lower body or
    /// `None` for the ground, and their names).
    pub fn for_bodies(
        names: Vec<String>,
        joints: Vec<(usize, Option<usize>, String, String)>,
        history: bool,
        log_events: bool,
    ) -> Recorder {
        let n = names.len();
        Recorder {
            max_d: vec![0.0; joints.len()],
            names,
            joints,
            max_u: vec![0.0; n],
            max_v: vec![0.0; n],
            max_a: vec![0.0; n],
            max_theta: vec![0.0; n],
            uplift: vec![None; n],
            rocking_impacts: vec![0; n],
            fell: vec![false; n],
            history: history.then(History::default),
            events: Vec::new(),
            log_events,
            decisions: None,
            impacts: 0,
            touches: 0,
            zeno: 0,
            transitions: 0,
            collapse: None,
            energy: Energy::default(),
            stats: Stats::default(),
            warnings: Vec::new(),
            model: ModelUsed::default(),
        }
    }

    /// Time of the last history row, if rows are kept and there is one.
    pub fn last_row_time(&self) -> Option<f64> {
        self.history.as_ref()?.time_s.last().copied()
    }

    /// True when history rows are wanted.
    pub fn wants_history(&self) -> bool {
        self.history.is_some()
    }

    /// Block names.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Notes that block i reached |u| = `u_abs` and |v| = `v_abs`.
    pub fn block_extremes(&mut self, i: usize, u_abs: f64, v_abs: f64) {
        self.max_u[i] = self.max_u[i].max(u_abs);
        self.max_v[i] = self.max_v[i].max(v_abs);
    }

    /// Notes the relative displacement of every joint from block displacements u.
    pub fn joint_extremes(&mut self, u: &[f64]) {
        for (k, (upper, lower, _, _)) in self.joints.iter().enumerate() {
            let d = u[*upper] - lower.map_or(0.0, |l| u[l]);
            self.max_d[k] = self.max_d[k].max(d.abs());
        }
    }

    /// Notes that block i reached an absolute acceleration of magnitude `a_abs` (m/s2).
    pub fn block_accel(&mut self, i: usize, a_abs: f64) {
        self.max_a[i] = self.max_a[i].max(a_abs);
    }

    /// Peak absolute acceleration of each block so far (m/s2).
    pub fn peak_accel(&self) -> &[f64] {
        &self.max_a
    }

    /// Notes that support k reached |u_upper - u_lower| = `d_abs`.
    pub fn joint_extreme(&mut self, k: usize, d_abs: f64) {
        self.max_d[k] = self.max_d[k].max(d_abs);
    }

    /// Notes that block i reached |theta| = `theta_abs` (rad).
    pub fn rotation_extreme(&mut self, i: usize, theta_abs: f64) {
        self.max_theta[i] = self.max_theta[i].max(theta_abs);
    }

    /// Notes that block i lifted at `time_s` (the first time counts).
    pub fn uplift(&mut self, i: usize, time_s: f64) {
        self.uplift[i].get_or_insert(time_s);
    }

    /// Counts a landing of rocking block i.
    pub fn rocking_impact(&mut self, i: usize) {
        self.rocking_impacts[i] += 1;
    }

    /// Logs an event of rocking block i: its angular velocity before and after, and the mode
    /// it goes on in.
    pub fn rocking_event(
        &mut self,
        time_s: f64,
        kind: EventKind,
        i: usize,
        omega: Option<(f64, f64)>,
        mode: String,
    ) {
        if self.log_events {
            self.events.push(EventRecord {
                time_s,
                kind,
                blocks: vec![self.names[i].clone()],
                joint: Some(format!("{}/ground", self.names[i])),
                approach_speed_m_s: None,
                before_m_s: None,
                after_m_s: None,
                angular_velocity_before_rad_s: omega.map(|w| w.0),
                angular_velocity_after_rad_s: omega.map(|w| w.1),
                mode: Some(mode),
            });
        }
    }

    /// Adds a history row with rotations.
    pub fn sample_rotating(&mut self, t: f64, u: &[f64], v: &[f64], theta: &[f64], omega: &[f64]) {
        if let Some(h) = &mut self.history {
            h.time_s.push(t);
            h.displacement_m.push(u.to_vec());
            h.velocity_m_s.push(v.to_vec());
            h.rotation_rad.push(theta.to_vec());
            h.angular_velocity_rad_s.push(omega.to_vec());
        }
    }

    /// Marks a block as fallen.
    pub fn fell(&mut self, i: usize) {
        self.fell[i] = true;
    }

    /// Adds a history row.
    pub fn sample(&mut self, t: f64, u: &[f64], v: &[f64]) {
        if let Some(h) = &mut self.history {
            h.time_s.push(t);
            h.displacement_m.push(u.to_vec());
            h.velocity_m_s.push(v.to_vec());
        }
    }

    /// Logs an event (when logging) — counting is the caller's business.
    pub fn event(
        &mut self,
        time_s: f64,
        kind: EventKind,
        blocks: &[usize],
        joint: Option<String>,
        speed: Option<f64>,
    ) {
        if self.log_events {
            self.events.push(EventRecord {
                time_s,
                kind,
                blocks: blocks.iter().map(|&b| self.names[b].clone()).collect(),
                joint,
                approach_speed_m_s: speed,
                before_m_s: None,
                after_m_s: None,
                angular_velocity_before_rad_s: None,
                angular_velocity_after_rad_s: None,
                mode: None,
            });
        }
    }

    /// Logs an impact between blocks l and r with their velocities before and after (m/s).
    pub fn impact(
        &mut self,
        time_s: f64,
        l: usize,
        r: usize,
        joint: String,
        before: [f64; 2],
        after: [f64; 2],
    ) {
        self.impacts += 1;
        if self.log_events {
            self.events.push(EventRecord {
                time_s,
                kind: EventKind::Impact,
                blocks: vec![self.names[l].clone(), self.names[r].clone()],
                joint: Some(joint),
                approach_speed_m_s: Some(before[0] - before[1]),
                before_m_s: Some(before),
                after_m_s: Some(after),
                angular_velocity_before_rad_s: None,
                angular_velocity_after_rad_s: None,
                mode: None,
            });
        }
    }

    /// Logs support k starting to stick or to slip, when logging (only then is its name built).
    pub fn support_event(&mut self, time_s: f64, kind: EventKind, k: usize, blocks: &[usize]) {
        if self.log_events {
            let joint = self.joint_name(k);
            self.event(time_s, kind, blocks, Some(joint), None);
        }
    }

    /// The name of joint k as `"upper/lower"`.
    fn joint_name(&self, k: usize) -> String {
        format!("{}/{}", self.joints[k].2, self.joints[k].3)
    }

    /// Finishes the run: final state u, v (m, m/s) at time `t_end`.
    pub fn finish(
        mut self,
        method: &str,
        wall: &str,
        motion: String,
        t_end: f64,
        u: &[f64],
        v: &[f64],
    ) -> Response {
        self.joint_extremes(u);
        for (i, (&ui, &vi)) in u.iter().zip(v).enumerate() {
            self.block_extremes(i, ui.abs(), vi.abs());
        }
        self.events.sort_by(|a, b| a.time_s.total_cmp(&b.time_s));
        let e = &mut self.energy;
        e.residual_j = e.initial_j + e.input_j
            - e.friction_j
            - e.impact_loss_j
            - e.kinetic_j
            - e.potential_j
            - e.fallen_j;
        let blocks = (0..u.len())
            .map(|i| BlockSummary {
                name: self.names[i].clone(),
                max_abs_displacement_m: self.max_u[i],
                final_displacement_m: u[i],
                max_abs_velocity_m_s: self.max_v[i],
                max_abs_accel_m_s2: self.max_a[i],
                max_abs_rotation_rad: self.max_theta[i],
                uplift_time_s: self.uplift[i],
                rocking_impacts: self.rocking_impacts[i],
                fell: self.fell[i],
            })
            .collect();
        let joints = self
            .joints
            .iter()
            .enumerate()
            .map(|(k, (upper, lower, un, ln))| JointSummary {
                upper: un.clone(),
                lower: ln.clone(),
                max_abs_relative_displacement_m: self.max_d[k],
                final_relative_displacement_m: u[*upper] - lower.map_or(0.0, |l| u[l]),
            })
            .collect();
        Response {
            summary: Summary {
                method: method.to_string(),
                model: self.model,
                wall: wall.to_string(),
                motion,
                motion_processing: Vec::new(),
                duration_s: t_end,
                blocks,
                joints,
                impacts: self.impacts,
                touches: self.touches,
                zeno_accumulations: self.zeno,
                stick_slip_transitions: self.transitions,
                collapse: self.collapse,
                energy: self.energy,
                stats: self.stats,
                warnings: self.warnings,
                worst: None,
            },
            history: self.history,
            events: self.events,
            decisions: self.decisions.unwrap_or_default(),
            final_displacement_m: u.to_vec(),
        }
    }
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

    /// `history.csv` text, or `None` without a history.
    pub fn history_csv(&self) -> Option<String> {
        let h = self.history.as_ref()?;
        let names: Vec<&str> = self
            .summary
            .blocks
            .iter()
            .map(|b| b.name.as_str())
            .collect();
        let mut s = String::from("time_s");
        for n in &names {
            let _ = write!(s, ",u_{n}_m");
        }
        for n in &names {
            let _ = write!(s, ",v_{n}_m_s");
        }
        let rotating = !h.rotation_rad.is_empty();
        if rotating {
            for n in &names {
                let _ = write!(s, ",theta_{n}_rad");
            }
            for n in &names {
                let _ = write!(s, ",omega_{n}_rad_s");
            }
        }
        s.push('\n');
        let none: &[f64] = &[];
        for (k, t) in h.time_s.iter().enumerate() {
            let _ = write!(s, "{t}");
            let (theta, omega) = if rotating {
                (&h.rotation_rad[k][..], &h.angular_velocity_rad_s[k][..])
            } else {
                (none, none)
            };
            for x in h.displacement_m[k]
                .iter()
                .chain(&h.velocity_m_s[k])
                .chain(theta)
                .chain(omega)
            {
                let _ = write!(s, ",{x:e}");
            }
            s.push('\n');
        }
        Some(s)
    }
}
