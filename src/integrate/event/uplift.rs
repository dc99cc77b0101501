//! Watching a sliding run for its first uplift (`Params::watch_uplift`): between two events the
//! wall's state is fixed, and whether it keeps every block seated is an interval of a_g
//! (`limit::seated`), remembered by state. Where the state holds every block seated at its stick
//! limits the interval reaches past them and is not worked out; otherwise each stretch the run
//! advances by is compared with it, and the crossing located as a stuck cluster's stick limit is
//! (`schedule_segment`). The watch reads the engine and changes nothing in it: a run
//! watched gives the same answer as one not watched, with the check added.

use super::cluster::{ClusterId, Mode};
use super::roots::Counter;
use super::schedule::limit_passed;
use super::{Engine, EventDriven, Params};
use crate::error::SimulationError;
use crate::exact::Q;
use crate::integrate::Progress;
use crate::integrate::Scenario;
use crate::limit::seated::{self, Interval, Moving, Side, State};
use crate::limit::{Moves, Uniqueness};
use crate::response::{EventKind, EventsTo, HistoryTo, Recorder, Uplift, UpliftCheck, Warning};
use std::collections::HashMap;
use std::rc::Rc;

/// What the watch keeps.
#[derive(Default)]
pub(super) struct Watch {
    /// What is known of the states met.
    memo: HashMap<State, Known>,
    /// What decides the state since the last event; `None` once an event may have changed it.
    current: Option<Current>,
    /// The first uplift was found (the sliding answer leaves rocking out from there on).
    done: bool,
    /// The run stops at the first uplift for a model with rotations to go on from there
    /// (`EventDriven::run_to_uplift`), instead of sliding on with a warning.
    pub(super) hand_off: bool,
    /// When the first uplift was found, until the run has handed off there.
    due: Option<f64>,
    /// Function evaluations of its crossings, kept out of the run's own count.
    count: Counter,
}

/// What decides a state for the watch: its interval, where some end of it comes before the
/// stuck clusters' stick limits or the state keeps no block seated, and which ends (towards -x,
/// towards +x) do.
type Current = (Option<Rc<Interval>>, [bool; 2]);

/// What the watch knows of a state's interval of seated ground accelerations.
#[derive(Default)]
struct Known {
    /// The interval, once worked out.
    interval: Option<Rc<Interval>>,
    /// Per side (towards -x, towards +x), the furthest ground acceleration that way at which
    /// the state was found to keep every block seated: the interval reaches at least that far.
    seated_to: [Option<Q>; 2],
}

/// What the watch sees over a stretch of the run.
enum Look {
    /// Every block stays seated.
    Clear,
    /// The first uplift, at this time, so.
    Lifts(f64, Cause),
    /// The run was asked to stop while the programs ran.
    Stopped,
}

/// How the first uplift comes.
enum Cause {
    /// The state keeps no block seated whatever the ground does; the mechanism is the
    /// program's certificate of that.
    Always(Vec<Moves>),
    /// a_g passes this end of the state's interval (towards +x where the sign is +1).
    Passes(i128, Side),
}

impl Cause {
    fn mechanism(&self) -> &[Moves] {
        match self {
            Cause::Always(mechanism) | Cause::Passes(_, Side { mechanism, .. }) => mechanism,
        }
    }
}

/// What the run does after the watch has looked at a stretch.
pub(super) enum Next {
    /// Goes on.
    Run,
    /// Stops at the first uplift, advanced to it, for a model with rotations.
    HandOff,
    /// Stops: asked to, while writing the history up to the uplift.
    Stop,
}

/// How a block moves with others: touching faces of blocks that move together can push.
#[derive(PartialEq)]
enum Together {
    Ground,
    Cluster(ClusterId),
}

impl EventDriven {
    /// Whether the exact sliding model, set going at `t_s` from blocks seated at `u_m` (m)
    /// moving at `v_m_s` (m/s), the `fallen` ones gone, lets some block turn by `t_s +
    /// horizon_s`: a resumed run, watched as [`EventDriven::resume`] watches it, run that far
    /// with nothing recorded and no progress shown (events at its first instant, a touch or a
    /// stop, can change the state whose interval decides). A model with rotations asks before
    /// it hands a wall back seated: where the answer is yes, the wall would be handed straight
    /// back to it.
    pub(crate) fn lifts_within(
        &self,
        sc: &Scenario,
        (t_s, u_m, v_m_s, fallen): (f64, &[f64], &[f64], &[bool]),
        horizon_s: f64,
    ) -> Result<bool, SimulationError> {
        let params = Params {
            watch_uplift: true,
            ..self.params.clone()
        };
        let rec = Recorder::new(sc.wall, sc.topology, HistoryTo::Nowhere, EventsTo::Nowhere);
        let mut engine = Engine::new(sc, &params, Some(rec))?;
        engine.given.progress = None;
        engine.given.t_end = engine.given.t_end.min(t_s + horizon_s);
        engine.start_from(t_s, u_m.to_vec(), v_m_s, fallen.to_vec(), 0)?;
        if let Some(w) = &mut engine.uplift {
            w.hand_off = true;
        }
        engine.run_loop()
    }
}

