//! `pirqa run`: one simulation, written as summary.json, history.csv and events.jsonl (and,
//! when asked, decisions.jsonl).

use super::{print_out, write_file};
use indicatif::{ProgressBar, ProgressStyle};
use pirqa::integrate::baselines::Regularized;
use pirqa::integrate::{AfterCollapse, Progress};
use pirqa::motion::{
    check_scale, process, read_companion, read_record, Baseline, Motion, Processing, Pulse,
    ReadOptions, Sine,
};
use pirqa::plot::{chart, response_charts};
use pirqa::response::{partial_name, DecisionCause, DecisionRecord, Response};
use pirqa::units::{parse_acceleration, AccelUnit};
use pirqa::Error;
use pirqa::{ContactSolver, Direction, Equations, Model, ModelChoice, RunSettings};
use std::collections::BTreeMap;
use std::fmt::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// Ground motion options shared by the commands that run simulations.
#[derive(clap::Args, Debug, Clone)]
pub struct MotionArgs {
    /// Sine amplitude with units: 400gal, 0.41g, 4.0m/s2.
    #[arg(
        long,
        value_name = "AMP",
        conflicts_with = "record",
        requires = "freq",
        allow_hyphen_values = true
    )]
    pub sine: Option<String>,
    /// Sine frequency (Hz).
    #[arg(long, value_name = "HZ", allow_negative_numbers = true)]
    pub freq: Option<f64>,
    /// Sine phase at t = 0 (degrees).
    #[arg(
        long,
        value_name = "DEG",
        default_value_t = 0.0,
        allow_hyphen_values = true
    )]
    pub phase: f64,
    /// Only this many cycles of the sine, then the ground rests (a pulse: one cycle is the
    /// one-sine pulse of the rocking literature); --duration may run past them.
    #[arg(
        long,
        value_name = "N",
        requires = "sine",
        allow_negative_numbers = true
    )]
    pub cycles: Option<f64>,
    /// A rectangular pulse of this amplitude with units (0.3g, 300gal), then the ground rests.
    #[arg(
        long,
        value_name = "AMP",
        conflicts_with_all = ["sine", "record"],
        requires = "pulse_s",
        allow_hyphen_values = true
    )]
    pub pulse: Option<String>,
    /// Duration of the rectangular pulse (s).
    #[arg(
        long,
        value_name = "S",
        requires = "pulse",
        allow_negative_numbers = true
    )]
    pub pulse_s: Option<f64>,
    /// Acceleration record: PEER AT2, K-NET/KiK-net, COSMOS V2, or plain text/CSV.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Record format: at2, knet, cosmos, plain (default: recognised from the content).
    #[arg(long, value_name = "FORMAT", conflicts_with = "sine")]
    pub format: Option<String>,
    /// Component: the column after time in a plain multi-column file (1-based), the channel of
    /// a multi-channel COSMOS file (0-based).
    #[arg(
        long,
        value_name = "N",
        conflicts_with = "sine",
        allow_negative_numbers = true
    )]
    pub component: Option<usize>,
    /// Units of a plain record whose header does not say: gal, g, m/s2.
    #[arg(long, value_name = "UNITS", conflicts_with = "sine")]
    pub units: Option<String>,
    /// Sample interval of a one-column plain record (s).
    #[arg(
        long,
        value_name = "S",
        conflicts_with = "sine",
        allow_negative_numbers = true
    )]
    pub record_dt: Option<f64>,
    /// Keep the record from this time (s).
    #[arg(
        long,
        value_name = "S",
        conflicts_with = "sine",
        allow_negative_numbers = true
    )]
    pub start: Option<f64>,
    /// Keep the record up to this time (s).
    #[arg(
        long,
        value_name = "S",
        conflicts_with = "sine",
        allow_negative_numbers = true
    )]
    pub end: Option<f64>,
    /// Baseline correction of the record.
    #[arg(long, value_enum, default_value_t = Baseline::None, conflicts_with = "sine")]
    pub baseline: Baseline,
    /// Scale the record (or the sine) to this peak: 258gal, 0.3g.
    #[arg(long, value_name = "PGA", allow_hyphen_values = true)]
    pub pga: Option<String>,
    /// Then multiply by this factor (the paper's "amplified by 5"; a negative one reverses the
    /// motion, 0 is refused).
    #[arg(long, value_name = "X", allow_hyphen_values = true)]
    pub scale: Option<f64>,
    /// Vertical component (same time step as the record): every normal load, hence every
    /// friction capacity, is multiplied by 1 + a_v/g. Windowed, corrected and scaled like the
    /// horizontal record.
    #[arg(long, value_name = "FILE", requires = "record")]
    pub vertical: Option<PathBuf>,
    /// Component of the vertical record, as --component is of the horizontal one (a column of
    /// a plain file, a channel of a COSMOS file); --component does not apply to it.
    #[arg(
        long,
        value_name = "N",
        requires = "vertical",
        allow_negative_numbers = true
    )]
    pub vertical_component: Option<usize>,
}

