//! Line charts with axes, labels in engineering units and legends, drawn with plotters' SVG
//! backend (no system fonts needed). Several charts can share one figure as panels.

use plotters::coord::Shift;
use plotters::prelude::*;

/// One line of a chart.
#[derive(Debug, Clone, Default)]
pub struct Series {
    /// Legend entry (empty: no entry).
    pub label: String,
    /// Points (x, y).
    pub points: Vec<(f64, f64)>,
    /// Colour index into the palette.
    pub color: usize,
    /// Dashed line.
    pub dashed: bool,
    /// Mark each point with a dot (a single point is drawn as a dot alone).
    pub markers: bool,
    /// Dots only, no line (a scatter of cases).
    pub scatter: bool,
}

/// A chart: axes, labels, lines.
#[derive(Debug, Clone, Default)]
pub struct Chart {
    /// Title above the plot.
    pub title: String,
    /// X axis label with units.
    pub x_label: String,
    /// Y axis label with units.
    pub y_label: String,
    /// Lines.
    pub series: Vec<Series>,
    /// Logarithmic x axis.
    pub log_x: bool,
    /// Logarithmic y axis.
    pub log_y: bool,
    /// Text notes drawn at data coordinates (x, y, text).
    pub notes: Vec<(f64, f64, String)>,
    /// Where the legend goes.
    pub legend: Corner,
}

/// A corner of the plot area.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum Corner {
    /// Top right (the default).
    #[default]
    UpperRight,
    /// Bottom right.
    LowerRight,
    /// Top left.
    UpperLeft,
    /// Bottom left.
    LowerLeft,
}

const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 95, 168),
    RGBColor(194, 87, 26),
    RGBColor(46, 139, 87),
    RGBColor(179, 38, 30),
    RGBColor(120, 81, 169),
    RGBColor(140, 86, 75),
    RGBColor(0, 128, 128),
    RGBColor(90, 90, 90),
];

/// The colour of palette entry k.
pub fn color(k: usize) -> RGBColor {
    PALETTE[k % PALETTE.len()]
}

/// Axis numbers in the shortest form that keeps three significant digits: 0.5, 120, 1e-6, 2.5e9.
fn tick(v: &f64) -> String {
    let a = v.abs();
    if a == 0.0 || !a.is_finite() {
        return if a == 0.0 { "0".into() } else { v.to_string() };
    }
    let trim = |m: &str| -> String {
        if m.contains('.') {
            m.trim_end_matches('0').trim_end_matches('.').to_string()
        } else {
            m.to_string()
        }
    };
    if (1e-3..1e5).contains(&a) {
        let decimals = (2 - a.log10().floor() as i32).max(0) as usize;
        let s = trim(&format!("{v:.decimals$}"));
        if s == "-0" {
            "0".into()
        } else {
            s
        }
    } else {
        let s = format!("{v:.2e}");
        let (m, e) = s.split_once('e').expect("exponent form");
        format!("{}e{e}", trim(m))
    }
}

/// A tick on a linear axis spanning `span`: values within round-off of zero (what a tick
/// generator's sums leave, such as -5.55e-17) read 0. Log axes pass a span of 0.
fn tick_on(v: f64, span: f64) -> String {
    if v.abs() < 1e-9 * span {
        "0".into()
    } else {
        tick(&v)
    }
}

fn bounds(chart: &Chart) -> ((f64, f64), (f64, f64)) {
    let pts = chart
        .series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|(x, y)| {
            x.is_finite()
                && y.is_finite()
                && (!chart.log_x || *x > 0.0)
                && (!chart.log_y || *y > 0.0)
        });
    let (mut x0, mut x1, mut y0, mut y1) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for &(x, y) in pts {
        x0 = x0.min(x);
        x1 = x1.max(x);
        y0 = y0.min(y);
        y1 = y1.max(y);
    }
    if !x0.is_finite() {
        return ((0.0, 1.0), (0.0, 1.0));
    }
    let log_pad = |lo: f64, hi: f64| {
        if hi > lo {
            (lo / 1.2, hi * 1.2)
        } else {
            (lo / 2.0, hi * 2.0)
        }
    };
    let lin_pad = |lo: f64, hi: f64| {
        let span = if hi > lo {
            hi - lo
        } else {
            lo.abs().max(1e-12)
        };
        (lo - 0.05 * span, hi + 0.05 * span)
    };
    let x = if chart.log_x {
        log_pad(x0, x1)
    } else if x1 > x0 {
        (x0, x1)
    } else {
        (x0 - 0.5, x0 + 0.5)
    };
    let y = if chart.log_y {
        log_pad(y0, y1)
    } else {
        lin_pad(y0, y1)
    };
    (x, y)
}

