//! What happens when a rocking body lands on its other corner (theta returns to 0). The landing
//! corner takes an impulse and the old pivot lifts (Housner 1963): the normal impulse is plastic
//! (the landing corner does not bounce), the angular momentum about the landing corner is kept,
//! and friction limits the tangential impulse. If friction can hold the landing corner, it
//! sticks and the body rocks on it with theta' multiplied by Housner's r = 1 - 2 m b^2 / I_O
//! (times the wall's factor); if not, the corner slips through the impact with the friction
//! impulse at its limit (Routh's construction with a plastic normal impulse). A body whose
//! rotation would reverse lands flat on both corners. A body in free flight lands by the same
//! law at whatever angle and velocity it comes down with (`land_from_flight`).

use super::body::RockingBody;
use super::modes::{Corner, Equations, Scales, State};
use super::series;
use crate::error::SimulationError;

/// The outcome of a landing.
#[derive(Debug, Clone, PartialEq)]
pub struct Landing {
    /// The state just after: theta = 0, the new angular velocity and slip velocity.
    pub state: State,
    /// The corner it rocks on next; `None` when it lands flat (seated).
    pub pivot: Option<Corner>,
    /// Whether the landing corner slipped through the impact.
    pub slipped: bool,
    /// Kinetic energy lost (J).
    pub loss_j: f64,
}

/// Kinetic energy at theta = 0 rocking on the corner of sign `c` (0 when seated).
pub(super) fn kinetic(body: &RockingBody, c: f64, omega: f64, v: f64) -> f64 {
    let (m, b, h) = (body.mass_kg, body.half_base_m, body.centroid_height_m);
    let (xg, yg) = (v + h * omega, c * b * omega);
    0.5 * m * (xg * xg + yg * yg) + 0.5 * body.inertia_kg_m2 * omega * omega
}

/// The landing of a body rocking on `pivot` that reaches theta = 0 with angular velocity
/// `omega` and pivot slip velocity `v`, at `time_s` (for messages).
pub fn land(
    body: &RockingBody,
    equations: Equations,
    pivot: Corner,
    omega: f64,
    v: f64,
    time_s: f64,
) -> Result<Landing, SimulationError> {
    let f = body.restitution_factor;
    let next = pivot.other();
    if equations == Equations::Linearised {
        let w = f * body.housner_restitution() * omega;
        let io = body.corner_inertia_kg_m2();
        return Ok(Landing {
            state: State {
                omega: w,
                ..State::default()
            },
            pivot: (w != 0.0).then_some(next),
            slipped: false,
            loss_j: 0.5 * io * (omega * omega - w * w),
        });
    }
    let (m, b, h) = (body.mass_kg, body.half_base_m, body.centroid_height_m);
    let (ig, io, mu) = (
        body.inertia_kg_m2,
        body.corner_inertia_kg_m2(),
        body.friction,
    );
    let s = pivot.sign();
    let before = kinetic(body, s, omega, v);
    let (xg0, yg0) = (v + h * omega, s * b * omega);
    // Sticking landing corner: angular momentum about it is kept.
    let stick_omega = ((ig + m * (h * h - b * b)) * omega + m * h * v) / io;
    let pt_stick = m * (h * stick_omega - xg0);
    let pn_stick = m * (-s * b * stick_omega - yg0);
    let (mut w, mut vq, mut slipped) = (stick_omega, 0.0, false);
    if pt_stick.abs() > mu * pn_stick {
        // The corner slips through the impact; friction at its limit opposes the slip (at
        // theta = 0 the landing corner slips with the pivot, at v), or, where there was none,
        // takes the sticking impulse's sense.
        let dir = if v != 0.0 {
            -v.signum()
        } else {
            pt_stick.signum()
        };
        let inv_mass = 1.0 / m + (b * b - s * dir * mu * b * h) / ig;
        if inv_mass <= 0.0 {
            return Err(SimulationError::RigidModel {
                at: format!("{} at t = {time_s} s", body.name),
                why: format!(
                    "landing on its {} corner with friction {mu}, the corner's effective mass \
                     is not positive (Painleve's paradox in impact): the rigid model with \
                     Coulomb friction cannot go on",
                    next.name()
                ),
            });
        }
        let pn = -2.0 * s * b * omega / inv_mass;
        let pt = dir * mu * pn;
        w = omega + (-h * pt + s * b * pn) / ig;
        vq = xg0 + pt / m - h * w;
        slipped = true;
        if vq * dir > 0.0 && v == 0.0 {
            // From no slip, the slip cannot take the friction's sense: the sticking impulse is
            // on the cone's edge to round-off (|W_tn| = mu W_tt, a square block on friction
            // 0.6), and the corner sticks.
            (w, vq, slipped) = (stick_omega, 0.0, false);
        } else if vq * dir > 0.0 {
            // The slip stops within the impact and turns: Routh's construction, as for a
            // landing from flight, the landing corner's arm (h, -s b) from the centroid.
            let at = format!("{} at t = {time_s} s", body.name);
            let dx = -s * b;
            (w, vq) = slip_turning((body, h, dx), (v, yg0 - dx * omega, omega), dir, &at)?;
        }
    }
    // The rotation must carry on onto the new corner (theta' of the sign of the new corner,
    // -s); otherwise the body lands flat.
    if w * -s <= 0.0 {
        return land_flat(body, v + h * omega, yg0, omega, before, time_s);
    }
    let (w, vq) = (f * w, f * vq);
    let after = kinetic(body, -s, w, vq);
    Ok(Landing {
        state: State {
            omega: w,
            v: vq,
            ..State::default()
        },
        pivot: Some(next),
        slipped,
        loss_j: before - after,
    })
}

