//! Blocks seated face on face (`abutting`): two blocks alone in their columns that touch from
//! the start rest together while a push between them can balance both, slide together as one,
//! and part where one lifts away.

use super::clearance_tests::never_overlap;
use super::tie_tests::{balances, el_centro_to_end, row, run, slab_and_block};
use crate::response::{EventKind, Response};

/// Asserts that the slab 0.3 x 1.2 m and the block (`w` x `h` m) touching it on its right,
/// drawn from the rows of `r`, never overlap, and that the energy balance closes.
fn whole(r: &Response, (w, h): (f64, f64)) {
    never_overlap(
        r,
        [(0.15, (0.3, 1.2)), (0.3 + 0.5 * w, (w, h))],
        1.2f64.hypot(1.2),
    );
    balances(r);
}

/// The run of `model` under a sine (`amplitude_g`, `frequency_hz`, `phase_deg`) for `t` s,
/// asserted to reach its end without a warning.
fn to_end(model: &crate::model::Model, sine: (f64, f64, f64), t: f64) -> Response {
    let r = run(model, sine, t);
    assert_eq!(r.summary.duration_s, t, "{:?}", r.summary.warnings);
    assert!(r.summary.warnings.is_empty(), "{:?}", r.summary.warnings);
    r
}

/// The first event of `kind` for block `name`.
fn first(r: &Response, kind: EventKind, name: &str) -> f64 {
    (r.events.iter())
        .find(|e| e.kind == kind && e.blocks.iter().any(|b| b == name))
        .map(|e| e.time_s)
        .unwrap_or_else(|| panic!("no {kind:?} of {name}: {:#?}", r.events))
}

/// A slab 0.3 x 1.2 m touching a block 0.8 x 1.2 m on its right (friction 0.6, no restitution)
/// under a 0.5 g sine at 2.5 Hz. The ground accelerating to +x tips the slab away from the
/// block, which cannot hold it, so the pair rests until the slab's own uplift, a_g = g b/h =
/// g/4: t = 1/30 s exactly, found to round-off. The slab rocks away and back onto the block,
/// comes upright as its face comes flat on the block's (its base and both ends of the faces
/// taking their impulses at once), and the run goes on to its end: the blocks, drawn from the
/// rows, never overlap, and the energy balance closes.
#[test]
fn a_slab_beside_a_block_rests_with_it_until_it_lifts_away_at_its_own_threshold() {
    let model = slab_and_block(0.6, 0.0, (0.8, 1.2, 0.0));
    let r = to_end(&model, (0.5, 2.5, 0.0), 4.0);
    let lifts = first(&r, EventKind::Uplift, "S");
    assert!((lifts - 1.0 / 30.0).abs() <= 2e-17, "{lifts}");
    assert_eq!(first(&r, EventKind::Separation, "S"), lifts);
    assert!(
        r.events.iter().any(|e| e
            .mode
            .as_ref()
            .is_some_and(|m| m.contains("S upright on its base"))),
        "{:#?}",
        r.events
    );
    whole(&r, (0.8, 1.2));
}

