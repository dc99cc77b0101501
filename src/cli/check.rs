//! `pirqa check` and `pirqa draw`.

use super::{print_out, write_file};
use pirqa::plot::chart::{self, Chart, Series};
use pirqa::plot::{draw_wall, WallDrawing};
use pirqa::response::saved::state_at;
use pirqa::topology;
use pirqa::topology::sections::{self, Top};
use std::fmt::Write;
use std::path::Path;

/// `pirqa check --out-of-plane`: every section's static threshold and capacity curve, the
/// lowest threshold named.
pub fn out_of_plane(
    path: &Path,
    json: bool,
    top: Top,
    overburden_kn_m: Option<f64>,
    plot: Option<&Path>,
) -> Result<(), pirqa::Error> {
    let (wall, topo) = topology::load(path)?;
    let q = overburden_kn_m.unwrap_or(0.0);
    if !(q.is_finite() && q >= 0.0) {
        return Err(pirqa::Error::Option {
            option: "--overburden-kn-m".into(),
            rule: format!("{q} kN/m: an overburden must be a finite load, zero or more"),
        });
    }
    let report = sections::check(&wall, &topo, top, q);
    if let Some(file) = plot {
        let chart = Chart {
            title: format!(
                "{}: capacity across the plane, top {}",
                wall.name,
                top_name(top)
            ),
            x_label: "theta (rad)".into(),
            y_label: "lambda (g)".into(),
            series: report
                .sections
                .iter()
                .enumerate()
                .map(|(k, c)| Series {
                    label: c.section.name.clone(),
                    points: c
                        .capacity_curve
                        .iter()
                        .map(|p| (p.theta_rad, p.lambda_g))
                        .collect(),
                    color: k,
                    ..Series::default()
                })
                .collect(),
            ..Chart::default()
        };
        write_file(
            file,
            &chart::render(std::slice::from_ref(&chart), 1, (700, 450)),
        )?;
        write_file(&file.with_extension("csv"), &chart::to_csv(&[chart]))?;
    }
    if json {
        print_out(&(serde_json::to_string_pretty(&report).expect("report serialises") + "\n"));
        return Ok(());
    }
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{} ({}) across its plane: top {}, overburden {q} kN/m, thickness {} m",
        wall.name,
        path.display(),
        top_name(top),
        wall.thickness_m.to_f64()
    );
    let width = report
        .sections
        .iter()
        .map(|c| c.section.name.len())
        .max()
        .unwrap_or(0)
        .max(8);
    let _ = writeln!(
        out,
        "  {:<width$} {:>8} {:>9} {:>11} {:>8} {:>9} {:>10} {:>10} {:>15}",
        "section",
        "level_m",
        "height_m",
        "mass_kg",
        "h_c_m",
        "friction",
        "lambda0_g",
        "a0_m_s2",
        "theta_zero_rad"
    );
    for c in &report.sections {
        let s = &c.section;
        let _ = writeln!(
            out,
            "  {:<width$} {:>8.3} {:>9.3} {:>11.1} {:>8.3} {:>9.3} {:>10.4} {:>10.4} {:>15.4}",
            s.name,
            s.level_m,
            s.height_m,
            s.mass_kg,
            s.centroid_height_m,
            s.friction,
            c.threshold_g,
            c.threshold_m_s2,
            c.zero_capacity_rotation_rad
        );
    }
    if let Some(w) = &report.lowest_threshold {
        let _ = writeln!(
            out,
            "  lowest threshold: {w} (lambda0 g starts a section rocking if its base holds: a \
             bed joint whose friction is below lambda0 slides first)"
        );
    }
    for k in &report.skipped {
        let _ = writeln!(out, "  level {} m not checked: {}", k.level_m, k.why);
    }
    if let Some(file) = plot {
        let _ = writeln!(
            out,
            "  wrote {} and {}",
            file.display(),
            file.with_extension("csv").display()
        );
    }
    print_out(&out);
    Ok(())
}

