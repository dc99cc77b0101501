//! Whether two runs of one scenario that differ only in their work (a setting of the integrator
//! that must never change the answer) gave the same answer.

use pirqa::response::{Energy, Response};

/// The same events with the same numbers, in any order within an instant (the event queue
/// breaks ties by when each was scheduled, which the work changes), and the same summary but for
/// the work counters and the energies. The energies are running sums over the clusters in the
/// order of their slots, which the work changes too: they agree to round-off, 1e-12 of the
/// input. `Err` says what differs.
pub fn same_answer(a: &Response, b: &Response) -> Result<(), String> {
    let sorted = |r: &Response| {
        let log = r.events_jsonl();
        let mut lines: Vec<String> = log.lines().map(str::to_owned).collect();
        lines.sort();
        lines
    };
    if sorted(a) != sorted(b) {
        return Err("the event logs differ".into());
    }
    let (ea, eb) = (&a.summary.energy, &b.summary.energy);
    let terms = |e: &Energy| {
        [
            e.input_j,
            e.friction_j,
            e.impact_loss_j,
            e.kinetic_j,
            e.fallen_j,
            e.residual_j,
        ]
    };
    let scale = 1e-12 * ea.input_j.abs().max(1e-300);
    if terms(ea)
        .iter()
        .zip(terms(eb))
        .any(|(x, y)| (x - y).abs() > scale)
    {
        return Err(format!("the energies differ: {ea:?} against {eb:?}"));
    }
    let mut same = b.summary.clone();
    same.stats = a.summary.stats;
    same.energy = a.summary.energy;
    if same != a.summary {
        return Err(format!(
            "the summaries differ: {:?} against {:?}",
            a.summary, b.summary
        ));
    }
    Ok(())
}
