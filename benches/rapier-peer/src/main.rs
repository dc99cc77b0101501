//! rapier2d-f64, the game-physics engine a user might otherwise pick, on pirqa's speed-accuracy
//! chart. Blocks are dynamic boxes with rotations locked; the ground (and any abutment) is a
//! kinematic velocity-based body driven by the same ground motion; friction and restitution are
//! set per contact pair in a contact-modification hook, so the per-joint friction table of the
//! paper is honoured (no collider-level combine rule can express it): horizontal contacts get the
//! joint's mu and no restitution, vertical faces no friction and the wall's e.
//!
//! `cargo run --release -p rapier-peer -- [OUT.csv]` from the repository root writes the points
//! (same columns as `pirqa bench work-precision`), to be drawn with
//! `pirqa bench work-precision --peer OUT.csv`, and prints how rapier splits the weight of the
//! bridging block B4 between B1 and B2. `cargo run --release -p rapier-peer -- rocking [OUT.csv]`
//! does the same for the rocking panel (`pirqa bench work-precision-rocking --peer OUT.csv`),
//! with the block's rotation unlocked.

use pirqa::integrate::stepping::{lerp, outputs_in_step, Model, Observer};
use pirqa::integrate::{Integrator, Scenario};
use pirqa::response::Response;
use pirqa::study::work_precision::{self, Point};
use pirqa::topology::Base;
use rapier2d_f64::prelude::*;
use std::collections::HashMap;

/// Marks the ground in the collider map.
const GROUND: usize = usize::MAX;

struct Hook {
    block_of: HashMap<ColliderHandle, usize>,
    /// mu of (upper, lower or GROUND).
    mu: HashMap<(usize, usize), f64>,
    restitution: f64,
}

impl PhysicsHooks for Hook {
    fn modify_solver_contacts(&self, ctx: &mut ContactModificationContext) {
        let (a, b) = (self.block_of[&ctx.collider1], self.block_of[&ctx.collider2]);
        let Some(m) = ctx.rigid_mut() else { return };
        if m.normal.y.abs() > m.normal.x.abs() {
            // Horizontal joint: which one is on top decides the key.
            let upper_first = m.manifold.local_n1.y < 0.0;
            let (up, low) = if upper_first { (a, b) } else { (b, a) };
            *m.friction = self
                .mu
                .get(&(up, low))
                .or_else(|| self.mu.get(&(low, up)))
                .copied()
                .unwrap_or(0.0);
            *m.restitution = 0.0;
        } else {
            *m.friction = 0.0;
            *m.restitution = self.restitution;
        }
    }
}

/// A wall in a rapier world: blocks, the kinematic ground, the per-joint friction hook.
struct Sim {
    world: PhysicsWorld,
    hook: Hook,
    ground: RigidBodyHandle,
    /// Body, collider and initial x of each block.
    blocks: Vec<(RigidBodyHandle, ColliderHandle, f64)>,
    fixed: Vec<bool>,
    dt_s: f64,
}

impl Sim {
    fn new(sc: &Scenario, dt_s: f64) -> Sim {
        Sim::with_rotation(sc, dt_s, None)
    }

