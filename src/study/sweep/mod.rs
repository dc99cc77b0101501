//! Sweeps: many runs of the exact integrator over walls x motions x friction samples, described
//! in RON, run in parallel, stored as they finish (so an interrupted sweep resumes), and reduced
//! to charts. This module owns the description and the cases; [`store`] the files, [`analysis`]
//! what the rows show.

pub mod analysis;
pub mod batch;
pub mod merge;
pub mod residual;
pub mod shard;
pub mod store;

use crate::clock::ThreadClock;
use crate::error::{Error, MotionError, SimulationError, SweepError};
use crate::exact::Q;
use crate::integrate::baselines::{ContactSolver, HANDED_OFF};
use crate::integrate::rocking::ModelChoice;
use crate::integrate::stepping::steps_fit;
use crate::integrate::{Progress, Scenario, Settings};
use crate::motion::{read_record, Motion, ReadOptions, Sine};
use crate::response::Response;
use crate::response::Summary;
use crate::rng::Rng;
use crate::run::{in_plane_model, run_scenario, AfterStop, AfterUplift, Method, RunSettings};
use crate::topology::Topology;
use crate::units::parse_acceleration;
use crate::wall::{RunningBond, Wall, WallDescription};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};
use store::{BlockRow, CaseRow};

/// Sweep-file format version this pirqa reads.
pub const SWEEP_FORMAT_VERSION: u32 = 1;

/// Sampled friction coefficients are rounded to this step: friction is never known to more
/// digits, and short decimals keep the exact arithmetic of mode decisions cheap.
pub const FRICTION_STEP: f64 = 1e-4;

/// A sweep file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepDescription {
    /// Format version (1).
    pub version: u32,
    /// Name shown on charts.
    pub name: String,
    /// The walls.
    pub walls: Vec<WallSource>,
    /// The motions.
    pub motion: MotionSet,
    /// Friction: the walls' own coefficients, or random samples around them.
    #[serde(default)]
    pub friction: FrictionModel,
    /// The model of the blocks, as `pirqa run --model` (default `Auto`: a case rocks where its
    /// wall is a column the motion can lift, and slides otherwise).
    #[serde(default, skip_serializing_if = "is_auto")]
    pub model: ModelChoice,
    /// The integrator, as `pirqa run --method` (default `Event`, the exact one).
    #[serde(default, skip_serializing_if = "is_event")]
    pub method: SweepMethod,
    /// What answers a case the exact model stops before its end (default `Fail`: the case
    /// fails with the reason).
    #[serde(default, skip_serializing_if = "is_fail")]
    pub fallback: Fallback,
    /// How Moreau-Jean with rotations (the method, or the fallback) solves each step's
    /// contacts, as `pirqa run --contact-solver` (default `GaussSeidel`; `Newton`: the whole
    /// wall at once, docs/rocking-walls.md).
    #[serde(default, skip_serializing_if = "is_gauss_seidel")]
    pub contact_solver: ContactSolver,
    /// Watch each case that slides for the first instant some block must start to turn, as
    /// `pirqa run --check-uplift` (cases.csv's `uplift_*` columns; default false). The exact
    /// sliding engine only: the method at Event and the model Auto or Slide.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub check_uplift: bool,
    /// What follows the first uplift of a case that slides, as `pirqa run --after-uplift`
    /// (default `Slide`; `Moreau(dt_s: S)`: Moreau-Jean with every block's rotation from there,
    /// the case's `model` reading [`AFTER_UPLIFT_MODEL`] where it lifted;
    /// `MoreauWhileRocking(dt_s: S)`: the same until every block is seated again, then exact
    /// sliding again, the `model` reading [`WHILE_ROCKING_MODEL`]). The method at Event and the
    /// model Auto.
    #[serde(default, skip_serializing_if = "is_slide_on")]
    pub after_uplift: AfterUplift,
}

fn is_slide_on(a: &AfterUplift) -> bool {
    *a == AfterUplift::Slide
}

fn is_gauss_seidel(s: &ContactSolver) -> bool {
    *s == ContactSolver::GaussSeidel
}

fn is_fail(f: &Fallback) -> bool {
    *f == Fallback::Fail
}

/// What a sweep does with a case the exact model stops before its end (a held joint of a
/// column gives way, a body takes flight: [`beyond_model`]).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Fallback {
    /// The case fails, its `error` saying where and why the model stopped.
    #[default]
    Fail,
    /// The case is run again, whole, with Moreau-Jean time stepping of every block with its
    /// rotation (`pirqa run --model slide-rock --method moreau --dt DT_S`), and that run answers
    /// it: its `model` column reads [`FALLBACK_MODEL`].
    Moreau {
        /// Time step (s).
        dt_s: f64,
    },
    /// The case runs on the exact model up to where it stops, and Moreau-Jean time stepping of
    /// every block with its rotation goes on from the state there (`pirqa run --after-stop
    /// moreau --dt DT_S`): exact as far as the exact model goes, time stepped beyond; its
    /// `model` column reads [`FROM_STOP_MODEL`].
    MoreauFromStop {
        /// Time step (s).
        dt_s: f64,
    },
}

/// The `model` of a case the fallback answered.
pub const FALLBACK_MODEL: &str = "slide-rock (moreau fallback)";

/// The `model` of a case the exact rocking model followed to where it stops, and Moreau-Jean
/// from there (`fallback: MoreauFromStop(...)`).
pub const FROM_STOP_MODEL: &str = "slide-rock, then moreau from where the exact model stopped";

/// The `model` of a case that slid exactly to its first uplift and was time stepped with
/// rotations from there (`after_uplift: Moreau(...)`).
pub const AFTER_UPLIFT_MODEL: &str = "slide, then slide-rock (moreau after the first uplift)";

/// The `model` of a case that slid exactly while every block was seated and was time stepped
/// with rotations while any rocked (`after_uplift: MoreauWhileRocking(...)`).
pub const WHILE_ROCKING_MODEL: &str = "slide, slide-rock while rocking (moreau)";

