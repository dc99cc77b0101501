//! `--after-uplift moreau-while-rocking`, on the slab beside the block of `hand_off.rs`: the
//! exact sliding run up to an uplift, Moreau-Jean with every block's rotation while anything
//! rocks, and the exact sliding run again from where every block is seated and calm, set down
//! flat. The stepping is the same step for step as the stepping that runs to the end, until the
//! wall is set down; from there nothing moves on still ground, every rotation is zero, and the
//! stepping's answer is kept to round-off at a fraction of its steps; under a sine the wall is
//! handed back and forth, and where its blocks end settles as the step falls; fillers that
//! rattle between monoliths are set down where the exact model keeps them seated.

use super::hand_off::{history, pair, settings};
use crate::engine::el_centro_first_s;
use pirqa::motion::{Motion, Record, Sine};
use pirqa::response::EventKind;
use pirqa::{AfterUplift, Response, RunSettings};

const G: f64 = 9.81;

/// The ground acceleration rising linearly to 3.5 m/s2 at 0.4 s, back to zero at 0.8 s, then
/// still to 3 s: S lifts on the way up, at g/4 / 3.5 * 0.4 s.
fn pulse() -> Motion {
    let rise: Vec<f64> = (0..=40).map(|k| 3.5 * k as f64 / 40.0).collect();
    let samples = rise
        .iter()
        .chain(rise.iter().rev().skip(1))
        .copied()
        .chain(std::iter::repeat_n(0.0, 220))
        .collect();
    Motion::Record(Record::new("pulse", 0.01, samples).unwrap())
}

/// The stretches `model.why` lists, as (from, to) in s; `to` is `None` for one that ran to the
/// end.
fn stretches(r: &Response) -> Vec<(f64, Option<f64>)> {
    let why = &r.summary.model.why;
    let (_, after) = why.split_once("stretches stepped (").unwrap();
    let (_, list) = after.split_once("): ").unwrap();
    let list = list.split("; ").next().unwrap();
    list.split(", ")
        .filter(|s| !s.ends_with("more"))
        .map(|s| {
            let s = s.trim_end_matches(" s");
            match s.split_once(" to ") {
                Some((a, "the end")) | Some((a, "the end s")) => (a.parse().unwrap(), None),
                Some((a, b)) => (a.parse().unwrap(), Some(b.parse().unwrap())),
                None => panic!("{why}"),
            }
        })
        .collect()
}

/// Every history row strictly between a set-down and the next uplift is unturned, and each
/// stretch begins strictly after the set-down before it (a wall set down where the exact model
/// lifts a block at once would begin it at the same instant).
fn unturned_between(r: &Response, spans: &[(f64, Option<f64>)]) {
    let h = history(r);
    for w in spans.windows(2) {
        let (Some(set_down), next) = (w[0].1, w[1].0) else {
            panic!("{spans:?}");
        };
        assert!(set_down < next, "{spans:?}");
        let rows = (h.time_s.iter().enumerate()).filter(|(_, &t)| t > set_down && t < next);
        for (k, _) in rows {
            assert!(h.rotation_rad[k].iter().all(|&x| x == 0.0), "{k}");
        }
    }
}

/// The Ollantaytambo wall under the first `seconds` of El Centro scaled to `pga_g` g, time
/// stepped with step `dt_s` while its blocks rock.
fn ollantaytambo(seconds: usize, pga_g: f64, dt_s: f64) -> Response {
    let wall = pirqa::Model::from_file("walls/inca/ollantaytambo-monoliths.ron").unwrap();
    let motion = el_centro_first_s(seconds, pga_g * G);
    let after_uplift = AfterUplift::MoreauWhileRocking { dt_s };
    pirqa::run(&wall, &motion, &settings(seconds as f64, after_uplift)).unwrap()
}

