//! What a run will cost, worked out before it starts from the wall, the motion and the settings
//! alone: the history it will hold and write, the steps a time stepper takes, and for the exact
//! integrator the episodes of sliding the motion can start and the events they bring. `pirqa
//! run` says so when a run is large (`--estimate` prints it without running), so that a run of
//! hours or a history of gigabytes is never a surprise.

use crate::integrate::rocking::ModelChoice;
use crate::model::Model;
use crate::motion::Motion;
use crate::run::{AfterUplift, Method, RunSettings};
use std::fmt;

/// A run is called large from these amounts on.
const LARGE_EVENTS: f64 = 1e6;
const LARGE_STEP_BLOCKS: f64 = 1e9;
/// Time stepping with every block's rotation solves a contact problem over the whole wall at
/// each step: 12-41 microseconds per block and step with the whole-wall Newton solver on the
/// development machine (docs/reliability.md), a thousand times a sliding step's.
const LARGE_ROTATING_STEP_BLOCKS: f64 = 1e7;
const LARGE_HISTORY_BYTES: f64 = 1e9;

/// Bytes of one number in history.csv (`-1.2345678901234567e-3,` at most).
const BYTES_PER_NUMBER: f64 = 24.0;

/// The work of a run, estimated before it starts.
#[derive(Debug, Clone, PartialEq)]
pub struct Estimate {
    /// Simulated time (s).
    pub duration_s: f64,
    /// Blocks of the wall.
    pub blocks: usize,
    /// Times the ground acceleration rises past the weakest joint's friction limit mu g: each
    /// can start sliding somewhere.
    pub slip_episodes: f64,
    /// Horizontal joints whose mu g the motion's peak exceeds.
    pub joints_that_can_slip: usize,
    /// Events of the exact integrator: a start and a stop per episode and joint that can slip
    /// (blocks sliding one by one; a wall that slides as one body has fewer, impacts add more).
    pub events: f64,
    /// Time steps of a fixed-step method (0 for the exact one and the adaptive one).
    pub steps: f64,
    /// Whether each step turns every block (Moreau-Jean with `--model slide-rock`, or after the
    /// first uplift): a contact problem over the whole wall per step.
    pub rotating: bool,
    /// The steps are those of `--after-uplift moreau` (or `moreau-while-rocking`): at most,
    /// from an uplift at the start.
    pub after_uplift: bool,
    /// Rows of the history, when one is kept.
    pub history_rows: f64,
    /// Size of history.csv (bytes), when a history is kept.
    pub history_bytes: f64,
}

/// The estimate for `model` under `motion` run as `settings` say.
pub fn estimate(model: &Model, motion: &Motion, settings: &RunSettings) -> Estimate {
    let duration_s = settings.duration_s.unwrap_or_else(|| motion.duration_s());
    let g = model.wall().g_m_s2.to_f64();
    let topo = model.topology();
    let peak = motion.peak_accel_m_s2();
    let mu: Vec<f64> = topo
        .horizontal
        .iter()
        .map(|h| h.friction.to_f64())
        .collect();
    let weakest = mu.iter().copied().fold(f64::INFINITY, f64::min);
    let joints_that_can_slip = mu.iter().filter(|&&m| m * g < peak).count();
    let slip_episodes = if weakest.is_finite() {
        rises_past(motion, weakest * g, duration_s)
    } else {
        0.0
    };
    let events = 2.0 * slip_episodes * joints_that_can_slip as f64;
    let steps = settings
        .method
        .step_s()
        .or(settings.after_uplift.step_s())
        .map_or(0.0, |dt_s| (duration_s / dt_s).ceil());
    let after_uplift = settings.after_uplift != AfterUplift::Slide;
    let rotating = after_uplift
        || (matches!(settings.method, Method::Moreau { .. })
            && settings.model == ModelChoice::SlideRock);
    let blocks = model.wall().blocks.len();
    let history_rows = settings.output_dt_s.map_or(0.0, |dt| {
        let rows = (duration_s / dt).floor() + 1.0;
        // The exact integrator adds a row after every event.
        match settings.method {
            Method::Event => rows + events,
            _ => rows,
        }
    });
    // u and v of every block, and theta, omega and w where steps turn them.
    let per_block = if rotating { 5.0 } else { 2.0 };
    let history_bytes = history_rows * (1.0 + per_block * blocks as f64) * BYTES_PER_NUMBER;
    Estimate {
        duration_s,
        blocks,
        slip_episodes,
        joints_that_can_slip,
        events,
        steps,
        rotating,
        after_uplift,
        history_rows,
        history_bytes,
    }
}