/// Why a run ended before its end where the model stops being valid (its warning), if it did:
/// a held joint gave way, a body left the ground.
pub fn beyond_model(s: &Summary) -> Option<String> {
    s.warnings
        .iter()
        .find(|w| w.stops_exact_model())
        .map(ToString::to_string)
}

fn is_auto(m: &ModelChoice) -> bool {
    *m == ModelChoice::Auto
}

fn is_event(m: &SweepMethod) -> bool {
    *m == SweepMethod::Event
}

/// The integrator of a sweep's cases.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum SweepMethod {
    /// The exact event-driven integrator (the sliding engine, or the exact rocking model where
    /// the case rocks).
    #[default]
    Event,
    /// Moreau-Jean time stepping, step `dt_s`: with `model: SlideRock`, every block with its
    /// rotation on any wall (the fallback for walls beyond the exact rocking model).
    Moreau {
        /// Time step (s).
        dt_s: f64,
    },
    /// The paper's Newmark scheme with sgn(v) friction, step `dt_s` (sliding only).
    Paper {
        /// Time step (s).
        dt_s: f64,
    },
}

impl Fallback {
    /// The time step of the fallback's stepping; `None` where cases fail instead.
    fn step_s(self) -> Option<f64> {
        match self {
            Fallback::Fail => None,
            Fallback::Moreau { dt_s } | Fallback::MoreauFromStop { dt_s } => Some(dt_s),
        }
    }
}

impl SweepMethod {
    /// The integrator `pirqa run` takes for it.
    fn method(self) -> Method {
        match self {
            SweepMethod::Event => Method::Event,
            SweepMethod::Moreau { dt_s } => Method::Moreau { dt_s },
            SweepMethod::Paper { dt_s } => Method::Paper { dt_s },
        }
    }

    /// Its options of `pirqa run` (none for the default).
    pub fn run_options(self) -> String {
        match self {
            SweepMethod::Event => String::new(),
            SweepMethod::Moreau { dt_s } => format!(" --method moreau --dt {dt_s}"),
            SweepMethod::Paper { dt_s } => format!(" --method paper --dt {dt_s}"),
        }
    }
}

/// Where a wall comes from.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum WallSource {
    /// A wall file, relative to the sweep file; `friction` replaces every coefficient of the
    /// wall (default: the file's own).
    File {
        /// Path relative to the sweep file.
        path: String,
        /// One coefficient for every joint, replacing the file's.
        #[serde(default)]
        friction: Option<f64>,
        /// Label in tables and charts (default: the file name, and the friction if replaced).
        #[serde(default)]
        label: Option<String>,
    },
    /// A generated running-bond wall.
    RunningBond(RunningBond),
}

/// The motions of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum MotionSet {
    /// Sines: every amplitude at every frequency.
    Sine {
        /// Amplitudes with units (`"300gal"`, `"0.3g"`, `"3m/s2"`).
        amplitudes: Vec<String>,
        /// Frequencies.
        frequencies_hz: Frequencies,
        /// Duration of the sine and of the run (s).
        duration_s: f64,
        /// Phase at t = 0 (degrees, default 0).
        #[serde(default)]
        phase_deg: f64,
    },
    /// Records (paths relative to the sweep file, format detected), each scaled by every factor
    /// in `scales` or to every peak in `pga` (give one of the two).
    Records {
        /// Record files.
        files: Vec<String>,
        /// Scale factors.
        #[serde(default)]
        scales: Vec<f64>,
        /// Target peak accelerations with units.
        #[serde(default)]
        pga: Vec<String>,
    },
}

/// A list of frequencies.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum Frequencies {
    /// These values.
    List(Vec<f64>),
    /// `count` values evenly spaced from `from` to `to`.
    Linear {
        /// First (Hz).
        from: f64,
        /// Last (Hz).
        to: f64,
        /// How many.
        count: usize,
    },
    /// `count` values evenly spaced in log from `from` to `to`.
    Log {
        /// First (Hz).
        from: f64,
        /// Last (Hz).
        to: f64,
        /// How many.
        count: usize,
    },
}

impl Frequencies {
    /// The values (Hz).
    pub fn values(&self) -> Vec<f64> {
        // s runs over [0, 1] in `count` steps; values are rounded to 1 uHz so that labels and
        // the CSV read cleanly.
        let spaced = |count: usize, f: &dyn Fn(f64) -> f64| -> Vec<f64> {
            (0..count)
                .map(|k| {
                    let s = if count > 1 {
                        k as f64 / (count - 1) as f64
                    } else {
                        0.0
                    };
                    (f(s) * 1e6).round() / 1e6
                })
                .collect()
        };
        match *self {
            Frequencies::List(ref v) => v.clone(),
            Frequencies::Linear { from, to, count } => spaced(count, &|s| from + s * (to - from)),
            Frequencies::Log { from, to, count } => {
                spaced(count, &|s| (from.ln() + s * (to.ln() - from.ln())).exp())
            }
        }
    }
}

/// Friction in a sweep.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum FrictionModel {
    /// The walls' own coefficients: one case per wall and motion.
    #[default]
    Nominal,
    /// Each joint's coefficient drawn independently around the wall's own (its mean), `samples`
    /// walls per motion, the same samples at every motion (common random numbers).
    Random {
        /// Normal or lognormal.
        distribution: Distribution,
        /// Coefficient of variation (standard deviation / mean).
        cov: f64,
        /// Samples per wall and motion.
        samples: usize,
        /// Seed: the same seed gives the same samples on any machine.
        seed: u64,
    },
}

/// Distribution of a random friction coefficient.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Distribution {
    /// Normal, truncated to (0, 2] by redrawing.
    Normal,
    /// Lognormal with the given mean and coefficient of variation, truncated to (0, 2].
    Lognormal,
}

