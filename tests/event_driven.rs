//! The exact event-driven integrator against closed forms, hand derivations, conservation laws
//! and the paper's findings.

use pirqa::integrate::event::EventDriven;
use pirqa::integrate::{Integrator, Scenario, Settings};
use pirqa::motion::{Motion, Record, Sine};
use pirqa::response::{EventKind, EventRecord, Response};
use pirqa::samples::{self, SlidingBlockReference};
use pirqa::{Topology, Wall};

mod answers;

fn run(wall: &Wall, motion: &Motion, duration: f64, output_dt: Option<f64>) -> Response {
    let settings = Settings {
        duration_s: duration,
        output_dt_s: output_dt,
        log_events: true,
        log_decisions: false,
        after_collapse: Default::default(),
        progress: None,
    };
    run_with(wall, &Topology::new(wall).unwrap(), motion, &settings)
}

fn run_with(wall: &Wall, topology: &Topology, motion: &Motion, settings: &Settings) -> Response {
    let sc = Scenario {
        wall,
        topology,
        motion,
        settings,
    };
    EventDriven::default().run(&sc).unwrap()
}

fn sine(amp: f64, freq: f64, phase_deg: f64, duration: f64) -> Motion {
    Motion::Sine(Sine::new(amp, freq, phase_deg.to_radians(), duration).unwrap())
}

fn constant(a: f64, duration: f64) -> Motion {
    let dt = 0.01;
    let n = (duration / dt).round() as usize + 2;
    Motion::Record(Record::new("constant", dt, vec![a; n]).unwrap())
}

fn load(path: &str) -> Wall {
    Wall::load(std::path::Path::new(path)).unwrap()
}

/// The impacts a run logged, in order.
fn impacts(r: &Response) -> Vec<&EventRecord> {
    r.events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .collect()
}

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
        for j in &r.summary.joints {
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
        .joints
        .iter()
        .find(|j| j.upper == "B3" && j.lower == "B1")
        .unwrap();
    assert!(b3b1.max_abs_relative_displacement_m > 1e-3);
}

/// Locating an event takes a few evaluations of its functions (a closed-form guess polished to
/// the float, or a handful of Newton steps), not a bisection's fifty. The paper's variable wall
/// under 20 s of sine needs about 38 per event; 101 when Newton bisected back from the end of a
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

fn el_centro_first_s(seconds: usize, pga_m_s2: f64) -> Motion {
    let record = pirqa::motion::read_record(
        std::path::Path::new("../shared/records/elcentro1940_IELC180_peer_dt0p01_g.AT2"),
        None,
        &pirqa::motion::ReadOptions::default(),
    )
    .unwrap();
    let n = seconds * 100 + 1;
    let first = Record::new("El Centro", 0.01, record.accel_m_s2[..n].to_vec()).unwrap();
    Motion::Record(first.scaled(pga_m_s2 / record.pga_m_s2()))
}

/// The wall's topology with every joint's friction drawn uniformly from lowest / 10,000 to
/// (lowest + span) / 10,000 (seed 5).
fn random_friction(wall: &Wall, lowest: i128, span: i128) -> Topology {
    let mut rng = pirqa::rng::Rng::new(5);
    let nominal = Topology::new(wall).unwrap();
    let mu: Vec<pirqa::Q> = nominal
        .supports
        .iter()
        .map(|_| pirqa::Q::frac(lowest + (rng.uniform() * span as f64) as i128, 10_000))
        .collect();
    nominal.with_frictions(mu)
}

fn big_wall() -> Wall {
    let d = pirqa::wall::RunningBond::paper_wall(2100)
        .description()
        .unwrap();
    Wall::from_description(&d).unwrap()
}

