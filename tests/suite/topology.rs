//! The support graph reproduces the paper's friction forces, eq. (3), exactly.

use pirqa::topology::{self, Base, Topology};
use pirqa::{Wall, Q};
use std::path::Path;

fn dec(x: f64) -> Q {
    Q::from_decimal(x).unwrap()
}

/// F_ij of eq. (3) for the reference geometry: a, b lower widths; c, e upper end widths;
/// h1, h2 course heights; t thickness; gamma = rho g.
#[test]
fn capacities_match_eq_3_exactly() {
    let (wall, topo) = topology::load(Path::new("walls/five-block-variable.ron")).unwrap();
    let (a, b, c, e) = (dec(1.2), dec(1.2), dec(0.6), dec(0.6));
    let (h1, h2, t) = (dec(0.6), dec(0.6), dec(0.8));
    let gamma = dec(2650.0) * dec(9.81);
    let expected = [
        ("B1", "ground", &a * &t * (&h1 + &h2) * &gamma * dec(0.29)),
        ("B2", "ground", &b * &t * (&h1 + &h2) * &gamma * dec(0.31)),
        ("B3", "B1", &c * &t * &h2 * &gamma * dec(0.28)),
        ("B4", "B1", (&a - &c) * &t * &h2 * &gamma * dec(0.30)),
        ("B4", "B2", (&b - &e) * &t * &h2 * &gamma * dec(0.30)),
        ("B5", "B2", &e * &t * &h2 * &gamma * dec(0.28)),
    ];
    assert_eq!(topo.horizontal.len(), 6);
    for (upper, lower, f) in expected {
        let s = topo
            .horizontal
            .iter()
            .find(|s| {
                wall.blocks[s.upper.0].name == upper && topo.base_name(&wall, s.lower) == lower
            })
            .unwrap_or_else(|| panic!("no support {upper}/{lower}"));
        assert_eq!(s.capacity_n, f, "{upper}/{lower}");
    }
    // Spot value: F10 = 1.2 * 0.8 * 1.2 * 2650 * 9.81 * 0.29 N.
    assert_eq!(
        topo.horizontal[0].capacity_n,
        Q::parse_decimal("8684.91072").unwrap()
    );
}

#[test]
fn loads_are_tributary_and_conserve_weight() {
    let (wall, topo) = topology::load(Path::new("walls/inca-coursed.ron")).unwrap();
    let total: Q = topo.blocks.iter().map(|b| b.weight_n.clone()).sum();
    let on_ground: Q = topo
        .horizontal
        .iter()
        .filter(|s| s.lower == Base::Ground)
        .map(|s| s.load_n.clone())
        .sum();
    assert_eq!(
        on_ground, total,
        "every newton of weight reaches the ground exactly"
    );
    for (i, b) in topo.blocks.iter().enumerate() {
        let carried: Q = topo.below[i]
            .iter()
            .map(|s| topo.horizontal[s.0].load_n.clone())
            .sum();
        assert_eq!(carried, b.load_n, "{}", wall.blocks[i].name);
        let from_above: Q = topo.above[i]
            .iter()
            .map(|s| topo.horizontal[s.0].load_n.clone())
            .sum();
        assert_eq!(&b.weight_n + &from_above, b.load_n);
    }
}

#[test]
fn vertical_joints_of_the_reference_wall() {
    let (wall, topo) = topology::load(Path::new("walls/five-block-uniform.ron")).unwrap();
    let pairs: Vec<(String, String)> = topo
        .vertical
        .iter()
        .map(|j| {
            (
                wall.blocks[j.left.0].name.clone(),
                wall.blocks[j.right.0].name.clone(),
            )
        })
        .collect();
    let want = [("B1", "B2"), ("B3", "B4"), ("B4", "B5")];
    assert_eq!(pairs.len(), 3);
    for (l, r) in want {
        assert!(
            pairs.contains(&(l.to_string(), r.to_string())),
            "{l}|{r} missing: {pairs:?}"
        );
    }
    assert!(topo
        .vertical
        .iter()
        .all(|j| j.gap_m.is_zero() && j.height_m == dec(0.6)));
}

