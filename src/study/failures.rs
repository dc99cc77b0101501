//! Where the time-stepping methods fail: six small scenarios, each run by the exact integrator
//! and the baselines, drawn as one chart panel and reduced to the measured numbers that
//! docs/accuracy.md quotes (tests/suite/baselines.rs pins the same behaviours on the same scenarios).

use crate::integrate::baselines::{Moreau, PaperNewmark, Regularized};
use crate::integrate::event::EventDriven;
use crate::integrate::{Integrator, Scenario, Settings};
use crate::motion::{Motion, Record, Sine};
use crate::plot::chart::{Chart, Corner, Series};
use crate::response::{EventKind, Response};
use crate::samples;
use crate::study::work_precision::Case;
use crate::topology::Topology;

/// Sine of 400 gal at 1 Hz, the paper's standard input.
fn sine(phase_deg: f64, duration_s: f64) -> Motion {
    Motion::sine(Sine {
        amplitude_m_s2: 4.0,
        frequency_hz: 1.0,
        phase_rad: crate::motion::phase_rad(phase_deg),
        duration_s,
    })
    .expect("valid sine")
}

fn case(name: &str, wall: crate::Wall, motion: Motion, duration_s: f64) -> Case {
    Case {
        name: name.into(),
        topology: Topology::new(&wall).expect("valid sample wall"),
        wall,
        motion,
        duration_s,
    }
}

/// The paper's wall with uniform friction (mu 0.3 everywhere), 400 gal, 1 Hz, 10 s: the exact
/// answer keeps the upper row stuck on the lower one.
pub fn drift_case() -> Result<Case, crate::Error> {
    let (wall, topology) =
        crate::topology::load(std::path::Path::new("walls/five-block-uniform.ron"))?;
    Ok(Case {
        name: "five-block uniform sine".into(),
        wall,
        topology,
        motion: sine(0.0, 10.0),
        duration_s: 10.0,
    })
}

/// One block, mu 0.3, 400 gal, 1 Hz, 10 s: it sticks 27 % of the time.
pub fn chatter_case() -> Case {
    case(
        "one block sine",
        samples::one_block(0.3),
        sine(0.0, 10.0),
        10.0,
    )
}

/// Two blocks side by side (mu 0.25 and 0.3, no gap, e = 1) under a sine at phase 135 deg:
/// about ten elastic impacts in 10 s.
pub fn elastic_pair_case() -> Case {
    case(
        "elastic pair",
        samples::course(&[0.25, 0.3], &[0.0, 0.0], 1.0),
        sine(135.0, 10.0),
        10.0,
    )
}

/// Two blocks 5 cm apart (mu 0.3 and 0.2, e = 0.5) under a constant 5 m/s2: the bounces
/// accumulate at a finite time.
pub fn zeno_case() -> Case {
    let constant = Record::new("constant 5 m/s2", 0.01, vec![5.0; 202]).expect("valid record");
    case(
        "Zeno pair",
        samples::course(&[0.3, 0.2], &[0.0, 0.05], 0.5),
        Motion::Record(constant),
        2.0,
    )
}

/// Gap of the grazing pair (m): its faces close by only 1.5e-8 m, at 0.6795 s.
pub const GRAZING_GAP_M: f64 = 0.04065824;

/// Two blocks whose gap closes by a hair (an impact at 0.34 mm/s) under a sine at 135 deg.
pub fn grazing_case() -> Case {
    case(
        "grazing pair",
        samples::course(&[0.25, 0.3], &[0.0, GRAZING_GAP_M], 1.0),
        sine(135.0, 1.0),
        1.0,
    )
}

/// The regularized method at rtol 1e-6 with friction regularized over `eps` (m/s).
fn with_eps(eps: f64) -> Regularized {
    Regularized {
        eps,
        ..Regularized::new(1e-6)
    }
}