/// Two squat blocks touching (1.2 x 1.2 m and 0.8 x 0.8 m, friction 0.3: neither can lift
/// before it slides) under a 0.5 g sine at 1 Hz slide together, each as the large block alone
/// does: with one friction the push between them stays zero, and every row of both is the lone
/// block's to round-off (the pair's motion comes from the contact's equations, the lone
/// block's from its own), its slips and sticks at the same instants to round-off.
#[test]
fn squat_blocks_touching_slide_together_as_one_of_them_alone() {
    let pair = row(
        0.3,
        0.0,
        "(width_m: 1.2, name: \"A\"), (width_m: 0.8, height_m: 0.8, name: \"B\")",
    );
    let alone = row(0.3, 0.0, "(width_m: 1.2, name: \"A\")");
    let (two, one) = (
        run(&pair, (0.5, 1.0, 0.0), 5.0),
        run(&alone, (0.5, 1.0, 0.0), 5.0),
    );
    let (h2, h1) = (two.history.as_ref().unwrap(), one.history.as_ref().unwrap());
    assert_eq!(h2.time_s.len(), h1.time_s.len());
    let largest = |x: &[Vec<f64>]| x.iter().map(|r| r[0].abs()).fold(0.0, f64::max);
    let (u, v) = (largest(&h1.displacement_m), largest(&h1.velocity_m_s));
    assert!(u > 1e-3 && v > 1e-2, "{u} {v}");
    for i in 0..h1.time_s.len() {
        assert!((h2.time_s[i] - h1.time_s[i]).abs() <= 2e-16 * h1.time_s[i].max(1.0));
        for k in 0..2 {
            let (du, dv) = (
                h2.displacement_m[i][k] - h1.displacement_m[i][0],
                h2.velocity_m_s[i][k] - h1.velocity_m_s[i][0],
            );
            assert!(
                du.abs() <= 1e-15 * u && dv.abs() <= 1e-15 * v,
                "row {i}: {du} {dv}"
            );
            assert_eq!(h2.rotation_rad[i][k], 0.0);
        }
    }
    let kinds = |r: &Response, name: &str| -> Vec<(EventKind, f64)> {
        (r.events.iter())
            .filter(|e| e.blocks.iter().any(|b| b == name))
            .map(|e| (e.kind, e.time_s))
            .collect()
    };
    let lone = kinds(&one, "A");
    assert!(lone.len() >= 18, "{lone:?}");
    for name in ["A", "B"] {
        let each = kinds(&two, name);
        assert_eq!(each.len(), lone.len(), "{name}");
        for ((k, t), (k1, t1)) in each.iter().zip(&lone) {
            assert_eq!(k, k1);
            assert!((t - t1).abs() <= 2e-16 * t1, "{name}: {t} {t1}");
        }
    }
    assert_eq!(
        two.summary.stick_slip_transitions,
        2 * one.summary.stick_slip_transitions
    );
}

/// The shipped slab beside a block (walls/rocking/slab-beside-block.ron: touching, elastic
/// faces) under a 0.3 g sine at 1 Hz: the slab lifts away at g/4, swings back and strikes the
/// block flat, bouncing off its face, and the contact that stays is at the two blocks' bottom
/// corners, together, where the slab leaves the ground (a push there moves it in flight, without
/// an arm about its pivot) and the block slips. The two turn on together on that contact, whose
/// push falls to zero at once: they part there (0.5524 s), each going on alone. Before, the
/// run stopped there; then (with the push said to move neither body) the contact held none
/// without a decision. It runs to its end, never overlapping, its balance closing.
#[test]
fn a_contact_at_two_blocks_bottom_corners_moves_a_slab_in_flight() {
    let model = crate::model::Model::from_file("walls/rocking/slab-beside-block.ron").unwrap();
    let r = to_end(&model, (0.3, 1.0, 0.0), 5.0);
    let lifts = first(&r, EventKind::Uplift, "S");
    let quarter_g = (0.25f64 / 0.3).asin() / (2.0 * std::f64::consts::PI);
    assert!((lifts - quarter_g).abs() <= 1e-15, "{lifts} {quarter_g}");
    let together = |e: &&crate::response::EventRecord| {
        e.mode.as_ref().is_some_and(|m| {
            m.contains("leaving the ground at") && m.contains("they turn on together")
        })
    };
    let met = (r.events.iter())
        .find(together)
        .expect("a couple of the slab in flight");
    assert!((met.time_s - 0.552_388_768).abs() < 1e-8, "{}", met.time_s);
    let parts =
        (r.events.iter()).any(|e| e.kind == EventKind::Separation && e.time_s == met.time_s);
    assert!(parts, "{:#?}", r.events);
    whole(&r, (1.2, 1.2));
}

/// The slab touching the block 1.2 x 1.2 m (friction 0.9, no restitution) under El Centro at
/// 0.4 g (a run of the scans' fifth grid): after the slab's rocking, the two turn with their
/// faces lying on each other, the slab in flight, and the block's slipping pivot sticks
/// (2.3138 s). Its slip of round-off was set to zero without booking what it carried of kinetic
/// energy (a term of first order in it, the block turning): the balance closed only to 3.5e-12
/// of the energies. It closes to round-off through 2.3142 s, where no way of the pivots and the
/// ends held and the run stopped, and where both bodies, a billionth of their alpha from rest,
/// are now set down seated, to the run's end.
#[test]
fn a_pivot_that_sticks_under_lying_faces_books_what_its_slip_carried() {
    use super::clearance_tests::run;
    use super::handoff_tests::el_centro;
    let model = slab_and_block(0.9, 0.0, (1.2, 1.2, 0.0));
    let r = run(&model, &el_centro(0.4), 2.4, 0.0);
    let sticks = (r.events.iter())
        .any(|e| e.kind == EventKind::PivotStick && (e.time_s - 2.313_794).abs() < 1e-6);
    assert!(sticks, "{:#?}", r.events);
    // Where it stopped before (no way of the pivots and the ends held), both are set down.
    let set_down = set_downs(&r);
    assert!(
        set_down.iter().any(|e| (e.time_s - 2.314_18).abs() < 1e-5),
        "{set_down:#?}"
    );
    assert_eq!(r.summary.duration_s, 2.4, "{:?}", r.summary.warnings);
    balances(&r);
}

