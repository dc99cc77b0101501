//! The impact where two blocks meet, a corner of one on a face of the other, each block fixed
//! or turning with a body that rocks on a pivot of its base. This module owns that impact law.
//!
//! The law is the one the sliding model uses at its vertical joints and the time-stepped model
//! at every face between blocks: Newton's, frictionless at the contact, the normal velocity
//! reversed and scaled by the wall's coefficient of restitution e, v_n+ = -e v_n-. Each body
//! has three velocities through the impact: its pivot's slip v and rise w, and its rotation's
//! rate theta'. Its pivot either stays on the ground and passes the impulse the body needs, a
//! normal impulse that presses and a tangential one in Coulomb's cone (sticking: v+ = 0; or
//! slipping, the tangential impulse at mu times the normal one against v+, as Moreau's impact
//! law puts friction on the velocities after), or leaves it with no impulse (w+ >= 0: a body
//! swinging out whose centroid rises as it strikes cannot have that rise reversed by a
//! frictionless face and a base that only pushes). Every combination of the pivots' laws is a
//! linear system; exactly one must be consistent: none (Painleve-type: no impulse obeys the
//! law) or two that differ is reported, never chosen between.

use nalgebra::{DMatrix, DVector};

/// A body that turns through the impact: what the law needs of it at the instant of the
/// impact, positions in the wall's frame (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turning {
    pub mass_kg: f64,
    /// About its centroid (kg m2).
    pub inertia_kg_m2: f64,
    /// Of its base under the pivot.
    pub friction: f64,
    pub pivot: [f64; 2],
    pub centroid: [f64; 2],
    /// theta' (rad/s, clockwise positive) and the pivot's velocity (v, w) (m/s) before.
    pub omega: f64,
    pub v: f64,
    pub w: f64,
    /// Whether the body is in free flight (its pivot, the corner it left, off the ground).
    pub flying: bool,
}

/// The contact: where the corner touches the face (m), the face's normal pointing into the
/// block whose corner it is, and the coefficient of restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    pub point: [f64; 2],
    pub normal: [f64; 2],
    pub restitution: f64,
}

/// How a pivot goes through the impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Pivot {
    /// It stays where it is: its slip velocity after the impact is zero.
    Sticks,
    /// It slips after the impact towards the given sign of x, friction at its limit.
    Slips(f64),
    /// It leaves the ground: the body is in free flight after the impact.
    Lifts,
    /// The body was in free flight and stays so: nothing acts on it but the contact.
    Flies,
}

/// A body's velocities after the impact: theta' (rad/s), and its pivot's horizontal and
/// vertical velocities (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct After {
    pub omega: f64,
    pub v: f64,
    pub lift_v: f64,
    pub pivot: Pivot,
}

/// What the impact does. Sides in the order given: the corner's block, then the face's.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Per side that turns, its velocities after.
    pub after: [Option<After>; 2],
    /// The normal impulse at the contact (N s).
    pub impulse_n_s: f64,
    /// Normal velocity of the corner against the face before (negative: approaching) and
    /// after (m/s).
    pub normal_m_s: (f64, f64),
    /// Kinetic energy lost (J).
    pub loss_j: f64,
}

/// Why an impact is not followed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Refusal {
    /// The corner does not approach the face faster than round-off: the blocks touch and stay
    /// in contact, which the exact model does not follow.
    Grazing,
    /// No combination of sticking, slipping and lifting pivots obeys the law.
    Inconsistent,
    /// Two combinations obey it with different outcomes.
    Indeterminate,
}

impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Refusal::Grazing => {
                "they touch without approaching, and the contact that follows is not followed"
            }
            Refusal::Inconsistent => {
                "no impulse obeys the impact law with Coulomb friction at the pivots (a \
                 Painleve-type inconsistency)"
            }
            Refusal::Indeterminate => {
                "the impact law with Coulomb friction at the pivots has two outcomes"
            }
        })
    }
}

