//! Shards: a sweep cut into N parts that run anywhere (the tasks of a Slurm job array, separate
//! machines), each into its own folder `OUT/parts/I-of-N`, and their merge into the very files a
//! single machine writes. Case `id` belongs to shard `id mod N`: neighbouring cases (the samples
//! of one wall and motion, often of like cost) spread over the shards.

use super::store::{self, check_complete, read_cases, read_manifest, read_table, table_error};
use super::store::{BlockRow, CaseRow, Paths, BLOCKS_HEADER};
use super::Sweep;
use crate::error::Error;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

/// Part `index` of `count` (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// Which part.
    pub index: usize,
    /// How many parts.
    pub count: usize,
}

/// The most parts a sweep is cut into (Slurm's own limit on an array is lower).
pub const MAX_SHARDS: usize = 1_000_000;

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

fn shard_error(rule: String) -> Error {
    Error::Option {
        option: "--shard".into(),
        rule,
    }
}

impl Shard {
    /// Part `index` of `count`, checked.
    pub fn new(index: usize, count: usize) -> Result<Shard, Error> {
        if count == 0 || count > MAX_SHARDS || index >= count {
            return Err(shard_error(format!(
                "part {index} of {count}: give I/N with N from 1 to {MAX_SHARDS} and I from 0 to N-1"
            )));
        }
        Ok(Shard { index, count })
    }

    /// Reads `I/N`, or `auto`: the part from the Slurm job array this process runs in, read
    /// from the variables `env` gives (`SLURM_ARRAY_TASK_ID`, `_MIN`, `_STEP`, `_COUNT`).
    pub fn parse(text: &str, env: impl Fn(&str) -> Option<String>) -> Result<Shard, Error> {
        if text == "auto" {
            return Shard::from_slurm(env);
        }
        let parsed = text
            .split_once('/')
            .and_then(|(i, n)| Some((i.trim().parse().ok()?, n.trim().parse().ok()?)));
        let (index, count) = parsed.ok_or_else(|| {
            shard_error(format!(
                "\"{text}\": give I/N (part I of N, from 0: 0/3, 1/3, 2/3) or auto (the Slurm \
                 array task)"
            ))
        })?;
        Shard::new(index, count)
    }

    /// The part of a Slurm array task: its place among the array's task ids.
    fn from_slurm(env: impl Fn(&str) -> Option<String>) -> Result<Shard, Error> {
        let var = |name: &str, default: Option<usize>| -> Result<usize, Error> {
            match env(name) {
                Some(v) => v.trim().parse().map_err(|_| {
                    shard_error(format!("auto: {name} is \"{v}\", not a whole number"))
                }),
                None => default.ok_or_else(|| {
                    shard_error(format!(
                        "auto: {name} is not set (this is not a Slurm array task): give I/N"
                    ))
                }),
            }
        };
        let id = var("SLURM_ARRAY_TASK_ID", None)?;
        let min = var("SLURM_ARRAY_TASK_MIN", None)?;
        let step = var("SLURM_ARRAY_TASK_STEP", Some(1))?.max(1);
        let count = var("SLURM_ARRAY_TASK_COUNT", None)?;
        if id < min || (id - min) % step != 0 {
            return Err(shard_error(format!(
                "auto: task {id} is not on the array's range from {min} in steps of {step}: \
                 submit the array as --array=0-{} or give I/N",
                count.saturating_sub(1)
            )));
        }
        Shard::new((id - min) / step, count)
    }

    /// Whether case `id` is in this part.
    pub fn contains(&self, id: usize) -> bool {
        id % self.count == self.index
    }

    /// The number of this part's cases in a sweep of `cases`.
    pub fn len(&self, cases: usize) -> usize {
        (cases + self.count - 1 - self.index) / self.count
    }

    /// Whether this part of a sweep of `cases` has none (more parts than cases).
    pub fn is_empty(&self, cases: usize) -> bool {
        self.len(cases) == 0
    }

