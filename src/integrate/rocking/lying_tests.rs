//! The motion of two faces lying on each other against the laws it must obey, written here on
//! their own: each body's Newton-Euler equations about its centroid with the two pushes (bodies
//! in flight: nothing else but their weight and the ground's inertial force), and both ends of
//! the faces' overlap staying on the face they lie on.

use super::body::RockingBody;
use super::clearance::{Side, Touch};
use super::couple::Member;
use super::couple_tests::centroid;
use super::lying::Lying;
use super::modes::{test_inputs_at, Corner, Mode, State};
use super::series::{derivative, eval};

/// The clockwise rotation by theta of r.
fn turned(r: [f64; 2], theta: f64) -> [f64; 2] {
    let (sin, cos) = theta.sin_cos();
    [r[0] * cos + r[1] * sin, -r[0] * sin + r[1] * cos]
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Slab A (0.3 x 1.2 m) and slab B (0.2 x 1.6 m), both in flight, turned by 0.2 rad, A's right
/// face on B's left face, B's base 0.1 m up the face from A's: the overlap's ends are A's top
/// right corner on B's face and B's bottom left corner on A's. Both turn at 0.5 rad/s and
/// slide along each other (their pivots' velocities differ, with no velocity along the faces'
/// normal). Over 0.02 s of the motion under the test sine, at every instant sampled both ends
/// stay on the face they lie on (to 1e-15 m), and each body's Newton-Euler equations about its
/// centroid hold with the two pushes at the two ends (to 1e-12 of its weight); the contact
/// problem's matrix is positive definite and the pushes are not round-off.
#[test]
fn faces_lying_on_each_other_in_flight_obey_newton_euler_and_stay_on_each_other() {
    let g = 9.81;
    let a = RockingBody::rectangle("A", 0.3, 1.2, 1350.0, 0.4, g);
    let b = RockingBody::rectangle("B", 0.2, 1.6, 800.0, 0.5, g);
    let (theta, omega, d) = (0.2f64, 0.5, 0.1);
    let (sin, cos) = theta.sin_cos();
    // A's pivot (its right corner) and B's (its left corner), lifted; B's d up A's face.
    let home_a = [0.3, 0.0];
    let pivot_a = [0.3, 0.05];
    let pivot_b = [pivot_a[0] + d * sin, pivot_a[1] + d * cos];
    let home_b = [pivot_b[0], 0.0];
    // The faces' relative normal velocity, dv cos - dl sin + omega d, is zero.
    let (v_a, v_b) = (0.3, 0.1);
    let (lift_v_a, lift_v_b) = (0.2, 0.2 - ((v_a - v_b) * cos + omega * d) / sin);
    let states = [
        State {
            theta,
            omega,
            v: v_a,
            lift: pivot_a[1],
            lift_v: lift_v_a,
            ..State::default()
        },
        State {
            theta,
            omega,
            v: v_b,
            lift: pivot_b[1],
            lift_v: lift_v_b,
            ..State::default()
        },
    ];
    let sides = [
        Side::Body(0, [0.15, 0.0]),
        Side::Body(1, [home_b[0] + 0.1, 0.0]),
    ];
    let top = turned([0.0, 1.2], theta);
    let ends = [
        Touch {
            blocks: [0, 1],
            sides,
            point: [pivot_a[0] + top[0], pivot_a[1] + top[1]],
            normal: [-cos, sin],
            scales: (0.1, 1.0),
            pair: 0,
            corner: 2,
            edge: 3,
            stays: true,
        },
        Touch {
            blocks: [1, 0],
            sides: [sides[1], sides[0]],
            point: pivot_b,
            normal: [cos, -sin],
            scales: (0.1, 1.0),
            pair: 0,
            corner: 0,
            edge: 1,
            stays: true,
        },
    ];
    let lying = Lying::new(
        [&ends[0], &ends[1]],
        [0, 1],
        [home_a, home_b],
        [&states[0], &states[1]],
    );
    let bodies = [&a, &b];
    let modes = [Mode::Flight(Corner::Right), Mode::Flight(Corner::Left)];
    let homes = [home_a, home_b];
    let inputs = test_inputs_at(0.4);
    let motion = lying.motion(
        [0, 1].map(|k| Member::Moves(bodies[k], modes[k], &states[k])),
        &inputs,
    );
    let [[w00, w01], [w10, w11]] = motion.compliance;
    assert!(w00 > 0.0 && w11 > 0.0 && w00 * w11 - w01 * w10 > 0.0);
    assert!((w01 - w10).abs() < 1e-12 * w00, "{w01} {w10}");
    for tau in [0.0, 0.005, 0.01, 0.02] {
        let t = &motion.bodies;
        let pivot = |k: usize| [homes[k][0] + eval(&t[k].u, tau), eval(&t[k].lift, tau)];
        let (theta_a, theta_b) = (eval(&t[0].theta, tau), eval(&t[1].theta, tau));
        let (p_a, p_b) = (pivot(0), pivot(1));
        // A's top right corner off B's left face, and B's bottom left corner off A's right.
        let top = turned([0.0, 1.2], theta_a);
        let corner = [p_a[0] + top[0], p_a[1] + top[1]];
        let n_b = [-theta_b.cos(), theta_b.sin()];
        let n_a = [theta_a.cos(), -theta_a.sin()];
        let off = [
            (corner[0] - p_b[0]) * n_b[0] + (corner[1] - p_b[1]) * n_b[1],
            (p_b[0] - p_a[0]) * n_a[0] + (p_b[1] - p_a[1]) * n_a[1],
        ];
        assert!(off.iter().all(|x| x.abs() < 1e-15), "{tau}: {off:?}");
        let pushes = motion.pushes.map(|p| eval(&p, tau));
        assert!(pushes.iter().all(|p| p.abs() > 1.0), "{tau}: {pushes:?}");
        // Each push on each body: +n on its corner's body, -n on its face's, at its end.
        let on_a = [
            (corner, [pushes[0] * n_b[0], pushes[0] * n_b[1]]),
            (p_b, [-pushes[1] * n_a[0], -pushes[1] * n_a[1]]),
        ];
        let on_b = on_a.map(|(at, f)| (at, [-f[0], -f[1]]));
        let (accel, lambda) = (eval(&inputs.accel, tau), eval(&inputs.lambda, tau));
        for (k, loads) in [on_a, on_b].iter().enumerate() {
            let (body, tk) = (bodies[k], &t[k]);
            let s = modes[k].corner().unwrap().sign();
            let m = body.mass_kg;
            let th = eval(&tk.theta, tau);
            let w = eval(&tk.omega, tau);
            let th2 = eval(&derivative(&tk.omega), tau);
            let u2 = eval(&derivative(&tk.v), tau);
            let lift2 = eval(&derivative(&tk.lift_v), tau);
            assert_eq!(
                (eval(&tk.tangential, tau), eval(&tk.normal, tau)),
                (0.0, 0.0)
            );
            let (r, [gx2, gy2]) = centroid(body, s, [th, w, th2, u2, lift2]);
            let force = [loads[0].1[0] + loads[1].1[0], loads[0].1[1] + loads[1].1[1]];
            let weight = m * g;
            assert!(
                (m * (gx2 + accel) - force[0]).abs() < 1e-12 * weight,
                "{k} {tau}"
            );
            assert!(
                (m * (gy2 + g * lambda) - force[1]).abs() < 1e-12 * weight,
                "{k} {tau}"
            );
            // About the centroid, clockwise.
            let p = pivot(k);
            let centroid = [p[0] + r[0], p[1] + r[1]];
            let torque: f64 = (loads.iter())
                .map(|(at, f)| -cross([at[0] - centroid[0], at[1] - centroid[1]], *f))
                .sum();
            assert!(
                (body.inertia_kg_m2 * th2 - torque).abs() < 1e-12 * weight,
                "{k} {tau}: {} {torque}",
                body.inertia_kg_m2 * th2
            );
        }
    }
}

/// A wall W (0.6 x 1.2 m) at rest and a slab S (0.25 x 1.2 m) against its right face, rocking on
/// its right corner, turned a tie's angle (theta from 1e-12 to 5e-11 rad, as round-off leaves a
/// slab set down beside a wall): the faces lie on each other, W's bottom right corner on S's
/// face and S's top left corner on W's. Both ends press on S's one degree of freedom, so the
/// contact problem's matrix W is singular (the bottom end's arm about S's pivot is a tie's);
/// whatever its round-off solves the two pushes to, the way "W at rest, S rocking, pressing at
/// both ends" does not hold, at any theta and instant sampled (and at some, its round-off
/// determinant is positive and both solved pushes press, so the rule is what decides).
#[test]
fn a_matrix_singular_to_a_tie_decides_no_pushes() {
    use super::series::TIE;
    let g = 9.81;
    let w = RockingBody::rectangle("W", 0.6, 1.2, 900.0, 0.8, g);
    let s = RockingBody::rectangle("S", 0.25, 1.2, 375.0, 0.8, g);
    let homes = [[0.6, 0.0], [0.87, 0.0]];
    let trial = [Mode::Rest, Mode::Rock(Corner::Right)];
    let both = "W rest with S rock on the right corner pressing at both ends";
    let mut decisive = 0;
    for step in 1..=50 {
        let theta = step as f64 * 1e-12;
        let states = [
            State::default(),
            State {
                theta,
                u: -0.02,
                ..State::default()
            },
        ];
        let pivot = [homes[1][0] + states[1].u, 0.0];
        let top = turned([-0.25, 1.2], theta);
        let sides = [Side::Body(0, [0.3, 0.0]), Side::Body(1, [0.745, 0.0])];
        let touch = |blocks: [usize; 2], point, normal, corner, edge| Touch {
            blocks,
            sides: blocks.map(|b| sides[b]),
            point,
            normal,
            scales: (1.2f64.hypot(0.6), 0.29),
            pair: 0,
            corner,
            edge,
            stays: true,
        };
        let ends = [
            touch([0, 1], [0.6, 0.0], [-theta.cos(), theta.sin()], 1, 3),
            touch([1, 0], [pivot[0] + top[0], top[1]], [1.0, 0.0], 3, 1),
        ];
        let lying = Lying::new(
            [&ends[0], &ends[1]],
            [0, 1],
            homes,
            [&states[0], &states[1]],
        );
        let bodies = [&w, &s];
        let members = [0, 1].map(|k| Member::Moves(bodies[k], trial[k], &states[k]));
        for t in [0.1, 0.3, 0.5, 0.7, 0.9] {
            let inputs = test_inputs_at(t);
            let motion = lying.motion(members, &inputs);
            let [[w00, w01], [w10, w11]] = motion.compliance;
            let det = w00 * w11 - w01 * w10;
            assert!(
                w00 > 0.0 && w11 > 0.0 && det <= TIE * w00 * w11,
                "{theta} {t}"
            );
            let pushes = motion.pushes.map(|p| p[0]);
            if det > 0.0 && pushes.iter().all(|p| p.is_finite() && *p > 0.0) {
                decisive += 1;
            }
            match lying.decide(members, &inputs) {
                Ok(d) => assert!(d.modes != trial || d.pressed != [true, true], "{theta} {t}"),
                Err(why) => {
                    // Only the list of ways that hold, not those friction leaves a paradox.
                    let held = why.strip_prefix("several ways of the pivots and the ends hold (");
                    let held = held.map(|h| h.split(')').next().unwrap_or_default());
                    assert!(
                        !held.unwrap_or_default().contains(both),
                        "{theta} {t}: {why}"
                    );
                }
            }
        }
    }
    assert!(decisive > 0);
}
