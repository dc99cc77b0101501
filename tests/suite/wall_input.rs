//! Bad wall input gets an error that names the file, the line or block, and what to fix.

use crate::common;

use common::file as write_temp;
use pirqa::topology;

/// Loads a wall file and returns the error message, which must name the file.
fn error_of(name: &str, text: &str) -> String {
    let path = write_temp(name, text);
    let err = topology::load(&path).expect_err("this wall must be rejected");
    let msg = err.to_string();
    assert!(msg.contains(name), "message does not name the file: {msg}");
    msg
}

const GOOD_ROWS: &str = r#"rows: [
        (height_m: 0.6, blocks: [(width_m: 1.2), (width_m: 1.2)]),
        (height_m: 0.6, blocks: [(width_m: 0.6), (width_m: 1.2), (width_m: 0.6)]),
    ],"#;

fn wall(extra_top: &str, rows: &str, extra_bottom: &str) -> String {
    format!(
        "(\n    version: 1,\n    thickness_m: 0.8,\n    density_kg_m3: 2650,\n    friction: 0.3,\n{extra_top}\n    {rows}\n{extra_bottom}\n)\n"
    )
}

#[test]
fn the_reference_wall_is_accepted() {
    let path = write_temp("ok.ron", &wall("", GOOD_ROWS, ""));
    let (w, t) = topology::load(&path).unwrap();
    assert_eq!(w.blocks.len(), 5);
    assert_eq!(t.horizontal.len(), 6);
    assert_eq!(w.name, "ok");
}

#[test]
fn malformed_ron_gives_line_and_column() {
    let msg = error_of(
        "syntax.ron",
        "(\n    version: 1,\n    thickness_m: 0.8\n    density_kg_m3: 2650,\n)",
    );
    assert!(msg.contains("line 4"), "{msg}");
    assert!(msg.contains("column"), "{msg}");
}

#[test]
fn unknown_field_is_named_with_its_position() {
    let msg = error_of("unknown.ron", &wall("    widht_m: 3,", GOOD_ROWS, ""));
    assert!(msg.contains("widht_m"), "{msg}");
    assert!(msg.contains("line 6"), "{msg}");
}

#[test]
fn non_positive_and_non_finite_sizes_name_the_block() {
    let rows =
        r#"rows: [(height_m: 0.6, blocks: [(width_m: 1.2), (width_m: -0.5, name: "Bad")])],"#;
    let msg = error_of("negative.ron", &wall("", rows, ""));
    assert!(
        msg.contains("Bad") && msg.contains("row 1, block 2") && msg.contains("width_m = -0.5"),
        "{msg}"
    );
    assert!(msg.contains("a length from 0.001 to 10000 m"), "{msg}");

    let rows = r#"rows: [(height_m: NaN, blocks: [(width_m: 1.2)])],"#;
    let msg = error_of("nan.ron", &wall("", rows, ""));
    assert!(msg.contains("row 1: height_m = NaN"), "{msg}");

    let rows = r#"rectangles: [(x_m: 0, y_m: 0, width_m: inf, height_m: 1)],"#;
    let msg = error_of("inf.ron", &wall("", rows, ""));
    assert!(
        msg.contains("rectangle 1") && msg.contains("width_m = inf"),
        "{msg}"
    );

    let msg = error_of(
        "thick.ron",
        &wall("", GOOD_ROWS, "").replace("thickness_m: 0.8", "thickness_m: 0"),
    );
    assert!(msg.contains("thickness_m = 0"), "{msg}");

    // A block without a name is placed by its row and position (its default name comes later).
    let rows = r#"rows: [(height_m: 0.6, blocks: [(width_m: 1.2), (width_m: -0.5)])],"#;
    let msg = error_of("unnamed.ron", &wall("", rows, ""));
    assert!(
        msg.contains("the block at row 1, block 2: width_m = -0.5"),
        "{msg}"
    );
}

