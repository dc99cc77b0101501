//! A sweep's files: `cases.csv` (one row per case), `blocks.csv` (one row per case and block),
//! `timing.csv` (the CPU time of each case), `manifest.json` (what sweep they belong to). Rows
//! are appended and flushed as cases finish, so an interrupted sweep keeps every finished case;
//! a resumed one reads them back and runs the rest. At the end the tables are rewritten in case
//! order. The results (cases.csv, blocks.csv) hold only what the runs compute, so the same sweep
//! gives the same bytes on any machine, number of threads or shards; what was measured (CPU time)
//! is kept apart in timing.csv.

use super::shard::Shard;
use super::Sweep;
use crate::error::Error;
use crate::table;
use std::collections::{HashMap, HashSet};
use std::io::Write;
use std::path::{Path, PathBuf};

/// A vertical joint counts as opened when its faces end further apart than this (m).
pub const OPEN_JOINT_M: f64 = 1e-3;

/// One case: its inputs and what the run gave (a row of `cases.csv`, its fields the columns).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct CaseRow {
    /// Case number (wall-major, then motion, then sample).
    pub case: usize,
    /// Wall label.
    pub wall: String,
    /// Motion label.
    pub motion: String,
    /// Sine amplitude (gal).
    #[serde(serialize_with = "table::plain_opt")]
    pub amplitude_gal: Option<f64>,
    /// Sine frequency (Hz).
    #[serde(serialize_with = "table::plain_opt")]
    pub frequency_hz: Option<f64>,
    /// Record label.
    pub record: Option<String>,
    /// Record scale factor.
    #[serde(serialize_with = "table::plain_opt")]
    pub scale: Option<f64>,
    /// Peak ground acceleration (gal).
    #[serde(serialize_with = "table::plain")]
    pub pga_gal: f64,
    /// Friction sample (0 for nominal friction).
    pub sample: usize,
    /// Number of blocks.
    pub blocks: usize,
    /// Largest |u| of any block (m).
    #[serde(serialize_with = "table::sci")]
    pub max_abs_u_m: f64,
    /// The block that reached it.
    pub max_abs_u_block: String,
    /// Largest |final u| of a block still standing (m).
    #[serde(serialize_with = "table::sci")]
    pub residual_u_m: f64,
    /// Largest |relative displacement| at a joint between two blocks (m): the ground joints
    /// are the blocks' own u.
    #[serde(serialize_with = "table::sci")]
    pub max_rel_u_m: f64,
    /// Widest final opening of a vertical joint (m).
    #[serde(serialize_with = "table::sci")]
    pub max_opening_m: f64,
    /// Vertical joints that end open by more than [`OPEN_JOINT_M`].
    pub open_joints: usize,
    /// Impacts.
    pub impacts: u64,
    /// Events handled by the integrator.
    pub events: u64,
    /// Stick-slip transitions of the joints.
    pub transitions: u64,
    /// Blocks in the mode decisions, summed over decisions ([`Stats`]).
    ///
    /// [`Stats`]: crate::response::Stats
    pub decision_blocks: u64,
    /// Nodes of the decisions' maximum-flow passes, summed over passes ([`Stats`]).
    ///
    /// [`Stats`]: crate::response::Stats
    pub flow_nodes: u64,
    /// Work of the ground motion on the blocks (J).
    #[serde(serialize_with = "table::sci")]
    pub energy_input_j: f64,
    /// Energy balance residual (J): round-off for the exact integrator, a check on every case.
    #[serde(serialize_with = "table::sci")]
    pub energy_residual_j: f64,
    /// A block fell.
    pub collapsed: bool,
    /// When (s).
    #[serde(serialize_with = "table::plain_opt")]
    pub collapse_time_s: Option<f64>,
    /// Which block.
    pub collapse_block: Option<String>,
    /// The model the case ran (`slide` or `slide-rock`: a sweep's `auto` rocks the cases
    /// whose walls are columns the motion can lift, docs/rocking-walls.md).
    pub model: String,
    /// Largest |rotation| of any block (rad; 0 when it slid).
    #[serde(serialize_with = "table::sci")]
    pub max_abs_rotation_rad: f64,
    /// Largest ratio of a movable block's peak absolute acceleration to the one at which it
    /// would start to tip standing free, g b/h ([`max_accel_over_tipping`]): below 1 no block
    /// could have rocked, so the sliding-only answer needs no rocking model. Empty where the
    /// case ran a model that rocks blocks.
    ///
    /// [`max_accel_over_tipping`]: crate::validity::max_accel_over_tipping
    #[serde(serialize_with = "table::sci_opt")]
    pub max_accel_over_tipping: Option<f64>,
    /// The largest share of a joint's overlap at rest that sliding took away (a block on
    /// another; 0 to 1): the sliding model keeps the loads of the overlaps at rest, so its
    /// answer is one of small displacements while this is small. Empty where the case ran a
    /// model that rocks blocks.
    #[serde(serialize_with = "table::sci_opt")]
    pub max_overlap_loss: Option<f64>,
    /// How far the uplift check watched the case (s; the sweep's `check_uplift`): to its end,
    /// or to where the run stopped. Empty where the case was not checked (the sweep did not
    /// ask, or the case rocked).
    #[serde(serialize_with = "table::plain_opt")]
    pub uplift_checked_until_s: Option<f64>,
    /// The first instant at which no contact forces keep every block seated (s): from there
    /// the sliding answer leaves out rocking the motion causes. Empty where the check found
    /// none (or did not run).
    #[serde(serialize_with = "table::plain_opt")]
    pub uplift_time_s: Option<f64>,
    /// The blocks that would turn then, and how (`; ` between blocks).
    pub uplift_turning: Option<String>,
    /// Whether the first uplift's mechanism is the only one that holds then (`unique`,
    /// `one_of_several` or `undecided`, as the run's summary.json says): where it is not,
    /// `uplift_turning` names one of several ways the wall can start to rock.
    pub uplift_mechanism_uniqueness: Option<crate::limit::Uniqueness>,
    /// The blocks that turn in every mechanism that holds then (`; ` between them; `none`
    /// where no block does, as for twin slabs either of which may turn): the run's
    /// summary.json `turning_in_every_mechanism`. Empty where not decided or no uplift.
    pub uplift_turning_in_every: Option<String>,
    /// CPU time of the run (s): a measurement, kept in timing.csv, not in cases.csv.
    #[serde(skip)]
    pub cpu_s: f64,
    /// Why the run failed, if it did.
    pub error: Option<String>,
}

