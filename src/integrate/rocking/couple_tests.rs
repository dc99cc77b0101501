//! A couple's series against the laws they must obey, written here on their own: each body's
//! Newton-Euler equations about its centroid with the ground's forces and the push (the push
//! alone on a body in flight), Coulomb's law at a slipping pivot, and the corner staying on the
//! face.

use super::body::RockingBody;
use super::clearance::{Side, Touch};
use super::couple::{Couple, Member};
use super::enumeration::PivotLaw;
use super::modes::{test_inputs_at, Corner, Mode, Slip, State};
use super::series::{derivative, eval};

/// Slab A (0.3 x 1.2 m) rocking on its right corner, its top right corner on the left face of
/// slab B (0.2 x 1.6 m), which rocks on its left corner or flies from it, lifted by l_b: where
/// B's pivot stands, so that the corner touches the face, for A's slip u_a and the rotations.
fn face_pivot(theta_a: f64, u_a: f64, theta_b: f64, l_b: f64) -> f64 {
    let corner = [0.3 + u_a + 1.2 * theta_a.sin(), 1.2 * theta_a.cos()];
    let y = (corner[1] - l_b) / theta_b.cos();
    corner[0] - y * theta_b.sin()
}

/// The distance of A's corner from B's face (m), B's pivot at (x_b + u_b, l_b).
fn gap(x_b: f64, [theta_a, u_a, theta_b, u_b, l_b]: [f64; 5]) -> f64 {
    let corner = [0.3 + u_a + 1.2 * theta_a.sin(), 1.2 * theta_a.cos()];
    let n = [-theta_b.cos(), theta_b.sin()];
    (corner[0] - x_b - u_b) * n[0] + (corner[1] - l_b) * n[1]
}

/// How B moves in each case: A's pivot slips towards B and B's sticks, both slip towards each
/// other, or A's slips and B flies.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Case {
    OneSlips,
    BothSlip,
    BFlies,
    BSeated,
    BSlides,
}

/// Where `body`'s centroid stands from its pivot (the corner of sign s) turned by theta, and
/// the centroid's acceleration, from theta, theta', theta'' and the pivot's u'' and lift''.
pub(super) fn centroid(
    body: &RockingBody,
    s: f64,
    [theta, omega, theta2, u2, lift2]: [f64; 5],
) -> ([f64; 2], [f64; 2]) {
    let (bb, hh) = (body.half_base_m, body.centroid_height_m);
    let (sin, cos) = theta.sin_cos();
    // The centroid from the pivot and its derivatives in theta.
    let r = [-s * bb * cos + hh * sin, s * bb * sin + hh * cos];
    let r1 = [s * bb * sin + hh * cos, s * bb * cos - hh * sin];
    let r2 = [s * bb * cos - hh * sin, -s * bb * sin - hh * cos];
    (
        r,
        [
            u2 + r1[0] * theta2 + r2[0] * omega * omega,
            lift2 + r1[1] * theta2 + r2[1] * omega * omega,
        ],
    )
}

