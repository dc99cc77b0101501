//! The uplift check of a sliding run (`--check-uplift`, `limit::seated`): the first instant at
//! which no contact forces keep every block seated, located exactly. Against closed forms: a
//! slender block where a sine reaches g b/h, a block dragged by one sliding on it where its
//! moments say (the sliding state's own interval, not the one at rest); against the limit at
//! rest on the Ollantaytambo wall under El Centro; a watched run's answer otherwise the same to
//! the bit as an unwatched one; refused where the sliding engine does not run.

use pirqa::limit::{at_rest, Limit, Uniqueness};
use pirqa::motion::{Motion, Sine};
use pirqa::response::{Uplift, UpliftCheck};
use pirqa::{Direction, Method, Model, ModelChoice, Response, RunSettings, Warning};
use std::f64::consts::PI;

fn sine(amplitude_g: f64, duration_s: f64) -> Motion {
    Motion::sine(Sine {
        amplitude_m_s2: amplitude_g * 9.81,
        frequency_hz: 1.0,
        duration_s,
        ..Sine::default()
    })
    .unwrap()
}

fn watched(model: &Model, motion: &Motion, check_uplift: bool) -> Response {
    let settings = RunSettings {
        model: ModelChoice::Slide,
        check_uplift,
        log_events: true,
        ..RunSettings::default()
    };
    pirqa::run(model, motion, &settings).unwrap()
}

