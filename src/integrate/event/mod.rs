//! The exact event-driven integrator (design note `event-driven.md`).
//!
//! No time step: between events every cluster (blocks that move as one body) follows its mode
//! in closed form (`cluster`); events are roots of closed-form functions, located to round-off
//! (`roots`); at each event the new mode is decided exactly by a pure solver on a value type
//! (`solver::Problem`) and impacts are resolved exactly (`impact::resolve`). Work per event
//! touches only the clusters whose mode changed and their neighbours; a stuck cluster costs one
//! threshold check per segment of the ground motion.
//!
//! Two words are kept apart: the **solver** (`solver/`) decides accelerations and stick
//! intervals of a `Problem` and knows nothing of the engine; **regrouping** (`regroup/`) is
//! the engine's glue around it: it gathers the blocks an event concerns, builds their
//! `Problem`, calls the solver and installs the clusters it returns. A joint's state is a
//! `slip::Slip` (stuck, slipping forward or back), and the one place where a slip becomes a
//! friction sign is `Slip::on_upper`.
//!
//! | event (`queue::Ev`) | found by | handled by (`Engine::handle`) | decided by |
//! |---|---|---|---|
//! | start (t = 0) | `Engine::run` | `Engine::regroup` (regroup/mod.rs) | `Problem::stick_sides` / `Problem::solve` |
//! | stick limit: a_g leaves a stuck cluster's interval (`Threshold`) | `Engine::schedule_segment` (schedule.rs) | `Engine::regroup` | `Engine::solve_component` (regroup/solving.rs) -> `Engine::stuck_pieces` (stuck.rs) or `Engine::decide_general` -> `Problem::solve` (solver/solve.rs) |
//! | a sliding cluster stops (`Stop`) | `Engine::schedule` (schedule.rs) | `Engine::regroup`, velocities set to 0 | as above |
//! | two sliding clusters meet (`Meet`) | `Engine::schedule` | `Engine::regroup`, common velocity | as above |
//! | faces close (`GroundBound`/`PairBound`, `Constraint::Gap`) | `Engine::schedule` | `Engine::faces_meet` (collisions.rs): a touch, or `impact` -> `impact::resolve`, `zeno_accumulation` | then `Engine::regroup` |
//! | a support's span runs out (`Constraint::Collapse`) | `Engine::schedule` | `Engine::constraint_reached`, `Engine::stands`, `Engine::collapse` (collapse.rs) | `Engine::remove_fallen` (regroup/fallen.rs) then `Engine::regroup` |
//! | a split: a sliding cluster whose friction changed | step 8 of `Engine::regroup` | `Engine::regroup` | as above |
//! | end of a ground-motion segment | `Queue::pop_until` finds nothing before it | `Engine::enter_segment` | nothing, unless a_g jumps past a limit |
//!
//! Clusters are named by `ClusterId` (`cluster.rs`, with `Clusters`, the table they live in,
//! and `ClusterId::NONE` for a fixed or fallen block's), beside the topology's `BlockId`,
//! `HorizontalId` and `VerticalId`; blocks, horizontal and vertical joints are plain indices
//! inside the engine, where every table is indexed by them.
//!
//! Stuck clusters get their stick intervals in `stuck.rs` (`Engine::set_thresholds`, from
//! `Problem::stick_sides_*` in solver/stick.rs); `accounting.rs` keeps the energies, extremes
//! and history between events; `queue.rs` orders the events and drops stale ones; `memo.rs`
//! remembers decisions and intervals met before (`Caches`); `progress.rs` stops a run whose
//! state at one instant keeps coming back (with `cycle.rs`, which impact chains use too).

mod accounting;
mod cluster;
mod collapse;
mod collisions;
mod cycle;
mod flow;
mod impact;
mod memo;
mod progress;
mod queue;
mod regroup;
mod roots;
mod schedule;
mod slip;
mod solver;
mod stuck;
mod uplift;
use uplift::Next;

use crate::error::SimulationError;
use crate::exact::Q;
use crate::integrate::{AfterCollapse, Integrator, Progress, Scenario};
use crate::motion::{Motion, Segment};
use crate::response::{DecisionCause as Cause, Recorder, Response};
use crate::topology::{Base, Topology};
use crate::wall::Wall;
use cluster::{ClusterId, Clusters, Mode};
use memo::Memo;
use queue::{Ev, Queue};
use roots::Counter;
use slip::Slip;
use std::collections::VecDeque;
use std::rc::Rc;

