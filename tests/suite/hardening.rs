//! Hostile and extreme inputs (issue 34): each class gets a clear error naming what to change,
//! or a run whose answer is right; never a panic (exit code 101), a hang or a silent default.

use crate::common;
use std::process::Command;

const WALL: &str = "walls/five-block-variable.ron";

/// Runs pirqa; returns (exit code, stdout, stderr).
fn pirqa(args: &[&str]) -> (i32, String, String) {
    common::pirqa(args, &[])
}

/// A refused input: exit code 1 (not a panic's 101) and a message holding `says`.
fn refused(args: &[&str], says: &str) {
    let (code, _, err) = pirqa(args);
    assert_eq!(code, 1, "{args:?}: {err}");
    assert!(err.contains(says), "{args:?}: {err}");
}

/// `pirqa run` of the paper's wall under a sine of `amplitude`, `freq` Hz for `duration` s, and
/// the options `extra`.
fn sine_of(amplitude: &str, freq: &str, duration: &str, extra: &[&str]) -> Vec<String> {
    [
        "run",
        WALL,
        "--sine",
        amplitude,
        "--freq",
        freq,
        "--duration",
        duration,
    ]
    .iter()
    .chain(extra)
    .map(|s| s.to_string())
    .collect()
}

/// The same under 400 gal, 1 Hz for 2 s.
fn sine(extra: &[&str]) -> Vec<String> {
    sine_of("400gal", "1", "2", extra)
}

fn strs(v: &[String]) -> Vec<&str> {
    v.iter().map(String::as_str).collect()
}

#[test]
fn motions_beyond_the_bounds_are_refused_with_the_bound() {
    let frequency = "a frequency from 0.0001 to 1000 Hz";
    for (amplitude, freq, duration, says) in [
        ("1e307m/s2", "1", "2", "at most 1000 m/s2"),
        // The value shown as a number, not its 308 digits.
        (
            "1e307m/s2",
            "1",
            "2",
            "sine of 1e307 m/s2, phase 0 rad, 1 Hz, 2 s",
        ),
        ("4m/s2", "1e12", "2", frequency),
        // Found by the fuzzer: a subnormal frequency overflowed A / omega^2 into NaN energies.
        ("4m/s2", "5e-324", "2", frequency),
        ("4m/s2", "5e-324", "2", "5e-324 Hz"),
        (
            "4m/s2",
            "1",
            "1e12",
            "a positive duration of at most 1000000 s",
        ),
    ] {
        refused(&strs(&sine_of(amplitude, freq, duration, &[])), says);
    }
    refused(
        &strs(&sine(&["--output-dt", "1e-9", "--out", "unused"])),
        "a history written to a file (duration / interval rows of every block) at most 2e9",
    );
    refused(
        &strs(&sine(&["--method", "moreau", "--dt", "1e-9"])),
        "more than 1e9 steps",
    );
}

/// A phase is reduced exactly (in degrees): 1e18 degrees is 280 degrees to the bit, so the
/// runs agree to the last digit; negative values are values, not unknown options.
#[test]
fn phases_reduce_exactly_and_negative_numbers_are_numbers() {
    let file = common::scratch("summary.json");
    let path = file.to_str().unwrap();
    let summary = |phase: &str| {
        let (code, _, err) = pirqa(&strs(&sine(&["--phase", phase, "--summary", path])));
        assert_eq!(code, 0, "{err}");
        let v: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap();
        v["blocks"].clone()
    };
    assert_eq!(summary("1e18"), summary("280"));
    assert_eq!(summary("-80"), summary("280"));
    let (code, _, err) = pirqa(&strs(&sine(&["--scale", "-1"])));
    assert_eq!(code, 0, "{err}");
    let (code, _, err) = pirqa(&strs(&sine_of("-4m/s2", "1", "2", &[])));
    assert_eq!(code, 0, "{err}");
}

