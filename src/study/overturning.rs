//! The minimum overturning acceleration of a free-standing block under one-sine pulses: the
//! spectra of Zhang and Makris (2001, J. Eng. Mech. 127(5)), recomputed with pirqa's exact
//! rocking equations (on a base that holds, and on one of finite friction, where the block may
//! slide and slide-rock) beside Housner's linearisation. For each pulse frequency the smallest
//! amplitude that overturns the block is found by stepping the amplitude up by 2 % from the
//! uplift threshold and bisecting the first step that overturns (the boundary is not monotone
//! above it: there are amplitudes above the first that do not overturn, Zhang and Makris's
//! "safe region"; the minimum is the first).
//!
//! The same spectra for triliths whose columns are that block ([`trilith_spectra`]): a lintel
//! of mass M = 2 gamma m on two of them, the joints holding, rocking as Makris and Vassiliou's
//! (2013) frame.

use crate::integrate::rocking::{self, Equations, RockingBody, Scene, Trilith};
use crate::integrate::Settings;
use crate::motion::{Motion, Sine};
use crate::plot::chart::{Chart, Corner, Series};
use crate::response::CollapseCause;
use rayon::prelude::*;
use serde::Serialize;

/// What to compute.
#[derive(Debug, Clone)]
pub struct Options {
    /// Half width b of the block (m).
    pub half_width_m: f64,
    /// Half height h of the block (m).
    pub half_height_m: f64,
    /// The finite friction of the third curve (the other exact curve has a base that holds).
    pub friction: f64,
    /// Pulse frequencies, as omega_p / p.
    pub frequency_ratios: Vec<f64>,
    /// Relative width of the bracket the bisection leaves.
    pub tolerance: f64,
}

impl Default for Options {
    fn default() -> Options {
        Options {
            half_width_m: 0.25,
            half_height_m: 1.0,
            friction: 0.3,
            frequency_ratios: (0..=40).map(|k| 10f64.powf(k as f64 / 40.0)).collect(),
            tolerance: 1e-6,
        }
    }
}

/// The minimum overturning amplitude at one pulse frequency, in units of g tan(alpha); `None`
/// where no amplitude up to [`HIGHEST`] overturns, or where the search met a pulse that throws
/// the block off the ground (then named in `flight`).
#[derive(Debug, Clone, Serialize)]
pub struct SpectrumPoint {
    /// omega_p / p.
    pub frequency_ratio: f64,
    /// Exact equations, a base that holds.
    pub exact: Option<f64>,
    /// Exact equations with the finite friction.
    pub exact_with_friction: Option<f64>,
    /// Housner's linearisation.
    pub linearised: Option<f64>,
    /// The curves whose search stopped at free flight (beyond the model), with the amplitude.
    pub flight: Vec<(String, f64)>,
}

/// The highest amplitude tried, in units of g tan(alpha).
pub const HIGHEST: f64 = 30.0;

/// A friction no pulse here overcomes: the base holds.
const HOLDING_FRICTION: f64 = 1e3;

/// The spectra, with the block's alpha and p.
pub fn spectra(opts: &Options) -> (Vec<SpectrumPoint>, f64, f64) {
    let (b, h) = (opts.half_width_m, opts.half_height_m);
    let block = |mu: f64| RockingBody::rectangle("block", 2.0 * b, 2.0 * h, 1000.0, mu, 9.81);
    let base = block(HOLDING_FRICTION);
    let (alpha, p) = (base.slenderness_rad(), base.frequency_parameter_rad_s());
    let points = opts
        .frequency_ratios
        .par_iter()
        .map(|&ratio| {
            let mut flight = Vec::new();
            let mut search = |name: &str, body: &RockingBody, eq: Equations| {
                minimum(body, eq, ratio, opts.tolerance).unwrap_or_else(|at| {
                    flight.push((name.to_string(), at));
                    None
                })
            };
            let exact = search("exact", &base, Equations::Exact);
            let exact_with_friction = search(
                "exact_with_friction",
                &block(opts.friction),
                Equations::Exact,
            );
            let linearised = search("linearised", &base, Equations::Linearised);
            SpectrumPoint {
                frequency_ratio: ratio,
                exact,
                exact_with_friction,
                linearised,
                flight,
            }
        })
        .collect();
    (points, alpha, p)
}

