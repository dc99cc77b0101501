//! Tests of a body rocking on a sliding stack: its equations against slide-rock's as the
//! stack's mass goes to zero and against a body on a base that friction alone decelerates as it
//! grows without bound, and the energy balance of body and stack along their motion.
use super::*;
use crate::integrate::rocking::modes::test_inputs_at;

/// The slender block of walls/rocking/slender-on-stack.ron (0.2 by 0.8 m, 416 kg).
fn top(friction: f64) -> RockingBody {
    RockingBody::rectangle("Top", 0.2, 0.8, 416.0, friction, 9.81)
}

fn stack(mass_kg: f64, slip: Slip) -> Stack {
    Stack {
        joint: 0,
        first: 0,
        mass_kg,
        friction: 0.6,
        slip,
        u_start_m: 0.0,
        apart: None,
    }
}

/// Three instants along the step the engine takes on `t`'s series (the body's and every
/// stack's, accurate to round-off there).
fn along_step(body: &RockingBody, t: &Trajectory) -> [f64; 3] {
    let sc = Scales::of(body);
    let mut series = vec![
        (&t.theta, 1.0),
        (&t.omega, body.frequency_parameter_rad_s()),
        (&t.u, body.size_m()),
        (&t.v, sc.velocity),
    ];
    for [u, v] in t.stack.iter().chain(&t.beneath) {
        series.extend([(u, body.size_m()), (v, sc.velocity)]);
    }
    let h = series::step_size(&series);
    [h / 3.0, 2.0 * h / 3.0, h]
}

/// The horizontal momentum of body and stacks along `t`, m x_G' + sum M u_s' (x_G' = u' +
/// G_y theta'), changes by the ground's inertial force and the lowest joint's friction alone,
/// -(m + sum M) a_g - mu sigma (N + sum M g lambda): every other force is internal. To 1e-12.
fn assert_momentum(
    body: &RockingBody,
    on: &Displaced,
    t: &Trajectory,
    inputs: &Inputs,
    taus: &[f64],
) {
    let stacks: Vec<&Stack> = on.sliding.iter().chain(&on.beneath).collect();
    let velocities: Vec<&Coeffs> = std::iter::once(velocity(t))
        .chain(t.beneath.iter().map(|[_, v]| v))
        .collect();
    let momentum = |tau: f64| {
        let x_g = series::eval(&t.v, tau) + series::eval(&t.gy, tau) * series::eval(&t.omega, tau);
        let carried = (stacks.iter().zip(&velocities))
            .map(|(st, v)| st.mass_kg * series::eval(*v, tau))
            .sum::<f64>();
        body.mass_kg * x_g + carried
    };
    let mass: f64 = stacks.iter().map(|st| st.mass_kg).sum();
    let lowest = stacks.last().expect("a stack that slides");
    let mut load = t.normal;
    series::add_to(&mut load, &inputs.lambda, mass * body.g_m_s2);
    let mut force = series::scaled(&load, -lowest.friction * lowest.slip.sign());
    series::add_to(&mut force, &inputs.accel, -(body.mass_kg + mass));
    for &tau in taus {
        let impulse = series::integral(&force, tau);
        let moved = momentum(tau) - momentum(0.0);
        assert!(
            (moved - impulse).abs() <= 1e-12 * (momentum(0.0).abs() + impulse.abs()),
            "{on:?} at {tau} s: {moved} N s against {impulse} N s"
        );
    }
}

/// The column's held blocks with `st` sliding alone under the body.
fn alone(st: Stack) -> Displaced {
    Displaced {
        sliding: Some(st),
        ..Displaced::default()
    }
}

/// Rocking on the left corner, turning back, the stack sliding forward; and the mirror case:
/// each stack fast enough to slide through the 0.05 s the tests follow.
fn cases() -> [(Corner, Slip, State); 2] {
    let state = |theta: f64, omega: f64, v: f64| State {
        theta,
        omega,
        u: 0.01,
        v,
        ..State::default()
    };
    [
        (Corner::Left, Slip::Forward, state(-0.05, 0.3, 0.5)),
        (Corner::Right, Slip::Backward, state(0.12, 0.7, -0.6)),
    ]
}

/// Series values along the first 0.05 s, where they are compared.
fn along(c: &Coeffs) -> Vec<f64> {
    (0..=10)
        .map(|k| series::eval(c, 0.005 * k as f64))
        .collect()
}

