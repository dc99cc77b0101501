//! The limits at rest against closed forms: a block standing alone (Shenton 1996: the smaller of
//! its friction and b/h), a column (the column model's joint limits, computed from centroids,
//! not from a program), two blocks side by side pushing one another, the paper's uniform wall,
//! and a block the abutments hold.
use super::*;
use crate::model::Model;

fn model(rows: &str, friction: &str) -> Model {
    Model::from_ron_str(&format!(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: {friction}, rows: [{rows}])"
    ))
    .unwrap()
}

fn limits(m: &Model) -> Limits {
    at_rest(m.wall(), m.topology()).unwrap()
}

/// The limit as an exact fraction of g, and its mechanism.
fn holds(l: &Limit) -> (Q, &[Moves]) {
    let Limit::Holds {
        exact_g,
        accel_g,
        accel_m_s2,
        mechanism,
        ..
    } = l
    else {
        panic!("unlimited: {l:?}");
    };
    let g = parse(exact_g);
    assert_eq!(*accel_g, g.to_f64());
    assert_eq!(*accel_m_s2, (&g * &Q::frac(981, 100)).to_f64());
    (g, mechanism)
}

fn parse(s: &str) -> Q {
    match s.split_once('/') {
        Some((n, d)) => Q::frac(
            n.parse().unwrap_or_else(|e| panic!("{s}: {e}")),
            d.parse().unwrap(),
        ),
        None => Q::frac(s.parse().unwrap_or_else(|e| panic!("{s}: {e}")), 1),
    }
}

#[test]
fn a_block_alone_slides_at_its_friction_or_tips_at_b_over_h() {
    // 0.6 by 1.2 m: b/h = 1/2. Friction 0.3 slides first, 0.7 tips first, 0.5 is the tie.
    let rows = "(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\")])";
    let slides = limits(&model(rows, "0.3"));
    for (l, towards) in [
        (&slides.towards_plus_x, "-x"),
        (&slides.towards_minus_x, "+x"),
    ] {
        let (g, mech) = holds(l);
        assert_eq!(g, Q::frac(3, 10));
        assert_eq!(mech.len(), 1);
        assert_eq!(mech[0].how, format!("slides towards {towards}"));
        assert_eq!(mech[0].omega_rad_s, 0.0);
    }
    let tips = limits(&model(rows, "0.7"));
    let (g, mech) = holds(&tips.towards_plus_x);
    assert_eq!(g, Q::frac(1, 2));
    // Left behind by a ground that accelerates towards +x, it turns back over its trailing
    // corner.
    assert_eq!(
        mech[0].how,
        "turns counterclockwise about its bottom-left corner"
    );
    let (g, mech) = holds(&tips.towards_minus_x);
    assert_eq!(g, Q::frac(1, 2));
    assert_eq!(mech[0].how, "turns clockwise about its bottom-right corner");
    // A column of two such blocks turns as one about the lower one's corner.
    let two = limits(&model(
        &format!("{rows}, {}", rows.replace('A', "B")),
        "0.7",
    ));
    let (g, mech) = holds(&two.towards_plus_x);
    assert_eq!(g, Q::frac(1, 4));
    assert_eq!(
        mech[1].how,
        "turns counterclockwise about A's bottom-left corner"
    );
    let tie = limits(&model(rows, "0.5"));
    assert_eq!(holds(&tie.towards_plus_x).0, Q::frac(1, 2));
}

