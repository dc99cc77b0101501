//! Examples in the documentation are tests: every ```ron block in docs/ must parse and check
//! (walls everywhere, sweep files in docs/sweeps.md, whose paths start in walls/studies/).

use pirqa::{Topology, Wall};

#[test]
fn ron_examples_in_docs_are_valid_walls() {
    let mut found = 0;
    for entry in std::fs::read_dir("docs").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for block in text.split("```ron").skip(1) {
            let body = block.split("```").next().unwrap();
            if path.ends_with("sweeps.md") {
                let d = pirqa::study::sweep::parse_description(body)
                    .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                pirqa::study::sweep::Sweep::from_description(
                    &d,
                    std::path::Path::new("walls/studies"),
                    &path,
                )
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
                found += 1;
                continue;
            }
            let wall =
                Wall::from_ron_str(body).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            Topology::new(&wall).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            found += 1;
        }
    }
    assert!(found >= 1, "no ```ron examples found in docs/");
}

#[test]
fn every_shipped_wall_checks_and_is_pictured() {
    let pictures = std::fs::read_to_string("docs/walls.md").unwrap();
    let mut n = 0;
    let mut stack = vec![std::path::PathBuf::from("walls")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "ron")
                && !path.to_string_lossy().contains("studies")
            {
                pirqa::topology::load(&path).unwrap_or_else(|e| panic!("{e}"));
                // docs/walls.md shows every shipped wall.
                let stem = path.file_stem().unwrap().to_string_lossy().into_owned();
                let picture = format!("walls/{stem}.svg");
                assert!(
                    std::path::Path::new("docs").join(&picture).exists()
                        && pictures.contains(&format!("]({picture})")),
                    "{}: no picture docs/{picture} in docs/walls.md",
                    path.display()
                );
                n += 1;
            }
        }
    }
    assert!(n >= 7);
}

#[test]
fn relative_links_in_the_docs_point_to_files_that_exist() {
    let mut pages = vec![std::path::PathBuf::from("README.md")];
    for entry in std::fs::read_dir("docs").unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            pages.push(path);
        }
    }
    let mut checked = 0;
    for page in pages {
        let text = std::fs::read_to_string(&page).unwrap();
        let dir = page.parent().unwrap();
        for link in text.split("](").skip(1) {
            let target = link.split(')').next().unwrap();
            let file = target.split('#').next().unwrap();
            if file.is_empty() || file.contains("://") {
                continue;
            }
            assert!(
                dir.join(file).exists(),
                "{}: the link `{target}` names no file",
                page.display()
            );
            checked += 1;
        }
    }
    assert!(checked >= 10, "{checked} links");
}

/// The sweeps committed in docs/ (their cases.csv, without blocks.csv) draw to the very charts
/// and results.json committed beside them: a change to the analysis or the charts must redraw
/// them (`pirqa sweep FILE --out DIR --redraw`).
#[test]
fn committed_studies_are_what_their_cases_draw() {
    use pirqa::study::sweep::{analysis::analyse, store::Store, Sweep};
    for (file, dir) in [
        ("walls/studies/block-count.ron", "docs/block-count"),
        ("walls/studies/long-walls.ron", "docs/long-walls"),
        (
            "walls/studies/block-count-rocking.ron",
            "docs/block-count-rocking",
        ),
        (
            "walls/studies/ollantaytambo-rocking.ron",
            "docs/rocking/ollantaytambo",
        ),
        (
            "walls/studies/ollantaytambo-sliding.ron",
            "docs/rocking/ollantaytambo-sliding",
        ),
        (
            "walls/studies/ollantaytambo-uplift.ron",
            "docs/rocking/ollantaytambo-uplift",
        ),
        (
            "walls/studies/ollantaytambo-handed.ron",
            "docs/rocking/ollantaytambo-handed",
        ),
        (
            "walls/studies/ollantaytambo-while-rocking.ron",
            "docs/rocking/ollantaytambo-while-rocking",
        ),
        (
            "walls/studies/slab-while-rocking.ron",
            "docs/rocking/slab-while-rocking",
        ),
        (
            "walls/studies/slab-rocking.ron",
            "docs/rocking/slab-rocking",
        ),
    ] {
        let sweep = Sweep::load(std::path::Path::new(file)).unwrap();
        let rows = Store::finished(std::path::Path::new(dir), &sweep).unwrap();
        for (name, text) in analyse(&sweep, &rows).files() {
            let committed = std::fs::read_to_string(format!("{dir}/{name}")).unwrap();
            assert!(
                committed == text,
                "{dir}/{name} is not what its cases.csv draws: redraw it with \
                 `pirqa sweep {file} --out {dir} --redraw`"
            );
        }
    }
}

/// What docs/block-count.md says of the study's overlaps: each wall's 8 cases slid, and those
/// that lost a tenth of some joint's overlap or more (so warned) are none up to 105 blocks, 7 at
/// 976 and all 8 at 10,050, in the study's cases.csv and in the results.json drawn from it.
#[test]
fn the_block_count_studys_finest_cuts_are_beyond_small_displacements() {
    use pirqa::study::sweep::{analysis::analyse, store::Store, Sweep};
    let dir = std::path::Path::new("docs/block-count");
    let sweep = Sweep::load(std::path::Path::new("walls/studies/block-count.ron")).unwrap();
    let rows = Store::finished(dir, &sweep).unwrap();
    let results = analyse(&sweep, &rows).results;
    let found: Vec<(u64, u64, u64)> = results["small_displacements"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| {
            let blocks = c["wall"].as_str().unwrap().split(' ').nth(2).unwrap();
            let beyond = rows
                .iter()
                .filter(|r| r.blocks.to_string() == blocks)
                .filter(|r| r.max_overlap_loss.unwrap() >= 0.1)
                .count();
            assert_eq!(c["beyond_small"], beyond, "{c}");
            let slid = c["slid"].as_u64().unwrap();
            (blocks.parse().unwrap(), slid, beyond as u64)
        })
        .collect();
    assert_eq!(
        found,
        [
            (5, 8, 0),
            (18, 8, 0),
            (105, 8, 0),
            (976, 8, 7),
            (10050, 8, 8)
        ]
    );
}

