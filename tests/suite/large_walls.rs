//! Large walls: thousands of blocks moving as one body or breaking up, energy balances, the work
//! counters and decision log, and the settings that change the work of the exact integrator but
//! never its answer.

use crate::answers;
use crate::engine;

use engine::{constant, el_centro_first_s, exact_on, impacts, load, run, sine};
use pirqa::integrate::event::{EventDriven, Params};
use pirqa::integrate::{Integrator, Scenario, Settings};
use pirqa::motion::Motion;
use pirqa::response::{EventKind, Response};
use pirqa::samples;
use pirqa::{SimulationError, Topology, Wall};

/// The wall's topology with every joint's friction drawn uniformly from lowest / 10,000 to
/// (lowest + span) / 10,000 (seed 5).
fn random_friction(wall: &Wall, lowest: i128, span: i128) -> Topology {
    let mut rng = pirqa::rng::Rng::new(5);
    let nominal = Topology::new(wall).unwrap();
    let mu: Vec<pirqa::Q> = nominal
        .horizontal
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
    for j in r
        .summary
        .horizontal_joints
        .iter()
        .filter(|j| j.lower != "ground")
    {
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
    let r = exact_on(&wall, &topo, &el_centro_first_s(10, 4.0), &settings);
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
        .horizontal_joints
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
    let r = exact_on(&wall, &topo, &constant(-3.0, 0.4), &settings);
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

/// The shaken running bond, summary only, with the engine's `params`.
fn shaken_with(params: Params) -> Result<Response, SimulationError> {
    let (wall, topo, motion) = shaken_running_bond();
    let settings = Settings::summary_only(10.0);
    EventDriven { params }.run(&Scenario {
        wall: &wall,
        topology: &topo,
        motion: &motion,
        settings: &settings,
    })
}

/// The work counters are the run's own: a run that failed part-way on the same thread, after
/// flows of its own, leaves nothing in them.
#[test]
fn work_counters_count_the_run_alone() {
    let counters = |params: Params| {
        shaken_with(params).map(|r| {
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
        max_collisions_per_chain: Some(0),
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
        exact_on(&wall, &topo, &motion, &settings)
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
            history_file: None,
            log_events: true,
            events_file: None,
            decisions_file: None,
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
        history_file: None,
        log_events: true,
        events_file: None,
        decisions_file: None,
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
    let r = exact_on(&wall, &topo, &el_centro_first_s(10, 4.0), &settings);
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
        exact_on(&wall, &topo, &motion, &settings).events_jsonl()
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

/// The backstops on events at one instant and on collisions in a chain say where they stopped
/// with the blocks named, a few of them and how many more: never thousands of names, never a
/// debug structure.
#[test]
fn backstops_name_a_few_blocks_and_the_event_in_words() {
    let fail = |params: Params| match shaken_with(params) {
        Err(e) => e,
        other => panic!("expected a stop, got {:?}", other.map(|r| r.summary.stats)),
    };
    let chain = fail(Params {
        max_collisions_per_chain: Some(0),
        ..Params::default()
    });
    assert!(
        matches!(chain, SimulationError::ImpactChain { count: 0, .. }),
        "{chain}"
    );
    let events = fail(Params {
        max_events_per_instant: Some(1),
        ..Params::default()
    });
    let SimulationError::TooManyEvents {
        count: 2, detail, ..
    } = &events
    else {
        panic!("{events}");
    };
    for message in [chain.to_string(), events.to_string()] {
        assert!(message.len() < 400, "{message}");
        assert!(
            !message.contains('{') && !message.contains("ClusterId"),
            "{message}"
        );
    }
    assert!(detail.contains('B'), "the event names its blocks: {detail}");
}
