//! What a sweep's rows show: response spectra and collapse maps for sine grids, incremental
//! dynamic analysis for scaled records, and, with random friction, the distribution of the
//! maximum displacement, the probability of collapse with its confidence interval, and
//! lognormal fragility curves (and, where the sweep checked uplift, the probability that some
//! block must start to turn beside them); across walls cut into different numbers of blocks,
//! how response and cost change with the block count.

use super::store::CaseRow;
use super::{FrictionModel, Sweep, SweepMethod};
use crate::plot::chart::{self, Chart, Corner, Series};
use crate::study::stats::{fit_fragility, power_law_exponent, quantile, wilson};
use serde_json::{json, Value};
use std::collections::BTreeMap;

/// Normal quantile of the two-sided 95 % intervals.
pub const Z95: f64 = 1.959_963_984_540_054;

/// Charts (one SVG each, panels `columns` across) and the numbers behind them.
pub struct Report {
    /// (file stem, panels, columns).
    pub figures: Vec<(String, Vec<Chart>, usize)>,
    /// Derived numbers (results.json).
    pub results: Value,
}

impl Report {
    /// The files of the report: each figure as SVG with its data as CSV, and results.json
    /// (name, contents).
    pub fn files(&self) -> Vec<(String, String)> {
        let mut files = Vec::new();
        for (stem, charts, columns) in &self.figures {
            files.push((
                format!("{stem}.svg"),
                chart::render(charts, *columns, (620, 420)),
            ));
            files.push((format!("{stem}.csv"), chart::to_csv(charts)));
        }
        files.push((
            "results.json".into(),
            serde_json::to_string_pretty(&self.results).expect("json") + "\n",
        ));
        files
    }

    /// Writes [`Report::files`] into `dir`, each file whole or not at all.
    pub fn write(&self, dir: &std::path::Path) -> Result<(), crate::Error> {
        for (name, text) in self.files() {
            crate::text::write(&dir.join(name), &text)?;
        }
        Ok(())
    }
}

/// The cases of one wall under one motion (one per friction sample), in sample order.
struct Cell<'a> {
    wall: usize,
    rows: Vec<&'a CaseRow>,
}

impl Cell<'_> {
    fn first(&self) -> &CaseRow {
        self.rows[0]
    }
    fn ok(&self) -> impl Iterator<Item = &&CaseRow> {
        self.rows.iter().filter(|r| r.error.is_none())
    }
    /// Median over samples of a quantity (the value itself for nominal friction).
    fn median(&self, f: impl Fn(&CaseRow) -> f64) -> Option<f64> {
        quantile(&sorted(self, f), 0.5)
    }
    fn collapses(&self) -> (u64, u64) {
        let n = self.ok().count() as u64;
        (self.ok().filter(|r| r.collapsed).count() as u64, n)
    }
    /// (cases where some block had to start to turn, cases the uplift check watched).
    fn uplifts(&self) -> (u64, u64) {
        let checked = || self.ok().filter(|r| r.uplift_checked_until_s.is_some());
        let lifted = checked().filter(|r| r.uplift_time_s.is_some()).count();
        (lifted as u64, checked().count() as u64)
    }
}

fn line(label: String, color: usize, points: Vec<(f64, f64)>) -> Series {
    Series {
        label,
        points,
        color,
        markers: true,
        ..Default::default()
    }
}

fn scatter(label: &str, color: usize, points: Vec<(f64, f64)>) -> Series {
    Series {
        label: label.into(),
        points,
        color,
        scatter: true,
        ..Default::default()
    }
}

