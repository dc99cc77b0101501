//! `--after-uplift moreau`: the exact sliding run up to its first uplift, Moreau-Jean with every
//! block's rotation from there. Before the uplift the answer is the exact sliding run's to the
//! bit; after it, a slender block that tips away from its neighbour rocks as the exact rocking
//! model rocks it standing alone, the gap closing as the step falls; a wall that never lifts
//! keeps its exact sliding answer; a stop request ends either part with what it reached;
//! combinations that cannot hand off are refused.

use pirqa::motion::{Motion, Record, Sine};
use pirqa::{AfterUplift, Method, Model, ModelChoice, Response, RunSettings};

const G: f64 = 9.81;

/// A slender block S (0.3 x 1.2 m, b/h = 1/4) beside a squat one W (1.2 x 1.2 m), touching, on
/// the ground, friction 0.6 (walls/rocking/slab-beside-block.ron): `auto` slides walls whose
/// blocks touch, so the sliding model runs it. Under a ground accelerating to the right both lean
/// left; S has nothing on its left to hold it and lifts alone at g b/h = g/4, turning away from W,
/// which would lift at g and slide at 0.6 g.
pub(crate) fn pair() -> Model {
    Model::from_file("walls/rocking/slab-beside-block.ron").unwrap()
}

/// S alone.
fn alone() -> Model {
    Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\")])])",
    )
    .unwrap()
}

/// The ground acceleration rising at 2 m/s3 (linear between samples, so exactly s t).
fn ramp() -> Motion {
    let (dt, n) = (0.01, 301);
    let samples = (0..n).map(|k| 2.0 * (k as f64 * dt)).collect();
    Motion::Record(Record::new("ramp", dt, samples).unwrap())
}

pub(crate) fn settings(duration_s: f64, after_uplift: AfterUplift) -> RunSettings {
    RunSettings {
        duration_s: Some(duration_s),
        output_dt_s: Some(0.01),
        log_events: true,
        after_uplift,
        ..RunSettings::default()
    }
}

pub(crate) fn history(r: &Response) -> &pirqa::response::History {
    r.history.as_ref().expect("a history")
}

