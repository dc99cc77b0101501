//! The paper's figures, reproduced: Fig. 3 (maximum displacement against sine frequency,
//! uniform friction), Fig. 4 (variable friction, blocks B4 and B3, uniform dashed), Fig. 5 (the
//! wall after the record scaled by 5) and Fig. 6 (every block's displacement history), plus the
//! checks docs/paper.md discusses: convergence with the sine's duration and the paper's
//! findings as numbers.

use crate::error::Error;
use crate::integrate::event::EventDriven;
use crate::integrate::{AfterCollapse, Integrator, Scenario, Settings};
use crate::motion::synthetic::Synthetic;
use crate::motion::{read_record, Motion, ReadOptions, Record};
use crate::plot::chart::{self, Chart, Corner, Series};
use crate::plot::{draw_wall, WallDrawing};
use crate::response::Response;
use crate::study::sweep::store::{BlockRow, CaseRow};
use crate::study::sweep::{
    Frequencies, FrictionModel, MotionSet, Sweep, SweepDescription, WallSource,
};
use serde_json::{json, Value};
use std::collections::{BTreeMap, HashSet};
use std::path::{Path, PathBuf};

/// The Miyagi record's peak (gal), to which El Centro is scaled before the paper's factor 5.
pub const MIYAGI_PGA_GAL: f64 = 258.0;

/// What to reproduce the figures with.
#[derive(Debug, Clone)]
pub struct Options {
    /// Directory of five-block-uniform.ron and five-block-variable.ron.
    pub walls: PathBuf,
    /// El Centro (or another record) for Fig. 5 and 6.
    pub record: PathBuf,
    /// Sine duration (s); the paper does not give it.
    pub duration_s: f64,
    /// Sine frequencies.
    pub frequencies: Frequencies,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            walls: PathBuf::from("walls"),
            record: PathBuf::from(crate::motion::EL_CENTRO),
            duration_s: 20.0,
            frequencies: Frequencies::Log {
                from: 0.2,
                to: 10.0,
                count: 100,
            },
        }
    }
}

/// The figures (file name, contents) and the numbers docs/paper.md quotes.
pub struct Output {
    /// Files to write.
    pub files: Vec<(String, String)>,
    /// Findings as numbers (paper.json).
    pub numbers: Value,
}

/// Wall labels of the grid.
const MU20: &str = "uniform mu 0.20";
const MU30: &str = "uniform mu 0.30";
const VARIABLE: &str = "variable";

/// The grid of Fig. 3 and 4; wall paths are relative to the walls directory.
fn grid(duration_s: f64, frequencies: Frequencies) -> SweepDescription {
    let file = |name: &str, friction: Option<f64>, label: &str| WallSource::File {
        path: name.into(),
        friction,
        label: Some(label.into()),
    };
    SweepDescription {
        version: 1,
        name: format!("paper grid, {duration_s} s"),
        walls: vec![
            file("five-block-uniform.ron", Some(0.2), MU20),
            file("five-block-uniform.ron", None, MU30),
            file("five-block-variable.ron", None, VARIABLE),
        ],
        motion: MotionSet::Sine {
            amplitudes: ["200gal", "300gal", "400gal", "500gal"]
                .map(String::from)
                .to_vec(),
            frequencies_hz: frequencies,
            duration_s,
            phase_deg: 0.0,
        },
        friction: FrictionModel::Nominal,
        model: Default::default(),
        method: Default::default(),
        fallback: Default::default(),
        contact_solver: Default::default(),
        check_uplift: false,
        after_uplift: Default::default(),
    }
}

/// Runs a sweep in memory: every row and block row.
fn run_all(
    sweep: &Sweep,
    progress: &mut (dyn FnMut(&str, u64, u64) + Send),
) -> Result<(Vec<CaseRow>, Vec<BlockRow>), Error> {
    let (mut rows, mut blocks) = (Vec::new(), Vec::new());
    let total = sweep.len() as u64;
    sweep.run_cases(&HashSet::new(), |r, b| {
        rows.push(r);
        blocks.extend(b);
        progress(&sweep.name, rows.len() as u64, total);
        Ok(())
    })?;
    rows.sort_by_key(|r| r.case);
    Ok((rows, blocks))
}