/// Everything the rows show.
pub fn analyse(sweep: &Sweep, rows: &[CaseRow]) -> Report {
    // Group by (wall, motion) in the sweep's order.
    let mut cells: BTreeMap<(usize, usize), Cell> = BTreeMap::new();
    for r in rows {
        let (w, m, _) = sweep.case(r.case);
        cells
            .entry((w, m))
            .or_insert_with(|| Cell {
                wall: w,
                rows: Vec::new(),
            })
            .rows
            .push(r);
    }
    for c in cells.values_mut() {
        c.rows.sort_by_key(|r| r.sample);
    }
    let mut figures = Vec::new();
    let mut results = serde_json::Map::new();
    results.insert("name".into(), json!(sweep.name));
    results.insert("cases".into(), json!(rows.len()));
    let errors: Vec<Value> = rows
        .iter()
        .filter_map(|r| {
            r.error
                .as_ref()
                .map(|e| json!({"case": r.case, "wall": r.wall, "motion": r.motion, "error": e}))
        })
        .collect();
    results.insert("failed_runs".into(), json!(errors.len()));
    results.insert(
        "failed_examples".into(),
        Value::Array(errors.into_iter().take(10).collect()),
    );
    let sine = sweep.motions.iter().any(|m| m.frequency_hz.is_some());
    if sine {
        figures.push(("spectra".into(), spectra(sweep, &cells), 2));
        figures.push(("collapse-map".into(), collapse_map(sweep, &cells), 2));
    } else if sweep.motions.len() > 1 {
        // Intensity against response needs at least two intensities.
        let (charts, ida) = ida(sweep, &cells);
        figures.push(("ida".into(), charts, 2));
        results.insert("ida".into(), ida);
    }
    if let FrictionModel::Random { .. } = sweep.friction {
        let (charts, numbers) = distributions(sweep, &cells);
        figures.push(("distribution".into(), charts, 2));
        results.insert("levels".into(), numbers);
        if sweep.motions.len() > 1 {
            let (charts, fits) = fragility(sweep, &cells);
            figures.push(("fragility".into(), charts, 2));
            results.insert("fragility".into(), fits);
        }
    }
    if sweep.check_uplift {
        results.insert("uplift".into(), uplift(&cells, sweep));
    }
    if rows.iter().any(|r| r.max_overlap_loss.is_some()) {
        let beyond = small_displacements(&cells, sweep);
        results.insert("small_displacements".into(), beyond);
    }
    if let Some((charts, numbers)) = block_count(sweep, &cells) {
        figures.push(("block-count".into(), charts, 2));
        results.insert("block_count".into(), numbers);
    }
    Report {
        figures,
        results: Value::Object(results),
    }
}

/// Per wall: maximum and residual displacement against frequency, one line per amplitude.
fn spectra(sweep: &Sweep, cells: &BTreeMap<(usize, usize), Cell>) -> Vec<Chart> {
    let random = sweep.samples() > 1;
    let what = if random { "median " } else { "" };
    let mut charts = Vec::new();
    for (w, wall) in sweep.walls.iter().enumerate() {
        let mut by_amp: BTreeMap<i64, Vec<&Cell>> = BTreeMap::new();
        for c in cells.values().filter(|c| c.wall == w) {
            let a = c.first().amplitude_gal.unwrap_or(f64::NAN);
            by_amp.entry((a * 1e3) as i64).or_default().push(c);
        }
        let panel = |title: &str, y: &str, f: &dyn Fn(&CaseRow) -> f64| {
            let mut series = Vec::new();
            let mut fell = Vec::new();
            for (k, (amp, cs)) in by_amp.iter().enumerate() {
                let mut pts: Vec<(f64, f64)> = cs
                    .iter()
                    .filter_map(|c| Some((c.first().frequency_hz?, c.median(f)?)))
                    .collect();
                pts.sort_by(|a, b| a.0.total_cmp(&b.0));
                fell.extend(
                    cs.iter()
                        .filter(|c| c.collapses().0 > 0)
                        .filter_map(|c| Some((c.first().frequency_hz?, c.median(f)?))),
                );
                series.push(Series {
                    markers: false,
                    ..line(format!("{:.0} gal", *amp as f64 / 1e3), k, pts)
                });
            }
            if !fell.is_empty() {
                series.push(scatter("collapse", 3, fell));
            }
            Chart {
                title: format!("{}: {title}", wall.label),
                x_label: "sine frequency (Hz)".into(),
                y_label: format!("{what}{y} (m)"),
                series,
                log_x: true,
                log_y: true,
                ..Default::default()
            }
        };
        charts.push(panel(
            "maximum displacement",
            "max |u| of any block",
            &|r| r.max_abs_u_m,
        ));
        charts.push(panel(
            "residual displacement",
            "max |final u| of a standing block",
            &|r| r.residual_u_m,
        ));
    }
    charts
}

