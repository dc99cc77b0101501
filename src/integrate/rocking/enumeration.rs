//! Test of the mode decision of a seated block ([`super::modes::decide`]) against an
//! independent enumeration of its two corners' contacts, written for the tests with nalgebra
//! (not the engine's own decision code), and against Shenton's (1996) closed-form boundaries.

use super::modes::{self, Inputs, Mode, State};
use super::series::ZERO;
use super::{Equations, RockingBody};
use nalgebra::{SMatrix, SVector};

const G: f64 = 9.81;

/// The regimes of a block at rest under a step of A g (Shenton 1996), by an enumeration of the
/// 16 combinations of its two corners' contacts (separated, stuck, slipping either way), each a
/// 7 x 7 linear system solved by nalgebra and checked for its signs: exactly one holds, and the
/// engine decides the same; both agree with Shenton's closed-form boundaries.
#[test]
fn step_regimes_match_an_enumeration_of_both_corners_and_shenton() {
    let (b, h) = (0.2, 0.8); // tan alpha = 0.25
    let body = RockingBody::rectangle("B", 2.0 * b, 2.0 * h, 1000.0, 0.5, G);
    let mut seen = std::collections::BTreeSet::new();
    for mu in [0.1, 0.2, 0.24, 0.26, 0.3, 0.45, 0.6, 0.9, 1.3] {
        for a in [0.05, 0.15, 0.23, 0.27, 0.35, 0.5, 0.8, 1.2, 1.9] {
            let body = RockingBody {
                friction: mu,
                ..body.clone()
            };
            let enumerated = enumerate(&body, a);
            assert_eq!(enumerated.len(), 1, "mu {mu}, A {a}: {enumerated:?}");
            let mut inputs = Inputs {
                accel: ZERO,
                lambda: ZERO,
            };
            // a_g = -A g pushes the block to the right (theta > 0).
            inputs.accel[0] = -a * G;
            inputs.lambda[0] = 1.0;
            let t = modes::decide(
                &body,
                Equations::Exact,
                &State::default(),
                None,
                &inputs,
                0.0,
            )
            .unwrap();
            let regime = match t.mode {
                Mode::Rest => "rest",
                Mode::Slide(_) => "slide",
                Mode::Rock(_) => "rock",
                Mode::SlideRock(..) => "slide-rock",
                Mode::Flight(_) => "flight",
            };
            assert_eq!(regime, enumerated[0], "mu {mu}, A {a}");
            assert_eq!(regime, shenton(b, h, mu, a), "mu {mu}, A {a}");
            seen.insert(regime);
        }
    }
    assert_eq!(seen.len(), 4, "{seen:?}");
}

/// Shenton's boundaries for a rectangle at rest under a step A g.
fn shenton(b: f64, h: f64, mu: f64, a: f64) -> &'static str {
    let ratio = b / h;
    if a <= mu.min(ratio) {
        return "rest";
    }
    if mu < ratio {
        return "slide";
    }
    let phi = 3.0 * (a * h - b) / (4.0 * (b * b + h * h)); // phi'' / g
    let needed = (a - h * phi) / (1.0 + b * phi);
    if mu >= needed {
        "rock"
    } else {
        "slide-rock"
    }
}

/// Every combination of the corners' contacts of a seated block under a_g = -A g, by the
/// Newton-Euler equations and the contact conditions: unknowns (x_G'', y_G'', theta'', F_L,
/// N_L, F_R, N_R), theta clockwise, corners at (-+b, -h) from the centroid.
fn enumerate(body: &RockingBody, a: f64) -> Vec<&'static str> {
    #[derive(Clone, Copy, Debug)]
    enum C {
        Off,
        Stuck,
        Slip(f64),
    }
    let (m, ig, b, h, mu) = (
        body.mass_kg,
        body.inertia_kg_m2,
        body.half_base_m,
        body.centroid_height_m,
        body.friction,
    );
    let all = [C::Off, C::Stuck, C::Slip(1.0), C::Slip(-1.0)];
    let mut out = Vec::new();
    for left in all {
        for right in all {
            let mut k = SMatrix::<f64, 7, 7>::zeros();
            let mut rhs = SVector::<f64, 7>::zeros();
            // m x'' = F_L + F_R - m a_g;  m y'' = N_L + N_R - m g.
            k[(0, 0)] = m;
            k[(0, 3)] = -1.0;
            k[(0, 5)] = -1.0;
            rhs[0] = m * a * G;
            k[(1, 1)] = m;
            k[(1, 4)] = -1.0;
            k[(1, 6)] = -1.0;
            rhs[1] = -m * G;
            // I theta'' = sum over corners (r_y F - r_x N), r = (c b, -h), clockwise.
            k[(2, 2)] = ig;
            for (j, c) in [(3, -1.0), (5, 1.0)] {
                k[(2, j)] = h;
                k[(2, j + 1)] = c * b;
            }
            // Corner accelerations: tangential x'' - h theta'', normal y'' - c b theta''.
            for (row, (contact, c, f, n)) in [(left, -1.0, 3, 4), (right, 1.0, 5, 6)]
                .into_iter()
                .enumerate()
            {
                let (r1, r2) = (3 + 2 * row, 4 + 2 * row);
                match contact {
                    C::Off => {
                        k[(r1, f)] = 1.0;
                        k[(r2, n)] = 1.0;
                    }
                    C::Stuck => {
                        k[(r1, 0)] = 1.0;
                        k[(r1, 2)] = -h;
                        k[(r2, 1)] = 1.0;
                        k[(r2, 2)] = -c * b;
                    }
                    C::Slip(s) => {
                        k[(r1, f)] = 1.0;
                        k[(r1, n)] = mu * s;
                        k[(r2, 1)] = 1.0;
                        k[(r2, 2)] = -c * b;
                    }
                }
            }
            if let (C::Stuck, C::Stuck) = (left, right) {
                // Both corners stuck: their tangential rows coincide and the friction split is
                // indeterminate; split it evenly and check the cone on the sums below.
                k.row_mut(5).fill(0.0);
                k[(5, 3)] = 1.0;
                k[(5, 5)] = -1.0;
            }
            let Some(x) = k.lu().solve(&rhs) else {
                continue;
            };
            let tol = 1e-9 * m * G;
            let sums = (x[3] + x[5]).abs() <= mu * (x[4] + x[6]) + tol;
            let ok =
                [(left, -1.0, 3, 4), (right, 1.0, 5, 6)]
                    .into_iter()
                    .all(|(contact, c, f, n)| {
                        let (ft, nn) = (x[f], x[n]);
                        let tangential = x[0] - h * x[2];
                        let normal = x[1] - c * b * x[2];
                        match contact {
                            C::Off => normal > 1e-9,
                            C::Stuck if matches!((left, right), (C::Stuck, C::Stuck)) => {
                                nn >= -tol && sums
                            }
                            C::Stuck => nn >= -tol && ft.abs() <= mu * nn + tol,
                            C::Slip(s) => nn >= -tol && s * tangential > 1e-9,
                        }
                    });
            if ok {
                out.push(match (left, right) {
                    (C::Stuck, C::Stuck) => "rest",
                    (C::Slip(p), C::Slip(q)) if p == q => "slide",
                    (C::Off, C::Stuck) | (C::Stuck, C::Off) => "rock",
                    (C::Off, C::Slip(_)) | (C::Slip(_), C::Off) => "slide-rock",
                    (C::Off, C::Off) => "flight",
                    _ => "mixed",
                });
            }
        }
    }
    out
}
