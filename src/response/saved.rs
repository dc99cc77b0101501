//! Reading a run back from its directory (`summary.json`, `history.csv`, `events.jsonl`): the
//! state of every block at the end or at a chosen time, to draw it after the fact.

use crate::error::Error;
use crate::wall::Wall;
use std::path::Path;

/// Where each block of a wall was at one instant of a saved run.
#[derive(Debug, Clone, PartialEq)]
pub struct SavedState {
    /// The instant (s): the end of the run, or the last history sample at or before the time asked.
    pub time_s: f64,
    /// Displacement of each block relative to the ground (m), in the wall's block order.
    pub displacement_m: Vec<f64>,
    /// Blocks that had fallen by then.
    pub fallen: Vec<bool>,
    /// Each block's rotation (rad, clockwise positive) and the vertical displacement of the
    /// middle of its base (m), when the run rotated blocks and its history says.
    pub pose: Option<(Vec<f64>, Vec<f64>)>,
}

fn table(path: &Path, line: usize, message: String) -> Error {
    Error::Table {
        path: path.to_path_buf(),
        line,
        message,
    }
}

fn read(path: &Path) -> Result<String, Error> {
    std::fs::read_to_string(path).map_err(|source| Error::Io {
        path: path.to_path_buf(),
        source,
    })
}

/// The state of the blocks of `wall` in the run saved in `dir`: at the end (`at_s` = `None`,
/// exact final displacements from summary.json) or at the last history sample at or before
/// `at_s`. A run of another wall (by name), a block the run does not know, or a time outside
/// the run is an error.
pub fn state_at(dir: &Path, wall: &Wall, at_s: Option<f64>) -> Result<SavedState, Error> {
    let summary_path = dir.join("summary.json");
    let summary: serde_json::Value = serde_json::from_str(&read(&summary_path)?)
        .map_err(|e| table(&summary_path, e.line(), format!("not a pirqa summary: {e}")))?;
    let ran = summary["wall"]
        .as_str()
        .ok_or_else(|| table(&summary_path, 1, "no `wall`: not a pirqa summary".into()))?;
    if ran != wall.name {
        return Err(table(
            &summary_path,
            1,
            format!(
                "this is a run of the wall \"{ran}\", not of \"{}\": give the wall file it ran \
                 (the wall.ron beside its summary)",
                wall.name
            ),
        ));
    }
    let names: Vec<String> = wall.blocks.iter().map(|b| b.name.clone()).collect();
    let names = names.as_slice();
    let duration_s = summary["duration_s"].as_f64().ok_or_else(|| {
        table(
            &summary_path,
            1,
            "no `duration_s`: not a pirqa summary".into(),
        )
    })?;
    let blocks = summary["blocks"].as_array().cloned().unwrap_or_default();
    // Looked up by name once each: a wall of 10,000 blocks searched block by block took seconds.
    let by_name: std::collections::HashMap<&str, &serde_json::Value> = (blocks.iter())
        .filter_map(|b| Some((b["name"].as_str()?, b)))
        .collect();
    let summary_block = |name: &str| {
        by_name.get(name).copied().ok_or_else(|| {
            table(
                &summary_path,
                1,
                format!("the run has no block {name}: was it run on this wall?"),
            )
        })
    };
    let Some(t) = at_s else {
        // The last history row is the end's: it gives the rotations the summary does not.
        let history = dir.join("history.csv");
        let pose = if history.exists() {
            history_at(&history, names, duration_s)?.2
        } else {
            None
        };
        let mut state = SavedState {
            time_s: duration_s,
            displacement_m: Vec::new(),
            fallen: Vec::new(),
            pose,
        };
        for name in names {
            let b = summary_block(name)?;
            state
                .displacement_m
                .push(b["final_displacement_m"].as_f64().ok_or_else(|| {
                    table(
                        &summary_path,
                        1,
                        format!("block {name} has no final_displacement_m"),
                    )
                })?);
            state.fallen.push(b["fell"].as_bool().unwrap_or(false));
        }
        return Ok(state);
    };
    if !(0.0..=duration_s).contains(&t) {
        return Err(table(
            &summary_path,
            1,
            format!("--at {t} s is outside the run, which lasts from 0 to {duration_s} s"),
        ));
    }
    let (time_s, displacement_m, pose) = history_at(&dir.join("history.csv"), names, t)?;
    let fallen = fallen_by(dir, &summary, names, t)?;
    Ok(SavedState {
        time_s,
        displacement_m,
        fallen,
        pose,
    })
}