    /// A world whose blocks keep their rotations locked (`None`), or whose one block may rotate,
    /// starting at rest on a corner at rotation theta0 (clockwise, as pirqa's rocking engine).
    fn with_rotation(sc: &Scenario, dt_s: f64, theta0: Option<f64>) -> Sim {
        let (wall, topo) = (sc.wall, sc.topology);
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::new(0.0, -wall.g_m_s2.to_f64());
        world.integration_parameters.dt = dt_s;
        let hooks = ActiveHooks::MODIFY_SOLVER_CONTACTS;
        let mut block_of = HashMap::new();
        let (ground, gc) = world.insert(
            RigidBodyBuilder::kinematic_velocity_based().translation(Vector::new(0.0, -0.5)),
            ColliderBuilder::cuboid(1e3, 0.5).active_hooks(hooks),
        );
        block_of.insert(gc, GROUND);
        let mut blocks = Vec::new();
        for (i, b) in wall.blocks.iter().enumerate() {
            let (w, h) = (b.width.to_f64(), b.height.to_f64());
            let mut centre = Vector::new(b.centroid_x().to_f64(), b.y.to_f64() + h / 2.0);
            let builder = match theta0 {
                _ if b.fixed => RigidBodyBuilder::kinematic_velocity_based(),
                None => RigidBodyBuilder::dynamic()
                    .lock_rotations()
                    .can_sleep(false),
                Some(theta) => {
                    // Resting on the corner it leans on: the centre is the corner plus the
                    // corner-to-centre arm turned by phi = -theta.
                    let (phi, c) = (-theta, if theta >= 0.0 { 1.0 } else { -1.0 });
                    let (sn, cs) = phi.sin_cos();
                    let arm = (-c * w / 2.0, h / 2.0);
                    centre = Vector::new(
                        centre.x + c * w / 2.0 + cs * arm.0 - sn * arm.1,
                        b.y.to_f64() + sn * arm.0 + cs * arm.1,
                    );
                    RigidBodyBuilder::dynamic().can_sleep(false).rotation(phi)
                }
            };
            let density = topo.blocks[i].mass_kg.to_f64() / (w * h);
            let (body, c) = world.insert(
                builder.translation(centre),
                ColliderBuilder::cuboid(w / 2.0, h / 2.0)
                    .density(density)
                    .active_hooks(hooks),
            );
            block_of.insert(c, i);
            blocks.push((body, c, b.centroid_x().to_f64()));
        }
        let mut mu = HashMap::new();
        for s in &topo.horizontal {
            let lower = match s.lower {
                Base::Ground => GROUND,
                Base::Block(l) => l.0,
            };
            mu.insert((s.upper.0, lower), s.friction.to_f64());
        }
        let hook = Hook {
            block_of,
            mu,
            restitution: wall.restitution.to_f64(),
        };
        let fixed = wall.blocks.iter().map(|b| b.fixed).collect();
        Sim {
            world,
            hook,
            ground,
            blocks,
            fixed,
            dt_s,
        }
    }

    /// Step k (from (k-1) dt to k dt). The kinematic ground moves at its mean velocity over the
    /// step, so it is where the ground is at every step end; within a step it cannot follow a_g.
    fn step(&mut self, k: u64, motion: &pirqa::motion::Motion) {
        let (t0, t) = ((k - 1) as f64 * self.dt_s, k as f64 * self.dt_s);
        let vg = (motion.displacement(t) - motion.displacement(t0)) / self.dt_s;
        self.world.bodies[self.ground].set_linvel(Vector::new(vg, 0.0), true);
        for (i, b) in self.blocks.iter().enumerate() {
            if self.fixed[i] {
                self.world.bodies[b.0].set_linvel(Vector::new(vg, 0.0), true);
            }
        }
        self.world.step_with_events(&self.hook, &());
    }

    /// Vertical impulse of the last step between two blocks' colliders (N s).
    fn normal_impulse(&self, a: usize, b: usize) -> f64 {
        self.world
            .contact_pair(self.blocks[a].1, self.blocks[b].1)
            .map_or(0.0, |p| p.total_impulse().y.abs())
    }
}

/// rapier2d-f64 with a fixed step.
struct RapierPeer {
    dt_s: f64,
}

impl Integrator for RapierPeer {
    fn method(&self) -> &'static str {
        "rapier2d"
    }

    fn run(&self, sc: &Scenario) -> Result<Response, pirqa::error::SimulationError> {
        let model = Model::new(sc);
        let mut obs = Observer::new(sc, &model, sc.motion);
        let mut sim = Sim::new(sc, self.dt_s);
        let n = sc.wall.blocks.len();
        let (mut u, mut v) = (vec![0.0; n], vec![0.0; n]);
        let steps = (sc.settings.duration_s / self.dt_s).ceil() as u64;
        let ground_x0 = sim.world.bodies[sim.ground].translation().x;
        for k in 1..=steps {
            sim.step(k, sc.motion);
            let t = k as f64 * self.dt_s;
            let gx = sim.world.bodies[sim.ground].translation().x - ground_x0;
            for i in 0..n {
                let body = &sim.world.bodies[sim.blocks[i].0];
                u[i] = body.translation().x - sim.blocks[i].2 - gx;
                v[i] = body.linvel().x - sc.motion.velocity(t);
            }
            obs.step(t, &u, &v);
            if obs.stopped {
                break;
            }
        }
        Ok(obs.finish("rapier2d", sc, steps))
    }
}

