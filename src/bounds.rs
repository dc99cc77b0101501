//! Where an input stops being meaningful, for the model or for f64: the bounds every wall,
//! motion and run is checked against before anything is computed (docs/reliability.md says why
//! each lies where it does). Outside them pirqa refuses with the bound in the message, rather
//! than compute an answer that round-off, overflow or sheer size makes wrong.

/// Shortest length of a block, course or wall (m): below a millimetre a block is not masonry,
/// and masses and loads shrink towards f64's subnormal range, where the answer (which does not
/// depend on the thickness) starts to.
pub const MIN_LENGTH_M: f64 = 1e-3;

/// Longest length (m): ten kilometres, past any wall.
pub const MAX_LENGTH_M: f64 = 1e4;

/// Farthest a block may be placed from the origin (m).
pub const MAX_POSITION_M: f64 = 1e6;

/// Densities (kg/m3): from a light foam to past the densest metal.
pub const DENSITY_KG_M3: (f64, f64) = (1.0, 1e5);

/// Gravity (m/s2): from a small moon's to ten times the Earth's.
pub const GRAVITY_M_S2: (f64, f64) = (0.1, 100.0);

/// Largest ground acceleration (m/s2), about 100 g: 25 times the largest ever recorded. Beyond
/// about 1e154 m/s2 energies overflow f64 and come out as NaN.
pub const MAX_ACCEL_M_S2: f64 = 1000.0;

/// Sine frequencies (Hz): from a period of about three hours (quasi-static for any wall; at
/// 5e-324 Hz the ground's displacement A / omega^2 overflows and energies came out NaN) to
/// 1 kHz (records are sampled at 1 kHz at most).
pub const FREQUENCY_HZ: (f64, f64) = (1e-4, 1000.0);

/// Longest motion or run (s): eleven days of shaking.
pub const MAX_DURATION_S: f64 = 1e6;

/// Most cycles of a sine (frequency x duration): each costs a few events at the least.
pub const MAX_CYCLES: f64 = 1e7;

/// Largest sine phase (rad) taken as given; a larger one must be reduced by the caller (the
/// command line reduces degrees exactly), for reducing it in floating point loses its digits.
pub const MAX_PHASE_RAD: f64 = 1e4;

/// Sample intervals of a record (s): from a microsecond to ten seconds.
pub const RECORD_DT_S: (f64, f64) = (1e-6, 10.0);

/// Most steps of a time-stepping run (duration / step).
pub const MAX_STEPS: f64 = 1e9;

/// Most numbers a run may keep in its history in memory (rows x columns): 400 MB of f64.
pub const MAX_HISTORY_VALUES: f64 = 5e7;

/// Most numbers a run may write to a history file as it goes (memory stays bounded): about
/// 50 GB of CSV; `--output-dt 1e-9` wrote 63 GB in ten minutes before this bound.
pub const MAX_HISTORY_FILE_VALUES: f64 = 2e9;

/// Is x within [lo, hi] (and so finite)?
pub fn within(x: f64, (lo, hi): (f64, f64)) -> bool {
    (lo..=hi).contains(&x)
}