fn bad(option: &str, rule: String) -> Error {
    Error::Option {
        option: option.into(),
        rule,
    }
}

impl MotionArgs {
    /// No ground motion was given.
    pub fn is_empty(&self) -> bool {
        self.sine.is_none() && self.record.is_none() && self.pulse.is_none()
    }
}

/// `--scale` checked, naming the option.
fn scale_factor(k: f64) -> Result<f64, Error> {
    check_scale(k).map_err(|source| Error::Motion {
        path: PathBuf::from("--scale"),
        source,
    })?;
    Ok(k)
}

/// Builds the ground motion described by the options (`duration` is needed for a sine, `g` for
/// a vertical component), with a log of the processing applied.
pub fn build_motion(
    m: &MotionArgs,
    duration: Option<f64>,
    g: f64,
) -> Result<(Motion, Vec<String>), Error> {
    // clap's `requires = "record"` is not enforced beside `--sine` (which conflicts with
    // `--record`), and a vertical component given there would be dropped without a word.
    if m.vertical.is_some() && m.record.is_none() {
        return Err(bad(
            "--vertical",
            "a vertical component goes with --record; a sine or a pulse has none: leave \
             --vertical out"
                .into(),
        ));
    }
    let pga = m.pga.as_deref().map(parse_acceleration).transpose()?;
    // A sine's or a pulse's amplitude: as given, set to --pga, then times --scale.
    let amplitude = |text: &str, notes: &mut Vec<String>| -> Result<f64, Error> {
        let mut a = parse_acceleration(text)?;
        if let Some(p) = pga {
            notes.push(format!("amplitude set to PGA {p} m/s2"));
            a = p;
        }
        if let Some(k) = m.scale {
            notes.push(format!("scaled by {k}"));
            a *= scale_factor(k)?;
        }
        Ok(a)
    };
    if let (Some(amp), Some(length)) = (&m.pulse, m.pulse_s) {
        let mut notes = Vec::new();
        let a = amplitude(amp, &mut notes)?;
        let pulse = Pulse {
            amplitude_m_s2: a,
            duration_s: length,
        }
        .checked()
        .map_err(|source| Error::Motion {
            path: PathBuf::from("--pulse"),
            source,
        })?;
        return Ok((Motion::Pulse(pulse), notes));
    }
    match (&m.sine, &m.record) {
        (Some(amp), None) => {
            let mut notes = Vec::new();
            let a = amplitude(amp, &mut notes)?;
            let freq = m
                .freq
                .ok_or_else(|| bad("--freq", "a sine needs --freq HZ".into()))?;
            let duration = match m.cycles {
                Some(n) if n.is_finite() && n > 0.0 && freq.is_finite() && freq > 0.0 => {
                    notes.push(format!("{n} cycles, then the ground rests"));
                    n / freq
                }
                Some(n) => {
                    return Err(bad(
                        "--cycles",
                        format!("{n} cycles: give a positive number of cycles"),
                    ))
                }
                None => {
                    duration.ok_or_else(|| bad("--duration", "a sine needs --duration S".into()))?
                }
            };
            let sine = Sine {
                amplitude_m_s2: a,
                frequency_hz: freq,
                phase_rad: pirqa::motion::phase_rad(m.phase),
                duration_s: duration,
            }
            .checked()
            .map_err(|source| Error::Motion {
                path: PathBuf::from("--sine"),
                source,
            })?;
            Ok((Motion::Sine(sine), notes))
        }
        (None, Some(path)) => {
            let units = match &m.units {
                Some(u) => Some(AccelUnit::parse(u).ok_or_else(|| {
                    bad(
                        "--units",
                        format!("unknown units \"{u}\": use gal, g or m/s2"),
                    )
                })?),
                None => None,
            };
            let opts = ReadOptions {
                dt_s: m.record_dt,
                units,
                component: m.component,
            };
            let record = read_record(path, m.format.as_deref(), &opts)?;
            let p = Processing {
                start_s: m.start,
                end_s: m.end,
                baseline: m.baseline,
                pga_m_s2: pga,
                scale: m.scale,
            };
            let at = |path: &PathBuf| {
                let path = path.clone();
                move |source| Error::Motion { path, source }
            };
            let (mut processed, mut notes) = process(&record, &p).map_err(at(path))?;
            if let Some(vpath) = &m.vertical {
                // The vertical record gets the same window, correction and overall factor.
                let unscaled = Processing {
                    pga_m_s2: None,
                    scale: None,
                    ..p.clone()
                };
                let (base, _) = process(&record, &unscaled).map_err(at(path))?;
                let factor = if base.pga_m_s2() > 0.0 {
                    processed.pga_m_s2() / base.pga_m_s2()
                } else {
                    1.0
                };
                let same_file =
                    std::fs::canonicalize(vpath).ok() == std::fs::canonicalize(path).ok();
                if same_file && m.vertical_component == m.component {
                    return Err(bad(
                        "--vertical",
                        format!(
                            "{} is also the horizontal record, and the same component of it: pass --component and --vertical-component",
                            vpath.display()
                        ),
                    ));
                }
                let vertical_opts = ReadOptions {
                    component: m.vertical_component,
                    ..opts
                };
                let vertical = read_companion(
                    vpath,
                    m.format.as_deref(),
                    &vertical_opts,
                    "--vertical-component",
                )?;
                let (vertical, _) = process(
                    &vertical,
                    &Processing {
                        scale: Some(factor),
                        ..unscaled
                    },
                )
                .map_err(at(vpath))?;
                processed = processed.with_vertical(&vertical, g).map_err(at(vpath))?;
                notes.push(format!(
                    "vertical component {} (PGA {:.4} m/s2) scales the normal loads by 1 + a_v/g",
                    vpath.display(),
                    vertical.pga_m_s2()
                ));
            }
            Ok((Motion::Record(processed), notes))
        }
        _ => Err(bad(
            "motion",
            "give the ground motion: --sine AMP --freq HZ, --record FILE or --pulse AMP \
             --pulse-s S (or, to release a block from a rotation on still ground, \
             --initial-rotation NAME=RAD with --duration)"
                .into(),
        )),
    }
}

