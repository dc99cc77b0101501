//! What each case of a finished sweep left of its wall's capacity (`pirqa sweep FILE
//! --residual`): the limit at rest of the wall where the case's run left it (its blocks moved by
//! their final displacements from blocks.csv, the fallen ones taken out:
//! [`crate::response::moved`]), beside the limit of the case's wall as built, and the share of
//! it left. Nothing is run again: the tables are read back exactly (`{:e}` floats).

use super::store::{read_table, BlockRow, CaseRow, Paths, BLOCKS_HEADER};
use super::Sweep;
use crate::error::{Error, SimulationError};
use crate::exact::Q;
use crate::limit::{self, Limit, Limits};
use crate::plot::chart::{self, Chart, Series};
use crate::response::moved;
use crate::response::saved::SavedState;
use crate::study::stats::quantile;
use crate::table;
use rayon::prelude::*;
use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

/// The columns of `residual.csv`.
pub const RESIDUAL_HEADER: &str = "case,wall,motion,pga_gal,sample,plus_x_g,minus_x_g,\
plus_x_exact_g,minus_x_exact_g,as_built_plus_x_g,as_built_minus_x_g,capacity_left,fallen,\
joints_lost,joints_new,error";

/// One case's residual limit (a row of `residual.csv`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct ResidualRow {
    /// Case number.
    pub case: usize,
    /// Wall label.
    pub wall: String,
    /// Motion label.
    pub motion: String,
    /// Peak ground acceleration (gal).
    #[serde(serialize_with = "table::plain")]
    pub pga_gal: f64,
    /// Friction sample.
    pub sample: usize,
    /// The limit at rest of the wall where the run left it, ground towards +x and -x (g);
    /// empty where it holds at any acceleration or was not computed.
    #[serde(serialize_with = "table::sci_opt")]
    pub plus_x_g: Option<f64>,
    /// Ground towards -x, as `plus_x_g`.
    #[serde(serialize_with = "table::sci_opt")]
    pub minus_x_g: Option<f64>,
    /// `plus_x_g` as an exact fraction, or `unlimited`.
    pub plus_x_exact_g: String,
    /// `minus_x_g` as an exact fraction, or `unlimited`.
    pub minus_x_exact_g: String,
    /// The limit of the case's wall as built (its friction sample), ground towards +x (g).
    #[serde(serialize_with = "table::sci_opt")]
    pub as_built_plus_x_g: Option<f64>,
    /// The same towards -x.
    #[serde(serialize_with = "table::sci_opt")]
    pub as_built_minus_x_g: Option<f64>,
    /// The smaller side left over the smaller side as built: 1 where the run took nothing.
    #[serde(serialize_with = "table::sci_opt")]
    pub capacity_left: Option<f64>,
    /// Blocks fallen (`; ` between them).
    pub fallen: String,
    /// Horizontal joints slid apart (`upper/lower`).
    pub joints_lost: String,
    /// Horizontal joints slid onto.
    pub joints_new: String,
    /// Why the limit was not computed.
    pub error: Option<String>,
}

/// Both sides of a limit as floats (g; `None` where it holds at any acceleration) and exact.
fn sides(l: &Limits) -> [(Option<f64>, String); 2] {
    [&l.towards_plus_x, &l.towards_minus_x].map(|l| match l {
        Limit::Unlimited => (None, "unlimited".into()),
        Limit::Holds {
            accel_g, exact_g, ..
        } => (Some(*accel_g), exact_g.clone()),
    })
}

/// The smaller side of a limit exactly (g), `None` where either side holds at any acceleration.
fn least(l: &Limits) -> Option<Q> {
    Some(
        l.towards_plus_x
            .in_g()?
            .clone()
            .min(l.towards_minus_x.in_g()?.clone()),
    )
}

