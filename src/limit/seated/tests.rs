//! The seated interval against closed forms: a block alone stuck (the smaller of its friction
//! and b/h, a lift only where b/h is the smaller) and sliding (it tips whatever the ground does
//! once its friction passes b/h), a block dragged by one sliding on it (its balance of moments
//! by hand); and, with nothing sliding, against the limit at rest on columns, a running bond
//! of blocks on two others, the paper's wall and the Ollantaytambo wall.
use super::*;
use crate::limit::{at_rest, Limit};
use crate::model::Model;

fn model(rows: &str, friction: &str) -> Model {
    Model::from_ron_str(&format!(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: {friction}, rows: [{rows}])"
    ))
    .unwrap()
}

/// Every block moving with the ground, every joint stuck, touching faces pushing.
fn at_rest_state(m: &Model) -> State {
    let (wall, topo) = (m.wall(), m.topology());
    State {
        moving: wall
            .blocks
            .iter()
            .map(|b| (!b.fixed).then_some(Moving::Ground))
            .collect(),
        slip: vec![0; topo.horizontal.len()],
        pushes: topo.vertical.iter().map(|v| v.gap_m.is_zero()).collect(),
    }
}

fn seated(m: &Model, state: &State) -> Interval {
    interval(m.wall(), m.topology(), state, &|| false)
        .unwrap()
        .expect("not stopped")
}

fn sides(i: Interval) -> (Side, Side) {
    match i {
        Interval::Between {
            lo: Some(lo),
            hi: Some(hi),
        } => (lo, hi),
        other => panic!("not two sides: {other:?}"),
    }
}

/// A side's acceleration as a fraction of g, and how its blocks move (those that turn, where
/// some do).
fn lifts(side: &Side, g: &Q) -> (Q, Vec<String>) {
    let how = side
        .mechanism
        .iter()
        .filter(|m| m.omega_rad_s != 0.0 || !side.turns())
        .map(|m| format!("{} {}", m.block, m.how))
        .collect();
    (&side.accel / g, how)
}

const ALONE: &str = "(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\")])";

#[test]
fn a_block_alone_lifts_at_b_over_h_only_where_it_would_not_slide_first() {
    // b/h = 1/2. Friction 0.7: it lifts at g/2 either way, turning back over its trailing
    // corner. Friction 0.3: it slides first, at 0.3 g (the side is the sliding model's own
    // limit, where the state ends by a slip).
    let m = model(ALONE, "0.7");
    let g = m.wall().g_m_s2.clone();
    let (lo, hi) = sides(seated(&m, &at_rest_state(&m)));
    assert_eq!(
        lifts(&hi, &g),
        (
            Q::frac(1, 2),
            vec!["A turns counterclockwise about its bottom-left corner".to_string()]
        )
    );
    assert_eq!(
        lifts(&lo, &g),
        (
            Q::frac(-1, 2),
            vec!["A turns clockwise about its bottom-right corner".to_string()]
        )
    );
    let m = model(ALONE, "0.3");
    let (lo, hi) = sides(seated(&m, &at_rest_state(&m)));
    assert_eq!(
        lifts(&hi, &g),
        (Q::frac(3, 10), vec!["A slides towards -x".to_string()])
    );
    assert_eq!(lifts(&lo, &g).0, Q::frac(-3, 10));
}

#[test]
fn a_sliding_block_tips_whatever_the_ground_does_once_its_friction_passes_b_over_h() {
    // Sliding towards +x on the ground, friction mu N against it at its base, h/2 below its
    // centroid: the resultant sits mu h/2 ahead of the centroid, inside the base while
    // mu <= b/h (1/2). Nothing depends on a_g (no block moves with the ground).
    for (friction, tips) in [("0.3", false), ("0.5", false), ("0.55", true)] {
        let m = model(ALONE, friction);
        let mu = Q::parse_decimal(friction).unwrap();
        let mut state = at_rest_state(&m);
        state.slip[0] = 1;
        state.moving[0] = Some(Moving::At(-(&mu * &m.wall().g_m_s2)));
        match seated(&m, &state) {
            Interval::Empty { mechanism } => {
                assert!(tips, "friction {friction}");
                // It goes on over its leading edge: its top forward, clockwise.
                assert_eq!(mechanism.len(), 1);
                assert_eq!(mechanism[0].how, "turns clockwise");
            }
            Interval::Between { lo, hi } => {
                assert!(!tips, "friction {friction}");
                assert_eq!((lo, hi), (None, None));
            }
        }
    }
}