/// Per wall: which (frequency, amplitude) pairs collapse.
fn collapse_map(sweep: &Sweep, cells: &BTreeMap<(usize, usize), Cell>) -> Vec<Chart> {
    sweep
        .walls
        .iter()
        .enumerate()
        .map(|(w, wall)| {
            let (mut none, mut some, mut all) = (Vec::new(), Vec::new(), Vec::new());
            for c in cells.values().filter(|c| c.wall == w) {
                let (Some(f), Some(a)) = (c.first().frequency_hz, c.first().amplitude_gal) else {
                    continue;
                };
                match c.collapses() {
                    (0, _) => none.push((f, a)),
                    (k, n) if k == n => all.push((f, a)),
                    _ => some.push((f, a)),
                }
            }
            let mut series = vec![scatter("stands", 7, none)];
            if sweep.samples() > 1 {
                series.push(scatter("collapse in some samples", 1, some));
            }
            series.push(scatter("collapse", 3, all));
            Chart {
                title: format!("{}: collapse", wall.label),
                x_label: "sine frequency (Hz)".into(),
                y_label: "amplitude (gal)".into(),
                series,
                log_x: true,
                legend: Corner::UpperRight,
                ..Default::default()
            }
        })
        .collect()
}

/// Per wall: maximum displacement against PGA, one line per record, and, where any block
/// turned, its largest rotation against PGA likewise; the collapse intensity of each record
/// (the lowest PGA at which the wall collapses, or at which most samples do).
fn ida(sweep: &Sweep, cells: &BTreeMap<(usize, usize), Cell>) -> (Vec<Chart>, Value) {
    let median = if sweep.samples() > 1 { "median " } else { "" };
    let mut charts = Vec::new();
    let mut out = Vec::new();
    for (w, wall) in sweep.walls.iter().enumerate() {
        let mut by_record: BTreeMap<String, Vec<&Cell>> = BTreeMap::new();
        for c in cells.values().filter(|c| c.wall == w) {
            by_record
                .entry(c.first().record.clone().unwrap_or_default())
                .or_default()
                .push(c);
        }
        let mut series = Vec::new();
        let mut turned = Vec::new();
        let mut fell = Vec::new();
        for (k, (record, cs)) in by_record.iter().enumerate() {
            let mut cs = cs.clone();
            cs.sort_by(|a, b| a.first().pga_gal.total_cmp(&b.first().pga_gal));
            let against_pga = |f: fn(&CaseRow) -> f64| -> Vec<(f64, f64)> {
                cs.iter()
                    .filter_map(|c| Some((c.first().pga_gal, c.median(f)?)))
                    .collect()
            };
            let pts = against_pga(|r| r.max_abs_u_m);
            turned.push(line(
                record.clone(),
                k,
                against_pga(|r| r.max_abs_rotation_rad),
            ));
            // The lowest level at which the wall collapses (nominal) or most samples do.
            let collapsing = cs.iter().find(|c| {
                let (k, n) = c.collapses();
                n > 0 && 2 * k >= n
            });
            fell.extend(
                cs.iter()
                    .filter(|c| c.collapses().0 > 0)
                    .filter_map(|c| Some((c.first().pga_gal, c.median(|r| r.max_abs_u_m)?))),
            );
            out.push(json!({
                "wall": wall.label,
                "record": record,
                "collapse_pga_gal": collapsing.map(|c| c.first().pga_gal),
                "collapse_scale": collapsing.and_then(|c| c.first().scale),
            }));
            series.push(line(record.clone(), k, pts));
        }
        if !fell.is_empty() {
            series.push(scatter("collapse", 3, fell));
        }
        charts.push(Chart {
            title: format!("{}: incremental dynamic analysis", wall.label),
            x_label: "PGA (gal)".into(),
            y_label: format!("{median}max |u| of any block (m)"),
            series,
            log_y: true,
            legend: Corner::LowerRight,
            ..Default::default()
        });
        // Where blocks turned, how far: what the displacement alone does not tell.
        if turned.iter().flat_map(|s| &s.points).any(|p| p.1 > 0.0) {
            charts.push(Chart {
                title: format!("{}: rotation", wall.label),
                x_label: "PGA (gal)".into(),
                y_label: format!("{median}max |theta| of any block (rad)"),
                series: turned,
                legend: Corner::UpperLeft,
                ..Default::default()
            });
        }
    }
    (charts, Value::Array(out))
}

