//! The exact event-driven integrator against closed forms, hand derivations, conservation laws
//! and the paper's findings.

use crate::engine;

use engine::{constant, impacts, load, run, sine};
use pirqa::integrate::event::EventDriven;
use pirqa::integrate::{Integrator, Scenario, Settings};
use pirqa::response::{EventKind, Response};
use pirqa::samples::{self, SlidingBlockReference};
use pirqa::Topology;

/// Largest |event-driven u - reference u| over the sampled history of block `i`.
fn history_error(r: &Response, i: usize, reference: impl Fn(f64) -> f64) -> f64 {
    let h = r.history.as_ref().unwrap();
    h.time_s
        .iter()
        .zip(&h.displacement_m)
        .map(|(&t, u)| (u[i] - reference(t)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn one_block_above_threshold_follows_the_closed_form() {
    for (amp, freq, phase) in [(4.0, 1.0, 0.0), (6.0, 2.5, 30.0), (3.5, 0.7, 200.0)] {
        let duration = 20.0;
        let r = run(
            &samples::one_block(0.3),
            &sine(amp, freq, phase, duration),
            duration,
            Some(0.01),
        );
        let reference =
            SlidingBlockReference::new(0.3, 9.81, amp, freq, phase.to_radians(), duration);
        assert!(reference.phase_count() > 20, "many cycles of stick-slip");
        let err = history_error(&r, 0, |t| reference.displacement(t));
        assert!(
            err < 1e-10,
            "{amp} m/s2 {freq} Hz: |u - u_ref| up to {err:e} m"
        );
        let b = &r.summary.blocks[0];
        assert!((b.max_abs_displacement_m - reference.max_abs_displacement()).abs() < 1e-10);
        assert!((b.final_displacement_m - reference.displacement(duration)).abs() < 1e-10);
    }
}

#[test]
fn a_long_run_of_many_thousand_events_stays_on_the_closed_form() {
    // 3,000 cycles of stick-slip: more events than the per-instant guard allows at one instant
    // (10,000), spread over 300 s; the guard must count instants, not the whole run.
    let (amp, freq, duration) = (4.0, 10.0, 300.0);
    let r = run(
        &samples::one_block(0.3),
        &sine(amp, freq, 0.0, duration),
        duration,
        None,
    );
    assert!(
        r.summary.stats.events > 10_000,
        "{}",
        r.summary.stats.events
    );
    let reference = SlidingBlockReference::new(0.3, 9.81, amp, freq, 0.0, duration);
    let b = &r.summary.blocks[0];
    assert!((b.final_displacement_m - reference.displacement(duration)).abs() < 1e-10);
    assert!((b.max_abs_displacement_m - reference.max_abs_displacement()).abs() < 1e-10);
}

#[test]
fn one_block_below_threshold_does_not_move_at_all() {
    let r = run(
        &samples::one_block(0.3),
        &sine(2.9, 1.0, 0.0, 10.0),
        10.0,
        Some(0.01),
    );
    let h = r.history.as_ref().unwrap();
    assert!(h.displacement_m.iter().all(|u| u[0] == 0.0));
    assert!(h.velocity_m_s.iter().all(|v| v[0] == 0.0));
    assert_eq!(r.summary.blocks[0].max_abs_displacement_m, 0.0);
    assert_eq!(r.summary.stick_slip_transitions, 0);
    assert_eq!(r.summary.stats.events, 0);
}

#[test]
fn two_stacked_blocks_match_the_hand_derivation() {
    // 1000 kg each; top on bottom mu = 0.2 (F = 1962 N), bottom on ground mu = 0.5 (F = 9810 N).
    // Constant a_g = a from rest:
    //  - a <= 1.962: nothing moves;
    //  - 1.962 < a <= (9810 - 1962)/1000 = 7.848: the top slides, u2 = (0.2 g - a) t^2/2;
    //  - a > 7.848: both slide, u1 = (7.848 - a) t^2/2, u2 = (1.962 - a) t^2/2.
    let wall = samples::stacked_pair(0.5, 0.2);
    for (a, c1, c2) in [
        (1.9, None, None),
        (3.0, None, Some(1.962)),
        (7.5, None, Some(1.962)),
        (8.0, Some(7.848), Some(1.962)),
    ] {
        let r = run(&wall, &constant(a, 1.0), 1.0, Some(0.05));
        for (i, c) in [(0, c1), (1, c2)] {
            let expect = |t: f64| c.map_or(0.0, |c: f64| (c - a) * t * t / 2.0);
            let err = history_error(&r, i, expect);
            assert!(err < 1e-12, "a = {a}, block {i}: error {err:e}");
        }
    }
}

#[test]
fn side_by_side_blocks_touch_at_phase_0_and_collide_at_phase_135() {
    let wall = samples::course(&[0.25, 0.3], &[0.0, 0.0], 1.0);
    let r = run(&wall, &sine(4.0, 1.0, 0.0, 10.0), 10.0, None);
    assert_eq!(
        r.summary.impacts, 0,
        "a symmetric sine brings them back together at rest"
    );
    assert_eq!(r.summary.touches, 9, "one touch per cycle after the first");
    let r = run(&wall, &sine(4.0, 1.0, 135.0, 10.0), 10.0, None);
    assert!(r.summary.impacts >= 5, "{} impacts", r.summary.impacts);
    assert_eq!(r.summary.energy.impact_loss_j, 0.0, "e = 1 loses nothing");
    let m = 1000.0;
    for e in r.events.iter().filter(|e| e.kind == EventKind::Impact) {
        let (b, a) = (e.before_m_s.unwrap(), e.after_m_s.unwrap());
        let scale = b[0].abs() + b[1].abs();
        assert!(
            (m * (b[0] + b[1]) - m * (a[0] + a[1])).abs() <= 4.0 * f64::EPSILON * m * scale,
            "momentum"
        );
        let ke = |v: [f64; 2]| 0.5 * m * (v[0] * v[0] + v[1] * v[1]);
        assert!(
            (ke(b) - ke(a)).abs() <= 8.0 * f64::EPSILON * ke(b),
            "energy"
        );
        assert!(a[1] - a[0] > 0.0, "they separate after the impact");
    }
}

#[test]
fn energy_balances_on_every_shipped_wall() {
    for path in [
        "walls/five-block-uniform.ron",
        "walls/five-block-variable.ron",
        "walls/inca-coursed.ron",
    ] {
        for (amp, freq, phase) in [(4.0, 1.0, 0.0), (5.0, 3.0, 45.0)] {
            let r = run(&load(path), &sine(amp, freq, phase, 10.0), 10.0, None);
            let e = r.summary.energy;
            assert!(e.input_j > 0.0);
            assert!(
                e.residual_j.abs() <= 1e-9 * e.input_j,
                "{path}: residual {:e} of {:e}",
                e.residual_j,
                e.input_j
            );
        }
    }
}

#[test]
fn uniform_friction_wall_moves_as_one_rigid_body() {
    let wall = load("walls/five-block-uniform.ron");
    for freq in [0.5, 1.0, 2.0, 5.0] {
        let motion = sine(4.0, freq, 0.0, 10.0);
        let r = run(&wall, &motion, 10.0, Some(0.01));
        assert_eq!(r.summary.impacts, 0);
        // Every decision takes in the one body of five blocks, and cuts over five blocks try
        // every set: no flow is run.
        let stats = r.summary.stats;
        assert_eq!(stats.decision_blocks, 5 * stats.mode_decisions);
        assert_eq!(stats.flow_nodes, 0);
        for j in &r.summary.horizontal_joints {
            if j.lower != "ground" {
                assert_eq!(
                    j.max_abs_relative_displacement_m, 0.0,
                    "{}/{} slid",
                    j.upper, j.lower
                );
            }
        }
        let h = r.history.as_ref().unwrap();
        assert!(
            h.displacement_m
                .iter()
                .all(|u| u.iter().all(|&x| x == u[0])),
            "every block moves identically"
        );
        // ... and exactly as one block with the same friction.
        let one = run(&samples::one_block(0.3), &motion, 10.0, Some(0.01));
        assert_eq!(
            r.summary.blocks[0].max_abs_displacement_m,
            one.summary.blocks[0].max_abs_displacement_m
        );
        let reference = SlidingBlockReference::new(0.3, 9.81, 4.0, freq, 0.0, 10.0);
        assert!(history_error(&r, 3, |t| reference.displacement(t)) < 1e-10);
    }
}

#[test]
fn variable_friction_gives_relative_slip_impacts_and_larger_maxima() {
    let uniform = load("walls/five-block-uniform.ron");
    let variable = load("walls/five-block-variable.ron");
    let motion = sine(4.0, 1.0, 0.0, 20.0);
    let u = run(&uniform, &motion, 20.0, None);
    let v = run(&variable, &motion, 20.0, None);
    let max = |r: &Response| {
        r.summary
            .blocks
            .iter()
            .map(|b| b.max_abs_displacement_m)
            .fold(0.0, f64::max)
    };
    assert!(
        max(&v) > 1.2 * max(&u),
        "variable {} vs uniform {}",
        max(&v),
        max(&u)
    );
    assert!(v.summary.impacts > 0);
    let b3b1 = v
        .summary
        .horizontal_joints
        .iter()
        .find(|j| j.upper == "B3" && j.lower == "B1")
        .unwrap();
    assert!(b3b1.max_abs_relative_displacement_m > 1e-3);
}

/// Locating an event takes a few evaluations of its functions (a closed-form guess polished to
/// the float, or a handful of Newton steps), not a bisection's fifty. The paper's variable wall
/// under 20 s of sine needs about 28 per event (31 while a refinement evaluated its bracket's
/// ends again); 101 when Newton bisected back from the end of a
/// bracket it had landed on and the closed-form time of a sine acceleration could pick the arc
/// before a crest. A count of evaluations, not a timing: it is the same on every machine.
#[test]
fn events_are_located_in_a_few_evaluations_each() {
    let wall = load("walls/five-block-variable.ron");
    let r = run(&wall, &sine(4.0, 1.0, 0.0, 20.0), 20.0, None);
    let stats = &r.summary.stats;
    let per_event = stats.root_evaluations as f64 / stats.events as f64;
    assert!(per_event < 50.0, "{per_event} evaluations per event");
}

#[test]
fn newtons_cradle_passes_the_velocity_down_the_row() {
    // C B (gap 0.1) A: A alone can slide (mu 0.1), B and C are held (mu 0.5 > 3 / 9.81).
    let wall = samples::course(&[0.5, 0.5, 0.1], &[0.0, 0.0, 0.1], 1.0);
    let r = run(&wall, &constant(3.0, 0.6), 0.6, Some(0.1));
    let impacts = impacts(&r);
    assert_eq!(impacts.len(), 2, "A hits B, B hits C, at one instant");
    assert_eq!(impacts[0].time_s, impacts[1].time_s);
    let t = impacts[0].time_s;
    let v_a = impacts[0].before_m_s.unwrap()[1];
    assert!((t - (2.0f64 * 0.1 / (3.0 - 0.981)).sqrt()).abs() < 1e-12);
    let h = r.history.as_ref().unwrap();
    let row = h.time_s.iter().rposition(|&x| x == t).unwrap();
    assert_eq!(
        h.velocity_m_s[row],
        vec![v_a, 0.0, 0.0],
        "C leaves with A's velocity, A and B stop"
    );
}

#[test]
fn zeno_bounces_follow_the_closed_form_to_the_accumulation_point() {
    // Both blocks slide left under a_g = 5; the right one (mu 0.2) gains on the left one (mu 0.3)
    // at a = (0.3 - 0.2) g, closes the 5 cm gap at t1 with speed v0 = a t1, and bounces with
    // e = 0.5: rebound k leaves at e^k v0 and lands 2 e^k v0 / a later; the bounces accumulate
    // at t1 + 2 e v0 / (a (1 - e)), after which the pair slides as one.
    let (e, gap0) = (0.5, 0.05);
    let wall = samples::course(&[0.3, 0.2], &[0.0, gap0], e);
    let g = wall.g_m_s2.to_f64();
    let mass = Topology::new(&wall).unwrap().blocks[0].mass_kg.to_f64();
    let r = run(&wall, &constant(5.0, 2.0), 2.0, Some(1e-3));
    let (a0, a1) = (-5.0 + 0.3 * g, -5.0 + 0.2 * g);
    let a = a0 - a1;
    let t1 = (2.0 * gap0 / a).sqrt();
    let v0 = a * t1;
    let t_acc = t1 + 2.0 * e * v0 / (a * (1.0 - e));

    // Every impact where the closed form puts it.
    let impacts: Vec<f64> = r
        .events
        .iter()
        .filter(|ev| ev.kind == EventKind::Impact)
        .map(|ev| ev.time_s)
        .collect();
    assert!(impacts.len() >= 10, "{} impacts", impacts.len());
    let mut bounce = vec![(t1, 1.0)];
    for k in 1..impacts.len() {
        let (t, ek) = bounce[k - 1];
        bounce.push((t + 2.0 * ek * e * v0 / a, ek * e));
    }
    for (k, (&t, &(tk, _))) in impacts.iter().zip(&bounce).enumerate() {
        assert!((t - tk).abs() < 1e-12, "impact {k}: {t} vs {tk}");
    }
    let zeno: Vec<f64> = r
        .events
        .iter()
        .filter(|ev| ev.kind == EventKind::Zeno)
        .map(|ev| ev.time_s)
        .collect();
    assert_eq!(zeno.len(), 1);
    assert!((zeno[0] - t_acc).abs() < 1e-12, "{} vs {t_acc}", zeno[0]);
    // The rest of the series, summed in closed form, is within round-off of the faces.
    let (_, e_last) = bounce[impacts.len() - 1];
    let tail = (e_last * e * v0).powi(2) / (2.0 * a);
    assert!(tail < 1e-11, "{tail}");

    // The history: the gap opens and closes on the closed-form parabolas, and the centre of
    // mass never notices the impacts (equal masses, unchanged friction).
    let gap = |t: f64| -> f64 {
        if t < t1 {
            return gap0 - 0.5 * a * t * t;
        }
        match bounce.iter().rposition(|&(tk, _)| tk <= t) {
            Some(k) if t < t_acc => {
                let (tk, ek) = bounce[k];
                let s = t - tk;
                (ek * e * v0 * s - 0.5 * a * s * s).max(0.0)
            }
            _ => 0.0,
        }
    };
    let h = r.history.as_ref().unwrap();
    let mut widest: f64 = 0.0;
    for (&t, u) in h.time_s.iter().zip(&h.displacement_m) {
        let cm = 0.25 * (a0 + a1) * t * t;
        let d = gap(t) - gap0;
        widest = widest.max(if t > t1 { gap(t) } else { 0.0 });
        assert!((u[0] - (cm - 0.5 * d)).abs() < 1e-12, "u0 at {t}");
        assert!((u[1] - (cm + 0.5 * d)).abs() < 1e-12, "u1 at {t}");
    }
    assert!(widest > 0.01, "the first rebound opens the gap by 12 mm");

    // All the relative kinetic energy at the first impact is lost, and the balance closes.
    let en = r.summary.energy;
    let loss = 0.5 * (mass / 2.0) * v0 * v0;
    assert!((en.impact_loss_j - loss).abs() < 1e-9 * loss, "{en:?}");
    assert!(en.residual_j.abs() <= 1e-9 * en.input_j);
}

#[test]
fn mirrored_wall_and_motion_give_the_mirrored_answer() {
    let wall = load("walls/five-block-variable.ron");
    let r = run(&wall, &sine(4.0, 1.0, 0.0, 10.0), 10.0, None);
    let m = run(&wall.mirrored(), &sine(4.0, 1.0, 180.0, 10.0), 10.0, None);
    for (a, b) in r.summary.blocks.iter().zip(&m.summary.blocks) {
        assert!(
            (a.final_displacement_m + b.final_displacement_m).abs() < 1e-9,
            "{}",
            a.name
        );
        assert!(
            (a.max_abs_displacement_m - b.max_abs_displacement_m).abs() < 1e-9,
            "{}",
            a.name
        );
    }
    assert_eq!(r.summary.impacts, m.summary.impacts);
}

/// Under a sine, time scales out: with t' = f t the equations of motion of u f^2 / A do not
/// depend on the frequency (every force is a fixed multiple of g, and the sine's amplitude is
/// fixed). So each block's max |u| times f^2 is the same at every frequency over the same number
/// of cycles, impacts and all: the straight lines of slope -2 in the paper's Fig. 3 and 4.
#[test]
fn maxima_scale_exactly_as_one_over_frequency_squared() {
    let variable = load("walls/five-block-variable.ron");
    let scaled = |f: f64| -> (Vec<f64>, u64) {
        let r = run(&variable, &sine(4.0, f, 0.0, 10.0 / f), 10.0 / f, None);
        assert!(r.summary.collapse.is_none());
        let m = r
            .summary
            .blocks
            .iter()
            .map(|b| b.max_abs_displacement_m * f * f)
            .collect();
        (m, r.summary.impacts)
    };
    let (reference, impacts) = scaled(1.0);
    assert!(impacts > 0, "the case should include impacts");
    for f in [0.5, 2.0, 3.7, 8.0] {
        let (m, n) = scaled(f);
        assert_eq!(n, impacts, "{f} Hz");
        for (a, b) in m.iter().zip(&reference) {
            assert!((a - b).abs() <= 1e-13 * b, "{f} Hz: {a:e} vs {b:e}");
        }
    }
}

/// Every integrator tells its progress: simulated times that never go back or past the
/// duration, ending at it (the bar of `pirqa run` reaches 100 %).
#[test]
fn every_integrator_reports_its_progress_up_to_the_duration() {
    use pirqa::integrate::baselines::{Moreau, PaperNewmark, Regularized};
    use pirqa::integrate::Progress;
    use std::sync::{Arc, Mutex};
    let wall = samples::stacked_pair(0.5, 0.2);
    let topology = Topology::new(&wall).unwrap();
    let motion = sine(4.0, 1.0, 0.0, 3.0);
    let integrators: [Box<dyn Integrator>; 4] = [
        Box::new(EventDriven::default()),
        Box::new(PaperNewmark { dt_s: 1e-3 }),
        Box::new(Moreau::new(1e-3)),
        Box::new(Regularized::new(1e-6)),
    ];
    for integrator in integrators {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let log = seen.clone();
        let settings = Settings {
            progress: Some(Progress::new(move |t| log.lock().unwrap().push(t))),
            ..Settings::summary_only(3.0)
        };
        integrator
            .run(&Scenario {
                wall: &wall,
                topology: &topology,
                motion: &motion,
                settings: &settings,
            })
            .unwrap();
        let seen = seen.lock().unwrap();
        let method = integrator.method();
        assert!(seen.len() >= 6, "{method}: {} reports", seen.len());
        assert!(seen.windows(2).all(|w| w[0] <= w[1]), "{method} went back");
        assert!(seen[0] > 0.0, "{method}");
        assert_eq!(seen.last(), Some(&3.0), "{method}");
    }
}

/// The work of the README's run (the paper's variable wall, 400 gal, 1 Hz, 20 s) is pinned:
/// the counts are the same on every machine, so a change that doubles the work shows here
/// (times are not tested; docs/performance.md has them).
#[test]
fn the_readme_runs_work_counters_are_pinned() {
    let r = run(
        &load("walls/five-block-variable.ron"),
        &sine(4.0, 1.0, 0.0, 20.0),
        20.0,
        None,
    );
    assert_eq!(
        r.summary.stats,
        pirqa::response::Stats {
            events: 245,
            mode_decisions: 246,
            segments: 40,
            root_evaluations: 6836,
            steps: 0,
            decision_blocks: 735,
            flow_nodes: 0,
            pair_schedules: 169,
            unconverged_steps: 0,
        }
    );
}
