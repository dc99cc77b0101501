//! Time-stepping baselines, for comparison with the exact integrator: the paper's own scheme,
//! Moreau-Jean nonsmooth time stepping (also with rotations, for every block of a wall: a
//! free-standing block is a wall of one), and
//! regularized friction with penalty contacts under an adaptive Runge-Kutta method. Same trait, same outputs; `docs/accuracy.md` says where each
//! fails.

mod anderson;
mod moreau;
mod moreau_wall;
mod paper;
mod regularized;
mod release;
mod set_down;
mod wall_dual;
mod wall_newton;

pub use moreau::Moreau;
pub use moreau_wall::{ContactSolver, MoreauWall, HANDED_OFF};
pub(crate) use moreau_wall::{KeepsSeated, Stepped};
pub use paper::PaperNewmark;
pub use regularized::Regularized;
pub use set_down::{SEATED_M, SEATED_M_S, SEATED_STEPS};

/// Pairwise Newton impact between velocities vl, vr (m/s) of masses ml, mr (kg; `None` = fixed).
pub(crate) fn collide(vl: f64, vr: f64, ml: Option<f64>, mr: Option<f64>, e: f64) -> (f64, f64) {
    let approach = vl - vr;
    match (ml, mr) {
        (Some(ml), Some(mr)) => {
            let p = (1.0 + e) * ml * mr / (ml + mr) * approach;
            (vl - p / ml, vr + p / mr)
        }
        (None, Some(_)) => (0.0, e * approach),
        (Some(_), None) => (-e * approach, 0.0),
        (None, None) => (vl, vr),
    }
}