/// The minimum overturning amplitude of triliths at one pulse frequency, one per lintel ratio,
/// in units of g tan(alpha) (`None`: none up to [`HIGHEST`], or the search met free flight,
/// named in `flight` by its ratio).
#[derive(Debug, Clone, Serialize)]
pub struct TrilithPoint {
    /// omega_p / p, p a column's (standing alone).
    pub frequency_ratio: f64,
    /// Per lintel ratio gamma = M / 2m, in the order asked.
    pub minima: Vec<Option<f64>>,
    /// The lintel ratios whose search stopped at free flight, with the amplitude.
    pub flight: Vec<(f64, f64)>,
}

/// The spectra of triliths whose columns are the block of `opts`, under lintels of mass M = 2
/// gamma m for each gamma of `lintel_ratios` (0: the column alone), exact equations on joints
/// that hold. The pulse frequencies are taken relative to one column's p, so that the curves
/// compare one set of columns under ever heavier lintels.
pub fn trilith_spectra(opts: &Options, lintel_ratios: &[f64]) -> Vec<TrilithPoint> {
    let (b, h) = (opts.half_width_m, opts.half_height_m);
    let column = RockingBody::rectangle("column", 2.0 * b, 2.0 * h, 1000.0, HOLDING_FRICTION, 9.81);
    let p = column.frequency_parameter_rad_s();
    let frames: Vec<RockingBody> = lintel_ratios
        .iter()
        .map(|gamma| {
            let shape = Trilith {
                half_width_m: b,
                half_height_m: h,
                column_kg: column.mass_kg,
                lintel_kg: 2.0 * gamma * column.mass_kg,
            };
            shape
                .body(
                    &format!("trilith, gamma {gamma}"),
                    HOLDING_FRICTION,
                    9.81,
                    1.0,
                )
                .expect("a frame of a block that rocks rocks")
        })
        .collect();
    opts.frequency_ratios
        .par_iter()
        .map(|&ratio| {
            let mut flight = Vec::new();
            let minima = frames
                .iter()
                .zip(lintel_ratios)
                .map(|(frame, &gamma)| {
                    let own = ratio * p / frame.frequency_parameter_rad_s();
                    minimum(frame, Equations::Exact, own, opts.tolerance).unwrap_or_else(|at| {
                        flight.push((gamma, at));
                        None
                    })
                })
                .collect();
            TrilithPoint {
                frequency_ratio: ratio,
                minima,
                flight,
            }
        })
        .collect()
}

/// Does one cycle of a_p sin(omega_p t) overturn the block? The run goes on after the pulse
/// until the block has rested or fallen (the ground then rests, so a block that passes alpha
/// falls, and one that has not within 60 time scales 1/p has rested: a block falls on the
/// excursion after the pulse or the one after the next landing). `None`: free flight.
fn overturns(body: &RockingBody, eq: Equations, ratio: f64, amplitude: f64) -> Option<bool> {
    let p = body.frequency_parameter_rad_s();
    let f = ratio * p / (2.0 * std::f64::consts::PI);
    let sine = Motion::sine(Sine {
        amplitude_m_s2: amplitude,
        frequency_hz: f,
        phase_rad: 0.0,
        duration_s: 1.0 / f,
    })
    .ok()?;
    let settings = Settings::summary_only(1.0 / f + 60.0 / p);
    let r = rocking::run(&Scene {
        bodies: std::slice::from_ref(body),
        watches: &[],
        wall: None,
        initial_rotation_rad: &[0.0],
        equations: eq,
        motion: &sine,
        settings: &settings,
    })
    .ok()?;
    if !r.summary.warnings.is_empty() {
        // A frame's free flight, or a landing from flight beyond Housner's law: beyond the
        // model (a free block's flight is followed to its landing).
        return None;
    }
    Some(
        r.summary
            .collapse
            .is_some_and(|c| c.cause == CollapseCause::Overturning),
    )
}