#[test]
fn a_block_that_rocks_and_settles_gives_the_wall_back_to_the_exact_model() {
    let dt = 1e-3;
    let back = pirqa::run(
        &pair(),
        &pulse(),
        &settings(3.0, AfterUplift::MoreauWhileRocking { dt_s: dt }),
    )
    .unwrap();
    let on = pirqa::run(
        &pair(),
        &pulse(),
        &settings(3.0, AfterUplift::Moreau { dt_s: dt }),
    )
    .unwrap();
    assert_eq!(back.summary.method, "event+moreau");
    assert_eq!(back.summary.model.name, "slide-rock");
    // The first uplift is the check's, at g/4 on the rise; the stepping stops once S has
    // landed and every block has been still for ten steps, well before the end.
    let t_u = (G / 4.0) / 3.5 * 0.4;
    let uplift = back.summary.uplift_check.as_ref().unwrap();
    let first = uplift.first_uplift.as_ref().unwrap();
    assert!((first.time_s - t_u).abs() <= 1e-12, "{}", first.time_s);
    assert_eq!(Some(uplift), on.summary.uplift_check.as_ref());
    let spans = stretches(&back);
    assert_eq!(spans.len(), 1, "{}", back.summary.model.why);
    let (from, to) = spans[0];
    let to = to.expect("set down before the end");
    assert_eq!(from, first.time_s);
    assert!(to > 0.8 && to < 2.0, "{to}");
    // Both hand-overs in the event log: S lifting, and the wall set down with the blocks that
    // rocked (W, struck by S, turned a little too under the stepping).
    let handed: Vec<(EventKind, f64, Vec<String>)> = (back.events.iter())
        .filter(|e| matches!(e.kind, EventKind::Uplift | EventKind::Rest))
        .map(|e| (e.kind, e.time_s, e.blocks.clone()))
        .collect();
    assert_eq!(
        handed,
        [
            (EventKind::Uplift, from, vec!["S".to_string()]),
            (EventKind::Rest, to, vec!["S".to_string(), "W".to_string()]),
        ]
    );
    // Step for step the stepping that runs on, up to the set-down: its steps, and its rows.
    let steps = ((to - from) / dt).round() as u64;
    assert_eq!(back.summary.stats.steps, steps);
    assert!(2 * steps < on.summary.stats.steps);
    let (hb, ho) = (history(&back), history(&on));
    let before = hb.time_s.iter().take_while(|&&t| t <= to).count();
    assert_eq!(hb.time_s[..before], ho.time_s[..before]);
    assert_eq!(hb.displacement_m[..before], ho.displacement_m[..before]);
    assert_eq!(hb.velocity_m_s[..before], ho.velocity_m_s[..before]);
    assert_eq!(hb.rotation_rad[..before], ho.rotation_rad[..before]);
    assert!(hb.rotation_rad[..before]
        .iter()
        .flatten()
        .any(|&x| x.abs() > 0.04));
    // From there the exact sliding model: on still ground nothing moves, nothing turns.
    let last = hb.displacement_m.last().unwrap().clone();
    assert_eq!(*hb.time_s.last().unwrap(), 3.0);
    for k in before..hb.time_s.len() {
        assert_eq!(hb.displacement_m[k], last);
        assert!(hb.velocity_m_s[k].iter().all(|&v| v == 0.0));
        assert!(hb.rotation_rad[k].iter().all(|&x| x == 0.0));
    }
    // Set down where the stepping had the middles of the bases: it keeps them still to
    // round-off, and ends where the set-down started.
    for (i, b) in back.summary.blocks.iter().enumerate() {
        let stepped = on.summary.blocks[i].final_displacement_m;
        assert!(
            (b.final_displacement_m - stepped).abs() <= 1e-15,
            "{} {} {stepped}",
            b.name,
            b.final_displacement_m
        );
        assert_eq!(
            b.max_abs_rotation_rad,
            on.summary.blocks[i].max_abs_rotation_rad
        );
    }
    // The energy: what the stepping and the set-down took are the contacts' share, so the
    // balance closes as the exact parts close it, to round-off.
    let e = &back.summary.energy;
    assert!(e.residual_j.abs() <= 1e-12 * e.input_j.abs(), "{e:?}");
    assert_eq!((e.kinetic_j, e.potential_j), (0.0, 0.0));
}