/// The events that set a body down seated beside another ([`super::Engine::sets_down`]).
fn set_downs(r: &Response) -> Vec<&crate::response::EventRecord> {
    let set_down = |e: &&crate::response::EventRecord| {
        e.kind == EventKind::Rest
            && (e.mode.as_deref()).is_some_and(|m| m.starts_with("set down seated beside"))
    };
    r.events.iter().filter(set_down).collect()
}

/// The slab of a slab touching a block 1.2 x 1.2 m (friction 0.9, no restitution) under a
/// 0.3 g sine at 1 Hz (scan run 1609): at 0.5757796 s both are turned by 1.7e-11 rad, the block
/// coming down at 2.7e-5 rad/s, as the block's face comes down flat on the slab's and both ends
/// stay on each other, where none of the eight ways of the pivots and the ends holds (lying
/// faces on two pivots, docs/rocking-walls.md). The run stopped there; what either body has
/// beyond rest would turn it by less than 1e-9 of its alpha, so both are set down seated, face
/// on face, and the run goes on to its end: every set-down within that bound (the kinetic
/// energy of each body's rate before it, the only part an event reports, under the potential
/// energy of a tilt of 1e-9 alpha), the blocks never overlapping, the balance closing. Bodies
/// in motion where no mode holds still stop the run.
#[test]
fn bodies_within_a_billionth_of_alpha_of_rest_where_no_way_holds_are_set_down() {
    let model = slab_and_block(0.9, 0.0, (1.2, 1.2, 0.0));
    let r = to_end(&model, (0.3, 1.0, 0.0), 4.0);
    let set_down = set_downs(&r);
    let at = |t: f64, name: &str| {
        set_down.iter().any(|e| {
            e.time_s == t
                && e.blocks == [name]
                && (e.mode.as_deref()).is_some_and(|m| {
                    m.contains("none of the 8 ways of the pivots and the ends holds")
                })
        })
    };
    assert!(
        at(0.575_779_626_194_736_4, "S") && at(0.575_779_626_194_736_4, "W"),
        "{set_down:#?}"
    );
    for e in &set_down {
        let (w, h): (f64, f64) = if e.blocks == ["S"] {
            (0.3, 1.2)
        } else {
            (1.2, 1.2)
        };
        let mass = 2500.0 * 0.5 * w * h;
        let corner_inertia = mass * (w * w + h * h) / 3.0;
        let omega = e.angular_velocity_before_rad_s.expect("a rate before");
        let tilt = 1e-9 * (0.5 * w).atan2(0.5 * h);
        assert!(
            0.5 * corner_inertia * omega * omega <= mass * 9.81 * 0.5 * w * tilt,
            "{e:?}"
        );
    }
    whole(&r, (1.2, 1.2));
    // Bodies in motion where no mode holds are not set down: scan run 1646 (the slab turning at
    // 0.73 rad/s as its face comes flat on the block's) stops there as it did.
    let moving = run(
        &slab_and_block(0.6, 0.5, (0.8, 0.9, 0.0)),
        (0.5, 2.5, 0.0),
        1.6,
    );
    assert!(
        (moving.summary.duration_s - 1.541_559_545_6).abs() < 1e-9,
        "{:?}",
        moving.summary.warnings
    );
    assert!(set_downs(&moving).is_empty());
}

