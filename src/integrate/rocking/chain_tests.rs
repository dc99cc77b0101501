//! Tests of the chain of open joints: its equations against the single body's where one joint
//! is open, its energy and pivot moments where several are, and its landings against an
//! independent Newton-Euler impulse balance written here with nalgebra.
use super::*;
use crate::integrate::rocking::column::{columns, Column};
use crate::integrate::rocking::modes::{self, test_inputs_at, Equations};
use nalgebra::{SMatrix, SVector};

/// Three blocks of different sizes: the top one tips first (friction 0.9 between it and the
/// middle one), or with a low friction between the lower two the upper two slide as one.
fn three_blocks() -> Column {
    let model = crate::model::Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
          joint_friction: {\"C/B\": 0.9},
          rows: [(height_m: 0.4, blocks: [(width_m: 1.2, name: \"A\")]),
                 (height_m: 0.6, x_m: 0.2, blocks: [(width_m: 0.8, name: \"B\")]),
                 (height_m: 1.5, x_m: 0.35, blocks: [(width_m: 0.5, name: \"C\")])])",
    )
    .unwrap();
    columns(model.wall(), model.topology()).unwrap().remove(0)
}

/// Two drums of different sizes, the upper narrower: the whole column tips first.
fn two_drums() -> Column {
    let model = crate::model::Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2600, friction: 0.8,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.6, name: \"Low\")]),
                 (height_m: 1.0, x_m: 0.05, blocks: [(width_m: 0.5, name: \"High\")])])",
    )
    .unwrap();
    let c = columns(model.wall(), model.topology()).unwrap().remove(0);
    assert_eq!(c.body.name, "Low+High");
    c
}

fn still() -> Inputs {
    let mut lambda = ZERO;
    lambda[0] = 1.0;
    Inputs {
        accel: ZERO,
        lambda,
    }
}

/// Relative difference, against a floor.
fn close(a: f64, b: f64, floor: f64) -> bool {
    (a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(floor)
}

/// With only the body's own joint open, the chain is the body: its rotation and rate along a
/// step are the single body's series (Housner's equation with the ground's acceleration), on
/// either corner, for a one-block and a two-block body.
#[test]
fn one_open_joint_moves_as_the_body_alone() {
    let c = three_blocks();
    for column in [c, two_drums()] {
        let links = Links::of(&column.watch, 0.013, Vec::new()).unwrap();
        let inputs = test_inputs_at(0.37);
        for (s, theta, omega) in [(1.0, 0.04, -0.3), (-1.0, -0.02, 0.5)] {
            let pose = Pose {
                open: vec![Open {
                    joint: links.body_joint,
                    s,
                }],
                phi: vec![theta],
                omega: vec![omega],
                slide: None,
                moved: Vec::new(),
            };
            let path = links.path(&pose, &inputs).unwrap();
            let body = modes::trajectory(
                &column.body,
                Equations::Exact,
                Mode::Rock(Corner::of_sign(s)),
                &State {
                    theta,
                    omega,
                    u: 0.013,
                    ..State::default()
                },
                &inputs,
            );
            for tau in [0.0, 0.01, 0.03, 0.06] {
                let (a, b) = (eval(&path.phi[0], tau), eval(&body.theta, tau));
                assert!(
                    close(a, b, 1e-3),
                    "{} {s}: {a} {b} at {tau}",
                    column.body.name
                );
                let (a, b) = (eval(&path.omega[0], tau), eval(&body.omega, tau));
                assert!(
                    close(a, b, 1e-2),
                    "{} {s}: {a} {b} at {tau}",
                    column.body.name
                );
            }
        }
    }
}

/// A column whose held blocks slid together and were held again (its body on them moved by as
/// much) turns as it would where it stood: the same rotations, every block moved by the slip.
#[test]
fn a_chain_on_held_blocks_that_slid_turns_as_where_they_stood() {
    let column = three_blocks();
    let (d, shift) = (-0.0146, 0.0021);
    let pose = Pose {
        open: vec![Open { joint: 1, s: 1.0 }, Open { joint: 2, s: -1.0 }],
        phi: vec![0.004, -0.03],
        omega: vec![0.2, -0.5],
        slide: None,
        moved: Vec::new(),
    };
    let inputs = test_inputs_at(0.37);
    let stood = Links::of(&column.watch, shift, Vec::new()).unwrap();
    let slid = Links::of(&column.watch, shift + d, vec![d, d]).unwrap();
    let (a, b) = (
        stood.path(&pose, &inputs).unwrap(),
        slid.path(&pose, &inputs).unwrap(),
    );
    for tau in [0.0, 0.02, 0.05] {
        for c in 0..2 {
            let (x, y) = (eval(&a.phi[c], tau), eval(&b.phi[c], tau));
            assert!(close(x, y, 1e-3), "phi {c}: {x} {y} at {tau}");
            let (x, y) = (eval(&a.omega[c], tau), eval(&b.omega[c], tau));
            assert!(close(x, y, 1e-1), "omega {c}: {x} {y} at {tau}");
        }
        for p in 0..3 {
            for (r, s) in [(&a.centroid[p], &b.centroid[p]), (&a.base[p], &b.base[p])] {
                let (x, y) = (eval(&r[0], tau) + d, eval(&s[0], tau));
                assert!((x - y).abs() < 1e-15, "block {p}: {x} {y} at {tau}");
                assert_eq!(eval(&r[1], tau), eval(&s[1], tau));
            }
        }
    }
}

/// A chain whose base slips: the three-block column turning on B/A and C/B while A slips on
/// the ground under it (a stack carrying the chain), and turning on A/ground and C/B while A's
/// pivot corner slips on the ground, each way. Along a step under a shaking ground the energy
/// of the blocks grows by the work of the ground's inertial forces less what the slipping
/// joint's friction dissipates, the joint passes up exactly the limit of its friction against
/// the slip (the horizontal momentum of the blocks above it), and each pivot passes no moment.
#[test]
fn a_chain_on_a_slipping_joint_balances_energy_and_momentum() {
    let column = three_blocks();
    let links = Links::of(&column.watch, 0.0, Vec::new()).unwrap();
    let inputs = test_inputs_at(0.37);
    let open = |joint, s| Open { joint, s };
    for (opens, sigma) in [
        ([open(1, 1.0), open(2, -1.0)], 1.0),
        ([open(1, -1.0), open(2, 1.0)], -1.0),
        ([open(0, 1.0), open(2, 1.0)], 1.0),
        ([open(0, -1.0), open(2, -1.0)], -1.0),
    ] {
        let pose = Pose {
            open: opens.to_vec(),
            phi: vec![0.01 * opens[0].s, 0.03 * opens[1].s],
            omega: vec![0.1 * opens[0].s, 0.4 * opens[1].s],
            slide: Some(Slide {
                joint: 0,
                sigma,
                u: 0.002,
                v: 0.3 * sigma,
            }),
            moved: vec![0.001; 3],
        };
        balances_energy_and_friction(&links, &pose, &inputs);
    }
}

/// Every pose of three open joints on the three-block column, and two on the two drums: on
/// still ground the chain's energy stays what it was along a step, and the moment of what
/// each open joint passes up about its pivot vanishes (its equation of motion); under a
/// shaking ground the energy grows by the work of the ground's inertial forces.
#[test]
fn a_chain_keeps_its_energy_and_no_moment_at_its_pivots() {
    let three = three_blocks();
    let two = two_drums();
    let open = |joint, s| Open { joint, s };
    let cases = [
        (
            &three,
            Pose {
                open: vec![open(0, 1.0), open(1, -1.0), open(2, 1.0)],
                phi: vec![0.02, -0.01, 0.05],
                omega: vec![0.1, -0.4, 0.6],
                slide: None,
                moved: Vec::new(),
            },
        ),
        (
            &two,
            Pose {
                open: vec![open(0, -1.0), open(1, 1.0)],
                phi: vec![-0.03, 0.02],
                omega: vec![-0.2, 0.7],
                slide: None,
                moved: Vec::new(),
            },
        ),
    ];
    for (column, pose) in cases {
        let links = Links::of(&column.watch, 0.0, Vec::new()).unwrap();
        let w = &column.watch;
        for (inputs, shaking) in [(still(), false), (test_inputs_at(0.37), true)] {
            let path = links.path(&pose, &inputs).unwrap();
            let energy =
                |tau: f64| -> f64 { links.energies(&path, tau).iter().map(|(k, p)| k + p).sum() };
            let scale = w.moment_scale * 0.1;
            let power = links.input_power(&path, &inputs);
            for tau in [0.01, 0.02, 0.04] {
                let gained = if shaking { integral(&power, tau) } else { 0.0 };
                let change = energy(tau) - energy(0.0);
                assert!(
                    (change - gained).abs() < 1e-12 * scale,
                    "{}: {change} J against {gained} J at {tau} s",
                    column.body.name
                );
                for (c, o) in pose.open.iter().enumerate() {
                    let e = [0, 1].map(|a| path.pivot[c][a]);
                    let m = eval(&links.moment(&path, o.joint, &e), tau);
                    assert!(m.abs() < 1e-12 * w.moment_scale, "{c}: {m} N m");
                }
            }
            // The work compared is far above the tolerance: the check can fail.
            assert!(
                !shaking || integral(&power, 0.04).abs() > 1e-6 * scale,
                "{}",
                integral(&power, 0.04) / scale
            );
        }
    }
}

/// A landing while the joint under the chain slips: C lands on B's other corner as B turns on
/// A, and A slides on the ground, each way. The rates and A's velocity after keep the angular
/// momentum of the part above each open joint about its pivot, and the ground joint passes the
/// limit of its friction against the slip (what the three blocks gain), to 1e-12; A moves with
/// the slip alone.
#[test]
fn a_landing_on_a_slipping_joint_keeps_momenta_and_the_friction_limit() {
    let column = three_blocks();
    let links = Links::of(&column.watch, 0.0, Vec::new()).unwrap();
    for sigma in [-1.0, 1.0] {
        let pose = Pose {
            open: vec![Open { joint: 1, s: 1.0 }, Open { joint: 2, s: -1.0 }],
            phi: vec![0.01, 0.01],
            omega: vec![0.3, 0.9],
            slide: Some(Slide {
                joint: 0,
                sigma,
                u: 0.002,
                v: 0.2 * sigma,
            }),
            moved: Vec::new(),
        };
        let path = links.path(&pose, &still()).unwrap();
        let at = Instant::of(&pose, &path, 0.0);
        let before: Vec<[f64; 2]> = (path.centroid.iter())
            .map(|g| g.map(|x| derivative(&x)[0]))
            .collect();
        let spin = [0.0, 0.3, 0.9];
        let mut flipped = pose.open.clone();
        flipped[1].s = 1.0;
        let (rates, w, after) = links
            .momentum_balance(&flipped, Some((0, sigma)), &at, &before, &spin)
            .unwrap();
        assert_eq!(after[0], [w, 0.0]);
        let spin_after = [0.0, rates[0], rates[1]];
        let normal = kept_and_at_the_limit(
            &links,
            &at,
            &flipped,
            [(&before, &spin), (&after, &spin_after)],
            sigma,
        );
        // The impulse is not nothing: the check can fail.
        assert!(normal.abs() > 1.0, "{normal}");
    }
}

/// The two balances of a landing on the slipping ground joint of `three_blocks`, checked apart
/// from the law: the angular momentum of the part above each joint of `open` about its pivot
/// at `at`, kept from the blocks' velocities and spins before to those after, and the ground
/// joint's impulse (what the three blocks gain) at its friction's limit against the slip
/// sigma, to 1e-12. Returns the vertical impulse.
fn kept_and_at_the_limit(
    links: &Links,
    at: &Instant,
    open: &[Open],
    [before, after]: [(&[[f64; 2]], &[f64]); 2],
    sigma: f64,
) -> f64 {
    let pieces = &links.watch.pieces;
    let cross = |r: [f64; 2], v: [f64; 2]| r[1] * v[0] - r[0] * v[1];
    for o in open {
        let pivot = at.point(links, o.joint, o.s);
        let momentum = |(v, spin): (&[[f64; 2]], &[f64])| -> f64 {
            (o.joint..3)
                .map(|p| {
                    let d = [at.centroid[p][0] - pivot[0], at.centroid[p][1] - pivot[1]];
                    pieces[p].mass_kg * cross(d, v[p]) + pieces[p].inertia_kg_m2 * spin[p]
                })
                .sum()
        };
        let (kept, had) = (momentum(after), momentum(before));
        assert!(close(kept, had, 1.0), "{sigma} {o:?}: {kept} {had}");
    }
    let gained = (0..3).fold([0.0; 2], |g, p| {
        let m = pieces[p].mass_kg;
        [
            g[0] + m * (after.0[p][0] - before.0[p][0]),
            g[1] + m * (after.0[p][1] - before.0[p][1]),
        ]
    });
    let limit = gained[0] + links.joints[0].friction * sigma * gained[1];
    assert!(
        limit.abs() < 1e-12 * (gained[0].abs() + gained[1].abs()),
        "{sigma}: {gained:?}"
    );
    gained[1]
}

/// A landing of the upper drum on the lower one's other corner while the lower rocks on the
/// ground: the rates after keep each part's angular momentum about its pivot. Checked against
/// Newton-Euler for each drum with an impulse at the ground pivot and one at the new corner,
/// both pivots held after (ten equations in ten unknowns); and a one-body landing gives
/// Housner's r.
#[test]
fn landings_keep_the_momentum_newton_euler_impulses_give() {
    let column = two_drums();
    let links = Links::of(&column.watch, 0.0, Vec::new()).unwrap();
    let pose = Pose {
        open: vec![Open { joint: 0, s: 1.0 }, Open { joint: 1, s: 1.0 }],
        phi: vec![0.03, 0.03],
        omega: vec![0.2, -0.5],
        slide: None,
        moved: Vec::new(),
    };
    let path = links.path(&pose, &still()).unwrap();
    let at = Instant::of(&pose, &path, 0.0);
    let velocity: Vec<[f64; 2]> = path
        .centroid
        .iter()
        .map(|g| g.map(|x| derivative(&x)[0]))
        .collect();
    let spin = [0.2, -0.5];
    let mut flipped = pose.open.clone();
    flipped[1].s = -1.0;
    let (rates, _, _) = links
        .momentum_balance(&flipped, None, &at, &velocity, &spin)
        .unwrap();
    // Unknowns: v1 (2), w1, v2 (2), w2, P (2, ground on the lower), Q (2, lower on upper).
    let p = &column.watch.pieces;
    let ground = at.point(&links, 0, 1.0);
    let corner = at.point(&links, 1, -1.0);
    let g = &at.centroid;
    let mut a = SMatrix::<f64, 10, 10>::zeros();
    let mut b = SVector::<f64, 10>::zeros();
    let r = |pt: [f64; 2], i: usize| [pt[0] - g[i][0], pt[1] - g[i][1]];
    // Momentum of each drum: m (v' - v) = impulses on it.
    for (i, sign_q) in [(0usize, -1.0), (1, 1.0)] {
        for k in 0..2 {
            a[(3 * i + k, 3 * i + k)] = p[i].mass_kg;
            if i == 0 {
                a[(k, 6 + k)] = -1.0;
            }
            a[(3 * i + k, 8 + k)] = -sign_q;
            b[3 * i + k] = p[i].mass_kg * velocity[i][k];
        }
        // Clockwise angular momentum about its centroid: I (w' - w) = r_y J_x - r_x J_y.
        a[(3 * i + 2, 3 * i + 2)] = p[i].inertia_kg_m2;
        if i == 0 {
            let rp = r(ground, 0);
            a[(2, 6)] = -rp[1];
            a[(2, 7)] = rp[0];
        }
        let rq = r(corner, i);
        a[(3 * i + 2, 8)] = -sign_q * rq[1];
        a[(3 * i + 2, 9)] = sign_q * rq[0];
        b[3 * i + 2] = p[i].inertia_kg_m2 * spin[i];
    }
    // The ground pivot at rest after; the new corner moving with both drums.
    let point = |i: usize, pt: [f64; 2]| {
        let rr = r(pt, i);
        // v + w (r_y, -r_x)
        [[1.0, 0.0, rr[1]], [0.0, 1.0, -rr[0]]]
    };
    let pg = point(0, ground);
    for k in 0..2 {
        for c in 0..3 {
            a[(6 + k, c)] = pg[k][c];
        }
    }
    let (q0, q1) = (point(0, corner), point(1, corner));
    for k in 0..2 {
        for c in 0..3 {
            a[(8 + k, c)] = q0[k][c];
            a[(8 + k, 3 + c)] = -q1[k][c];
        }
    }
    let x = a.lu().solve(&b).unwrap();
    assert!(close(rates[0], x[2], 1e-2), "{} {}", rates[0], x[2]);
    assert!(close(rates[1], x[5], 1e-2), "{} {}", rates[1], x[5]);
    // The upper drum turns onto its new corner, the normal impulse there presses.
    assert!(rates[1] - rates[0] < 0.0 && x[9] > 0.0, "{rates:?} {x}");

    // One body landing: Housner.
    let one = Pose {
        open: vec![Open { joint: 0, s: 1.0 }],
        phi: vec![0.0],
        omega: vec![-0.4],
        slide: None,
        moved: Vec::new(),
    };
    let path = links.path(&one, &still()).unwrap();
    let at = Instant::of(&one, &path, 0.0);
    let velocity: Vec<[f64; 2]> = path
        .centroid
        .iter()
        .map(|g| g.map(|x| derivative(&x)[0]))
        .collect();
    let (rates, _, _) = links
        .momentum_balance(
            &[Open { joint: 0, s: -1.0 }],
            None,
            &at,
            &velocity,
            &[-0.4, -0.4],
        )
        .unwrap();
    let r = column.body.housner_restitution();
    assert!(close(rates[0], -0.4 * r, 1e-2), "{} {}", rates[0], -0.4 * r);
    // Seated by the landing: no body left, every block at rest.
    let (rates, _, after) = links
        .momentum_balance(&[], None, &at, &velocity, &[-0.4, -0.4])
        .unwrap();
    assert!(rates.is_empty() && after.iter().all(|v| *v == [0.0; 2]));
    let seated = Pose {
        open: Vec::new(),
        phi: Vec::new(),
        omega: Vec::new(),
        slide: None,
        moved: Vec::new(),
    };
    let path = links.path(&seated, &test_inputs_at(0.37)).unwrap();
    assert!(links.energies(&path, 0.0).iter().all(|e| *e == (0.0, 0.0)));
}

/// A landing that opens a held joint through the impact: C lands on B's other corner while A,
/// under both, slides on the ground, and the ground joint opens at A's left or right end, its
/// pivot slipping on. The rates and A's velocity after keep the angular momentum of the part
/// above each open joint about its pivot (A's corner where the slip has carried it), and the
/// ground joint passes the limit of its friction, to 1e-12; a joint that would close as it
/// opens is reported as the condition it breaks.
#[test]
fn a_landing_that_opens_a_held_joint_keeps_momenta_about_the_new_pivot() {
    let column = three_blocks();
    let links = Links::of(&column.watch, 0.0, Vec::new()).unwrap();
    let pose = Pose {
        open: vec![Open { joint: 2, s: 1.0 }],
        phi: vec![1e-3],
        omega: vec![-2.0],
        slide: Some(Slide {
            joint: 0,
            sigma: -1.0,
            u: -0.03,
            v: -0.3,
        }),
        moved: Vec::new(),
    };
    let path = links.path(&pose, &still()).unwrap();
    let at = Instant::of(&pose, &path, 0.0);
    // The slip carries A's corners: the points of the instant are where the path has them.
    let rest = links.end(0, -1.0);
    assert_eq!(at.point(&links, 0, -1.0), [rest[0] - 0.03, rest[1]]);
    let before: Vec<[f64; 2]> = (path.centroid.iter())
        .map(|g| g.map(|x| derivative(&x)[0]))
        .collect();
    let spin = [0.0, 0.0, -2.0];
    let mut opened = 0;
    for s in [-1.0, 1.0] {
        let new = Open { joint: 0, s };
        let way = links
            .landed(
                &pose,
                0,
                (Some((0, -1.0)), Some(new)),
                (&at, &before, &spin),
                (0.0, 1.0),
            )
            .unwrap();
        let next = &way.next;
        assert_eq!(next.open, vec![new, Open { joint: 2, s: -1.0 }]);
        let w = next.slide.expect("the slip goes on").v;
        // Each body turns clockwise about its pivot, carrying the next pivot along.
        let pivots: Vec<[f64; 2]> = (next.open.iter())
            .map(|o| at.point(&links, o.joint, o.s))
            .collect();
        let after: Vec<[f64; 2]> = (0..3)
            .map(|p| {
                let on = next.open.iter().rposition(|o| o.joint <= p).unwrap();
                (0..=on).fold([w, 0.0], |v, c| {
                    let to = if c < on {
                        pivots[c + 1]
                    } else {
                        at.centroid[p]
                    };
                    let r = [to[0] - pivots[c][0], to[1] - pivots[c][1]];
                    [v[0] + next.omega[c] * r[1], v[1] - next.omega[c] * r[0]]
                })
            })
            .collect();
        let spin_after = [next.omega[0], next.omega[0], next.omega[1]];
        let normal = kept_and_at_the_limit(
            &links,
            &at,
            &next.open,
            [(&before, &spin), (&after, &spin_after)],
            -1.0,
        );
        assert!(normal.abs() > 1.0, "{s}: {normal}");
        let opens = s * next.omega[0] > 0.0;
        opened += usize::from(opens);
        let closing = Cut::Closed(0, 2 + usize::from(s > 0.0));
        assert_eq!(way.breaks == Some(closing), !opens, "{s}: {:?}", way.breaks);
    }
    assert!(opened >= 1);
}

/// A joint inside the chain that slips: C slides on B inside the body turning on the ground, B
/// and C slide on A in a body turning on the ground under C's own open joint, and C's pivot
/// slips on B while A and B turn on the ground or B alone on A. Along a step the energy
/// changes by the ground's work less the friction's, mu N |u_s'| (1e-12), the force the joint
/// passes up lies at its friction's limit in the frame of the face it slides on, and what each
/// open joint passes up has no moment about its pivot (1e-12).
#[test]
fn a_joint_slipping_inside_the_chain_balances_energy_and_its_friction() {
    let column = three_blocks();
    let links = Links::of(&column.watch, 0.0, Vec::new()).unwrap();
    let inputs = test_inputs_at(0.37);
    let open = |joint, s| Open { joint, s };
    for (opens, joint, sigma) in [
        (vec![open(0, 1.0)], 2, 1.0),
        (vec![open(0, -1.0)], 2, -1.0),
        (vec![open(0, 1.0), open(2, -1.0)], 1, 1.0),
        (vec![open(0, 1.0), open(2, 1.0)], 2, -1.0),
        (vec![open(1, -1.0), open(2, -1.0)], 2, 1.0),
    ] {
        let n = opens.len();
        let pose = Pose {
            phi: [0.01 * opens[0].s, 0.03 * opens[n - 1].s][..n].to_vec(),
            omega: [0.1 * opens[0].s, 0.4 * opens[n - 1].s][..n].to_vec(),
            open: opens,
            slide: Some(Slide {
                joint,
                sigma,
                u: 0.002,
                v: 0.6 * sigma,
            }),
            moved: vec![0.0, 0.001, 0.001],
        };
        let path = links.path(&pose, &inputs).unwrap();
        assert!(path.inner.is_some(), "a slip inside the chain");
        balances_energy_and_friction(&links, &pose, &inputs);
    }
}

/// Along a step of `pose`'s chain, whose joint slips: the energy changes by the ground's work
/// less the friction's, mu N |u_s'| (1e-12 of a tenth of the moment scale), the slip keeps its
/// sign, the force the joint passes up lies at its friction's limit in the frame of the face it
/// slides on (1e-12 of the force scale), and what each open joint passes up has no moment about
/// its pivot (1e-12 of the moment scale); the friction's work is far above the tolerance.
fn balances_energy_and_friction(links: &Links, pose: &Pose, inputs: &Inputs) {
    let w = links.watch;
    let sl = pose.slide.expect("a slip");
    let path = links.path(pose, inputs).unwrap();
    let energy = |tau: f64| -> f64 { links.energies(&path, tau).iter().map(|(k, p)| k + p).sum() };
    let power = links.input_power(&path, inputs);
    let friction = links.friction_power(pose, &path);
    let scale = w.moment_scale * 0.1;
    let mu = links.joints[sl.joint].friction;
    let case = format!("{:?} on {}", pose.open, sl.joint);
    for tau in [0.005, 0.01, 0.02] {
        let (_, _, v) = path.slide.as_ref().unwrap();
        assert!(
            sl.sigma * eval(v, tau) > 0.0,
            "{case}: still slipping at {tau}"
        );
        let change = energy(tau) - energy(0.0);
        let gained = integral(&power, tau) - integral(&friction, tau);
        assert!(
            (change - gained).abs() < 1e-12 * scale,
            "{case}: {change} J against {gained} J at {tau} s"
        );
        let (h, v) = links.passed(&path, sl.joint);
        let (h, v) = (eval(&h, tau), eval(&v, tau));
        let (sin, cos) = path.inner.map_or((0.0, 1.0), |b| {
            (eval(&path.sin[b], tau), eval(&path.cos[b], tau))
        });
        let limit = (h * cos - v * sin) + mu * sl.sigma * (h * sin + v * cos);
        assert!(limit.abs() < 1e-12 * w.force_scale, "{case}: {limit} N");
        for (c, o) in pose.open.iter().enumerate() {
            let e = [0, 1].map(|a| path.pivot[c][a]);
            let m = eval(&links.moment(&path, o.joint, &e), tau);
            assert!(m.abs() < 1e-12 * w.moment_scale, "{case}, {c}: {m} N m");
        }
    }
    assert!(integral(&friction, 0.02) > 1e-3 * scale, "{case}");
}
