//! Sweeps: descriptions and their errors, reproducible friction samples, storage that survives
//! an interruption, and what the analysis reports.

use crate::common;

use common::scratch as temp_dir;
use pirqa::limit::Uniqueness;
use pirqa::study::sweep::store::{read_table, CaseRow, Existing, Store, CASES_HEADER};
use pirqa::study::sweep::{parse_description, Sweep, SweepDescription, FRICTION_STEP};
use std::collections::HashSet;
use std::path::Path;

const EL_CENTRO: &str = "records/elcentro1940_IELC180_peer_dt0p01_g.AT2";

fn sweep(text: &str) -> Result<Sweep, pirqa::Error> {
    let d: SweepDescription = parse_description(text).map_err(|source| pirqa::Error::Sweep {
        path: "<test>".into(),
        source: Box::new(source),
    })?;
    Sweep::from_description(&d, Path::new("."), Path::new("<test>"))
}

/// Two five-block walls, two sine amplitudes at three frequencies, three friction samples.
const SMALL: &str = r#"(
    version: 1,
    name: "small",
    walls: [File(path: "walls/five-block-uniform.ron"), File(path: "walls/five-block-variable.ron")],
    motion: Sine(amplitudes: ["350gal", "0.5g"], frequencies_hz: List([0.5, 1.0, 2.0]), duration_s: 5.0),
    friction: Random(distribution: Lognormal, cov: 0.15, samples: 3, seed: 11),
)"#;

fn without_time(rows: &[CaseRow]) -> Vec<CaseRow> {
    rows.iter()
        .map(|r| CaseRow {
            cpu_s: 0.0,
            ..r.clone()
        })
        .collect()
}

fn run_all(s: &Sweep, dir: &Path, existing: Existing) -> Vec<CaseRow> {
    let mut store = Store::open(dir, s, existing).unwrap();
    let done = store.done();
    s.run_cases(&done, |r, b| store.append(r, b)).unwrap();
    store.finish().unwrap().0
}

#[test]
fn bad_sweep_files_get_errors_that_say_what_to_fix() {
    let e = parse_description("(version: 1, name: \"x\", walls: [], colour: 3)").unwrap_err();
    assert!(e.to_string().contains("colour"), "{e}");
    let e = sweep(&SMALL.replace("version: 1", "version: 7")).unwrap_err();
    assert!(e.to_string().contains("version 7"), "{e}");
    let e = sweep(&SMALL.replace("five-block-uniform", "nowhere")).unwrap_err();
    let e = e.to_string();
    assert!(
        e.starts_with("<test>: wall \"walls/nowhere.ron\"") && e.contains("start in ."),
        "{e}"
    );
    // Every part of a sweep file refuses keys it does not know (none is silently ignored).
    let e = parse_description(&SMALL.replace("seed: 11", "seed: 11, sead: 12")).unwrap_err();
    assert!(e.to_string().contains("sead"), "{e}");
    let e = parse_description(&SMALL.replace(".ron\")", ".ron\", mu: 0.3)")).unwrap_err();
    assert!(e.to_string().contains("`mu`"), "{e}");
    let e = parse_description(&SMALL.replace("duration_s: 5.0", "duration_s: 5.0, dt: 0.01"))
        .unwrap_err();
    assert!(e.to_string().contains("`dt`"), "{e}");
    let e = sweep(&SMALL.replace("\"350gal\"", "\"350 furlongs\"")).unwrap_err();
    assert!(
        e.to_string()
            .contains("<test>: cannot read acceleration \"350 furlongs\""),
        "{e}"
    );
    let e = sweep(&SMALL.replace("List([0.5, 1.0, 2.0])", "Log(from: 0.0, to: 2.0, count: 3)"))
        .unwrap_err();
    assert!(
        e.to_string()
            .contains("a Log range needs `from` and `to` above 0"),
        "{e}"
    );
    let e = sweep(&SMALL.replace("cov: 0.15", "cov: 1.5")).unwrap_err();
    assert!(e.to_string().contains("cov"), "{e}");
    let records = format!(
        r#"(version: 1, name: "r", walls: [File(path: "walls/five-block-variable.ron")],
            motion: Records(files: ["{EL_CENTRO}"], scales: [1.0], pga: ["300gal"]))"#
    );
    let e = sweep(&records).unwrap_err();
    assert!(e.to_string().contains("either `scales` or `pga`"), "{e}");
    let e =
        sweep(&records.replace("scales: [1.0], pga: [\"300gal\"]", "pga: [\"0gal\"]")).unwrap_err();
    assert!(
        e.to_string()
            .contains("pga \"0gal\": a target peak must be positive"),
        "{e}"
    );
    // A time step longer than a case's run is refused with the file, before any case runs
    // (the run refuses it too: one step would stand for the whole motion).
    for (key, setting) in [
        ("method", "method: Moreau(dt_s: 6.0)"),
        ("method", "method: Paper(dt_s: 6.0)"),
        ("fallback", "fallback: Moreau(dt_s: 6.0)"),
        ("after_uplift", "after_uplift: Moreau(dt_s: 6.0)"),
        (
            "after_uplift",
            "after_uplift: MoreauWhileRocking(dt_s: 6.0)",
        ),
    ] {
        let text = SMALL.replace("friction: Random", &format!("{setting}, friction: Random"));
        let e = sweep(&text).unwrap_err().to_string();
        assert!(
            e.contains(key)
                && e.contains("time step 6 s: it is longer than the run")
                && e.contains("(motion "),
            "{e}"
        );
        // The same step within the run is taken.
        sweep(&text.replace("6.0", "5.0")).unwrap();
        // A step so short that the run would take more than 1e9 of them is refused as well.
        let e = sweep(&text.replace("6.0", "1e-9")).unwrap_err().to_string();
        assert!(
            e.contains(key) && e.contains("more than 1e9 steps") && e.contains("(motion "),
            "{e}"
        );
    }
}

