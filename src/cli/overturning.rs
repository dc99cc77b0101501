//! `pirqa overturning`: the minimum overturning spectra of a free-standing block under one-sine
//! pulses (exact, exact with friction, linearised), as a chart with its data.

use super::write_file;
use pirqa::plot::chart;
use pirqa::study::overturning::{chart as spectrum_chart, spectra, Options};
use pirqa::Error;
use std::path::PathBuf;

/// Options of `pirqa overturning`.
#[derive(clap::Args, Debug)]
pub struct OverturningArgs {
    /// Output directory (the committed spectra live in docs/rocking).
    #[arg(long, default_value = "docs/rocking")]
    pub out: PathBuf,
    /// Width of the block (m).
    #[arg(long, default_value_t = 0.5)]
    pub width_m: f64,
    /// Height of the block (m).
    #[arg(long, default_value_t = 2.0)]
    pub height_m: f64,
    /// Friction of the curve with a base that can slip.
    #[arg(long, default_value_t = 0.3)]
    pub friction: f64,
    /// Pulse frequencies, log-spaced over omega_p / p from 1 to 10.
    #[arg(long, default_value_t = 41)]
    pub points: usize,
}

pub fn run(args: &OverturningArgs) -> Result<(), Error> {
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(args.width_m) && ok(args.height_m) && ok(args.friction) && args.points >= 2) {
        return Err(Error::Option {
            option: format!(
                "--width-m {} --height-m {} --friction {} --points {}",
                args.width_m, args.height_m, args.friction, args.points
            ),
            rule: "sizes and friction must be positive, and at least 2 points".into(),
        });
    }
    let n = args.points;
    let opts = Options {
        half_width_m: 0.5 * args.width_m,
        half_height_m: 0.5 * args.height_m,
        friction: args.friction,
        frequency_ratios: (0..n)
            .map(|k| 10f64.powf(k as f64 / (n - 1) as f64))
            .collect(),
        ..Options::default()
    };
    let bar = super::sweep::progress_bar(1, 0, "overturning spectra");
    let (points, alpha, p) = spectra(&opts);
    bar.finish_and_clear();
    let c = spectrum_chart(&points, alpha, args.friction);
    let out = &args.out;
    write_file(
        &out.join("overturning-spectrum.svg"),
        &chart::render(std::slice::from_ref(&c), 1, (800, 500)),
    )?;
    write_file(&out.join("overturning-spectrum.csv"), &chart::to_csv(&[c]))?;
    let json = serde_json::json!({
        "block": {"width_m": args.width_m, "height_m": args.height_m,
                  "alpha_rad": alpha, "p_rad_s": p, "friction": args.friction},
        "pulse": "one cycle of a_p sin(omega_p t), then the ground rests",
        "amplitude_unit": "g tan(alpha)",
        "points": points,
    });
    write_file(
        &out.join("overturning-spectrum.json"),
        &(serde_json::to_string_pretty(&json).expect("json") + "\n"),
    )?;
    eprintln!(
        "wrote overturning-spectrum.svg, .csv and .json to {} (alpha = {alpha:.4} rad, p = {p:.4} rad/s)",
        out.display()
    );
    Ok(())
}
