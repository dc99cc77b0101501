//! The impact where two blocks meet, a corner of one on a face of the other, each block fixed
//! or moved by a body standing on the ground on one corner, on both, or on none (rocking,
//! seated, in flight). This module owns that impact law.
//!
//! The law is the one the sliding model uses at its vertical joints and the time-stepped model
//! at every face between blocks: Newton's, frictionless at the contact, the normal velocity
//! reversed and scaled by the wall's coefficient of restitution e, v_n+ = -e v_n-. Each body
//! has three velocities through the impact: a base corner's slip v and rise w, and its
//! rotation's rate theta'. Each corner of its base on the ground either stays on it, passing a
//! normal impulse that presses, or leaves it with none (its rise after >= 0); the base's
//! friction, while a corner stays, either sticks (v+ = 0, the tangential impulse in Coulomb's
//! cone) or slips (the tangential impulse at mu times the normal ones, against v+, as
//! Moreau's impact law puts friction on the velocities after). A body swinging out whose
//! centroid rises as it strikes cannot have that rise reversed by a frictionless face and a
//! base that only pushes: its pivot leaves the ground. A seated body struck on its side turns
//! on the corner away from the blow, slides, or leaves the ground, as the law says. Every
//! combination of the corners' and the friction's laws is a linear system; exactly one must be
//! consistent: none (Painleve-type: no impulse obeys the law) or two that differ is reported,
//! never chosen between. Every contact between blocks is closed (Newton's law, an impulse that
//! presses) or open (no impulse, the corner leaving at least as fast as the law would have it),
//! so the same law takes several contacts at once (`resolve_all`): a landing in contact (a base
//! corner coming down onto the ground while a contact stays, `resolve_landing`), or a blow on a
//! block in contact with others.

use super::modes::Corner;
use nalgebra::{DMatrix, DVector};

/// A body that moves through the impact: what the law needs of it at the instant of the
/// impact, positions in the wall's frame (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turning {
    pub mass_kg: f64,
    /// About its centroid (kg m2).
    pub inertia_kg_m2: f64,
    /// Of its base.
    pub friction: f64,
    /// A corner of its base: the point whose velocity (v, w) the law uses.
    pub pivot: [f64; 2],
    pub centroid: [f64; 2],
    /// theta' (rad/s, clockwise positive) and the pivot's velocity (v, w) (m/s) before.
    pub omega: f64,
    pub v: f64,
    pub w: f64,
    /// The corners of its base on the ground, with their horizontal offsets from the pivot (m):
    /// the pivot alone while rocking, both corners while seated, none in flight.
    pub ground: [Option<(Corner, f64)>; 2],
}

/// The contact: where the corner touches the face (m), the face's normal pointing into the
/// block whose corner it is, and the coefficient of restitution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    pub point: [f64; 2],
    pub normal: [f64; 2],
    pub restitution: f64,
}

/// How the base's friction goes through the impact, while a corner stays on the ground.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Friction {
    Sticks,
    /// It slips after the impact towards the given sign of x.
    Slips(f64),
    /// No corner stays on the ground.
    Free,
}

/// Where a body stands after the impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Base {
    /// On both corners, its base slipping or not.
    Seated { slips: bool },
    /// On one corner, slipping or not.
    Pivot { corner: Corner, slips: bool },
    /// On none: in free flight.
    Flies,
}

/// A body's velocities after the impact: theta' (rad/s), and its pivot's horizontal and
/// vertical velocities (m/s).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct After {
    pub omega: f64,
    pub v: f64,
    pub lift_v: f64,
    pub base: Base,
}

