use super::*;
use approx::assert_relative_eq;

/// The corners on the ground of a body rocking on the corner of sign s (its pivot), or of a
/// seated one `width` wide (s = 0: its pivot the right corner).
fn standing(s: f64, width: f64) -> [Option<(Corner, f64)>; 2] {
    if s == 0.0 {
        [Some((Corner::Right, 0.0)), Some((Corner::Left, -width))]
    } else {
        [Some((Corner::of_sign(s), 0.0)), None]
    }
}

/// A slab 0.3 m wide and 1.2 m high, 900 kg, rocking on its corner of sign `s` (at the
/// origin) by `theta` (clockwise) at `omega`, its pivot slipping at `v`.
fn slab(s: f64, theta: f64, omega: f64, v: f64, friction: f64) -> Turning {
    let (b, h, m) = (0.15, 0.6, 900.0);
    Turning {
        mass_kg: m,
        inertia_kg_m2: m * (4.0 * b * b + 4.0 * h * h) / 12.0,
        friction,
        pivot: [0.0, 0.0],
        centroid: turned([0.0, 0.0], theta, [-s * b, h]),
        omega,
        v,
        w: 0.0,
        ground: standing(s, 0.3),
    }
}

/// The point `r` from `origin` turned clockwise by `theta`.
fn turned(origin: [f64; 2], theta: f64, r: [f64; 2]) -> [f64; 2] {
    let (s, c) = theta.sin_cos();
    [
        origin[0] + r[0] * c + r[1] * s,
        origin[1] - r[0] * s + r[1] * c,
    ]
}

/// Angular momentum about the point `o` (counter-clockwise positive).
fn momentum_about(b: &Turning, o: [f64; 2], omega: f64, v: f64, w: f64) -> f64 {
    let vg = point_velocity(b, b.centroid, omega, v, w);
    let g = [b.centroid[0] - o[0], b.centroid[1] - o[1]];
    -b.inertia_kg_m2 * omega + b.mass_kg * (g[0] * vg[1] - g[1] * vg[0])
}

/// Checks, from an outcome's velocities alone, the laws it must obey: Newton's at the
/// contact; each body's angular momentum about its pivot against the contact's impulse; the
/// pivot's impulse (what the body's momentum needs besides the contact's) pressing and in
/// Coulomb's cone with the pivot still, at the cone's edge against the slip with it slipping,
/// and zero with the pivot rising.
fn obeys(sides: [Option<&Turning>; 2], c: &Contact, out: &Outcome) {
    let sign = [1.0, -1.0];
    let n = c.normal;
    let normal = |after: bool| -> f64 {
        (0..2)
            .filter_map(|k| {
                let b = sides[k]?;
                let a = out.after[k].unwrap();
                let u = if after {
                    point_velocity(b, c.point, a.omega, a.v, a.lift_v)
                } else {
                    point_velocity(b, c.point, b.omega, b.v, b.w)
                };
                Some(sign[k] * (n[0] * u[0] + n[1] * u[1]))
            })
            .sum()
    };
    let (before, after) = (normal(false), normal(true));
    assert!(before < 0.0);
    assert_relative_eq!(
        after,
        -c.restitution * before,
        epsilon = 1e-14 * before.abs()
    );
    assert_relative_eq!(out.normal_m_s.0, before, epsilon = 1e-15 * before.abs());
    for k in 0..2 {
        let Some(b) = sides[k] else { continue };
        let a = out.after[k].unwrap();
        let p = [
            sign[k] * out.impulse_n_s * n[0],
            sign[k] * out.impulse_n_s * n[1],
        ];
        // Impulses are measured against the momenta before and after, moments against those
        // over twice the centroid's reach (the contact lies up to there).
        let speeds = b.v.abs() + a.v.abs() + (b.omega.abs() + a.omega.abs()) * reach(b);
        let tol = 1e-14 * b.mass_kg * (speeds + a.lift_v.abs());
        let moment_tol = 2.0 * reach(b) * tol;
        // Angular momentum about the pivot: besides the contact's impulse, only a seated
        // body's other corner has a moment there (its normal impulse at its offset).
        let d = [c.point[0] - b.pivot[0], c.point[1] - b.pivot[1]];
        let dh = momentum_about(b, b.pivot, a.omega, a.v, a.lift_v)
            - momentum_about(b, b.pivot, b.omega, b.v, b.w);
        let other = dh - (d[0] * p[1] - d[1] * p[0]);
        let (g1, g0) = (
            point_velocity(b, b.centroid, a.omega, a.v, a.lift_v),
            point_velocity(b, b.centroid, b.omega, b.v, b.w),
        );
        let pt = b.mass_kg * (g1[0] - g0[0]) - p[0];
        let pn = b.mass_kg * (g1[1] - g0[1]) - p[1];
        let cone = |slips: bool| {
            if slips {
                assert!(a.v != 0.0);
                assert_relative_eq!(pt, -b.friction * pn * a.v.signum(), epsilon = tol);
            } else {
                assert_eq!(a.v, 0.0);
                assert!(pt.abs() <= b.friction * pn + tol, "{pt} {pn}");
            }
        };
        match a.base {
            Base::Pivot { slips, .. } => {
                assert!(other.abs() <= moment_tol, "{other}");
                assert!(pn > 0.0, "{pn}");
                cone(slips);
            }
            Base::Seated { slips } => {
                assert_eq!((a.omega, a.lift_v), (0.0, 0.0));
                let (_, dx) = b.ground[1].unwrap();
                let left = other / dx;
                assert!(
                    left >= -moment_tol && pn - left >= -moment_tol,
                    "{left} {pn}"
                );
                cone(slips);
            }
            Base::Flies => {
                assert!(other.abs() <= moment_tol, "{other}");
                assert!(pt.abs() <= tol && pn.abs() <= tol, "{pt} {pn}");
            }
        }
        // Every corner on the ground before does not sink.
        for (_, dx) in b.ground.iter().flatten() {
            assert!(a.lift_v - a.omega * dx >= -tol, "corner at {dx} sinks");
        }
    }
}

