//! Whether every block of a sliding state can stay seated: the ground accelerations at which
//! contact forces exist that give each block the acceleration its state gives it (moving with
//! the ground, or a sliding cluster's constant one) with no block turning. The sliding model
//! decides horizontal forces only; a block also needs the moments of its forces balanced, by
//! where its joints' normal forces act inside each joint's overlap. Where no such forces exist
//! some block must start to turn: the uplift the sliding model leaves out.
//!
//! The contact forces are those of the limit at rest (`at_rest`), with the state's slips: each
//! horizontal joint is two corner forces, each in its friction cone where the joint is stuck
//! and on the cone's edge against the slip where it slips (Coulomb, eq. 2); touching faces of
//! blocks that move together push. The loads are free: a block on two others may pass its
//! weight however its balance needs, so an interval's side is where no load split at all keeps
//! the blocks seated (eq. 3's tributary split is one of those tried). In a state with nothing
//! sliding the interval is the limit at rest.

use super::simplex::{Outcome, Program};
use super::{centroid, crash_groups, entries, mechanism, overlap, pushes, Force, Moves, ROWS};
use super::{
    certify, crash, degenerate, every, uniqueness, Uniqueness, DECIDED_ROWS, EVERY_BLOCKS,
};
use crate::error::SimulationError;
use crate::exact::Q;
use crate::topology::{Base, BlockId, Topology};
use crate::wall::Wall;

/// How a block moves in the state.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Moving {
    /// With the ground (stuck to it, through its joints).
    Ground,
    /// At this constant absolute acceleration (m/s2): a sliding cluster's.
    At(Q),
}

/// A sliding state of the wall, as the sliding model has it between two events.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct State {
    /// Per block: how it moves; `None` for a fixed block or one that has fallen.
    pub moving: Vec<Option<Moving>>,
    /// Per horizontal joint: 0 where it is stuck, +1 (-1) where its upper block slips towards
    /// +x (-x) on the lower one.
    pub slip: Vec<i8>,
    /// Per vertical joint: its faces touch and its blocks move together, so it may push.
    pub pushes: Vec<bool>,
}

/// One side of the interval: the furthest ground acceleration that way (m/s2) at which every
/// block stays seated, and how the blocks move past it. Friction is in the program, so a side
/// may be a slip (a mechanism that turns no block); which comes first, that side or the
/// sliding model's own limit, is the caller's comparison (`integrate::event::uplift`).
#[derive(Debug, Clone, PartialEq)]
pub struct Side {
    /// The acceleration.
    pub accel: Q,
    /// How the blocks move past it, from the program's multipliers (the mechanism, as the
    /// limit at rest gives it).
    pub mechanism: Vec<Moves>,
    /// The program's forces at this side are degenerate: another mechanism may hold here too
    /// ([`Programs::decide`] decides).
    pub degenerate: bool,
}

impl Side {
    /// Some block of the mechanism turns.
    pub fn turns(&self) -> bool {
        self.mechanism.iter().any(|m| m.omega_rad_s != 0.0)
    }
}

/// What [`Programs::decide`] decides of a side.
#[derive(Debug, Clone, PartialEq)]
pub struct Decided {
    /// Whether the side's mechanism is the only one that holds there.
    pub uniqueness: Uniqueness,
    /// The blocks that turn in every mechanism that holds there; `None` where not decided.
    pub turning_in_every_mechanism: Option<Vec<String>>,
}

impl Decided {
    fn new(uniqueness: Uniqueness, turning_in_every_mechanism: Option<Vec<String>>) -> Decided {
        Decided {
            uniqueness,
            turning_in_every_mechanism,
        }
    }
}

/// The ground accelerations at which the state keeps every block seated.
#[derive(Debug, Clone, PartialEq)]
pub enum Interval {
    /// None: in this state some block turns whatever the ground does.
    Empty {
        /// How the blocks move, from the program's certificate.
        mechanism: Vec<Moves>,
    },
    /// Seated between `lo` and `hi`; `None`: no limit that way (no block moves with the ground,
    /// or abutments hold the wall).
    Between {
        /// Towards -x.
        lo: Option<Side>,
        /// Towards +x.
        hi: Option<Side>,
    },
}