/// Per wall: the empirical distribution of the maximum displacement at (up to six) motions, and
/// per (wall, motion) the collapse probability with its 95 % interval and quantiles.
fn distributions(sweep: &Sweep, cells: &BTreeMap<(usize, usize), Cell>) -> (Vec<Chart>, Value) {
    let mut charts = Vec::new();
    let mut numbers = Vec::new();
    for (w, wall) in sweep.walls.iter().enumerate() {
        let cs: Vec<&Cell> = cells.values().filter(|c| c.wall == w).collect();
        let shown: Vec<usize> = if cs.len() <= 6 {
            (0..cs.len()).collect()
        } else {
            (0..6).map(|k| k * (cs.len() - 1) / 5).collect()
        };
        let mut series = Vec::new();
        for (k, c) in cs.iter().enumerate() {
            let v = sorted(c, |r| r.max_abs_u_m);
            let (hits, n) = c.collapses();
            let (lo, hi) = wilson(hits, n, Z95);
            numbers.push(json!({
                "wall": wall.label,
                "motion": c.first().motion,
                "pga_gal": c.first().pga_gal,
                "samples": n,
                "collapses": hits,
                "p_collapse": if n > 0 { hits as f64 / n as f64 } else { f64::NAN },
                "p_collapse_ci95": [lo, hi],
                "max_abs_u_m_p05": quantile(&v, 0.05),
                "max_abs_u_m_p50": quantile(&v, 0.5),
                "max_abs_u_m_p95": quantile(&v, 0.95),
            }));
            if shown.contains(&k) && !v.is_empty() {
                let n = v.len() as f64;
                let pts = v
                    .iter()
                    .enumerate()
                    .map(|(i, &x)| (x, (i as f64 + 1.0) / n))
                    .collect();
                series.push(Series {
                    label: c.first().motion.clone(),
                    points: pts,
                    color: series.len(),
                    ..Default::default()
                });
            }
        }
        charts.push(Chart {
            title: format!("{}: distribution over friction samples", wall.label),
            x_label: "max |u| of any block (m)".into(),
            y_label: "fraction of samples at or below".into(),
            series,
            log_x: true,
            legend: Corner::LowerRight,
            ..Default::default()
        });
    }
    (charts, Value::Array(numbers))
}

/// Pushes the series of a probability against PGA (observed, its 95 % interval dashed, and its
/// lognormal fit) in colour `k`, labelled by `what`; returns the fit.
fn probability_series(
    series: &mut Vec<Series>,
    levels: &[(f64, u64, u64)],
    k: usize,
    what: &str,
) -> Option<crate::study::stats::Fragility> {
    let [p, lower, upper] = observed(levels);
    series.push(Series {
        scatter: true,
        ..line(format!("{what}: observed"), k, p)
    });
    for band in [lower, upper] {
        series.push(Series {
            dashed: true,
            ..line(String::new(), k, band)
        });
    }
    let fit = fit_fragility(levels);
    if let Some(f) = fit {
        let (x0, x1) = (levels[0].0, levels[levels.len() - 1].0);
        let curve = (0..=60)
            .map(|i| {
                let x = x0 + (x1 - x0) * i as f64 / 60.0;
                (x, f.probability(x))
            })
            .collect();
        series.push(Series {
            markers: false,
            ..line(
                format!(
                    "{what}: lognormal fit, median {:.0} gal, beta {:.2}",
                    f.median, f.beta
                ),
                k,
                curve,
            )
        });
    }
    fit
}