/// The slab meets a fixed face on its right with its top right corner: rocking on its left
/// corner swinging back (theta < 0, theta' > 0) or on its right corner swinging out.
fn against_a_face(s: f64, friction: f64, restitution: f64) -> (Turning, Contact) {
    let theta = 0.05 * s;
    let body = slab(s, theta, 0.4, 0.0, friction);
    let point = turned([0.0, 0.0], theta, [0.15 - s * 0.15, 1.2]);
    let contact = Contact {
        point,
        normal: [-1.0, 0.0],
        restitution,
    };
    (body, contact)
}

#[test]
fn a_slab_swinging_back_rebounds_from_a_face_with_its_rate_times_e() {
    for e in [1.0, 0.5, 0.0] {
        let (body, contact) = against_a_face(-1.0, 10.0, e);
        let out = resolve([Some(&body), None], &contact).unwrap();
        let a = out.after[0].unwrap();
        // One degree of freedom: the corner's normal velocity is theta' times its arm.
        assert_relative_eq!(a.omega, -e * body.omega, epsilon = 1e-15);
        assert!(matches!(a.base, Base::Pivot { slips: false, .. }));
        let before = kinetic_j(&body, body.omega, 0.0, 0.0);
        assert_relative_eq!(out.loss_j, (1.0 - e * e) * before, epsilon = 1e-14 * before);
        obeys([Some(&body), None], &contact, &out);
    }
}

#[test]
fn a_slab_slips_on_its_pivot_when_its_base_cannot_hold_the_impulse() {
    // The pivot's impulse leans by 0.175 / 0.15 of the vertical: past mu 0.8.
    let (body, contact) = against_a_face(-1.0, 0.8, 1.0);
    let out = resolve([Some(&body), None], &contact).unwrap();
    assert!(matches!(
        out.after[0].unwrap().base,
        Base::Pivot { slips: true, .. }
    ));
    obeys([Some(&body), None], &contact, &out);
    // Friction at the pivot takes energy even though the contact is elastic.
    assert!(out.loss_j > 0.0);
}

