//! The running-bond generator: the paper's wall at five blocks, exact sizes at any count.

use pirqa::exact::Q;
use pirqa::wall::{parse_description, to_ron_string, RunningBond};
use pirqa::{Topology, Wall};

#[test]
fn five_blocks_are_the_papers_wall() {
    let generated =
        Wall::from_description(&RunningBond::paper_wall(5).description().unwrap()).unwrap();
    let shipped = Wall::load(std::path::Path::new("walls/five-block-uniform.ron")).unwrap();
    assert_eq!(generated.blocks.len(), 5);
    for (g, s) in generated.blocks.iter().zip(&shipped.blocks) {
        assert_eq!(
            (&g.name, &g.x, &g.y, &g.width, &g.height),
            (&s.name, &s.x, &s.y, &s.width, &s.height)
        );
    }
    let (tg, ts) = (
        Topology::new(&generated).unwrap(),
        Topology::new(&shipped).unwrap(),
    );
    let caps =
        |t: &Topology| -> Vec<Q> { t.horizontal.iter().map(|s| s.capacity_n.clone()).collect() };
    assert_eq!(caps(&tg), caps(&ts));
}

#[test]
fn every_count_fills_the_same_wall_exactly() {
    for (target, count) in [(5, 5), (20, 18), (100, 105), (1000, 976), (10_000, 10_050)] {
        let spec = RunningBond::paper_wall(target);
        assert_eq!(spec.block_count(), count, "target {target}");
        let d = spec.description().unwrap();
        let wall = Wall::from_description(&d).unwrap();
        assert_eq!(wall.blocks.len(), count);
        // Every course spans 0..2.4 m exactly; the courses stack to 1.2 m exactly.
        let w = Q::parse_decimal("2.4").unwrap();
        let h = Q::parse_decimal("1.2").unwrap();
        let top = wall.blocks.iter().map(|b| b.top()).max().unwrap();
        assert_eq!(top, h);
        let mut area = Q::zero();
        for b in &wall.blocks {
            area = area + b.area();
            assert!(!b.x.is_negative() && b.right() <= w);
        }
        assert_eq!(area, &w * &h, "target {target}");
        let topo = Topology::new(&wall).unwrap();
        // Nothing floats; the bottom course stands on the ground.
        assert_eq!(topo.blocks.len(), count);
        if target <= 1000 {
            let back = parse_description(&to_ron_string(&d)).unwrap();
            assert_eq!(back, d);
        }
    }
}

#[test]
fn impossible_walls_are_refused_with_the_field_named() {
    let mut spec = RunningBond::paper_wall(5);
    spec.courses = 0;
    let e = spec.description().unwrap_err().to_string();
    assert!(e.contains("courses"), "{e}");
    let mut spec = RunningBond::paper_wall(5);
    spec.blocks_per_course = 20_000;
    let e = spec.description().unwrap_err().to_string();
    assert!(
        e.contains("blocks_per_course") && e.contains("0.1 mm"),
        "{e}"
    );
    let mut spec = RunningBond::paper_wall(5);
    spec.width_m = f64::NAN;
    assert!(spec
        .description()
        .unwrap_err()
        .to_string()
        .contains("width_m"));
}
