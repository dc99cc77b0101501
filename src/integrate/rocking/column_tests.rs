//! Tests of the column model's watch: its forces against the body's own equations, and the
//! impulses of landings through held joints.
use super::*;
use crate::integrate::rocking::modes::{self, Equations, Mode, Slip, State};

/// A column of three blocks of different sizes, one joint given its own friction: the top
/// block moves on the others (it tips first), or with a low friction between the lower two
/// the upper two move as one body.
fn column_of(joint: &str, friction: f64) -> Column {
    let model = crate::model::Model::from_ron_str(&format!(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
          joint_friction: {{\"{joint}\": {friction}}},
          rows: [(height_m: 0.4, blocks: [(width_m: 1.2, name: \"A\")]),
                 (height_m: 0.6, x_m: 0.2, blocks: [(width_m: 0.8, name: \"B\")]),
                 (height_m: 1.5, x_m: 0.35, blocks: [(width_m: 0.5, name: \"C\")])])"
    ))
    .unwrap();
    let mut c = columns(model.wall(), model.topology()).unwrap();
    assert_eq!(c.len(), 1);
    c.remove(0)
}

/// The watch with one joint more: the body's own base, so that what it computes there can
/// be checked against the contact forces of the body's equations.
fn with_own_base(c: &Column) -> Watch {
    let mut w = c.watch.clone();
    let b = c.body.half_base_m;
    w.joints = vec![Held {
        name: "own base".into(),
        upper: 0,
        friction: c.body.friction,
        ends: [(-b, 0.0), (b, 0.0)],
        inside: false,
        above: (0..w.pieces.len())
            .filter(|&i| w.pieces[i].moving)
            .collect(),
        upper_corner: [true; 2],
    }];
    w
}

use modes::test_inputs_at as inputs_at;

/// The d'Alembert balance of the body's pieces gives back, at its own base, the contact
/// forces its equations of motion give (normal, tangential) and the resultant where the
/// mode puts it: through the pivot while it rocks (no moment about that end, 2 b N about
/// the other), at the corner forces while seated; along a step, to round-off.
#[test]
fn the_watch_balances_the_bodys_own_contact_forces() {
    for (joint, friction, pieces) in [("C/B", 0.9, 1), ("B/A", 0.2, 2)] {
        let c = column_of(joint, friction);
        assert_eq!(
            c.watch.pieces.iter().filter(|p| p.moving).count(),
            pieces,
            "{}",
            c.body.name
        );
        let w = with_own_base(&c);
        let b = c.body.half_base_m;
        let inputs = inputs_at(0.37);
        let rocking = State {
            theta: 0.04,
            omega: -0.3,
            ..State::default()
        };
        let sliding = State { v: 0.05, ..rocking };
        let cases = [
            (Mode::Rock(Corner::Right), rocking),
            (
                Mode::Rock(Corner::Left),
                State {
                    theta: -0.04,
                    ..rocking
                },
            ),
            (Mode::SlideRock(Corner::Right, Slip::Forward), sliding),
            (Mode::Rest, State::default()),
            (
                Mode::Slide(Slip::Backward),
                State {
                    v: -0.1,
                    ..State::default()
                },
            ),
        ];
        for (mode, state) in cases {
            let t = modes::trajectory(&c.body, Equations::Exact, mode, &state, &inputs);
            let cond = w.conditions(&t, &inputs, &Displaced::default());
            let force = c.body.mass_kg * c.body.g_m_s2;
            for tau in [0.0, 0.01, 0.03] {
                let at = |k: usize| crate::integrate::rocking::series::eval(&cond[k].series, tau);
                let e = |s: &Coeffs| crate::integrate::rocking::series::eval(s, tau);
                let mu = c.body.friction;
                let normal = (at(0) + at(1)) / (2.0 * mu);
                let tangential = (at(1) - at(0)) / 2.0;
                let close = |a: f64, b: f64, what: &str| {
                    assert!(
                        (a - b).abs() <= 1e-12 * force,
                        "{}: {mode:?} tau {tau}: {what} {a} against {b}",
                        c.body.name
                    )
                };
                close(normal, e(&t.normal), "normal");
                close(tangential, e(&t.tangential), "tangential");
                // The pivot has moved by u (sliding): moments about the base's ends at rest.
                let u = e(&t.u);
                let (left, right) = (at(2), at(3));
                match mode.pivot() {
                    Some(Corner::Right) => {
                        close(
                            left / (2.0 * b + u),
                            e(&t.normal),
                            "moment about the left end",
                        );
                        close(
                            right,
                            -u * e(&t.normal),
                            "moment about the pivot's place at rest",
                        );
                    }
                    Some(Corner::Left) => {
                        close(
                            left,
                            u * e(&t.normal),
                            "moment about the pivot's place at rest",
                        );
                        close(
                            right / (2.0 * b - u),
                            e(&t.normal),
                            "moment about the right end",
                        );
                    }
                    None => {
                        let (nl, nr) = t.corners.as_ref().unwrap();
                        close(
                            left / (2.0 * b),
                            e(nr) + u * e(&t.normal) / (2.0 * b),
                            "left",
                        );
                        close(
                            right / (2.0 * b),
                            e(nl) - u * e(&t.normal) / (2.0 * b),
                            "right",
                        );
                    }
                }
            }
        }
    }
}

/// Through a landing on the other corner the impulse passes through the new pivot alone
/// (Housner): no moment about that end, and the normal impulse m (v_Gy after - before).
#[test]
fn a_landing_passes_its_impulse_through_the_new_pivot() {
    for (joint, friction) in [("C/B", 0.9), ("B/A", 0.2)] {
        let c = column_of(joint, friction);
        let w = with_own_base(&c);
        let landing =
            super::super::impact::land(&c.body, Equations::Exact, Corner::Right, -0.4, 0.0, 1.0)
                .unwrap();
        assert_eq!(landing.pivot, Some(Corner::Left));
        let before = (Some(Corner::Right), -0.4, 0.0);
        let after = (landing.pivot, landing.state.omega, landing.state.v);
        let still = Displaced::default();
        let m = w.impulse_margins(&w.joints[0], 0.0, (before, after), (&still, &still));
        let b = c.body.half_base_m;
        let h = c.body.centroid_height_m;
        // v_Gy = -omega x_G about the pivot: x_G = -b about the right corner, +b about the left.
        let jn = c.body.mass_kg * (-after.1 * b - (-before.1 * -b));
        let scale = c.body.mass_kg * 0.4 * (b + h);
        assert!(m[2].abs() <= 1e-12 * scale, "{}: {m:?}", c.body.name);
        assert!(
            (-m[3] / (-2.0 * b) - jn).abs() <= 1e-12 * scale / b,
            "{m:?} {jn}"
        );
        assert_eq!(
            w.landing(
                0.0,
                before,
                after,
                &Displaced::default(),
                &Displaced::default()
            ),
            None
        );
    }
}