/// How many times |a_g| rises past `limit` within the first `duration_s` of the motion: in closed
/// form for a sine (twice a period when its amplitude exceeds the limit) and a pulse, by the
/// samples of a record.
fn rises_past(motion: &Motion, limit: f64, duration_s: f64) -> f64 {
    match motion {
        Motion::Sine(s) => {
            let t = duration_s.min(s.duration_s);
            if s.amplitude_m_s2.abs() > limit {
                (2.0 * s.frequency_hz * t).ceil()
            } else {
                0.0
            }
        }
        Motion::Pulse(p) => f64::from(u8::from(p.amplitude_m_s2.abs() > limit)),
        Motion::Record(r) => {
            let last = ((duration_s / r.dt_s()).ceil() as usize).min(r.accel_m_s2().len());
            let mut above = false;
            let mut rises = 0u64;
            for &a in &r.accel_m_s2()[..last] {
                let now = a.abs() > limit;
                rises += u64::from(now && !above);
                above = now;
            }
            rises as f64
        }
    }
}

impl Estimate {
    /// Why this run is large, if it is: one line per reason.
    pub fn large(&self) -> Vec<String> {
        let mut why = Vec::new();
        if self.events > LARGE_EVENTS {
            why.push(format!(
                "about {:.1e} events ({:.0} episodes of sliding x {} joints that can slip)",
                self.events, self.slip_episodes, self.joints_that_can_slip
            ));
        }
        let block_steps = self.steps * self.blocks as f64;
        if self.rotating && block_steps > LARGE_ROTATING_STEP_BLOCKS {
            why.push(format!(
                "{:.1e} time steps of {} blocks, each with its rotation (a contact problem over \
                 the whole wall per step: minutes from 1e7 block-steps)",
                self.steps, self.blocks
            ));
        } else if block_steps > LARGE_STEP_BLOCKS {
            why.push(format!(
                "{:.1e} time steps of {} blocks",
                self.steps, self.blocks
            ));
        }
        if self.history_bytes > LARGE_HISTORY_BYTES {
            why.push(format!(
                "a history of {:.1e} rows, about {:.1} GB (a larger --output-dt or --no-history \
                 makes it smaller)",
                self.history_rows,
                self.history_bytes / 1e9
            ));
        }
        why
    }
}