fn top_name(top: Top) -> &'static str {
    match top {
        Top::Free => "free",
        Top::Restrained => "restrained",
    }
}

pub fn check(
    path: &Path,
    json: bool,
    limit: bool,
    mechanism: Option<&Path>,
    run: Option<(&Path, Option<f64>)>,
) -> Result<(), pirqa::Error> {
    let (built, built_topo) = topology::load(path)?;
    // Where a run left the wall, the rest of the check is that wall's, and the limit as built
    // stands beside its own.
    let moved = match run {
        Some((dir, at_s)) => {
            let state = state_at(dir, &built, at_s)?;
            let (wall, topo, moves) = pirqa::response::moved::moved(&built, &built_topo, &state)
                .map_err(|source| pirqa::Error::Moved {
                    dir: dir.to_path_buf(),
                    time_s: state.time_s,
                    source: Box::new(source),
                })?;
            Some((wall, topo, moves, dir, state.time_s))
        }
        None => None,
    };
    let (wall, topo) = match &moved {
        Some((wall, topo, ..)) => (wall, topo),
        None => (&built, &built_topo),
    };
    let as_built = (limit && moved.is_some()).then(|| limit_at_rest(&built, &built_topo));
    let r = topo.report(wall);
    // A wall made of columns: where each joint gives way, and which the column moves on.
    let columns = (wall.blocks.len() > 1)
        .then(|| pirqa::integrate::rocking::columns(wall, topo).ok())
        .flatten();
    // Where the wall at rest stops being held, when asked (a wall too large for the exact
    // program says why instead).
    let limit = limit.then(|| limit_at_rest(wall, topo));
    // Stopped by Ctrl-C, the report says so and the command ends with 130, drawing nothing.
    if let (Some(dir), Some(l), false) = (mechanism, &limit, super::interrupted()) {
        // Drawings asked for and not made are an error, not a line of the report.
        let l = l
            .as_ref()
            .map_err(|why| pirqa::SimulationError::NotApplicable(why.clone()))?;
        let title = match &moved {
            Some((.., run, time_s)) => format!(
                "{} where the run in {} left it (t = {time_s} s)",
                wall.name,
                run.display()
            ),
            None => wall.name.clone(),
        };
        write_mechanisms(dir, &title, wall, topo, l)?;
    }
    let moves = moved
        .as_ref()
        .map(|(_, _, moves, dir, time_s)| (moves, *dir, *time_s));
    if json {
        /// The graph's report, a wall of columns' joint limits and the limits at rest after it.
        #[derive(serde::Serialize)]
        struct Report<'a> {
            #[serde(flatten)]
            graph: &'a topology::TopologyReport,
            #[serde(skip_serializing_if = "Option::is_none")]
            columns: Option<Vec<&'a [pirqa::integrate::rocking::JointLimit]>>,
            #[serde(skip_serializing_if = "Option::is_none")]
            limit_at_rest: Option<&'a pirqa::limit::Limits>,
            #[serde(skip_serializing_if = "Option::is_none")]
            limit_at_rest_not_computed: Option<&'a str>,
            #[serde(skip_serializing_if = "Option::is_none")]
            moved_by_run: Option<MovedByRun<'a>>,
            #[serde(skip_serializing_if = "Option::is_none")]
            limit_at_rest_as_built: Option<&'a pirqa::limit::Limits>,
            #[serde(skip_serializing_if = "Option::is_none")]
            limit_at_rest_as_built_not_computed: Option<&'a str>,
        }
        /// Where the blocks are: the run and what moving the wall changed.
        #[derive(serde::Serialize)]
        struct MovedByRun<'a> {
            run: String,
            time_s: f64,
            #[serde(flatten)]
            moves: &'a pirqa::response::moved::Moves,
        }
        let report = Report {
            graph: &r,
            columns: columns
                .as_ref()
                .map(|cs| cs.iter().map(|c| c.limits.as_slice()).collect()),
            limit_at_rest: limit.as_ref().and_then(|l| l.as_ref().ok()),
            limit_at_rest_not_computed: limit
                .as_ref()
                .and_then(|l| l.as_ref().err())
                .map(String::as_str),
            moved_by_run: moves.map(|(moves, dir, time_s)| MovedByRun {
                run: dir.display().to_string(),
                time_s,
                moves,
            }),
            limit_at_rest_as_built: as_built.as_ref().and_then(|l| l.as_ref().ok()),
            limit_at_rest_as_built_not_computed: as_built
                .as_ref()
                .and_then(|l| l.as_ref().err())
                .map(String::as_str),
        };
        print_out(&(serde_json::to_string_pretty(&report).expect("report serialises") + "\n"));
        return Ok(());
    }
    let mut out = String::new();
    let _ = writeln!(out, "{} ({})", r.name, path.display());
    if let Some((m, dir, time_s)) = moves {
        write_moves(&mut out, m, dir, time_s);
    }
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
    for s in &r.horizontal {
        let _ = writeln!(
            out,
            "  {:<8} {:<8} {:>10.3} {:>11.2} {:>9.3} {:>12.2}",
            s.upper, s.lower, s.overlap_m, s.load_n, s.friction, s.capacity_n
        );
    }
    let _ = writeln!(out, "\nvertical joints");
    if r.vertical.is_empty() {
        let _ = writeln!(out, "  (none)");
    } else {
        let _ = writeln!(
            out,
            "  {:<8} {:<8} {:>8} {:>9}",
            "left", "right", "gap_m", "height_m"
        );
        for j in &r.vertical {
            let _ = writeln!(
                out,
                "  {:<8} {:<8} {:>8.3} {:>9.3}",
                j.left, j.right, j.gap_m, j.height_m
            );
        }
    }
    for c in columns.iter().flatten() {
        let _ = writeln!(
            out,
            "\ncolumn {} (in the wall's plane: where each joint gives way, in g, the part above it \
             rigid and the rest moving with the ground)",
            c.body.name
        );
        let width = c
            .limits
            .iter()
            .map(|l| l.joint.len())
            .max()
            .unwrap_or(0)
            .max(5);
        let _ = writeln!(
            out,
            "  {:<width$} {:>8} {:>12} {:>13}",
            "joint", "slip_g", "tips_left_g", "tips_right_g"
        );
        for l in &c.limits {
            let _ = writeln!(
                out,
                "  {:<width$} {:>8.4} {:>12.4} {:>13.4}{}",
                l.joint,
                l.slip_g,
                l.tips_left_g,
                l.tips_right_g,
                if l.moves {
                    format!("  <- gives way first: {} moves on it", c.body.name)
                } else {
                    String::new()
                }
            );
        }
    }
    let Some(limit) = limit else {
        print_out(&out);
        return Ok(());
    };
    let _ = writeln!(
        out,
        "\nlimit at rest (every block seated and moving with the ground; rigid blocks, joints \
         without tension, Coulomb's cone at each end of each joint)"
    );
    if moves.is_some() {
        let _ = writeln!(out, "  of the wall where the run left it:");
    }
    match &limit {
        Ok(l) => {
            for (side, l) in [("+x", &l.towards_plus_x), ("-x", &l.towards_minus_x)] {
                write_limit(&mut out, side, l);
            }
        }
        Err(why) => {
            let _ = writeln!(out, "  not computed: {why}");
        }
    }
    match &as_built {
        Some(Ok(l)) => {
            let side = |l: &pirqa::limit::Limit| match l {
                pirqa::limit::Limit::Unlimited => "held at any acceleration".to_string(),
                pirqa::limit::Limit::Holds {
                    accel_g, exact_g, ..
                } => format!("{accel_g:.4} g ({exact_g} g)"),
            };
            let _ = writeln!(
                out,
                "  of the wall as built: towards +x {}; towards -x {}",
                side(&l.towards_plus_x),
                side(&l.towards_minus_x)
            );
        }
        Some(Err(why)) => {
            let _ = writeln!(out, "  of the wall as built: not computed: {why}");
        }
        None => {}
    }
    print_out(&out);
    Ok(())
}