/// Settings of the event-driven integrator. None is a tolerance: the first two are backstops
/// that stop a run which neither repeats a state nor ends (a run whose state repeats is
/// stopped by the check for that, `cycle.rs`), with an error that says where; the others
/// change the work, never the answer.
#[derive(Debug, Clone, PartialEq)]
pub struct Params {
    /// Events allowed at one instant; `None`: 10,000 plus 100 per block and joint of the wall.
    pub max_events_per_instant: Option<usize>,
    /// Pairwise collisions allowed in one impact chain; `None`: 100,000 plus the square of the
    /// chain's blocks (n equal blocks with e = 1 may need n (n - 1) / 2).
    pub max_collisions_per_chain: Option<usize>,
    /// A stuck group of at least this many blocks that a decision leaves, forms or turns a
    /// joint of keeps the limits its change cannot have narrowed, as bounds, and works them out
    /// only when a_g reaches them (`usize::MAX`: always at once). Below it, working a limit out
    /// costs less than the event a bound may add.
    pub kept_limits_from: usize,
    /// A decision at the ground over a stuck group of at least this many blocks and a few
    /// blocks beside it decides those few with the group held at a_g, and the group from its
    /// stick interval, where that shows the answer (`usize::MAX`: never). Below it, the
    /// decision over the whole piece costs no more.
    pub beside_stuck_from: usize,
    /// Watch the run for the first instant at which no contact forces keep every block seated
    /// (`uplift.rs`, summary.json's `uplift_check`): adds to the answer, changes none of it.
    /// Walls of up to `limit::EXACT_BLOCKS` moving blocks.
    pub watch_uplift: bool,
}

impl Default for Params {
    fn default() -> Params {
        Params {
            max_events_per_instant: None,
            max_collisions_per_chain: None,
            kept_limits_from: KEPT_LIMITS_FROM,
            beside_stuck_from: BESIDE_STUCK_FROM,
            watch_uplift: false,
        }
    }
}

/// The default of [`Params::kept_limits_from`].
const KEPT_LIMITS_FROM: usize = 256;

/// The default of [`Params::beside_stuck_from`].
const BESIDE_STUCK_FROM: usize = 256;

/// The property tests' configuration: many cases (each is cheap), and no regression file, which
/// would sit at the top level.
#[cfg(test)]
pub(crate) fn many_cheap_cases() -> proptest::test_runner::Config {
    proptest::test_runner::Config {
        cases: 3000,
        failure_persistence: None,
        ..Default::default()
    }
}

/// The exact event-driven integrator.
#[derive(Debug, Clone, Default)]
pub struct EventDriven {
    /// Safeguards.
    pub params: Params,
}

impl Integrator for EventDriven {
    fn method(&self) -> &'static str {
        "event"
    }

    fn run(&self, scenario: &Scenario) -> Result<Response, SimulationError> {
        let mut engine = Engine::new(scenario, &self.params, None)?;
        engine.run_loop()?;
        Ok(engine.finish())
    }
}

/// How a run watched for its first uplift ended.
pub(crate) enum Ended {
    /// Every block stayed seated (or the run stopped first): the sliding answer is the answer.
    Seated(Box<Response>),
    /// Some block must start to turn: the state at that instant, for a model with rotations.
    Lifted(Box<HandOff>),
}

/// The state where one model hands the run to the other, with what was recorded up to then:
/// the sliding run's at an uplift, the stepping's where it set the wall down (every block
/// seated, unturned), or the exact rocking model's where it stopped (blocks turned).
pub(crate) struct HandOff {
    /// The instant (s).
    pub t_s: f64,
    /// Every block's horizontal displacement (m) and velocity (m/s) relative to the ground: its
    /// centroid's (for a seated block, any of its points').
    pub u_m: Vec<f64>,
    pub v_m_s: Vec<f64>,
    /// Every block's rise and rotation with their rates, where some are turned (empty: every
    /// block seated and unturned).
    pub turned: Vec<Turned>,
    /// Blocks fallen before it (`--after-collapse continue`).
    pub fallen: Vec<bool>,
    /// Kinetic and potential energy at the instant (J), for the balance of what follows.
    pub mechanical_j: f64,
    /// Extremes, history rows (with rotations at zero), events and energy terms so far.
    pub rec: Recorder,
    /// The first history row still to write (its time: this times the output interval).
    pub next_output: u64,
}

/// A block's centroid above where it rests (m) and its rotation (counter-clockwise, rad), with
/// their rates (m/s, rad/s).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Turned {
    pub rise_m: f64,
    pub phi_rad: f64,
    pub rise_m_s: f64,
    pub omega_rad_s: f64,
}

impl EventDriven {
    /// Runs the exact sliding model, watched for its first uplift, and stops there with the
    /// state of that instant (the whole run where every block stays seated): the first part
    /// of a run that a model with rotations takes over.
    pub(crate) fn run_to_uplift(&self, scenario: &Scenario) -> Result<Ended, SimulationError> {
        self.watched(scenario, None)
    }

    /// Goes on from the state a model with rotations handed back at `from.t_s`, every block
    /// seated (unturned, touching faces closed), as [`EventDriven::run_to_uplift`] runs from
    /// rest: to the end, or to the next uplift.
    pub(crate) fn resume(
        &self,
        scenario: &Scenario,
        from: HandOff,
    ) -> Result<Ended, SimulationError> {
        self.watched(scenario, Some(from))
    }