#[test]
fn friction_samples_are_reproducible_rounded_and_centred_on_the_wall() {
    let s = sweep(SMALL).unwrap();
    assert_eq!(s.len(), 2 * 6 * 3);
    // The same sample at every motion, different samples otherwise.
    assert_eq!(s.frictions(1, 2), s.frictions(1, 2));
    assert_ne!(s.frictions(1, 0), s.frictions(1, 1));
    let many = sweep(&SMALL.replace("samples: 3", "samples: 4000")).unwrap();
    let nominal: Vec<f64> = many.walls[1]
        .topology
        .horizontal
        .iter()
        .map(|sup| sup.friction.to_f64())
        .collect();
    let mut sum = vec![0.0; nominal.len()];
    for k in 0..4000 {
        for (j, mu) in many.frictions(1, k).iter().enumerate() {
            let x = mu.to_f64();
            assert!(x > 0.0 && x <= 2.0);
            // A multiple of the friction step, exactly.
            assert_eq!(
                *mu,
                pirqa::exact::Q::frac((x / FRICTION_STEP).round() as i128, 10_000)
            );
            sum[j] += x;
        }
    }
    for (s, mu) in sum.iter().zip(&nominal) {
        // The sample mean is within five standard errors (cov / sqrt(n)) of the wall's own.
        let mean = s / 4000.0;
        assert!(
            (mean - mu).abs() < 5.0 * 0.15 * mu / 4000f64.sqrt() + FRICTION_STEP,
            "{mean} vs {mu}"
        );
    }
}

#[test]
fn an_interrupted_sweep_resumes_to_the_same_table() {
    let s = sweep(SMALL).unwrap();
    let fresh = run_all(&s, &temp_dir("fresh"), Existing::Refuse);
    assert_eq!(fresh.len(), s.len());
    assert!(fresh.iter().all(|r| r.error.is_none()));

    // Interrupted after 7 cases (the writer fails), with half a line left at the end.
    let dir = temp_dir("resume");
    let mut store = Store::open(&dir, &s, Existing::Refuse).unwrap();
    let mut written = 0;
    let stopped = s.run_cases(&HashSet::new(), |r, b| {
        if written == 7 {
            return Err(pirqa::Error::Table {
                path: dir.to_path_buf(),
                line: 0,
                message: "disk full".into(),
            });
        }
        written += 1;
        store.append(r, b)
    });
    assert!(stopped.is_err());
    drop(store);
    let cases = dir.join("cases.csv");
    let mut text = std::fs::read_to_string(&cases).unwrap();
    text.push_str("99,five-block");
    std::fs::write(&cases, text).unwrap();

    // Not touched without --resume or --fresh.
    let e = Store::open(&dir, &s, Existing::Refuse).err().unwrap();
    assert!(e.to_string().contains("--resume"), "{e}");
    let store = Store::open(&dir, &s, Existing::Resume).unwrap();
    assert_eq!(store.done().len(), 7);
    drop(store);
    let resumed = run_all(&s, &dir, Existing::Resume);
    assert_eq!(without_time(&resumed), without_time(&fresh));
    let back: Vec<CaseRow> = read_table(&cases, CASES_HEADER).unwrap();
    assert_eq!(without_time(&back), without_time(&fresh));

    // Without its blocks.csv (the studies in docs/ leave it out) a sweep cannot resume, and
    // the message says what to do; its charts can still be drawn again from cases.csv alone.
    let blocks = dir.join("blocks.csv");
    let kept = std::fs::read(&blocks).unwrap();
    std::fs::remove_file(&blocks).unwrap();
    let e = Store::open(&dir, &s, Existing::Resume)
        .err()
        .unwrap()
        .to_string();
    assert!(e.contains("blocks.csv") && e.contains("--fresh"), "{e}");
    assert_eq!(Store::finished(&dir, &s).unwrap(), resumed);
    assert!(!blocks.exists());
    std::fs::write(&blocks, kept).unwrap();

    // Drawing again needs every case, and says how to run the rest.
    let table = std::fs::read_to_string(&cases).unwrap();
    let mut lines: Vec<&str> = table.lines().collect();
    let gone = lines.remove(5);
    std::fs::write(&cases, lines.join("\n") + "\n").unwrap();
    let e = Store::finished(&dir, &s).err().unwrap().to_string();
    assert!(
        e.contains("cases.csv") && e.contains("1 of the sweep's 36 cases") && e.contains("case 4"),
        "{e}"
    );
    assert!(e.contains("--resume"), "{e}");
    lines.push(gone);
    lines.push(gone);
    std::fs::write(&cases, lines.join("\n") + "\n").unwrap();
    let e = Store::finished(&dir, &s).err().unwrap().to_string();
    assert!(e.contains("case 4 is listed twice"), "{e}");
    std::fs::write(&cases, &table).unwrap();

    // Another sweep's results are refused.
    let other = sweep(&SMALL.replace("seed: 11", "seed: 12")).unwrap();
    let e = Store::open(&dir, &other, Existing::Resume).err().unwrap();
    assert!(e.to_string().contains("another sweep"), "{e}");
    let e = Store::finished(&dir, &other).err().unwrap();
    assert!(e.to_string().contains("another sweep"), "{e}");

    // A table with other columns (another version of pirqa) names the file and says what to do.
    let old_columns = CASES_HEADER.replace("transitions,decision_blocks,flow_nodes,", "");
    let text = std::fs::read_to_string(&cases).unwrap();
    std::fs::write(&cases, text.replacen(CASES_HEADER, &old_columns, 1)).unwrap();
    let e = read_table::<CaseRow>(&cases, CASES_HEADER)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("cases.csv: line 1") && e.contains("--fresh"),
        "{e}"
    );
    std::fs::write(&cases, text).unwrap();
    // So does a blocks.csv written before it had each block's rotation.
    let kept = std::fs::read_to_string(&blocks).unwrap();
    let old: String = kept
        .lines()
        .map(|l| l.rsplit_once(',').unwrap().0.to_string() + "\n")
        .collect();
    std::fs::write(&blocks, old).unwrap();
    let e = Store::open(&dir, &s, Existing::Resume)
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("blocks.csv: line 1")
            && e.contains("max_abs_rotation_rad")
            && e.contains("--fresh"),
        "{e}"
    );
}