/// One block of one case (a row of `blocks.csv`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct BlockRow {
    /// Case number.
    pub case: usize,
    /// Block name.
    pub block: String,
    /// Largest |u| (m).
    #[serde(serialize_with = "table::sci")]
    pub max_abs_u_m: f64,
    /// Final u (m).
    #[serde(serialize_with = "table::sci")]
    pub final_u_m: f64,
    /// It fell.
    pub fell: bool,
    /// Largest |rotation| (rad; 0 when the case slid).
    #[serde(serialize_with = "table::sci")]
    pub max_abs_rotation_rad: f64,
}

/// The CPU time of one case (a row of `timing.csv`).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct TimingRow {
    /// Case number.
    pub case: usize,
    /// CPU time of the thread that ran it (s).
    #[serde(serialize_with = "table::sci")]
    pub cpu_s: f64,
}

/// Columns of `cases.csv`.
pub const CASES_HEADER: &str = "case,wall,motion,amplitude_gal,frequency_hz,record,scale,pga_gal,sample,blocks,max_abs_u_m,max_abs_u_block,residual_u_m,max_rel_u_m,max_opening_m,open_joints,impacts,events,transitions,decision_blocks,flow_nodes,energy_input_j,energy_residual_j,collapsed,collapse_time_s,collapse_block,model,max_abs_rotation_rad,max_accel_over_tipping,max_overlap_loss,uplift_checked_until_s,uplift_time_s,uplift_turning,uplift_mechanism_uniqueness,uplift_turning_in_every,error";

/// Columns of `timing.csv`.
pub const TIMING_HEADER: &str = "case,cpu_s";

/// Columns of `blocks.csv`.
pub const BLOCKS_HEADER: &str = "case,block,max_abs_u_m,final_u_m,fell,max_abs_rotation_rad";

/// What to do with results already in the output directory.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Existing {
    /// Refuse to touch them (the default: never overwrite a finished study by accident).
    Refuse,
    /// Keep the finished cases and run the rest (the sweep must be the same).
    Resume,
    /// Start again.
    Overwrite,
}