/// A clone is the whole project: no tracked file outside `.ci/` reaches above the repository's
/// root for data. Every relative path that climbs (two dots, a slash) must land on something in the tree
/// when started from one of the tree's folders (a sweep file's paths start in its own folder, a
/// command in the docs at the root); one that only lands outside, like a record beside the
/// development checkout, fails here with the file and line that names it.
#[test]
fn no_tracked_file_reads_data_from_above_the_repository() {
    let files = tracked_files();
    let mut folders: std::collections::BTreeSet<std::path::PathBuf> = files
        .iter()
        .filter_map(|f| f.parent().map(std::path::Path::to_path_buf))
        .collect();
    folders.insert(std::path::PathBuf::new());
    let inside = |token: &str| {
        folders.iter().any(|folder| {
            let mut at = folder.clone();
            for part in token.split('/').filter(|p| !p.is_empty() && *p != ".") {
                if part == ".." {
                    if !at.pop() {
                        return false;
                    }
                } else {
                    at.push(part);
                }
            }
            at.exists()
        })
    };
    let mut climbing = 0;
    let mut outside = Vec::new();
    for file in files.iter().filter(|f| !f.starts_with(".ci")) {
        let Ok(text) = std::fs::read_to_string(file) else {
            continue;
        };
        for (line, content) in text.lines().enumerate() {
            for token in content
                .split(|c: char| !(c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.' | '/')))
            {
                let Some(start) = token.find("../") else {
                    continue;
                };
                let path = token[start..].trim_end_matches(['.', '/']);
                climbing += 1;
                if !inside(path) {
                    outside.push(format!("{}:{}: {path}", file.display(), line + 1));
                }
            }
        }
    }
    assert!(climbing >= 10, "only {climbing} relative paths found");
    assert!(
        outside.is_empty(),
        "these paths name nothing inside the repository (ship the data in the tree, e.g. \
         records/, and name it from there):\n{}",
        outside.join("\n")
    );
}

/// The files git tracks, or, outside a git checkout, every file but build output.
fn tracked_files() -> Vec<std::path::PathBuf> {
    if let Ok(out) = std::process::Command::new("git")
        .args(["ls-files", "-z"])
        .output()
    {
        if out.status.success() && !out.stdout.is_empty() {
            return out
                .stdout
                .split(|&b| b == 0)
                .filter(|name| !name.is_empty())
                .map(|name| std::path::PathBuf::from(String::from_utf8_lossy(name).into_owned()))
                .collect();
        }
    }
    let mut files = Vec::new();
    let mut stack = vec![std::path::PathBuf::from(".")];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            let name = path.file_name().unwrap().to_string_lossy();
            if name.starts_with('.') || name == "target" || name == "out" {
                continue;
            }
            if path.is_dir() {
                stack.push(path);
            } else {
                files.push(path.strip_prefix(".").unwrap().to_path_buf());
            }
        }
    }
    files
}

/// The limits at rest committed in docs/rocking/limit-at-rest are what the program gives now:
/// a change to it must write them again (`pirqa check FILE --limit --mechanism DIR`).
#[test]
fn committed_limits_at_rest_are_what_the_program_gives() {
    let model = pirqa::Model::from_file("walls/inca/ollantaytambo-monoliths.ron").unwrap();
    let limits = pirqa::limit::at_rest(model.wall(), model.topology()).unwrap();
    let committed =
        std::fs::read_to_string("docs/rocking/limit-at-rest/ollantaytambo/limit.json").unwrap();
    // Compared as text: what `--mechanism` writes, to the digit.
    assert_eq!(
        serde_json::to_string_pretty(&limits).unwrap() + "\n",
        committed
    );
}

/// The residual limits committed in docs/rocking/residual-fragility are what the program gives
/// now: the fragility study run, then `pirqa sweep ... --residual` (docs/rocking-walls.md, the
/// limit where a run left the wall); a change to either must write them again.
#[test]
fn committed_residual_limits_are_what_the_program_gives() {
    let dir = crate::common::scratch("residual-fragility");
    let out = dir.to_str().unwrap();
    let sweep = |extra: &[&str]| {
        let args = [
            &["sweep", "walls/studies/fragility.ron", "--out", out][..],
            extra,
        ]
        .concat();
        let (code, _, err) = crate::common::pirqa(&args, &[]);
        assert_eq!(code, 0, "{err}");
    };
    sweep(&[]);
    sweep(&["--residual"]);
    for name in ["residual.csv", "capacity-left.csv", "capacity-left.svg"] {
        let committed = std::fs::read_to_string(format!("docs/rocking/residual-fragility/{name}"));
        let made = std::fs::read_to_string(dir.join(name)).unwrap();
        assert!(
            committed.unwrap() == made,
            "docs/rocking/residual-fragility/{name} differs"
        );
    }
}
