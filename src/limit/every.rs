//! Which blocks move, and which turn, in every mechanism that holds at a limit: where the
//! mechanism named is one of several, the blocks that cannot stay still (or cannot stop
//! turning) whichever of them the wall takes.
//!
//! The mechanisms at a limit are the optimal multipliers of its program, the face F = {y :
//! A^T y <= c, b y = z*} of the dual (z* the limit's value; the velocities are -y). A block k
//! moves in every mechanism exactly where F holds no y with its three multipliers zero, and
//! turns in every one exactly where F holds none with its rotation's zero (F is convex, so
//! where the named mechanism turns it and none holds it still, every one turns it the same
//! way). Multipliers held at zero are the dual of the same program with a free reaction on
//! those balances (a pair of unit columns at no cost each): the block held to the ground, or
//! held from turning. So block k moves in every mechanism exactly where holding it raises the
//! limit, and turns in every one exactly where stopping it turning does; where the limit stays,
//! the held program's multipliers are a mechanism of F that keeps the block still, which
//! answers the same question for every other block it keeps still: one program settles many
//! blocks of a wall whose mechanisms are layers (a uniform wall slides on any bed joint: the
//! blocks under the highest joint are still in one of them). Each held program is the limit's
//! with a few columns more, answered as the limit is but from the limit's optimal basis
//! (feasible for it: the new columns start at zero): where the limit stays, a few pivots reach
//! the held program's optimum, and where it rises, the first vertex below the limit's value
//! shows so, without the optimum (on a generated bond of 410 blocks, a run from the limit's
//! basis to such a held optimum took 5,500 pivots, where the limit's own from the crash took
//! 1,900 and 4,900).

use super::certify::{self, Against};
use super::crash::Group;
use super::simplex::{Outcome, Program};
use super::ROWS;
use crate::error::SimulationError;
use crate::exact::Q;

/// The blocks (places among the movable ones) that move (where `moving` asks), and those that
/// turn, in every mechanism that holds at the limit of `program`: with `optimum` its value and
/// the optimal basis `y` was read from (`y` one of its optimal multipliers, the mechanism
/// named), or, where the program is infeasible (`optimum` none), in every certificate of that
/// (`y` one of them: A^T y <= 0, b y > 0; they too are convex, and a block holding which makes
/// the program feasible moves in every one). `None` where `stop` said so.
pub(super) fn in_every_mechanism(
    program: &Program,
    groups: &[Group],
    optimum: Option<(&Q, &[usize])>,
    y: &[Q],
    moving: bool,
    stop: &dyn Fn() -> bool,
) -> Result<Option<Every>, SimulationError> {
    let mut found = vec![y.to_vec()];
    let mut every = Every::default();
    for k in 0..y.len() / ROWS {
        let whole: Vec<usize> = (ROWS * k..ROWS * (k + 1)).collect();
        let asked = [(moving, whole), (true, vec![ROWS * k + 2])];
        for (i, (ask, rows)) in asked.into_iter().enumerate() {
            if !ask {
                continue;
            }
            let Some(always) = always(program, groups, optimum, &rows, &mut found, stop)? else {
                return Ok(None);
            };
            if always {
                [&mut every.moving, &mut every.turning][i].push(k);
            }
        }
    }
    every.another = optimum.is_some() && found[1..].iter().any(|z| differs(program, y, z));
    Ok(Some(every))
}

/// Whether multipliers `y` and `z` are two mechanisms, not one seen twice: some contact force
/// does work on their difference d (a_j d != 0 for some column j). A d with A^T d = 0 moves a
/// block along the normal of the cone's edge it slides on, which the multipliers cannot tell
/// apart (`Uniqueness::Unique`).
fn differs(program: &Program, y: &[Q], z: &[Q]) -> bool {
    let d: Vec<Q> = z.iter().zip(y).map(|(a, b)| a - b).collect();
    (0..program.c.len()).any(|j| !program.dot(j, &d).is_zero())
}

/// Whether every mechanism (of the limit `optimum`, or every certificate where none)
/// moves the multipliers of `rows`: none of the mechanisms `found` so far holds them at zero,
/// and the program holding them reaches a higher limit, or becomes feasible; where it does
/// not, its multipliers join `found`. `None` where `stop` said so.
fn always(
    program: &Program,
    groups: &[Group],
    optimum: Option<(&Q, &[usize])>,
    rows: &[usize],
    found: &mut Vec<Vec<Q>>,
    stop: &dyn Fn() -> bool,
) -> Result<Option<bool>, SimulationError> {
    if (found.iter()).any(|y| rows.iter().all(|&r| y[r].is_zero())) {
        return Ok(Some(false));
    }
    let held = held(program, rows);
    let outcome = match optimum {
        Some((value, basis)) => {
            // The artificial variables' columns follow the reactions' in the held program.
            let (n, added) = (program.c.len(), held.c.len() - program.c.len());
            let start = (basis.iter()).map(|&j| if j < n { j } else { j + added });
            certify::solve_below(&held, start.collect(), value, groups, stop)
        }
        None => certify::solve(&held, groups, stop).map(Against::Solved),
    };
    let Some(outcome) = outcome else {
        return Ok(None);
    };
    match (outcome, optimum.map(|(value, _)| value)) {
        (Against::Solved(Outcome::Optimal { value: v, y, .. }), Some(value)) if v == *value => {
            found.push(y);
            Ok(Some(false))
        }
        (Against::Solved(Outcome::Infeasible { y }), None) => {
            found.push(y);
            Ok(Some(false))
        }
        // Held, the wall stands to a higher limit, at any acceleration, or at all.
        (Against::Below | Against::Solved(Outcome::Optimal { .. } | Outcome::Unbounded), _) => {
            Ok(Some(true))
        }
        // The limit's own forces, the new reactions at zero, balance the held program: an
        // exact answer cannot say otherwise.
        (Against::Solved(Outcome::Infeasible { .. }), Some(_)) => Err(SimulationError::Bug(
            "a limit's program with reactions added came out infeasible".into(),
        )),
    }
}

/// The blocks that move and those that turn in every mechanism (places among the movable
/// blocks, in order), and whether the programs that asked met a mechanism other than the one
/// named (then it is one of several, whatever the deciding program could be run for).
#[derive(Debug, Default, PartialEq)]
pub(super) struct Every {
    pub(super) moving: Vec<usize>,
    pub(super) turning: Vec<usize>,
    pub(super) another: bool,
}

impl Every {
    /// Those of the one mechanism of multipliers `y`: its blocks and its turning ones.
    pub(super) fn of(y: &[Q]) -> Every {
        let nonzero = |rows: std::ops::Range<usize>| rows.into_iter().any(|r| !y[r].is_zero());
        let blocks = 0..y.len() / ROWS;
        Every {
            moving: (blocks.clone())
                .filter(|&k| nonzero(ROWS * k..ROWS * (k + 1)))
                .collect(),
            turning: blocks
                .filter(|&k| nonzero(ROWS * k + 2..ROWS * (k + 1)))
                .collect(),
            another: false,
        }
    }
}

/// The program with a free reaction on the balances of `rows` (the module's comment).
fn held(program: &Program, rows: &[usize]) -> Program {
    let n = program.c.len();
    let mut columns: Vec<Vec<(usize, Q)>> = (0..n).map(|j| program.column(j).to_vec()).collect();
    for &r in rows {
        columns.push(vec![(r, Q::one())]);
        columns.push(vec![(r, -Q::one())]);
    }
    let mut c = program.c.clone();
    c.resize(columns.len(), Q::zero());
    Program::new(columns, program.b.clone(), c)
}