#[test]
fn before_the_uplift_the_answer_is_the_exact_sliding_runs_to_the_bit() {
    let t_u = (G / 4.0) / 2.0;
    let handed = pirqa::run(
        &pair(),
        &ramp(),
        &settings(2.0, AfterUplift::Moreau { dt_s: 1e-3 }),
    )
    .unwrap();
    let sliding = pirqa::run(
        &pair(),
        &ramp(),
        &RunSettings {
            model: ModelChoice::Slide,
            check_uplift: true,
            ..settings(2.0, AfterUplift::Slide)
        },
    )
    .unwrap();
    let check = handed.summary.uplift_check.as_ref().unwrap();
    assert_eq!(Some(check), sliding.summary.uplift_check.as_ref());
    let uplift = check.first_uplift.as_ref().unwrap();
    assert!((uplift.time_s - t_u).abs() <= 1e-12, "{}", uplift.time_s);
    assert_eq!(
        uplift.turning,
        ["S turns counterclockwise about its bottom-left corner"]
    );
    let (h, s) = (history(&handed), history(&sliding));
    let before = s.time_s.iter().take_while(|&&t| t <= uplift.time_s).count();
    assert!(before > 100);
    assert_eq!(h.time_s[..before], s.time_s[..before]);
    assert_eq!(h.displacement_m[..before], s.displacement_m[..before]);
    assert_eq!(h.velocity_m_s[..before], s.velocity_m_s[..before]);
    // One history of one shape: rotations at zero while the sliding model ran.
    assert_eq!(h.rotation_rad.len(), h.time_s.len());
    assert!(h.rotation_rad[..before].iter().flatten().all(|&x| x == 0.0));
    // The row at the hand-off, then the output times after it.
    assert_eq!(h.time_s[before], uplift.time_s);
    assert!((h.time_s[before + 1] - 1.23).abs() < 1e-12);
    assert_eq!(*h.time_s.last().unwrap(), 2.0);
    assert_eq!(handed.summary.duration_s, 2.0);
    assert_eq!(handed.summary.method, "event+moreau");
    assert_eq!(handed.summary.model.name, "slide-rock");
    // The hand-over in the event log, with the block that turns.
    let lifted = (handed.events.iter())
        .find(|e| e.kind == pirqa::response::EventKind::Uplift)
        .expect("an uplift event");
    assert_eq!(
        (lifted.time_s, &lifted.blocks[..]),
        (uplift.time_s, &["S".to_string()][..])
    );
    assert!(handed
        .summary
        .model
        .why
        .contains("first uplift at t = 1.22625"));
    // The sliding run warns that it leaves the rocking out; the handed-off run follows it.
    assert!(sliding
        .summary
        .warnings
        .iter()
        .any(|w| matches!(w, pirqa::Warning::Lifts { .. })));
    assert!(!handed
        .summary
        .warnings
        .iter()
        .any(|w| matches!(w, pirqa::Warning::Lifts { .. })));
    // S turns from the uplift on; W stays seated. Time stepping counts a block lifted once a
    // corner has risen 1e-6 m (`moreau_wall.rs`), theta = 1e-6 / 0.6 here. About its corner,
    // I_O theta'' = m (h/2) (a_g - g b/h) to first order, with I_O = m (b^2 + h^2)/3 and
    // a_g - g b/h = s tau after the uplift: theta = h s tau^3 / (4 (b^2 + h^2)), which
    // reaches it at tau = 16.2 ms; the step in which it does is where the run marks it.
    let (b, h, s): (f64, f64, f64) = (0.3, 1.2, 2.0);
    let tau = (1e-6 / 0.6 * 4.0 * (b * b + h * h) / (h * s)).cbrt();
    let lifted = handed.summary.blocks[0].uplift_time_s.unwrap();
    assert!(
        (lifted - (t_u + tau)).abs() <= 2e-3,
        "{lifted} {}",
        t_u + tau
    );
    assert!(handed.summary.blocks[0].max_abs_rotation_rad > 0.25);
    assert!(handed.summary.blocks[1].max_abs_rotation_rad < 1e-6);
    // The energy balance: what the stepping took is friction and landings, so the residual
    // is the sliding part's own, closed to round-off.
    let e = &handed.summary.energy;
    assert!(
        e.residual_j.abs() <= 1e-9 * e.input_j.abs().max(1.0),
        "{e:?}"
    );
    assert!(e.friction_j >= 0.0 && e.kinetic_j > 0.0);
}

#[test]
fn after_the_uplift_the_block_rocks_as_the_exact_model_rocks_it_alone() {
    // S turns away from W, so it rocks as if it stood alone, which the exact rocking model
    // answers; Moreau-Jean is first order, so the gap to it falls with the step.
    let duration = 2.0;
    let exact = pirqa::run(&alone(), &ramp(), &settings(duration, AfterUplift::Slide)).unwrap();
    assert_eq!(exact.summary.method, "event");
    assert_eq!(exact.summary.model.name, "slide-rock");
    let theta_exact = history(&exact).rotation_rad.iter().map(|r| r[0]);
    let times = history(&exact).time_s.clone();
    let theta_exact: Vec<(f64, f64)> = times.iter().copied().zip(theta_exact).collect();
    let gap = |dt_s: f64| -> f64 {
        let r = pirqa::run(
            &pair(),
            &ramp(),
            &settings(duration, AfterUplift::Moreau { dt_s }),
        )
        .unwrap();
        let h = history(&r);
        let mut worst: f64 = 0.0;
        for (t, theta) in &theta_exact {
            // At the output times both write.
            let Some(k) = h.time_s.iter().position(|s| s == t) else {
                continue;
            };
            worst = worst.max((h.rotation_rad[k][0] - theta).abs());
        }
        worst
    };
    let peak = exact.summary.blocks[0].max_abs_rotation_rad;
    // Past its slenderness angle atan(1/4) = 0.245 rad by the end: on its way over.
    assert!(peak > 0.25, "{peak}");
    let (coarse, fine) = (gap(1e-3), gap(1e-4));
    // First order: a tenth of the step, a tenth of the gap (3.9e-4 and 3.9e-5 rad).
    assert!(fine < 1e-3 * peak, "{coarse} {fine} of {peak}");
    let ratio = coarse / fine;
    assert!((7.0..13.0).contains(&ratio), "{coarse} {fine}");
}