/// The slab of a slab touching a block (restitution 0.5) under El Centro at 0.4 g, alone after
/// the faces part: its pivot stops slipping where its slip is located to round-off, and the run
/// goes to its end (15 s). Setting that slip to zero without booking what it carried left
/// 2.4e-13 of the energies in the balance; booked as on lying faces, it closes to round-off.
#[test]
fn a_pivot_that_sticks_alone_books_what_its_slip_carried() {
    use super::clearance_tests::run;
    use super::handoff_tests::el_centro;
    let model = slab_and_block(0.6, 0.5, (0.8, 0.9, 0.0));
    let r = run(&model, &el_centro(0.4), 15.0, 0.0);
    assert_eq!(r.summary.duration_s, 15.0);
    let sticks = (r.events.iter())
        .filter(|e| e.kind == EventKind::PivotStick)
        .count();
    assert!(sticks > 0, "{:#?}", r.events);
    balances(&r);
}

/// The slab of a slab touching a block 0.5 x 0.9 m (friction 0.6, restitution 0.5) under a 0.3 g
/// sine at 1 Hz lands upright against the block at 0.5524 s: the faces' top end parts, their
/// bottom corners stay together, the slab leaves the ground at that corner (in flight, a push
/// there moves it without turning it about its pivot) and the block lifts about its far corner.
/// The couple at that corner is followed, and the slab's corner slides off the end of the
/// block's face at once (the face flat against the slab's only at that instant, its other end
/// leaving): the two part, and the run goes to its end. Before, the contact with no arm about
/// the slab's pivot stopped the run, and taken as a couple it rattled 10,001 times at one
/// instant, the flat faces found again and again.
#[test]
fn a_corner_at_the_end_of_a_face_slides_off_it_as_the_faces_part() {
    let model = slab_and_block(0.6, 0.5, (0.5, 0.9, 0.0));
    let r = run(&model, (0.3, 1.0, 0.0), 4.0);
    assert_eq!(r.summary.duration_s, 4.0, "{:?}", r.summary.warnings);
    let off = (r.events.iter()).find(|e| {
        e.kind == EventKind::Separation
            && e.mode.as_deref().is_some_and(|m| m.contains("off an end"))
    });
    let off = off.unwrap_or_else(|| panic!("{:#?}", r.events));
    assert!((off.time_s - 0.552_388_768).abs() < 1e-9, "{}", off.time_s);
    whole(&r, (0.5, 0.9));
}

/// The slab beside a block 0.8 x 1.2 m (friction 0.6, restitution 0.5) under a 0.5 g sine at
/// 2.5 Hz: at 1.1255 s the slab lands upright as its face comes flat on the block's, and the
/// contact that stays is at the block's pivot, where neither body's rotation moves it by more
/// than round-off. Closing the contact's normal velocity of round-off (4.7e-15 m/s) with the
/// block's rotation, whose arm there was 1.4e-14 m, changed its theta' by -0.32 rad/s and the
/// run ended in an error a step later; such a contact's round-off is left as it is now, and
/// the run goes to its end.
#[test]
fn a_contact_at_a_pivot_keeps_its_round_off() {
    let model = slab_and_block(0.6, 0.5, (0.8, 1.2, 0.0));
    let r = run(&model, (0.5, 2.5, 0.0), 4.0);
    assert_eq!(r.summary.duration_s, 4.0, "{:?}", r.summary.warnings);
    let landed = (r.events.iter())
        .any(|e| e.kind == EventKind::BlocksImpact && (e.time_s - 1.125_498_676_6).abs() < 1e-9);
    assert!(landed, "{:#?}", r.events);
    whole(&r, (0.8, 1.2));
}

/// The slab touching a block 1.2 x 1.2 m (friction 0.9, restitution 0.5) under a 0.3 g sine at
/// 1 Hz: at 0.6122 s the slab comes down flat on the block, upright on its base, and the contact
/// that stays is at the two bottom corners, both bodies rocking on stuck pivots after it, which
/// the push there turns neither: as neither body's own motion closes it, it holds no push and
/// each goes on alone. At 0.6139 s the block lands on its base with the slab's corner again on
/// its face at that point, the slab rocking on its corner there after the landing (left rising
/// by 1e-19 m/s): no way of the pivots holds with a push, and the run stopped; there the slab's
/// pivot stays on the ground, no push moves either body and their motions alone keep the
/// contact, so it carries nothing and each goes on alone again (`Couple::unpushed`). The run
/// goes on to 1.6139 s, where the two rattle; followed here to 1.6 s, without a warning.
#[test]
fn a_contact_at_a_corner_both_blocks_turn_about_holds_no_push() {
    let model = slab_and_block(0.9, 0.5, (1.2, 1.2, 0.0));
    let r = to_end(&model, (0.3, 1.0, 0.0), 1.6);
    let holds: Vec<f64> = (r.events.iter())
        .filter(|e| {
            e.mode.as_ref().is_some_and(|m| {
                m.contains("their contact is at a corner both turn about, where it holds no push")
            })
        })
        .map(|e| e.time_s)
        .collect();
    assert!(holds.len() >= 2, "{:#?}", r.events);
    assert!((holds[0] - 0.612_2).abs() < 1e-3, "{holds:?}");
    let lands = 0.613_885_586_8;
    assert!(holds.iter().any(|t| (t - lands).abs() < 1e-9), "{holds:?}");
    whole(&r, (1.2, 1.2));
}

