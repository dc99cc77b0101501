//! What every time-stepping baseline shares: the wall as plain floats, and an observer that turns
//! step states into the same outputs as the event-driven integrator (history at output times by
//! linear interpolation between steps, extremes at steps, energy terms, collapse at steps).
//! The baselines are deliberately ordinary: their errors are what the accuracy study measures.

use crate::error::SimulationError;
use crate::integrate::{AfterCollapse, Progress, Scenario};
use crate::motion::Motion;
use crate::response::{Collapse, CollapseCause, EventKind, Recorder, Response};
use crate::topology::{Base, VerticalId};

/// A fixed time step `dt_s` for the scenario's run: positive, no longer than the run, and few
/// enough steps (`bounds::MAX_STEPS`) that the run ends; the run's own settings checked too.
pub fn time_step(sc: &Scenario, dt_s: f64) -> Result<(), SimulationError> {
    sc.settings.validate(sc.wall.blocks.len())?;
    steps_fit(dt_s, sc.settings.duration_s)
}

/// A time step `dt_s` that can take a run of `duration_s`: positive, no longer than the run,
/// and few enough steps (`bounds::MAX_STEPS`) that the run ends.
pub fn steps_fit(dt_s: f64, duration_s: f64) -> Result<(), SimulationError> {
    positive("time step", dt_s, " s")?;
    within_run(dt_s, duration_s)?;
    if duration_s / dt_s > crate::bounds::MAX_STEPS {
        return Err(SimulationError::Setting {
            what: "time step".into(),
            value: dt_s,
            unit: " s",
            rule: "it would take more than 1e9 steps over the duration: take a larger step",
        });
    }
    Ok(())
}

/// A time step `dt_s` no longer than a run of `duration_s`: a longer one would take one step for
/// the whole motion.
fn within_run(dt_s: f64, duration_s: f64) -> Result<(), SimulationError> {
    if dt_s > duration_s {
        return Err(SimulationError::Setting {
            what: "time step".into(),
            value: dt_s,
            unit: " s",
            rule: "it is longer than the run: one step would stand for the whole motion; take a \
                   step of a small part of the motion's shortest period or sample interval",
        });
    }
    Ok(())
}

/// A method parameter (a step, a tolerance, a stiffness) must be finite and positive; `unit`
/// is written after the value (with its leading space, or empty).
pub fn positive(what: &str, x: f64, unit: &'static str) -> Result<(), SimulationError> {
    if x.is_finite() && x > 0.0 {
        return Ok(());
    }
    Err(SimulationError::Setting {
        what: what.into(),
        value: x,
        unit,
        rule: "it must be positive and finite",
    })
}

/// A horizontal joint in floats.
#[derive(Debug, Clone, Copy)]
pub struct Horizontal {
    /// Upper block.
    pub upper: usize,
    /// Lower block; `None` for the ground or a fixed block.
    pub lower: Option<usize>,
    /// Lower block index even when fixed (for collapse geometry); `None` for the ground.
    pub lower_any: Option<usize>,
    /// Friction capacity (N).
    pub capacity: f64,
    /// Friction coefficient.
    pub mu: f64,
}

/// A vertical joint in floats.
#[derive(Debug, Clone, Copy)]
pub struct Vertical {
    /// Left block (`None`: fixed).
    pub left: Option<usize>,
    /// Right block (`None`: fixed).
    pub right: Option<usize>,
    /// Left and right block indices, fixed or not.
    pub pair: (usize, usize),
    /// Initial gap (m).
    pub gap0: f64,
}

/// The wall as floats for time stepping.
#[derive(Debug, Clone)]
pub struct Model {
    /// Blocks.
    pub n: usize,
    /// Mass (kg).
    pub mass: Vec<f64>,
    /// Moves (not fixed).
    pub movable: Vec<bool>,
    /// Horizontal joints.
    pub horizontal: Vec<Horizontal>,
    /// Vertical joints.
    pub vertical: Vec<Vertical>,
    /// Left edges, right edges, centroids (m).
    pub xl: Vec<f64>,
    /// Right edges (m).
    pub xr: Vec<f64>,
    /// Centroids (m).
    pub xc: Vec<f64>,
    /// Restitution.
    pub restitution: f64,
    /// Gravity (m/s2).
    pub g: f64,
}