fn close(a: &[f64], b: &[f64], tol: f64, what: &str) {
    for (x, y) in a.iter().zip(b) {
        assert!(
            (x - y).abs() <= tol,
            "{what}: {x} against {y} ({:e})",
            x - y
        );
    }
}

/// With M = 0 the stack is the body's own slipping base: the motion is slide-rock's on a
/// joint of the stack's friction, to round-off.
#[test]
fn a_stack_without_mass_is_slide_rock() {
    let body = top(0.6);
    for (c, slip, state) in cases() {
        let inputs = test_inputs_at(0.37);
        let on_stack = trajectory(&body, &stack(0.0, slip), c, &state, &inputs);
        let own = modes::trajectory(
            &body,
            Equations::Exact,
            Mode::SlideRock(c, slip),
            &state,
            &inputs,
        );
        close(&along(&on_stack.theta), &along(&own.theta), 1e-16, "theta");
        close(&along(&on_stack.omega), &along(&own.omega), 1e-14, "theta'");
        close(&along(&on_stack.u), &along(&own.u), 1e-17, "u");
        close(&along(&on_stack.v), &along(&own.v), 1e-15, "u'");
        close(&along(&on_stack.normal), &along(&own.normal), 1e-11, "N");
        close(
            &along(&on_stack.tangential),
            &along(&own.tangential),
            1e-11,
            "F",
        );
    }
}

/// With M far above m the stack decelerates by friction alone, u'' + a_g = -mu_s sigma g
/// lambda, and the body rocks on it as on a base moving so: Housner's rocking equation with
/// that acceleration in place of the ground's, to m / M (here 4e-16: round-off).
#[test]
fn a_stack_of_unbounded_mass_is_a_base_that_friction_decelerates() {
    let body = top(0.8);
    for (c, slip, state) in cases() {
        let inputs = test_inputs_at(0.37);
        let big = stack(1e18, slip);
        let on_stack = trajectory(&body, &big, c, &state, &inputs);
        let mut base = inputs.clone();
        base.accel = series::scaled(&inputs.lambda, -big.friction * slip.sign() * 9.81);
        let rocking = modes::trajectory(&body, Equations::Exact, Mode::Rock(c), &state, &base);
        close(
            &along(&on_stack.theta),
            &along(&rocking.theta),
            1e-15,
            "theta",
        );
        close(
            &along(&on_stack.omega),
            &along(&rocking.omega),
            1e-12,
            "theta'",
        );
        let stack_acc = series::add(&base.accel, &inputs.accel, -1.0);
        close(
            &along(&series::derivative(&on_stack.v)),
            &along(&stack_acc),
            1e-11,
            "u''",
        );
    }
}

/// The energy of body and stack along `t` changes by the input less the friction dissipated,
/// to 1e-13 of the energies, at each of `taus`.
fn assert_balance(
    body: &RockingBody,
    on: &Displaced,
    t: &Trajectory,
    inputs: &Inputs,
    taus: &[f64],
) {
    let energy = |tau: f64| {
        modes::kinetic_j(body, t, tau) + kinetic_j(on, t, tau) + modes::potential_j(body, t, tau)
    };
    let (input, friction) = power_series(body, on, t, inputs);
    for &tau in taus {
        let work = series::integral(&input, tau) - series::integral(&friction, tau);
        let change = energy(tau) - energy(0.0);
        let scale = energy(0.0).abs() + series::integral(&friction, tau).abs();
        assert!(
            (change - work).abs() <= 1e-13 * scale,
            "{on:?} at {tau} s: {change} J against {work} J"
        );
    }
}

/// The kinetic and potential energy of body and stack change by the work of the ground's
/// inertial forces on both less the friction dissipated on the joint the stack slides on (the
/// pivot's force is inside the system), to round-off of the energies.
#[test]
fn body_and_stack_balance_their_energy() {
    let body = top(0.8);
    for (c, slip, state) in cases() {
        for m_stack in [100.0, 2600.0, 1e5] {
            let inputs = test_inputs_at(1.1);
            let st = stack(m_stack, slip);
            let t = trajectory(&body, &st, c, &state, &inputs);
            let taus = [0.01, 0.03, 0.05];
            assert_balance(&body, &alone(st), &t, &inputs, &taus);
            let (_, friction) = power_series(&body, &alone(st), &t, &inputs);
            for tau in taus {
                assert!(
                    series::integral(&friction, tau) > 0.0,
                    "friction dissipates"
                );
            }
        }
    }
}