/// A response value by (wall, amplitude in gal) over frequency.
type Curves = BTreeMap<(String, i64), Vec<(f64, f64)>>;

fn curves(rows: &[CaseRow], value: impl Fn(&CaseRow) -> Option<f64>) -> Curves {
    let mut out: Curves = BTreeMap::new();
    for r in rows.iter().filter(|r| r.error.is_none()) {
        if let (Some(f), Some(a), Some(v)) = (r.frequency_hz, r.amplitude_gal, value(r)) {
            out.entry((r.wall.clone(), a.round() as i64))
                .or_default()
                .push((f, v));
        }
    }
    for v in out.values_mut() {
        v.sort_by(|a, b| a.0.total_cmp(&b.0));
    }
    out
}

fn amp_color(gal: i64) -> usize {
    ((gal / 100 - 2).max(0)) as usize
}

fn curve_series(c: &Curves, wall: &str, amps: &[i64], dashed: bool, suffix: &str) -> Vec<Series> {
    amps.iter()
        .filter_map(|&a| {
            let pts = c.get(&(wall.to_string(), a))?;
            Some(Series {
                label: format!("{a} gal{suffix}"),
                points: pts.clone(),
                color: amp_color(a),
                dashed,
                ..Default::default()
            })
        })
        .collect()
}

fn freq_chart(title: &str, y: &str, series: Vec<Series>) -> Chart {
    Chart {
        title: title.into(),
        x_label: "sine frequency (Hz)".into(),
        y_label: y.into(),
        series,
        log_x: true,
        log_y: true,
        legend: Corner::UpperRight,
        ..Default::default()
    }
}