/// Runs one method on a case, with the history every `output_dt_s` when given.
pub fn run(
    integrator: &dyn Integrator,
    case: &Case,
    output_dt_s: Option<f64>,
) -> Result<Response, crate::error::SimulationError> {
    let settings = Settings {
        duration_s: case.duration_s,
        output_dt_s,
        history_file: None,
        log_events: true,
        events_file: None,
        decisions_file: None,
        log_decisions: false,
        after_collapse: Default::default(),
        progress: None,
    };
    integrator.run(&Scenario {
        wall: &case.wall,
        topology: &case.topology,
        motion: &case.motion,
        settings: &settings,
    })
}

/// Largest |u_upper - u_lower| at the joint named by the two blocks (m).
pub fn creep_m(r: &Response, upper: &str, lower: &str) -> f64 {
    r.summary
        .horizontal_joints
        .iter()
        .find(|j| j.upper == upper && j.lower == lower)
        .map_or(f64::NAN, |j| j.max_abs_relative_displacement_m)
}

/// Number of impacts in the event log.
pub fn impacts(r: &Response) -> usize {
    r.events
        .iter()
        .filter(|e| e.kind == EventKind::Impact)
        .count()
}

/// Gap between blocks 0 and 1 of a two-block course at each history row (m).
fn gaps_m(r: &Response, gap0_m: f64) -> Vec<(f64, f64)> {
    let h = r.history.as_ref().expect("history asked for");
    h.time_s
        .iter()
        .zip(&h.displacement_m)
        .map(|(&t, u)| (t, gap0_m + u[1] - u[0]))
        .collect()
}

/// Smallest gap of a two-block course over its history, or zero (m).
fn min_gap_m(r: &Response, gap0_m: f64) -> f64 {
    gaps_m(r, gap0_m).iter().fold(0.0f64, |m, p| m.min(p.1))
}

/// One panel and the numbers read from it (name with unit, value).
pub struct Demo {
    /// The panel.
    pub chart: Chart,
    /// Measured numbers, quoted in docs/accuracy.md.
    pub measured: Vec<(String, f64)>,
}

fn line(label: &str, color: usize, points: Vec<(f64, f64)>) -> Series {
    Series {
        label: label.into(),
        points,
        color,
        ..Default::default()
    }
}

/// Drift of a wall that should stay stuck: B3 relative to B1 over time, and the creep after
/// 10 s against the step (paper) and eps (regularized).
pub fn drift() -> Result<Vec<Demo>, crate::Error> {
    let c = drift_case()?;
    let rel = |r: &Response| -> Vec<(f64, f64)> {
        let h = r.history.as_ref().expect("history asked for");
        // B3 rests on B1 (index 2 on index 0).
        h.time_s
            .iter()
            .zip(&h.displacement_m)
            .map(|(&t, u)| (t, (u[2] - u[0]) * 1e3))
            .collect()
    };
    let out = Some(0.01);
    let exact = run(&EventDriven::default(), &c, out)?;
    let paper = run(&PaperNewmark { dt_s: 1e-3 }, &c, out)?;
    let moreau = run(&Moreau::new(1e-3), &c, out)?;
    let reg = run(&Regularized::new(1e-6), &c, out)?;
    let history = Chart {
        title: "Drift: B3 on B1, uniform friction, 400 gal 1 Hz".into(),
        x_label: "t (s)".into(),
        y_label: "u(B3) - u(B1) (mm)".into(),
        series: vec![
            line("event (exact: 0)", 0, rel(&exact)),
            line("paper dt 1e-3 s", 1, rel(&paper)),
            line("moreau dt 1e-3 s", 2, rel(&moreau)),
            line("regularized eps 1e-4 m/s", 3, rel(&reg)),
        ],
        ..Default::default()
    };
    let mut measured = vec![
        (
            "drift exact creep (m)".to_string(),
            creep_m(&exact, "B3", "B1"),
        ),
        (
            "drift moreau dt=1e-3 creep (m)".to_string(),
            creep_m(&moreau, "B3", "B1"),
        ),
    ];
    let (mut paper_pts, mut reg_pts) = (Vec::new(), Vec::new());
    for dt in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4] {
        let creep = creep_m(&run(&PaperNewmark { dt_s: dt }, &c, None)?, "B3", "B1");
        measured.push((format!("drift paper dt={dt:e} creep (m)"), creep));
        paper_pts.push((dt, creep));
    }
    for eps in [1e-2, 1e-3, 1e-4, 1e-5] {
        let r = run(&with_eps(eps), &c, None)?;
        let creep = creep_m(&r, "B3", "B1");
        measured.push((format!("drift regularized eps={eps:e} creep (m)"), creep));
        reg_pts.push((eps, creep));
    }
    let ladder = Chart {
        title: "Drift after 10 s against the method's parameter".into(),
        x_label: "paper: dt (s); regularized: eps (m/s)".into(),
        y_label: "max |u(B3) - u(B1)| (m)".into(),
        series: vec![
            Series {
                markers: true,
                ..line("paper (x = dt)", 1, paper_pts)
            },
            Series {
                markers: true,
                ..line("regularized (x = eps)", 3, reg_pts)
            },
        ],
        log_x: true,
        log_y: true,
        legend: Corner::LowerRight,
        ..Default::default()
    };
    Ok(vec![
        Demo {
            chart: history,
            measured,
        },
        Demo {
            chart: ladder,
            measured: Vec::new(),
        },
    ])
}

