//! Limit analysis of the wall at rest: the largest horizontal ground acceleration, each way, at
//! which contact forces can still hold every block seated and stuck, moving with the ground,
//! and the mechanism the wall must move by beyond it (Livesley 1978: rigid blocks, joints that
//! carry no tension). Every joint is two corner forces, each in its friction cone; vertical
//! joints push and carry no friction, as in the sliding model. The program and its dual are
//! answered exactly (`certify`: a floating-point simplex run's basis proved in rationals, or
//! the exact tableau of `simplex`), so a limit is exact: a block that tips at g b/h tips
//! there to the last digit.
//!
//! What the limit means: below it, rest is a state the rigid model admits (a distribution of
//! contact forces balances every block); beyond it, none exists and the wall must move. With
//! Coulomb friction the rigid model does not make rest the only state it admits below the limit
//! (Drucker 1954; Gilbert, Casapulla and Ahmed 2006), and the mechanism of the dual is the
//! associative one (a sliding joint dilates at the friction angle), so the mechanism says which
//! blocks move and about which points, not how fast. The loads here are free: a block on two
//! others passes its weight however its balance needs, not by eq. (3)'s tributary split.

mod certify;
mod crash;
mod every;
mod factors;
mod padic;
mod revised;
pub mod seated;
mod simplex;

use crate::error::SimulationError;
use crate::exact::Q;
use crate::topology::{Base, BlockId, HorizontalJoint, Topology, VerticalJoint};
use crate::wall::{Block, Wall};
use simplex::{Outcome, Program};

/// Balances per movable block, its rows in every program here: horizontal, vertical, moment.
const ROWS: usize = 3;

/// An entry of an entering column below this cannot be its pivot (`revised`), nor a pivot of
/// the small solves that choose a crash basis (`crash`). Far above the ratio test's
/// tolerance for values: the bases of long degenerate runs are ill-conditioned (smallest
/// singular value near 1e-5 on the block-count study's 315-row programs, rows scaled to 1), so
/// the entries of B^-1 a_j carry errors near 1e-11 and more as the basis worsens; a pivot on
/// such an entry (1.5e-9 in case 17) made the next basis singular, and the run gave up.
const PIVOT: f64 = 1e-7;

/// The most movable blocks the limit at rest is computed for: where a user still waits for it
/// (about a minute and a half on the largest walls tried below it), every wall tried proved
/// (generated running bonds up to 1,958 blocks, slender ones up to 1,610, the block-count
/// study's 976-block wall and a long wall of 1,005 with sampled friction; docs/rocking-walls.md
/// "The limit at rest from the crash too"). The programs are sparse, tens of megabytes at this
/// size; the time grows faster than the square of a wall cut finer.
pub const MAX_BLOCKS: usize = 2000;

/// The most movable blocks whose programs fall back to the exact tableau where no
/// floating-point run's basis is proved, and so the most the uplift check takes (a run asks it
/// for many programs, each of which must be answered). The tableau is dense, rows times
/// columns of rationals whose fractions grow with every pivot: it had not finished on 495
/// blocks after 400 s (a running bond of 102 blocks took it 0.7 s, the 60 blocks of
/// walls/inca/qorikancha.ron 25 s), and at 600 blocks it starts at half a gigabyte.
pub const EXACT_BLOCKS: usize = 600;

/// Why a program over `movable` blocks is not built (beyond `bound`), naming `what` it is for
/// and `why` the bound.
pub(crate) fn too_large(what: &str, movable: usize, bound: usize, why: &str) -> Option<String> {
    (movable > bound).then(|| {
        format!(
            "{what} is computed for walls of up to {bound} movable blocks ({why}); this wall \
             has {movable}"
        )
    })
}

/// Why the uplift check is not computed for `movable` blocks, where it is not.
pub(crate) fn too_large_for_exact(what: &str, movable: usize) -> Option<String> {
    too_large(
        what,
        movable,
        EXACT_BLOCKS,
        "its exact fallback is a dense tableau",
    )
}

/// The wall's limits at rest, towards +x and towards -x.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Limits {
    /// The ground accelerating towards +x.
    pub towards_plus_x: Limit,
    /// The ground accelerating towards -x.
    pub towards_minus_x: Limit,
}

