//! What happens when a rocking body lands on its other corner (theta returns to 0). The landing
//! corner takes an impulse and the old pivot lifts (Housner 1963): the normal impulse is plastic
//! (the landing corner does not bounce), the angular momentum about the landing corner is kept,
//! and friction limits the tangential impulse. If friction can hold the landing corner, it
//! sticks and the body rocks on it with theta' multiplied by Housner's r = 1 - 2 m b^2 / I_O
//! (times the wall's factor); if not, the corner slips through the impact with the friction
//! impulse at its limit (Routh's construction with a plastic normal impulse). A body whose
//! rotation would reverse lands flat on both corners.

use super::body::RockingBody;
use super::modes::{Corner, Equations, State};
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
fn kinetic(body: &RockingBody, c: f64, omega: f64, v: f64) -> f64 {
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
        // The corner slips through the impact; friction at its limit opposes the slip.
        let dir = pt_stick.signum();
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
        if vq * dir > 0.0 {
            return Err(SimulationError::Bug(format!(
                "{} at t = {time_s} s: the slipping landing reverses its slip",
                body.name
            )));
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
            theta: 0.0,
            omega: w,
            u: 0.0,
            v: vq,
        },
        pivot: Some(next),
        slipped,
        loss_j: before - after,
    })
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
    if right < 0.0 || left < 0.0 {
        return Err(SimulationError::RigidModel {
            at: format!("{} at t = {time_s} s", body.name),
            why: format!(
                "landing flat needs a pulling impulse at a corner (left {left} N s, right \
                 {right} N s): no landing of the rigid model fits"
            ),
        });
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
}
