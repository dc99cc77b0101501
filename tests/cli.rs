//! The command line end to end: what a user types and what they get back.

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

#[test]
fn invalid_input_exits_non_zero_with_the_file_named() {
    let (ok, _, err) = pirqa(&["check", "walls/does-not-exist.ron"]);
    assert!(!ok);
    assert!(err.starts_with("error: walls/does-not-exist.ron"), "{err}");
}

#[test]
fn draw_writes_an_svg_with_names_and_friction() {
    let out = std::env::temp_dir().join(format!("pirqa-draw-{}.svg", std::process::id()));
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

fn temp_dir(name: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("pirqa-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn run_writes_summary_history_and_events() {
    let out = temp_dir("run");
    let (ok, stdout, err) = pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--sine",
        "400gal",
        "--freq",
        "1",
        "--duration",
        "5",
        "--out",
        out.to_str().unwrap(),
    ]);
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
}

#[test]
fn amplitudes_in_gal_g_and_m_s2_give_the_same_run() {
    let mut maxima = Vec::new();
    for amp in ["400gal", "4m/s2", "4.0 m/s^2"] {
        let file = temp_dir("units").with_extension("json");
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