/// Per wall and motion, what the uplift check found: the cases it watched, those in which some
/// block had to start to turn, the earliest such instant, and how many of those first uplifts
/// start by the only mechanism that holds then (the rest by one of several, or undecided).
fn uplift(cells: &BTreeMap<(usize, usize), Cell>, sweep: &Sweep) -> Value {
    use crate::limit::Uniqueness;
    let rows: Vec<Value> = cells
        .values()
        .map(|c| {
            let (lifted, checked) = c.uplifts();
            let first = c
                .ok()
                .filter_map(|r| r.uplift_time_s)
                .min_by(f64::total_cmp);
            let by = |u: Uniqueness| {
                c.ok()
                    .filter(|r| r.uplift_mechanism_uniqueness == Some(u))
                    .count()
            };
            json!({
                "wall": sweep.walls[c.wall].label,
                "motion": c.first().motion,
                "pga_gal": c.first().pga_gal,
                "checked": checked,
                "lifted": lifted,
                "first_uplift_s": first,
                "lifted_by_unique_mechanism": by(Uniqueness::Unique),
                "lifted_by_one_of_several": by(Uniqueness::OneOfSeveral),
                "lifted_undecided": by(Uniqueness::Undecided),
            })
        })
        .collect();
    Value::Array(rows)
}

/// Per wall and motion, how far the sliding cases left the overlaps at rest whose loads the
/// model keeps: the cases that slid, those that lost a share of some joint's overlap no longer
/// small ([`SMALL_OVERLAP_LOSS`], each of them warned), and the largest share lost.
///
/// [`SMALL_OVERLAP_LOSS`]: crate::validity::SMALL_OVERLAP_LOSS
fn small_displacements(cells: &BTreeMap<(usize, usize), Cell>, sweep: &Sweep) -> Value {
    let rows: Vec<Value> = cells
        .values()
        .map(|c| {
            let losses: Vec<f64> = c.ok().filter_map(|r| r.max_overlap_loss).collect();
            let beyond = losses
                .iter()
                .filter(|&&l| l >= crate::validity::SMALL_OVERLAP_LOSS)
                .count();
            json!({
                "wall": sweep.walls[c.wall].label,
                "motion": c.first().motion,
                "pga_gal": c.first().pga_gal,
                "slid": losses.len(),
                "beyond_small": beyond,
                "largest_overlap_loss": losses.iter().copied().reduce(f64::max),
            })
        })
        .collect();
    Value::Array(rows)
}

/// The points of a probability against PGA (gal) from (pga, cases, hits) levels, with the
/// 95 % interval's lower and upper bounds.
fn observed(levels: &[(f64, u64, u64)]) -> [Vec<(f64, f64)>; 3] {
    let counted = || levels.iter().filter(|l| l.1 > 0);
    [
        counted()
            .map(|&(x, n, h)| (x, h as f64 / n as f64))
            .collect(),
        counted()
            .map(|&(x, n, h)| (x, wilson(h, n, Z95).0))
            .collect(),
        counted()
            .map(|&(x, n, h)| (x, wilson(h, n, Z95).1))
            .collect(),
    ]
}