/// One direction's limit.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Limit {
    /// Held up to this acceleration, then moving by the mechanism.
    Holds {
        /// The limit, |a_g| (m/s2).
        accel_m_s2: f64,
        /// The same in g.
        accel_g: f64,
        /// The same, exact, as a fraction of g (`p/q`).
        exact_g: String,
        /// The same as the rational it is, for arithmetic on it (not written out: `exact_g`).
        #[serde(skip)]
        exact: Q,
        /// How each block that moves moves.
        mechanism: Vec<Moves>,
        /// Whether `mechanism` is the only one that holds at this limit (where it is not, it
        /// is the one the solver's basis gives).
        mechanism_uniqueness: Uniqueness,
        /// The blocks that move in every mechanism that holds at this limit (those of
        /// `mechanism` where it is the only one), decided whether or not uniqueness is; `None`
        /// beyond [`EVERY_BLOCKS`] movable blocks.
        moving_in_every_mechanism: Option<Vec<String>>,
        /// The blocks that turn in every mechanism that holds at this limit, each always the
        /// same way (as `mechanism` turns it); `None` where not decided.
        turning_in_every_mechanism: Option<Vec<String>>,
    },
    /// Held at every acceleration: the abutments hold the wall whatever the ground does.
    Unlimited,
}

impl Limit {
    /// The limit exactly, as a fraction of g; `None` where the wall holds at any acceleration.
    pub fn in_g(&self) -> Option<&Q> {
        match self {
            Limit::Holds { exact, .. } => Some(exact),
            Limit::Unlimited => None,
        }
    }
}

/// Whether a limit's mechanism is the only one that holds there (docs/rocking-walls.md, "What
/// it says and what it does not").
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Uniqueness {
    /// No other mechanism holds at the limit (but for motions that no contact force does work
    /// on, which the program cannot tell apart: a block that slides on a joint moved along the
    /// normal of the friction cone's edge it slides on; they turn no block, since each rests on
    /// a joint with forces at two corners).
    Unique,
    /// Others hold at the same limit too (a uniform wall slides on any of its bed joints).
    OneOfSeveral,
    /// Not decided: the forces at the limit are degenerate in more rows than the deciding
    /// program is run for ([`DECIDED_ROWS`]), the basis shows no other mechanism at once, and
    /// neither do the programs asking which blocks move in every one (where they are run);
    /// or (the uplift check) the mechanism is a certificate that a state keeps no block seated
    /// whatever the ground does, or the run was stopped while deciding.
    Undecided,
}

impl Uniqueness {
    /// What the mechanism named is, in words.
    pub fn which(self) -> &'static str {
        match self {
            Uniqueness::Unique => "the mechanism",
            Uniqueness::OneOfSeveral => "one of several mechanisms that hold at this limit",
            Uniqueness::Undecided => {
                "one mechanism of those that may hold at this limit; whether others do is not \
                 decided"
            }
        }
    }
}

/// Blocks in every mechanism (`moving_in_every_mechanism`, `turning_in_every_mechanism`), as
/// reports write them: their names between `separator`s, or `none`.
pub fn in_every_listed(names: &[String], separator: &str) -> String {
    match names {
        [] => "none".to_string(),
        _ => names.join(separator),
    }
}

/// The most degenerate rows (basic columns at zero) for which a degenerate limit's mechanism is
/// decided in full where its basis shows no other at once (`limit::uniqueness`): the deciding
/// program takes an exact solve in B^T per such row. Walls of up to 200 movable blocks have
/// at most 600 rows in all, so each is decided; larger ones where their limit is degenerate in
/// few rows (a slender running bond of 405 blocks: 10 and 7, decided in milliseconds).
pub const DECIDED_ROWS: usize = 600;

/// The most movable blocks for which the blocks moving and turning in every mechanism are
/// decided where the mechanism is one of several: a program as large as the limit's for each
/// block that no mechanism found before holds still (`every`). On generated running bonds of
/// one friction, `check --limit` with them takes 2.8 s at 297 blocks and 3.9 s at 410 where the
/// limit alone takes 0.8 and 1.3 s; 15 s at 588 (4.3 s) and 43 s at 976 (15 s).
pub const EVERY_BLOCKS: usize = 500;

