//! Sweeps cut into shards (`pirqa sweep FILE --shard I/N`, as the tasks of a Slurm job array
//! run them) and merged (`pirqa sweep merge DIR`): the same files, byte for byte, as the sweep
//! run at once, whatever the number of threads; and parts that do not belong together refused.

use crate::common;
use std::path::Path;
use std::process::Command;

/// (exit code, stderr).
fn pirqa(args: &[&str], env: &[(&str, &str)]) -> (i32, String) {
    let (code, _, err) = common::pirqa(args, env);
    (code, err)
}

fn ok(args: &[&str], env: &[(&str, &str)]) {
    let (code, err) = pirqa(args, env);
    assert_eq!(code, 0, "{args:?}: {err}");
}

/// A friction Monte Carlo on the paper's wall (60 cases, random samples, sines): small enough
/// to run many times, with every kind of column filled.
fn monte_carlo(dir: &Path, seed: u64) -> std::path::PathBuf {
    let wall = std::fs::canonicalize("walls/five-block-variable.ron").unwrap();
    let file = dir.join(format!("mc-{seed}.ron"));
    std::fs::create_dir_all(dir).unwrap();
    std::fs::write(
        &file,
        format!(
            r#"(
    version: 1,
    name: "shards",
    walls: [File(path: "{}")],
    motion: Sine(amplitudes: ["300gal", "500gal"], frequencies_hz: List([1.0, 2.0]), duration_s: 5.0),
    friction: Random(distribution: Lognormal, cov: 0.2, samples: 15, seed: {seed}),
)"#,
            wall.display()
        ),
    )
    .unwrap();
    file
}

/// Three shards, one of them told its part by Slurm's variables, merged: every result file equal
/// to the sweep run at once on one thread and on two.
#[test]
fn three_shards_merged_equal_the_sweep_run_at_once() {
    let base = common::scratch("shards");
    let sweep = monte_carlo(&base, 7);
    let sweep = sweep.to_str().unwrap();
    let (one, two, sharded) = (base.join("one"), base.join("two"), base.join("sharded"));
    let out = |d: &Path| d.to_str().unwrap().to_string();
    ok(
        &["sweep", sweep, "--out", &out(&one), "--threads", "1"],
        &[],
    );
    ok(
        &["sweep", sweep, "--out", &out(&two), "--threads", "2"],
        &[],
    );
    assert!(common::same_sweep_files(&one, &two) >= 6);
    ok(
        &["sweep", sweep, "--shard", "0/3", "--out", &out(&sharded)],
        &[],
    );
    ok(
        &[
            "sweep",
            sweep,
            "--shard",
            "2/3",
            "--out",
            &out(&sharded),
            "--threads",
            "1",
        ],
        &[],
    );
    let slurm = [
        ("SLURM_ARRAY_TASK_ID", "2"),
        ("SLURM_ARRAY_TASK_MIN", "1"),
        ("SLURM_ARRAY_TASK_COUNT", "3"),
    ];
    ok(
        &["sweep", sweep, "--shard", "auto", "--out", &out(&sharded)],
        &slurm,
    );
    let part = std::fs::read_to_string(sharded.join("parts/1-of-3/cases.csv")).unwrap();
    assert_eq!(
        part.lines().count(),
        1 + 20,
        "part 1 of 3 holds cases 1, 4, ..., 58"
    );
    ok(&["sweep", "merge", &out(&sharded)], &[]);
    assert!(common::same_sweep_files(&one, &sharded) >= 6);
    // Every case's time is there too, measured where it ran.
    let timing = std::fs::read_to_string(sharded.join("timing.csv")).unwrap();
    assert_eq!(timing.lines().count(), 61);
}