#[test]
fn every_case_closes_its_energy_balance_including_a_former_wrong_friction_direction() {
    // Case 1509 of this sweep once ran with a joint's friction pointing the wrong way after an
    // impact chain (rounding gave the two sides' velocities opposite orders): -4.7e-3 J of
    // energy from nowhere. The pair now meets when the velocity leaves the assumed sign.
    let text = format!(
        r#"(version: 1, name: "regression",
            walls: [
                RunningBond(courses: 4, blocks_per_course: 4, width_m: 2.4, height_m: 1.2, thickness_m: 0.8, density_kg_m3: 2650, friction: 0.3),
                RunningBond(courses: 6, blocks_per_course: 6, width_m: 2.4, height_m: 1.2, thickness_m: 0.8, density_kg_m3: 2650, friction: 0.3),
            ],
            motion: Records(files: ["{EL_CENTRO}"], pga: ["300gal", "400gal", "600gal"]),
            friction: Random(distribution: Lognormal, cov: 0.1, samples: 300, seed: 1))"#
    );
    let s = sweep(&text).unwrap();
    for id in [1501, 1509, 1547] {
        let (row, _) = s.run_case(id);
        assert!(row.error.is_none(), "{:?}", row.error);
        assert!(
            row.energy_residual_j.abs() <= 1e-9 * row.energy_input_j,
            "case {id}: residual {:e} J of {:e} J",
            row.energy_residual_j,
            row.energy_input_j
        );
    }
}

#[test]
fn a_case_reruns_exactly_from_its_written_wall() {
    let s = sweep(SMALL).unwrap();
    let id = 31;
    let (row, _) = s.run_case(id);
    let d = s.case_wall(id);
    let wall = pirqa::Wall::from_description(&d).unwrap();
    let topo = pirqa::Topology::new(&wall).unwrap();
    let (_, m, _) = s.case(id);
    let settings = pirqa::integrate::Settings::summary_only(s.motions[m].duration_s);
    use pirqa::integrate::Integrator;
    let r = pirqa::integrate::event::EventDriven::default()
        .run(&pirqa::integrate::Scenario {
            wall: &wall,
            topology: &topo,
            motion: &s.motions[m].motion,
            settings: &settings,
        })
        .unwrap();
    let max = r
        .summary
        .blocks
        .iter()
        .map(|b| b.max_abs_displacement_m)
        .fold(0.0, f64::max);
    assert_eq!(max, row.max_abs_u_m);
    assert_eq!(r.summary.stats.events, row.events);
}

#[test]
fn the_analysis_reports_collapse_probabilities_and_a_fragility_fit() {
    let text = format!(
        r#"(version: 1, name: "fragility",
            walls: [File(path: "walls/five-block-variable.ron")],
            motion: Records(files: ["{EL_CENTRO}"], pga: ["1000gal", "2000gal", "3000gal"]),
            friction: Random(distribution: Lognormal, cov: 0.2, samples: 60, seed: 7))"#
    );
    let s = sweep(&text).unwrap();
    let rows = run_all(&s, &temp_dir("fragility"), Existing::Refuse);
    let report = pirqa::study::sweep::analysis::analyse(&s, &rows);
    let stems: Vec<&str> = report.figures.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(stems, ["ida", "distribution", "fragility"]);
    let levels = report.results["levels"].as_array().unwrap();
    assert_eq!(levels.len(), 3);
    for l in levels {
        let (n, k) = (
            l["samples"].as_u64().unwrap(),
            l["collapses"].as_u64().unwrap(),
        );
        let expected = rows
            .iter()
            .filter(|r| r.motion == l["motion"].as_str().unwrap() && r.collapsed)
            .count() as u64;
        assert_eq!((n, k), (60, expected));
        let ci = l["p_collapse_ci95"].as_array().unwrap();
        let p = l["p_collapse"].as_f64().unwrap();
        assert!(ci[0].as_f64().unwrap() <= p && p <= ci[1].as_f64().unwrap());
    }
    assert_eq!(report.results["failed_runs"], 0);
    let fit = &report.results["fragility"][0];
    assert!(fit["median_pga_gal"].as_f64().is_some(), "{fit}");
}

/// A record sweep whose cases turn blocks draws, beside a wall's displacement against PGA, its
/// largest rotation against PGA, point for point the cases' own; a wall that only slid gets
/// the displacement alone.
#[test]
fn an_incremental_analysis_draws_the_rotation_of_walls_that_rock() {
    let text = format!(
        r#"(version: 1, name: "ida",
            walls: [File(path: "walls/rocking/slender-on-stack.ron"), File(path: "walls/five-block-uniform.ron")],
            motion: Records(files: ["{EL_CENTRO}"], pga: ["0.1g", "0.3g", "0.4g"]))"#
    );
    let s = sweep(&text).unwrap();
    let rows: Vec<CaseRow> = (0..s.len()).map(|id| s.run_case(id).0).collect();
    let report = pirqa::study::sweep::analysis::analyse(&s, &rows);
    let (_, charts, _) = &report.figures[0];
    let titles: Vec<&str> = charts.iter().map(|c| c.title.as_str()).collect();
    assert_eq!(
        titles,
        [
            "slender-on-stack: incremental dynamic analysis",
            "slender-on-stack: rotation",
            "five-block-uniform: incremental dynamic analysis"
        ]
    );
    let stack: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.wall == rows[0].wall)
        .map(|r| (r.pga_gal, r.max_abs_rotation_rad))
        .collect();
    assert_eq!(charts[1].series[0].points, stack);
    assert!(
        stack[0].1 == 0.0 && stack[2].1 > stack[1].1 && stack[1].1 > 0.0,
        "{stack:?}"
    );
}

/// The block-count study's sweep (`walls/studies/block-count.ron`) over the paper's wall cut
/// into n x n running-bond blocks for each n of `cuts`, with `samples` friction samples.
fn running_bond_sweep(cuts: &[usize], samples: usize) -> Sweep {
    let walls: Vec<String> = cuts
        .iter()
        .map(|n| {
            format!(
                "RunningBond(courses: {n}, blocks_per_course: {n}, width_m: 2.4, height_m: 1.2, \
                 thickness_m: 0.8, density_kg_m3: 2650, friction: 0.3)"
            )
        })
        .collect();
    let text = format!(
        r#"(version: 1, name: "blocks", walls: [{}],
            motion: Records(files: ["{EL_CENTRO}"], pga: ["400gal"]),
            friction: Random(distribution: Lognormal, cov: 0.1, samples: {samples}, seed: 5))"#,
        walls.join(", ")
    );
    sweep(&text).unwrap()
}

