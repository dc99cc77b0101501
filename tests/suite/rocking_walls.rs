//! Walls whose blocks may rock, time stepped (Moreau-Jean with three degrees of freedom per
//! block, `--model slide-rock --method moreau`): where nothing lifts it converges to the exact
//! sliding answer as the step falls; a slender block on a stack rocks and overturns as the exact
//! engine's free-standing block does while the stack stays seated; a block on two others is
//! flagged, its load split being indeterminate.

use pirqa::{Method, Model, ModelChoice, Motion, RunSettings, Sine, Summary};

fn sine(amplitude_m_s2: f64, frequency_hz: f64, duration_s: f64) -> Motion {
    Motion::sine(Sine {
        amplitude_m_s2,
        frequency_hz,
        duration_s,
        ..Sine::default()
    })
    .unwrap()
}

fn exact(model: &Model, motion: &Motion, choice: ModelChoice) -> Summary {
    let settings = RunSettings {
        model: choice,
        ..RunSettings::default()
    };
    pirqa::run(model, motion, &settings).unwrap().summary
}

fn stepped(model: &Model, motion: &Motion, dt_s: f64) -> Summary {
    let settings = RunSettings {
        model: ModelChoice::SlideRock,
        method: Method::Moreau { dt_s },
        ..RunSettings::default()
    };
    let s = pirqa::run(model, motion, &settings).unwrap().summary;
    assert_eq!(s.model.equations.as_deref(), Some("moreau-jean"));
    s
}

/// Largest difference of the blocks' max |u| (m).
fn u_error(a: &Summary, b: &Summary) -> f64 {
    a.blocks
        .iter()
        .zip(&b.blocks)
        .map(|(x, y)| (x.max_abs_displacement_m - y.max_abs_displacement_m).abs())
        .fold(0.0, f64::max)
}

/// A column of two blocks and the paper's uniform wall (a block on two others, all joints of
/// one friction), under motions that slide them but lift nothing: the error in every block's
/// peak displacement against the exact sliding engine falls at least fourfold when the step
/// falls fourfold, to a few micrometres; no block turns by more than round-off's share.
#[test]
fn walls_that_only_slide_converge_to_the_exact_sliding_answer() {
    let column = Model::from_ron_str(
        "(version: 1, thickness_m: 1.0, density_kg_m3: 2600, friction: 0.3,
          joint_friction: {\"B2/B1\": 0.25},
          rows: [(height_m: 0.5, blocks: [(width_m: 1.0)]), (height_m: 0.5, blocks: [(width_m: 1.0)])])",
    )
    .unwrap();
    let uniform = Model::from_file("walls/five-block-uniform.ron").unwrap();
    for (model, duration_s) in [(&column, 20.0), (&uniform, 20.0)] {
        let motion = sine(4.0, 1.0, duration_s);
        let reference = exact(model, &motion, ModelChoice::Slide);
        let coarse = u_error(&stepped(model, &motion, 1e-3), &reference);
        let fine_run = stepped(model, &motion, 2.5e-4);
        let fine = u_error(&fine_run, &reference);
        assert!(
            fine < coarse / 4.0 && fine < 1e-5,
            "{}: {coarse:e} -> {fine:e} m",
            model.wall().name
        );
        for b in &fine_run.blocks {
            assert!(
                b.max_abs_rotation_rad < 1e-5,
                "{}: {:?}",
                b.name,
                b.max_abs_rotation_rad
            );
        }
        let e = &fine_run.energy;
        assert!(e.friction_j > 0.0 && e.input_j.is_finite());
    }
}

/// A slender block (0.2 x 0.8 m, friction 0.8) on two squat ones under a 0.3 g, 1.5 Hz sine:
/// it rocks and overturns when the exact engine's free-standing block of the same size does
/// (2.027 s; the time stepping calls it fallen when it lies flat, a few milliseconds later),
/// while the stack under it turns by less than a micro-radian.
#[test]
fn only_the_slender_top_of_a_stack_rocks_and_it_overturns_as_the_exact_block_does() {
    let stack = Model::from_ron_str(
        "(version: 1, thickness_m: 1.0, density_kg_m3: 2600, friction: 0.8,
          rows: [(height_m: 0.5, blocks: [(width_m: 1.0)]), (height_m: 0.5, blocks: [(width_m: 1.0)]),
                 (height_m: 0.8, x_m: 0.4, blocks: [(width_m: 0.2)])])",
    )
    .unwrap();
    let alone = Model::from_ron_str(
        "(version: 1, thickness_m: 1.0, density_kg_m3: 2600, friction: 0.8,
          rows: [(height_m: 0.8, blocks: [(width_m: 0.2)])])",
    )
    .unwrap();
    let motion = sine(0.3 * 9.81, 1.5, 6.0);
    let free = exact(&alone, &motion, ModelChoice::SlideRock);
    let t_exact = free
        .collapse
        .as_ref()
        .expect("the free block overturns")
        .time_s;
    let s = stepped(&stack, &motion, 2.5e-4);
    let c = s.collapse.as_ref().expect("the top block overturns");
    assert_eq!(c.block, "B3");
    assert!(
        (c.time_s - t_exact).abs() < 5e-3,
        "{} against {t_exact}",
        c.time_s
    );
    for b in &s.blocks[..2] {
        assert!(
            b.max_abs_rotation_rad < 1e-6 && b.uplift_time_s.is_none(),
            "{b:?}"
        );
    }
    let lift = s.blocks[2].uplift_time_s.expect("the top block lifts");
    let exact_lift = free.blocks[0].uplift_time_s.unwrap();
    assert!(
        lift >= exact_lift && lift < exact_lift + 0.01,
        "{lift} against {exact_lift}"
    );
}

/// A block on two others is named in a warning: its load split is indeterminate for rigid
/// blocks (docs/rocking-walls.md); a column, where every block rests on one, has none.
#[test]
fn a_block_on_two_others_is_flagged() {
    let uniform = Model::from_file("walls/five-block-uniform.ron").unwrap();
    let s = stepped(&uniform, &sine(1.0, 1.0, 0.5), 1e-3);
    let text: Vec<String> = s.warnings.iter().map(|w| w.to_string()).collect();
    assert!(
        text.iter()
            .any(|w| w.starts_with("B4 rests on two or more blocks") && w.contains("indeterminate")),
        "{text:?}"
    );
}
