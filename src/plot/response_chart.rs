//! The chart a run writes beside its history (`response.svg`, its data in `response.csv`): the
//! ground acceleration, the displacement of the blocks that moved most and, when blocks rock,
//! their rotation and the opening angle of the joints between them, each line thinned to what a
//! chart shows with every extreme kept.

use super::chart::{envelope, Chart, Envelope, Series};
use crate::motion::Motion;
use crate::response::{each_row, Response, RowVisitor};
use crate::Error;

/// Blocks drawn at most: those with the largest max |u| (more lines could not be told apart).
pub const MOST_MOVED: usize = 8;

/// Bins of each line's envelope: about two per pixel column of a panel.
const BINS: usize = 1500;

/// Ground samples at most (a sine is sampled 40 times a period, a record at its own samples).
const GROUND_SAMPLES: f64 = 1e6;

/// The panels of a run's chart (two; with rotations, three, or four where a drawn block rests on
/// another drawn block), `None` without a history; from
/// the history in memory, or read back from its file (twice, holding only the lines drawn).
pub fn response_charts(r: &Response, motion: &Motion) -> Result<Option<Vec<Chart>>, Error> {
    let blocks = &r.summary.blocks;
    let each = |f: &mut RowVisitor| -> Result<(), Error> {
        match (&r.history, &r.history_file) {
            (Some(h), _) => {
                for (k, &t) in h.time_s.iter().enumerate() {
                    let theta = h.rotation_rad.get(k).map_or(&[][..], |x| &x[..]);
                    f(t, &h.displacement_m[k], theta);
                }
                Ok(())
            }
            (None, Some(file)) => each_row(&file.path, blocks.len(), f),
            (None, None) => Ok(()),
        }
    };
    // The first pass: the rows' number, first and last times, and whether blocks rotate.
    let (mut count, mut first, mut end, mut rotating) = (0, None, 0.0, false);
    each(&mut |t, _, theta| {
        count += 1;
        first.get_or_insert(t);
        end = t;
        rotating = !theta.is_empty();
    })?;
    let Some(first) = first else {
        return Ok(None);
    };
    let step = match motion {
        Motion::Record(rec) => rec.dt_s(),
        Motion::Sine(s) => 1.0 / (40.0 * s.frequency_hz),
        // Constant stretches: the envelope keeps the jumps whatever the step.
        Motion::Pulse(_) => end / 2000.0,
    }
    .max(end / GROUND_SAMPLES);
    let samples = (end / step).ceil() as usize;
    let ground: Vec<(f64, f64)> = (0..=samples)
        .map(|k| {
            let t = (k as f64 * step).min(end);
            (t, motion.accel(t))
        })
        .collect();
    let mut drawn: Vec<usize> = (0..blocks.len()).collect();
    drawn.sort_by(|&a, &b| {
        blocks[b]
            .max_abs_displacement_m
            .total_cmp(&blocks[a].max_abs_displacement_m)
    });
    drawn.truncate(MOST_MOVED);
    drawn.sort_unstable();
    // The joints between two drawn blocks: a rotation of the upper block relative to the lower
    // opens the joint (a column whose drums rock one on another, a lintel on its columns),
    // which the blocks' own rotations, nearly equal, do not show.
    let index = |name: &str| drawn.iter().copied().find(|&i| blocks[i].name == name);
    let joints: Vec<(usize, usize)> = if rotating {
        r.summary
            .horizontal_joints
            .iter()
            .filter_map(|j| Some((index(&j.upper)?, index(&j.lower)?)))
            .take(MOST_MOVED)
            .collect()
    } else {
        Vec::new()
    };
    // The second pass: the drawn lines, thinned as they come.
    let fresh = |n: usize| vec![Envelope::new(first, end, count, BINS); n];
    let (mut u_lines, mut theta_lines) = (fresh(drawn.len()), fresh(drawn.len()));
    let mut opening_lines = fresh(joints.len());
    each(&mut |t, u, theta| {
        for (k, &i) in drawn.iter().enumerate() {
            u_lines[k].push((t, u[i]));
            if rotating {
                theta_lines[k].push((t, theta[i]));
            }
        }
        for (line, &(upper, lower)) in opening_lines.iter_mut().zip(&joints) {
            line.push((t, theta[upper] - theta[lower]));
        }
    })?;
    let series = |lines: Vec<Envelope>| -> Vec<Series> {
        lines
            .into_iter()
            .zip(&drawn)
            .enumerate()
            .map(|(colour, (line, &i))| Series {
                label: blocks[i].name.clone(),
                points: line.finish(),
                color: colour,
                ..Series::default()
            })
            .collect()
    };
    let which = if blocks.len() <= MOST_MOVED {
        "every block".to_string()
    } else {
        format!(
            "the {MOST_MOVED} of {} blocks that moved most",
            blocks.len()
        )
    };
    let mut charts = vec![
        Chart {
            title: "ground acceleration".into(),
            x_label: "t (s)".into(),
            y_label: "a_g (m/s2)".into(),
            series: vec![Series {
                label: String::new(),
                points: envelope(&ground, BINS),
                ..Series::default()
            }],
            ..Chart::default()
        },
        Chart {
            title: format!("displacement relative to the ground, {which}"),
            x_label: "t (s)".into(),
            y_label: "u (m)".into(),
            series: series(u_lines),
            ..Chart::default()
        },
    ];
    if rotating {
        charts.push(Chart {
            title: format!("rotation (positive: on the right corner), {which}"),
            x_label: "t (s)".into(),
            y_label: "theta (rad)".into(),
            series: series(theta_lines),
            ..Chart::default()
        });
    }
    if !joints.is_empty() {
        charts.push(Chart {
            title: "opening of the joints between blocks: rotation of the upper block less the \
                    lower one's"
                .into(),
            x_label: "t (s)".into(),
            y_label: "theta_upper - theta_lower (rad)".into(),
            series: opening_lines
                .into_iter()
                .zip(&joints)
                .enumerate()
                .map(|(colour, (line, &(upper, lower)))| Series {
                    label: format!("{}/{}", blocks[upper].name, blocks[lower].name),
                    points: line.finish(),
                    color: colour,
                    ..Series::default()
                })
                .collect(),
            ..Chart::default()
        });
    }
    Ok(Some(charts))
}