/// The paper's uniform wall cut into 2,139 blocks under El Centro at 400 gal: every mode
/// decision spans the whole wall (a flow over 2,141 nodes: push-relabel, not Dinic), every upper
/// joint needs exactly its capacity, and the wall still moves as one body, exactly.
#[test]
fn a_uniform_wall_of_two_thousand_blocks_moves_as_one_body() {
    let wall = big_wall();
    let r = run(&wall, &el_centro_first_s(8, 4.0), 8.0, None);
    assert_eq!(wall.blocks.len(), 2139);
    assert!(r.summary.stats.events > 0);
    // The work counters see it: every decision takes in all 2,139 blocks, and every flow pass
    // runs over them and the two terminals.
    let stats = r.summary.stats;
    assert_eq!(stats.decision_blocks, 2139 * stats.mode_decisions);
    assert!(stats.flow_nodes > 0);
    assert_eq!(
        stats.flow_nodes % 2141,
        0,
        "{} flow nodes",
        stats.flow_nodes
    );
    let first = r.summary.blocks[0].max_abs_displacement_m;
    assert!(first > 1e-3, "it slides: {first} m");
    for j in r.summary.joints.iter().filter(|j| j.lower != "ground") {
        assert_eq!(
            j.max_abs_relative_displacement_m, 0.0,
            "{}/{}",
            j.upper, j.lower
        );
    }
    assert_eq!(r.summary.impacts, 0);
}

/// The same wall with every joint's friction drawn at random (0.27 to 0.33): hundreds of events
/// with flows over large parts of the wall, and the energy balance closes to round-off.
#[test]
fn a_wall_of_two_thousand_blocks_with_random_friction_balances_its_energy() {
    let wall = big_wall();
    let topo = random_friction(&wall, 2700, 600);
    let settings = Settings::summary_only(10.0);
    let r = run_with(&wall, &topo, &el_centro_first_s(10, 4.0), &settings);
    assert!(
        r.summary.stats.events > 500,
        "{} events",
        r.summary.stats.events
    );
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() < 1e-12 * e.input_j, "{e:?}");
}

#[test]
fn a_sliding_cluster_splits_when_an_impact_reverses_the_friction_on_it() {
    // X slides on the ground carrying Y (stuck to it) and C (sliding ahead on 0.2); C hits the
    // abutment A and bounces back, so C's friction on X turns from +0.2 m_C g to -0.2 m_C g.
    // Masses 1.3 : 0.7 : 0.4 (widths). Before the impact X and Y move at
    // (-0.72 + 0.08) / 2 g = -0.32 g and Y needs 0.32 g of the 0.36 g its joint holds; after it
    // they would move at (-0.72 - 0.08) / 2 g = -0.40 g: Y must slip on X at that instant.
    let wall = Wall::from_ron_str(
        r#"(
            version: 1,
            thickness_m: 1.0,
            density_kg_m3: 2000,
            friction: 0.3,
            joint_friction: { "C/X": 0.2, "Y/X": 0.36 },
            rectangles: [
                (x_m: 0.0, y_m: 0.0, width_m: 1.3, height_m: 0.5, name: "X"),
                (x_m: 1.6, y_m: 0.0, width_m: 0.4, height_m: 1.0, name: "A", fixed: true),
                (x_m: 0.0, y_m: 0.5, width_m: 0.7, height_m: 0.5, name: "Y"),
                (x_m: 1.0, y_m: 0.5, width_m: 0.4, height_m: 0.5, name: "C"),
            ],
        )"#,
    )
    .unwrap();
    let g = wall.g_m_s2.to_f64();
    let r = run(&wall, &constant(-0.5 * g, 0.6), 0.6, None);
    // C gains 0.3 g on the ground and closes its 0.2 m gap first (X needs 0.18 g for 0.3 m).
    let t_hit = (2.0 * 0.2 / (0.3 * g)).sqrt();
    let impact = r
        .events
        .iter()
        .find(|e| e.kind == EventKind::Impact)
        .expect("C hits the abutment");
    assert_eq!(impact.blocks, ["C", "A"]);
    assert!((impact.time_s - t_hit).abs() < 1e-12);
    let slip = r
        .events
        .iter()
        .find(|e| e.kind == EventKind::Slip && e.joint.as_deref() == Some("Y/X"))
        .expect("Y slips on X");
    assert_eq!(slip.time_s, impact.time_s, "at the impact, not later");
    // Then Y moves at -0.36 g (its joint at capacity) and X at (-0.72 - 0.08 + 0.36 * 0.7) / 1.3 g
    // until 0.6 s, with no other event (C drifts back on X, X is 6 cm short of the abutment).
    assert_eq!(r.events.len(), 5, "{:?}", r.events);
    let a_rel = (-0.36 + 0.548 / 1.3) * g;
    let expected = 0.5 * a_rel * (0.6 - impact.time_s).powi(2);
    let yx = r
        .summary
        .joints
        .iter()
        .find(|j| j.upper == "Y" && j.lower == "X")
        .unwrap();
    assert!(
        (yx.final_relative_displacement_m - expected).abs() < 1e-13,
        "{} against {expected}",
        yx.final_relative_displacement_m
    );
}