/// A block 0.6 x 1.2 m (b/h = 1/2) alone on the ground.
fn slender(friction: &str) -> Model {
    Model::from_ron_str(&format!(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: {friction},
          rows: [(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\")])])"
    ))
    .unwrap()
}

/// El Centro 1940 (N-S) scaled to a peak of `pga_g` g.
fn el_centro(pga_g: f64) -> Motion {
    let record = pirqa::motion::read_record(
        std::path::Path::new("records/elcentro1940_IELC180_peer_dt0p01_g.AT2"),
        None,
        &pirqa::motion::ReadOptions::default(),
    )
    .unwrap();
    Motion::Record(record.scaled(pga_g * 9.81 / record.pga_m_s2()).unwrap())
}

fn first_uplift(r: &Response) -> &Uplift {
    let check = r.summary.uplift_check.as_ref().expect("checked");
    let u = check.first_uplift.as_ref().expect("an uplift");
    assert_eq!(check.checked_until_s, u.time_s);
    assert!(r
        .summary
        .warnings
        .iter()
        .any(|w| matches!(w, Warning::Lifts { time_s, .. } if *time_s == u.time_s)));
    u
}

/// Where a unit sine of amplitude `amplitude_g` (1 Hz) first reaches `level_g`.
fn first_reach(level_g: f64, amplitude_g: f64) -> f64 {
    (level_g / amplitude_g).asin() / (2.0 * PI)
}

#[test]
fn a_slender_block_lifts_where_a_sine_reaches_g_b_over_h() {
    // b/h = 1/2 under friction 0.6: at rest it tips at g/2 before it could slide.
    let r = watched(&slender("0.6"), &sine(0.55, 2.0), true);
    let u = first_uplift(&r);
    assert!(
        (u.time_s - first_reach(0.5, 0.55)).abs() <= 1e-13,
        "{}",
        u.time_s
    );
    assert!((u.ground_accel_m_s2 - 0.5 * 9.81).abs() <= 1e-12);
    assert_eq!(
        u.turning,
        ["A turns counterclockwise about its bottom-left corner"]
    );
    assert_eq!(u.mechanism_uniqueness, Uniqueness::Unique);
    assert_eq!(u.turning_in_every_mechanism, Some(vec!["A".to_string()]));
}

/// Two slabs of one size standing apart reach g b/h at one instant, and either may turn (or
/// both): the mechanism named is one of several. With the second slab stouter, the first
/// turns alone, and its mechanism is the only one.
#[test]
fn where_twin_slabs_lift_at_one_instant_the_mechanism_is_one_of_several() {
    let pair = |second_width_m: f64| {
        Model::from_ron_str(&format!(
            "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
              rows: [(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\"),
                     (width_m: {second_width_m}, gap_m: 0.2, name: \"B\")])])"
        ))
        .unwrap()
    };
    let twins = watched(&pair(0.6), &sine(0.55, 2.0), true);
    let u = first_uplift(&twins);
    assert!((u.time_s - first_reach(0.5, 0.55)).abs() <= 1e-13);
    assert_eq!(u.mechanism_uniqueness, Uniqueness::OneOfSeveral);
    // Either may turn alone: neither turns in every mechanism.
    assert_eq!(u.turning_in_every_mechanism, Some(vec![]));
    let stout = watched(&pair(0.66), &sine(0.55, 2.0), true);
    let u = first_uplift(&stout);
    assert!((u.time_s - first_reach(0.5, 0.55)).abs() <= 1e-13);
    assert_eq!(
        u.turning,
        ["A turns counterclockwise about its bottom-left corner"]
    );
    assert_eq!(u.mechanism_uniqueness, Uniqueness::Unique);
    assert_eq!(u.turning_in_every_mechanism, Some(vec!["A".to_string()]));
}

#[test]
fn at_the_tie_of_friction_and_b_over_h_a_block_slides_and_stays_seated() {
    // Friction 0.5 = b/h: the ground reaches the stick limit and the seated side at one
    // instant, and the sliding model's slip ends the state there; sliding, the resultant sits
    // at the leading corner, still seated. Friction 0.51 lifts, at g/2.
    let r = watched(&slender("0.5"), &sine(0.7, 3.0), true);
    assert!(r.summary.stick_slip_transitions > 0);
    assert_eq!(
        r.summary.uplift_check,
        Some(UpliftCheck {
            checked_until_s: 3.0,
            first_uplift: None
        })
    );
    let r = watched(&slender("0.51"), &sine(0.7, 3.0), true);
    assert!((first_uplift(&r).time_s - first_reach(0.5, 0.7)).abs() <= 1e-13);
}

#[test]
fn a_block_dragged_by_a_sliding_one_lifts_where_its_moments_say() {
    // L (0.5 x 1.0 m, friction 0.8 on the ground) carries U (0.25 x 0.25 m, centred, friction
    // 0.3). At rest the pair would tip at 0.439 g, but U slides first, at 0.3 g, backwards on
    // L; then L's balance of moments (the unit test of `seated` works it by hand) holds while
    // a_g <= 153/320 g = 0.478 g, where L turns, U's friction dragging its top.
    let m = Model::from_file("walls/rocking/dragged-block.ron").unwrap();
    let r = watched(&m, &sine(0.7, 2.0), true);
    let u = first_uplift(&r);
    let slip = r
        .events
        .iter()
        .find(|e| e.joint.as_deref() == Some("U/L"))
        .expect("U slips");
    assert!((slip.time_s - first_reach(0.3, 0.7)).abs() <= 1e-13);
    assert!(
        (u.time_s - first_reach(153.0 / 320.0, 0.7)).abs() <= 1e-13,
        "{}",
        u.time_s
    );
    assert!(u.time_s > slip.time_s);
    assert_eq!(
        u.turning[0],
        "L turns counterclockwise about its bottom-left corner"
    );
    // U, sliding on one joint, leaves its balances dependent (its two corner forces lie on one
    // edge of the cone): the multipliers may move U along that edge's normal, and nothing
    // else, so the mechanism is decided the only one.
    assert_eq!(u.mechanism_uniqueness, Uniqueness::Unique);
}

#[test]
fn at_rest_the_check_meets_the_limit_at_rest_on_the_ollantaytambo_wall() {
    // El Centro at 0.3 g takes the wall past its limit towards -x (0.2834 g: F5 rocks against
    // its monolith) before anything slides.
    let m = Model::from_file("walls/inca/ollantaytambo-monoliths.ron").unwrap();
    let motion = el_centro(0.3);
    let r = watched(&m, &motion, true);
    let u = first_uplift(&r);
    let limits = at_rest(m.wall(), m.topology()).unwrap();
    let Limit::Holds {
        accel_m_s2,
        mechanism,
        mechanism_uniqueness,
        turning_in_every_mechanism,
        ..
    } = limits.towards_minus_x
    else {
        panic!("unlimited");
    };
    assert!((u.ground_accel_m_s2 + accel_m_s2).abs() <= 1e-12 * accel_m_s2);
    let turning: Vec<String> = mechanism
        .iter()
        .filter(|b| b.omega_rad_s != 0.0)
        .map(|b| format!("{} {}", b.block, b.how))
        .collect();
    assert_eq!(u.turning, turning);
    assert_eq!(u.mechanism_uniqueness, mechanism_uniqueness);
    assert_eq!(u.turning_in_every_mechanism, turning_in_every_mechanism);
    assert!(
        r.events.iter().all(|e| e.time_s >= u.time_s),
        "still at rest"
    );
}

/// The run's warnings that a block's peak acceleration reaches g b/h bound what a block
/// standing free could do; a check that watched the run and found every block seated answers
/// it for the wall, and they are left out. The Ollantaytambo fillers would lift standing free
/// at 0.06-0.09 g: under El Centro at 0.1 g each is warned about unwatched, and watched the
/// check finds them seated throughout, without those warnings; at 0.3 g, where it finds an
/// uplift, the warnings stay beside it.
#[test]
fn a_check_that_finds_every_block_seated_supersedes_the_free_standing_warnings() {
    let m = Model::from_file("walls/inca/ollantaytambo-monoliths.ron").unwrap();
    let could_rock = |r: &Response| -> Vec<String> {
        (r.summary.warnings.iter())
            .filter_map(|w| match w {
                Warning::CouldRock { name, .. } => Some(name.clone()),
                _ => None,
            })
            .collect()
    };
    let (plain, seen) = (
        watched(&m, &el_centro(0.1), false),
        watched(&m, &el_centro(0.1), true),
    );
    assert_eq!(could_rock(&plain), ["F1", "F2", "F3", "F4", "F5"]);
    let check = seen.summary.uplift_check.as_ref().unwrap();
    assert_eq!(check.first_uplift, None);
    assert!(could_rock(&seen).is_empty(), "{:?}", seen.summary.warnings);
    let mut seen_summary = seen.summary.clone();
    seen_summary.uplift_check = None;
    seen_summary.warnings.clone_from(&plain.summary.warnings);
    assert_eq!(seen_summary, plain.summary);
    let lifted = watched(&m, &el_centro(0.3), true);
    first_uplift(&lifted);
    assert_eq!(
        could_rock(&lifted),
        could_rock(&watched(&m, &el_centro(0.3), false))
    );
    assert!(!could_rock(&lifted).is_empty());
}

#[test]
fn watching_changes_nothing_else_and_finds_nothing_on_the_papers_wall() {
    let m = Model::from_file("walls/five-block-variable.ron").unwrap();
    let motion = sine(400.0 / 981.0, 20.0);
    let (plain, seen) = (watched(&m, &motion, false), watched(&m, &motion, true));
    assert_eq!(
        seen.summary.uplift_check,
        Some(UpliftCheck {
            checked_until_s: 20.0,
            first_uplift: None
        })
    );
    let mut seen_summary = seen.summary.clone();
    seen_summary.uplift_check = None;
    assert_eq!(seen_summary, plain.summary);
    assert_eq!(seen.events, plain.events);
    assert_eq!(seen.final_displacement_m, plain.final_displacement_m);
    assert!(!plain.summary_json().contains("uplift_check"));
}

#[test]
fn the_check_is_refused_where_the_sliding_engine_does_not_run() {
    // Time stepping, a block alone that `auto` gives the exact rocking model, and the
    // direction across the plane.
    let wall = Model::from_file("walls/five-block-variable.ron").unwrap();
    let block = slender("0.6");
    for (m, method, model, direction) in [
        (
            &wall,
            Method::Moreau { dt_s: 1e-3 },
            ModelChoice::Slide,
            Direction::InPlane,
        ),
        (&block, Method::Event, ModelChoice::Auto, Direction::InPlane),
        (
            &wall,
            Method::Event,
            ModelChoice::Auto,
            Direction::OutOfPlane,
        ),
    ] {
        let settings = RunSettings {
            method,
            model,
            direction,
            check_uplift: true,
            ..RunSettings::default()
        };
        let e = pirqa::run(m, &sine(0.55, 2.0), &settings)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("--check-uplift watches the exact sliding engine"),
            "{e}"
        );
    }
}

#[test]
fn a_stop_request_ends_the_run_while_the_checks_programs_run() {
    // A request to stop (Ctrl-C, a job's SIGTERM) reaches the check's linear programs, which
    // look at it at every pivot: an exact program of a large wall can take hours, and a run
    // that looked only where it reports its progress would not stop within them. Asked from
    // the start, the run without the check stops where it first reports (a quarter of the
    // sine's period); with the check it stops in the first state's programs, at t = 0.
    use pirqa::integrate::Progress;
    use std::sync::atomic::AtomicBool;
    use std::sync::Arc;
    let m = Model::from_file("walls/five-block-variable.ron").unwrap();
    let motion = sine(400.0 / 981.0, 20.0);
    let run = |check_uplift: bool| {
        let settings = RunSettings {
            model: ModelChoice::Slide,
            check_uplift,
            output_dt_s: None,
            progress: Some(Progress::new(|_| {}).with_stop(Arc::new(AtomicBool::new(true)))),
            ..RunSettings::default()
        };
        pirqa::run(&m, &motion, &settings).unwrap().summary
    };
    assert_eq!(run(false).interrupted_at_s, Some(0.25));
    let stopped = run(true);
    assert_eq!(stopped.interrupted_at_s, Some(0.0));
    assert_eq!(
        stopped.uplift_check,
        Some(UpliftCheck {
            checked_until_s: 0.0,
            first_uplift: None
        })
    );
}

#[test]
fn under_vertical_shaking_a_block_lifts_where_its_ground_acceleration_over_the_load_reaches_g_b_over_h(
) {
    // Every load of a seated state scales with the vertical load factor lambda = 1 + a_v/g,
    // so the block lifts where a_h / lambda = g b/h. Ramps in both directions, linear between
    // samples as every record is: a_h = s_h t, lambda = 1 + s_v t / g, so the block lifts at
    // t = (g b/h) / (s_h - s_v b/h). A falling ground (s_v < 0) lightens the block and it
    // lifts sooner than on level ground, still before it could slide (friction 0.6 > 1/2).
    let (g, dt, n) = (9.81, 0.01, 301);
    let (s_h, s_v) = (4.0, -3.0);
    let ramp = |s: f64| (0..n).map(|k| s * (k as f64 * dt)).collect::<Vec<f64>>();
    let horizontal = pirqa::motion::Record::new("h", dt, ramp(s_h)).unwrap();
    let vertical = pirqa::motion::Record::new("v", dt, ramp(s_v)).unwrap();
    let both = Motion::Record(horizontal.with_vertical(&vertical, g).unwrap());
    let u = first_uplift(&watched(&slender("0.6"), &both, true)).clone();
    let expected = (g / 2.0) / (s_h - s_v / 2.0);
    assert!(
        (u.time_s - expected).abs() <= 1e-12,
        "{} {expected}",
        u.time_s
    );
    assert!((u.ground_accel_m_s2 - s_h * expected).abs() <= 1e-12);
    assert_eq!(
        u.turning,
        ["A turns counterclockwise about its bottom-left corner"]
    );
    // The same ramp without the vertical component: later, at g/2 itself.
    let level = first_uplift(&watched(&slender("0.6"), &Motion::Record(horizontal), true)).clone();
    assert!(
        (level.time_s - (g / 2.0) / s_h).abs() <= 1e-12,
        "{}",
        level.time_s
    );
}

#[test]
fn after_a_fall_the_check_goes_on_without_the_fallen_block() {
    // A slender block (0.4 x 1.0 m, friction 0.6 on the ground) carries a slab (0.4 x 0.2 m,
    // friction 0.1). Under 3 m/s2 the slab slides off, relative acceleration 3 - 0.1 g, and
    // falls once its centroid passes the edge, 0.2 m on: at sqrt(0.4 / (3 - 0.1 g)). From 1 s
    // the ground ramps up at 2 m/s3; run on past the fall (`after_collapse: Continue`), the
    // check takes the block alone, which lifts at g b/h = 0.4 g (at 1 + (0.4 g - 3) / 2 s).
    // Had the fallen slab still weighed on it, the pair would lift elsewhere.
    use pirqa::integrate::AfterCollapse;
    let g = 9.81;
    let m = Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
          joint_friction: {\"S/A\": 0.1},
          rows: [(height_m: 1.0, blocks: [(width_m: 0.4, name: \"A\")]),
                 (height_m: 0.2, blocks: [(width_m: 0.4, name: \"S\")])])",
    )
    .unwrap();
    let dt = 0.01;
    let samples: Vec<f64> = (0..=200)
        .map(|k| 3.0 + 2.0 * (k as f64 * dt - 1.0).max(0.0))
        .collect();
    let motion = Motion::Record(pirqa::motion::Record::new("ramp", dt, samples).unwrap());
    let settings = RunSettings {
        model: ModelChoice::Slide,
        check_uplift: true,
        after_collapse: AfterCollapse::Continue,
        ..RunSettings::default()
    };
    let r = pirqa::run(&m, &motion, &settings).unwrap();
    let fall = r.summary.collapse.as_ref().expect("the slab falls");
    assert_eq!(fall.block, "S");
    let falls_at = (0.4f64 / (3.0 - 0.1 * g)).sqrt();
    assert!((fall.time_s - falls_at).abs() <= 1e-12, "{}", fall.time_s);
    let u = first_uplift(&r);
    let lifts_at = 1.0 + (0.4 * g - 3.0) / 2.0;
    assert!(
        (u.time_s - lifts_at).abs() <= 1e-12,
        "{} {lifts_at}",
        u.time_s
    );
    assert_eq!(
        u.turning,
        ["A turns counterclockwise about its bottom-left corner"]
    );
    assert_eq!(u.mechanism_uniqueness, Uniqueness::Unique);
    assert_eq!(u.turning_in_every_mechanism, Some(vec!["A".to_string()]));
}