impl fmt::Display for Estimate {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        writeln!(
            f,
            "estimate for {} s of {} blocks:",
            self.duration_s, self.blocks
        )?;
        writeln!(
            f,
            "  episodes of sliding  {:.0} (the ground acceleration rising past the weakest mu g)",
            self.slip_episodes
        )?;
        writeln!(
            f,
            "  joints that can slip {} (mu g below the peak ground acceleration)",
            self.joints_that_can_slip
        )?;
        writeln!(
            f,
            "  events (exact)       {:.1e} (a start and a stop per episode and joint; impacts add)",
            self.events
        )?;
        if self.steps > 0.0 {
            let turning = match (self.rotating, self.after_uplift) {
                (_, true) => {
                    " at most (from the first uplift on, every block with its rotation: a contact \
                     problem over the whole wall each)"
                }
                (true, false) => {
                    " (every block with its rotation: a contact problem over the whole wall each)"
                }
                (false, false) => "",
            };
            writeln!(f, "  time steps           {:.1e}{turning}", self.steps)?;
        }
        if self.history_rows > 0.0 {
            writeln!(
                f,
                "  history              {:.1e} rows, {:.2e} bytes",
                self.history_rows, self.history_bytes
            )?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::Sine;

    fn paper_wall() -> Model {
        Model::from_file("walls/five-block-uniform.ron").unwrap()
    }

    fn sine(amplitude: f64, duration: f64) -> Motion {
        Motion::sine(Sine {
            amplitude_m_s2: amplitude,
            frequency_hz: 1.0,
            phase_rad: 0.0,
            duration_s: duration,
        })
        .unwrap()
    }

    #[test]
    fn a_sine_past_the_friction_limit_starts_two_episodes_a_period() {
        let settings = RunSettings {
            output_dt_s: Some(0.01),
            ..RunSettings::default()
        };
        let e = estimate(&paper_wall(), &sine(4.0, 20.0), &settings);
        assert_eq!(e.slip_episodes, 40.0);
        // B1, B2 on the ground, B3 on B1, B4 on B1 and B2, B5 on B2.
        assert_eq!(e.joints_that_can_slip, 6);
        assert_eq!(e.events, 480.0);
        assert_eq!(e.history_rows, 2001.0 + 480.0);
        assert!(e.large().is_empty());
        // Below mu g = 0.3 x 9.81 nothing slides.
        let still = estimate(&paper_wall(), &sine(2.9, 20.0), &settings);
        assert_eq!((still.slip_episodes, still.events), (0.0, 0.0));
    }

    #[test]
    fn a_long_run_with_a_fine_history_is_called_large() {
        let settings = RunSettings {
            output_dt_s: Some(1e-3),
            method: Method::Moreau { dt_s: 1e-6 },
            ..RunSettings::default()
        };
        let e = estimate(&paper_wall(), &sine(4.0, 1e5), &settings);
        let why = e.large().join("\n");
        assert!(why.contains("time steps") && why.contains("GB"), "{why}");
    }

    /// 3e6 steps of the paper's five blocks: 1.5e7 block-steps, a short run sliding (a few
    /// seconds) and a long one with every block's rotation (minutes).
    #[test]
    fn time_steps_with_rotations_are_large_sooner() {
        let sliding = RunSettings {
            method: Method::Moreau { dt_s: 1e-5 },
            ..RunSettings::default()
        };
        let rotating = RunSettings {
            model: ModelChoice::SlideRock,
            ..sliding.clone()
        };
        let motion = sine(4.0, 30.0);
        let e = estimate(&paper_wall(), &motion, &sliding);
        assert!(!e.rotating && e.large().is_empty(), "{:?}", e.large());
        let e = estimate(&paper_wall(), &motion, &rotating);
        let why = e.large().join("\n");
        assert!(
            e.rotating && why.contains("each with its rotation"),
            "{why}"
        );
        assert!(
            e.to_string().contains("every block with its rotation"),
            "{e}"
        );
    }

    /// After the first uplift the steps turn every block; the uplift may come at once, so the
    /// whole duration's steps are the most it can take, and each history row holds five
    /// numbers a block.
    #[test]
    fn the_steps_after_an_uplift_are_counted_as_at_most_the_whole_run() {
        let settings = RunSettings {
            output_dt_s: Some(0.01),
            after_uplift: AfterUplift::Moreau { dt_s: 1e-5 },
            ..RunSettings::default()
        };
        let e = estimate(&paper_wall(), &sine(2.9, 30.0), &settings);
        assert_eq!(e.steps, 3e6);
        assert!(e.rotating && e.after_uplift);
        assert_eq!(e.history_bytes, 3001.0 * 26.0 * BYTES_PER_NUMBER);
        assert!(e.large().join("\n").contains("each with its rotation"));
        assert!(
            e.to_string().contains("at most (from the first uplift on"),
            "{e}"
        );
    }
}
