//! Collapse: a block falls when its centroid leaves the span its supports give it; until then
//! the sliding model keeps the overlaps at rest, and says how much of them sliding took away.

use crate::engine;

use engine::{constant, exact};
use pirqa::integrate::{AfterCollapse, Settings};
use pirqa::motion::Motion;
use pirqa::response::{Response, Warning};
use pirqa::{samples, Wall};

fn run(wall: &Wall, motion: &Motion, duration: f64, after: AfterCollapse) -> Response {
    let settings = Settings {
        log_events: true,
        after_collapse: after,
        ..Settings::summary_only(duration)
    };
    exact(wall, motion, &settings)
}

#[test]
fn a_block_sliding_off_its_support_falls_at_half_its_width() {
    // Top block (1 m wide) slides on the bottom one (held by mu 0.5) at (0.2 g - 3) m/s2
    // relative: its centroid leaves the bottom block's top after 0.5 m.
    let r = run(
        &samples::stacked_pair(0.5, 0.2),
        &constant(3.0, 2.0),
        2.0,
        AfterCollapse::Stop,
    );
    let c = r.summary.collapse.as_ref().expect("it falls");
    assert_eq!(c.block, "B2");
    let expect = (2.0f64 * 0.5 / (3.0 - 0.2 * 9.81)).sqrt();
    assert!(
        (c.time_s - expect).abs() < 1e-12,
        "{} vs {expect}",
        c.time_s
    );
    assert_eq!(
        r.summary.duration_s, c.time_s,
        "the run stops at the first collapse by default"
    );
    assert!(r.summary.blocks[1].fell);
}

/// Two abutments with a 0.2 m gap between them; a block, "Top", bridges it, on 0.8 m of the
/// left one and 0.2 m of the right.
pub const BRIDGE_RON: &str = r#"(version: 1, thickness_m: 1, density_kg_m3: 2000, friction: 0.2,
    rectangles: [
        (x_m: 0, y_m: 0, width_m: 1, height_m: 0.5, fixed: true),
        (x_m: 1.2, y_m: 0, width_m: 1, height_m: 0.5, fixed: true),
        (x_m: 0.2, y_m: 0.5, width_m: 1.2, height_m: 0.5, name: "Top"),
    ])"#;

fn bridge() -> Wall {
    Wall::from_ron_str(BRIDGE_RON).unwrap()
}

#[test]
fn a_block_bridging_a_gap_stands_until_its_centroid_leaves_the_far_support() {
    // Ground acceleration -3 m/s2: the top block slides +x at 3 - 0.2 g. Its centroid (x = 0.8)
    // crosses the gap (1.0..1.2) without falling and falls past the right support's edge
    // (x = 2.2), after 1.4 m.
    let r = run(&bridge(), &constant(-3.0, 3.0), 3.0, AfterCollapse::Stop);
    let c = r.summary.collapse.as_ref().expect("it falls eventually");
    let expect = (2.0f64 * 1.4 / (3.0 - 0.2 * 9.81)).sqrt();
    assert!(
        (c.time_s - expect).abs() < 1e-12,
        "{} vs {expect}",
        c.time_s
    );
}

/// The bridge's top block, pushed right at (3 - 0.2 g) m/s2 relative to its abutments for t
/// seconds, leaves (3 - 0.2 g) t^2 / 2 of its 0.8 m on the left one: the share lost, to
/// round-off, and a warning from a tenth (at 0.3 s 5.8 %, at 0.5 s 16.2 %).
#[test]
fn a_sliding_run_says_how_much_overlap_sliding_took_away() {
    let relative = 3.0 - 0.2 * 9.81;
    for (t, warned) in [(0.3, false), (0.5, true)] {
        let r = run(&bridge(), &constant(-3.0, t), t, AfterCollapse::Stop);
        let slip = relative * t * t / 2.0;
        let loss = r.summary.max_overlap_loss.expect("a sliding run notes it");
        assert!(
            (loss - slip / 0.8).abs() < 1e-15,
            "{t} s: {loss} vs {}",
            slip / 0.8
        );
        let warning = r.summary.warnings.iter().find_map(|w| match w {
            Warning::OverlapLost {
                upper,
                lower,
                least_m,
                ..
            } => Some((upper.as_str(), lower.as_str(), *least_m)),
            _ => None,
        });
        if warned {
            let (upper, lower, least_m) = warning.expect("a warning from a tenth lost");
            assert_eq!((upper, lower), ("Top", "B1"));
            assert!((least_m - (0.8 - slip)).abs() < 1e-15, "{least_m}");
        } else {
            assert_eq!(warning, None, "{t} s");
        }
    }
}

#[test]
fn after_collapse_continue_runs_on_without_the_fallen_block() {
    let wall = Wall::load(std::path::Path::new("walls/five-block-variable.ron")).unwrap();
    let motion = Motion::sine(pirqa::motion::Sine {
        amplitude_m_s2: 5.0,
        frequency_hz: 0.2,
        phase_rad: 0.0,
        duration_s: 10.0,
    })
    .unwrap();
    let stop = run(&wall, &motion, 10.0, AfterCollapse::Stop);
    let first = stop
        .summary
        .collapse
        .clone()
        .expect("a strong slow sine topples the wall");
    let go_on = run(&wall, &motion, 10.0, AfterCollapse::Continue);
    assert_eq!(
        go_on.summary.collapse,
        Some(first.clone()),
        "same first collapse"
    );
    assert_eq!(go_on.summary.duration_s, 10.0);
    let e = go_on.summary.energy;
    assert!(
        e.residual_j.abs() <= 1e-9 * e.input_j,
        "residual {:e} of {:e}",
        e.residual_j,
        e.input_j
    );
    assert!(go_on.summary.blocks.iter().any(|b| b.fell));
}