/// Options of `pirqa run`.
#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Wall description (RON).
    pub wall: PathBuf,
    #[command(flatten)]
    pub motion: MotionArgs,
    /// Simulated time (s); default: the sine's duration is required, a record's length.
    #[arg(long, value_name = "S", allow_negative_numbers = true)]
    pub duration: Option<f64>,
    /// Directory for summary.json, history.csv, events.jsonl and wall.ron (the wall run).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Also write decisions.jsonl (event-driven only): every mode decision with what brought
    /// it, the blocks it took in, the stuck groups it took in and formed with their limits, the
    /// nodes of its maximum flows and its CPU time; and print where the decisions' time went.
    #[arg(long, requires = "out")]
    pub decisions: bool,
    /// With --out, leave history.csv out (on a wall of thousands of blocks, writing a row of
    /// every block at every event takes longer than the run); the logs are written as usual.
    #[arg(long, requires = "out", conflicts_with = "output_dt")]
    pub no_history: bool,
    /// Watch the sliding run for the first instant at which no contact forces keep every block
    /// seated (each block's moments balanced inside its joints), and say when and which blocks
    /// would start to turn (summary.json's `uplift_check`); exact sliding engine only, walls of
    /// up to 600 movable blocks.
    #[arg(long)]
    pub check_uplift: bool,
    /// What follows the first instant some block must start to turn, on a wall the sliding
    /// model runs: slide (slide on; with --check-uplift the run says when and which blocks), or
    /// moreau (exact sliding up to that instant, found by the uplift check, then Moreau-Jean
    /// with every block's rotation, step --dt; docs/rocking-walls.md), or moreau-while-rocking
    /// (as moreau until every block is seated and calm again, then exact sliding again, to
    /// the next uplift).
    #[arg(long, value_enum, value_name = "MODEL", default_value_t = AfterUplift::Slide)]
    pub after_uplift: AfterUplift,
    /// What follows where the exact rocking model stops following a wall of columns or a
    /// trilith before the end (a held joint gives way, a body would fly): end (the run ends
    /// there, its warning says where and why), or moreau (Moreau-Jean with every block's
    /// rotation, step --dt, from every block's state there to the end; docs/rocking-walls.md).
    #[arg(long, value_enum, value_name = "MODEL", default_value_t = AfterStop::End)]
    pub after_stop: AfterStop,
    /// Write only the summary, to this file.
    #[arg(long, value_name = "FILE")]
    pub summary: Option<PathBuf>,
    /// Print what the run would cost (episodes of sliding, events, steps, history size) and
    /// stop without running it; a run that is large says so on its own before it starts.
    #[arg(long)]
    pub estimate: bool,
    /// With --out, the history's sampling interval (s); every event time is added.
    #[arg(
        long,
        value_name = "S",
        default_value_t = 0.01,
        requires = "out",
        allow_negative_numbers = true
    )]
    pub output_dt: f64,
    /// What to do when a block falls.
    #[arg(long, value_enum, default_value_t = AfterCollapse::Stop)]
    pub after_collapse: AfterCollapse,
    /// Integrator: the exact event-driven one, or a time-stepping baseline.
    #[arg(long, value_enum, default_value_t = Method::Event)]
    pub method: Method,
    /// Time step of `paper` and `moreau`, and of `--after-uplift moreau` or
    /// `moreau-while-rocking` and `--after-stop moreau` (s).
    #[arg(
        long,
        value_name = "S",
        default_value_t = 1e-3,
        allow_negative_numbers = true
    )]
    pub dt: f64,
    /// Relative tolerance of `regularized`.
    #[arg(long, default_value_t = 1e-6, allow_negative_numbers = true)]
    pub rtol: f64,
    /// Friction regularization velocity of `regularized` (m/s).
    #[arg(long, default_value_t = 1e-4, allow_negative_numbers = true)]
    pub eps: f64,
    /// Penalty contact stiffness of `regularized` (N/m).
    #[arg(long, default_value_t = 1e9, allow_negative_numbers = true)]
    pub stiffness: f64,
    /// Model: blocks that only slide, blocks that may also lift, rock and overturn, or auto
    /// (sliding while no block can lift, rocking from the first uplift). Rocking runs walls of
    /// one free-standing block, and every wall across its plane.
    #[arg(long, value_enum, default_value_t = ModelChoice::Auto)]
    pub model: ModelChoice,
    /// The rocking equations: exact, or Housner's slender-block linearisation (no sliding), for
    /// comparison with the literature.
    #[arg(long, value_enum, value_name = "EQUATIONS")]
    pub rocking: Option<Equations>,
    /// In the wall's plane, or across it (the motion perpendicular to the wall: the part above
    /// each bed joint rocks on it as one body).
    #[arg(long, value_enum, default_value_t = Direction::InPlane)]
    pub direction: Direction,
    /// Start a block (or a section across the plane) from rest at this rotation, NAME=RAD
    /// (positive: on its right corner, or towards the back face); in a wall of one column, a
    /// block of its moving body releases the body; time stepped (--method moreau), any block
    /// with the blocks resting on it alone, turned as one clear of the others; repeatable
    /// across the plane.
    /// Without a ground motion the ground rests for --duration.
    #[arg(long, value_name = "NAME=RAD", value_parser = parse_rotation)]
    pub initial_rotation: Vec<(String, f64)>,
    /// How Moreau-Jean with rotations (--model slide-rock --method moreau) solves each step's
    /// contacts: gauss-seidel (rigid contacts, sweeps) or newton (the whole wall at once, stiff
    /// contacts; many times faster on tall walls; docs/rocking-walls.md).
    #[arg(long, value_enum, default_value_t = ContactSolver::GaussSeidel)]
    pub contact_solver: ContactSolver,
}

