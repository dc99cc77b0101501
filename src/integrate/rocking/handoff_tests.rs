//! The state the exact model hands over where it stops following a wall (`run_to_stop`): every
//! block where the exact run's own last row has it, moving as it moves, with its energy.

use super::{Equations, Finished, Rocking};
use crate::integrate::baselines::{MoreauWall, Stepped};
use crate::integrate::{AfterCollapse, Integrator, Scenario, Settings};
use crate::model::Model;
use crate::motion::{read_record, Motion, ReadOptions, Sine};

/// El Centro 1940 (N-S) scaled to a peak of `pga_g` g.
pub(super) fn el_centro(pga_g: f64) -> Motion {
    let record = read_record(
        std::path::Path::new(crate::motion::EL_CENTRO),
        None,
        &ReadOptions::default(),
    )
    .unwrap();
    Motion::Record(record.scaled(pga_g * 9.81 / record.pga_m_s2()).unwrap())
}

/// Moreau-Jean's step after a hand-off (s).
const STEP_S: f64 = 1e-4;

const EXACT: Rocking = Rocking {
    equations: Equations::Exact,
    initial_rotation_rad: 0.0,
};

/// Runs `model` under `motion` for `duration_s` exactly, and again to where the exact model
/// stops, if it does, then on by Moreau-Jean for 2 ms. The state handed over must be the one
/// the run's row at the stop shows (places, rotations, horizontal and angular velocities) to
/// round-off; each corner turning on a support that stays put at rest must have no vertical
/// velocity, and the kinetic and potential energy must be the engine's (the vertical
/// velocities, which no row carries). The rows up to the stop, and the row at the stop, are the
/// exact run's. Where the exact model stopped at a landing whose impulse a held joint could not
/// pass, that row and the state are the ones just before the impact, for the time stepping to
/// resolve it; at any other stop (but one where a corner comes down on the face under it before
/// the stepper's next row) Moreau-Jean, going on from the state, must change no velocity by more than three times
/// (g + peak ground acceleration) times the time it runs (a state its contacts accept, not one
/// an impulse must mend). Returns why the exact model stopped, and
/// whether it stopped at a landing.
fn handed_over(
    model: &Model,
    motion: &Motion,
    duration_s: f64,
    pga_m_s2: f64,
) -> Option<(String, bool)> {
    let wall = model.wall();
    let settings = Settings {
        output_dt_s: Some(1e-3),
        log_events: true,
        ..Settings::summary_only(duration_s)
    };
    let sc = Scenario {
        wall,
        topology: model.topology(),
        motion,
        settings: &settings,
    };
    let exact = EXACT.run(&sc).unwrap();
    let Finished::Stopped(h, why) = EXACT.run_to_stop(&sc).unwrap() else {
        assert!(
            !exact
                .summary
                .warnings
                .iter()
                .any(|w| w.to_string().contains("stops there")),
            "{}: stopped, not handed over",
            wall.name
        );
        return None;
    };
    let name = &wall.name;
    let t0 = h.t_s;
    assert_eq!(t0, exact.summary.duration_s, "{name}");
    let at_landing = why.contains("under the impulse of the landing");
    // At a landing whose impulses it cannot resolve the exact model stops just before the
    // impact; where it resolved one, what it stops at comes after.
    assert!(
        !at_landing
            || !exact
                .events
                .iter()
                .any(|e| e.time_s == t0 && e.kind == crate::response::EventKind::RockingImpact),
        "{name}"
    );
    // The stop is the hand-over's event, not a warning of where the run ended.
    assert!(
        !h.rec
            .warnings
            .iter()
            .any(|w| w.to_string().contains("stops there")),
        "{name}"
    );
    let g = wall.g_m_s2.to_f64();
    let (state, mechanical_j) = (
        (h.u_m.clone(), h.v_m_s.clone(), h.turned.clone()),
        h.mechanical_j,
    );
    let gone = h.fallen.clone();
    // Every block stepped on, those that fall gone.
    let on = Settings {
        output_dt_s: Some(1e-3),
        after_collapse: AfterCollapse::Continue,
        ..Settings::summary_only(t0 + 2e-3)
    };
    let stepping = Scenario {
        settings: &on,
        ..sc
    };
    let Stepped::Ended(stepped) = MoreauWall::new(STEP_S)
        .run_from(&stepping, *h, None)
        .unwrap()
    else {
        panic!("{name}: set down");
    };
    let (rows, history) = (
        stepped.history.as_ref().unwrap(),
        exact.history.as_ref().unwrap(),
    );
    let last = history.time_s.len() - 1;
    assert_eq!(
        (history.time_s[last], rows.time_s[last]),
        (t0, t0),
        "{name}"
    );
    let columns = |h: &crate::response::History, k: usize| {
        [
            &h.displacement_m,
            &h.velocity_m_s,
            &h.rotation_rad,
            &h.angular_velocity_rad_s,
            &h.lift_m,
        ]
        .map(|c| c[k].clone())
    };
    for k in 0..=last {
        assert_eq!(columns(rows, k), columns(history, k), "{name}: row {k}");
    }
    let (u, v, turned) = state;
    let (mut mechanical, mut scale, mut imminent) = (0.0, 0.0, false);
    // The time stepping's first row after the hand-off, which the check below reads.
    let window_s = rows.time_s.get(last + 1).map_or(0.0, |t| t - t0);
    for (i, b) in wall.blocks.iter().enumerate() {
        let t = &turned[i];
        let (half, width) = (0.5 * b.height.to_f64(), b.width.to_f64());
        let (sin, cos) = t.phi_rad.sin_cos();
        let row = |x: &Vec<Vec<f64>>| x[last][i];
        // The base's middle lies half the height below the centroid along the block's axis.
        let pairs = [
            (u[i] + half * sin, row(&rows.displacement_m)),
            (t.rise_m + half * (1.0 - cos), row(&rows.lift_m)),
            (-t.phi_rad, row(&rows.rotation_rad)),
            (v[i] + half * cos * t.omega_rad_s, row(&rows.velocity_m_s)),
            (-t.omega_rad_s, row(&rows.angular_velocity_rad_s)),
        ];
        for (handed, written) in pairs {
            let size = 1.0 + written.abs();
            assert!(
                (handed - written).abs() <= 1e-12 * size,
                "{name} {}: {handed} {written}",
                b.name
            );
        }
        // On supports that stay put (the ground, held blocks), a bottom corner left at the
        // level it rests on at rest is one it may turn on, and one of those (both, at a
        // landing) is: it does not move up or down either.
        let resting = |j: usize| {
            let s = &wall.blocks[j];
            s.y.clone() + s.height.clone() == b.y
                && s.x < b.x.clone() + b.width.clone()
                && b.x < s.x.clone() + s.width.clone()
        };
        let supports_move = (0..wall.blocks.len())
            .filter(|&j| resting(j))
            .any(|j| v[j] != 0.0 || turned[j] != Default::default());
        let ups: Vec<f64> = [-0.5 * width, 0.5 * width]
            .into_iter()
            .filter_map(|x| {
                let (rx, ry) = (x * cos + half * sin, x * sin - half * cos);
                ((t.rise_m + ry + half).abs() < 1e-9).then_some(t.rise_m_s + t.omega_rad_s * rx)
            })
            .collect();
        // A bottom corner above the face it rests on at rest (the ground's, or a block's top
        // face, moved and turned with that block) coming down on it before the stepper's next
        // row, at its speed now: an impact the stepper resolves (the exact model's next event).
        let moving = |k: usize| {
            let (b, t) = (&wall.blocks[k], &turned[k]);
            let h = 0.5 * b.height.to_f64();
            let centre = [
                b.x.to_f64() + 0.5 * b.width.to_f64() + u[k],
                b.y.to_f64() + h + t.rise_m,
            ];
            (centre, [v[k], t.rise_m_s], t.phi_rad, t.omega_rad_s, h)
        };
        // Each face: a point on it, its normal, and its block's centre, velocity and rate.
        let ground = ([0.0; 2], [0.0, 1.0], ([0.0; 2], [0.0; 2], 0.0));
        let faces: Vec<_> = if b.y.to_f64() == 0.0 {
            vec![ground]
        } else {
            (0..wall.blocks.len())
                .filter(|&j| resting(j))
                .map(|j| {
                    let (c, w, phi, omega, h) = moving(j);
                    let (s, co) = phi.sin_cos();
                    ([c[0] - h * s, c[1] + h * co], [-s, co], (c, w, omega))
                })
                .collect()
        };
        let (centre, velocity, _, omega, _) = moving(i);
        for x in [-0.5 * width, 0.5 * width] {
            let r = [x * cos + half * sin, x * sin - half * cos];
            let corner = [centre[0] + r[0], centre[1] + r[1]];
            let speed = [velocity[0] - omega * r[1], velocity[1] + omega * r[0]];
            for &(point, normal, (c, w, om)) in &faces {
                let under = [
                    w[0] - om * (corner[1] - c[1]),
                    w[1] + om * (corner[0] - c[0]),
                ];
                let gap = (corner[0] - point[0]) * normal[0] + (corner[1] - point[1]) * normal[1];
                let closing = (speed[0] - under[0]) * normal[0] + (speed[1] - under[1]) * normal[1];
                imminent |= gap > 0.0 && gap < -closing * window_s;
            }
        }
        let still = ups.iter().map(|x| x.abs()).fold(f64::INFINITY, f64::min);
        assert!(
            supports_move || ups.is_empty() || still < 1e-12,
            "{name} {}: {ups:?} m/s",
            b.name
        );
        let mass = model.topology().blocks[i].mass_kg.to_f64();
        let inertia = mass * (width * width + 4.0 * half * half) / 12.0;
        let (vx, vy, w) = (v[i], t.rise_m_s, t.omega_rad_s);
        let kinetic = 0.5 * mass * (vx * vx + vy * vy) + 0.5 * inertia * w * w;
        mechanical += kinetic + mass * g * t.rise_m;
        scale += kinetic + mass * g * half;
    }
    let e = &exact.summary.energy;
    for total in [mechanical_j, e.kinetic_j + e.potential_j] {
        assert!(
            (mechanical - total).abs() <= 1e-12 * scale,
            "{name}: {mechanical} {total}"
        );
    }
    // A block the handed state has already dropped by half its height or turned to a right
    // angle, the stepper's criterion of a fall, falls at the hand-off, whatever the step.
    let dropped: Vec<bool> = wall
        .blocks
        .iter()
        .zip(&turned)
        .zip(&gone)
        .map(|((b, t), &gone)| {
            !gone
                && (t.rise_m < -0.5 * b.height.to_f64()
                    || t.phi_rad.abs() >= std::f64::consts::FRAC_PI_2)
        })
        .collect();
    if dropped.contains(&true) {
        let fell = &stepped.summary.collapse;
        assert_eq!(fell.as_ref().map(|c| c.time_s), Some(t0), "{name}");
        for (b, &d) in stepped.summary.blocks.iter().zip(&dropped) {
            assert!(!d || b.fell, "{name} {}", b.name);
        }
    }
    // At a landing, where blocks meet, and where a corner lands within the first step, the
    // stepper's contacts resolve an impact at once.
    if !at_landing && !why.contains(" meets ") && !imminent {
        let k = last + 1;
        let bound = 3.0 * (g + pga_m_s2) * (rows.time_s[k] - t0);
        for (i, b) in wall.blocks.iter().enumerate() {
            if stepped.summary.blocks[i].fell {
                // Gone: its row is where it fell, not a velocity.
                continue;
            }
            let half = 0.5 * b.height.to_f64();
            let dv = rows.velocity_m_s[k][i] - rows.velocity_m_s[last][i];
            let dw = rows.angular_velocity_rad_s[k][i] - rows.angular_velocity_rad_s[last][i];
            assert!(
                dv.abs() <= bound && dw.abs() * half <= bound,
                "{name} {}: {dv} m/s, {dw} rad/s",
                b.name
            );
        }
    }
    Some((why, at_landing))
}

