//! `pirqa sweep`: run a sweep file with a progress bar, then write its tables, charts and
//! derived numbers.

use super::write_file;
use indicatif::{ProgressBar, ProgressStyle};
use pirqa::study::sweep::analysis::{analyse, Report};
use pirqa::study::sweep::store::{Existing, Store};
use pirqa::study::sweep::Sweep;
use pirqa::Error;
use std::path::{Path, PathBuf};

/// Options of `pirqa sweep`.
#[derive(clap::Args, Debug)]
pub struct SweepArgs {
    /// Sweep description (RON; see docs/sweeps.md).
    pub file: PathBuf,
    /// Output directory: cases.csv, blocks.csv, manifest.json, results.json, charts.
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
    /// Keep the finished cases of an interrupted run of the same sweep and run the rest.
    #[arg(long, conflicts_with = "fresh")]
    pub resume: bool,
    /// Discard results already in the output directory.
    #[arg(long)]
    pub fresh: bool,
    /// Run nothing: draw the charts and results.json again from a finished sweep's cases.csv
    /// (blocks.csv is not needed, and not touched).
    #[arg(long, conflicts_with_all = ["resume", "fresh", "case"])]
    pub redraw: bool,
    /// Worker threads (default: every core).
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    /// Rerun only this case in full detail into OUT/case-N: its wall with the sampled friction
    /// written out (wall.ron), its motion, summary.json, history.csv, events.jsonl, and the
    /// `pirqa run` command that reproduces it.
    #[arg(long, value_name = "N")]
    pub case: Option<usize>,
    /// With --case, leave history.csv out (a row of every block at every event: 2 GB for a
    /// 10,000-block case, and most of its time); `rerun.txt` then says --no-history too.
    #[arg(long, requires = "case")]
    pub no_history: bool,
}

/// A progress bar on the terminal, nothing when output is redirected (indicatif hides itself).
pub fn progress_bar(total: u64, done: u64, what: &str) -> ProgressBar {
    let bar = ProgressBar::new(total);
    bar.set_style(
        ProgressStyle::with_template("{msg} [{bar:40}] {pos}/{len} cases, {per_sec}, eta {eta}")
            .expect("a valid template")
            .progress_chars("=> "),
    );
    bar.set_message(what.to_string());
    bar.set_position(done);
    bar
}

/// Runs a sweep into `out` and writes its report.
pub fn run_sweep(sweep: &Sweep, out: &Path, existing: Existing) -> Result<Report, Error> {
    let mut store = Store::open(out, sweep, existing)?;
    let done = store.done();
    let bar = progress_bar(sweep.len() as u64, done.len() as u64, &sweep.name);
    sweep.run_cases(&done, |row, blocks| {
        bar.inc(1);
        store.append(row, blocks)
    })?;
    bar.finish_and_clear();
    let (rows, _) = store.finish()?;
    let report = analyse(sweep, &rows);
    write_report(&report, out)?;
    Ok(report)
}

/// Writes each figure as SVG with its data as CSV, and results.json.
fn write_report(report: &Report, out: &Path) -> Result<(), Error> {
    for (name, text) in report.files() {
        write_file(&out.join(name), &text)?;
    }
    Ok(())
}

/// One case in full: its files and the command that reruns it.
fn rerun_case(sweep: &Sweep, id: usize, out: &Path, history: bool) -> Result<(), Error> {
    if id >= sweep.len() {
        return Err(Error::Table {
            path: PathBuf::from("--case"),
            line: 0,
            message: format!(
                "case {id} does not exist: the sweep has {} cases",
                sweep.len()
            ),
        });
    }
    let dir = out.join(format!("case-{id}"));
    let (_, m, _) = sweep.case(id);
    let motion = &sweep.motions[m];
    write_file(
        &dir.join("wall.ron"),
        &format!(
            "// Case {id} of the sweep \"{}\": the wall with this case's friction.\n{}\n",
            sweep.name,
            pirqa::wall::to_ron_string(&sweep.case_wall(id))
        ),
    )?;
    let motion_args = match &motion.motion {
        pirqa::motion::Motion::Record(r) => {
            write_file(
                &dir.join("motion.txt"),
                &super::motion::record_text(r, &motion.label),
            )?;
            format!("--record {}/motion.txt", dir.display())
        }
        pirqa::motion::Motion::Sine(s) => format!(
            "--sine {}m/s2 --freq {} --phase {} --duration {}",
            s.amplitude_m_s2,
            s.frequency_hz,
            s.phase_rad.to_degrees(),
            s.duration_s
        ),
        pirqa::motion::Motion::Pulse(p) => {
            format!(
                "--pulse {}m/s2 --pulse-s {}",
                p.amplitude_m_s2, p.duration_s
            )
        }
    };
    let command = format!(
        "pirqa run {}/wall.ron {motion_args} --model slide --duration {} --out {}{}\n",
        dir.display(),
        motion.duration_s,
        dir.display(),
        if history { "" } else { " --no-history" }
    );
    write_file(&dir.join("rerun.txt"), &command)?;
    let (bar, progress) = super::run::simulated_time_bar(motion.duration_s, &format!("case {id}"));
    let r = sweep.run_case_in_full(id, history.then_some(0.01), progress);
    bar.finish_and_clear();
    let r = r?;
    super::run::write_outputs(&dir, &r, &motion.motion)?;
    eprintln!(
        "case {id} ({}, {}) in {}",
        sweep.walls[sweep.case(id).0].label,
        motion.label,
        dir.display()
    );
    Ok(())
}

pub fn run(args: &SweepArgs) -> Result<(), Error> {
    let sweep = Sweep::load(&args.file)?;
    if let Some(id) = args.case {
        return rerun_case(&sweep, id, &args.out, !args.no_history);
    }
    if args.redraw {
        let rows = Store::finished(&args.out, &sweep)?;
        write_report(&analyse(&sweep, &rows), &args.out)?;
        eprintln!(
            "{}: charts and results.json redrawn in {}",
            sweep.name,
            args.out.display()
        );
        return Ok(());
    }
    let existing = if args.resume {
        Existing::Resume
    } else if args.fresh {
        Existing::Overwrite
    } else {
        Existing::Refuse
    };
    let go = || run_sweep(&sweep, &args.out, existing);
    let report = match args.threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n.into())
            .build()
            .expect("a thread pool")
            .install(go)?,
        None => go()?,
    };
    let failed = report.results["failed_runs"].as_u64().unwrap_or(0);
    eprintln!(
        "{}: {} cases in {}{}",
        sweep.name,
        sweep.len(),
        args.out.display(),
        if failed > 0 {
            format!(" ({failed} runs failed: see results.json)")
        } else {
            String::new()
        }
    );
    Ok(())
}