/// Walls cut into three block counts get the block-count figure; its numbers are the medians
/// of the rows, in block-count order; one intensity gets no IDA or fragility chart.
#[test]
fn walls_in_several_block_counts_get_the_block_count_analysis() {
    let s = running_bond_sweep(&[4, 2, 3], 3);
    let rows = run_all(&s, &temp_dir("block-count"), Existing::Refuse);
    let report = pirqa::study::sweep::analysis::analyse(&s, &rows);
    let stems: Vec<&str> = report.figures.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(stems, ["distribution", "block-count"]);
    let bc = &report.results["block_count"][0];
    let walls = bc["walls"].as_array().unwrap();
    let counts: Vec<u64> = walls
        .iter()
        .map(|w| w["blocks"].as_u64().unwrap())
        .collect();
    assert_eq!(counts, [5, 10, 18]);
    for w in walls {
        let mut events: Vec<f64> = rows
            .iter()
            .filter(|r| r.blocks as u64 == w["blocks"].as_u64().unwrap())
            .map(|r| r.events as f64)
            .collect();
        events.sort_by(f64::total_cmp);
        assert_eq!(w["events_p50"].as_f64().unwrap(), events[1]);
        assert_eq!(w["samples"], 3);
    }
    assert!(bc["events_exponent"].as_f64().unwrap().is_finite());
    // The CPU panel's line of events times courses (2, 3 and 4 courses): the smallest wall's
    // median CPU time scaled by the medians of events times courses.
    let median = |blocks: usize, f: &dyn Fn(&pirqa::study::sweep::store::CaseRow) -> f64| {
        let mut v: Vec<f64> = rows.iter().filter(|r| r.blocks == blocks).map(f).collect();
        v.sort_by(f64::total_cmp);
        v[1]
    };
    let work: Vec<(f64, f64)> = [(5, 2.0), (10, 3.0), (18, 4.0)]
        .iter()
        .map(|&(b, courses)| (b as f64, median(b, &|r| r.events as f64) * courses))
        .collect();
    let cpu0 = median(5, &|r| r.cpu_s);
    let cpu_panel = report.figures[1]
        .1
        .iter()
        .find(|c| c.title == "CPU time per case")
        .unwrap();
    let line = cpu_panel
        .series
        .iter()
        .find(|s| s.label == "if it grew as the events x the courses")
        .unwrap();
    let want: Vec<(f64, f64)> = work
        .iter()
        .map(|&(x, w)| (x, cpu0 * w / work[0].1))
        .collect();
    assert_eq!(line.points, want);
    assert!(bc["cpu_exponent_in_events_x_courses"]
        .as_f64()
        .unwrap()
        .is_finite());
}

/// An impact can knock blocks of a large sliding body into different pieces of the next decision
/// (the block-count study's case 17, 105 blocks, which stopped the whole study with a panic
/// when only whole bodies were expected). Decided, it keeps its energy balance.
#[test]
fn a_sliding_body_split_by_an_impact_is_decided() {
    let s = running_bond_sweep(&[2, 4, 10], 8);
    assert_eq!(s.case(17), (2, 0, 1));
    let (row, _) = s.run_case(17);
    assert_eq!(row.error, None);
    assert_eq!(row.blocks, 105);
    assert!(row.impacts > 0);
    assert!(row.energy_residual_j.abs() <= 1e-9 * row.energy_input_j);
}

/// Every shipped study loads (its walls, records and friction model) with the number of cases
/// its comment promises.
#[test]
fn every_shipped_study_loads() {
    let expected = [
        ("block-count-rocking.ron", 3 * 8),
        ("block-count.ron", 5 * 8),
        ("columns-fragility-sliding.ron", 3 * 6 * 20),
        ("columns-fragility.ron", 3 * 6 * 20),
        ("elcentro-ida.ron", 3 * 11),
        ("fragility-moreau.ron", 6 * 200),
        ("fragility.ron", 6 * 200),
        ("friction-mc.ron", 1000),
        ("long-walls.ron", 5 * 8),
        ("ollantaytambo-handed.ron", 6),
        ("ollantaytambo-rocking.ron", 6),
        ("ollantaytambo-sliding.ron", 6),
        ("ollantaytambo-uplift.ron", 9 * 50),
        ("ollantaytambo-while-rocking.ron", 6),
        ("paper-fig3-4.ron", 3 * 4 * 100),
        ("slab-rocking.ron", 10),
        ("slab-while-rocking.ron", 10),
        ("trilith-fragility.ron", 11 * 20),
        ("trilith-moreau.ron", 11),
        ("trilith.ron", 11),
    ];
    let mut found: Vec<String> = std::fs::read_dir("walls/studies")
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    found.sort();
    let names: Vec<&str> = expected.iter().map(|(n, _)| *n).collect();
    assert_eq!(found, names, "a study was added or removed: list it here");
    for (name, cases) in expected {
        let s = Sweep::load(&Path::new("walls/studies").join(name))
            .unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(s.len(), cases, "{name}");
    }
}

/// A sweep's fingerprint sees the names and contents of the files it reads, not their folders:
/// the same sweep file, wall and record copied elsewhere resume the same results; a record with
/// one number changed does not.
#[test]
fn a_sweep_moved_with_its_files_keeps_its_fingerprint() {
    let text = |wall: &str, record: &str| {
        format!(
            r#"(version: 1, name: "moved", walls: [File(path: "{wall}")],
                motion: Records(files: ["{record}"], pga: ["400gal"]))"#
        )
    };
    let here = sweep(&text("walls/five-block-variable.ron", EL_CENTRO)).unwrap();
    let dir = temp_dir("moved");
    std::fs::create_dir_all(dir.join("data")).unwrap();
    std::fs::copy(
        "walls/five-block-variable.ron",
        dir.join("data/five-block-variable.ron"),
    )
    .unwrap();
    let record = std::fs::read_to_string(EL_CENTRO).unwrap();
    let copied = dir.join("data/elcentro1940_IELC180_peer_dt0p01_g.AT2");
    std::fs::write(&copied, &record).unwrap();
    let file = dir.join("moved.ron");
    std::fs::write(
        &file,
        text(
            "data/five-block-variable.ron",
            "data/elcentro1940_IELC180_peer_dt0p01_g.AT2",
        ),
    )
    .unwrap();
    assert_eq!(Sweep::load(&file).unwrap().fingerprint, here.fingerprint);
    std::fs::write(&copied, record.replacen(".6403182E-02", ".6403183E-02", 1)).unwrap();
    assert_ne!(Sweep::load(&file).unwrap().fingerprint, here.fingerprint);
}