/// What the run did to the wall the report describes.
fn write_moves(out: &mut String, m: &pirqa::response::moved::Moves, dir: &Path, time_s: f64) {
    let list = |names: &[String]| {
        if names.is_empty() {
            "none".to_string()
        } else {
            names.join(", ")
        }
    };
    let _ = writeln!(
        out,
        "  where the run in {} left it at t = {} s: every block moved by its displacement (the \
         largest {:.4} m)",
        dir.display(),
        time_s,
        m.largest_displacement_m,
    );
    let _ = writeln!(
        out,
        "  fallen, taken out: {}; joints slid apart: {}; joints slid onto: {} (friction: the \
         wall's default); vertical joints the run left touching (within {:e} m), set touching: {}",
        list(&m.fallen),
        list(&m.joints_lost),
        list(&m.joints_new),
        pirqa::response::moved::TOUCHING_M,
        m.faces_set_touching
    );
}

/// The wall's limit at rest, a spinner on the terminal while the exact program runs; a wall
/// too large for it gives the reason, and so does a Ctrl-C that stopped it (a large wall's
/// programs can take minutes).
fn limit_at_rest(
    wall: &pirqa::wall::Wall,
    topo: &topology::Topology,
) -> Result<pirqa::limit::Limits, String> {
    let spinner = indicatif::ProgressBar::new_spinner();
    spinner.set_message("the limit at rest: solving its exact linear programs (Ctrl-C stops)");
    spinner.enable_steady_tick(std::time::Duration::from_millis(200));
    let stop = super::stop_flag();
    let started = std::time::Instant::now();
    // The programs ask before every pivot: a count of them shows a large wall's check moving.
    let pivots = std::cell::Cell::new(0_u64);
    let limit = pirqa::limit::at_rest_until(wall, topo, &|| {
        pivots.set(pivots.get() + 1);
        if pivots.get().is_multiple_of(1024) {
            spinner.set_message(format!(
                "the limit at rest: {} pivots of its linear programs in {:.0} s (Ctrl-C stops)",
                pivots.get(),
                started.elapsed().as_secs_f64()
            ));
        }
        stop.load(std::sync::atomic::Ordering::Relaxed)
    });
    spinner.finish_and_clear();
    match limit {
        Ok(Some(limit)) => Ok(limit),
        Ok(None) => Err(format!(
            "stopped by Ctrl-C after {:.1} s, before the programs of both sides were proved",
            started.elapsed().as_secs_f64()
        )),
        Err(pirqa::SimulationError::NotApplicable(why)) => Err(why),
        Err(other) => Err(other.to_string()),
    }
}

