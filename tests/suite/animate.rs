//! `pirqa animate`: the page that plays a run back, loaded in a real browser (headless
//! Chromium, Debian's package, installed here when missing): the state it draws at a time asked
//! in its address is the one `pirqa draw --run --at` draws (the same history sample, every u to
//! the bit; the rotations of a rocking block too, and a trilith's pose, turned and lifted), its
//! pictures change as the time does, and it reaches for nothing outside itself.

use crate::common;
use pirqa::response::saved;
use std::path::Path;
use std::process::Command;

const CHROMIUM: &str = "/usr/bin/chromium";

/// Debian's Chromium, installed when missing (the README's test command installs what its tests
/// need).
fn chromium() -> &'static str {
    if !Path::new(CHROMIUM).exists() {
        let install = || {
            Command::new("apt-get")
                .args(["install", "-y", "-q", "chromium"])
                .env("DEBIAN_FRONTEND", "noninteractive")
                .output()
                .expect("apt-get runs")
        };
        let mut out = install();
        if !out.status.success() {
            // A machine whose package lists are old or absent: read them, then try again.
            let _ = Command::new("apt-get").args(["update", "-q"]).output();
            out = install();
        }
        assert!(
            out.status.success() && Path::new(CHROMIUM).exists(),
            "installing Debian's chromium failed (the browser test needs it, as root): {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
    CHROMIUM
}

/// Chromium headless on `url` with `args` (as the machine's probe runs it: no sandbox as root,
/// no background network), killed after two minutes; its stdout.
fn browse(profile: &Path, args: &[&str], url: &str) -> String {
    let out = Command::new("timeout")
        .arg("120")
        .arg(chromium())
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .args(args)
        .arg(url)
        .output()
        .expect("chromium runs");
    assert!(
        out.status.success(),
        "chromium: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

fn pirqa(args: &[&str]) {
    let (code, _, err) = common::pirqa(args, &[]);
    assert_eq!(code, 0, "{args:?}: {err}");
}

/// The state the page drew, read from its `#state` element after the page ran: the JSON, and
/// its text (serde_json reads some floats an ulp off; `numbers` reads them exactly).
fn drawn_state(profile: &Path, page: &Path, t: f64) -> (serde_json::Value, String) {
    let dom = browse(
        profile,
        &["--dump-dom"],
        &format!("file://{}#t={t}", page.display()),
    );
    let start = dom.find("<pre id=\"state\">").expect("the page's state") + 16;
    let end = start + dom[start..].find("</pre>").unwrap();
    let text = dom[start..end].to_string();
    let json = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    (json, text)
}

/// Every value of `key` in JSON text, in order, read by Rust's correctly rounded parser.
fn numbers(text: &str, key: &str) -> Vec<f64> {
    let pattern = format!("\"{key}\":");
    text.match_indices(&pattern)
        .map(|(at, _)| {
            let rest = &text[at + pattern.len()..];
            let end = rest.find([',', '}']).unwrap();
            rest[..end].parse().unwrap()
        })
        .collect()
}

#[test]
fn the_page_draws_in_a_browser_what_pirqa_draw_draws_at_that_time() {
    let base = common::scratch("animate");
    let profile = base.join("profile");
    for (wall, motion, t) in [
        (
            "walls/five-block-variable.ron",
            ["--sine", "400gal", "--freq", "1", "--duration", "5"],
            2.5,
        ),
        (
            "walls/inca/stela.ron",
            ["--sine", "0.5g", "--freq", "2", "--duration", "3"],
            1.2,
        ),
        (
            "walls/rocking/trilith.ron",
            ["--sine", "0.3g", "--freq", "1", "--duration", "3"],
            1.5,
        ),
    ] {
        let dir = base.join(Path::new(wall).file_stem().unwrap());
        let d = dir.to_str().unwrap();
        let mut args = vec!["run", wall, "--out", d];
        args.extend(motion);
        pirqa(&args);
        let page = dir.join("run.html");
        pirqa(&["animate", d, "-o", page.to_str().unwrap()]);
        let html = std::fs::read_to_string(&page).unwrap();
        // Self-contained: no script, style or picture from elsewhere.
        for outside in ["<link", " src=", "href=", "https://", "@import"] {
            assert!(
                !html.contains(outside),
                "{wall}: the page reaches outside with {outside}"
            );
        }
        let w = pirqa::Wall::load(Path::new(wall)).unwrap();
        let expected = saved::state_at(&dir, &w, Some(t)).unwrap();
        let (state, text) = drawn_state(&profile, &page, t);
        assert_eq!(numbers(&text, "time_s"), [expected.time_s], "{wall}");
        let (u, theta) = (numbers(&text, "u_m"), numbers(&text, "theta_rad"));
        let names: Vec<String> = w.blocks.iter().map(|b| b.name.clone()).collect();
        let history = saved::history(&dir, &names).unwrap();
        let row = history.time_s.iter().rposition(|&s| s <= t).unwrap();
        for (k, b) in state["blocks"].as_array().unwrap().iter().enumerate() {
            assert_eq!(b["name"].as_str(), Some(names[k].as_str()));
            assert_eq!(u[k], expected.displacement_m[k], "{wall} {}", names[k]);
            assert_eq!(b["fallen"].as_bool(), Some(expected.fallen[k]));
            let saved = history.rotation_rad.get(row).map_or(0.0, |r| r[k]);
            assert_eq!(theta[k], saved, "{wall} {}", names[k]);
        }
        if wall.contains("stela") || wall.contains("trilith") {
            assert!(theta[0].abs() > 1e-4, "it rocks");
            // The pose drawn (turned, and lifted by w) is the one pirqa draw draws.
            let (turned, lifted) = expected.pose.as_ref().expect("a rotating run's pose");
            assert_eq!(&theta, turned, "{wall}");
            assert_eq!(&numbers(&text, "w_m"), lifted, "{wall}");
        }
        // A screenshot at that time, and one at the start: pictures, and not the same one.
        let shot = |at: f64, name: &str| {
            let png = dir.join(name);
            browse(
                &profile,
                &[
                    "--window-size=1000,720",
                    &format!("--screenshot={}", png.display()),
                ],
                &format!("file://{}#t={at}", page.display()),
            );
            std::fs::read(&png).unwrap()
        };
        let (at_t, at_0) = (shot(t, "t.png"), shot(0.0, "start.png"));
        assert!(
            at_t.starts_with(b"\x89PNG\r\n\x1a\n") && at_t.len() > 10_000,
            "{wall}"
        );
        assert_ne!(at_t, at_0, "{wall}: the picture does not follow the time");
    }
}

/// A run without a history, or a page asked of another wall's run: refused with what to do.
#[test]
fn runs_it_cannot_play_are_refused() {
    let base = common::scratch("animate-bad");
    let d = base.to_str().unwrap();
    pirqa(&[
        "run",
        "walls/five-block-variable.ron",
        "--sine",
        "400gal",
        "--freq",
        "1",
        "--duration",
        "1",
        "--out",
        d,
        "--no-history",
    ]);
    let page = base.join("x.html");
    let page = page.to_str().unwrap();
    let (code, _, err) = common::pirqa(&["animate", d, "-o", page], &[]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("history.csv") && err.contains("--no-history"),
        "{err}"
    );
    let other = ["--wall", "walls/five-block-uniform.ron"];
    let (code, _, err) = common::pirqa(&["animate", d, "-o", page, other[0], other[1]], &[]);
    assert_eq!(code, 1, "{err}");
    assert!(
        err.contains("not of \"Five-block wall, uniform friction\""),
        "{err}"
    );
}
