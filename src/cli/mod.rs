//! The `pirqa` command line: parses arguments (clap) and turns library results into text, JSON,
//! CSV and SVG files. Errors come back to `main` as typed library errors.

mod bench;
mod check;
mod generate;
mod import;
mod motion;
mod overturning;
mod paper;
mod run;
mod sweep;

use clap::error::ErrorKind;
use clap::{CommandFactory, Parser, Subcommand};
use pirqa::topology::sections::Top;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, OnceLock};

/// Exact event-driven dynamics of dry-stone block walls under earthquakes.
#[derive(Parser, Debug)]
#[command(name = "pirqa", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

/// Where a saved run left the wall: `--run DIR`, and `--at T`.
#[derive(clap::Args, Debug)]
struct SavedRun {
    /// The output directory of `pirqa run` on this wall: every block where the run left it (at
    /// its end, from the exact final displacements), fallen blocks apart.
    #[arg(long, value_name = "DIR")]
    run: Option<PathBuf>,
    /// With --run: the state at this time (s), the last history sample at or before it.
    #[arg(
        long,
        value_name = "T",
        requires = "run",
        allow_negative_numbers = true
    )]
    at: Option<f64>,
}

impl SavedRun {
    /// The directory and the time asked, where a run was given.
    fn asked(&self) -> Option<(&std::path::Path, Option<f64>)> {
        self.run.as_deref().map(|dir| (dir, self.at))
    }
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Check a wall file and print its topology: blocks, supports with loads and friction
    /// capacities, vertical joints.
    Check {
        /// Wall description (RON).
        wall: PathBuf,
        /// Print JSON instead of tables.
        #[arg(long)]
        json: bool,
        /// Check the wall across its plane instead: for the part above every bed joint, the
        /// ground acceleration that starts it rocking and its capacity curve lambda(theta).
        #[arg(long, conflicts_with = "run")]
        out_of_plane: bool,
        /// Also find the wall's limit at rest in its plane: the ground acceleration, each way,
        /// beyond which no contact forces hold every block seated, and the mechanism past it
        /// (an exact linear program, walls of up to 2000 movable blocks; under a second on the
        /// shipped walls, seconds at a thousand blocks, a minute or two at two thousand;
        /// Ctrl-C stops it). With --run, of the wall where the run left it, beside the wall's
        /// as built.
        #[arg(long, conflicts_with = "out_of_plane")]
        limit: bool,
        /// With --limit: write the limits (limit.json) and a drawing of each mechanism
        /// (mechanism-plus-x.svg, mechanism-minus-x.svg) into this folder.
        #[arg(long, value_name = "DIR", requires = "limit")]
        mechanism: Option<PathBuf>,
        /// With --out-of-plane: the top free (a cantilever) or held sideways (a one-way
        /// spanning wall).
        #[arg(long, value_enum, default_value_t = Top::Free, requires = "out_of_plane")]
        top: Top,
        /// With --out-of-plane: a load on top of the wall (kN per metre of wall), carried down
        /// without inertia of its own.
        #[arg(
            long,
            value_name = "KN_M",
            requires = "out_of_plane",
            allow_hyphen_values = true
        )]
        overburden_kn_m: Option<f64>,
        /// With --out-of-plane: draw the capacity curves to this SVG (their data beside it, as
        /// CSV).
        #[arg(long, value_name = "FILE", requires = "out_of_plane")]
        plot: Option<PathBuf>,
        /// The wall where a run left it.
        #[command(flatten)]
        moved: SavedRun,
    },
    /// Draw a wall's elevation as SVG with block names and joint friction.
    Draw {
        /// Wall description (RON).
        wall: PathBuf,
        /// Output SVG file.
        #[arg(short, long)]
        output: PathBuf,
        /// Also draw the support graph (block to support) and the vertical joints.
        #[arg(long)]
        graph: bool,
        /// Draw the blocks where a run left them (fallen blocks marked).
        #[command(flatten)]
        moved: SavedRun,
    },
    /// Play a saved run back: one self-contained HTML page with the blocks moving (and
    /// rotating), a time slider, play/pause, a magnification, and the ground acceleration with
    /// the run's events.
    Animate {
        /// The output directory of `pirqa run` (it needs history.csv).
        dir: PathBuf,
        /// Output HTML file.
        #[arg(short, long)]
        output: PathBuf,
        /// The wall file the run was made on (default: DIR/wall.ron, which `pirqa run` writes).
        #[arg(long)]
        wall: Option<PathBuf>,
    },
    /// Simulate a wall under a ground motion with the exact event-driven integrator.
    Run(Box<run::RunArgs>),
    /// Ground motions: measures of a record, synthetic motions.
    #[command(subcommand)]
    Motion(motion::MotionCommand),
    /// Speed and accuracy of the integrators.
    #[command(subcommand)]
    Bench(bench::BenchCommand),
    /// Run a sweep file (walls x motions x friction samples) in parallel: tables, charts,
    /// statistics; resumable.
    Sweep(sweep::SweepArgs),
    /// Reproduce the paper's Fig. 3-6 (and the checks of docs/paper.md).
    Paper(paper::PaperArgs),
    /// The smallest one-sine pulse that overturns a free-standing block, over the pulse's
    /// frequency: exact equations, with friction, and Housner's linearisation.
    Overturning(overturning::OverturningArgs),
    /// Generate a running-bond wall: one overall size cut into any number of blocks.
    Generate(generate::GenerateArgs),
    /// Import a survey of block outlines (CSV) into a wall file, snapping edges within a
    /// tolerance; `pirqa draw --graph` then shows what it made.
    Import(import::ImportArgs),
}