#[test]
fn a_slab_swinging_out_into_a_face_leaves_the_ground() {
    // Its centroid rises as it strikes: only a pull on its base could turn that rise back.
    for friction in [0.8, 10.0] {
        let (body, contact) = against_a_face(1.0, friction, 1.0);
        let out = resolve([Some(&body), None], &contact).unwrap();
        assert_eq!(out.after[0].unwrap().base, Base::Flies);
        obeys([Some(&body), None], &contact, &out);
        // Nothing but the elastic contact acts: the energy is kept.
        let before = kinetic_j(&body, body.omega, 0.0, 0.0);
        assert!(out.loss_j.abs() <= 1e-14 * before, "{}", out.loss_j);
    }
}

#[test]
fn a_slab_in_flight_takes_the_contact_impulse_alone() {
    let (mut body, contact) = against_a_face(1.0, 0.8, 1.0);
    (body.ground, body.w, body.v) = ([None, None], 0.05, 0.1);
    for (b, c) in [(body, contact), (Turning { w: -0.05, ..body }, contact)] {
        let out = resolve([Some(&b), None], &c).unwrap();
        assert_eq!(out.after[0].unwrap().base, Base::Flies);
        obeys([Some(&b), None], &c, &out);
        let before = kinetic_j(&b, b.omega, b.v, b.w);
        assert!(out.loss_j.abs() <= 1e-14 * before, "{}", out.loss_j);
    }
}

/// Slab A (on its corner of sign sa) swinging right into slab B's left face, B 1.8 m high and
/// 0.4 m wide rocking on its corner of sign sb by theta_b at omega_b; A's top right corner on
/// B's face at 1.2 cos theta_a and some.
fn two_slabs(sa: f64, sb: f64, omega_b: f64, friction: f64, e: f64) -> (Turning, Turning, Contact) {
    let (ta, tb) = (0.04 * sa, 0.03 * sb);
    let a = slab(sa, ta, 0.5, 0.0, friction);
    let point = turned([0.0, 0.0], ta, [0.15 - sa * 0.15, 1.2]);
    let (b, h, m) = (0.2, 0.9, 1440.0);
    // B's left face from its bottom left corner, (-b - sr b, 0) from its pivot (a seated B's
    // the right corner): the point lies lambda up that face.
    let sr = if sb == 0.0 { 1.0 } else { sb };
    let x0 = -b - sr * b;
    let lambda = (point[1] + x0 * tb.sin()) / tb.cos();
    let rel = turned([0.0, 0.0], tb, [x0, lambda]);
    let origin = [point[0] - rel[0], 0.0];
    let body = Turning {
        mass_kg: m,
        inertia_kg_m2: m * (4.0 * b * b + 4.0 * h * h) / 12.0,
        friction,
        pivot: origin,
        centroid: turned(origin, tb, [-sr * b, h]),
        omega: omega_b,
        v: 0.0,
        w: 0.0,
        ground: standing(sb, 2.0 * b),
    };
    let contact = Contact {
        point,
        normal: turned([0.0, 0.0], tb, [-1.0, 0.0]),
        restitution: e,
    };
    (a, body, contact)
}

#[test]
fn two_slabs_swinging_back_into_each_other_keep_their_energy_when_elastic() {
    // A on its left corner swinging right, B on its right corner swinging left.
    let (a, b, c) = two_slabs(-1.0, 1.0, -0.3, 10.0, 1.0);
    let out = resolve([Some(&a), Some(&b)], &c).unwrap();
    let (xa, xb) = (out.after[0].unwrap(), out.after[1].unwrap());
    for x in [xa, xb] {
        assert!(matches!(x.base, Base::Pivot { slips: false, .. }));
    }
    let before = kinetic_j(&a, a.omega, 0.0, 0.0) + kinetic_j(&b, b.omega, 0.0, 0.0);
    assert!(out.loss_j.abs() <= 1e-14 * before, "{}", out.loss_j);
    assert!(xa.omega < 0.0 && xb.omega > 0.0, "both turn back");
    obeys([Some(&a), Some(&b)], &c, &out);
    let (a, b, c) = two_slabs(-1.0, 1.0, -0.3, 10.0, 0.3);
    let out = resolve([Some(&a), Some(&b)], &c).unwrap();
    assert!(out.loss_j > 0.0);
    obeys([Some(&a), Some(&b)], &c, &out);
}

