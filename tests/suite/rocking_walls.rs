//! Walls whose blocks may rock. Time stepped (Moreau-Jean with three degrees of freedom per
//! block, `--model slide-rock --method moreau`): where nothing lifts it converges to the exact
//! sliding answer as the step falls; a slender block on a stack rocks and overturns as the exact
//! engine's free-standing block does while the stack stays seated; a block on two others is
//! flagged, its load split being indeterminate. Exact (the column model, `--model auto`): the
//! top of a stack is the free block on a base held to the ground; a held joint gives way where
//! the closed form says, and one inside the moving body where time stepping sees it slip; a
//! stack that slides under a rocking top is followed; on these columns the time-stepped answer
//! converges to the exact one as the step falls.

use pirqa::study::work_precision::rocking_errors;
use pirqa::{
    ContactSolver, Method, Model, ModelChoice, Motion, Response, RunSettings, Sine, Summary,
    Warning,
};

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
    stepped_by(model, motion, dt_s, ContactSolver::GaussSeidel)
}

fn stepped_by(model: &Model, motion: &Motion, dt_s: f64, solver: ContactSolver) -> Summary {
    let settings = RunSettings {
        model: ModelChoice::SlideRock,
        method: Method::Moreau { dt_s },
        contact_solver: solver,
        ..RunSettings::default()
    };
    let s = pirqa::run(model, motion, &settings).unwrap().summary;
    let equations = match solver {
        ContactSolver::GaussSeidel => "moreau-jean",
        ContactSolver::Newton => "moreau-jean-newton",
    };
    assert_eq!(s.model.equations.as_deref(), Some(equations));
    s
}

const SOLVERS: [ContactSolver; 2] = [ContactSolver::GaussSeidel, ContactSolver::Newton];

/// Largest difference of the blocks' max |u| (m).
fn u_error(a: &Summary, b: &Summary) -> f64 {
    a.blocks
        .iter()
        .zip(&b.blocks)
        .map(|(x, y)| (x.max_abs_displacement_m - y.max_abs_displacement_m).abs())
        .fold(0.0, f64::max)
}

/// Blocks stacked at rest stay at rest under time stepping when nothing can move them (a ground
/// acceleration of 0.001 g against joints of friction 0.2 and more): every shipped wall of
/// several blocks, whose faces meet exactly in rationals but whose float positions leave some
/// of them 1e-16 m apart. Those contacts once looked open for the first step, the blocks on
/// them fell freely for it and landed (up to 15 mm/s, Gauss-Seidel unconverged in steps after,
/// the wall sinking by joules of potential energy); now every velocity stays at round-off.
/// The same with the whole-wall Newton solver, whose stiff contacts close at eps p_n: a
/// resting wall sinks, by less than 0.1 nm in 0.05 s, and moves at under 1 nm/s.
#[test]
fn time_stepping_keeps_a_wall_at_rest_where_nothing_can_move_it() {
    let still = sine(0.001 * 9.81, 1.0, 0.05);
    let mut walls = 0;
    for dir in ["walls", "walls/inca", "walls/rocking"] {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.extension().is_none_or(|e| e != "ron") {
                continue;
            }
            let model = Model::from_file(&path).unwrap();
            if model.wall().blocks.len() < 2 {
                continue;
            }
            walls += 1;
            let weight_n: f64 = model
                .topology()
                .blocks
                .iter()
                .map(|b| b.weight_n.to_f64())
                .sum();
            for solver in SOLVERS {
                let s = stepped_by(&model, &still, 5e-4, solver);
                let fastest = s
                    .blocks
                    .iter()
                    .map(|b| b.max_abs_velocity_m_s)
                    .fold(0.0, f64::max);
                let at = format!("{} ({solver:?})", path.display());
                // Newton's contacts close at eps p_n, a few billionths of g dt, and the blocks
                // turn as much at their corners.
                let allowed_m_s = match solver {
                    ContactSolver::GaussSeidel => 1e-11,
                    ContactSolver::Newton => 1e-9,
                };
                assert!(fastest < allowed_m_s, "{at}: {fastest} m/s");
                // Gauss-Seidel's rigid contacts hold the blocks up to round-off; Newton's stiff
                // ones let the wall sink at eps p_n, by picometres in these 0.05 s (2 to 13).
                let sunk_m = -s.energy.potential_j / weight_n;
                let allowed_m = match solver {
                    ContactSolver::GaussSeidel => 1e-9 / weight_n,
                    ContactSolver::Newton => 1e-10,
                };
                assert!(sunk_m.abs() < allowed_m, "{at}: sunk by {sunk_m:e} m");
                assert_eq!(s.stats.unconverged_steps, 0, "{at}");
            }
        }
    }
    assert!(walls >= 10, "{walls} walls");
}

