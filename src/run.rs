//! One run: a model under a ground motion with its settings, the model of the blocks chosen as
//! asked (sliding, rocking, or auto: sliding while no block can lift), the response returned
//! with a word on which model ran and why. `pirqa run` is this function behind its options.

use crate::error::{Error, SimulationError};
use crate::integrate::baselines::{
    ContactSolver, KeepsSeated, Moreau, MoreauWall, PaperNewmark, Regularized, Stepped, HANDED_OFF,
};
use crate::integrate::event::{Ended, EventDriven, Params};
use crate::integrate::rocking::{self, Equations, Finished, ModelChoice, Rocking};
use crate::integrate::stepping::{positive, steps_fit, time_step};
use crate::integrate::{AfterCollapse, Integrator, Progress, Scenario, Settings};
use crate::model::Model;
use crate::motion::Motion;
use crate::response::Response;

/// The integrator.
#[derive(Debug, Clone, Default)]
pub enum Method {
    /// The exact event-driven integrator.
    #[default]
    Event,
    /// The paper's Newmark scheme with sgn(v) friction, step `dt_s`.
    Paper {
        /// Time step (s).
        dt_s: f64,
    },
    /// Moreau-Jean time stepping (with rotations for a rocking block), step `dt_s`.
    Moreau {
        /// Time step (s).
        dt_s: f64,
    },
    /// Regularized friction and penalty contacts under Dormand-Prince 5(4).
    Regularized(Regularized),
}

impl Method {
    /// Its fixed time step; `None` for the exact integrator and the adaptive one.
    pub fn step_s(&self) -> Option<f64> {
        match *self {
            Method::Paper { dt_s } | Method::Moreau { dt_s } => Some(dt_s),
            Method::Event | Method::Regularized(_) => None,
        }
    }
}

/// What a sliding run does at the first instant some block must start to turn (found by the
/// uplift check, `limit::seated`); a sweep file's `after_uplift` (`Slide`, `Moreau(dt_s: S)`,
/// `MoreauWhileRocking(dt_s: S)`).
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
pub enum AfterUplift {
    /// Slides on, the check saying when and which blocks would turn (with `check_uplift`).
    #[default]
    Slide,
    /// Hands the state of that instant to Moreau-Jean with rotations, step `dt_s`, which runs
    /// the rest: exact sliding while every block stays seated, every block with its rotation
    /// from the first uplift on.
    Moreau {
        /// Time step (s).
        dt_s: f64,
    },
    /// As `Moreau`, until every block is seated again and has stopped turning: the exact
    /// sliding run takes the wall back from there (blocks set down flat, `docs/rocking-walls.md`)
    /// and hands it over again at its next uplift. Only the stretches in which something rocks
    /// are time stepped.
    MoreauWhileRocking {
        /// Time step (s).
        dt_s: f64,
    },
}

impl AfterUplift {
    /// The time step of the stepping after an uplift; `None`: slides on.
    pub fn step_s(&self) -> Option<f64> {
        match *self {
            AfterUplift::Slide => None,
            AfterUplift::Moreau { dt_s } | AfterUplift::MoreauWhileRocking { dt_s } => Some(dt_s),
        }
    }

    /// The value of `--after-uplift` that asks for it.
    pub fn option(&self) -> &'static str {
        match self {
            AfterUplift::Slide => "slide",
            AfterUplift::Moreau { .. } => "moreau",
            AfterUplift::MoreauWhileRocking { .. } => "moreau-while-rocking",
        }
    }
}

/// What a run of the exact rocking model does where it stops following the wall before the end
/// (a held joint of a column gives way, a column's body or a trilith's frame would fly:
/// docs/rocking-walls.md); a sweep's `fallback: MoreauFromStop(dt_s: S)` asks for `Moreau`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum AfterStop {
    /// The run ends there, its warning saying where and why.
    #[default]
    End,
    /// Moreau-Jean with every block's rotation, step `dt_s`, from every block's state there
    /// (turned, moving) to the end: the run exact up to the stop, time stepped only beyond it.
    Moreau {
        /// Time step (s).
        dt_s: f64,
    },
}