#[test]
fn simultaneous_impacts_on_two_courses_are_one_decision() {
    // Two columns of two equal blocks, 10 cm apart, their vertical joints in line. The left
    // column slides on mu 0.1 under 3 m/s2 (2.019 m/s2 relative); the right one is held (mu 0.5)
    // and neither column can shear (mu 0.5 and 0.6 on the block below). Both faces close at
    // one instant: each pair exchanges velocities (equal masses, e = 1), so the right column
    // leaves as a whole with the left one's velocity, and neither column ever slips inside.
    let wall = Wall::from_ron_str(
        r#"(
            version: 1,
            thickness_m: 1.0,
            density_kg_m3: 2000,
            friction: 0.5,
            joint_friction: { "L0/ground": 0.1, "R1/R0": 0.6 },
            rows: [
                (height_m: 0.5, blocks: [
                    (width_m: 0.5, name: "L0"), (width_m: 0.5, gap_m: 0.1, name: "R0"),
                ]),
                (height_m: 0.5, blocks: [
                    (width_m: 0.5, name: "L1"), (width_m: 0.5, gap_m: 0.1, name: "R1"),
                ]),
            ],
        )"#,
    )
    .unwrap();
    let settings = Settings {
        log_events: true,
        log_decisions: true,
        ..Settings::summary_only(0.4)
    };
    let topo = Topology::new(&wall).unwrap();
    let r = run_with(&wall, &topo, &constant(-3.0, 0.4), &settings);
    let a_rel = 3.0 - 0.1 * wall.g_m_s2.to_f64();
    let t_hit = (2.0 * 0.1 / a_rel).sqrt();
    let impacts = impacts(&r);
    assert_eq!(impacts.len(), 2, "{impacts:?}");
    let mut pairs: Vec<_> = impacts.iter().map(|e| e.blocks.join("|")).collect();
    pairs.sort();
    assert_eq!(pairs, ["L0|R0", "L1|R1"]);
    for e in &impacts {
        assert!(
            (e.time_s - t_hit).abs() < 1e-12,
            "{} against {t_hit}",
            e.time_s
        );
        let (before, after) = (e.before_m_s.unwrap(), e.after_m_s.unwrap());
        assert!((before[0] - a_rel * t_hit).abs() < 1e-12);
        assert_eq!(
            (before[1], after),
            (0.0, [0.0, before[0]]),
            "an exact exchange"
        );
    }
    let inside: Vec<_> = r
        .events
        .iter()
        .filter(|e| matches!(e.joint.as_deref(), Some("L1/L0" | "R1/R0")))
        .collect();
    assert!(inside.is_empty(), "no column slips inside: {inside:?}");
    let at_hit: Vec<_> = r
        .decisions
        .iter()
        .filter(|d| d.time_s == impacts[0].time_s)
        .collect();
    assert_eq!(
        at_hit.len(),
        1,
        "one decision after both impacts: {at_hit:?}"
    );
    assert_eq!(r.summary.energy.impact_loss_j, 0.0);
    // Absolute accelerations: the left column's 0.1 g throughout, the right one's 0.5 g once
    // it slides (no mode of zero duration between the two impacts counts).
    let g = wall.g_m_s2.to_f64();
    for (b, mu) in r.summary.blocks.iter().zip([0.1, 0.5, 0.1, 0.5]) {
        assert!(
            (b.max_abs_accel_m_s2 - mu * g).abs() < 1e-12,
            "{}: {} m/s2",
            b.name,
            b.max_abs_accel_m_s2
        );
    }
}

/// The paper's wall cut into 105 blocks with random friction (mu 0.2-0.4), and the first 10 s
/// of El Centro at 4 m/s2: flows, impacts and every kind of decision.
fn shaken_running_bond() -> (Wall, Topology, Motion) {
    let d = pirqa::wall::RunningBond::paper_wall(100)
        .description()
        .unwrap();
    let wall = Wall::from_description(&d).unwrap();
    let topo = random_friction(&wall, 2000, 2000);
    (wall, topo, el_centro_first_s(10, 4.0))
}