/// A column of two blocks and the paper's uniform wall (a block on two others, all joints of
/// one friction), under motions that slide them but lift nothing: the error in every block's
/// peak displacement against the exact sliding engine falls at least fourfold when the step
/// falls fourfold, to a few micrometres; no block turns by more than round-off's share (1e-9
/// rad; 1e-13 rad since stacked blocks no longer fall for the first step). Both contact
/// solvers: where every joint has one friction the split of a block on two others does not
/// change the answer, and the whole-wall Newton solver's stiff contacts converge to it too.
#[test]
fn walls_that_only_slide_converge_to_the_exact_sliding_answer() {
    let column = Model::from_ron_str(
        "(version: 1, thickness_m: 1.0, density_kg_m3: 2600, friction: 0.3,
          joint_friction: {\"B2/B1\": 0.25},
          rows: [(height_m: 0.5, blocks: [(width_m: 1.0)]), (height_m: 0.5, blocks: [(width_m: 1.0)])])",
    )
    .unwrap();
    let uniform = Model::from_file("walls/five-block-uniform.ron").unwrap();
    for ((model, duration_s), solver) in [(&column, 20.0), (&uniform, 20.0)]
        .into_iter()
        .flat_map(|m| SOLVERS.map(|s| (m, s)))
    {
        let motion = sine(4.0, 1.0, duration_s);
        let reference = exact(model, &motion, ModelChoice::Slide);
        let coarse = u_error(&stepped_by(model, &motion, 1e-3, solver), &reference);
        let fine_run = stepped_by(model, &motion, 2.5e-4, solver);
        let fine = u_error(&fine_run, &reference);
        assert!(
            fine < coarse / 4.0 && fine < 1e-5,
            "{} ({solver:?}): {coarse:e} -> {fine:e} m",
            model.wall().name
        );
        for b in &fine_run.blocks {
            assert!(
                b.max_abs_rotation_rad < 1e-9,
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

fn with_history(model: &Model, motion: &Motion, method: Method, output_dt_s: f64) -> Response {
    let settings = RunSettings {
        model: ModelChoice::SlideRock,
        method,
        output_dt_s: Some(output_dt_s),
        ..RunSettings::default()
    };
    pirqa::run(model, motion, &settings).unwrap()
}

/// A block (width, height, name) on another standing on the ground, the wall's settings in
/// `head`, the joint between them of friction `joint_friction`.
fn two_blocks(head: &str, joint_friction: f64, blocks: [(f64, f64, &str); 2]) -> Model {
    let [(w0, h0, n0), (w1, h1, n1)] = blocks;
    Model::from_ron_str(&format!(
        "(version: 1, {head}, joint_friction: {{\"{n1}/{n0}\": {joint_friction}}},
          rows: [(height_m: {h0}, blocks: [(width_m: {w0}, name: \"{n0}\")]),
                 (height_m: {h1}, blocks: [(width_m: {w1}, name: \"{n1}\")])])"
    ))
    .unwrap()
}

/// The time and words of the warning that a held joint gave way.
fn gave_way(s: &Summary) -> (f64, String, String) {
    s.warnings
        .iter()
        .find_map(|w| match w {
            Warning::HeldJointGives {
                joint, how, time_s, ..
            } => Some((*time_s, joint.clone(), how.clone())),
            _ => None,
        })
        .expect("a held joint gives way")
}

/// The top of walls/rocking/slender-on-stack.ron is, for the column model, the free block of
/// its size on a base held to the ground: under `auto` it lifts and overturns at the free
/// block's times (to round-off: the same equations from a body built another way), the stack
/// stays put, and every block is reported by name.
#[test]
fn the_top_of_a_stack_rocks_as_the_free_block_on_a_held_stack() {
    let stack = Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let alone = Model::from_ron_str(
        "(version: 1, thickness_m: 1.0, density_kg_m3: 2600, friction: 0.8,
          rows: [(height_m: 0.8, blocks: [(width_m: 0.2)])])",
    )
    .unwrap();
    let motion = sine(0.3 * 9.81, 1.5, 6.0);
    let free = exact(&alone, &motion, ModelChoice::SlideRock);
    let s = exact(&stack, &motion, ModelChoice::Auto);
    assert_eq!(s.model.name, "slide-rock");
    let names: Vec<&str> = s.blocks.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["Base", "Middle", "Top"]);
    let (fell, fell_free) = (s.collapse.unwrap(), free.collapse.unwrap());
    assert_eq!(fell.block, "Top");
    assert!(
        (fell.time_s - fell_free.time_s).abs() < 1e-9,
        "{} against {}",
        fell.time_s,
        fell_free.time_s
    );
    let (lift, lift_free) = (s.blocks[2].uplift_time_s, free.blocks[0].uplift_time_s);
    assert!((lift.unwrap() - lift_free.unwrap()).abs() < 1e-12);
    assert!(
        (s.blocks[2].max_abs_displacement_m - free.blocks[0].max_abs_displacement_m).abs() < 1e-12
    );
    for b in &s.blocks[..2] {
        assert_eq!(
            (
                b.max_abs_displacement_m,
                b.max_abs_rotation_rad,
                b.uplift_time_s
            ),
            (0.0, 0.0, None)
        );
    }
}

/// The exact run of `model` under `motion` with its events logged, which must run to `block`'s
/// overturning (not stop before it) balancing its energy to 1e-13 of the input, the friction
/// dissipated and the fallen block's energy: the run and the instant it falls (s).
fn overturns(model: &Model, motion: &Motion, block: &str) -> (pirqa::Response, f64) {
    let settings = RunSettings {
        log_events: true,
        ..RunSettings::default()
    };
    let r = pirqa::run(model, motion, &settings).unwrap();
    assert_eq!(r.summary.stopped_at_s, None, "{:?}", r.summary.warnings);
    let fell = r.summary.collapse.as_ref().expect("a block overturns");
    assert_eq!(fell.block, block);
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.friction_j + e.fallen_j.abs();
    assert!(e.residual_j.abs() <= 1e-13 * scale, "{e:?}");
    let fell_s = fell.time_s;
    (r, fell_s)
}

/// walls/rocking/slender-on-stack.ron under El Centro at 1.0 g: where the ground joint under
/// the rocking top reaches its friction, the stack (Base and Middle, as one) slides on the
/// ground and stops, twice, the top rocking on it, until the top overturns; the run balances
/// its energy to round-off, and Moreau-Jean with every block's rotation converges to it as the
/// step falls: the stack's slip and the instant the top falls.
#[test]
fn a_stack_sliding_under_a_rocking_block_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let motion = crate::engine::el_centro_first_s(5, 9.81);
    let (r, fell_s) = overturns(&model, &motion, "Top");
    let s = &r.summary;
    let on_ground = |kind: pirqa::response::EventKind| {
        r.events
            .iter()
            .filter(|e| e.kind == kind && e.joint.as_deref() == Some("Base/ground"))
            .count()
    };
    assert_eq!(
        (
            on_ground(pirqa::response::EventKind::Slip),
            on_ground(pirqa::response::EventKind::Stick)
        ),
        (2, 2)
    );
    let (base, middle) = (&s.blocks[0], &s.blocks[1]);
    assert_eq!(base.final_displacement_m, middle.final_displacement_m);
    assert!(base.final_displacement_m > 1e-3, "{base:?}");
    let mut last = (f64::INFINITY, f64::INFINITY);
    for dt_s in [1e-3, 3e-4, 1e-4] {
        let m = stepped(&model, &motion, dt_s);
        let slid = (m.blocks[0].final_displacement_m - base.final_displacement_m).abs();
        let late = (m.collapse.as_ref().unwrap().time_s - fell_s).abs();
        assert!(
            slid < last.0 && late < last.1,
            "dt {dt_s}: {slid} m, {late} s"
        );
        last = (slid, late);
    }
    assert!(last.0 < 2e-6 && last.1 < 1e-2, "{last:?}");
}

/// Moreau-Jean with every block's rotation run to the instant the exact run's top falls, at
/// each of `steps`: the differences of the stack's final u (m) and of the top's peak speed
/// (m/s) from the exact run's must both fall with the step and end below `bounds`.
fn converges_to_the_fall(
    model: &Model,
    motion: &Motion,
    exact: &Summary,
    fell_s: f64,
    steps: [f64; 3],
    bounds: (f64, f64),
) {
    let mut last = (f64::INFINITY, f64::INFINITY);
    for dt_s in steps {
        let settings = RunSettings {
            model: ModelChoice::SlideRock,
            method: Method::Moreau { dt_s },
            duration_s: Some(fell_s),
            ..RunSettings::default()
        };
        let m = pirqa::run(model, motion, &settings).unwrap().summary;
        let slid = (m.blocks[0].final_displacement_m - exact.blocks[0].final_displacement_m).abs();
        let speed = (m.blocks[2].max_abs_velocity_m_s - exact.blocks[2].max_abs_velocity_m_s).abs();
        assert!(
            slid < last.0 && speed < last.1,
            "dt {dt_s}: {slid} m, {speed} m/s"
        );
        last = (slid, speed);
    }
    assert!(last.0 < bounds.0 && last.1 < bounds.1, "{last:?}");
}

/// The same wall at 2.0 g: the top lands on the sliding stack at 1.842 s and the impact stops
/// the stack (the landing on a moving base, the stack's joint passing the impulse within its
/// friction); from 2.412 s the stack slides twice under the top as it slide-rocks, its pivot
/// slipping on the stack (until 2026-12-07 the run stopped there); from 2.475 s the pivot
/// slips on the stack the way the stack slides, Middle/Base exactly at its limit (until
/// 2026-12-07 the run stopped there too), and the top overturns at 2.489 s, the energy
/// balancing to round-off. Moreau-Jean run to that instant converges to it.
#[test]
fn a_landing_on_a_sliding_stack_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let motion = crate::engine::el_centro_first_s(5, 2.0 * 9.81);
    let (r, fell_s) = overturns(&model, &motion, "Top");
    let s = &r.summary;
    let landed = r
        .events
        .iter()
        .find(|e| {
            e.mode
                .as_deref()
                .is_some_and(|m| m.contains("on the sliding stack"))
        })
        .expect("a landing on the sliding stack");
    assert!((landed.time_s - 1.8418).abs() < 1e-4, "{landed:?}");
    let under = |e: &&pirqa::response::EventRecord| {
        e.mode
            .as_deref()
            .is_some_and(|m| m.contains("under Top slide-rocking"))
    };
    assert_eq!(r.events.iter().filter(under).count(), 2);
    assert!(fell_s > 2.48 && fell_s < 2.49, "{fell_s}");
    // The top's peak speed is 1.09 m/s, Moreau-Jean's first-order error at dt = 1e-3 s 7e-3.
    converges_to_the_fall(&model, &motion, s, fell_s, [1e-3, 1e-4, 1e-5], (1e-6, 1e-4));
}

/// The same wall at 1.2 g: from 2.616 s Base+Middle slide on the ground towards -x under the
/// top slide-rocking on its left corner, its pivot slipping on Middle towards -x too, every
/// joint at friction 0.8: Middle/Base passes up exactly its limit as long as both slip, its
/// holding and its slipping one motion (until 2026-12-07 the run stopped there, at 2.64 s).
/// The stack stops at 2.643 s and the top overturns at 2.672 s, the energy balancing to
/// round-off; Moreau-Jean run to that instant converges to it.
#[test]
fn a_joint_at_its_limit_inside_a_sliding_stack_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let motion = crate::engine::el_centro_first_s(5, 1.2 * 9.81);
    let (r, fell_s) = overturns(&model, &motion, "Top");
    let s = &r.summary;
    let with =
        |what: &str| (r.events.iter()).any(|e| e.mode.as_deref().is_some_and(|m| m.contains(what)));
    assert!(with("slipping -x on the stack"));
    assert!(with(
        "towards -x (M = 2600 kg, mu = 0.8) under Top slide-rocking"
    ));
    assert!(fell_s > 2.67 && fell_s < 2.68, "{fell_s}");
    converges_to_the_fall(
        &model,
        &motion,
        s,
        fell_s,
        [1e-3, 1e-4, 2.5e-5],
        (5e-7, 1e-3),
    );
}

/// walls/rocking/top-on-slipping-blocks.ron, a slender top on two blocks whose joints slip
/// under it (friction 0.4 on the ground, 0.35 between them), under El Centro at 1.6 g: the stack under the top splits where the joint
/// inside it slips (M sliding on P as P slides), joins again where that slip stops, and gains a
/// stack at its bottom where the lower joint slips under the upper one's slide; the top
/// overturns at 3.3315 s, the energy balancing to round-off, and Moreau-Jean converges to it.
#[test]
fn stacks_that_split_and_join_under_a_rocking_block_are_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/top-on-slipping-blocks.ron").unwrap();
    let motion = crate::engine::el_centro_first_s(5, 1.6 * 9.81);
    let (r, fell_s) = overturns(&model, &motion, "T");
    let s = &r.summary;
    for what in [
        "on P, sliding too",
        "sliding on with the stack under it",
        "under the stacks sliding on it",
    ] {
        assert!(
            (r.events.iter()).any(|e| e.mode.as_deref().is_some_and(|m| m.contains(what))),
            "{what}"
        );
    }
    let mut last = [f64::INFINITY; 2];
    for dt_s in [1e-3, 3e-4, 1e-4] {
        let m = stepped(&model, &motion, dt_s);
        let errors = [0, 1]
            .map(|k| (m.blocks[k].final_displacement_m - s.blocks[k].final_displacement_m).abs());
        assert!(
            errors[0] < last[0] && errors[1] < last[1],
            "dt {dt_s}: {errors:?} m"
        );
        last = errors;
        if dt_s == 1e-4 {
            let late = (m.collapse.as_ref().unwrap().time_s - fell_s).abs();
            assert!(late < 5e-4, "dt {dt_s}: falls {late} s apart");
        }
    }
    assert!(last[0] < 2e-5 && last[1] < 5e-5, "{last:?}");
}

/// How far Moreau-Jean with every block's rotation at `dt_s` is from an exact run: the largest
/// difference of the blocks' displacements at `at_s` (the exact run's summary to then given;
/// its blocks, from the bottom, are those compared) and of the instant a block falls (`fell_s`
/// the exact one's; infinite where none falls).
fn stepped_apart(
    model: &Model,
    motion: &Motion,
    (exact, at_s): (&Summary, f64),
    fell_s: f64,
    dt_s: f64,
) -> (f64, f64) {
    let settings = RunSettings {
        model: ModelChoice::SlideRock,
        method: Method::Moreau { dt_s },
        ..RunSettings::default()
    };
    let fell = pirqa::run(model, motion, &settings)
        .unwrap()
        .summary
        .collapse;
    let late = fell.map_or(f64::INFINITY, |c| (c.time_s - fell_s).abs());
    (moved_apart(model, motion, (exact, at_s), dt_s), late)
}

/// Moreau-Jean's distance from an exact run ([`stepped_apart`]) at each of `steps_s`: both the
/// displacements' and the fall's fall with the step; the last pair.
fn converges_with_the_step(
    model: &Model,
    motion: &Motion,
    exact: (&Summary, f64),
    fell_s: f64,
    steps_s: [f64; 3],
) -> (f64, f64) {
    let mut last = (f64::INFINITY, f64::INFINITY);
    for dt_s in steps_s {
        let (moved, late) = stepped_apart(model, motion, exact, fell_s, dt_s);
        assert!(
            moved < last.0 && late < last.1,
            "dt {dt_s}: {moved} m, {late} s"
        );
        last = (moved, late);
    }
    last
}

/// The largest difference of the blocks' displacements at `at_s` between Moreau-Jean with
/// every block's rotation at `dt_s` and an exact run (its summary to then; its blocks, from
/// the bottom, are those compared).
fn moved_apart(model: &Model, motion: &Motion, (exact, at_s): (&Summary, f64), dt_s: f64) -> f64 {
    let settings = RunSettings {
        model: ModelChoice::SlideRock,
        method: Method::Moreau { dt_s },
        duration_s: Some(at_s),
        ..RunSettings::default()
    };
    let m = pirqa::run(model, motion, &settings).unwrap().summary;
    (m.blocks.iter().zip(&exact.blocks))
        .map(|(a, b)| (a.final_displacement_m - b.final_displacement_m).abs())
        .fold(0.0, f64::max)
}

/// The exact run of `model` to `at_s`, and Moreau-Jean's distance from it there
/// ([`moved_apart`]) at steps of 1e-4, 2.5e-5 and 1e-5 s, which must fall with the step: the
/// exact run's summary and the last distance (m). `what` names the case in a failure.
fn moved_apart_falls(model: &Model, motion: &Motion, at_s: f64, what: &str) -> (Summary, f64) {
    let upto = RunSettings {
        duration_s: Some(at_s),
        ..RunSettings::default()
    };
    let exact = pirqa::run(model, motion, &upto).unwrap().summary;
    let mut last = f64::INFINITY;
    for dt_s in [1e-4, 2.5e-5, 1e-5] {
        let moved = moved_apart(model, motion, (&exact, at_s), dt_s);
        assert!(moved < last, "{what}, dt {dt_s}: {moved} m");
        last = moved;
    }
    (exact, last)
}

/// A chain of open joints on a joint that slips: walls/rocking/rough-tapered-column.ron under
/// a 1.5 g, 2 Hz sine tips on the ground as its top rocks on the middle block, and the
/// column's pivot corner slips on the ground from 0.058 s to 0.278 s (59.8 mm);
/// walls/rocking/stepped-column.ron under a 1.1 g, 2 Hz sine rocks on the middle block's
/// joint and its top's, and the plinth under the chain slides on the ground from 0.083 s to
/// 0.215 s (6.7 mm). Until 2026-12-07 both runs stopped where the slip began. Each now stops
/// later, where the chain meets what it does not follow (the ground pivot slipping again while
/// the top's slips on the middle block; the middle block's pivot slipping just after a landing
/// whose impulse tips the plinth), its energy balanced to round-off, and Moreau-Jean converges
/// to it: every block's displacement after the slip under the chain stopped.
#[test]
fn a_chain_on_a_slipping_joint_is_what_time_stepping_converges_to() {
    for (wall, amplitude_g, stops_s, at_s, slid_m, bound_m) in [
        (
            "rough-tapered-column",
            1.5,
            0.30926,
            0.27,
            -5.984333e-2,
            5e-6,
        ),
        ("stepped-column", 1.1, 0.22416, 0.21, -6.705228e-3, 2e-6),
    ] {
        let model = Model::from_file(format!("walls/rocking/{wall}.ron")).unwrap();
        let motion = sine(amplitude_g * 9.81, 2.0, 2.0);
        let settings = RunSettings {
            log_events: true,
            ..RunSettings::default()
        };
        let r = pirqa::run(&model, &motion, &settings).unwrap();
        let stopped = r.summary.stopped_at_s.expect("a stop beyond the chain");
        assert!((stopped - stops_s).abs() < 1e-5, "{wall}: {stopped}");
        let slid: Vec<&str> = (r.events.iter())
            .filter(|e| {
                matches!(
                    e.kind,
                    pirqa::response::EventKind::Slip | pirqa::response::EventKind::Stick
                )
            })
            .filter_map(|e| e.mode.as_deref())
            .filter(|m| m.contains("the chain") && !m.contains("inside the chain"))
            .collect();
        assert_eq!(slid.len(), 2, "{wall}: {slid:?}");
        let stop = format!("having slid {slid_m:.6e} m");
        assert!(slid[1].contains(&stop), "{wall}: {slid:?}");
        let e = &r.summary.energy;
        let scale = e.input_j.abs() + e.friction_j;
        assert!(e.residual_j.abs() <= 1e-13 * scale, "{wall}: {e:?}");
        let (_, last) = moved_apart_falls(&model, &motion, at_s, wall);
        assert!(last < bound_m, "{wall}: {last} m");
    }
}

/// A pivot above the lowest that slips: walls/rocking/rough-tapered-column.ron under a 1.5 g,
/// 2 Hz sine, its column tipped on the ground and its top rocking on the middle block, whose
/// joint opened at 0.278 s: at 0.289 s the top's pivot corner slips on the middle block's
/// turned face (until 2026-12-07 the run stopped there), until at 0.309 s the ground pivot
/// would slip too (two slips, not followed). The energy balances to round-off, and Moreau-Jean
/// converges to it: every block's displacement at 0.30 s, 11 ms into the slip.
#[test]
fn a_slip_inside_the_chain_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/rough-tapered-column.ron").unwrap();
    let motion = sine(1.5 * 9.81, 2.0, 2.0);
    let settings = RunSettings {
        log_events: true,
        ..RunSettings::default()
    };
    let r = pirqa::run(&model, &motion, &settings).unwrap();
    let inside: Vec<f64> = (r.events.iter())
        .filter(|e| {
            (e.mode.as_deref())
                .is_some_and(|m| m.starts_with("D2 slip on D2/D1 inside the chain towards -x"))
        })
        .map(|e| e.time_s)
        .collect();
    assert!(
        inside.len() == 1 && (inside[0] - 0.28901).abs() < 1e-5,
        "{inside:?}"
    );
    let stopped = r.summary.stopped_at_s.expect("a second slip, not followed");
    assert!((stopped - 0.30926).abs() < 1e-5, "{stopped}");
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.friction_j;
    assert!(e.residual_j.abs() <= 1e-13 * scale, "{e:?}");
    let (_, last) = moved_apart_falls(&model, &motion, 0.30, "the top's slip");
    assert!(last < 1e-5, "{last} m");
}

/// walls/rocking/top-on-slipping-blocks.ron under El Centro at 1.0 g: at 2.238 s the top lands
/// on the two blocks under it as M slides on P and P on the ground, and the impact stops both
/// slips (until 2026-12-07 the run stopped there, the landing not followed); the top overturns
/// at 5.003 s, the energy balancing to round-off. Moreau-Jean converges to it: the three
/// blocks' displacements at 3 s, after the landing, and the instant the top falls.
#[test]
fn a_landing_on_stacks_sliding_on_stacks_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/top-on-slipping-blocks.ron").unwrap();
    let motion = crate::engine::el_centro_first_s(6, 9.81);
    let (r, fell_s) = overturns(&model, &motion, "T");
    let landed = (r.events.iter())
        .find(|e| {
            e.mode
                .as_deref()
                .is_some_and(|m| m.contains("on the sliding stacks"))
        })
        .expect("a landing on stacks sliding on stacks");
    assert!((landed.time_s - 2.2379).abs() < 1e-4, "{landed:?}");
    let what = landed.mode.as_deref().unwrap_or_default();
    assert!(
        what.contains("the slip on M/P and P/ground stops"),
        "{what}"
    );
    assert!((fell_s - 5.003).abs() < 1e-3, "{fell_s}");
    let settings = RunSettings {
        duration_s: Some(3.0),
        ..RunSettings::default()
    };
    let exact = pirqa::run(&model, &motion, &settings).unwrap().summary;
    let mut last = (f64::INFINITY, f64::INFINITY);
    for dt_s in [1e-3, 1e-4, 2.5e-5] {
        let (moved, late) = stepped_apart(&model, &motion, (&exact, 3.0), fell_s, dt_s);
        if dt_s < 1e-3 {
            assert!(
                moved < last.0 && late < last.1,
                "dt {dt_s}: {moved} m, {late} s"
            );
        }
        last = (moved, late);
    }
    assert!(last.0 < 3e-5 && last.1 < 1e-3, "{last:?}");
}

/// walls/rocking/slender-on-slipping-blocks.ron, a slender top (0.2 by 0.8 m) on two squat
/// blocks (1.0 by 0.5 m; friction 0.4 on the ground, 0.35 between them) under El Centro at
/// 1.4 g: at 1.758 s the top lands on the two as the
/// upper slides on the lower and the lower on the ground, the impact stopping the upper's slip
/// alone (the two slide on as one); at 2.480 s the upper stops slipping on the lower and at
/// once slips again, the other way, the force on it beyond the joint's friction (until
/// 2026-12-07 both stopped the run). The top overturns at 2.533 s, the energy balancing to
/// round-off, and Moreau-Jean converges to it: every block's displacement at that instant and
/// the instant it falls.
#[test]
fn a_stack_that_stops_slipping_and_slips_back_at_once_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/slender-on-slipping-blocks.ron").unwrap();
    let motion = crate::engine::el_centro_first_s(4, 1.4 * 9.81);
    let (r, fell_s) = overturns(&model, &motion, "D2");
    let at = |what: &str| {
        (r.events.iter())
            .filter(|e| e.mode.as_deref().is_some_and(|m| m.contains(what)))
            .map(|e| e.time_s)
            .collect::<Vec<_>>()
    };
    let landed = at("the slip on D1/D0 stops");
    assert!(
        landed.len() == 1 && (landed[0] - 1.7580).abs() < 1e-4,
        "{landed:?}"
    );
    let stopped = at("stops slipping on D1/D0");
    assert!(!stopped.is_empty());
    let again = at("D1 slide on D1/D0 towards -x");
    assert!(
        stopped.iter().any(|t| again.contains(t)),
        "{stopped:?} {again:?}"
    );
    assert!((fell_s - 2.5334).abs() < 1e-4, "{fell_s}");
    let last = converges_with_the_step(
        &model,
        &motion,
        (&r.summary, fell_s),
        fell_s,
        [1e-3, 1e-4, 2.5e-5],
    );
    assert!(last.0 < 1e-5 && last.1 < 2e-4, "{last:?}");
}

/// walls/rocking/tapered-column.ron (a slender top on two blocks, each narrower than the one
/// under it; friction 0.4 on the ground, 0.35 between the two) under a 0.5 g, 1.5 Hz sine: at
/// 0.527 s the top lands on the middle block, held on the base as the base is on the ground,
/// and just after the impact the ground joint would slip if the middle block held on the base;
/// with the base slipping too the middle block would slip on it the other way, and with both
/// slipping the base would not move as assumed; the middle block slips alone, the base held
/// (until 2026-12-07 no way held and the run stopped there). The top overturns at 1.580 s, the
/// energy balancing to round-off, and Moreau-Jean converges to it: the two lower blocks'
/// displacements at 1.5 s and the instant the top falls.
#[test]
fn a_joint_inside_a_stack_slipping_alone_after_a_landing_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/tapered-column.ron").unwrap();
    let motion = sine(0.5 * 9.81, 1.5, 6.0);
    let (r, fell_s) = overturns(&model, &motion, "D2");
    let at = |what: &str| {
        (r.events.iter())
            .filter(|e| e.mode.as_deref().is_some_and(|m| m.contains(what)))
            .map(|e| e.time_s)
            .collect::<Vec<_>>()
    };
    let landed: Vec<f64> = (r.events.iter())
        .filter(|e| e.kind == pirqa::response::EventKind::RockingImpact)
        .map(|e| e.time_s)
        .collect();
    assert!(
        landed.len() == 1 && (landed[0] - 0.52671).abs() < 1e-5,
        "{landed:?}"
    );
    let alone = at("D1 slide on D1/D0 towards +x");
    assert_eq!(alone.first(), landed.first(), "{alone:?}");
    assert!((fell_s - 1.57979).abs() < 1e-5, "{fell_s}");
    // The two blocks whose slips the landing decided, compared before the fall: the top's
    // rotation, turning fast, comes within 1e-4 rad at these steps but not monotonically.
    let settings = RunSettings {
        duration_s: Some(1.5),
        ..RunSettings::default()
    };
    let mut before = pirqa::run(&model, &motion, &settings).unwrap().summary;
    before.blocks.truncate(2);
    let last = converges_with_the_step(
        &model,
        &motion,
        (&before, 1.5),
        fell_s,
        [1e-3, 1e-4, 2.5e-5],
    );
    assert!(last.0 < 1e-5 && last.1 < 2e-4, "{last:?}");
}

/// walls/rocking/stepped-column.ron under a 1.5 g, 2 Hz sine: the middle block's joint opens
/// under the rocking top at 0.051 s and the plinth slides under the chain from 0.055 s; at
/// 0.237 s the middle block lands seated on the sliding plinth, the slip going on through the
/// impact at the ground joint's friction limit (until 2026-12-07 the run stopped there), and
/// the chain, down to the top's joint, hands the column back to the stack model: the plinth and
/// the middle block slide under the rocking top, stop and slide again until the top overturns
/// at 0.912 s. The energy balances to round-off, and Moreau-Jean converges to it: every block's
/// displacement at 0.85 s and the instant the top falls.
#[test]
fn a_chain_landing_on_its_sliding_plinth_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/stepped-column.ron").unwrap();
    let motion = sine(1.5 * 9.81, 2.0, 2.0);
    let (r, fell_s) = overturns(&model, &motion, "D2");
    assert!((fell_s - 0.91220).abs() < 1e-5, "{fell_s}");
    let landed: Vec<f64> = (r.events.iter())
        .filter(|e| e.mode.as_deref() == Some("D1/D0 lands seated"))
        .map(|e| e.time_s)
        .collect();
    assert!(
        landed.len() == 1 && (landed[0] - 0.23738).abs() < 1e-5,
        "{landed:?}"
    );
    let stack = (r.events.iter())
        .filter_map(|e| e.mode.as_deref())
        .any(|m| m.starts_with("D0+D1 slide on D0/ground"));
    assert!(stack);
    let settings = RunSettings {
        duration_s: Some(0.85),
        ..RunSettings::default()
    };
    let before = pirqa::run(&model, &motion, &settings).unwrap().summary;
    let last = converges_with_the_step(
        &model,
        &motion,
        (&before, 0.85),
        fell_s,
        [1e-4, 2.5e-5, 1e-5],
    );
    assert!(last.0 < 1e-5 && last.1 < 5e-5, "{last:?}");
}