/// Reproduces every figure.
pub fn reproduce(
    opts: &Options,
    progress: &mut (dyn FnMut(&str, u64, u64) + Send),
) -> Result<Output, Error> {
    let mut files = Vec::new();
    let mut numbers = serde_json::Map::new();
    let origin = PathBuf::from(format!("<pirqa paper --walls {}>", opts.walls.display()));
    let origin = origin.as_path();
    let sweep = Sweep::from_description(
        &grid(opts.duration_s, opts.frequencies.clone()),
        &opts.walls,
        origin,
    )?;
    let (rows, blocks) = run_all(&sweep, progress)?;
    let by_case: BTreeMap<(usize, &str), f64> = blocks
        .iter()
        .map(|b| ((b.case, b.block.as_str()), b.max_abs_u_m))
        .collect();
    let max_u = curves(&rows, |r| (r.max_abs_u_m > 0.0).then_some(r.max_abs_u_m));
    let block_u = |name: &'static str| {
        curves(&rows, |r| {
            by_case.get(&(r.case, name)).copied().filter(|&u| u > 0.0)
        })
    };

    // Fig. 3.
    let fig3 = vec![
        freq_chart(
            "Fig. 3(a): uniform friction mu = 0.20",
            "max |u| of any block (m)",
            curve_series(&max_u, MU20, &[200, 300, 400, 500], false, ""),
        ),
        freq_chart(
            "Fig. 3(b): uniform friction mu = 0.30",
            "max |u| of any block (m)",
            curve_series(&max_u, MU30, &[300, 400, 500], false, ""),
        ),
    ];
    push_chart(&mut files, "fig3", &fig3, 2);

    // Fig. 4: variable solid, uniform 0.30 dashed, collapse marked.
    let amps = [300, 400, 500];
    let collapse_pts = |c: &Curves| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.wall == VARIABLE && r.collapsed)
            .filter_map(|r| {
                let a = r.amplitude_gal?.round() as i64;
                let f = r.frequency_hz?;
                c.get(&(VARIABLE.to_string(), a))?
                    .iter()
                    .find(|p| p.0 == f)
                    .copied()
            })
            .collect()
    };
    let mut fig4 = Vec::new();
    for (name, title) in [
        ("B4", "Fig. 4(a): upper central block B4"),
        ("B3", "Fig. 4(b): upper left block B3"),
    ] {
        let c = block_u(name);
        let mut series = curve_series(&c, VARIABLE, &amps, false, " variable");
        series.extend(curve_series(&c, MU30, &amps, true, " uniform"));
        let fell = collapse_pts(&c);
        if !fell.is_empty() {
            series.push(Series {
                label: "collapse".into(),
                points: fell,
                color: 3,
                scatter: true,
                ..Default::default()
            });
        }
        fig4.push(freq_chart(title, &format!("max |u| of {name} (m)"), series));
    }
    // The paper's comparison as a ratio: variable over uniform.
    let ratio: Vec<Series> = amps
        .iter()
        .filter_map(|&a| {
            let v = max_u.get(&(VARIABLE.to_string(), a))?;
            let u = max_u.get(&(MU30.to_string(), a))?;
            let pts = v
                .iter()
                .filter_map(|&(f, x)| u.iter().find(|p| p.0 == f).map(|&(_, y)| (f, x / y)))
                .collect();
            Some(Series {
                label: format!("{a} gal"),
                points: pts,
                color: amp_color(a),
                ..Default::default()
            })
        })
        .collect();
    fig4.push(Chart {
        title: "Fig. 4, as a ratio: variable over uniform (mu 0.30)".into(),
        x_label: "sine frequency (Hz)".into(),
        y_label: "max |u| variable / max |u| uniform".into(),
        series: ratio,
        log_x: true,
        log_y: true,
        ..Default::default()
    });
    push_chart(&mut files, "fig4", &fig4, 2);
    numbers.insert("findings".into(), findings(&rows, &max_u));

    // Convergence with duration: every tenth frequency at 10, 20 and 40 s.
    let some: Vec<f64> = opts.frequencies.values().into_iter().step_by(10).collect();
    let mut by_duration = BTreeMap::new();
    for d in [10.0, 20.0, 40.0] {
        let s = Sweep::from_description(
            &grid(d, Frequencies::List(some.clone())),
            &opts.walls,
            origin,
        )?;
        let (r, _) = run_all(&s, progress)?;
        by_duration.insert(d as i64, curves(&r, |r| Some(r.max_abs_u_m)));
    }
    let (conv, worst) = convergence(&by_duration);
    push_chart(&mut files, "duration", &conv, 2);
    numbers.insert("duration".into(), worst);

    // Fig. 5 and 6: the records scaled by 5.
    let raw = read_record(&opts.record, None, &ReadOptions::default())?;
    let motion_error = |path: &Path| {
        let path = path.to_path_buf();
        move |source| Error::Motion { path, source }
    };
    let el_centro = raw
        .scaled(MIYAGI_PGA_GAL / 100.0 / raw.pga_m_s2() * 5.0)
        .map_err(motion_error(&opts.record))?;
    let miyagi = Synthetic::miyagi_like()
        .record(0.01)
        .and_then(|r| r.scaled(5.0))
        .map_err(motion_error(Path::new("<miyagi-like>")))?;
    let mut records = serde_json::Map::new();
    for (tag, record) in [("elcentro", el_centro), ("miyagi-like", miyagi)] {
        let numbers = record_figures(opts, tag, &record, &mut files)?;
        records.insert(tag.into(), numbers);
    }
    numbers.insert("records".into(), Value::Object(records));
    numbers.insert(
        "settings".into(),
        json!({
            "duration_s": opts.duration_s,
            "frequencies_hz": opts.frequencies.values(),
            "record": opts.record.to_string_lossy(),
        }),
    );
    Ok(Output {
        files,
        numbers: Value::Object(numbers),
    })
}

fn push_chart(files: &mut Vec<(String, String)>, stem: &str, charts: &[Chart], columns: usize) {
    files.push((
        format!("{stem}.svg"),
        chart::render(charts, columns, (620, 440)),
    ));
    files.push((format!("{stem}.csv"), chart::to_csv(charts)));
}