/// A wall of a sweep, with its graph.
#[derive(Debug, Clone)]
pub struct SweepWall {
    /// Label in tables and charts.
    pub label: String,
    /// Its description (to write a case's wall back as a file).
    pub description: WallDescription,
    /// The wall.
    pub wall: Wall,
    /// Its graph (nominal friction).
    pub topology: Topology,
}

/// A motion of a sweep.
#[derive(Debug, Clone)]
pub struct SweepMotion {
    /// Label in tables and charts.
    pub label: String,
    /// The motion.
    pub motion: Motion,
    /// Run duration (s).
    pub duration_s: f64,
    /// Sine amplitude (m/s2).
    pub amplitude_m_s2: Option<f64>,
    /// Sine frequency (Hz).
    pub frequency_hz: Option<f64>,
    /// Record label.
    pub record: Option<String>,
    /// Record scale factor.
    pub scale: Option<f64>,
    /// Peak ground acceleration (m/s2).
    pub pga_m_s2: f64,
}

/// A sweep ready to run.
#[derive(Debug, Clone)]
pub struct Sweep {
    /// Name.
    pub name: String,
    /// Walls.
    pub walls: Vec<SweepWall>,
    /// Motions.
    pub motions: Vec<SweepMotion>,
    /// Friction.
    pub friction: FrictionModel,
    /// Hash of the description and of every file it reads: a resumed sweep must match.
    pub fingerprint: String,
    /// The sweep file it was read from (`<string>` for a description given as text).
    pub origin: PathBuf,
    /// The model of the blocks.
    pub model: ModelChoice,
    /// The integrator.
    pub method: SweepMethod,
    /// What answers a case beyond the exact model.
    pub fallback: Fallback,
    /// How Moreau-Jean with rotations solves a step's contacts.
    pub contact_solver: ContactSolver,
    /// Watch the cases that slide for their first uplift.
    pub check_uplift: bool,
    /// What follows the first uplift of a case that slides.
    pub after_uplift: AfterUplift,
}

/// An error of the sweep file `path`.
fn sweep_error(path: &Path, source: SweepError) -> Error {
    Error::Sweep {
        path: path.to_path_buf(),
        source: Box::new(source),
    }
}

/// A rule of the format that `field` breaks, in the sweep file `path`.
fn field(path: &Path, field: &str, rule: String) -> Error {
    sweep_error(
        path,
        SweepError::Field {
            field: field.into(),
            rule,
        },
    )
}

/// The bytes of a file a sweep names (`what`, as written: `path`), relative to `base` (a sweep
/// file's own folder); a file that cannot be read is an error of the sweep `origin`, which
/// says where it was looked for.
fn named_file(
    origin: &Path,
    base: &Path,
    what: &'static str,
    path: &str,
) -> Result<Vec<u8>, Error> {
    let file = base.join(path);
    std::fs::read(&file).map_err(|source| {
        let start = if base.as_os_str().is_empty() {
            Path::new(".")
        } else {
            base
        };
        sweep_error(
            origin,
            SweepError::File {
                what,
                name: path.into(),
                file: file.clone(),
                start: start.to_path_buf(),
                source,
            },
        )
    })
}

