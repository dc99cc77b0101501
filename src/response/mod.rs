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
#[serde(rename_all = "lowercase")]
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
    /// Largest absolute acceleration (m/s2), for the rocking check.
    pub max_abs_accel_m_s2: f64,
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
    /// Work of the inertial forces -m a_g on the blocks.
    pub input_j: f64,
    /// Dissipated by friction.
    pub friction_j: f64,
    /// Lost in impacts.
    pub impact_loss_j: f64,
    /// Kinetic energy at the end.
    pub kinetic_j: f64,
    /// Kinetic energy carried away by blocks that fell.
    pub fallen_j: f64,
    /// input - friction - impact loss - kinetic - fallen: zero up to round-off for an exact
    /// integrator.
    pub residual_j: f64,
}

/// A collapse.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Collapse {
    /// When (s).
    pub time_s: f64,
    /// Which block fell first.
    pub block: String,
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
}

/// `summary.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Summary {
    /// Integrator.
    pub method: String,
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
    pub warnings: Vec<String>,
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
    pub warnings: Vec<String>,
}

impl Recorder {
    /// A recorder for this wall; `history` keeps sampled rows, `log_events` keeps the event log.
    pub fn new(wall: &Wall, topo: &Topology, history: bool, log_events: bool) -> Recorder {
        let n = wall.blocks.len();
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
        Recorder {
            names: wall.blocks.iter().map(|b| b.name.clone()).collect(),
            joints,
            max_u: vec![0.0; n],
            max_v: vec![0.0; n],
            max_d: vec![0.0; topo.supports.len()],
            max_a: vec![0.0; n],
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
        }
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
        wall: &Wall,
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
        e.residual_j = e.input_j - e.friction_j - e.impact_loss_j - e.kinetic_j - e.fallen_j;
        let blocks = (0..u.len())
            .map(|i| BlockSummary {
                name: self.names[i].clone(),
                max_abs_displacement_m: self.max_u[i],
                final_displacement_m: u[i],
                max_abs_velocity_m_s: self.max_v[i],
                max_abs_accel_m_s2: self.max_a[i],
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
                wall: wall.name.clone(),
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
        s.push('\n');
        for (k, t) in h.time_s.iter().enumerate() {
            let _ = write!(s, "{t}");
            for x in h.displacement_m[k].iter().chain(&h.velocity_m_s[k]) {
                let _ = write!(s, ",{x:e}");
            }
            s.push('\n');
        }
        Some(s)
    }
}
