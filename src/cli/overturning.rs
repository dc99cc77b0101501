//! `pirqa overturning`: the minimum overturning spectra of a free-standing block under one-sine
//! pulses (exact, exact with friction, linearised), or of triliths whose columns are that block
//! under lintels of several weights, as a chart with its data.

use super::write_file;
use pirqa::plot::chart;
use pirqa::study::overturning::{
    chart as spectrum_chart, spectra, trilith_chart, trilith_spectra, Options,
};
use pirqa::Error;
use std::path::PathBuf;

/// Options of `pirqa overturning`.
#[derive(clap::Args, Debug)]
pub struct OverturningArgs {
    /// Output directory (the committed spectra live in docs/rocking).
    #[arg(long, default_value = "docs/rocking")]
    pub out: PathBuf,
    /// Width of the block (m).
    #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
    pub width_m: f64,
    /// Height of the block (m).
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    pub height_m: f64,
    /// Friction of the curve with a base that can slip (0.3 if not given; not with
    /// --lintel-ratios, whose joints hold).
    #[arg(long, allow_negative_numbers = true)]
    pub friction: Option<f64>,
    /// Pulse frequencies, log-spaced over omega_p / p from 1 to 10.
    #[arg(long, default_value_t = 41, allow_negative_numbers = true)]
    pub points: usize,
    /// Instead, triliths whose columns are this block: one curve per lintel ratio gamma =
    /// M / 2m, comma-separated (0: the column alone), exact equations on joints that hold;
    /// writes overturning-trilith.svg, .csv and .json.
    #[arg(long, value_delimiter = ',')]
    pub lintel_ratios: Vec<f64>,
}

pub fn run(args: &OverturningArgs) -> Result<(), Error> {
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if let (Some(mu), false) = (args.friction, args.lintel_ratios.is_empty()) {
        return Err(Error::Option {
            option: format!("--friction {mu} with --lintel-ratios"),
            rule: "the triliths' spectra hold every joint (a trilith whose feet slip is \
                   beyond the exact frame); leave --friction out"
                .into(),
        });
    }
    let friction = args.friction.unwrap_or(0.3);
    if !(ok(args.width_m) && ok(args.height_m) && ok(friction) && args.points >= 2) {
        return Err(Error::Option {
            option: format!(
                "--width-m {} --height-m {} --friction {} --points {}",
                args.width_m, args.height_m, friction, args.points
            ),
            rule: "sizes and friction must be positive, and at least 2 points".into(),
        });
    }
    let n = args.points;
    let opts = Options {
        half_width_m: 0.5 * args.width_m,
        half_height_m: 0.5 * args.height_m,
        friction,
        frequency_ratios: (0..n)
            .map(|k| 10f64.powf(k as f64 / (n - 1) as f64))
            .collect(),
        ..Options::default()
    };
    if !args.lintel_ratios.is_empty() {
        return triliths(args, &opts);
    }
    let bar = super::sweep::progress_bar(1, 0, "overturning spectra");
    let (points, alpha, p) = spectra(&opts);
    bar.finish_and_clear();
    let c = spectrum_chart(&points, alpha, friction);
    let json = serde_json::json!({
        "block": {"width_m": args.width_m, "height_m": args.height_m,
                  "alpha_rad": alpha, "p_rad_s": p, "friction": friction},
        "pulse": "one cycle of a_p sin(omega_p t), then the ground rests",
        "amplitude_unit": "g tan(alpha)",
        "points": points,
    });
    write_spectrum(
        &args.out,
        "overturning-spectrum",
        c,
        &json,
        &format!("alpha = {alpha:.4} rad, p = {p:.4} rad/s"),
    )
}

/// A spectrum's chart (`STEM.svg`), its points (`.csv`) and its data (`.json`).
fn write_spectrum(
    out: &std::path::Path,
    stem: &str,
    c: chart::Chart,
    json: &serde_json::Value,
    what: &str,
) -> Result<(), Error> {
    write_file(
        &out.join(format!("{stem}.svg")),
        &chart::render(std::slice::from_ref(&c), 1, (800, 500)),
    )?;
    write_file(&out.join(format!("{stem}.csv")), &chart::to_csv(&[c]))?;
    write_file(
        &out.join(format!("{stem}.json")),
        &(serde_json::to_string_pretty(json).expect("json") + "\n"),
    )?;
    eprintln!(
        "wrote {stem}.svg, .csv and .json to {} ({what})",
        out.display()
    );
    Ok(())
}

/// The triliths' spectra, written beside the block's.
fn triliths(args: &OverturningArgs, opts: &Options) -> Result<(), Error> {
    let ratios = &args.lintel_ratios;
    if let Some(bad) = ratios.iter().find(|g| !(g.is_finite() && **g >= 0.0)) {
        return Err(Error::Option {
            option: format!("--lintel-ratios {bad}"),
            rule: "each lintel ratio gamma = M / 2m must be a number >= 0".into(),
        });
    }
    let column = pirqa::integrate::rocking::RockingBody::rectangle(
        "column",
        args.width_m,
        args.height_m,
        1.0,
        1.0,
        9.81,
    );
    let (alpha, p) = (column.slenderness_rad(), column.frequency_parameter_rad_s());
    let bar = super::sweep::progress_bar(1, 0, "overturning spectra of triliths");
    let points = trilith_spectra(opts, ratios);
    bar.finish_and_clear();
    let c = trilith_chart(&points, ratios, alpha);
    let json = serde_json::json!({
        "column": {"width_m": args.width_m, "height_m": args.height_m,
                   "alpha_rad": alpha, "p_rad_s": p},
        "lintel_ratios": ratios,
        "lintel": "mass M = 2 gamma m on two such columns, joints holding (Makris and Vassiliou 2013)",
        "pulse": "one cycle of a_p sin(omega_p t), then the ground rests",
        "amplitude_unit": "g tan(alpha)",
        "points": points,
    });
    write_spectrum(
        &args.out,
        "overturning-trilith",
        c,
        &json,
        &format!("columns of alpha = {alpha:.4} rad, p = {p:.4} rad/s"),
    )
}