/// How rapier splits a bridging block's weight between its two supports, over a run: the
/// smallest, mean and largest share carried by the first support (the paper's tributary rule,
/// eq. 3, gives the overlap ratio, fixed).
fn weight_split(sc: &Scenario, dt_s: f64, upper: usize, supports: (usize, usize)) -> [f64; 3] {
    let mut sim = Sim::new(sc, dt_s);
    let steps = (sc.settings.duration_s / dt_s).ceil() as u64;
    let (mut lo, mut hi, mut sum, mut count) = (f64::INFINITY, 0.0f64, 0.0, 0u64);
    for k in 1..=steps {
        sim.step(k, sc.motion);
        let (a, b) = (
            sim.normal_impulse(upper, supports.0),
            sim.normal_impulse(upper, supports.1),
        );
        if a + b > 0.0 {
            let share = a / (a + b);
            lo = lo.min(share);
            hi = hi.max(share);
            sum += share;
            count += 1;
        }
    }
    [lo, sum / count.max(1) as f64, hi]
}

/// rapier2d-f64 with a fixed step on a wall of one free-standing block that may rotate.
struct RockingPeer {
    dt_s: f64,
    theta0: f64,
}

impl Integrator for RockingPeer {
    fn method(&self) -> &'static str {
        "rapier2d"
    }

    fn run(&self, sc: &Scenario) -> Result<Response, pirqa::error::SimulationError> {
        let name = sc.wall.blocks[0].name.clone();
        let half = sc.wall.blocks[0].height.to_f64() / 2.0;
        let settings = sc.settings;
        let mut rec = pirqa::response::Recorder::for_bodies(
            vec![name.clone()],
            vec![(0, None, name, "ground".into())],
            settings.history_to(),
            pirqa::response::EventsTo::Nowhere,
        );
        let mut sim = Sim::with_rotation(sc, self.dt_s, Some(self.theta0));
        let steps = (settings.duration_s / self.dt_s).ceil() as u64;
        let ground_x0 = sim.world.bodies[sim.ground].translation().x;
        let base_y = |sim: &Sim| {
            let body = &sim.world.bodies[sim.blocks[0].0];
            body.translation().y - half * body.rotation().angle().cos()
        };
        // Released on its corner, the base centre stands b |sin theta0| above the ground.
        let lift0 = base_y(&sim) - 0.5 * sc.wall.blocks[0].width.to_f64() * self.theta0.sin().abs();
        // The base centre relative to where it stood at rest; theta clockwise.
        let state = |sim: &Sim, t: f64| {
            let body = &sim.world.bodies[sim.blocks[0].0];
            let phi = body.rotation().angle();
            let gx = sim.world.bodies[sim.ground].translation().x - ground_x0;
            let u = body.translation().x + half * phi.sin() - sim.blocks[0].2 - gx;
            let v = body.linvel().x + half * phi.cos() * body.angvel() - sc.motion.velocity(t);
            (u, v, -phi, -body.angvel(), base_y(sim) - lift0)
        };
        let mut previous = state(&sim, 0.0);
        let (u, v, th, om, w) = previous;
        rec.sample_rotating(0.0, [&[u], &[v], &[th], &[om], &[w]]);
        let (mut t, mut next_output) = (0.0, 1);
        for k in 1..=steps {
            sim.step(k, sc.motion);
            let t_prev = t;
            t = k as f64 * self.dt_s;
            let now = state(&sim, t);
            rec.block_extremes(0, now.0.abs(), now.1.abs());
            rec.rotation_extreme(0, now.2.abs());
            // Rows at the output times, between steps by linear interpolation, as pirqa's own
            // steppers write them.
            if let Some(o) = settings.output_dt_s {
                outputs_in_step(&mut next_output, o, t_prev, t, |tk, f| {
                    let at = |a: f64, b: f64| lerp(&[a], &[b], f);
                    rec.sample_rotating(
                        tk,
                        [
                            &at(previous.0, now.0),
                            &at(previous.1, now.1),
                            &at(previous.2, now.2),
                            &at(previous.3, now.3),
                            &at(previous.4, now.4),
                        ],
                    );
                });
            }
            previous = now;
        }
        let (u, v, _, _, _) = state(&sim, t);
        Ok(rec.finish(
            "rapier2d",
            &sc.wall.name,
            sc.motion.describe(),
            t,
            &[u],
            &[v],
        ))
    }
}

