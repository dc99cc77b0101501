//! Columns that stand apart from each other and from fixed blocks: followed as if alone while
//! they stay apart, and from the instant a corner reaches the other's face through the impact,
//! or stopped there.

use super::{columns, Equations, Rocking};
use crate::integrate::{Integrator, Scenario, Settings};
use crate::model::Model;
use crate::motion::{Motion, Sine};
use crate::response::{CollapseCause, EventKind, EventRecord, Response, Warning};

/// A slab 0.3 m wide and 1.2 m high (friction 0.8: it rocks, it does not slide) and `rest`,
/// the blocks of its row after it.
fn wall(rest: &str) -> Model {
    wall_with(rest, 1.0)
}

/// The same with a coefficient of restitution.
fn wall_with(rest: &str, restitution: f64) -> Model {
    Model::from_ron_str(&format!(
        "(version: 1, name: \"slab\", thickness_m: 0.5, density_kg_m3: 2500, friction: 0.8,
          restitution: {restitution:?},
          rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"){rest}])])"
    ))
    .unwrap()
}

/// A slab 0.3 x 1.2 m beside a block 1.0 x 1.2 m, 0.05 m apart, no restitution: a scene of the
/// scans (docs/rocking/scans).
fn slab_beside_block(friction: f64) -> Model {
    Model::from_ron_str(&format!(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: {friction:?},
          restitution: 0.0, rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"),
          (width_m: 1.0, height_m: 1.2, gap_m: 0.05, name: \"W\")])])"
    ))
    .unwrap()
}

/// A sine of the scans: 4 s at `frequency_hz`.
fn sine_of(amplitude_g: f64, frequency_hz: f64) -> Motion {
    Motion::Sine(Sine {
        amplitude_m_s2: amplitude_g * 9.81,
        frequency_hz,
        phase_rad: 0.0,
        duration_s: 4.0,
    })
}

fn sine(amplitude_g: f64, phase_deg: f64) -> Motion {
    Motion::Sine(Sine {
        amplitude_m_s2: amplitude_g * 9.81,
        frequency_hz: 1.0,
        phase_rad: phase_deg.to_radians(),
        duration_s: 5.0,
    })
}

pub(super) fn run(model: &Model, motion: &Motion, duration_s: f64, initial: f64) -> Response {
    let settings = Settings {
        output_dt_s: Some(1e-2),
        log_events: true,
        ..Settings::summary_only(duration_s)
    };
    Rocking {
        equations: Equations::Exact,
        initial_rotation_rad: initial,
    }
    .run(&Scenario {
        wall: model.wall(),
        topology: model.topology(),
        motion,
        settings: &settings,
    })
    .unwrap()
}

/// Block k's rows: u, v, theta, theta', w.
pub(super) fn rows(r: &Response, k: usize) -> Vec<[f64; 6]> {
    let h = r.history.as_ref().unwrap();
    (0..h.time_s.len())
        .map(|i| {
            [
                h.time_s[i],
                h.displacement_m[i][k],
                h.velocity_m_s[i][k],
                h.rotation_rad[i][k],
                h.angular_velocity_rad_s[i][k],
                h.lift_m[i][k],
            ]
        })
        .collect()
}

/// Where two blocks first meet, and which: the run's first impact between blocks, or its stop
/// where they meet.
fn met(r: &Response) -> Option<(f64, Vec<String>)> {
    r.events
        .iter()
        .find(|e| matches!(e.kind, EventKind::BlocksMeet | EventKind::BlocksImpact))
        .map(|e| (e.time_s, e.blocks.clone()))
}

/// The run's impacts between blocks.
fn impacts(r: &Response) -> Vec<&crate::response::EventRecord> {
    r.events
        .iter()
        .filter(|e| e.kind == EventKind::BlocksImpact)
        .collect()
}

/// The run's events after t, but uplifts (a body leaving its seat, logged for each).
fn events_after(r: &Response, t: f64) -> Vec<&crate::response::EventRecord> {
    (r.events.iter())
        .filter(|e| e.time_s > t && e.kind != EventKind::Uplift)
        .collect()
}

/// Block k's first row at t.
fn row_at(r: &Response, k: usize, t: f64) -> [f64; 6] {
    *rows(r, k)
        .iter()
        .find(|x| x[0] == t)
        .expect("a row at the event")
}

/// The distance (m) of the left corner at height y of a slab T (its left corner at x_t, its
/// width w_t, turned by theta_t) from the right face of the 0.3 m slab S at x = 0 turned by
/// theta_s, each rocking on the corner of its rotation's sign, which stays where it stood.
fn from_face(theta_s: f64, (theta_t, x_t, w_t): (f64, f64, f64), y: f64) -> f64 {
    let turn = |theta: f64, x: f64, y: f64| {
        let (sin, cos) = theta.sin_cos();
        [x * cos + y * sin, -x * sin + y * cos]
    };
    let (ps, fs) = if theta_s > 0.0 {
        (0.3, 0.0)
    } else {
        (0.0, 0.3)
    };
    let (pt, ct) = if theta_t > 0.0 {
        (x_t + w_t, -w_t)
    } else {
        (x_t, 0.0)
    };
    let (c, f, n) = (
        turn(theta_t, ct, y),
        turn(theta_s, fs, 0.0),
        turn(theta_s, 1.0, 0.0),
    );
    (pt + c[0] - ps - f[0]) * n[0] + (c[1] - f[1]) * n[1]
}

/// Two slabs 2 m apart under sines that rock them a little, or overturn them both the same
/// way, one falling away from the other (its face that kept the pair apart turns to face up:
/// the pair keeps apart by another edge from then on), the other towards it, short of it:
/// each moves as the slab alone does, every row equal to the bit; nothing meets.
#[test]
fn columns_standing_apart_move_each_as_alone_to_the_bit() {
    let apart = wall(", (width_m: 0.3, gap_m: 2.0, name: \"T\")");
    assert_eq!(columns(apart.wall(), apart.topology()).unwrap().len(), 2);
    let alone = wall("");
    for (amplitude_g, phase_deg, fall) in [(0.3, 0.0, -1.0), (0.3, 180.0, 1.0), (0.26, 0.0, 0.0)] {
        let motion = sine(amplitude_g, phase_deg);
        let (two, one) = (
            run(&apart, &motion, 5.0, 0.0),
            run(&alone, &motion, 5.0, 0.0),
        );
        assert_eq!(met(&two), None);
        if fall != 0.0 {
            let theta = rows(&two, 0).last().unwrap()[3];
            assert_eq!(theta, fall * std::f64::consts::FRAC_PI_2, "{amplitude_g} g");
        }
        assert!(two.summary.blocks[0].max_abs_rotation_rad > 1e-4);
        let alone = rows(&one, 0);
        for k in 0..2 {
            assert_eq!(rows(&two, k), alone, "{amplitude_g} g, block {k}");
        }
    }
}

/// The slab 2 cm from an abutment on its right rocks towards it: it meets the abutment where
/// its top right corner reaches the face, h sin theta = 0.02 m (its pivot sticks: its base's
/// middle has moved by b (1 - cos theta)), where the slab alone, run to that instant, stands.
/// Without restitution the corner stays on the face, and the blow lifts the slab's pivot off
/// the ground: it flies with its corner on the face and lands, the landing and the contact
/// taking their impulses at once (plastic both), which leaves its pivot on the ground and its
/// corner on the face. It turns away from the face, strikes it again, and its last blow throws
/// it up along the face until its corner reaches the face's top, (0.32, 1.2) m to the bit,
/// where it slides off: they part. The abutment's corner then strikes the slab's face, and
/// the abutment's face comes down flat on the slab's: both ends of their contact stay on it, the
/// slab lying on the abutment's face, and the run stops there, saying so. The energy balance
/// closes, and Moreau-Jean, which resolves the same contacts at once, converges on the
/// rotation and the displacement through the whole run.
#[test]
fn a_slab_meets_an_abutment_where_its_corner_reaches_the_face() {
    let niche = wall_with(
        ", (width_m: 0.5, gap_m: 0.02, fixed: true, name: \"A\")",
        0.0,
    );
    let motion = sine(0.3, 0.0);
    let r = run(&niche, &motion, 5.0, 0.0);
    let (t, blocks) = met(&r).expect("meets");
    assert_eq!(blocks, ["S", "A"]);
    let blows = impacts(&r);
    assert_eq!(blows[0].time_s, t);
    let what = |e: &crate::response::EventRecord| e.mode.clone().unwrap_or_default();
    assert!(
        what(blows[0]).contains("leaving the ground at"),
        "{blows:?}"
    );
    // Positions do not jump at an impact: the row at its instant is where the slab met A.
    let at = rows(&r, 0).into_iter().find(|x| x[0] == t).unwrap();
    let (u, theta) = (at[1], at[3]);
    assert!((1.2 * theta.sin() - 0.02).abs() < 1e-16, "{theta}");
    assert!((u - 0.15 * (1.0 - theta.cos())).abs() < 1e-16, "{u}");
    // Alone, to that instant (reached from the last step's start by the same step, to
    // round-off: t0 + (t - t0) need not be t).
    let alone = *rows(&run(&wall(""), &motion, t, 0.0), 0).last().unwrap();
    for k in [0, 1, 3] {
        assert!(
            (alone[k] - at[k]).abs() <= 1e-15 * (1.0 + at[k].abs()),
            "{alone:?} {at:?}"
        );
    }
    // One flight along the face, ended by a landing that keeps the corner on the face and
    // the pivot on the ground.
    let landing = (r.events.iter())
        .find(|e| e.time_s > t && e.kind == EventKind::RockingImpact)
        .unwrap();
    assert!(
        what(landing).contains(
            "lands from free flight on its right corner in contact with A, \
             both contacts plastic at once"
        ),
        "{landing:?}"
    );
    assert_eq!(blows[1].time_s, landing.time_s);
    assert!(
        what(blows[1]).contains("S's corner stays on A's face, its impulse"),
        "{:?}",
        blows[1]
    );
    assert!(
        !what(blows[1]).contains("leaving the ground"),
        "{:?}",
        blows[1]
    );
    let stop = r.summary.duration_s;
    assert!(r.events.iter().any(|e| e.time_s > landing.time_s
        && e.time_s < stop
        && e.mode
            .as_deref()
            .unwrap_or_default()
            .contains("S turns away from A's face")));
    let off = (r.events.iter())
        .find(|e| {
            e.kind == EventKind::Separation
                && what(e) == "S's corner slides off an end of A's face: the two part"
        })
        .expect("the corner slides off the face's top");
    // The top right corner, from the middle of the slab's base (lifted by w, moved by u).
    let [_, u, _, theta, _, w] = row_at(&r, 0, off.time_s);
    let (sin, cos) = theta.sin_cos();
    assert!(
        (0.15 + u + 0.15 * cos + 1.2 * sin - 0.32).abs() <= 1e-15,
        "{u} {theta}"
    );
    assert!(
        (w - 0.15 * sin + 1.2 * cos - 1.2).abs() <= 1e-15,
        "{w} {theta}"
    );
    let after = events_after(&r, off.time_s);
    assert!(
        what(after[0]).starts_with("A's corner strikes S's face"),
        "{after:?}"
    );
    assert!(stop > off.time_s && stop < 5.0, "{stop}");
    assert!(r.summary.warnings.iter().any(|w| matches!(
        w,
        Warning::BlocksMeet { first, second, time_s, why }
            if first == "S" && second == "A" && *time_s == stop
                && why.contains("A's face comes down flat on S's, and both ends of their")
                && why.ends_with(
                    "and S leaves the ground through it: a face that moves along a face it lies \
                     on is not followed"
                )
    )), "{:?}", r.summary.warnings);
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-14 * e.input_j, "{e:?}");
    for col in [1, 3] {
        converges_in(&niche, &motion, &r, t, 0, col);
    }
}

