//! `pirqa bench`: the speed-accuracy study and the failure demonstrations.

use super::write_file;
use pirqa::plot::chart;
use pirqa::study::failures;
use pirqa::study::work_precision::{self, Ladder};
use pirqa::Error;
use std::path::PathBuf;

/// Benchmarks.
#[derive(clap::Subcommand, Debug)]
pub enum BenchCommand {
    /// Error against CPU time of every method on the standard scenarios (CSV and SVG).
    WorkPrecision {
        /// Output directory for work-precision.csv, .svg and work-precision-reach.csv.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// A short ladder (a quick look, not the committed figure).
        #[arg(long)]
        quick: bool,
        /// The El Centro record used by the last scenario.
        #[arg(long, default_value = pirqa::motion::EL_CENTRO)]
        record: PathBuf,
        /// Extra points from a peer engine (CSV with the same columns), drawn on the same chart.
        #[arg(long)]
        peer: Option<PathBuf>,
        /// Redraw the chart and the reach table from a saved work-precision.csv instead of
        /// running the ladder.
        #[arg(long, value_name = "CSV", conflicts_with_all = ["quick", "peer"])]
        from: Option<PathBuf>,
    },
    /// Error against CPU time of the rocking model: the exact engine against Moreau-Jean with
    /// rotations on a free-standing block (CSV and SVG).
    WorkPrecisionRocking {
        /// Output directory for work-precision-rocking.csv, .svg and -reach.csv.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// A short ladder (a quick look, not the committed figure).
        #[arg(long)]
        quick: bool,
        /// The El Centro record of the last scenario.
        #[arg(long, default_value = pirqa::motion::EL_CENTRO)]
        record: PathBuf,
        /// Extra points from a peer engine (CSV with the same columns), drawn on the same chart.
        #[arg(long)]
        peer: Option<PathBuf>,
    },
    /// Error against CPU time of rocking inside walls: the exact column model against
    /// Moreau-Jean with every block's rotation on the columns of walls/rocking/ (CSV and SVG).
    WorkPrecisionRockingWalls {
        /// Output directory for work-precision-rocking-walls.csv, .svg and -reach.csv.
        #[arg(long, default_value = "out")]
        out: PathBuf,
        /// A short ladder (a quick look, not the committed figure).
        #[arg(long)]
        quick: bool,
        /// The El Centro record of the scenarios.
        #[arg(long, default_value = pirqa::motion::EL_CENTRO)]
        record: PathBuf,
    },
    /// Where the time-stepping methods fail (drift, chatter, energy, stiffness, Zeno, grazing):
    /// failures.svg, the data behind it (failures.csv) and the measured numbers (failures.json).
    Failures {
        /// Output directory.
        #[arg(long, default_value = "out")]
        out: PathBuf,
    },
}

/// Writes a speed-accuracy study: its points (`STEM.csv`), its chart (`STEM.svg`) and what each
/// method costs to reach each error level (`STEM-reach.csv`, also printed).
fn write_panel(
    out: &std::path::Path,
    stem: &str,
    points: &[work_precision::Point],
    charts: &[chart::Chart],
) -> Result<(), Error> {
    write_file(
        &out.join(format!("{stem}.csv")),
        &work_precision::csv(points),
    )?;
    write_file(
        &out.join(format!("{stem}.svg")),
        &chart::render(charts, 2, (620, 440)),
    )?;
    let reach = work_precision::reach_csv(points);
    write_file(&out.join(format!("{stem}-reach.csv")), &reach)?;
    print!("{reach}");
    eprintln!(
        "wrote {}/{stem}.csv, {stem}.svg and {stem}-reach.csv",
        out.display()
    );
    Ok(())
}

/// A rocking panel's steps (s) and the least time each run is repeated for (s): a quick look
/// runs each once.
fn ladder<'a>(quick: bool, short: &'a [f64], full: &'a [f64]) -> (&'a [f64], f64) {
    if quick {
        (short, 0.0)
    } else {
        (full, 0.2)
    }
}

pub fn run(cmd: &BenchCommand) -> Result<(), Error> {
    match cmd {
        BenchCommand::WorkPrecision {
            out,
            quick,
            record,
            peer,
            from,
        } => {
            let mut points = Vec::new();
            if let Some(saved) = from {
                points = work_precision::read_csv(saved)?;
            } else {
                let cases = work_precision::standard_cases(record)?;
                let ladder = if *quick {
                    Ladder::quick()
                } else {
                    Ladder::full()
                };
                let min_time = if *quick { 0.0 } else { 0.2 };
                for case in &cases {
                    points.extend(work_precision::run_case(case, &ladder, min_time, |what| {
                        eprintln!("  {what}")
                    })?);
                }
            }
            if let Some(p) = peer {
                points.extend(work_precision::read_csv(p)?);
            }
            let charts = work_precision::charts(&points);
            write_panel(out, "work-precision", &points, &charts)
        }
        BenchCommand::WorkPrecisionRocking {
            out,
            quick,
            record,
            peer,
        } => {
            let (steps, min_time) = ladder(
                *quick,
                &[1e-2, 1e-3],
                &[1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5],
            );
            let mut points = Vec::new();
            for case in &work_precision::rocking_cases(record)? {
                points.extend(work_precision::run_rocking_case(
                    case,
                    steps,
                    min_time,
                    |what| eprintln!("  {what}"),
                )?);
            }
            if let Some(p) = peer {
                points.extend(work_precision::read_csv(p)?);
            }
            let charts = work_precision::rocking_charts(&points);
            write_panel(out, "work-precision-rocking", &points, &charts)
        }
        BenchCommand::WorkPrecisionRockingWalls { out, quick, record } => {
            let (steps, min_time) =
                ladder(*quick, &[1e-3, 2.5e-4], &[1e-3, 3e-4, 1e-4, 3e-5, 1e-5]);
            let mut points = Vec::new();
            for case in &work_precision::rocking_wall_cases(record)? {
                points.extend(work_precision::run_rocking_wall_case(
                    case,
                    steps,
                    min_time,
                    |what| eprintln!("  {what}"),
                )?);
            }
            let mut charts = work_precision::charts(&points);
            for c in &mut charts {
                c.y_label = "max error in a block top's u(t) (m)".into();
            }
            write_panel(out, "work-precision-rocking-walls", &points, &charts)
        }
        BenchCommand::Failures { out } => {
            let demos = failures::all(|what| eprintln!("  {what}"))?;
            let charts: Vec<chart::Chart> = demos.iter().map(|d| d.chart.clone()).collect();
            let measured: serde_json::Map<String, serde_json::Value> = demos
                .iter()
                .flat_map(|d| &d.measured)
                .map(|(k, v)| (k.clone(), serde_json::json!(v)))
                .collect();
            write_file(&out.join("failures.csv"), &chart::to_csv(&charts))?;
            write_file(
                &out.join("failures.svg"),
                &chart::render(&charts, 2, (620, 420)),
            )?;
            let json = serde_json::to_string_pretty(&measured).expect("numbers serialize");
            write_file(&out.join("failures.json"), &format!("{json}\n"))?;
            for (k, v) in demos.iter().flat_map(|d| &d.measured) {
                println!("{k}: {v:e}");
            }
            eprintln!("wrote {}/failures.csv, .svg and .json", out.display());
            Ok(())
        }
    }
}