/// The interval of ground accelerations in which `state` keeps every block seated; `None`
/// where `stop` asked the programs to stop (a Ctrl-C, a job's time limit), which they look at
/// at every pivot.
pub fn interval(
    wall: &Wall,
    topo: &Topology,
    state: &State,
    stop: &dyn Fn() -> bool,
) -> Result<Option<Interval>, SimulationError> {
    Ok(Programs::new(wall, topo, state)?.interval(stop))
}

/// The programs of one state, built once for every question asked of it (the watch asks
/// [`Programs::seated_at`] at each stick limit, then [`Programs::interval`] where those do not
/// settle it).
pub struct Programs<'w> {
    wall: &'w Wall,
    topo: &'w Topology,
    /// `None` where no block can move.
    builder: Option<Builder>,
}

impl<'w> Programs<'w> {
    /// The programs of `state`, refused where it has too many movable blocks for them.
    pub fn new(
        wall: &'w Wall,
        topo: &'w Topology,
        state: &State,
    ) -> Result<Programs<'w>, SimulationError> {
        let movable: Vec<usize> = (0..wall.blocks.len())
            .filter(|&i| state.moving[i].is_some())
            .collect();
        if let Some(why) = super::too_large_for_exact(WHAT, movable.len()) {
            return Err(SimulationError::NotApplicable(why));
        }
        let builder = (!movable.is_empty()).then(|| Builder::new(wall, topo, state, movable));
        Ok(Programs {
            wall,
            topo,
            builder,
        })
    }

    /// The state's interval (see [`interval`]); `None` where `stop` said so.
    pub fn interval(&self, stop: &dyn Fn() -> bool) -> Option<Interval> {
        let Some(program) = &self.builder else {
            return Some(Interval::Between { lo: None, hi: None });
        };
        let (wall, topo) = (self.wall, self.topo);
        let mut sides = Vec::with_capacity(2);
        for s in [-1, 1] {
            let p = program.program(s);
            match certify::solve(&p, &program.groups, stop)? {
                // Infeasibility does not depend on the objective: the first side tells.
                Outcome::Infeasible { y } => {
                    return Some(Interval::Empty {
                        mechanism: program.mechanism(wall, topo, &y),
                    })
                }
                Outcome::Unbounded => sides.push(None),
                Outcome::Optimal { value, y, x, .. } => sides.push(Some(Side {
                    accel: -&value * &Q::frac(s, 1),
                    mechanism: program.mechanism(wall, topo, &y),
                    degenerate: degenerate(&p, &x),
                })),
            }
        }
        let hi = sides.pop().expect("two sides");
        let lo = sides.pop().expect("two sides");
        Some(Interval::Between { lo, hi })
    }

    /// Whether `side`, the end of [`Programs::interval`] towards the side of `s` (+1: +x), has
    /// the only mechanism that holds there, decided as the limit at rest's is (docs/rocking-
    /// walls.md, "What it says and what it does not"): a side whose forces are degenerate is
    /// solved again for its basis, and decided in full where it is degenerate in at most
    /// [`DECIDED_ROWS`] rows; with the blocks that turn in every mechanism that holds there,
    /// decided whether or not uniqueness is (`None` beyond [`EVERY_BLOCKS`] movable blocks).
    /// `None` where `stop` said so.
    pub fn decide(
        &self,
        side: &Side,
        s: i128,
        stop: &dyn Fn() -> bool,
    ) -> Result<Option<Decided>, SimulationError> {
        let own = || {
            let turning = side.mechanism.iter().filter(|m| m.omega_rad_s != 0.0);
            Some(turning.map(|m| m.block.clone()).collect())
        };
        // A side comes from a program, so without one there is none to ask about.
        let builder = self.builder.as_ref().filter(|_| side.degenerate);
        let Some(builder) = builder else {
            return Ok(Some(Decided::new(Uniqueness::Unique, own())));
        };
        let program = builder.program(s);
        let Some(outcome) = certify::solve(&program, &builder.groups, stop) else {
            return Ok(None);
        };
        let Outcome::Optimal { x, y, basis, value } = outcome else {
            // The side was solved from this program: the same solve ends the same way.
            return Ok(Some(Decided::new(Uniqueness::Undecided, None)));
        };
        let Some(found) = uniqueness(&program, &x, &y, &basis, DECIDED_ROWS, stop) else {
            return Ok(None);
        };
        if found == Uniqueness::Unique {
            return Ok(Some(Decided::new(found, own())));
        }
        // Which blocks turn in every mechanism is its own question, answered exactly whether
        // or not the mechanism's uniqueness was decided; where it was not and the programs
        // asking meet another mechanism, it is one of several.
        let asked = builder.turning(self.wall, &program, Some((&value, &basis)), &y, stop)?;
        let found = match (found, &asked) {
            (Uniqueness::Undecided, Some((_, true))) => Uniqueness::OneOfSeveral,
            (found, _) => found,
        };
        Ok(Some(Decided::new(found, asked.map(|(turning, _)| turning))))
    }

    /// The blocks that turn in every certificate that the state keeps no block seated whatever
    /// the ground does (where [`Programs::interval`] is [`Interval::Empty`]; each such
    /// certificate is a mechanism, and they are convex as a limit's are): those whose turning,
    /// held by a reaction, lets some ground acceleration keep every block seated. `None` where
    /// not decided (more than [`EVERY_BLOCKS`] movable blocks, `stop` said so) or where the
    /// state keeps the blocks seated after all.
    pub fn turning_whatever_the_ground(
        &self,
        stop: &dyn Fn() -> bool,
    ) -> Result<Option<Vec<String>>, SimulationError> {
        let Some(builder) = &self.builder else {
            return Ok(None);
        };
        let program = builder.program(1);
        match certify::solve(&program, &builder.groups, stop) {
            Some(Outcome::Infeasible { y }) => {
                let asked = builder.turning(self.wall, &program, None, &y, stop)?;
                Ok(asked.map(|(turning, _)| turning))
            }
            _ => Ok(None),
        }
    }

    /// Whether the state is shown to keep every block seated at the ground acceleration
    /// `accel` (m/s2, in the interval's units: a_g / lambda with a vertical component): one
    /// program without an objective (phase 1 of the simplex alone, from a basis that passes
    /// each block's loads down through its base) where [`Programs::interval`] solves two to
    /// their optima. The watch asks it at a stuck cluster's stick limit, where a yes shows
    /// that the interval reaches past the limit that way, which is all the watch needs there.
    /// False where `stop` asked the program to stop or where the answer could not be shown
    /// (the program is infeasible, or round-off): the interval answers then.
    pub fn seated_at(&self, accel: &Q, stop: &dyn Fn() -> bool) -> bool {
        self.builder.as_ref().is_none_or(|builder| {
            certify::feasible(&builder.program_at(accel), &builder.groups, stop)
        })
    }
}