/// How a block moves in a mechanism, relative to the ground.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Moves {
    /// The block's name.
    pub block: String,
    /// The motion in words ("turns about its bottom-left corner", "slides towards -x").
    pub how: String,
    /// Its centroid's velocity and its angular velocity (counterclockwise), scaled so that the
    /// largest velocity component of any centroid of the mechanism is 1 (m/s, m/s, rad/s).
    pub u: f64,
    /// See `u`.
    pub v: f64,
    /// See `u`.
    pub omega_rad_s: f64,
}

/// One column of the program: a unit force along `direction` at `at` on block `on`, and its
/// opposite on block `against` (none for the ground or an abutment).
struct Force {
    on: usize,
    against: Option<usize>,
    at: [Q; 2],
    direction: [Q; 2],
}

/// The limits of the wall at rest (every block seated, moving with the ground).
pub fn at_rest(wall: &Wall, topo: &Topology) -> Result<Limits, SimulationError> {
    Ok(at_rest_until(wall, topo, &|| false)?.expect("never stopped"))
}

/// [`at_rest`], asking `stop` before every pivot of its programs (a large wall's can take
/// minutes): `None` where it said so, with nothing of either side kept (a side is known only
/// once its program is proved).
pub fn at_rest_until(
    wall: &Wall,
    topo: &Topology,
    stop: &dyn Fn() -> bool,
) -> Result<Option<Limits>, SimulationError> {
    let movable: Vec<usize> = (0..wall.blocks.len())
        .filter(|&i| !wall.blocks[i].fixed)
        .collect();
    let why = "its programs take minutes at that size, and more beyond";
    if let Some(why) = too_large("the limit at rest", movable.len(), MAX_BLOCKS, why) {
        return Err(SimulationError::NotApplicable(why));
    }
    let (forces, bases) = forces(wall, topo);
    let groups = crash_groups(wall, &movable, &forces[..bases]);
    let direction = |s| direction(wall, topo, &movable, &forces, &groups, s, stop);
    let Some(towards_plus_x) = direction(1)? else {
        return Ok(None);
    };
    let Some(towards_minus_x) = direction(-1)? else {
        return Ok(None);
    };
    Ok(Some(Limits {
        towards_plus_x,
        towards_minus_x,
    }))
}

/// Every contact force of the wall as unit forces: at each end of each horizontal joint the two
/// edges of the friction cone (one where friction is zero), at each end of each touching
/// vertical joint a push; and how many of them, first, are the horizontal joints' (the bases').
fn forces(wall: &Wall, topo: &Topology) -> (Vec<Force>, usize) {
    let movable = |i: usize| (!wall.blocks[i].fixed).then_some(i);
    let mut out = Vec::new();
    for h in &topo.horizontal {
        let up = &wall.blocks[h.upper.0];
        let [l, r] = overlap(wall, h);
        let against = match h.lower {
            Base::Ground => None,
            Base::Block(BlockId(j)) => movable(j),
        };
        let edges: &[i128] = if h.friction.is_zero() { &[1] } else { &[1, -1] };
        for x in [l, r] {
            for &s in edges {
                out.push(Force {
                    on: h.upper.0,
                    against,
                    at: [x.clone(), up.y.clone()],
                    direction: [&h.friction * &Q::frac(s, 1), Q::one()],
                });
            }
        }
    }
    let bases = out.len();
    for v in topo.vertical.iter().filter(|v| v.gap_m.is_zero()) {
        out.extend(pushes(wall, v, movable));
    }
    (out, bases)
}

/// The crash's groups (`crash::Group`): each movable block's three balances (rows `ROWS k` on for
/// the k-th of `movable`) with the forces of `base` on it, blocks top down, since a base force
/// loads its block and the one under it, whose base is lower.
fn crash_groups(wall: &Wall, movable: &[usize], base: &[Force]) -> Vec<crash::Group> {
    let mut top_down: Vec<usize> = (0..movable.len()).collect();
    top_down.sort_by(|&a, &b| wall.blocks[movable[b]].y.cmp(&wall.blocks[movable[a]].y));
    let mut on: Vec<Vec<usize>> = vec![Vec::new(); wall.blocks.len()];
    base.iter().enumerate().for_each(|(j, f)| on[f.on].push(j));
    top_down
        .into_iter()
        .map(|k| crash::Group {
            rows: ROWS * k..ROWS * (k + 1),
            columns: std::mem::take(&mut on[movable[k]]),
        })
        .collect()
}

