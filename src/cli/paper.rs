//! `pirqa paper`: the paper's figures and the numbers docs/paper.md quotes.

use super::sweep::progress_bar;
use super::write_file;
use pirqa::study::paper::{reproduce, Options};
use pirqa::Error;
use std::path::PathBuf;

/// Options of `pirqa paper`.
#[derive(clap::Args, Debug)]
pub struct PaperArgs {
    /// Output directory (the committed figures live in docs/paper).
    #[arg(long, default_value = "docs/paper")]
    pub out: PathBuf,
    /// Directory holding five-block-uniform.ron and five-block-variable.ron.
    #[arg(long, default_value = "walls")]
    pub walls: PathBuf,
    /// Record for Fig. 5 and 6, scaled to 258 gal (Miyagi's peak) and then by 5.
    #[arg(long, default_value = pirqa::motion::EL_CENTRO)]
    pub record: PathBuf,
    /// Sine duration (s); the paper does not give it.
    #[arg(long, default_value_t = 20.0, allow_negative_numbers = true)]
    pub duration: f64,
}

pub fn run(args: &PaperArgs) -> Result<(), Error> {
    let opts = Options {
        walls: args.walls.clone(),
        record: args.record.clone(),
        duration_s: args.duration,
        ..Options::default()
    };
    let mut bar: Option<(String, indicatif::ProgressBar)> = None;
    let out = reproduce(&opts, &mut |stage, done, total| {
        if bar.as_ref().is_none_or(|(s, _)| s != stage) {
            if let Some((_, b)) = bar.take() {
                b.finish_and_clear();
            }
            bar = Some((stage.to_string(), progress_bar(total, 0, stage)));
        }
        if let Some((_, b)) = &bar {
            b.set_position(done);
        }
    })?;
    if let Some((_, b)) = bar {
        b.finish_and_clear();
    }
    for (name, contents) in &out.files {
        write_file(&args.out.join(name), contents)?;
    }
    write_file(
        &args.out.join("paper.json"),
        &(serde_json::to_string_pretty(&out.numbers).expect("json") + "\n"),
    )?;
    eprintln!(
        "wrote {} figures and paper.json to {}",
        out.files.len(),
        args.out.display()
    );
    Ok(())
}