/// What the impact does. Sides in the order given: the corner's block, then the face's.
#[derive(Debug, Clone, PartialEq)]
pub struct Outcome {
    /// Per side that moves, its velocities after.
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
    /// No combination of the laws obeys the impact law.
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

/// One side's laws in one combination: which of its ground corners stay on (bit k: corner k)
/// and its friction.
type Laws = (usize, Friction);

/// Every combination of laws of a body with `n` corners on the ground.
fn laws(n: usize) -> Vec<Laws> {
    let mut out = vec![(0, Friction::Free)];
    for mask in 1..1usize << n {
        for f in [
            Friction::Sticks,
            Friction::Slips(1.0),
            Friction::Slips(-1.0),
        ] {
            out.push((mask, f));
        }
    }
    out
}

/// The sides' signs in the contact's normal velocity: the corner's block, then the face's.
const SIGN: [f64; 2] = [1.0, -1.0];

/// The weights with which theta', v and w of a side enter the normal velocity at the contact.
fn arms(b: &Turning, c: &Contact) -> [f64; 3] {
    let (n, d) = (c.normal, [c.point[0] - b.pivot[0], c.point[1] - b.pivot[1]]);
    [n[0], n[0] * d[1] - n[1] * d[0], n[1]]
}

/// The normal velocity of the corner against the face (m/s, negative: approaching), the sum of
/// the sides' speeds (m/s: what round-off is measured against) and of their momenta (N s).
pub fn approach(sides: [Option<&Turning>; 2], c: &Contact) -> (f64, f64, f64) {
    let (mut approach, mut speed, mut momentum) = (0.0, 0.0, 0.0);
    for (k, b) in sides.iter().enumerate() {
        if let Some(b) = b {
            let a = arms(b, c);
            approach += SIGN[k] * (a[0] * b.v + a[1] * b.omega + a[2] * b.w);
            let s = b.v.abs() + b.w.abs() + b.omega.abs() * reach(b);
            speed += s;
            momentum += b.mass_kg * s;
        }
    }
    (approach, speed, momentum)
}

/// The side whose rotation moves the contact most, among those that may turn (`turns`: a
/// seated body does not), and the change of its theta' (rad/s) that leaves the corner's normal
/// velocity against the face zero: what closes the round-off (up to a tie, which no impulse
/// takes up) at a contact that stays. None where no side's rotation moves the contact by more
/// than a tie of its reach (a contact at the pivots, as where two blocks' bottom corners are
/// together): a change of theta' there would be round-off divided by round-off.
pub fn closing(
    sides: [Option<&Turning>; 2],
    c: &Contact,
    turns: [bool; 2],
) -> Option<(usize, f64)> {
    let (rate, ..) = approach(sides, c);
    let (k, arm, reach) = (0..2)
        .filter(|&k| turns[k])
        .filter_map(|k| {
            let b = sides[k]?;
            Some((k, SIGN[k] * arms(b, c)[1], reach(b)))
        })
        .max_by(|x, y| x.1.abs().total_cmp(&y.1.abs()))?;
    (arm.abs() > super::series::TIE * reach).then_some((k, -rate / arm))
}

/// The changes of the bodies' velocities (v, theta', w each, m/s and rad/s) that leave the
/// normal velocity at every contact of `links` zero, each body changing only the velocities
/// its mode leaves free (`free`, in that order), by the least in the norm that weights v and w
/// by the mass and theta' by the inertia about the centroid (the kinetic energy, were v and w
/// the centroid's: for changes of round-off any such norm serves): what closes the round-off
/// at contacts that stay where a decision made a rate at a tie zero. One or two contacts; none
/// where the free velocities cannot close them (a singular system).
pub fn closing_all(
    bodies: &[Turning],
    links: &[Link],
    free: &[[bool; 3]],
) -> Option<Vec<[f64; 3]>> {
    let side = |l: &Link, k: usize| l.sides[k].map(|j| &bodies[j]);
    let rates: Vec<f64> = (links.iter())
        .map(|l| approach([side(l, 0), side(l, 1)], &l.contact).0)
        .collect();
    // J[e][j][d]: how contact e's normal velocity grows with velocity d of body j.
    let jac: Vec<Vec<[f64; 3]>> = (links.iter())
        .map(|l| {
            let mut row = vec![[0.0; 3]; bodies.len()];
            for (side, sign) in l.sides.iter().zip(SIGN) {
                if let Some(j) = *side {
                    let a = arms(&bodies[j], &l.contact);
                    for d in 0..3 {
                        row[j][d] += sign * a[d];
                    }
                }
            }
            row
        })
        .collect();
    let weight = |j: usize, d: usize| match d {
        1 => bodies[j].inertia_kg_m2,
        _ => bodies[j].mass_kg,
    };
    let n = links.len();
    let mut a = [[0.0; 2]; 2];
    for e in 0..n {
        for f in 0..n {
            for (j, dofs) in free.iter().enumerate() {
                for d in (0..3).filter(|&d| dofs[d]) {
                    a[e][f] += jac[e][j][d] * jac[f][j][d] / weight(j, d);
                }
            }
        }
    }
    let lambda = match n {
        1 => [-rates[0] / a[0][0], 0.0],
        2 => {
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            [
                (-rates[0] * a[1][1] + a[0][1] * rates[1]) / det,
                (-a[0][0] * rates[1] + a[1][0] * rates[0]) / det,
            ]
        }
        _ => return None,
    };
    if !lambda.iter().all(|x| x.is_finite()) {
        return None;
    }
    Some(
        (free.iter().enumerate())
            .map(|(j, dofs)| {
                [0, 1, 2].map(|d| match dofs[d] {
                    true => (0..n).map(|e| jac[e][j][d] * lambda[e]).sum::<f64>() / weight(j, d),
                    false => 0.0,
                })
            })
            .collect(),
    )
}

/// The impact of the corner of side 0 on the face of side 1 (`None`: a fixed block).
pub fn resolve(sides: [Option<&Turning>; 2], c: &Contact) -> Result<Outcome, Refusal> {
    let (approach, speed, _) = approach(sides, c);
    if approach >= -super::series::TIE * speed {
        return Err(Refusal::Grazing);
    }
    resolve_landing(sides, c)
}

/// A landing in contact: a corner of a side's base comes down on the ground (a ground corner
/// whose rise before is negative) while the corner of side 0 stays on the face of side 1.
/// Every contact takes its impulse at once (Moreau's law, as the time-stepped model resolves
/// them): a ground corner stays on the ground with an impulse that presses, or leaves it with
/// none, and so does the contact between the blocks, which may open.
pub fn resolve_landing(sides: [Option<&Turning>; 2], c: &Contact) -> Result<Outcome, Refusal> {
    let moving: Vec<usize> = (0..2).filter(|&k| sides[k].is_some()).collect();
    let bodies: Vec<Turning> = moving.iter().filter_map(|&k| sides[k].copied()).collect();
    let link = Link {
        sides: [0, 1].map(|k| moving.iter().position(|&m| m == k)),
        contact: *c,
    };
    let all = resolve_all(&bodies, &[link])?;
    let mut after = [None; 2];
    for (j, &k) in moving.iter().enumerate() {
        after[k] = Some(all.after[j]);
    }
    Ok(Outcome {
        after,
        impulse_n_s: all.impulse_n_s[0],
        normal_m_s: all.normal_m_s[0],
        loss_j: all.loss_j,
    })
}

/// A contact of an impact at several contacts: the corner of side 0's block on the face of
/// side 1's, each side a body's index in the impact's list (`None`: a fixed block).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Link {
    pub sides: [Option<usize>; 2],
    pub contact: Contact,
}