/// The open files of a running sweep, or of one shard of it.
pub struct Store {
    dir: PathBuf,
    /// The cases this store holds: every case of the sweep, or a shard's.
    scope: Option<Shard>,
    cases: std::fs::File,
    blocks: std::fs::File,
    timing: std::fs::File,
    /// Rows so far (read back when resuming, then appended).
    pub rows: Vec<CaseRow>,
    /// Block rows so far.
    pub block_rows: Vec<BlockRow>,
}

pub(super) fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |source| Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

pub(super) fn table_error(path: &Path, line: usize, message: String) -> Error {
    Error::Table {
        path: path.to_path_buf(),
        line,
        message,
    }
}

/// The manifest of a sweep's files: what sweep they hold (its fingerprint) and, for a shard,
/// which part and the sweep file (so that `pirqa sweep merge` finds it).
pub(super) fn manifest(sweep: &Sweep, shard: Option<Shard>) -> String {
    let mut m = serde_json::json!({
        "name": sweep.name,
        "fingerprint": sweep.fingerprint,
        "cases": sweep.len(),
        "walls": sweep.walls.iter().map(|w| w.label.clone()).collect::<Vec<_>>(),
        "motions": sweep.motions.len(),
        "samples": sweep.samples(),
    });
    if let Some(shard) = shard {
        m["shard"] = serde_json::json!({"index": shard.index, "count": shard.count});
        m["sweep_file"] = serde_json::json!(
            std::path::absolute(&sweep.origin).unwrap_or_else(|_| sweep.origin.clone())
        );
    }
    serde_json::to_string_pretty(&m).expect("json") + "\n"
}

impl Store {
    /// Opens the output directory of `sweep`.
    pub fn open(dir: &Path, sweep: &Sweep, existing: Existing) -> Result<Store, Error> {
        Store::open_scope(dir, sweep, None, existing)
    }

    /// Opens the folder of one shard of `sweep` in the output directory `out`
    /// (`out/parts/I-of-N`).
    pub fn open_shard(
        out: &Path,
        sweep: &Sweep,
        shard: Shard,
        existing: Existing,
    ) -> Result<Store, Error> {
        Store::open_scope(&shard.folder(out), sweep, Some(shard), existing)
    }

    fn open_scope(
        dir: &Path,
        sweep: &Sweep,
        scope: Option<Shard>,
        existing: Existing,
    ) -> Result<Store, Error> {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let paths = Paths::of(dir);
        let mut rows: Vec<CaseRow> = Vec::new();
        let mut block_rows: Vec<BlockRow> = Vec::new();
        if paths.cases.exists() {
            match existing {
                Existing::Refuse => {
                    return Err(table_error(
                        &paths.cases,
                        1,
                        "results of a sweep are already here: pass --resume to finish it or --fresh to start again".into(),
                    ))
                }
                Existing::Overwrite => {}
                Existing::Resume => {
                    check_manifest(&paths.manifest, sweep, scope)?;
                    for (path, what) in [(&paths.blocks, "blocks.csv"), (&paths.timing, "timing.csv")] {
                        if !path.exists() {
                            return Err(table_error(
                                path,
                                1,
                                format!("missing: a sweep resumes from cases.csv and {what} together (the studies in docs/ leave blocks.csv out): pass --fresh to run it again"),
                            ));
                        }
                    }
                    rows = read_cases(&paths)?;
                    let done: HashSet<usize> = rows.iter().map(|r| r.case).collect();
                    block_rows = read_table(&paths.blocks, BLOCKS_HEADER)?;
                    // Block rows are written before their case row: drop those of unfinished cases.
                    block_rows.retain(|b| done.contains(&b.case));
                }
            }
        }
        crate::text::write(&paths.manifest, &manifest(sweep, scope))?;
        let (cases, blocks, timing) = write_tables(&paths, &rows, &block_rows)?;
        Ok(Store {
            dir: dir.to_path_buf(),
            scope,
            cases,
            blocks,
            timing,
            rows,
            block_rows,
        })
    }