/// The rocking panel's ladder of steps, written as CSV to `out`.
fn rocking_points(out: &str) {
    let record = std::path::Path::new("records/elcentro1940_IELC180_peer_dt0p01_g.AT2");
    let cases = work_precision::rocking_cases(record)
        .expect("scenarios load (run from the repository root)");
    let mut points: Vec<Point> = Vec::new();
    for rc in &cases {
        let case = &rc.case;
        let settings = pirqa::integrate::Settings {
            duration_s: case.duration_s,
            output_dt_s: Some(work_precision::OUTPUT_DT_S),
            history_file: None,
            log_events: false,
            events_file: None,
            decisions_file: None,
            log_decisions: false,
            after_collapse: Default::default(),
            progress: None,
        };
        let sc = Scenario {
            wall: &case.wall,
            topology: &case.topology,
            motion: &case.motion,
            settings: &settings,
        };
        let reference = pirqa::integrate::rocking::Rocking {
            initial_rotation_rad: rc.initial_rotation_rad,
            ..Default::default()
        }
        .run(&sc)
        .expect("reference");
        for dt in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5] {
            eprintln!("  {} rapier2d dt={dt:e}", case.name);
            let peer = RockingPeer {
                dt_s: dt,
                theta0: rc.initial_rotation_rad,
            };
            let (cpu, r) = work_precision::timed(&peer, &sc, 0.2);
            let errors = r.map(|r| work_precision::rocking_errors(&r, &reference, &case.wall));
            let parameter = format!("dt={dt:e}");
            points.push(work_precision::point(
                &case.name, "rapier2d", parameter, cpu, errors,
            ));
        }
    }
    std::fs::write(out, work_precision::csv(&points)).expect("write the CSV");
    eprintln!("wrote {out}");
}

fn main() {
    let arg = std::env::args().nth(1);
    if arg.as_deref() == Some("rocking") {
        let out = std::env::args().nth(2);
        rocking_points(
            out.as_deref()
                .unwrap_or("docs/figures/work-precision-rocking-rapier.csv"),
        );
        return;
    }
    let record = std::path::Path::new("records/elcentro1940_IELC180_peer_dt0p01_g.AT2");
    let cases = work_precision::standard_cases(record)
        .expect("scenarios load (run from the repository root)");
    if arg.as_deref() != Some("split") {
        chart_points(
            &cases,
            arg.as_deref()
                .unwrap_or("docs/figures/work-precision-rapier.csv"),
        );
    }
    split(&cases);
}

/// The ladder of steps on every standard case, written as CSV to `out`.
fn chart_points(cases: &[work_precision::Case], out: &str) {
    let mut points: Vec<Point> = Vec::new();
    for case in cases {
        let settings = pirqa::integrate::Settings {
            duration_s: case.duration_s,
            output_dt_s: Some(work_precision::OUTPUT_DT_S),
            history_file: None,
            log_events: false,
            events_file: None,
            decisions_file: None,
            log_decisions: false,
            after_collapse: Default::default(),
            progress: None,
        };
        let sc = Scenario {
            wall: &case.wall,
            topology: &case.topology,
            motion: &case.motion,
            settings: &settings,
        };
        let reference = pirqa::integrate::event::EventDriven::default()
            .run(&sc)
            .expect("reference");
        for dt in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5] {
            eprintln!("  {} rapier2d dt={dt:e}", case.name);
            let (cpu, r) = work_precision::timed(&RapierPeer { dt_s: dt }, &sc, 0.2);
            let errors = r.map(|r| work_precision::errors(&r, &reference));
            let parameter = format!("dt={dt:e}");
            points.push(work_precision::point(
                &case.name, "rapier2d", parameter, cpu, errors,
            ));
        }
    }
    std::fs::write(out, work_precision::csv(&points)).expect("write the CSV");
    eprintln!("wrote {out}");
}

/// Prints how rapier splits B4's weight (`cargo run --release -p rapier-peer -- split`).
fn split(cases: &[work_precision::Case]) {
    // The bridging block of the paper's wall: B4 (index 3) on B1 and B2, half on each by eq. 3.
    let case = cases
        .iter()
        .find(|c| c.name == "five-block variable sine")
        .expect("the case");
    let settings = pirqa::integrate::Settings::summary_only(case.duration_s);
    let sc = Scenario {
        wall: &case.wall,
        topology: &case.topology,
        motion: &case.motion,
        settings: &settings,
    };
    for dt in [1e-2, 1e-3, 1e-4, 1e-5] {
        let [lo, mean, hi] = weight_split(&sc, dt, 3, (0, 1));
        println!(
            "B4's weight on B1, five-block variable sine, dt {dt:e} s: min {lo:.4}, mean {mean:.4}, max {hi:.4} (eq. 3: 0.5)"
        );
    }
}