/// What an impact at several contacts does: per body its velocities after; per contact its
/// normal impulse (N s) and the corner's normal velocity against the face before and after
/// (m/s); the kinetic energy lost (J).
#[derive(Debug, Clone, PartialEq)]
pub struct Impulses {
    pub after: Vec<After>,
    pub impulse_n_s: Vec<f64>,
    pub normal_m_s: Vec<(f64, f64)>,
    pub loss_j: f64,
}

/// An impact at several contacts at once, every contact between blocks by Moreau's law with
/// its coefficient of restitution e: closed, its normal velocity after -e times before and an
/// impulse that presses, or open, no impulse and its normal velocity after at least that; each
/// body's base by the laws above. Every combination of the laws is a linear system; exactly one
/// outcome must obey them all.
pub fn resolve_all(bodies: &[Turning], links: &[Link]) -> Result<Impulses, Refusal> {
    let tie = super::series::TIE;
    let side = |l: &Link| l.sides.map(|s| s.map(|k| &bodies[k]));
    let approaches: Vec<f64> = links
        .iter()
        .map(|l| approach(side(l), &l.contact).0)
        .collect();
    let (speed, momentum) = bodies.iter().fold((0.0, 0.0), |(speed, momentum), b| {
        let s = b.v.abs() + b.w.abs() + b.omega.abs() * reach(b);
        (speed + s, momentum + b.mass_kg * s)
    });
    let corners =
        |b: &Turning| -> Vec<(Corner, f64)> { b.ground.iter().flatten().copied().collect() };
    // Per body, from its offset: the changes of v, theta' and w, the base's tangential impulse,
    // each ground corner's normal impulse; then each contact's.
    let mut offsets = Vec::new();
    let mut p = 0;
    for b in bodies {
        offsets.push(p);
        p += 4 + corners(b).len();
    }
    let n = p + links.len();
    let choices: Vec<Vec<Laws>> = bodies.iter().map(|b| laws(corners(b).len())).collect();
    let closings = 1usize << links.len();
    let combos: usize = choices.iter().map(Vec::len).product::<usize>() * closings;
    let mut found: Vec<Impulses> = Vec::new();
    for combo in 0..combos {
        let opens = |l: usize| (combo % closings) & 1 << l != 0;
        let mut rest = combo / closings;
        let picked: Vec<Laws> = choices
            .iter()
            .map(|ch| {
                let l = ch[rest % ch.len()];
                rest /= ch.len();
                l
            })
            .collect();
        let mut a = DMatrix::<f64>::zeros(n, n);
        let mut rhs = DVector::<f64>::zeros(n);
        for (j, b) in bodies.iter().enumerate() {
            let (m, r) = (b.mass_kg, offsets[j]);
            let g = [b.centroid[0] - b.pivot[0], b.centroid[1] - b.pivot[1]];
            let ground = corners(b);
            let (mask, friction) = picked[j];
            // Momentum in the velocities q = (v, theta', w), whose centroid moves at
            // (v + theta' g_y, w - theta' g_x): M dq = (P_T, -sum N_k d_k, sum N_k) + sum over
            // the contacts of s P J^T n (the ground corners lie on the pivot's level: no moment
            // from P_T).
            let mass = [
                [m, m * g[1], 0.0],
                [
                    m * g[1],
                    m * (g[0] * g[0] + g[1] * g[1]) + b.inertia_kg_m2,
                    -m * g[0],
                ],
                [0.0, -m * g[0], m],
            ];
            for row in 0..3 {
                for col in 0..3 {
                    a[(r + row, r + col)] = mass[row][col];
                }
            }
            for (l, link) in links.iter().enumerate() {
                for k in (0..2).filter(|&k| link.sides[k] == Some(j)) {
                    let (s, arm) = (SIGN[k], arms(b, &link.contact));
                    for row in 0..3 {
                        a[(r + row, p + l)] = -s * arm[row];
                        // Newton's law at the contact, summed over the sides.
                        a[(p + l, r + row)] = s * arm[row];
                    }
                }
            }
            a[(r, r + 3)] = -1.0;
            for (q, &(_, dx)) in ground.iter().enumerate() {
                a[(r + 1, r + 4 + q)] = dx;
                a[(r + 2, r + 4 + q)] = -1.0;
                if mask & 1 << q != 0 {
                    // On the ground: its rise after, w - theta' d, is zero.
                    a[(r + 4 + q, r + 2)] = 1.0;
                    a[(r + 4 + q, r + 1)] = -dx;
                    rhs[r + 4 + q] = -(b.w - b.omega * dx);
                } else {
                    a[(r + 4 + q, r + 4 + q)] = 1.0;
                }
            }
            match friction {
                Friction::Sticks => {
                    a[(r + 3, r)] = 1.0;
                    rhs[r + 3] = -b.v;
                }
                Friction::Slips(dir) => {
                    a[(r + 3, r + 3)] = 1.0;
                    for q in 0..ground.len() {
                        a[(r + 3, r + 4 + q)] = b.friction * dir;
                    }
                }
                Friction::Free => a[(r + 3, r + 3)] = 1.0,
            }
        }
        for (l, link) in links.iter().enumerate() {
            if opens(l) {
                for col in 0..p {
                    a[(p + l, col)] = 0.0;
                }
                a[(p + l, p + l)] = 1.0;
            } else {
                rhs[p + l] = -(1.0 + link.contact.restitution) * approaches[l];
            }
        }
        let Some(x) = a.lu().solve(&rhs) else {
            continue;
        };
        let mut consistent = true;
        let mut outcome = Impulses {
            after: Vec::with_capacity(bodies.len()),
            impulse_n_s: Vec::with_capacity(links.len()),
            normal_m_s: Vec::with_capacity(links.len()),
            loss_j: 0.0,
        };
        // Impulses are measured against the contacts' and the bodies' momenta.
        let impulse_tol = tie * ((0..links.len()).map(|l| x[p + l].abs()).sum::<f64>() + momentum);
        for (l, link) in links.iter().enumerate() {
            let (before, e) = (approaches[l], link.contact.restitution);
            let impulse = x[p + l];
            // The normal velocity after: what the law holds where the contact closes.
            let normal_after = if opens(l) {
                let change: f64 = (0..2)
                    .filter_map(|k| {
                        let j = link.sides[k]?;
                        let (arm, r) = (arms(&bodies[j], &link.contact), offsets[j]);
                        Some(SIGN[k] * (arm[0] * x[r] + arm[1] * x[r + 1] + arm[2] * x[r + 2]))
                    })
                    .sum();
                consistent &= before + change >= -e * before - tie * speed;
                before + change
            } else {
                consistent &= impulse >= -impulse_tol;
                -e * before
            };
            outcome
                .impulse_n_s
                .push(if opens(l) { 0.0 } else { impulse.max(0.0) });
            outcome.normal_m_s.push((before, normal_after));
        }
        for (j, b) in bodies.iter().enumerate() {
            let r = offsets[j];
            let ground = corners(b);
            let (mask, friction) = picked[j];
            let omega = b.omega + x[r + 1];
            let (v, w) = (b.v + x[r], b.w + x[r + 2]);
            let mut pressed = 0.0;
            for (q, &(_, dx)) in ground.iter().enumerate() {
                if mask & 1 << q != 0 {
                    consistent &= x[r + 4 + q] >= -impulse_tol;
                    pressed += x[r + 4 + q].max(0.0);
                } else {
                    consistent &= w - omega * dx >= -tie * speed;
                }
            }
            consistent &= match friction {
                Friction::Sticks => x[r + 3].abs() <= b.friction * pressed + impulse_tol,
                Friction::Slips(dir) => dir * v >= -tie * speed,
                Friction::Free => true,
            };
            let on: Vec<Corner> = (0..ground.len())
                .filter(|q| mask & 1 << q != 0)
                .map(|q| ground[q].0)
                .collect();
            let slips = matches!(friction, Friction::Slips(_));
            let base = match on.as_slice() {
                [] => Base::Flies,
                [corner] => Base::Pivot {
                    corner: *corner,
                    slips,
                },
                _ => Base::Seated { slips },
            };
            // What the law holds is held to the bit (the solve leaves round-off there): a
            // base that sticks does not slip, a pivot on the ground does not rise, a seated
            // body does not turn.
            let pivot_on = ground.first().is_some_and(|_| mask & 1 != 0);
            let after = After {
                omega: if matches!(base, Base::Seated { .. }) {
                    0.0
                } else {
                    omega
                },
                v: if friction == Friction::Sticks { 0.0 } else { v },
                lift_v: if pivot_on && ground[0].1 == 0.0 {
                    0.0
                } else {
                    w
                },
                base,
            };
            outcome.loss_j +=
                kinetic_j(b, b.omega, b.v, b.w) - kinetic_j(b, after.omega, after.v, after.lift_v);
            outcome.after.push(after);
        }
        if consistent {
            found.push(outcome);
        }
    }
    // A base at the tie between two laws obeys both with one outcome: outcomes that agree to
    // 1e-9 of the speeds are one.
    let same = |x: &Impulses, y: &Impulses| {
        let apart: f64 = (x.after.iter().zip(&y.after).zip(bodies))
            .map(|((a, b), body)| {
                (a.omega - b.omega).abs() * reach(body)
                    + (a.v - b.v).abs()
                    + (a.lift_v - b.lift_v).abs()
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
