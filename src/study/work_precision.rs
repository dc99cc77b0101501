//! Speed against accuracy: each time-stepping method over a ladder of steps or tolerances, on
//! named scenarios, against the exact event-driven answer. Errors: the largest error in any
//! block's max |u|, and the largest error in u(t) over the sampled history.

use crate::integrate::baselines::{Moreau, PaperNewmark, Regularized};
use crate::integrate::event::EventDriven;
use crate::integrate::{Integrator, Scenario, Settings};
use crate::motion::Motion;
use crate::plot::chart::{Chart, Corner, Series};
use crate::response::Response;
use crate::topology::Topology;
use crate::wall::Wall;
use std::time::Instant;

/// The scenarios of the committed chart: one block under a sine, the paper's wall with uniform
/// and variable friction under a sine (400 gal, 1 Hz, 10 s), and the variable wall under El
/// Centro scaled to 258 gal and by 5 (from `record`).
pub fn standard_cases(record: &std::path::Path) -> Result<Vec<Case>, crate::Error> {
    use crate::motion::{read_record, ReadOptions, Sine};
    let sine = Motion::sine(Sine {
        amplitude_m_s2: 4.0,
        frequency_hz: 1.0,
        phase_rad: 0.0,
        duration_s: 10.0,
    })
    .expect("valid sine");
    let mut cases = Vec::new();
    let one = crate::samples::one_block(0.3);
    cases.push(Case {
        name: "one block sine".into(),
        topology: Topology::new(&one).expect("valid"),
        wall: one,
        motion: sine.clone(),
        duration_s: 10.0,
    });
    for (name, file) in [
        ("five-block uniform sine", "walls/five-block-uniform.ron"),
        ("five-block variable sine", "walls/five-block-variable.ron"),
    ] {
        let (wall, topology) = crate::topology::load(std::path::Path::new(file))?;
        cases.push(Case {
            name: name.into(),
            wall,
            topology,
            motion: sine.clone(),
            duration_s: 10.0,
        });
    }
    let raw = read_record(record, None, &ReadOptions::default())?;
    let el_centro =
        raw.scaled(2.58 / raw.pga_m_s2() * 5.0)
            .map_err(|source| crate::Error::Motion {
                path: record.to_path_buf(),
                source,
            })?;
    let (wall, topology) =
        crate::topology::load(std::path::Path::new("walls/five-block-variable.ron"))?;
    let duration_s = el_centro.duration_s();
    cases.push(Case {
        name: "five-block variable El Centro x5".into(),
        wall,
        topology,
        motion: Motion::Record(el_centro),
        duration_s,
    });
    Ok(cases)
}

/// A named scenario.
pub struct Case {
    /// Name used in the CSV and chart.
    pub name: String,
    /// The wall.
    pub wall: Wall,
    /// Its graph.
    pub topology: Topology,
    /// The motion.
    pub motion: Motion,
    /// Duration (s).
    pub duration_s: f64,
}

impl Case {
    /// The scenario to run under `settings`.
    fn scenario<'a>(&'a self, settings: &'a Settings) -> Scenario<'a> {
        Scenario {
            wall: &self.wall,
            topology: &self.topology,
            motion: &self.motion,
            settings,
        }
    }
}

/// One point of the chart (a row of its CSV).
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct Point {
    /// Scenario.
    pub scenario: String,
    /// Method.
    pub method: String,
    /// Step (s) or tolerance.
    pub parameter: String,
    /// CPU time of one run (s).
    #[serde(serialize_with = "crate::table::sci")]
    pub cpu_s: f64,
    /// Largest error in a block's max |u| (m).
    #[serde(serialize_with = "crate::table::sci")]
    pub err_max_m: f64,
    /// Largest error in u(t) at the history samples (m).
    #[serde(serialize_with = "crate::table::sci")]
    pub err_history_m: f64,
    /// The run failed (stalled, blew up); the errors are then infinite.
    pub failed: bool,
}