    fn watched(
        &self,
        scenario: &Scenario,
        from: Option<HandOff>,
    ) -> Result<Ended, SimulationError> {
        let params = Params {
            watch_uplift: true,
            ..self.params.clone()
        };
        let mut engine = match from {
            None => {
                let mut engine = Engine::new(scenario, &params, None)?;
                engine.rec.rows_with_rotations();
                engine
            }
            Some(h) => {
                let mut engine = Engine::new(scenario, &params, Some(h.rec))?;
                engine.start_from(h.t_s, h.u_m, &h.v_m_s, h.fallen, h.next_output)?;
                engine
            }
        };
        if let Some(w) = &mut engine.uplift {
            w.hand_off = true;
        }
        Ok(if engine.run_loop()? {
            Ended::Lifted(Box::new(engine.hand_off()))
        } else {
            Ended::Seated(Box::new(engine.finish()))
        })
    }
}

/// Positions and velocities carry round-off of a few ulps of the largest magnitudes that enter
/// them (block coordinates, ground displacement, block displacement). Quantities within this many
/// ulps of zero are zero: a gap that closes to within it is touching, an approach speed within it
/// is a touch, not an impact.
const ROUNDOFF_ULPS: f64 = 1024.0;

/// What a run is given and never changes: the wall, its graph, the motion and the settings,
/// and the numbers of blocks and joints read off them once, exact and as floats.
struct Given<'a> {
    wall: &'a Wall,
    topo: &'a Topology,
    motion: &'a Motion,
    after_collapse: AfterCollapse,
    params: &'a Params,
    t_end: f64,
    output_dt: Option<f64>,
    progress: Option<Progress>,
    /// Blocks.
    n: usize,
    /// Per block: mass (kg), as a float and exact.
    mass: Vec<f64>,
    mass_q: Vec<Q>,
    /// Per horizontal joint: friction capacity mu N (N), as a float and exact.
    cap: Vec<f64>,
    cap_q: Vec<Q>,
    /// Per block: fixed (an abutment).
    fixed: Vec<bool>,
    /// Per block: left edge, right edge and centroid at rest (m).
    xl: Vec<f64>,
    xr: Vec<f64>,
    xc: Vec<f64>,
    /// Per vertical joint: the gap at rest (m).
    gap0: Vec<f64>,
    restitution: Q,
    /// Scales of lengths (m) and velocities (m/s) that round-off is measured against.
    len_scale: f64,
    vel_scale: f64,
}

/// What the engine remembers to avoid working something out twice; dropping any of it changes
/// the work, never the answer.
struct Caches {
    /// Stick intervals already worked out, by problem, with the blocks that leave at each limit.
    stick_memo: Memo<solver::Problem, solver::Stick>,
    /// Sets of blocks (global indices, sorted) that broke away at recent stick limits, newest
    /// first: hints for the next stick intervals.
    breaking: VecDeque<Vec<usize>>,
    /// Decisions already worked out, by problem, and under it by ground acceleration (a
    /// problem meets few: it is looked up without building a key).
    free_memo: Memo<solver::Problem, Decisions>,
}

/// A problem's decisions at the ground accelerations it was met at, shared with the decisions
/// that look them up.
type Decisions = Vec<(solver::Lex, Rc<[solver::Group]>)>;

/// Working memory kept from one event to the next, empty between uses.
#[derive(Default)]
struct Scratch {
    /// Of the mode decisions.
    decisions: regroup::Buffers,
    /// Of what they install.
    after: regroup::After,
    /// Of the scheduling: pairs of sliding clusters.
    pairs: Vec<(ClusterId, ClusterId)>,
    /// Of an event's decision: the blocks it starts from and their set velocities (m/s).
    seeds: (Vec<usize>, Vec<(usize, f64)>),
}

/// The event-driven engine of one run: what it was given, the state of the wall (clusters,
/// joints, time, the segment of the ground motion), the event queue, the caches and the
/// scratch space, and the recorder of results.
pub(crate) struct Engine<'a> {
    given: Given<'a>,
    /// Per block: fallen.
    fallen: Vec<bool>,
    t: f64,
    seg: Segment,
    /// Per block: its cluster (`ClusterId::NONE`: fixed or fallen).
    of: Vec<ClusterId>,
    /// Clusters (slots of emptied ones are reused, listed in `free`).
    clusters: Clusters,
    free: Vec<ClusterId>,
    /// Per block: its displacement when its cluster formed (m).
    u_ref: Vec<f64>,
    /// Per horizontal joint: its joint stuck or slipping, and which way.
    slip: Vec<Slip>,
    /// Per vertical joint: the faces touch.
    touching: Vec<bool>,
    /// Per horizontal joint: relative displacement when friction work was last accounted.
    d_last: Vec<f64>,
    /// Per horizontal joint: when friction work was last accounted (s).
    t_fric: Vec<f64>,
    /// Cluster versions: a changed cluster gets a new one, and its queued events go stale.
    version: u64,
    /// History rows written so far at output times.
    output_k: u64,
    /// The instant the progress guard watches (`progress.rs`).
    instant: progress::Instant,
    stopped: bool,
    queue: Queue,
    caches: Caches,
    scratch: Scratch,
    count: Counter,
    rec: Recorder,
    /// The uplift watch, when asked for.
    uplift: Option<uplift::Watch>,
    /// The velocities (m/s) the first decision starts from: none from rest.
    start_vel: Vec<(usize, f64)>,
    /// The run goes on from a model with rotations (`EventDriven::resume`).
    resumed: bool,
}