/// walls/rocking/column-on-plinth.ron under a 1.1 g, 2 Hz sine: the column rocks on the
/// plinth sliding under it, and at 1.433 s and 2.215 s lands on it with an impulse that tips
/// the plinth on a corner, the slip going on through the impact (until 2026-12-07 the run
/// stopped at the first, the impact not followed); each time the plinth lands seated a few
/// milliseconds later. The run goes to its end with nothing falling, the energy balancing to
/// round-off, and Moreau-Jean converges to it: both blocks' displacements at 1.6 s, after the
/// first landing.
#[test]
fn a_landing_that_tips_the_sliding_plinth_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/column-on-plinth.ron").unwrap();
    let motion = sine(1.1 * 9.81, 2.0, 3.0);
    let settings = RunSettings {
        log_events: true,
        ..RunSettings::default()
    };
    let r = pirqa::run(&model, &motion, &settings).unwrap();
    let s = &r.summary;
    assert!(s.stopped_at_s.is_none() && s.collapse.is_none(), "{s:?}");
    let at = |what: &str| {
        (r.events.iter())
            .filter(|e| e.mode.as_deref().is_some_and(|m| m.starts_with(what)))
            .map(|e| e.time_s)
            .collect::<Vec<_>>()
    };
    let opened = at("opens through the landing: Plinth/ground");
    let [first, second] = opened[..] else {
        panic!("{opened:?}");
    };
    assert!((first - 1.43341).abs() < 1e-5 && (second - 2.21484).abs() < 1e-5);
    let landed = at("Column/Plinth lands on its");
    assert!(
        landed.contains(&first) && landed.contains(&second),
        "{landed:?}"
    );
    let seated = at("Plinth/ground lands seated");
    assert!(seated.len() == 2 && seated[0] - first < 3e-3 && seated[1] - second < 4e-3);
    let e = &s.energy;
    let scale = e.input_j.abs() + e.friction_j;
    assert!(e.residual_j.abs() <= 1e-13 * scale, "{e:?}");
    let (_, last) = moved_apart_falls(&model, &motion, 1.6, "column on a plinth");
    assert!(last < 5e-6, "{last} m");
}