impl Point {
    /// The exact method's point of a scenario: the reference, so its errors are zero.
    pub fn exact(scenario: &str, cpu_s: f64) -> Point {
        Point {
            scenario: scenario.to_string(),
            method: "event".into(),
            parameter: "exact".into(),
            cpu_s,
            err_max_m: 0.0,
            err_history_m: 0.0,
            failed: false,
        }
    }
}

/// A point of the chart from a run's outcome: its errors (max |u|, history), or why it failed
/// (the errors are then infinite).
pub fn point<E>(
    scenario: &str,
    method: &str,
    parameter: String,
    cpu_s: f64,
    errors: Result<(f64, f64), E>,
) -> Point {
    let ((err_max_m, err_history_m), failed) = match errors {
        Ok(e) => (e, false),
        Err(_) => ((f64::INFINITY, f64::INFINITY), true),
    };
    Point {
        scenario: scenario.to_string(),
        method: method.to_string(),
        parameter,
        cpu_s,
        err_max_m,
        err_history_m,
        failed,
    }
}

/// Output interval of the histories compared (s).
pub const OUTPUT_DT_S: f64 = 0.01;

fn settings(duration: f64) -> Settings {
    Settings {
        duration_s: duration,
        output_dt_s: Some(OUTPUT_DT_S),
        history_file: None,
        log_events: false,
        events_file: None,
        decisions_file: None,
        log_decisions: false,
        after_collapse: Default::default(),
        progress: None,
    }
}

/// Runs an integrator repeatedly for at least `min_time_s` and returns the mean CPU time of one
/// run (single thread) and the response.
pub fn timed(
    integrator: &dyn Integrator,
    sc: &Scenario,
    min_time_s: f64,
) -> (f64, Result<Response, crate::error::SimulationError>) {
    let start = Instant::now();
    let mut runs = 0u32;
    loop {
        let r = integrator.run(sc);
        runs += 1;
        let elapsed = start.elapsed().as_secs_f64();
        if r.is_err() || elapsed >= min_time_s || runs >= 50 {
            return (elapsed / f64::from(runs), r);
        }
    }
}

/// Errors of a response against the reference: (max |u| error, history error).
pub fn errors(r: &Response, reference: &Response) -> (f64, f64) {
    let max = r
        .summary
        .blocks
        .iter()
        .zip(&reference.summary.blocks)
        .map(|(a, b)| (a.max_abs_displacement_m - b.max_abs_displacement_m).abs())
        .fold(0.0, f64::max);
    let (h, href) = (
        r.history.as_ref().expect("history"),
        reference.history.as_ref().expect("history"),
    );
    let mut hist: f64 = 0.0;
    for (row, &t) in h.time_s.iter().enumerate() {
        // Both sample every OUTPUT_DT_S from 0; the reference adds event rows in between.
        let k = href.time_s.partition_point(|&x| x < t - 1e-9);
        if let Some(uref) = href.displacement_m.get(k) {
            for (a, b) in h.displacement_m[row].iter().zip(uref) {
                hist = hist.max((a - b).abs());
            }
        }
    }
    (max, hist)
}

/// The ladders: steps of the fixed-step methods and (rtol, eps) pairs of the regularized one.
pub struct Ladder {
    /// Steps of `paper` and `moreau` (s).
    pub steps: Vec<f64>,
    /// (rtol, eps) of `regularized`.
    pub regularized: Vec<(f64, f64)>,
}

impl Ladder {
    /// The full ladder of the committed figure.
    pub fn full() -> Ladder {
        Ladder {
            steps: vec![1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5],
            regularized: vec![
                (1e-3, 1e-2),
                (1e-4, 1e-3),
                (1e-5, 1e-4),
                (1e-6, 1e-5),
                (1e-7, 1e-6),
            ],
        }
    }
    /// A short ladder for tests and quick looks.
    pub fn quick() -> Ladder {
        Ladder {
            steps: vec![1e-2, 1e-3],
            regularized: vec![(1e-4, 1e-3)],
        }
    }
}