#[test]
fn rows_and_rectangles_build_the_same_model() {
    let rows = std::fs::read_to_string("walls/five-block-uniform.ron").unwrap();
    let rects = r#"(
        version: 1, name: "Five-block wall, uniform friction", thickness_m: 0.8,
        density_kg_m3: 2650, friction: 0.30,
        rectangles: [
            (x_m: 0.6, y_m: 0.6, width_m: 1.2, height_m: 0.6),
            (x_m: 0, y_m: 0, width_m: 1.2, height_m: 0.6),
            (x_m: 1.8, y_m: 0.6, width_m: 0.6, height_m: 0.6),
            (x_m: 1.2, y_m: 0, width_m: 1.2, height_m: 0.6),
            (x_m: 0, y_m: 0.6, width_m: 0.6, height_m: 0.6),
        ],
    )"#;
    let a = Wall::from_ron_str(&rows).unwrap();
    let b = Wall::from_ron_str(rects).unwrap();
    let strip = |w: &Wall| -> Vec<_> {
        w.blocks
            .iter()
            .map(|b| {
                (
                    b.name.clone(),
                    b.x.clone(),
                    b.y.clone(),
                    b.width.clone(),
                    b.height.clone(),
                )
            })
            .collect()
    };
    assert_eq!(strip(&a), strip(&b));
    assert_eq!(Topology::new(&a).unwrap(), Topology::new(&b).unwrap());
}

#[test]
fn a_block_bridging_a_gap_and_faces_seen_past_short_blocks() {
    // B3 bridges the 0.2 m gap between B1 and B2; B4 is short, so B3 and B5 see each other above it.
    let text = r#"(
        version: 1, thickness_m: 1, density_kg_m3: 2000, friction: 0.5,
        rectangles: [
            (x_m: 0, y_m: 0, width_m: 1, height_m: 1),
            (x_m: 1.2, y_m: 0, width_m: 1, height_m: 1),
            (x_m: 0.5, y_m: 1, width_m: 1.2, height_m: 1),
            (x_m: 1.8, y_m: 1, width_m: 0.3, height_m: 0.4),
            (x_m: 1.8, y_m: 1.4, width_m: 0.4, height_m: 0.6),
        ],
    )"#;
    let wall = Wall::from_ron_str(text).unwrap();
    let topo = Topology::new(&wall).unwrap();
    let names = |j: &pirqa::topology::VerticalJoint| {
        format!(
            "{}|{}:{}",
            wall.blocks[j.left.0].name, wall.blocks[j.right.0].name, j.gap_m
        )
    };
    let got: Vec<String> = topo.vertical.iter().map(names).collect();
    assert_eq!(got, vec!["B1|B2:0.2", "B3|B4:0.1", "B3|B5:0.1"]);
    // B3's load splits 0.5 : 0.5 over its two supports.
    let b3 = wall.block_index("B3").unwrap();
    let loads: Vec<Q> = topo.below[b3]
        .iter()
        .map(|s| topo.horizontal[s.0].load_n.clone())
        .collect();
    assert_eq!(loads[0], loads[1]);
}

/// Rectangles on a grid of half metres, (x, y, width, height) in halves: scattered ones (which
/// mostly overlap or float), and courses of blocks with gaps, some shorter than their course.
fn rectangles() -> impl proptest::strategy::Strategy<Value = Vec<(i64, i64, i64, i64)>> {
    use proptest::prelude::*;
    let scattered = prop::collection::vec((0i64..10, 0i64..5, 1i64..5, 1i64..3), 1..14);
    let course = (
        1i64..3,
        prop::collection::vec((0i64..2, 1i64..5, 0i64..2), 1..6),
    );
    let coursed = prop::collection::vec(course, 1..5).prop_map(|courses| {
        let mut rects = Vec::new();
        let mut y = 0;
        for (height, blocks) in courses {
            let mut x = 0;
            for (gap, width, shorter) in blocks {
                x += gap;
                rects.push((x, y, width, (height - shorter).max(1)));
                x += width;
            }
            y += height;
        }
        rects
    });
    prop_oneof![scattered, coursed]
}

fn wall_of(rects: &[(i64, i64, i64, i64)]) -> Result<Wall, pirqa::error::WallError> {
    let half = |k: i64| k as f64 / 2.0;
    let list: Vec<String> = rects
        .iter()
        .map(|&(x, y, w, h)| {
            format!(
                "(x_m: {}, y_m: {}, width_m: {}, height_m: {})",
                half(x),
                half(y),
                half(w),
                half(h)
            )
        })
        .collect();
    Wall::from_ron_str(&format!(
        "(version: 1, thickness_m: 1, density_kg_m3: 2000, friction: 0.5, rectangles: [{}])",
        list.join(", ")
    ))
}