#[test]
fn under_a_sine_the_wall_is_handed_back_and_forth_and_its_answer_settles_as_the_step_falls() {
    let sine = Motion::sine(Sine {
        amplitude_m_s2: 0.3 * G,
        frequency_hz: 1.0,
        duration_s: 6.0,
        ..Sine::default()
    })
    .unwrap();
    let run = |after_uplift| pirqa::run(&pair(), &sine, &settings(6.0, after_uplift)).unwrap();
    let mut ends = Vec::new();
    for dt_s in [2.5e-4, 1e-4, 5e-5] {
        let back = run(AfterUplift::MoreauWhileRocking { dt_s });
        // S lifts in every half cycle past g/4: stepped while it rocks, exact between.
        let spans = stretches(&back);
        assert!(spans.len() >= 4, "{}", back.summary.model.why);
        unturned_between(&back, &spans);
        let e = &back.summary.energy;
        assert!(e.residual_j.abs() <= 1e-12 * e.input_j.abs(), "{e:?}");
        if dt_s == 1e-4 {
            // The largest rocking is the first stretch's, stepped as the stepping that runs on
            // steps it; the rest costs fewer steps.
            let on = run(AfterUplift::Moreau { dt_s });
            let (a, b) = (&back.summary.blocks[0], &on.summary.blocks[0]);
            let rotation = a.max_abs_rotation_rad;
            assert!(rotation > 0.012, "{rotation}");
            assert!((rotation - b.max_abs_rotation_rad).abs() <= 1e-12 * rotation);
            assert!(4 * back.summary.stats.steps < 3 * on.summary.stats.steps);
        }
        ends.push(back.summary.blocks[0].final_displacement_m);
    }
    // Where S ends: 4.952, 4.918 and 4.909 mm (set down each time, the stepping's drift does
    // not build up from one stretch to the next; docs/rocking-walls.md).
    let (lo, hi) = (
        ends.iter().copied().fold(f64::MAX, f64::min),
        ends.iter().copied().fold(0.0, f64::max),
    );
    assert!(lo > 4e-3 && hi - lo < 1e-2 * lo, "{ends:?}");
}

#[test]
fn what_cannot_hand_back_is_refused_as_what_cannot_hand_off() {
    let while_rocking = AfterUplift::MoreauWhileRocking { dt_s: 1e-3 };
    let e = pirqa::run(
        &pair(),
        &pulse(),
        &RunSettings {
            method: pirqa::Method::Paper { dt_s: 1e-3 },
            ..settings(1.0, while_rocking)
        },
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("--method chooses another integrator"), "{e}");
    let e = pirqa::run(
        &pair(),
        &pulse(),
        &settings(1.0, AfterUplift::MoreauWhileRocking { dt_s: 0.0 }),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("time step"), "{e}");
}

