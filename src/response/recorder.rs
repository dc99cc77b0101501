//! The recorder integrators feed as they run: extremes, counts, energy terms, history rows and
//! the event log, turned into a [`Response`] when the run ends.

use super::partial::PartialFile;
use super::{
    BlockSummary, Collapse, DecisionRecord, Energy, EventKind, EventRecord, EventsTo, History,
    HistoryFile, HistoryTo, HorizontalJointSummary, ModelUsed, Response, Stats, Stream, Summary,
    UpliftCheck, Warning,
};
use crate::topology::{Base, BlockId, HorizontalId, JointRef, Topology, VerticalId};
use crate::wall::Wall;

/// Collects results as an integrator runs. Public for integrators outside the crate (the rapier
/// peer engine), hidden from the documentation: not part of the curated surface.
#[doc(hidden)]
pub struct Recorder {
    names: Vec<String>,
    horizontal: Vec<(usize, Option<usize>, String, String)>,
    /// The blocks left and right of each vertical joint.
    vertical: Vec<(usize, usize)>,
    max_u: Vec<f64>,
    max_v: Vec<f64>,
    /// Least and greatest u_upper - u_lower of each horizontal joint so far (m).
    relative_range: Vec<(f64, f64)>,
    max_a: Vec<f64>,
    max_theta: Vec<f64>,
    uplift: Vec<Option<f64>>,
    rocking_impacts: Vec<u64>,
    fell: Vec<bool>,
    history: Option<History>,
    /// The history going to a file instead, and the time of its last row.
    stream: Option<(Stream, f64)>,
    /// Logged events.
    pub events: Vec<EventRecord>,
    log_events: bool,
    /// The event log going to a file as well, as the run goes.
    event_file: Option<PartialFile>,
    /// Logged mode decisions, when the integrator keeps them.
    decisions: Option<Vec<DecisionRecord>>,
    /// The decision log going to a file as well, as the run goes.
    decision_file: Option<PartialFile>,
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
    /// The run was asked to stop and ended at this time (s).
    pub interrupted_at_s: Option<f64>,
    /// The exact model stopped following the wall and the run ended at this time (s).
    pub stopped_at_s: Option<f64>,
    /// The model that ran.
    pub model: ModelUsed,
    /// The uplift check, when asked for.
    pub uplift_check: Option<UpliftCheck>,
    /// The largest share of a joint's overlap lost to sliding, noted at a sliding run's end
    /// ([`crate::validity::note_overlap_loss`]).
    pub overlap_loss: Option<f64>,
    /// Rows without rotations are written with theta, omega and w at zero (these, one per
    /// block): a run that hands off to a model with rotations writes one history of one shape.
    rotating_rows: Option<Vec<f64>>,
}

/// A wall's horizontal joints as a recorder lists them: (upper block, lower block or `None`
/// for the ground, the upper block's name, its base's name), blocks by their place in the wall.
pub fn horizontal_joints(
    wall: &Wall,
    topo: &Topology,
) -> Vec<(usize, Option<usize>, String, String)> {
    topo.horizontal
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
        .collect()
}

/// Widens the range (least, greatest) to take in `x`.
fn widen((lo, hi): &mut (f64, f64), x: f64) {
    *lo = lo.min(x);
    *hi = hi.max(x);
}

impl Recorder {
    /// A recorder for this wall; `history` says where sampled rows go, `events` where the
    /// event log goes.
    pub fn new(wall: &Wall, topo: &Topology, history: HistoryTo, events: EventsTo) -> Recorder {
        let horizontal = horizontal_joints(wall, topo);
        let names = wall.blocks.iter().map(|b| b.name.clone()).collect();
        Recorder {
            vertical: topo
                .vertical
                .iter()
                .map(|j| (j.left.0, j.right.0))
                .collect(),
            ..Recorder::for_bodies(names, horizontal, history, events)
        }
    }

    /// A recorder for bodies named `names`, with horizontal joints (upper body, lower body or
    /// `None` for the ground, and their names) and no vertical joints.
    pub fn for_bodies(
        names: Vec<String>,
        horizontal: Vec<(usize, Option<usize>, String, String)>,
        history: HistoryTo,
        events: EventsTo,
    ) -> Recorder {
        let n = names.len();
        let stream = match &history {
            HistoryTo::File(path) => Some((Stream::new(path, &names), f64::NEG_INFINITY)),
            HistoryTo::Nowhere | HistoryTo::Memory => None,
        };
        Recorder {
            relative_range: vec![(0.0, 0.0); horizontal.len()],
            names,
            horizontal,
            vertical: Vec::new(),
            max_u: vec![0.0; n],
            max_v: vec![0.0; n],
            max_a: vec![0.0; n],
            max_theta: vec![0.0; n],
            uplift: vec![None; n],
            rocking_impacts: vec![0; n],
            fell: vec![false; n],
            history: (history == HistoryTo::Memory).then(History::default),
            stream,
            events: Vec::new(),
            log_events: events != EventsTo::Nowhere,
            event_file: match &events {
                EventsTo::File(path) => Some(PartialFile::new(path)),
                EventsTo::Nowhere | EventsTo::Memory => None,
            },
            decisions: None,
            decision_file: None,
            impacts: 0,
            touches: 0,
            zeno: 0,
            transitions: 0,
            collapse: None,
            energy: Energy::default(),
            stats: Stats::default(),
            warnings: Vec::new(),
            interrupted_at_s: None,
            stopped_at_s: None,
            model: ModelUsed::default(),
            uplift_check: None,
            overlap_loss: None,
            rotating_rows: None,
        }
    }