/// walls/rocking/stepped-column.ron under El Centro at 1.0 g: at 2.144 s the top lands on the
/// plinth and block sliding under it, the impact stopping their slip, and at once the ground
/// joint would slip again where the block on the plinth would tip; the plinth slides alone
/// under the chain, the block's joint on it opening as the slip begins (until 2026-12-07 the
/// run stopped there, no way of the sliding stack holding). The top overturns at 3.061 s, the
/// energy balancing to round-off, and Moreau-Jean converges to it: every block's displacement
/// at 2.5 s, and the instant the top falls within 1e-4 s at the finest step.
#[test]
fn a_slip_that_opens_the_joint_above_it_is_what_time_stepping_converges_to() {
    let model = Model::from_file("walls/rocking/stepped-column.ron").unwrap();
    let motion = crate::engine::el_centro_first_s(4, 9.81);
    let (r, fell_s) = overturns(&model, &motion, "D2");
    let at = |what: &str| {
        (r.events.iter())
            .filter(|e| e.mode.as_deref().is_some_and(|m| m.starts_with(what)))
            .map(|e| e.time_s)
            .collect::<Vec<_>>()
    };
    let slips = at("D0 (M = 1560 kg) slides under the chain on D0/ground towards +x");
    assert!(
        slips.len() == 1 && (slips[0] - 2.14419).abs() < 1e-5,
        "{slips:?}"
    );
    assert_eq!(at("opens as the slip begins: D1/D0"), slips);
    assert!((fell_s - 3.06069).abs() < 1e-5, "{fell_s}");
    let (exact, last) = moved_apart_falls(&model, &motion, 2.5, "stepped column");
    assert!(last < 1e-6, "{last} m");
    let (_, late) = stepped_apart(&model, &motion, (&exact, 2.5), fell_s, 1e-5);
    assert!(late < 1e-4, "{late} s");
}

/// A squat block sliding on another (joint friction 0.2) that stands on the ground (0.3), both
/// of mass m, under 0.5 g sin(2 pi t): the top slides from a_g = 0.2 g with its friction
/// pushing it forward, so the ground joint carries m a_g + 0.2 m g, which reaches its capacity
/// 0.3 (2 m) g at a_g = 0.4 g: at t = asin(0.8) / (2 pi), where the run stops and says the
/// held joint would slip with the lower block lagging.
#[test]
fn a_held_joint_gives_way_where_the_closed_form_says() {
    let model = two_blocks(
        "thickness_m: 1.0, density_kg_m3: 2500, friction: 0.3",
        0.2,
        [(2.0, 0.5, "Base"), (2.0, 0.5, "Top")],
    );
    let motion = sine(0.5 * 9.81, 1.0, 1.0);
    let s = exact(&model, &motion, ModelChoice::SlideRock);
    let (t, joint, how) = gave_way(&s);
    let closed = 0.8f64.asin() / (2.0 * std::f64::consts::PI);
    assert!((t - closed).abs() < 1e-12, "{t} against {closed}");
    assert_eq!(joint, "Base/ground");
    assert!(
        how.starts_with("would slip, the block on it towards -x"),
        "{how}"
    );
    assert_eq!(s.duration_s, t);
    assert!(s.blocks[1].max_abs_displacement_m > 0.0);
    assert_eq!(s.blocks[0].max_abs_displacement_m, 0.0);
}

/// A two-block column whose inner joint has friction 0.2 rocks as one body on the ground
/// (0.3 g, 1.5 Hz) until the exact model finds that joint would slip; Moreau-Jean with every
/// block's rotation (dt = 2.5e-5 s) sees the upper block start to slide on the lower one
/// (its base leaving where the turning lower block carries it by more than a micrometre)
/// within 10 ms after that instant, and not before.
#[test]
fn a_joint_inside_the_moving_body_slips_when_time_stepping_sees_it() {
    let model = two_blocks(
        "thickness_m: 0.5, density_kg_m3: 2650, friction: 0.7",
        0.2,
        [(0.5, 1.5, "Drum1"), (0.5, 1.5, "Drum2")],
    );
    let motion = sine(0.3 * 9.81, 1.5, 0.6);
    let s = exact(&model, &motion, ModelChoice::SlideRock);
    let (t, joint, how) = gave_way(&s);
    assert_eq!(joint, "Drum2/Drum1");
    assert!(how.contains("slip"), "{how}");
    let r = with_history(&model, &motion, Method::Moreau { dt_s: 2.5e-5 }, 1e-3);
    let h = r.history.unwrap();
    let slip_start = h
        .time_s
        .iter()
        .zip(h.displacement_m.iter().zip(&h.rotation_rad))
        .find(|(_, (u, th))| (u[1] - u[0] - 1.5 * th[0].sin()).abs() > 1e-6)
        .map(|(t, _)| *t)
        .expect("the upper block slides in the time-stepped run");
    assert!(
        slip_start > t && slip_start < t + 0.01,
        "slides from {slip_start} s, exact {t} s"
    );
}

/// On the three columns of walls/rocking/ under 0.28 g, 1.5 Hz for 3 s (the top of the
/// stack, the whole two-block column, the standing stone on its plinth rock; nothing falls),
/// Moreau-Jean with every block's rotation converges to the exact column model: the largest
/// error in any block top's u(t) falls with each fourfold cut of the step from 1e-3 s, at
/// least halving from 2.5e-4 to 6.25e-5 s, to a few millimetres (rocking amplitudes of
/// 0.05-0.2 m). The committed chart (docs/figures/work-precision-rocking-walls.svg) carries
/// the ladder down to 1e-5 s under El Centro.
#[test]
fn time_stepping_converges_to_the_exact_column_model() {
    let motion = sine(0.28 * 9.81, 1.5, 3.0);
    for file in [
        "slender-on-stack",
        "two-block-column",
        "huanca-on-plinth",
        "trilith",
    ] {
        let model = Model::from_file(format!("walls/rocking/{file}.ron")).unwrap();
        let reference = with_history(&model, &motion, Method::Event, 0.01);
        let s = &reference.summary;
        assert!(s.warnings.is_empty() && s.collapse.is_none(), "{file}");
        assert!(s.blocks.iter().any(|b| b.uplift_time_s.is_some()), "{file}");
        let err = |dt_s: f64| {
            let r = with_history(&model, &motion, Method::Moreau { dt_s }, 0.01);
            rocking_errors(&r, &reference, model.wall()).1
        };
        let e = [err(1e-3), err(2.5e-4), err(6.25e-5)];
        assert!(
            e[1] < e[0] && e[2] < e[1] / 2.0 && e[2] < 5e-3,
            "{file}: {e:?} m"
        );
    }
}