/// Runs every method of the ladder on a case; the first point is the event-driven reference.
pub fn run_case(
    case: &Case,
    ladder: &Ladder,
    min_time_s: f64,
    mut progress: impl FnMut(&str),
) -> Result<Vec<Point>, crate::error::SimulationError> {
    let s = settings(case.duration_s);
    let sc = case.scenario(&s);
    let mut runs: Vec<(String, String, Box<dyn Integrator>)> = Vec::new();
    for &dt in &ladder.steps {
        runs.push((
            "paper".into(),
            format!("dt={dt:e}"),
            Box::new(PaperNewmark { dt_s: dt }),
        ));
        runs.push((
            "moreau".into(),
            format!("dt={dt:e}"),
            Box::new(Moreau::new(dt)),
        ));
    }
    for &(rtol, eps) in &ladder.regularized {
        runs.push((
            "regularized".into(),
            format!("rtol={rtol:e};eps={eps:e}"),
            Box::new(Regularized {
                eps,
                ..Regularized::new(rtol)
            }),
        ));
    }
    ladder_points(
        &case.name,
        &sc,
        &EventDriven::default(),
        runs,
        min_time_s,
        &mut progress,
        errors,
    )
}

/// A scenario's points: the reference integrator's (timed), then each run's (method,
/// parameter, integrator), timed, with `errors` of its response against the reference's.
fn ladder_points(
    name: &str,
    sc: &Scenario,
    reference: &dyn Integrator,
    runs: Vec<(String, String, Box<dyn Integrator>)>,
    min_time_s: f64,
    progress: &mut dyn FnMut(&str),
    errors: impl Fn(&Response, &Response) -> (f64, f64),
) -> Result<Vec<Point>, crate::error::SimulationError> {
    let (cpu, reference) = timed(reference, sc, min_time_s);
    // The reference's own error names the body, the time and what failed.
    let reference = reference?;
    let mut points = vec![Point::exact(name, cpu)];
    for (method, parameter, integrator) in runs {
        progress(&format!("{name} {method} {parameter}"));
        let (cpu, r) = timed(integrator.as_ref(), sc, min_time_s);
        let errors = r.map(|r| errors(&r, &reference));
        points.push(point(name, &method, parameter, cpu, errors));
    }
    Ok(points)
}

/// Moreau-Jean runs over a ladder of steps, built by `moreau` from each step.
fn moreau_runs<I: Integrator + 'static>(
    steps: &[f64],
    moreau: impl Fn(f64) -> I,
) -> Vec<(String, String, Box<dyn Integrator>)> {
    steps
        .iter()
        .map(|&dt| {
            let run: Box<dyn Integrator> = Box::new(moreau(dt));
            ("moreau".to_string(), format!("dt={dt:e}"), run)
        })
        .collect()
}

/// Error shown for the exact method on a log axis (its own error is round-off).
pub const EXACT_FLOOR_M: f64 = 1e-15;