/// The direction of the ground motion relative to the wall.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum Direction {
    /// Along the wall, in its plane.
    #[default]
    InPlane,
    /// Across the wall: the part above each bed joint rocks (or slides) on it as one body.
    OutOfPlane,
}

/// How to run: the defaults give the exact integrator, the model chosen by the motion (auto),
/// in the wall's plane, for the motion's own length, with the summary only.
#[derive(Debug, Clone, Default)]
pub struct RunSettings {
    /// Simulated time (s); `None`: the motion's length (a sine's or pulse's duration, a record's
    /// last sample).
    pub duration_s: Option<f64>,
    /// History sampling interval (s); `None`: no history.
    pub output_dt_s: Option<f64>,
    /// Write the history to this CSV file as the run goes (bounded memory) instead of keeping
    /// it in the response.
    pub history_file: Option<std::path::PathBuf>,
    /// Keep the event log.
    pub log_events: bool,
    /// With `log_events`, also write the log to this JSON-lines file as the run goes, under a
    /// partial name until the run ends ([`Settings::events_file`]).
    pub events_file: Option<std::path::PathBuf>,
    /// Keep the log of mode decisions (event-driven sliding only).
    pub log_decisions: bool,
    /// With `log_decisions`, also write that log to this JSON-lines file as the run goes
    /// ([`Settings::decisions_file`]).
    pub decisions_file: Option<std::path::PathBuf>,
    /// What to do once a block falls.
    pub after_collapse: AfterCollapse,
    /// The integrator.
    pub method: Method,
    /// Sliding, rocking, or auto.
    pub model: ModelChoice,
    /// The rocking equations (default exact).
    pub rocking: Option<Equations>,
    /// In the wall's plane or across it.
    pub direction: Direction,
    /// Blocks (or sections across the plane) released from a rotation, by name (rad).
    pub initial_rotation: Vec<(String, f64)>,
    /// How Moreau-Jean with rotations solves each step's contacts.
    pub contact_solver: ContactSolver,
    /// Told the simulated time as the run goes on.
    pub progress: Option<Progress>,
    /// Watch the exact sliding run for the first instant some block must start to turn
    /// (`limit::seated`; summary.json's `uplift_check`).
    pub check_uplift: bool,
    /// What follows that instant (the watch is on whenever this is not `Slide`).
    pub after_uplift: AfterUplift,
    /// What follows where the exact rocking model stops before the end.
    pub after_stop: AfterStop,
}

fn incompatible(asked: &'static str, fix: &'static str) -> SimulationError {
    SimulationError::Incompatible { asked, fix }
}