/// Whether a body in free flight, turned by `theta`, reaches the ground on `corner` without
/// coming down: its centroid rising at `yg0` (m/s) and turning at `omega` (rad/s) leave the
/// corner's vertical velocity zero to a tie (a flight of round-off, after a blow that left its
/// pivot rising at a tie's rate). That is a touch, not an impact: no impulse, and the body
/// goes on from the corner at the velocities it has (less the corner's vertical speed, a tie,
/// whose share of the kinetic energy counts as lost).
pub fn touches(body: &RockingBody, theta: f64, corner: Corner, (yg0, omega): (f64, f64)) -> bool {
    super::tie_speed(body, rise_m_s(body, theta, corner, (yg0, omega)))
}

/// The vertical velocity (m/s) of `corner` of a body in free flight turned by `theta`, its
/// centroid rising at `yg0` (m/s) and turning at `omega` (rad/s).
pub fn rise_m_s(body: &RockingBody, theta: f64, corner: Corner, (yg0, omega): (f64, f64)) -> f64 {
    let (b, h, s) = (body.half_base_m, body.centroid_height_m, corner.sign());
    let (sin, cos) = theta.sin_cos();
    yg0 - (s * b * cos - h * sin) * omega
}

/// The landing of a body in free flight on its corner `corner`, turned by `theta`, with its
/// centroid's velocity (`xg0`, `yg0`, m/s) and angular velocity `omega` (clockwise, rad/s):
/// the law of [`land`] at any angle and any velocity (Housner's assumption, the impulse at the
/// landing corner alone, plastic in its normal). Where friction holds the corner, the angular
/// momentum about it is kept and the body rocks on it; where not, the corner slips through the
/// impact with the friction impulse at its limit (Routh), turning its slip within the impact
/// where it stops there ([`slip_turning`]). At theta = 0 both corners land ([`land_flat`]),
/// unless the other one rises: then `corner` alone does; where landing flat would pull at a
/// corner, the one corner whose landing leaves the other rising lands alone. The wall's
/// restitution factor multiplies the velocities after, as it does Housner's. A corner that
/// reaches the ground without coming down touches it ([`touches`]).
/// (The landing at theta = 0 from rocking keeps [`land`], whose arithmetic every earlier run's
/// outputs were computed with.)
pub fn land_from_flight(
    body: &RockingBody,
    theta: f64,
    corner: Corner,
    (xg0, yg0, omega): (f64, f64, f64),
    time_s: f64,
) -> Result<Landing, SimulationError> {
    let (m, ig) = (body.mass_kg, body.inertia_kg_m2);
    let before = 0.5 * m * (xg0 * xg0 + yg0 * yg0) + 0.5 * ig * omega * omega;
    if theta == 0.0 {
        // Upright, both corners reach the ground; where the other one rises (an impact at a
        // vertical face left the body turning up off it), this one alone lands.
        let other = corner.other();
        let alone = rise_m_s(body, theta, other, (yg0, omega)) > 0.0
            && !touches(body, theta, other, (yg0, omega));
        if !alone {
            return match flat(body, xg0, yg0, omega, before) {
                Ok(landing) => Ok(landing),
                Err(pull) => land_pulled_off(body, pull, (xg0, yg0, omega), before, time_s),
            };
        }
    }
    land_on_corner(body, theta, corner, (xg0, yg0, omega), before, time_s)
}