/// A slender slab (0.2 by 2 m) 5 cm from a low fixed block (0.5 by 0.3 m) on its left leans
/// towards it: its top left corner passes over the block's face line (the pair then keeps
/// apart by the slab's own face), and the block's top right corner meets the slab's left face,
/// at tan theta = 0.05 / 0.3.
#[test]
fn a_slab_leaning_over_a_low_block_meets_its_corner() {
    let model = Model::from_ron_str(
        "(version: 1, name: \"over\", thickness_m: 0.5, density_kg_m3: 2500, friction: 0.8,
          rows: [(height_m: 2.0, blocks: [(width_m: 0.5, height_m: 0.3, fixed: true, name: \"B\"),
                                          (width_m: 0.2, gap_m: 0.05, name: \"A\")])])",
    )
    .unwrap();
    let r = run(&model, &sine(0.15, 180.0), 5.0, 0.0);
    let (t, blocks) = met(&r).expect("meets");
    assert_eq!(blocks, ["B", "A"]);
    let last = row_at(&r, 1, t);
    let (u, phi) = (last[1], -last[3]);
    assert!(phi > 0.0, "leans left: {phi}");
    assert!((phi - (0.05f64 / 0.3).atan()).abs() < 1e-15, "{phi}");
    // Its pivot, the bottom left corner at x = 0.55 at rest, from its base's middle.
    let pivot = 0.65 + u - 0.1 * phi.cos();
    let (sin, cos) = phi.sin_cos();
    let distance = (pivot - 0.5) * cos - 0.3 * sin;
    assert!(distance.abs() < 1e-15, "{distance}");
    assert!(
        pivot - 2.0 * sin < 0.5,
        "its top corner passed the block's face line"
    );
}

/// A column of two drums (0.5 by 1.5 m) rocking as one body, 5 cm from a fixed wall higher than
/// it: the upper drum's top corner, carried by the body, meets the wall's face, at 3 sin theta =
/// 0.05 m.
#[test]
fn a_column_of_two_drums_meets_a_wall_with_its_upper_drum() {
    let model = Model::from_ron_str(
        "(version: 1, name: \"drums\", thickness_m: 0.5, density_kg_m3: 2600, friction: 0.7,
          rows: [(height_m: 1.5, blocks: [(width_m: 0.5, name: \"D1\"),
                    (width_m: 0.5, height_m: 3.5, gap_m: 0.05, fixed: true, name: \"W\")]),
                 (height_m: 1.5, blocks: [(width_m: 0.5, name: \"D2\")])])",
    )
    .unwrap();
    let r = run(&model, &sine(0.3, 0.0), 5.0, 0.0);
    let (_, blocks) = met(&r).expect("meets");
    assert_eq!(blocks, ["W", "D2"]);
    let theta = rows(&r, 2).last().unwrap()[3];
    assert!((3.0 * theta.sin() - 0.05).abs() < 1e-15, "{theta}");
    // The joint between the drums would pass the impulse, which the model does not check.
    let why = r.summary.warnings.iter().find_map(|w| match w {
        Warning::BlocksMeet { why, .. } => Some(why.clone()),
        _ => None,
    });
    assert!(why.is_some_and(|w| w.contains("holds joints")));
}

/// Blocks that touch a column beside it are not columns standing apart, but for two blocks
/// each alone in its column face on face (`abutting`): a block touching two, or touching one
/// that carries another, is refused by name; a release that puts the slab into the abutment is
/// refused by name, as is one that starts it touching.
#[test]
fn touching_blocks_are_refused_by_name() {
    let face_on_face = wall(", (width_m: 1.2, name: \"W\")");
    assert_eq!(
        columns(face_on_face.wall(), face_on_face.topology())
            .unwrap()
            .len(),
        2
    );
    let three = wall(", (width_m: 1.2, name: \"W\"), (width_m: 0.3, name: \"T\")");
    let e = columns(three.wall(), three.topology()).unwrap_err();
    assert!(e.to_string().contains("S touches W beside it"), "{e}");
    let niche = wall(", (width_m: 0.5, gap_m: 0.02, fixed: true, name: \"A\")");
    let settings = Settings::summary_only(1.0);
    let sc = Scenario {
        wall: niche.wall(),
        topology: niche.topology(),
        motion: &sine(0.1, 0.0),
        settings: &settings,
    };
    for theta in [0.05, (0.02f64 / 1.2).asin()] {
        let e = Rocking {
            equations: Equations::Exact,
            initial_rotation_rad: theta,
        }
        .run(&sc)
        .unwrap_err();
        assert!(e.to_string().contains("S and A touch"), "{theta}: {e}");
    }
}

/// The slab beside the abutment with elastic faces (e = 1, the default): it strikes the
/// abutment at the instant it met it above, swinging out with its centroid rising, which a
/// frictionless face and a base that only pushes cannot turn back: its pivot leaves the ground
/// (`collision.rs`), and it flies, lands and rocks on. Up to the impact the run is the one
/// without restitution, to the bit; the energy balance closes through it; and from it, time
/// stepping with every block's rotation (Moreau-Jean) converges on the exact rotation as its
/// step falls.
#[test]
fn a_slab_that_strikes_an_abutment_flies_off_as_time_stepping_converges_to() {
    let gap = ", (width_m: 0.5, gap_m: 0.02, fixed: true, name: \"A\")";
    let motion = sine(0.3, 0.0);
    let plastic = run(&wall_with(gap, 0.0), &motion, 5.0, 0.0);
    let elastic = wall(gap);
    let r = run(&elastic, &motion, 0.9, 0.0);
    let impact = impacts(&r)[0];
    let first = impacts(&plastic)[0];
    let t = first.time_s;
    assert_eq!(impact.time_s, t);
    assert_eq!(
        impact.angular_velocity_before_rad_s,
        first.angular_velocity_before_rad_s
    );
    let what = impact.mode.as_deref().unwrap_or_default();
    assert!(what.contains("leaves the ground"), "{what}");
    // The joint across which they face each other, not one either block stands on.
    assert_eq!(impact.joint.as_deref(), Some("S|A"));
    assert_eq!(r.summary.duration_s, 0.9);
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-13 * e.input_j, "{e:?}");
    converges(&elastic, &motion, &r, t, 0);
}

/// The slab 0.68 m from an abutment, without restitution, under a 0.6 g sine: it falls past
/// its alpha onto the abutment, its top corner on the face at 1.2 sin theta = 0.68 m, and the
/// impact leaves it at rest there, its pivot stuck (`lean.rs`); the abutment pushes on it until
/// the ground's acceleration turns it away, a_g r_Gy = g r_Gx (the moment of its weight about
/// the pivot balanced by the inertial load's), and it swings back, falls onto the abutment
/// again and rests there, cycle after cycle. Every rest holds the slab still, to the bit; each
/// ends where the push is zero (the closed form's root, to round-off) and nowhere before; the
/// energy balance closes through it all; and Moreau-Jean with every block's rotation converges
/// on the slab's rotation as its step falls.
#[test]
fn a_slab_fallen_onto_an_abutment_rests_on_it_until_the_ground_turns_it_away() {
    let model = wall_with(
        ", (width_m: 0.5, gap_m: 0.68, fixed: true, name: \"A\")",
        0.0,
    );
    let motion = sine(0.6, 180.0);
    let r = run(&model, &motion, 1.7, 0.0);
    let rests: Vec<f64> = impacts(&r)
        .iter()
        .filter(|e| {
            e.mode
                .as_deref()
                .unwrap_or_default()
                .contains("at rest against A")
        })
        .map(|e| e.time_s)
        .collect();
    let parts: Vec<f64> = (r.events.iter())
        .filter(|e| e.kind == EventKind::Separation)
        .map(|e| e.time_s)
        .collect();
    assert_eq!(rests.len(), 2, "{:?}", r.events);
    assert_eq!(parts.len(), 2);
    assert_eq!(r.summary.duration_s, 1.7);
    let (b, h, g) = (0.15, 0.6, 9.81);
    let theta: f64 = (0.68f64 / 1.2).asin();
    let (sin, cos) = theta.sin_cos();
    let (gx, gy) = (-b * cos + h * sin, b * sin + h * cos);
    // The push is a positive multiple of g r_Gx - a_g r_Gy.
    let push = |t: f64| g * gx - motion.accel(t) * gy;
    for (&from, &to) in rests.iter().zip(&parts) {
        assert!(to >= from);
        let still: Vec<[f64; 6]> = rows(&r, 0)
            .into_iter()
            .filter(|x| x[0] >= from && x[0] <= to)
            .collect();
        assert!(!still.is_empty());
        for x in &still {
            assert_eq!(x[3], still[0][3], "{x:?}");
            assert_eq!((x[1], x[2], x[4]), (still[0][1], 0.0, 0.0), "{x:?}");
            assert!(x[0] == to || push(x[0]) > 0.0, "{x:?}");
        }
        assert!(
            (1.2 * still[0][3].sin() - 0.68).abs() < 1e-15,
            "{:?}",
            still[0]
        );
        assert!((still[0][1] - b * (1.0 - still[0][3].cos())).abs() < 1e-15);
        if to > from {
            // The root of the push from the event's time by Newton's method.
            let mut t = to;
            for _ in 0..4 {
                let slope = -gy
                    * 0.6
                    * g
                    * std::f64::consts::TAU
                    * (std::f64::consts::TAU * t + std::f64::consts::PI).cos();
                t -= push(t) / slope;
            }
            assert!((t - to).abs() < 1e-12, "{t} {to}");
        } else {
            assert!(push(from) <= 0.0);
        }
    }
    // The ground takes back more than it put in (the slab ends lower than it stood).
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
    converges(&model, &motion, &r, rests[0], 0);
}

/// The same slab on a base of friction 0.3 (walls/rocking/slab-on-abutment.ron), under 0.3 g:
/// it falls onto the abutment and rests against it, the abutment's push P and the ground's
/// acceleration loading its pivot with m a_g + P horizontally against m g vertically; where that
/// reaches Coulomb's cone (closed form) the pivot slips, and the slab slides down the face it
/// touches, its corner on it, as a ladder does: its one degree of freedom theta, the pivot
/// at X - H sin theta. Against that ladder's own equations (Newton-Euler about the centroid, the
/// push, the pivot's normal force and its friction mu N against the slip as unknowns,
/// integrated by Runge-Kutta), the slab's rotation at every row of the slide and the instant its
/// slip stops (where it rests against the abutment again, still to the bit until it slips once
/// more) agree to round-off; the corner stays on the face; the energy balance closes with the
/// pivot's friction in it; and Moreau-Jean converges on the rotation.
#[test]
fn a_slab_resting_on_an_abutment_slides_down_it_where_its_pivot_slips() {
    let model = Model::from_file("walls/rocking/slab-on-abutment.ron").unwrap();
    let motion = sine(0.3, 180.0);
    let r = run(&model, &motion, 5.0, 0.0);
    let rest = impacts(&r)[0];
    assert!(rest
        .mode
        .as_deref()
        .unwrap_or_default()
        .contains("at rest against A"));
    let after = events_after(&r, rest.time_s);
    let [slip, stick, again, ..] = after[..] else {
        panic!("{after:?}")
    };
    assert_eq!(
        (slip.kind, stick.kind, again.kind),
        (
            EventKind::PivotSlip,
            EventKind::PivotStick,
            EventKind::PivotSlip
        )
    );
    assert!(slip
        .mode
        .as_deref()
        .unwrap_or_default()
        .contains("sliding along A's face"));
    let (b, h, g, mu) = (0.15, 0.6, 9.81, 0.3);
    let (sin, cos) = (0.68f64 / 1.2).asin().sin_cos();
    let (gx, gy) = (-b * cos + h * sin, b * sin + h * cos);
    // The friction the pivot needs at rest, per unit mass, less what it holds.
    let excess = |t: f64| {
        let a = motion.accel(t);
        (a + (g * gx - a * gy) / (1.2 * cos)).abs() - mu * g
    };
    assert!(
        excess(slip.time_s).abs() < 1e-12 * g,
        "{}",
        excess(slip.time_s)
    );
    let s = rows(&r, 0);
    let resting = |from: f64, to: f64| s.iter().filter(move |x| x[0] >= from && x[0] <= to);
    assert!(resting(rest.time_s, slip.time_s).count() > 10);
    assert!(resting(rest.time_s, slip.time_s).all(|x| x[0] == slip.time_s || excess(x[0]) < 0.0));
    let still = resting(stick.time_s, again.time_s).collect::<Vec<_>>();
    assert!(still.len() > 10 && still.iter().all(|x| x[3] == still[0][3] && x[4] == 0.0));
    let abutment = [[0.98, 0.0], [1.48, 0.0], [1.48, 1.2], [0.98, 1.2]];
    for x in resting(rest.time_s, again.time_s) {
        let sep = apart(&block_corners(0.15, (0.3, 1.2), x), &abutment);
        assert!(sep.abs() < 1e-15, "{x:?}: {sep}");
    }
    // The ladder: pivot at (X - H sin theta, 0), X = 0.98 m the face, H = 1.2 m; the centroid
    // at G = pivot + (-b cos + h sin, b sin + h cos); the slip to -x, so friction +mu N.
    let (m, big_h, x_face) = (2500.0 * 0.5 * 0.3 * 1.2, 1.2, 0.98);
    let inertia = m * (0.3f64.powi(2) + 1.2f64.powi(2)) / 12.0;
    let accel = |t: f64, th: f64, w: f64| -> f64 {
        let (sn, cs) = th.sin_cos();
        // G_x = X - H sin + (-b cos + h sin), G_y = b sin + h cos: their first and second
        // derivatives in theta.
        let (gx1, gx2) = (-big_h * cs + b * sn + h * cs, big_h * sn + b * cs - h * sn);
        let (gy1, gy2) = (b * cs - h * sn, -b * sn - h * cs);
        let pivot = [x_face - big_h * sn, 0.0];
        let centroid = [pivot[0] - b * cs + h * sn, b * sn + h * cs];
        let corner = [x_face, big_h * cs];
        let rp = [pivot[0] - centroid[0], pivot[1] - centroid[1]];
        let rc = [corner[0] - centroid[0], corner[1] - centroid[1]];
        // Unknowns theta'', N, P: m G_x'' = mu N - P - m a_g, m G_y'' = N - m g, and
        // I_G theta'' = -(r_P x (mu N, N) + r_C x (-P, 0)) (clockwise positive).
        let a = nalgebra::Matrix3::new(
            m * gx1,
            -mu,
            1.0,
            m * gy1,
            -1.0,
            0.0,
            inertia,
            rp[0] - rp[1] * mu,
            rc[1],
        );
        let rhs = nalgebra::Vector3::new(
            -m * gx2 * w * w - m * motion.accel(t),
            -m * gy2 * w * w - m * g,
            0.0,
        );
        a.lu().solve(&rhs).unwrap()[0]
    };
    // Runge-Kutta from the slip's start (at rest), steps of at most 1e-4 s, to each row of the
    // slide, and on to where theta' (the slip's rate over -H cos theta) returns to zero.
    let step = |(t, th, w): (f64, f64, f64), d: f64| {
        let f = |t: f64, th: f64, w: f64| (w, accel(t, th, w));
        let k1 = f(t, th, w);
        let k2 = f(t + d / 2.0, th + d / 2.0 * k1.0, w + d / 2.0 * k1.1);
        let k3 = f(t + d / 2.0, th + d / 2.0 * k2.0, w + d / 2.0 * k2.1);
        let k4 = f(t + d, th + d * k3.0, w + d * k3.1);
        (
            t + d,
            th + d / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            w + d / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    };
    let start = s.iter().find(|x| x[0] == slip.time_s).unwrap();
    let mut at = (slip.time_s, start[3], 0.0);
    let dt: f64 = 1e-4;
    let mut checked = 0;
    for x in s
        .iter()
        .filter(|x| x[0] > slip.time_s && x[0] < stick.time_s)
    {
        while at.0 < x[0] {
            at = step(at, dt.min(x[0] - at.0));
        }
        // The reference's own round-off: its answers at steps of 1e-4 and 2e-5 s differ by
        // 4e-12 rad.
        assert!((at.1 - x[3]).abs() < 1e-11, "{x:?}: {at:?}");
        checked += 1;
    }
    assert!(checked > 30, "{checked}");
    while step(at, dt).2 > 0.0 {
        at = step(at, dt);
    }
    // The stop within the last step, by secant iterations on the step's length.
    let (mut d0, mut d1) = (0.0, dt);
    for _ in 0..6 {
        let (w0, w1) = (step(at, d0).2, step(at, d1).2);
        if w1 == w0 {
            break;
        }
        (d0, d1) = (d1, d1 - w1 * (d1 - d0) / (w1 - w0));
    }
    let stops = at.0 + d1;
    assert!(
        (stops - stick.time_s).abs() < 1e-10,
        "{stops} {}",
        stick.time_s
    );
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.friction_j > 1.0, "{e:?}");
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
    converges(&model, &motion, &r, slip.time_s, 0);
}

/// The slab released at 0.4 rad towards the abutment 0.68 m away, on still ground, with a
/// coefficient of restitution of 0.5: it falls onto the abutment and bounces, each rebound at
/// half the speed it struck at, each flight (under a nearly constant pull towards the face) half
/// as long as the one before, until what is left of the bounces is round-off: it then rests
/// against the abutment for good, its corner on the face, before the geometric series of the
/// flights ends.
#[test]
fn a_slab_bouncing_on_an_abutment_comes_to_rest_against_it() {
    let model = wall_with(
        ", (width_m: 0.5, gap_m: 0.68, fixed: true, name: \"A\")",
        0.5,
    );
    let motion = Motion::Pulse(crate::motion::Pulse::rest());
    let r = run(&model, &motion, 2.0, 0.4);
    let events = impacts(&r);
    let (rest, bounces) = events.split_last().expect("impacts");
    let what = rest.mode.as_deref().unwrap_or_default();
    assert!(what.contains("at rest against A"), "{what}");
    assert!(bounces.len() > 10, "{}", bounces.len());
    for e in bounces {
        let what = e.mode.as_deref().unwrap_or_default();
        let (before, after) = e
            .angular_velocity_before_rad_s
            .zip(e.angular_velocity_after_rad_s)
            .unwrap();
        assert!(
            (after + 0.5 * before).abs() < 1e-12 * before.abs(),
            "{what}"
        );
    }
    let times: Vec<f64> = bounces.iter().map(|e| e.time_s).collect();
    let flights: Vec<f64> = times.windows(2).map(|w| w[1] - w[0]).collect();
    for w in flights[flights.len() - 5..].windows(2) {
        assert!((w[1] / w[0] - 0.5).abs() < 1e-3, "{flights:?}");
    }
    // The flights after the last bounce add up to the last flight (halved, and halved...);
    // the rest starts within them, where the gap the bounces open is below the tie tolerance
    // (1e-11 of the slab's diagonal).
    let last = times.last().unwrap();
    let end = last + flights.last().unwrap();
    assert!(
        rest.time_s > *last && rest.time_s <= end,
        "{} {end}",
        rest.time_s
    );
    let still: Vec<[f64; 6]> = rows(&r, 0)
        .into_iter()
        .filter(|x| x[0] >= rest.time_s)
        .collect();
    assert!(still.len() > 50);
    for x in &still {
        assert_eq!(x[1..], still[0][1..], "{x:?}");
        assert_eq!(x[4], 0.0);
    }
    assert!(
        (1.2 * still[0][3].sin() - 0.68).abs() < 1e-10,
        "{:?}",
        still[0]
    );
    assert_eq!(r.summary.duration_s, 2.0);
    let e = &r.summary.energy;
    assert_eq!(e.kinetic_j, 0.0);
    let scale = e.initial_j + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
}

/// The largest difference in block k's rotation between the exact run `r` (rows every 1e-2
/// s) and Moreau-Jean with every block's rotation, after t, must fall with the step: at dt =
/// 1e-5 s under a quarter of that at 1e-4 s and 1 % of the largest rotation.
fn converges(model: &Model, motion: &Motion, r: &Response, t: f64, k: usize) {
    converges_in(model, motion, r, t, k, 3);
}

/// The same for column `col` of block k's rows (1: the base's displacement, 3: the rotation).
fn converges_in(model: &Model, motion: &Motion, r: &Response, t: f64, k: usize, col: usize) {
    let exact = rows(r, k);
    let error = |dt: f64| {
        let settings = Settings {
            output_dt_s: Some(1e-2),
            ..Settings::summary_only(r.summary.duration_s)
        };
        let stepped = crate::integrate::baselines::MoreauWall::new(dt)
            .run(&Scenario {
                wall: model.wall(),
                topology: model.topology(),
                motion,
                settings: &settings,
            })
            .unwrap();
        let h = stepped.history.unwrap();
        exact
            .iter()
            .filter(|x| x[0] > t)
            .filter_map(|x| {
                let i = h.time_s.iter().position(|&s| (s - x[0]).abs() < 1e-9)?;
                let stepped = match col {
                    1 => h.displacement_m[i][k],
                    _ => h.rotation_rad[i][k],
                };
                Some((stepped - x[col]).abs())
            })
            .fold(0.0, f64::max)
    };
    let (coarse, fine) = (error(1e-4), error(1e-5));
    let largest = exact.iter().map(|x| x[col].abs()).fold(0.0, f64::max);
    assert!(largest > 1e-3, "{largest}");
    assert!(
        fine < 0.25 * coarse && fine < 1e-2 * largest,
        "block {k}: {coarse} {fine} of {largest}"
    );
}

/// Two slabs 2 cm apart (0.3 m wide, 1.2 and 1.6 m high) under a 0.3 g, 1 Hz sine strike each
/// other twice in 0.8 s, the shorter one's corner on the taller one's face: the shorter one's
/// pivot slips through each impact and the taller one's leaves the ground. The energy balance
/// closes through both, and Moreau-Jean converges on both slabs' rotations after them.
#[test]
fn two_rocking_slabs_strike_each_other_as_time_stepping_converges_to() {
    let model = Model::from_ron_str(
        "(version: 1, name: \"two slabs\", thickness_m: 0.5, density_kg_m3: 2500, friction: 0.8,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"),
                    (width_m: 0.3, height_m: 1.6, gap_m: 0.02, name: \"T\")])])",
    )
    .unwrap();
    let motion = sine(0.3, 0.0);
    let r = run(&model, &motion, 0.8, 0.0);
    let impacts = impacts(&r);
    assert_eq!(impacts.len(), 2);
    for e in &impacts {
        assert_eq!(e.blocks, ["S", "T"]);
        let what = e.mode.as_deref().unwrap_or_default();
        assert!(
            what.contains("S: theta'") && what.contains("slipping at"),
            "{what}"
        );
        assert!(
            what.contains("T: theta'") && what.contains("leaves the ground"),
            "{what}"
        );
    }
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-13 * e.input_j, "{e:?}");
    for k in 0..2 {
        converges(&model, &motion, &r, impacts[0].time_s, k);
    }
}

/// The slab (it lifts at 0.25 g) 2 cm from a squat column (0.6 by 1.6 m: it would lift at
/// 0.375 g) under 0.3 g at 1 Hz: the slab strikes the seated column at 0.6297 s, as it struck
/// the abutment, flying off it, and the column, struck above its centroid, turns on its far
/// corner, rocks and comes to rest. Moreau-Jean converges on both rotations from the strike.
#[test]
fn a_slab_strikes_a_seated_column_which_rocks_as_time_stepping_converges_to() {
    let model = wall(", (width_m: 0.6, height_m: 1.6, gap_m: 0.02, name: \"T\")");
    let motion = sine(0.3, 0.0);
    let r = run(&model, &motion, 1.0, 0.0);
    let impact = impacts(&r)[0];
    let what = impact.mode.as_deref().unwrap_or_default();
    assert!(
        what.contains("T: theta' 0.000000e0") && what.contains("rocks on its right corner"),
        "{what}"
    );
    assert!(r.summary.blocks[1].max_abs_rotation_rad > 1e-3);
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-13 * e.input_j, "{e:?}");
    for k in 0..2 {
        converges(&model, &motion, &r, impact.time_s, k);
    }
}

/// The slab 0.1 m from a squat block (1.2 x 1.2 m, friction 0.6, no restitution) under 0.3 g at
/// 1 Hz: it falls onto the block at 0.8739 s, whose blows tip the block, which lands again,
/// until it lands with the slab's corner on its face and stays seated, the push passing through
/// its base to the ground: the two move on together, the block seated (its base sliding, then
/// stuck), the slab's pivot slipping, then stuck, until the push falls to zero and they part
/// (0.9067 s). Before, the contact could only stay between bodies that rock or fly, and the run
/// stopped at that landing. The energy balance closes and Moreau-Jean converges on the slab's
/// rotation from the block's seating on (through the blows before it, a series of ever shorter
/// flights, more slowly: 2.3e-5, 3.7e-6 and 1.7e-7 rad at dt = 1e-4, 1e-5, 1e-6 s).
#[test]
fn a_slab_fallen_onto_a_squat_block_leans_on_it_while_the_block_stays_seated() {
    let model = Model::from_ron_str(
        "(version: 1, name: \"slab and block\", thickness_m: 0.5, density_kg_m3: 2500,
          friction: 0.6, restitution: 0.0, rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name:
          \"S\"), (width_m: 1.2, gap_m: 0.1, name: \"W\")])])",
    )
    .unwrap();
    let motion = sine(0.3, 0.0);
    let r = run(&model, &motion, 1.1, 0.0);
    assert!(r.summary.warnings.is_empty(), "{:?}", r.summary.warnings);
    let seated = impacts(&r)
        .into_iter()
        .find(|e| {
            let what = e.mode.as_deref().unwrap_or_default();
            // Seated from a rotation of round-off (its last landing, with the slab's).
            what.contains("W: theta' ") && what.contains(" -> 0.000000e0 rad/s, seated")
        })
        .expect("the block seated in the contact")
        .time_s;
    let events = &r.events;
    let named = |kind: EventKind, block: &str| {
        events
            .iter()
            .filter(|e| e.kind == kind && e.blocks.iter().any(|b| b == block))
            .map(|e| e.time_s)
            .collect::<Vec<_>>()
    };
    let parts = named(EventKind::Separation, "W");
    assert!(!parts.is_empty());
    let stuck = named(EventKind::Stick, "W");
    assert!(
        stuck.iter().any(|&t| t < parts[parts.len() - 1]),
        "{stuck:?} {parts:?}"
    );
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-13 * e.input_j, "{e:?}");
    converges(&model, &motion, &r, seated, 0);
}

/// A slab 0.2 m wide and 0.8 m high 0.5 m to the right of the 1.2 m slab (friction 2; no
/// restitution; walls/rocking/leaning-slabs.ron), under 0.4 g at 1 Hz from 180 degrees: both
/// rock to the left and the short one falls onto the tall one, its top corner on the tall one's
/// right face, where it stays: the two turn together on their pivots, the push between them from
/// the mechanism's equations, until the short one's left face comes down flat on the tall one's
/// (their rotations equal) at 1.621 s. There both ends of the faces' overlap take their impulses
/// at once: S's corner strikes T's face plastically while T's old corner leaves S's face, so the
/// two turn on together on the new contact, until S's corner slides off the end of T's face
/// (1.676 s) and S, alone, overturns. Until the faces meet the old corner stays on the face to
/// round-off and the bottom of T's face stays off it; the energy balance closes through the
/// overturning, and Moreau-Jean converges on both rotations up to the faces' meeting.
#[test]
fn two_slabs_fallen_together_turn_as_one_mechanism_until_their_faces_meet() {
    let model = Model::from_file("walls/rocking/leaning-slabs.ron").unwrap();
    let motion = sine(0.4, 180.0);
    let r = run(&model, &motion, 5.0, 0.0);
    let [impact, flat] = impacts(&r)[..] else {
        panic!("{:?}", r.events)
    };
    let what = impact.mode.as_deref().unwrap_or_default();
    assert!(
        impact.blocks == ["T", "S"] && what.contains("they turn on together"),
        "{what}"
    );
    let lands = flat.mode.as_deref().unwrap_or_default();
    assert!(
        flat.blocks == ["S", "T"]
            && lands.contains("S's corner strikes T's face")
            && lands.contains("T's face comes down flat on S's and T's corner leaves S's face")
            && lands.contains("they turn on together"),
        "{lands}"
    );
    assert!(flat.time_s > impact.time_s + 0.1, "{}", flat.time_s);
    let after = events_after(&r, flat.time_s);
    let part = (after.iter())
        .find(|e| e.kind == EventKind::Separation)
        .expect("the two part");
    assert!(
        part.blocks == ["S", "T"]
            && part
                .mode
                .as_deref()
                .unwrap()
                .contains("slides off an end of T's face"),
        "{part:?}"
    );
    let collapse = r.summary.collapse.as_ref().expect("S overturns");
    assert!(collapse.block == "S" && collapse.cause == CollapseCause::Overturning);
    assert!(collapse.time_s > part.time_s, "{collapse:?}");
    assert!(r.summary.warnings.is_empty(), "{:?}", r.summary.warnings);
    // Both rock on their left corners, at x = 0 and 0.8 m, which stay where they are: the
    // distance of T's top left corner, and of its bottom left one, from S's right face.
    let from_face = |ts: f64, tt: f64, y: f64| from_face(ts, (tt, 0.8, 0.2), y);
    let (s, t) = (rows(&r, 0), rows(&r, 1));
    let together: Vec<usize> = (0..s.len())
        .filter(|&i| s[i][0] >= impact.time_s && s[i][0] <= flat.time_s)
        .collect();
    assert!(together.len() > 10);
    for &i in &together {
        let gap = from_face(s[i][3], t[i][3], 0.8);
        assert!(gap.abs() < 1e-15, "{:?} {:?}: {gap}", s[i], t[i]);
        assert!(s[i][0] == flat.time_s || from_face(s[i][3], t[i][3], 0.0) > 0.0);
    }
    let last = *together.last().unwrap();
    assert_eq!(s[last][0], flat.time_s);
    assert!(from_face(s[last][3], t[last][3], 0.0).abs() < 1e-14);
    assert!(
        (s[last][3] - t[last][3]).abs() < 1e-13,
        "{:?} {:?}",
        s[last],
        t[last]
    );
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
    let to_flat = run(&model, &motion, flat.time_s, 0.0);
    for k in 0..2 {
        converges(&model, &motion, &to_flat, impact.time_s, k);
    }
}

/// The same two slabs under the same sine until 1.499 s, then (within one 1 ms sample) a ground
/// acceleration of -1.5 g: it throws both back to the right, the short one faster, and the
/// push between them falls to zero at 1.5347 s: they part there (`separation`) and each rocks
/// on alone. At that instant the push of the mechanism's closed form is zero to round-off
/// (with d = 0.8 cos A + 0.8 sin(B - A) - 0.3 the distance of T's corner from S's face, A and B
/// their rotations: I_A A'' = Q_A + P d_A, I_B B'' = Q_B + P d_B, d_A A'' + d_B B'' + A' B'
/// terms = 0), and positive at every row between the impact and it.
#[test]
fn two_slabs_turning_together_part_where_their_push_falls_to_zero() {
    let model = Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 2.0, restitution: 0.0,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"),
                    (width_m: 0.2, height_m: 0.8, gap_m: 0.5, name: \"T\")])])",
    )
    .unwrap();
    let (g, dt) = (9.81, 1e-3);
    let accel = |t: f64| {
        if t < 1.4995 {
            0.4 * g * (std::f64::consts::TAU * t + std::f64::consts::PI).sin()
        } else {
            -1.5 * g
        }
    };
    let samples = (0..2500).map(|i| accel(i as f64 * dt)).collect();
    let motion = Motion::Record(crate::motion::Record::new("throw", dt, samples).unwrap());
    let r = run(&model, &motion, 2.4, 0.0);
    let [impact] = impacts(&r)[..] else {
        panic!("{:?}", r.events)
    };
    let parts: Vec<_> = (r.events.iter())
        .filter(|e| e.kind == EventKind::Separation)
        .collect();
    let [part] = parts[..] else {
        panic!("{:?}", r.events)
    };
    assert_eq!(part.blocks, ["T", "S"]);
    assert!(
        part.time_s > 1.5 + dt && part.time_s < 1.6,
        "{}",
        part.time_s
    );
    // The push from the state: both on their left corners (s = -1), corner inertias m (w^2 +
    // h^2) / 3, and the ground's acceleration between the samples.
    let push = |t: f64, a: f64, b: f64, wa: f64, wb: f64| {
        let rocking = |m: f64, half: f64, hc: f64, theta: f64| {
            let (sin, cos) = theta.sin_cos();
            let (gy, dx) = (-half * sin + hc * cos, -half * cos - hc * sin);
            let inertia = m * (4.0 * half * half + 4.0 * hc * hc) / 3.0;
            (-m * (gy * motion.accel(t) + dx * g), inertia)
        };
        let (qa, ia) = rocking(450.0, 0.15, 0.6, a);
        let (qb, ib) = rocking(200.0, 0.1, 0.4, b);
        let (sin, cos) = (b - a).sin_cos();
        let (da, db) = (-0.8 * a.sin() - 0.8 * cos, 0.8 * cos);
        let (daa, dab, dbb) = (-0.8 * a.cos() - 0.8 * sin, 0.8 * sin, -0.8 * sin);
        let h = daa * wa * wa + 2.0 * dab * wa * wb + dbb * wb * wb;
        (-h - da * qa / ia - db * qb / ib) / (da * da / ia + db * db / ib)
    };
    let (s, t) = (rows(&r, 0), rows(&r, 1));
    let mut checked = 0;
    for i in (0..s.len()).filter(|&i| s[i][0] >= impact.time_s && s[i][0] <= part.time_s) {
        let (a, b) = (s[i][3], t[i][3]);
        assert!((0.8 * a.cos() + 0.8 * (b - a).sin() - 0.3).abs() < 1e-15);
        let p = push(s[i][0], a, b, s[i][4], t[i][4]);
        if s[i][0] == part.time_s {
            assert!(p.abs() < 1e-12 * 200.0 * g, "{p}");
            checked += 1;
        } else {
            assert!(p > 0.0, "{:?} {p}", s[i]);
        }
    }
    assert_eq!(checked, 1);
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
}

/// The slabs 0.4 m apart under 0.3 g from 180 degrees: T falls onto S's face at 1.3982 s and
/// they turn together, S pushing T to the right, until S lands on its base at 1.4037 s. The
/// landing and the contact take their impulses at once, and the contact's is zero: the
/// landing is Housner's, S alone (theta' falls by r = 1 - 1.5 sin^2 alpha), and T moves away
/// from S's slower face: they part at that instant, and stand apart until they meet again at
/// 1.5117 s, where S's pivot leaves the ground, T's corner on its face; S lands from that
/// flight (1.5121 s), both contacts taking their impulses at once, and the two turn together
/// from there, through S's next landing, until T's face comes down flat on S's (2.881 s): S's
/// corner strikes T's face there while T's leaves S's, and S, turning on with T, overturns
/// (2.988 s). Moreau-Jean converges on both rotations from the first meeting through the second
/// and the landing from flight, to 1.6 s.
#[test]
fn a_slab_that_lands_while_turning_with_another_parts_from_it() {
    let model = Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 2.0, restitution: 0.0,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"),
                    (width_m: 0.2, height_m: 0.8, gap_m: 0.4, name: \"T\")])])",
    )
    .unwrap();
    let motion = sine(0.3, 180.0);
    let r = run(&model, &motion, 5.0, 0.0);
    let impact = impacts(&r)[0];
    assert!(impact
        .mode
        .as_deref()
        .unwrap_or_default()
        .contains("turn on together"));
    let after = events_after(&r, impact.time_s);
    let [landing, part, meet, ..] = after[..] else {
        panic!("{after:?}")
    };
    assert_eq!(
        (landing.kind, part.kind, meet.kind),
        (
            EventKind::RockingImpact,
            EventKind::Separation,
            EventKind::BlocksImpact
        )
    );
    assert_eq!(
        (landing.blocks.as_slice(), part.time_s),
        (&["S".to_string()][..], landing.time_s)
    );
    let (before, after) = (
        landing.angular_velocity_before_rad_s.unwrap(),
        landing.angular_velocity_after_rad_s.unwrap(),
    );
    let housner = 1.0 - 1.5 * (0.25f64.atan().sin()).powi(2);
    assert!((after / before - housner).abs() < 1e-12, "{before} {after}");
    let meets = meet.mode.as_deref().unwrap_or_default();
    assert!(
        meets.contains("S: theta'") && meets.contains("leaving the ground at"),
        "{meets}"
    );
    let settled = (impacts(&r).into_iter())
        .find(|e| e.time_s > meet.time_s && !e.mode.as_deref().unwrap().contains("leaving"))
        .unwrap();
    assert!(settled.time_s < meet.time_s + 1e-3, "{settled:?}");
    assert!(settled
        .mode
        .as_deref()
        .unwrap()
        .contains("turn on together"));
    assert!(r.events.iter().any(|e| e.time_s == settled.time_s
        && e.kind == EventKind::RockingImpact
        && e.mode
            .as_deref()
            .unwrap()
            .contains("both contacts plastic at once")));
    let flat = (impacts(&r).into_iter())
        .find(|e| e.mode.as_deref().unwrap().contains("comes down flat"))
        .expect("T's face comes down flat on S's");
    assert!(flat.time_s > settled.time_s);
    let lands = flat.mode.as_deref().unwrap();
    assert!(
        lands.contains("S's corner strikes T's face")
            && lands.contains("T's face comes down flat on S's and T's corner leaves S's face"),
        "{lands}"
    );
    assert!(flat.time_s > 2.8 && flat.time_s < 2.9, "{}", flat.time_s);
    let collapse = r.summary.collapse.as_ref().expect("S overturns");
    assert!(collapse.block == "S" && collapse.cause == CollapseCause::Overturning);
    assert!(collapse.time_s > flat.time_s && r.summary.warnings.is_empty());
    let stop = meet.time_s;
    let (s, t) = (rows(&r, 0), rows(&r, 1));
    let (mut on, mut apart) = (0, 0);
    for i in (0..s.len()).filter(|&i| s[i][0] >= impact.time_s && s[i][0] < stop) {
        let gap = from_face(s[i][3], (t[i][3], 0.7, 0.2), 0.8);
        if s[i][0] <= landing.time_s {
            assert!(gap.abs() < 1e-15, "{:?} {:?}: {gap}", s[i], t[i]);
            on += 1;
        } else {
            assert!(gap > 0.0, "{:?} {:?}: {gap}", s[i], t[i]);
            apart += 1;
        }
    }
    assert!(on >= 2 && apart > 5, "{on} {apart}");
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
    let through_landing = run(&model, &motion, 1.6, 0.0);
    for k in 0..2 {
        converges(&model, &motion, &through_landing, impact.time_s, k);
    }
}

/// The corners of a block w wide and h high whose base's middle stood at x0, from a history
/// row (u and w: the base middle's displacement and height, theta: the rotation).
pub(super) fn block_corners(x0: f64, (w, h): (f64, f64), row: &[f64; 6]) -> [[f64; 2]; 4] {
    let (sin, cos) = row[3].sin_cos();
    let turn = |x: f64, y: f64| [x * cos + y * sin, -x * sin + y * cos];
    let mid = [x0 + row[1], row[5]];
    [(-0.5, 0.0), (0.5, 0.0), (0.5, 1.0), (-0.5, 1.0)].map(|(a, b)| {
        let r = turn(a * w, b * h);
        [mid[0] + r[0], mid[1] + r[1]]
    })
}

/// Asserts that, drawn from the rows of `r` alone, its first two blocks (each the middle of its
/// base at rest and its width and height, m) never overlap by more than 1e-14 of `size_m`.
pub(super) fn never_overlap(r: &Response, blocks: [(f64, (f64, f64)); 2], size_m: f64) {
    let (s, t) = (rows(r, 0), rows(r, 1));
    for i in 0..s.len() {
        let sep = apart(
            &block_corners(blocks[0].0, blocks[0].1, &s[i]),
            &block_corners(blocks[1].0, blocks[1].1, &t[i]),
        );
        assert!(sep > -1e-14 * size_m, "{:?} {:?}: {sep}", s[i], t[i]);
    }
}

/// How far apart two convex quadrilaterals stand (m): the largest, over the edges of both, of
/// the least distance of the other's corners outside that edge (negative: they overlap).
fn apart(a: &[[f64; 2]; 4], b: &[[f64; 2]; 4]) -> f64 {
    let outside = |own: &[[f64; 2]; 4], other: &[[f64; 2]; 4]| {
        (0..4)
            .map(|e| {
                let (p, q) = (own[e], own[(e + 1) % 4]);
                let len = (q[0] - p[0]).hypot(q[1] - p[1]);
                let n = [(q[1] - p[1]) / len, -(q[0] - p[0]) / len];
                other
                    .iter()
                    .map(|c| (c[0] - p[0]) * n[0] + (c[1] - p[1]) * n[1])
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(f64::NEG_INFINITY, f64::max)
    };
    outside(a, b).max(outside(b, a))
}

/// Two slabs (the 0.3 x 1.2 m one and one w x h, `gap` m to its right, friction mu, no
/// restitution) under sines that make them fall onto each other and turn together, one's
/// corner on the other's face whichever way they lean, the couple ending every way it can
/// (faces flat, after a pivot starts slipping or not, a landing and parting, the run's end):
/// at every row the two blocks, drawn from the rows alone, do not overlap by more than
/// round-off, and while they turn together they touch to round-off; every energy balance
/// closes.
#[test]
fn slabs_turning_together_touch_and_never_overlap_however_they_lean() {
    // (mu, gap, w, h, frequency, amplitude in g, phase in degrees)
    let scenes = [
        (2.0, 0.5, 0.2, 0.8, 1.0, 0.4, 180.0),
        (2.0, 0.5, 0.3, 0.9, 1.0, 0.4, 0.0),
        (2.0, 0.45, 0.15, 0.8, 1.0, 0.4, 0.0),
        (2.0, 0.5, 0.2, 0.8, 3.0, 0.8, 180.0),
        (2.0, 0.3, 0.2, 0.8, 1.5, 0.6, 180.0),
        (1.0, 0.5, 0.25, 0.9, 1.0, 0.8, 0.0),
        (2.0, 0.5, 0.2, 0.8, 2.0, 0.4, 0.0),
        (2.0, 0.3, 0.2, 0.8, 1.0, 0.3, 180.0),
    ];
    let mut couples = 0;
    for (mu, gap, w, h, f, amplitude, phase) in scenes {
        let model = Model::from_ron_str(&format!(
            "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: {mu:?},
              restitution: 0.0, rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"),
              (width_m: {w:?}, height_m: {h:?}, gap_m: {gap:?}, name: \"T\")])])"
        ))
        .unwrap();
        let motion = Motion::Sine(Sine {
            amplitude_m_s2: amplitude * 9.81,
            frequency_hz: f,
            phase_rad: f64::to_radians(phase),
            duration_s: 5.0,
        });
        let r = run(&model, &motion, 5.0, 0.0);
        let starts: Vec<(usize, f64)> = (r.events.iter().enumerate())
            .filter(|(_, e)| {
                e.kind == EventKind::BlocksImpact
                    && e.mode
                        .as_deref()
                        .unwrap_or_default()
                        .contains("turn on together")
            })
            .map(|(j, e)| (j, e.time_s))
            .collect();
        assert!(!starts.is_empty(), "{:?}", r.events);
        couples += starts.len();
        // A couple lasts to the next event between the blocks (at the same instant, where one
        // is logged after it), or the run's end.
        let ends: Vec<f64> = starts
            .iter()
            .map(|&(from, _)| {
                (r.events.iter().skip(from + 1))
                    .filter(|e| {
                        matches!(
                            e.kind,
                            EventKind::Separation
                                | EventKind::BlocksMeet
                                | EventKind::RockingImpact
                        )
                    })
                    .map(|e| e.time_s)
                    .next()
                    .unwrap_or(r.summary.duration_s)
            })
            .collect();
        let (s, t) = (rows(&r, 0), rows(&r, 1));
        let size = (0.3f64).hypot(1.2);
        for i in 0..s.len() {
            let sep = apart(
                &block_corners(0.15, (0.3, 1.2), &s[i]),
                &block_corners(0.3 + gap + 0.5 * w, (w, h), &t[i]),
            );
            assert!(sep > -1e-14 * size, "{:?} {:?}: {sep}", s[i], t[i]);
            let together =
                (starts.iter().zip(&ends)).any(|(&(_, a), &b)| s[i][0] >= a && s[i][0] <= b);
            assert!(
                !together || sep < 1e-14 * size,
                "{:?} {:?}: {sep}",
                s[i],
                t[i]
            );
        }
        let e = &r.summary.energy;
        let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
        assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
    }
    assert!(couples >= scenes.len());
}

/// The slabs of walls/rocking/leaning-slabs.ron with friction 0.6 under the same sine (0.4 g
/// at 1 Hz from 180 degrees): T falls onto S's face at 1.4631 s, and the impact leaves S's
/// pivot slipping: they turn together, S's pivot sliding to the left under the push, until it
/// sticks (1.4702 s), then slips again (1.5903 s) until T's face comes down flat on S's
/// (1.6213 s): S's corner strikes T's face there, T's corner leaves S's, and the two turn on
/// together until S's corner slides off the end of T's face (1.6727 s) and S overturns. From the
/// first impact to the parting the blocks drawn from the rows (the pivots' slip among them)
/// touch to round-off, the energy balance closes with the work of the pivots' friction in it,
/// and Moreau-Jean converges on both rotations and on S's displacement up to the faces' meeting.
#[test]
fn two_slabs_turn_together_while_a_pivot_slips_and_sticks() {
    let mut text = std::fs::read_to_string("walls/rocking/leaning-slabs.ron").unwrap();
    text = text.replace("friction: 2.0", "friction: 0.6");
    let model = Model::from_ron_str(&text).unwrap();
    let motion = sine(0.4, 180.0);
    let r = run(&model, &motion, 5.0, 0.0);
    let [impact, _] = impacts(&r)[..] else {
        panic!("{:?}", r.events)
    };
    let what = impact.mode.as_deref().unwrap_or_default();
    assert!(
        impact.blocks == ["T", "S"]
            && what.contains("S: theta'")
            && what.contains("slipping at")
            && what.contains("they turn on together"),
        "{what}"
    );
    let after = events_after(&r, impact.time_s);
    let [stick, slip, flat, ..] = after[..] else {
        panic!("{after:?}")
    };
    assert_eq!(
        (stick.kind, slip.kind, flat.kind),
        (
            EventKind::PivotStick,
            EventKind::PivotSlip,
            EventKind::BlocksImpact
        )
    );
    assert!(stick.blocks == ["S"] && slip.blocks == ["S"]);
    assert!(flat
        .mode
        .as_deref()
        .unwrap()
        .contains("T's face comes down flat on S's"));
    let part = (after.iter())
        .find(|e| e.kind == EventKind::Separation)
        .expect("the two part");
    assert!(part
        .mode
        .as_deref()
        .unwrap()
        .contains("slides off an end of T's face"));
    let collapse = r.summary.collapse.as_ref().expect("S overturns");
    assert!(collapse.block == "S" && collapse.cause == CollapseCause::Overturning);
    assert!(collapse.time_s > part.time_s && r.summary.warnings.is_empty());
    let (s, t) = (rows(&r, 0), rows(&r, 1));
    let size = (0.3f64).hypot(1.2);
    let mut together = 0;
    for i in (0..s.len()).filter(|&i| s[i][0] >= impact.time_s && s[i][0] <= part.time_s) {
        let sep = apart(
            &block_corners(0.15, (0.3, 1.2), &s[i]),
            &block_corners(0.9, (0.2, 0.8), &t[i]),
        );
        assert!(sep.abs() < 1e-14 * size, "{:?} {:?}: {sep}", s[i], t[i]);
        together += 1;
    }
    assert!(together > 10, "{together}");
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.friction_j > 0.1, "{e:?}");
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
    let to_flat = run(&model, &motion, flat.time_s, 0.0);
    for k in 0..2 {
        converges(&model, &motion, &to_flat, impact.time_s, k);
    }
    converges_in(&model, &motion, &to_flat, impact.time_s, 0, 1);
}

/// A slab T (0.2 x 0.9 m) 0.3 m left of S (0.3 x 1.2 m), S 0.68 m left of a fixed abutment A
/// (friction 0.8, restitution 0.5), under 0.6 g at 1 Hz from 180 degrees: T comes to lean on
/// S, the two turning together, and S, carrying T, strikes A again and again. Each such blow
/// takes its impulse at A and T's contact its own at once (T stays on S); S's pivot sticks,
/// so S has one degree of freedom and its rebound is exactly -e times its strike, as for a slab
/// alone (theta'+ = -0.5 theta'-), whatever T's impulse. The bounces accumulate until S rests
/// against A with T on it, a chain of three in contact, where the run stops, saying so. The
/// blocks drawn from the rows never overlap; the energy balance closes.
#[test]
fn a_column_struck_while_another_leans_on_it_takes_the_blow_and_the_contact_at_once() {
    let model = Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.8, restitution: 0.5,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.2, height_m: 0.9, name: \"T\"),
                    (width_m: 0.3, gap_m: 0.3, name: \"S\"),
                    (width_m: 0.5, gap_m: 0.68, fixed: true, name: \"A\")])])",
    )
    .unwrap();
    let motion = sine(0.6, 180.0);
    let r = run(&model, &motion, 5.0, 0.0);
    let hits = impacts(&r);
    let mut at_once = 0;
    for (k, e) in hits.iter().enumerate() {
        let what = e.mode.as_deref().unwrap_or_default();
        if e.blocks != ["S", "A"] || !what.contains("parting") {
            continue;
        }
        // T leaned on S just before: its contact is logged right after, at this instant.
        let Some(next) = hits.get(k + 1).filter(|n| n.time_s == e.time_s) else {
            continue;
        };
        assert!(
            what.contains("every contact it touches taking its impulse at once"),
            "{what}"
        );
        let then = next.mode.as_deref().unwrap_or_default();
        assert!(
            next.blocks == ["T", "S"]
                && then.contains("T's corner stays on S's face, its impulse")
                && then.contains("they stay in contact"),
            "{then}"
        );
        let (before, after) = (
            e.angular_velocity_before_rad_s.unwrap(),
            e.angular_velocity_after_rad_s.unwrap(),
        );
        assert!((after / before + 0.5).abs() < 1e-12, "{before} {after}");
        at_once += 1;
    }
    assert!(at_once >= 5, "{at_once}");
    let stop = r.summary.duration_s;
    assert!(r.summary.warnings.iter().any(|w| matches!(
        w,
        Warning::BlocksMeet { time_s, why, .. }
            if *time_s == stop && why.contains("on two sides at once")
    )));
    let (t, s) = (rows(&r, 0), rows(&r, 1));
    let abutment = [[1.48, 0.0], [1.98, 0.0], [1.98, 1.2], [1.48, 1.2]];
    for i in 0..s.len() {
        let (bt, bs) = (
            block_corners(0.1, (0.2, 0.9), &t[i]),
            block_corners(0.65, (0.3, 1.2), &s[i]),
        );
        for sep in [apart(&bt, &bs), apart(&bs, &abutment)] {
            assert!(sep > -1e-14, "{:?} {:?}: {sep}", t[i], s[i]);
        }
    }
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
}

/// A 0.3 x 1.2 m slab beside a 1.0 x 1.2 m block 0.05 m away (friction 0.9, no restitution)
/// under 0.3 g at 1.5 Hz: at 3.9954 s the slab's face comes down flat
/// on the block's, the impact leaves both ends of their overlap at rest on each other and both
/// bodies off the ground, and the contact problem at the level of accelerations opens both ends
/// (the faces turn apart): the bodies part with no push between them, and the run goes on to its
/// end. Drawn from the rows alone, the blocks touch at the impact (to round-off), never overlap
/// after it and stand apart at the next row (the slab landing 1.3 ms later); the energy balance
/// closes.
#[test]
fn faces_left_at_rest_on_each_other_part_where_they_turn_apart() {
    let r = run(&slab_beside_block(0.9), &sine_of(0.3, 1.5), 4.0, 0.0);
    assert!(r.summary.warnings.is_empty(), "{:?}", r.summary.warnings);
    assert_eq!(r.summary.duration_s, 4.0);
    let parting = (r.events.iter())
        .find(|e| {
            e.kind == EventKind::Separation
                && (e.mode.as_deref().unwrap_or_default())
                    .contains("at rest on it after the impact (impulses")
                && (e.mode.as_deref().unwrap_or_default())
                    .ends_with("and the faces turn apart from both ends")
        })
        .unwrap_or_else(|| panic!("{:#?}", r.events));
    assert!((parting.time_s - 3.9954).abs() < 1e-4, "{}", parting.time_s);
    let (s, w) = (rows(&r, 0), rows(&r, 1));
    let size = (0.3f64).hypot(1.2);
    let sep = |i: usize| {
        apart(
            &block_corners(0.15, (0.3, 1.2), &s[i]),
            &block_corners(0.3 + 0.05 + 0.5, (1.0, 1.2), &w[i]),
        )
    };
    let at = (s.iter()).position(|row| row[0] == parting.time_s).unwrap();
    assert!(sep(at).abs() < 1e-14 * size, "{}", sep(at));
    for i in at + 1..s.len() {
        assert!(sep(i) > -1e-14 * size, "{:?} {:?}: {}", s[i], w[i], sep(i));
    }
    // 1.3 ms later, apart by 3.3e-8 m: an opening of 0.04 m/s2, far above round-off.
    assert!(sep(at + 1) > 1e-8, "{}", sep(at + 1));
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
}

/// A 0.3 x 1.2 m slab beside a 1.0 x 1.2 m block 0.05 m away (friction 0.6, no restitution)
/// under 0.4 g at 1 Hz: at 1.8272 s the block's face comes down flat on the slab's, both bodies
/// off the ground, and the contact problem at the level of accelerations presses both ends of
/// their overlap: the faces lie on each other, two pushes between them, until the block lands
/// on a corner 8.6 ms later. Both ends stay through that landing and both press, the block
/// rocking on its corner and slipping: the faces lie on each other on, one body on the ground,
/// until the slab lands 17.1 ms later and they turn apart at one end; the run goes on to its
/// end. Drawn from the rows alone, while the faces lie on each other the blocks touch (to
/// round-off, never overlapping) and turn together (their rotations' difference as at the
/// impact, to round-off); the energy balance closes.
#[test]
fn faces_that_lie_on_each_other_go_on_with_a_body_on_the_ground() {
    let r = run(&slab_beside_block(0.6), &sine_of(0.4, 1.0), 4.0, 0.0);
    let mode = |e: &EventRecord| e.mode.clone().unwrap_or_default();
    let find = |what: &str| {
        (r.events.iter())
            .find(|e| mode(e).contains(what))
            .unwrap_or_else(|| panic!("{what}: {:#?}", r.events))
    };
    let lies = find("and both ends press: the faces lie on each other");
    assert!((lies.time_s - 1.8272).abs() < 1e-4, "{}", lies.time_s);
    let on = find(
        "both ends of the contact of S's face with W's stay on it as W lands from free flight on \
         its right corner",
    );
    assert!(mode(on).contains("and both press: the faces lie on each other on"));
    assert!(mode(on).contains("W: theta'") && mode(on).contains("rocking on its right corner"));
    assert!(
        (on.time_s - lies.time_s - 8.6e-3).abs() < 1e-4,
        "{}",
        on.time_s
    );
    let lands = find("S lands from free flight on its right corner while W's face lies on S's");
    assert!(
        (lands.time_s - on.time_s - 17.1e-3).abs() < 1e-4,
        "{}",
        lands.time_s
    );
    assert!(
        (r.events.iter()).all(|e| e.kind != EventKind::BlocksMeet),
        "{:#?}",
        r.events
    );
    assert!(r.summary.collapse.is_none());
    let (s, w) = (rows(&r, 0), rows(&r, 1));
    assert_eq!(s.last().unwrap()[0], 4.0);
    let size = (1.0f64).hypot(1.2);
    let sep = |i: usize| {
        apart(
            &block_corners(0.15, (0.3, 1.2), &s[i]),
            &block_corners(0.3 + 0.05 + 0.5, (1.0, 1.2), &w[i]),
        )
    };
    let at = (s.iter()).position(|row| row[0] == lies.time_s).unwrap();
    let turn = s[at][3] - w[at][3];
    let lying: Vec<usize> = (at..s.len()).filter(|&i| s[i][0] < lands.time_s).collect();
    let grounded = lying.iter().filter(|&&i| s[i][0] > on.time_s).count();
    assert!(lying.len() >= 5 && grounded >= 2, "{lying:?} {grounded}");
    for i in lying {
        assert!(
            sep(i).abs() < 1e-14 * size,
            "{:?} {:?}: {}",
            s[i],
            w[i],
            sep(i)
        );
        let drift = s[i][3] - w[i][3] - turn;
        assert!(drift.abs() < 1e-14, "{}: {drift}", s[i][0]);
    }
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
}

/// A 0.3 x 1.2 m slab S and a 0.2 x 0.6 m block T 0.5 m from it (friction 0.4, no restitution)
/// under 0.3 g at 0.8 Hz (phase 60 degrees), a scene of the scans: at 1.9853 s S's face comes
/// down flat on T's, both in flight, and the faces lie on each other until T lands from free
/// flight on its right corner 0.95 ms later. The landing and both ends take their impulses at
/// once, plastic: one end stays, the other opens, and the two turn on together on it, part at
/// once (its push falls), and T overturns at 2.0229 s. Drawn from the rows alone, the blocks
/// never overlap; the energy balance closes through the three-contact landing.
#[test]
fn a_landing_of_faces_lying_on_each_other_takes_three_contacts_at_once() {
    let model = Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.4, restitution: 0.0,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"),
          (width_m: 0.2, height_m: 0.6, gap_m: 0.5, name: \"T\")])])",
    )
    .unwrap();
    let motion = Motion::Sine(Sine {
        amplitude_m_s2: 0.3 * 9.81,
        frequency_hz: 0.8,
        phase_rad: 60f64.to_radians(),
        duration_s: 8.0,
    });
    let r = run(&model, &motion, 8.0, 0.0);
    let mode = |e: &EventRecord| e.mode.clone().unwrap_or_default();
    let find = |what: &str| {
        (r.events.iter())
            .position(|e| mode(e).contains(what))
            .unwrap_or_else(|| panic!("{what}: {:#?}", r.events))
    };
    let lies = find("and both ends press: the faces lie on each other");
    let lands = find(
        "T lands from free flight on its right corner while T's face lies on S's, the three \
         contacts plastic at once",
    );
    let stays = find("they stay in contact as T lands from free flight on its right corner");
    assert!(lies < lands && lands < stays, "{lies} {lands} {stays}");
    assert!((r.events[lies].time_s - 1.9853).abs() < 1e-4);
    assert!((r.events[lands].time_s - r.events[lies].time_s - 0.95e-3).abs() < 1e-5);
    let collapse = r.summary.collapse.as_ref().expect("T overturns");
    assert!(collapse.block == "T" && collapse.cause == CollapseCause::Overturning);
    assert!(
        (collapse.time_s - 2.0229).abs() < 1e-4,
        "{}",
        collapse.time_s
    );
    let blocks = [(0.15, (0.3, 1.2)), (0.3 + 0.5 + 0.1, (0.2, 0.6))];
    never_overlap(&r, blocks, (0.3f64).hypot(1.2));
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
}

/// A 0.3 x 1.2 m slab beside a 1.2 x 1.2 m block 0.05 m away (friction 0.9, no restitution)
/// under 0.5 g at 2.5 Hz, a scene of the scans: the faces lie on each other from 2.4537 s until
/// the block lands on its left corner 0.75 ms later, where the three impulses open both ends
/// (each at a positive normal velocity, named): the bodies part, the block rocks on, and the
/// run goes on 0.3 s more. Drawn from the rows alone, the blocks never overlap; the energy
/// balance closes through the landing.
#[test]
fn a_landing_of_faces_lying_on_each_other_can_part_them_at_both_ends() {
    let model = Model::from_ron_str(
        "(version: 1, thickness_m: 0.5, density_kg_m3: 2500, friction: 0.9, restitution: 0.0,
          rows: [(height_m: 1.2, blocks: [(width_m: 0.3, name: \"S\"),
          (width_m: 1.2, height_m: 1.2, gap_m: 0.05, name: \"W\")])])",
    )
    .unwrap();
    let r = run(&model, &sine_of(0.5, 2.5), 4.0, 0.0);
    let mode = |e: &EventRecord| e.mode.clone().unwrap_or_default();
    let parts = (r.events.iter())
        .find(|e| {
            e.kind == EventKind::Separation
                && mode(e).starts_with(
                    "S's and W's faces, which lay on each other, part at both ends as W lands \
                     from free flight on its left corner, at ",
                )
        })
        .unwrap_or_else(|| panic!("{:#?}", r.events));
    assert!((parts.time_s - 2.4544).abs() < 1e-4, "{}", parts.time_s);
    let speeds: Vec<f64> = (mode(parts).rsplit(", at ").next().unwrap())
        .trim_end_matches(" m/s")
        .split(" and ")
        .map(|x| x.parse().unwrap())
        .collect();
    assert!(speeds.iter().all(|&v| v > 1e-4), "{speeds:?}");
    assert!(r.summary.duration_s > parts.time_s + 0.3);
    let blocks = [(0.15, (0.3, 1.2)), (0.3 + 0.05 + 0.6, (1.2, 1.2))];
    never_overlap(&r, blocks, (1.2f64).hypot(1.2));
    let e = &r.summary.energy;
    let scale = e.input_j.abs() + e.impact_loss_j + e.potential_j.abs();
    assert!(e.residual_j.abs() <= 1e-14 * scale, "{e:?}");
}