/// What a history row says of a pose: rotations and lifts, when it has both.
type Pose = Option<(Vec<f64>, Vec<f64>)>;

/// The last row of history.csv at or before `t`: its time, the named blocks' u and their pose.
fn history_at(path: &Path, names: &[String], t: f64) -> Result<(f64, Vec<f64>, Pose), Error> {
    let mut found = None;
    each_row(path, names, |time, u, theta, w| {
        if time > t {
            return false;
        }
        found = Some((time, u, theta.zip(w)));
        true
    })?;
    found.ok_or_else(|| table(path, 2, format!("no sample at or before t = {t} s")))
}

/// A saved run's history: every row's time, the named blocks' u and, when the run rotated
/// blocks, their rotations and lifts.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SavedHistory {
    /// Times (s).
    pub time_s: Vec<f64>,
    /// u per row, per block (m).
    pub displacement_m: Vec<Vec<f64>>,
    /// theta per row, per block (rad, clockwise positive); empty when nothing rotated.
    pub rotation_rad: Vec<Vec<f64>>,
    /// w per row, per block: the vertical displacement of the middle of its base (m); empty
    /// when nothing rotated or the history predates it.
    pub lift_m: Vec<Vec<f64>>,
}

/// Reads the whole history.csv of the run in `dir`, for the blocks `names`.
pub fn history(dir: &Path, names: &[String]) -> Result<SavedHistory, Error> {
    let mut h = SavedHistory::default();
    each_row(&dir.join("history.csv"), names, |time, u, theta, w| {
        h.time_s.push(time);
        h.displacement_m.push(u);
        if let Some(theta) = theta {
            h.rotation_rad.push(theta);
        }
        if let Some(w) = w {
            h.lift_m.push(w);
        }
        true
    })?;
    Ok(h)
}

/// Hands each row of a history.csv to `row` (time, the named blocks' u, their rotations and
/// lifts when the file has them) until it returns false.
fn each_row(
    path: &Path,
    names: &[String],
    mut row: impl FnMut(f64, Vec<f64>, Option<Vec<f64>>, Option<Vec<f64>>) -> bool,
) -> Result<(), Error> {
    if !path.exists() {
        return Err(table(
            path,
            1,
            "missing: the run was made without a history (--no-history); a state at a time \
             needs one (run again without --no-history), the final state does not (leave --at \
             out)"
                .into(),
        ));
    }
    let text = read(path)?;
    let mut reader = csv::ReaderBuilder::new().from_reader(text.as_bytes());
    let header = reader
        .headers()
        .map_err(|e| table(path, 1, e.to_string()))?
        .clone();
    if header.get(0) != Some("time_s") {
        return Err(table(path, 1, "the header must start with time_s".into()));
    }
    // Each name looked up in a table of the header, not searched for along it.
    let at: std::collections::HashMap<&str, usize> =
        header.iter().enumerate().map(|(i, h)| (h, i)).collect();
    let column = |name: String| at.get(name.as_str()).copied();
    let columns = names
        .iter()
        .map(|n| {
            column(format!("u_{n}_m")).ok_or_else(|| {
                table(
                    path,
                    1,
                    format!("no column u_{n}_m: was the run made on this wall?"),
                )
            })
        })
        .collect::<Result<Vec<usize>, Error>>()?;
    let rotations: Option<Vec<usize>> = names
        .iter()
        .map(|n| column(format!("theta_{n}_rad")))
        .collect();
    let lifts: Option<Vec<usize>> = names.iter().map(|n| column(format!("w_{n}_m"))).collect();
    for record in reader.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line() as usize);
            table(path, line, e.to_string())
        })?;
        let line = record.position().map_or(0, |p| p.line() as usize);
        let num = |i: usize| -> Result<f64, Error> {
            (record.get(i).and_then(|f| f.parse().ok()))
                .filter(|v: &f64| v.is_finite())
                .ok_or_else(|| {
                    table(
                        path,
                        line,
                        format!("column `{}` is not a finite number", &header[i]),
                    )
                })
        };
        let time = num(0)?;
        let u = columns.iter().map(|&c| num(c)).collect::<Result<_, _>>()?;
        let optional = |columns: &Option<Vec<usize>>| -> Result<Option<Vec<f64>>, Error> {
            columns
                .as_ref()
                .map(|cols| cols.iter().map(|&c| num(c)).collect())
                .transpose()
        };
        let (theta, w) = (optional(&rotations)?, optional(&lifts)?);
        if !row(time, u, theta, w) {
            break;
        }
    }
    Ok(())
}