#[test]
fn two_slabs_obey_the_law_whatever_their_bases_do() {
    // Every pair of pivots, B seated too, and three frictions: each outcome, sticking,
    // slipping, lifting or seated, obeys Newton's law, momentum and Coulomb.
    let mut laws = std::collections::BTreeSet::new();
    for (sa, sb) in [
        (-1.0, 1.0),
        (1.0, -1.0),
        (1.0, 1.0),
        (-1.0, -1.0),
        (-1.0, 0.0),
        (1.0, 0.0),
    ] {
        for friction in [0.3, 0.8, 10.0] {
            let omega_b = if sb == 0.0 { 0.0 } else { -0.3 };
            let (a, b, c) = two_slabs(sa, sb, omega_b, friction, 1.0);
            let out = resolve([Some(&a), Some(&b)], &c).unwrap();
            obeys([Some(&a), Some(&b)], &c, &out);
            for x in out.after.iter().flatten() {
                laws.insert(match x.base {
                    Base::Pivot { slips: false, .. } => "sticks",
                    Base::Pivot { slips: true, .. } => "slips",
                    Base::Seated { .. } => "seated",
                    Base::Flies => "flies",
                });
            }
        }
    }
    // The cases reach every law on one corner and off the ground.
    for law in ["sticks", "slips", "flies"] {
        assert!(laws.contains(law), "{laws:?}");
    }
}

#[test]
fn a_seated_slab_struck_above_its_centroid_turns_on_its_far_corner() {
    // B, 1.8 m high, seated, struck at 1.2 m from the left: it turns on its right corner, and
    // with both bases holding and the contact elastic the energy is kept.
    let (a, b, c) = two_slabs(-1.0, 0.0, 0.0, 10.0, 1.0);
    let out = resolve([Some(&a), Some(&b)], &c).unwrap();
    let xb = out.after[1].unwrap();
    assert_eq!(
        xb.base,
        Base::Pivot {
            corner: Corner::Right,
            slips: false
        }
    );
    assert!(xb.omega > 0.0, "it turns clockwise, onto its right corner");
    let before = kinetic_j(&a, a.omega, 0.0, 0.0);
    assert!(out.loss_j.abs() <= 1e-14 * before, "{}", out.loss_j);
    obeys([Some(&a), Some(&b)], &c, &out);
}

#[test]
fn blocks_that_do_not_approach_are_not_an_impact() {
    let (mut body, contact) = against_a_face(-1.0, 10.0, 1.0);
    for omega in [-0.4, 0.0] {
        body.omega = omega;
        assert_eq!(
            resolve([Some(&body), None], &contact),
            Err(Refusal::Grazing)
        );
    }
}

/// The slab rocking on its right corner comes down onto its left one (theta = 0, theta' =
/// -0.6 rad/s), both corners on the ground for the law, while its top left corner stays on a
/// fixed face whose normal is perpendicular to that corner's velocity: the normal (0.3, -1.2)
/// scaled by `into`, the face on the side of the corner's motion (-1) or behind it (1).
/// Returns the slab, the contact and the landing's outcome, after which the slab turns on its
/// left corner, which sticks.
fn landing_against(into: f64) -> (Turning, Contact, Outcome) {
    let mut body = slab(1.0, 0.0, -0.6, 0.0, 10.0);
    body.ground = standing(0.0, 0.3);
    let len = 0.3f64.hypot(1.2);
    let contact = Contact {
        point: [-0.3, 1.2],
        normal: [-into * 0.3 / len, into * 1.2 / len],
        restitution: 0.0,
    };
    let out = resolve_landing([Some(&body), None], &contact).unwrap();
    assert_eq!(
        out.after[0].unwrap().base,
        Base::Pivot {
            corner: Corner::Left,
            slips: false
        }
    );
    (body, contact, out)
}