/// The chart: per scenario, history error against CPU time, one line per method, the exact
/// method as a point, and the 1e-3, 1e-6, 1e-9 m levels.
pub fn charts(points: &[Point]) -> Vec<Chart> {
    let mut scenarios: Vec<String> = Vec::new();
    for p in points {
        if !scenarios.contains(&p.scenario) {
            scenarios.push(p.scenario.clone());
        }
    }
    let mut methods: Vec<String> = Vec::new();
    for p in points {
        if !methods.contains(&p.method) {
            methods.push(p.method.clone());
        }
    }
    scenarios
        .iter()
        .map(|sc| {
            let pts: Vec<&Point> = points
                .iter()
                .filter(|p| &p.scenario == sc && !p.failed)
                .collect();
            let exact_cpu = pts.iter().find(|p| p.method == "event").map(|p| p.cpu_s);
            let (t0, t1) = pts.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
                (a.min(p.cpu_s), b.max(p.cpu_s))
            });
            let mut series: Vec<Series> = methods
                .iter()
                .enumerate()
                .filter_map(|(c, m)| {
                    let mut xy: Vec<(f64, f64)> = pts
                        .iter()
                        .filter(|p| &p.method == m)
                        .map(|p| {
                            (
                                p.cpu_s,
                                if p.method == "event" {
                                    EXACT_FLOOR_M
                                } else {
                                    p.err_history_m.max(EXACT_FLOOR_M)
                                },
                            )
                        })
                        .collect();
                    xy.sort_by(|a, b| a.0.total_cmp(&b.0));
                    (!xy.is_empty()).then(|| Series {
                        label: if m == "event" {
                            "event (exact, reference)".into()
                        } else {
                            m.clone()
                        },
                        points: xy,
                        color: c,
                        markers: true,
                        ..Default::default()
                    })
                })
                .collect();
            for level in LEVELS_M {
                series.push(Series {
                    points: vec![(t0 * 0.8, level), (t1 * 1.25, level)],
                    color: 7,
                    dashed: true,
                    ..Default::default()
                });
            }
            Chart {
                title: sc.clone(),
                x_label: "CPU time per run (s)".into(),
                y_label: "max error in u(t) (m)".into(),
                series,
                log_x: true,
                log_y: true,
                notes: LEVELS_M
                    .iter()
                    .map(|&level| (t0, level * 8.0, format!("{level:e} m")))
                    .chain(exact_cpu.map(|t| (t * 1.15, EXACT_FLOOR_M * 2.0, "exact".into())))
                    .collect(),
                legend: Corner::LowerRight,
            }
        })
        .collect()
}

/// Columns of the points' CSV.
pub const CSV_HEADER: &str = "scenario,method,parameter,cpu_s,err_max_m,err_history_m,failed";

/// The points as CSV.
pub fn csv(points: &[Point]) -> String {
    let mut s = format!("{CSV_HEADER}\n");
    s.extend(points.iter().map(crate::table::line));
    s
}

/// Reads points back from the CSV that [`csv()`] writes, by column name.
pub fn read_csv(path: &std::path::Path) -> Result<Vec<Point>, crate::Error> {
    let text = std::fs::read_to_string(path).map_err(|source| crate::Error::Io {
        path: path.to_path_buf(),
        source,
    })?;
    let columns: Vec<&str> = CSV_HEADER.split(',').collect();
    crate::table::read_rows(path, &text, &columns)
}

/// Error levels the chart marks (m).
pub const LEVELS_M: [f64; 3] = [1e-3, 1e-6, 1e-9];

/// What each method costs to reach each level, as CSV: per scenario, method and level, the
/// cheapest point whose history error is at most the level, or `never` and the best error the
/// ladder reached.
pub fn reach_csv(points: &[Point]) -> String {
    let mut s = String::from("scenario,method,level_m,parameter,cpu_s,err_history_m\n");
    let mut keys: Vec<(&str, &str)> = Vec::new();
    for p in points {
        if !keys.contains(&(p.scenario.as_str(), p.method.as_str())) {
            keys.push((&p.scenario, &p.method));
        }
    }
    for (scenario, method) in keys {
        let pts: Vec<&Point> = points
            .iter()
            .filter(|p| p.scenario == scenario && p.method == method && !p.failed)
            .collect();
        for level in LEVELS_M {
            let cheapest = pts
                .iter()
                .filter(|p| p.err_history_m <= level)
                .min_by(|a, b| a.cpu_s.total_cmp(&b.cpu_s));
            let (parameter, cpu, err) = match cheapest {
                Some(p) => (
                    p.parameter.clone(),
                    format!("{:e}", p.cpu_s),
                    p.err_history_m,
                ),
                None => {
                    let best = pts
                        .iter()
                        .map(|p| p.err_history_m)
                        .fold(f64::INFINITY, f64::min);
                    ("never".into(), String::new(), best)
                }
            };
            let level = format!("{level:e}");
            let err = format!("{err:e}");
            s.push_str(&crate::table::line(&(
                scenario, method, level, parameter, cpu, err,
            )));
        }
    }
    s
}

