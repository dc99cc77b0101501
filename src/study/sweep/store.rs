//! A sweep's files: `cases.csv` (one row per case), `blocks.csv` (one row per case and block),
//! `manifest.json` (what sweep they belong to). Rows are appended and flushed as cases finish, so
//! an interrupted sweep keeps every finished case; a resumed one reads them back and runs the
//! rest. At the end both tables are rewritten in case order.

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
    /// CPU time of the run (s).
    #[serde(serialize_with = "table::sci")]
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
}

/// Columns of `cases.csv`.
pub const CASES_HEADER: &str = "case,wall,motion,amplitude_gal,frequency_hz,record,scale,pga_gal,sample,blocks,max_abs_u_m,max_abs_u_block,residual_u_m,max_rel_u_m,max_opening_m,open_joints,impacts,events,transitions,decision_blocks,flow_nodes,energy_input_j,energy_residual_j,collapsed,collapse_time_s,collapse_block,cpu_s,error";

/// Columns of `blocks.csv`.
pub const BLOCKS_HEADER: &str = "case,block,max_abs_u_m,final_u_m,fell";

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

/// The open files of a running sweep.
pub struct Store {
    dir: PathBuf,
    cases: std::fs::File,
    blocks: std::fs::File,
    /// Rows so far (read back when resuming, then appended).
    pub rows: Vec<CaseRow>,
    /// Block rows so far.
    pub block_rows: Vec<BlockRow>,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> Error + '_ {
    move |source| Error::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn table_error(path: &Path, line: usize, message: String) -> Error {
    Error::Table {
        path: path.to_path_buf(),
        line,
        message,
    }
}

impl Store {
    /// Opens the output directory of `sweep`.
    pub fn open(dir: &Path, sweep: &Sweep, existing: Existing) -> Result<Store, Error> {
        std::fs::create_dir_all(dir).map_err(io(dir))?;
        let (cases_path, blocks_path, manifest_path) = (
            dir.join("cases.csv"),
            dir.join("blocks.csv"),
            dir.join("manifest.json"),
        );
        let mut rows: Vec<CaseRow> = Vec::new();
        let mut block_rows: Vec<BlockRow> = Vec::new();
        if cases_path.exists() {
            match existing {
                Existing::Refuse => {
                    return Err(table_error(
                        &cases_path,
                        1,
                        "results of a sweep are already here: pass --resume to finish it or --fresh to start again".into(),
                    ))
                }
                Existing::Overwrite => {}
                Existing::Resume => {
                    check_manifest(&manifest_path, sweep)?;
                    if !blocks_path.exists() {
                        return Err(table_error(
                            &blocks_path,
                            1,
                            "missing: a sweep resumes from cases.csv and blocks.csv together (the studies in docs/ leave blocks.csv out): pass --fresh to run it again".into(),
                        ));
                    }
                    rows = read_table(&cases_path, CASES_HEADER)?;
                    let done: HashSet<usize> = rows.iter().map(|r| r.case).collect();
                    block_rows = read_table(&blocks_path, BLOCKS_HEADER)?;
                    // Block rows are written before their case row: drop those of unfinished cases.
                    block_rows.retain(|b| done.contains(&b.case));
                }
            }
        }
        let manifest = serde_json::json!({
            "name": sweep.name,
            "fingerprint": sweep.fingerprint,
            "cases": sweep.len(),
            "walls": sweep.walls.iter().map(|w| w.label.clone()).collect::<Vec<_>>(),
            "motions": sweep.motions.len(),
            "samples": sweep.samples(),
        });
        crate::text::write(
            &manifest_path,
            &(serde_json::to_string_pretty(&manifest).expect("json") + "\n"),
        )?;
        let cases = rewrite(&cases_path, CASES_HEADER, &rows)?;
        let blocks = rewrite(&blocks_path, BLOCKS_HEADER, &block_rows)?;
        Ok(Store {
            dir: dir.to_path_buf(),
            cases,
            blocks,
            rows,
            block_rows,
        })
    }