    /// From now on every history row carries rotations (zero where the integrator has none).
    pub(crate) fn rows_with_rotations(&mut self) {
        self.rotating_rows = Some(vec![0.0; self.names.len()]);
    }

    /// Time of the last history row, if rows are kept and there is one.
    pub fn last_row_time(&self) -> Option<f64> {
        match &self.stream {
            Some((_, t)) => t.is_finite().then_some(*t),
            None => self.history.as_ref()?.time_s.last().copied(),
        }
    }

    /// True when history rows are wanted.
    pub fn wants_history(&self) -> bool {
        self.history.is_some() || self.stream.is_some()
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
        let joints = self.horizontal.iter().zip(&mut self.relative_range);
        for ((upper, lower, _, _), range) in joints {
            widen(range, u[*upper] - lower.map_or(0.0, |l| u[l]));
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

    /// Notes that horizontal joint k reached u_upper - u_lower = `d` (m).
    pub fn horizontal_extreme(&mut self, k: usize, d: f64) {
        widen(&mut self.relative_range[k], d);
    }

    /// Least and greatest u_upper - u_lower of each horizontal joint so far (m).
    pub fn relative_ranges(&self) -> &[(f64, f64)] {
        &self.relative_range
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

    /// Logs an event of a rocking body made of `blocks` (the lowest first, whose joint it
    /// moves on): its angular velocity before and after, and the mode it goes on in. Where two
    /// blocks meet, part or move their contact (`BlocksMeet`, `BlocksImpact`, `Separation`,
    /// `Touch`), the joint is the vertical one between them, if they face each other across
    /// one, not a joint either moves on.
    pub fn rocking_event(
        &mut self,
        time_s: f64,
        kind: EventKind,
        blocks: &[usize],
        omega: Option<(f64, f64)>,
        mode: String,
    ) {
        if self.log_events {
            let joint = if matches!(
                kind,
                EventKind::BlocksMeet
                    | EventKind::BlocksImpact
                    | EventKind::Separation
                    | EventKind::Touch
            ) {
                self.vertical
                    .iter()
                    .position(|&(l, r)| {
                        (l, r) == (blocks[0], blocks[1]) || (r, l) == (blocks[0], blocks[1])
                    })
                    .map(|k| JointRef::Vertical(VerticalId(k)))
            } else {
                // The joint under the lowest block: one, as a rocking body's block rests on one.
                self.horizontal
                    .iter()
                    .position(|h| h.0 == blocks[0])
                    .map(|k| JointRef::Horizontal(HorizontalId(k)))
            };
            self.log(EventRecord {
                time_s,
                kind,
                blocks: blocks.iter().map(|&b| self.names[b].clone()).collect(),
                block_ids: blocks.iter().map(|&b| BlockId(b)).collect(),
                joint: joint.map(|j| self.label(j)),
                joint_id: joint,
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
    pub fn sample_rotating(&mut self, t: f64, [u, v, theta, omega, w]: [&[f64]; 5]) {
        if let Some((stream, last)) = &mut self.stream {
            stream.row(t, [u, v, theta, omega, w]);
            *last = t;
        }
        if let Some(h) = &mut self.history {
            h.time_s.push(t);
            h.displacement_m.push(u.to_vec());
            h.velocity_m_s.push(v.to_vec());
            h.rotation_rad.push(theta.to_vec());
            h.angular_velocity_rad_s.push(omega.to_vec());
            h.lift_m.push(w.to_vec());
        }
    }

    /// Marks a block as fallen.
    pub fn fell(&mut self, i: usize) {
        self.fell[i] = true;
    }

    /// Adds a history row.
    pub fn sample(&mut self, t: f64, u: &[f64], v: &[f64]) {
        if let Some(zero) = self.rotating_rows.take() {
            self.sample_rotating(t, [u, v, &zero, &zero, &zero]);
            self.rotating_rows = Some(zero);
            return;
        }
        if let Some((stream, last)) = &mut self.stream {
            stream.row(t, [u, v, &[], &[], &[]]);
            *last = t;
        }
        if let Some(h) = &mut self.history {
            h.time_s.push(t);
            h.displacement_m.push(u.to_vec());
            h.velocity_m_s.push(v.to_vec());
        }
    }

    /// Keeps the log of mode decisions from now on, and writes it to `file` as the run goes
    /// if one is given (under its partial name until the run ends).
    pub fn log_decisions(&mut self, file: Option<&std::path::Path>) {
        self.decisions = Some(Vec::new());
        self.decision_file = file.map(PartialFile::new);
    }

    /// Whether mode decisions are logged.
    pub fn logs_decisions(&self) -> bool {
        self.decisions.is_some()
    }

    /// Keeps a mode decision, and writes it to the decision file if there is one.
    pub fn decision(&mut self, record: DecisionRecord) {
        let Some(log) = &mut self.decisions else {
            return;
        };
        if let Some(file) = &mut self.decision_file {
            file.write(&(serde_json::to_string(&record).expect("record serialises") + "\n"));
        }
        log.push(record);
    }

    /// Keeps a logged event, and writes it to the event file if there is one.
    fn log(&mut self, event: EventRecord) {
        if let Some(file) = &mut self.event_file {
            file.write(&(serde_json::to_string(&event).expect("record serialises") + "\n"));
        }
        self.events.push(event);
    }

    /// Logs an event (when logging) — counting is the caller's business.
    pub fn event(
        &mut self,
        time_s: f64,
        kind: EventKind,
        blocks: &[usize],
        joint: Option<JointRef>,
        speed: Option<f64>,
    ) {
        if self.log_events {
            self.log(EventRecord {
                time_s,
                kind,
                blocks: blocks.iter().map(|&b| self.names[b].clone()).collect(),
                block_ids: blocks.iter().map(|&b| BlockId(b)).collect(),
                joint: joint.map(|j| self.label(j)),
                joint_id: joint,
                approach_speed_m_s: speed,
                before_m_s: None,
                after_m_s: None,
                angular_velocity_before_rad_s: None,
                angular_velocity_after_rad_s: None,
                mode: None,
            });
        }
    }

    /// Logs an impact at vertical joint j with the velocities of its left and right blocks
    /// before and after (m/s).
    pub fn impact(&mut self, time_s: f64, j: VerticalId, before: [f64; 2], after: [f64; 2]) {
        self.impacts += 1;
        if self.log_events {
            let (l, r) = self.vertical[j.0];
            let joint = JointRef::Vertical(j);
            self.log(EventRecord {
                time_s,
                kind: EventKind::Impact,
                blocks: vec![self.names[l].clone(), self.names[r].clone()],
                block_ids: vec![BlockId(l), BlockId(r)],
                joint: Some(self.label(joint)),
                joint_id: Some(joint),
                approach_speed_m_s: Some(before[0] - before[1]),
                before_m_s: Some(before),
                after_m_s: Some(after),
                angular_velocity_before_rad_s: None,
                angular_velocity_after_rad_s: None,
                mode: None,
            });
        }
    }

    /// A joint's name: `"upper/lower"` for a horizontal one, `"left|right"` for a vertical one.
    fn label(&self, joint: JointRef) -> String {
        match joint {
            JointRef::Horizontal(k) => {
                format!("{}/{}", self.horizontal[k.0].2, self.horizontal[k.0].3)
            }
            JointRef::Vertical(j) => {
                let (l, r) = self.vertical[j.0];
                format!("{}|{}", self.names[l], self.names[r])
            }
        }
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
        for file in [self.event_file.take(), self.decision_file.take()]
            .into_iter()
            .flatten()
        {
            file.discard();
        }
        let e = &mut self.energy;
        e.residual_j = e.initial_j + e.input_j
            - e.friction_j
            - e.impact_loss_j
            - e.kinetic_j
            - e.potential_j
            - e.fallen_j;
        let blocks = (0..u.len())
            .map(|i| BlockSummary {
                id: BlockId(i),
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
        let horizontal_joints = self
            .horizontal
            .iter()
            .enumerate()
            .map(|(k, (upper, lower, un, ln))| HorizontalJointSummary {
                joint: HorizontalId(k),
                upper: un.clone(),
                lower: ln.clone(),
                max_abs_relative_displacement_m: {
                    let (lo, hi) = self.relative_range[k];
                    lo.abs().max(hi.abs())
                },
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
                interrupted_at_s: self.interrupted_at_s,
                stopped_at_s: self.stopped_at_s,
                blocks,
                horizontal_joints,
                impacts: self.impacts,
                touches: self.touches,
                zeno_accumulations: self.zeno,
                stick_slip_transitions: self.transitions,
                collapse: self.collapse,
                energy: self.energy,
                stats: self.stats,
                max_overlap_loss: self.overlap_loss,
                warnings: self.warnings,
                worst: None,
                uplift_check: self.uplift_check,
            },
            history: self.history,
            history_file: self.stream.map(|(stream, _)| {
                let rows = stream.rows();
                match stream.finish() {
                    Ok(path) => HistoryFile {
                        path,
                        rows,
                        failed: None,
                    },
                    Err((path, e)) => HistoryFile {
                        path,
                        rows,
                        failed: Some((e.kind(), e.to_string())),
                    },
                }
            }),
            events: self.events,
            decisions: self.decisions.unwrap_or_default(),
            final_displacement_m: u.to_vec(),
        }
    }
}