/// A body slide-rocking on a sliding stack, its pivot slipping on the stack: both ways
/// relative to it, for the cases above (the stack's own velocity a third of the pivot's, so the
/// pivot slips on it). The energy of body and stack changes by the input less what both joints
/// dissipate (each positive), and their horizontal momentum, m x_G' + M u_s', by the ground's
/// inertial force and the stack joint's friction alone: the pivot's force is internal.
#[test]
fn a_body_slide_rocking_on_a_sliding_stack_balances_energy_and_momentum() {
    let body = top(0.5);
    for (c, slip, state) in cases() {
        for m_stack in [100.0, 2600.0] {
            let inputs = test_inputs_at(1.1);
            let st = Stack {
                apart: Some([0.002, state.v / 3.0]),
                ..stack(m_stack, slip)
            };
            let relative = if state.v > state.v / 3.0 {
                Slip::Forward
            } else {
                Slip::Backward
            };
            let t = slide_rocking(&body, &st, c, relative, &state, &inputs);
            let (_, friction) = power_series(&body, &alone(st), &t, &inputs);
            let [_, v_s] = t.stack.expect("the stack's own series");
            let taus = along_step(&body, &t);
            assert_balance(&body, &alone(st), &t, &inputs, &taus);
            assert_momentum(&body, &alone(st), &t, &inputs, &taus);
            // Each joint dissipates over the first 5 ms, both slips going on (friction stops
            // the stack within the step).
            let pivot = series::add(&t.v, &v_s, -1.0);
            let tau = 0.005_f64.min(taus[2]);
            assert!(series::eval(&pivot, tau) * relative.sign() > 0.0);
            assert!(series::eval(&v_s, tau) * slip.sign() > 0.0);
            let on_pivot = series::scaled(&series::product(&t.tangential, &pivot), -1.0);
            assert!(
                series::integral(&on_pivot, tau) > 0.0,
                "the pivot dissipates"
            );
            assert!(
                series::integral(&friction, tau) > series::integral(&on_pivot, tau),
                "the stack's joint dissipates"
            );
        }
    }
}

/// walls/rocking/slender-on-stack.ron (every joint at friction 0.8), Base+Middle sliding on the
/// ground and the top's pivot slipping on Middle the same way: the whole stack decelerates by
/// mu g lambda, the pivot's -mu sigma N on it cancelling the same part of its joint's, and so
/// does Middle, so that Middle/Base passes up exactly its limit, mu (N + M_mid g lambda), for
/// as long as both slip. The column's margin of that joint is zero in every coefficient to
/// round-off but the last, which it builds from derivatives of the body's velocities that have
/// none (series::leading): a tie, the joint holding (not strictly) and its slip not beginning.
/// Until 2026-12-07 that last coefficient decided, of any sign and size, and the wall stopped
/// at 1.2 g and 1.5 g; the states here are late in a swing, as there, where it is large.
#[test]
fn a_joint_inside_a_stack_whose_top_slips_with_it_stays_at_its_limit() {
    let model = crate::model::Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let column = super::super::column::columns(model.wall(), model.topology())
        .unwrap()
        .remove(0);
    let (body, watch) = (&column.body, &column.watch);
    let ts = body.time_scale_s();
    let inputs = test_inputs_at(1.1);
    for (c, slip, theta, omega, v) in [
        (Corner::Left, Slip::Backward, -1.3, -3.5, -0.9),
        (Corner::Right, Slip::Forward, 1.1, 4.0, 0.6),
    ] {
        let state = State {
            theta,
            omega,
            u: 0.01,
            v,
            ..State::default()
        };
        // The ground joint's condition that slips the stack this way: 4 j, towards -x.
        let ground = usize::from(slip == Slip::Forward);
        let st = watch.stack_on(ground, state.u).expect("Base+Middle");
        assert_eq!((st.first, st.slip, st.friction), (0, slip, 0.8));
        let shift = alone(Stack {
            apart: Some([0.002, v / 3.0]),
            ..st
        });
        let t = on(body, &shift, Mode::SlideRock(c, slip), &state, &inputs).unwrap();
        let all = watch.conditions(&t, &inputs, &shift);
        let inside = all
            .iter()
            .find(|k| k.guard == Guard::Held(4 + ground))
            .expect("Middle/Base slipping the same way");
        let mut tk = 1.0;
        for (k, x) in inside.series.iter().take(ORDER).enumerate() {
            assert!(
                x.abs() * tk <= 1e-13 * inside.scale,
                "coefficient {k}: {x} against {} N",
                inside.scale
            );
            tk *= ts;
        }
        // The last alone is far from a tie here: it would decide were it read.
        assert!(inside.series[ORDER].abs() * tk > 1e-3 * inside.scale);
        assert!(inside.holds_after(ts), "{:?}", inside.series);
        let slips = Constraint {
            strict: true,
            ..inside.clone()
        };
        assert!(!slips.holds_after(ts));
    }
}

