//! The state the exact model hands over where it stops following a wall (`run_to_stop`): every
//! block where the exact run's own last row has it, moving as it moves, with its energy.

use super::{Equations, Finished, Rocking};
use crate::integrate::baselines::{MoreauWall, Stepped};
use crate::integrate::{Integrator, Scenario, Settings};
use crate::model::Model;
use crate::motion::{read_record, Motion, ReadOptions};

/// El Centro 1940 (N-S) scaled to a peak of `pga_g` g.
fn el_centro(pga_g: f64) -> Motion {
    let record = read_record(
        std::path::Path::new("records/elcentro1940_IELC180_peer_dt0p01_g.AT2"),
        None,
        &ReadOptions::default(),
    )
    .unwrap();
    Motion::Record(record.scaled(pga_g * 9.81 / record.pga_m_s2()).unwrap())
}

/// The three ways the exact model stops, each on its wall: a chain's pivot lifting off (the
/// two-block column), a trilith's lintel slipping on its columns, a held joint slipping under a
/// rocking body (the standing stone, its plinth on little friction). The places and the
/// horizontal and angular velocities are the exact run's last row's to round-off; the vertical
/// velocities, which no row carries, keep a corner turning on a support that stays put at rest,
/// and give the exact run's energy; and Moreau-Jean, going on from the state, changes no
/// velocity by more than a few g times the time it runs (the state it starts from is one its
/// contacts accept, not one an impulse must mend).
#[test]
fn a_hand_off_places_every_block_where_the_exact_run_leaves_it() {
    let stone = Model::from_ron_str(
        r#"(
    version: 1,
    name: "Standing stone on a plinth of little friction",
    thickness_m: 0.45,
    density_kg_m3: 2650,
    friction: 0.8,
    joint_friction: {"Plinth/ground": 0.3},
    rows: [
        (height_m: 0.4, blocks: [(width_m: 1.4, name: "Plinth")]),
        (height_m: 2.8, x_m: 0.4, blocks: [(width_m: 0.6, name: "Huanca")]),
    ],
)"#,
    )
    .unwrap();
    let column = Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let trilith = Model::from_file("walls/rocking/trilith.ron").unwrap();
    let rocking = Rocking {
        equations: Equations::Exact,
        initial_rotation_rad: 0.0,
    };
    for (model, pga_g, how) in [
        (&column, 0.5, "would lift off"),
        (&trilith, 0.5, "would slip"),
        (&stone, 0.5, "Plinth/ground would slip"),
    ] {
        let (wall, motion) = (model.wall(), el_centro(pga_g));
        let settings = Settings {
            output_dt_s: Some(1e-3),
            ..Settings::summary_only(20.0)
        };
        let sc = Scenario {
            wall,
            topology: model.topology(),
            motion: &motion,
            settings: &settings,
        };
        let exact = rocking.run(&sc).unwrap();
        let Finished::Stopped(h, why) = rocking.run_to_stop(&sc).unwrap() else {
            panic!("{}: the exact model runs to the end", wall.name);
        };
        assert!(why.contains(how), "{}: {why}", wall.name);
        assert_eq!(h.t_s, exact.summary.duration_s);
        let history = exact.history.as_ref().unwrap();
        let last = history.time_s.len() - 1;
        assert_eq!(history.time_s[last], h.t_s);
        // The exact run's last row from the state handed over (the centroid's place and
        // velocity, the rotation counter-clockwise): the base's middle lies half the height
        // below the centroid along the block's axis.
        let g = wall.g_m_s2.to_f64();
        let (mut mechanical, mut scale, mut checked) = (0.0, 0.0, 0);
        for (i, b) in wall.blocks.iter().enumerate() {
            let t = &h.turned[i];
            let half = 0.5 * b.height.to_f64();
            let (sin, cos) = t.phi_rad.sin_cos();
            let row = |x: &Vec<Vec<f64>>| x[last][i];
            let near = |a: f64, b: f64, size: f64| (a - b).abs() <= 1e-12 * size;
            let place = [
                (h.u_m[i] + half * sin, row(&history.displacement_m)),
                (t.rise_m + half * (1.0 - cos), row(&history.lift_m)),
                (-t.phi_rad, row(&history.rotation_rad)),
            ];
            for (handed, written) in place {
                assert!(
                    near(handed, written, 1.0),
                    "{} {}: {handed} {written}",
                    wall.name,
                    b.name
                );
            }
            let rate = [
                (
                    h.v_m_s[i] + half * cos * t.omega_rad_s,
                    row(&history.velocity_m_s),
                ),
                (-t.omega_rad_s, row(&history.angular_velocity_rad_s)),
            ];
            for (handed, written) in rate {
                assert!(
                    near(handed, written, 1.0),
                    "{} {}: {handed} {written}",
                    wall.name,
                    b.name
                );
            }
            // A bottom corner left at the level it rests on at rest turns on a support that
            // does not move up or down (the ground, a held block): it does not either.
            let mut pivots = 0;
            for x in [-0.5, 0.5].map(|s| s * b.width.to_f64()) {
                let (rx, ry) = (x * cos + half * sin, x * sin - half * cos);
                if (t.rise_m + ry + half).abs() < 1e-9 {
                    pivots += 1;
                    let up = t.rise_m_s + t.omega_rad_s * rx;
                    assert!(up.abs() < 1e-12, "{} {}: {up} m/s", wall.name, b.name);
                }
            }
            checked += usize::from(pivots == 1);
            let mass = model.topology().blocks[i].mass_kg.to_f64();
            let inertia = mass * (b.width.to_f64().powi(2) + b.height.to_f64().powi(2)) / 12.0;
            let (vx, vy, w) = (h.v_m_s[i], t.rise_m_s, t.omega_rad_s);
            let kinetic = 0.5 * mass * (vx * vx + vy * vy) + 0.5 * inertia * w * w;
            mechanical += kinetic + mass * g * t.rise_m;
            scale += kinetic + mass * g * half;
        }
        assert!(checked > 0, "{}: no block turning on a corner", wall.name);
        // The vertical velocities, which the rows do not carry, through the energy: the exact
        // run's own kinetic and potential energy at the stop.
        let e = &exact.summary.energy;
        for total in [h.mechanical_j, e.kinetic_j + e.potential_j] {
            assert!(
                (mechanical - total).abs() <= 1e-12 * scale,
                "{}: {mechanical} {total}",
                wall.name
            );
        }
        // The stop is the hand-over's event, not a warning of where the run ended.
        assert!(
            !h.rec
                .warnings
                .iter()
                .any(|w| w.to_string().contains("stops there")),
            "{}",
            wall.name
        );
        let (t0, dt) = (h.t_s, 1e-4);
        let on = Settings {
            output_dt_s: Some(1e-3),
            ..Settings::summary_only(t0 + 2e-3)
        };
        let sc = Scenario {
            settings: &on,
            ..sc
        };
        let Stepped::Ended(stepped) = MoreauWall::new(dt).run_from(&sc, *h, None).unwrap() else {
            panic!("set down");
        };
        let rows = stepped.history.as_ref().unwrap();
        let k = rows.time_s.iter().position(|&t| t > t0).unwrap();
        let elapsed = rows.time_s[k] - t0;
        let accel = 3.0 * (g + pga_g * g);
        for (i, b) in wall.blocks.iter().enumerate() {
            let half = 0.5 * b.height.to_f64();
            let dv = rows.velocity_m_s[k][i] - history.velocity_m_s[last][i];
            let dw = rows.angular_velocity_rad_s[k][i] - history.angular_velocity_rad_s[last][i];
            assert!(
                dv.abs() <= accel * elapsed && dw.abs() * half <= accel * elapsed,
                "{} {}: {dv} m/s, {dw} rad/s in {elapsed} s",
                wall.name,
                b.name
            );
        }
    }
}