/// FNV-1a, 64 bits: a fingerprint that is the same on every machine and version of Rust.
fn fnv(hash: u64, bytes: &[u8]) -> u64 {
    bytes.iter().fold(hash, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// Parses a sweep description (RON).
pub fn parse_description(text: &str) -> Result<SweepDescription, SweepError> {
    ron::Options::default()
        .with_default_extension(
            ron::extensions::Extensions::IMPLICIT_SOME
                | ron::extensions::Extensions::UNWRAP_VARIANT_NEWTYPES,
        )
        .from_str(text)
        .map_err(|e| SweepError::Syntax {
            line: e.span.start.line,
            col: e.span.start.col,
            message: e.code.to_string(),
        })
}

impl SweepDescription {
    /// The description with every path cut to its file name. The fingerprint hashes this and
    /// the bytes of every file read, so results stay with their sweep when the sweep file, its
    /// walls or its records move to another folder, and only the names (which label walls and
    /// records in the results) and contents count.
    fn by_file_name(&self) -> SweepDescription {
        let name = |path: &String| {
            Path::new(path)
                .file_name()
                .map_or_else(|| path.clone(), |n| n.to_string_lossy().into_owned())
        };
        let mut d = self.clone();
        for source in &mut d.walls {
            if let WallSource::File { path, .. } = source {
                *path = name(path);
            }
        }
        if let MotionSet::Records { files, .. } = &mut d.motion {
            files.iter_mut().for_each(|f| *f = name(f));
        }
        d
    }
}

impl Sweep {
    /// Reads a sweep file and everything it names.
    pub fn load(path: &Path) -> Result<Sweep, Error> {
        let text = crate::text::read(path, "sweep")?;
        let d = parse_description(&text).map_err(|source| sweep_error(path, source))?;
        let base = path.parent().unwrap_or(Path::new("."));
        Sweep::from_description(&d, base, path)
    }

    /// Resolves a description whose relative paths start at `base`; `origin` names it in
    /// errors.
    pub fn from_description(
        d: &SweepDescription,
        base: &Path,
        origin: &Path,
    ) -> Result<Sweep, Error> {
        if d.version != SWEEP_FORMAT_VERSION {
            return Err(sweep_error(
                origin,
                SweepError::Version {
                    found: d.version,
                    supported: SWEEP_FORMAT_VERSION,
                },
            ));
        }
        // A sweep of the default model and method hashes the text it had before `model` and
        // `method` came, so that folders written before keep their fingerprint and resume.
        // Fields at their defaults leave the text as it was before they existed, so that
        // sweeps begun then resume.
        let text = format!("{:?}", d.by_file_name());
        let text = text
            .strip_suffix(", after_uplift: Slide }")
            .map_or_else(|| text.clone(), |t| format!("{t} }}"));
        let text = text
            .strip_suffix(", check_uplift: false }")
            .map_or_else(|| text.clone(), |t| format!("{t} }}"));
        let text = text
            .strip_suffix(", contact_solver: GaussSeidel }")
            .map_or_else(|| text.clone(), |t| format!("{t} }}"));
        let text = text
            .strip_suffix(", fallback: Fail }")
            .map_or_else(|| text.clone(), |t| format!("{t} }}"));
        let text = text
            .strip_suffix(", method: Event }")
            .map_or_else(|| text.clone(), |t| format!("{t} }}"));
        let text = text
            .strip_suffix(", model: Auto }")
            .map_or_else(|| text.clone(), |t| format!("{t} }}"));
        match d.method {
            SweepMethod::Moreau { dt_s } | SweepMethod::Paper { dt_s }
                if !(dt_s.is_finite() && dt_s > 0.0) =>
            {
                return Err(field(
                    origin,
                    "method",
                    format!("time step dt_s = {dt_s} s: give a positive step, e.g. 0.001"),
                ));
            }
            _ => {}
        }
        if let Some(dt_s) = d.fallback.step_s() {
            let refused = |why: String| Err(field(origin, "fallback", why));
            if !(dt_s.is_finite() && dt_s > 0.0) {
                return refused(format!(
                    "time step dt_s = {dt_s} s: give a positive step, e.g. 0.0005"
                ));
            }
            if matches!(
                d.method,
                SweepMethod::Moreau { .. } | SweepMethod::Paper { .. }
            ) {
                return refused(
                    "answers cases the exact integrator stops, and the method is a time \
                     stepper: leave fallback out, or method at Event"
                        .into(),
                );
            }
            if d.model == ModelChoice::Slide {
                return refused(
                    "answers cases the exact rocking model stops, and model Slide rocks none: \
                     leave fallback out, or model at Auto or SlideRock"
                        .into(),
                );
            }
        }
        let rotations_stepped = matches!(d.method, SweepMethod::Moreau { .. })
            && d.model == ModelChoice::SlideRock
            || d.fallback.step_s().is_some()
            || d.after_uplift.step_s().is_some();
        if d.contact_solver != ContactSolver::GaussSeidel && !rotations_stepped {
            return Err(field(
                origin,
                "contact_solver",
                "chooses how Moreau-Jean with rotations solves a step's contacts, and no case \
                 runs it: set method to Moreau(dt_s: ...) with model SlideRock (or a Moreau \
                 fallback, or after_uplift), or leave contact_solver out"
                    .into(),
            ));
        }
        if d.check_uplift && (d.method != SweepMethod::Event || d.model == ModelChoice::SlideRock) {
            return Err(field(
                origin,
                "check_uplift",
                "watches the exact sliding engine, and no case runs it: set method to Event \
                 (or leave it out) and model to Auto or Slide, or leave check_uplift out"
                    .into(),
            ));
        }
        if let Some(dt_s) = d.after_uplift.step_s() {
            if !(dt_s.is_finite() && dt_s > 0.0) {
                return Err(field(
                    origin,
                    "after_uplift",
                    format!("time step {dt_s} s: it must be positive and finite"),
                ));
            }
            if d.method != SweepMethod::Event || d.model != ModelChoice::Auto {
                return Err(field(
                    origin,
                    "after_uplift",
                    "hands a case's exact sliding run over at its first uplift, and no case \
                     runs it: set method to Event and model to Auto (or leave them out), or \
                     leave after_uplift out"
                        .into(),
                ));
            }
        }
        let mut hash = fnv(FNV_OFFSET, text.as_bytes());
        let mut walls = Vec::new();
        for source in &d.walls {
            let w = resolve_wall(source, base, origin, &mut hash)?;
            walls.push(w);
        }
        if walls.is_empty() {
            return Err(field(origin, "walls", "empty: name at least one".into()));
        }
        let motions = resolve_motions(&d.motion, base, origin, &mut hash)?;
        // The runs' own rule on a step (`stepping::steps_fit`: within the run, and few enough
        // steps that it ends), asked of the file before any case runs.
        let steps = [
            ("method", d.method.method().step_s()),
            ("fallback", d.fallback.step_s()),
            ("after_uplift", d.after_uplift.step_s()),
        ];
        for (name, dt_s) in steps.iter().filter_map(|&(n, dt)| Some((n, dt?))) {
            for m in &motions {
                steps_fit(dt_s, m.duration_s).map_err(|e| {
                    field(
                        origin,
                        name,
                        format!("{e} (motion {}, a run of {} s)", m.label, m.duration_s),
                    )
                })?;
            }
        }
        if let FrictionModel::Random { cov, samples, .. } = d.friction {
            if !(cov.is_finite() && cov > 0.0 && cov < 1.0) || samples == 0 {
                return Err(field(
                    origin,
                    "friction",
                    format!(
                        "cov {cov} and samples {samples}: cov must be in (0, 1) and samples at \
                         least 1"
                    ),
                ));
            }
        }
        Ok(Sweep {
            name: d.name.clone(),
            walls,
            motions,
            friction: d.friction.clone(),
            fingerprint: format!("{hash:016x}"),
            origin: origin.to_path_buf(),
            model: d.model,
            method: d.method,
            fallback: d.fallback,
            contact_solver: d.contact_solver,
            check_uplift: d.check_uplift,
            after_uplift: d.after_uplift,
        })
    }

    /// Friction samples per wall and motion.
    pub fn samples(&self) -> usize {
        match self.friction {
            FrictionModel::Nominal => 1,
            FrictionModel::Random { samples, .. } => samples,
        }
    }

    /// Number of cases.
    pub fn len(&self) -> usize {
        self.walls.len() * self.motions.len() * self.samples()
    }

    /// True when there is nothing to run (a resolved sweep always has a case).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// (wall, motion, sample) of a case.
    pub fn case(&self, id: usize) -> (usize, usize, usize) {
        let s = self.samples();
        (
            id / (s * self.motions.len()),
            (id / s) % self.motions.len(),
            id % s,
        )
    }

    /// The friction coefficients of a wall's horizontal joints for a sample: nominal, or drawn.
    pub fn frictions(&self, wall: usize, sample: usize) -> Vec<Q> {
        let nominal = self.walls[wall]
            .topology
            .horizontal
            .iter()
            .map(|s| s.friction.clone());
        let FrictionModel::Random {
            distribution,
            cov,
            seed,
            ..
        } = self.friction
        else {
            return nominal.collect();
        };
        // Wall and sample pick the stream: the same sample at every motion.
        let mut rng = Rng::new(seed ^ ((wall as u64) << 40) ^ sample as u64);
        nominal
            .map(|mu| draw(&mut rng, mu.to_f64(), cov, distribution))
            .collect()
    }

    /// The wall of a case as a description: the sampled friction of every joint written out,
    /// so that `pirqa run` on it reruns the case exactly.
    pub fn case_wall(&self, id: usize) -> WallDescription {
        let (w, _, s) = self.case(id);
        let sw = &self.walls[w];
        let mut d = sw.description.clone();
        if let FrictionModel::Random { .. } = self.friction {
            for (sup, mu) in sw.topology.horizontal.iter().zip(self.frictions(w, s)) {
                let key = format!(
                    "{}/{}",
                    sw.wall.blocks[sup.upper.0].name,
                    sw.topology.base_name(&sw.wall, sup.lower)
                );
                d.joint_friction.insert(key, mu.to_f64());
            }
        }
        d
    }

    /// Runs one case in full: the event log, and the history every `output_dt_s` if given,
    /// telling `progress` how far it is.
    pub fn run_case_in_full(
        &self,
        id: usize,
        output_dt_s: Option<f64>,
        progress: Progress,
    ) -> Result<Response, Error> {
        let (w, m, s) = self.case(id);
        let topology = self
            .sampled_topology(w, s)
            .unwrap_or_else(|| self.walls[w].topology.clone());
        let motion = &self.motions[m];
        let settings = Settings {
            duration_s: motion.duration_s,
            output_dt_s,
            history_file: None,
            log_events: true,
            events_file: None,
            decisions_file: None,
            log_decisions: false,
            after_collapse: Default::default(),
            progress: Some(progress),
        };
        Ok(self.integrate(&Scenario {
            wall: &self.walls[w].wall,
            topology: &topology,
            motion: &motion.motion,
            settings: &settings,
        })?)
    }

    /// The model case `id` runs, as `pirqa run --model` names it (`slide` or `slide-rock`),
    /// or why it cannot run.
    pub fn case_model(&self, id: usize) -> Result<&'static str, SimulationError> {
        let (w, m, s) = self.case(id);
        let motion = &self.motions[m];
        let sampled = self.sampled_topology(w, s);
        let settings = Settings::summary_only(motion.duration_s);
        let sc = Scenario {
            wall: &self.walls[w].wall,
            topology: sampled.as_ref().unwrap_or(&self.walls[w].topology),
            motion: &motion.motion,
            settings: &settings,
        };
        let (rocks, _) = in_plane_model(&sc, &self.run_settings())?;
        Ok(if rocks { "slide-rock" } else { "slide" })
    }

    /// Wall `w`'s graph with the friction of sample `s`, when friction is sampled.
    fn sampled_topology(&self, w: usize, s: usize) -> Option<Topology> {
        match self.friction {
            FrictionModel::Nominal => None,
            FrictionModel::Random { .. } => {
                Some(self.walls[w].topology.with_frictions(self.frictions(w, s)))
            }
        }
    }

    /// The choices of `pirqa run` a case takes: the sweep's model and integrator.
    fn run_settings(&self) -> RunSettings {
        RunSettings {
            model: self.model,
            method: self.method.method(),
            contact_solver: self.stepped_solver(self.method),
            ..RunSettings::default()
        }
    }

    /// Runs a case's scenario on the model the sweep asks for: with the fallback from the stop,
    /// handed over to time stepping where the exact model stops (its model
    /// [`FROM_STOP_MODEL`]); with the whole-case fallback, again where the exact model stops
    /// before the end (its model [`FALLBACK_MODEL`], its why naming where the exact run
    /// stopped).
    fn integrate(&self, sc: &Scenario) -> Result<Response, SimulationError> {
        let mut settings = self.run_settings();
        // The check watches the sliding engine: a case that rocks is not checked, nor handed
        // over at an uplift (the exact rocking model follows it).
        let slides = !in_plane_model(sc, &settings)?.0;
        settings.check_uplift = self.check_uplift && slides;
        if slides && self.after_uplift != AfterUplift::Slide {
            settings.after_uplift = self.after_uplift;
            settings.contact_solver = self.contact_solver;
        }
        if let (false, Fallback::MoreauFromStop { dt_s }) = (slides, self.fallback) {
            settings.after_stop = AfterStop::Moreau { dt_s };
            settings.contact_solver = self.contact_solver;
        }
        let mut r = run_scenario(sc, &settings)?;
        if r.summary.method == HANDED_OFF {
            r.summary.model.name = match self.after_uplift {
                _ if !slides => FROM_STOP_MODEL,
                AfterUplift::MoreauWhileRocking { .. } => WHILE_ROCKING_MODEL,
                _ => AFTER_UPLIFT_MODEL,
            }
            .into();
        }
        let (Fallback::Moreau { dt_s }, Some(why)) = (self.fallback, beyond_model(&r.summary))
        else {
            return Ok(r);
        };
        let settings = RunSettings {
            model: ModelChoice::SlideRock,
            method: Method::Moreau { dt_s },
            contact_solver: self.contact_solver,
            ..self.run_settings()
        };
        let mut fallen_back = run_scenario(sc, &settings)?;
        let model = &mut fallen_back.summary.model;
        model.name = FALLBACK_MODEL.into();
        model.why = format!(
            "the sweep's fallback: the exact model stopped ({why}); Moreau-Jean time stepping \
             at dt = {dt_s} s answers the case"
        );
        Ok(fallen_back)
    }

    /// The contact solver of runs on `method`: the sweep's for Moreau-Jean (validation
    /// keeps it at Gauss-Seidel unless those runs rotate blocks), none for the others.
    fn stepped_solver(&self, method: SweepMethod) -> ContactSolver {
        match method {
            SweepMethod::Moreau { .. } => self.contact_solver,
            SweepMethod::Event | SweepMethod::Paper { .. } => ContactSolver::GaussSeidel,
        }
    }

    /// `pirqa run`'s options of `method`, with the contact solver where it is not the default.
    fn method_options(&self, method: SweepMethod) -> String {
        match self.stepped_solver(method) {
            ContactSolver::GaussSeidel => method.run_options(),
            ContactSolver::Newton => format!("{} --contact-solver newton", method.run_options()),
        }
    }

    /// `pirqa run`'s option of the sweep's contact solver, where it is not the default.
    fn solver_option(&self) -> &'static str {
        match self.contact_solver {
            ContactSolver::GaussSeidel => "",
            ContactSolver::Newton => " --contact-solver newton",
        }
    }

    /// `pirqa run`'s options of the model and method case `id` runs on.
    pub fn case_options(&self, id: usize) -> Result<String, SimulationError> {
        let model = self.case_model(id)?;
        if let (Some(dt_s), "slide") = (self.after_uplift.step_s(), model) {
            return Ok(format!(
                "--after-uplift {} --dt {dt_s}{}",
                self.after_uplift.option(),
                self.solver_option()
            ));
        }
        let check = if self.check_uplift && model == "slide" {
            " --check-uplift"
        } else {
            ""
        };
        let after_stop = match (self.fallback, model) {
            (Fallback::MoreauFromStop { dt_s }, "slide-rock") => {
                format!(" --after-stop moreau --dt {dt_s}{}", self.solver_option())
            }
            _ => String::new(),
        };
        Ok(format!(
            "--model {model}{}{check}{after_stop}",
            self.method_options(self.method)
        ))
    }

    /// `pirqa run`'s options of the model and method that answered case `id` in `r`: the
    /// case's own, or the fallback's.
    pub fn answered_by(&self, id: usize, r: &Response) -> Result<String, SimulationError> {
        match self.fallback {
            Fallback::Moreau { dt_s } if r.summary.model.name == FALLBACK_MODEL => Ok(format!(
                "--model slide-rock{}",
                self.method_options(SweepMethod::Moreau { dt_s })
            )),
            _ => self.case_options(id),
        }
    }

    /// Runs one case.
    pub fn run_case(&self, id: usize) -> (CaseRow, Vec<BlockRow>) {
        let (w, m, s) = self.case(id);
        let (wall, motion) = (&self.walls[w], &self.motions[m]);
        let topology = self.sampled_topology(w, s);
        let topo = topology.as_ref().unwrap_or(&wall.topology);
        let settings = Settings::summary_only(motion.duration_s);
        let clock = ThreadClock::start();
        // A panic is a bug; caught, it fails this case instead of the whole sweep.
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            self.integrate(&Scenario {
                wall: &wall.wall,
                topology: topo,
                motion: &motion.motion,
                settings: &settings,
            })
        }))
        .unwrap_or_else(|panic| {
            let message = panic
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "a panic".into());
            Err(SimulationError::Bug(message))
        });
        let cpu_s = clock.seconds();
        let mut row = CaseRow {
            case: id,
            wall: wall.label.clone(),
            motion: motion.label.clone(),
            amplitude_gal: motion.amplitude_m_s2.map(|a| a * 100.0),
            frequency_hz: motion.frequency_hz,
            record: motion.record.clone(),
            scale: motion.scale,
            pga_gal: motion.pga_m_s2 * 100.0,
            sample: s,
            cpu_s,
            ..CaseRow::default()
        };
        match result {
            Ok(r) => {
                fill(&mut row, &r.summary, &wall.wall, topo);
                let blocks = r
                    .summary
                    .blocks
                    .iter()
                    .map(|b| BlockRow {
                        case: id,
                        block: b.name.clone(),
                        max_abs_u_m: b.max_abs_displacement_m,
                        final_u_m: b.final_displacement_m,
                        fell: b.fell,
                        max_abs_rotation_rad: b.max_abs_rotation_rad,
                    })
                    .collect();
                (row, blocks)
            }
            Err(e) => {
                row.error = Some(e.to_string());
                (row, Vec::new())
            }
        }
    }

    /// Runs every case not in `done` in parallel (on the current rayon pool), handing each
    /// result to `sink` as it finishes (on a writer thread, one result at a time); stops early
    /// when `sink` fails.
    pub fn run_cases(
        &self,
        done: &std::collections::HashSet<usize>,
        sink: impl FnMut(CaseRow, Vec<BlockRow>) -> Result<(), Error> + Send,
    ) -> Result<(), Error> {
        let pending: Vec<usize> = (0..self.len()).filter(|i| !done.contains(i)).collect();
        self.run_ids(&pending, sink)
    }

    /// Refuses case ids the sweep does not have.
    pub fn check_ids(&self, ids: &[usize]) -> Result<(), Error> {
        match ids.iter().find(|&&id| id >= self.len()) {
            Some(id) => Err(Error::Option {
                option: "case ids".into(),
                rule: format!(
                    "case {id} does not exist: the sweep has {} cases",
                    self.len()
                ),
            }),
            None => Ok(()),
        }
    }

    /// Runs the cases `ids` as [`Sweep::run_cases`] does.
    pub fn run_ids(
        &self,
        ids: &[usize],
        sink: impl FnMut(CaseRow, Vec<BlockRow>) -> Result<(), Error> + Send,
    ) -> Result<(), Error> {
        self.run_ids_until(ids, &std::sync::atomic::AtomicBool::new(false), sink)
    }

    /// Runs the cases `ids` as [`Sweep::run_ids`] does, starting none once `stop` is set: the
    /// cases already running finish and reach `sink` (a case stopped halfway would be a wrong
    /// row), the rest are left for a resumed sweep.
    pub fn run_ids_until(
        &self,
        ids: &[usize],
        stop: &std::sync::atomic::AtomicBool,
        mut sink: impl FnMut(CaseRow, Vec<BlockRow>) -> Result<(), Error> + Send,
    ) -> Result<(), Error> {
        use std::sync::atomic::{AtomicBool, Ordering};
        self.check_ids(ids)?;
        let failed = AtomicBool::new(false);
        let (tx, rx) = std::sync::mpsc::channel();
        std::thread::scope(|scope| {
            let failed = &failed;
            let writer = scope.spawn(move || {
                for (row, blocks) in rx {
                    if let Err(e) = sink(row, blocks) {
                        failed.store(true, Ordering::Relaxed);
                        return Err(e);
                    }
                }
                Ok(())
            });
            // On the calling thread, so that a pool the caller installed is the one used.
            ids.par_iter().for_each_with(tx, |tx, &id| {
                if !(stop.load(Ordering::Relaxed) || failed.load(Ordering::Relaxed)) {
                    let _ = tx.send(self.run_case(id));
                }
            });
            writer.join().expect("the writer thread does not panic")
        })
    }
}