/// Per wall and record (or sine frequency): the probability of collapse against PGA with its
/// 95 % interval, and the lognormal fragility curve fitted to it (and of uplift, where
/// the sweep checked it).
fn fragility(sweep: &Sweep, cells: &BTreeMap<(usize, usize), Cell>) -> (Vec<Chart>, Value) {
    let mut charts = Vec::new();
    let mut fits = Vec::new();
    for (w, wall) in sweep.walls.iter().enumerate() {
        let mut groups: BTreeMap<String, Vec<&Cell>> = BTreeMap::new();
        for c in cells.values().filter(|c| c.wall == w) {
            let key = match (&c.first().record, c.first().frequency_hz) {
                (Some(r), _) => r.clone(),
                (None, Some(f)) => format!("sine {f} Hz"),
                _ => String::new(),
            };
            groups.entry(key).or_default().push(c);
        }
        let mut series = Vec::new();
        for (k, (group, cs)) in groups.iter().enumerate().take(4) {
            let levels = |count: &dyn Fn(&Cell) -> (u64, u64)| -> Vec<(f64, u64, u64)> {
                let mut levels: Vec<(f64, u64, u64)> = cs
                    .iter()
                    .map(|c| {
                        let (hits, n) = count(c);
                        (c.first().pga_gal, n, hits)
                    })
                    .collect();
                levels.sort_by(|a, b| a.0.total_cmp(&b.0));
                levels
            };
            let collapses = levels(&|c| c.collapses());
            // Beside uplift, collapse says what it is.
            let what = if sweep.check_uplift {
                format!("{group}: collapse")
            } else {
                group.clone()
            };
            let fit = probability_series(&mut series, &collapses, k, &what);
            let mut numbers = json!({
                "wall": wall.label,
                "group": group,
                "levels": collapses.iter().map(|l| json!({"pga_gal": l.0, "samples": l.1, "collapses": l.2})).collect::<Vec<_>>(),
                "median_pga_gal": fit.map(|f| f.median),
                "beta": fit.map(|f| f.beta),
            });
            if sweep.check_uplift {
                // Beside collapse, the probability that the sliding answer leaves rocking out.
                let lifts = levels(&|c| c.uplifts());
                let fit =
                    probability_series(&mut series, &lifts, k + 4, &format!("{group}: uplift"));
                numbers["uplift_levels"] = lifts
                    .iter()
                    .map(|l| json!({"pga_gal": l.0, "checked": l.1, "lifted": l.2}))
                    .collect();
                numbers["uplift_median_pga_gal"] = json!(fit.map(|f| f.median));
                numbers["uplift_beta"] = json!(fit.map(|f| f.beta));
            }
            fits.push(numbers);
        }
        charts.push(Chart {
            title: format!("{}: fragility (95 % intervals dashed)", wall.label),
            x_label: "PGA (gal)".into(),
            y_label: if sweep.check_uplift {
                "probability of collapse, of uplift".into()
            } else {
                "probability of collapse".into()
            },
            series,
            legend: Corner::UpperLeft,
            ..Default::default()
        });
    }
    (charts, Value::Array(fits))
}

/// Sorted values of a quantity over a cell's successful samples.
fn sorted(c: &Cell, f: impl Fn(&CaseRow) -> f64) -> Vec<f64> {
    let mut v: Vec<f64> = c.ok().map(|r| f(r)).collect();
    v.sort_by(f64::total_cmp);
    v
}