/// The slab touching a block 0.5 x 0.9 m (friction 0.9, no restitution) under a 0.5 g sine at
/// 2.5 Hz: from 0.34740 s both rock on their right corners, the block's corner on the slab's
/// face, and each blow there lifts the block's pivot off the ground by a tenth of the blow's
/// rate, the block landing 1e-5 s later and striking again: a series of blows accumulating at
/// 0.3474702928 s. Its last blow leaves the block rising by round-off (5e-11 m/s), a round-off
/// above the ground: it is on the ground, and lands there with the contact (both contacts
/// plastic at once). Before, only a flight coming down landed so: the block stayed in flight,
/// and as it would land no mode of the pivots held with the contact and the run stopped there.
#[test]
fn a_flight_of_round_off_rising_at_a_ties_rate_lands_with_the_contact() {
    let model = slab_and_block(0.9, 0.0, (0.5, 0.9, 0.0));
    let r = to_end(&model, (0.5, 2.5, 0.0), 4.0);
    let lands = (r.events.iter()).find(|e| {
        e.mode.as_deref().is_some_and(|m| {
            m.contains("W lands from free flight on its right corner in contact with S, both")
        })
    });
    let lands = lands.unwrap_or_else(|| panic!("{:#?}", r.events));
    assert!(
        (lands.time_s - 0.347_470_292_8).abs() < 1e-9,
        "{}",
        lands.time_s
    );
    whole(&r, (0.5, 0.9));
}

/// The slab touching a block 1.2 x 0.9 m (friction 0.6, no restitution) under a 0.5 g sine at
/// 2.5 Hz: at 0.3715324 s the block's corner strikes the slab's face (they have not parted since
/// their last impact), and the blow leaves the block, which had lifted off its seat by 2.5e-12
/// rad, turning down onto it at -2.9e-5 rad/s: a round-off from landing on its base, every way
/// of the pivots broke at once (the block would land), and the run stopped. The block keeps the
/// mode the blow left it in and lands at once with the contact (both contacts plastic at once),
/// and the run goes to its end.
#[test]
fn a_blow_that_leaves_a_body_a_round_off_from_its_seat_lands_it_with_the_contact() {
    let model = slab_and_block(0.6, 0.0, (1.2, 0.9, 0.0));
    let r = to_end(&model, (0.5, 2.5, 0.0), 4.0);
    let blow = (r.events.iter()).position(|e| {
        e.kind == EventKind::BlocksImpact && (e.time_s - 0.371_532_420_4).abs() < 1e-9
    });
    let blow = blow.unwrap_or_else(|| panic!("{:#?}", r.events));
    let lands = &r.events[blow + 1];
    assert_eq!(lands.time_s, r.events[blow].time_s);
    assert!(
        (lands.mode.as_deref()).is_some_and(|m| {
            m.starts_with("W lands on its base in contact with S, both contacts plastic at once")
        }),
        "{lands:#?}"
    );
    whole(&r, (1.2, 0.9));
}

/// The slab touching a block 1.2 x 1.2 m (friction 0.6, no restitution) under a 0.5 g sine at
/// 2.5 Hz: at 0.3578 s the slab, whose face lies on the block's, comes down from free flight
/// upright but for round-off, on both corners of its base at once. That landing stopped the run
/// ("not followed with the faces' contacts"); the landing's law now takes both corners with the
/// faces' contacts, and the run goes to its end (scan run 1606).
#[test]
fn a_flight_upright_by_round_off_lands_flat_with_lying_faces() {
    let model = slab_and_block(0.6, 0.0, (1.2, 1.2, 0.0));
    let r = to_end(&model, (0.5, 2.5, 0.0), 4.0);
    whole(&r, (1.2, 1.2));
}