/// A scenario of the rocking panel: a wall of one free-standing block, released from a
/// rotation or shaken.
pub struct RockingCase {
    /// The scenario.
    pub case: Case,
    /// Initial rotation (rad).
    pub initial_rotation_rad: f64,
}

/// The rocking scenarios: the Inca standing stone (walls/inca/stela.ron) released from 0.1 rad
/// on still ground, under one cycle of a sine (1.3 g tan alpha at omega_p = 3 p: it rocks and
/// lands without overturning), and under the first 10 s of El Centro scaled to 0.4 g (from
/// `record`).
pub fn rocking_cases(record: &std::path::Path) -> Result<Vec<RockingCase>, crate::Error> {
    use crate::motion::{read_record, Pulse, ReadOptions, Sine};
    let (wall, topology) = crate::topology::load(std::path::Path::new("walls/inca/stela.ron"))?;
    let body = crate::integrate::rocking::free_standing(&wall, &topology)?;
    let (ratio, p) = (body.uplift_ratio(), body.frequency_parameter_rad_s());
    let f = 3.0 * p / (2.0 * std::f64::consts::PI);
    let pulse = Sine {
        amplitude_m_s2: 1.3 * ratio * body.g_m_s2,
        frequency_hz: f,
        phase_rad: 0.0,
        duration_s: 1.0 / f,
    }
    .checked()
    .map_err(|source| crate::Error::Motion {
        path: "rocking pulse".into(),
        source,
    })?;
    let raw = read_record(record, None, &ReadOptions::default())?;
    let el_centro = raw
        .scaled(0.4 * body.g_m_s2 / raw.pga_m_s2())
        .map_err(|source| crate::Error::Motion {
            path: record.to_path_buf(),
            source,
        })?;
    let case = |name: &str, motion: Motion, duration_s: f64, theta: f64| RockingCase {
        case: Case {
            name: name.into(),
            wall: wall.clone(),
            topology: topology.clone(),
            motion,
            duration_s,
        },
        initial_rotation_rad: theta,
    };
    Ok(vec![
        case(
            "huanca free rocking from 0.1 rad",
            Motion::Pulse(Pulse::rest()),
            3.0,
            0.1,
        ),
        case(
            "huanca one-sine pulse 1.3 g tan alpha",
            Motion::Sine(pulse),
            4.0,
            0.0,
        ),
        case(
            "huanca El Centro 0.4 g for 10 s",
            Motion::Record(el_centro),
            10.0,
            0.0,
        ),
    ])
}

/// Errors of a run whose blocks rotate against the reference, on the horizontal displacement
/// of the middle of each block's top (its u plus its height times sin theta, m), the blocks of
/// `wall` in its order: (largest error in a block's largest |value|, largest error over the
/// sampled history). Each sample is compared with the reference's first at or after it: the
/// same time for pirqa's steppers, which write rows at the output times; a peer's rows need
/// not fall on them.
pub fn rocking_errors(r: &Response, reference: &Response, wall: &Wall) -> (f64, f64) {
    let top = |resp: &Response, i: usize| -> Vec<(f64, f64)> {
        let h = resp.history.as_ref().expect("history");
        let height = wall.blocks[i].height.to_f64();
        h.time_s
            .iter()
            .zip(&h.displacement_m)
            .zip(&h.rotation_rad)
            .map(|((&t, u), th)| (t, u[i] + height * th[i].sin()))
            .collect()
    };
    let peak = |v: &[(f64, f64)]| v.iter().fold(0.0f64, |m, x| m.max(x.1.abs()));
    let (mut max_err, mut hist) = (0.0f64, 0.0f64);
    for i in 0..wall.blocks.len() {
        let (a, b) = (top(r, i), top(reference, i));
        max_err = max_err.max((peak(&a) - peak(&b)).abs());
        for &(t, x) in &a {
            let k = b.partition_point(|&(s, _)| s < t - 1e-9);
            if let Some(&(_, y)) = b.get(k) {
                hist = hist.max((x - y).abs());
            }
        }
    }
    (max_err, hist)
}