impl Engine<'_> {
    /// The watch must work the state out again: an event may have changed it.
    pub(super) fn uplift_state_changed(&mut self) {
        if let Some(w) = &mut self.uplift {
            w.current = None;
        }
    }

    /// The run is about to advance from `self.t` to `t_next` in its state: records the first
    /// instant in between at which no contact forces keep every block seated, if there is one.
    /// False (and the run marked interrupted at `self.t`) where the run was asked to stop
    /// while the check's programs ran.
    pub(super) fn watch_uplift(&mut self, t_next: f64) -> Result<bool, SimulationError> {
        let Some(mut w) = self.uplift.take() else {
            return Ok(true);
        };
        let look = if w.done || t_next <= self.t {
            Look::Clear
        } else {
            self.first_uplift(&mut w, t_next)?
        };
        let mut go_on = true;
        match look {
            Look::Clear => {}
            Look::Lifts(t, cause) => {
                self.record_uplift(t, &cause, !w.hand_off)?;
                w.done = true;
                w.due = w.hand_off.then_some(t);
            }
            Look::Stopped => {
                self.interrupt();
                go_on = false;
            }
        }
        self.uplift = Some(w);
        Ok(go_on)
    }

    /// Where the watch has found the first uplift and is to hand off there: advances the run to
    /// that instant (its history rows up to it, and one at it).
    pub(super) fn at_hand_off(&mut self) -> Next {
        let Some(t) = self.uplift.as_mut().and_then(|w| w.due.take()) else {
            return Next::Run;
        };
        if !self.output_until(t) {
            return Next::Stop;
        }
        self.t = t;
        if self.rec.last_row_time() != Some(t) {
            self.sample();
        }
        Next::HandOff
    }

    /// Records the first uplift, at `t`, as `cause` has it; with `warn`, warns that the sliding
    /// answer leaves out the rocking from there; without, the run hands over there, and every
    /// uplift it hands over at is logged with the blocks that turn.
    fn record_uplift(&mut self, t: f64, cause: &Cause, warn: bool) -> Result<(), SimulationError> {
        // The blocks that turn; the others of the mechanism move with them.
        let turning = cause.mechanism().iter().filter(|m| m.omega_rad_s != 0.0);
        if !warn {
            let blocks: Vec<usize> = turning
                .clone()
                .filter_map(|m| self.given.wall.block_index(&m.block))
                .collect();
            self.rec.event(t, EventKind::Uplift, &blocks, None, None);
        }
        if self.resumed {
            // Not the first: the check keeps the first.
            return Ok(());
        }
        let g = &self.given;
        let stop = || (g.progress.as_ref()).is_some_and(Progress::stop_requested);
        let programs = seated::Programs::new(g.wall, g.topo, &self.seated_state())?;
        let (mechanism_uniqueness, turning_in_every_mechanism) = match cause {
            // Its certificates are another question than a side's multipliers: which is the
            // only one is left open, which blocks turn in all of them is not.
            Cause::Always(_) => (
                Uniqueness::Undecided,
                programs.turning_whatever_the_ground(&stop)?,
            ),
            // Stopped while deciding: the uplift stands, the rest not decided.
            Cause::Passes(s, side) => match programs.decide(side, *s, &stop)? {
                Some(d) => (d.uniqueness, d.turning_in_every_mechanism),
                None => (Uniqueness::Undecided, None),
            },
        };
        let names: Vec<String> = turning.map(|m| format!("{} {}", m.block, m.how)).collect();
        self.rec.uplift_check = Some(UpliftCheck {
            checked_until_s: t,
            first_uplift: Some(Uplift {
                time_s: t,
                ground_accel_m_s2: self.seg.accel(t - self.seg.t0),
                turning: names.clone(),
                mechanism_uniqueness,
                turning_in_every_mechanism,
            }),
        });
        if warn {
            self.rec.warnings.push(Warning::Lifts {
                time_s: t,
                turning: names,
            });
        }
        Ok(())
    }

    /// The run's end: a watch that found no uplift says how far it looked.
    pub(super) fn uplift_watch_ends(&mut self) {
        if self.uplift.as_ref().is_some_and(|w| !w.done) && !self.resumed {
            self.rec.uplift_check = Some(UpliftCheck {
                checked_until_s: self.t,
                first_uplift: None,
            });
        }
    }

    fn first_uplift(&self, w: &mut Watch, t_next: f64) -> Result<Look, SimulationError> {
        if w.current.is_none() {
            // The stick limits change only at events, so this holds until the next one.
            let Some(current) = self.decide_state(&mut w.memo)? else {
                return Ok(Look::Stopped);
            };
            w.current = Some(current);
        }
        let Some((Some(interval), watched)) = &w.current else {
            return Ok(Look::Clear);
        };
        let (interval, watched) = (interval.clone(), *watched);
        let (lo, hi) = match &*interval {
            Interval::Empty { mechanism } => {
                return Ok(Look::Lifts(self.t, Cause::Always(mechanism.clone())))
            }
            Interval::Between { lo, hi } => (lo, hi),
        };
        let mut first: Option<(f64, Cause)> = None;
        for (side, s, watch) in [(hi, 1, watched[1]), (lo, -1, watched[0])] {
            let Some(side) = side.as_ref().filter(|_| watch) else {
                continue;
            };
            // a_g / lambda passes the side: as a stuck cluster's limit is found.
            let limit = side.accel.to_f64();
            let hit = limit_passed(&self.seg, limit, s as f64, (self.t, t_next), &mut w.count);
            if let Some(t) = hit {
                if first.as_ref().is_none_or(|(f, _)| t < *f) {
                    first = Some((t, Cause::Passes(s, side.clone())));
                }
            }
        }
        Ok(first.map_or(Look::Clear, |(t, cause)| Look::Lifts(t, cause)))
    }

    /// Which ends of the current state's seated interval the watch follows (see
    /// [`Watch::current`]), and the interval where it needs it; `None` where the run was asked
    /// to stop while the programs ran.
    ///
    /// A seated end matters only where it comes strictly before every stuck cluster's stick
    /// limit that way; where it does not, the sliding model's own event (a slip) ends the state
    /// first, or at the same instant, and the state has no uplift of its own. So where the
    /// state keeps every block seated at the nearest stick limit, that side needs nothing more
    /// (the interval is convex: it reaches the limit); only a side without a stick limit, or
    /// one whose limit the state is not shown to hold seated, takes the interval solved to its
    /// ends, so every answer is the interval's. A limit kept as a bound is at or inside the
    /// exact one: a seated side inside the bound is inside the limit; one at or past it is met
    /// again after the bound's event works the limit out.
    fn decide_state(
        &self,
        memo: &mut HashMap<State, Known>,
    ) -> Result<Option<Current>, SimulationError> {
        let stop = || (self.given.progress.as_ref()).is_some_and(Progress::stop_requested);
        let g = &self.given;
        let state = self.seated_state();
        let limits = self.stick_limits();
        let mut known = memo.remove(&state).unwrap_or_default();
        let interval = match &known.interval {
            Some(interval) => Some(interval.clone()),
            None => {
                let programs = seated::Programs::new(g.wall, g.topo, &state)?;
                let mut settled = [false; 2];
                for (k, limit) in limits.iter().enumerate() {
                    let Some(limit) = limit else { break };
                    let reaches = |a: &Q| if k == 1 { a >= limit } else { a <= limit };
                    if !known.seated_to[k].as_ref().is_some_and(reaches) {
                        if !programs.seated_at(limit, &stop) {
                            break;
                        }
                        known.seated_to[k] = Some(limit.clone());
                    }
                    settled[k] = true;
                }
                if settled == [true; 2] {
                    None
                } else {
                    let interval = programs.interval(&stop).map(Rc::new);
                    known.interval.clone_from(&interval);
                    if interval.is_none() {
                        memo.insert(state, known);
                        return Ok(None);
                    }
                    interval
                }
            }
        };
        memo.insert(state, known);
        let Some(interval) = interval else {
            return Ok(Some((None, [false; 2])));
        };
        let before = |accel: &Q, k: usize| match &limits[k] {
            None => true,
            Some(limit) if k == 1 => accel < limit,
            Some(limit) => accel > limit,
        };
        let watched = match &*interval {
            Interval::Empty { .. } => [false; 2],
            Interval::Between { lo, hi } => [(lo, 0), (hi, 1)]
                .map(|(side, k)| side.as_ref().is_some_and(|d| before(&d.accel, k))),
        };
        Ok(Some((Some(interval), watched)))
    }

    /// The nearest stuck cluster's stick limit each way (towards -x, towards +x): the state
    /// ends where a_g (a_g / lambda) reaches either. `None` where no stuck cluster has one.
    fn stick_limits(&self) -> [Option<Q>; 2] {
        let mut limits: [Option<Q>; 2] = [None, None];
        for k in self.clusters.ids() {
            if self.clusters[k].blocks.is_empty() {
                continue;
            }
            if let Mode::Stuck { lo_q, hi_q, .. } = &self.clusters[k].mode {
                if let Some(lo) = lo_q {
                    if limits[0].as_ref().is_none_or(|l| lo > l) {
                        limits[0] = Some(lo.clone());
                    }
                }
                if let Some(hi) = hi_q {
                    if limits[1].as_ref().is_none_or(|l| hi < l) {
                        limits[1] = Some(hi.clone());
                    }
                }
            }
        }
        limits
    }

    /// The state of the wall as the sliding model has it now.
    fn seated_state(&self) -> State {
        let g = &self.given;
        let together = |i: usize| -> Option<Together> {
            if g.fixed[i] {
                return Some(Together::Ground);
            }
            if self.fallen[i] {
                return None;
            }
            match self.clusters[self.of[i]].mode {
                Mode::Stuck { .. } => Some(Together::Ground),
                Mode::Sliding(_) => Some(Together::Cluster(self.of[i])),
            }
        };
        let moving = (0..g.n)
            .map(|i| {
                if g.fixed[i] || self.fallen[i] {
                    return None;
                }
                Some(match &self.clusters[self.of[i]].mode {
                    Mode::Stuck { .. } => Moving::Ground,
                    Mode::Sliding(sl) => Moving::At(sl.c_q.clone()),
                })
            })
            .collect();
        State {
            moving,
            slip: self.slip.iter().map(|s| s.sign()).collect(),
            pushes: g
                .topo
                .vertical
                .iter()
                .zip(&self.touching)
                .map(|(v, &touching)| {
                    touching && {
                        let (l, r) = (together(v.left.0), together(v.right.0));
                        l.is_some() && l == r
                    }
                })
                .collect(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::Settings;
    use crate::motion::{Motion, Sine};
    use crate::topology::Topology;
    use crate::wall::Wall;

    /// A slab 0.3 m wide and 1.2 m tall (friction 0.6, so it lifts before it slides) under a
    /// sine of 0.3 g: it turns once a_g passes g/4, at t* = asin(5/6) / (2 pi) s. A check set
    /// going at rest from 0.15 s sees the uplift within a horizon that reaches t* and not within
    /// one that stops short of it, by a nanosecond either way; one set going past t* sees it at
    /// once.
    #[test]
    fn the_check_before_a_set_down_finds_the_uplift_where_the_watch_would() {
        let wall = Wall::from_ron_str(
            "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
              rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\")])])",
        )
        .unwrap();
        let topology = Topology::new(&wall).unwrap();
        let g = wall.g_m_s2.to_f64();
        let motion = Motion::sine(Sine {
            amplitude_m_s2: 0.3 * g,
            frequency_hz: 1.0,
            phase_rad: 0.0,
            duration_s: 1.0,
        })
        .unwrap();
        let settings = Settings::summary_only(1.0);
        let sc = Scenario {
            wall: &wall,
            topology: &topology,
            motion: &motion,
            settings: &settings,
        };
        let t_star = (5.0_f64 / 6.0).asin() / std::f64::consts::TAU;
        let lifts = |t: f64, horizon: f64| {
            EventDriven::default()
                .lifts_within(&sc, (t, &[0.0], &[0.0], &[false]), horizon)
                .unwrap()
        };
        assert!(!lifts(0.1, 0.01));
        assert!(!lifts(0.15, t_star - 0.15 - 1e-9));
        assert!(lifts(0.15, t_star - 0.15 + 1e-9));
        assert!(lifts(t_star + 0.01, 1e-9));
        // Past the uplift the ground falls back below g/4 at 0.5 s - t*: seated again there.
        assert!(!lifts(0.5 - t_star + 0.01, 0.01));
    }
}