/// What the programs here are for, in refusals.
pub(crate) const WHAT: &str = "the uplift check";

/// The program of a state: columns are unit contact forces (and a_g's two parts), rows each
/// block's horizontal, vertical and moment balances (moments about its centroid).
struct Builder {
    movable: Vec<usize>,
    centroids: Vec<[Q; 2]>,
    /// A's columns, a_g's two parts last.
    columns: Vec<Vec<(usize, Q)>>,
    b: Vec<Q>,
    /// Column of a_g's positive part (its negative part follows).
    ag: usize,
    /// Each block's balances and its base's corner forces, blocks top down: the crash basis
    /// of the state's programs.
    groups: Vec<crash::Group>,
}

impl Builder {
    fn new(wall: &Wall, topo: &Topology, state: &State, movable: Vec<usize>) -> Builder {
        let mut row_of = vec![None; wall.blocks.len()];
        for (k, &i) in movable.iter().enumerate() {
            row_of[i] = Some(ROWS * k);
        }
        let centroids: Vec<[Q; 2]> = wall.blocks.iter().map(centroid).collect();
        let alive = |i: usize| state.moving[i].is_some().then_some(i);
        let mut columns: Vec<Force> = Vec::new();
        for (h, joint) in topo.horizontal.iter().enumerate() {
            let Some(on) = alive(joint.upper.0) else {
                continue;
            };
            let against = match joint.lower {
                Base::Ground => None,
                // A fallen support left with its load.
                Base::Block(BlockId(j)) if !wall.blocks[j].fixed && alive(j).is_none() => continue,
                Base::Block(BlockId(j)) => alive(j),
            };
            // The cone's edges: both where the joint is stuck, the one against the slip where
            // it slips (a slip towards +x meets friction towards -x).
            let edges: &[i128] = match state.slip[h] {
                _ if joint.friction.is_zero() => &[1],
                0 => &[1, -1],
                s if s > 0 => &[-1],
                _ => &[1],
            };
            for x in overlap(wall, joint) {
                for &e in edges {
                    columns.push(Force {
                        on,
                        against,
                        at: [x.clone(), wall.blocks[on].y.clone()],
                        direction: [&joint.friction * &Q::frac(e, 1), Q::one()],
                    });
                }
            }
        }
        let groups = crash_groups(wall, &movable, &columns);
        for (v, joint) in topo.vertical.iter().enumerate() {
            if state.pushes[v] {
                columns.extend(pushes(wall, joint, alive));
            }
        }
        let m = ROWS * movable.len();
        let ag = columns.len();
        let mut a: Vec<Vec<(usize, Q)>> = columns
            .iter()
            .map(|f| {
                let mut column = Vec::with_capacity(2 * ROWS);
                for (o, sign) in [(Some(f.on), 1), (f.against, -1)] {
                    let Some((o, r0)) = o.and_then(|o| Some((o, row_of[o]?))) else {
                        continue;
                    };
                    let e = entries(f, &centroids[o]).into_iter().enumerate();
                    column.extend(e.map(|(k, x)| (r0 + k, &x * &Q::frac(sign, 1))));
                }
                column
            })
            .collect();
        let mut b = vec![Q::zero(); m];
        let (mut plus, mut minus) = (Vec::new(), Vec::new());
        for (k, &i) in movable.iter().enumerate() {
            let mass = &topo.blocks[i].mass_kg;
            let row = ROWS * k;
            match state.moving[i].as_ref().expect("movable") {
                Moving::Ground => {
                    plus.push((row, -mass.clone()));
                    minus.push((row, mass.clone()));
                }
                Moving::At(c) => b[row] = mass * c,
            }
            b[row + 1] = mass * &wall.g_m_s2;
        }
        a.extend([plus, minus]);
        Builder {
            movable,
            centroids,
            columns: a,
            b,
            ag,
            groups,
        }
    }