/// Runs the command line.
pub fn run() -> Result<(), pirqa::Error> {
    let cli = Cli::parse();
    match cli.command {
        Command::Check {
            wall,
            json,
            out_of_plane: true,
            top,
            overburden_kn_m,
            plot,
            ..
        } => check::out_of_plane(&wall, json, top, overburden_kn_m, plot.as_deref()),
        Command::Check {
            wall,
            json,
            limit,
            mechanism,
            moved,
            ..
        } => check::check(&wall, json, limit, mechanism.as_deref(), moved.asked()),
        Command::Draw {
            wall,
            output,
            graph,
            moved,
        } => check::draw(&wall, &output, graph, moved.asked()),
        Command::Animate { dir, output, wall } => check::animate(&dir, &output, wall.as_deref()),
        Command::Run(args) => {
            if args.decisions && args.method != run::Method::Event {
                Cli::command()
                    .error(
                        ErrorKind::ArgumentConflict,
                        "--decisions: only the event-driven integrator (--method event) decides \
                         modes; the time-stepping baselines have no decisions to log",
                    )
                    .exit();
            }
            run::run(&args)
        }
        Command::Motion(cmd) => motion::run(&cmd),
        Command::Bench(cmd) => bench::run(&cmd),
        Command::Sweep(args) => sweep::run(&args),
        Command::Paper(args) => paper::run(&args),
        Command::Overturning(args) => overturning::run(&args),
        Command::Generate(args) => generate::run(&args),
        Command::Import(args) => import::run(&args),
    }
}

/// The request to stop, set by the first Ctrl-C (or SIGTERM): a run then ends at the time it
/// reached and writes what it has, flagged (a sweep keeps its finished cases, `check --limit`
/// reports the limit not computed); a second Ctrl-C ends the process at once. The
/// handler is installed at the first call (a command that never asks keeps the default).
pub fn stop_flag() -> Arc<AtomicBool> {
    STOP.get_or_init(|| {
        let flag = Arc::new(AtomicBool::new(false));
        let set = flag.clone();
        // Without a handler (another one installed, an odd platform) Ctrl-C keeps its default:
        // the process ends, and the results written so far stay whole (files are written by
        // rename); nothing is lost by going on.
        let _ = ctrlc::set_handler(move || {
            if set.swap(true, Ordering::SeqCst) {
                std::process::exit(130);
            }
            eprintln!("\nstopping: what was reached is kept (Ctrl-C again to quit at once)");
        });
        flag
    })
    .clone()
}

static STOP: OnceLock<Arc<AtomicBool>> = OnceLock::new();

/// A run was asked to stop through [`stop_flag`]: the process exits with 130, as after a
/// Ctrl-C, once it has written what it has.
pub fn interrupted() -> bool {
    STOP.get().is_some_and(|f| f.load(Ordering::SeqCst))
}

/// Writes a result file whole or not at all, naming it in the error.
pub use pirqa::text::write as write_file;

/// Prints to stdout; a closed pipe (`pirqa check ... | head`) ends the output quietly.
pub fn print_out(text: &str) {
    use std::io::Write;
    let mut out = std::io::stdout().lock();
    let _ = out.write_all(text.as_bytes()).and_then(|()| out.flush());
}
