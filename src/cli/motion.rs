//! `pirqa motion info` and `pirqa motion generate`.

use super::{print_out, write_file};
use pirqa::motion::measures::{fourier_amplitude, Measures};
use pirqa::motion::synthetic::Synthetic;
use pirqa::motion::{process, read_record, Baseline, Motion, Processing, ReadOptions, Record};
use pirqa::plot::chart::{self, Chart, Series};
use pirqa::units::{parse_acceleration, AccelUnit};
use pirqa::Error;
use std::fmt::Write;
use std::path::{Path, PathBuf};

/// Ground-motion tools.
#[derive(clap::Subcommand, Debug)]
pub enum MotionCommand {
    /// Intensity measures of a record: PGA, PGV, PGD, Arias intensity, D5-95, mean and
    /// predominant periods.
    Info(InfoArgs),
    /// Write a synthetic motion as a plain-text record with a units header.
    Generate {
        #[command(subcommand)]
        kind: GenerateKind,
        /// Output file.
        #[arg(short, long, global = true)]
        output: Option<PathBuf>,
        /// Sample interval (s).
        #[arg(
            long,
            default_value_t = 0.01,
            global = true,
            allow_negative_numbers = true
        )]
        dt: f64,
    },
}

/// Options of `pirqa motion info`.
#[derive(clap::Args, Debug)]
pub struct InfoArgs {
    /// Record file (AT2, K-NET, COSMOS V2, plain).
    pub file: PathBuf,
    /// Record format (default: recognised from the content).
    #[arg(long)]
    pub format: Option<String>,
    /// Units of a plain record: gal, g, m/s2.
    #[arg(long)]
    pub units: Option<String>,
    /// Sample interval of a one-column plain record (s).
    #[arg(long, allow_negative_numbers = true)]
    pub dt: Option<f64>,
    /// Component (plain: column after time, 1-based; COSMOS: channel, 0-based).
    #[arg(long, allow_negative_numbers = true)]
    pub component: Option<usize>,
    /// Baseline correction before the measures.
    #[arg(long, value_enum, default_value_t = Baseline::None)]
    pub baseline: Baseline,
    /// Print JSON (keys with units).
    #[arg(long)]
    pub json: bool,
    /// Draw acceleration, velocity, displacement and the Fourier amplitude spectrum to this SVG
    /// (the data go to the same name with .csv).
    #[arg(long, value_name = "SVG")]
    pub plot: Option<PathBuf>,
}

/// Synthetic motions.
#[derive(clap::Subcommand, Debug)]
pub enum GenerateKind {
    /// A sine with half-cosine ramp-in and taper.
    Sine {
        /// Amplitude: 400gal, 0.4g, 4m/s2.
        #[arg(long, allow_hyphen_values = true)]
        amp: String,
        /// Frequency (Hz).
        #[arg(long, allow_negative_numbers = true)]
        freq: f64,
        /// Length (s).
        #[arg(long, allow_negative_numbers = true)]
        duration: f64,
        /// Ramp-in (s).
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
        ramp: f64,
        /// Taper (s).
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
        taper: f64,
        /// Phase (degrees).
        #[arg(long, default_value_t = 0.0, allow_negative_numbers = true)]
        phase: f64,
    },
    /// A linear frequency sweep.
    Chirp {
        /// Amplitude.
        #[arg(long, allow_hyphen_values = true)]
        amp: String,
        /// Start frequency (Hz).
        #[arg(long, allow_negative_numbers = true)]
        f0: f64,
        /// End frequency (Hz).
        #[arg(long, allow_negative_numbers = true)]
        f1: f64,
        /// Length (s).
        #[arg(long, allow_negative_numbers = true)]
        duration: f64,
        /// Ramp-in (s).
        #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
        ramp: f64,
        /// Taper (s).
        #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
        taper: f64,
    },
    /// A Ricker wavelet.
    Ricker {
        /// Peak acceleration.
        #[arg(long, allow_hyphen_values = true)]
        amp: String,
        /// Peak frequency (Hz).
        #[arg(long, allow_negative_numbers = true)]
        freq: f64,
        /// Time of the peak (s).
        #[arg(long, default_value_t = 1.0, allow_negative_numbers = true)]
        center: f64,
        /// Length (s).
        #[arg(long, allow_negative_numbers = true)]
        duration: f64,
    },
    /// One cycle of a sine.
    Pulse {
        /// Amplitude.
        #[arg(long, allow_hyphen_values = true)]
        amp: String,
        /// Frequency (Hz).
        #[arg(long, allow_negative_numbers = true)]
        freq: f64,
        /// Start of the pulse (s).
        #[arg(long, default_value_t = 0.5, allow_negative_numbers = true)]
        delay: f64,
        /// Length (s).
        #[arg(long, allow_negative_numbers = true)]
        duration: f64,
    },
    /// Kanai-Tajimi filtered white noise under an envelope.
    KanaiTajimi {
        /// Peak acceleration.
        #[arg(long, allow_hyphen_values = true)]
        pga: String,
        /// Ground frequency (Hz).
        #[arg(long, allow_negative_numbers = true)]
        fg: f64,
        /// Ground damping ratio.
        #[arg(long, default_value_t = 0.6, allow_negative_numbers = true)]
        zeta: f64,
        /// Length (s).
        #[arg(long, allow_negative_numbers = true)]
        duration: f64,
        /// Random seed.
        #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
        seed: u64,
    },
    /// The stand-in for the paper's 1978 Miyagi-ken-oki record (Kanai-Tajimi, 258 gal).
    MiyagiLike,
}