/// A header's point count is a claim, not an allocation: NPTS = 1e30 reads what is there and
/// says the data end early.
#[test]
fn an_absurd_point_count_is_an_error_not_an_allocation() {
    for npts in ["1e30", "1000000000000"] {
        let f = common::file(
            "huge.at2",
            &format!(
                "PEER STRONG MOTION DATABASE RECORD\nTEST\nACCELERATION TIME SERIES IN UNITS OF G\n\
                 NPTS= {npts}, DT= .0100 SEC\n0.01 0.02 0.03\n"
            ),
        );
        let path = f.to_str().unwrap();
        refused(
            &strs(&["run", WALL, "--record", path].map(String::from)),
            "NPTS",
        );
    }
}

/// A plain record that says its units or interval twice is refused, naming the line (it was
/// read by its last line, so a record in gal followed by a stray `# units: g` was 981 times off).
#[test]
fn a_record_that_says_its_units_twice_is_refused() {
    let f = common::file(
        "twice.txt",
        "# units: gal\n# dt_s: 0.01\n# units: g\n1\n2\n3\n",
    );
    refused(
        &[
            "run",
            WALL,
            "--record",
            f.to_str().unwrap(),
            "--duration",
            "1",
        ],
        "line 3: a second `# units:` line",
    );
    let f = common::file(
        "dt.txt",
        "# units: gal\n# dt_s: 0.01\n# dt_s: 0.02\n1\n2\n3\n",
    );
    refused(
        &[
            "run",
            WALL,
            "--record",
            f.to_str().unwrap(),
            "--duration",
            "1",
        ],
        "line 3: a second `# dt_s:` line",
    );
}

/// Sizes where masses fall towards f64's subnormals (the answer, which does not depend on the
/// thickness, started to) are refused with the bound.
#[test]
fn walls_outside_the_size_bounds_are_refused() {
    let text = std::fs::read_to_string(WALL).unwrap();
    for thickness in ["1e-50", "5e-324", "1e9"] {
        let f = common::file(
            "thin.ron",
            &text.replace("thickness_m: 0.8", &format!("thickness_m: {thickness}")),
        );
        refused(
            &["check", f.to_str().unwrap()],
            "must be a length from 0.001 to 10000 m",
        );
    }
}