fn parse_rotation(text: &str) -> Result<(String, f64), String> {
    let (name, value) = text
        .split_once('=')
        .ok_or_else(|| format!("\"{text}\": write NAME=RAD, e.g. B1=0.05"))?;
    let theta: f64 = value
        .trim()
        .parse()
        .map_err(|_| format!("\"{value}\" is not a number of radians"))?;
    if !theta.is_finite() || theta.abs() >= std::f64::consts::FRAC_PI_2 {
        return Err(format!(
            "{} rad: a rotation must be finite and below pi/2 in size",
            value.trim()
        ));
    }
    Ok((name.trim().to_string(), theta))
}

/// What follows a sliding run's first uplift.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum AfterUplift {
    /// Slide on.
    Slide,
    /// Moreau-Jean with rotations from there.
    Moreau,
    /// Moreau-Jean with rotations from there while any block rocks: exact sliding again once
    /// every block is seated and calm, until the next uplift.
    MoreauWhileRocking,
}

/// What follows where the exact rocking model stops.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum AfterStop {
    /// The run ends there.
    End,
    /// Moreau-Jean with rotations from there.
    Moreau,
}

/// Integrators.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Method {
    /// Exact event-driven.
    Event,
    /// The paper's Newmark scheme with sgn(v) friction.
    Paper,
    /// Moreau-Jean nonsmooth time stepping.
    Moreau,
    /// Regularized friction, penalty contacts, Dormand-Prince 5(4).
    Regularized,
}

