//! The merge of a sharded sweep's parts (`OUT/parts/I-of-N`) into the very files a single
//! machine writes, after checking that they make one sweep.

use super::shard::{parts, Shard};
use super::store::{self, check_complete, read_cases, read_manifest, read_table, table_error};
use super::store::{BlockRow, CaseRow, Paths, BLOCKS_HEADER};
use super::Sweep;
use crate::error::Error;
use std::collections::HashSet;
use std::path::{Path, PathBuf};

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