/// A sweep runs the model `pirqa run` would (`model`, default Auto): a slender block on a stack
/// (it lifts at 0.25 g) rocks where the motion can lift it and slides where it cannot, a
/// two-block column (0.167 g) rocks at all three levels, the five-block wall slides, and each case's row says which model ran and how far its blocks turned; with
/// `model: Slide` every case slides; the rerun command names the model a case ran; a case that
/// the model stopped early (a held joint gave way) is reported as failed with the reason.
/// Every number of a rocked case is `pirqa run`'s.
#[test]
fn a_sweep_rocks_the_cases_pirqa_run_would() {
    let text = |model: &str| {
        format!(
            r#"(
    version: 1,
    name: "columns",
    walls: [File(path: "walls/rocking/slender-on-stack.ron"), File(path: "walls/five-block-uniform.ron"),
            File(path: "walls/rocking/two-block-column.ron")],
    motion: Sine(amplitudes: ["0.2g", "0.3g", "0.5g"], frequencies_hz: List([1.5]), duration_s: 6.0),
    {model}
)"#
        )
    };
    let auto = sweep(&text("")).unwrap();
    let (rows, blocks): (Vec<CaseRow>, Vec<_>) =
        (0..auto.len()).map(|id| auto.run_case(id)).unzip();
    let models: Vec<&str> = rows.iter().map(|r| r.model.as_str()).collect();
    assert_eq!(
        models,
        [
            "slide",
            "slide-rock",
            "slide-rock",
            "slide",
            "slide",
            "slide",
            "slide-rock",
            "slide-rock",
            "slide-rock"
        ]
    );
    for (id, r) in rows.iter().enumerate() {
        assert_eq!(auto.case_model(id).unwrap(), r.model, "case {id}");
        assert_eq!(
            r.max_abs_rotation_rad > 0.0,
            r.model == "slide-rock",
            "{r:?}"
        );
    }
    // The stack's top overturns at 0.3 g, as `pirqa run` has it.
    let model = pirqa::Model::from_file("walls/rocking/slender-on-stack.ron").unwrap();
    let run = pirqa::run(
        &model,
        &auto.motions[1].motion,
        &pirqa::RunSettings::default(),
    )
    .unwrap()
    .summary;
    assert_eq!(rows[1].collapse_time_s, run.collapse.map(|c| c.time_s));
    assert_eq!(rows[1].collapse_block.as_deref(), Some("Top"));
    // The two-block column's inner joint opens at 0.5 g: the upper drum rocks on the lower
    // one (the chain of open joints) to the end of the motion, as `pirqa run` has it.
    assert!(rows.iter().all(|r| r.error.is_none()), "{rows:?}");
    let model = pirqa::Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let run = pirqa::run(
        &model,
        &auto.motions[2].motion,
        &pirqa::RunSettings::default(),
    )
    .unwrap()
    .summary;
    assert_eq!(run.duration_s, 6.0);
    let turned = run.blocks.iter().map(|b| b.max_abs_rotation_rad);
    assert_eq!(rows[8].max_abs_rotation_rad, turned.fold(0.0, f64::max));
    // blocks.csv's rows carry each block's own rotation.
    let each = |rows: &[pirqa::study::sweep::store::BlockRow]| -> Vec<(String, f64)> {
        rows.iter()
            .map(|b| (b.block.clone(), b.max_abs_rotation_rad))
            .collect()
    };
    let ran: Vec<(String, f64)> = run
        .blocks
        .iter()
        .map(|b| (b.name.clone(), b.max_abs_rotation_rad))
        .collect();
    assert_eq!(each(&blocks[8]), ran);
    assert!(ran.iter().all(|b| b.1 > 0.0), "{ran:?}");
    // On the stack only the top block turns.
    let stack = each(&blocks[1]);
    assert!(
        stack[0].1 == 0.0 && stack[1].1 == 0.0 && stack[2].1 > 0.0,
        "{stack:?}"
    );
    assert!(each(&blocks[3]).iter().all(|b| b.1 == 0.0));
    assert!(run.blocks[1].max_abs_displacement_m > 10.0 * run.blocks[0].max_abs_displacement_m);

    let slide = sweep(&text("model: Slide,")).unwrap();
    assert_ne!(slide.fingerprint, auto.fingerprint);
    for id in 0..slide.len() {
        let (r, _) = slide.run_case(id);
        assert_eq!((r.model.as_str(), r.max_abs_rotation_rad), ("slide", 0.0));
        assert!(!r.collapsed && r.error.is_none(), "{r:?}");
    }
}

