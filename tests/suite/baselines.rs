//! Where the time-stepping baselines fail, pinned on the scenarios of
//! `pirqa::study::failures` (docs/accuracy.md has the pictures, `pirqa bench failures` the
//! numbers): each test states the behaviour and the parameter range measured.

use pirqa::integrate::baselines::{Moreau, PaperNewmark, Regularized};
use pirqa::integrate::event::EventDriven;
use pirqa::integrate::Integrator;
use pirqa::response::{EventKind, Response};
use pirqa::study::failures::{self, creep_m, impacts, run};

fn go(integrator: &dyn Integrator, case: &pirqa::study::work_precision::Case) -> Response {
    run(integrator, case, None).unwrap()
}

#[test]
fn a_wall_that_should_move_as_one_slips_under_the_papers_scheme() {
    // Uniform friction: the exact answer keeps the upper row on the lower one (0.0). The paper's
    // scheme lets B3 slip on B1 by about 2 dt (m per second of step) over 10 s of 400 gal, 1 Hz.
    let c = failures::drift_case().unwrap();
    assert_eq!(creep_m(&go(&EventDriven::default(), &c), "B3", "B1"), 0.0);
    for dt in [1e-2, 1e-3, 1e-4] {
        let creep = creep_m(&go(&PaperNewmark { dt_s: dt }, &c), "B3", "B1");
        assert!(
            creep > 1.5 * dt && creep < 3.0 * dt,
            "dt {dt}: creep {creep}"
        );
    }
    // Regularized friction slips at about eps x 2 s under load: 2e-4 m for eps = 1e-4 m/s.
    let creep = creep_m(&go(&Regularized::new(1e-6), &c), "B3", "B1");
    assert!(creep > 1e-4 && creep < 4e-4, "{creep}");
    // Moreau-Jean sticks at velocity level: its slip is round-off (< 1e-12 m).
    assert!(creep_m(&go(&Moreau::new(1e-3), &c), "B3", "B1") < 1e-12);
}

#[test]
fn sgn_friction_never_lets_a_block_stop_under_the_papers_scheme() {
    // One block, 400 gal, 1 Hz: the exact block is at rest 27 % of the time. With sgn(v) the
    // friction force flips sign every step around v = 0 and the velocity hovers at up to
    // about 2 mu g dt instead of zero: no sample of the paper's run is exactly at rest after the
    // motion starts.
    let dt = 1e-3;
    let c = failures::chatter_case();
    let exact = run(&EventDriven::default(), &c, Some(dt)).unwrap();
    let paper = run(&PaperNewmark { dt_s: dt }, &c, Some(dt)).unwrap();
    let (he, hp) = (exact.history.unwrap(), paper.history.unwrap());
    let at_rest: Vec<f64> = he
        .time_s
        .iter()
        .zip(&he.velocity_m_s)
        .filter(|(t, v)| **t > 0.2 && v[0] == 0.0)
        .map(|(t, _)| *t)
        .collect();
    assert!(at_rest.len() > 2000, "{}", at_rest.len());
    let mut hover: f64 = 0.0;
    let mut zero = 0;
    for (t, v) in hp.time_s.iter().zip(&hp.velocity_m_s) {
        if at_rest.iter().any(|x| (x - t).abs() < 1e-9) {
            hover = hover.max(v[0].abs());
            zero += usize::from(v[0] == 0.0);
        }
    }
    assert!(zero < 10, "{zero} samples at rest");
    let mu_g_dt = 0.3 * 9.81 * dt;
    assert!(hover > 0.5 * mu_g_dt && hover < 4.0 * mu_g_dt, "{hover}");
}