    /// The rows of a sweep in `dir` whose every case is done, in case order, read from
    /// `cases.csv` and `timing.csv` (nothing is run or written): what its charts and
    /// `results.json` are drawn from again after a change to the analysis, with or without
    /// `blocks.csv`.
    pub fn finished(dir: &Path, sweep: &Sweep) -> Result<Vec<CaseRow>, Error> {
        let paths = Paths::of(dir);
        if !paths.manifest.exists() {
            return Err(Error::Option {
                option: "--out".into(),
                rule: format!(
                    "{} holds no sweep (no manifest.json): run it there first, `pirqa sweep FILE \
                     --out {}`; charts are drawn again and residual limits found from a \
                     finished one",
                    dir.display(),
                    dir.display()
                ),
            });
        }
        check_manifest(&paths.manifest, sweep, None)?;
        let rows = read_cases(&paths)?;
        check_complete(&paths.cases, rows, sweep, None, "--resume")
    }

    /// The folder it writes.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// Cases already finished.
    pub fn done(&self) -> HashSet<usize> {
        self.rows.iter().map(|r| r.case).collect()
    }

    /// The cases of this store's scope (the sweep, or the shard) not finished yet, in order.
    pub fn pending(&self, sweep: &Sweep) -> Vec<usize> {
        let done = self.done();
        (0..sweep.len())
            .filter(|&id| self.scope.is_none_or(|s| s.contains(id)) && !done.contains(&id))
            .collect()
    }

    /// Stores a finished case: its block rows and its time first, then the case row that marks
    /// it done.
    pub fn append(&mut self, row: CaseRow, blocks: Vec<BlockRow>) -> Result<(), Error> {
        let paths = Paths::of(&self.dir);
        let text: String = blocks.iter().map(table::line).collect();
        append(&mut self.blocks, &paths.blocks, &text)?;
        let timing = TimingRow {
            case: row.case,
            cpu_s: row.cpu_s,
        };
        append(&mut self.timing, &paths.timing, &table::line(&timing))?;
        append(&mut self.cases, &paths.cases, &table::line(&row))?;
        self.rows.push(row);
        self.block_rows.extend(blocks);
        Ok(())
    }

    /// Rewrites the tables in case order and returns the rows.
    pub fn finish(mut self) -> Result<(Vec<CaseRow>, Vec<BlockRow>), Error> {
        sort(&mut self.rows, &mut self.block_rows);
        write_tables(&Paths::of(&self.dir), &self.rows, &self.block_rows)?;
        Ok((self.rows, self.block_rows))
    }
}

/// The files of a sweep (or of a shard) in `dir`.
pub(super) struct Paths {
    pub cases: PathBuf,
    pub blocks: PathBuf,
    pub timing: PathBuf,
    pub manifest: PathBuf,
}

impl Paths {
    pub fn of(dir: &Path) -> Paths {
        Paths {
            cases: dir.join("cases.csv"),
            blocks: dir.join("blocks.csv"),
            timing: dir.join("timing.csv"),
            manifest: dir.join("manifest.json"),
        }
    }
}

fn append(file: &mut std::fs::File, path: &Path, text: &str) -> Result<(), Error> {
    file.write_all(text.as_bytes()).map_err(io(path))?;
    file.flush().map_err(io(path))
}

/// Puts rows in case order, each case's block rows in the order its run gave them.
pub(super) fn sort(rows: &mut [CaseRow], block_rows: &mut [BlockRow]) {
    rows.sort_by_key(|r| r.case);
    let order: HashMap<usize, usize> = rows.iter().enumerate().map(|(k, r)| (r.case, k)).collect();
    block_rows.sort_by_key(|b| order[&b.case]);
}

/// Writes the three tables afresh and returns them open for appending.
pub(super) fn write_tables(
    paths: &Paths,
    rows: &[CaseRow],
    block_rows: &[BlockRow],
) -> Result<(std::fs::File, std::fs::File, std::fs::File), Error> {
    let timing: Vec<TimingRow> = rows
        .iter()
        .map(|r| TimingRow {
            case: r.case,
            cpu_s: r.cpu_s,
        })
        .collect();
    Ok((
        rewrite(&paths.cases, CASES_HEADER, rows)?,
        rewrite(&paths.blocks, BLOCKS_HEADER, block_rows)?,
        rewrite(&paths.timing, TIMING_HEADER, &timing)?,
    ))
}

/// The case rows in `paths`, each with its CPU time from timing.csv.
pub(super) fn read_cases(paths: &Paths) -> Result<Vec<CaseRow>, Error> {
    let mut rows: Vec<CaseRow> = read_table(&paths.cases, CASES_HEADER)?;
    let timing: Vec<TimingRow> = read_table(&paths.timing, TIMING_HEADER)?;
    let cpu: HashMap<usize, f64> = timing.into_iter().map(|t| (t.case, t.cpu_s)).collect();
    for r in &mut rows {
        // The time is written before the case row, so a finished case always has one.
        r.cpu_s = *cpu.get(&r.case).ok_or_else(|| {
            table_error(
                &paths.timing,
                1,
                format!(
                    "case {} of cases.csv has no time here: pass --fresh to run it again",
                    r.case
                ),
            )
        })?;
    }
    Ok(rows)
}

