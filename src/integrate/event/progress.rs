//! The guard against a run that would never end: events at one instant (within a few ulps of
//! time) are counted, and past a few dozen the engine's state at each is fed to a cycle check
//! (`cycle.rs`): a state that keeps coming back is a real lack of progress and stops the run
//! with an error that says where; a long but changing sequence (a course of thousands of blocks
//! stopping one after another at one instant) is left to finish. A backstop sized to the wall
//! (`Params::max_events_per_instant`) ends what neither repeats nor ends.

use super::cluster::ClusterId;
use super::cycle::{key_of, Cycle};
use super::queue::{Constraint, Ev, Pending};
use super::slip::Slip;
use super::Engine;
use crate::error::{name_list, SimulationError};

/// Events closer together than this many ulps of time count as one instant.
const WINDOW_ULPS: f64 = 1e6;

/// Events at one instant before its states are checked for repetition: fewer cost nothing to
/// let through, and checking one costs the wall's size.
const CHECK_FROM: usize = 64;

/// The instant the guard is watching.
pub(super) struct Instant {
    t: f64,
    events: usize,
    cycle: Cycle<Vec<u64>>,
}

impl Instant {
    /// The instant t, before its first event.
    fn at(t: f64) -> Instant {
        Instant {
            t,
            events: 0,
            cycle: Cycle::default(),
        }
    }

    /// Before the run's first event.
    pub(super) fn start() -> Instant {
        Instant::at(f64::NEG_INFINITY)
    }
}

impl Engine<'_> {
    /// Counts event `p` at its instant and stops the run if the instant's state repeats or the
    /// backstop is reached.
    pub(super) fn progress_guard(&mut self, p: &Pending) -> Result<(), SimulationError> {
        let window = WINDOW_ULPS * f64::EPSILON * self.instant.t.abs().max(1.0);
        // The first event opens the first instant (before it, `t` is -inf).
        if !(self.instant.t.is_finite() && p.t - self.instant.t <= window) {
            self.instant = Instant::at(p.t);
        }
        self.instant.events += 1;
        let events = self.instant.events;
        if events > CHECK_FROM {
            let state = self.state_at(&p.ev);
            if let Some(period) = self.instant.cycle.step(key_of(&state), || state) {
                return Err(SimulationError::NoProgress {
                    time_s: p.t,
                    count: events,
                    period,
                    detail: self.describe(&p.ev),
                });
            }
        }
        let given = &self.given;
        let most = given.params.max_events_per_instant.unwrap_or_else(|| {
            10_000 + 100 * (given.n + given.topo.horizontal.len() + given.topo.vertical.len())
        });
        if events > most {
            return Err(SimulationError::TooManyEvents {
                time_s: p.t,
                count: events,
                detail: self.describe(&p.ev),
                limit: "for a wall of this size; raise `integrate::event::Params::\
                        max_events_per_instant` if it needs more",
            });
        }
        Ok(())
    }

    /// What the next step of the run depends on, as words: the event about to be handled (its
    /// kind and the first block of each cluster, not the clusters' versions, which only grow),
    /// every block's velocity, every horizontal joint's state and every vertical joint's
    /// contact.
    fn state_at(&self, ev: &Ev) -> Vec<u64> {
        let first = |k: ClusterId| {
            self.clusters[k]
                .blocks
                .first()
                .map_or(u64::MAX, |&b| b as u64)
        };
        let mut words = match *ev {
            Ev::Threshold { k, upper, .. } => vec![0, first(k), u64::from(upper)],
            Ev::Stop { k, .. } => vec![1, first(k)],
            Ev::GroundBound { k, c, .. } => vec![2, first(k), constraint_word(c)],
            Ev::Meet { a, b, .. } => vec![3, first(a), first(b)],
            Ev::PairBound { a, b, c, .. } => vec![4, first(a), first(b), constraint_word(c)],
        };
        words.extend((0..self.given.n).map(|i| self.block_vel(i).to_bits()));
        words.extend(self.slip.iter().map(|s| match s {
            Slip::Stuck => 0,
            Slip::Forward => 1,
            Slip::Backward => 2,
        }));
        words.extend(self.touching.iter().map(|&t| u64::from(t)));
        words
    }

    /// An event in words, with the blocks it concerns.
    fn describe(&self, ev: &Ev) -> String {
        let names = |k: ClusterId| {
            let blocks = &self.clusters[k].blocks;
            name_list(
                blocks
                    .iter()
                    .map(|&b| self.given.wall.blocks[b].name.as_str()),
                3,
            )
        };
        let constraint = |c: Constraint| match c {
            Constraint::Gap(j) => {
                let joint = &self.given.topo.vertical[j];
                let name = |b: usize| self.given.wall.blocks[b].name.as_str();
                format!(
                    "the vertical joint {}|{} closing",
                    name(joint.left.0),
                    name(joint.right.0)
                )
            }
            Constraint::Collapse(s) => {
                let joint = &self.given.topo.horizontal[s];
                let upper = &self.given.wall.blocks[joint.upper.0].name;
                format!("{upper} reaching a collapse threshold of its supports")
            }
        };
        match *ev {
            Ev::Threshold { k, .. } => {
                format!("the stuck group {} reaching its friction limit", names(k))
            }
            Ev::Stop { k, .. } => format!("the sliding group {} coming to rest", names(k)),
            Ev::GroundBound { k, c, .. } => format!("{} for the group {}", constraint(c), names(k)),
            Ev::Meet { a, b, .. } => {
                format!(
                    "the sliding groups {} and {} reaching one velocity",
                    names(a),
                    names(b)
                )
            }
            Ev::PairBound { a, b, c, .. } => {
                format!(
                    "{} between the groups {} and {}",
                    constraint(c),
                    names(a),
                    names(b)
                )
            }
        }
    }
}

fn constraint_word(c: Constraint) -> u64 {
    match c {
        Constraint::Gap(j) => 2 * j as u64,
        Constraint::Collapse(s) => 2 * s as u64 + 1,
    }
}