/// The ends of a horizontal joint's contact (m): where its upper block meets its base.
fn overlap(wall: &Wall, h: &HorizontalJoint) -> [Q; 2] {
    let up = &wall.blocks[h.upper.0];
    match h.lower {
        Base::Ground => [up.x.clone(), up.right()],
        Base::Block(BlockId(j)) => {
            let lo = &wall.blocks[j];
            [up.x.clone().max(lo.x.clone()), up.right().min(lo.right())]
        }
    }
}

/// The pushes of a vertical joint, one at each end of the height its faces share: on the right
/// block towards +x and its opposite on the left; where the right one does not move (an
/// abutment; `moves` says which do), the push on the left is the force.
fn pushes(wall: &Wall, v: &VerticalJoint, moves: impl Fn(usize) -> Option<usize>) -> Vec<Force> {
    let (a, b) = (&wall.blocks[v.left.0], &wall.blocks[v.right.0]);
    let lo = a.y.clone().max(b.y.clone());
    let hi = a.top().min(b.top());
    let (right, left) = (moves(v.right.0), moves(v.left.0));
    [lo, hi]
        .into_iter()
        .filter_map(|y| {
            let at = [a.right(), y];
            match (right, left) {
                (Some(on), against) => Some(Force {
                    on,
                    against,
                    at,
                    direction: [Q::one(), Q::zero()],
                }),
                (None, Some(on)) => Some(Force {
                    on,
                    against: None,
                    at,
                    direction: [-Q::one(), Q::zero()],
                }),
                (None, None) => None,
            }
        })
        .collect()
}

/// The centroid of a block (m).
fn centroid(b: &Block) -> [Q; 2] {
    [b.centroid_x(), &b.y + &b.height * Q::frac(1, 2)]
}

/// A unit force's entries in the three balances of the block it acts on: horizontal, vertical,
/// and moment about the centroid (counterclockwise).
fn entries(f: &Force, c: &[Q; 2]) -> [Q; 3] {
    let [fx, fy] = &f.direction;
    let (dx, dy) = (&f.at[0] - &c[0], &f.at[1] - &c[1]);
    [fx.clone(), fy.clone(), &dx * fy - &dy * fx]
}