#[test]
fn block_names_that_joint_keys_cannot_tell_apart_are_refused() {
    for name in ["ground", "B1/B2", " "] {
        let rows = format!(r#"rows: [(height_m: 0.6, blocks: [(width_m: 1.2, name: "{name}")])],"#);
        let msg = error_of("names.ron", &wall("", &rows, ""));
        assert!(
            msg.contains(&format!("block name \"{name}\" (row 1, block 1)"))
                && msg.contains("must not be empty, contain '/', or be \"ground\""),
            "{msg}"
        );
    }
}

#[test]
fn overlapping_blocks_are_named_with_the_overlap() {
    let rows = r#"rectangles: [
        (x_m: 0, y_m: 0, width_m: 1.0, height_m: 0.5),
        (x_m: 0.9, y_m: 0, width_m: 1.0, height_m: 0.5),
    ],"#;
    let msg = error_of("overlap.ron", &wall("", rows, ""));
    assert!(msg.contains("B1 and B2 overlap by 0.1 m x 0.5 m"), "{msg}");
}

#[test]
fn a_floating_block_is_reported() {
    let rows = r#"rectangles: [
        (x_m: 0, y_m: 0, width_m: 1.0, height_m: 0.5),
        (x_m: 0.2, y_m: 0.6, width_m: 0.5, height_m: 0.5, name: "Loose"),
    ],"#;
    let msg = error_of("floating.ron", &wall("", rows, ""));
    assert!(
        msg.contains("block Loose (rectangle 2) has no support"),
        "{msg}"
    );
    assert!(msg.contains("y = 0.6 m"), "{msg}");
}

#[test]
fn a_block_that_would_topple_is_reported() {
    let rows = r#"rectangles: [
        (x_m: 0, y_m: 0, width_m: 1.0, height_m: 0.5),
        (x_m: 0.8, y_m: 0.5, width_m: 1.0, height_m: 0.5, name: "Overhang"),
    ],"#;
    let msg = error_of("topple.ron", &wall("", rows, ""));
    assert!(
        msg.contains("Overhang") && msg.contains("would topple") && msg.contains("1.3"),
        "{msg}"
    );
}