/// A missing part, an unfinished one, a part of another sweep or of another cut, and a sweep
/// file changed since: each refused, naming the file and what to do.
#[test]
fn parts_that_do_not_make_one_sweep_are_refused() {
    let base = common::scratch("bad-shards");
    let sweep = monte_carlo(&base, 7);
    let other = monte_carlo(&base.join("other"), 8);
    let (sweep, other) = (sweep.to_str().unwrap(), other.to_str().unwrap());
    let dir = base.join("out");
    let d = dir.to_str().unwrap();
    let refused = |args: &[&str], says: &[&str]| {
        let (code, err) = pirqa(args, &[]);
        assert_eq!(code, 1, "{args:?}: {err}");
        for s in says {
            assert!(err.contains(s), "{args:?}: {err} lacks {s}");
        }
    };
    refused(
        &["sweep", "merge", d],
        &["parts", "no parts here", "--shard I/N"],
    );
    refused(
        &["sweep", sweep, "--shard", "3/3", "--out", d],
        &["--shard: part 3 of 3"],
    );
    refused(
        &["sweep", sweep, "--shard", "auto", "--out", d],
        &["SLURM_ARRAY_TASK_ID is not set"],
    );
    ok(&["sweep", sweep, "--shard", "0/2", "--out", d], &[]);
    refused(&["sweep", "merge", d], &["1 of 2 parts are missing (1/2)"]);
    // A part of another sweep in the same folder.
    ok(&["sweep", other, "--shard", "1/2", "--out", d], &[]);
    refused(
        &["sweep", "merge", d],
        &["1-of-2/manifest.json", "another sweep or another cut"],
    );
    // The right part, cut short as a killed task leaves it: its missing cases named, and its
    // resumption finishing it.
    ok(
        &["sweep", sweep, "--shard", "1/2", "--out", d, "--fresh"],
        &[],
    );
    let cases = dir.join("parts/1-of-2/cases.csv");
    let text = std::fs::read_to_string(&cases).unwrap();
    let kept: Vec<&str> = text.lines().take(11).collect();
    std::fs::write(&cases, kept.join("\n") + "\n").unwrap();
    refused(
        &["sweep", "merge", d],
        &[
            "1-of-2/cases.csv",
            "20 of the 30 cases of shard 1/2 are not done",
            "--shard 1/2 --resume",
        ],
    );
    ok(
        &["sweep", sweep, "--shard", "1/2", "--out", d, "--resume"],
        &[],
    );
    ok(&["sweep", "merge", d], &[]);
    // A part of another cut.
    ok(&["sweep", sweep, "--shard", "2/3", "--out", d], &[]);
    refused(
        &["sweep", "merge", d],
        &["2-of-3/manifest.json", "another cut"],
    );
    std::fs::remove_dir_all(dir.join("parts/2-of-3")).unwrap();
    // The sweep file changed since the parts ran.
    let changed = std::fs::read_to_string(sweep)
        .unwrap()
        .replace("\"shards\"", "\"changed\"");
    std::fs::write(sweep, changed).unwrap();
    refused(
        &["sweep", "merge", d],
        &["another version of", "run the shards again"],
    );
}

/// docs/python/slurm-array.sh run as three tasks of an array (Slurm's variables set as sbatch
/// sets them), one of them twice as a requeued task is, then merged: the sweep run at once.
#[test]
#[cfg(unix)]
fn the_slurm_array_script_of_the_docs_runs_a_sweep() {
    let base = common::scratch("slurm");
    let sweep = monte_carlo(&base, 11);
    let (whole, array) = (base.join("whole"), base.join("array"));
    ok(
        &[
            "sweep",
            sweep.to_str().unwrap(),
            "--out",
            whole.to_str().unwrap(),
        ],
        &[],
    );
    for task in ["4", "5", "6", "5"] {
        let out = Command::new("bash")
            .arg("docs/python/slurm-array.sh")
            .arg(&sweep)
            .arg(&array)
            .env("PIRQA", env!("CARGO_BIN_EXE_pirqa"))
            .envs([
                ("SLURM_ARRAY_TASK_ID", task),
                ("SLURM_ARRAY_TASK_MIN", "4"),
                ("SLURM_ARRAY_TASK_COUNT", "3"),
                ("SLURM_CPUS_PER_TASK", "2"),
            ])
            .output()
            .unwrap();
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    ok(&["sweep", "merge", array.to_str().unwrap()], &[]);
    assert!(common::same_sweep_files(&whole, &array) >= 6);
}