/// A friction coefficient drawn around `mean` and rounded to [`FRICTION_STEP`], redrawn until it
/// lies in (0, 2].
fn draw(rng: &mut Rng, mean: f64, cov: f64, distribution: Distribution) -> Q {
    let steps = loop {
        let x = match distribution {
            Distribution::Normal => mean * (1.0 + cov * rng.normal()),
            Distribution::Lognormal => {
                let s2 = (1.0 + cov * cov).ln();
                (mean.ln() - 0.5 * s2 + s2.sqrt() * rng.normal()).exp()
            }
        };
        let steps = (x / FRICTION_STEP).round();
        if steps >= 1.0 && steps * FRICTION_STEP <= 2.0 {
            break steps as i128;
        }
    };
    Q::frac(steps, 10_000)
}

fn resolve_wall(
    source: &WallSource,
    base: &Path,
    origin: &Path,
    hash: &mut u64,
) -> Result<SweepWall, Error> {
    match source {
        WallSource::File {
            path,
            friction,
            label,
        } => {
            let file: PathBuf = base.join(path);
            let bytes = named_file(origin, base, "wall", path)?;
            *hash = fnv(*hash, &bytes);
            let text = String::from_utf8(bytes).map_err(|_| Error::Io {
                path: file.clone(),
                source: std::io::Error::new(
                    std::io::ErrorKind::InvalidData,
                    "not a text file (UTF-8 expected)",
                ),
            })?;
            let mut d = crate::wall::parse_description(&text).map_err(|source| Error::Wall {
                path: file.clone(),
                source,
            })?;
            if let Some(mu) = friction {
                d.friction = *mu;
                d.joint_friction.clear();
            }
            let wall = Wall::from_description(&d).map_err(|source| Error::Wall {
                path: file.clone(),
                source,
            })?;
            let topology = Topology::new(&wall).map_err(|source| Error::Wall {
                path: file.clone(),
                source,
            })?;
            let stem = file
                .file_stem()
                .map_or_else(|| path.clone(), |s| s.to_string_lossy().into_owned());
            let label = label.clone().unwrap_or_else(|| match friction {
                Some(mu) => format!("{stem} mu={mu}"),
                None => stem,
            });
            Ok(SweepWall {
                label,
                description: d,
                wall,
                topology,
            })
        }
        WallSource::RunningBond(spec) => {
            let origin = PathBuf::from(format!("<running bond {} blocks>", spec.block_count()));
            let err = |source| Error::Wall {
                path: origin.clone(),
                source,
            };
            let description = spec.description().map_err(err)?;
            let wall = Wall::from_description(&description).map_err(err)?;
            let topology = Topology::new(&wall).map_err(err)?;
            Ok(SweepWall {
                label: format!("running bond {} blocks", spec.block_count()),
                description,
                wall,
                topology,
            })
        }
    }
}