/// Where a state keeps no block seated whatever the ground does, the blocks that turn in every
/// certificate of that: a block alone sliding past its b/h turns in each; of two such blocks
/// standing apart, either turning alone is one, so neither turns in all; beside a block that
/// slides within its b/h, the one past it turns in all.
#[test]
fn the_blocks_turning_whatever_the_ground_does_are_those_of_every_certificate() {
    let turning = |rows: &str, friction: &str, sliding: &[usize]| {
        let m = model(rows, friction);
        let mut state = at_rest_state(&m);
        for &i in sliding {
            let mu = &m.topology().horizontal[i].friction;
            state.slip[i] = 1;
            state.moving[i] = Some(Moving::At(-(mu * &m.wall().g_m_s2)));
        }
        // Standing apart: nothing pushes.
        let programs = Programs::new(m.wall(), m.topology(), &state).unwrap();
        assert!(matches!(
            programs.interval(&|| false),
            Some(Interval::Empty { .. })
        ));
        programs.turning_whatever_the_ground(&|| false).unwrap()
    };
    let a = || Some(vec!["A".to_string()]);
    assert_eq!(turning(ALONE, "0.55", &[0]), a());
    let two = "(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\"), (width_m: 0.6, gap_m: 0.2, \
               name: \"B\")])";
    assert_eq!(turning(two, "0.55", &[0, 1]), Some(vec![]));
    let stout = "(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\"), (width_m: 1.2, gap_m: \
                 0.2, name: \"B\")])";
    assert_eq!(turning(stout, "0.55", &[0, 1]), a());
}

#[test]
fn a_block_dragged_by_one_sliding_on_it_lifts_where_its_moments_say() {
    // Lower block L (0.5 x 1.0 m) stuck to the ground, friction 0.8; upper block U (0.25 x
    // 0.25 m, centred on L) sliding towards +x on it with friction 0.3 (kinetic force
    // F = 0.3 N_U, -x on U, +x on L, at L's top). U: its resultant sits 0.3 * 0.25 / 2 =
    // 0.0375 m ahead of its centroid (inside its base). L, with T the ground's friction
    // (T + F = m_L a_g), moments about L's centroid (N_0 = total weight at x_0, N_U down at U's
    // resultant x_1):
    //   N_0 (x_0 - c) - N_U (x_1 - c) + (h/2) (T - F) = 0,  |x_0 - c| <= 0.25,
    // so a_g's limits are where x_0 reaches L's ends, unless friction (|T| <= 0.8 N_0) stops
    // the state first.
    let m = Model::from_file("walls/rocking/dragged-block.ron").unwrap();
    let (wall, topo) = (m.wall(), m.topology());
    let g = wall.g_m_s2.clone();
    let mass = |i: usize| topo.blocks[i].mass_kg.clone();
    let (m_l, m_u) = (mass(0), mass(1));
    let n_u = &m_u * &g;
    let n_0 = &(&m_l + &m_u) * &g;
    let f = &Q::frac(3, 10) * &n_u;
    let upper = topo.horizontal.iter().position(|h| h.upper.0 == 1).unwrap();
    let mut state = at_rest_state(&m);
    state.slip[upper] = 1;
    state.moving[1] = Some(Moving::At(-(&f / &m_u)));
    // x measured from L's centroid: x_1 = 0.0375 m; x_0 = [N_U x_1 - (h/2)(T - F)] / N_0.
    let (x1, half_h, half_b) = (Q::frac(3, 80), Q::frac(1, 2), Q::frac(1, 4));
    let accel_at = |x0: &Q| {
        // (h/2)(T - F) = N_U x_1 - N_0 x_0, T = m_L a - F.
        let t = &(&(&(&n_u * &x1) - &(&n_0 * x0)) / &half_h) + &f;
        &(&t + &f) / &m_l
    };
    let hi_lift = accel_at(&-half_b.clone());
    let lo_lift = accel_at(&half_b);
    let (hi_slip, lo_slip) = (
        &(&(&Q::frac(8, 10) * &n_0) + &f) / &m_l,
        &(&(&Q::frac(-8, 10) * &n_0) + &f) / &m_l,
    );
    assert!(
        hi_lift < hi_slip && lo_lift > lo_slip,
        "the case lifts both ways"
    );
    let (lo, hi) = sides(seated(&m, &state));
    // U, seated on L, turns with it while it slides.
    assert_eq!(
        lifts(&hi, &g),
        (
            &hi_lift / &g,
            vec![
                "L turns counterclockwise about its bottom-left corner".to_string(),
                "U turns counterclockwise".to_string()
            ]
        )
    );
    assert_eq!(lifts(&lo, &g).0, &lo_lift / &g);
}