impl RunArgs {
    /// The integrator the options ask for.
    pub fn method(&self) -> pirqa::Method {
        match self.method {
            Method::Event => pirqa::Method::Event,
            Method::Paper => pirqa::Method::Paper { dt_s: self.dt },
            Method::Moreau => pirqa::Method::Moreau { dt_s: self.dt },
            Method::Regularized => pirqa::Method::Regularized(Regularized {
                eps: self.eps,
                stiffness: self.stiffness,
                ..Regularized::new(self.rtol)
            }),
        }
    }
}

pub fn run(args: &RunArgs) -> Result<(), Error> {
    let model = Model::from_file(&args.wall)?;
    let wall = model.wall();
    let (motion, notes) = if args.motion.is_empty() && !args.initial_rotation.is_empty() {
        if args.duration.is_none() {
            return Err(bad(
                "--duration",
                "a block released on still ground needs --duration S".into(),
            ));
        }
        (Motion::Pulse(Pulse::rest()), Vec::new())
    } else {
        build_motion(&args.motion, args.duration, wall.g_m_s2.to_f64())?
    };
    let duration = args.duration.unwrap_or_else(|| motion.duration_s());
    let (bar, progress) = simulated_time_bar(duration, &wall.name);
    let history = args.out.as_ref().filter(|_| !args.no_history);
    let mut settings = RunSettings {
        duration_s: Some(duration),
        output_dt_s: history.map(|_| args.output_dt),
        // Straight to disk as the run goes: memory stays bounded however long the history.
        history_file: history.map(|dir| dir.join("history.csv")),
        log_events: args.out.is_some(),
        events_file: args.out.as_ref().map(|dir| dir.join("events.jsonl")),
        decisions_file: args
            .out
            .as_ref()
            .filter(|_| args.decisions)
            .map(|dir| dir.join("decisions.jsonl")),
        log_decisions: args.decisions,
        after_collapse: args.after_collapse,
        method: args.method(),
        model: args.model,
        rocking: args.rocking,
        direction: args.direction,
        initial_rotation: args.initial_rotation.clone(),
        contact_solver: args.contact_solver,
        progress: None,
        check_uplift: args.check_uplift,
        after_uplift: match args.after_uplift {
            AfterUplift::Slide => pirqa::AfterUplift::Slide,
            AfterUplift::Moreau => pirqa::AfterUplift::Moreau { dt_s: args.dt },
            AfterUplift::MoreauWhileRocking => {
                pirqa::AfterUplift::MoreauWhileRocking { dt_s: args.dt }
            }
        },
        after_stop: match args.after_stop {
            AfterStop::End => pirqa::AfterStop::End,
            AfterStop::Moreau => pirqa::AfterStop::Moreau { dt_s: args.dt },
        },
    };
    // Settings the run would refuse are refused before the estimate speaks of them.
    settings.validate()?;
    let cost = pirqa::estimate(&model, &motion, &settings);
    if args.estimate {
        print_out(&cost.to_string());
        return Ok(());
    }
    for why in cost.large() {
        eprintln!(
            "note: a large run: {why}; it shows its progress and stops at Ctrl-C with what it has"
        );
    }
    let partials: Vec<PathBuf> = args.out.as_ref().map_or_else(Vec::new, |dir| {
        ["history.csv", "events.jsonl", "decisions.jsonl"]
            .map(|name| partial_name(&dir.join(name)))
            .to_vec()
    });
    if let Some(dir) = &args.out {
        // The folder holds one run's files: an older run's would pass for this one's while it
        // runs, and after it if it fails.
        for name in RUN_FILES {
            write_or_remove(&dir.join(name), None)?;
        }
        for partial in &partials {
            write_or_remove(partial, None)?;
        }
    }
    settings.progress = Some(progress);
    let response = pirqa::run(&model, &motion, &settings);
    bar.finish_and_clear();
    let mut response = response.map_err(|e| match e {
        // A run that failed part-way keeps what it wrote as it went.
        Error::Simulation(source) => {
            let kept: Vec<PathBuf> = partials.into_iter().filter(|p| p.exists()).collect();
            if kept.is_empty() {
                Error::Simulation(source)
            } else {
                Error::Stopped { source, kept }
            }
        }
        other => other,
    })?;
    response.summary.motion_processing = notes;
    if let Some(dir) = &args.out {
        // The wall beside its run, so that the folder alone draws and plays it again
        // (`pirqa animate DIR`).
        let text = pirqa::text::read(&args.wall, "wall")?;
        write_file(&dir.join("wall.ron"), &text)?;
        write_outputs(dir, &response, &motion)?;
    }
    if let Some(path) = &args.summary {
        write_file(path, &response.summary_json())?;
    }
    print_out(&terminal_summary(&response, args.out.as_deref()));
    if args.decisions {
        print_out(&decision_table(&response.decisions));
    }
    Ok(())
}