/// The velocity of the point at `x` of a body turning about `pivot` at `omega` (clockwise)
/// while the pivot moves at (v, w): (v + omega d_y, w - omega d_x), d = x - pivot.
fn point_velocity(b: &Turning, x: [f64; 2], omega: f64, v: f64, w: f64) -> [f64; 2] {
    let d = [x[0] - b.pivot[0], x[1] - b.pivot[1]];
    [v + omega * d[1], w - omega * d[0]]
}

/// How far the body's centroid lies from its pivot (m): the arm its speeds are measured by.
fn reach(b: &Turning) -> f64 {
    (b.centroid[0] - b.pivot[0]).hypot(b.centroid[1] - b.pivot[1])
}

/// Kinetic energy of a body at (omega, v, w) (J).
fn kinetic_j(b: &Turning, omega: f64, v: f64, w: f64) -> f64 {
    let vg = point_velocity(b, b.centroid, omega, v, w);
    0.5 * b.mass_kg * (vg[0] * vg[0] + vg[1] * vg[1]) + 0.5 * b.inertia_kg_m2 * omega * omega
}

/// The impact of the corner of side 0 on the face of side 1 (`None`: a fixed block). A body
/// in flight has no pivot law: only the contact acts on it.
pub fn resolve(sides: [Option<&Turning>; 2], c: &Contact) -> Result<Outcome, Refusal> {
    const SIGN: [f64; 2] = [1.0, -1.0];
    const CHOICES: [Pivot; 4] = [
        Pivot::Sticks,
        Pivot::Slips(1.0),
        Pivot::Slips(-1.0),
        Pivot::Lifts,
    ];
    let n = c.normal;
    // theta', v and w of a side enter the normal velocity at the contact with these weights.
    let arms = |b: &Turning| {
        let d = [c.point[0] - b.pivot[0], c.point[1] - b.pivot[1]];
        [n[0], n[0] * d[1] - n[1] * d[0], n[1]]
    };
    let (mut approach, mut speed, mut momentum) = (0.0, 0.0, 0.0);
    for (k, b) in sides.iter().enumerate() {
        if let Some(b) = b {
            let a = arms(b);
            approach += SIGN[k] * (a[0] * b.v + a[1] * b.omega + a[2] * b.w);
            let s = b.v.abs() + b.w.abs() + b.omega.abs() * reach(b);
            speed += s;
            momentum += b.mass_kg * s;
        }
    }
    let tie = super::series::TIE;
    if approach >= -tie * speed {
        return Err(Refusal::Grazing);
    }
    let moving: Vec<usize> = (0..2).filter(|&k| sides[k].is_some()).collect();
    // Per side that turns: the changes of v, theta' and w, the pivot's tangential and normal
    // impulses; then the contact's normal impulse.
    let p = 5 * moving.len();
    let mut found: Vec<Outcome> = Vec::new();
    for combo in 0..CHOICES.len().pow(moving.len() as u32) {
        let pivots: Vec<Pivot> = (0..moving.len())
            .map(|j| match sides[moving[j]] {
                Some(b) if b.flying => Pivot::Flies,
                _ => CHOICES[combo / CHOICES.len().pow(j as u32) % CHOICES.len()],
            })
            .collect();
        if combo > 0 && pivots.iter().all(|&p| p == Pivot::Flies) {
            break;
        }
        let mut a = DMatrix::<f64>::zeros(p + 1, p + 1);
        let mut rhs = DVector::<f64>::zeros(p + 1);
        for (j, &k) in moving.iter().enumerate() {
            let b = sides[k].expect("a side that turns");
            let (m, s) = (b.mass_kg, SIGN[k]);
            let g = [b.centroid[0] - b.pivot[0], b.centroid[1] - b.pivot[1]];
            let r = 5 * j;
            let (pt, pn) = (r + 3, r + 4);
            // Momentum in the velocities q = (v, theta', w), whose centroid moves at
            // (v + theta' g_y, w - theta' g_x): M dq = (P_T, 0, P_N) + s P J^T n.
            let mass = [
                [m, m * g[1], 0.0],
                [
                    m * g[1],
                    m * (g[0] * g[0] + g[1] * g[1]) + b.inertia_kg_m2,
                    -m * g[0],
                ],
                [0.0, -m * g[0], m],
            ];
            let arm = arms(b);
            for row in 0..3 {
                for col in 0..3 {
                    a[(r + row, r + col)] = mass[row][col];
                }
                a[(r + row, p)] = -s * arm[row];
                // Newton's law at the contact, summed over the sides.
                a[(p, r + row)] = s * arm[row];
            }
            a[(r, pt)] = -1.0;
            a[(r + 2, pn)] = -1.0;
            // The pivot's law: on the ground (w stays 0) sticking or slipping, or off it
            // (no impulse).
            match pivots[j] {
                Pivot::Sticks => {
                    a[(pt, r)] = 1.0;
                    rhs[pt] = -b.v;
                    a[(pn, r + 2)] = 1.0;
                }
                Pivot::Slips(dir) => {
                    a[(pt, pt)] = 1.0;
                    a[(pt, pn)] = b.friction * dir;
                    a[(pn, r + 2)] = 1.0;
                }
                Pivot::Lifts | Pivot::Flies => {
                    a[(pt, pt)] = 1.0;
                    a[(pn, pn)] = 1.0;
                }
            }
        }
        rhs[p] = -(1.0 + c.restitution) * approach;
        let Some(x) = a.lu().solve(&rhs) else {
            continue;
        };
        let impulse = x[p];
        let impulse_tol = tie * (impulse.abs() + momentum);
        let mut consistent = impulse >= -impulse_tol;
        let mut outcome = Outcome {
            after: [None; 2],
            impulse_n_s: impulse.max(0.0),
            normal_m_s: (approach, -c.restitution * approach),
            loss_j: 0.0,
        };
        for (j, &k) in moving.iter().enumerate() {
            let b = sides[k].expect("a side that turns");
            let r = 5 * j;
            let (pt, pn) = (x[r + 3], x[r + 4]);
            // A pivot on the ground does not rise, and one that sticks does not slip, to the
            // bit (the solve leaves round-off there).
            let after = After {
                omega: b.omega + x[r + 1],
                v: if pivots[j] == Pivot::Sticks {
                    0.0
                } else {
                    b.v + x[r]
                },
                lift_v: match pivots[j] {
                    Pivot::Lifts | Pivot::Flies => b.w + x[r + 2],
                    _ => 0.0,
                },
                pivot: pivots[j],
            };
            consistent &= match pivots[j] {
                Pivot::Sticks => {
                    pn >= -impulse_tol && pt.abs() <= b.friction * pn.max(0.0) + impulse_tol
                }
                Pivot::Slips(dir) => pn >= -impulse_tol && dir * after.v >= -tie * speed,
                Pivot::Lifts => after.lift_v >= -tie * speed,
                Pivot::Flies => true,
            };
            outcome.loss_j +=
                kinetic_j(b, b.omega, b.v, b.w) - kinetic_j(b, after.omega, after.v, after.lift_v);
            outcome.after[k] = Some(after);
        }
        if consistent {
            found.push(outcome);
        }
    }
    // A pivot at the tie between two laws obeys both with one outcome: outcomes that agree to
    // 1e-9 of the speeds are one.
    let same = |x: &Outcome, y: &Outcome| {
        let apart: f64 = (0..2)
            .filter_map(|k| {
                let (a, b) = (x.after[k]?, y.after[k]?);
                let r = sides[k].map_or(0.0, reach);
                Some(
                    (a.omega - b.omega).abs() * r + (a.v - b.v).abs() + (a.lift_v - b.lift_v).abs(),
                )
            })
            .sum();
        apart <= 1e-9 * speed
    };
    match found.as_slice() {
        [] => Err(Refusal::Inconsistent),
        [first, rest @ ..] if rest.iter().all(|o| same(first, o)) => Ok(first.clone()),
        _ => Err(Refusal::Indeterminate),
    }
}

#[cfg(test)]
#[path = "collision_tests.rs"]
mod tests;