/// The slab touching a block 0.8 x 0.9 m (friction 0.9, no restitution) under El Centro at
/// 0.4 g (scan run 1604): at 2.3265067 s both bodies, rocking on their left corners with the
/// slab's face lying on the block's, come down on their bases at the same instant. That landing
/// stopped the run ("the other body lands at the same instant, which is not followed"); the
/// landing's law now takes both bodies' ground contacts with both ends of the faces, plastic at
/// once. A body then left at its seat, theta exactly zero, turning through it on its pivot (a
/// contact's round-off closed by its rotation) lands there, where the run ended in an error
/// (its tilt times its rotation, zero, read as not closing). The run goes on: to 2.4 s without a
/// warning, never overlapping, its balance closing.
#[test]
fn both_bodies_under_lying_faces_land_on_their_bases_at_once() {
    let model = slab_and_block(0.9, 0.0, (0.8, 0.9, 0.0));
    let r = el_centro_to_end(&model, 0.4, 2.4);
    let both = "S lands on its base and W lands on its base while S's face lies on W's, the four \
                contacts plastic at once";
    let landings: Vec<_> = (r.events.iter())
        .filter(|e| e.mode.as_deref().is_some_and(|m| m.starts_with(both)))
        .collect();
    assert_eq!(landings.len(), 2, "{:#?}", r.events);
    assert!(
        (landings[0].time_s - 2.326_506_684).abs() < 1e-9,
        "{}",
        landings[0].time_s
    );
    assert!(landings.iter().all(|e| e.time_s == landings[0].time_s));
    whole(&r, (0.8, 0.9));
}

/// The slab touching a block 0.8 x 0.9 m (friction 0.6, restitution 0.5) under a 0.5 g sine at
/// 2.5 Hz (scan run 1646): at 1.1839629 s the slab comes down flat on the block, upright on its
/// base, the block's top corner strikes its face and parts, and the contact that stays is at the
/// two bottom corners, on the line through both pivots (the slab seated, the block turning on
/// its far corner): a push there turns neither body, and their motions alone close it. The run
/// stopped there ("the contact's push has no moment about a body's pivot"). The mode is now
/// decided among the ways a pivot slips or lifts, where such a push does move a body (here the
/// block's pivot slipping, the one way that holds), a way whose push moves neither body holding
/// no contact; its push falls at once and the two part. The run goes on to 1.5 s (it stops at
/// 1.5416 s, where no mode holds with a contact after another flat landing), never
/// overlapping, its balance closing.
#[test]
fn a_contact_on_the_line_through_both_pivots_that_closes_slips_a_pivot() {
    let model = slab_and_block(0.6, 0.5, (0.8, 0.9, 0.0));
    let r = to_end(&model, (0.5, 2.5, 0.0), 1.5);
    let at = |e: &crate::response::EventRecord| (e.time_s - 1.183_962_86).abs() < 1e-9;
    let slips = (r.events.iter()).find(|e| {
        e.kind == EventKind::BlocksImpact
            && at(e)
            && e.mode.as_ref().is_some_and(|m| {
                m.contains("W: theta' 0.000000e0 -> 4.187213e-1 rad/s, slipping at")
            })
    });
    assert!(slips.is_some(), "{:#?}", r.events);
    let parts = (r.events.iter()).any(|e| e.kind == EventKind::Separation && at(e));
    assert!(parts, "{:#?}", r.events);
    whole(&r, (0.8, 0.9));
}

/// A slab 0.3 x 1.2 m touching a block 0.5 x 1.2 m (friction 0.9, restitution 0.5) under 0.3 g
/// at 1 Hz (scan run 1625): at 0.9368795 s the slab, tipping onto the block after a series of
/// landings, brings its top corner to the block's, the two corners one point to the bit (the
/// slab's a round-off below the block's top). Each corner lies on the other's two faces there,
/// and the run stopped ("two corners meet"). On the top faces neither corner is a contact (each
/// block lies below the other's top); on the side faces both cross the line at first order
/// alike, and the block's corner moves in along the slab's face faster (at second order), so it
/// strikes: the contact whose corner goes in across its face fastest and, of those, along it
/// first. The blocks part at once and the run goes on to its end, never overlapping, its
/// balance closing.
#[test]
fn two_corners_at_one_point_strike_where_one_goes_in_fastest() {
    let model = slab_and_block(0.9, 0.5, (0.5, 1.2, 0.0));
    let r = to_end(&model, (0.3, 1.0, 0.0), 4.0);
    let strikes = (r.events.iter()).any(|e| {
        e.kind == EventKind::BlocksImpact
            && (e.time_s - 0.936_879_502).abs() < 1e-9
            && e.mode.as_ref().is_some_and(|m| {
                m.starts_with("W's corner strikes S's face at 1.183135e-4 m/s, parting")
            })
    });
    assert!(strikes, "{:#?}", r.events);
    whole(&r, (0.5, 1.2));
}