impl RunSettings {
    /// Checks the numbers and the combination of choices; the errors say what to change.
    pub fn validate(&self) -> Result<(), Error> {
        if let Some(d) = self.duration_s {
            positive("duration", d, " s")?;
        }
        if let Some(dt) = self.output_dt_s {
            positive("history interval", dt, " s")?;
        }
        match &self.method {
            Method::Paper { dt_s } | Method::Moreau { dt_s } => positive("time step", *dt_s, " s")?,
            Method::Event | Method::Regularized(_) => {}
        }
        // With the duration known, a step that cannot take the run is refused here, before a
        // caller estimates (and announces) the run's size from it.
        if let Some(d) = self.duration_s {
            let after_stop = match self.after_stop {
                AfterStop::Moreau { dt_s } => Some(dt_s),
                AfterStop::End => None,
            };
            let steps = [self.method.step_s(), self.after_uplift.step_s(), after_stop];
            for dt_s in steps.into_iter().flatten() {
                steps_fit(dt_s, d)?;
            }
        }
        for (name, theta) in &self.initial_rotation {
            if !(theta.is_finite() && theta.abs() < std::f64::consts::FRAC_PI_2) {
                return Err(Error::Simulation(SimulationError::Setting {
                    what: format!("initial rotation of {name}:"),
                    value: *theta,
                    unit: " rad",
                    rule: "a rotation must be finite and below pi/2 in size",
                }));
            }
        }
        if self.contact_solver != ContactSolver::GaussSeidel
            && !matches!(self.method, Method::Moreau { .. })
            && self.after_uplift == AfterUplift::Slide
            && self.after_stop == AfterStop::End
        {
            return Err(Error::Simulation(incompatible(
                "--contact-solver chooses how Moreau-Jean solves a step's contacts",
                "add --method moreau --dt S, or leave --contact-solver out",
            )));
        }
        if let AfterStop::Moreau { dt_s } = self.after_stop {
            positive("time step", dt_s, " s")?;
            let refused = |asked| {
                Err(Error::Simulation(incompatible(
                    asked,
                    "leave --after-stop out, or the option it names",
                )))
            };
            if !matches!(self.method, Method::Event) {
                return refused(
                    "--after-stop hands the exact rocking model's run over where it stops, and \
                     --method chooses another integrator for the whole run",
                );
            }
            if self.after_uplift != AfterUplift::Slide {
                return refused(
                    "--after-stop follows the exact rocking model, and --after-uplift the exact \
                     sliding model: a wall runs on one of them",
                );
            }
            if self.direction == Direction::OutOfPlane {
                return refused(
                    "--after-stop follows a wall's columns in its plane, and across the plane \
                     each section rocks on its own to the end",
                );
            }
            if self.rocking == Some(Equations::Linearised) {
                return refused(
                    "--after-stop hands the state of the rigid blocks to Moreau-Jean, and \
                     --rocking linearised follows other equations",
                );
            }
        }
        if let Some(dt_s) = self.after_uplift.step_s() {
            positive("time step", dt_s, " s")?;
            let hand_off = |asked| {
                Err(Error::Simulation(incompatible(
                    asked,
                    "leave --after-uplift out, or the option it names",
                )))
            };
            if !matches!(self.method, Method::Event) {
                return hand_off(
                    "--after-uplift hands the exact sliding run over at its first uplift, and \
                     --method chooses another integrator for the whole run",
                );
            }
            if self.model != ModelChoice::Auto {
                return hand_off(
                    "--after-uplift chooses what follows a sliding run's first uplift, which \
                     the model auto runs, and --model chooses one model for the whole run",
                );
            }
            if self.direction == Direction::OutOfPlane || !self.initial_rotation.is_empty() {
                return hand_off(
                    "--after-uplift follows a wall that starts at rest and slides in its \
                     plane, and --direction out-of-plane or --initial-rotation starts it rocking",
                );
            }
        }
        if self.rocking.is_some() && self.model == ModelChoice::Slide {
            return Err(Error::Simulation(incompatible(
                "--model slide rotates no block",
                "leave --rocking out, or use --model slide-rock",
            )));
        }
        if self.direction == Direction::OutOfPlane && self.model == ModelChoice::Slide {
            return Err(Error::Simulation(incompatible(
                "across the wall's plane the wall rocks",
                "use --model slide-rock or auto",
            )));
        }
        if self.direction == Direction::InPlane && self.initial_rotation.len() > 1 {
            return Err(Error::Simulation(SimulationError::NotApplicable(format!(
                "{} initial rotations given: in the wall's plane one body is released, so give \
                 one --initial-rotation (across the plane, each section takes its own)",
                self.initial_rotation.len()
            ))));
        }
        Ok(())
    }
}