/// The work counters are the run's own: a run that failed part-way on the same thread, after
/// flows of its own, leaves nothing in them.
#[test]
fn work_counters_count_the_run_alone() {
    use pirqa::integrate::event::Params;
    let (wall, topo, motion) = shaken_running_bond();
    let settings = Settings::summary_only(10.0);
    let scenario = Scenario {
        wall: &wall,
        topology: &topo,
        motion: &motion,
        settings: &settings,
    };
    let counters = |params: Params| {
        EventDriven { params }.run(&scenario).map(|r| {
            let stats = r.summary.stats;
            assert!(r.summary.impacts > 0, "the wall meets impacts");
            (stats.decision_blocks, stats.flow_nodes)
        })
    };
    let fresh = std::thread::scope(|s| s.spawn(|| counters(Params::default())).join())
        .unwrap()
        .unwrap();
    assert!(fresh.1 > 0, "a 105-block wall runs flows");
    // No impact allowed: the run stops with an error at the first one, after the flows of the
    // decisions before it.
    let strict = Params {
        max_collisions_per_chain: 0,
        ..Params::default()
    };
    assert!(counters(strict).is_err());
    assert_eq!(counters(Params::default()).unwrap(), fresh);
}

/// The decision log adds up to the run's counters, decision by decision, and every group it
/// says stuck to the ground holds the ground acceleration of its decision: a 105-block wall with
/// random friction under El Centro, which meets every kind of event but a fall.
#[test]
fn decision_log_adds_up_to_the_run() {
    use pirqa::response::DecisionCause;
    let (wall, topo, motion) = shaken_running_bond();
    let run = |log_decisions: bool| {
        let settings = Settings {
            log_decisions,
            ..Settings::summary_only(10.0)
        };
        run_with(&wall, &topo, &motion, &settings)
    };
    let r = run(true);
    let (log, stats) = (&r.decisions, &r.summary.stats);
    assert_eq!(log.len() as u64, stats.mode_decisions);
    let blocks: usize = log.iter().map(|d| d.blocks).sum();
    assert_eq!(blocks as u64, stats.decision_blocks);
    assert_eq!(
        log.iter().map(|d| d.flow_nodes).sum::<u64>(),
        stats.flow_nodes
    );
    assert!(stats.flow_nodes > 0);
    assert_eq!((log[0].cause, log[0].time_s), (DecisionCause::Start, 0.0));
    assert!(log.windows(2).all(|w| w[0].time_s <= w[1].time_s));
    for cause in [
        DecisionCause::StickLimit,
        DecisionCause::Stop,
        DecisionCause::Meet,
        DecisionCause::Impact,
    ] {
        assert!(log.iter().any(|d| d.cause == cause), "{cause:?} is logged");
    }
    for d in log {
        assert!(d.blocks >= 1 && d.clusters >= 1 && d.cpu_s >= 0.0);
        assert_eq!(d.load_factor, 1.0, "no vertical component");
        if let Some(g) = &d.stuck_formed {
            let (lo, hi) = (g.a_g_lo_m_s2, g.a_g_hi_m_s2);
            assert!(
                lo.is_none_or(|lo| lo <= d.a_g_m_s2) && hi.is_none_or(|hi| d.a_g_m_s2 <= hi),
                "a group formed stuck at {} s holds a_g = {} m/s2: {g:?}",
                d.time_s,
                d.a_g_m_s2
            );
        }
    }
    // Asked for or not, the run is the same; the log is kept only when asked for.
    let quiet = run(false);
    assert!(quiet.decisions.is_empty());
    assert_eq!(quiet.summary.stats, r.summary.stats);
    assert_eq!(quiet.final_displacement_m, r.final_displacement_m);
}

