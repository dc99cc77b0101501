//! Sweeps at the sizes issue 6 sets targets for (docs/performance.md): the grid behind the
//! paper's Fig. 3 and 4 (1,200 sine cases of 20 s) and a 1,000-case friction Monte Carlo on the
//! five-block wall under El Centro, each run on all cores as `pirqa sweep` runs them, without
//! writing files: `cargo bench --features bench --bench studies`.

use criterion::{criterion_group, criterion_main, Criterion};
use pirqa::study::sweep::Sweep;
use std::collections::HashSet;
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

fn run(sweep: &Sweep) -> usize {
    let mut rows = 0;
    sweep
        .run_cases(&HashSet::new(), |row, _| {
            rows += usize::from(row.error.is_none());
            Ok(())
        })
        .unwrap();
    assert_eq!(rows, sweep.len(), "every case runs");
    rows
}

fn benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("sweeps");
    group
        .sample_size(10)
        .measurement_time(Duration::from_secs(20));
    for (name, file) in [
        ("paper_fig3_4_1200_sine_cases_20s", "paper-fig3-4.ron"),
        (
            "friction_mc_1000_cases_el_centro_1500gal",
            "friction-mc.ron",
        ),
    ] {
        let sweep = Sweep::load(&Path::new("walls/studies").join(file)).unwrap();
        group.bench_function(name, |b| b.iter(|| black_box(run(&sweep))));
    }
    group.finish();
}

criterion_group!(studies, benches);
criterion_main!(studies);