macro_rules! draw_on {
    ($area:expr, $chart:expr, $xr:expr, $yr:expr, $xspan:expr, $yspan:expr) => {{
        let chart = $chart;
        let (xspan, yspan): (f64, f64) = ($xspan, $yspan);
        let fx = move |v: &f64| tick_on(*v, xspan);
        let fy = move |v: &f64| tick_on(*v, yspan);
        let mut c = ChartBuilder::on($area)
            .caption(&chart.title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(70)
            .build_cartesian_2d($xr, $yr)
            .map_err(|e| e.to_string())?;
        c.configure_mesh()
            .x_desc(chart.x_label.as_str())
            .y_desc(chart.y_label.as_str())
            .x_label_formatter(&fx)
            .y_label_formatter(&fy)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 14))
            .draw()
            .map_err(|e| e.to_string())?;
        let mut legend = false;
        for s in &chart.series {
            let style = ShapeStyle::from(&color(s.color)).stroke_width(2);
            let pts: Vec<(f64, f64)> = s
                .points
                .iter()
                .copied()
                .filter(|(x, y)| {
                    x.is_finite()
                        && y.is_finite()
                        && (!chart.log_x || *x > 0.0)
                        && (!chart.log_y || *y > 0.0)
                })
                .collect();
            if s.markers || s.scatter {
                c.draw_series(pts.iter().map(|&p| Circle::new(p, 3, style.filled())))
                    .map_err(|e| e.to_string())?;
            }
            let drawn = if s.scatter {
                c.draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                    .map_err(|e| e.to_string())?
            } else if s.dashed {
                c.draw_series(DashedLineSeries::new(pts, 6, 4, style))
                    .map_err(|e| e.to_string())?
            } else {
                c.draw_series(LineSeries::new(pts, style))
                    .map_err(|e| e.to_string())?
            };
            if !s.label.is_empty() {
                legend = true;
                let col = color(s.color);
                let drawn = drawn.label(s.label.as_str());
                if s.scatter {
                    drawn.legend(move |(x, y)| Circle::new((x + 9, y), 3, col.filled()));
                } else if s.dashed {
                    drawn.legend(move |(x, y)| {
                        EmptyElement::at((x, y))
                            + PathElement::new(vec![(0, 0), (7, 0)], col.stroke_width(2))
                            + PathElement::new(vec![(11, 0), (18, 0)], col.stroke_width(2))
                    });
                } else {
                    drawn.legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 18, y)], col.stroke_width(2))
                    });
                }
            }
        }
        for (x, y, text) in &chart.notes {
            c.draw_series(std::iter::once(Text::new(
                text.clone(),
                (*x, *y),
                ("sans-serif", 12).into_font().color(&BLACK),
            )))
            .map_err(|e| e.to_string())?;
        }
        if legend {
            c.configure_series_labels()
                .background_style(WHITE.mix(0.85))
                .border_style(BLACK.mix(0.3))
                .label_font(("sans-serif", 12))
                .position(match chart.legend {
                    Corner::UpperRight => SeriesLabelPosition::UpperRight,
                    Corner::LowerRight => SeriesLabelPosition::LowerRight,
                    Corner::UpperLeft => SeriesLabelPosition::UpperLeft,
                    Corner::LowerLeft => SeriesLabelPosition::LowerLeft,
                })
                .draw()
                .map_err(|e| e.to_string())?;
        }
        Ok::<(), String>(())
    }};
}

fn draw(area: &DrawingArea<SVGBackend, Shift>, chart: &Chart) -> Result<(), String> {
    let ((x0, x1), (y0, y1)) = bounds(chart);
    let (xs, ys) = (x1 - x0, y1 - y0);
    match (chart.log_x, chart.log_y) {
        (false, false) => draw_on!(area, chart, x0..x1, y0..y1, xs, ys),
        (true, false) => draw_on!(area, chart, (x0..x1).log_scale(), y0..y1, 0.0, ys),
        (false, true) => draw_on!(area, chart, x0..x1, (y0..y1).log_scale(), xs, 0.0),
        (true, true) => draw_on!(
            area,
            chart,
            (x0..x1).log_scale(),
            (y0..y1).log_scale(),
            0.0,
            0.0
        ),
    }
}

/// Draws charts as panels of one SVG figure, `columns` across (at most one per chart), each
/// `panel` pixels.
pub fn render(charts: &[Chart], columns: usize, panel: (u32, u32)) -> String {
    // The canvas follows the panels: fewer charts than columns take fewer columns.
    let columns = columns.min(charts.len()).max(1);
    let rows = charts.len().div_ceil(columns).max(1);
    let mut svg = String::new();
    {
        let root =
            SVGBackend::with_string(&mut svg, (panel.0 * columns as u32, panel.1 * rows as u32))
                .into_drawing_area();
        let _ = root.fill(&WHITE);
        let areas = root.split_evenly((rows, columns));
        for (chart, area) in charts.iter().zip(&areas) {
            if let Err(e) = draw(area, chart) {
                let _ = area.draw(&Text::new(
                    format!("cannot draw: {e}"),
                    (10, 20),
                    ("sans-serif", 14),
                ));
            }
        }
        let _ = root.present();
    }
    svg
}