/// sgn(v) chatter: the velocity of one block through its first long stick, exact against the
/// paper's scheme.
pub fn chatter() -> Result<Demo, crate::Error> {
    let c = chatter_case();
    let dt = 1e-3;
    let exact = run(&EventDriven::default(), &c, Some(dt))?;
    let paper = run(&PaperNewmark { dt_s: dt }, &c, Some(dt))?;
    let he = exact.history.as_ref().expect("history");
    // The longest stick of the exact run within the first 3 s after the block starts.
    let (mut best, mut start) = ((0.0, 0.0), None);
    for (&t, v) in he.time_s.iter().zip(&he.velocity_m_s) {
        match (v[0] == 0.0 && t > 0.2 && t < 3.0, start) {
            (true, None) => start = Some(t),
            (false, Some(s)) => {
                if t - s > best.1 - best.0 {
                    best = (s, t);
                }
                start = None;
            }
            _ => {}
        }
    }
    let window = (best.0 - 0.05, best.1 + 0.05);
    let cut = |r: &Response| -> Vec<(f64, f64)> {
        let h = r.history.as_ref().expect("history");
        h.time_s
            .iter()
            .zip(&h.velocity_m_s)
            .filter(|(t, _)| **t >= window.0 && **t <= window.1)
            .map(|(&t, v)| (t, v[0] * 1e3))
            .collect()
    };
    let at_rest = |r: &Response| -> (f64, usize) {
        let h = r.history.as_ref().expect("history");
        h.time_s
            .iter()
            .zip(&h.velocity_m_s)
            .filter(|(t, _)| **t > best.0 + 1e-9 && **t < best.1 - 1e-9)
            .fold((0.0f64, 0), |(m, z), (_, v)| {
                (m.max(v[0].abs()), z + usize::from(v[0] == 0.0))
            })
    };
    let (hover, zeros) = at_rest(&paper);
    let moving = he.time_s.iter().position(|&t| t > 0.2).unwrap_or(0);
    let resting = he.velocity_m_s[moving..]
        .iter()
        .filter(|v| v[0] == 0.0)
        .count();
    let rest_fraction = resting as f64 / (he.time_s.len() - moving).max(1) as f64;
    let mu_g_dt = 0.3 * c.wall.g_m_s2.to_f64() * dt;
    Ok(Demo {
        chart: Chart {
            title: format!(
                "Chatter: one block through a stick ({:.3}-{:.3} s), dt 1e-3 s",
                best.0, best.1
            ),
            x_label: "t (s)".into(),
            y_label: "v (mm/s)".into(),
            series: vec![
                line("event (exact)", 0, cut(&exact)),
                line("paper sgn(v)", 1, cut(&paper)),
            ],
            ..Default::default()
        },
        measured: vec![
            (
                "chatter exact fraction of samples at rest after 0.2 s".into(),
                rest_fraction,
            ),
            ("chatter stick length (s)".into(), best.1 - best.0),
            (
                "chatter paper dt=1e-3 max |v| while stuck (m/s)".into(),
                hover,
            ),
            (
                "chatter paper dt=1e-3 hover / (mu g dt)".into(),
                hover / mu_g_dt,
            ),
            (
                "chatter paper dt=1e-3 samples at rest while stuck".into(),
                zeros as f64,
            ),
        ],
    })
}