/// Two slabs turning together, A's pivot slipping towards B and B's pivot stuck, slipping
/// towards A, or off the ground (B in flight): over 0.02 s of the couple's series under the
/// test sine, at every instant sampled each body's Newton-Euler equations about its centroid
/// hold with the ground's forces and the push (to 1e-12 of its weight; a body in flight has no
/// ground force and its pivot rises as it must), each slipping pivot's friction is mu N against
/// its slip, every normal force and the push press, and the corner stays on the face (to 1e-15
/// m).
#[test]
fn a_couple_with_slipping_or_flying_pivots_obeys_newton_euler_coulomb_and_its_contact() {
    for case in [
        Case::OneSlips,
        Case::BothSlip,
        Case::BFlies,
        Case::BSeated,
        Case::BSlides,
    ] {
        let g = 9.81;
        let a = RockingBody::rectangle("A", 0.3, 1.2, 1350.0, 0.4, g);
        let b = RockingBody::rectangle("B", 0.2, 1.6, 800.0, 0.5, g);
        let seated = matches!(case, Case::BSeated | Case::BSlides);
        let (theta_a, u_a, theta_b) = (0.3, 0.01, if seated { 0.0 } else { -0.1 });
        let (l_b, w_b) = match case {
            Case::BFlies => (0.02, 0.3),
            _ => (0.0, 0.0),
        };
        let x_b = face_pivot(theta_a, u_a, theta_b, l_b);
        let corner = [0.3 + u_a + 1.2 * theta_a.sin(), 1.2 * theta_a.cos()];
        let normal = [-theta_b.cos(), theta_b.sin()];
        let touch = Touch {
            blocks: [0, 1],
            sides: [Side::Body(0, [0.15, 0.0]), Side::Body(1, [x_b + 0.1, l_b])],
            point: corner,
            normal,
            scales: (0.1, 1.0),
            pair: 0,
            corner: 2,
            edge: 3,
            stays: false,
        };
        // Velocities that keep the corner on the face: d gap / dt = 0.
        let v_b = match case {
            Case::OneSlips | Case::BSeated => 0.0,
            _ => -0.5,
        };
        let v_a = 1.0;
        // gap = (C_x - x_b - u_b) (-cos theta_b) + (C_y - l_b) sin theta_b: its partials.
        let (sa, ca) = theta_a.sin_cos();
        let (sb, cb) = theta_b.sin_cos();
        let d_theta_a = -1.2 * ca * cb - 1.2 * sa * sb;
        let d_theta_b = (corner[0] - x_b) * sb + (corner[1] - l_b) * cb;
        // A seated B does not turn: A's rate keeps the corner on B's face.
        let omega_a = if seated {
            (cb * v_a - cb * v_b) / d_theta_a
        } else {
            0.5
        };
        let omega_b = if seated {
            0.0
        } else {
            -(d_theta_a * omega_a - cb * v_a + cb * v_b - sb * w_b) / d_theta_b
        };
        let states = [
            State {
                theta: theta_a,
                omega: omega_a,
                u: u_a,
                v: v_a,
                ..State::default()
            },
            State {
                theta: theta_b,
                omega: omega_b,
                v: v_b,
                lift: l_b,
                lift_v: w_b,
                ..State::default()
            },
        ];
        let homes = [[0.3, 0.0], [x_b, 0.0]];
        let couple = Couple::new(
            &touch,
            [Some(0), Some(1)],
            homes,
            [Some(&states[0]), Some(&states[1])],
            1e-12,
        )
        .unwrap();
        let modes = [
            Mode::SlideRock(Corner::Right, Slip::Forward),
            match case {
                Case::OneSlips => Mode::Rock(Corner::Left),
                Case::BothSlip => Mode::SlideRock(Corner::Left, Slip::Backward),
                Case::BFlies => Mode::Flight(Corner::Left),
                Case::BSeated => Mode::Rest,
                Case::BSlides => Mode::Slide(Slip::Backward),
            },
        ];
        let bodies = [&a, &b];
        let inputs = test_inputs_at(0.4);
        let motion = couple.motion(
            [0, 1].map(|k| Member::Moves(bodies[k], modes[k], &states[k])),
            &inputs,
        );
        assert!(motion.compliance > 0.0);
        let at = |tau: f64| {
            let t = &motion.bodies;
            [
                eval(&t[0].theta, tau),
                eval(&t[0].u, tau),
                eval(&t[1].theta, tau),
                eval(&t[1].u, tau),
                eval(&t[1].lift, tau),
            ]
        };
        for tau in [0.0, 0.005, 0.01, 0.02] {
            let [ta, ua, tb, ub, lb] = at(tau);
            let face = gap(x_b, [ta, ua, tb, ub, lb]);
            assert!(face.abs() < 1e-15, "{case:?} {tau}: {face}");
            let push = eval(&motion.push, tau);
            assert!(push > 0.0, "{push}");
            let n = [-tb.cos(), tb.sin()];
            let contact = [0.3 + ua + 1.2 * ta.sin(), 1.2 * ta.cos()];
            let (accel, lambda) = (eval(&inputs.accel, tau), eval(&inputs.lambda, tau));
            for k in 0..2 {
                let (body, t) = (bodies[k], &motion.bodies[k]);
                // A seated B's pivot's home is its left corner, the centroid at (b, h) from it.
                let s = modes[k].corner().map_or(-1.0, Corner::sign);
                let on = if k == 0 { 1.0 } else { -1.0 };
                let (bb, hh, m) = (body.half_base_m, body.centroid_height_m, body.mass_kg);
                let theta = eval(&t.theta, tau);
                let omega = eval(&t.omega, tau);
                let theta2 = eval(&derivative(&t.omega), tau);
                let u2 = eval(&derivative(&t.v), tau);
                let lift2 = eval(&derivative(&t.lift_v), tau);
                let (f, normal_n) = (eval(&t.tangential, tau), eval(&t.normal, tau));
                let (r, [gx2, gy2]) = centroid(body, s, [theta, omega, theta2, u2, lift2]);
                let p = [on * push * n[0], on * push * n[1]];
                let weight = m * g;
                assert!(
                    (m * (gx2 + accel) - f - p[0]).abs() < 1e-12 * weight,
                    "{case:?} {k} {tau}"
                );
                assert!(
                    (m * (gy2 + g * lambda) - normal_n - p[1]).abs() < 1e-12 * weight,
                    "{case:?} {k} {tau}"
                );
                // About the centroid, clockwise: the ground's force at the pivot (-r from G)
                // and the push at the contact.
                let pivot = [homes[k][0] + eval(&t.u, tau), eval(&t.lift, tau)];
                let centroid = [pivot[0] + r[0], pivot[1] + r[1]];
                let cross = |a: [f64; 2], b: [f64; 2]| a[0] * b[1] - a[1] * b[0];
                let to_contact = [contact[0] - centroid[0], contact[1] - centroid[1]];
                if seated && k == 1 {
                    // Seated: no turn, the ground's forces at the base's corners and the push
                    // in balance about the centroid (whether both corners press is the
                    // engine's uplift condition, not the motion's).
                    let (left, right) = t.corners.as_ref().unwrap();
                    let (nl, nr) = (eval(left, tau), eval(right, tau));
                    assert_eq!(theta2, 0.0);
                    assert!((nl + nr - normal_n).abs() < 1e-12 * weight);
                    let moment = bb * (nr - nl) + hh * f + cross(to_contact, p);
                    assert!(moment.abs() < 1e-12 * weight, "{case:?} {tau}: {moment}");
                    if let Mode::Slide(slip) = modes[k] {
                        let coulomb = -body.friction * slip.sign() * normal_n;
                        assert!((f - coulomb).abs() < 1e-12 * weight, "{case:?} {tau}");
                        assert!(eval(&t.v, tau) * slip.sign() > 0.0);
                    } else {
                        assert_eq!(eval(&t.v, tau), 0.0);
                    }
                    continue;
                }
                let torque = -cross([-r[0], -r[1]], [f, normal_n]) - cross(to_contact, p);
                assert!(
                    (body.inertia_kg_m2 * theta2 - torque).abs() < 1e-12 * weight * 1.6,
                    "{case:?} {k} {tau}"
                );
                if let Mode::Flight(_) = modes[k] {
                    assert_eq!((f, normal_n), (0.0, 0.0));
                    assert!(lb > 0.0, "{lb}");
                    continue;
                }
                assert!(normal_n > 0.0);
                if let Mode::SlideRock(_, slip) = modes[k] {
                    let coulomb = -body.friction * slip.sign() * normal_n;
                    assert!((f - coulomb).abs() < 1e-12 * weight, "{case:?} {k} {tau}");
                    assert!(eval(&t.v, tau) * slip.sign() > 0.0);
                } else {
                    assert_eq!(eval(&t.v, tau), 0.0);
                }
            }
        }
    }
}