/// Runs `model` under `motion` as `settings` say.
pub fn run(model: &Model, motion: &Motion, settings: &RunSettings) -> Result<Response, Error> {
    settings.validate()?;
    let duration_s = settings.duration_s.unwrap_or_else(|| motion.duration_s());
    let s = Settings {
        duration_s,
        output_dt_s: settings.output_dt_s,
        history_file: settings.history_file.clone(),
        log_events: settings.log_events,
        events_file: settings.events_file.clone(),
        decisions_file: settings.decisions_file.clone(),
        log_decisions: settings.log_decisions,
        after_collapse: settings.after_collapse,
        progress: settings.progress.clone(),
    };
    let sc = Scenario {
        wall: model.wall(),
        topology: model.topology(),
        motion,
        settings: &s,
    };
    Ok(run_scenario(&sc, settings)?)
}

/// Runs a scenario on the model and integrator `settings` choose (`method`, `model`,
/// `rocking`, `direction`, `initial_rotation`; duration, history and logs are the scenario's
/// own): what `pirqa run` and every case of a sweep run.
pub fn run_scenario(sc: &Scenario, settings: &RunSettings) -> Result<Response, SimulationError> {
    let equations = settings.rocking.unwrap_or_default();
    let exact_only = |what: &str| -> Result<(), SimulationError> {
        match settings.method {
            Method::Event => Ok(()),
            _ => Err(SimulationError::NotApplicable(format!(
                "{what} runs on the exact event-driven integrator only: leave --method out (a \
                 sweep: its `method`), or run with --model slide (`model: Slide`)"
            ))),
        }
    };
    let no_uplift_check = |why: &str| {
        SimulationError::NotApplicable(format!(
            "--check-uplift watches the exact sliding engine, which does not run here ({why}): \
             leave --check-uplift out, or run the sliding model with the exact integrator \
             (--model slide, no --method)"
        ))
    };
    if settings.direction == Direction::OutOfPlane {
        if settings.check_uplift {
            return Err(no_uplift_check("across the plane the wall rocks"));
        }
        exact_only("rocking across the plane")?;
        return rocking::out_of_plane(
            sc.wall,
            sc.topology,
            sc.motion,
            sc.settings,
            equations,
            &settings.initial_rotation,
        );
    }
    let (rocks, why) = in_plane_model(sc, settings)?;
    if settings.check_uplift && (rocks || !matches!(settings.method, Method::Event)) {
        return Err(no_uplift_check(&why));
    }
    if let Some(dt_s) = settings.after_uplift.step_s() {
        if rocks {
            return Err(SimulationError::NotApplicable(format!(
                "the exact rocking model follows this wall's uplift itself ({why}): leave \
                 --after-uplift out"
            )));
        }
        return hand_off_at_uplift(sc, settings, dt_s);
    }
    let initial = settings.initial_rotation.first().map_or(0.0, |r| r.1);
    let mut response = match (&settings.method, rocks) {
        (Method::Moreau { .. }, true) if settings.rocking.is_some() => {
            return Err(incompatible(
                "Moreau-Jean steps the rigid bodies' own equations",
                "leave --rocking out",
            ))
        }
        (Method::Moreau { dt_s }, true) => MoreauWall {
            initial_rotation: settings.initial_rotation.first().cloned(),
            solver: settings.contact_solver,
            ..MoreauWall::new(*dt_s)
        }
        .run(sc)?,
        (_, true) => {
            exact_only("the rocking model (or --method moreau)")?;
            let rocking = Rocking {
                equations,
                initial_rotation_rad: initial,
            };
            match settings.after_stop {
                AfterStop::End => rocking.run(sc)?,
                AfterStop::Moreau { dt_s } => {
                    return hand_off_at_stop(sc, settings, &rocking, dt_s, why)
                }
            }
        }
        (_, false) if settings.after_stop != AfterStop::End => {
            return Err(SimulationError::NotApplicable(format!(
                "--after-stop follows the exact rocking model where it stops, and this wall runs \
                 on the sliding model ({why}): leave --after-stop out"
            )))
        }
        (Method::Event, false) => EventDriven {
            params: Params {
                watch_uplift: settings.check_uplift,
                ..Params::default()
            },
        }
        .run(sc)?,
        (Method::Paper { dt_s }, false) => PaperNewmark { dt_s: *dt_s }.run(sc)?,
        (Method::Moreau { .. }, false) if settings.contact_solver != ContactSolver::GaussSeidel => {
            return Err(incompatible(
                "the whole-wall Newton solver belongs to the model with rotations",
                "add --model slide-rock, or leave --contact-solver out",
            ))
        }
        (Method::Moreau { dt_s }, false) => Moreau::new(*dt_s).run(sc)?,
        (Method::Regularized(r), false) => r.run(sc)?,
    };
    response.summary.model.why = why;
    Ok(response)
}

