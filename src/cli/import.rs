//! `pirqa import`: a survey of block outlines (CSV) into a wall file, with a report of every
//! snap and of the topology it gives.

use super::generate::Material;
use super::{print_out, write_file};
use pirqa::error::SurveyError;
use pirqa::error::UnitError;
use pirqa::units::{length_unit_m, parse_length, LENGTH_UNITS};
use pirqa::wall::survey::{import, parse_survey, Edge, SurveyOptions};
use pirqa::wall::to_ron_string;
use pirqa::{Error, Topology, Wall};
use std::fmt::Write;
use std::path::PathBuf;

/// Options of `pirqa import`.
#[derive(clap::Args, Debug)]
pub struct ImportArgs {
    /// Survey CSV: a header `id,x,y,width,height` (optional columns material, friction, fixed),
    /// then one block per line (docs/walls.md).
    pub survey: PathBuf,
    /// Output wall file (RON).
    #[arg(short, long)]
    pub output: PathBuf,
    /// Units of the survey's lengths: mm, cm or m.
    #[arg(long, default_value = "m")]
    pub units: String,
    /// Edges closer than this are snapped together (`5mm`, `0.5cm`).
    #[arg(long, default_value = "5mm", allow_hyphen_values = true)]
    pub snap: String,
    /// List every snapped edge.
    #[arg(long)]
    pub verbose: bool,
    /// Wall name (default: the survey's file name).
    #[arg(long)]
    pub name: Option<String>,
    /// What a survey of an elevation does not give.
    #[command(flatten)]
    pub material: Material,
}

fn edge_name(e: Edge) -> &'static str {
    match e {
        Edge::Bottom => "bottom",
        Edge::Top => "top",
        Edge::Left => "left face",
        Edge::Right => "right face",
    }
}

pub fn run(args: &ImportArgs) -> Result<(), Error> {
    let unit_m = length_unit_m(&args.units).ok_or_else(|| UnitError::Unreadable {
        what: "survey unit",
        text: args.units.clone(),
        units: LENGTH_UNITS,
    })?;
    let snap_m = parse_length(&args.snap)?;
    let survey_error = |source: SurveyError| Error::Survey {
        path: args.survey.clone(),
        source: Box::new(source),
    };
    let text = std::fs::read_to_string(&args.survey).map_err(|source| Error::Io {
        path: args.survey.clone(),
        source,
    })?;
    let blocks = parse_survey(&text, unit_m).map_err(survey_error)?;
    let name = args.name.clone().unwrap_or_else(|| {
        args.survey
            .file_stem()
            .map_or_else(|| "survey".into(), |s| s.to_string_lossy().into_owned())
    });
    let options = SurveyOptions {
        snap_m,
        name,
        thickness_m: parse_length(&args.material.thickness)?,
        density_kg_m3: args.material.density,
        friction: args.material.friction,
        restitution: args.material.restitution,
    };
    let imported = import(&blocks, &options).map_err(survey_error)?;
    let wall = Wall::from_description(&imported.description).map_err(|source| Error::Wall {
        path: args.output.clone(),
        source,
    })?;
    let topo = Topology::new(&wall).map_err(|source| Error::Wall {
        path: args.output.clone(),
        source,
    })?;
    let largest = imported.largest_snap();
    let gaps: Vec<f64> = topo
        .vertical
        .iter()
        .map(|j| j.gap_m.to_f64())
        .filter(|&g| g > 0.0)
        .collect();
    let mut report = String::new();
    let _ = writeln!(
        report,
        "{}: {} blocks, {} supports, {} vertical joints ({} with a measured gap{})",
        args.survey.display(),
        wall.blocks.len(),
        topo.horizontal.len(),
        topo.vertical.len(),
        gaps.len(),
        gaps.iter()
            .copied()
            .reduce(f64::max)
            .map_or(String::new(), |g| format!(", widest {:.1} mm", g * 1e3))
    );
    let _ = writeln!(
        report,
        "snapped {} edges within {:.1} mm; largest adjustment {}",
        imported.snaps.len(),
        snap_m * 1e3,
        largest.map_or("none".to_string(), |s| format!(
            "{:.2} mm ({} {} onto {})",
            (s.to_m - s.from_m).abs() * 1e3,
            s.block,
            edge_name(s.edge),
            s.onto
        ))
    );
    let _ = writeln!(
        report,
        "levels measured from the lowest bottom (survey y = {} m); thickness {} m, density {} kg/m3, friction {} (wall-level values: --thickness, --density, --friction)",
        imported.ground_y_m,
        options.thickness_m,
        options.density_kg_m3,
        options.friction,
    );
    if args.verbose {
        for s in &imported.snaps {
            let _ = writeln!(
                report,
                "  {:<10} {:<10} {:>10.5} -> {:>10.5} m ({:+.2} mm) onto {}",
                s.block,
                edge_name(s.edge),
                s.from_m,
                s.to_m,
                (s.to_m - s.from_m) * 1e3,
                s.onto
            );
        }
    }
    let header = format!(
        "// Imported by `pirqa import` from {} (units {}, snap {:.1} mm): {} blocks, {} edges snapped, largest {:.2} mm.\n// Thickness, density and friction are wall-level values given on the command line; edit them here.\n",
        args.survey.display(),
        args.units,
        snap_m * 1e3,
        wall.blocks.len(),
        imported.snaps.len(),
        largest.map_or(0.0, |s| (s.to_m - s.from_m).abs() * 1e3)
    );
    write_file(
        &args.output,
        &(header + &to_ron_string(&imported.description) + "\n"),
    )?;
    let _ = writeln!(report, "wrote {}", args.output.display());
    print_out(&report);
    Ok(())
}