#[test]
fn a_column_gives_way_where_the_column_model_says_and_no_earlier() {
    // Three blocks of different sizes, off-centre from one another (the column model's own
    // test column), each joint's friction in turn low enough to slip first or not.
    let rows = "(height_m: 0.4, blocks: [(width_m: 1.2, name: \"A\")]),
                (height_m: 0.6, x_m: 0.2, blocks: [(width_m: 0.8, name: \"B\")]),
                (height_m: 1.5, x_m: 0.35, blocks: [(width_m: 0.5, name: \"C\")])";
    for friction in ["0.15", "0.25", "0.6"] {
        let m = model(rows, friction);
        let wall = m.wall();
        // Each joint's limits from the centroid of what is above it: friction, and its
        // distances to the joint's ends over its height.
        let mut plus = Q::frac(1000, 1);
        let mut minus = Q::frac(1000, 1);
        for j in 0..3 {
            let above = &wall.blocks[j..];
            let mass: Q = above.iter().map(Block::area).sum();
            let x_g = above.iter().map(|b| b.area() * b.centroid_x()).sum::<Q>() / &mass;
            let y_g = above
                .iter()
                .map(|b| b.area() * (&b.y + &b.height * Q::frac(1, 2)))
                .sum::<Q>()
                / &mass;
            let b = &wall.blocks[j];
            let (l, r) = match j {
                0 => (b.x.clone(), b.right()),
                _ => {
                    let below = &wall.blocks[j - 1];
                    (
                        b.x.clone().max(below.x.clone()),
                        b.right().min(below.right()),
                    )
                }
            };
            let h = &y_g - &b.y;
            let mu = Q::parse_decimal(friction).unwrap();
            plus = plus.min(mu.clone().min((&x_g - &l) / &h));
            minus = minus.min(mu.min((&r - &x_g) / &h));
        }
        let l = limits(&m);
        assert_eq!(holds(&l.towards_plus_x).0, plus, "friction {friction}");
        assert_eq!(holds(&l.towards_minus_x).0, minus, "friction {friction}");
        // The column model (floating point) finds the same smallest limit.
        let col = crate::integrate::rocking::columns(wall, m.topology()).unwrap();
        let smallest = col[0]
            .limits
            .iter()
            .map(|j| j.slip_g.min(j.tips_left_g))
            .fold(f64::INFINITY, f64::min);
        assert!(
            (smallest - plus.to_f64()).abs() <= 1e-15,
            "{smallest} {plus}"
        );
    }
}

#[test]
fn blocks_side_by_side_push_one_another_but_cannot_pull() {
    // Two squat blocks touching on the ground, 2.0 and 1.0 m wide (masses 2:1), frictions
    // 0.2 (left) and 0.5 (right). Towards +x the right block can be helped by the left one
    // pushing it, not the left by the right: min(mu_l, (mu_l m_l + mu_r m_r) / (m_l + m_r)).
    let m = Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.2,
          joint_friction: {\"R/ground\": 0.5},
          rows: [(height_m: 0.25, blocks: [(width_m: 2.0, name: \"L\"), (width_m: 1.0, name: \"R\")])])",
    )
    .unwrap();
    let l = limits(&m);
    let (plus, mech) = holds(&l.towards_plus_x);
    assert_eq!(plus, Q::frac(2, 10));
    assert_eq!(mech.len(), 1, "{mech:?}");
    assert_eq!(mech[0].block, "L");
    // Towards -x the left block is pushed by the right one: (0.2 * 2 + 0.5 * 1) / 3 = 0.3.
    let (minus, mech) = holds(&l.towards_minus_x);
    assert_eq!(minus, Q::frac(3, 10));
    assert_eq!(mech.len(), 2, "{mech:?}");
    assert!(mech.iter().all(|b| b.how == "slides towards +x"));
}

#[test]
fn the_papers_uniform_wall_slides_at_its_friction() {
    let m = Model::from_file("walls/five-block-uniform.ron").unwrap();
    let l = limits(&m);
    assert_eq!(holds(&l.towards_plus_x).0, Q::frac(3, 10));
    assert_eq!(holds(&l.towards_minus_x).0, Q::frac(3, 10));
}

/// Where one mechanism alone holds at the limit it is said to be unique; where several do, it
/// is one of several: a block alone slides (friction 0.3) or tips (0.7, about its corner, at
/// b/h = 0.5) by one mechanism, at the tie (0.5) by either; the paper's uniform wall, one
/// friction everywhere, slides at it with both bottom blocks or with one of them and what it
/// carries (the next test has both), and its basis shows another at once, so it is one of
/// several even where the full decision is not asked for; the paper's variable wall's
/// degenerate side shows none there, and is unique decided in full, undecided otherwise.
#[test]
fn a_mechanism_is_unique_where_no_other_holds_at_its_limit() {
    let uniqueness = |l: &Limit| match l {
        Limit::Holds {
            mechanism_uniqueness,
            ..
        } => *mechanism_uniqueness,
        Limit::Unlimited => panic!("unlimited"),
    };
    let rows = "(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\")])";
    for (friction, expected) in [
        ("0.3", Uniqueness::Unique),
        ("0.7", Uniqueness::Unique),
        ("0.5", Uniqueness::OneOfSeveral),
    ] {
        let l = limits(&model(rows, friction));
        for side in [&l.towards_plus_x, &l.towards_minus_x] {
            assert_eq!(uniqueness(side), expected, "friction {friction}: {side:?}");
        }
    }
    let uniform = Model::from_file("walls/five-block-uniform.ron").unwrap();
    let l = limits(&uniform);
    for side in [&l.towards_plus_x, &l.towards_minus_x] {
        assert_eq!(uniqueness(side), Uniqueness::OneOfSeveral, "{side:?}");
    }
    let (p, groups) = side_program(&uniform, -1);
    let Some(Outcome::Optimal { x, y, basis, .. }) = certify::solve(&p, &groups, &|| false) else {
        panic!("the uniform wall's limit");
    };
    let kept = |j: usize| x[j].is_positive() || p.c[j] == p.dot(j, &y);
    assert_eq!(
        certify::Degenerate::of(&p, &basis, &x, kept).and_then(|mut q| q.moves_off()),
        Some(true)
    );
    let shown = uniqueness_of(&p, &x, &y, &basis, false);
    assert_eq!(shown, Uniqueness::OneOfSeveral);
    let variable = Model::from_file("walls/five-block-variable.ron").unwrap();
    let mut degenerate_sides = 0;
    for s in [1, -1] {
        let (p, groups) = side_program(&variable, s);
        let Some(Outcome::Optimal { x, y, basis, .. }) = certify::solve(&p, &groups, &|| false)
        else {
            panic!("the variable wall's limit");
        };
        if !degenerate(&p, &x) {
            continue;
        }
        degenerate_sides += 1;
        let kept = |j: usize| x[j].is_positive() || p.c[j] == p.dot(j, &y);
        assert_eq!(
            certify::Degenerate::of(&p, &basis, &x, kept).and_then(|mut q| q.moves_off()),
            Some(false)
        );
        let undecided = uniqueness_of(&p, &x, &y, &basis, false);
        assert_eq!(undecided, Uniqueness::Undecided);
        assert_eq!(uniqueness_of(&p, &x, &y, &basis, true), Uniqueness::Unique);
    }
    assert_eq!(degenerate_sides, 1);
}

/// Which blocks move and turn in every mechanism is its own question, asked whether or not
/// uniqueness was decided: on the paper's variable wall's degenerate side, left undecided (no
/// degenerate row decided), the programs give the mechanism's own blocks, as the unique
/// mechanism it is decided in full; on the uniform wall they meet another mechanism, so an
/// undecided answer there becomes one of several, with the blocks its limit reports.
#[test]
fn in_every_mechanism_is_decided_where_uniqueness_is_not() {
    let optimum = |m: &Model, s: i128| {
        let (p, groups) = side_program(m, s);
        let Some(Outcome::Optimal { value, x, y, basis }) = certify::solve(&p, &groups, &|| false)
        else {
            panic!("a limit");
        };
        (p, groups, value, x, y, basis)
    };
    let variable = Model::from_file("walls/five-block-variable.ron").unwrap();
    let mut undecided = 0;
    for s in [1, -1] {
        let (p, groups, value, x, y, basis) = optimum(&variable, s);
        let found = uniqueness_of(&p, &x, &y, &basis, false);
        if found != Uniqueness::Undecided {
            continue;
        }
        undecided += 1;
        let asked = every_at_optimum(found, &p, &groups, (&value, &y, &basis), 5, &|| false);
        let (still, every) = asked.unwrap().expect("not stopped");
        assert_eq!(still, Uniqueness::Undecided);
        let (every, own) = (every.expect("five blocks"), every::Every::of(&y));
        assert!(!every.another);
        assert!(!own.moving.is_empty());
        assert_eq!((every.moving, every.turning), (own.moving, own.turning));
    }
    assert_eq!(undecided, 1);
    let uniform = Model::from_file("walls/five-block-uniform.ron").unwrap();
    let l = limits(&uniform);
    for (s, side) in [(1, &l.towards_plus_x), (-1, &l.towards_minus_x)] {
        let Limit::Holds {
            moving_in_every_mechanism: Some(moving),
            turning_in_every_mechanism: Some(turning),
            ..
        } = side
        else {
            panic!("the uniform wall's limit: {side:?}");
        };
        let (p, groups, value, _, y, basis) = optimum(&uniform, s);
        let asked = every_at_optimum(
            Uniqueness::Undecided,
            &p,
            &groups,
            (&value, &y, &basis),
            5,
            &|| false,
        );
        let (found, every) = asked.unwrap().expect("not stopped");
        assert_eq!(found, Uniqueness::OneOfSeveral);
        let every = every.expect("five blocks");
        let names = |places: &[usize]| -> Vec<String> {
            let wall = uniform.wall();
            places
                .iter()
                .map(|&k| wall.blocks[k].name.clone())
                .collect()
        };
        assert_eq!(
            (&names(&every.moving), &names(&every.turning)),
            (moving, turning)
        );
        assert!(!moving.is_empty());
    }
}

/// Multipliers that differ by a d with A^T d = 0 (dependent rows) are one mechanism: the
/// program max x1 over x1 + x2 = 1 and twice that row has every (y1, y2) with y1 + 2 y2 = -1
/// optimal, and its basis keeps an artificial variable on the dependent row, which no longer
/// leaves the answer undecided. With a third column x3 along x1 + x2 = 1 alone (cost -1 too),
/// x1 and x3 both optimal, another multiplier holds as well: one of several.
#[test]
fn multipliers_that_differ_where_the_rows_depend_on_one_another_are_one_mechanism() {
    let q = |v: i128| Q::frac(v, 1);
    let column = |a: &[i128]| a.iter().map(|&v| q(v)).enumerate().collect::<Vec<_>>();
    let solved = |columns: Vec<Vec<(usize, Q)>>, c: Vec<Q>| {
        let p = Program::new(columns, vec![q(1), q(2), q(0)], c);
        let Some(Outcome::Optimal { x, y, basis, .. }) = certify::solve(&p, &[], &|| false) else {
            panic!("optimal");
        };
        assert!(
            basis.iter().any(|&j| j >= p.c.len()),
            "an artificial left: {basis:?}"
        );
        uniqueness_of(&p, &x, &y, &basis, true)
    };
    let (x1, x2) = (column(&[1, 2, 0]), column(&[1, 2, 0]));
    let one = solved(vec![x1.clone(), x2.clone()], vec![q(-1), q(0)]);
    assert_eq!(one, Uniqueness::Unique);
    let x3 = column(&[1, 2, 1]);
    let several = solved(vec![x1, x2, x3], vec![q(-1), q(0), q(-1)]);
    assert_eq!(several, Uniqueness::OneOfSeveral);
}

/// [`uniqueness`] never stopped.
fn uniqueness_of(p: &Program, x: &[Q], y: &[Q], basis: &[usize], decide: bool) -> Uniqueness {
    let most_rows = if decide { DECIDED_ROWS } else { 0 };
    uniqueness(p, x, y, basis, most_rows, &|| false).expect("not stopped")
}

#[test]
fn a_trilith_lifts_where_its_columns_would_alone() {
    // A lintel on two equal columns moves as a parallelogram whose columns turn on their
    // corners, at the acceleration a column alone tips at, g b/h (Makris and Vassiliou 2013).
    let m = Model::from_file("walls/rocking/trilith.ron").unwrap();
    let column = m.wall().blocks.iter().find(|b| b.name == "Left").unwrap();
    let l = limits(&m);
    let (g, mech) = holds(&l.towards_plus_x);
    assert_eq!(g, &column.width / &column.height);
    let how: Vec<&str> = mech.iter().map(|b| b.how.as_str()).collect();
    assert_eq!(
        how,
        [
            "turns counterclockwise about its bottom-left corner",
            "turns counterclockwise about its bottom-left corner",
            "moves towards -x without turning, carried"
        ]
    );
}

#[test]
fn a_block_between_abutments_is_held_whatever_the_ground_does() {
    let rows = "(height_m: 0.5, blocks: [(width_m: 0.4, fixed: true, name: \"P\"),
                 (width_m: 1.0, name: \"A\"), (width_m: 0.4, fixed: true, name: \"Q\")])";
    let l = limits(&model(rows, "0.3"));
    assert_eq!(l.towards_plus_x, Limit::Unlimited);
    assert_eq!(l.towards_minus_x, Limit::Unlimited);
}

/// A on the ground, B on A reaching past its right end, and C (x, width, height) on B's right
/// part.
fn stack(c: (f64, f64, f64)) -> Model {
    let (x, width, height) = c;
    Model::from_ron_str(&format!(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6, rectangles: [
          (x_m: 0.0, y_m: 0.0, width_m: 1.0, height_m: 0.5, name: \"A\"),
          (x_m: 0.2, y_m: 0.5, width_m: 1.4, height_m: 0.5, name: \"B\"),
          (x_m: {x}, y_m: 1.0, width_m: {width}, height_m: {height}, name: \"C\")])"
    ))
    .unwrap()
}

/// Each block stands over its own support, so the graph takes the wall; but B and C together
/// lean past A's right end (their centroid at 1.154 m over A's 0 to 1 m), and the program,
/// with no seated balance even at rest, says so with the fall: B turning over A's corner (how
/// C goes with it is one of many motions that show it, not asked for).
#[test]
fn a_stack_leaning_past_its_base_cannot_stand() {
    let m = stack((1.3, 0.3, 2.0));
    let err = at_rest(m.wall(), m.topology()).unwrap_err().to_string();
    assert!(
        err.contains("cannot stand even on still ground")
            && err.contains("B turns clockwise about A's top-right corner"),
        "{err}"
    );
    // A squat C leans B and C past A's corner too (centroid at 1.063 m) but does not tip
    // itself: the ground accelerating towards +x at about 0.12 g would hold them back, and
    // the wall still cannot stand at rest.
    let m = stack((1.0, 0.6, 0.8));
    let err = at_rest(m.wall(), m.topology()).unwrap_err().to_string();
    assert!(err.contains("cannot stand even on still ground"), "{err}");
    let (w, t) = (m.wall(), m.topology());
    let (forces, bases) = forces(w, t);
    let groups = crash_groups(w, &[0, 1, 2], &forces[..bases]);
    let plus = direction(w, t, &[0, 1, 2], &forces, &groups, 1, &|| false).unwrap();
    assert!(holds(&plus.expect("not stopped")).0.is_positive());
}

/// Asked to stop at its k-th question, the limit stops there whichever side's program it is
/// in, keeping nothing; never asked, it is the limit `at_rest` gives.
#[test]
fn a_stop_request_ends_the_limit_without_an_answer() {
    let m = Model::from_file("walls/inca/ollantaytambo-monoliths.ron").unwrap();
    let (w, t) = (m.wall(), m.topology());
    let asked = std::cell::Cell::new(0_usize);
    let count = || {
        asked.set(asked.get() + 1);
        false
    };
    assert_eq!(at_rest_until(w, t, &count).unwrap(), Some(limits(&m)));
    let questions = asked.get();
    // Both sides' programs take pivots, so the last question comes in the second one's.
    assert!(questions > 4, "{questions}");
    for k in [1, 2, questions / 2, questions - 1, questions] {
        let asked = std::cell::Cell::new(0_usize);
        let stop_at_k = || {
            asked.set(asked.get() + 1);
            asked.get() >= k
        };
        assert_eq!(
            at_rest_until(w, t, &stop_at_k).unwrap(),
            None,
            "stopped at {k}"
        );
        // The exact fallback asks once more before its first pivot, and nothing after that.
        assert!(
            asked.get() <= k + 1,
            "asked {} times after the stop",
            asked.get() - k
        );
    }
}

#[test]
fn a_wall_beyond_the_size_of_the_exact_program_is_refused_by_name() {
    let blocks = vec!["(width_m: 1.0)"; MAX_BLOCKS + 1].join(", ");
    let m = model(&format!("(height_m: 0.5, blocks: [{blocks}])"), "0.3");
    let err = at_rest(m.wall(), m.topology()).unwrap_err().to_string();
    assert!(
        err.contains(&format!("up to {MAX_BLOCKS} movable blocks")),
        "{err}"
    );
    assert!(
        err.contains(&format!("this wall has {}", MAX_BLOCKS + 1)),
        "{err}"
    );
}

/// The drawing of a mechanism keeps still the point the mechanism turns a block about: a
/// block tipping on its bottom-left corner is drawn turned counterclockwise (at most 0.1 rad)
/// about that corner.
#[test]
fn a_mechanism_is_drawn_turning_about_its_point_at_rest() {
    let m = model(
        "(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\")])",
        "0.7",
    );
    let l = limits(&m);
    let (_, mech) = holds(&l.towards_plus_x);
    let (u, theta, w) = crate::plot::mechanism_pose(m.wall(), mech);
    let phi = -theta[0];
    assert!(phi > 0.0 && phi <= 0.1, "{theta:?}");
    // The middle of the base, 0.3 m from the corner, swung up by phi about it.
    assert!((u[0] - 0.3 * (phi.cos() - 1.0)).abs() < 1e-15, "{u:?}");
    assert!((w[0] - 0.3 * phi.sin()).abs() < 1e-15, "{w:?}");
}

/// The limit program of the wall towards the side of `s` and its crash's groups, as
/// `at_rest` builds them.
fn side_program(m: &Model, s: i128) -> (Program, Vec<crash::Group>) {
    let (wall, topo) = (m.wall(), m.topology());
    let movable: Vec<usize> = (0..wall.blocks.len())
        .filter(|&i| !wall.blocks[i].fixed)
        .collect();
    let centroids: Vec<[Q; 2]> = wall.blocks.iter().map(centroid).collect();
    let (forces, bases) = forces(wall, topo);
    let groups = crash_groups(wall, &movable, &forces[..bases]);
    let program = program(wall, topo, &movable, &forces, &centroids, s);
    (program, groups)
}

#[test]
fn the_shipped_walls_limits_are_proved_from_their_floating_point_bases() {
    // The floating-point run answers (its basis is certified, no exact tableau needed) on every
    // shipped wall, with the exact tableau's limit where that takes under a second.
    let walls = [
        ("walls/five-block-uniform.ron", true),
        ("walls/five-block-variable.ron", true),
        ("walls/inca-coursed.ron", true),
        ("walls/inca/ollantaytambo-monoliths.ron", true),
        ("walls/inca/ollantaytambo-filler.ron", true),
        ("walls/inca/machu-picchu-torreon.ron", false),
        ("walls/inca/kancha-enclosure.ron", false),
        ("walls/inca/qorikancha.ron", false),
        ("walls/rocking/trilith.ron", true),
        ("walls/rocking/dragged-block.ron", true),
    ];
    for (path, compare) in walls {
        let m = Model::from_file(path).unwrap();
        for s in [1, -1] {
            let (p, groups) = side_program(&m, s);
            let fast = certify::certified(&p, &groups, &|| false)
                .unwrap_or_else(|| panic!("{path}, side {s}: no certified basis"));
            if compare {
                let value = |o: &Outcome| match o {
                    Outcome::Optimal { value, .. } => value.clone(),
                    other => panic!("{path}: {other:?}"),
                };
                assert_eq!(
                    value(&fast),
                    value(&simplex::exact(&p, &|| false).unwrap()),
                    "{path}, side {s}"
                );
            }
        }
    }
}

/// Uniqueness is the program's, not the vertex's: runs from two starts (the crash and the
/// artificial basis) decide it alike on seven walls, both sides; where it is unique they end
/// on the same multipliers to the last digit, and the uniform wall's -x side, one of several,
/// shows two starts ending on two mechanisms.
#[test]
fn a_unique_mechanism_is_the_one_every_start_ends_on() {
    let mut differ = Vec::new();
    for path in [
        "walls/five-block-uniform.ron",
        "walls/five-block-variable.ron",
        "walls/inca/ollantaytambo-monoliths.ron",
        "walls/inca/ollantaytambo-filler.ron",
        "walls/inca/stela.ron",
        "walls/rocking/trilith.ron",
        "walls/rocking/two-block-column.ron",
    ] {
        let m = Model::from_file(path).unwrap();
        for s in [1, -1] {
            let (p, groups) = side_program(&m, s);
            let solve = |groups: &[crash::Group]| match certify::solve(&p, groups, &|| false) {
                Some(Outcome::Optimal { x, y, basis, .. }) => {
                    (uniqueness_of(&p, &x, &y, &basis, true), y)
                }
                other => panic!("{path}, side {s}: {other:?}"),
            };
            let ((one, y), (other, other_y)) = (solve(&groups), solve(&[]));
            assert_eq!(one, other, "{path}, side {s}");
            assert_ne!(one, Uniqueness::Undecided, "{path}, side {s}");
            if one == Uniqueness::Unique {
                assert_eq!(y, other_y, "{path}, side {s}");
            } else if y != other_y {
                differ.push((path, s));
            }
        }
    }
    assert!(
        differ.contains(&("walls/five-block-uniform.ron", -1)),
        "{differ:?}"
    );
}

/// Running bonds beyond the old bound of 300 blocks whose programs each needed a change to the
/// floating-point run (docs/rocking-walls.md, "Raising the bound"); the +x side of each (the
/// walls are symmetric), about 5 to 10 s a wall. With one friction everywhere each slides at
/// 3/10 g.
#[test]
fn large_running_bonds_are_proved_from_their_floating_point_bases() {
    // Each by the run that moves the bounds of degenerate basic variables where it stalls,
    // alone. Under Bland's rule instead: at 495 blocks, decided on the usual pricing, two
    // columns whose reduced costs were round-off took turns on one row, then a pivot on a
    // small entry ruined the basis and the run gave up (the exact tableau after it had not
    // finished in 400 s); decided on the careful pricing, the 370-block run ends on a singular
    // basis, and with ties among pivots of a tenth of the largest at least the 451-block one.
    for (target, blocks) in [(500, 495), (450, 451), (360, 370)] {
        let d = crate::wall::RunningBond::paper_wall(target)
            .description()
            .unwrap();
        let m = Model::from_ron_str(&crate::wall::to_ron_string(&d)).unwrap();
        assert_eq!(m.wall().blocks.len(), blocks);
        let moving = super::revised::RUNS[1];
        let (p, groups) = side_program(&m, 1);
        // From the artificial basis (where a crash run's infeasible end goes again) and from
        // the crash, as the limit at rest starts.
        for groups in [&[][..], &groups] {
            match certify::certified_by(&p, groups, moving, &|| false) {
                Some(Outcome::Optimal { value, .. }) => {
                    assert_eq!(
                        -value,
                        &Q::frac(3, 10) * &m.wall().g_m_s2,
                        "{blocks} blocks"
                    )
                }
                other => panic!("{blocks} blocks: {other:?}"),
            }
        }
    }
}

fn in_every(l: &Limit) -> (Uniqueness, Vec<String>, Vec<String>) {
    let Limit::Holds {
        mechanism_uniqueness,
        moving_in_every_mechanism,
        turning_in_every_mechanism,
        ..
    } = l
    else {
        panic!("unlimited: {l:?}");
    };
    (
        *mechanism_uniqueness,
        moving_in_every_mechanism.clone().expect("decided"),
        turning_in_every_mechanism.clone().expect("decided"),
    )
}

/// The blocks that move, and those that turn, in every mechanism that holds at a limit: all of
/// a unique mechanism's; for a block alone at the tie of its friction and b/h (0.5), it moves
/// in both (sliding, tipping) and turns in one; of two slabs standing touching (b/h 0.1), the
/// one on the side the ground leaves behind tips alone or pushed by the other, so it alone
/// turns in every one; the paper's uniform wall slides on either bed joint, by a top end block
/// alone or with what pushes it, and only that end block (B3 on the left, B5 on the right)
/// moves in every mechanism.
#[test]
fn the_blocks_in_every_mechanism_are_those_whose_holding_raises_the_limit() {
    let rows = "(height_m: 1.2, blocks: [(width_m: 0.6, name: \"A\")])";
    let a = || vec!["A".to_string()];
    let tips = limits(&model(rows, "0.7"));
    assert_eq!(
        in_every(&tips.towards_plus_x),
        (Uniqueness::Unique, a(), a())
    );
    let tie = limits(&model(rows, "0.5"));
    assert_eq!(
        in_every(&tie.towards_minus_x),
        (Uniqueness::OneOfSeveral, a(), vec![])
    );
    let slabs = limits(&model(
        "(height_m: 2.0, blocks: [(width_m: 0.2, name: \"L\"), (width_m: 0.2, name: \"R\")])",
        "0.7",
    ));
    for (side, slab) in [(&slabs.towards_plus_x, "L"), (&slabs.towards_minus_x, "R")] {
        let (g, _) = holds(side);
        assert_eq!(g, Q::frac(1, 10));
        let one = vec![slab.to_string()];
        assert_eq!(in_every(side), (Uniqueness::OneOfSeveral, one.clone(), one));
    }
    let uniform = limits(&Model::from_file("walls/five-block-uniform.ron").unwrap());
    for (side, end) in [
        (&uniform.towards_plus_x, "B3"),
        (&uniform.towards_minus_x, "B5"),
    ] {
        let found = in_every(side);
        assert_eq!(
            found,
            (Uniqueness::OneOfSeveral, vec![end.to_string()], vec![])
        );
    }
}