/// A stack sliding on another that slides on a held joint, under a body rocking on its stuck
/// pivot and under one slide-rocking on the upper stack: the energy of body and both stacks
/// changes by the input less what every joint dissipates, and their horizontal momentum,
/// m x_G' + M_1 u_1' + M_2 u_2', by the ground's inertial force and the lowest joint's friction
/// alone (every other force is internal).
#[test]
fn stacks_sliding_on_each_other_balance_energy_and_momentum() {
    let body = top(0.5);
    for (c, slip, state) in cases() {
        for (m_top, m_under) in [(400.0, 2200.0), (2200.0, 400.0)] {
            for slipping in [false, true] {
                let inputs = test_inputs_at(1.1);
                let upper = Stack {
                    apart: slipping.then_some([0.001, state.v / 3.0]),
                    ..stack(m_top, slip)
                };
                let lower = Stack {
                    first: 0,
                    apart: Some([0.002, state.v / 6.0]),
                    friction: 0.4,
                    ..stack(m_under, slip)
                };
                let held = Displaced {
                    sliding: Some(Stack { first: 1, ..upper }),
                    beneath: vec![lower],
                    ..Displaced::default()
                };
                let mode = if slipping {
                    // The pivot slips on the upper stack the way it moves on it.
                    Mode::SlideRock(c, slip)
                } else {
                    Mode::Rock(c)
                };
                let t = on(&body, &held, mode, &state, &inputs).expect("a rocking mode");
                let taus = along_step(&body, &t);
                assert_balance(&body, &held, &t, &inputs, &taus);
                assert_momentum(&body, &held, &t, &inputs, &taus);
            }
        }
    }
}

/// The angular momentum of a body about its new corner, I_G omega + m (h_c x_G' - s b y_G') with
/// s the old pivot's sign (the landing's impulse acts at that corner: it is kept).
fn about_new_corner(body: &RockingBody, s: f64, omega: f64, (xg, yg): (f64, f64)) -> f64 {
    let (m, b, h) = (body.mass_kg, body.half_base_m, body.centroid_height_m);
    body.inertia_kg_m2 * omega + m * (h * xg - s * b * yg)
}

/// A landing on a sliding stack keeps the body's angular momentum about its new corner; the
/// horizontal momentum of body and stack changes by the friction impulse of the stack's joint,
/// at its limit where the stack slides on and within it where the impact stops the stack; kinetic
/// energy is lost; and a stack of unbounded mass is a base moving steadily, on which the landing
/// is Housner's.
#[test]
fn a_landing_on_a_sliding_stack_keeps_momentum_about_the_new_corner() {
    let body = top(0.8);
    let (m, b, h) = (body.mass_kg, body.half_base_m, body.centroid_height_m);
    let mut kinds = [0, 0];
    for (pivot, omega) in [(Corner::Right, -1.3), (Corner::Left, 0.9)] {
        let s = pivot.sign();
        for (slip, v_s) in [
            (Slip::Forward, 0.4),
            (Slip::Backward, -0.4),
            (Slip::Forward, 0.004),
        ] {
            for m_stack in [100.0, 2600.0, 1e5] {
                let st = stack(m_stack, slip);
                let l = landing(&body, &[st], &[v_s], pivot, omega).expect("a landing it follows");
                let (before, after) = (
                    (v_s + h * omega, s * b * omega),
                    (l.v[0] + h * l.omega, -s * b * l.omega),
                );
                let kept = about_new_corner(&body, s, omega, before);
                let now = about_new_corner(&body, s, l.omega, after);
                assert!((kept - now).abs() <= 1e-12 * kept.abs(), "{kept} {now}");
                let normal = m * (after.1 - before.1);
                let friction = m * (after.0 - before.0) + m_stack * (l.v[0] - v_s);
                if l.v[0] == 0.0 {
                    kinds[1] += 1;
                    assert!(
                        friction.abs() <= st.friction * normal,
                        "{friction} {normal}"
                    );
                } else {
                    kinds[0] += 1;
                    let limit = -st.friction * slip.sign() * normal;
                    assert!(
                        (friction - limit).abs() <= 1e-12 * normal,
                        "{friction} {limit}"
                    );
                }
                assert!(l.loss_j > 0.0);
            }
        }
        let steady = landing(&body, &[stack(1e18, Slip::Forward)], &[0.3], pivot, omega).unwrap();
        let housner = crate::integrate::rocking::impact::land(
            &body,
            Equations::Exact,
            pivot,
            omega,
            0.0,
            0.0,
        )
        .unwrap();
        assert!((steady.omega - housner.state.omega).abs() <= 1e-15 * omega.abs());
    }
    assert!(kinds[0] > 0 && kinds[1] > 0, "{kinds:?}");
}