/// A case the exact model stops before its end fails with the reason, unless the sweep names a
/// fallback: then Moreau-Jean time stepping answers it, whole, and its row says so (its model,
/// no error) with the numbers `pirqa run --model slide-rock --method moreau --dt` gives; a
/// case the exact model finishes keeps the exact answer. A fallback's step must be positive,
/// and it goes with the exact integrator and a model that can rock only.
#[test]
fn a_case_beyond_the_exact_model_is_answered_by_the_fallback_the_sweep_names() {
    let text = |extra: &str| {
        format!(
            r#"(
    version: 1,
    name: "fallback",
    walls: [File(path: "walls/rocking/two-block-column.ron")],
    motion: Records(files: ["records/elcentro1940_IELC180_peer_dt0p01_g.AT2"], pga: ["0.2g", "0.5g"]),
    {extra}
)"#
        )
    };
    let plain = sweep(&text("")).unwrap();
    let with = sweep(&text("fallback: Moreau(dt_s: 0.0005),")).unwrap();
    assert_ne!(plain.fingerprint, with.fingerprint);
    let (low, high) = (plain.run_case(0).0, plain.run_case(1).0);
    assert!(low.error.is_none() && low.model == "slide-rock", "{low:?}");
    // At 0.5 g the column leans past 0.9 rad, its joint opens and the upper drum would lift
    // off the lower one's corner: beyond the exact model.
    assert!(
        high.error
            .as_deref()
            .is_some_and(|e| e.contains("stops there")),
        "{high:?}"
    );
    let (low_again, answered) = (with.run_case(0).0, with.run_case(1).0);
    assert_eq!(
        (
            low_again.model.as_str(),
            low_again.max_abs_u_m,
            low_again.max_abs_rotation_rad
        ),
        ("slide-rock", low.max_abs_u_m, low.max_abs_rotation_rad)
    );
    assert_eq!(answered.model, pirqa::study::sweep::FALLBACK_MODEL);
    assert!(
        answered.error.is_none() && answered.collapsed,
        "{answered:?}"
    );
    let model = pirqa::Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let settings = pirqa::RunSettings {
        model: pirqa::ModelChoice::SlideRock,
        method: pirqa::Method::Moreau { dt_s: 0.0005 },
        ..pirqa::RunSettings::default()
    };
    let run = pirqa::run(&model, &with.motions[1].motion, &settings)
        .unwrap()
        .summary;
    assert_eq!(answered.collapse_time_s, run.collapse.map(|c| c.time_s));
    let turned = run.blocks.iter().map(|b| b.max_abs_rotation_rad);
    assert_eq!(answered.max_abs_rotation_rad, turned.fold(0.0, f64::max));

    for (extra, says) in [
        ("fallback: Moreau(dt_s: 0.0),", "positive step"),
        (
            "method: Moreau(dt_s: 0.001), fallback: Moreau(dt_s: 0.001),",
            "leave fallback out",
        ),
        (
            "model: Slide, fallback: Moreau(dt_s: 0.001),",
            "model Slide rocks none",
        ),
    ] {
        let e = sweep(&text(extra)).unwrap_err().to_string();
        assert!(e.contains("fallback") && e.contains(says), "{extra}: {e}");
    }
    // The whole-wall Newton solver goes with runs that step rotations: the fallback's, or the
    // method's with model SlideRock.
    let newton = sweep(&text(
        "fallback: Moreau(dt_s: 0.0005), contact_solver: Newton,",
    ))
    .unwrap();
    assert_ne!(newton.fingerprint, with.fingerprint);
    let answered_newton = newton.run_case(1).0;
    assert_eq!(answered_newton.model, pirqa::study::sweep::FALLBACK_MODEL);
    let settings = pirqa::RunSettings {
        contact_solver: pirqa::ContactSolver::Newton,
        ..settings
    };
    let run = pirqa::run(&model, &with.motions[1].motion, &settings)
        .unwrap()
        .summary;
    assert_eq!(run.model.equations.as_deref(), Some("moreau-jean-newton"));
    assert_eq!(
        answered_newton.collapse_time_s,
        run.collapse.map(|c| c.time_s)
    );
    for extra in [
        "contact_solver: Newton,",
        "method: Moreau(dt_s: 0.001), contact_solver: Newton,",
    ] {
        let e = sweep(&text(extra)).unwrap_err().to_string();
        assert!(
            e.contains("contact_solver") && e.contains("leave contact_solver out"),
            "{extra}: {e}"
        );
    }
}

/// `fallback: MoreauFromStop(dt_s)`: a case the exact model stops before its end goes on from
/// the state there with Moreau-Jean time stepping of every block with its rotation, and its row
/// is that of `pirqa run --after-stop moreau --dt`, its model saying so, its rerun options
/// those; a case the exact model finishes keeps the exact answer and the exact row. The same
/// checks as the whole-case fallback's refuse a step that is not positive, a time-stepping
/// method, and a model that rocks nothing.
#[test]
fn a_case_the_exact_model_stops_goes_on_from_there_with_the_fallback_from_stop() {
    let text = |extra: &str| {
        format!(
            r#"(
    version: 1,
    name: "from stop",
    walls: [File(path: "walls/rocking/two-block-column.ron")],
    motion: Records(files: ["records/elcentro1940_IELC180_peer_dt0p01_g.AT2"], pga: ["0.2g", "0.5g"]),
    {extra}
)"#
        )
    };
    let plain = sweep(&text("")).unwrap();
    let from = sweep(&text("fallback: MoreauFromStop(dt_s: 0.0005),")).unwrap();
    assert_ne!(plain.fingerprint, from.fingerprint);
    let (low, low_again) = (plain.run_case(0).0, from.run_case(0).0);
    assert_eq!(
        (
            low_again.model.as_str(),
            low_again.max_abs_u_m,
            low_again.max_abs_rotation_rad
        ),
        ("slide-rock", low.max_abs_u_m, low.max_abs_rotation_rad)
    );
    let answered = from.run_case(1).0;
    assert_eq!(answered.model, pirqa::study::sweep::FROM_STOP_MODEL);
    assert!(
        answered.error.is_none() && answered.collapsed,
        "{answered:?}"
    );
    let model = pirqa::Model::from_file("walls/rocking/two-block-column.ron").unwrap();
    let settings = pirqa::RunSettings {
        after_stop: pirqa::AfterStop::Moreau { dt_s: 0.0005 },
        ..pirqa::RunSettings::default()
    };
    let run = pirqa::run(&model, &from.motions[1].motion, &settings)
        .unwrap()
        .summary;
    assert_eq!(run.method, "event+moreau");
    assert_eq!(answered.collapse_time_s, run.collapse.map(|c| c.time_s));
    let turned = run.blocks.iter().map(|b| b.max_abs_rotation_rad);
    assert_eq!(answered.max_abs_rotation_rad, turned.fold(0.0, f64::max));
    assert_eq!(
        from.case_options(1).unwrap(),
        "--model slide-rock --after-stop moreau --dt 0.0005"
    );
    for (extra, says) in [
        ("fallback: MoreauFromStop(dt_s: -1.0),", "positive step"),
        (
            "method: Moreau(dt_s: 0.001), fallback: MoreauFromStop(dt_s: 0.001),",
            "leave fallback out",
        ),
        (
            "model: Slide, fallback: MoreauFromStop(dt_s: 0.001),",
            "model Slide rocks none",
        ),
    ] {
        let e = sweep(&text(extra)).unwrap_err().to_string();
        assert!(e.contains("fallback") && e.contains(says), "{extra}: {e}");
    }
}