fn resolve_motions(
    set: &MotionSet,
    base: &Path,
    origin: &Path,
    hash: &mut u64,
) -> Result<Vec<SweepMotion>, Error> {
    let mut out = Vec::new();
    let accel =
        |text: &str| parse_acceleration(text).map_err(|e| sweep_error(origin, SweepError::Unit(e)));
    match set {
        MotionSet::Sine {
            amplitudes,
            frequencies_hz,
            duration_s,
            phase_deg,
        } => {
            let freqs = frequencies_hz.values();
            if amplitudes.is_empty() || freqs.is_empty() {
                return Err(field(
                    origin,
                    "Sine",
                    "give at least one amplitude and one frequency".into(),
                ));
            }
            if let Some(f) = freqs.iter().find(|f| !(f.is_finite() && **f > 0.0)) {
                return Err(field(
                    origin,
                    "frequencies_hz",
                    format!(
                        "{frequencies_hz:?} gives {f} Hz: every frequency must be positive and finite (a Log \
                         range needs `from` and `to` above 0)"
                    ),
                ));
            }
            for text in amplitudes {
                let a = accel(text)?;
                for &f in &freqs {
                    let sine = Sine {
                        amplitude_m_s2: a,
                        frequency_hz: f,
                        phase_rad: crate::motion::phase_rad(*phase_deg),
                        duration_s: *duration_s,
                    }
                    .checked()
                    .map_err(|source| Error::Motion {
                        path: origin.to_path_buf(),
                        source,
                    })?;
                    out.push(SweepMotion {
                        label: format!("sine {:.0} gal {f} Hz", a * 100.0),
                        motion: Motion::Sine(sine),
                        duration_s: *duration_s,
                        amplitude_m_s2: Some(a),
                        frequency_hz: Some(f),
                        record: None,
                        scale: None,
                        pga_m_s2: a.abs(),
                    });
                }
            }
        }
        MotionSet::Records { files, scales, pga } => {
            if files.is_empty() || scales.is_empty() == pga.is_empty() {
                return Err(field(
                    origin,
                    "Records",
                    "give at least one file, and either `scales` or `pga` (not both)".into(),
                ));
            }
            let mut targets = Vec::new();
            for text in pga {
                let t = accel(text)?;
                if t <= 0.0 {
                    return Err(field(
                        origin,
                        &format!("pga \"{text}\""),
                        "a target peak must be positive".into(),
                    ));
                }
                targets.push(t);
            }
            for f in files {
                let file = base.join(f);
                let bytes = named_file(origin, base, "record", f)?;
                *hash = fnv(*hash, &bytes);
                let record = read_record(&file, None, &ReadOptions::default())?;
                let peak = record.pga_m_s2();
                if peak == 0.0 {
                    return Err(Error::Motion {
                        path: file,
                        source: MotionError::Parameter {
                            what: "the record".into(),
                            rule: "it is all zeros: there is nothing to scale".into(),
                        },
                    });
                }
                let name = file
                    .file_stem()
                    .map_or_else(|| f.clone(), |s| s.to_string_lossy().into_owned());
                let factors: Vec<f64> = if scales.is_empty() {
                    targets.iter().map(|t| t / peak).collect()
                } else {
                    scales.clone()
                };
                for (k, &factor) in factors.iter().enumerate() {
                    if !(factor.is_finite() && factor > 0.0) {
                        return Err(field(
                            origin,
                            "scales",
                            format!("factor {factor}: it must be positive and finite"),
                        ));
                    }
                    let scaled = record.scaled(factor).map_err(|source| Error::Motion {
                        path: file.clone(),
                        source,
                    })?;
                    let label = if scales.is_empty() {
                        format!("{name} pga {}", pga[k])
                    } else {
                        format!("{name} x{factor}")
                    };
                    out.push(SweepMotion {
                        label,
                        duration_s: scaled.duration_s(),
                        pga_m_s2: scaled.pga_m_s2(),
                        motion: Motion::Record(scaled),
                        amplitude_m_s2: None,
                        frequency_hz: None,
                        record: Some(name.clone()),
                        scale: Some(factor),
                    });
                }
            }
        }
    }
    Ok(out)
}