/// A landing on two stacks, one sliding on the other: the body's angular momentum about its
/// new corner is kept; each joint passes the friction impulse the momenta above it say (the
/// body's and the stacks'), at its limit against its slip where the slip goes on, within it
/// where the impact stopped the slip (the two sides then at one velocity exactly, or the
/// lowest at rest); kinetic energy is lost; and every one of the four ways is met.
#[test]
fn a_landing_on_stacks_sliding_on_stacks_keeps_each_joints_law() {
    let body = top(0.8);
    let (m, b, h) = (body.mass_kg, body.half_base_m, body.centroid_height_m);
    let mut kinds = std::collections::BTreeSet::new();
    for (pivot, omega) in [
        (Corner::Right, -1.3),
        (Corner::Left, 0.9),
        (Corner::Left, 0.3),
    ] {
        let s = pivot.sign();
        for (v1, v2) in [
            (0.4, 0.1),
            (-0.6, -0.5),
            (0.01, 0.008),
            (0.5, 0.02),
            (-0.05, -0.3),
        ] {
            for (m1, m2) in [(300.0, 2000.0), (2000.0, 300.0)] {
                let slip = |v: f64| {
                    if v > 0.0 {
                        Slip::Forward
                    } else {
                        Slip::Backward
                    }
                };
                let upper = Stack {
                    first: 1,
                    friction: 0.35,
                    ..stack(m1, slip(v1 - v2))
                };
                let lower = Stack {
                    friction: 0.4,
                    ..stack(m2, slip(v2))
                };
                let Some(l) = landing(&body, &[upper, lower], &[v1, v2], pivot, omega) else {
                    continue;
                };
                kinds.insert(l.stuck.clone());
                let (before, after) = (
                    (v1 + h * omega, s * b * omega),
                    (l.v[0] + h * l.omega, -s * b * l.omega),
                );
                let kept = about_new_corner(&body, s, omega, before);
                let now = about_new_corner(&body, s, l.omega, after);
                assert!((kept - now).abs() <= 1e-12 * kept.abs(), "{kept} {now}");
                let normal = m * (after.1 - before.1);
                assert!(normal >= 0.0);
                let mut passed = m * (after.0 - before.0);
                for (k, (st, v)) in [(upper, v1), (lower, v2)].into_iter().enumerate() {
                    passed += st.mass_kg * (l.v[k] - v);
                    let under = l.v.get(k + 1).copied().unwrap_or(0.0);
                    if l.stuck[k] {
                        assert_eq!(l.v[k], under, "{l:?}");
                        assert!(passed.abs() <= st.friction * normal, "{passed} {normal}");
                    } else {
                        assert!(st.slip.sign() * (l.v[k] - under) > 0.0, "{l:?}");
                        let limit = -st.friction * st.slip.sign() * normal;
                        assert!((passed - limit).abs() <= 1e-12 * normal, "{passed} {limit}");
                    }
                }
                assert!(l.loss_j > 0.0, "{l:?}");
            }
        }
    }
    assert_eq!(kinds.len(), 4, "{kinds:?}");
}