/// `max_accel_over_tipping` is the largest peak absolute acceleration of a block over the one
/// at which it would tip standing free, g b/h: the stack of walls/rocking/ held to the ground
/// moves with it, so the slender top (b/h = 0.25) reaches a_g, and the ratio is the sine's
/// amplitude over 0.25 g to round-off (0.4 and 0.8); at 0.3 g the top lifts and rocks, and the
/// column is left empty (the check is asked of sliding answers only).
#[test]
fn the_tipping_ratio_of_a_case_is_its_peak_acceleration_over_g_b_over_h() {
    let s = sweep(
        r#"(
    version: 1,
    name: "tipping",
    walls: [File(path: "walls/rocking/slender-on-stack.ron")],
    motion: Sine(amplitudes: ["0.1g", "0.2g", "0.3g"], frequencies_hz: List([1.5]), duration_s: 2.0),
)"#,
    )
    .unwrap();
    let rows: Vec<CaseRow> = (0..s.len()).map(|id| s.run_case(id).0).collect();
    for (r, ratio) in rows.iter().zip([0.4, 0.8]) {
        assert_eq!(r.model, "slide");
        assert!(
            (r.max_accel_over_tipping.unwrap() - ratio).abs() < 1e-15,
            "{:?} against {ratio}",
            r.max_accel_over_tipping
        );
    }
    assert_eq!(rows[2].model, "slide-rock");
    assert_eq!(
        rows[2].max_accel_over_tipping, None,
        "a rocking answer needs no check"
    );
}

/// A case that rocks under `auto` needs the exact rocking model or Moreau-Jean: asked for the
/// paper's Newmark scheme, it fails, and its error says what to change in the sweep's own terms.
#[test]
fn a_rocking_case_on_a_sliding_stepper_fails_with_the_sweeps_own_words() {
    let s = sweep(
        r#"(
    version: 1,
    name: "paper's scheme",
    walls: [File(path: "walls/rocking/slender-on-stack.ron")],
    motion: Sine(amplitudes: ["0.3g"], frequencies_hz: List([1.5]), duration_s: 2.0),
    method: Paper(dt_s: 0.001),
)"#,
    )
    .unwrap();
    let row = s.run_case(0).0;
    let error = row.error.unwrap_or_default();
    assert!(
        error.contains("`method`") && error.contains("`model: Slide`"),
        "{error}"
    );
}

/// The first uplift of `wall` sliding under a 1 Hz sine of `amplitude_m_s2` for `duration_s`,
/// as `pirqa run --model slide --check-uplift` finds it: what a sweep's case must say.
fn checked_first_uplift(
    wall: &str,
    amplitude_m_s2: f64,
    duration_s: f64,
) -> pirqa::response::Uplift {
    let run = pirqa::run(
        &pirqa::Model::from_file(wall).unwrap(),
        &pirqa::Motion::sine(pirqa::Sine {
            amplitude_m_s2,
            frequency_hz: 1.0,
            duration_s,
            ..pirqa::Sine::default()
        })
        .unwrap(),
        &pirqa::RunSettings {
            model: pirqa::ModelChoice::Slide,
            check_uplift: true,
            ..pirqa::RunSettings::default()
        },
    )
    .unwrap();
    run.summary.uplift_check.unwrap().first_uplift.unwrap()
}

/// `check_uplift: true` watches every case that slides, as `pirqa run --check-uplift` does: on
/// the dragged block of walls/rocking/ (model Slide, a 0.7 g sine) the first uplift is where
/// L's balance of moments fails, a_g = 153/320 g after U started to slide (the closed form of
/// `tests/suite/uplift_check.rs`, to 1e-13 s), and the case's rerun command asks for the
/// check; at 0.3 g nothing lifts and the case is checked to its end.
#[test]
fn a_sweep_asked_to_check_uplift_gives_each_cases_first_uplift() {
    let s = sweep(
        r#"(
    version: 1,
    name: "uplift",
    walls: [File(path: "walls/rocking/dragged-block.ron")],
    motion: Sine(amplitudes: ["2.943m/s2", "6.867m/s2"], frequencies_hz: List([1.0]), duration_s: 2.0),
    model: Slide,
    check_uplift: true,
)"#,
    )
    .unwrap();
    let rows: Vec<CaseRow> = (0..s.len()).map(|id| s.run_case(id).0).collect();
    assert_eq!(rows[0].uplift_checked_until_s, Some(2.0));
    assert_eq!(
        (&rows[0].uplift_time_s, &rows[0].uplift_turning),
        (&None, &None)
    );
    let expected = (153.0f64 / 320.0 / 0.7).asin() / (2.0 * std::f64::consts::PI);
    let t = rows[1].uplift_time_s.expect("an uplift");
    assert!((t - expected).abs() <= 1e-13, "{t} against {expected}");
    assert_eq!(rows[1].uplift_checked_until_s, Some(t));
    // The run `rerun.txt` names says the same, to the bit.
    let first = checked_first_uplift("walls/rocking/dragged-block.ron", 6.867, 2.0);
    assert_eq!(first.time_s, t);
    assert!(first.turning[0].starts_with("L turns counterclockwise about its bottom-left"));
    assert_eq!(rows[1].uplift_turning, Some(first.turning.join("; ")));
    // The dragged block's first uplift starts by the only mechanism that holds then.
    assert_eq!(first.mechanism_uniqueness, Uniqueness::Unique);
    assert_eq!(
        (
            rows[0].uplift_mechanism_uniqueness,
            rows[1].uplift_mechanism_uniqueness
        ),
        (None, Some(Uniqueness::Unique))
    );
    // Its own turning blocks, then: L, and U turning with it as it slides on it.
    assert_eq!(rows[1].uplift_turning_in_every.as_deref(), Some("L; U"));
    for id in 0..2 {
        assert!(s.case_options(id).unwrap().ends_with("--check-uplift"));
    }
    // results.json counts them per wall and motion.
    let results = pirqa::study::sweep::analysis::analyse(&s, &rows).results;
    let found: Vec<(u64, u64, Option<f64>, [u64; 3])> = results["uplift"]
        .as_array()
        .unwrap()
        .iter()
        .map(|u| {
            let n = |k: &str| u[k].as_u64().unwrap();
            let by = [
                "lifted_by_unique_mechanism",
                "lifted_by_one_of_several",
                "lifted_undecided",
            ]
            .map(n);
            (n("checked"), n("lifted"), u["first_uplift_s"].as_f64(), by)
        })
        .collect();
    assert_eq!(found, [(1, 0, None, [0, 0, 0]), (1, 1, Some(t), [1, 0, 0])]);
    // The check watches the sliding engine: a case that rocks under Auto is left unchecked,
    // and a sweep no case of which slides exactly is refused, naming the field.
    let stack = |extra: &str| {
        sweep(&format!(
            r#"(version: 1, name: "uplift, auto", walls: [File(path: "walls/rocking/slender-on-stack.ron")],
    motion: Sine(amplitudes: ["0.2g", "0.3g"], frequencies_hz: List([1.5]), duration_s: 2.0){extra})"#
        ))
        .unwrap()
    };
    let auto = stack(", check_uplift: true");
    let (slid, rocked) = (auto.run_case(0).0, auto.run_case(1).0);
    assert_eq!(
        (slid.model.as_str(), slid.uplift_checked_until_s),
        ("slide", Some(2.0))
    );
    assert_eq!(
        (rocked.model.as_str(), rocked.uplift_checked_until_s),
        ("slide-rock", None)
    );
    assert!(!auto.case_options(1).unwrap().contains("--check-uplift"));
    // Left out or false, the sweep is the one it was before the field existed (its folders
    // resume); asked for, another.
    let unchecked = stack("");
    assert_eq!(
        unchecked.fingerprint,
        stack(", check_uplift: false").fingerprint
    );
    assert_ne!(unchecked.fingerprint, auto.fingerprint);
    for (model, method) in [("Slide", "Moreau(dt_s: 0.001)"), ("SlideRock", "Event")] {
        let e = sweep(&format!(
            r#"(version: 1, name: "x", walls: [File(path: "walls/rocking/dragged-block.ron")],
    motion: Sine(amplitudes: ["0.3g"], frequencies_hz: List([1.0]), duration_s: 1.0),
    model: {model}, method: {method}, check_uplift: true)"#
        ))
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("check_uplift") && e.contains("set method to Event"),
            "{e}"
        );
    }
}