/// The contacts of an upright landing complementary: where landing flat would pull at a corner,
/// one corner lands alone, which holds where that corner comes down and the landing leaves the
/// other rising (or touching to a tie). Exactly one such corner must hold; with none, or both,
/// no landing of the rigid model fits.
fn land_pulled_off(
    body: &RockingBody,
    pull: Pull,
    (xg0, yg0, omega): (f64, f64, f64),
    before: f64,
    time_s: f64,
) -> Result<Landing, SimulationError> {
    let mut holds = Vec::new();
    for lands in [Corner::Left, Corner::Right] {
        if rise_m_s(body, 0.0, lands, (yg0, omega)) >= 0.0 {
            continue;
        }
        let landing = land_on_corner(body, 0.0, lands, (xg0, yg0, omega), before, time_s)?;
        // After it the body turns about the landing corner: its centroid rises at s b theta'.
        let w = landing.state.omega;
        let yg = lands.sign() * body.half_base_m * w;
        if rise_m_s(body, 0.0, lands.other(), (yg, w)) > 0.0
            || touches(body, 0.0, lands.other(), (yg, w))
        {
            holds.push(landing);
        }
    }
    match <[Landing; 1]>::try_from(holds) {
        Ok([landing]) => Ok(landing),
        Err(holds) => {
            let alone = if holds.is_empty() {
                ", and neither corner landing alone leaves the other off the ground"
            } else {
                ", and each corner landing alone leaves the other off the ground"
            };
            Err(pull.error(body, time_s, alone))
        }
    }
}

/// The landing of a body in free flight on `corner` alone (the rest of [`land_from_flight`]).
fn land_on_corner(
    body: &RockingBody,
    theta: f64,
    corner: Corner,
    (xg0, yg0, omega): (f64, f64, f64),
    before: f64,
    time_s: f64,
) -> Result<Landing, SimulationError> {
    let (m, b, h, mu) = (
        body.mass_kg,
        body.half_base_m,
        body.centroid_height_m,
        body.friction,
    );
    let (ig, io) = (body.inertia_kg_m2, body.corner_inertia_kg_m2());
    // The centroid G_y above the corner and dx = dG_y/dtheta; turning about the corner, the
    // centroid moves at theta' (G_y, dx).
    let s = corner.sign();
    let (sin, cos) = theta.sin_cos();
    let (gy, dx) = (s * b * sin + h * cos, s * b * cos - h * sin);
    let fall = yg0 - dx * omega;
    if touches(body, theta, corner, (yg0, omega)) {
        return Ok(Landing {
            state: State {
                theta,
                omega,
                v: xg0 - gy * omega,
                ..State::default()
            },
            pivot: Some(corner),
            slipped: !super::tie_speed(body, xg0 - gy * omega),
            // The corner's vertical speed, a tie, is gone: the centroid's vertical velocity
            // becomes dx theta', and what that takes of the kinetic energy (first order in
            // the tie, not second) goes with the loss.
            loss_j: 0.5 * m * (yg0 * yg0 - (dx * omega) * (dx * omega)),
        });
    }
    let stick = (ig * omega + m * (gy * xg0 + dx * yg0)) / io;
    let (pt, pn) = (m * (gy * stick - xg0), m * (dx * stick - yg0));
    let (mut w, mut vq, mut slipped) = (stick, 0.0, false);
    if pt.abs() > mu * pn {
        // Friction cannot hold the corner (or holding it would pull): it slips through the
        // impact, friction at its limit against its slip before (the sticking impulse's sense
        // where it had none). Its normal velocity after, yg + P_n / m - dx w, is zero, with w
        // changed by the impulse's moment about the centroid, -(G_y P_t + dx P_n).
        let slip = xg0 - gy * omega;
        let dir = if slip != 0.0 {
            -slip.signum()
        } else {
            pt.signum()
        };
        let inv_mass = 1.0 / m + (dx * dx + dir * mu * gy * dx) / ig;
        let pn = -fall / inv_mass;
        let at = format!("{} at t = {time_s} s", body.name);
        if inv_mass <= 0.0 {
            return Err(SimulationError::RigidModel {
                at,
                why: format!(
                    "landing from free flight on its {} corner with friction {mu}, the \
                     corner's effective mass is not positive (Painleve's paradox in impact): \
                     the rigid model with Coulomb friction cannot go on",
                    corner.name()
                ),
            });
        }
        let pt = dir * mu * pn;
        w = omega - (gy * pt + dx * pn) / ig;
        vq = xg0 + pt / m - gy * w;
        slipped = true;
        if pn <= 0.0 {
            return Err(SimulationError::Bug(format!(
                "{at}: a landing from free flight whose corner does not come down (normal \
                 impulse {pn} N s)"
            )));
        }
        if vq * dir > 0.0 {
            // The slip stops within the impact and turns (Routh's construction goes on from
            // there): friction cannot hold it, as the sticking impulse outside the cone says.
            (w, vq) = slip_turning((body, gy, dx), (slip, yg0 - dx * omega, omega), dir, &at)?;
        }
    }
    let (w, vq) = (body.restitution_factor * w, body.restitution_factor * vq);
    let (xg, yg) = (vq + gy * w, dx * w);
    let after = 0.5 * m * (xg * xg + yg * yg) + 0.5 * ig * w * w;
    Ok(Landing {
        state: State {
            theta,
            omega: w,
            v: vq,
            ..State::default()
        },
        pivot: Some(corner),
        slipped,
        loss_j: before - after,
    })
}