#[test]
fn a_landing_that_turns_the_slab_off_a_face_is_housners_and_opens_the_contact() {
    let (body, _, out) = landing_against(1.0);
    let a = out.after[0].unwrap();
    let r = 1.0 - 1.5 * 0.25f64.atan().sin().powi(2);
    assert_relative_eq!(a.omega, r * body.omega, epsilon = 1e-15);
    assert_eq!((a.v, out.impulse_n_s), (0.0, 0.0));
    assert_eq!(out.normal_m_s.0, 0.0);
    // Turning on its left corner, the corner above it moves off the face.
    assert!(out.normal_m_s.1 > 0.1, "{:?}", out.normal_m_s);
    let before = kinetic_j(&body, body.omega, 0.0, 0.0);
    assert_relative_eq!(out.loss_j, (1.0 - r * r) * before, epsilon = 1e-14 * before);
}

/// Turning on its left corner would drive the top left corner into the face, whose normal has
/// a component along that corner's velocity about the left corner (1.2 theta', 0): the
/// contact holds only where theta' is zero, so the slab stops on its left corner, all its
/// kinetic energy lost (seated, in effect: both corners on the ground would give the same
/// velocities, but the impulses' split between three contacts that all hold is not
/// determined, so the law returns the one that is). The impulses the outcome implies (the
/// contact's along the normal, the ground's from momentum, at the left corner) press, and
/// friction holds the base.
#[test]
fn a_landing_held_by_a_face_stops_the_slab_with_every_contact_pressing() {
    let (body, contact, out) = landing_against(-1.0);
    let a = out.after[0].unwrap();
    let speed = body.omega.abs() * reach(&body);
    assert_eq!(a.v, 0.0);
    assert!(
        a.omega.abs() * reach(&body) <= 1e-14 * speed && a.lift_v.abs() <= 1e-14 * speed,
        "{a:?}"
    );
    assert!(
        out.normal_m_s.1.abs() <= 1e-15 * speed,
        "{:?}",
        out.normal_m_s
    );
    let before = kinetic_j(&body, body.omega, 0.0, 0.0);
    assert_relative_eq!(out.loss_j, before, epsilon = 1e-14 * before);
    // The ground's impulse is what the momentum needs besides the contact's; its moment about
    // the left corner is zero (it acts there), so the angular momentum about that corner
    // changes by the contact's moment alone.
    let p = out.impulse_n_s;
    assert!(p > 0.0, "{p}");
    let pc = [p * contact.normal[0], p * contact.normal[1]];
    let g0 = point_velocity(&body, body.centroid, body.omega, 0.0, 0.0);
    let ground = [-body.mass_kg * g0[0] - pc[0], -body.mass_kg * g0[1] - pc[1]];
    let left = [-0.3, 0.0];
    let dh = momentum_about(&body, left, a.omega, a.v, a.lift_v)
        - momentum_about(&body, left, body.omega, 0.0, 0.0);
    let arm = [contact.point[0] - left[0], contact.point[1] - left[1]];
    let contact_moment = arm[0] * pc[1] - arm[1] * pc[0];
    let tol = 1e-14 * body.mass_kg * speed;
    assert!(
        (dh - contact_moment).abs() <= 2.0 * reach(&body) * tol,
        "{dh} {contact_moment}"
    );
    assert!(ground[1] > 0.0, "{ground:?}");
    assert!(ground[0].abs() <= body.friction * ground[1], "{ground:?}");
}