fn synthetic(kind: &GenerateKind) -> Result<Synthetic, Error> {
    let acc = |s: &str| parse_acceleration(s).map_err(Error::from);
    Ok(match kind {
        GenerateKind::Sine {
            amp,
            freq,
            duration,
            ramp,
            taper,
            phase,
        } => Synthetic::Sine {
            amplitude: acc(amp)?,
            frequency: *freq,
            phase: pirqa::motion::phase_rad(*phase),
            duration: *duration,
            ramp_s: *ramp,
            taper_s: *taper,
        },
        GenerateKind::Chirp {
            amp,
            f0,
            f1,
            duration,
            ramp,
            taper,
        } => Synthetic::Chirp {
            amplitude: acc(amp)?,
            f0: *f0,
            f1: *f1,
            duration: *duration,
            ramp_s: *ramp,
            taper_s: *taper,
        },
        GenerateKind::Ricker {
            amp,
            freq,
            center,
            duration,
        } => Synthetic::Ricker {
            amplitude: acc(amp)?,
            frequency: *freq,
            center: *center,
            duration: *duration,
        },
        GenerateKind::Pulse {
            amp,
            freq,
            delay,
            duration,
        } => Synthetic::SinePulse {
            amplitude: acc(amp)?,
            frequency: *freq,
            delay: *delay,
            duration: *duration,
        },
        GenerateKind::KanaiTajimi {
            pga,
            fg,
            zeta,
            duration,
            seed,
        } => Synthetic::KanaiTajimi {
            pga: acc(pga)?,
            fg: *fg,
            zeta_g: *zeta,
            duration: *duration,
            seed: *seed,
        },
        GenerateKind::MiyagiLike => Synthetic::miyagi_like(),
    })
}

/// A record as plain text with the header lines pirqa's reader understands; every number in
/// its shortest exact form, so reading it back gives the same record bit for bit.
pub fn record_text(r: &Record, comment: &str) -> String {
    let mut s = format!("# {comment}\n# units: m/s2\n# dt_s: {}\n", r.dt_s());
    for a in r.accel_m_s2() {
        let _ = writeln!(s, "{a:e}");
    }
    s
}

pub fn run(cmd: &MotionCommand) -> Result<(), Error> {
    match cmd {
        MotionCommand::Info(args) => info(args),
        MotionCommand::Generate { kind, output, dt } => {
            let syn = synthetic(kind)?;
            let record = syn.record(*dt).map_err(|source| Error::Motion {
                path: PathBuf::from("generate"),
                source,
            })?;
            let text = record_text(
                &record,
                &format!("pirqa motion generate: {}", syn.describe()),
            );
            match output {
                Some(path) => {
                    write_file(path, &text)?;
                    eprintln!(
                        "wrote {} ({} samples at {} s)",
                        path.display(),
                        record.accel_m_s2().len(),
                        dt
                    );
                }
                None => print_out(&text),
            }
            Ok(())
        }
    }
}