#[test]
fn elastic_impacts_gain_or_lose_energy_under_time_stepping() {
    // Two blocks side by side colliding 11 times in 10 s, e = 1. Exact: no impact loss,
    // residual round-off. The paper's scheme (velocity exchange, no position correction)
    // creates about 10 J at dt = 1e-3 (1 J at 1e-4); Moreau-Jean's impacts gain or lose
    // 1e-3 to 1e-1 J.
    let c = failures::elastic_pair_case();
    let exact = go(&EventDriven::default(), &c).summary.energy;
    assert_eq!(exact.impact_loss_j, 0.0);
    assert!(exact.residual_j.abs() < 1e-9 * exact.input_j);
    let paper = go(&PaperNewmark { dt_s: 1e-3 }, &c).summary.energy;
    assert!(
        paper.residual_j.abs() > 5.0 && paper.residual_j.abs() < 20.0,
        "{paper:?}"
    );
    let paper = go(&PaperNewmark { dt_s: 1e-4 }, &c).summary.energy;
    assert!(
        paper.residual_j.abs() > 0.5 && paper.residual_j.abs() < 2.0,
        "{paper:?}"
    );
    let moreau = go(&Moreau::new(1e-3), &c).summary.energy;
    assert!(
        moreau.impact_loss_j.abs() > 1e-3 && moreau.impact_loss_j.abs() < 1e-1,
        "{moreau:?}"
    );
}

#[test]
fn regularized_friction_pays_for_accuracy_with_steps_proportional_to_one_over_eps() {
    // Step-size collapse: the tanh law's stiffness F/(m eps) sets the step; steps grow as
    // 1/eps (measured: 1.7e4 steps at 1e-4 m/s, 1.6e5 at 1e-5 for 10 s of one block).
    let c = failures::chatter_case();
    let steps = |eps: f64| {
        let r = go(
            &Regularized {
                eps,
                ..Regularized::new(1e-6)
            },
            &c,
        );
        r.summary.stats.steps as f64
    };
    let (a, b) = (steps(1e-4), steps(1e-5));
    assert!(b / a > 6.0 && b / a < 14.0, "{a} {b}");
    // And it stalls outright when the step would have to fall below its floor.
    let stalled = Regularized {
        eps: 1e-7,
        min_step: 1e-7,
        ..Regularized::new(1e-6)
    };
    assert!(run(&stalled, &c, None).is_err());
}

#[test]
fn penalty_contacts_pay_for_stiffness_with_steps_while_the_faces_stay_pressed() {
    // The Zeno pair ends pressed together: stiffer springs overlap less but need more steps
    // (measured: 579 steps at 1e9 N/m, 5,419 at 1e11 N/m).
    let c = failures::zeno_case();
    let steps = |k: f64| {
        go(
            &Regularized {
                stiffness: k,
                ..Regularized::new(1e-6)
            },
            &c,
        )
        .summary
        .stats
        .steps as f64
    };
    let (soft, stiff) = (steps(1e9), steps(1e11));
    assert!(stiff / soft > 5.0, "{soft} {stiff}");
}

#[test]
fn zeno_bounces_chatter_under_time_stepping() {
    // e = 0.5 bounces accumulating at a closed-form time: the exact integrator follows the
    // bounces until the rest of the series is within round-off, then sums it (one Zeno
    // event); the paper's scheme chatters through about a thousand impacts at dt = 1e-3 and
    // leaves the faces 0.17 mm into each other.
    let c = failures::zeno_case();
    let exact = go(&EventDriven::default(), &c);
    assert_eq!(exact.summary.zeno_accumulations, 1);
    assert!(exact.summary.impacts < 40, "{}", exact.summary.impacts);
    let paper = run(&PaperNewmark { dt_s: 1e-3 }, &c, Some(1e-3)).unwrap();
    assert!(paper.summary.impacts > 500, "{}", paper.summary.impacts);
    let b = &paper.summary.blocks;
    let gap = 0.05 + b[1].final_displacement_m - b[0].final_displacement_m;
    assert!(gap < -1e-4, "overlap {gap}");
}