    /// The program that pushes a_g furthest towards the side of `s` (+1: +x): minimise -s a_g.
    fn program(&self, s: i128) -> Program {
        let mut c = vec![Q::zero(); self.columns.len()];
        c[self.ag] = Q::frac(-s, 1);
        c[self.ag + 1] = Q::frac(s, 1);
        Program::new(self.columns.clone(), self.b.clone(), c)
    }

    /// The program of the balances with a_g fixed at `accel`, without an objective: its
    /// columns moved to the right-hand side.
    fn program_at(&self, accel: &Q) -> Program {
        let mut b = self.b.clone();
        for (row, a) in &self.columns[self.ag] {
            b[*row] = &b[*row] - &(a * accel);
        }
        let columns = self.columns[..self.ag].to_vec();
        Program::new(columns, b, vec![Q::zero(); self.ag])
    }

    /// The blocks that turn in every mechanism of `program` ([`every`]: `optimum` its value and
    /// optimal basis and `y` its multipliers, or `y` its certificate of infeasibility), and
    /// whether the programs asking met a mechanism other than `y`'s; `None` where the state has
    /// more than [`EVERY_BLOCKS`] movable blocks or `stop` said so.
    fn turning(
        &self,
        wall: &Wall,
        program: &Program,
        optimum: Option<(&Q, &[usize])>,
        y: &[Q],
        stop: &dyn Fn() -> bool,
    ) -> Result<Option<(Vec<String>, bool)>, SimulationError> {
        if self.movable.len() > EVERY_BLOCKS {
            return Ok(None);
        }
        let found = every::in_every_mechanism(program, &self.groups, optimum, y, false, stop)?;
        Ok(found.map(|e| {
            let names = (e.turning.into_iter())
                .map(|k| wall.blocks[self.movable[k]].name.clone())
                .collect();
            (names, e.another)
        }))
    }

    /// The mechanism the multipliers of the balances give. A turn about a point that is no
    /// block's corner keeps only its sense: with blocks sliding the multipliers' field mixes
    /// the slip into the turn, and such a point is nowhere a user could find on the wall.
    fn mechanism(&self, wall: &Wall, topo: &Topology, y: &[Q]) -> Vec<Moves> {
        let mut moves = mechanism(wall, topo, &self.movable, &self.centroids, y);
        for m in &mut moves {
            if let Some((sense, point)) = m.how.split_once(" about ") {
                if !point.ends_with("corner") {
                    m.how = sense.to_string();
                }
            }
        }
        moves
    }
}

#[cfg(test)]
mod tests;