/// Limits kept as bounds (`Params::kept_limits_from`) change the work, never the answer: with
/// every stuck group of two blocks or more keeping them, the 105-block wall under El Centro
/// (with and without a vertical component), the five-block variable wall under the paper's
/// sine, and the same wall toppled by a slow sine and run on after the fall give the same event
/// log, history and maxima as with every limit worked out at once; the bounds save flow work
/// on the large wall, and where a_g reaches one it is worked out there (a bookkeeping event
/// that changes nothing).
#[test]
fn kept_limits_change_the_work_not_the_answer() {
    use pirqa::integrate::event::Params;
    use pirqa::integrate::AfterCollapse::{Continue, Stop};
    let (wall, topo, motion) = shaken_running_bond();
    let Motion::Record(horizontal) = &motion else {
        unreachable!("El Centro is a record")
    };
    let vertical = samples::broadband_record(10.0, 0.01, 1.5);
    let shaken_both_ways = Motion::Record(horizontal.with_vertical(&vertical, 9.81).unwrap());
    let five = load("walls/five-block-variable.ron");
    let five_topo = Topology::new(&five).unwrap();
    let paper_sine = sine(4.0, 1.0, 0.0, 20.0);
    let toppling = sine(5.0, 0.2, 0.0, 10.0);
    let (mut bound_events, mut logged_bounds) = (0, 0);
    for (wall, topo, motion, duration_s, after_collapse) in [
        (&wall, &topo, &motion, 10.0, Stop),
        (&wall, &topo, &shaken_both_ways, 10.0, Stop),
        (&five, &five_topo, &paper_sine, 20.0, Stop),
        (&five, &five_topo, &toppling, 10.0, Continue),
    ] {
        let settings = Settings {
            duration_s,
            output_dt_s: Some(0.01),
            log_events: true,
            log_decisions: true,
            after_collapse,
            progress: None,
        };
        let scenario = Scenario {
            wall,
            topology: topo,
            motion,
            settings: &settings,
        };
        let run = |kept_limits_from: usize| {
            let params = Params {
                kept_limits_from,
                ..Params::default()
            };
            EventDriven { params }.run(&scenario).unwrap()
        };
        let (exact, kept) = (run(usize::MAX), run(2));
        assert_eq!(kept.events_jsonl(), exact.events_jsonl());
        assert_eq!(kept.history_csv(), exact.history_csv());
        let (e, k) = (exact.summary.stats, kept.summary.stats);
        let mut same = kept.summary.clone();
        same.stats = e;
        assert_eq!(same, exact.summary);
        assert_eq!(k.mode_decisions, e.mode_decisions);
        assert!(k.events >= e.events);
        if after_collapse == Continue {
            assert!(kept.summary.blocks.iter().any(|b| b.fell), "a block falls");
        }
        bound_events += k.events - e.events;
        // The decision log says which limits are bounds: none where every limit is exact.
        let bounds = |r: &Response| {
            r.decisions
                .iter()
                .filter_map(|d| d.stuck_formed.as_ref())
                .filter(|g| g.lo_is_bound || g.hi_is_bound)
                .count()
        };
        assert_eq!(bounds(&exact), 0);
        logged_bounds += bounds(&kept);
        if wall.blocks.len() > 100 {
            assert!(
                k.flow_nodes < e.flow_nodes,
                "bounds save flows: {} against {}",
                k.flow_nodes,
                e.flow_nodes
            );
        }
    }
    assert!(bound_events > 0, "a_g reaches a bound");
    assert!(logged_bounds > 0, "the log shows the bounds kept");
}

/// A wall of 1,000 blocks (10 courses of 100, 24 m long, 1.2 m high) with random friction
/// (`random_friction`, 0.2 to 0.4): under El Centro its courses meet thousands of slow
/// collisions on the stuck group.
fn thousand_block_wall() -> (Wall, Topology) {
    let spec = pirqa::wall::RunningBond {
        courses: 10,
        blocks_per_course: 100,
        width_m: 24.0,
        height_m: 1.2,
        ..pirqa::wall::RunningBond::paper_wall(5)
    };
    let wall = Wall::from_description(&spec.description().unwrap()).unwrap();
    let topo = random_friction(&wall, 2000, 2000);
    (wall, topo)
}

/// A run of `duration_s` that logs its events and nothing else.
fn events_logged(duration_s: f64) -> Settings {
    Settings {
        duration_s,
        output_dt_s: None,
        log_events: true,
        log_decisions: false,
        after_collapse: Default::default(),
        progress: None,
    }
}

