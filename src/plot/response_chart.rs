//! The chart a run writes beside its history (`response.svg`, its data in `response.csv`): the
//! ground acceleration, the displacement of the blocks that moved most and, when blocks rock,
//! their rotation, each line thinned to what a chart shows with every extreme kept.

use super::chart::{envelope, Chart, Series};
use crate::motion::Motion;
use crate::response::Response;

/// Blocks drawn at most: those with the largest max |u| (more lines could not be told apart).
pub const MOST_MOVED: usize = 8;

/// Bins of each line's envelope: about two per pixel column of a panel.
const BINS: usize = 1500;

/// Ground samples at most (a sine is sampled 40 times a period, a record at its own samples).
const GROUND_SAMPLES: f64 = 1e6;

/// The panels of a run's chart (two, three with rotations), `None` without a history.
pub fn response_charts(r: &Response, motion: &Motion) -> Option<Vec<Chart>> {
    let h = r.history.as_ref()?;
    let end = *h.time_s.last()?;
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
    let blocks = &r.summary.blocks;
    let mut drawn: Vec<usize> = (0..blocks.len()).collect();
    drawn.sort_by(|&a, &b| {
        blocks[b]
            .max_abs_displacement_m
            .total_cmp(&blocks[a].max_abs_displacement_m)
    });
    drawn.truncate(MOST_MOVED);
    drawn.sort_unstable();
    let lines = |rows: &[Vec<f64>]| -> Vec<Series> {
        drawn
            .iter()
            .enumerate()
            .map(|(colour, &i)| {
                let line: Vec<(f64, f64)> =
                    h.time_s.iter().zip(rows).map(|(&t, x)| (t, x[i])).collect();
                Series {
                    label: blocks[i].name.clone(),
                    points: envelope(&line, BINS),
                    color: colour,
                    ..Series::default()
                }
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
            series: lines(&h.displacement_m),
            ..Chart::default()
        },
    ];
    if !h.rotation_rad.is_empty() {
        charts.push(Chart {
            title: format!("rotation (positive: on the right corner), {which}"),
            x_label: "t (s)".into(),
            y_label: "theta (rad)".into(),
            series: lines(&h.rotation_rad),
            ..Chart::default()
        });
    }
    Some(charts)
}