/// The limits as JSON and each direction's mechanism drawn, into `dir`.
fn write_mechanisms(
    dir: &Path,
    title: &str,
    wall: &pirqa::wall::Wall,
    topo: &topology::Topology,
    limits: &pirqa::limit::Limits,
) -> Result<(), pirqa::Error> {
    std::fs::create_dir_all(dir).map_err(|source| pirqa::Error::Io {
        path: dir.to_path_buf(),
        source,
    })?;
    let json = serde_json::to_string_pretty(limits).expect("limits serialise") + "\n";
    write_file(&dir.join("limit.json"), &json)?;
    for (side, name, l) in [
        ("+x", "plus-x", &limits.towards_plus_x),
        ("-x", "minus-x", &limits.towards_minus_x),
    ] {
        let pirqa::limit::Limit::Holds {
            accel_g,
            exact_g,
            mechanism,
            mechanism_uniqueness,
            ..
        } = l
        else {
            continue;
        };
        let (u, theta, w) = pirqa::plot::mechanism_pose(wall, mechanism);
        let which = mechanism_uniqueness.which();
        let drawing = WallDrawing {
            title: format!(
                "{title}: past its limit at rest towards {side}, {accel_g:.4} g ({exact_g} g)"
            ),
            displacement_m: Some(u),
            pose: Some((theta, w)),
            note: Some(format!(
                "{which}, exaggerated (pirqa check --limit; a slipping joint dilates at the \
                 friction angle: the associative mechanism)"
            )),
            ..WallDrawing::default()
        };
        write_file(
            &dir.join(format!("mechanism-{name}.svg")),
            &draw_wall(wall, topo, &drawing),
        )?;
    }
    Ok(())
}