/// A line of many points (x increasing) thinned to what a chart can show: the x range cut into
/// `bins` equal bins, and of each bin its first and last points and its lowest and highest, in
/// order. Every extreme of the line is kept exactly, so a peak read off the chart (or its CSV)
/// is the peak of the data; at most 4 points per bin.
pub fn envelope(points: &[(f64, f64)], bins: usize) -> Vec<(f64, f64)> {
    let (Some(&(x0, _)), Some(&(x1, _))) = (points.first(), points.last()) else {
        return Vec::new();
    };
    let mut e = Envelope::new(x0, x1, points.len(), bins);
    for &p in points {
        e.push(p);
    }
    e.finish()
}

/// The points an envelope keeps of one bin, each with its position in the bin: its first,
/// lowest, highest and last.
type Kept = [(usize, (f64, f64)); 4];

/// [`envelope`] of a line given point by point, in memory of its result alone (a history read
/// back from a file of gigabytes): the line's first and last x and its number of points are
/// given first. Lines of at most 4 points per bin are kept whole.
#[derive(Debug, Clone)]
pub struct Envelope {
    x0: f64,
    x1: f64,
    bins: usize,
    whole: bool,
    /// The current bin: its index, and its first, lowest, highest and last points with their
    /// positions in the bin (the lowest the first of equals, the highest the last, as
    /// `min_by` and `max_by` choose).
    bin: Option<(usize, Kept)>,
    seen: usize,
    out: Vec<(f64, f64)>,
}

impl Envelope {
    /// For a line from x0 to x1 of `count` points.
    pub fn new(x0: f64, x1: f64, count: usize, bins: usize) -> Envelope {
        Envelope {
            x0,
            x1,
            bins,
            whole: count <= 4 * bins || x1 <= x0,
            bin: None,
            seen: 0,
            out: Vec::new(),
        }
    }

    /// The next point.
    pub fn push(&mut self, p: (f64, f64)) {
        if self.whole {
            self.out.push(p);
            return;
        }
        let b = (((p.0 - self.x0) / (self.x1 - self.x0) * self.bins as f64) as usize)
            .min(self.bins - 1);
        match &mut self.bin {
            Some((current, kept)) if *current == b => {
                self.seen += 1;
                let k = self.seen;
                if p.1.total_cmp(&kept[1].1 .1).is_lt() {
                    kept[1] = (k, p);
                }
                if p.1.total_cmp(&kept[2].1 .1).is_ge() {
                    kept[2] = (k, p);
                }
                kept[3] = (k, p);
            }
            _ => {
                self.flush();
                self.seen = 0;
                self.bin = Some((b, [(0, p); 4]));
            }
        }
    }

    fn flush(&mut self) {
        if let Some((_, mut kept)) = self.bin.take() {
            kept.sort_by_key(|k| k.0);
            let mut last = None;
            for (k, p) in kept {
                if last != Some(k) {
                    self.out.push(p);
                    last = Some(k);
                }
            }
        }
    }

    /// The thinned line.
    pub fn finish(mut self) -> Vec<(f64, f64)> {
        self.flush();
        self.out
    }
}