/// Left, bottom, right and top of block i (m).
fn edges(wall: &Wall, i: usize) -> [Q; 4] {
    let b = &wall.blocks[i];
    [b.x.clone(), b.y.clone(), b.right(), b.top()]
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 512, rng_seed: proptest::test_runner::RngSeed::Fixed(20261124), ..proptest::prelude::ProptestConfig::default() })]

    /// The sweeps that find overlaps, supports and faces (n log n) agree with their
    /// definitions checked pair by pair.
    #[test]
    fn overlaps_supports_and_faces_agree_with_their_definitions(rects in rectangles()) {
        let overlapping = rects.iter().enumerate().any(|(i, a)| {
            rects[i + 1..].iter().any(|b| {
                a.0 < b.0 + b.2 && b.0 < a.0 + a.2 && a.1 < b.1 + b.3 && b.1 < a.1 + a.3
            })
        });
        let wall = match wall_of(&rects) {
            Err(pirqa::error::WallError::Overlap { .. }) => {
                proptest::prop_assert!(overlapping);
                return Ok(());
            }
            Err(e) => panic!("{e}"),
            Ok(wall) => wall,
        };
        proptest::prop_assert!(!overlapping);
        let Ok(topo) = Topology::new(&wall) else {
            return Ok(()); // floating or toppling: another test's business
        };
        let n = wall.blocks.len();
        for i in 0..n {
            let [x0, y0, x1, _] = edges(&wall, i);
            // What block i rests on: the ground, or every block whose top is its bottom and
            // which it overlaps, left to right.
            let mut expected: Vec<(Base, Q)> = Vec::new();
            if y0.is_zero() {
                expected.push((Base::Ground, &x1 - &x0));
            }
            let mut under: Vec<usize> = (0..n).filter(|&j| edges(&wall, j)[3] == y0).collect();
            under.sort_by(|&a, &b| wall.blocks[a].x.cmp(&wall.blocks[b].x));
            for j in under {
                let [l0, _, l1, _] = edges(&wall, j);
                let overlap = x1.clone().min(l1) - x0.clone().max(l0);
                if overlap.is_positive() {
                    expected.push((Base::Block(pirqa::topology::BlockId(j)), overlap));
                }
            }
            let got: Vec<(Base, Q)> = topo.below[i]
                .iter()
                .map(|s| (topo.horizontal[s.0].lower, topo.horizontal[s.0].overlap_m.clone()))
                .collect();
            proptest::prop_assert_eq!(got, expected);
        }
        // Faces: j faces i where some height they share is hidden by no block between them
        // (coordinates are halves, so the quarter points between them decide).
        let quarter = Q::frac(1, 4);
        let mut expected = Vec::new();
        for i in 0..n {
            let [_, y0, x1, y1] = edges(&wall, i);
            for j in 0..n {
                let [o0, p0, _, p1] = edges(&wall, j);
                let (lo, hi) = (y0.clone().max(p0), y1.clone().min(p1));
                if o0 < x1 || hi <= lo {
                    continue;
                }
                let mut y = &lo + &quarter;
                let mut seen = false;
                while y < hi {
                    let hidden = (0..n).any(|k| {
                        let [k0, q0, _, q1] = edges(&wall, k);
                        k0 >= x1 && k0 < o0 && q0 < y && y < q1
                    });
                    seen |= !hidden;
                    y = &y + &Q::frac(1, 2);
                }
                if seen {
                    expected.push((i, j, &o0 - &x1, &hi - &lo));
                }
            }
        }
        // By left block, then right block from the bottom up (and nearest first).
        expected.sort_by(|a, b| {
            let (p, q) = (&wall.blocks[a.1], &wall.blocks[b.1]);
            a.0.cmp(&b.0).then(p.y.cmp(&q.y)).then(p.x.cmp(&q.x))
        });
        let got: Vec<_> = topo
            .vertical
            .iter()
            .map(|j| (j.left.0, j.right.0, j.gap_m.clone(), j.height_m.clone()))
            .collect();
        proptest::prop_assert_eq!(got, expected);
    }
}

/// A wall's height in blocks is its number of courses: the paper's wall has two, a running-bond
/// wall as many as it was generated with (its offset courses end in half blocks), a stack of two
/// blocks two.
#[test]
fn courses_count_the_blocks_resting_on_one_another() {
    let (wall, topo) = topology::load(Path::new("walls/five-block-variable.ron")).unwrap();
    assert_eq!(topo.courses(&wall), 2);
    for (courses, blocks_per_course) in [(1, 3), (3, 2), (7, 5), (12, 4)] {
        let spec = pirqa::wall::RunningBond {
            courses,
            blocks_per_course,
            ..pirqa::wall::RunningBond::paper_wall(5)
        };
        let wall = Wall::from_description(&spec.description().unwrap()).unwrap();
        let topo = Topology::new(&wall).unwrap();
        assert_eq!(
            topo.courses(&wall),
            courses,
            "{courses} x {blocks_per_course}"
        );
    }
    let pair = pirqa::samples::stacked_pair(0.5, 0.2);
    assert_eq!(Topology::new(&pair).unwrap().courses(&pair), 2);
}