/// A block leaning on a fixed block's face, its pivot stuck, slipping or leaving the ground:
/// the couple's decision against an enumeration of every law of its pivot and its contact
/// (closed, pressing, or open, parting), written here with nalgebra. Where exactly one law holds
/// and keeps the contact, the couple takes it; where none or two hold (Painleve's paradox: a
/// slipping pivot whose effective mass, or a contact whose compliance, is not positive), the
/// couple refuses, naming the paradox. Cases whose one law opens the contact are the parting
/// the engine finds from the push (not this decision's), and are left out; the grid holds each
/// of the other outcomes.
#[test]
fn a_leaning_blocks_decision_is_the_contact_law_and_painleves_cases_are_refused() {
    use super::modes::Inputs;
    use super::series::ZERO;
    let g = 9.81;
    let (b, h) = (0.25, 0.5);
    let mut seen = std::collections::BTreeMap::new();
    for theta in [0.05f64, 0.3, 0.6] {
        for v in [-5.0, -0.2, 0.0, 0.2, 5.0] {
            for a in [-15.0, -6.0, -2.0, 0.0, 2.0, 6.0, 15.0] {
                for mu in [0.3, 0.8, 1.5, 2.5, 4.0] {
                    let body = RockingBody::rectangle("T", 2.0 * b, 2.0 * h, 500.0, mu, g);
                    // The top right corner on the fixed face, kept there by the rates.
                    let omega = -v / (2.0 * h * theta.cos());
                    let state = State {
                        theta,
                        omega,
                        v,
                        ..State::default()
                    };
                    let corner = [2.0 * b + 2.0 * h * theta.sin(), 2.0 * h * theta.cos()];
                    let touch = Touch {
                        blocks: [0, 1],
                        sides: [Side::Body(0, [b, 0.0]), Side::Fixed],
                        point: corner,
                        normal: [-1.0, 0.0],
                        scales: (0.1, 1.0),
                        pair: 0,
                        corner: 2,
                        edge: 3,
                        stays: false,
                    };
                    let homes = [[2.0 * b, 0.0], corner];
                    let couple =
                        Couple::new(&touch, [Some(0), None], homes, [Some(&state), None], 1e-12)
                            .unwrap();
                    let laws = |tol| enumerate_leaning(&body, &state, a, tol);
                    let strict = laws(1e-7);
                    if strict != laws(-1e-7) {
                        continue;
                    }
                    let mut inputs = Inputs {
                        accel: ZERO,
                        lambda: ZERO,
                    };
                    inputs.accel[0] = a;
                    inputs.lambda[0] = 1.0;
                    let member = Member::Moves(&body, Mode::Rock(Corner::Right), &state);
                    let decided = couple.decide([member, Member::Fixed], &inputs);
                    let case = format!("{state:?} a_g {a} mu {mu}: {strict:?}");
                    let outcome = match (&strict[..], decided) {
                        ([(_, false)], _) => "opens",
                        ([(one, true)], Ok([Some(mode), None])) => {
                            let law = match mode {
                                Mode::Rock(_) => "stuck",
                                Mode::SlideRock(..) => "slipping",
                                Mode::Flight(_) => "off",
                                other => panic!("{case}: {other:?}"),
                            };
                            assert_eq!(law, *one, "{case}");
                            "one"
                        }
                        ([_], other) => panic!("{case}: {other:?}"),
                        (_, Ok(modes)) => panic!("{case}: decided {modes:?}"),
                        (ways, Err(e)) => {
                            assert!(e.contains("Painleve's paradox"), "{case}: {e}");
                            if ways.is_empty() {
                                "none"
                            } else {
                                "two"
                            }
                        }
                    };
                    *seen.entry(outcome).or_insert(0) += 1;
                }
            }
        }
    }
    assert_eq!(seen.len(), 4, "{seen:?}");
}