/// Energy with e = 1 impacts: the error of the energy balance against the step.
pub fn energy() -> Result<Demo, crate::Error> {
    let c = elastic_pair_case();
    let exact = run(&EventDriven::default(), &c, None)?;
    let mut measured = vec![
        (
            "energy exact residual (J)".to_string(),
            exact.summary.energy.residual_j,
        ),
        (
            "energy exact input (J)".to_string(),
            exact.summary.energy.input_j,
        ),
        (
            "energy exact impacts".to_string(),
            exact.summary.impacts as f64,
        ),
    ];
    let (mut p, mut m) = (Vec::new(), Vec::new());
    let steps = [1e-2, 3e-3, 1e-3, 3e-4, 1e-4, 3e-5, 1e-5];
    for dt in steps {
        let rp = run(&PaperNewmark { dt_s: dt }, &c, None)?.summary.energy;
        let rm = run(&Moreau::new(dt), &c, None)?.summary.energy;
        // The paper's scheme books no impact loss: its error is the balance residual. Moreau's
        // impacts are where its energy goes: the (signed) impact loss.
        measured.push((
            format!("energy paper dt={dt:e} residual (J)"),
            rp.residual_j,
        ));
        measured.push((
            format!("energy moreau dt={dt:e} impact loss (J)"),
            rm.impact_loss_j,
        ));
        p.push((dt, rp.residual_j.abs()));
        m.push((dt, rm.impact_loss_j.abs() + rm.residual_j.abs()));
    }
    let floor = exact.summary.energy.residual_j.abs().max(1e-15);
    Ok(Demo {
        chart: Chart {
            title: format!(
                "Energy with e = 1 impacts (10 s, {} impacts)",
                exact.summary.impacts
            ),
            x_label: "dt (s)".into(),
            y_label: "energy error (J)".into(),
            series: vec![
                Series {
                    markers: true,
                    ..line("paper: |balance residual|", 1, p)
                },
                Series {
                    markers: true,
                    ..line("moreau: |impact loss| + |residual|", 2, m)
                },
                line(
                    "event (exact): |residual|",
                    0,
                    vec![(1e-5, floor), (1e-2, floor)],
                ),
            ],
            log_x: true,
            log_y: true,
            legend: Corner::LowerRight,
            ..Default::default()
        },
        measured,
    })
}