/// The limit towards the side of `s` (+1: the ground accelerating towards +x): the largest a
/// with every block's balance m a s = sum of forces on it, the weight carried, no moment;
/// `None` where `stop` said so.
fn direction(
    wall: &Wall,
    topo: &Topology,
    movable: &[usize],
    forces: &[Force],
    groups: &[crash::Group],
    s: i128,
    stop: &dyn Fn() -> bool,
) -> Result<Option<Limit>, SimulationError> {
    let centroids: Vec<[Q; 2]> = wall.blocks.iter().map(centroid).collect();
    let program = program(wall, topo, movable, forces, &centroids, s);
    let outcome = if movable.len() <= EXACT_BLOCKS {
        certify::solve(&program, groups, stop)
    } else {
        certify::proved(&program, groups, stop).map_err(|certify::NotProved| {
            SimulationError::NotApplicable(format!(
                "the limit at rest towards {} was not proved: no floating-point run of its \
                 program ended on a basis that checks exactly, and the exact tableau is run \
                 only for walls of up to {EXACT_BLOCKS} movable blocks (it is dense); this \
                 wall has {}",
                if s > 0 { "+x" } else { "-x" },
                movable.len()
            ))
        })?
    };
    let Some(outcome) = outcome else {
        return Ok(None);
    };
    match outcome {
        Outcome::Unbounded => Ok(Some(Limit::Unlimited)),
        Outcome::Infeasible { y } => {
            // The graph checks each block over its own supports; a stack can pass that and
            // still lean past a support lower down. The accelerations that hold a wall are one
            // interval (the program is convex); a side with none means the interval misses
            // zero, so the wall cannot stand at rest, even where shaking the other way would
            // hold it. The certificate is the fall.
            let falls: Vec<String> = mechanism(wall, topo, movable, &centroids, &y)
                .into_iter()
                .map(|m| format!("{} {}", m.block, m.how))
                .collect();
            Err(SimulationError::NotApplicable(format!(
                "the wall cannot stand even on still ground: no contact forces hold its blocks \
                 seated, and it would fall thus: {}; support the blocks that lean past their \
                 base",
                falls.join(", ")
            )))
        }
        Outcome::Optimal { value, y, x, basis } => {
            let accel = -&value;
            let g = &accel / &wall.g_m_s2;
            let Some(found) = uniqueness(&program, &x, &y, &basis, DECIDED_ROWS, stop) else {
                return Ok(None);
            };
            let optimum = (&value, &y[..], &basis[..]);
            let asked = every_at_optimum(found, &program, groups, optimum, movable.len(), stop)?;
            let Some((mechanism_uniqueness, every)) = asked else {
                return Ok(None);
            };
            let names = |places: Vec<usize>| {
                (places.into_iter())
                    .map(|k| wall.blocks[movable[k]].name.clone())
                    .collect()
            };
            let (moving, turning) = match every {
                Some(e) => (Some(names(e.moving)), Some(names(e.turning))),
                None => (None, None),
            };
            Ok(Some(Limit::Holds {
                accel_m_s2: accel.to_f64(),
                accel_g: g.to_f64(),
                exact_g: format!("{g:?}"),
                exact: g,
                mechanism: mechanism(wall, topo, movable, &centroids, &y),
                mechanism_uniqueness,
                moving_in_every_mechanism: moving,
                turning_in_every_mechanism: turning,
            }))
        }
    }
}

/// The blocks that move and turn in every mechanism that holds at a limit's optimum (its value,
/// multipliers y and their basis), whose uniqueness `found` says ([`uniqueness`]): a unique
/// mechanism's own; otherwise asked by programs ([`every`]) for at most [`EVERY_BLOCKS`] movable
/// blocks, whether or not uniqueness was decided, since it is its own question. Where it was
/// not and those programs meet another mechanism, the mechanism is one of several: the
/// uniqueness comes back with that. `None` where `stop` said so.
fn every_at_optimum(
    found: Uniqueness,
    program: &Program,
    groups: &[crash::Group],
    (value, y, basis): (&Q, &[Q], &[usize]),
    blocks: usize,
    stop: &dyn Fn() -> bool,
) -> Result<Option<(Uniqueness, Option<every::Every>)>, SimulationError> {
    if found == Uniqueness::Unique {
        return Ok(Some((found, Some(every::Every::of(y)))));
    }
    if blocks > EVERY_BLOCKS {
        return Ok(Some((found, None)));
    }
    let optimum = Some((value, basis));
    let Some(every) = every::in_every_mechanism(program, groups, optimum, y, true, stop)? else {
        return Ok(None);
    };
    let found = match found {
        Uniqueness::Undecided if every.another => Uniqueness::OneOfSeveral,
        other => other,
    };
    Ok(Some((found, Some(every))))
}