/// The ways the exact model stops, each on its wall under El Centro at 0.5 g: a chain's pivot
/// lifting off (the two-block column), a trilith's lintel slipping on its columns, a slab
/// meeting the low block beside it and staying against it (no restitution); and at 2.2 g the
/// slender top landing on the stack sliding under it, its impulse opening the ground joint, and
/// the middle block at once slipping on the base (the blocks handed over as the impact leaves
/// them).
#[test]
fn a_hand_off_places_every_block_where_the_exact_run_leaves_it() {
    let stack = Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let column = Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let trilith = Model::from_file("walls/rocking/trilith.ron").unwrap();
    let beside = Model::from_ron_str(
        "(version: 1, name: \"slab beside a low block\", thickness_m: 0.5, density_kg_m3: 2500,
          friction: 0.8, restitution: 0.0, rows: [(height_m: 2.0, blocks: [
            (width_m: 0.5, height_m: 0.3, fixed: true, name: \"B\"),
            (width_m: 0.2, gap_m: 0.05, name: \"A\")])])",
    )
    .unwrap();
    for (model, pga_g, how) in [
        (&column, 0.5, "would lift off"),
        (&trilith, 0.5, "would slip"),
        (&stack, 2.2, "Middle/Base would slip"),
        (&beside, 0.5, "B meets A"),
    ] {
        let why = handed_over(model, &el_centro(pga_g), 20.0, pga_g * 9.81);
        assert!(
            why.as_ref().is_some_and(|(w, _)| w.contains(how)),
            "{}: {why:?}",
            model.wall().name
        );
    }
}

/// Columns of two and three blocks of several proportions and frictions under sines of several
/// strengths and frequencies: wherever the exact model stops, whatever stops it, the state it
/// hands over is the exact run's (as above); the stops met include a held joint opening, a
/// stack sliding under a body that lands on it or whose pivot would slip on it, a chain's pivot
/// slipping and lifting off.
#[test]
fn every_stop_of_generated_columns_hands_over_the_exact_state() {
    let mut kinds = std::collections::BTreeMap::new();
    let (mut cases, mut landings) = (0, 0);
    for (widths, heights) in [
        (&[0.5, 0.5][..], &[1.5, 1.5][..]),
        (&[0.8, 0.4][..], &[0.6, 1.8][..]),
        (&[0.6, 0.5, 0.4][..], &[1.0, 1.2, 1.4][..]),
    ] {
        for (lower, upper) in [(0.7, 0.7), (0.3, 0.8), (0.8, 0.35)] {
            let rows: Vec<String> = widths
                .iter()
                .zip(heights)
                .enumerate()
                .map(|(k, (w, h))| {
                    // Centred on the widest: the exact model takes bodies centred on their base.
                    let x = 0.5 * (widths.iter().fold(0.0_f64, |a, &b| a.max(b)) - w);
                    format!(
                        "(height_m: {h}, x_m: {x:.3}, blocks: [(width_m: {w}, name: \"D{k}\")])"
                    )
                })
                .collect();
            let model = Model::from_ron_str(&format!(
                "(version: 1, name: \"column {cases}\", thickness_m: 0.5, density_kg_m3: 2650, \
                 friction: {upper}, joint_friction: {{\"D0/ground\": {lower}}}, rows: [{}])",
                rows.join(", ")
            ))
            .unwrap();
            for (amplitude_g, frequency_hz) in [(0.4, 0.7), (0.6, 1.0), (0.8, 1.5)] {
                cases += 1;
                let a = amplitude_g * 9.81;
                let sine = Motion::Sine(Sine {
                    amplitude_m_s2: a,
                    frequency_hz,
                    phase_rad: 0.0,
                    duration_s: 6.0,
                });
                if let Some((why, at_landing)) = handed_over(&model, &sine, 6.0, a) {
                    let kind = ["lift off", "slip", "open", "leave"]
                        .into_iter()
                        .find(|k| why.contains(k))
                        .unwrap_or("other");
                    *kinds.entry(kind).or_insert(0) += 1;
                    landings += usize::from(at_landing);
                }
            }
        }
    }
    assert!(
        kinds.len() >= 3 && kinds.values().sum::<i32>() >= 10 && landings >= 1,
        "stops by kind over {cases} cases: {kinds:?}, {landings} at a landing"
    );
}
