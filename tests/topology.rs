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
    assert_eq!(topo.supports.len(), 6);
    for (upper, lower, f) in expected {
        let s = topo
            .supports
            .iter()
            .find(|s| {
                wall.blocks[s.upper.0].name == upper && topo.base_name(&wall, s.lower) == lower
            })
            .unwrap_or_else(|| panic!("no support {upper}/{lower}"));
        assert_eq!(s.capacity_n, f, "{upper}/{lower}");
    }
    // Spot value: F10 = 1.2 * 0.8 * 1.2 * 2650 * 9.81 * 0.29 N.
    assert_eq!(
        topo.supports[0].capacity_n,
        Q::parse_decimal("8684.91072").unwrap()
    );
}

#[test]
fn loads_are_tributary_and_conserve_weight() {
    let (wall, topo) = topology::load(Path::new("walls/inca-coursed.ron")).unwrap();
    let total: Q = topo.blocks.iter().map(|b| b.weight_n.clone()).sum();
    let on_ground: Q = topo
        .supports
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
            .map(|s| topo.supports[s.0].load_n.clone())
            .sum();
        assert_eq!(carried, b.load_n, "{}", wall.blocks[i].name);
        let from_above: Q = topo.above[i]
            .iter()
            .map(|s| topo.supports[s.0].load_n.clone())
            .sum();
        assert_eq!(&b.weight_n + &from_above, b.load_n);
    }
}

#[test]
fn vertical_joints_of_the_reference_wall() {
    let (wall, topo) = topology::load(Path::new("walls/five-block-uniform.ron")).unwrap();
    let pairs: Vec<(String, String)> = topo
        .joints
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
        .joints
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
    let got: Vec<String> = topo.joints.iter().map(names).collect();
    assert_eq!(got, vec!["B1|B2:0.2", "B3|B4:0.1", "B3|B5:0.1"]);
    // B3's load splits 0.5 : 0.5 over its two supports.
    let b3 = wall.block_index("B3").unwrap();
    let loads: Vec<Q> = topo.below[b3]
        .iter()
        .map(|s| topo.supports[s.0].load_n.clone())
        .collect();
    assert_eq!(loads[0], loads[1]);
}