/// Slab B of [`two_slabs`] (on its right corner, leaning right and swinging right) strikes a
/// fixed face with its top right corner while slab A's corner stays on its left face, A turning
/// with it (A's theta' set so that the contact neither approaches nor leaves). B's rebound
/// drives its face into A's corner, so both contacts take impulses, at once: whatever the
/// friction, the blow obeys Newton's law with e, the
/// contact that stayed is closed with an impulse that presses or open without one, and each
/// slab's momentum and angular momentum about its pivot change by the impulses on it alone, its
/// pivot's pressing and within Coulomb's cone (at its edge where it slips), or zero where the
/// pivot leaves the ground.
#[test]
fn a_blow_on_a_slab_another_leans_on_obeys_both_contacts_laws_at_once() {
    for friction in [0.3, 0.8, 10.0] {
        let (mut a, b, held) = two_slabs(-1.0, 1.0, 0.4, friction, 0.0);
        let (still, ..) = approach([Some(&Turning { omega: 0.0, ..a }), Some(&b)], &held);
        a.omega = -still / arms(&a, &held)[1];
        assert!(approach([Some(&a), Some(&b)], &held).0.abs() < 1e-15);
        let top = turned(b.pivot, 0.03, [0.0, 1.8]);
        let blow = Contact {
            point: top,
            normal: [-1.0, 0.0],
            restitution: 0.5,
        };
        let links = [
            Link {
                sides: [Some(1), None],
                contact: blow,
            },
            Link {
                sides: [Some(0), Some(1)],
                contact: held,
            },
        ];
        let bodies = [a, b];
        let all = resolve_all(&bodies, &links).unwrap();
        let (before, after) = all.normal_m_s[0];
        assert!(before < -0.1, "{before}");
        assert_relative_eq!(after, -0.5 * before, epsilon = 1e-14 * before.abs());
        assert!(all.impulse_n_s[0] > 0.0);
        // Rebounding, B drives its face into A's corner: both contacts take an impulse.
        assert!(all.impulse_n_s[1] > 0.0, "{friction}: {all:?}");
        let (held_before, held_after) = all.normal_m_s[1];
        assert!(held_before.abs() < 1e-15);
        if all.impulse_n_s[1] > 0.0 {
            assert!(held_after.abs() <= 1e-14, "{held_after}");
        } else {
            assert!(held_after >= 0.0, "{held_after}");
        }
        for (j, body) in bodies.iter().enumerate() {
            let x = all.after[j];
            // The contacts' impulses on this body, at their points.
            let mut p = [0.0; 2];
            let mut moment = 0.0;
            for (l, link) in links.iter().enumerate() {
                for k in (0..2).filter(|&k| link.sides[k] == Some(j)) {
                    let s = [1.0, -1.0][k] * all.impulse_n_s[l];
                    let f = [s * link.contact.normal[0], s * link.contact.normal[1]];
                    let d = [
                        link.contact.point[0] - body.pivot[0],
                        link.contact.point[1] - body.pivot[1],
                    ];
                    p = [p[0] + f[0], p[1] + f[1]];
                    moment += d[0] * f[1] - d[1] * f[0];
                }
            }
            let dh = momentum_about(body, body.pivot, x.omega, x.v, x.lift_v)
                - momentum_about(body, body.pivot, body.omega, body.v, body.w);
            let (g1, g0) = (
                point_velocity(body, body.centroid, x.omega, x.v, x.lift_v),
                point_velocity(body, body.centroid, body.omega, body.v, body.w),
            );
            let pt = body.mass_kg * (g1[0] - g0[0]) - p[0];
            let pn = body.mass_kg * (g1[1] - g0[1]) - p[1];
            let speeds =
                body.v.abs() + x.v.abs() + (body.omega.abs() + x.omega.abs()) * reach(body);
            let tol = 1e-13 * body.mass_kg * speeds;
            assert!(
                (dh - moment).abs() <= 2.0 * reach(body) * tol,
                "{dh} {moment}"
            );
            let slips = match x.base {
                Base::Pivot { corner, slips } => {
                    assert_eq!(corner, body.ground[0].unwrap().0);
                    slips
                }
                Base::Flies => {
                    // Off the ground: no impulse there, and its pivot rises.
                    assert!(pt.abs() <= tol && pn.abs() <= tol, "{pt} {pn}");
                    assert!(x.lift_v >= 0.0, "{x:?}");
                    continue;
                }
                Base::Seated { .. } => panic!("{friction}: {x:?}"),
            };
            assert!(pn > 0.0, "{pn}");
            if slips {
                assert_relative_eq!(pt, -body.friction * pn * x.v.signum(), epsilon = tol);
            } else {
                assert_eq!(x.v, 0.0);
                assert!(pt.abs() <= body.friction * pn + tol, "{pt} {pn}");
            }
        }
    }
}