    /// This part's folder in the output directory `out`.
    pub fn folder(&self, out: &Path) -> PathBuf {
        parts(out).join(format!("{}-of-{}", self.index, self.count))
    }
}

/// Where the shards of a sweep into `out` write their parts.
pub fn parts(out: &Path) -> PathBuf {
    out.join("parts")
}

/// A merged sweep: the sweep (loaded again from the file its parts name) and every case, in
/// order.
pub struct Merged {
    /// The sweep.
    pub sweep: Sweep,
    /// Its rows.
    pub rows: Vec<CaseRow>,
}

/// Merges the parts in `out/parts` into `out`: checks that they come from one sweep (the same
/// fingerprint, of the sweep file as it is now), that every part is there and finished, and
/// that every case is there once; then writes cases.csv, blocks.csv, timing.csv and
/// manifest.json as one machine would have. `sweep_file` overrides the file the parts name
/// (when the sweep moved, or the parts ran on another file system).
pub fn merge(out: &Path, sweep_file: Option<&Path>) -> Result<Merged, Error> {
    let dir = parts(out);
    let none = || {
        table_error(
            &dir,
            0,
            "no parts here: run `pirqa sweep FILE --shard I/N --out DIR` for each part first"
                .into(),
        )
    };
    let mut folders: Vec<PathBuf> = match std::fs::read_dir(&dir) {
        Ok(entries) => entries
            .filter_map(|e| e.ok().map(|e| e.path()))
            .filter(|p| p.is_dir())
            .collect(),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Err(none()),
        Err(e) => return Err(store::io(&dir)(e)),
    };
    folders.sort();
    let Some(first) = folders.first() else {
        return Err(none());
    };
    let manifests = folders
        .iter()
        .map(|f| read_manifest(&Paths::of(f).manifest))
        .collect::<Result<Vec<_>, _>>()?;
    let (fingerprint, count) = (
        &manifests[0]["fingerprint"],
        &manifests[0]["shard"]["count"],
    );
    let mut shards = Vec::new();
    for (folder, m) in folders.iter().zip(&manifests) {
        let path = Paths::of(folder).manifest;
        if &m["fingerprint"] != fingerprint || &m["shard"]["count"] != count {
            return Err(table_error(
                &path,
                1,
                format!(
                    "this part is of another sweep or another cut than {} (fingerprint {}, {} \
                     parts): every part in {} must come from one `pirqa sweep FILE --shard I/N`",
                    first.display(),
                    fingerprint,
                    count,
                    dir.display()
                ),
            ));
        }
        let shard = m["shard"]
            .as_object()
            .and_then(|s| Some((s.get("index")?.as_u64()?, s.get("count")?.as_u64()?)))
            .and_then(|(i, n)| Shard::new(i as usize, n as usize).ok())
            .filter(|s| &s.folder(out) == folder)
            .ok_or_else(|| {
                table_error(
                    &path,
                    1,
                    "not the manifest of a shard in its own folder (parts/I-of-N): remove the \
                     folder or run its shard again"
                        .into(),
                )
            })?;
        shards.push(shard);
    }
    let count = shards[0].count;
    let present: HashSet<usize> = shards.iter().map(|s| s.index).collect();
    let missing: Vec<String> = (0..count)
        .filter(|i| !present.contains(i))
        .map(|i| format!("{i}/{count}"))
        .collect();
    if !missing.is_empty() {
        return Err(table_error(
            &dir,
            0,
            format!(
                "{} of {count} parts are missing ({}{}): run `pirqa sweep FILE --shard I/N --out \
                 {}` for each",
                missing.len(),
                missing[..missing.len().min(8)].join(", "),
                if missing.len() > 8 { ", ..." } else { "" },
                out.display()
            ),
        ));
    }
    let file = match sweep_file {
        Some(f) => f.to_path_buf(),
        None => manifests[0]["sweep_file"]
            .as_str()
            .map(PathBuf::from)
            .ok_or_else(|| {
                table_error(
                    &Paths::of(first).manifest,
                    1,
                    "no sweep_file: give the sweep file with --sweep".into(),
                )
            })?,
    };
    let sweep = Sweep::load(&file)?;
    if fingerprint != sweep.fingerprint.as_str() {
        return Err(table_error(
            &Paths::of(first).manifest,
            1,
            format!(
                "the parts were run on another version of {} (the sweep file, a wall or a \
                 record changed since): run the shards again",
                file.display()
            ),
        ));
    }
    let mut rows = Vec::with_capacity(sweep.len());
    let mut block_rows = Vec::new();
    for (shard, folder) in shards.iter().zip(&folders) {
        let paths = Paths::of(folder);
        let fix = format!("--shard {shard} --resume");
        let part = check_complete(
            &paths.cases,
            read_cases(&paths)?,
            &sweep,
            Some(*shard),
            &fix,
        )?;
        let done: HashSet<usize> = part.iter().map(|r| r.case).collect();
        let mut blocks: Vec<BlockRow> = read_table(&paths.blocks, BLOCKS_HEADER)?;
        blocks.retain(|b| done.contains(&b.case));
        rows.extend(part);
        block_rows.extend(blocks);
    }
    store::sort(&mut rows, &mut block_rows);
    let paths = Paths::of(out);
    store::write_tables(&paths, &rows, &block_rows)?;
    crate::text::write(&paths.manifest, &store::manifest(&sweep, None))?;
    Ok(Merged { sweep, rows })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every case falls in exactly one part, and `len` counts them.
    #[test]
    fn parts_cover_every_case_once() {
        for count in 1..8 {
            for cases in 0..30 {
                let mut seen = vec![0; cases];
                for index in 0..count {
                    let s = Shard::new(index, count).unwrap();
                    let ids: Vec<usize> = (0..cases).filter(|&id| s.contains(id)).collect();
                    assert_eq!(ids.len(), s.len(cases), "{s} of {cases}");
                    ids.iter().for_each(|&id| seen[id] += 1);
                }
                assert!(seen.iter().all(|&n| n == 1));
            }
        }
    }

    /// `I/N` and Slurm's array variables read as the part they name; anything else is refused
    /// with what to give.
    #[test]
    fn shards_read_from_text_and_from_slurm() {
        let none = |_: &str| None;
        assert_eq!(
            Shard::parse("2/3", none).unwrap(),
            Shard { index: 2, count: 3 }
        );
        for bad in ["3/3", "0/0", "1", "a/b", "-1/3", "1/2000000"] {
            let e = Shard::parse(bad, none).unwrap_err().to_string();
            assert!(
                e.starts_with("--shard: ") && e.contains("I/N"),
                "{bad}: {e}"
            );
        }
        let slurm = |id: &'static str, step: Option<&'static str>| {
            move |name: &str| match name {
                "SLURM_ARRAY_TASK_ID" => Some(id.to_string()),
                "SLURM_ARRAY_TASK_MIN" => Some("1".into()),
                "SLURM_ARRAY_TASK_STEP" => step.map(String::from),
                "SLURM_ARRAY_TASK_COUNT" => Some("4".into()),
                _ => None,
            }
        };
        assert_eq!(
            Shard::parse("auto", slurm("3", None)).unwrap(),
            Shard { index: 2, count: 4 }
        );
        assert_eq!(
            Shard::parse("auto", slurm("7", Some("2"))).unwrap(),
            Shard { index: 3, count: 4 }
        );
        let e = Shard::parse("auto", slurm("4", Some("2")))
            .unwrap_err()
            .to_string();
        assert!(e.contains("not on the array's range"), "{e}");
        let e = Shard::parse("auto", none).unwrap_err().to_string();
        assert!(e.contains("SLURM_ARRAY_TASK_ID is not set"), "{e}");
    }
}