/// The summary numbers of a case row: maxima over blocks and joints, separations, collapse.
fn fill(row: &mut CaseRow, s: &Summary, wall: &Wall, topo: &Topology) {
    let (k, max) = s
        .blocks
        .iter()
        .enumerate()
        .fold((0, 0.0f64), |(k, m), (i, b)| {
            if b.max_abs_displacement_m > m {
                (i, b.max_abs_displacement_m)
            } else {
                (k, m)
            }
        });
    row.max_abs_u_m = max;
    row.max_abs_u_block = s.blocks.get(k).map_or_else(String::new, |b| b.name.clone());
    row.residual_u_m = s
        .blocks
        .iter()
        .filter(|b| !b.fell)
        .map(|b| b.final_displacement_m.abs())
        .fold(0.0, f64::max);
    row.max_rel_u_m = s
        .horizontal_joints
        .iter()
        .filter(|j| j.lower != "ground")
        .map(|j| j.max_abs_relative_displacement_m)
        .fold(0.0, f64::max);
    // Final opening of each vertical joint: how far its faces moved apart.
    let mut widest = 0.0f64;
    let mut opened = 0;
    for j in &topo.vertical {
        let (l, r) = (&s.blocks[j.left.0], &s.blocks[j.right.0]);
        if l.fell || r.fell {
            continue;
        }
        let opening = r.final_displacement_m - l.final_displacement_m;
        widest = widest.max(opening);
        opened += usize::from(opening > store::OPEN_JOINT_M);
    }
    row.max_opening_m = widest;
    row.open_joints = opened;
    row.impacts = s.impacts;
    row.events = s.stats.events;
    row.transitions = s.stick_slip_transitions;
    row.decision_blocks = s.stats.decision_blocks;
    row.flow_nodes = s.stats.flow_nodes;
    row.energy_input_j = s.energy.input_j;
    row.energy_residual_j = s.energy.residual_j;
    row.blocks = wall.blocks.len();
    if let Some(c) = &s.collapse {
        row.collapsed = true;
        row.collapse_time_s = Some(c.time_s);
        row.collapse_block = Some(c.block.clone());
    }
    row.model = s.model.name.clone();
    row.max_abs_rotation_rad = s
        .blocks
        .iter()
        .map(|b| b.max_abs_rotation_rad)
        .fold(0.0, f64::max);
    // Could a block have rocked? Asked of a sliding answer only.
    row.max_accel_over_tipping = (row.model == "slide").then(|| {
        let peaks: Vec<f64> = s.blocks.iter().map(|b| b.max_abs_accel_m_s2).collect();
        crate::validity::max_accel_over_tipping(wall, &peaks)
    });
    row.max_overlap_loss = s.max_overlap_loss;
    if let Some(check) = &s.uplift_check {
        row.uplift_checked_until_s = Some(check.checked_until_s);
        if let Some(first) = &check.first_uplift {
            row.uplift_time_s = Some(first.time_s);
            row.uplift_turning = Some(first.turning.join("; "));
            row.uplift_mechanism_uniqueness = Some(first.mechanism_uniqueness);
            row.uplift_turning_in_every = (first.turning_in_every_mechanism.as_deref())
                .map(|names| crate::limit::in_every_listed(names, "; "));
        }
    }
    // A run the model stopped before its end (a held joint gave way, a body left the ground)
    // has no answer past that instant: the case says so instead of passing for complete.
    row.error = beyond_model(s);
}