/// The two-block column released from 0.1 rad on still ground (`--initial-rotation Drum2=0.1`:
/// a block of the body names it) rocks as its body standing alone: every landing at the same
/// instant and with the same angular velocities, to round-off, the joint between the drums
/// held through them (its friction 0.7 carries the landing impulses). A held block cannot be
/// released, nor can two blocks.
#[test]
fn a_column_released_from_a_rotation_rocks_as_its_body_alone() {
    use pirqa::integrate::rocking::{self, columns, Scene};
    use pirqa::response::EventKind;
    let model = Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let body = columns(model.wall(), model.topology()).unwrap()[0]
        .body
        .clone();
    let motion = Motion::Pulse(pirqa::Pulse::rest());
    let settings = RunSettings {
        initial_rotation: vec![("Drum2".into(), 0.1)],
        duration_s: Some(5.0),
        log_events: true,
        ..RunSettings::default()
    };
    let column = pirqa::run(&model, &motion, &settings).unwrap();
    let alone = rocking::run(&Scene {
        bodies: std::slice::from_ref(&body),
        watches: &[],
        wall: None,
        initial_rotation_rad: &[0.1],
        equations: pirqa::Equations::Exact,
        motion: &motion,
        settings: &pirqa::integrate::Settings {
            log_events: true,
            ..pirqa::integrate::Settings::summary_only(5.0)
        },
    })
    .unwrap();
    let landings = |r: &Response| -> Vec<(f64, f64)> {
        r.events
            .iter()
            .filter(|e| e.kind == EventKind::RockingImpact)
            .map(|e| (e.time_s, e.angular_velocity_after_rad_s.unwrap()))
            .collect()
    };
    let (a, b) = (landings(&column), landings(&alone));
    assert!(a.len() >= 4 && a.len() == b.len(), "{a:?} against {b:?}");
    for ((t, w), (s, x)) in a.iter().zip(&b) {
        assert!(
            (t - s).abs() < 1e-12 && (w - x).abs() < 1e-12,
            "{t} {w} against {s} {x}"
        );
    }
    assert!(column.summary.warnings.is_empty());
    for (released, expect) in [
        (vec![("Drum1".to_string(), 0.1)], None),
        (
            vec![("Drum1".to_string(), 0.1), ("Drum2".to_string(), 0.1)],
            Some("give one"),
        ),
    ] {
        let settings = RunSettings {
            initial_rotation: released,
            ..settings.clone()
        };
        match (pirqa::run(&model, &motion, &settings), expect) {
            (Ok(r), None) => assert_eq!(landings(&r), a),
            (Err(e), Some(words)) => assert!(e.to_string().contains(words), "{e}"),
            (r, _) => panic!("{:?}", r.map(|r| r.summary.model)),
        }
    }
    let stack = Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let held = RunSettings {
        initial_rotation: vec![("Base".into(), 0.1)],
        ..settings
    };
    let e = pirqa::run(&stack, &motion, &held).unwrap_err().to_string();
    assert!(
        e.contains("Base does not move with the column's body Top"),
        "{e}"
    );
}

/// Two squat blocks of one friction (0.3) under 0.5 g: the column slides as one on the ground
/// and the joint between the blocks sits exactly at its friction limit all the while (the
/// upper block needs mu m g to follow the lower one's mu g): a tie, not a joint giving way. The
/// column model then gives the exact sliding engine's answer, every block's largest and final
/// displacement to 1e-12 m.
#[test]
fn a_column_sliding_as_one_is_the_sliding_engines_answer() {
    let model = two_blocks(
        "thickness_m: 1.0, density_kg_m3: 2500, friction: 0.3",
        0.3,
        [(2.0, 0.5, "A"), (2.0, 0.5, "B")],
    );
    let motion = sine(0.5 * 9.81, 1.0, 5.0);
    let column = exact(&model, &motion, ModelChoice::SlideRock);
    let sliding = exact(&model, &motion, ModelChoice::Slide);
    assert_eq!(column.model.name, "slide-rock");
    assert!(column.warnings.is_empty(), "{:?}", column.warnings);
    for (c, s) in column.blocks.iter().zip(&sliding.blocks) {
        assert!(
            (c.max_abs_displacement_m - s.max_abs_displacement_m).abs() < 1e-12
                && (c.final_displacement_m - s.final_displacement_m).abs() < 1e-12,
            "{c:?} against {s:?}"
        );
        assert!(c.max_abs_displacement_m > 0.05);
    }
}

/// Moreau-Jean starts a released column where the exact model does (the body turned about the
/// end of its base: the same initial energy to 1e-12 of itself), and converges to it: over 3 s
/// of free rocking of the two-block column from 0.1 rad, the energy lost (the exact model's
/// two landings) and the upper drum's final displacement come fourfold closer to the exact
/// ones from dt = 1e-3 to 6.25e-5 s.
#[test]
fn time_stepping_releases_a_column_as_the_exact_model_does() {
    let model = Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let motion = Motion::Pulse(pirqa::Pulse::rest());
    let settings = |method: Method| RunSettings {
        initial_rotation: vec![("Drum1".into(), 0.1)],
        duration_s: Some(3.0),
        model: ModelChoice::SlideRock,
        method,
        ..RunSettings::default()
    };
    let exact = pirqa::run(&model, &motion, &settings(Method::Event))
        .unwrap()
        .summary;
    let errors = |dt_s: f64| {
        let s = pirqa::run(&model, &motion, &settings(Method::Moreau { dt_s }))
            .unwrap()
            .summary;
        let e = (s.energy.initial_j - exact.energy.initial_j).abs();
        assert!(e < 1e-12 * exact.energy.initial_j, "{e}");
        let lost = s.energy.friction_j + s.energy.impact_loss_j;
        (
            (lost - exact.energy.impact_loss_j).abs(),
            (s.blocks[1].final_displacement_m - exact.blocks[1].final_displacement_m).abs(),
        )
    };
    let (coarse, fine) = (errors(1e-3), errors(6.25e-5));
    assert!(
        fine.0 < coarse.0 / 4.0 && fine.1 < coarse.1 / 4.0,
        "{coarse:?} -> {fine:?}"
    );
}

/// A rocking run tells its progress the time reached and stops when asked (Ctrl-C, a
/// notebook's interrupt): the exact column model and the time-stepped wall end where the stop
/// found them, their summaries saying when, the time-stepped wall at its next step (a step of
/// a large wall takes long: it used to look every 1,024); unasked, both run to the end and
/// report it.
#[test]
fn rocking_runs_report_progress_and_stop_when_asked() {
    use pirqa::integrate::Progress;
    use std::sync::atomic::{AtomicBool, Ordering};
    use std::sync::{Arc, Mutex};
    let model = Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let motion = sine(0.28 * 9.81, 1.5, 3.0);
    for method in [Method::Event, Method::Moreau { dt_s: 1e-3 }] {
        let seen = Arc::new(Mutex::new(0.0f64));
        let stop = Arc::new(AtomicBool::new(false));
        let run = |stop: Arc<AtomicBool>| {
            let seen = seen.clone();
            let progress = Progress::new(move |t| {
                let mut s = seen.lock().unwrap();
                *s = s.max(t);
            })
            .with_stop(stop);
            let settings = RunSettings {
                model: ModelChoice::SlideRock,
                method: method.clone(),
                progress: Some(progress),
                ..RunSettings::default()
            };
            pirqa::run(&model, &motion, &settings).unwrap().summary
        };
        let full = run(stop.clone());
        assert_eq!(full.interrupted_at_s, None, "{method:?}");
        assert!(*seen.lock().unwrap() > 2.9, "{method:?}");
        stop.store(true, Ordering::Relaxed);
        let cut = run(stop);
        let at = cut.interrupted_at_s.expect("the run stops when asked");
        let within = match method {
            Method::Moreau { dt_s } => dt_s,
            _ => 1.1,
        };
        assert!(
            at <= within && cut.duration_s <= at + 1e-9,
            "{method:?}: {at} {}",
            cut.duration_s
        );
    }
}