/// The files `pirqa run --out DIR` writes, the summary first (it goes last, and an older one
/// first), but for `wall.ron`: a case's folder is rerun from the copy it holds.
const RUN_FILES: [&str; 6] = [
    "summary.json",
    "events.jsonl",
    "decisions.jsonl",
    "history.csv",
    "response.svg",
    "response.csv",
];

/// Writes a run's files into `dir`; with a history, also its chart (`response.svg`) and the
/// data it draws (`response.csv`); the summary last.
pub fn write_outputs(dir: &Path, r: &Response, motion: &Motion) -> Result<(), Error> {
    // summary.json goes last, an older run's first: where it is, every file of its run is
    // there whole (a disk that fills up part-way leaves no summary).
    let summary = dir.join("summary.json");
    write_or_remove(&summary, None)?;
    write_file(&dir.join("events.jsonl"), &r.events_jsonl())?;
    let decisions = (!r.decisions.is_empty()).then(|| r.decisions_jsonl());
    write_or_remove(&dir.join("decisions.jsonl"), decisions)?;
    match &r.history_file {
        // Written as the run went; only a failure is left to report.
        Some(file) => {
            if let Some((kind, message)) = &file.failed {
                return Err(Error::Io {
                    path: file.path.clone(),
                    source: std::io::Error::new(*kind, message.clone()),
                });
            }
        }
        None => write_or_remove(&dir.join("history.csv"), r.history_csv())?,
    }
    let charts = response_charts(r, motion)?;
    write_or_remove(
        &dir.join("response.svg"),
        charts.as_ref().map(|c| chart::render(c, 1, (900, 300))),
    )?;
    write_or_remove(
        &dir.join("response.csv"),
        charts.as_deref().map(chart::to_csv),
    )?;
    write_file(&summary, &r.summary_json())
}

/// Writes `text` to `path`, or removes a file an earlier run left there: a directory holds one
/// run's files, and an older log or history would pass for this run's.
fn write_or_remove(path: &Path, text: Option<String>) -> Result<(), Error> {
    match text {
        Some(text) => write_file(path, &text),
        None if path.exists() => std::fs::remove_file(path).map_err(|source| Error::Io {
            path: path.to_path_buf(),
            source,
        }),
        None => Ok(()),
    }
}