/// `after_uplift: Moreau(dt_s: ...)` hands each case that slides to Moreau-Jean with rotations
/// at its first uplift, as `pirqa run --after-uplift moreau` does: on the Ollantaytambo wall
/// under a 1 Hz sine, at 0.2 g nothing lifts (the wall's limit at rest is 0.28 g) and the case
/// keeps its exact sliding answer; at 0.3 g it lifts where the checked sliding run says, to the
/// bit, and its blocks turn from there; both cases rerun with the hand-off's options. Asked of
/// a sweep whose cases do not run the exact sliding engine, it is refused.
#[test]
fn a_sweep_asked_to_hand_off_at_the_first_uplift_does_so_case_by_case() {
    let text = |method: &str| {
        format!(
            r#"(
    version: 1,
    name: "hand-off",
    walls: [File(path: "walls/inca/ollantaytambo-monoliths.ron")],
    motion: Sine(amplitudes: ["0.2g", "0.3g"], frequencies_hz: List([1.0]), duration_s: 0.5),
    {method}
    after_uplift: Moreau(dt_s: 0.001),
)"#
        )
    };
    let s = sweep(&text("")).unwrap();
    let rows: Vec<CaseRow> = (0..s.len()).map(|id| s.run_case(id).0).collect();
    assert_eq!(rows[0].model, "slide");
    assert_eq!(rows[0].uplift_time_s, None);
    assert_eq!(rows[0].max_abs_rotation_rad, 0.0);
    assert_eq!(rows[1].model, pirqa::study::sweep::AFTER_UPLIFT_MODEL);
    assert!(rows[1].max_abs_rotation_rad > 0.0);
    let first = checked_first_uplift("walls/inca/ollantaytambo-monoliths.ron", 0.3 * 9.81, 0.5);
    assert_eq!(rows[1].uplift_time_s, Some(first.time_s));
    assert_eq!(rows[1].error, None);
    for id in 0..2 {
        assert_eq!(
            s.case_options(id).unwrap(),
            "--after-uplift moreau --dt 0.001"
        );
    }
    let refused = sweep(&text("method: Moreau(dt_s: 0.001),")).unwrap_err();
    assert!(format!("{refused}").contains("after_uplift"), "{refused}");
}

/// `after_uplift: MoreauWhileRocking(dt_s: ...)`: each case that slides is time stepped from
/// its first uplift while its blocks rock, as `pirqa run --after-uplift moreau-while-rocking`
/// does: the case that lifts is named for it, lifts where the checked sliding run says, and
/// reruns with its option; the sweep is another than the one that steps to the end.
#[test]
fn a_sweep_asked_to_step_only_while_blocks_rock_does_so_case_by_case() {
    let text = |after: &str| {
        format!(
            r#"(
    version: 1,
    name: "while-rocking",
    walls: [File(path: "walls/rocking/slab-beside-block.ron")],
    motion: Sine(amplitudes: ["0.2g", "0.3g"], frequencies_hz: List([1.0]), duration_s: 3.0),
    after_uplift: {after}(dt_s: 0.001),
)"#
        )
    };
    let s = sweep(&text("MoreauWhileRocking")).unwrap();
    let rows: Vec<CaseRow> = (0..s.len()).map(|id| s.run_case(id).0).collect();
    assert_eq!(rows[0].model, "slide");
    assert_eq!(rows[0].max_abs_rotation_rad, 0.0);
    assert_eq!(rows[1].model, pirqa::study::sweep::WHILE_ROCKING_MODEL);
    assert!(rows[1].max_abs_rotation_rad > 0.01);
    let first = checked_first_uplift("walls/rocking/slab-beside-block.ron", 0.3 * 9.81, 3.0);
    assert_eq!(rows[1].uplift_time_s, Some(first.time_s));
    assert_eq!(rows[1].error, None);
    assert_eq!(
        s.case_options(1).unwrap(),
        "--after-uplift moreau-while-rocking --dt 0.001"
    );
    assert_ne!(s.fingerprint, sweep(&text("Moreau")).unwrap().fingerprint);
}