#[test]
fn friction_and_restitution_out_of_range() {
    let msg = error_of(
        "mu.ron",
        &wall("", GOOD_ROWS, "").replace("friction: 0.3", "friction: 2.5"),
    );
    assert!(
        msg.contains("friction = 2.5") && msg.contains("(0, 2]"),
        "{msg}"
    );
    let msg = error_of(
        "mu0.ron",
        &wall("", GOOD_ROWS, r#"    joint_friction: {"B3/B1": 0.0},"#),
    );
    assert!(
        msg.contains("\"B3/B1\" = 0") && msg.contains("(0, 2]"),
        "{msg}"
    );
    let msg = error_of("e.ron", &wall("    restitution: 1.2,", GOOD_ROWS, ""));
    assert!(
        msg.contains("restitution = 1.2") && msg.contains("[0, 1]"),
        "{msg}"
    );
    let msg = error_of(
        "r.ron",
        &wall("    rocking_restitution_factor: -0.1,", GOOD_ROWS, ""),
    );
    assert!(
        msg.contains("r.ron: rocking_restitution_factor = -0.1") && msg.contains("[0, 1]"),
        "{msg}"
    );
}

#[test]
fn joint_keys_must_name_support_edges() {
    let msg = error_of(
        "key-unknown.ron",
        &wall("", GOOD_ROWS, r#"    joint_friction: {"B9/B1": 0.28},"#),
    );
    assert!(
        msg.contains("no block named B9") && msg.contains("B1, B2, B3, B4, B5"),
        "{msg}"
    );
    let msg = error_of(
        "key-edge.ron",
        &wall("", GOOD_ROWS, r#"    joint_friction: {"B5/B1": 0.28},"#),
    );
    assert!(
        msg.contains("B5 does not rest on B1 (B5 rests on B2)"),
        "{msg}"
    );
    let msg = error_of(
        "key-ground.ron",
        &wall("", GOOD_ROWS, r#"    joint_friction: {"B4/ground": 0.28},"#),
    );
    assert!(
        msg.contains("B4 does not rest on ground (B4 rests on B1 and B2)"),
        "{msg}"
    );
    let msg = error_of(
        "key-form.ron",
        &wall("", GOOD_ROWS, r#"    joint_friction: {"B3-B1": 0.28},"#),
    );
    assert!(msg.contains("\"upper/lower\""), "{msg}");
}

#[test]
fn duplicate_names_are_reported_with_both_places() {
    let rows = r#"rows: [(height_m: 0.6, blocks: [(width_m: 1.2, name: "A"), (width_m: 1.2, name: "A")])],"#;
    let msg = error_of("dup.ron", &wall("", rows, ""));
    assert!(
        msg.contains("name A is used twice")
            && msg.contains("row 1, block 1")
            && msg.contains("row 1, block 2"),
        "{msg}"
    );
    let rows = r#"rows: [(height_m: 0.6, blocks: [(width_m: 1.2), (width_m: 1.2, name: "B1")])],"#;
    let msg = error_of("dup-auto.ron", &wall("", rows, ""));
    assert!(
        msg.contains("B1 is used twice") && msg.contains("(numbered)") && msg.contains("(named)"),
        "{msg}"
    );
}

#[test]
fn version_material_and_empty_walls() {
    let msg = error_of(
        "version.ron",
        &wall("", GOOD_ROWS, "").replace("version: 1", "version: 7"),
    );
    assert!(msg.contains("version 7 is not supported"), "{msg}");
    let msg = error_of(
        "material.ron",
        &wall("    unit_weight_kn_m3: 26,", GOOD_ROWS, ""),
    );
    assert!(msg.contains("exactly one"), "{msg}");
    let msg = error_of("empty.ron", &wall("", "", ""));
    assert!(msg.contains("no blocks"), "{msg}");
}

#[test]
fn an_abutment_cannot_stand_on_a_movable_block() {
    let rows = r#"rectangles: [
        (x_m: 0, y_m: 0, width_m: 1.0, height_m: 0.5),
        (x_m: 0, y_m: 0.5, width_m: 1.0, height_m: 0.5, fixed: true),
    ],"#;
    let msg = error_of("fixed.ron", &wall("", rows, ""));
    assert!(
        msg.contains("fixed block B2 rests on movable block B1"),
        "{msg}"
    );
}

#[test]
fn a_missing_file_is_named() {
    let err = topology::load(std::path::Path::new("walls/no-such-wall.ron")).unwrap_err();
    assert!(err.to_string().contains("walls/no-such-wall.ron"), "{err}");
}

/// A stone of its own density weighs what it should and loads what is under it; a density that
/// is not positive names the block.
#[test]
fn a_block_can_have_its_own_density() {
    let rows = r#"rows: [
        (height_m: 0.6, blocks: [(width_m: 1.2), (width_m: 1.2)]),
        (height_m: 0.6, blocks: [(width_m: 0.6), (width_m: 1.2, density_kg_m3: 5300), (width_m: 0.6)]),
    ],"#;
    let path = write_temp("dense.ron", &wall("", rows, ""));
    let (w, t) = topology::load(&path).unwrap();
    // B4 (1.2 x 0.6 x 0.8 m) at twice the wall's density.
    assert_eq!(w.mass_kg(3).to_f64(), 5300.0 * 1.2 * 0.6 * 0.8);
    assert_eq!(w.mass_kg(2).to_f64(), 2650.0 * 0.6 * 0.6 * 0.8);
    // B1 carries B3 (0.36 m2) and half of B4 (0.72 m2 / 2 at 5300 kg/m3) on top of its own.
    let carried = t.blocks[0].load_n.to_f64() - t.blocks[0].weight_n.to_f64();
    let expect = (0.36 * 2650.0 + 0.36 * 5300.0) * 0.8 * 9.81;
    assert!((carried - expect).abs() < 1e-9, "{carried} vs {expect}");
    let e = error_of(
        "light.ron",
        &wall(
            "",
            &rows.replace("density_kg_m3: 5300", "density_kg_m3: -1"),
            "",
        ),
    );
    assert!(
        e.contains("row 2, block 2") && e.contains("density_kg_m3 = -1"),
        "{e}"
    );
}
