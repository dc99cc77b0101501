//! A record read from a file, scaled, and a free-standing stone under it: El Centro 1940 at
//! 0.4 g on the Inca standing stone of walls/inca/stela.ron, which the default model (auto)
//! computes rocking: `cargo run --release --example record`.

use pirqa::motion::{read_record, ReadOptions};
use pirqa::{Model, Motion, RunSettings};

fn main() -> Result<(), pirqa::Error> {
    let path = std::path::Path::new("records/elcentro1940_IELC180_peer_dt0p01_g.AT2");
    // Format, units, interval and point count come from the file's header.
    let record = read_record(path, None, &ReadOptions::default())?;
    let scaled = record.scaled(0.4 * 9.81 / record.pga_m_s2())?;
    let model = Model::from_file("walls/inca/stela.ron")?;
    let settings = RunSettings {
        log_events: true,
        ..RunSettings::default()
    };
    let result = pirqa::run(&model, &Motion::Record(scaled), &settings)?;
    let block = &result.summary.blocks[0];
    println!(
        "{}: {}",
        result.summary.model.name, result.summary.model.why
    );
    println!(
        "{} lifted at {:?} s, rocked to {:.4} rad, landed {} times; fell: {}",
        block.name,
        block.uplift_time_s,
        block.max_abs_rotation_rad,
        block.rocking_impacts,
        block.fell
    );
    Ok(())
}

/// `cargo test` runs the example (Cargo.toml: `test = true`).
#[test]
fn runs() {
    main().unwrap();
}