#[test]
fn with_nothing_sliding_the_interval_is_the_limit_at_rest() {
    // The same contact forces and balances: each side is the limit at rest, exactly, and turns
    // a block where the limit's mechanism does. Columns off-centre with each joint's friction in
    // turn the weaker, a slender running bond (blocks on two others), the paper's variable wall
    // and the Ollantaytambo wall.
    let column = "(height_m: 0.4, blocks: [(width_m: 1.2, name: \"A\")]),
                  (height_m: 0.6, x_m: 0.2, blocks: [(width_m: 0.8, name: \"B\")]),
                  (height_m: 1.5, x_m: 0.35, blocks: [(width_m: 0.5, name: \"C\")])";
    let bond = "(height_m: 1.0, blocks: [(width_m: 0.25, name: \"A\"), (width_m: 0.5, name: \"B\"),
                 (width_m: 0.25, name: \"C\")]),
                (height_m: 1.0, blocks: [(width_m: 0.5, name: \"D\"), (width_m: 0.5, name: \"E\")])";
    let mut walls: Vec<Model> = ["0.15", "0.25", "0.6"]
        .iter()
        .map(|f| model(column, f))
        .collect();
    walls.push(model(bond, "0.6"));
    for file in [
        "walls/five-block-variable.ron",
        "walls/inca/ollantaytambo-monoliths.ron",
    ] {
        walls.push(Model::from_file(file).unwrap());
    }
    let mut turned = 0;
    for m in &walls {
        let limits = at_rest(m.wall(), m.topology()).unwrap();
        let (lo, hi) = sides(seated(m, &at_rest_state(m)));
        for (side, limit, sign) in [
            (hi, limits.towards_plus_x, 1),
            (lo, limits.towards_minus_x, -1),
        ] {
            let Limit::Holds {
                mechanism, exact_g, ..
            } = &limit
            else {
                panic!("unlimited");
            };
            let name = &m.wall().name;
            let g = &(&side.accel / &m.wall().g_m_s2) * &Q::frac(sign, 1);
            assert_eq!(format!("{g:?}"), *exact_g, "{name}");
            let turns = mechanism.iter().any(|b| b.omega_rad_s != 0.0);
            assert_eq!(side.turns(), turns, "{name}");
            turned += usize::from(turns);
        }
    }
    assert!(turned >= 4, "{turned} sides turn a block");
}

/// Whether the state is shown seated at `accel`, and the pivots its phase 1 took (the program
/// asks `stop` once before its run and once a pivot).
fn seated_at_counted(m: &Model, state: &State, accel: &Q) -> (bool, usize) {
    let asked = std::cell::Cell::new(0usize);
    let count = || {
        asked.set(asked.get() + 1);
        false
    };
    let seated = Programs::new(m.wall(), m.topology(), state)
        .unwrap()
        .seated_at(accel, &count);
    (seated, asked.get().saturating_sub(1))
}

#[test]
fn a_state_is_shown_seated_up_to_each_end_of_its_interval_and_not_past_it() {
    // The question the watch asks at a stick limit, against the interval's exact ends: seated
    // at each end and between them, not a millionth of a m/s2 past either. The walls of the
    // tests above, at rest and (the dragged block) with a block sliding.
    let mut cases: Vec<(Model, State)> = Vec::new();
    for (rows, friction) in [(ALONE, "0.7"), (ALONE, "0.3")] {
        let m = model(rows, friction);
        let state = at_rest_state(&m);
        cases.push((m, state));
    }
    for file in [
        "walls/five-block-variable.ron",
        "walls/inca/ollantaytambo-monoliths.ron",
        "walls/rocking/dragged-block.ron",
    ] {
        let m = Model::from_file(file).unwrap();
        let state = at_rest_state(&m);
        cases.push((m, state));
    }
    let dragged = Model::from_file("walls/rocking/dragged-block.ron").unwrap();
    let mut state = at_rest_state(&dragged);
    let upper = (dragged.topology().horizontal.iter())
        .position(|h| h.upper.0 == 1)
        .unwrap();
    state.slip[upper] = 1;
    let g = dragged.wall().g_m_s2.clone();
    let kinetic = &(&Q::frac(3, 10) * &g) * &Q::frac(-1, 1);
    state.moving[1] = Some(Moving::At(kinetic));
    cases.push((dragged, state));
    let step = Q::frac(1, 1_000_000);
    for (m, state) in &cases {
        let name = &m.wall().name;
        let (lo, hi) = sides(seated(m, state));
        let middle = &(&lo.accel + &hi.accel) * &Q::frac(1, 2);
        for (accel, seated) in [
            (&lo.accel, true),
            (&hi.accel, true),
            (&middle, true),
            (&(&hi.accel + &step), false),
            (&(&lo.accel - &step), false),
        ] {
            assert_eq!(
                seated_at_counted(m, state, accel).0,
                seated,
                "{name} at {accel:?}"
            );
        }
    }
}

#[test]
fn a_wall_at_rest_on_still_ground_needs_no_pivot_past_its_crash() {
    // Each block's weight goes down through its base, block by block, which the crash basis
    // takes in one pass: phase 1 has nothing left to do.
    for file in [
        "walls/five-block-variable.ron",
        "walls/five-block-uniform.ron",
        "walls/inca-coursed.ron",
    ] {
        let m = Model::from_file(file).unwrap();
        let (seated, pivots) = seated_at_counted(&m, &at_rest_state(&m), &Q::zero());
        assert!(seated, "{file}");
        assert_eq!(pivots, 0, "{file}");
    }
}