/// Every law of the leaning block's pivot (off, stuck, slipping the way it slips, or either way
/// from rest) with its contact closed (the corner's acceleration along the face's normal zero,
/// the push pressing) or open (no push, the corner leaving the face): unknowns (theta'', u'',
/// l'', F, N, P), the block's Newton-Euler equations about its centroid. Each law that holds,
/// and whether its contact stays closed.
fn enumerate_leaning(
    body: &RockingBody,
    state: &State,
    a_g: f64,
    tol: f64,
) -> Vec<(&'static str, bool)> {
    use nalgebra::{SMatrix, SVector};
    let g = body.g_m_s2;
    let (m, ig, b, h, mu) = (
        body.mass_kg,
        body.inertia_kg_m2,
        body.half_base_m,
        body.centroid_height_m,
        body.friction,
    );
    let (sin, cos) = state.theta.sin_cos();
    let (gy, dx, w) = (b * sin + h * cos, b * cos - h * sin, state.omega.powi(2));
    // The corner from the pivot, the face's normal, and the corner from the centroid.
    let t = [2.0 * h * sin, 2.0 * h * cos];
    let n = [-1.0, 0.0];
    let arm = [t[0] + dx, t[1] - gy];
    let arm_x_n = arm[0] * n[1] - arm[1] * n[0];
    let (force, accel) = (tol * m * g, tol * g);
    let mut out = Vec::new();
    for law in PivotLaw::ways(state) {
        for closed in [true, false] {
            let mut k = SMatrix::<f64, 6, 6>::zeros();
            let mut rhs = SVector::<f64, 6>::zeros();
            (k[(0, 1)], k[(0, 0)], k[(0, 3)], k[(0, 5)]) = (m, m * gy, -1.0, -n[0]);
            rhs[0] = -m * (dx * w + a_g);
            (k[(1, 2)], k[(1, 0)], k[(1, 4)], k[(1, 5)]) = (m, m * dx, -1.0, -n[1]);
            rhs[1] = m * (gy * w - g);
            (k[(2, 0)], k[(2, 3)], k[(2, 4)], k[(2, 5)]) = (ig, gy, dx, arm_x_n);
            law.rows(&mut k, mu);
            // The corner's acceleration along n: u'' + theta'' t_y - w t_x across, l'' -
            // theta'' t_x - w t_y up.
            let gap = |x: &SVector<f64, 6>| {
                n[0] * (x[1] + x[0] * t[1] - w * t[0]) + n[1] * (x[2] - x[0] * t[0] - w * t[1])
            };
            if closed {
                (k[(5, 1)], k[(5, 2)], k[(5, 0)]) = (n[0], n[1], n[0] * t[1] - n[1] * t[0]);
                rhs[5] = w * (n[0] * t[0] + n[1] * t[1]);
            } else {
                k[(5, 5)] = 1.0;
            }
            let Some(x) = k.lu().solve(&rhs) else {
                continue;
            };
            let pivot = law.holds(x.as_slice(), state, mu, force, accel);
            let contact = if closed {
                x[5] > force
            } else {
                gap(&x) > accel
            };
            if pivot && contact {
                out.push((law.name(), closed));
            }
        }
    }
    out
}