fn terminal_summary(r: &Response, out: Option<&Path>) -> String {
    let s = &r.summary;
    let mut t = String::new();
    let _ = writeln!(
        t,
        "{} | {} | {} | {} s",
        s.wall, s.method, s.motion, s.duration_s
    );
    if let Some(at) = s.interrupted_at_s {
        let _ = writeln!(
            t,
            "  INTERRUPTED at t = {at} s: every number below is of the motion up to then \
             (summary.json: interrupted_at_s)"
        );
    }
    if let Some(at) = s.stopped_at_s {
        let _ = writeln!(
            t,
            "  STOPPED at t = {at} s, where the exact model stops following the wall (the warning \
             below says why): every number below is of the motion up to then (summary.json: \
             stopped_at_s)"
        );
    }
    let m = &s.model;
    let _ = writeln!(
        t,
        "  model {}{}, {}: {}",
        m.name,
        m.equations
            .as_deref()
            .map_or(String::new(), |e| format!(" ({e} equations)")),
        m.direction,
        m.why
    );
    let rocking = m.name != "slide";
    let width = s
        .blocks
        .iter()
        .map(|b| b.name.len())
        .max()
        .unwrap_or(0)
        .max(8);
    let _ = write!(
        t,
        "  {:<width$} {:>12} {:>12} {:>12}",
        "block", "max|u| m", "final u m", "max|v| m/s"
    );
    if rocking {
        let _ = write!(
            t,
            " {:>14} {:>10} {:>8}",
            "max|theta| rad", "uplift s", "landings"
        );
    }
    t.push('\n');
    for b in &s.blocks {
        let _ = write!(
            t,
            "  {:<width$} {:>12.6} {:>12.6} {:>12.6}",
            b.name, b.max_abs_displacement_m, b.final_displacement_m, b.max_abs_velocity_m_s,
        );
        if rocking {
            let uplift = b.uplift_time_s.map_or("-".into(), |u| format!("{u:.4}"));
            let _ = write!(
                t,
                " {:>14.6} {:>10} {:>8}",
                b.max_abs_rotation_rad, uplift, b.rocking_impacts
            );
        }
        let _ = writeln!(t, "{}", if b.fell { "  fell" } else { "" });
    }
    let _ = writeln!(
        t,
        "  impacts {}, touches {}, stick-slip transitions {}, events {}",
        s.impacts, s.touches, s.stick_slip_transitions, s.stats.events
    );
    match &s.collapse {
        Some(c) => {
            let cause = serde_json::to_value(c.cause).expect("a cause serialises");
            let _ = writeln!(
                t,
                "  COLLAPSE: {} fell at t = {:.6} s ({})",
                c.block,
                c.time_s,
                cause.as_str().unwrap_or_default()
            );
        }
        None => {
            let ended_early = s.stopped_at_s.or(s.interrupted_at_s).is_some();
            let _ = writeln!(
                t,
                "  no collapse{}",
                if ended_early { " up to then" } else { "" }
            );
        }
    }
    if let Some(loss) = s.max_overlap_loss {
        let _ = writeln!(
            t,
            "  overlap lost to sliding: at most {:.1} % of a joint's at rest",
            100.0 * loss
        );
    }
    match &s.worst {
        Some(w) => {
            let _ = writeln!(
                t,
                "  nearest to overturning: {} (max |theta| = {:.4} alpha){}",
                w.block,
                w.rotation_over_alpha,
                if w.overturned { ", overturned" } else { "" }
            );
        }
        None if m.direction == "out-of-plane" => {
            let _ = writeln!(t, "  no section lifted");
        }
        None => {}
    }
    let e = &s.energy;
    let _ = write!(
        t,
        "  energy J: input {:.6e}, friction {:.6e}, impacts {:.6e}, kinetic {:.6e}",
        e.input_j, e.friction_j, e.impact_loss_j, e.kinetic_j
    );
    if rocking {
        let _ = write!(
            t,
            ", potential {:.6e}, initial {:.6e}, fallen {:.6e}",
            e.potential_j, e.initial_j, e.fallen_j
        );
    }
    let _ = writeln!(t, ", residual {:.2e}", e.residual_j);
    if let Some(c) = &s.uplift_check {
        let _ = match &c.first_uplift {
            None => writeln!(
                t,
                "  uplift check: every block stays seated up to t = {} s",
                c.checked_until_s
            ),
            Some(u) => writeln!(
                t,
                "  uplift check: at t = {:.6} s (a_g = {:.4} m/s2) no contact forces keep every \
                 block seated: {}{}",
                u.time_s,
                u.ground_accel_m_s2,
                u.turning.join(", "),
                match (u.mechanism_uniqueness, &u.turning_in_every_mechanism) {
                    (pirqa::limit::Uniqueness::Unique, _) => String::new(),
                    // Not decided for the wall's size alone, whatever its uniqueness (a stopped
                    // run says so).
                    (other, None) => format!(
                        " ({}; which blocks turn in every one is decided for walls of up to {} \
                         movable blocks)",
                        other.which(),
                        pirqa::limit::EVERY_BLOCKS
                    ),
                    (other, Some(every)) => format!(
                        " ({}; turning in every one: {})",
                        other.which(),
                        pirqa::limit::in_every_listed(every, ", ")
                    ),
                }
            ),
        };
    }
    for w in &s.warnings {
        let _ = writeln!(t, "  warning: {w}");
    }
    if let Some(dir) = out {
        let history = r.history.is_some() || r.history_file.is_some();
        let written: Vec<&str> = [
            Some("summary.json"),
            history.then_some("history.csv"),
            history.then_some("response.svg"),
            history.then_some("response.csv"),
            Some("events.jsonl"),
            (!r.decisions.is_empty()).then_some("decisions.jsonl"),
            Some("wall.ron"),
        ]
        .into_iter()
        .flatten()
        .collect();
        let _ = writeln!(t, "  wrote {}/{}", dir.display(), written.join(", "));
    }
    t
}