/// Routh's construction where a landing corner's slip stops within a plastic impact and turns:
/// the normal impulse P_n grows from zero, the corner's velocity changing by W P (W the
/// Delassus matrix of the corner: its tangential and normal velocity per unit impulse), the
/// friction impulse at the limit against the slip, `dir` mu dP_n, until the slip is zero;
/// friction cannot hold it there (|W_tn| > mu W_tt, else the sticking impulse lies in the cone
/// and the landing sticks), so it slips the other way, friction reversed, until the corner's
/// normal velocity is zero. `(slip, fall)`: the corner's velocity before; returns the angular
/// velocity and the slip after (before the restitution factor).
fn slip_turning(
    (body, gy, dx): (&RockingBody, f64, f64),
    (slip, fall, omega): (f64, f64, f64),
    dir: f64,
    at: &str,
) -> Result<(f64, f64), SimulationError> {
    let (m, ig, mu) = (body.mass_kg, body.inertia_kg_m2, body.friction);
    let (wtt, wtn, wnn) = (1.0 / m + gy * gy / ig, gy * dx / ig, 1.0 / m + dx * dx / ig);
    // The slip's phase: the slip and the fall per unit normal impulse.
    let pn1 = -slip / (wtn + dir * mu * wtt);
    let fall1 = fall + (wnn + dir * mu * wtn) * pn1;
    let back = -dir;
    let inv_mass = wnn + back * mu * wtn;
    if wtn.abs() <= mu * wtt || inv_mass <= 0.0 || !(pn1 > 0.0 && fall1 < 0.0) {
        return Err(SimulationError::RigidModel {
            at: at.into(),
            why: format!(
                "landing from free flight, its slip stops within the impact (after {pn1} N s of \
                 normal impulse) where {}: Routh's construction for a plastic landing has no \
                 next phase here",
                if inv_mass <= 0.0 {
                    "the corner's effective mass slipping back is not positive (Painleve's \
                     paradox in impact)"
                } else {
                    "friction could hold it or the impact ends, though the sticking impulse lies \
                     outside the cone (a tie within round-off)"
                }
            ),
        });
    }
    let pn2 = -fall1 / inv_mass;
    let (pt, pn) = (mu * (dir * pn1 + back * pn2), pn1 + pn2);
    let w = omega - (gy * pt + dx * pn) / ig;
    Ok((w, slip + pt / m + gy * (omega - w)))
}