/// A slab 0.3 x 1.2 m touching a block 0.8 x 1.2 m (friction 0.6, restitution 0.5) under 0.3 g
/// at 1 Hz (scan run 1637): at 0.6540316 s, as the block lands on its near corner, the slab,
/// tilted 3.6e-6 rad onto it about its own near corner, brings its top corner to the block's,
/// 8e-12 m below it (h (1 - cos theta) with the pivots' heights), within the tie. The slab's
/// corner crosses the block's side at first order and leaves the end of that face only at
/// second order (the slab's tilt slowing); the block's corner lies beyond the end of the slab's
/// face. No corner was seen to move in from an end and the run stopped ("two corners meet");
/// the slab's corner, inside the face at the instant and crossing it before it could leave,
/// strikes, and the run goes on to its end (4 s), its balance closing, the two never
/// overlapping: at 1.7001698 s a strike of the slab's corner meets the block's landing from a
/// tilt within the tie (under 6e-12 rad), set to zero, which moved the block's face into the
/// slab's corner by 4.5e-12 m; the block's base now moves along the ground by what keeps the
/// corner where it was (`Engine::seat_shift_touching_m`).
#[test]
fn a_corner_that_crosses_a_face_at_its_end_before_it_leaves_the_end_strikes() {
    let model = slab_and_block(0.6, 0.5, (0.8, 1.2, 0.0));
    let r = to_end(&model, (0.3, 1.0, 0.0), 4.0);
    let strikes = (r.events.iter()).any(|e| {
        e.kind == EventKind::BlocksImpact
            && (e.time_s - 0.654_031_554_5).abs() < 1e-9
            && e.mode.as_ref().is_some_and(|m| {
                m.starts_with("S's corner strikes W's face at 2.696469e-6 m/s, parting")
            })
    });
    assert!(strikes, "{:#?}", r.events);
    whole(&r, (0.8, 1.2));
}

/// The slab touching the block 1.2 x 1.2 m (friction 0.6, no restitution) under El Centro at
/// 0.4 g (scan run 1608), near rest at 4.8329 s: the slab's corner held on the block's face
/// drifts a tie and a tenth off it by round-off, where a search for the pair's next event finds
/// it at once again and again. Taken as a change of the edge that keeps them apart, the search
/// stopped the run after 64 of them within one step (an error); a pair held in contact parts
/// only as the engine decides, so what the search finds for it is a meeting: the slab lands on
/// its base in contact, and both are set down. At 5.0696 s the block's face comes down flat on
/// the slab's, the block upright on its base: setting its tilt of a tie (3.2e-12 rad) to zero
/// turned its face into the slab's, by 3.8e-12 m at the top; its base now moves along the
/// ground so that neither end goes in. The run reaches its end, the blocks never overlapping
/// (by more than 1e-14 of their size), the balance closing.
#[test]
fn what_the_search_finds_for_a_held_pair_is_a_meeting() {
    use super::clearance_tests::run;
    use super::handoff_tests::el_centro;
    let model = slab_and_block(0.6, 0.0, (1.2, 1.2, 0.0));
    let r = run(&model, &el_centro(0.4), 15.0, 0.0);
    let lands = (r.events.iter()).any(|e| {
        (e.time_s - 4.832_936_52).abs() < 1e-8
            && (e.mode.as_deref())
                .is_some_and(|m| m.starts_with("S lands on its base in contact with W"))
    });
    assert!(lands, "{:#?}", r.events);
    assert_eq!(r.summary.duration_s, 15.0, "{:?}", r.summary.warnings);
    assert!(r.summary.warnings.is_empty(), "{:?}", r.summary.warnings);
    whole(&r, (1.2, 1.2));
}