#[test]
fn a_wall_that_never_lifts_keeps_its_exact_sliding_answer() {
    let model = Model::from_file("walls/five-block-variable.ron").unwrap();
    let sine = Motion::sine(Sine {
        amplitude_m_s2: 4.0,
        frequency_hz: 1.0,
        duration_s: 20.0,
        ..Sine::default()
    })
    .unwrap();
    let handed = pirqa::run(
        &model,
        &sine,
        &settings(20.0, AfterUplift::Moreau { dt_s: 1e-3 }),
    )
    .unwrap();
    let plain = pirqa::run(&model, &sine, &settings(20.0, AfterUplift::Slide)).unwrap();
    let (a, b) = (&handed.summary, &plain.summary);
    assert!(a.uplift_check.as_ref().unwrap().first_uplift.is_none());
    assert_eq!(a.method, "event");
    assert_eq!(a.blocks, b.blocks);
    assert_eq!(a.horizontal_joints, b.horizontal_joints);
    assert_eq!(a.energy, b.energy);
    assert_eq!(a.impacts, b.impacts);
    assert_eq!(
        history(&handed).displacement_m,
        history(&plain).displacement_m
    );
    assert_eq!(handed.events, plain.events);
}

#[test]
fn what_cannot_hand_off_is_refused_with_the_reason() {
    let moreau = AfterUplift::Moreau { dt_s: 1e-3 };
    let refused = |model: &Model, s: RunSettings| -> String {
        pirqa::run(model, &ramp(), &s).unwrap_err().to_string()
    };
    let e = refused(
        &pair(),
        RunSettings {
            method: Method::Moreau { dt_s: 1e-3 },
            ..settings(1.0, moreau)
        },
    );
    assert!(e.contains("--method chooses another integrator"), "{e}");
    let e = refused(
        &pair(),
        RunSettings {
            model: ModelChoice::Slide,
            ..settings(1.0, moreau)
        },
    );
    assert!(e.contains("--model chooses one model"), "{e}");
    let e = refused(&alone(), settings(3.0, moreau));
    assert!(
        e.contains("the exact rocking model follows this wall's uplift"),
        "{e}"
    );
    let e = refused(&pair(), settings(1.0, AfterUplift::Moreau { dt_s: -1.0 }));
    assert!(e.contains("time step"), "{e}");
}

#[test]
fn a_stop_request_ends_a_handed_over_run_with_what_it_reached() {
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::Arc;
    // Asked before it starts: the sliding part ends at once, and says so.
    let at_once = RunSettings {
        progress: Some(pirqa::integrate::Progress::new(|_| {}).with_stop_when(|| true)),
        ..settings(2.0, AfterUplift::Moreau { dt_s: 1e-4 })
    };
    let r = pirqa::run(&pair(), &ramp(), &at_once).unwrap();
    assert!(r.summary.interrupted_at_s.is_some());
    assert!(r
        .summary
        .model
        .why
        .contains("stopped while the exact sliding model ran"));
    // Asked once the steps after the uplift (1.22625 s) have passed 1.5 s: they end there,
    // the hand-off and the rotations so far kept.
    let stop = Arc::new(AtomicBool::new(false));
    let flag = Arc::clone(&stop);
    let later = RunSettings {
        progress: Some(
            pirqa::integrate::Progress::new(move |t| {
                if t >= 1.5 {
                    flag.store(true, Ordering::Relaxed);
                }
            })
            .with_stop(stop),
        ),
        ..settings(2.0, AfterUplift::Moreau { dt_s: 1e-4 })
    };
    let r = pirqa::run(&pair(), &ramp(), &later).unwrap();
    let t = r.summary.interrupted_at_s.expect("stopped");
    assert!((1.5..1.7).contains(&t), "{t}");
    assert_eq!(r.summary.method, "event+moreau");
    assert_eq!(r.summary.duration_s, t);
    let h = history(&r);
    assert!(*h.time_s.last().unwrap() <= t);
    assert!(h.rotation_rad.last().unwrap()[0].abs() > 0.0);
}