/// Which blocks had fallen by `t`: from the collapse events of events.jsonl, or, for a run
/// saved without its event log, from the first collapse in the summary.
fn fallen_by(
    dir: &Path,
    summary: &serde_json::Value,
    names: &[String],
    t: f64,
) -> Result<Vec<bool>, Error> {
    let mut fell: Vec<(f64, String)> = Vec::new();
    if dir.join("events.jsonl").exists() {
        for e in events(dir)?.into_iter().filter(|e| e.kind == "collapse") {
            fell.extend(e.blocks.into_iter().map(|b| (e.time_s, b)));
        }
    } else if let (Some(time), Some(b)) = (
        summary["collapse"]["time_s"].as_f64(),
        summary["collapse"]["block"].as_str(),
    ) {
        fell.push((time, b.to_string()));
    }
    Ok(names
        .iter()
        .map(|n| fell.iter().any(|(time, b)| b == n && *time <= t))
        .collect())
}

/// An event of a saved run, as events.jsonl gives it.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SavedEvent {
    /// Time (s).
    pub time_s: f64,
    /// What happened (`slip`, `impact`, `collapse`, ...).
    pub kind: String,
    /// Blocks involved.
    pub blocks: Vec<String>,
    /// The joint, when one is involved.
    pub joint: Option<String>,
}

/// The events of the run saved in `dir` (events.jsonl; none when the run kept no log).
pub fn events(dir: &Path) -> Result<Vec<SavedEvent>, Error> {
    let log = dir.join("events.jsonl");
    if !log.exists() {
        return Ok(Vec::new());
    }
    read(&log)?
        .lines()
        .enumerate()
        .map(|(k, line)| {
            let e: serde_json::Value = serde_json::from_str(line)
                .map_err(|e| table(&log, k + 1, format!("not an event: {e}")))?;
            let blocks = e["blocks"].as_array().into_iter().flatten();
            Ok(SavedEvent {
                time_s: e["time_s"].as_f64().unwrap_or(f64::INFINITY),
                kind: e["kind"].as_str().unwrap_or("event").to_string(),
                blocks: blocks
                    .filter_map(|b| b.as_str().map(String::from))
                    .collect(),
                joint: e["joint"].as_str().map(String::from),
            })
        })
        .collect()
}

/// The ground acceleration the run's chart drew (response.csv, series "ground acceleration"):
/// (t in s, a in m/s2); empty when the run drew no chart.
pub fn ground_acceleration(dir: &Path) -> Result<Vec<(f64, f64)>, Error> {
    #[derive(serde::Deserialize)]
    struct Point {
        chart: String,
        x: f64,
        y: f64,
    }
    let path = dir.join("response.csv");
    if !path.exists() {
        return Ok(Vec::new());
    }
    let points: Vec<Point> = crate::table::read_rows(&path, &read(&path)?, &["chart", "x", "y"])?;
    Ok(points
        .into_iter()
        .filter(|p| p.chart == "ground acceleration")
        .map(|p| (p.x, p.y))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A run's final displacements come back as the doubles it wrote: serde_json's default
    /// parser rounds some 17-digit decimals to the neighbouring double, which moved a block of
    /// `pirqa check --run` by an ulp from where the run left it.
    #[test]
    fn final_displacements_read_back_to_the_bit() {
        let dir = std::env::temp_dir().join(format!("pirqa-saved-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let wall = Wall::from_ron_str(
            r#"(version: 1, name: "one", thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
                rows: [(height_m: 1.0, blocks: [(width_m: 1.0, name: "A")])])"#,
        )
        .unwrap();
        for written in [
            -0.22352064980702174_f64,
            0.1 + 0.2,
            1e-300,
            -7.450580596923828e-9,
        ] {
            let summary = serde_json::json!({
                "wall": "one",
                "duration_s": 0.5,
                "blocks": [{"name": "A", "final_displacement_m": written, "fell": false}],
            });
            std::fs::write(dir.join("summary.json"), summary.to_string()).unwrap();
            let state = state_at(&dir, &wall, None).unwrap();
            assert_eq!(
                state.displacement_m[0].to_bits(),
                written.to_bits(),
                "{written}"
            );
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