/// Whether the multipliers `y` of the optimal vertex `x` (read from `basis`) are the program's
/// only optimal ones; `None` where `stop` said so. Another optimal y + d meets complementary
/// slackness with x: a_j d = 0 where x_j > 0 (the set P) and a_j d <= 0 where x_j = 0 and c_j -
/// a_j y = 0 (the set T; elsewhere a small d keeps the constraint). A d with A^T d = 0 is a
/// motion no contact force does work on (a block sliding on a joint has one: moved along the
/// normal of the cone's edge it slides on), which the multipliers cannot tell apart: the
/// question is whether every such d is one of those. Where x has as many positive entries as
/// rows (nondegenerate) P alone spans the rows and d = 0. Otherwise: a few degenerate rows of
/// the basis are tried for such a d directly (`certify::Degenerate::moves_off`, an exact solve
/// each; one found is a no for milliseconds); where P and T do not span A's columns
/// (`certify::spanned`, from the basis, whose own columns lie in P and T) some d in that span
/// is orthogonal to all of them: no; where they do, every d is -B^-T v for a basis of P and T's
/// columns, and the program of such v (`certify::Degenerate::directions`, at most `most_rows`
/// degenerate rows) is feasible exactly where another optimal y exists.
fn uniqueness(
    program: &Program,
    x: &[Q],
    y: &[Q],
    basis: &[usize],
    most_rows: usize,
    stop: &dyn Fn() -> bool,
) -> Option<Uniqueness> {
    if !degenerate(program, x) {
        return Some(Uniqueness::Unique);
    }
    let tight = |j: usize| program.c[j] == program.dot(j, y);
    // P and T: the columns the directions d must keep (a_j d = 0 on P, <= 0 on T).
    let kept: Vec<bool> = (x.iter().enumerate())
        .map(|(j, x_j)| x_j.is_positive() || tight(j))
        .collect();
    let Some(mut questions) = certify::Degenerate::of(program, basis, x, |j| kept[j]) else {
        return Some(Uniqueness::Undecided);
    };
    match questions.moves_off() {
        Some(true) => return Some(Uniqueness::OneOfSeveral),
        Some(false) => {}
        None => return Some(Uniqueness::Undecided),
    }
    let mut questions = match certify::spanned(program, basis, |j| kept[j]) {
        None => return Some(Uniqueness::Undecided),
        // Some d in the columns' span is orthogonal to all of P and T: y + d holds too.
        Some(certify::Span::Short) => return Some(Uniqueness::OneOfSeveral),
        // The usual case: the basis had no artificial variable to replace, and its rows
        // already solved serve the program of directions.
        Some(certify::Span::All(spanning)) if spanning == basis => questions,
        Some(certify::Span::All(spanning)) => {
            match certify::Degenerate::of(program, &spanning, x, |j| kept[j]) {
                Some(questions) => questions,
                None => return Some(Uniqueness::Undecided),
            }
        }
    };
    let Some(directions) = questions.directions(most_rows) else {
        return Some(Uniqueness::Undecided);
    };
    Some(match certify::solve(&directions, &[], stop)? {
        Outcome::Infeasible { .. } => Uniqueness::Unique,
        Outcome::Optimal { .. } | Outcome::Unbounded => Uniqueness::OneOfSeveral,
    })
}

/// Whether the optimal vertex `x` has fewer positive entries than the program has rows: only
/// then can another mechanism hold at the same optimum ([`uniqueness`]'s first step, which the
/// uplift check takes when it solves a side, to decide the rest only for the side it reports).
fn degenerate(program: &Program, x: &[Q]) -> bool {
    x.iter().filter(|v| v.is_positive()).count() < program.b.len()
}

/// The program of the limit towards the side of `s`: columns are the unit contact forces and
/// the acceleration a (last), rows each movable block's horizontal, vertical and moment
/// balances; minimise -a.
fn program(
    wall: &Wall,
    topo: &Topology,
    movable: &[usize],
    forces: &[Force],
    centroids: &[[Q; 2]],
    s: i128,
) -> Program {
    let row_of: std::collections::HashMap<usize, usize> = movable
        .iter()
        .enumerate()
        .map(|(k, &i)| (i, ROWS * k))
        .collect();
    let m = ROWS * movable.len();
    let mut columns: Vec<Vec<(usize, Q)>> = forces
        .iter()
        .map(|f| {
            let on = entries(f, &centroids[f.on]).into_iter();
            let mut column: Vec<(usize, Q)> = on
                .enumerate()
                .map(|(k, x)| (row_of[&f.on] + k, x))
                .collect();
            if let Some(o) = f.against {
                let against = entries(f, &centroids[o]).into_iter().enumerate();
                column.extend(against.map(|(k, x)| (row_of[&o] + k, -x)));
            }
            column
        })
        .collect();
    let mut b = vec![Q::zero(); m];
    let mut accel = Vec::with_capacity(movable.len());
    for (k, &i) in movable.iter().enumerate() {
        let mass = &topo.blocks[i].mass_kg;
        accel.push((ROWS * k, -(mass * &Q::frac(s, 1))));
        b[ROWS * k + 1] = mass * &wall.g_m_s2;
    }
    columns.push(accel);
    let mut c = vec![Q::zero(); columns.len()];
    c[columns.len() - 1] = -Q::one();
    Program::new(columns, b, c)
}

