//! The paper's five-block wall with variable friction under a 400 gal, 1 Hz sine for 20 s, with
//! the exact event-driven integrator: `cargo run --release --example paper_wall`.

use pirqa::{Model, Motion, RunSettings, Sine};

fn main() -> Result<(), pirqa::Error> {
    let model = Model::from_file("walls/five-block-variable.ron")?;
    let sine = Sine {
        amplitude_m_s2: 4.0,
        frequency_hz: 1.0,
        duration_s: 20.0,
        ..Sine::default()
    };
    let result = pirqa::run(&model, &Motion::sine(sine)?, &RunSettings::default())?;
    let summary = &result.summary;
    println!(
        "{} ({}, {})",
        summary.wall, summary.model.name, summary.model.why
    );
    for block in &summary.blocks {
        println!(
            "  {}: max |u| {:.6} m, final u {:.6} m",
            block.name, block.max_abs_displacement_m, block.final_displacement_m
        );
    }
    println!(
        "  {} impacts, energy residual {:.1e} J",
        summary.impacts, summary.energy.residual_j
    );
    Ok(())
}

/// `cargo test` runs the example (Cargo.toml: `test = true`).
#[test]
fn runs() {
    main().unwrap();
}
