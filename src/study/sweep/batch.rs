//! Batches: cases run away from the store that keeps them (a worker process of Dask, MPI or a
//! process pool, on this machine or another), their rows carried back as plain text, the same
//! CSV lines the store writes, so that a float comes back to the bit and a batch pickles as
//! three strings.

use super::store::{
    BlockRow, CaseRow, Store, TimingRow, BLOCKS_HEADER, CASES_HEADER, TIMING_HEADER,
};
use super::Sweep;
use crate::error::Error;
use crate::table;
use std::collections::HashMap;
use std::path::Path;

/// The rows of some cases as CSV lines without headers: `cases.csv`'s, `blocks.csv`'s and
/// `timing.csv`'s.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Batch {
    /// Case rows.
    pub cases: String,
    /// Block rows.
    pub blocks: String,
    /// CPU times.
    pub timing: String,
}

impl Batch {
    /// The rows of finished cases.
    pub fn of(results: &[(CaseRow, Vec<BlockRow>)]) -> Batch {
        let mut b = Batch::default();
        for (row, blocks) in results {
            b.cases.push_str(&table::line(row));
            b.blocks.extend(blocks.iter().map(table::line));
            b.timing.push_str(&table::line(&TimingRow {
                case: row.case,
                cpu_s: row.cpu_s,
            }));
        }
        b
    }

    /// The rows back, each case with its block rows and CPU time; `from` names the batch in
    /// errors.
    pub fn rows(&self, from: &Path) -> Result<Vec<(CaseRow, Vec<BlockRow>)>, Error> {
        let read = |header: &str, text: &str| format!("{header}\n{text}");
        let columns = |header: &'static str| header.split(',').collect::<Vec<_>>();
        let mut cases: Vec<CaseRow> = table::read_rows(
            from,
            &read(CASES_HEADER, &self.cases),
            &columns(CASES_HEADER),
        )?;
        let blocks: Vec<BlockRow> = table::read_rows(
            from,
            &read(BLOCKS_HEADER, &self.blocks),
            &columns(BLOCKS_HEADER),
        )?;
        let timing: Vec<TimingRow> = table::read_rows(
            from,
            &read(TIMING_HEADER, &self.timing),
            &columns(TIMING_HEADER),
        )?;
        let cpu: HashMap<usize, f64> = timing.into_iter().map(|t| (t.case, t.cpu_s)).collect();
        let mut by_case: HashMap<usize, Vec<BlockRow>> = HashMap::new();
        for b in blocks {
            by_case.entry(b.case).or_default().push(b);
        }
        cases
            .drain(..)
            .map(|mut row| {
                row.cpu_s = *cpu.get(&row.case).ok_or_else(|| Error::Table {
                    path: from.to_path_buf(),
                    line: 0,
                    message: format!("case {} has no CPU time in its batch", row.case),
                })?;
                let blocks = by_case.remove(&row.case).unwrap_or_default();
                Ok((row, blocks))
            })
            .collect()
    }
}

impl Store {
    /// Stores the finished cases of a batch run elsewhere.
    pub fn append_batch(&mut self, batch: &Batch) -> Result<(), Error> {
        let done = self.done();
        for (row, blocks) in batch.rows(self.dir())? {
            // A case stored already (an executor that ran a task twice) is kept as it was: its
            // rows do not depend on where it ran.
            if !done.contains(&row.case) {
                self.append(row, blocks)?;
            }
        }
        Ok(())
    }
}

impl Sweep {
    /// Runs the cases `ids` one after the other on this thread (a worker's share: the
    /// parallelism is the workers'), and returns their rows.
    pub fn run_batch(&self, ids: &[usize]) -> Result<Batch, Error> {
        self.check_ids(ids)?;
        let results: Vec<_> = ids.iter().map(|&id| self.run_case(id)).collect();
        Ok(Batch::of(&results))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows with awkward names and every kind of number come back from text to the bit.
    #[test]
    fn a_batch_round_trips_its_rows() {
        let row = CaseRow {
            case: 7,
            wall: "wall, \"quoted\"".into(),
            motion: "sine\nsecond line".into(),
            amplitude_gal: Some(0.1 + 0.2),
            max_abs_u_m: 1.0 / 3.0,
            collapse_time_s: None,
            uplift_mechanism_uniqueness: Some(crate::limit::Uniqueness::OneOfSeveral),
            cpu_s: 1.234_567_890_123e-4,
            error: Some("it failed, twice".into()),
            ..CaseRow::default()
        };
        let blocks = vec![BlockRow {
            case: 7,
            block: "B1".into(),
            max_abs_u_m: f64::MIN_POSITIVE,
            final_u_m: -2.0 / 7.0,
            fell: true,
            max_abs_rotation_rad: 0.1 + 0.2,
        }];
        let results = vec![
            (row, blocks),
            (
                CaseRow {
                    case: 9,
                    ..CaseRow::default()
                },
                vec![],
            ),
        ];
        let back = Batch::of(&results).rows(Path::new("batch")).unwrap();
        assert_eq!(back, results);
    }
}
