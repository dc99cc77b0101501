//! A couple's series against the laws they must obey, written here on their own: each body's
//! Newton-Euler equations about its centroid with the ground's forces and the push (the push
//! alone on a body in flight), Coulomb's law at a slipping pivot, and the corner staying on the
//! face.

use super::body::RockingBody;
use super::clearance::{Side, Touch};
use super::couple::{Couple, Member};
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
    for case in [Case::OneSlips, Case::BothSlip, Case::BFlies] {
        let g = 9.81;
        let a = RockingBody::rectangle("A", 0.3, 1.2, 1350.0, 0.4, g);
        let b = RockingBody::rectangle("B", 0.2, 1.6, 800.0, 0.5, g);
        let (theta_a, u_a, theta_b) = (0.3, 0.01, -0.1);
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
            tie_m_s: 1e-12,
            pair: 0,
            corner: 2,
            stays: false,
        };
        // Velocities that keep the corner on the face: d gap / dt = 0.
        let (omega_a, v_a) = (0.5, 1.0);
        let v_b = if case == Case::OneSlips { 0.0 } else { -0.5 };
        // gap = (C_x - x_b - u_b) (-cos theta_b) + (C_y - l_b) sin theta_b: its partials.
        let (sa, ca) = theta_a.sin_cos();
        let (sb, cb) = theta_b.sin_cos();
        let d_theta_a = -1.2 * ca * cb - 1.2 * sa * sb;
        let d_theta_b = (corner[0] - x_b) * sb + (corner[1] - l_b) * cb;
        let omega_b = -(d_theta_a * omega_a - cb * v_a + cb * v_b - sb * w_b) / d_theta_b;
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
                let s = modes[k].corner().unwrap().sign();
                let on = if k == 0 { 1.0 } else { -1.0 };
                let (bb, hh, m) = (body.half_base_m, body.centroid_height_m, body.mass_kg);
                let theta = eval(&t.theta, tau);
                let omega = eval(&t.omega, tau);
                let theta2 = eval(&derivative(&t.omega), tau);
                let u2 = eval(&derivative(&t.v), tau);
                let lift2 = eval(&derivative(&t.lift_v), tau);
                let (f, normal_n) = (eval(&t.tangential, tau), eval(&t.normal, tau));
                let (sin, cos) = theta.sin_cos();
                // The centroid from the pivot and its derivatives in theta.
                let r = [-s * bb * cos + hh * sin, s * bb * sin + hh * cos];
                let r1 = [s * bb * sin + hh * cos, s * bb * cos - hh * sin];
                let r2 = [s * bb * cos - hh * sin, -s * bb * sin - hh * cos];
                let gx2 = u2 + r1[0] * theta2 + r2[0] * omega * omega;
                let gy2 = lift2 + r1[1] * theta2 + r2[1] * omega * omega;
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
                let torque = -cross([-r[0], -r[1]], [f, normal_n])
                    - cross([contact[0] - centroid[0], contact[1] - centroid[1]], p);
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