/// A column on a fixed plinth is the same column on the ground: under `auto` its run lists
/// every block of the wall in the wall's order, the plinth at rest with the ground's peak
/// acceleration, the column's blocks moving as they do on the ground (to the last bit: the
/// same equations), and its events (the uplift on the plinth, the held joint that gives way
/// inside the column and the chain that follows) name the joints they happen on.
#[test]
fn a_column_on_an_abutment_is_the_column_on_the_ground_listed_with_the_wall() {
    let column = |plinth: &str| {
        Model::from_ron_str(&format!(
            "(version: 1, thickness_m: 1.0, density_kg_m3: 2500, friction: 0.8,
              rows: [{plinth}
                     (height_m: 0.8, x_m: 0.4, blocks: [(width_m: 0.3, name: \"B\")]),
                     (height_m: 0.6, x_m: 0.45, blocks: [(width_m: 0.2, name: \"D\")])])"
        ))
        .unwrap()
    };
    let on_plinth = column("(height_m: 0.5, blocks: [(width_m: 3.0, name: \"P\", fixed: true)]),");
    let on_ground = column("");
    let motion = sine(0.4 * 9.81, 1.5, 4.0);
    let run = |model: &Model| {
        let settings = RunSettings {
            model: ModelChoice::Auto,
            output_dt_s: Some(0.05),
            log_events: true,
            ..RunSettings::default()
        };
        pirqa::run(model, &motion, &settings).unwrap()
    };
    let (p, g) = (run(&on_plinth), run(&on_ground));
    assert_eq!(p.summary.model.name, "slide-rock");
    let names: Vec<&str> = p.summary.blocks.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(names, ["P", "B", "D"]);
    let plinth = &p.summary.blocks[0];
    assert_eq!(
        (plinth.max_abs_displacement_m, plinth.max_abs_rotation_rad),
        (0.0, 0.0)
    );
    assert_eq!(plinth.max_abs_accel_m_s2, 0.4 * 9.81);
    for (a, b) in p.summary.blocks[1..].iter().zip(&g.summary.blocks) {
        assert_eq!(a.name, b.name);
        assert_eq!(a.max_abs_displacement_m, b.max_abs_displacement_m);
        assert_eq!(a.max_abs_rotation_rad, b.max_abs_rotation_rad);
        assert_eq!(a.uplift_time_s, b.uplift_time_s);
    }
    assert!(p.summary.blocks[2].max_abs_rotation_rad > 0.01);
    let joints = |r: &Response| -> Vec<(f64, Option<String>)> {
        r.events
            .iter()
            .map(|e| (e.time_s, e.joint.clone()))
            .collect()
    };
    let (jp, jg) = (joints(&p), joints(&g));
    // The column lifts on its base, then its top opens on B and rocks there (the chain of
    // open joints), the same joints on the plinth and on the ground.
    let on = |j: &[(f64, Option<String>)], base: &str| -> Vec<String> {
        j.iter()
            .map(|j| j.1.clone().unwrap().replace(base, "BASE"))
            .collect()
    };
    assert_eq!(on(&jp, "/P"), on(&jg, "/ground"));
    assert_eq!(on(&jp, "/P")[..2], ["BBASE", "D/B"]);
    assert_eq!(
        jp.iter().map(|j| j.0).collect::<Vec<_>>(),
        jg.iter().map(|j| j.0).collect::<Vec<_>>()
    );
    let (hp, hg) = (p.history.as_ref().unwrap(), g.history.as_ref().unwrap());
    assert_eq!(hp.time_s, hg.time_s);
    for (rp, rg) in [
        (&hp.displacement_m, &hg.displacement_m),
        (&hp.rotation_rad, &hg.rotation_rad),
    ] {
        for (a, b) in rp.iter().zip(rg) {
            assert_eq!((a[0], &a[1..]), (0.0, &b[..]));
        }
    }
    assert!(hp.rotation_rad.iter().any(|row| row[2].abs() > 1e-3));
}

/// Time stepping with rotations writes its history at the output times whatever its step (a
/// step of 3e-4 s does not divide 0.01 s), interpolated between steps: the rows fall on the
/// exact model's sample times, so the two are compared at the same instants, and a row between
/// two steps lies on the chord between them.
#[test]
fn time_stepping_with_rotations_writes_its_history_at_the_output_times() {
    let model = Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let motion = sine(0.3 * 9.81, 1.5, 1.0);
    let stepped = with_history(&model, &motion, Method::Moreau { dt_s: 3e-4 }, 0.01);
    let h = stepped.history.as_ref().unwrap();
    let expected: Vec<f64> = (0..=100).map(|k| k as f64 * 0.01).collect();
    assert_eq!(h.time_s, expected);
    let exact = with_history(&model, &motion, Method::Event, 0.01);
    let times = &exact.history.as_ref().unwrap().time_s;
    assert!(h.time_s.iter().all(|t| times.contains(t)));
    // The row at 0.5 s lies between the steps at 1666 dt and 1667 dt, on their chord.
    let fine = with_history(&model, &motion, Method::Moreau { dt_s: 3e-4 }, 3e-4);
    let f = fine.history.as_ref().unwrap();
    let (t0, t1) = (1666.0 * 3e-4, 1667.0 * 3e-4);
    assert_eq!((f.time_s[1666], f.time_s[1667]), (t0, t1));
    let w = (0.5 - t0) / (t1 - t0);
    for (rows, row) in [
        (&f.rotation_rad, &h.rotation_rad[50]),
        (&f.displacement_m, &h.displacement_m[50]),
    ] {
        for (i, &x) in row.iter().enumerate() {
            let (a, b) = (rows[1666][i], rows[1667][i]);
            assert!(a != 0.0 && b != a, "{a} {b}");
            assert!(
                (x - (a + w * (b - a))).abs() <= 1e-15 * x.abs(),
                "{x} against {a}, {b}"
            );
        }
    }
}

/// walls/rocking/trilith.ron (a lintel of a column's mass: gamma = M / 2m = 1/2) released
/// from 0.1 rad on still ground rocks with Makris and Vassiliou's (2013) numbers for a frame:
/// with the linearised equations its first landing comes at arccosh(alpha / (alpha - theta0))
/// / p_frame (p_frame^2 = 3 g / 4R (1 + 2 gamma) / (1 + 3 gamma), R and alpha of a column);
/// with the exact ones it lands at the angular velocity that energy gives, 2 p_frame^2
/// (cos(alpha - theta0) - cos alpha), and leaves at r_frame = (1 - 1.5 sin^2 alpha + 3 gamma
/// cos 2 alpha) / (1 + 3 gamma) times it; every landing, to round-off, logged with the four
/// contacts it strikes. The columns turn, the lintel does not (the history's w carries it on the
/// columns' corners), and no joint gives way.
#[test]
fn a_released_trilith_rocks_with_the_frames_closed_forms() {
    use pirqa::response::EventKind;
    let model = Model::from_file("walls/rocking/trilith.ron").unwrap();
    let (b, h, gamma, theta0) = (0.25f64, 1.25f64, 0.5, 0.1);
    let (r, alpha) = (b.hypot(h), b.atan2(h));
    let p = (3.0 * 9.81 / (4.0 * r) * (1.0 + 2.0 * gamma) / (1.0 + 3.0 * gamma)).sqrt();
    let restitution =
        (1.0 - 1.5 * alpha.sin().powi(2) + 3.0 * gamma * (2.0 * alpha).cos()) / (1.0 + 3.0 * gamma);
    let motion = Motion::Pulse(pirqa::Pulse::rest());
    let run = |equations| {
        let settings = RunSettings {
            initial_rotation: vec![("Lintel".into(), theta0)],
            duration_s: Some(4.0),
            log_events: true,
            rocking: Some(equations),
            output_dt_s: Some(0.01),
            ..RunSettings::default()
        };
        pirqa::run(&model, &motion, &settings).unwrap()
    };
    let landings = |r: &Response| -> Vec<(f64, f64, f64)> {
        r.events
            .iter()
            .filter(|e| e.kind == EventKind::RockingImpact)
            .map(|e| {
                let w = |x: Option<f64>| x.unwrap();
                (
                    e.time_s,
                    w(e.angular_velocity_before_rad_s),
                    w(e.angular_velocity_after_rad_s),
                )
            })
            .collect()
    };
    let linear = run(pirqa::Equations::Linearised);
    let first = (alpha / (alpha - theta0)).acosh() / p;
    let t1 = landings(&linear)[0].0;
    assert!((t1 - first).abs() < 1e-12, "{t1} against {first}");
    let exact = run(pirqa::Equations::Exact);
    let l = landings(&exact);
    assert!(l.len() >= 3, "{l:?}");
    let w1 = -p * (2.0 * ((alpha - theta0).cos() - alpha.cos())).sqrt();
    assert!((l[0].1 - w1).abs() < 1e-12 * p, "{} against {w1}", l[0].1);
    for (_, before, after) in &l {
        assert!(
            (after - restitution * before).abs() < 1e-12 * p,
            "{after} against {restitution} x {before}"
        );
    }
    // Every landing strikes four contacts at once, and says so.
    for e in exact
        .events
        .iter()
        .filter(|e| e.kind == EventKind::RockingImpact)
    {
        let m = e.mode.as_deref().unwrap();
        let all = "Left/ground, Right/ground, Lintel/Left and Lintel/Right at once";
        assert!(m.ends_with(all), "{m}");
    }
    let s = &exact.summary;
    assert!(
        s.warnings.is_empty() && s.collapse.is_none(),
        "{:?}",
        s.warnings
    );
    let hist = exact.history.unwrap();
    // The columns turn alike on their feet, the middle of each base rising by b |sin theta|;
    // the lintel does not turn and is carried on the top corners opposite the feet, w =
    // 2 b |sin theta| + 2 h (cos theta - 1).
    for (row, w) in hist.rotation_rad.iter().zip(&hist.lift_m) {
        assert_eq!(row[0], row[1]);
        assert_eq!(row[2], 0.0);
        let th = row[0];
        assert!((w[0] - b * th.sin().abs()).abs() < 1e-15 && w[0] == w[1]);
        let lintel = 2.0 * b * th.sin().abs() + 2.0 * h * (th.cos() - 1.0);
        assert!((w[2] - lintel).abs() < 1e-15, "{} against {lintel}", w[2]);
    }
    assert_eq!(hist.lift_m.len(), hist.time_s.len());
}

/// The trilith under 0.3 g, 1 Hz leans far over; at 3.99 s its lintel's contacts can no longer
/// carry what the one-degree-of-freedom mechanism asks of them (both within a few percent of
/// their friction, the right one first) and the exact model stops, naming the joint. Time
/// stepping with every block's three degrees of freedom (dt = 2.5e-5 s) sees the lintel start
/// to slide on the columns' tops (faster than 0.1 mm/s against the top corner it rests on) within
/// 15 ms after that instant and not before; until then it agrees with the exact frame.
#[test]
fn a_trilith_s_lintel_slides_when_time_stepping_sees_it() {
    let model = Model::from_file("walls/rocking/trilith.ron").unwrap();
    let motion = sine(0.3 * 9.81, 1.0, 4.3);
    let s = exact(&model, &motion, ModelChoice::Auto);
    let (t, joint, how) = gave_way(&s);
    assert!(joint.starts_with("Lintel/"), "{joint}");
    assert!(how.contains("slip"), "{how}");
    let r = with_history(&model, &motion, Method::Moreau { dt_s: 2.5e-5 }, 1e-3);
    let h = r.history.unwrap();
    let (b, hh) = (0.25, 1.25);
    // The lintel's u less that of the top corner of each column it rests on.
    let off = |k: usize| -> [f64; 2] {
        let (u, th) = (&h.displacement_m[k], &h.rotation_rad[k]);
        [0, 1].map(|c| {
            let s = th[c].signum();
            u[2] - (u[c] - s * b * (th[c].cos() - 1.0) + 2.0 * hh * th[c].sin())
        })
    };
    let slip_start = (1..h.time_s.len())
        .find(|&k| {
            let (a, z) = (off(k - 1), off(k));
            (0..2).any(|c| (z[c] - a[c]).abs() > 1e-4 * (h.time_s[k] - h.time_s[k - 1]))
        })
        .map(|k| h.time_s[k])
        .expect("the lintel slides in the time-stepped run");
    assert!(
        slip_start > t && slip_start < t + 0.015,
        "slides from {slip_start} s, exact {t} s"
    );
}

/// A trilith whose lintel holds on its columns with friction 0.1 only (they lift at 0.2 g):
/// seated, the lintel moves with the ground and needs M a_g of friction from its two joints
/// together, so under a 0.15 g sine the exact model stops where a_g first reaches 0.1 g,
/// arcsin(0.1 / 0.15) / (2 pi f), naming both joints; nothing has moved.
#[test]
fn a_seated_trilith_s_lintel_slips_where_the_closed_form_says() {
    let text = std::fs::read_to_string("walls/rocking/trilith.ron").unwrap();
    let model = Model::from_ron_str(&text.replace(
        "friction: 0.7,",
        "friction: 0.7, joint_friction: {\"Lintel/Left\": 0.1, \"Lintel/Right\": 0.1},",
    ))
    .unwrap();
    let motion = sine(0.15 * 9.81, 2.0, 1.0);
    let s = exact(&model, &motion, ModelChoice::SlideRock);
    let (t, joint, how) = gave_way(&s);
    let closed = (0.1f64 / 0.15).asin() / (2.0 * std::f64::consts::PI * 2.0);
    assert!((t - closed).abs() < 1e-12, "{t} against {closed}");
    assert_eq!(joint, "Lintel/Left and Lintel/Right");
    // The ground pushes towards +x: the lintel would stay behind, slipping towards -x.
    assert!(
        how.starts_with("would slip, the block on it towards -x"),
        "{how}"
    );
    assert!(s.blocks.iter().all(|b| b.max_abs_displacement_m == 0.0));
}

/// A trilith on feet of different friction (0.1 and 0.15; it would lift at 0.2 g): seated, how
/// its weight divides between the feet is not determined, so the exact model stops where the
/// smaller friction could no longer hold it whatever the split, where a 0.12 g sine first
/// reaches 0.1 g, naming both feet; rocking, each foot keeps its own friction (the released
/// trilith's landings are those of equal feet of 0.7: the feet never come near slipping).
#[test]
fn a_trilith_on_feet_of_different_friction_stops_where_the_smaller_could_slip() {
    let text = std::fs::read_to_string("walls/rocking/trilith.ron").unwrap();
    let feet = |left: f64, right: f64| {
        Model::from_ron_str(&text.replace(
            "friction: 0.7,",
            &format!(
                "friction: 0.7, joint_friction: {{\"Left/ground\": {left}, \"Right/ground\": {right}}},"
            ),
        ))
        .unwrap()
    };
    let motion = sine(0.12 * 9.81, 2.0, 1.0);
    let s = exact(&feet(0.1, 0.15), &motion, ModelChoice::SlideRock);
    let (t, joint, how) = gave_way(&s);
    let closed = (0.1f64 / 0.12).asin() / (2.0 * std::f64::consts::PI * 2.0);
    assert!((t - closed).abs() < 1e-12, "{t} against {closed}");
    assert_eq!(joint, "Left/ground and Right/ground");
    assert!(how.starts_with("could slip"), "{how}");
    let released = |model: &Model| {
        let settings = RunSettings {
            initial_rotation: vec![("Lintel".into(), 0.1)],
            duration_s: Some(3.0),
            log_events: true,
            ..RunSettings::default()
        };
        let r = pirqa::run(model, &Motion::Pulse(pirqa::Pulse::rest()), &settings).unwrap();
        assert!(r.summary.warnings.is_empty(), "{:?}", r.summary.warnings);
        r.events
            .iter()
            .map(|e| (e.time_s, e.angular_velocity_after_rad_s))
            .collect::<Vec<_>>()
    };
    assert_eq!(released(&feet(0.6, 0.7)), released(&feet(0.7, 0.7)));
}

/// A trilith the exact model cannot take says why and what to run instead: columns of two
/// widths, a lintel short of a column's outer edge; under auto it slides and its summary says
/// why.
#[test]
fn a_trilith_beyond_the_frame_model_is_refused_by_name() {
    let text = std::fs::read_to_string("walls/rocking/trilith.ron").unwrap();
    let motion = sine(0.3 * 9.81, 1.0, 1.0);
    for (from, to, words) in [
        (
            "(width_m: 2.5, name: \"Lintel\")",
            "(width_m: 2.4, name: \"Lintel\")",
            "the lintel Lintel does not cover the whole top of Right",
        ),
        (
            "(width_m: 0.5, gap_m: 1.5, name: \"Right\")",
            "(width_m: 0.6, gap_m: 1.4, name: \"Right\")",
            "its columns Left (0.5 x 2.5 m, 1656.25 kg) and Right (0.6 x 2.5 m, 1987.5 kg) differ",
        ),
    ] {
        assert!(text.contains(from), "{from}");
        let model = Model::from_ron_str(&text.replace(from, to)).unwrap();
        let settings = RunSettings {
            model: ModelChoice::SlideRock,
            ..RunSettings::default()
        };
        let e = pirqa::run(&model, &motion, &settings)
            .unwrap_err()
            .to_string();
        assert!(e.contains(words) && e.contains("--method moreau"), "{e}");
        // Under auto it slides, and says why.
        let why = exact(&model, &motion, ModelChoice::Auto).model.why;
        assert!(
            why.starts_with("auto: Trilith: ") && why.contains(words),
            "{why}"
        );
    }
}

/// The two-block column under 0.5 g at 1.5 Hz: its whole body lifts, then the joint between
/// the drums opens and the upper drum rocks on the lower one while that one rocks on the
/// ground (Psycharis's third pattern: the chain of open joints), lands back, and the column
/// rocks as one body again, over and over. The exact run follows it to the end of the motion
/// with its energy balance closed to round-off, and Moreau-Jean with every block's rotation
/// converges to it as the step falls.
#[test]
fn time_stepping_converges_to_a_column_whose_joints_open_one_above_another() {
    use pirqa::response::EventKind;
    let motion = sine(0.5 * 9.81, 1.5, 2.5);
    let model = Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let settings = RunSettings {
        output_dt_s: Some(0.01),
        log_events: true,
        ..RunSettings::default()
    };
    let reference = pirqa::run(&model, &motion, &settings).unwrap();
    let s = &reference.summary;
    assert!(
        s.warnings.is_empty() && s.collapse.is_none(),
        "{:?}",
        s.warnings
    );
    assert_eq!(s.duration_s, 2.5);
    let opens = |joint: &str| {
        reference
            .events
            .iter()
            .filter(|e| e.kind == EventKind::Uplift && e.joint.as_deref() == Some(joint))
            .count()
    };
    assert!(opens("Drum2/Drum1") >= 2, "{:?}", reference.events);
    let e = &s.energy;
    assert!(e.residual_j.abs() < 1e-12 * e.input_j, "{e:?}");
    let err = |dt_s: f64| {
        let r = with_history(&model, &motion, Method::Moreau { dt_s }, 0.01);
        rocking_errors(&r, &reference, model.wall()).1
    };
    // (2.1 mm, 0.28 mm, 0.017 mm measured; 0.026 mm for the finest before stacked blocks
    // stopped falling for the first step.)
    let e = [err(1e-3), err(2.5e-4), err(1.5625e-5)];
    assert!(
        e[1] < e[0] / 5.0 && e[2] < e[1] / 5.0 && e[2] < 1e-4,
        "{e:?} m"
    );
}

/// Where Newton's method on the whole wall does not converge (here made so by a tolerance no
/// step can meet), Gauss-Seidel solves the step instead, from the free velocities and the last
/// step's impulses: the run is then Gauss-Seidel's own to the bit, and a warning counts every
/// step that fell back (all 300: the wall rests on its contacts throughout).
#[test]
fn a_step_newton_cannot_solve_is_left_to_gauss_seidel() {
    use pirqa::integrate::baselines::MoreauWall;
    use pirqa::integrate::{Integrator, Scenario, Settings};
    let model = Model::from_file("walls/five-block-uniform.ron").unwrap();
    let motion = sine(4.0, 1.0, 0.3);
    let settings = Settings::summary_only(0.3);
    let sc = Scenario {
        wall: model.wall(),
        topology: model.topology(),
        motion: &motion,
        settings: &settings,
    };
    let gauss_seidel = MoreauWall::new(1e-3).run(&sc).unwrap().summary;
    let never = MoreauWall {
        solver: ContactSolver::Newton,
        newton_tolerance: -1.0,
        ..MoreauWall::new(1e-3)
    }
    .run(&sc)
    .unwrap()
    .summary;
    let json = |s: &Summary| serde_json::to_value((&s.blocks, &s.energy)).unwrap();
    assert_eq!(json(&never), json(&gauss_seidel));
    assert!(gauss_seidel
        .blocks
        .iter()
        .any(|b| b.max_abs_displacement_m > 1e-3));
    assert!(
        never.warnings.iter().any(|w| matches!(
            w,
            Warning::NewtonFellBack { steps: 300, first_s } if *first_s == 1e-3
        )),
        "{:?}",
        never.warnings
    );
    // One sweep per step is too few for Gauss-Seidel as well: its warning says when the
    // first such step ended and which blocks it left changing fastest, most often first.
    let one_sweep = MoreauWall {
        max_sweeps: 1,
        ..MoreauWall::new(1e-3)
    }
    .run(&sc)
    .unwrap()
    .summary;
    let Some(Warning::Unconverged {
        steps,
        sweeps: 1,
        first_s: Some(first_s),
        blocks,
    }) = one_sweep
        .warnings
        .iter()
        .find(|w| matches!(w, Warning::Unconverged { .. }))
    else {
        panic!("{:?}", one_sweep.warnings);
    };
    assert_eq!((*steps, *first_s), (300, 1e-3));
    // The three named (of five), most often first, each a block of the wall, their steps
    // among the 300.
    assert_eq!(blocks.len(), 3, "{blocks:?}");
    assert!(blocks.windows(2).all(|w| w[0].1 >= w[1].1), "{blocks:?}");
    assert!(blocks
        .iter()
        .all(|(name, _)| model.wall().block_index(name).is_some()));
    assert!(blocks.iter().map(|b| b.1).sum::<u64>() <= 300, "{blocks:?}");
}

/// A running bond of two courses of eight blocks (`pirqa generate --courses 2
/// --blocks-per-course 8`): docs/rocking-walls.md's 17-block wall, whose slender end half
/// blocks and inner blocks turn under 400 gal at 2 Hz.
fn running_bond_2x8() -> Model {
    let spec = pirqa::wall::RunningBond {
        courses: 2,
        blocks_per_course: 8,
        ..pirqa::wall::RunningBond::paper_wall(5)
    };
    Model::new(pirqa::Wall::from_description(&spec.description().unwrap()).unwrap()).unwrap()
}

/// The steps of a whole-wall Newton run that its velocity-space phases did not solve, as its
/// warnings count them: solved in the contacts' impulses, left to Gauss-Seidel, and left
/// unconverged by Gauss-Seidel too.
#[derive(Debug, Default, PartialEq)]
struct Fallbacks {
    in_impulses: u64,
    fell_back: u64,
    unconverged: u64,
}

fn fallbacks(s: &Summary) -> Fallbacks {
    let mut f = Fallbacks::default();
    for w in &s.warnings {
        match w {
            Warning::NewtonInImpulses { steps, .. } => f.in_impulses = *steps,
            Warning::NewtonFellBack { steps, .. } => f.fell_back = *steps,
            Warning::Unconverged { steps, .. } => f.unconverged = *steps,
            _ => {}
        }
    }
    f
}

/// A running bond of two courses of eight blocks (docs/rocking-walls.md's 17-block wall) under
/// 400 gal at 2 Hz for 1 s, dt = 5e-4 s: once its inner blocks turn (from 0.37 s) the fixed
/// point on the friction bounds cycles, and on its own it left 158 steps to Gauss-Seidel, which
/// failed in 24. Semismooth Newton on Coulomb's law, taking over where the fixed point stops,
/// leaves a few. Which few depends on round-off (a rocking wall's path does: the simplicial and
/// supernodal Cholesky factorisations left 2 steps, none unsolved, and 3, one unsolved; once
/// the line search stopped at its derivative's round-off, one, solved in impulses; since
/// Coulomb's Newton is tried at the fixed point's first stall, none), so the test bounds their
/// number, far below the fixed point's alone.
#[test]
fn newton_on_coulombs_law_solves_a_running_bond_whose_blocks_turn() {
    let model = running_bond_2x8();
    let s = stepped_by(&model, &sine(4.0, 2.0, 1.0), 5e-4, ContactSolver::Newton);
    assert!(
        s.blocks
            .iter()
            .filter(|b| b.uplift_time_s.is_some())
            .count()
            >= 8,
        "{:?}",
        s.blocks
    );
    let f = fallbacks(&s);
    assert!(f.fell_back <= 10 && f.unconverged <= 2, "{:?}", s.warnings);
}

/// The same wall at dt = 1.25e-4 s, where the two phases in velocities leave a few of the
/// 8,000 steps (their fixed point and Coulomb's Newton cycling at the kinks of turning blocks):
/// the third solver, projected Newton on the same problem in the contacts' impulses, solves
/// them, and a warning counts them. There were 20 such steps while Coulomb's Newton waited for
/// the fixed point to use its 200 iterations; handed the fixed point's iterate at its first
/// stall (and giving it back where it fails), it leaves 2, so the test asks for at least one,
/// that the impulses are exercised, and for fewer than 20.
#[test]
fn the_impulses_solve_the_steps_the_velocities_leave() {
    let model = running_bond_2x8();
    let s = stepped_by(&model, &sine(4.0, 2.0, 1.0), 1.25e-4, ContactSolver::Newton);
    let f = fallbacks(&s);
    assert!((1..=5).contains(&f.in_impulses), "{:?}", s.warnings);
    assert_eq!((f.fell_back, f.unconverged), (0, 0), "{:?}", s.warnings);
}

/// The uniform 976-block running bond (31 courses of 31 blocks) under 600 gal at 2 Hz, dt =
/// 5e-4 s: from 0.041 s, as its end blocks lift, neither Newton in the velocities nor the
/// solver in the impulses settles a step, and the interior point does. Its directions lost
/// the blocks' balance deep in its path (multipliers read from their complementarity at l / w
/// of 1e19), which left 4 of the 8 steps to 0.0445 s to Gauss-Seidel, failing in all; now none.
/// After a step only it solved, it is given the next steps first (the answers are those of the
/// usual order, in a fraction of the time). Run to 0.05 s: in the step ending there the plain
/// update of the friction bounds, b = mu p_n, cycled with period three through all its 30
/// updates and the step went to Gauss-Seidel, which failed; with Anderson's mix of the updates
/// after the fourth, every step is solved.
#[test]
fn the_interior_point_solves_a_976_block_wall_as_its_end_blocks_lift() {
    let spec = pirqa::wall::RunningBond {
        courses: 31,
        blocks_per_course: 31,
        ..pirqa::wall::RunningBond::paper_wall(5)
    };
    let model =
        Model::new(pirqa::Wall::from_description(&spec.description().unwrap()).unwrap()).unwrap();
    let s = stepped_by(&model, &sine(6.0, 2.0, 0.05), 5e-4, ContactSolver::Newton);
    let by_interior = s.warnings.iter().find_map(|w| match w {
        Warning::NewtonByInteriorPoint {
            steps, given_first, ..
        } => Some((*steps, *given_first)),
        _ => None,
    });
    let (steps, given_first) = by_interior.expect("steps solved by the interior point");
    assert!(
        steps >= 1 && given_first >= 1 && steps + given_first >= 19,
        "{:?}",
        s.warnings
    );
    let f = fallbacks(&s);
    assert_eq!((f.fell_back, f.unconverged), (0, 0), "{:?}", s.warnings);
}

/// Newton's exact line search stops where the derivative along the step is zero within the
/// round-off of its own sum. It went on while that derivative was not exactly zero, and in
/// the steps where Newton's step is tiny (the iteration converged) it then followed the
/// round-off for up to its 100 iterations, moving the blocks by noise: on the same wall at
/// dt = 1e-3 s that sent one step to Gauss-Seidel, which could not solve it either (10,000
/// sweeps). Now every step is solved in the blocks' velocities: no step falls back, none is
/// left unconverged.
#[test]
fn the_line_search_stops_at_its_derivatives_round_off() {
    let model = running_bond_2x8();
    let s = stepped_by(&model, &sine(4.0, 2.0, 1.0), 1e-3, ContactSolver::Newton);
    assert_eq!(fallbacks(&s), Fallbacks::default(), "{:?}", s.warnings);
    assert!(
        s.blocks
            .iter()
            .filter(|b| b.uplift_time_s.is_some())
            .count()
            >= 8,
        "{:?}",
        s.blocks
    );
}

/// The warnings give the end of a step k dt as a reader writes it: the step ending at
/// 1,128 x 5e-4 s is 0.564 s, not the float product 0.5640000000000001 s.
#[test]
fn a_warning_gives_a_steps_end_to_the_nanosecond() {
    let t = 1128.0 * 5e-4;
    assert_ne!(t, 0.564);
    let fell_back = Warning::NewtonFellBack {
        steps: 3,
        first_s: t,
    };
    let unconverged = Warning::Unconverged {
        steps: 1,
        sweeps: 10_000,
        first_s: Some(t),
        blocks: vec![("B13".to_string(), 1)],
    };
    // The steps Newton leaves are given to Gauss-Seidel, which may fail in them too: the
    // warning must not say they were solved.
    assert!(!fell_back.to_string().contains("solved"), "{fell_back}");
    for w in [fell_back, unconverged] {
        let text = w.to_string();
        assert!(text.contains("the first ending at 0.564 s"), "{text}");
    }
}

/// A block that carries another, released inside a wall, time stepped: a slender block (0.2 by
/// 0.8 m) with a squat one on it, beside a wide block, turned 0.05 rad about the base corner
/// away from its neighbour, turns with the block it carries and falls back as the same two
/// blocks alone (a column, which the column's own release turns as one body), the neighbour
/// holding still, until it meets the neighbour just before landing: to 1e-9 rad for both
/// blocks (3e-16 measured). Turned towards the neighbour,
/// the block it carries reaches into it first; the wide block carries nothing and is released
/// alone.
#[test]
fn a_block_released_in_a_wall_turns_with_the_block_it_carries() {
    use pirqa::response::EventKind;
    let wall = |beside: &str| {
        Model::from_ron_str(&format!(
            "(version: 1, name: \"column\", thickness_m: 1.0, density_kg_m3: 2600, \
             friction: 0.8, rows: [(height_m: 0.8, x_m: {}, blocks: [{beside}(width_m: 0.2, \
             name: \"B\")]), (height_m: 0.2, x_m: 1.0, blocks: [(width_m: 0.2, name: \"C\")])])",
            if beside.is_empty() { 1.0 } else { 0.0 }
        ))
        .unwrap()
    };
    let in_wall = wall("(width_m: 1.0, name: \"A\"), ");
    let alone = wall("");
    let rest = Motion::Pulse(pirqa::Pulse::rest());
    let released = |model: &Model, name: &str, theta: f64| {
        let settings = RunSettings {
            model: ModelChoice::SlideRock,
            method: Method::Moreau { dt_s: 1e-4 },
            initial_rotation: vec![(name.to_string(), theta)],
            duration_s: Some(0.5),
            output_dt_s: Some(0.005),
            log_events: true,
            ..RunSettings::default()
        };
        pirqa::run(model, &rest, &settings)
    };
    let (beside, by_themselves) = (
        released(&in_wall, "B", 0.05).unwrap(),
        released(&alone, "B", 0.05).unwrap(),
    );
    // Just before it lands, the turning block's lower corner, which its pivot's slip has
    // carried 6e-8 m towards the neighbour, grazes the neighbour's face (an impact of the
    // joint, logged): the wall and the column alone part there.
    let grazed = beside
        .events
        .iter()
        .find(|e| e.kind == EventKind::Impact)
        .map(|e| e.time_s)
        .unwrap();
    let (h, alone_h) = (beside.history.unwrap(), by_themselves.history.unwrap());
    let compared = h.time_s.iter().take_while(|&&t| t < grazed).count();
    assert!(
        compared > 20
            && alone_h.rotation_rad[compared - 1][0] < 0.01
            && h.rotation_rad[0] == [0.0, 0.05, 0.05],
        "{compared} {:?}",
        h.rotation_rad[0]
    );
    let most = h.rotation_rad[..compared]
        .iter()
        .zip(&alone_h.rotation_rad)
        .map(|(a, b)| (a[1] - b[0]).abs().max((a[2] - b[1]).abs()).max(a[0].abs()))
        .fold(0.0, f64::max);
    assert!(most < 1e-9, "{most}");
    let refused = released(&in_wall, "B", -0.05).unwrap_err().to_string();
    assert!(refused.contains("would reach into A"), "{refused}");
    let wide = released(&in_wall, "A", -0.05).unwrap();
    assert_eq!(wide.history.unwrap().rotation_rad[0], [-0.05, 0.0, 0.0]);
}

/// A block of a wall's top course released from a rotation, time stepped (the exact column
/// model refuses walls of blocks beside others): the right end half block of a 2 x 8 running
/// bond, turned 0.1 rad about the outer corner of its base, where nothing stands beside it,
/// falls back as the same block alone on the ground released the same way, the wall below
/// holding still, until it lands: to 1e-9 rad (4.5e-10 measured; the two runs' Gauss-Seidel
/// sweeps stop within their tolerance at different iterates, the wall's having more contacts
/// to settle). Turned the other way it would reach into its neighbour, a block that carries
/// a block resting also on another cannot turn with it, and a name the wall does not have is
/// no block: each refused with the reason.
#[test]
fn a_top_block_released_in_a_running_bond_falls_back_as_the_block_alone() {
    let model = running_bond_2x8();
    let wall = model.wall();
    let last = wall.blocks.last().unwrap().clone();
    let alone = Model::from_ron_str(&format!(
        "(version: 1, name: \"alone\", thickness_m: {}, density_kg_m3: {}, friction: {}, \
         rows: [(height_m: {}, blocks: [(width_m: {}, name: \"{}\")])])",
        wall.thickness_m.to_f64(),
        wall.density_kg_m3.to_f64(),
        wall.friction.to_f64(),
        last.height.to_f64(),
        last.width.to_f64(),
        last.name
    ))
    .unwrap();
    let rest = Motion::Pulse(pirqa::Pulse::rest());
    let released = |model: &Model, name: &str, theta: f64| {
        let settings = RunSettings {
            model: ModelChoice::SlideRock,
            method: Method::Moreau { dt_s: 1e-4 },
            initial_rotation: vec![(name.to_string(), theta)],
            duration_s: Some(0.5),
            output_dt_s: Some(0.005),
            ..RunSettings::default()
        };
        pirqa::run(model, &rest, &settings)
    };
    let rotation = |r: &Response, i: usize| -> Vec<f64> {
        let h = r.history.as_ref().unwrap();
        h.rotation_rad.iter().map(|th| th[i]).collect()
    };
    let in_wall = rotation(
        &released(&model, &last.name, 0.1).unwrap(),
        wall.blocks.len() - 1,
    );
    let by_itself = rotation(&released(&alone, &last.name, 0.1).unwrap(), 0);
    let falling = by_itself.iter().take_while(|&&th| th > 0.0).count();
    assert!(
        falling > 20 && in_wall[0] == 0.1,
        "{falling} {}",
        in_wall[0]
    );
    let most = in_wall
        .iter()
        .zip(&by_itself)
        .take(falling)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(most < 1e-9, "{most}");
    for (name, theta, words) in [
        (last.name.as_str(), -0.1, "would reach into B16"),
        ("B8", 0.1, "rests on it and also on"),
        ("B99", 0.1, "no block of that name"),
    ] {
        let refused = released(&model, name, theta).unwrap_err().to_string();
        assert!(refused.contains(words), "{refused}");
    }
}

/// The limit at rest (`pirqa check --limit`, exact limit analysis) is where time stepping with
/// every block's rotation leaves rest, on walls whose loads the balances determine: a ground
/// acceleration held for 0.3 s at 2 % under the limit turns no block (rotations at round-off),
/// 2 % over it turns the mechanism's. (A block on two others is another matter: time stepping
/// takes its own split of the load and leaves rest earlier; docs/rocking-walls.md.)
#[test]
fn time_stepping_leaves_rest_at_the_limit_at_rest() {
    for (file, turns) in [
        ("walls/rocking/two-block-column.ron", "Drum1"),
        ("walls/rocking/trilith.ron", "Left"),
        ("walls/inca/ollantaytambo-monoliths.ron", "F1"),
    ] {
        let model = Model::from_file(file).unwrap();
        let limits = pirqa::limit::at_rest(model.wall(), model.topology()).unwrap();
        let pirqa::limit::Limit::Holds { accel_m_s2, .. } = limits.towards_plus_x else {
            panic!("{file}: no limit");
        };
        for (factor, moves) in [(0.98, false), (1.02, true)] {
            let motion = Motion::Pulse(pirqa::Pulse {
                amplitude_m_s2: factor * accel_m_s2,
                duration_s: 0.3,
            });
            let s = stepped(&model, &motion, 1e-4);
            let largest = s
                .blocks
                .iter()
                .map(|b| b.max_abs_rotation_rad)
                .fold(0.0, f64::max);
            let turned = s
                .blocks
                .iter()
                .find(|b| b.name == turns)
                .unwrap()
                .max_abs_rotation_rad;
            if moves {
                assert!(
                    turned > 1e-5,
                    "{file} at {factor} of its limit: {turned} rad"
                );
            } else {
                assert!(
                    largest < 1e-10,
                    "{file} at {factor} of its limit: {largest} rad"
                );
            }
        }
    }
}