/// The limit at rest of a wall, `stop` asked before every pivot; the reason where there is none.
fn limit_until(
    wall: &crate::wall::Wall,
    topo: &crate::topology::Topology,
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<Limits, String> {
    match limit::at_rest_until(wall, topo, &|| stop()) {
        Ok(Some(l)) => Ok(l),
        Ok(None) => Err("stopped before the limit was proved".into()),
        Err(SimulationError::NotApplicable(why)) => Err(why),
        Err(e) => Err(e.to_string()),
    }
}

/// A case's wall as built: its graph with the case's friction sample, and its limit.
type Built = (crate::topology::Topology, Result<Limits, String>);

/// The residual limit of case `row`: its blocks' rows `blocks` (every block of its wall, by
/// name), `built` its wall's graph and limit as built.
fn of_case(
    sweep: &Sweep,
    row: &CaseRow,
    blocks: &[&BlockRow],
    (topo, as_built): &Built,
    stop: &(dyn Fn() -> bool + Sync),
) -> ResidualRow {
    let built = as_built.as_ref().ok().map(sides);
    let mut out = ResidualRow {
        case: row.case,
        wall: row.wall.clone(),
        motion: row.motion.clone(),
        pga_gal: row.pga_gal,
        sample: row.sample,
        plus_x_g: None,
        minus_x_g: None,
        plus_x_exact_g: String::new(),
        minus_x_exact_g: String::new(),
        as_built_plus_x_g: built.as_ref().and_then(|b| b[0].0),
        as_built_minus_x_g: built.as_ref().and_then(|b| b[1].0),
        capacity_left: None,
        fallen: String::new(),
        joints_lost: String::new(),
        joints_new: String::new(),
        error: None,
    };
    let sw = &sweep.walls[sweep.case(row.case).0];
    let limits = || -> Result<(Limits, moved::Moves), String> {
        if row.error.is_some() {
            return Err("the case's run failed (cases.csv says why)".into());
        }
        let by_name: HashMap<&str, &BlockRow> = blocks.iter().map(|b| (&*b.block, *b)).collect();
        let mut state = SavedState {
            time_s: 0.0,
            displacement_m: Vec::with_capacity(sw.wall.blocks.len()),
            fallen: Vec::with_capacity(sw.wall.blocks.len()),
            pose: None,
        };
        for b in &sw.wall.blocks {
            let r = by_name.get(&*b.name).ok_or_else(|| {
                format!("blocks.csv has no row for block {} of this case", b.name)
            })?;
            if r.max_abs_rotation_rad != 0.0 {
                return Err(format!(
                    "the case turned block {} (it ran a model that rocks blocks): the wall where \
                     a run left it is built for runs whose blocks slide",
                    b.name
                ));
            }
            state.displacement_m.push(r.final_u_m);
            state.fallen.push(r.fell);
        }
        let (wall, topo, moves) = moved::moved(&sw.wall, topo, &state)
            .map_err(|e| format!("the wall where the run left it: {e}"))?;
        Ok((limit_until(&wall, &topo, stop)?, moves))
    };
    match limits() {
        Ok((l, moves)) => {
            let [(p, pe), (m, me)] = sides(&l);
            (out.plus_x_g, out.minus_x_g) = (p, m);
            (out.plus_x_exact_g, out.minus_x_exact_g) = (pe, me);
            out.capacity_left = match (least(&l), as_built.as_ref().ok().and_then(least)) {
                // The ratio of the exact limits, rounded once.
                (Some(left), Some(built)) => Some((left / built).to_f64()),
                _ => None,
            };
            out.fallen = moves.fallen.join("; ");
            out.joints_lost = moves.joints_lost.join("; ");
            out.joints_new = moves.joints_new.join("; ");
        }
        Err(why) => out.error = Some(why),
    }
    out
}

/// The residual limits of every case of the sweep finished in `dir`, in case order, written
/// to `dir/residual.csv` as they come (a chunk of cases at a time, so a run stopped part way
/// keeps what it finished), then charted (`capacity-left.svg`, its data in
/// `capacity-left.csv`). `done` is called once per case; `stop` is asked before every pivot of
/// the limits' programs, and a stop leaves the rest of the cases out.
pub fn write(
    sweep: &Sweep,
    rows: &[CaseRow],
    dir: &Path,
    done: &(dyn Fn() + Sync),
    stop: &(dyn Fn() -> bool + Sync),
) -> Result<Vec<ResidualRow>, Error> {
    let paths = Paths::of(dir);
    let blocks: Vec<BlockRow> = read_table(&paths.blocks, BLOCKS_HEADER)?;
    let mut of: HashMap<usize, Vec<&BlockRow>> = HashMap::new();
    for b in &blocks {
        of.entry(b.case).or_default().push(b);
    }
    // The limit as built depends on the wall and the friction sample, not on the motion.
    let mut walls: Vec<(usize, usize)> = rows
        .iter()
        .map(|r| {
            let (w, _, s) = sweep.case(r.case);
            (w, s)
        })
        .collect();
    walls.sort_unstable();
    walls.dedup();
    let as_built: HashMap<(usize, usize), Built> = walls
        .par_iter()
        .map(|&(w, s)| {
            let sw = &sweep.walls[w];
            let topo = sw.topology.with_frictions(sweep.frictions(w, s));
            let limit = limit_until(&sw.wall, &topo, stop);
            ((w, s), (topo, limit))
        })
        .collect();
    let path = dir.join("residual.csv");
    let io = |e: std::io::Error| Error::Io {
        path: path.clone(),
        source: e,
    };
    let mut file = std::fs::File::create(&path).map_err(io)?;
    writeln!(file, "{RESIDUAL_HEADER}").map_err(io)?;
    let mut found = Vec::with_capacity(rows.len());
    let chunk = 4 * rayon::current_num_threads().max(1);
    for part in rows.chunks(chunk) {
        if stop() {
            break;
        }
        let residual: Vec<ResidualRow> = part
            .par_iter()
            .map(|r| {
                let (w, _, s) = sweep.case(r.case);
                let blocks = of.get(&r.case).map_or(&[][..], Vec::as_slice);
                let row = of_case(sweep, r, blocks, &as_built[&(w, s)], stop);
                done();
                row
            })
            .collect();
        let text: String = residual.iter().map(table::line).collect();
        file.write_all(text.as_bytes()).map_err(io)?;
        found.extend(residual);
    }
    if found.len() == rows.len() {
        let charts = [capacity_chart(sweep, &found)];
        let svg = dir.join("capacity-left.svg");
        std::fs::write(&svg, chart::render(&charts, 1, (900, 560))).map_err(|source| {
            Error::Io {
                path: svg.clone(),
                source,
            }
        })?;
        let csv = dir.join("capacity-left.csv");
        std::fs::write(&csv, chart::to_csv(&charts))
            .map_err(|source| Error::Io { path: csv, source })?;
    }
    Ok(found)
}

/// The share of its capacity each case left, against the motion's peak, a series per wall,
/// with its median and 5 % quantile at each peak (lines) over the cases (points).
fn capacity_chart(sweep: &Sweep, rows: &[ResidualRow]) -> Chart {
    let mut series = Vec::new();
    for (k, w) in sweep.walls.iter().enumerate() {
        let points: Vec<(f64, f64)> = (rows.iter())
            .filter(|r| r.wall == w.label)
            .filter_map(|r| Some((r.pga_gal, r.capacity_left?)))
            .collect();
        let mut levels: Vec<f64> = points.iter().map(|p| p.0).collect();
        levels.sort_by(f64::total_cmp);
        levels.dedup();
        let at = |p: f64| -> Vec<(f64, f64)> {
            (levels.iter())
                .filter_map(|&x| {
                    let mut ys: Vec<f64> =
                        (points.iter()).filter(|q| q.0 == x).map(|q| q.1).collect();
                    ys.sort_by(f64::total_cmp);
                    Some((x, quantile(&ys, p)?))
                })
                .collect()
        };
        series.push(Series {
            label: format!("{}: median", w.label),
            points: at(0.5),
            color: k,
            ..Series::default()
        });
        series.push(Series {
            label: format!("{}: 5 % quantile", w.label),
            points: at(0.05),
            color: k,
            dashed: true,
            ..Series::default()
        });
        series.push(Series {
            label: format!("{}: each case", w.label),
            points,
            color: k,
            scatter: true,
            ..Series::default()
        });
    }
    Chart {
        title: format!(
            "{}: the limit at rest left where each case's run left the wall",
            sweep.name
        ),
        x_label: "peak ground acceleration (gal)".into(),
        y_label: "limit left / limit as built".into(),
        series,
        legend: chart::Corner::LowerLeft,
        ..Chart::default()
    }
}
