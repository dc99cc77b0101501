//! `pirqa check` and `pirqa draw`.

use super::{print_out, write_file};
use pirqa::plot::{draw_wall, WallDrawing};
use pirqa::response::saved::state_at;
use pirqa::topology;
use std::fmt::Write;
use std::path::Path;

pub fn check(path: &Path, json: bool) -> Result<(), pirqa::Error> {
    let (wall, topo) = topology::load(path)?;
    let r = topo.report(&wall);
    if json {
        print_out(&(serde_json::to_string_pretty(&r).expect("report serialises") + "\n"));
        return Ok(());
    }
    let mut out = String::new();
    let _ = writeln!(out, "{} ({})", r.name, path.display());
    let _ = writeln!(
        out,
        "  {} blocks, thickness {} m, density {} kg/m3, g = {} m/s2, restitution {}",
        r.blocks.len(),
        r.thickness_m,
        r.density_kg_m3,
        r.g_m_s2,
        r.restitution
    );
    let _ = writeln!(out, "\nblocks");
    let _ = writeln!(
        out,
        "  {:<8} {:>8} {:>8} {:>8} {:>9} {:>11} {:>11} {:>11}",
        "name", "x_m", "y_m", "width_m", "height_m", "mass_kg", "weight_n", "load_n"
    );
    for b in &r.blocks {
        let _ = writeln!(
            out,
            "  {:<8} {:>8.3} {:>8.3} {:>8.3} {:>9.3} {:>11.2} {:>11.2} {:>11.2}{}",
            b.name,
            b.x_m,
            b.y_m,
            b.width_m,
            b.height_m,
            b.mass_kg,
            b.weight_n,
            b.load_n,
            if b.fixed { "  fixed" } else { "" }
        );
    }
    let _ = writeln!(
        out,
        "\nsupports (horizontal joints: capacity = friction x load)"
    );
    let _ = writeln!(
        out,
        "  {:<8} {:<8} {:>10} {:>11} {:>9} {:>12}",
        "upper", "lower", "overlap_m", "load_n", "friction", "capacity_n"
    );
    for s in &r.supports {
        let _ = writeln!(
            out,
            "  {:<8} {:<8} {:>10.3} {:>11.2} {:>9.3} {:>12.2}",
            s.upper, s.lower, s.overlap_m, s.load_n, s.friction, s.capacity_n
        );
    }
    let _ = writeln!(out, "\nvertical joints");
    if r.joints.is_empty() {
        let _ = writeln!(out, "  (none)");
    } else {
        let _ = writeln!(
            out,
            "  {:<8} {:<8} {:>8} {:>9}",
            "left", "right", "gap_m", "height_m"
        );
        for j in &r.joints {
            let _ = writeln!(
                out,
                "  {:<8} {:<8} {:>8.3} {:>9.3}",
                j.left, j.right, j.gap_m, j.height_m
            );
        }
    }
    print_out(&out);
    Ok(())
}

/// Draws the wall as built, or where the run saved in a directory left it (at its end or at a
/// time).
pub fn draw(
    path: &Path,
    output: &Path,
    graph: bool,
    run: Option<(&Path, Option<f64>)>,
) -> Result<(), pirqa::Error> {
    let (wall, topo) = topology::load(path)?;
    let mut drawing = WallDrawing {
        title: wall.name.clone(),
        friction_labels: true,
        support_graph: graph,
        note: Some(format!("pirqa draw {}", path.display())),
        ..WallDrawing::default()
    };
    if let Some((dir, at_s)) = run {
        let state = state_at(dir, &wall, at_s)?;
        let fell = state.fallen.iter().filter(|&&f| f).count();
        drawing.title = match at_s {
            None => format!("{}: final state, t = {} s", wall.name, state.time_s),
            Some(_) => format!("{}: t = {} s", wall.name, state.time_s),
        };
        drawing.note = Some(format!(
            "{}; largest |u| {:.1} mm; {fell} fallen; from {}",
            if at_s.is_some() {
                "history sample"
            } else {
                "exact final displacements"
            },
            state
                .displacement_m
                .iter()
                .fold(0.0f64, |m, u| m.max(u.abs()))
                * 1e3,
            dir.display()
        ));
        drawing.displacement_m = Some(state.displacement_m);
        drawing.fallen = state.fallen;
    }
    write_file(output, &draw_wall(&wall, &topo, &drawing))?;
    eprintln!("wrote {}", output.display());
    Ok(())
}