/// One direction's limit at rest and the mechanism beyond it.
fn write_limit(out: &mut String, side: &str, l: &pirqa::limit::Limit) {
    match l {
        pirqa::limit::Limit::Unlimited => {
            let _ = writeln!(
                out,
                "  ground towards {side}: held at any acceleration (the abutments hold it)"
            );
        }
        pirqa::limit::Limit::Holds {
            accel_m_s2,
            accel_g,
            exact_g,
            mechanism,
            mechanism_uniqueness,
            moving_in_every_mechanism,
            turning_in_every_mechanism,
            ..
        } => {
            let _ = writeln!(
                out,
                "  ground towards {side}: held up to {accel_g:.4} g ({accel_m_s2:.4} m/s2; exactly \
                 {exact_g} g), then"
            );
            for m in mechanism {
                let _ = writeln!(out, "    {:<8} {}", m.block, m.how);
            }
            if *mechanism_uniqueness != pirqa::limit::Uniqueness::Unique {
                let _ = writeln!(out, "    ({})", mechanism_uniqueness.which());
                let list = |names: &[String]| pirqa::limit::in_every_listed(names, ", ");
                match (moving_in_every_mechanism, turning_in_every_mechanism) {
                    (Some(moving), Some(turning)) => {
                        let _ = writeln!(
                            out,
                            "    in every mechanism that holds here: moving {}; turning {}",
                            list(moving),
                            list(turning)
                        );
                    }
                    // Not decided for the wall's size alone, whatever its uniqueness.
                    _ => {
                        let _ = writeln!(
                            out,
                            "    (which blocks move in every mechanism that holds here is \
                             decided for walls of up to {} movable blocks)",
                            pirqa::limit::EVERY_BLOCKS
                        );
                    }
                }
            }
        }
    }
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
        drawing.pose = state.pose;
        drawing.fallen = state.fallen;
    }
    write_file(output, &draw_wall(&wall, &topo, &drawing))?;
    eprintln!("wrote {}", output.display());
    Ok(())
}

/// Writes the page that plays the run saved in `dir` back (`pirqa animate`).
pub fn animate(dir: &Path, output: &Path, wall_file: Option<&Path>) -> Result<(), pirqa::Error> {
    let wall_file = wall_file.map_or_else(|| dir.join("wall.ron"), Path::to_path_buf);
    let (wall, _) = topology::load(&wall_file)?;
    // The summary's wall must be this one (state_at checks it), the history must be there.
    pirqa::response::saved::state_at(dir, &wall, None)?;
    let names: Vec<String> = wall.blocks.iter().map(|b| b.name.clone()).collect();
    let history = pirqa::response::saved::history(dir, &names)?;
    let ground = pirqa::response::saved::ground_acceleration(dir)?;
    let events = pirqa::response::saved::events(dir)?;
    let title = format!("{}: {}", wall.name, dir.display());
    let page = pirqa::plot::animation::html(&wall, &title, &history, &ground, &events);
    write_file(output, &page)?;
    eprintln!(
        "wrote {} ({} samples, {} events)",
        output.display(),
        history.time_s.len(),
        events.len()
    );
    Ok(())
}