/// `rows` sorted, once each, and every case of `scope` (the sweep, or a shard) among them;
/// the errors name `path` and what to do (`fix`).
pub(super) fn check_complete(
    path: &Path,
    mut rows: Vec<CaseRow>,
    sweep: &Sweep,
    scope: Option<Shard>,
    fix: &str,
) -> Result<Vec<CaseRow>, Error> {
    rows.sort_by_key(|r| r.case);
    let within = |id: usize| id < sweep.len() && scope.is_none_or(|s| s.contains(id));
    let expected = scope.map_or(sweep.len(), |s| s.len(sweep.len()));
    let cases = match scope {
        None => format!("the sweep's {expected} cases"),
        Some(s) => format!("the {expected} cases of shard {s}"),
    };
    if let Some(w) = rows
        .windows(2)
        .find(|w| w[0].case == w[1].case)
        .or_else(|| {
            rows.iter()
                .find(|r| !within(r.case))
                .map(std::slice::from_ref)
        })
    {
        return Err(table_error(
            path,
            1,
            format!(
                "case {} is listed twice or is not one of {cases}: pass --fresh to run it again",
                w[w.len() - 1].case,
            ),
        ));
    }
    let done: HashSet<usize> = rows.iter().map(|r| r.case).collect();
    if let Some(first) = (0..sweep.len()).find(|&k| within(k) && !done.contains(&k)) {
        return Err(table_error(
            path,
            1,
            format!(
                "{} of {cases} are not done (the first is case {first}): pass {fix} to run them",
                expected - done.len(),
            ),
        ));
    }
    Ok(rows)
}

/// Refuses results that another sweep wrote (its manifest's fingerprint differs: the sweep
/// file, a wall or a record changed), or another shard.
pub(super) fn check_manifest(
    path: &Path,
    sweep: &Sweep,
    scope: Option<Shard>,
) -> Result<(), Error> {
    let found = read_manifest(path)?;
    if found["fingerprint"] != sweep.fingerprint.as_str() {
        return Err(table_error(
            path,
            1,
            "these results belong to another sweep (the sweep file, a wall or a record changed): pass --fresh to start again".into(),
        ));
    }
    let shard = |index: usize, count: usize| serde_json::json!({"index": index, "count": count});
    let expected = scope.map(|s| shard(s.index, s.count));
    if found.get("shard") != expected.as_ref() {
        return Err(table_error(
            path,
            1,
            "these results belong to another shard of the sweep (or to the whole sweep): pass --fresh to start again".into(),
        ));
    }
    Ok(())
}

/// A manifest read back.
pub(super) fn read_manifest(path: &Path) -> Result<serde_json::Value, Error> {
    let manifest = std::fs::read_to_string(path).map_err(io(path))?;
    serde_json::from_str(&manifest).map_err(|e| table_error(path, e.line(), e.to_string()))
}

/// Writes a table afresh (through a temporary file, so an interruption never leaves half of
/// it) and returns it open for appending.
fn rewrite<T: serde::Serialize>(
    path: &Path,
    header: &str,
    rows: &[T],
) -> Result<std::fs::File, Error> {
    let mut text = format!("{header}\n");
    text.extend(rows.iter().map(table::line));
    let tmp = path.with_extension("csv.tmp");
    std::fs::write(&tmp, text).map_err(io(&tmp))?;
    std::fs::rename(&tmp, path).map_err(io(path))?;
    std::fs::OpenOptions::new()
        .append(true)
        .open(path)
        .map_err(io(path))
}

/// Reads a table written by a sweep (`header`: its columns), by column name; a last row cut
/// off by an interruption is dropped.
pub fn read_table<T: serde::de::DeserializeOwned>(
    path: &Path,
    header: &str,
) -> Result<Vec<T>, Error> {
    let text = std::fs::read_to_string(path).map_err(io(path))?;
    let columns: Vec<&str> = header.split(',').collect();
    table::read_rows(path, &text, &columns)
}