/// A landing that leaves the body seated: both corners share the normal impulse, the rotation
/// and the vertical velocity stop, and the base sticks or slips as friction allows.
fn land_flat(
    body: &RockingBody,
    xg0: f64,
    yg0: f64,
    omega: f64,
    before: f64,
    time_s: f64,
) -> Result<Landing, SimulationError> {
    flat(body, xg0, yg0, omega, before).map_err(|pull| pull.error(body, time_s, ""))
}

/// A flat landing that would need a pulling impulse: both corners' impulses (N s).
struct Pull {
    left: f64,
    right: f64,
}

impl Pull {
    /// The error, `alone` saying what single corners' landings did.
    fn error(&self, body: &RockingBody, time_s: f64, alone: &str) -> SimulationError {
        SimulationError::RigidModel {
            at: format!("{} at t = {time_s} s", body.name),
            why: format!(
                "landing flat needs a pulling impulse at a corner (left {} N s, right {} \
                 N s){alone}: no landing of the rigid model fits",
                self.left, self.right
            ),
        }
    }
}

/// [`land_flat`]'s impulses, or the corner where they would pull.
fn flat(body: &RockingBody, xg0: f64, yg0: f64, omega: f64, before: f64) -> Result<Landing, Pull> {
    let (m, b, h, mu) = (
        body.mass_kg,
        body.half_base_m,
        body.centroid_height_m,
        body.friction,
    );
    let pn = -m * yg0;
    let mut pt = -m * xg0;
    // The base sticks where friction can stop it: its velocity is then zero, not the round-off
    // of xg0 - (m xg0) / m (a slip of 1e-17 m/s left no mode to decide: it would slide, and
    // could not).
    let mut xg = 0.0;
    if pt.abs() > mu * pn {
        pt = pt.signum() * mu * pn;
        xg = xg0 + pt / m;
    }
    // Moment about the centroid: I_G (0 - omega) = -h P_t + b (P_R - P_L).
    let diff = (-body.inertia_kg_m2 * omega + h * pt) / b;
    let (right, left) = (0.5 * (pn + diff), 0.5 * (pn - diff));
    // A body that lands at a rate of round-off (back at its seat as a ground acceleration
    // touches its threshold) needs impulses of round-off, of either sign: none is taken.
    let tie = series::TIE * m * Scales::of(body).velocity;
    let (right, left) = if right.abs().max(left.abs()) <= tie {
        (right.max(0.0), left.max(0.0))
    } else {
        (right, left)
    };
    if right < 0.0 || left < 0.0 {
        return Err(Pull { left, right });
    }
    let state = State {
        v: xg,
        ..State::default()
    };
    Ok(Landing {
        state,
        pivot: None,
        slipped: pt.abs() == mu * pn,
        loss_j: before - 0.5 * m * xg * xg,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A body's mass (kg), half base and centroid height (m) and inertia about its centroid
    /// (kg m2), as the tests' formulas name them: m, b, h, I_G.
    fn sizes(body: &RockingBody) -> (f64, f64, f64, f64) {
        (
            body.mass_kg,
            body.half_base_m,
            body.centroid_height_m,
            body.inertia_kg_m2,
        )
    }

    /// Landings from free flight, over turned bodies and velocities that bring a corner down:
    /// the body rocks on the landing corner after; where that corner sticks, it is at rest and
    /// the angular momentum about it is kept; where it slips, its normal velocity is zero, the
    /// friction impulse is mu times the normal one and opposes its slip before, and the impulse
    /// accounts for the change of momentum and of angular momentum about the centroid; energy
    /// is lost either way. Both kinds come up.
    #[test]
    fn a_landing_from_flight_keeps_its_momenta_within_coulombs_cone() {
        let body = RockingBody::rectangle("B", 0.6, 1.2, 900.0, 0.5, 9.81);
        let (m, b, h, ig) = sizes(&body);
        let io = body.corner_inertia_kg_m2();
        let mut kinds = [0, 0];
        for theta in [-0.3, -0.05, 0.02, 0.2, 0.45] {
            let corner = Corner::of_sign(theta);
            let s = corner.sign();
            let (gy, dx) = (
                s * b * theta.sin() + h * theta.cos(),
                s * b * theta.cos() - h * theta.sin(),
            );
            for omega in [-2.0, -0.4, 0.0, 0.7, 1.5] {
                for xg in [-1.2, -0.1, 0.0, 0.3, 2.0] {
                    for yg in [-1.5, -0.6, -0.2] {
                        // The corner's velocity before: its fall, and its slip.
                        let (slip, fall) = (xg - gy * omega, yg - dx * omega);
                        if fall >= 0.0 {
                            continue;
                        }
                        let l =
                            land_from_flight(&body, theta, corner, (xg, yg, omega), 0.0).unwrap();
                        assert_eq!(l.pivot, Some(corner));
                        let w = l.state.omega;
                        let (xa, ya) = (l.state.v + gy * w, dx * w);
                        let (pt, pn) = (m * (xa - xg), m * (ya - yg));
                        // Moment of the impulse at the corner about the centroid.
                        assert!((ig * (w - omega) + gy * pt + dx * pn).abs() < 1e-9);
                        assert!(pn > 0.0 && l.loss_j >= -1e-9, "{pn} {}", l.loss_j);
                        if l.slipped {
                            kinds[1] += 1;
                            assert!((pt.abs() - body.friction * pn).abs() < 1e-9 * pn);
                            assert!(pt * slip < 0.0, "against the slip: {pt} {slip}");
                            assert!(l.state.v * slip >= 0.0, "the slip keeps its sense");
                        } else {
                            kinds[0] += 1;
                            assert_eq!(l.state.v, 0.0);
                            let before = ig * omega + m * (gy * xg + dx * yg);
                            assert!((io * w - before).abs() < 1e-12 * (1.0 + before.abs()));
                            assert!(pt.abs() <= body.friction * pn * (1.0 + 1e-12));
                        }
                    }
                }
            }
        }
        assert!(
            kinds.iter().all(|&k| k > 20),
            "stuck and slipped landings: {kinds:?}"
        );
    }

    /// Landings from free flight on little friction, where a corner's slip stops within the
    /// impact and turns: the impulse is Routh's two legs on the cone's edges, P1 (dir mu, 1)
    /// and P2 (-dir mu, 1), both positive, with the slip zero where the first ends (from the
    /// momenta after that leg alone), the slip after against the slip before and the second
    /// leg's friction against it; momentum about the centroid is balanced, energy is lost.
    #[test]
    fn a_slip_that_stops_within_a_landing_turns_the_other_way() {
        let body = RockingBody::rectangle("B", 0.6, 1.2, 900.0, 0.1, 9.81);
        let (m, b, h, ig, mu) = (
            body.mass_kg,
            body.half_base_m,
            body.centroid_height_m,
            body.inertia_kg_m2,
            body.friction,
        );
        let mut turned = 0;
        for theta in [-0.45, -0.3, -0.2, 0.2, 0.3, 0.45] {
            let corner = Corner::of_sign(theta);
            let s = corner.sign();
            let (gy, dx) = (
                s * b * theta.sin() + h * theta.cos(),
                s * b * theta.cos() - h * theta.sin(),
            );
            for omega in [-2.0, -0.7, -0.2, 0.0, 0.3, 0.9, 1.8] {
                for xg in [-1.5, -0.4, -0.05, 0.1, 0.6, 1.4] {
                    for yg in [-1.5, -0.6, -0.1] {
                        let (slip, fall) = (xg - gy * omega, yg - dx * omega);
                        if fall >= 0.0 {
                            continue;
                        }
                        let l =
                            land_from_flight(&body, theta, corner, (xg, yg, omega), 0.0).unwrap();
                        let w = l.state.omega;
                        let (pt, pn) = (m * (l.state.v + gy * w - xg), m * (dx * w - yg));
                        let scale = m * (xg.abs() + yg.abs() + omega.abs());
                        assert!((ig * (w - omega) + gy * pt + dx * pn).abs() < 1e-12 * scale);
                        assert!(pn > 0.0 && l.loss_j >= 0.0, "{pn} {}", l.loss_j);
                        if !(l.slipped && l.state.v * slip < 0.0) {
                            continue;
                        }
                        turned += 1;
                        let dir = -slip.signum();
                        let pn1 = 0.5 * (pn + pt / (dir * mu));
                        let pn2 = pn - pn1;
                        assert!(pn1 > 0.0 && pn2 > 0.0, "{pn1} {pn2}");
                        // The corner's slip after the first leg alone.
                        let w1 = omega - (gy * dir * mu * pn1 + dx * pn1) / ig;
                        let slip1 = xg + dir * mu * pn1 / m - gy * w1;
                        assert!(slip1.abs() < 1e-12 * scale / m, "{slip1}");
                        assert!(-dir * l.state.v < 0.0, "the second leg's friction opposes");
                    }
                }
            }
        }
        assert!(turned > 20, "landings whose slip turns: {turned}");
    }

    /// Landings at theta = 0 of a body whose pivot slips (slide-rock), over bodies, friction,
    /// rates and slips: the impulse at the landing corner (arm (h, -s b) from the centroid)
    /// balances the momentum about the centroid and presses; where the corner sticks its slip
    /// after is zero and the impulse lies in the cone; where it slips the friction impulse is
    /// at the cone's edge against the slip before, which keeps its sense (from none: against the
    /// slip it takes), or the slip stops within the impact and turns (Routh: the second leg's
    /// friction against the slip after); energy is lost. Every kind comes up, the turning one
    /// too, where the landing once took the sticking impulse's sense for the friction's and
    /// called the turn a bug.
    #[test]
    fn a_slipping_pivots_landing_keeps_its_momenta_within_coulombs_cone() {
        let mut kinds = [0, 0, 0];
        for (width, mu) in [(1.2, 0.6), (0.6, 0.3), (0.3, 0.6), (0.8, 0.15)] {
            let body = RockingBody::rectangle("B", width, 1.2, 900.0, mu, 9.81);
            let (m, b, h, ig) = sizes(&body);
            for pivot in [Corner::Left, Corner::Right] {
                let s = pivot.sign();
                let dx = -s * b;
                for rate in [0.01, 0.2, 0.9, 2.5] {
                    // Rocking back onto the other corner: theta' of its sign, -s.
                    let omega = -s * rate;
                    for v in [-1.5, -0.3, -0.02, -1e-4, 0.0, 1e-4, 0.02, 0.3, 1.5] {
                        let l = land(&body, Equations::Exact, pivot, omega, v, 0.0).unwrap();
                        let Some(next) = l.pivot else {
                            continue;
                        };
                        assert_eq!(next, pivot.other());
                        let w = l.state.omega;
                        let (pt, pn) = (
                            m * (l.state.v + h * w - (v + h * omega)),
                            m * (dx * w - s * b * omega),
                        );
                        let scale = m * (v.abs() + rate);
                        assert!((ig * (w - omega) + h * pt + dx * pn).abs() < 1e-12 * scale);
                        assert!(pn > 0.0 && l.loss_j >= 0.0, "{pn} {}", l.loss_j);
                        if !l.slipped {
                            kinds[0] += 1;
                            assert_eq!(l.state.v, 0.0);
                            assert!(pt.abs() <= mu * pn * (1.0 + 1e-12));
                        } else if l.state.v * v >= 0.0 {
                            kinds[1] += 1;
                            assert!((pt.abs() - mu * pn).abs() < 1e-12 * pn);
                            // Against the slip before, or from none, the slip it takes.
                            let slip = if v != 0.0 { v } else { l.state.v };
                            assert!(pt * slip < 0.0, "against the slip: {pt} {slip}");
                        } else {
                            kinds[2] += 1;
                            // Two legs on the cone's edges, both pressing; the second's
                            // friction against the slip after.
                            let dir = -v.signum();
                            let pn1 = 0.5 * (pn + pt / (dir * mu));
                            assert!(pn1 > 0.0 && pn - pn1 > 0.0, "{pn1} {pn}");
                            let w1 = omega - (h * dir * mu * pn1 + dx * pn1) / ig;
                            let slip1 = v + dir * mu * pn1 / m - h * (w1 - omega);
                            assert!(slip1.abs() < 1e-12 * scale / m, "{slip1}");
                        }
                    }
                }
            }
        }
        assert!(
            kinds.iter().all(|&k| k > 5),
            "stuck, slipped, turned: {kinds:?}"
        );
    }

    /// A pure rocking landing with friction to spare is Housner's: theta' times r, the
    /// corner stuck, the energy falling by r^2.
    #[test]
    fn a_stuck_landing_is_housners() {
        let body = RockingBody::rectangle("B", 0.4, 1.6, 100.0, 0.8, 9.81);
        let r = body.housner_restitution();
        let l = land(&body, Equations::Exact, Corner::Right, -0.5, 0.0, 0.0).unwrap();
        assert!((l.state.omega + 0.5 * r).abs() < 1e-15);
        assert_eq!(l.pivot, Some(Corner::Left));
        assert!(!l.slipped);
        let before = 0.5 * body.corner_inertia_kg_m2() * 0.25;
        assert!((l.loss_j - before * (1.0 - r * r)).abs() < 1e-12 * before);
    }

    /// An upright body in flight whose one corner comes down while the other rises (an impact
    /// at a vertical face left it turning up off its base: scan run 1148) lands on the falling
    /// corner alone and rocks on it, the other corner going on up; taken as a flat landing, it
    /// needed a pulling impulse at both corners and stopped the run. Where both come down, it
    /// lands flat.
    #[test]
    fn an_upright_body_lands_on_the_corner_that_comes_down() {
        let body = RockingBody::rectangle("B", 0.6, 1.2, 900.0, 0.8, 9.81);
        let (m, b, h, ig) = sizes(&body);
        let (xg, yg, omega) = (0.05, 0.2, -2.0);
        assert!(rise_m_s(&body, 0.0, Corner::Left, (yg, omega)) < 0.0);
        assert!(rise_m_s(&body, 0.0, Corner::Right, (yg, omega)) > 0.0);
        let l = land_from_flight(&body, 0.0, Corner::Left, (xg, yg, omega), 0.0).unwrap();
        assert_eq!(l.pivot, Some(Corner::Left));
        let w = l.state.omega;
        let (gy, dx) = (h, -b);
        let (pt, pn) = (m * (l.state.v + gy * w - xg), m * (dx * w - yg));
        assert!((ig * (w - omega) + gy * pt + dx * pn).abs() < 1e-12 * ig * omega.abs());
        assert!(pn > 0.0 && pt.abs() <= body.friction * pn && l.loss_j > 0.0);
        assert!(w < 0.0 && rise_m_s(&body, 0.0, Corner::Right, (dx * w, w)) > 0.0);
        let flat = land_from_flight(&body, 0.0, Corner::Left, (xg, -0.5, 0.3), 0.0).unwrap();
        assert_eq!((flat.pivot, flat.state.omega), (None, 0.0));
    }

    /// A slender body that comes down upright on both corners, sliding: stopping its base by
    /// friction would turn it harder than the ground's push can stop, so landing flat needs a
    /// pulling impulse at one corner (as scan run 1592's slab did at 3.4112 s, and stopped the
    /// run). It lands on one corner alone, the one whose landing leaves the other rising: its
    /// angular momentum about that corner kept where friction holds it, the impulse pushing and
    /// within Coulomb's cone, energy lost. Sliding the other way lands it on the other corner.
    #[test]
    fn an_upright_landing_that_would_pull_lands_on_one_corner() {
        let body = RockingBody::rectangle("S", 0.3, 1.2, 450.0, 0.6, 9.81);
        let (m, b, h, ig) = sizes(&body);
        let (mut pivots, yg) = (Vec::new(), -0.1_f64);
        for xg in [0.05_f64, -0.05] {
            // Stuck flat, the impulses' moment about the centroid h m x_g outweighs b m |y_g|.
            assert!(h * xg.abs() > b * yg.abs() && xg.abs() <= body.friction * yg.abs());
            let l = land_from_flight(&body, 0.0, Corner::Left, (xg, yg, 0.0), 0.0).unwrap();
            let c = l.pivot.expect("it rocks on a corner");
            let (w, dx) = (l.state.omega, c.sign() * b);
            let (pt, pn) = (m * (l.state.v + h * w - xg), m * (dx * w - yg));
            assert!((ig * w + h * pt + dx * pn).abs() < 1e-12 * m * b * xg.abs());
            assert!(pn > 0.0 && pt.abs() <= body.friction * pn && l.loss_j > 0.0);
            assert!(!l.slipped && l.state.v == 0.0);
            assert!(rise_m_s(&body, 0.0, c.other(), (dx * w, w)) > 0.0);
            pivots.push(c);
        }
        assert_eq!(pivots, [Corner::Right, Corner::Left]);
    }
}
