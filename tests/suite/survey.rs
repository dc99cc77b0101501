//! Surveyed walls: a survey of a shipped wall, clean or with noise under the snap tolerance,
//! imports to the same topology; broken surveys get errors that name the blocks and the
//! distances in mm; the Inca library walls run under El Centro.

use pirqa::error::SurveyError;
use pirqa::rng::Rng;
use pirqa::topology::{Base, Topology};
use pirqa::wall::survey::{import, parse_survey, Imported, SurveyOptions};
use pirqa::Wall;
use std::collections::BTreeMap;
use std::path::Path;

const TOL_M: f64 = 0.005;

fn options() -> SurveyOptions {
    SurveyOptions {
        snap_m: TOL_M,
        name: "survey".into(),
        thickness_m: 0.9,
        density_kg_m3: 2650.0,
        friction: 0.3,
        restitution: 1.0,
    }
}

/// A survey of `wall` in metres, every edge moved independently by up to `noise_m` (the
/// survey's origin moved too: levels are measured from the lowest bottom).
fn survey_of(wall: &Wall, noise_m: f64, seed: u64) -> String {
    let mut rng = Rng::new(seed);
    let mut jitter = || noise_m * (2.0 * rng.uniform() - 1.0);
    let mut csv = String::from("id,x,y,width,height\n");
    for b in &wall.blocks {
        let (x0, x1) = (b.x.to_f64() + jitter(), b.right().to_f64() + jitter());
        let (y0, y1) = (b.y.to_f64() + jitter(), b.top().to_f64() + jitter());
        csv += &format!(
            "{},{},{},{},{}\n",
            b.name,
            x0 + 100.0,
            y0 + 3400.0,
            x1 - x0,
            y1 - y0
        );
    }
    csv
}

fn import_text(text: &str, unit_m: f64) -> Result<Imported, SurveyError> {
    import(&parse_survey(text, unit_m)?, &options())
}

type Graph = (
    BTreeMap<(String, String), f64>,
    BTreeMap<(String, String), f64>,
);

/// Support edges with their overlap, vertical joints with their gap (m).
fn graph(wall: &Wall) -> Graph {
    let topo = Topology::new(wall).unwrap();
    let name = |i: pirqa::BlockId| wall.blocks[i.0].name.clone();
    let supports = topo
        .horizontal
        .iter()
        .map(|s| {
            let lower = match s.lower {
                Base::Ground => "ground".to_string(),
                Base::Block(b) => name(b),
            };
            ((name(s.upper), lower), s.overlap_m.to_f64())
        })
        .collect();
    let joints = topo
        .vertical
        .iter()
        .map(|j| ((name(j.left), name(j.right)), j.gap_m.to_f64()))
        .collect();
    (supports, joints)
}

fn same_graph(a: &Graph, b: &Graph, within_m: f64) {
    let keys = |m: &BTreeMap<(String, String), f64>| m.keys().cloned().collect::<Vec<_>>();
    assert_eq!(keys(&a.0), keys(&b.0), "support edges differ");
    assert_eq!(keys(&a.1), keys(&b.1), "vertical joints differ");
    for (k, v) in a.0.iter().chain(&a.1) {
        let w = b.0.get(k).or_else(|| b.1.get(k)).unwrap();
        assert!((v - w).abs() <= within_m, "{k:?}: {v} vs {w}");
    }
}

fn library() -> Vec<Wall> {
    [
        "walls/inca/qorikancha.ron",
        "walls/inca/machu-picchu-torreon.ron",
        "walls/inca/ollantaytambo-monoliths.ron",
        "walls/inca/kancha-enclosure.ron",
        "walls/five-block-variable.ron",
    ]
    .iter()
    .map(|p| Wall::load(Path::new(p)).unwrap())
    .collect()
}

#[test]
fn a_clean_survey_imports_to_the_same_wall() {
    for wall in library() {
        let imported = import_text(&survey_of(&wall, 0.0, 1), 1.0).unwrap();
        let got = Wall::from_description(&imported.description).unwrap();
        same_graph(&graph(&wall), &graph(&got), 1e-9);
        // Only the survey's origin moved: no edge needed more than rounding to 0.01 mm.
        assert!(imported.snaps.is_empty(), "{:?}", imported.snaps.first());
        assert_eq!(imported.ground_y_m, 3400.0);
    }
    // A clean survey in millimetres needs no tolerance at all.
    let wall = &library()[0];
    let mut mm = String::from("id,x,y,width,height\n");
    for b in &wall.blocks {
        let v = [
            b.x.to_f64(),
            b.y.to_f64(),
            b.width.to_f64(),
            b.height.to_f64(),
        ];
        let v: Vec<String> = v.iter().map(|x| format!("{}", (x * 1e3).round())).collect();
        mm += &format!("{},{}\n", b.name, v.join(","));
    }
    let exact = SurveyOptions {
        snap_m: 0.0,
        ..options()
    };
    let imported = import(&parse_survey(&mm, 1e-3).unwrap(), &exact).unwrap();
    let got = Wall::from_description(&imported.description).unwrap();
    same_graph(&graph(wall), &graph(&got), 1e-9);
}