/// The paper's findings, measured.
fn findings(rows: &[CaseRow], max_u: &Curves) -> Value {
    let wall_rows = |w: &'static str| {
        rows.iter()
            .filter(move |r| r.wall == w && r.error.is_none())
    };
    // Larger maxima at lower frequency: the share of neighbouring frequencies where the maximum
    // falls as the frequency rises.
    let mut falling = (0, 0);
    for pts in max_u.values() {
        for p in pts.windows(2) {
            falling.1 += 1;
            falling.0 += usize::from(p[1].1 < p[0].1);
        }
    }
    let ratio_at = |a: i64, low: bool| -> Option<f64> {
        let v = max_u.get(&(VARIABLE.to_string(), a))?;
        let u = max_u.get(&(MU30.to_string(), a))?;
        let (pv, pu) = if low {
            (v.first()?, u.first()?)
        } else {
            (v.last()?, u.last()?)
        };
        (pv.0 == pu.0).then(|| pv.1 / pu.1)
    };
    let collapses: Vec<Value> = wall_rows(VARIABLE)
        .filter(|r| r.collapsed)
        .map(|r| json!({"amplitude_gal": r.amplitude_gal, "frequency_hz": r.frequency_hz, "block": r.collapse_block, "time_s": r.collapse_time_s}))
        .collect();
    let (low, high) = (
        [300, 400, 500].map(|a| ratio_at(a, true)),
        [300, 400, 500].map(|a| ratio_at(a, false)),
    );
    json!({
        "falling_with_frequency": {"steps": falling.1, "falling": falling.0},
        "uniform_impacts": wall_rows(MU20).chain(wall_rows(MU30)).map(|r| r.impacts).sum::<u64>(),
        "uniform_max_block_on_block_slip_m": wall_rows(MU20).chain(wall_rows(MU30)).map(|r| r.max_rel_u_m).fold(0.0, f64::max),
        "variable_cases_with_impacts": wall_rows(VARIABLE).filter(|r| r.impacts > 0).count(),
        "variable_cases": wall_rows(VARIABLE).count(),
        "variable_max_opening_m": wall_rows(VARIABLE).map(|r| r.max_opening_m).fold(0.0, f64::max),
        "variable_over_uniform_lowest_frequency": low,
        "variable_over_uniform_highest_frequency": high,
        "variable_collapses": collapses,
        "failed_runs": rows.iter().filter(|r| r.error.is_some()).count(),
    })
}

/// max |u| after 40 s and 10 s against 20 s, per wall and amplitude.
fn convergence(by_duration: &BTreeMap<i64, Curves>) -> (Vec<Chart>, Value) {
    let base = &by_duration[&20];
    let mut charts = Vec::new();
    let mut worst = serde_json::Map::new();
    for wall in [MU30, VARIABLE] {
        let mut series = Vec::new();
        let mut w40: f64 = 0.0;
        for (k, (d, dash)) in [(40, false), (10, true)].into_iter().enumerate() {
            for a in [300, 400, 500] {
                let (Some(x), Some(b)) = (
                    by_duration[&d].get(&(wall.to_string(), a)),
                    base.get(&(wall.to_string(), a)),
                ) else {
                    continue;
                };
                let pts: Vec<(f64, f64)> = x
                    .iter()
                    .zip(b)
                    .filter(|(p, q)| q.1 > 0.0 && p.0 == q.0)
                    // Round-off shows as a floor of 1e-17 on the log axis.
                    .map(|(p, q)| (p.0, (p.1 / q.1 - 1.0).abs().max(1e-17)))
                    .collect();
                if d == 40 {
                    w40 = pts.iter().fold(w40, |m, p| m.max(p.1));
                }
                series.push(Series {
                    label: format!("{a} gal, {d} s against 20 s"),
                    points: pts,
                    color: amp_color(a) + 4 * k,
                    dashed: dash,
                    markers: true,
                    ..Default::default()
                });
            }
        }
        worst.insert(wall.into(), json!({"largest_change_from_20_to_40_s": w40}));
        charts.push(Chart {
            title: format!("{wall}: does max |u| depend on the duration?"),
            x_label: "sine frequency (Hz)".into(),
            y_label: "|max |u| / max |u| at 20 s - 1|".into(),
            series,
            log_x: true,
            log_y: true,
            legend: Corner::UpperRight,
            ..Default::default()
        });
    }
    (charts, Value::Object(worst))
}