/// The smallest amplitude (in g tan alpha) that overturns the block at this frequency
/// (`None`: none up to [`HIGHEST`]), or the amplitude at which the search met free flight.
fn minimum(
    body: &RockingBody,
    eq: Equations,
    ratio: f64,
    tolerance: f64,
) -> Result<Option<f64>, f64> {
    let unit = body.g_m_s2 * body.uplift_ratio();
    let falls = |x: f64| overturns(body, eq, ratio, x * unit).ok_or(x);
    let mut below = 1.0;
    let mut x = 1.0;
    while x < HIGHEST {
        x *= 1.02;
        if falls(x)? {
            let mut above = x;
            while above - below > tolerance * above {
                let mid = 0.5 * (above + below);
                if falls(mid)? {
                    above = mid;
                } else {
                    below = mid;
                }
            }
            return Ok(Some(above));
        }
        below = x;
    }
    Ok(None)
}

/// The spectra as a chart: the minimum overturning amplitude against the pulse frequency, both
/// normalised (a_p / (g tan alpha), omega_p / p).
pub fn chart(points: &[SpectrumPoint], alpha: f64, friction: f64) -> Chart {
    let line = |pick: &dyn Fn(&SpectrumPoint) -> Option<f64>| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter_map(|s| pick(s).map(|y| (s.frequency_ratio, y)))
            .collect()
    };
    Chart {
        title: format!(
            "one-sine pulse: smallest amplitude that overturns a block of alpha = {alpha:.4} rad"
        ),
        x_label: "omega_p / p".into(),
        y_label: "a_p / (g tan alpha)".into(),
        series: vec![
            Series {
                label: "exact, base holds".into(),
                points: line(&|s| s.exact),
                color: 0,
                ..Series::default()
            },
            Series {
                label: format!("exact, friction {friction}"),
                points: line(&|s| s.exact_with_friction),
                color: 1,
                ..Series::default()
            },
            Series {
                label: "linearised (Housner)".into(),
                points: line(&|s| s.linearised),
                color: 2,
                ..Series::default()
            },
        ],
        log_x: true,
        legend: Corner::UpperLeft,
        ..Chart::default()
    }
}

/// The triliths' spectra as a chart, one curve per lintel ratio.
pub fn trilith_chart(points: &[TrilithPoint], lintel_ratios: &[f64], alpha: f64) -> Chart {
    Chart {
        title: format!(
            "one-sine pulse that overturns a trilith (columns: alpha = {alpha:.4} rad; lintel 2 gamma m)"
        ),
        x_label: "omega_p / p (p of one column)".into(),
        y_label: "a_p / (g tan alpha)".into(),
        series: lintel_ratios
            .iter()
            .enumerate()
            .map(|(k, gamma)| Series {
                label: if *gamma == 0.0 {
                    "gamma 0 (the column alone)".into()
                } else {
                    format!("gamma {gamma}")
                },
                points: points
                    .iter()
                    .filter_map(|s| s.minima[k].map(|y| (s.frequency_ratio, y)))
                    .collect(),
                color: k,
                ..Series::default()
            })
            .collect(),
        log_x: true,
        legend: Corner::UpperLeft,
        ..Chart::default()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A trilith without a lintel is its column: its spectrum is the block's exact one to the
    /// bit. Under a lintel as heavy as both columns (gamma = 1) every pulse must be stronger,
    /// by more than 1 %, to overturn it: Makris and Vassiliou's (2013) heavier cap, more
    /// stable frame (its p falls by (1 + 2 gamma) / (1 + 3 gamma) under the root, and each
    /// landing loses more).
    #[test]
    fn a_heavier_lintel_makes_a_trilith_harder_to_overturn() {
        let opts = Options {
            frequency_ratios: vec![1.5, 3.0, 5.0],
            ..Options::default()
        };
        let (block, _, _) = spectra(&opts);
        let triliths = trilith_spectra(&opts, &[0.0, 1.0]);
        for (b, t) in block.iter().zip(&triliths) {
            assert_eq!(t.minima[0], b.exact, "omega_p / p = {}", b.frequency_ratio);
            let (alone, capped) = (t.minima[0].unwrap(), t.minima[1].unwrap());
            assert!(
                capped > 1.01 * alone,
                "omega_p / p = {}: {capped} against {alone}",
                b.frequency_ratio
            );
        }
    }
}