/// Where the mode decisions' time went: per cause, and per size of what they took in.
fn decision_table(decisions: &[DecisionRecord]) -> String {
    let mut rows: BTreeMap<(DecisionCause, usize), (u64, u64, u64, f64)> = BTreeMap::new();
    for d in decisions {
        // Sizes by decade: 1-9, 10-99, ... blocks.
        let decade = d.blocks.max(1).ilog10() as usize;
        let row = rows.entry((d.cause, decade)).or_default();
        row.0 += 1;
        row.1 += d.blocks as u64;
        row.2 += d.flow_nodes;
        row.3 += d.cpu_s;
    }
    let total_s: f64 = decisions.iter().map(|d| d.cpu_s).sum();
    let mut t = format!(
        "  mode decisions: {}, {:.1} ms of CPU\n  {:<12} {:>14} {:>10} {:>13} {:>13} {:>10} {:>6}\n",
        decisions.len(),
        1e3 * total_s,
        "cause",
        "blocks in",
        "decisions",
        "blocks, sum",
        "flow nodes",
        "CPU ms",
        "share"
    );
    for ((cause, decade), (n, blocks, nodes, cpu_s)) in &rows {
        let name = serde_json::to_value(cause).expect("a cause serialises");
        let sizes = format!(
            "{}-{}",
            10usize.pow(*decade as u32),
            10usize.pow(*decade as u32 + 1) - 1
        );
        let _ = writeln!(
            t,
            "  {:<12} {:>14} {:>10} {:>13} {:>13} {:>10.1} {:>5.1}%",
            name.as_str().unwrap_or_default(),
            sizes,
            n,
            blocks,
            nodes,
            1e3 * cpu_s,
            100.0 * cpu_s / total_s.max(f64::MIN_POSITIVE)
        );
    }
    t
}

/// A bar of simulated time for one long run (hidden, like every bar, when stderr is not a
/// terminal), and the [`Progress`] that moves it.
pub fn simulated_time_bar(duration_s: f64, what: &str) -> (ProgressBar, Progress) {
    let ms = |t: f64| (t * 1000.0).round() as u64;
    let bar = ProgressBar::new(ms(duration_s));
    bar.set_style(
        ProgressStyle::with_template(
            "{msg} [{bar:40}] {percent}% of the simulated time, {elapsed} elapsed, eta {eta}",
        )
        .expect("a valid template")
        .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    let moved = bar.clone();
    // The bar moves by a thousandth of the run at least, either way (a fallback starts again
    // from 0): a record's run reports at each of its samples, and moving the bar costs more
    // than the run does between two of them.
    let step_s = duration_s / 1000.0;
    let shown_s = AtomicU64::new(f64::NEG_INFINITY.to_bits());
    let progress = Progress::new(move |t| {
        if (t - f64::from_bits(shown_s.load(Ordering::Relaxed))).abs() >= step_s {
            shown_s.store(t.to_bits(), Ordering::Relaxed);
            moved.set_position(ms(t));
        }
    })
    .with_stop(super::stop_flag());
    (bar, progress)
}