impl Model {
    /// The float model of a scenario's wall.
    pub fn new(sc: &Scenario) -> Model {
        let (w, t) = (sc.wall, sc.topology);
        let movable: Vec<bool> = w.blocks.iter().map(|b| !b.fixed).collect();
        Model {
            n: w.blocks.len(),
            mass: t.blocks.iter().map(|b| b.mass_kg.to_f64()).collect(),
            horizontal: t
                .horizontal
                .iter()
                .map(|s| {
                    let lower_any = match s.lower {
                        Base::Ground => None,
                        Base::Block(b) => Some(b.0),
                    };
                    Horizontal {
                        upper: s.upper.0,
                        lower: lower_any.filter(|&b| movable[b]),
                        lower_any,
                        capacity: s.capacity_n.to_f64(),
                        mu: s.friction.to_f64(),
                    }
                })
                .collect(),
            vertical: t
                .vertical
                .iter()
                .map(|j| Vertical {
                    left: Some(j.left.0).filter(|&b| movable[b]),
                    right: Some(j.right.0).filter(|&b| movable[b]),
                    pair: (j.left.0, j.right.0),
                    gap0: j.gap_m.to_f64(),
                })
                .collect(),
            xl: w.blocks.iter().map(|b| b.x.to_f64()).collect(),
            xr: w.blocks.iter().map(|b| b.right().to_f64()).collect(),
            xc: w.blocks.iter().map(|b| b.centroid_x().to_f64()).collect(),
            restitution: w.restitution.to_f64(),
            g: w.g_m_s2.to_f64(),
            movable,
        }
    }

    /// Relative velocity across joint j (upper minus lower).
    pub fn slip_velocity(&self, j: &Horizontal, v: &[f64]) -> f64 {
        v[j.upper] - j.lower.map_or(0.0, |l| v[l])
    }

    /// Gap of face f.
    pub fn gap(&self, f: &Vertical, u: &[f64]) -> f64 {
        f.gap0 + f.right.map_or(0.0, |r| u[r]) - f.left.map_or(0.0, |l| u[l])
    }

    /// A block whose centroid has left its support span, if any (same rule as the exact
    /// integrator, evaluated at a step).
    pub fn fallen(&self, u: &[f64], gone: &[bool]) -> Option<usize> {
        for i in 0..self.n {
            if !self.movable[i] || gone[i] {
                continue;
            }
            let mut on_ground = false;
            let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
            for j in self.horizontal.iter().filter(|j| j.upper == i) {
                match j.lower_any {
                    None => on_ground = true,
                    Some(l) if gone[l] => {}
                    Some(l) => {
                        let ul = if self.movable[l] { u[l] } else { 0.0 };
                        let a = (self.xl[i] + u[i]).max(self.xl[l] + ul);
                        let b = (self.xr[i] + u[i]).min(self.xr[l] + ul);
                        if b > a {
                            lo = lo.min(a);
                            hi = hi.max(b);
                        }
                    }
                }
            }
            let c = self.xc[i] + u[i];
            if !(on_ground || (lo..=hi).contains(&c)) {
                return Some(i);
            }
        }
        None
    }

    /// Kinetic energy (J).
    pub fn kinetic(&self, v: &[f64]) -> f64 {
        (0..self.n)
            .filter(|&i| self.movable[i])
            .map(|i| 0.5 * self.mass[i] * v[i] * v[i])
            .sum()
    }
}

/// Hands `row` each output time k `output_dt` (k from `next`, which it advances) that a step
/// from t0 to t reaches, with its place in the step (0 at t0, 1 at t): the history of a time
/// stepper is written at the output times, the event-driven integrator's times, by linear
/// interpolation between steps (second order in the step, below a first-order scheme's error).
pub fn outputs_in_step(
    next: &mut u64,
    output_dt: f64,
    t0: f64,
    t: f64,
    mut row: impl FnMut(f64, f64),
) {
    loop {
        let tk = *next as f64 * output_dt;
        if tk > t + 1e-12 * output_dt {
            break;
        }
        let f = if t > t0 {
            ((tk - t0) / (t - t0)).clamp(0.0, 1.0)
        } else {
            1.0
        };
        row(tk, f);
        *next += 1;
    }
}

/// a + f (b - a), entry by entry.
pub fn lerp(a: &[f64], b: &[f64], f: f64) -> Vec<f64> {
    a.iter().zip(b).map(|(x, y)| x + f * (y - x)).collect()
}

/// Turns step states into a [`Response`].
pub struct Observer<'a> {
    /// The recorder.
    pub rec: Recorder,
    model: &'a Model,
    motion: &'a Motion,
    output_dt: Option<f64>,
    next_output: u64,
    last: (f64, Vec<f64>, Vec<f64>),
    d_last: Vec<f64>,
    after_collapse: AfterCollapse,
    /// Blocks that fell.
    pub gone: Vec<bool>,
    /// Stop the run (a collapse with `--after-collapse stop`).
    pub stopped: bool,
    impulsive: bool,
    progress: Option<Progress>,
    t_end: f64,
}