/// The exact sliding run up to its first uplift, Moreau-Jean with rotations from there: to the
/// end, or (`MoreauWhileRocking`) until every block is seated again, where the exact sliding
/// run goes on, to its next uplift.
fn hand_off_at_uplift(
    sc: &Scenario,
    settings: &RunSettings,
    dt_s: f64,
) -> Result<Response, SimulationError> {
    let sliding = EventDriven {
        params: Params::default(),
    };
    let stepper = MoreauWall {
        solver: settings.contact_solver,
        ..MoreauWall::new(dt_s)
    };
    let back = matches!(
        settings.after_uplift,
        AfterUplift::MoreauWhileRocking { .. }
    );
    let option = settings.after_uplift.option();
    // The step is checked before the sliding run, which may take long.
    time_step(sc, dt_s)?;
    let mut ended = sliding.run_to_uplift(sc)?;
    // A wall set down where the exact model lifts a block within a step would come straight
    // back.
    let keeps_seated: KeepsSeated = &|from| Ok(!sliding.lifts_within(sc, from, dt_s)?);
    // The stretches time stepped: from an uplift to where the wall was set down.
    let mut stepped: Vec<(f64, f64)> = Vec::new();
    let mut turning = String::new();
    loop {
        match ended {
            Ended::Seated(r) if stepped.is_empty() => {
                let mut r = *r;
                r.summary.model.why = if r.summary.interrupted_at_s.is_some() {
                    format!(
                        "auto with --after-uplift {option}: stopped while the exact sliding \
                         model ran"
                    )
                } else {
                    format!(
                        "auto with --after-uplift {option}: no block had to start turning \
                         before the run ended (the uplift check), so the exact sliding answer is \
                         the answer"
                    )
                };
                return Ok(r);
            }
            Ended::Seated(r) => {
                let mut r = *r;
                r.summary.method = HANDED_OFF.into();
                let why = stretches(&turning, &stepped, None, dt_s);
                r.summary.model = stepper.model_used(&why);
                return Ok(r);
            }
            Ended::Lifted(h) => {
                let t = h.t_s;
                if stepped.is_empty() {
                    turning = lifted_blocks(&h.rec);
                }
                match stepper.run_from(sc, *h, back.then_some(keeps_seated))? {
                    Stepped::Ended(r) => {
                        let mut r = *r;
                        r.summary.model.why = if back {
                            stretches(&turning, &stepped, Some(t), dt_s)
                        } else {
                            format!(
                                "auto with --after-uplift moreau: exact sliding while every \
                                 block stayed seated, to the first uplift at t = {t} s \
                                 ({turning}); from there Moreau-Jean with every block's \
                                 rotation, dt = {dt_s} s"
                            )
                        };
                        return Ok(r);
                    }
                    Stepped::Seated(h) => {
                        stepped.push((t, h.t_s));
                        ended = sliding.resume(sc, *h)?;
                    }
                }
            }
        }
    }
}

