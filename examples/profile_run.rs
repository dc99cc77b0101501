use pirqa::integrate::event::EventDriven;
use pirqa::integrate::{Integrator, Scenario, Settings};
use pirqa::motion::{Motion, Sine};
use std::time::Instant;
fn main() {
    let path = std::env::args()
        .nth(1)
        .unwrap_or("walls/five-block-variable.ron".into());
    let (wall, topo) = pirqa::topology::load(std::path::Path::new(&path)).unwrap();
    let motion = Motion::Sine(Sine::new(4.0, 1.0, 0.0, 20.0).unwrap());
    let settings = Settings::summary_only(20.0);
    let sc = Scenario {
        wall: &wall,
        topology: &topo,
        motion: &motion,
        settings: &settings,
    };
    let n = 200;
    let t = Instant::now();
    let mut ev = 0;
    for _ in 0..n {
        ev = EventDriven::default()
            .run(&sc)
            .unwrap()
            .summary
            .stats
            .events;
    }
    let r = EventDriven::default().run(&sc).unwrap();
    println!(
        "{:.3} ms per run, {} events, {:?}",
        t.elapsed().as_secs_f64() * 1e3 / n as f64,
        ev,
        r.summary.stats
    );
}