/// A decision beside a large stuck group (a block a collision stopped on it, or that came to
/// rest against it) decides the few blocks with the group held at a_g and the group from its
/// stick interval (`Params::beside_stuck_from`): it changes the work, never the answer. On a
/// wall of 1,000 blocks and on the 105-block wall under El Centro, with every stuck group of
/// two blocks or more treated so, and with the default, against none: the same answer
/// (`answers::same_answer`), the same number of decisions, and on the large wall fewer flow
/// nodes (416,367 -> 390,917).
#[test]
fn a_decision_beside_a_stuck_group_changes_the_work_not_the_answer() {
    use pirqa::integrate::event::Params;
    let (long, long_topo) = thousand_block_wall();
    let (short, short_topo, motion) = shaken_running_bond();
    for (wall, topo, duration_s) in [(&long, &long_topo, 4.0), (&short, &short_topo, 10.0)] {
        let settings = events_logged(duration_s);
        let scenario = Scenario {
            wall,
            topology: topo,
            motion: &motion,
            settings: &settings,
        };
        let run = |beside_stuck_from: usize| {
            let params = Params {
                beside_stuck_from,
                ..Params::default()
            };
            EventDriven { params }.run(&scenario).unwrap()
        };
        let whole = run(usize::MAX);
        let mut nodes = Vec::new();
        for beside in [run(2), run(Params::default().beside_stuck_from)] {
            answers::same_answer(&whole, &beside).unwrap();
            assert_eq!(
                beside.summary.stats.mode_decisions,
                whole.summary.stats.mode_decisions
            );
            nodes.push(beside.summary.stats.flow_nodes);
        }
        // Taken (the work differs) with every group, and a saving where groups are large.
        let w = whole.summary.stats.flow_nodes;
        assert_ne!(nodes[0], w);
        if wall.blocks.len() > 1000 {
            assert!(nodes[1] < w, "{} flow nodes against {w}", nodes[1]);
        }
    }
}

/// A long, low wall (4 courses of 60 blocks, 14.4 m, random friction) under El Centro: its
/// courses break into sliding bodies along which single blocks slide, collide and stick. A
/// decision beside a body none of whose joints it turned finds again the events of the pairs it
/// changed (its new clusters with their neighbours), not those of every sliding cluster along
/// the body: about 6 pairs per decision here, where rescheduling the bodies found 17.6.
#[test]
fn a_decision_beside_a_sliding_body_reschedules_only_the_pairs_it_changed() {
    let spec = pirqa::wall::RunningBond {
        courses: 4,
        blocks_per_course: 60,
        width_m: 14.4,
        ..pirqa::wall::RunningBond::paper_wall(5)
    };
    let wall = Wall::from_description(&spec.description().unwrap()).unwrap();
    let topo = random_friction(&wall, 2000, 2000);
    let settings = Settings::summary_only(10.0);
    let r = run_with(&wall, &topo, &el_centro_first_s(10, 4.0), &settings);
    assert!(r.summary.impacts > 1000, "{} impacts", r.summary.impacts);
    let stats = r.summary.stats;
    let per_decision = stats.pair_schedules as f64 / stats.mode_decisions as f64;
    assert!(per_decision < 10.0, "{per_decision} pairs per decision");
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() < 1e-12 * e.input_j, "{e:?}");
}

/// A run's answer up to an instant does not depend on how long it is asked to run: its
/// round-off scales come from the whole motion. A wall of 1,000 blocks (10 courses of 100, 24
/// m long, random friction) under El Centro meets thousands of collisions slow enough that
/// scales worked out over the run alone (2.3 s or 5 s of the record) made the two runs part
/// before 2.3 s; now the shorter one logs exactly the first events of the longer one.
#[test]
fn a_shorter_run_logs_the_first_events_of_a_longer_one() {
    let (wall, topo) = thousand_block_wall();
    let motion = el_centro_first_s(10, 4.0);
    let events = |duration_s: f64| {
        let settings = events_logged(duration_s);
        run_with(&wall, &topo, &motion, &settings).events_jsonl()
    };
    let (short, long) = (events(2.3), events(5.0));
    assert!(
        short.lines().count() > 5000,
        "{} events",
        short.lines().count()
    );
    assert!(long.len() > short.len());
    assert!(long.starts_with(&short));
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
            progress: Some(Progress(Arc::new(move |t| log.lock().unwrap().push(t)))),
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
