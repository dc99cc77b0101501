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