/// Stiffness of the regularized method: accepted steps against eps (tanh friction) and
/// against the penalty stiffness, and the eps at which it stalls.
pub fn stiffness() -> Result<Vec<Demo>, crate::Error> {
    let one = chatter_case();
    let mut measured = Vec::new();
    let mut eps_pts = Vec::new();
    for eps in [1e-2, 1e-3, 1e-4, 1e-5, 1e-6] {
        let r = run(&with_eps(eps), &one, None)?;
        let steps = r.summary.stats.steps as f64;
        measured.push((format!("stiffness eps={eps:e} steps (10 s)"), steps));
        eps_pts.push((eps, steps));
    }
    // Penalty contacts cost steps only while the faces stay pressed together (an isolated
    // impact takes a fixed number of adaptive steps whatever k): the Zeno pair, which ends
    // pressed together, shows the cost; the overlap is the price of a soft spring.
    let zeno = zeno_case();
    let mut k_pts = Vec::new();
    for k in [1e7, 1e8, 1e9, 1e10, 1e11, 1e12] {
        let r = run(
            &Regularized {
                stiffness: k,
                ..Regularized::new(1e-6)
            },
            &zeno,
            Some(1e-3),
        )?;
        let steps = r.summary.stats.steps as f64;
        measured.push((format!("stiffness k={k:e} N/m steps (Zeno pair)"), steps));
        measured.push((
            format!("stiffness k={k:e} N/m deepest overlap, 1 ms samples (m)"),
            -min_gap_m(&r, 0.05),
        ));
        k_pts.push((k, steps));
    }
    // The step floor (1e-12 s by default) turns step collapse into a stall.
    let mut stall = f64::NAN;
    for eps in [1e-7, 1e-8, 1e-9, 1e-10, 1e-11] {
        let r = run(
            &Regularized {
                eps,
                min_step: 1e-7,
                ..Regularized::new(1e-6)
            },
            &one,
            None,
        );
        if r.is_err() {
            stall = eps;
            break;
        }
    }
    measured.push((
        "stiffness largest eps stalling with a 1e-7 s step floor (m/s)".into(),
        stall,
    ));
    let chart = |title: &str, x: &str, pts, label: &str, legend| Chart {
        title: title.into(),
        x_label: x.into(),
        y_label: "accepted steps".into(),
        series: vec![Series {
            markers: true,
            ..line(label, 3, pts)
        }],
        log_x: true,
        log_y: true,
        legend,
        ..Default::default()
    };
    Ok(vec![
        Demo {
            chart: chart(
                "Step collapse: tanh friction, one block, 10 s",
                "eps (m/s)",
                eps_pts,
                "regularized, rtol 1e-6",
                Corner::UpperRight,
            ),
            measured,
        },
        Demo {
            chart: chart(
                "Step collapse: penalty contact, Zeno pair pressed together",
                "penalty stiffness (N/m)",
                k_pts,
                "regularized, rtol 1e-6, eps 1e-4",
                Corner::UpperLeft,
            ),
            measured: Vec::new(),
        },
    ])
}

/// The gap of a two-block course over a time window, scaled (1e3: mm, 1e6: um).
fn gap_window(r: &Response, gap0_m: f64, window_s: (f64, f64), scale: f64) -> Vec<(f64, f64)> {
    gaps_m(r, gap0_m)
        .into_iter()
        .filter(|(t, _)| (window_s.0..=window_s.1).contains(t))
        .map(|(t, g)| (t, g * scale))
        .collect()
}

/// Zeno bounces: the gap over time, exact against the paper's scheme and Moreau-Jean, and a
/// close-up of the faces after the accumulation point.
pub fn zeno() -> Result<Vec<Demo>, crate::Error> {
    let c = zeno_case();
    let dt = 1e-3;
    let out = Some(dt);
    let exact = run(&EventDriven::default(), &c, out)?;
    let paper = run(&PaperNewmark { dt_s: dt }, &c, out)?;
    let moreau = run(&Moreau::new(dt), &c, out)?;
    let panel = |title: &str, window_s: (f64, f64), scale: f64, unit: &str| Chart {
        title: title.into(),
        x_label: "t (s)".into(),
        y_label: format!("gap ({unit})"),
        series: vec![
            line(
                "event (exact)",
                0,
                gap_window(&exact, 0.05, window_s, scale),
            ),
            line(
                "paper dt 1e-3 s",
                1,
                gap_window(&paper, 0.05, window_s, scale),
            ),
            line(
                "moreau dt 1e-3 s",
                2,
                gap_window(&moreau, 0.05, window_s, scale),
            ),
        ],
        ..Default::default()
    };
    let accumulation = exact
        .events
        .iter()
        .find(|e| e.kind == EventKind::Zeno)
        .map_or(f64::NAN, |e| e.time_s);
    Ok(vec![
        Demo {
            chart: panel(
                "Zeno: e = 0.5 bounces under constant 5 m/s2",
                (0.0, c.duration_s),
                1e3,
                "mm",
            ),
            measured: vec![
                ("zeno exact impacts".into(), exact.summary.impacts as f64),
                (
                    "zeno exact accumulations".into(),
                    exact.summary.zeno_accumulations as f64,
                ),
                ("zeno exact accumulation time (s)".into(), accumulation),
                (
                    "zeno paper dt=1e-3 impacts".into(),
                    paper.summary.impacts as f64,
                ),
                (
                    "zeno paper dt=1e-3 deepest overlap (m)".into(),
                    -min_gap_m(&paper, 0.05),
                ),
                (
                    "zeno moreau dt=1e-3 impacts".into(),
                    moreau.summary.impacts as f64,
                ),
                (
                    "zeno moreau dt=1e-3 deepest overlap (m)".into(),
                    -min_gap_m(&moreau, 0.05),
                ),
            ],
        },
        Demo {
            chart: panel(
                "Zeno, close-up: the faces after the accumulation",
                (0.8, c.duration_s),
                1e6,
                "um",
            ),
            measured: Vec::new(),
        },
    ])
}