/// Fig. 5 (final state, variable and uniform) and Fig. 6 (histories) under one record.
fn record_figures(
    opts: &Options,
    tag: &str,
    record: &Record,
    files: &mut Vec<(String, String)>,
) -> Result<Value, Error> {
    let motion = Motion::Record(record.clone());
    let mut numbers = serde_json::Map::new();
    numbers.insert("pga_gal".into(), json!(record.pga_m_s2() * 100.0));
    numbers.insert("duration_s".into(), json!(record.duration_s()));
    let mut histories = Vec::new();
    for (name, file) in [
        ("variable", "five-block-variable.ron"),
        ("uniform", "five-block-uniform.ron"),
    ] {
        let (wall, topo) = crate::topology::load(&opts.walls.join(file))?;
        let settings = Settings {
            duration_s: record.duration_s(),
            output_dt_s: Some(0.02),
            history_file: None,
            log_events: false,
            events_file: None,
            decisions_file: None,
            log_decisions: false,
            after_collapse: AfterCollapse::Continue,
            progress: None,
        };
        let r: Response = EventDriven::default().run(&Scenario {
            wall: &wall,
            topology: &topo,
            motion: &motion,
            settings: &settings,
        })?;
        let s = &r.summary;
        let fallen: Vec<bool> = s.blocks.iter().map(|b| b.fell).collect();
        let opening = topo
            .vertical
            .iter()
            .filter(|j| !fallen[j.left.0] && !fallen[j.right.0])
            .map(|j| r.final_displacement_m[j.right.0] - r.final_displacement_m[j.left.0])
            .fold(0.0f64, f64::max);
        // The whole wall may have slid metres: draw it shifted back by the smallest slide so
        // that it fits and its separations show.
        let shift = r
            .final_displacement_m
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let drawing = draw_wall(
            &wall,
            &topo,
            &WallDrawing {
                title: format!(
                    "Fig. 5: {name} friction after {} x5 (PGA {:.0} gal)",
                    if tag == "elcentro" {
                        "El Centro 1940 scaled to 258 gal,"
                    } else {
                        "the Miyagi-like synthetic record,"
                    },
                    record.pga_m_s2() * 100.0
                ),
                displacement_m: Some(r.final_displacement_m.iter().map(|u| u - shift).collect()),
                fallen: fallen.clone(),
                note: Some(format!(
                    "final state, all blocks shifted by {:+.3} m to fit the picture (relative positions as computed); widest opening {:.1} mm; {}",
                    -shift,
                    opening * 1e3,
                    s.collapse
                        .as_ref()
                        .map_or("no collapse".into(), |c| format!(
                            "{} fell at {:.2} s",
                            c.block, c.time_s
                        ))
                )),
                ..Default::default()
            },
        );
        files.push((format!("fig5-{tag}-{name}.svg"), drawing));
        numbers.insert(
            name.into(),
            json!({
                "max_abs_u_m": s.blocks.iter().map(|b| (b.name.clone(), b.max_abs_displacement_m)).collect::<BTreeMap<_, _>>(),
                "final_u_m": s.blocks.iter().map(|b| (b.name.clone(), b.final_displacement_m)).collect::<BTreeMap<_, _>>(),
                "widest_final_opening_m": opening,
                "impacts": s.impacts,
                "collapse": s.collapse.as_ref().map(|c| json!({"block": c.block, "time_s": c.time_s})),
                "max_block_on_block_slip_m": s.horizontal_joints.iter().filter(|j| j.lower != "ground").map(|j| j.max_abs_relative_displacement_m).fold(0.0, f64::max),
            }),
        );
        let h = r.history.as_ref().expect("history asked for");
        let series: Vec<Series> = s
            .blocks
            .iter()
            .enumerate()
            .map(|(i, b)| Series {
                label: b.name.clone(),
                points: h
                    .time_s
                    .iter()
                    .zip(&h.displacement_m)
                    .map(|(&t, u)| (t, u[i]))
                    .collect(),
                color: i,
                ..Default::default()
            })
            .collect();
        histories.push(Chart {
            title: format!("Fig. 6: {name} friction, {tag} x5"),
            x_label: "t (s)".into(),
            y_label: "u, relative to the ground (m)".into(),
            series,
            ..Default::default()
        });
    }
    push_chart(files, &format!("fig6-{tag}"), &histories, 1);
    Ok(Value::Object(numbers))
}
