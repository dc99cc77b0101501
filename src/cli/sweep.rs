//! `pirqa sweep`: run a sweep file (or one shard of it) with a progress bar, then write its
//! tables, charts and derived numbers; `pirqa sweep merge`: the shards' parts into the files of
//! one sweep.

use super::write_file;
use indicatif::{ProgressBar, ProgressStyle};
use pirqa::study::sweep::analysis::{analyse, Report};
use pirqa::study::sweep::merge;
use pirqa::study::sweep::residual;
use pirqa::study::sweep::shard::{self, Shard};
use pirqa::study::sweep::store::{Existing, Store};
use pirqa::study::sweep::Sweep;
use pirqa::Error;
use std::path::{Path, PathBuf};

/// Options of `pirqa sweep`.
#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true, subcommand_negates_reqs = true)]
pub struct SweepArgs {
    /// Merge the parts of a sharded sweep.
    #[command(subcommand)]
    pub command: Option<SweepCommand>,
    /// Sweep description (RON; see docs/sweeps.md).
    #[arg(required = true)]
    pub file: Option<PathBuf>,
    /// Output directory: cases.csv, blocks.csv, timing.csv, manifest.json, results.json, charts.
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
    /// Run nothing: for every case of a finished sweep, the limit at rest of its wall where its
    /// run left it (blocks.csv's final displacements; fallen blocks taken out) beside the
    /// wall's as built, into residual.csv, and the share left against the peak acceleration
    /// (capacity-left.svg).
    #[arg(long, conflicts_with_all = ["resume", "fresh", "case", "redraw", "shard"])]
    pub residual: bool,
    /// Worker threads (default: every core).
    #[arg(long, value_parser = clap::value_parser!(u16).range(1..))]
    pub threads: Option<u16>,
    /// Rerun only this case in full detail into OUT/case-N: its wall with the sampled friction
    /// written out (wall.ron), its motion, summary.json, history.csv, events.jsonl, and the
    /// `pirqa run` command that reproduces it.
    #[arg(long, value_name = "N", allow_negative_numbers = true)]
    pub case: Option<usize>,
    /// With --case, leave history.csv out (a row of every block at every event: 2 GB for a
    /// 10,000-block case, and most of its time); `rerun.txt` then says --no-history too.
    #[arg(long, requires = "case")]
    pub no_history: bool,
    /// Run only part I of N (from 0; case k is in part k mod N) into OUT/parts/I-of-N, for a
    /// job array: `auto` reads the part from Slurm's SLURM_ARRAY_TASK_* variables. Merge the
    /// parts with `pirqa sweep merge OUT`.
    #[arg(long, value_name = "I/N|auto", conflicts_with_all = ["redraw", "case"])]
    pub shard: Option<String>,
}

/// What `pirqa sweep` does besides running a sweep.
#[derive(clap::Subcommand, Debug)]
pub enum SweepCommand {
    /// Merge the parts that `pirqa sweep FILE --shard I/N --out DIR` wrote into DIR/parts: checks
    /// that every part is there and finished and that all come from one sweep, then writes the
    /// files a sweep on one machine writes (byte for byte the same results) and its charts.
    Merge {
        /// The output directory the shards wrote into.
        dir: PathBuf,
        /// The sweep file, when it is no longer where the shards read it.
        #[arg(long)]
        sweep: Option<PathBuf>,
    },
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
    report.write(out)?;
    Ok(report)
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
            "--sine {}m/s2 --freq {} --phase {}",
            s.amplitude_m_s2,
            s.frequency_hz,
            s.phase_rad.to_degrees(),
        ),
        pirqa::motion::Motion::Pulse(p) => {
            format!(
                "--pulse {}m/s2 --pulse-s {}",
                p.amplitude_m_s2, p.duration_s
            )
        }
    };
    let command = |options: &str| {
        format!(
            "pirqa run {}/wall.ron {motion_args} {options} --duration {} --out {}{}\n",
            dir.display(),
            motion.duration_s,
            dir.display(),
            if history { "" } else { " --no-history" }
        )
    };
    let asked = sweep.case_options(id)?;
    write_file(&dir.join("rerun.txt"), &command(&asked))?;
    let (bar, progress) = super::run::simulated_time_bar(motion.duration_s, &format!("case {id}"));
    let r = sweep.run_case_in_full(id, history.then_some(0.01), progress);
    bar.finish_and_clear();
    let r = r?;
    // A case the fallback answered reruns with the fallback's options.
    let answered = sweep.answered_by(id, &r)?;
    if answered != asked {
        write_file(&dir.join("rerun.txt"), &command(&answered))?;
    }
    super::run::write_outputs(&dir, &r, &motion.motion)?;
    eprintln!(
        "case {id} ({}, {}) in {}",
        sweep.walls[sweep.case(id).0].label,
        motion.label,
        dir.display()
    );
    Ok(())
}