#[test]
fn a_noisy_survey_imports_to_the_same_topology() {
    for (k, wall) in library().iter().enumerate() {
        for seed in 0..5 {
            // Every edge off by up to 2.4 mm: two edges that touch are at most 4.8 mm apart.
            let imported = import_text(&survey_of(wall, 0.48 * TOL_M, seed + 10 * k as u64), 1.0)
                .unwrap_or_else(|e| panic!("{} seed {seed}: {e}", wall.name));
            let got = Wall::from_description(&imported.description).unwrap();
            // Overlaps and gaps move by at most two snaps.
            same_graph(&graph(wall), &graph(&got), 2.0 * TOL_M);
            let largest = imported.largest_snap().unwrap();
            assert!((largest.to_m - largest.from_m).abs() <= TOL_M);
            assert!(imported.snaps.len() > wall.blocks.len(), "most edges moved");
        }
    }
}

#[test]
fn millimetres_and_metres_give_the_same_wall() {
    let wall = &library()[1];
    let metres = survey_of(wall, 0.002, 3);
    let mut mm = String::from("id,x,y,width,height\n");
    for line in metres.lines().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let v: Vec<String> = f[1..]
            .iter()
            .map(|x| format!("{}", x.parse::<f64>().unwrap() * 1e3))
            .collect();
        mm += &format!("{},{}\n", f[0], v.join(","));
    }
    let a = import_text(&metres, 1.0).unwrap();
    let b = import_text(&mm, 1e-3).unwrap();
    same_graph(
        &graph(&Wall::from_description(&a.description).unwrap()),
        &graph(&Wall::from_description(&b.description).unwrap()),
        2e-5,
    );
}

#[test]
fn gaps_wider_than_the_tolerance_are_kept_as_measured() {
    // Two blocks 12 mm apart on the ground, a third bridging them; 3 mm is snapped shut.
    let text = "id,x,y,width,height\nA,0,0,1,0.5\nB,1.012,0.001,1,0.5\nC,0.5,0.5,1,0.4\nD,2.015,0,0.6,0.5\n";
    let imported = import_text(text, 1.0).unwrap();
    let (supports, joints) = graph(&Wall::from_description(&imported.description).unwrap());
    assert_eq!(joints[&("A".into(), "B".into())], 0.012);
    assert_eq!(joints[&("B".into(), "D".into())], 0.0);
    assert!(supports.contains_key(&("C".into(), "A".into())));
    assert!(supports.contains_key(&("C".into(), "B".into())));
    // B's bottom moved 1 mm onto the ground, B's right and D's left faces 1.5 mm each.
    let largest = imported.largest_snap().unwrap();
    assert!(
        (largest.to_m - largest.from_m).abs() - 0.0015 < 1e-12,
        "{largest:?}"
    );
}

#[test]
fn materials_friction_and_fixed_blocks_are_kept() {
    let text = "id,x,y,width,height,material,friction,fixed\n\
                A,0,0,1,0.5,granite,,no\n\
                B,1,0,1,0.5,2900,0.25,\n\
                C,0.5,0.5,1,0.4,andesite,0.6,false\n\
                W,2,0,0.5,1.5,,,yes\n";
    let d = import_text(text, 1.0).unwrap().description;
    let wall = Wall::from_description(&d).unwrap();
    assert_eq!(wall.mass_kg(1).to_f64(), 2900.0 * 0.5 * 0.9);
    assert_eq!(wall.mass_kg(0).to_f64(), 2650.0 * 0.5 * 0.9);
    assert!(wall.blocks[wall.block_index("W").unwrap()].fixed);
    let keys: Vec<(&str, f64)> = d
        .joint_friction
        .iter()
        .map(|(k, v)| (k.as_str(), *v))
        .collect();
    assert_eq!(
        keys,
        [("B/ground", 0.25), ("C/A", 0.6), ("C/B", 0.6)],
        "a block's friction is that of the joints it rests on"
    );
}

fn error(text: &str) -> String {
    import_text(text, 1.0).unwrap_err().to_string()
}