/// The data of charts as CSV: one row per point, with chart, series, x and y (titles and
/// labels quoted, so any text round-trips; numbers as the shortest decimal that reads back).
pub fn to_csv(charts: &[Chart]) -> String {
    use std::fmt::Write;
    // The csv crate quotes a field unless it reads as a number, which it finds by parsing the
    // field: every point's two numbers, a run's response.csv being most of its output's cost.
    // The names are quoted by it once per series; the numbers are written as they are, which
    // that check leaves unquoted (a float's `Display` always reads back as a number).
    let mut out = String::from("chart,series,x,y\n");
    for c in charts {
        let title = crate::table::non_numeric(&c.title);
        for ser in &c.series {
            let label = crate::table::non_numeric(&ser.label);
            for (x, y) in &ser.points {
                let _ = writeln!(out, "{title},{label},{x},{y}");
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::{envelope, render, tick, tick_on, Chart};

    /// A figure asked for two columns with one chart in it is one panel wide (the fragility and
    /// IDA figures of a sweep with one wall were drawn on the left half of an empty canvas).
    #[test]
    fn the_canvas_follows_the_panels() {
        let size = |svg: &str| {
            let head = &svg[..svg.find('>').unwrap()];
            let num = |key: &str| -> u32 {
                let at = head.find(key).unwrap() + key.len() + 2;
                head[at..].split('"').next().unwrap().parse().unwrap()
            };
            (num("width"), num("height"))
        };
        let one = vec![Chart::default()];
        assert_eq!(size(&render(&one, 2, (620, 420))), (620, 420));
        let three = vec![Chart::default(); 3];
        assert_eq!(size(&render(&three, 2, (620, 420))), (1240, 840));
    }

    #[test]
    fn an_envelope_keeps_every_bins_extremes_in_order() {
        // A fast oscillation under a slow one, with one spike: 100,000 points into 50 bins.
        let points: Vec<(f64, f64)> = (0..100_000)
            .map(|k| {
                let x = k as f64 * 1e-3;
                let spike = if k == 61_234 { 7.0 } else { 0.0 };
                (x, (x * 0.3).sin() + 0.1 * (x * 40.0).sin() + spike)
            })
            .collect();
        let thin = envelope(&points, 50);
        assert!(thin.len() <= 200, "{}", thin.len());
        assert!(thin.windows(2).all(|w| w[0].0 < w[1].0));
        assert_eq!(thin.first(), points.first());
        assert_eq!(thin.last(), points.last());
        // Every point kept is a point of the line, and in each bin the extremes are kept.
        assert!(thin.iter().all(|p| points.contains(p)));
        let x1 = points.last().unwrap().0;
        for b in 0..50 {
            let inside = |p: &&(f64, f64)| ((p.0 / x1 * 50.0) as usize).min(49) == b;
            let max = |v: Vec<&(f64, f64)>| v.iter().map(|p| p.1).fold(f64::MIN, f64::max);
            let min = |v: Vec<&(f64, f64)>| v.iter().map(|p| p.1).fold(f64::MAX, f64::min);
            let all: Vec<&(f64, f64)> = points.iter().filter(inside).collect();
            let kept: Vec<&(f64, f64)> = thin.iter().filter(inside).collect();
            assert_eq!(max(kept.clone()), max(all.clone()), "bin {b}");
            assert_eq!(min(kept), min(all), "bin {b}");
        }
        assert!(thin.contains(&points[61_234]));
        // Short lines are left as they are.
        assert_eq!(envelope(&points[..150], 50), points[..150].to_vec());
    }

    #[test]
    fn round_off_next_to_zero_reads_zero_on_a_linear_axis() {
        assert_eq!(tick_on(-5.551115123125783e-17, 0.35), "0");
        assert_eq!(tick_on(0.05, 0.35), "0.05");
        assert_eq!(tick_on(1e-13, 0.0), "1e-13");
    }

    #[test]
    fn ticks_are_short_and_keep_three_significant_digits() {
        for (v, s) in [
            (0.0, "0"),
            (0.5, "0.5"),
            (-1.5, "-1.5"),
            (0.95, "0.95"),
            (20.0, "20"),
            (0.001, "0.001"),
            (1e-4, "1e-4"),
            (9.999999999999999e-6, "1e-5"),
            (1e6, "1e6"),
            (2.5e9, "2.5e9"),
            (12345.0, "12345"),
            (-0.0001, "-1e-4"),
        ] {
            assert_eq!(tick(&v), s, "{v}");
        }
    }

    /// The data of a chart is what the csv crate writes with every field quoted but numbers:
    /// names with quotes, commas, line breaks, none, or that read as numbers, and points of
    /// every kind of float.
    #[test]
    fn chart_data_is_what_the_csv_crate_writes() {
        use super::{to_csv, Series};
        let points = vec![
            (0.0, -0.0),
            (0.025, 1e-300),
            (-1.5e22, f64::NAN),
            (f64::INFINITY, f64::NEG_INFINITY),
            (std::f64::consts::PI, 5e-324),
        ];
        let names = [
            "ground acceleration",
            "",
            "a, \"b\"",
            "1",
            "-2.5e3",
            "NaN",
            "line\nbreak",
        ];
        let charts: Vec<Chart> = names
            .iter()
            .map(|title| Chart {
                title: title.to_string(),
                series: names
                    .iter()
                    .map(|label| Series {
                        label: label.to_string(),
                        points: points.clone(),
                        ..Default::default()
                    })
                    .collect(),
                ..Default::default()
            })
            .collect();
        let mut w = csv::WriterBuilder::new()
            .quote_style(csv::QuoteStyle::NonNumeric)
            .from_writer(Vec::new());
        for c in &charts {
            for s in &c.series {
                for (x, y) in &s.points {
                    w.write_record([&c.title, &s.label, &x.to_string(), &y.to_string()])
                        .unwrap();
                }
            }
        }
        let expected = String::from("chart,series,x,y\n") + &crate::table::text(w);
        assert_eq!(to_csv(&charts), expected);
    }
}