/// Files that are not what they should be are named for what they are: empty, not text, an AT2
/// record cut after its title; a byte-order mark (spreadsheets write one) is read past.
#[test]
fn empty_binary_and_cut_files_are_named_and_a_byte_order_mark_is_read_past() {
    let read = |f: &common::Scratch, says: &str| {
        refused(
            &[
                "run",
                WALL,
                "--record",
                f.to_str().unwrap(),
                "--duration",
                "1",
            ],
            says,
        )
    };
    read(
        &common::file("empty.txt", "\n  \n"),
        "empty.txt: the file is empty",
    );
    let garbage = common::scratch("garbage.bin");
    std::fs::write(&*garbage, [0x7f, b'E', b'L', b'F', 0xff, 0x00, 0x13]).unwrap();
    read(&garbage, "not a text file (byte 5 is not UTF-8)");
    read(
        &common::file(
            "cut.at2",
            "PEER NGA STRONG MOTION DATABASE RECORD\nIMPERIAL VALLEY 5/19/40, EL CENTRO ARRAY #9\n",
        ),
        "an AT2 file has 4 header lines and then data; this one has 2",
    );
    let bom = common::file(
        "bom.txt",
        "\u{feff}# units: gal\n# dt_s: 0.01\n100\n-100\n50\n",
    );
    let (code, _, err) = pirqa(&[
        "run",
        WALL,
        "--record",
        bom.to_str().unwrap(),
        "--duration",
        "1",
    ]);
    assert_eq!(code, 0, "{err}");
    let text = std::fs::read_to_string(WALL).unwrap();
    let wall = common::file("bom.ron", &format!("\u{feff}{text}"));
    let (code, _, err) = pirqa(&["check", wall.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
}

/// A joint given twice in `joint_friction` is refused with its line, not read by its last value.
#[test]
fn a_joint_given_twice_is_refused() {
    let text = std::fs::read_to_string(WALL).unwrap();
    let twice = text.replace(
        "\"B5/B2\": 0.28,",
        "\"B5/B2\": 0.28,\n        \"B5/B2\": 0.35,",
    );
    assert_ne!(twice, text);
    let f = common::file("twice.ron", &twice);
    refused(
        &["check", f.to_str().unwrap()],
        "joint_friction key \"B5/B2\" is given twice",
    );
}

/// A sweep killed (SIGKILL) at several points and resumed each time ends with the results of an
/// uninterrupted sweep, byte for byte (the CPU times, in timing.csv, are measurements).
#[test]
fn a_sweep_killed_and_resumed_equals_an_uninterrupted_one() {
    let study = "walls/studies/paper-fig3-4.ron";
    let base = common::scratch("kill");
    let (whole, cut) = (base.join("whole"), base.join("cut"));
    let (code, _, err) = pirqa(&["sweep", study, "--out", whole.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    // Kill the first run and each resumption after a different delay (ms).
    let mut finished = false;
    for (k, delay) in [150u64, 400, 250, 700].into_iter().enumerate() {
        let mut args = vec![
            "sweep",
            study,
            "--out",
            cut.to_str().unwrap(),
            "--threads",
            "1",
        ];
        if k > 0 {
            args.push("--resume");
        }
        let mut child = Command::new(env!("CARGO_BIN_EXE_pirqa"))
            .args(&args)
            .stdout(std::process::Stdio::null())
            .stderr(std::process::Stdio::null())
            .spawn()
            .unwrap();
        std::thread::sleep(std::time::Duration::from_millis(delay));
        if child.try_wait().unwrap().is_some() {
            finished = true;
            break;
        }
        child.kill().unwrap();
        child.wait().unwrap();
    }
    if !finished {
        let (code, _, err) = pirqa(&["sweep", study, "--out", cut.to_str().unwrap(), "--resume"]);
        assert_eq!(code, 0, "{err}");
    }
    let cases = std::fs::read_to_string(whole.join("cases.csv")).unwrap();
    assert_eq!(cases.lines().count(), 1201);
    // cases.csv, blocks.csv, manifest.json, results.json and every chart: byte for byte.
    assert!(common::same_sweep_files(&whole, &cut) >= 8);
}

/// A vertical component beside a sine was dropped without a word, even from a file that does
/// not exist.
#[test]
fn a_vertical_component_beside_a_sine_is_refused() {
    refused(
        &strs(&sine(&["--vertical", "nowhere.at2"])),
        "--vertical: a vertical component goes with --record",
    );
}

/// Runs pirqa with `args`, sends it SIGINT (what Ctrl-C sends) after `wait_ms`, and returns
/// its exit code and stdout.
#[cfg(unix)]
fn interrupted_after(args: &[&str], wait_ms: u64) -> (Option<i32>, String) {
    let child = Command::new(env!("CARGO_BIN_EXE_pirqa"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(wait_ms));
    let sent = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(sent.success());
    let out = child.wait_with_output().unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

/// Ctrl-C (SIGINT) stops a long run at the time it reached: exit code 130, and the files of the
/// motion up to then, the summary saying where it stopped. Both kinds of integrator: the
/// event-driven one on a sine of one segment (it looks at the request every few thousand
/// events) and a time stepper (at every step).
#[test]
#[cfg(unix)]
fn ctrl_c_stops_a_run_and_writes_what_it_has() {
    let base = common::scratch("ctrl-c");
    let long = [
        [
            "--duration",
            "1000000",
            "--output-dt",
            "100",
            "--method",
            "event",
        ],
        [
            "--duration",
            "5000",
            "--output-dt",
            "1",
            "--method",
            "moreau",
        ],
    ];
    for (k, extra) in long.iter().enumerate() {
        let dir = base.join(format!("run{k}"));
        let mut args = vec!["run", WALL, "--sine", "400gal", "--freq", "1"];
        args.extend(extra);
        args.extend(["--out", dir.to_str().unwrap()]);
        let (code, stdout) = interrupted_after(&args, 800);
        assert_eq!(code, Some(130), "{args:?}: {stdout}");
        assert!(stdout.contains("INTERRUPTED at t = "), "{stdout}");
        let summary: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap())
                .unwrap();
        let at = summary["interrupted_at_s"]
            .as_f64()
            .expect("flagged partial");
        let duration: f64 = extra[1].parse().unwrap();
        assert!(at > 0.0 && at < duration, "{at}");
        assert_eq!(summary["duration_s"].as_f64().unwrap(), at);
        // The history ends where the run stopped.
        let history = std::fs::read_to_string(dir.join("history.csv")).unwrap();
        let last: f64 = history
            .lines()
            .last()
            .unwrap()
            .split(',')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        assert!(
            last <= at && last > at - 100.0,
            "history ends at {last}, run at {at}"
        );
    }
}

/// Ctrl-C stops `check --limit` on a wall whose exact programs take many seconds (a generated
/// running bond of 976 blocks): exit code 130, the report whole but for the limit, which it
/// says was stopped, and no mechanism drawn.
#[test]
#[cfg(unix)]
fn ctrl_c_stops_the_limit_at_rest_and_says_so() {
    let dir = common::scratch("ctrl-c-limit");
    let wall = dir.join("bond.ron");
    let (code, _, err) = pirqa(&["generate", "--blocks", "1000", "-o", wall.to_str().unwrap()]);
    assert_eq!(code, 0, "{err}");
    let drawings = dir.join("mechanism");
    let (wall, drawings_arg) = (wall.to_str().unwrap(), drawings.to_str().unwrap());
    let args = [
        "check",
        wall,
        "--limit",
        "--json",
        "--mechanism",
        drawings_arg,
    ];
    let (code, stdout) = interrupted_after(&args, 1500);
    assert_eq!(code, Some(130), "{stdout}");
    let report: serde_json::Value = serde_json::from_str(&stdout).unwrap();
    assert_eq!(report["blocks"].as_array().unwrap().len(), 976);
    assert!(report.get("limit_at_rest").is_none(), "{stdout}");
    let why = report["limit_at_rest_not_computed"].as_str().unwrap();
    assert!(
        why.starts_with("stopped by Ctrl-C after ")
            && why.ends_with("before the programs of both sides were proved"),
        "{why}"
    );
    assert!(!drawings.exists());
}

/// A disk that fills up during the writing of a run's files: a clear error that says so and
/// what to do, no cut file, and no summary.json (which is written last, so its presence means
/// the run's files are whole). Needs a small tmpfs, so root; elsewhere the test says it could
/// not run (the message itself is checked by a unit test in error.rs).
#[test]
#[cfg(target_os = "linux")]
fn a_full_disk_is_a_clear_error_and_leaves_no_summary() {
    struct Mounted(std::path::PathBuf);
    impl Drop for Mounted {
        fn drop(&mut self) {
            let _ = Command::new("umount").arg(&self.0).status();
        }
    }
    let dir = common::scratch("full-disk");
    std::fs::create_dir_all(&*dir).unwrap();
    let mounted = Command::new("mount")
        .args(["-t", "tmpfs", "-o", "size=32k", "tmpfs"])
        .arg(&*dir)
        .stderr(std::process::Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    if !mounted {
        eprintln!("a_full_disk_is_a_clear_error: no tmpfs could be mounted here (not root)");
        return;
    }
    let _guard = Mounted(dir.to_path_buf());
    let out = dir.join("out");
    let (code, _, err) = pirqa(&strs(&sine_of(
        "400gal",
        "1",
        "20",
        &["--out", out.to_str().unwrap()],
    )));
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("the disk is full"), "{err}");
    let left: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert!(
        !left
            .iter()
            .any(|f| f == "summary.json" || f.ends_with(".tmp")),
        "{left:?}"
    );
}

/// A run estimates its work before it starts: `--estimate` prints it without running, and a
/// large run says so before it starts (here killed once it has); a run refused for its number of
/// steps is refused before its size is announced.
#[test]
fn a_run_estimates_its_work_and_says_when_it_is_large() {
    use std::io::BufRead;
    let dir = common::scratch("estimate");
    let (code, out, err) = pirqa(&strs(&sine_of(
        "400gal",
        "1",
        "1000000",
        &["--estimate", "--out", dir.to_str().unwrap()],
    )));
    assert_eq!(code, 0, "{err}");
    assert!(out.contains("episodes of sliding  2000000"), "{out}");
    assert!(out.contains("events (exact)       2.4e7"), "{out}");
    assert!(
        out.contains("history") && out.contains("1.2e8 rows"),
        "{out}"
    );
    assert!(!dir.exists(), "an estimate writes nothing");
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_pirqa"))
        .args(sine_of("400gal", "1", "1000000", &[]))
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("pirqa starts");
    let first = std::io::BufReader::new(child.stderr.take().expect("stderr"))
        .lines()
        .next()
        .expect("a line")
        .expect("text");
    child.kill().expect("the run is killed");
    child.wait().expect("and ends");
    assert!(
        first.starts_with("note: a large run: about 2.4e7 events"),
        "{first}"
    );
    let (code, _, err) = pirqa(&strs(&sine_of(
        "400gal",
        "1",
        "1000000",
        &["--method", "moreau", "--dt", "1e-6"],
    )));
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("more than 1e9 steps"), "{err}");
    assert!(!err.contains("note:"), "{err}");
}

/// A time step that is no step is refused before anything is estimated or run: zero (the
/// estimate spoke of infinitely many steps), and longer than the run (one step stood for the
/// whole motion: walls/rocking/slab-beside-block.ron, whose slab rocks under a 0.3 g sine,
/// came out at rest).
#[test]
fn a_time_step_that_is_no_step_is_refused_before_any_estimate() {
    let (code, _, err) = pirqa(&strs(&sine(&[
        "--after-uplift",
        "moreau-while-rocking",
        "--dt",
        "0",
    ])));
    assert_eq!(code, 1, "{err}");
    assert!(err.contains("time step 0 s: it must be positive"), "{err}");
    assert!(!err.contains("note:"), "{err}");
    for extra in [
        &["--method", "moreau", "--dt", "5"][..],
        &["--method", "paper", "--dt", "2.5"],
        &["--after-uplift", "moreau", "--dt", "5"],
        &["--after-uplift", "moreau-while-rocking", "--dt", "5"],
    ] {
        refused(&strs(&sine(extra)), "it is longer than the run");
    }
    // Nor is an infinite one, which the message does not call positive.
    refused(
        &strs(&sine(&["--method", "moreau", "--dt", "inf"])),
        "time step inf s: it must be positive and finite",
    );
    // A step of the whole run is a step.
    let (code, _, err) = pirqa(&strs(&sine(&["--method", "moreau", "--dt", "2"])));
    assert_eq!(code, 0, "{err}");
}

/// A negative number given to an option reaches the check that names what to change, instead
/// of the command-line parser's "unexpected argument '-1' found" and its tip to write `-- -1`,
/// which does not work for an option's value; and an option that would be ignored is refused.
#[test]
fn negative_numbers_reach_the_checks_that_name_them() {
    refused(
        &strs(&sine_of("400gal", "1", "-1", &[])),
        "a positive duration",
    );
    refused(
        &strs(&sine(&["--method", "moreau", "--dt", "-1"])),
        "time step -1 s: it must be positive",
    );
    refused(
        &[
            "run",
            WALL,
            "--record",
            "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
            "--pga",
            "-1g",
        ],
        "peak -9.81 m/s2: cannot scale",
    );
    let dir = common::scratch("negative");
    let wall = dir.join("g.ron");
    refused(
        &["generate", "--width", "-2m", "-o", wall.to_str().unwrap()],
        "width_m = -2: must be positive",
    );
    let run = dir.join("run");
    let (code, _, err) = pirqa(&strs(&sine(&["--out", run.to_str().unwrap()])));
    assert_eq!(code, 0, "{err}");
    let drawn = dir.join("d.svg");
    refused(
        &[
            "draw",
            WALL,
            "--run",
            run.to_str().unwrap(),
            "--at",
            "-1",
            "-o",
            drawn.to_str().unwrap(),
        ],
        "--at -1 s is outside the run",
    );
    // A history interval without a history to write: refused, not ignored.
    let (code, _, err) = pirqa(&strs(&sine(&["--output-dt", "0.1"])));
    assert_eq!(code, 2, "{err}");
    assert!(err.contains("--out"), "{err}");
}

/// A history streamed to its file as the run goes is the history kept in memory, byte for byte,
/// and so is the chart drawn from it: for a sliding wall and for a rocking stela (rotations
/// in the columns). Memory then holds one row (docs/reliability.md: the RSS of a 422 MB history).
#[test]
fn a_streamed_history_and_its_chart_equal_the_ones_kept_in_memory() {
    use pirqa::plot::{chart, response_charts};
    let dir = common::scratch("streamed");
    for (wall, motion) in [
        (WALL, pirqa::motion::EL_CENTRO),
        ("walls/inca/stela.ron", pirqa::motion::EL_CENTRO),
    ] {
        let model = pirqa::Model::from_file(wall).unwrap();
        let record =
            pirqa::motion::read_record(std::path::Path::new(motion), None, &Default::default())
                .unwrap()
                .scaled(2.0)
                .unwrap();
        let motion = pirqa::Motion::Record(record);
        let memory = pirqa::RunSettings {
            duration_s: Some(15.0),
            output_dt_s: Some(0.01),
            ..Default::default()
        };
        let path = dir.join("history.csv");
        let file = pirqa::RunSettings {
            history_file: Some(path.clone()),
            ..memory.clone()
        };
        let kept = pirqa::run(&model, &motion, &memory).unwrap();
        let streamed = pirqa::run(&model, &motion, &file).unwrap();
        assert!(streamed.history.is_none());
        let rotating = !kept.history.as_ref().unwrap().rotation_rad.is_empty();
        assert_eq!(rotating, wall != WALL, "the stela rocks, the wall slides");
        let written = streamed.history_file.as_ref().unwrap();
        assert_eq!(
            (written.path.as_path(), &written.failed),
            (path.as_path(), &None)
        );
        assert_eq!(
            std::fs::read_to_string(&path).unwrap(),
            kept.history_csv().unwrap(),
            "{wall}"
        );
        let csv =
            |r: &pirqa::Response| chart::to_csv(&response_charts(r, &motion).unwrap().unwrap());
        assert_eq!(csv(&streamed), csv(&kept), "{wall}");
        assert_eq!(streamed.summary, kept.summary);
    }
}

/// A run that fails part-way keeps what it wrote as it went: its history and its event log,
/// under their partial names, which the error names; no older run's files stay beside them to
/// pass for its own. A run that ends leaves no partial file.
#[test]
fn a_run_that_fails_part_way_keeps_its_history_and_events() {
    let dir = common::scratch("out");
    let out = dir.to_str().unwrap();
    let names = || {
        let mut n: Vec<String> = std::fs::read_dir(&*dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        n.sort();
        n
    };
    let args = [
        "run",
        WALL,
        "--sine",
        "400gal",
        "--freq",
        "1",
        "--duration",
        "3",
    ];
    let (code, _, err) = common::pirqa(&[&args[..], &["--out", out]].concat(), &[]);
    assert_eq!(code, 0, "{err}");
    assert!(
        names().iter().all(|n| !n.ends_with(".partial")),
        "{:?}",
        names()
    );
    // The regularized method with a step floor of 1e-12 s stops at the first impact.
    let failing = [
        "--method",
        "regularized",
        "--rtol",
        "1e-10",
        "--eps",
        "1e-12",
    ];
    let (code, _, err) = common::pirqa(&[&args[..], &failing, &["--out", out]].concat(), &[]);
    assert_eq!(code, 1, "{err}");
    let kept = [".events.jsonl.partial", ".history.csv.partial"];
    assert!(err.contains("the step fell below"), "{err}");
    for name in kept {
        assert!(err.contains(&format!("{out}/{name}")), "{err}");
    }
    // The wall stays: a case's folder is rerun from its copy.
    assert_eq!(names(), [kept[0], kept[1], "wall.ron"]);
    let events = std::fs::read_to_string(dir.join(kept[0])).unwrap();
    let last: serde_json::Value = serde_json::from_str(events.lines().last().unwrap()).unwrap();
    assert_eq!(last["kind"], "impact");
    let history = std::fs::read_to_string(dir.join(kept[1])).unwrap();
    assert!(history.starts_with("time_s,u_B1_m,") && history.lines().count() >= 2);
}

/// The event and decision logs written as the run goes are the run's logs: a run stopped by an
/// error at its first impact leaves, line for line, the events and the mode decisions the whole
/// run logs before it (a decision's CPU time aside).
#[test]
fn the_event_log_written_as_a_run_goes_is_the_logs_beginning() {
    use pirqa::integrate::event::{EventDriven, Params};
    use pirqa::integrate::{Integrator, Scenario, Settings};
    let wall = pirqa::Wall::load(std::path::Path::new(WALL)).unwrap();
    let topology = pirqa::Topology::new(&wall).unwrap();
    let motion = crate::engine::sine(4.0, 1.0, 0.0, 20.0);
    let dir = common::scratch("out");
    let settings = Settings {
        log_events: true,
        events_file: Some(dir.join("events.jsonl")),
        log_decisions: true,
        decisions_file: Some(dir.join("decisions.jsonl")),
        ..Settings::summary_only(20.0)
    };
    let run = |params: Params| {
        EventDriven { params }.run(&Scenario {
            wall: &wall,
            topology: &topology,
            motion: &motion,
            settings: &settings,
        })
    };
    let whole = run(Params::default()).unwrap();
    assert!(whole.summary.impacts > 0);
    let partial = dir.join(".events.jsonl.partial");
    assert!(
        !partial.exists(),
        "a run that ends takes its partial file away"
    );
    let strict = Params {
        max_collisions_per_chain: Some(0),
        ..Params::default()
    };
    assert!(run(strict).is_err());
    let kept = std::fs::read_to_string(&partial).unwrap();
    let lines: Vec<&str> = kept.lines().collect();
    let first_impact = whole
        .events
        .iter()
        .position(|e| e.kind == pirqa::response::EventKind::Impact)
        .unwrap();
    assert!(
        lines.len() >= 10 && lines.len() <= first_impact,
        "{}",
        lines.len()
    );
    for (line, event) in lines.iter().zip(&whole.events) {
        assert_eq!(*line, serde_json::to_string(event).unwrap());
    }
    assert!(!dir.join("decisions.jsonl").exists());
    let kept = std::fs::read_to_string(dir.join(".decisions.jsonl.partial")).unwrap();
    let lines: Vec<&str> = kept.lines().collect();
    assert!(
        lines.len() >= 5 && lines.len() <= whole.decisions.len(),
        "{} of {}",
        lines.len(),
        whole.decisions.len()
    );
    // The text without its `"cpu_s":...` field.
    let timeless = |line: &str| -> String {
        let at = line.find("\"cpu_s\":").unwrap();
        let end = line[at..].find([',', '}']).unwrap();
        format!("{}{}", &line[..at], &line[at + end..])
    };
    for (line, decision) in lines.iter().zip(&whole.decisions) {
        assert_eq!(
            timeless(line),
            timeless(&serde_json::to_string(decision).unwrap())
        );
    }
}