#[test]
fn broken_surveys_name_the_blocks_and_the_distances() {
    let head = "id,x,y,width,height\n";
    // Overlap by more than the tolerance: both ids and the overlap in mm.
    let e = error(&format!("{head}A,0,0,1,0.5\nB,0.99,0,1,0.5\n"));
    assert!(
        e.contains("blocks A and B overlap by 10.0 mm x 500.0 mm") && e.contains("5 mm"),
        "{e}"
    );
    // A block with nothing under it: its id, the block below and the gap in mm.
    let e = error(&format!("{head}A,0,0,1,0.5\nB,0,0.52,1,0.5\n"));
    assert!(
        e.contains("block B has nothing under it") && e.contains("block A's, 20.0 mm lower"),
        "{e}"
    );
    // 7 mm above the ground, beside a block that stands on it: not snapped down.
    let e = error(&format!("{head}A,0,0,1,0.5\nB,1,0.007,1,0.5\n"));
    assert!(
        e.contains("block B has nothing under it") && e.contains("ground is 7.0 mm lower"),
        "{e}"
    );
    // Sinking into the block below by more than the tolerance is an overlap.
    let e = error(&format!("{head}A,0,0,1,0.5\nB,0,0.49,1,0.5\n"));
    assert!(
        e.contains("blocks A and B overlap by 1000.0 mm x 10.0 mm"),
        "{e}"
    );
    // Edges chained through neighbours farther than twice the tolerance.
    let e = error(&format!(
        "{head}A,0,0,1,0.5\nB,1,0,1,0.504\nC,2,0,1,0.508\nD,3,0,1,0.512\n\
         E,0.5,0.5,1,0.3\nF,1.5,0.504,1,0.3\nG,2.5,0.508,1,0.3\nH,3.5,0.513,0.5,0.3\n"
    ));
    assert!(
        e.contains("bottoms and tops") && e.contains("13.0 mm apart"),
        "{e}"
    );
    // Line-level problems.
    for (text, expect) in [
        ("x,y,width,height\n", "no `id` column"),
        ("id,x,y,width,height,colour\n", "unknown column `colour`"),
        ("id,x,y,width,height\nA,0,0,1\n", "line 2: 4 fields"),
        (
            "id,x,y,width,height\nA,0,zero,1,1\n",
            "line 2: column `y`: `zero` is not a number",
        ),
        (
            "id,x,y,width,height\nA,0,0,NaN,1\n",
            "`NaN` is not a number",
        ),
        (
            "id,x,y,width,height\nA,0,0,-1,1\n",
            "width must be positive",
        ),
        (
            "id,x,y,width,height\nA,0,0,1,1\nA,1,0,1,1\n",
            "`A` is used twice: on line 2",
        ),
        (
            "id,x,y,width,height,material\nA,0,0,1,1,cheese\n",
            "material `cheese` is unknown",
        ),
        (
            "id,x,y,width,height,friction\nA,0,0,1,1,3\n",
            "friction 3 must lie in (0, 2]",
        ),
        (
            "id,x,y,width,height,fixed\nA,0,0,1,1,maybe\n",
            "fixed `maybe`",
        ),
        ("# only a comment\n", "the survey is empty"),
    ] {
        let e = error(text);
        assert!(e.contains(expect), "`{text}`: {e}");
    }
}

/// The library walls run under El Centro (scaled to 0.5 g, where they slide) with the energy
/// balance closing to round-off.
#[test]
fn the_inca_library_walls_run_under_el_centro() {
    use pirqa::integrate::event::EventDriven;
    use pirqa::integrate::{Integrator, Scenario, Settings};
    use pirqa::motion::{read_record, Motion, ReadOptions};
    let record = read_record(
        Path::new("records/elcentro1940_IELC180_peer_dt0p01_g.AT2"),
        None,
        &ReadOptions::default(),
    )
    .unwrap();
    let record = record.scaled(0.5 * 9.81 / record.pga_m_s2()).unwrap();
    for wall in &library()[..4] {
        let topo = Topology::new(wall).unwrap();
        let settings = Settings::summary_only(record.duration_s());
        let r = EventDriven::default()
            .run(&Scenario {
                wall,
                topology: &topo,
                motion: &Motion::Record(record.clone()),
                settings: &settings,
            })
            .unwrap_or_else(|e| panic!("{}: {e}", wall.name));
        let e = &r.summary.energy;
        assert!(e.input_j > 0.0, "{}: it slides", wall.name);
        assert!(
            e.residual_j.abs() < 1e-11 * e.input_j,
            "{}: {e:?}",
            wall.name
        );
    }
}