#[test]
fn a_block_that_falls_while_stepped_is_gone_and_the_rest_is_set_down_without_it() {
    // A rectangular pulse of 0.35 g for 0.4 s overturns S; with --after-collapse continue W
    // comes to rest and the exact model has it, alone, from there.
    let pulse = Motion::pulse(pirqa::motion::Pulse {
        amplitude_m_s2: 0.35 * G,
        duration_s: 0.4,
    })
    .unwrap();
    let r = pirqa::run(
        &pair(),
        &pulse,
        &RunSettings {
            after_collapse: pirqa::AfterCollapse::Continue,
            ..settings(4.0, AfterUplift::MoreauWhileRocking { dt_s: 1e-3 })
        },
    )
    .unwrap();
    let collapse = r.summary.collapse.as_ref().expect("S falls");
    assert_eq!(collapse.block, "S");
    assert!(r.summary.blocks[0].fell && !r.summary.blocks[1].fell);
    let spans = stretches(&r);
    assert_eq!(spans.len(), 1, "{}", r.summary.model.why);
    let to = spans[0].1.expect("W set down before the end");
    assert!(to > collapse.time_s && to < 4.0, "{to}");
    let rest = (r.events.iter())
        .find(|e| e.kind == EventKind::Rest)
        .expect("a set-down");
    // The set-down lists the blocks still standing that rocked: S is gone, W never lifted.
    assert_eq!((rest.time_s, rest.blocks.len()), (to, 0));
    // From there W is the exact model's, at rest on still ground.
    let h = history(&r);
    let last = h.displacement_m.last().unwrap()[1];
    for k in (0..h.time_s.len()).filter(|&k| h.time_s[k] > to) {
        assert_eq!(h.displacement_m[k][1], last);
        assert_eq!(h.rotation_rad[k][1], 0.0);
    }
    assert_eq!(*h.time_s.last().unwrap(), 4.0);
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-12 * e.input_j.abs(), "{e:?}");
}

/// The Ollantaytambo wall under El Centro at 0.3 g, its first 12 s: its fillers rock, and the
/// stepper leaves two of them never still (F2's velocity flips sign at every step with its pose
/// frozen, F5 rattles between M5 and M6 at about 60 Hz, micrometres high), yet calm: the wall is
/// set down and handed back between stretches, each set-down where the exact model keeps every
/// block seated (the next stretch begins strictly later: a wall set down where the exact model
/// lifts a block at once would begin it at the same instant), at a fraction of the steps of
/// the stepping that runs on (docs/rocking-walls.md).
#[test]
fn the_ollantaytambo_fillers_that_rattle_are_set_down_where_the_exact_model_keeps_them_seated() {
    let dt = 1e-3;
    let r = ollantaytambo(12, 0.3, dt);
    let spans = stretches(&r);
    assert!(spans.len() >= 3, "{}", r.summary.model.why);
    unturned_between(&r, &spans);
    // The first uplift is the sliding run's, F5's at 2.13 s (the uplift check's test in cli.rs).
    let from = spans[0].0;
    assert!((from - 2.13).abs() < 0.01, "{from}");
    let stepped_on = ((12.0 - from) / dt).round() as u64;
    assert!(
        2 * r.summary.stats.steps < stepped_on,
        "{}",
        r.summary.stats.steps
    );
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-12 * e.input_j.abs(), "{e:?}");
}

/// The Ollantaytambo wall under El Centro at 0.4 g, dt = 2.5e-4 s: at 9.147 s the set-down
/// placed F2-F3 from M2 and M4-F5 from M4, which pushed F3, closing on M4, 1.4e-6 m into it;
/// the exact engine, started there, found that face closing at every event of its first
/// instant and stopped with "no progress". Faces the placement pushes into each other are now
/// closed, and the exact engine refuses an overlapping state by name: started from every
/// set-down state it goes on (there, F3 strikes M4 at once, after which the uplift check finds
/// F2 to F5 turning, so stepping goes on and sets the wall down ten steps later), and the run
/// ends.
#[test]
fn the_exact_model_goes_on_from_every_set_down_of_the_ollantaytambo_wall() {
    let r = ollantaytambo(10, 0.4, 2.5e-4);
    let rests: Vec<f64> = (r.events.iter())
        .filter(|e| e.kind == EventKind::Rest)
        .map(|e| e.time_s)
        .collect();
    assert!(
        rests.iter().any(|&t| (t - 9.14966).abs() < 1e-5),
        "{rests:?}"
    );
    let why = &r.summary.model.why;
    let (_, count) = why.split_once("stretches stepped (").unwrap();
    let count: usize = count.split(')').next().unwrap().parse().unwrap();
    assert!(count >= 10, "{why}");
    let e = &r.summary.energy;
    assert!(e.residual_j.abs() <= 1e-12 * e.input_j.abs(), "{e:?}");
}