/// Grazing: the gap near its closest approach, and which steps see the impact at all.
pub fn grazing() -> Result<Vec<Demo>, crate::Error> {
    let c = grazing_case();
    let exact = run(&EventDriven::default(), &c, Some(1e-4))?;
    let mut measured = vec![("grazing exact impacts".to_string(), impacts(&exact) as f64)];
    if let Some(e) = exact.events.iter().find(|e| e.kind == EventKind::Impact) {
        measured.push(("grazing exact impact time (s)".into(), e.time_s));
    }
    let (wide, close) = ((0.55, 0.8), (0.665, 0.695));
    let mut runs = vec![("event (exact)".to_string(), 0, false, exact)];
    for dt in [1e-2, 3e-3, 1e-3, 3e-4, 1e-4] {
        let rp = run(&PaperNewmark { dt_s: dt }, &c, Some(dt))?;
        let rm = run(&Moreau::new(dt), &c, Some(dt))?;
        let (np, nm) = (impacts(&rp), impacts(&rm));
        measured.push((format!("grazing paper dt={dt:e} impacts"), np as f64));
        measured.push((format!("grazing moreau dt={dt:e} impacts"), nm as f64));
        let seen = |n: usize| if n == 0 { "misses" } else { "sees it" };
        if dt == 1e-2 {
            runs.push((format!("paper dt 1e-2 s ({})", seen(np)), 1, true, rp));
            runs.push((format!("moreau dt 1e-2 s ({})", seen(nm)), 2, true, rm));
        } else if dt == 1e-3 {
            runs.push((format!("moreau dt 1e-3 s ({})", seen(nm)), 4, true, rm));
        }
    }
    // The close-up leaves out the paper's scheme, millimetres off by then.
    let panel = |title: &str, window_s: (f64, f64), scale: f64, unit: &str| Chart {
        title: title.into(),
        x_label: "t (s)".into(),
        y_label: format!("gap ({unit})"),
        series: runs
            .iter()
            .filter(|run| scale < 1e6 || !run.0.starts_with("paper"))
            .map(|(label, color, markers, r)| Series {
                markers: *markers,
                ..line(label, *color, gap_window(r, GRAZING_GAP_M, window_s, scale))
            })
            .collect(),
        ..Default::default()
    };
    Ok(vec![
        Demo {
            chart: panel(
                "Grazing: the faces close by 1.5e-8 m at 0.68 s",
                wide,
                1e3,
                "mm",
            ),
            measured,
        },
        Demo {
            chart: panel("Grazing, close-up: Moreau-Jean's steps", close, 1e6, "um"),
            measured: Vec::new(),
        },
    ])
}

/// Every demonstration, in the order of docs/accuracy.md.
pub fn all(mut progress: impl FnMut(&str)) -> Result<Vec<Demo>, crate::Error> {
    let mut demos = Vec::new();
    progress("drift");
    demos.extend(drift()?);
    progress("chatter");
    demos.push(chatter()?);
    progress("energy");
    demos.push(energy()?);
    progress("stiffness");
    demos.extend(stiffness()?);
    progress("zeno");
    demos.extend(zeno()?);
    progress("grazing");
    demos.extend(grazing()?);
    Ok(demos)
}