/// Two slabs in flight, the top right corner of A (0.3 x 1.2 m, its right corner lifted by l_a)
/// on the left face of B (0.2 x 1.6 m, its left corner lifted by l_b), each turning and moving
/// at its own rates: the acceleration at which the corner leaves the face (twice the second
/// coefficient of `Couple::gap`, what decides which ends of two faces lying on each other stay
/// pressed) is the second derivative of the corner's distance from the face, written here in
/// closed form from each body's trajectory alone (to 1e-12 of g), and zero on the couple's own
/// motion, whose push keeps the corner on the face (to 1e-12 of g).
#[test]
fn the_acceleration_at_which_a_corner_leaves_a_face_is_the_distances_second_derivative() {
    use super::modes::{trajectory, Equations};
    let g = 9.81;
    let a = RockingBody::rectangle("A", 0.3, 1.2, 1350.0, 0.4, g);
    let b = RockingBody::rectangle("B", 0.2, 1.6, 800.0, 0.5, g);
    let inputs = test_inputs_at(0.4);
    for (theta_a, theta_b, spin) in [(0.3, -0.1, 1.0), (0.05, 0.05, -2.0), (-0.2, 0.4, 0.5)] {
        let (l_a, l_b, u_a) = (0.01, 0.03, 0.02);
        let corner = [
            0.3 + u_a + 1.2 * f64::sin(theta_a),
            l_a + 1.2 * f64::cos(theta_a),
        ];
        let x_b = corner[0] - (corner[1] - l_b) / f64::cos(theta_b) * f64::sin(theta_b);
        let states = [
            State {
                theta: theta_a,
                omega: 0.7 * spin,
                u: u_a,
                v: 0.4,
                lift: l_a,
                lift_v: 0.2,
            },
            State {
                theta: theta_b,
                omega: -0.3 * spin,
                u: 0.0,
                v: -0.5,
                lift: l_b,
                lift_v: 0.1 * spin,
            },
        ];
        let touch = Touch {
            blocks: [0, 1],
            sides: [Side::Body(0, [0.15, 0.0]), Side::Body(1, [x_b + 0.1, 0.0])],
            point: corner,
            normal: [-f64::cos(theta_b), f64::sin(theta_b)],
            scales: (0.1, 1.0),
            pair: 0,
            corner: 2,
            edge: 3,
            stays: false,
        };
        let homes = [[0.3, 0.0], [x_b, 0.0]];
        let placed = [Some(&states[0]), Some(&states[1])];
        let couple = Couple::new(&touch, [Some(0), Some(1)], homes, placed, 1e-12).unwrap();
        let modes = [Mode::Flight(Corner::Right), Mode::Flight(Corner::Left)];
        let bodies = [&a, &b];
        let alone =
            [0, 1].map(|k| trajectory(bodies[k], Equations::Exact, modes[k], &states[k], &inputs));
        // The distance -(C_x - x_B) cos theta_B + (C_y - y_B) sin theta_B, C the corner and
        // (x_B, y_B) B's pivot, differentiated twice.
        let [ta, tb] = &alone;
        let (th_a, w_a, al_a) = (ta.theta[0], ta.omega[0], ta.omega[1]);
        let (th_b, w_b, al_b) = (tb.theta[0], tb.omega[0], tb.omega[1]);
        let (sa, ca) = th_a.sin_cos();
        let (sb, cb) = th_b.sin_cos();
        let d = [
            0.3 + ta.u[0] + 1.2 * sa - x_b - tb.u[0],
            ta.v[0] + 1.2 * ca * w_a - tb.v[0],
            ta.v[1] + 1.2 * (ca * al_a - sa * w_a * w_a) - tb.v[1],
        ];
        let e = [
            ta.lift[0] + 1.2 * ca - tb.lift[0],
            ta.lift_v[0] - 1.2 * sa * w_a - tb.lift_v[0],
            ta.lift_v[1] - 1.2 * (sa * al_a + ca * w_a * w_a) - tb.lift_v[1],
        ];
        let closed = -d[2] * cb
            + 2.0 * d[1] * sb * w_b
            + d[0] * (cb * w_b * w_b + sb * al_b)
            + e[2] * sb
            + 2.0 * e[1] * cb * w_b
            + e[0] * (cb * al_b - sb * w_b * w_b);
        let away = 2.0 * couple.gap(&alone)[2];
        assert!((away - closed).abs() < 1e-12 * g, "{away} {closed}");
        assert!(away.abs() > 1e-3 * g, "a case that shows nothing: {away}");
        let motion = couple.motion(
            [0, 1].map(|k| Member::Moves(bodies[k], modes[k], &states[k])),
            &inputs,
        );
        let held = 2.0 * couple.gap(&motion.bodies)[2];
        assert!(held.abs() < 1e-12 * g, "{held}");
    }
}