/// The closing of two contacts at once: slab A in flight touches slab B (rocking, its pivot
/// stuck: only theta' free) at two points of B's face, each approaching at a rate of
/// round-off. After the changes both normal velocities are zero, the velocities the modes
/// hold are untouched, and the changes are the least in their norm: weighted by the mass and
/// the inertia they are a combination of the contacts' normal rows (the condition of a
/// least-norm solution), the weights read back from A's v and theta' and checked
/// on the others.
#[test]
fn closing_two_contacts_changes_the_free_velocities_by_the_least() {
    let (a, b, c) = two_slabs(-1.0, 1.0, -0.3, 0.6, 0.0);
    let a = Turning {
        ground: [None, None],
        w: 0.02,
        ..a
    };
    // A second point on B's face, 0.3 m down it from the first.
    let down = turned([0.0, 0.0], 0.03, [0.0, -0.3]);
    let lower = Contact {
        point: [c.point[0] + down[0], c.point[1] + down[1]],
        ..c
    };
    // Velocities that leave both contacts approaching by about 1e-12 m/s.
    let rates = |a: &Turning, b: &Turning| [c, lower].map(|c| approach([Some(a), Some(b)], &c).0);
    let solve = |a: &Turning, b: &Turning| {
        let [r0, r1] = rates(a, b);
        let (d, e) = (-1e-12 - r0, -2e-12 - r1);
        // Move A's v and theta' so that the two rates become -1e-12 and -2e-12 m/s (v and w
        // enter both alike: the points share a face).
        let (p, q) = (arms(a, &c), arms(a, &lower));
        let det = p[0] * q[1] - p[1] * q[0];
        Turning {
            v: a.v + (d * q[1] - e * p[1]) / det,
            omega: a.omega + (p[0] * e - q[0] * d) / det,
            ..*a
        }
    };
    let a = solve(&a, &b);
    let before = rates(&a, &b);
    assert!((before[0] + 1e-12).abs() < 1e-15 && (before[1] + 2e-12).abs() < 1e-15);
    let links = [c, lower].map(|contact| Link {
        sides: [Some(0), Some(1)],
        contact,
    });
    let free = [[true; 3], [false, true, false]];
    let change = closing_all(&[a, b], &links, &free).expect("two contacts closed");
    assert_eq!((change[1][0], change[1][2]), (0.0, 0.0));
    let moved = |t: &Turning, d: [f64; 3]| Turning {
        v: t.v + d[0],
        omega: t.omega + d[1],
        w: t.w + d[2],
        ..*t
    };
    let (a1, b1) = (moved(&a, change[0]), moved(&b, change[1]));
    // Zero to the round-off of evaluating a rate from velocities of this size.
    for c in [c, lower] {
        let (rate, speed, _) = approach([Some(&a1), Some(&b1)], &c);
        assert!(rate.abs() <= 2.0 * f64::EPSILON * speed, "{rate} {speed}");
    }
    // M change = J^T lambda over the free velocities (A's v, theta', w and B's theta').
    let weighted = [
        a.mass_kg * change[0][0],
        a.inertia_kg_m2 * change[0][1],
        a.mass_kg * change[0][2],
        b.inertia_kg_m2 * change[1][1],
    ];
    let row = |c: &Contact| {
        let (p, q) = (arms(&a, c), arms(&b, c));
        [p[0], p[1], p[2], -q[1]]
    };
    let (j0, j1) = (row(&c), row(&lower));
    // lambda from A's v and theta', then A's w and B's theta' must agree.
    let det = j0[0] * j1[1] - j0[1] * j1[0];
    let l0 = (weighted[0] * j1[1] - weighted[1] * j1[0]) / det;
    let l1 = (j0[0] * weighted[1] - j0[1] * weighted[0]) / det;
    let scale = weighted.iter().map(|x| x.abs()).fold(0.0, f64::max);
    assert!(scale > 0.0);
    for k in [2, 3] {
        let r = weighted[k] - (l0 * j0[k] + l1 * j1[k]);
        assert!(r.abs() <= 1e-12 * scale, "{k}: {r} of {scale}");
    }
}