#[test]
fn a_grazing_impact_is_missed_by_a_coarse_step() {
    // Two blocks whose gap closes by only 1.5e-8 m at t = 0.6795 s (an impact at 0.34 mm/s).
    // Moreau-Jean at dt = 1e-2 and the paper's scheme at dt = 1e-2 and 1e-3 miss it;
    // Moreau-Jean at dt <= 3e-3 sees it.
    let c = failures::grazing_case();
    let exact = go(&EventDriven::default(), &c);
    assert_eq!(impacts(&exact), 1);
    let hit = exact
        .events
        .iter()
        .find(|e| e.kind == EventKind::Impact)
        .unwrap();
    assert!((hit.time_s - 0.6795).abs() < 1e-3);
    assert_eq!(impacts(&go(&Moreau::new(1e-2), &c)), 0);
    assert_eq!(impacts(&go(&PaperNewmark { dt_s: 1e-2 }, &c)), 0);
    assert_eq!(impacts(&go(&PaperNewmark { dt_s: 1e-3 }, &c)), 0);
    assert_eq!(impacts(&go(&Moreau::new(3e-3), &c)), 1);
    assert_eq!(impacts(&go(&Moreau::new(1e-3), &c)), 1);
}

#[test]
fn baselines_write_the_same_outputs() {
    let c = failures::drift_case().unwrap();
    let exact = go(&EventDriven::default(), &c);
    for (name, integ) in [
        (
            "paper",
            Box::new(PaperNewmark { dt_s: 1e-3 }) as Box<dyn Integrator>,
        ),
        ("moreau", Box::new(Moreau::new(1e-3))),
        ("regularized", Box::new(Regularized::new(1e-5))),
    ] {
        let r = run(integ.as_ref(), &c, Some(0.01)).unwrap();
        assert_eq!(r.summary.method, name);
        assert_eq!(r.summary.blocks.len(), 5);
        assert_eq!(r.history.as_ref().unwrap().time_s.len(), 1001);
        let err = (r.summary.blocks[2].max_abs_displacement_m
            - exact.summary.blocks[2].max_abs_displacement_m)
            .abs();
        assert!(err < 0.05, "{name}: {err}");
    }
}

#[test]
fn the_work_precision_errors_are_zero_for_the_reference_and_positive_otherwise() {
    use pirqa::study::work_precision::{errors, reach_csv, Point};
    let c = failures::chatter_case();
    let exact = run(&EventDriven::default(), &c, Some(0.01)).unwrap();
    assert_eq!(errors(&exact, &exact), (0.0, 0.0));
    let moreau = run(&Moreau::new(1e-3), &c, Some(0.01)).unwrap();
    let (max, hist) = errors(&moreau, &exact);
    assert!(
        max > 0.0 && max < 1e-5 && hist >= max * 0.5 && hist < 1e-5,
        "{max} {hist}"
    );
    let point = |method: &str, parameter: &str, cpu_s: f64, err: f64| Point {
        scenario: "s".into(),
        method: method.into(),
        parameter: parameter.into(),
        cpu_s,
        err_max_m: err,
        err_history_m: err,
        failed: false,
    };
    let table = reach_csv(&[
        point("m", "dt=1e-2", 1.0, 1e-2),
        point("m", "dt=1e-3", 2.0, 5e-4),
        point("m", "dt=1e-4", 3.0, 2e-7),
    ]);
    assert_eq!(
        table,
        "scenario,method,level_m,parameter,cpu_s,err_history_m\n\
         s,m,1e-3,dt=1e-3,2e0,5e-4\n\
         s,m,1e-6,dt=1e-4,3e0,2e-7\n\
         s,m,1e-9,never,,2e-7\n"
    );
}

/// Moreau-Jean's Gauss-Seidel stopped at its sweep limit is counted and said, not passed over:
/// one sweep a step cannot settle the paper's wall with its bridging block.
#[test]
fn moreau_says_when_gauss_seidel_does_not_converge() {
    let c = failures::drift_case().unwrap();
    let enough = go(&Moreau::new(1e-3), &c);
    assert_eq!(enough.summary.stats.unconverged_steps, 0);
    assert!(enough.summary.warnings.is_empty());
    let one_sweep = Moreau {
        max_sweeps: 1,
        ..Moreau::new(1e-3)
    };
    let r = go(&one_sweep, &c);
    assert!(r.summary.stats.unconverged_steps > 0);
    let said = r
        .summary
        .warnings
        .iter()
        .map(|w| w.to_string())
        .collect::<Vec<_>>();
    assert!(
        said.iter()
            .any(|w| w.contains("did not converge within 1 sweeps")),
        "{said:?}"
    );
}