/// The rocking panel for one scenario: the exact engine (the reference) and Moreau-Jean with
/// rotations over the ladder of steps.
pub fn run_rocking_case(
    rc: &RockingCase,
    steps: &[f64],
    min_time_s: f64,
    mut progress: impl FnMut(&str),
) -> Result<Vec<Point>, crate::Error> {
    use crate::integrate::baselines::MoreauWall;
    use crate::integrate::rocking::Rocking;
    let case = &rc.case;
    let s = settings(case.duration_s);
    let sc = case.scenario(&s);
    let exact = Rocking {
        initial_rotation_rad: rc.initial_rotation_rad,
        ..Rocking::default()
    };
    let release = (rc.initial_rotation_rad != 0.0)
        .then(|| (case.wall.blocks[0].name.clone(), rc.initial_rotation_rad));
    let runs = moreau_runs(steps, |dt| MoreauWall {
        initial_rotation: release.clone(),
        ..MoreauWall::new(dt)
    });
    Ok(ladder_points(
        &case.name,
        &sc,
        &exact,
        runs,
        min_time_s,
        &mut progress,
        |r, reference| rocking_errors(r, reference, &case.wall),
    )?)
}

/// The rocking panel's charts: as [`charts`], the error being that of the top's displacement.
pub fn rocking_charts(points: &[Point]) -> Vec<Chart> {
    let mut out = charts(points);
    for c in &mut out {
        c.y_label = "max error in the top's u(t) (m)".into();
    }
    out
}

/// The rocking-walls panel: the three columns of walls/rocking/ (a slender block on a stack, a
/// two-block column, a standing stone on its plinth) under the first 10 s of El Centro scaled
/// to 0.3 g (from `record`): the exact column model against Moreau-Jean with every block's
/// rotation (docs/rocking-walls.md).
pub fn rocking_wall_cases(record: &std::path::Path) -> Result<Vec<Case>, crate::Error> {
    use crate::motion::{read_record, ReadOptions};
    let raw = read_record(record, None, &ReadOptions::default())?;
    let el_centro =
        raw.scaled(0.3 * 9.81 / raw.pga_m_s2())
            .map_err(|source| crate::Error::Motion {
                path: record.to_path_buf(),
                source,
            })?;
    [
        ("slender block on a stack", "slender-on-stack"),
        ("two-block column", "two-block-column"),
        ("standing stone on a plinth", "huanca-on-plinth"),
    ]
    .into_iter()
    .map(|(name, file)| {
        let path = format!("walls/rocking/{file}.ron");
        let (wall, topology) = crate::topology::load(std::path::Path::new(&path))?;
        Ok(Case {
            name: format!("{name}, El Centro 0.3 g"),
            wall,
            topology,
            motion: Motion::Record(el_centro.clone()),
            duration_s: 10.0,
        })
    })
    .collect()
}

/// The rocking-walls panel for one scenario: the exact column model (the reference) and
/// Moreau-Jean with every block's rotation over the ladder of steps.
pub fn run_rocking_wall_case(
    case: &Case,
    steps: &[f64],
    min_time_s: f64,
    mut progress: impl FnMut(&str),
) -> Result<Vec<Point>, crate::Error> {
    use crate::integrate::baselines::MoreauWall;
    use crate::integrate::rocking::Rocking;
    let s = settings(case.duration_s);
    let sc = case.scenario(&s);
    Ok(ladder_points(
        &case.name,
        &sc,
        &Rocking::default(),
        moreau_runs(steps, MoreauWall::new),
        min_time_s,
        &mut progress,
        |r, reference| rocking_errors(r, reference, &case.wall),
    )?)
}
