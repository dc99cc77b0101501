//! A sweep from its RON file, run in parallel and reduced to the numbers of its charts: the
//! paper's Fig. 3 and 4 grid (two walls, 20 amplitudes, 20 frequencies, 800 runs):
//! `cargo run --release --example sweep`.

use pirqa::study::sweep::analysis::analyse;
use pirqa::study::sweep::Sweep;

fn main() -> Result<(), pirqa::Error> {
    let sweep = Sweep::load(std::path::Path::new("walls/studies/paper-fig3-4.ron"))?;
    let mut rows = Vec::new();
    // Every case (none done yet); each row arrives as its case finishes.
    sweep.run_cases(&Default::default(), |row, _blocks| {
        rows.push(row);
        Ok(())
    })?;
    rows.sort_by_key(|r| r.case);
    let worst = rows
        .iter()
        .max_by(|a, b| a.max_abs_u_m.total_cmp(&b.max_abs_u_m))
        .expect("cases ran");
    println!(
        "{}: {} cases; largest max |u| {:.4} m ({}, {})",
        sweep.name,
        rows.len(),
        worst.max_abs_u_m,
        worst.wall,
        worst.motion
    );
    let report = analyse(&sweep, &rows);
    println!(
        "{}",
        serde_json::to_string_pretty(&report.results).expect("json")
    );
    Ok(())
}

/// `cargo test` runs the example (Cargo.toml: `test = true`).
#[test]
fn runs() {
    main().unwrap();
}