impl<'a> Engine<'a> {
    /// The engine at rest at t = 0, recording into `rec` where given (a run that goes on from
    /// another model's), into a new recorder otherwise.
    fn new(
        sc: &Scenario<'a>,
        params: &'a Params,
        rec: Option<Recorder>,
    ) -> Result<Engine<'a>, SimulationError> {
        let (wall, topo) = (sc.wall, sc.topology);
        let n = wall.blocks.len();
        let t_end = sc.settings.duration_s;
        sc.settings.validate(n)?;
        let mass_q: Vec<Q> = topo.blocks.iter().map(|b| b.mass_kg.clone()).collect();
        let cap_q: Vec<Q> = topo
            .horizontal
            .iter()
            .map(|s| s.capacity_n.clone())
            .collect();
        let f = |v: &[Q]| v.iter().map(Q::to_f64).collect::<Vec<f64>>();
        // Over the whole motion, so a run's round-off scales, and with them its answer up to any
        // instant, do not depend on how long it is asked to run.
        let (v_max, d_max) = motion_bounds(sc.motion, t_end.max(sc.motion.duration_s()));
        let extent: f64 = wall
            .blocks
            .iter()
            .map(|b| b.right().to_f64().abs().max(b.top().to_f64()))
            .fold(1.0, f64::max);
        let seg = sc.motion.segment_at(0.0);
        let rec = match rec {
            Some(rec) => rec,
            None => {
                let mut rec = Recorder::new(
                    wall,
                    topo,
                    sc.settings.history_to(),
                    sc.settings.events_to(),
                );
                if sc.settings.log_decisions {
                    rec.log_decisions(sc.settings.decisions_file.as_deref());
                }
                rec
            }
        };
        let movable = wall.blocks.iter().filter(|b| !b.fixed).count();
        let too_large = crate::limit::too_large_for_exact(crate::limit::seated::WHAT, movable);
        if let Some(why) = too_large.filter(|_| params.watch_uplift) {
            return Err(SimulationError::NotApplicable(format!(
                "{why}: leave --check-uplift (and --after-uplift) out"
            )));
        }
        let uplift = params.watch_uplift.then(uplift::Watch::default);
        Ok(Engine {
            given: Given {
                wall,
                topo,
                motion: sc.motion,
                after_collapse: sc.settings.after_collapse,
                params,
                t_end,
                output_dt: sc.settings.output_dt_s,
                progress: sc.settings.progress.clone(),
                n,
                mass: f(&mass_q),
                mass_q,
                cap: f(&cap_q),
                cap_q,
                fixed: wall.blocks.iter().map(|b| b.fixed).collect(),
                xl: wall.blocks.iter().map(|b| b.x.to_f64()).collect(),
                xr: wall.blocks.iter().map(|b| b.right().to_f64()).collect(),
                xc: wall
                    .blocks
                    .iter()
                    .map(|b| b.centroid_x().to_f64())
                    .collect(),
                gap0: topo.vertical.iter().map(|j| j.gap_m.to_f64()).collect(),
                restitution: wall.restitution.clone(),
                len_scale: extent + d_max,
                vel_scale: v_max + 1e-3,
            },
            fallen: vec![false; n],
            t: 0.0,
            seg,
            of: vec![ClusterId::NONE; n],
            clusters: Clusters::default(),
            free: Vec::new(),
            u_ref: vec![0.0; n],
            slip: vec![Slip::Stuck; topo.horizontal.len()],
            touching: topo.vertical.iter().map(|j| j.gap_m.is_zero()).collect(),
            d_last: vec![0.0; topo.horizontal.len()],
            t_fric: vec![0.0; topo.horizontal.len()],
            version: 0,
            output_k: 0,
            instant: progress::Instant::start(),
            stopped: false,
            queue: Queue::default(),
            caches: Caches {
                stick_memo: Memo::new(),
                breaking: VecDeque::new(),
                free_memo: Memo::new(),
            },
            scratch: Scratch::default(),
            count: Counter::default(),
            rec,
            uplift,
            start_vel: Vec::new(),
            resumed: false,
        })
    }

    /// Starts at `t` from the state a model with rotations handed back: blocks displaced by
    /// `u` (m), seated, moving at `v` (m/s), faces touching where their gaps are closed to
    /// round-off; friction's work counted from here. Faces that overlap beyond round-off are
    /// refused as the bug of whatever handed the state over: the engine would find them
    /// closing at every event of its first instant and stop there for lack of progress.
    fn start_from(
        &mut self,
        t: f64,
        u: Vec<f64>,
        v: &[f64],
        fallen: Vec<bool>,
        next_output: u64,
    ) -> Result<(), SimulationError> {
        self.t = t;
        self.seg = self.given.motion.segment_at(t);
        self.u_ref = u;
        self.fallen = fallen;
        self.output_k = next_output;
        self.touching = (0..self.given.topo.vertical.len())
            .map(|j| self.is_touching(j))
            .collect();
        for j in 0..self.given.topo.vertical.len() {
            if self.live_vertical(j) && !self.touching[j] && self.gap(j) < 0.0 {
                let jt = &self.given.topo.vertical[j];
                let name = |b: usize| &self.given.wall.blocks[b].name;
                return Err(SimulationError::Bug(format!(
                    "the state handed to the exact sliding model at t = {t} s has {} and {} \
                     overlapping by {:e} m",
                    name(jt.left.0),
                    name(jt.right.0),
                    -self.gap(j)
                )));
            }
        }
        for s in 0..self.given.topo.horizontal.len() {
            self.d_last[s] = self.horizontal_d(s);
            self.t_fric[s] = t;
        }
        self.start_vel = (0..self.given.n)
            .filter(|&i| !self.given.fixed[i] && !self.fallen[i] && v[i] != 0.0)
            .map(|i| (i, v[i]))
            .collect();
        self.resumed = true;
        Ok(())
    }

    /// The first decision: every block standing is undecided against the ground (at rest,
    /// unless the run goes on from another model's state).
    fn start(&mut self) -> Result<(), SimulationError> {
        let seeds: Vec<usize> = (0..self.given.n)
            .filter(|&i| !self.given.fixed[i] && !self.fallen[i])
            .collect();
        let start_vel = std::mem::take(&mut self.start_vel);
        self.regroup(&seeds, &start_vel, None, Cause::Start)
    }

    /// Runs to the end, or to the first uplift where the watch is to hand off there (true,
    /// the engine advanced to that instant).
    fn run_loop(&mut self) -> Result<bool, SimulationError> {
        // The flow passes counted from here on are this run's (a failed run on this thread
        // may have left some).
        flow::take_pass_nodes();
        self.start()?;
        loop {
            let seg_end = self.seg.t1.min(self.given.t_end);
            match self.queue.pop_until(seg_end, &self.clusters) {
                Some(p) => {
                    if !self.watch_uplift(p.t)? {
                        break;
                    }
                    match self.at_hand_off() {
                        Next::Run => {}
                        Next::HandOff => return Ok(true),
                        Next::Stop => break,
                    }
                    if !self.output_until(p.t) {
                        break;
                    }
                    self.t = p.t;
                    self.rec.stats.events += 1;
                    self.progress_guard(&p)?;
                    self.handle(p.ev)?;
                    self.uplift_state_changed();
                    if self.stopped {
                        break;
                    }
                    if self.rec.stats.events.is_multiple_of(Progress::EVERY_EVENTS)
                        && !self.keep_going()
                    {
                        break;
                    }
                }
                None => {
                    if !self.watch_uplift(seg_end)? {
                        break;
                    }
                    match self.at_hand_off() {
                        Next::Run => {}
                        Next::HandOff => return Ok(true),
                        Next::Stop => break,
                    }
                    if !self.output_until(seg_end) {
                        break;
                    }
                    self.t = seg_end;
                    if !self.keep_going() || seg_end >= self.given.t_end {
                        break;
                    }
                    self.enter_segment(seg_end);
                }
            }
        }
        self.uplift_watch_ends();
        Ok(false)
    }

    /// Tells the caller how far the run is; false (and the run marked interrupted) when it is
    /// asked to stop.
    pub(super) fn keep_going(&mut self) -> bool {
        let Some(p) = &self.given.progress else {
            return true;
        };
        if p.at(self.t.min(self.given.t_end)) || self.t >= self.given.t_end {
            return true;
        }
        self.interrupt();
        false
    }

    /// Marks the run stopped at the time it reached: it ends there with what it has.
    pub(super) fn interrupt(&mut self) {
        self.rec.interrupted_at_s = Some(self.t);
    }

    fn s(&self) -> f64 {
        self.t - self.seg.t0
    }

    /// Displacement gained by cluster k since it formed (m), at the current time.
    fn cluster_disp(&self, k: ClusterId) -> f64 {
        self.clusters[k].slide().map_or(0.0, |sl| sl.disp(self.t))
    }

    /// Velocity of cluster k relative to the ground (m/s), at the current time.
    fn cluster_vel(&self, k: ClusterId) -> f64 {
        self.clusters[k].slide().map_or(0.0, |sl| sl.vel(self.t))
    }

    fn block_disp(&self, i: usize) -> f64 {
        match self.of[i] {
            ClusterId::NONE => self.u_ref[i],
            k => self.u_ref[i] + self.cluster_disp(k),
        }
    }

    fn block_vel(&self, i: usize) -> f64 {
        match self.of[i] {
            ClusterId::NONE => 0.0,
            k => self.cluster_vel(k),
        }
    }

    /// True for the ground side of a joint: the ground, an abutment, or a block stuck to the
    /// ground.
    fn grounded(&self, i: usize) -> bool {
        self.of[i] == ClusterId::NONE
            || matches!(self.clusters[self.of[i]].mode, Mode::Stuck { .. })
    }

    fn len_tol(&self, a: f64, b: f64) -> f64 {
        ROUNDOFF_ULPS * f64::EPSILON * (self.given.len_scale + a.abs() + b.abs())
    }

    fn vel_tol(&self, a: f64, b: f64) -> f64 {
        ROUNDOFF_ULPS * f64::EPSILON * (self.given.vel_scale + a.abs() + b.abs())
    }

    /// The lower block of a horizontal joint, if it is a block that can move.
    fn lower_block(&self, s: usize) -> Option<usize> {
        match self.given.topo.horizontal[s].lower {
            Base::Ground => None,
            Base::Block(b) => Some(b.0),
        }
    }

    /// A horizontal joint still in the model (neither end fell).
    fn live_horizontal(&self, s: usize) -> bool {
        let sup = &self.given.topo.horizontal[s];
        !self.fallen[sup.upper.0] && self.lower_block(s).is_none_or(|l| !self.fallen[l])
    }

    /// The blocks of cluster k that have a support or a face to the ground or to a block
    /// outside it ([`Cluster::boundary`](cluster::Cluster)): a large body's contacts with the
    /// rest of the wall, found from a fraction of its blocks.
    fn boundary(&self, k: ClusterId) -> &[usize] {
        self.clusters[k].boundary.get_or_init(|| {
            let outside = |o: usize| self.of[o] != k;
            self.clusters[k]
                .blocks
                .iter()
                .copied()
                .filter(|&i| {
                    let supports = self.given.topo.below[i]
                        .iter()
                        .chain(&self.given.topo.above[i]);
                    let across_horizontal = supports.map(|s| self.across_horizontal(s.0, i));
                    let faces = self.given.topo.sides[i]
                        .iter()
                        .map(|j| self.across_vertical(j.0, i));
                    across_horizontal
                        .chain(faces.map(Some))
                        .any(|o| o.is_none_or(outside))
                })
                .collect()
        })
    }

    /// The other ends of block `b`'s live supports (under and over it); `None` is the ground.
    fn live_neighbours(&self, b: usize) -> impl Iterator<Item = Option<usize>> + '_ {
        self.given.topo.below[b]
            .iter()
            .chain(&self.given.topo.above[b])
            .filter(|s| self.live_horizontal(s.0))
            .map(move |s| self.across_horizontal(s.0, b))
    }

    /// The block across horizontal joint s from block b; `None` is the ground.
    fn across_horizontal(&self, s: usize, b: usize) -> Option<usize> {
        let upper = self.given.topo.horizontal[s].upper.0;
        if upper == b {
            self.lower_block(s)
        } else {
            Some(upper)
        }
    }

    /// The block across vertical joint j from block b.
    fn across_vertical(&self, j: usize, b: usize) -> usize {
        let jt = &self.given.topo.vertical[j];
        if jt.left.0 == b {
            jt.right.0
        } else {
            jt.left.0
        }
    }

    fn live_vertical(&self, j: usize) -> bool {
        let jt = &self.given.topo.vertical[j];
        !self.fallen[jt.left.0] && !self.fallen[jt.right.0]
    }

    fn gap(&self, j: usize) -> f64 {
        let jt = &self.given.topo.vertical[j];
        self.given.gap0[j] + self.block_disp(jt.right.0) - self.block_disp(jt.left.0)
    }

    fn horizontal_d(&self, s: usize) -> f64 {
        let sup = &self.given.topo.horizontal[s];
        self.block_disp(sup.upper.0) - self.lower_block(s).map_or(0.0, |l| self.block_disp(l))
    }

    fn new_version(&mut self) -> u64 {
        self.version += 1;
        self.version
    }

    fn enter_segment(&mut self, t: f64) {
        if self.seg.has_vertical() {
            // Friction work with a varying capacity is integrated segment by segment.
            for s in 0..self.given.topo.horizontal.len() {
                self.account_horizontal(s);
            }
        }
        // A sliding cluster's closed form is rebased on the new segment: what it did on this
        // one is booked first. A stuck one moves with the ground, whatever the segment, and is
        // booked when it dissolves (a stuck wall costs nothing per block and segment).
        for k in self.clusters.ids() {
            if !self.clusters[k].blocks.is_empty() && self.clusters[k].slide().is_some() {
                self.account(k, t);
            }
        }
        self.seg = self.given.motion.segment_at(t);
        self.rec.stats.segments += 1;
        let seg = self.seg;
        for c in self.clusters.iter_mut() {
            if let Mode::Sliding(sl) = &mut c.mode {
                if !c.blocks.is_empty() {
                    sl.rebase(&seg);
                    c.roots = None;
                    c.ground_hits = None;
                }
            }
        }
        if self.given.motion.has_vertical() {
            // Relative motion of sliding clusters involves lambda(t): re-found per segment.
            let live: Vec<ClusterId> = self
                .clusters
                .ids()
                .filter(|&k| !self.clusters[k].blocks.is_empty())
                .collect();
            self.schedule(live);
        } else {
            for k in self.clusters.ids() {
                if !self.clusters[k].blocks.is_empty() {
                    self.schedule_segment(k);
                }
            }
        }
    }

    fn handle(&mut self, ev: Ev) -> Result<(), SimulationError> {
        match ev {
            Ev::Threshold { k, upper, .. } => {
                let side = usize::from(upper);
                let limit = |mode: &Mode| match mode {
                    Mode::Stuck { lo_q, hi_q, .. } => [lo_q, hi_q][side].clone(),
                    Mode::Sliding(_) => None,
                };
                let bound = limit(&self.clusters[k].mode);
                if matches!(&self.clusters[k].mode, Mode::Stuck { bound_only, .. } if bound_only[side])
                {
                    // a_g has reached a bound: the exact limit is at it or beyond. Beyond it,
                    // nothing happens (no history row either: the run is the same as if the
                    // limit had been worked out at once).
                    self.set_exact_thresholds(k);
                    if limit(&self.clusters[k].mode) != bound {
                        self.clusters[k].version = self.new_version();
                        self.schedule([k]);
                        return Ok(());
                    }
                }
                let limit = bound;
                // Snap a_g to the limit only when it is there. A stuck cluster whose neighbours
                // changed gets a new interval that a_g may already lie beyond; it is decided
                // with the a_g it has (snapping would keep it stuck and fire again, forever).
                let (ag, lambda) = (self.seg.accel(self.s()), self.seg.lambda_at(self.s()));
                let snap = limit.filter(|q| {
                    let at = q.to_f64() * lambda;
                    (ag - at).abs() <= ROUNDOFF_ULPS * f64::EPSILON * (ag.abs() + at.abs())
                });
                self.regroup_with(snap, Cause::StickLimit, |e, seeds, _| {
                    seeds.extend_from_slice(&e.clusters[k].blocks);
                })?;
            }
            Ev::Stop { k, .. } => self.regroup_with(None, Cause::Stop, |e, seeds, set_vel| {
                seeds.extend_from_slice(&e.clusters[k].blocks);
                set_vel.extend(seeds.iter().map(|&i| (i, 0.0)));
            })?,
            Ev::Meet { a, b, .. } => {
                let (ma, mb) = (self.clusters[a].mass, self.clusters[b].mass);
                let v = (ma * self.cluster_vel(a) + mb * self.cluster_vel(b)) / (ma + mb);
                self.regroup_with(None, Cause::Meet, |e, seeds, set_vel| {
                    seeds.extend(e.clusters[a].blocks.iter().chain(&e.clusters[b].blocks));
                    set_vel.extend(seeds.iter().map(|&i| (i, v)));
                })?;
            }
            Ev::GroundBound { k, c, .. } => self.constraint_reached(k, None, c)?,
            Ev::PairBound { a, b, c, .. } => self.constraint_reached(a, Some(b), c)?,
        }
        if self.rec.wants_history() {
            self.sample();
        }
        Ok(())
    }

    /// [`Engine::regroup`] of the seeds and set velocities that `fill` writes, in memory kept
    /// from one event to the next.
    fn regroup_with(
        &mut self,
        theta: Option<Q>,
        cause: Cause,
        fill: impl FnOnce(&Self, &mut Vec<usize>, &mut Vec<(usize, f64)>),
    ) -> Result<(), SimulationError> {
        let (mut seeds, mut set_vel) = std::mem::take(&mut self.scratch.seeds);
        fill(self, &mut seeds, &mut set_vel);
        let done = self.regroup(&seeds, &set_vel, theta, cause);
        seeds.clear();
        set_vel.clear();
        self.scratch.seeds = (seeds, set_vel);
        done
    }

    /// Every cluster's work, extremes and joints accounted up to now; the blocks'
    /// displacements and velocities and their kinetic energy.
    fn settle(&mut self) -> (Vec<f64>, Vec<f64>, f64) {
        let t = self.t;
        self.account_all(t);
        for k in self.clusters.ids() {
            self.record_extremes(k);
        }
        for s in 0..self.given.topo.horizontal.len() {
            self.account_horizontal(s);
        }
        let (u, v) = self.state_now();
        let kinetic = (0..self.given.n)
            .filter(|&i| !self.fallen[i])
            .map(|i| 0.5 * self.given.mass[i] * v[i] * v[i])
            .sum();
        // Added to: a run that went on from another model's state counted before.
        self.rec.stats.root_evaluations += self.count.0;
        self.rec.stats.flow_nodes += flow::take_pass_nodes();
        (u, v, kinetic)
    }

    /// The state at the first uplift, the engine advanced to it; how much overlap sliding took
    /// away up to then is noted (the check that found the uplift used the overlaps at rest).
    fn hand_off(mut self) -> HandOff {
        let (u, v, kinetic) = self.settle();
        crate::validity::note_overlap_loss(self.given.wall, self.given.topo, &mut self.rec);
        HandOff {
            t_s: self.t,
            u_m: u,
            v_m_s: v,
            turned: Vec::new(),
            fallen: self.fallen,
            mechanical_j: kinetic,
            rec: self.rec,
            next_output: self.output_k,
        }
    }

    fn finish(mut self) -> Response {
        self.t = self.t.min(self.given.t_end);
        let t = self.t;
        let (u, v, kinetic) = self.settle();
        self.rec.energy.kinetic_j = kinetic;
        // After the uplift check's, if it found one. Where it watched the run and found every
        // block seated throughout, it has answered for the wall what these bound for blocks
        // standing free, and they would only contradict it.
        // A run that went on from a model with rotations followed the rocking these warn of.
        let seated = (self.rec.uplift_check.as_ref()).is_some_and(|c| c.first_uplift.is_none());
        if !seated && !self.resumed {
            let could_rock = crate::validity::rocking_warnings(
                self.given.wall,
                self.given.topo,
                self.rec.peak_accel(),
            );
            self.rec.warnings.extend(could_rock);
        }
        crate::validity::note_overlap_loss(self.given.wall, self.given.topo, &mut self.rec);
        let motion = self.given.motion.describe();
        self.rec
            .finish("event", &self.given.wall.name, motion, t, &u, &v)
    }
}