    /// The rows of a sweep in `dir` whose every case is done, in case order, read from
    /// `cases.csv` alone (nothing is run or written): what its charts and `results.json` are
    /// drawn from again after a change to the analysis, with or without `blocks.csv`.
    pub fn finished(dir: &Path, sweep: &Sweep) -> Result<Vec<CaseRow>, Error> {
        check_manifest(&dir.join("manifest.json"), sweep)?;
        let cases_path = dir.join("cases.csv");
        let mut rows: Vec<CaseRow> = read_table(&cases_path, CASES_HEADER)?;
        rows.sort_by_key(|r| r.case);
        if let Some(w) = rows
            .windows(2)
            .find(|w| w[0].case == w[1].case)
            .or_else(|| {
                rows.last()
                    .filter(|r| r.case >= sweep.len())
                    .map(std::slice::from_ref)
            })
        {
            return Err(table_error(
                &cases_path,
                1,
                format!(
                    "case {} is listed twice or is not one of the sweep's {} cases: pass --fresh to run it again",
                    w[w.len() - 1].case,
                    sweep.len()
                ),
            ));
        }
        let done: HashSet<usize> = rows.iter().map(|r| r.case).collect();
        if let Some(first) = (0..sweep.len()).find(|k| !done.contains(k)) {
            return Err(table_error(
                &cases_path,
                1,
                format!(
                    "{} of the sweep's {} cases are not done (the first is case {first}): pass --resume to run them",
                    sweep.len() - done.len(),
                    sweep.len()
                ),
            ));
        }
        Ok(rows)
    }

    /// Cases already finished.
    pub fn done(&self) -> HashSet<usize> {
        self.rows.iter().map(|r| r.case).collect()
    }

    /// Stores a finished case: its block rows first, then the case row that marks it done.
    pub fn append(&mut self, row: CaseRow, blocks: Vec<BlockRow>) -> Result<(), Error> {
        let bpath = self.dir.join("blocks.csv");
        let text: String = blocks.iter().map(table::line).collect();
        self.blocks.write_all(text.as_bytes()).map_err(io(&bpath))?;
        self.blocks.flush().map_err(io(&bpath))?;
        let cpath = self.dir.join("cases.csv");
        self.cases
            .write_all(table::line(&row).as_bytes())
            .map_err(io(&cpath))?;
        self.cases.flush().map_err(io(&cpath))?;
        self.rows.push(row);
        self.block_rows.extend(blocks);
        Ok(())
    }

    /// Rewrites both tables in case order and returns the rows.
    pub fn finish(mut self) -> Result<(Vec<CaseRow>, Vec<BlockRow>), Error> {
        self.rows.sort_by_key(|r| r.case);
        let order: HashMap<usize, usize> = self
            .rows
            .iter()
            .enumerate()
            .map(|(k, r)| (r.case, k))
            .collect();
        self.block_rows.sort_by_key(|b| order[&b.case]);
        rewrite(&self.dir.join("cases.csv"), CASES_HEADER, &self.rows)?;
        rewrite(
            &self.dir.join("blocks.csv"),
            BLOCKS_HEADER,
            &self.block_rows,
        )?;
        Ok((self.rows, self.block_rows))
    }
}

/// Refuses results that another sweep wrote (its manifest's fingerprint differs: the sweep
/// file, a wall or a record changed).
fn check_manifest(path: &Path, sweep: &Sweep) -> Result<(), Error> {
    let manifest = std::fs::read_to_string(path).map_err(io(path))?;
    let found: serde_json::Value =
        serde_json::from_str(&manifest).map_err(|e| table_error(path, e.line(), e.to_string()))?;
    if found["fingerprint"] != sweep.fingerprint.as_str() {
        return Err(table_error(
            path,
            1,
            "these results belong to another sweep (the sweep file, a wall or a record changed): pass --fresh to start again".into(),
        ));
    }
    Ok(())
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
