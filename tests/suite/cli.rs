//! The command line end to end: what a user types and what they get back.

use crate::common;

use common::scratch as temp_dir;
use std::process::Command;

fn pirqa(args: &[&str]) -> (bool, String, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_pirqa"))
        .args(args)
        .output()
        .expect("pirqa runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// `pirqa sweep FILE --case N --no-history --out DIR`, which must succeed: the case's folder.
fn sweep_case(file: &std::path::Path, case: usize, out: &std::path::Path) -> std::path::PathBuf {
    let n = case.to_string();
    let (ok, _, err) = pirqa(&[
        "sweep",
        file.to_str().unwrap(),
        "--case",
        &n,
        "--no-history",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    out.join(format!("case-{case}"))
}

#[test]
fn check_prints_the_six_joints_with_their_capacities() {
    let (ok, out, err) = pirqa(&["check", "walls/five-block-variable.ron"]);
    assert!(ok, "{err}");
    for line in [
        "B1       ground        1.200    29947.97     0.290      8684.91",
        "B2       ground        1.200    29947.97     0.310      9283.87",
        "B3       B1            0.600     7486.99     0.280      2096.36",
        "B4       B1            0.600     7486.99     0.300      2246.10",
        "B4       B2            0.600     7486.99     0.300      2246.10",
        "B5       B2            0.600     7486.99     0.280      2096.36",
    ] {
        assert!(out.contains(line), "missing `{line}` in\n{out}");
    }
}

#[test]
fn check_json_has_blocks_supports_and_joints() {
    let (ok, out, err) = pirqa(&["check", "walls/five-block-variable.ron", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert_eq!(v["blocks"].as_array().unwrap().len(), 5);
    assert_eq!(v["blocks"][0]["name"], "B1");
    assert_eq!(v["blocks"][0]["mass_kg"], 1526.4);
    let s = &v["supports"][2];
    assert_eq!(
        (s["upper"].as_str(), s["lower"].as_str()),
        (Some("B3"), Some("B1"))
    );
    assert_eq!(s["friction"], 0.28);
    assert!(
        (s["capacity_n"].as_f64().unwrap() - 0.28 * 0.6 * 0.8 * 0.6 * 2650.0 * 9.81).abs() < 1e-9
    );
    assert_eq!(v["joints"].as_array().unwrap().len(), 3);
    assert_eq!(v["joints"][0]["gap_m"], 0.0);
}

/// A wall of columns: `check` says where each joint gives way (its friction and its tipping
/// ratios, the part above rigid) and which the column moves on; the slender top of the stack
/// (0.2 x 0.8 m: b/h = 0.25) tips before the stack under it (its two blocks and the top:
/// centroid 0.6241 m above the ground, 0.5 / 0.6241 = 0.8011). Walls that are not columns get
/// no such table (and their JSON no `columns`).
#[test]
fn check_gives_a_columns_joint_limits_and_the_joint_it_moves_on() {
    let (ok, out, err) = pirqa(&["check", "walls/rocking/slender-on-stack.ron"]);
    assert!(ok, "{err}");
    for line in [
        "Base/ground   0.8000       0.8011        0.8011",
        "Top/Middle    0.8000       0.2500        0.2500  <- gives way first: Top moves on it",
    ] {
        assert!(out.contains(line), "missing `{line}` in\n{out}");
    }
    let (ok, out, err) = pirqa(&["check", "walls/rocking/slender-on-stack.ron", "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let joints = v["columns"][0].as_array().unwrap();
    assert_eq!(joints.len(), 3);
    assert_eq!(joints[2]["joint"], "Top/Middle");
    assert_eq!(joints[2]["tips_left_g"], 0.25);
    assert_eq!(joints[2]["moves"], true);
    assert_eq!(joints[0]["moves"], false);
    assert_eq!(v["blocks"].as_array().unwrap().len(), 3);
    let (_, out, _) = pirqa(&["check", "walls/five-block-variable.ron", "--json"]);
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!(v.get("columns").is_none());
}

/// `check` gives the limit at rest each way, exact, and the mechanism beyond it: the paper's
/// variable wall lets B3 (friction 0.28 on B1) slide first towards -x, and B5 (0.28 on B2)
/// towards +x; the two-block column turns as one about the lower drum's corner at b/h of the
/// whole column (0.5 / 3.0 = 1/6).
#[test]
fn check_gives_the_limit_at_rest_and_its_mechanism() {
    let (ok, out, err) = pirqa(&["check", "walls/five-block-variable.ron", "--limit"]);
    assert!(ok, "{err}");
    for line in [
        "  ground towards +x: held up to 0.2800 g (2.7468 m/s2; exactly 7/25 g), then\n    B3       slides towards -x\n",
        "  ground towards -x: held up to 0.2800 g (2.7468 m/s2; exactly 7/25 g), then\n    B5       slides towards +x\n",
    ] {
        assert!(out.contains(line), "missing `{line}` in\n{out}");
    }
    let (ok, out, err) = pirqa(&[
        "check",
        "walls/rocking/two-block-column.ron",
        "--json",
        "--limit",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    let plus = &v["limit_at_rest"]["towards_plus_x"];
    assert_eq!(plus["kind"], "holds");
    assert_eq!(plus["exact_g"], "1/6");
    assert_eq!(
        plus["mechanism"][1]["how"],
        "turns counterclockwise about Drum1's bottom-left corner"
    );
    assert!(v.get("limit_at_rest_not_computed").is_none());
    // The mechanisms drawn, beside the limits they were drawn from.
    let dir = temp_dir("limit-mechanism");
    let drawn = |wall: &str| {
        pirqa(&[
            "check",
            wall,
            "--limit",
            "--mechanism",
            dir.to_str().unwrap(),
        ])
    };
    let (ok, _, err) = drawn("walls/rocking/two-block-column.ron");
    assert!(ok, "{err}");
    let saved: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("limit.json")).unwrap()).unwrap();
    assert_eq!(saved, v["limit_at_rest"]);
    assert_eq!(plus["mechanism_uniqueness"], "unique");
    for side in ["plus-x", "minus-x"] {
        let svg = std::fs::read_to_string(dir.join(format!("mechanism-{side}.svg"))).unwrap();
        assert!(
            svg.contains("past its limit at rest")
                && svg.contains("Drum2")
                && svg.contains("the mechanism, exaggerated"),
            "{svg}"
        );
    }
    // Where others hold at the limit too (the uniform wall: any part sliding on its bed reaches
    // 0.3 g), the report and the drawings say so.
    let several = "one of several mechanisms that hold at this limit";
    let (ok, out, err) = drawn("walls/five-block-uniform.ron");
    assert!(ok && out.matches(several).count() == 2, "{out}{err}");
    // Every one of them moves the top end block the blocks slide towards, and no other.
    for end in ["B3", "B5"] {
        let every = format!("in every mechanism that holds here: moving {end}; turning none");
        assert!(out.contains(&every), "{out}");
    }
    let svg = std::fs::read_to_string(dir.join("mechanism-minus-x.svg")).unwrap();
    assert!(svg.contains(&format!("{several}, exaggerated")), "{svg}");
    // Beyond 200 blocks: a bond of one friction (203 blocks) is one of several, its basis
    // showing another at once, and its top end blocks move in every mechanism; slender blocks
    // tipping at 4/75 g (244 blocks, degenerate in a few rows, their basis showing no other)
    // are decided unique by the program of directions; beyond 500 blocks (a course of 510
    // slender ones, any run of them from an end tipping) the report says up to where the
    // blocks in every mechanism are decided.
    let generated = |name: &str, spec: &[&str]| {
        let wall = dir.join(name);
        let (ok, _, err) = pirqa(&[&["generate"], spec, &["-o", wall.to_str().unwrap()]].concat());
        assert!(ok, "{err}");
        pirqa(&["check", wall.to_str().unwrap(), "--limit"])
    };
    let (ok, out, err) = generated("bond.ron", &["--blocks", "190"]);
    assert!(ok && out.matches(several).count() == 2, "{out}{err}");
    for end in ["B189", "B203"] {
        let every = format!("in every mechanism that holds here: moving {end}; turning none");
        assert!(out.contains(&every), "{out}");
    }
    let row = ["--courses", "1", "--blocks-per-course", "510"];
    let (ok, out, err) = generated("row.ron", &row);
    assert!(ok && out.matches(several).count() == 2, "{out}{err}");
    let beyond = "(which blocks move in every mechanism that holds here is decided for walls of \
                  up to 500 movable blocks)";
    assert_eq!(out.matches(beyond).count(), 2, "{out}");
    let slender = [
        "--courses",
        "8",
        "--blocks-per-course",
        "30",
        "--friction",
        "0.6",
        "--height",
        "3m",
        "--width",
        "1.2m",
    ];
    let (ok, out, err) = generated("slender.ron", &slender);
    assert!(ok && out.contains("exactly 4/75 g"), "{out}{err}");
    assert!(
        !out.contains("one of several") && !out.contains("not decided"),
        "{out}"
    );
    // A wall beyond the exact program's size: the report says why; drawings asked for are an
    // error that says it too.
    let blocks = vec!["(width_m: 1.0)"; 2001].join(", ");
    let big = common::file(
        "long.ron",
        &format!(
            "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.3, \
             rows: [(height_m: 0.5, blocks: [{blocks}])])"
        ),
    );
    let (ok, out, err) = pirqa(&["check", big.to_str().unwrap(), "--limit"]);
    assert!(ok, "{err}");
    assert!(out.contains("not computed: the limit at rest is computed for walls of up to 2000"));
    let (ok, _, err) = drawn(big.to_str().unwrap());
    assert!(!ok && err.contains("up to 2000 movable blocks"), "{err}");
    // Asked for only: a plain check stays a table of the graph.
    let (_, out, _) = pirqa(&["check", "walls/five-block-variable.ron"]);
    assert!(!out.contains("limit at rest"), "{out}");
}

#[test]
fn invalid_input_exits_non_zero_with_the_file_named() {
    let (ok, _, err) = pirqa(&["check", "walls/does-not-exist.ron"]);
    assert!(!ok);
    assert!(err.starts_with("error: walls/does-not-exist.ron"), "{err}");
}

#[test]
fn draw_writes_an_svg_with_names_and_friction() {
    let out = temp_dir("wall.svg");
    let (ok, _, err) = pirqa(&[
        "draw",
        "walls/five-block-variable.ron",
        "-o",
        out.to_str().unwrap(),
        "--graph",
    ]);
    assert!(ok, "{err}");
    let svg = std::fs::read_to_string(&out).unwrap();
    assert!(svg.starts_with("<svg"));
    for text in [">B1<", ">B5<", "\u{3bc} 0.28", "\u{3bc} 0.31"] {
        assert!(svg.contains(text), "missing {text}");
    }
}

/// `pirqa run` on the paper's variable wall, 400 gal at 1 Hz for 5 s, into `out`.
fn run_five_block(out: &std::path::Path, extra: &[&str]) -> (bool, String, String) {
    let mut args = vec!["--out", out.to_str().unwrap()];
    args.extend(extra);
    five_block(&args)
}

/// The five-block variable wall under the paper's sine (400 gal, 1 Hz, 5 s), with `extra`.
fn five_block(extra: &[&str]) -> (bool, String, String) {
    let mut args = vec![
        "run",
        "walls/five-block-variable.ron",
        "--sine",
        "400gal",
        "--freq",
        "1",
        "--duration",
        "5",
    ];
    args.extend(extra);
    pirqa(&args)
}

#[test]
fn run_writes_summary_history_and_events() {
    let out = temp_dir("run");
    let (ok, stdout, err) = run_five_block(&out, &[]);
    assert!(ok, "{err}");
    assert!(
        stdout.contains("B3") && stdout.contains("residual"),
        "{stdout}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["method"], "event");
    assert_eq!(summary["duration_s"], 5.0);
    assert_eq!(summary["blocks"].as_array().unwrap().len(), 5);
    for key in [
        "max_abs_displacement_m",
        "final_displacement_m",
        "max_abs_velocity_m_s",
    ] {
        assert!(summary["blocks"][0][key].is_number(), "{key}");
    }
    for key in [
        "upper",
        "lower",
        "max_abs_relative_displacement_m",
        "final_relative_displacement_m",
    ] {
        assert!(!summary["joints"][0][key].is_null(), "{key}");
    }
    for key in [
        "input_j",
        "friction_j",
        "impact_loss_j",
        "kinetic_j",
        "residual_j",
    ] {
        assert!(summary["energy"][key].is_number(), "{key}");
    }
    assert!(summary["collapse"].is_null());
    assert!(summary["impacts"].is_number() && summary["stick_slip_transitions"].is_number());
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let mut lines = history.lines();
    assert_eq!(
        lines.next().unwrap(),
        "time_s,u_B1_m,u_B2_m,u_B3_m,u_B4_m,u_B5_m,v_B1_m_s,v_B2_m_s,v_B3_m_s,v_B4_m_s,v_B5_m_s"
    );
    assert!(lines.count() > 500, "every 0.01 s plus every event");
    let events = std::fs::read_to_string(out.join("events.jsonl")).unwrap();
    let first: serde_json::Value = serde_json::from_str(events.lines().next().unwrap()).unwrap();
    assert_eq!(first["kind"], "slip");
    assert!(first["time_s"].is_number());
    assert!(
        !out.join("decisions.jsonl").exists(),
        "the decision log only when asked for"
    );
}

#[test]
fn run_logs_its_decisions_when_asked() {
    let out = temp_dir("decisions");
    let (ok, stdout, err) = run_five_block(&out, &["--decisions"]);
    assert!(ok, "{err}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    let decisions = std::fs::read_to_string(out.join("decisions.jsonl")).unwrap();
    let log: Vec<serde_json::Value> = decisions
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(
        log.len() as u64,
        summary["stats"]["mode_decisions"].as_u64().unwrap()
    );
    assert_eq!(log[0]["cause"], "start");
    let wall = &log[0]["stuck_formed"];
    assert_eq!(wall["blocks"], 5);
    // The wall at rest holds until B3 or B5, each alone on a joint of mu 0.28, slides: a_g =
    // 0.28 g = 2.7468 m/s2 either way (the nearest float to the exact limit).
    assert_eq!(wall["a_g_lo_m_s2"].as_f64(), Some(-2.7468));
    assert_eq!(wall["a_g_hi_m_s2"].as_f64(), Some(2.7468));
    for key in [
        "time_s",
        "a_g_m_s2",
        "blocks",
        "clusters",
        "flow_nodes",
        "cpu_s",
    ] {
        assert!(log[1][key].is_number(), "{key}");
    }
    assert!(
        stdout.contains("mode decisions: ") && stdout.contains("stick_limit"),
        "{stdout}"
    );
    // The table's counts add up to the log.
    let counted: u64 = stdout
        .lines()
        .skip_while(|l| !l.contains("mode decisions: "))
        .skip(2)
        .map(|l| l.split_whitespace().nth(2).unwrap().parse::<u64>().unwrap())
        .sum();
    assert_eq!(counted, log.len() as u64);

    let (ok, _, err) = run_five_block(&out, &["--method", "paper", "--decisions"]);
    assert!(
        !ok && err.contains("--decisions: only the event-driven integrator"),
        "{err}"
    );

    // Run again into the same directory without the log: the earlier run's log goes.
    let (ok, _, err) = run_five_block(&out, &[]);
    assert!(ok, "{err}");
    assert!(!out.join("decisions.jsonl").exists());
}

/// `--no-history` keeps the logs and leaves history.csv out, removing one an earlier run left;
/// it needs --out and does not go with --output-dt.
#[test]
fn run_without_history_keeps_the_logs() {
    let out = temp_dir("no-history");
    let (ok, _, err) = run_five_block(&out, &[]);
    assert!(ok, "{err}");
    assert!(out.join("history.csv").exists());
    let events = std::fs::read_to_string(out.join("events.jsonl")).unwrap();
    let (ok, stdout, err) = run_five_block(&out, &["--no-history", "--decisions"]);
    assert!(ok, "{err}");
    assert!(
        !out.join("history.csv").exists(),
        "the earlier history goes"
    );
    assert_eq!(
        std::fs::read_to_string(out.join("events.jsonl")).unwrap(),
        events
    );
    assert!(out.join("decisions.jsonl").exists() && out.join("summary.json").exists());
    assert!(
        stdout.contains("/summary.json, events.jsonl, decisions.jsonl"),
        "{stdout}"
    );
    let (ok, _, err) = run_five_block(&out, &["--no-history", "--output-dt", "0.1"]);
    assert!(!ok && err.contains("--output-dt"), "{err}");
    let (ok, _, err) = five_block(&["--no-history"]);
    assert!(!ok && err.contains("--out"), "{err}");
}

#[test]
fn amplitudes_in_gal_g_and_m_s2_give_the_same_run() {
    let mut maxima = Vec::new();
    for amp in ["400gal", "4m/s2", "4.0 m/s^2"] {
        let file = temp_dir("units.json");
        let (ok, _, err) = pirqa(&[
            "run",
            "walls/five-block-uniform.ron",
            "--sine",
            amp,
            "--freq",
            "2",
            "--duration",
            "3",
            "--summary",
            file.to_str().unwrap(),
        ]);
        assert!(ok, "{err}");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
        maxima.push(s["blocks"][0]["max_abs_displacement_m"].as_f64().unwrap());
    }
    assert!(
        maxima.windows(2).all(|w| (w[0] - w[1]).abs() < 1e-15),
        "{maxima:?}"
    );
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-uniform.ron",
        "--sine",
        "0.41g",
        "--freq",
        "2",
        "--duration",
        "1",
    ]);
    assert!(ok, "{err}");
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-uniform.ron",
        "--sine",
        "400",
        "--freq",
        "2",
        "--duration",
        "1",
    ]);
    assert!(!ok && err.contains("gal, g, m/s2"), "{err}");
}

#[test]
fn run_takes_a_plain_record_with_a_scale_factor() {
    let dir = temp_dir("record");
    std::fs::create_dir_all(&dir).unwrap();
    let rec = dir.join("pulse.txt");
    let values: Vec<String> = (0..300)
        .map(|k| format!("{}", 300.0 * (k as f64 * 0.05).sin()))
        .collect();
    std::fs::write(
        &rec,
        format!("# units: gal\n# dt_s: 0.01\n{}\n", values.join("\n")),
    )
    .unwrap();
    let (ok, out, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--record",
        rec.to_str().unwrap(),
        "--scale",
        "1.5",
    ]);
    assert!(ok, "{err}");
    assert!(
        out.contains("record pulse.txt") && out.contains("PGA 4.5"),
        "{out}"
    );
    std::fs::write(&rec, "1\n2\n3\n").unwrap();
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--record",
        rec.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("pulse.txt") && err.contains("units"),
        "{err}"
    );
}

#[test]
fn motion_info_json_has_units_in_its_keys() {
    let (ok, out, err) = pirqa(&[
        "motion",
        "info",
        "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    for key in [
        "pga_m_s2",
        "pgv_m_s",
        "pgd_m",
        "arias_m_s",
        "d5_95_s",
        "tm_s",
        "npts",
        "dt_s",
    ] {
        assert!(v[key].is_number(), "{key}");
    }
    assert_eq!(v["npts"], 4000);
    assert!((v["pga_m_s2"].as_f64().unwrap() / 9.81 - 0.3129).abs() < 1e-4);
    // El Centro 1940: Arias intensity about 1.7 m/s, D5-95 about 24 s.
    assert!((v["arias_m_s"].as_f64().unwrap() - 1.68).abs() < 0.05);
    assert!((v["d5_95_s"].as_f64().unwrap() - 24.1).abs() < 0.5);
    let svg = temp_dir("info.svg");
    let (ok, _, err) = pirqa(&[
        "motion",
        "info",
        "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
        "--plot",
        svg.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(std::fs::read_to_string(&svg)
        .unwrap()
        .contains("Fourier amplitude spectrum"));
    let data = std::fs::read_to_string(svg.with_extension("csv")).unwrap();
    assert!(data.starts_with("chart,series,x,y"));
    // The acceleration drawn peaks at the record's PGA (from the JSON above), exactly.
    let drawn = data
        .lines()
        .filter(|l| l.starts_with("\"ground acceleration"))
        .map(|l| l.rsplit(',').next().unwrap().parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max);
    assert_eq!(drawn, v["pga_m_s2"].as_f64().unwrap());
}

#[test]
fn generated_motions_read_back_and_run() {
    let dir = temp_dir("generate");
    let file = dir.join("miyagi-like.txt");
    let (ok, _, err) = pirqa(&[
        "motion",
        "generate",
        "miyagi-like",
        "-o",
        file.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let (ok, out, err) = pirqa(&["motion", "info", file.to_str().unwrap(), "--json"]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&out).unwrap();
    assert!((v["pga_m_s2"].as_f64().unwrap() - 2.58).abs() < 1e-6);
    let (ok, out, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--record",
        file.to_str().unwrap(),
        "--scale",
        "5",
    ]);
    assert!(ok && out.contains("B3"), "{err}");
    for kind in [
        vec![
            "sine",
            "--amp",
            "300gal",
            "--freq",
            "2",
            "--duration",
            "5",
            "--ramp",
            "1",
            "--taper",
            "1",
        ],
        vec![
            "chirp",
            "--amp",
            "0.2g",
            "--f0",
            "0.5",
            "--f1",
            "8",
            "--duration",
            "20",
        ],
        vec![
            "ricker",
            "--amp",
            "3m/s2",
            "--freq",
            "1.5",
            "--duration",
            "4",
        ],
        vec!["pulse", "--amp", "3m/s2", "--freq", "1", "--duration", "3"],
        vec![
            "kanai-tajimi",
            "--pga",
            "0.3g",
            "--fg",
            "2.5",
            "--duration",
            "20",
            "--seed",
            "7",
        ],
    ] {
        let f = dir.join(format!("{}.txt", kind[0]));
        let mut args = vec!["motion", "generate"];
        args.extend(kind.iter().copied());
        args.extend(["-o", f.to_str().unwrap()]);
        let (ok, _, err) = pirqa(&args);
        assert!(ok, "{kind:?}: {err}");
        let text = std::fs::read_to_string(&f).unwrap();
        assert!(text.contains("# units: m/s2") && text.contains("# dt_s: 0.01"));
    }
}

#[test]
fn a_tall_block_rocks_and_the_sliding_model_says_it_would() {
    let dir = temp_dir("tall");
    std::fs::create_dir_all(&dir).unwrap();
    let wall = dir.join("tall.ron");
    std::fs::write(&wall, "(version: 1, thickness_m: 1, density_kg_m3: 2000, friction: 0.6, rows: [(height_m: 2.0, blocks: [(width_m: 0.5)])])").unwrap();
    let summary = dir.join("s.json");
    let run = |model: &str| {
        pirqa(&[
            "run",
            wall.to_str().unwrap(),
            "--sine",
            "0.3g",
            "--freq",
            "1",
            "--duration",
            "3",
            "--model",
            model,
            "--summary",
            summary.to_str().unwrap(),
        ])
    };
    // Sliding only, it is flagged.
    let (ok, out, err) = run("slide");
    assert!(ok, "{err}");
    assert!(
        out.contains("warning: B1") && out.contains("Housner"),
        "{out}"
    );
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
    assert_eq!(s["warnings"].as_array().unwrap().len(), 1);
    assert_eq!(s["model"]["name"], "slide");
    // By default (auto) it is computed: it lifts where the sine reaches g b/h = 0.25 g.
    let (ok, out, err) = run("auto");
    assert!(ok, "{err}");
    assert!(!out.contains("warning:"), "{out}");
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&summary).unwrap()).unwrap();
    assert_eq!(s["model"]["name"], "slide-rock");
    assert!(
        s["model"]["why"].as_str().unwrap().contains("can lift"),
        "{s}"
    );
    let uplift = s["blocks"][0]["uplift_time_s"].as_f64().unwrap();
    let want = (0.25f64 / 0.3).asin() / (2.0 * std::f64::consts::PI);
    assert!((uplift - want).abs() < 1e-13, "{uplift} vs {want}");
    assert!(s["blocks"][0]["max_abs_rotation_rad"].as_f64().unwrap() > 0.0);
    // The squat five-block wall under the same motion gets none.
    let (ok, out, _) = pirqa(&[
        "run",
        "walls/five-block-uniform.ron",
        "--sine",
        "0.3g",
        "--freq",
        "1",
        "--duration",
        "3",
    ]);
    assert!(ok && !out.contains("warning:"), "{out}");
}

#[test]
fn run_checks_uplift_when_asked_and_refuses_walls_too_large_for_it() {
    let dir = temp_dir("uplift");
    let (ok, out, err) = pirqa(&[
        "run",
        "walls/inca/ollantaytambo-monoliths.ron",
        "--model",
        "slide",
        "--check-uplift",
        "--record",
        "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
        "--pga",
        "0.3g",
        "--no-history",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(
        out.contains("uplift check: at t = 2.13")
            && out.contains("F5 turns clockwise about its bottom-right corner")
            && out.contains("warning: at t = 2.13"),
        "{out}"
    );
    let s: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let first = &s["uplift_check"]["first_uplift"];
    assert_eq!(
        first["turning"][0],
        "F5 turns clockwise about its bottom-right corner"
    );
    assert!((first["ground_accel_m_s2"].as_f64().unwrap() + 0.2834 * 9.81).abs() < 0.001);
    assert_eq!(first["mechanism_uniqueness"], "unique");
    assert!(!out.contains("one of several"), "{out}");
    // Twin slabs standing apart lift at one instant, either or both: the report says so.
    let twins = dir.join("twins.ron");
    std::fs::write(
        &twins,
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6, rows: [(height_m: \
         1.2, blocks: [(width_m: 0.6), (width_m: 0.6, gap_m: 0.2)])])",
    )
    .unwrap();
    // A second of a 1 Hz sine, watched.
    let watched = |wall: &std::path::Path, amplitude: &str, model: &[&str]| {
        let sine = ["--sine", amplitude, "--freq", "1", "--duration", "1"];
        let run = ["run", wall.to_str().unwrap(), "--check-uplift"];
        pirqa(&[&run[..], model, &sine].concat())
    };
    let (ok, out, err) = watched(&twins, "0.55g", &["--model", "slide"]);
    assert!(ok, "{err}");
    assert!(
        out.contains(
            "(one of several mechanisms that hold at this limit; turning in every one: none)"
        ),
        "{out}"
    );
    // A course of 510 slender blocks, any run of them from an end turning: beyond the 500
    // movable blocks up to which the blocks turning in every mechanism are decided, the report
    // says so.
    let row = dir.join("row.ron");
    let spec = [
        "--courses",
        "1",
        "--blocks-per-course",
        "510",
        "--width",
        "51m",
    ];
    let (ok, _, err) = pirqa(&[&["generate"], &spec[..], &["-o", row.to_str().unwrap()]].concat());
    assert!(ok, "{err}");
    let (ok, out, err) = watched(&row, "0.3g", &["--model", "slide"]);
    assert!(ok, "{err}");
    assert!(
        out.contains(
            "(one of several mechanisms that hold at this limit; which blocks turn in every one \
             is decided for walls of up to 500 movable blocks)"
        ),
        "{out}"
    );
    // 25 courses of 25 (637 blocks): more movable blocks than the exact program takes.
    let wall = dir.join("large.ron");
    let (ok, _, err) = pirqa(&[
        "generate",
        "--courses",
        "25",
        "--blocks-per-course",
        "25",
        "-o",
        wall.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let (ok, _, err) = watched(&wall, "0.3g", &[]);
    assert!(!ok && err.contains("up to 600 movable blocks"), "{err}");
}

#[test]
fn every_method_writes_the_same_outputs_with_its_name() {
    for (method, extra) in [
        ("event", vec![]),
        ("paper", vec!["--dt", "1e-3"]),
        ("moreau", vec!["--dt", "1e-3"]),
        (
            "regularized",
            vec!["--rtol", "1e-5", "--eps", "1e-4", "--stiffness", "1e9"],
        ),
    ] {
        let out = temp_dir(&format!("method-{method}"));
        let mut args = vec![
            "run",
            "walls/five-block-variable.ron",
            "--sine",
            "400gal",
            "--freq",
            "1",
            "--duration",
            "3",
            "--method",
            method,
            "--out",
            out.to_str().unwrap(),
        ];
        args.extend(extra);
        let (ok, _, err) = pirqa(&args);
        assert!(ok, "{method}: {err}");
        let s: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(s["method"], method);
        assert_eq!(s["blocks"].as_array().unwrap().len(), 5);
        let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
        assert!(history.starts_with("time_s,"), "{method}");
        assert!(history.lines().count() >= 301, "{method}");
        assert!(out.join("events.jsonl").exists(), "{method}");
    }
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--sine",
        "400gal",
        "--freq",
        "1",
        "--duration",
        "1",
        "--method",
        "moreau",
        "--dt=-1e-3",
    ]);
    assert!(!ok);
    assert!(
        err.contains("time step -0.001 s") && err.contains("positive"),
        "{err}"
    );
}

#[test]
fn bench_work_precision_quick_writes_the_chart_its_data_and_the_reach_table() {
    let out = temp_dir("work-precision");
    let (ok, stdout, err) = pirqa(&[
        "bench",
        "work-precision",
        "--quick",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let csv = std::fs::read_to_string(out.join("work-precision.csv")).unwrap();
    for scenario in [
        "one block sine",
        "five-block uniform sine",
        "five-block variable sine",
        "five-block variable El Centro x5",
    ] {
        for method in ["event", "paper", "moreau", "regularized"] {
            assert!(
                csv.lines()
                    .any(|l| l.starts_with(&format!("{scenario},{method},"))),
                "{scenario} {method}"
            );
        }
    }
    assert!(csv.contains("one block sine,event,exact,"));
    let svg = std::fs::read_to_string(out.join("work-precision.svg")).unwrap();
    assert!(svg.contains("<svg") && svg.contains("CPU time per run (s)"));
    let reach = std::fs::read_to_string(out.join("work-precision-reach.csv")).unwrap();
    assert_eq!(reach, stdout);
    assert!(reach.contains("one block sine,event,1e-9,exact,"));
    // Redrawn from the saved points: the same table, no runs.
    let again = temp_dir("work-precision-from");
    let (ok, stdout, err) = pirqa(&[
        "bench",
        "work-precision",
        "--from",
        out.join("work-precision.csv").to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert_eq!(stdout, reach);
    assert!(again.join("work-precision.svg").exists());
    let broken = again.join("broken.csv");
    std::fs::write(
        &broken,
        "scenario,method,parameter,cpu_s,err_max_m,err_history_m,failed\none,two\n",
    )
    .unwrap();
    let (ok, _, err) = pirqa(&[
        "bench",
        "work-precision",
        "--from",
        broken.to_str().unwrap(),
        "--out",
        again.to_str().unwrap(),
    ]);
    assert!(!ok);
    assert!(
        err.contains("broken.csv: line 2: expected 7 fields, found 2"),
        "{err}"
    );
}

#[test]
fn bench_failures_writes_the_panels_and_the_measured_numbers() {
    let out = temp_dir("failures");
    let (ok, _, err) = pirqa(&["bench", "failures", "--out", out.to_str().unwrap()]);
    assert!(ok, "{err}");
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("failures.json")).unwrap()).unwrap();
    assert_eq!(json["drift exact creep (m)"], 0.0);
    assert_eq!(json["zeno exact accumulations"], 1.0);
    assert_eq!(json["grazing exact impacts"], 1.0);
    assert_eq!(json["grazing moreau dt=1e-2 impacts"], 0.0);
    let svg = std::fs::read_to_string(out.join("failures.svg")).unwrap();
    for title in [
        "Drift",
        "Chatter",
        "Energy",
        "Step collapse",
        "Zeno",
        "Grazing",
    ] {
        assert!(svg.contains(title), "{title}");
    }
    assert!(std::fs::read_to_string(out.join("failures.csv"))
        .unwrap()
        .starts_with("chart,series,x,y\n"));
}

/// `pirqa draw --run` draws where a run left the blocks: at the end (fallen blocks marked), or
/// at a time before the first fall; a time outside the run, or a run of another wall, is an
/// error that says so.
#[test]
fn draw_shows_a_run_at_its_end_and_at_a_chosen_time() {
    let dir = temp_dir("draw-run");
    let run = dir.join("run");
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--sine",
        "500gal",
        "--freq",
        "0.2",
        "--duration",
        "10",
        "--after-collapse",
        "continue",
        "--out",
        run.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let draw_on = |wall: &str, run: &std::path::Path, extra: &[&str]| {
        let svg = dir.join("wall.svg");
        let _ = std::fs::remove_file(&svg);
        let mut args = vec![
            "draw",
            wall,
            "-o",
            svg.to_str().unwrap(),
            "--run",
            run.to_str().unwrap(),
        ];
        args.extend_from_slice(extra);
        let (ok, _, err) = pirqa(&args);
        (ok, std::fs::read_to_string(&svg).unwrap_or_default(), err)
    };
    let draw = |extra: &[&str]| draw_on("walls/five-block-variable.ron", &run, extra);
    // B5 falls at 2.7225 s, B3 right after (see docs/paper.md).
    let (ok, end, err) = draw(&[]);
    assert!(ok, "{err}");
    assert!(end.contains("final state, t = 10 s"), "{end}");
    assert!(end.contains("B5 (fell)") && end.contains("B3 (fell)"));
    let (ok, before, err) = draw(&["--at", "2.7"]);
    assert!(ok, "{err}");
    assert!(before.contains("t = 2.7 s") && !before.contains("(fell)"));
    // Nothing turned: blocks are rectangles moved by u.
    assert!(!end.contains("<polygon") && !before.contains("<polygon"));
    // A rocking trilith: its three blocks drawn turned and lifted (polygons), at the end too.
    let trilith = dir.join("trilith");
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/rocking/trilith.ron",
        "--sine",
        "0.3g",
        "--freq",
        "1",
        "--duration",
        "2",
        "--out",
        trilith.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    for extra in [&["--at", "1.5"][..], &[]] {
        let (ok, svg, err) = draw_on("walls/rocking/trilith.ron", &trilith, extra);
        assert!(ok, "{err}");
        assert_eq!(svg.matches("<polygon").count(), 3, "{svg}");
        // The labels go with their blocks: the gap's beside the left column's right face at
        // 0.8 of its height, where the run turned it (2 px to the right of the face).
        let numbers = |text: &str| -> Vec<f64> {
            text.split([' ', ','])
                .filter_map(|x| x.parse().ok())
                .collect()
        };
        let left = svg.split("<polygon points=\"").nth(1).unwrap();
        let p = numbers(left.split('"').next().unwrap());
        let (bottom_right, top_right) = ((p[2], p[3]), (p[4], p[5]));
        let label = svg
            .split("<text x=\"")
            .find(|t| t.contains(">gap "))
            .unwrap();
        let x: f64 = label.split('"').next().unwrap().parse().unwrap();
        let y: f64 = label
            .split("y=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap()
            .parse()
            .unwrap();
        let on_face = |a: f64, b: f64| a + 0.8 * (b - a);
        assert!(
            (x - 2.0 - on_face(bottom_right.0, top_right.0)).abs() < 0.02,
            "{label}"
        );
        assert!(
            (y - on_face(bottom_right.1, top_right.1)).abs() < 0.02,
            "{label}"
        );
    }
    let (ok, _, err) = draw(&["--at", "12"]);
    assert!(
        !ok && err.contains("outside the run") && err.contains("10 s"),
        "{err}"
    );
    let (ok, _, err) = pirqa(&[
        "draw",
        "walls/five-block-uniform.ron",
        "-o",
        dir.join("x.svg").to_str().unwrap(),
        "--at",
        "1",
    ]);
    assert!(!ok && err.contains("--run"), "{err}");
    // A run without its history has no state at a time, and says what to do.
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--sine",
        "500gal",
        "--freq",
        "1",
        "--duration",
        "1",
        "--no-history",
        "--out",
        dir.join("bare").to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let (ok, _, err) = draw_on(
        "walls/five-block-variable.ron",
        &dir.join("bare"),
        &["--at", "0.5"],
    );
    assert!(
        !ok && err.contains("history.csv") && err.contains("--no-history"),
        "{err}"
    );
    // A run of another wall with the same block names is refused, not drawn.
    let (ok, _, err) = draw_on("walls/five-block-uniform.ron", &run, &[]);
    assert!(
        !ok && err.contains("summary.json") && err.contains("variable friction\", not of"),
        "{err}"
    );
}

/// `pirqa import` on the survey shipped in docs/walls: the report gives the topology, the
/// largest snap and (with --verbose) every snap; the wall it writes checks and draws.
#[test]
fn import_reports_the_snaps_and_writes_a_wall_that_checks() {
    let dir = temp_dir("import");
    std::fs::create_dir_all(&dir).unwrap();
    let wall = dir.join("wall.ron");
    let (ok, out, err) = pirqa(&[
        "import",
        "docs/walls/example-survey.csv",
        "--units",
        "mm",
        "-o",
        wall.to_str().unwrap(),
        "--verbose",
    ]);
    assert!(ok, "{err}");
    for expect in [
        "9 blocks, 13 supports, 6 vertical joints (1 with a measured gap, widest 12.0 mm)",
        "snapped 25 edges within 5.0 mm; largest adjustment 3.00 mm (B2 bottom onto",
        "  B5         top           0.85200 ->    0.85300 m (+1.00 mm)",
    ] {
        assert!(out.contains(expect), "missing `{expect}` in\n{out}");
    }
    let (ok, out, err) = pirqa(&["check", wall.to_str().unwrap()]);
    assert!(ok, "{err}");
    assert!(out.contains("B3       ground"), "{out}");
    let svg = dir.join("wall.svg");
    let (ok, _, err) = pirqa(&[
        "draw",
        wall.to_str().unwrap(),
        "--graph",
        "-o",
        svg.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    // A broken survey: the error names the file, the line and what to fix.
    let bad = dir.join("bad.csv");
    std::fs::write(&bad, "id,x,y,width,height\nA,0,0,1,0.5\nB,0.5,oops,1,0.5\n").unwrap();
    let (ok, _, err) = pirqa(&[
        "import",
        bad.to_str().unwrap(),
        "-o",
        wall.to_str().unwrap(),
    ]);
    assert!(!ok);
    assert!(
        err.contains("bad.csv: line 3: column `y`: `oops` is not a number"),
        "{err}"
    );
    let (ok, _, err) = pirqa(&[
        "import",
        "docs/walls/example-survey.csv",
        "--units",
        "furlongs",
        "-o",
        wall.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("furlongs") && err.contains("mm, cm, m"),
        "{err}"
    );
}

/// A small sweep end to end; one case rerun in full without the history, and the command its
/// rerun.txt gives reproducing that case's numbers and event log exactly.
#[test]
fn sweep_then_one_case_rerun_without_history_reproduces_itself() {
    let root = env!("CARGO_MANIFEST_DIR");
    let file = common::file(
        "small.ron",
        &format!(
            r#"(
    version: 1,
    name: "small",
    walls: [File(path: "{root}/walls/five-block-variable.ron")],
    motion: Records(
        files: ["{root}/records/elcentro1940_IELC180_peer_dt0p01_g.AT2"],
        pga: ["400gal"],
    ),
    friction: Random(distribution: Lognormal, cov: 0.2, samples: 2, seed: 3),
)"#
        ),
    );
    let out = temp_dir("sweep");
    let (ok, _, err) = pirqa(&[
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let cases = std::fs::read_to_string(out.join("cases.csv")).unwrap();
    assert_eq!(cases.lines().count(), 3, "a header and two cases:\n{cases}");
    let results = std::fs::read_to_string(out.join("results.json")).unwrap();

    // Drawn again from cases.csv alone, to the same numbers; blocks.csv is neither needed nor
    // written.
    std::fs::remove_file(out.join("blocks.csv")).unwrap();
    std::fs::remove_file(out.join("results.json")).unwrap();
    let redraw = [
        "sweep",
        file.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--redraw",
    ];
    let (ok, _, err) = pirqa(&redraw);
    assert!(ok && err.contains("redrawn"), "{err}");
    assert_eq!(
        std::fs::read_to_string(out.join("results.json")).unwrap(),
        results
    );
    assert!(!out.join("blocks.csv").exists());
    let (ok, _, err) = pirqa(&[&redraw[..], &["--fresh"]].concat());
    assert!(!ok && err.contains("--fresh"), "{err}");

    let case = sweep_case(&file, 1, &out);
    assert!(!case.join("history.csv").exists());
    let read = |name: &str| std::fs::read_to_string(case.join(name)).unwrap();
    let (summary, events) = (read("summary.json"), read("events.jsonl"));
    assert!(events.lines().count() > 1, "the case moves:\n{events}");
    let rerun = read("rerun.txt");
    let words: Vec<&str> = rerun.split_whitespace().collect();
    assert_eq!(words[0], "pirqa");
    assert_eq!(words.last(), Some(&"--no-history"), "{rerun}");
    let (ok, _, err) = pirqa(&words[1..]);
    assert!(ok, "{err}");
    assert!(!case.join("history.csv").exists());
    // The same numbers; only the motion's label names the file the rerun read, and the model's
    // reason says the rerun asked for the model that the sweep's auto chose.
    let without_label = |text: &str| {
        let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
        v["motion"] = serde_json::Value::Null;
        v["model"]["why"] = serde_json::Value::Null;
        v
    };
    let again = read("summary.json");
    assert!(again.contains("record motion.txt"), "{again}");
    assert_eq!(without_label(&again), without_label(&summary));
    assert_eq!(read("events.jsonl"), events);

    let (ok, _, err) = pirqa(&["sweep", file.to_str().unwrap(), "--no-history"]);
    assert!(!ok && err.contains("--case"), "{err}");
    // Zero worker threads would silently mean every core.
    let (ok, _, err) = pirqa(&["sweep", file.to_str().unwrap(), "--threads", "0"]);
    assert!(!ok && err.contains("--threads"), "{err}");
}

/// `pirqa generate`: about N blocks in the paper's proportions, or any cut, written to a file
/// that loads; counts the proportions cannot give and impossible cuts refused with what to do.
#[test]
fn generated_walls_load_and_impossible_cuts_are_refused() {
    let dir = temp_dir("generate-wall");
    let file = dir.join("wall.ron");
    let path = file.to_str().unwrap();
    let blocks = |args: &[&str]| {
        let (ok, _, err) = pirqa(&[&["generate", "-o", path], args].concat());
        assert!(ok, "{args:?}: {err}");
        let wall = pirqa::topology::load(&file).unwrap().0;
        assert!(
            err.contains(&format!("({} blocks)", wall.blocks.len())),
            "{err}"
        );
        wall.blocks.len()
    };
    // n courses of n blocks give n^2 + floor(n / 2) (half blocks end the odd courses).
    assert_eq!(blocks(&["--blocks", "100"]), 105);
    assert_eq!(blocks(&["--blocks", "5"]), 5);
    assert_eq!(blocks(&["--courses", "3", "--blocks-per-course", "4"]), 13);
    for few in ["0", "4"] {
        let (ok, _, err) = pirqa(&["generate", "-o", path, "--blocks", few]);
        assert!(
            !ok && err.contains("at least 5") && err.contains("--courses"),
            "{err}"
        );
    }
    let (ok, _, err) = pirqa(&[
        "generate",
        "-o",
        path,
        "--courses",
        "2",
        "--blocks-per-course",
        "0",
    ]);
    assert!(!ok && err.contains("blocks_per_course = 0"), "{err}");
}

/// Record options beside a sine are refused, not ignored.
#[test]
fn record_options_with_a_sine_are_refused() {
    for option in [
        &["--start", "2"][..],
        &["--baseline", "mean"],
        &["--units", "gal"],
    ] {
        let args = [
            &[
                "run",
                "walls/five-block-variable.ron",
                "--sine",
                "400gal",
                "--freq",
                "1",
                "--duration",
                "1",
            ][..],
            option,
        ]
        .concat();
        let (ok, _, err) = pirqa(&args);
        assert!(
            !ok && err.contains("cannot be used with") && err.contains(option[0]),
            "{err}"
        );
    }
}

/// A run with a history draws its chart beside it: the ground acceleration and the blocks that
/// moved most (all of them up to 8), each line thinned with its extremes kept, so the largest
/// |u| read from response.csv is the summary's, exactly. Without a history the chart is
/// removed with it.
#[test]
fn a_run_draws_its_response_with_every_peak_kept() {
    let dir = temp_dir("response-chart");
    let read_json = |path: &std::path::Path| -> serde_json::Value {
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    };
    let peaks = |dir: &std::path::Path| {
        let text = std::fs::read_to_string(dir.join("response.csv")).unwrap();
        let mut peak: std::collections::BTreeMap<String, (f64, usize)> = Default::default();
        for line in text.lines().skip(1) {
            let f: Vec<&str> = line.rsplitn(3, ',').collect();
            let series = f[2].split("\",\"").nth(1).unwrap().trim_end_matches('"');
            let e = peak.entry(series.to_string()).or_insert((0.0, 0));
            e.0 = e.0.max(f[0].parse::<f64>().unwrap().abs());
            e.1 += 1;
        }
        peak
    };
    // 18 blocks with lognormal friction (a sweep's case writes the wall) under El Centro at
    // 600 gal, a history row every 2 ms: 20,000 rows a line.
    let root = env!("CARGO_MANIFEST_DIR");
    let sweep = common::file(
        "chart.ron",
        &format!(
            r#"(
    version: 1,
    name: "chart",
    walls: [RunningBond(courses: 4, blocks_per_course: 4, width_m: 2.4, height_m: 1.2,
                        thickness_m: 0.8, density_kg_m3: 2650.0, friction: 0.3)],
    motion: Records(
        files: ["{root}/records/elcentro1940_IELC180_peer_dt0p01_g.AT2"],
        pga: ["600gal"],
    ),
    friction: Random(distribution: Lognormal, cov: 0.2, samples: 1, seed: 7),
)"#
        ),
    );
    let wall = sweep_case(&sweep, 0, &dir).join("wall.ron");
    let run = dir.join("run");
    let (ok, out, err) = pirqa(&[
        "run",
        wall.to_str().unwrap(),
        "--record",
        "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
        "--pga",
        "600gal",
        "--output-dt",
        "0.002",
        "--out",
        run.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(
        out.contains("history.csv, response.svg, response.csv"),
        "{out}"
    );
    let summary = read_json(&run.join("summary.json"));
    let mut most: Vec<(f64, String)> = summary["blocks"]
        .as_array()
        .unwrap()
        .iter()
        .map(|b| {
            let u = b["max_abs_displacement_m"].as_f64().unwrap();
            (u, b["name"].as_str().unwrap().to_string())
        })
        .collect();
    most.sort_by(|a, b| b.0.total_cmp(&a.0));
    assert!(
        most[7].0 > most[8].0,
        "the eighth is not tied with the ninth"
    );
    let peak = peaks(&run);
    assert!(std::fs::read_to_string(run.join("response.svg"))
        .unwrap()
        .contains("the 8 of 18 blocks that moved most"));
    assert_eq!(peak.len(), 8 + 1, "the ground and eight blocks: {peak:?}");
    for (u, name) in &most[..8] {
        let (drawn, points) = peak[name];
        assert_eq!(drawn, *u, "{name}");
        assert!(points <= 6000, "{name}: {points} points");
    }
    let (ground, _) = peak[""];
    assert!((ground - 6.0).abs() < 1e-12, "the record's peak: {ground}");

    // Without a history, no chart (and the old one goes).
    let (ok, _, err) = pirqa(&[
        "run",
        wall.to_str().unwrap(),
        "--sine",
        "100gal",
        "--freq",
        "1",
        "--duration",
        "1",
        "--no-history",
        "--out",
        run.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(!run.join("response.svg").exists() && !run.join("response.csv").exists());
}

/// A column whose drums rock one on another draws the opening of the joint between them (the
/// upper drum's rotation less the lower one's, a few milliradians the two rotations' panel
/// cannot show), its extreme the history's exactly; a single block has no such panel.
#[test]
fn a_column_draws_the_opening_of_the_joint_between_its_drums() {
    let dir = temp_dir("opening-chart");
    // `wall` under 0.5 g at 1.5 Hz for 3 s: its folder and the chart's data.
    let run = |wall: &str, name: &str| {
        let out = dir.join(name);
        let (ok, _, err) = pirqa(&[
            "run",
            wall,
            "--sine",
            "0.5g",
            "--freq",
            "1.5",
            "--duration",
            "3",
            "--out",
            out.to_str().unwrap(),
        ]);
        assert!(ok, "{err}");
        let chart = std::fs::read_to_string(out.join("response.csv")).unwrap();
        (out, chart)
    };
    // The joint between the drums opens 11 times in 6 s under this sine.
    let (column, chart) = run("walls/rocking/two-block-column.ron", "column");
    let drawn = chart
        .lines()
        .filter(|l| l.starts_with("\"opening of the joints"))
        .map(|l| {
            assert!(l.contains("\"Drum2/Drum1\""), "{l}");
            l.rsplit(',').next().unwrap().parse::<f64>().unwrap().abs()
        })
        .fold(0.0, f64::max);
    let names = ["Drum1".to_string(), "Drum2".to_string()];
    let history = pirqa::response::saved::history(&column, &names).unwrap();
    let widest = history
        .rotation_rad
        .iter()
        .map(|theta| (theta[1] - theta[0]).abs())
        .fold(0.0, f64::max);
    assert!(widest > 1e-3, "the joint opens: {widest} rad");
    assert_eq!(drawn, widest);

    let (_, chart) = run("walls/inca/stela.ron", "stela");
    assert!(chart.contains("\"rotation") && !chart.contains("\"opening"));
}

/// A case of a sweep with a fallback, rerun alone, names what answered it: its rerun command
/// carries the time stepper's options and its summary the fallback's model.
#[test]
fn a_case_the_fallback_answered_reruns_with_the_fallbacks_options() {
    let root = env!("CARGO_MANIFEST_DIR");
    let sweep = common::file(
        "fallback.ron",
        &format!(
            r#"(
    version: 1,
    name: "fallback",
    walls: [File(path: "{root}/walls/rocking/two-block-column.ron")],
    motion: Records(
        files: ["{root}/records/elcentro1940_IELC180_peer_dt0p01_g.AT2"],
        pga: ["0.5g"],
    ),
    fallback: Moreau(dt_s: 0.0005),
)"#
        ),
    );
    let dir = temp_dir("fallback-case");
    let case = sweep_case(&sweep, 0, &dir);
    let rerun = std::fs::read_to_string(case.join("rerun.txt")).unwrap();
    assert!(
        rerun.contains(" --model slide-rock --method moreau --dt 0.0005 "),
        "{rerun}"
    );
    let summary = std::fs::read_to_string(case.join("summary.json")).unwrap();
    assert!(
        summary.contains("\"slide-rock (moreau fallback)\"")
            && summary.contains("the sweep's fallback: the exact model stopped"),
        "{summary}"
    );
}

/// Options given for the horizontal record that the vertical one's format gives itself are
/// left aside for the vertical (an AT2 file says its units), not refused; the vertical record's
/// component is its own option.
#[test]
fn a_vertical_record_ignores_options_meant_for_the_horizontal_one() {
    let samples: String = (0..200).map(|k| format!("{}\n", 50 + k % 7)).collect();
    let horizontal = common::file("h.txt", &format!("# dt_s: 0.01\n{samples}"));
    let (ok, out, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--record",
        horizontal.to_str().unwrap(),
        "--units",
        "gal",
        "--vertical",
        "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
    ]);
    assert!(ok, "{err}");
    assert!(out.contains("200 samples at 0.01 s"), "{out}");
    // The horizontal record itself still refuses what it would not use.
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--record",
        "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
        "--units",
        "gal",
    ]);
    assert!(!ok && err.contains("leave --units out"), "{err}");

    // Both components in one file: each names its column, and the same column twice is refused.
    let rows: String = (0..300)
        .map(|k| format!("{} {} {}\n", k as f64 * 0.01, 100 + k % 5, 20 - k % 3))
        .collect();
    let both = common::file("hv.txt", &format!("# units: gal\n{rows}"));
    let both = both.to_str().unwrap();
    let run = |extra: &[&str]| {
        let args = [
            &[
                "run",
                "walls/five-block-variable.ron",
                "--record",
                both,
                "--vertical",
                both,
            ][..],
            extra,
        ]
        .concat();
        pirqa(&args)
    };
    let (ok, _, err) = run(&[]);
    assert!(!ok && err.contains("--vertical-component"), "{err}");
    let (ok, _, err) = run(&["--component", "1", "--vertical-component", "2"]);
    assert!(ok, "{err}");
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--record",
        both,
        "--component",
        "1",
        "--vertical",
        "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
        "--vertical-component",
        "1",
    ]);
    assert!(
        !ok && err.contains("leave --vertical-component out"),
        "{err}"
    );
}

/// The rocking model from the command line: a block released on still ground, pulses (a
/// rectangular one and a sine of a few cycles), what is logged and written, and the options
/// that do not fit refused with what to do.
#[test]
fn rocking_runs_pulses_releases_and_refusals() {
    let out = temp_dir("rocking");
    let dir = out.to_str().unwrap();
    let stela = "walls/inca/stela.ron";
    // Released from 0.05 rad on still ground: it rocks down to rest.
    let (ok, text, err) = pirqa(&[
        "run",
        stela,
        "--initial-rotation",
        "Huanca=0.05",
        "--duration",
        "30",
        "--out",
        dir,
    ]);
    assert!(ok, "{err}");
    assert!(
        text.contains("model slide-rock (exact equations)"),
        "{text}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["motion"], "ground at rest");
    assert_eq!(summary["blocks"][0]["max_abs_rotation_rad"], 0.05);
    assert!(summary["energy"]["initial_j"].as_f64().unwrap() > 0.0);
    let events = std::fs::read_to_string(out.join("events.jsonl")).unwrap();
    for kind in ["\"uplift\"", "\"rocking_impact\"", "\"rest\""] {
        assert!(events.contains(kind), "no {kind} in\n{events}");
    }
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    assert!(history.starts_with(
        "time_s,u_Huanca_m,v_Huanca_m_s,theta_Huanca_rad,omega_Huanca_rad_s,w_Huanca_m\n"
    ));
    assert!(std::fs::read_to_string(out.join("response.csv"))
        .unwrap()
        .contains("rotation"));
    // A rectangular pulse that overturns it, with the linearised equations too.
    for rocking in ["exact", "linearised"] {
        let (ok, text, err) = pirqa(&[
            "run",
            stela,
            "--pulse",
            "0.5g",
            "--pulse-s",
            "1",
            "--duration",
            "6",
            "--rocking",
            rocking,
        ]);
        assert!(ok, "{err}");
        assert!(text.contains("(overturning)"), "{rocking}: {text}");
    }
    // One sine cycle, then still ground for the rest of the run.
    let (ok, text, err) = pirqa(&[
        "run",
        stela,
        "--sine",
        "0.25g",
        "--freq",
        "1",
        "--cycles",
        "1",
        "--duration",
        "5",
    ]);
    assert!(ok, "{err}");
    assert!(text.contains("| 5 s") && text.contains("1 s"), "{text}");
    // Across the plane of the paper's wall: every section, and the one nearest to overturning.
    let (ok, text, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--direction",
        "out-of-plane",
        "--sine",
        "0.4g",
        "--freq",
        "2",
        "--duration",
        "3",
    ]);
    assert!(ok, "{err}");
    assert!(
        text.contains("above_0m")
            && text.contains("above_0.6m")
            && text.contains("no section lifted"),
        "{text}"
    );
    for (args, expect) in [
        (
            vec![
                "run",
                stela,
                "--initial-rotation",
                "B9=0.1",
                "--duration",
                "1",
            ],
            "no block of that name",
        ),
        (
            vec!["run", stela, "--initial-rotation", "Huanca=0.1"],
            "needs --duration",
        ),
        (
            vec![
                "run",
                stela,
                "--initial-rotation",
                "Huanca=2",
                "--duration",
                "1",
            ],
            "below pi/2",
        ),
        (
            // The value as written, not its 301-digit decimal expansion.
            vec![
                "run",
                stela,
                "--initial-rotation",
                "Huanca=-1e300",
                "--duration",
                "1",
            ],
            "'Huanca=-1e300' for '--initial-rotation <NAME=RAD>': -1e300 rad: a rotation",
        ),
        (
            vec![
                "run",
                stela,
                "--initial-rotation",
                "Huanca=0.1",
                "--duration",
                "1",
                "--model",
                "slide",
            ],
            "--model slide-rock or auto",
        ),
        (
            vec![
                "run",
                stela,
                "--pulse",
                "0.5g",
                "--pulse-s",
                "1",
                "--method",
                "paper",
            ],
            "leave --method out",
        ),
        (
            vec![
                "run",
                "walls/five-block-variable.ron",
                "--sine",
                "0.4g",
                "--freq",
                "1",
                "--duration",
                "1",
                "--model",
                "slide-rock",
            ],
            "--direction out-of-plane",
        ),
        (
            vec![
                "run",
                stela,
                "--pulse",
                "0.5g",
                "--pulse-s",
                "1",
                "--model",
                "slide",
                "--rocking",
                "linearised",
            ],
            "leave --rocking out",
        ),
        (
            vec![
                "run",
                "walls/five-block-uniform.ron",
                "--sine",
                "0.4g",
                "--freq",
                "1",
                "--duration",
                "1",
                "--contact-solver",
                "newton",
            ],
            "add --method moreau --dt S, or leave --contact-solver out",
        ),
        (
            vec![
                "run",
                "walls/five-block-uniform.ron",
                "--sine",
                "0.4g",
                "--freq",
                "1",
                "--duration",
                "1",
                "--model",
                "slide",
                "--method",
                "moreau",
                "--dt",
                "1e-3",
                "--contact-solver",
                "newton",
            ],
            "add --model slide-rock, or leave --contact-solver out",
        ),
        (
            vec!["run", stela, "--pulse", "0.5g", "--pulse-s", "0"],
            "positive duration",
        ),
        (
            vec![
                "run", stela, "--sine", "0.5g", "--freq", "1", "--cycles", "0",
            ],
            "positive number of cycles",
        ),
        (
            vec![
                "run",
                "walls/five-block-variable.ron",
                "--direction",
                "out-of-plane",
                "--sine",
                "0.4g",
                "--freq",
                "1",
                "--duration",
                "1",
                "--initial-rotation",
                "B1=0.1",
            ],
            "sections: above_0m, above_0.6m",
        ),
    ] {
        let (ok, _, err) = pirqa(&args);
        assert!(!ok && err.contains(expect), "{args:?}: {err}");
    }
}

#[test]
fn check_out_of_plane_gives_thresholds_curves_and_a_chart() {
    let out = temp_dir("capacity");
    let plot = out.join("capacity.svg");
    let (ok, text, err) = pirqa(&[
        "check",
        "walls/five-block-variable.ron",
        "--out-of-plane",
        "--top",
        "restrained",
        "--overburden-kn-m",
        "10",
        "--json",
        "--plot",
        plot.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(v["top"], "restrained");
    let ground = &v["sections"][0];
    assert_eq!(ground["name"], "above_0m");
    // 4 t / H (1 + 1.5 P / W): t 0.8 m, H 1.2 m, P 10 kN/m over 2.4 m, W the wall's weight.
    let w = ground["mass_kg"].as_f64().unwrap() * 9.81;
    let want = 4.0 * 0.8 / 1.2 * (1.0 + 1.5 * 24_000.0 / w);
    assert!((ground["threshold_g"].as_f64().unwrap() - want).abs() < 1e-12 * want);
    assert_eq!(ground["capacity_curve"].as_array().unwrap().len(), 41);
    assert_eq!(v["lowest_threshold"], "above_0m");
    assert!(plot.exists() && plot.with_extension("csv").exists());
    let (ok, text, _) = pirqa(&["check", "walls/five-block-variable.ron", "--out-of-plane"]);
    assert!(ok && text.contains("lowest threshold: above_0m"), "{text}");
    let (ok, _, err) = pirqa(&[
        "check",
        "walls/five-block-variable.ron",
        "--out-of-plane",
        "--overburden-kn-m",
        "-1",
    ]);
    assert!(!ok && err.contains("zero or more"), "{err}");
    let (ok, _, err) = pirqa(&["check", "walls/five-block-variable.ron", "--top", "free"]);
    assert!(!ok && err.contains("--out-of-plane"), "{err}");
}

/// Block names with the CSV's own separators in them (a comma, a quote) go through history.csv
/// quoted and are read back by column name: the state drawn at a time is the history's row.
#[test]
fn block_names_with_commas_and_quotes_round_trip_through_history_csv() {
    let dir = temp_dir("awkward-names");
    std::fs::create_dir_all(&*dir).unwrap();
    let wall = dir.join("wall.ron");
    std::fs::write(
        &wall,
        r#"(version: 1, name: "awkward", thickness_m: 0.8, density_kg_m3: 2650, friction: 0.3,
            restitution: 1.0,
            rows: [(height_m: 0.6, blocks: [(width_m: 1.2, name: "left, \"big\""),
                                            (width_m: 1.2, name: "right")])])"#,
    )
    .unwrap();
    let out = dir.join("run");
    let (ok, _, err) = pirqa(&[
        "run",
        wall.to_str().unwrap(),
        "--sine",
        "400gal",
        "--freq",
        "1",
        "--duration",
        "3",
        "--output-dt",
        "0.5",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let header = history.lines().next().unwrap();
    assert!(header.contains(r#""u_left, ""big""_m""#), "{header}");
    let model = pirqa::Model::from_file(&wall).unwrap();
    let state = pirqa::response::saved::state_at(&out, model.wall(), Some(2.0)).unwrap();
    let row = history
        .lines()
        .find(|l| l.starts_with("2,"))
        .expect("a row at t = 2 s");
    let u_left: f64 = row.split(',').nth(1).unwrap().parse().unwrap();
    assert_eq!(state.time_s, 2.0);
    assert_eq!(state.displacement_m[0], u_left);
    assert!(u_left != 0.0, "the block slid");
}

/// A sweep may run its cases on time stepping (`method: Moreau(dt_s: S)`): with `model:
/// SlideRock`, every block of the paper's wall (blocks beside others, beyond the exact rocking
/// model) turns; each case says so, and its rerun.txt (a sine's: the motion's length given once)
/// reproduces its numbers, with either contact solver (`contact_solver: Newton` puts
/// `--contact-solver newton` in it). A step that is not positive is refused with the file and
/// the field.
#[test]
fn a_sweep_runs_its_cases_on_time_stepping_with_rotations_when_asked() {
    let root = env!("CARGO_MANIFEST_DIR");
    let spec = |method: &str| {
        format!(
            r#"(
    version: 1,
    name: "stepped",
    walls: [File(path: "{root}/walls/five-block-uniform.ron")],
    motion: Sine(amplitudes: ["0.5g"], frequencies_hz: List([1.5]), duration_s: 1.0),
    model: SlideRock,
    method: {method},
)"#
        )
    };
    let out = temp_dir("stepped");
    for (method, equations, option) in [
        ("Moreau(dt_s: 0.001)", "\"moreau-jean\"", ""),
        (
            "Moreau(dt_s: 0.001), contact_solver: Newton",
            "\"moreau-jean-newton\"",
            " --contact-solver newton",
        ),
    ] {
        let file = common::file("stepped.ron", &spec(method));
        let out = out.join(equations.trim_matches('"'));
        let sweep = |extra: &[&str]| {
            let args = [
                &[
                    "sweep",
                    file.to_str().unwrap(),
                    "--out",
                    out.to_str().unwrap(),
                ],
                extra,
            ];
            pirqa(&args.concat())
        };
        let (ok, _, err) = sweep(&[]);
        assert!(ok, "{err}");
        let cases = std::fs::read_to_string(out.join("cases.csv")).unwrap();
        let row = cases.lines().nth(1).unwrap();
        assert!(row.contains(",slide-rock,"), "{cases}");
        let (ok, _, err) = sweep(&["--case", "0"]);
        assert!(ok, "{err}");
        let case = out.join("case-0");
        let read = |name: &str| std::fs::read_to_string(case.join(name)).unwrap();
        let summary = read("summary.json");
        assert!(summary.contains(equations), "{summary}");
        let rerun = read("rerun.txt");
        let options = format!("--method moreau --dt 0.001{option} ");
        assert!(rerun.contains(&options), "{rerun}");
        assert_eq!(rerun.matches("--duration").count(), 1, "{rerun}");
        let words: Vec<&str> = rerun.split_whitespace().collect();
        let (ok, _, err) = pirqa(&words[1..]);
        assert!(ok, "{err}");
        let without_label = |text: &str| {
            let mut v: serde_json::Value = serde_json::from_str(text).unwrap();
            v["motion"] = serde_json::Value::Null;
            v["stats"] = serde_json::Value::Null;
            v
        };
        assert_eq!(
            without_label(&read("summary.json")),
            without_label(&summary)
        );
    }

    let bad = common::file("bad-step.ron", &spec("Moreau(dt_s: -0.001)"));
    let (ok, _, err) = pirqa(&[
        "sweep",
        bad.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(
        !ok && err.contains("bad-step.ron") && err.contains("method"),
        "{err}"
    );
}

/// Every sliding run, time stepped too, says how much of a joint's overlap at rest sliding took
/// away (the bridge's top block of tests/suite/collapse.rs, 0.1298 m of its 0.8 m on the left
/// abutment: 16.2 %); a run whose blocks turn has its geometry moved, and says nothing of it.
#[test]
fn sliding_runs_say_how_much_overlap_sliding_took_away() {
    let wall = common::file("bridge.ron", crate::collapse::BRIDGE_RON);
    // The bridge pushed for 0.5 s with `more` arguments: the terminal's text and summary.json.
    let pushed = |more: &[&str]| {
        let file = temp_dir("bridge.json");
        let mut args = vec![
            "run",
            wall.to_str().unwrap(),
            "--pulse=-3m/s2",
            "--pulse-s",
            "0.5",
        ];
        args.extend(["--duration", "0.5", "--summary", file.to_str().unwrap()]);
        args.extend(more);
        let (ok, out, err) = pirqa(&args);
        assert!(ok, "{more:?}: {err}");
        let text = std::fs::read_to_string(&*file).unwrap();
        (
            out,
            serde_json::from_str::<serde_json::Value>(&text).unwrap(),
        )
    };
    let exact = (3.0 - 0.2 * 9.81) * 0.5 * 0.5 / 2.0 / 0.8;
    for (method, tolerance) in [("event", 1e-15), ("moreau", 1e-3), ("paper", 1e-3)] {
        let stepped = ["--method", method, "--dt", "1e-4"];
        let (out, s) = pushed(if method == "event" { &[] } else { &stepped });
        assert!(
            out.contains("overlap lost to sliding: at most 16.2 % of a joint's at rest"),
            "{method}: {out}"
        );
        assert!(
            out.contains("warning: Top on B1: at u_Top - u_B1 = 0.129"),
            "{out}"
        );
        let loss = s["max_overlap_loss"].as_f64().unwrap();
        assert!(
            (loss - exact).abs() < tolerance,
            "{method}: {loss} vs {exact}"
        );
    }
    let turning = [
        "--model",
        "slide-rock",
        "--method",
        "moreau",
        "--dt",
        "1e-3",
    ];
    let (out, s) = pushed(&turning);
    assert!(!out.contains("overlap lost"), "{out}");
    assert!(s.get("max_overlap_loss").is_none(), "{s}");
}

/// `--after-uplift moreau`: the Ollantaytambo wall under a 0.3 g sine slides exactly until F1
/// must turn (the instant the uplift check finds, the same to the last digit as the checked
/// sliding run's), then every block steps with its rotation; one history with rotations, the
/// summary naming both methods. Combinations that cannot hand off are refused with the reason.
#[test]
fn after_the_first_uplift_time_stepping_with_rotations_takes_over() {
    let dir = temp_dir("after-uplift");
    let run = |more: &[&str]| {
        let mut args = vec![
            "run",
            "walls/inca/ollantaytambo-monoliths.ron",
            "--sine",
            "0.3g",
            "--freq",
            "1",
            "--duration",
            "0.5",
        ];
        args.extend(more);
        pirqa(&args)
    };
    let summary = |name: &str| -> serde_json::Value {
        let text = std::fs::read_to_string(dir.join(name).join("summary.json")).unwrap();
        serde_json::from_str(&text).unwrap()
    };
    let out_dir = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (handed, checked) = (out_dir("handed"), out_dir("checked"));
    let (ok, out, err) = run(&["--after-uplift", "moreau", "--dt", "1e-3", "--out", &handed]);
    assert!(ok, "{err}");
    assert!(
        out.contains("| event+moreau |") && out.contains("from there Moreau-Jean with every"),
        "{out}"
    );
    let (ok, _, err) = run(&["--model", "slide", "--check-uplift", "--out", &checked]);
    assert!(ok, "{err}");
    let (a, b) = (summary("handed"), summary("checked"));
    assert_eq!(a["uplift_check"], b["uplift_check"]);
    assert_eq!(
        a["uplift_check"]["first_uplift"]["turning"][0],
        "F1 turns counterclockwise about its bottom-left corner"
    );
    assert_eq!(a["method"], "event+moreau");
    let history = std::fs::read_to_string(dir.join("handed").join("history.csv")).unwrap();
    assert!(history.lines().next().unwrap().contains(",theta_F1_rad,"));
    let (ok, _, err) = run(&["--after-uplift", "moreau", "--method", "paper"]);
    assert!(
        !ok && err.contains("--method chooses another integrator"),
        "{err}"
    );
}

/// `--after-stop moreau`: the two-block column under El Centro at 0.5 g runs exactly until its
/// upper drum would lift off the lower one's corner as it slips (6.24 s), then every block
/// steps with its rotation from there: one history whose rows up to the stop are the exact run's own, to the
/// last digit, and go on past it; the summary names both methods and where the exact model
/// stopped, and carries no warning that the run ended there, nor the exact run's
/// `stopped_at_s`. The upper drum, leaning by 1 rad
/// with its centroid dropped by more than half its height, has fallen by the stepper's
/// criterion at the stop itself: it falls there, and the lower one steps on
/// (`--after-collapse continue`). A run the exact model finishes is
/// its own answer; a sliding wall and other integrators are refused with the reason.
#[test]
fn where_the_exact_rocking_model_stops_time_stepping_goes_on() {
    let dir = temp_dir("after-stop");
    let run = |wall: &str, pga: &str, more: &[&str]| {
        let mut args = vec![
            "run",
            wall,
            "--record",
            "records/elcentro1940_IELC180_peer_dt0p01_g.AT2",
            "--pga",
            pga,
            "--duration",
            "8",
        ];
        args.extend(more);
        pirqa(&args)
    };
    let column = "walls/rocking/two-block-column.ron";
    let out_dir = |name: &str| dir.join(name).to_str().unwrap().to_string();
    let (exact, handed) = (out_dir("exact"), out_dir("handed"));
    let (ok, out, err) = run(column, "0.5g", &["--out", &exact]);
    assert!(ok && out.contains("stops there"), "{out}{err}");
    // Its numbers are of the motion up to the stop, and it says so before them.
    assert!(
        out.contains("  STOPPED at t = 6.23") && out.contains("  no collapse up to then\n"),
        "{out}"
    );
    let more = [
        "--after-stop",
        "moreau",
        "--dt",
        "5e-4",
        "--after-collapse",
        "continue",
        "--out",
        &handed,
    ];
    let (ok, out, err) = run(column, "0.5g", &more);
    assert!(ok, "{err}");
    assert!(
        out.contains("| event+moreau |")
            && out.contains("with --after-stop moreau: the exact model to t = 6.23")
            && out.contains("would lift off the corner it turns on")
            && out.contains("Drum2 fell")
            && !out.contains("stops there"),
        "{out}"
    );
    let rows = |name: &str| -> Vec<String> {
        let text = std::fs::read_to_string(dir.join(name).join("history.csv")).unwrap();
        text.lines().map(str::to_string).collect()
    };
    let (a, b) = (rows("exact"), rows("handed"));
    // The exact run's rows, its last (the stop) included, then the stepper's.
    assert!(b.len() > a.len(), "{} {}", a.len(), b.len());
    assert_eq!(a[..], b[..a.len()]);
    let summary = |name: &str| -> serde_json::Value {
        let text = std::fs::read_to_string(dir.join(name).join("summary.json")).unwrap();
        serde_json::from_str(&text).unwrap()
    };
    let (stop, fell) = (summary("exact"), summary("handed"));
    assert_eq!(stop["stopped_at_s"], stop["duration_s"]);
    assert!(fell.get("stopped_at_s").is_none(), "{fell}");
    assert_eq!(
        fell["collapse"]["time_s"], stop["duration_s"],
        "{}",
        fell["collapse"]
    );
    assert_eq!(fell["collapse"]["block"], "Drum2");
    let (ok, out, err) = run(column, "0.3g", &["--after-stop", "moreau"]);
    assert!(
        ok && out.contains("| event |")
            && out.contains("followed the wall to the end")
            && out.contains("  no collapse\n")
            && !out.contains("STOPPED"),
        "{out}{err}"
    );
    for (wall, more, says) in [
        (
            column,
            &["--after-stop", "moreau", "--method", "paper"][..],
            "--method chooses another integrator",
        ),
        (
            "walls/five-block-variable.ron",
            &["--after-stop", "moreau"][..],
            "runs on the sliding model",
        ),
        (
            column,
            &["--after-stop", "moreau", "--dt", "0"][..],
            "time step",
        ),
    ] {
        let (ok, _, err) = run(wall, "0.5g", more);
        assert!(!ok && err.contains(says), "{wall} {more:?}: {err}");
    }
}

#[test]
fn while_blocks_rock_time_stepping_takes_over_and_gives_the_wall_back() {
    let dir = temp_dir("while-rocking");
    let out = dir.join("pulse");
    let (ok, text, err) = pirqa(&[
        "run",
        "walls/rocking/slab-beside-block.ron",
        "--pulse",
        "0.3g",
        "--pulse-s",
        "0.3",
        "--duration",
        "3",
        "--after-uplift",
        "moreau-while-rocking",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(ok, "{err}");
    assert!(
        text.contains("| event+moreau |") && text.contains("stretches stepped (1): 0 to "),
        "{text}"
    );
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap()).unwrap();
    assert_eq!(summary["model"]["name"], "slide-rock");
    let history = std::fs::read_to_string(out.join("history.csv")).unwrap();
    let last = history.lines().last().unwrap();
    // At the end the exact sliding model has the wall: rotations and velocities exactly zero.
    let columns: Vec<&str> = history.lines().next().unwrap().split(',').collect();
    let values: Vec<&str> = last.split(',').collect();
    for (name, value) in columns.iter().zip(&values) {
        if name.starts_with("theta_") || name.starts_with("omega_") || name.starts_with("v_") {
            assert_eq!(*value, "0e0", "{name} in {last}");
        }
    }
    let (ok, _, err) = pirqa(&[
        "run",
        "walls/rocking/slab-beside-block.ron",
        "--pulse",
        "0.3g",
        "--pulse-s",
        "0.3",
        "--after-uplift",
        "moreau-while-rocking",
        "--model",
        "slide",
    ]);
    assert!(!ok && err.contains("--model chooses one model"), "{err}");
}

/// `check --run DIR --limit`: the wall where a run left it. A slender block on a fixed ledge
/// slides off its edge under a half cycle of a 0.5 g sine; where it stands then, it tips about
/// the edge at its centroid's distance from it over its height above it (Shenton's lone block
/// on the moved geometry), below the friction at which the wall as built gives way. A NaN in
/// the history is refused by line, not read.
#[test]
fn check_gives_the_limit_at_rest_where_a_run_left_the_wall() {
    use pirqa::exact::Q;
    let dir = temp_dir("moved-check");
    std::fs::create_dir_all(&dir).unwrap();
    let wall = std::path::Path::new("walls/rocking/block-on-ledge.ron");
    let (wall, run) = (wall.to_str().unwrap(), dir.join("run"));
    let run = run.to_str().unwrap();
    let (ok, _, err) = pirqa(&[
        "run",
        wall,
        "--sine",
        "0.5g",
        "--freq",
        "1",
        "--duration",
        "0.5",
        "--model",
        "slide",
        "--out",
        run,
    ]);
    assert!(ok, "{err}");
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("run/summary.json")).unwrap())
            .unwrap();
    let u = summary["blocks"][1]["final_displacement_m"]
        .as_f64()
        .unwrap();
    assert!(u < -0.1, "the block slid past the ledge's edge: u = {u}");
    let q = |x: f64| Q::from_decimal(x).unwrap();
    // Resting on 0 .. 0.4 + u of the ledge, centroid at 0.25 + u, 0.6 m above the joint.
    let expected = ((q(0.25) + q(u)) / q(0.6)).min(q(0.15));
    let (ok, out, err) = pirqa(&["check", wall, "--run", run, "--limit", "--json"]);
    assert!(ok, "{err}");
    let report: serde_json::Value = serde_json::from_str(&out).unwrap();
    let side = |key: &str, side: &str| report[key][side]["exact_g"].as_str().unwrap().to_string();
    assert_eq!(
        side("limit_at_rest", "towards_plus_x"),
        format!("{expected:?}")
    );
    assert_eq!(side("limit_at_rest", "towards_minus_x"), "3/20");
    assert_eq!(side("limit_at_rest_as_built", "towards_plus_x"), "3/20");
    assert_eq!(report["moved_by_run"]["time_s"], 0.5);
    assert_eq!(report["moved_by_run"]["largest_displacement_m"], -u);
    assert_eq!(report["supports"][0]["overlap_m"], (q(0.4) + q(u)).to_f64());

    let (ok, out, err) = pirqa(&["check", wall, "--run", run, "--limit"]);
    assert!(ok, "{err}");
    for text in [
        "where the run in",
        "of the wall where the run left it:",
        "U        turns",
        "of the wall as built: towards +x 0.1500 g (3/20 g); towards -x 0.1500 g (3/20 g)",
    ] {
        assert!(out.contains(text), "missing {text:?} in\n{out}");
    }
    // At an instant of the history: its last sample at or before it.
    let (ok, out, err) = pirqa(&["check", wall, "--run", run, "--at", "0.25", "--json"]);
    assert!(ok, "{err}");
    let report: serde_json::Value = serde_json::from_str(&out).unwrap();
    let t = report["moved_by_run"]["time_s"].as_f64().unwrap();
    assert!(t <= 0.25 && t > 0.2, "{t}");

    let history = dir.join("run/history.csv");
    let text = std::fs::read_to_string(&history).unwrap();
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let last = lines.len() - 1;
    let mut fields: Vec<String> = lines[last].split(',').map(String::from).collect();
    fields[1] = "NaN".into();
    lines[last] = fields.join(",");
    std::fs::write(&history, lines.join("\n") + "\n").unwrap();
    let (ok, _, err) = pirqa(&["check", wall, "--run", run, "--at", "0.5"]);
    assert!(
        !ok && err.contains("history.csv") && err.contains("not a finite number"),
        "{err}"
    );
}

/// `sweep FILE --residual`: each case's limit at rest where its run left the wall, from a
/// finished sweep's blocks.csv. The block on a ledge under half a cycle of 0.3, 0.5 and 0.6 g:
/// left on the ledge it keeps its friction, 3/20 g (all of its capacity); slid past the end it
/// tips about it at (0.25 + u) / 0.6 g, u its final displacement in blocks.csv; fallen, what is
/// left (the ledge) holds at any acceleration. The chart is drawn from the rows.
#[test]
fn sweep_residual_gives_each_cases_limit_where_its_run_left_the_wall() {
    use pirqa::exact::Q;
    let dir = temp_dir("residual-sweep");
    std::fs::create_dir_all(&dir).unwrap();
    let ledge = std::fs::canonicalize("walls/rocking/block-on-ledge.ron").unwrap();
    let file = dir.join("ledge.ron");
    std::fs::write(
        &file,
        format!(
            r#"(version: 1, name: "ledge", walls: [File(path: "{}")],
                motion: Sine(amplitudes: ["0.3g", "0.5g", "0.6g"], frequencies_hz: List([1.0]),
                             duration_s: 0.5),
                model: Slide)"#,
            ledge.display()
        ),
    )
    .unwrap();
    let (file, out) = (file.to_str().unwrap(), dir.join("out"));
    let out = out.to_str().unwrap();
    let (ok, _, err) = pirqa(&["sweep", file, "--out", out, "--residual"]);
    assert!(
        !ok && err.contains("holds no sweep (no manifest.json): run it there first"),
        "a sweep not run yet: {err}"
    );
    let (ok, _, err) = pirqa(&["sweep", file, "--out", out]);
    assert!(ok, "{err}");
    let (ok, _, err) = pirqa(&["sweep", file, "--out", out, "--residual"]);
    assert!(
        ok && err.contains("the limit at rest left by 3 of 3 cases"),
        "{err}"
    );
    let read = |name: &str| -> Vec<std::collections::HashMap<String, String>> {
        let mut r = csv::Reader::from_path(dir.join("out").join(name)).unwrap();
        r.deserialize().map(Result::unwrap).collect()
    };
    let (residual, blocks) = (read("residual.csv"), read("blocks.csv"));
    let u: Vec<f64> = (blocks.iter())
        .filter(|b| b["block"] == "U")
        .map(|b| b["final_u_m"].parse().unwrap())
        .collect();
    assert!(u[0] > -0.1 && u[1] < -0.1, "{u:?}");
    let q = |x: f64| Q::from_decimal(x).unwrap();
    let tips = (q(0.25) + q(u[1])) / q(0.6);
    let expected = [
        ("3/20", "3/20", "1e0", ""),
        (&*format!("{tips:?}"), "3/20", "", ""),
        ("unlimited", "unlimited", "", "U"),
    ];
    for (row, (plus, minus, left, fallen)) in residual.iter().zip(expected) {
        assert_eq!(row["plus_x_exact_g"], plus, "{row:?}");
        assert_eq!(row["minus_x_exact_g"], minus, "{row:?}");
        assert_eq!(row["as_built_plus_x_g"], "1.5e-1", "{row:?}");
        assert_eq!(row["fallen"], fallen, "{row:?}");
        if !left.is_empty() {
            assert_eq!(row["capacity_left"], left, "{row:?}");
        }
        assert_eq!(row["error"], "", "{row:?}");
    }
    let share: f64 = residual[1]["capacity_left"].parse().unwrap();
    assert_eq!(share, (tips / q(0.15)).to_f64());
    // Each case a point, and with one case per peak its median and 5 % quantile the same.
    let chart = read("capacity-left.csv");
    for series in ["each case", "median", "5 % quantile"] {
        let points: Vec<(f64, f64)> = (chart.iter())
            .filter(|r| r["series"] == format!("block-on-ledge: {series}"))
            .map(|r| (r["x"].parse().unwrap(), r["y"].parse().unwrap()))
            .collect();
        assert_eq!(points, [(294.3, 1.0), (490.5, share)], "{series}");
    }
}