/// The mechanism from the multipliers of the balances: minus each block's three multipliers
/// are its velocity (u, v, omega), the dual's virtual motion.
fn mechanism(
    wall: &Wall,
    topo: &Topology,
    movable: &[usize],
    centroids: &[[Q; 2]],
    y: &[Q],
) -> Vec<Moves> {
    let mut speeds = vec![[Q::zero(), Q::zero(), Q::zero()]; wall.blocks.len()];
    for (k, &i) in movable.iter().enumerate() {
        speeds[i] = [-&y[ROWS * k], -&y[ROWS * k + 1], -&y[ROWS * k + 2]];
    }
    let scale = speeds
        .iter()
        .map(|[u, v, _]| u.abs().max(v.abs()))
        .max()
        .filter(Q::is_positive)
        .unwrap_or_else(Q::one);
    let field = Field {
        wall,
        centroids,
        speeds: &speeds,
    };
    movable
        .iter()
        .filter(|&&i| speeds[i].iter().any(|x| !x.is_zero()))
        .map(|&i| {
            let [u, v, w] = &speeds[i];
            Moves {
                block: wall.blocks[i].name.clone(),
                how: field.describe(topo, i),
                u: (u / &scale).to_f64(),
                v: (v / &scale).to_f64(),
                omega_rad_s: (w / &scale).to_f64(),
            }
        })
        .collect()
}

/// The mechanism's velocities, one (u, v, omega) per block of the wall (zero for those that
/// stay).
struct Field<'a> {
    wall: &'a Wall,
    centroids: &'a [[Q; 2]],
    speeds: &'a [[Q; 3]],
}

impl Field<'_> {
    /// Block i's horizontal velocity at height y (m/s).
    fn u_at(&self, i: usize, y: &Q) -> Q {
        let [u, _, w] = &self.speeds[i];
        u - &(w * &(y - &self.centroids[i][1]))
    }

    /// Block i's motion in words: the corner it turns about (its own or another block's), or,
    /// without turning, whether it slides on every support or is carried.
    fn describe(&self, topo: &Topology, i: usize) -> String {
        let [u, v, w] = &self.speeds[i];
        let sign = |x: &Q| if x.is_negative() { "-" } else { "+" };
        if w.is_zero() {
            let b = &self.wall.blocks[i];
            // A joint that slips dilates in the associative mechanism (v = mu |u| on it), so
            // what tells a slide is the horizontal velocity against every support's there.
            let slides = topo.below[i].iter().all(|h| {
                let under = match topo.horizontal[h.0].lower {
                    Base::Ground => Q::zero(),
                    Base::Block(BlockId(j)) => self.u_at(j, &b.y),
                };
                *u != under
            });
            return if slides {
                format!("slides towards {}x", sign(u))
            } else {
                format!("moves towards {}x without turning, carried", sign(u))
            };
        }
        // The point at rest: the centroid's velocity plus w x r vanishes there.
        let c = &self.centroids[i];
        let (px, py) = (&c[0] - &(v / w), &c[1] + &(u / w));
        let turning = if w.is_positive() {
            "counterclockwise"
        } else {
            "clockwise"
        };
        let corner_of = |k: usize| {
            let b = &self.wall.blocks[k];
            [
                (b.x.clone(), b.y.clone(), "bottom-left"),
                (b.right(), b.y.clone(), "bottom-right"),
                (b.x.clone(), b.top(), "top-left"),
                (b.right(), b.top(), "top-right"),
            ]
            .into_iter()
            .find(|(x, y, _)| *x == px && *y == py)
            .map(|(_, _, name)| name)
        };
        if let Some(name) = corner_of(i) {
            return format!("turns {turning} about its {name} corner");
        }
        match (0..self.wall.blocks.len()).find_map(|k| corner_of(k).map(|n| (k, n))) {
            Some((k, name)) => format!(
                "turns {turning} about {}'s {name} corner",
                self.wall.blocks[k].name
            ),
            None => format!(
                "turns {turning} about ({:.4} m, {:.4} m)",
                px.to_f64(),
                py.to_f64()
            ),
        }
    }
}

#[cfg(test)]
mod tests;