fn info(args: &InfoArgs) -> Result<(), Error> {
    let units = match &args.units {
        Some(u) => Some(AccelUnit::parse(u).ok_or_else(|| Error::Motion {
            path: PathBuf::from("--units"),
            source: pirqa::error::MotionError::Unknown {
                what: "units",
                given: u.into(),
                choices: "gal, g or m/s2",
            },
        })?),
        None => None,
    };
    let opts = ReadOptions {
        dt_s: args.dt,
        units,
        component: args.component,
    };
    let raw = read_record(&args.file, args.format.as_deref(), &opts)?;
    let (record, notes) = process(
        &raw,
        &Processing {
            baseline: args.baseline,
            ..Default::default()
        },
    )
    .map_err(|source| Error::Motion {
        path: args.file.clone(),
        source,
    })?;
    let m = Measures::of(&record);
    if args.json {
        print_out(&(serde_json::to_string_pretty(&m).expect("measures serialise") + "\n"));
    } else {
        let mut t = String::new();
        let _ = writeln!(
            t,
            "{} ({} samples at {} s, {} s)",
            record.name,
            m.npts,
            m.dt_s,
            record.duration_s()
        );
        for n in &notes {
            let _ = writeln!(t, "  {n}");
        }
        let g = pirqa::units::G_UNIT_M_S2;
        let _ = writeln!(
            t,
            "  PGA   {:.4} m/s2 = {:.1} gal = {:.4} g",
            m.pga_m_s2,
            m.pga_m_s2 * 100.0,
            m.pga_m_s2 / g
        );
        let _ = writeln!(t, "  PGV   {:.4} m/s", m.pgv_m_s);
        let _ = writeln!(t, "  PGD   {:.4} m", m.pgd_m);
        let _ = writeln!(t, "  Arias intensity       {:.4} m/s", m.arias_m_s);
        let _ = writeln!(t, "  significant duration  {:.2} s (D5-95)", m.d5_95_s);
        let _ = writeln!(
            t,
            "  mean period Tm        {:.3} s (Rathje et al. 1998)",
            m.tm_s
        );
        let _ = writeln!(
            t,
            "  predominant period    {:.3} s (peak of the 5 % spectrum)",
            m.predominant_period_s
        );
        print_out(&t);
    }
    if let Some(svg) = &args.plot {
        write_plot(svg, &record)?;
    }
    Ok(())
}

fn write_plot(svg: &Path, r: &Record) -> Result<(), Error> {
    let motion = Motion::Record(r.clone());
    let times: Vec<f64> = (0..r.accel_m_s2().len())
        .map(|k| k as f64 * r.dt_s())
        .collect();
    // Every sample's extremes kept: the peaks on the chart are the record's.
    let panel = |title: &str, y: &str, f: &dyn Fn(f64) -> f64| Chart {
        title: format!("{title} — {}", r.name),
        x_label: "time (s)".into(),
        y_label: y.into(),
        series: vec![Series {
            points: chart::envelope(&times.iter().map(|&t| (t, f(t))).collect::<Vec<_>>(), 1000),
            ..Default::default()
        }],
        ..Default::default()
    };
    let fas: Vec<(f64, f64)> = fourier_amplitude(r)
        .into_iter()
        .filter(|&(f, c)| (0.05..=50.0).contains(&f) && c > 0.0)
        .collect();
    let charts = vec![
        panel("ground acceleration", "a_g (m/s2)", &|t| motion.accel(t)),
        panel("ground velocity", "v_g (m/s)", &|t| motion.velocity(t)),
        panel("ground displacement", "d_g (m)", &|t| {
            motion.displacement(t)
        }),
        Chart {
            title: "Fourier amplitude spectrum".into(),
            x_label: "frequency (Hz)".into(),
            y_label: "|A(f)| (m/s)".into(),
            series: vec![Series {
                points: fas,
                ..Default::default()
            }],
            log_x: true,
            log_y: true,
            ..Default::default()
        },
    ];
    write_file(svg, &chart::render(&charts, 1, (900, 260)))?;
    write_file(&svg.with_extension("csv"), &chart::to_csv(&charts))?;
    eprintln!(
        "wrote {} and {}",
        svg.display(),
        svg.with_extension("csv").display()
    );
    Ok(())
}