impl<'a> Observer<'a> {
    /// An observer for this scenario, at rest at t = 0.
    pub fn new(sc: &Scenario, model: &'a Model, motion: &'a Motion) -> Observer<'a> {
        let rec = Recorder::new(
            sc.wall,
            sc.topology,
            sc.settings.history_to(),
            sc.settings.events_to(),
        );
        let n = model.n;
        Observer {
            rec,
            model,
            motion,
            output_dt: sc.settings.output_dt_s,
            next_output: 0,
            last: (0.0, vec![0.0; n], vec![0.0; n]),
            d_last: vec![0.0; model.horizontal.len()],
            after_collapse: sc.settings.after_collapse,
            gone: vec![false; n],
            stopped: false,
            impulsive: false,
            progress: sc.settings.progress.clone(),
            t_end: sc.settings.duration_s,
        }
    }

    /// Relative displacement of joint j.
    fn d(&self, j: &Horizontal, u: &[f64]) -> f64 {
        u[j.upper] - j.lower.map_or(0.0, |l| u[l])
    }

    /// Records the state after a step ending at t: history rows at output times in between
    /// (interpolated), extremes, input work (trapezoid), friction work F |delta d|, collapse.
    pub fn step(&mut self, t: f64, u: &[f64], v: &[f64]) {
        let (t0, u0, v0) = (self.last.0, self.last.1.clone(), self.last.2.clone());
        if let Some(dt) = self.output_dt {
            let rec = &mut self.rec;
            outputs_in_step(&mut self.next_output, dt, t0, t, |tk, f| {
                rec.sample(tk, &lerp(&u0, u, f), &lerp(&v0, v, f));
            });
        }
        let (a0, a1) = (self.motion.accel(t0), self.motion.accel(t));
        let m = self.model;
        let mut work = 0.0;
        for i in 0..m.n {
            if m.movable[i] && !self.gone[i] {
                work += -m.mass[i] * 0.5 * (a0 * v0[i] + a1 * v[i]) * (t - t0);
                self.rec.block_extremes(i, u[i].abs(), v[i].abs());
                // Over a step with an impulse, delta v / dt is no acceleration.
                if t > t0 && !self.impulsive {
                    self.rec
                        .block_accel(i, ((v[i] - v0[i]) / (t - t0) + a1).abs());
                }
            }
        }
        self.rec.energy.input_j += work;
        for (k, j) in m.horizontal.iter().enumerate() {
            if self.gone[j.upper] || j.lower_any.is_some_and(|l| self.gone[l]) {
                continue;
            }
            let d = self.d(j, u);
            self.rec.energy.friction_j += j.capacity * (d - self.d_last[k]).abs();
            self.d_last[k] = d;
            self.rec.horizontal_extreme(k, d);
        }
        if let Some(i) = m.fallen(u, &self.gone) {
            if self.rec.collapse.is_none() {
                self.rec.collapse = Some(Collapse {
                    time_s: t,
                    block: self.rec.names()[i].clone(),
                    cause: CollapseCause::SlidingOff,
                });
            }
            self.rec.event(t, EventKind::Collapse, &[i], None, None);
            self.rec.fell(i);
            self.gone[i] = true;
            self.rec.energy.fallen_j += 0.5 * m.mass[i] * v[i] * v[i];
            if self.after_collapse == AfterCollapse::Stop {
                self.stopped = true;
            }
        }
        self.last = (t, u.to_vec(), v.to_vec());
        self.impulsive = false;
        if let Some(p) = &self.progress {
            if !p.at(t.min(self.t_end)) && t < self.t_end {
                self.stopped = true;
                self.rec.interrupted_at_s = Some(t);
            }
        }
    }

    /// Marks the current step as carrying an impulse (an impact, a penalty contact).
    pub fn impulsive(&mut self) {
        self.impulsive = true;
    }

    /// Logs an impact at face k with velocities before and after, and its energy loss.
    pub fn impact(&mut self, t: f64, k: usize, before: [f64; 2], after: [f64; 2]) {
        let (l, r) = self.model.vertical[k].pair;
        let m = |b: usize| {
            if self.model.movable[b] {
                self.model.mass[b]
            } else {
                0.0
            }
        };
        let ke = |v: [f64; 2]| 0.5 * (m(l) * v[0] * v[0] + m(r) * v[1] * v[1]);
        self.rec.energy.impact_loss_j += ke(before) - ke(after);
        self.impulsive = true;
        self.rec.impact(t, VerticalId(k), before, after);
    }

    /// Finishes the run at time t with the last state.
    pub fn finish(mut self, method: &str, sc: &Scenario, steps: u64) -> Response {
        let (t, u, v) = self.last.clone();
        self.rec.energy.kinetic_j = (0..self.model.n)
            .filter(|&i| self.model.movable[i] && !self.gone[i])
            .map(|i| 0.5 * self.model.mass[i] * v[i] * v[i])
            .sum();
        self.rec.stats.steps = steps;
        self.rec.stats.events = steps;
        self.rec.warnings =
            crate::validity::rocking_warnings(sc.wall, sc.topology, self.rec.peak_accel());
        crate::validity::note_overlap_loss(sc.wall, sc.topology, &mut self.rec);
        self.rec
            .finish(method, &sc.wall.name, sc.motion.describe(), t, &u, &v)
    }
}