/// The exact rocking model up to where it stops following the wall, Moreau-Jean with every
/// block's rotation from the state there to the end (`why`: why the wall rocks).
fn hand_off_at_stop(
    sc: &Scenario,
    settings: &RunSettings,
    rocking: &Rocking,
    dt_s: f64,
    why: String,
) -> Result<Response, SimulationError> {
    let stepper = MoreauWall {
        solver: settings.contact_solver,
        ..MoreauWall::new(dt_s)
    };
    // The step is checked before the exact run.
    time_step(sc, dt_s)?;
    match rocking.run_to_stop(sc)? {
        Finished::Ended(r) => {
            let mut r = *r;
            r.summary.model.why = format!(
                "{why}; with --after-stop moreau: the exact model followed the wall to the end \
                 of the run, so its answer is the answer"
            );
            Ok(r)
        }
        Finished::Stopped(h, stop) => {
            let t = h.t_s;
            let Stepped::Ended(r) = stepper.run_from(sc, *h, None)? else {
                return Err(SimulationError::Bug(
                    "a stepper not asked to set the wall down did".into(),
                ));
            };
            let mut r = *r;
            r.summary.model.why = format!(
                "{why}; with --after-stop moreau: the exact model to t = {t} s, where {stop}; \
                 from there Moreau-Jean with every block's rotation, dt = {dt_s} s"
            );
            Ok(r)
        }
    }
}

/// Stretches listed in `model.why` one by one; beyond them, counted.
const STRETCHES_LISTED: usize = 5;

/// The `model.why` of a run handed back and forth: the first uplift (the blocks that
/// turned), the stretches time stepped until the wall was set down again, and the last,
/// from `open_from`, where stepping ran to the end.
fn stretches(turning: &str, stepped: &[(f64, f64)], open_from: Option<f64>, dt_s: f64) -> String {
    let mut spans: Vec<String> = stepped
        .iter()
        .map(|(a, b)| format!("{a} to {b} s"))
        .chain(open_from.map(|a| format!("{a} s to the end")))
        .collect();
    let count = spans.len();
    if count > STRETCHES_LISTED {
        spans.truncate(STRETCHES_LISTED);
        spans.push(format!("{} more", count - STRETCHES_LISTED));
    }
    let first = stepped
        .first()
        .map(|s| s.0)
        .or(open_from)
        .unwrap_or_default();
    format!(
        "auto with --after-uplift moreau-while-rocking: exact sliding while every block stayed \
         seated; from each uplift (the first at t = {first} s: {turning}) Moreau-Jean with every \
         block's rotation, dt = {dt_s} s, until every block was seated and calm again and the exact \
         sliding model kept it so (set down flat, the exact sliding model went on); stretches stepped ({count}): {}",
        spans.join(", ")
    )
}

/// The blocks the uplift check found turning, as its warning names them.
fn lifted_blocks(rec: &crate::response::Recorder) -> String {
    rec.uplift_check
        .as_ref()
        .and_then(|c| c.first_uplift.as_ref())
        .map_or_else(String::new, |u| u.turning.join(", "))
}

/// Whether a run in the wall's plane turns blocks under `settings`, and why (the sentence of
/// summary.json's `model.why`), decided before running it: Moreau-Jean asked to rock a wall
/// that is not one free-standing block turns every block, any wall; otherwise the model is
/// [`rocking::rocks_in_plane`]'s choice.
pub fn in_plane_model(
    sc: &Scenario,
    settings: &RunSettings,
) -> Result<(bool, String), SimulationError> {
    if matches!(settings.method, Method::Moreau { .. })
        && settings.model == ModelChoice::SlideRock
        && rocking::free_standing(sc.wall, sc.topology).is_err()
    {
        return Ok((
            true,
            format!(
                "asked for (--model slide-rock --method moreau): each of the {} blocks with its \
                 rotation, every contact at the corners of its joints",
                sc.wall.blocks.len()
            ),
        ));
    }
    rocking::rocks_in_plane(
        settings.model,
        sc.wall,
        sc.topology,
        sc.motion,
        sc.settings.duration_s,
        &settings.initial_rotation,
    )
}