/// Runs `go` on a pool of `threads` threads (default: rayon's, one per core).
fn in_pool<T: Send>(threads: Option<u16>, go: impl FnOnce() -> T + Send) -> T {
    match threads {
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n.into())
            .build()
            .expect("a thread pool")
            .install(go),
        None => go(),
    }
}

/// Runs one shard of a sweep into its part folder.
fn run_shard(sweep: &Sweep, shard: Shard, out: &Path, existing: Existing) -> Result<(), Error> {
    let mut store = Store::open_shard(out, sweep, shard, existing)?;
    let pending = store.pending(sweep);
    let total = shard.len(sweep.len()) as u64;
    let bar = progress_bar(
        total,
        total - pending.len() as u64,
        &format!("{} part {shard}", sweep.name),
    );
    sweep.run_ids(&pending, |row, blocks| {
        bar.inc(1);
        store.append(row, blocks)
    })?;
    bar.finish_and_clear();
    store.finish()?;
    eprintln!(
        "{}: part {shard} ({total} cases) in {}; merge the parts with `pirqa sweep merge {}`",
        sweep.name,
        shard.folder(out).display(),
        out.display()
    );
    Ok(())
}

/// Merges the parts in `dir` and writes the sweep's report.
fn merge_parts(dir: &Path, sweep_file: Option<&Path>) -> Result<(), Error> {
    let merged = merge::merge(dir, sweep_file)?;
    analyse(&merged.sweep, &merged.rows).write(dir)?;
    eprintln!(
        "{}: {} cases merged from {} into {}",
        merged.sweep.name,
        merged.rows.len(),
        shard::parts(dir).display(),
        dir.display()
    );
    Ok(())
}

pub fn run(args: &SweepArgs) -> Result<(), Error> {
    if let Some(SweepCommand::Merge { dir, sweep }) = &args.command {
        return merge_parts(dir, sweep.as_deref());
    }
    let file = args
        .file
        .as_deref()
        .expect("clap requires the file without a subcommand");
    let sweep = Sweep::load(file)?;
    if let Some(id) = args.case {
        return rerun_case(&sweep, id, &args.out, !args.no_history);
    }
    if args.redraw {
        let rows = Store::finished(&args.out, &sweep)?;
        analyse(&sweep, &rows).write(&args.out)?;
        eprintln!(
            "{}: charts and results.json redrawn in {}",
            sweep.name,
            args.out.display()
        );
        return Ok(());
    }
    if args.residual {
        let rows = Store::finished(&args.out, &sweep)?;
        let bar = progress_bar(rows.len() as u64, 0, "the limit left by each case");
        let stop = super::stop_flag();
        let stop = || stop.load(std::sync::atomic::Ordering::Relaxed);
        let found = in_pool(args.threads, || {
            residual::write(&sweep, &rows, &args.out, &|| bar.inc(1), &stop)
        })?;
        bar.finish_and_clear();
        let failed = found.iter().filter(|r| r.error.is_some()).count();
        eprintln!(
            "{}: the limit at rest left by {} of {} cases in {}{}{}",
            sweep.name,
            found.len(),
            rows.len(),
            args.out.join("residual.csv").display(),
            if found.len() == rows.len() {
                format!(
                    ", charted in {}",
                    args.out.join("capacity-left.svg").display()
                )
            } else {
                " (stopped: the rest not computed, and not charted)".into()
            },
            if failed > 0 {
                format!("; {failed} not computed (residual.csv's error column says why)")
            } else {
                String::new()
            }
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
    if let Some(text) = &args.shard {
        let shard = Shard::parse(text, |name| std::env::var(name).ok())?;
        return in_pool(args.threads, || {
            run_shard(&sweep, shard, &args.out, existing)
        });
    }
    let report = in_pool(args.threads, || run_sweep(&sweep, &args.out, existing))?;
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