/// When the walls come in at least three block counts (one wall cut ever finer): per motion,
/// the response (median and 5-95 % band over friction samples), the probability of collapse with
/// its 95 % interval, and the cost (CPU time and events per case, CPU time per event, the work
/// of the exact decisions per event) against the number of blocks, with the power-law exponents
/// of the cost. A time-stepped sweep handles no events and makes no exact decisions: its cost is
/// the CPU time per case alone.
fn block_count(
    sweep: &Sweep,
    cells: &BTreeMap<(usize, usize), Cell>,
) -> Option<(Vec<Chart>, Value)> {
    let counts: std::collections::BTreeSet<usize> =
        sweep.walls.iter().map(|w| w.wall.blocks.len()).collect();
    if counts.len() < 3 {
        return None;
    }
    let exact = sweep.method == SweepMethod::Event;
    let panel = |title: &str, y: &str, log_y: bool| Chart {
        title: title.into(),
        x_label: "blocks in the wall".into(),
        y_label: y.into(),
        log_x: true,
        log_y,
        legend: Corner::UpperLeft,
        ..Default::default()
    };
    let mut charts = vec![
        panel("maximum displacement", "max |u| of any block (m)", true),
        Chart {
            // The small walls' upper band starts high on the left.
            legend: Corner::LowerRight,
            ..panel(
                "widest final opening of a vertical joint",
                "opening (m)",
                false,
            )
        },
        panel(
            "probability of collapse (95 % intervals dashed)",
            "probability",
            false,
        ),
        panel("events per case", "events", true),
        panel("CPU time per case", "CPU time (s)", true),
        panel("CPU time per event", "CPU time per event (s)", true),
        panel(
            "work of the exact decisions per event",
            "blocks in decisions, flow-network nodes",
            true,
        ),
    ];
    let mut numbers = Vec::new();
    for (m, motion) in sweep.motions.iter().enumerate().take(4) {
        let mut by_count: Vec<&Cell> = cells
            .values()
            .filter(|c| sweep.case(c.first().case).1 == m)
            .collect();
        by_count.sort_by_key(|c| c.first().blocks);
        let x = |c: &Cell| c.first().blocks as f64;
        let band = |f: &dyn Fn(&CaseRow) -> f64, p: f64| -> Vec<(f64, f64)> {
            by_count
                .iter()
                .filter_map(|c| Some((x(c), quantile(&sorted(c, f), p)?)))
                .collect()
        };
        let label = |what: &str| {
            if sweep.motions.len() > 1 {
                format!("{}: {what}", motion.label)
            } else {
                what.to_string()
            }
        };
        let mut add = |panel: usize, f: &dyn Fn(&CaseRow) -> f64, with_band: bool| {
            let s = &mut charts[panel].series;
            s.push(line(label("median"), m, band(f, 0.5)));
            if with_band && sweep.samples() > 1 {
                for p in [0.05, 0.95] {
                    s.push(Series {
                        dashed: true,
                        ..line(
                            if p < 0.5 {
                                label("5 % and 95 %")
                            } else {
                                String::new()
                            },
                            m,
                            band(f, p),
                        )
                    });
                }
            }
        };
        add(0, &|r| r.max_abs_u_m, true);
        add(1, &|r| r.max_opening_m, true);
        add(3, &|r| r.events as f64, false);
        add(4, &|r| r.cpu_s, false);
        add(5, &|r| r.cpu_s / r.events.max(1) as f64, false);
        if let Some(events) = charts[3].series.last_mut() {
            events.label = label("events handled (median)");
        }
        // Stick-slip transitions beside the events: what a run reports, against what the
        // integrator handled (one event can start many joints slipping).
        let transitions = band(&|r| r.transitions as f64, 0.5);
        charts[3].series.push(Series {
            dashed: true,
            ..line(
                label("stick-slip transitions (median)"),
                m + 4,
                transitions.clone(),
            )
        });
        // What the cost follows: the size of the groups the decisions take in, and the flows
        // over them.
        let per_event =
            |f: fn(&CaseRow) -> u64| move |r: &CaseRow| f(r) as f64 / r.events.max(1) as f64;
        charts[6].series.push(line(
            label("blocks in decisions per event"),
            m,
            band(&per_event(|r| r.decision_blocks), 0.5),
        ));
        charts[6].series.push(line(
            label("flow-network nodes per event"),
            m + 4,
            band(&per_event(|r| r.flow_nodes), 0.5),
        ));
        let p: Vec<(f64, f64, f64, f64)> = by_count
            .iter()
            .filter_map(|c| {
                let (k, n) = c.collapses();
                let (lo, hi) = wilson(k, n, Z95);
                (n > 0).then(|| (x(c), k as f64 / n as f64, lo, hi))
            })
            .collect();
        let s = &mut charts[2].series;
        s.push(line(
            label("observed"),
            m,
            p.iter().map(|q| (q.0, q.1)).collect(),
        ));
        for hi in [false, true] {
            s.push(Series {
                dashed: true,
                ..line(
                    String::new(),
                    m,
                    p.iter()
                        .map(|q| (q.0, if hi { q.3 } else { q.2 }))
                        .collect(),
                )
            });
        }
        let cpu = band(&|r| r.cpu_s, 0.5);
        let events = band(&|r| r.events as f64, 0.5);
        // The events times the wall's height in courses, which the cost follows in the
        // block-count studies (docs/block-count.md): per block count, (blocks, events x courses,
        // CPU time), medians.
        let by_work: Vec<(f64, f64, f64)> = by_count
            .iter()
            .filter_map(|c| {
                let w = &sweep.walls[c.wall];
                let courses = w.topology.courses(&w.wall) as f64;
                let events = c.median(|r| r.events as f64)?;
                Some((x(c), events * courses, c.median(|r| r.cpu_s)?))
            })
            .collect();
        let events_x_courses: Vec<(f64, f64)> = by_work.iter().map(|p| (p.0, p.1)).collect();
        // The cost of the smallest wall scaled by the events, and by the events times the
        // courses: where the measured line runs above one, each event (or each event and
        // course) costs more on a larger wall.
        if let Some(&(x0, c0)) = cpu.first() {
            for (what, work, colour) in [
                ("if it grew as the events", &events, m),
                (
                    "if it grew as the events x the courses",
                    &events_x_courses,
                    m + 4,
                ),
            ] {
                if let Some(&(_, w0)) = work.first().filter(|p| p.0 == x0 && p.1 > 0.0) {
                    charts[4].series.push(Series {
                        dashed: true,
                        ..line(
                            label(what),
                            colour,
                            work.iter().map(|&(x, w)| (x, c0 * w / w0)).collect(),
                        )
                    });
                }
            }
        }
        let mut motion_numbers = json!({
            "motion": motion.label,
            "cpu_exponent": power_law_exponent(&cpu),
            "cpu_exponent_in_events_x_courses": power_law_exponent(
                &by_work.iter().map(|p| (p.1, p.2)).collect::<Vec<_>>()
            ),
            "events_exponent": power_law_exponent(&events),
            "transitions_exponent": power_law_exponent(&transitions),
            "decision_blocks_exponent":
                power_law_exponent(&band(&|r| r.decision_blocks as f64, 0.5)),
            "flow_nodes_exponent": power_law_exponent(&band(&|r| r.flow_nodes as f64, 0.5)),
            "walls": by_count.iter().map(|c| {
                let (k, n) = c.collapses();
                json!({
                    "wall": sweep.walls[c.wall].label,
                    "blocks": c.first().blocks,
                    "samples": n,
                    "collapses": k,
                    "p_collapse_ci95": wilson(k, n, Z95),
                    "max_abs_u_m_p50": c.median(|r| r.max_abs_u_m),
                    "max_rel_u_m_p50": c.median(|r| r.max_rel_u_m),
                    "max_opening_m_p50": c.median(|r| r.max_opening_m),
                    "open_joints_p50": c.median(|r| r.open_joints as f64),
                    "impacts_p50": c.median(|r| r.impacts as f64),
                    "events_p50": c.median(|r| r.events as f64),
                    "transitions_p50": c.median(|r| r.transitions as f64),
                    "decision_blocks_p50": c.median(|r| r.decision_blocks as f64),
                    "flow_nodes_p50": c.median(|r| r.flow_nodes as f64),
                    "cpu_s_p50": c.median(|r| r.cpu_s),
                    "cpu_s_per_event_p50": c.median(|r| r.cpu_s / r.events.max(1) as f64),
                })
            }).collect::<Vec<_>>(),
        });
        if !exact {
            strip_event_numbers(&mut motion_numbers);
        }
        numbers.push(motion_numbers);
    }
    if !exact {
        // Events per case, CPU time per event, the exact decisions' work.
        for panel in [6, 5, 3] {
            charts.remove(panel);
        }
    }
    Some((charts, Value::Array(numbers)))
}

/// Removes from a motion's block-count numbers those of the exact engine's events and
/// decisions (a time-stepped sweep has neither).
fn strip_event_numbers(numbers: &mut Value) {
    if let Some(o) = numbers.as_object_mut() {
        for key in [
            "cpu_exponent_in_events_x_courses",
            "events_exponent",
            "transitions_exponent",
            "decision_blocks_exponent",
            "flow_nodes_exponent",
        ] {
            o.remove(key);
        }
    }
    if let Some(walls) = numbers.get_mut("walls").and_then(Value::as_array_mut) {
        for wall in walls.iter_mut().filter_map(Value::as_object_mut) {
            for key in [
                "events_p50",
                "transitions_p50",
                "decision_blocks_p50",
                "flow_nodes_p50",
                "cpu_s_per_event_p50",
            ] {
                wall.remove(key);
            }
        }
    }
}