/// Bounds on |V_g| and |D_g| over [0, t_end], for round-off scales.
fn motion_bounds(m: &Motion, t_end: f64) -> (f64, f64) {
    match m {
        Motion::Sine(s) => {
            let w = 2.0 * std::f64::consts::PI * s.frequency_hz;
            let a = s.amplitude_m_s2.abs();
            (2.0 * a / w, a / w * t_end + 2.0 * a / (w * w))
        }
        Motion::Pulse(p) => {
            let v = p.amplitude_m_s2.abs() * p.duration_s;
            (v, v * t_end.max(p.duration_s))
        }
        Motion::Record(_) => {
            let mut v: f64 = 0.0;
            let mut d: f64 = 0.0;
            let steps = 2000;
            for k in 0..=steps {
                let t = t_end * k as f64 / steps as f64;
                let (vt, dt) = m.velocity_displacement(t);
                v = v.max(vt.abs());
                d = d.max(dt.abs());
            }
            (2.0 * v, 2.0 * d + v * t_end / steps as f64)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::Settings;
    use crate::motion::Sine;
    use crate::wall::RunningBond;

    /// A running-bond wall at rest is one stuck cluster, which meets nothing but the ground
    /// under its bottom course: that course is its boundary. (Clusters that meet other
    /// clusters are covered by the runs whose event logs and energy balances the integration
    /// tests check: leaving out the supports above a block fails three of them.)
    #[test]
    fn a_cluster_meets_the_rest_of_the_wall_only_at_its_boundary() {
        let spec = RunningBond {
            courses: 4,
            blocks_per_course: 6,
            ..RunningBond::paper_wall(5)
        };
        let wall = Wall::from_description(&spec.description().unwrap()).unwrap();
        let topology = Topology::new(&wall).unwrap();
        let motion = Motion::sine(Sine {
            amplitude_m_s2: 1.0,
            frequency_hz: 1.0,
            phase_rad: 0.0,
            duration_s: 1.0,
        })
        .unwrap();
        let settings = Settings::summary_only(1.0);
        let params = Params::default();
        let scenario = Scenario {
            wall: &wall,
            topology: &topology,
            motion: &motion,
            settings: &settings,
        };
        let mut engine = Engine::new(&scenario, &params, None).unwrap();
        let all: Vec<usize> = (0..wall.blocks.len()).collect();
        engine.regroup(&all, &[], None, Cause::Start).unwrap();
        let k = engine.of[0];
        assert!(all.iter().all(|&i| engine.of[i] == k), "one cluster");
        let bottom: Vec<usize> = all
            .iter()
            .copied()
            .filter(|&i| wall.blocks[i].y.is_zero())
            .collect();
        assert!(bottom.len() >= 6 && bottom.len() < all.len());
        assert_eq!(engine.boundary(k), bottom.as_slice());
    }
}
