//! Blocks of different columns, or a column's block and a fixed one, that stand apart: the
//! exact model follows the columns while every such pair stays apart, and finds where two meet.
//! This module owns those pairs and the instant they meet.
//!
//! Two rectangles are apart exactly when an edge of one has every corner of the other strictly
//! outside it (the separating axis theorem: for convex polygons an edge's normal separates them
//! whenever anything does). Each pair keeps the edge that separated it last; the signed
//! distances of the other block's four corners from that edge, moved and turned with their
//! bodies, are series along each step like every contact condition, and the first to come down
//! to zero is an event located to round-off. There the pair either has another edge with every
//! corner of the other block outside it by more than the tie tolerance, which it keeps from
//! then on; or, the blocks touching at that instant, an edge every corner of the other block
//! is outside of just after (a corner that slides off the end of a face, or grazes one, and
//! moves away); or none: the blocks meet (a corner on a face, or two corners on each other),
//! and the pair says where: the corner, the face and its normal (`collision` has the impact).

use super::layout::point_series;
use super::modes::Trajectory;
use super::series::{self, Coeffs, TIE, ZERO};
use super::{RockingBody, Watch};
use crate::error::SimulationError;
use crate::topology::{Base, BlockId, Topology};
use crate::wall::Wall;

/// Changes of a pair's separating edge within one step before the run is declared stuck: each
/// needs a corner to cross another block's edge line beside it, a few per pair at most.
const PASSES: usize = 64;

/// Outward normals of a rectangle's edges at rest, edge e running from corner e to corner e + 1
/// (corners counter-clockwise from the bottom left).
const NORMALS: [[f64; 2]; 4] = [[0.0, -1.0], [1.0, 0.0], [0.0, 1.0], [-1.0, 0.0]];

/// A block a pair watches.
struct Piece {
    /// Its output (its place in the wall).
    output: usize,
    /// The body that moves it, with its corners at rest from the middle of that body's base
    /// (m); none: it stays with the ground (held in its column, or fixed).
    body: Option<(usize, [[f64; 2]; 4])>,
    /// Its corners at rest (m), counter-clockwise from the bottom left.
    corners: [[f64; 2]; 4],
    /// Its diagonal (m): the size its distances are measured against.
    size_m: f64,
    /// Whether it is a fixed block (else, without a body, it is held in its column).
    fixed: bool,
}

/// Two blocks that must stay apart, and the edge that separates them: (true: of `b`, its index).
struct Pair {
    a: usize,
    b: usize,
    edge: (bool, usize),
    /// Struck at an impact, and not parted since by more than the tie tolerance.
    struck: bool,
    /// A body of the pair rests leaning on the other block (`lean`): their contact is held,
    /// not watched, until it ends.
    leaning: bool,
    /// The pair's bodies turn in contact (`couple`), this corner of one block on the edge of
    /// the other: the corner is watched along the edge, not across it.
    held: Option<usize>,
    /// The pair's faces lie on each other (`lying`): each end of their overlap is watched
    /// along the face it is on, not across it.
    lies: Option<Lies>,
}

/// Two faces lying on each other: the edge of each block that lies on the other's (`a`'s,
/// then `b`'s), and the ends of their overlap, each a corner of one block (true: of `b`; its
/// index) on the other's edge.
#[derive(Clone, Copy)]
struct Lies {
    edges: [usize; 2],
    ends: [(bool, usize); 2],
}

/// Where two blocks meet: the instant within the step, their outputs and how.
pub(super) type Meet = (f64, (usize, usize), Meeting);

/// Where a pair's blocks stand at an instant (see [`Clearance::set_down`]).
pub(super) enum Seated {
    /// Apart by more than the tie tolerance, this edge keeping them apart by most.
    Apart((bool, usize)),
    /// Upright side by side, a face of each on the other's: the ends of their overlap.
    FaceOnFace(Box<[Touch; 2]>),
    /// Touching otherwise (or inside one another).
    Touching,
}

/// How two blocks meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Meeting {
    /// A corner of one on a face of the other, strictly inside it: the contact.
    Strikes(Touch),
    /// Two corners of one on the face of the other: a face comes down flat on a face. Where
    /// the pair is held in contact (a corner on the face), the contact at the other end of the
    /// faces' overlap, which strikes there.
    Flat(Option<Touch>),
    /// The same where the pair was apart: the contacts at both ends of the faces' overlap,
    /// which strike at once.
    Faces([Touch; 2]),
    /// A corner at an end of the other's face, or none on it: corner meets corner.
    Corners,
}

/// A block of a contact: what moves it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Side {
    /// A body, the middle of its base at rest where its frame starts (m, in the wall's frame).
    Body(usize, [f64; 2]),
    /// A fixed block.
    Fixed,
    /// A block held in its column (a joint above it opened).
    Held,
}

/// A corner of one block on a face of another, where they meet.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Touch {
    /// The block whose corner touches, then the block whose face it touches (outputs).
    pub blocks: [usize; 2],
    pub sides: [Side; 2],
    /// The corner (m, in the wall's frame).
    pub point: [f64; 2],
    /// The face's outward normal, pointing into the corner's block.
    pub normal: [f64; 2],
    /// The size (m) and time (s) scales by which the pair tells a distance between its blocks
    /// from zero ([`Clearance::scales`]): whatever decides on this contact takes them.
    pub scales: (f64, f64),
    /// The pair, for [`Clearance::strike`].
    pub pair: usize,
    /// Which of its block's corners (counter-clockwise from the bottom left) the corner is.
    pub corner: usize,
    /// Which edge of the face's block (edge e from its corner e to e + 1) the face is.
    pub edge: usize,
    /// The pair was struck and has not parted since by more than the tie tolerance: the blocks
    /// stay in contact (the gap an elastic impact opens closes again within round-off).
    pub stays: bool,
}

impl Touch {
    /// The speed along the normal (m/s) the pair tells from round-off: the tie tolerance over
    /// the bodies' shortest time scale.
    pub fn tie_m_s(&self) -> f64 {
        TIE * self.scales.0 / self.scales.1
    }
}

/// The pairs of blocks of a scene that stand apart, and the edge that keeps each apart.
#[derive(Default)]
pub(super) struct Clearance {
    pieces: Vec<Piece>,
    pairs: Vec<Pair>,
    /// Per body, half the width of the base it turns on (m).
    half_bases: Vec<f64>,
}

/// A block's place over a step: its corners and its rotation's sine and cosine, as series.
struct Placed {
    corners: [[Coeffs; 2]; 4],
    sin: Coeffs,
    cos: Coeffs,
}

/// The same at one instant.
struct At {
    corners: [[f64; 2]; 4],
    sin: f64,
    cos: f64,
}

impl Placed {
    fn at(&self, tau: f64) -> At {
        At {
            corners: self.corners.map(|c| c.map(|x| series::eval(&x, tau))),
            sin: series::eval(&self.sin, tau),
            cos: series::eval(&self.cos, tau),
        }
    }
}

/// The distances of `other`'s corners from edge e of `own`, outward positive: each corner's
/// offset from the edge's first corner projected on the edge's normal, turned with `own`
/// (a point r goes to R r, R the clockwise rotation by theta).
fn distances(own: &Placed, e: usize, other: &Placed) -> [Coeffs; 4] {
    let [n0x, n0y] = NORMALS[e];
    let nx = series::add(&series::scaled(&own.cos, n0x), &own.sin, n0y);
    let ny = series::add(&series::scaled(&own.sin, -n0x), &own.cos, n0y);
    let c = &own.corners[e];
    other.corners.map(|p| {
        let rx = series::add(&p[0], &c[0], -1.0);
        let ry = series::add(&p[1], &c[1], -1.0);
        series::add(&series::product(&rx, &nx), &series::product(&ry, &ny), 1.0)
    })
}

/// How far `other`'s corner j lies along edge e of `own`, from the edge's first corner.
fn along(own: &Placed, e: usize, other: &Placed, j: usize) -> Coeffs {
    let [n0x, n0y] = NORMALS[e];
    let (t0x, t0y) = (-n0y, n0x);
    let tx = series::add(&series::scaled(&own.cos, t0x), &own.sin, t0y);
    let ty = series::add(&series::scaled(&own.sin, -t0x), &own.cos, t0y);
    let (c, p) = (&own.corners[e], &other.corners[j]);
    let rx = series::add(&p[0], &c[0], -1.0);
    let ry = series::add(&p[1], &c[1], -1.0);
    series::add(&series::product(&rx, &tx), &series::product(&ry, &ty), 1.0)
}

/// How a corner met at the line of a face crosses that line and moves in from the face's
/// nearer end: the order and coefficient of the first term of each distance (outside the line;
/// in from the end) that is not zero to the tie.
#[derive(Debug, Clone, Copy)]
struct Crossing {
    across: Option<(usize, f64)>,
    inward: Option<(usize, f64)>,
}

impl Crossing {
    /// Of the contacts found where two corners meet (`all`), the one that strikes: the
    /// corner that crosses its face's line first (at the lowest order, then the fastest; the
    /// impact stops that approach, any other is slower) and, of those that cross alike, the
    /// one that moves in from its face's end first (it lies on that face just after; the other
    /// corners only graze the ends of theirs). None where that leaves a tie.
    fn first(all: &[Crossing]) -> Option<usize> {
        let earliest = |among: Vec<usize>, term: fn(&Crossing) -> Option<(usize, f64)>| {
            let terms = || among.iter().filter_map(|&c| term(&all[c]));
            let order = terms().map(|(k, _)| k).min();
            let size = (terms().filter(|&(k, _)| Some(k) == order))
                .fold(0.0, |m: f64, (_, x)| m.max(x.abs()));
            let alike = |(k, x): (usize, f64)| Some(k) == order && size - x.abs() <= TIE * size;
            (among.iter().copied())
                .filter(|&c| term(&all[c]).is_some_and(alike))
                .collect::<Vec<_>>()
        };
        let crossing = earliest((0..all.len()).collect(), |c| c.across);
        match earliest(crossing, |c| c.inward).as_slice() {
            [one] => Some(*one),
            _ => None,
        }
    }
}

/// Edge e of a placed block at an instant, as points are measured against it.
struct Line {
    /// Its first corner (m).
    c0: [f64; 2],
    /// Its outward normal.
    n: [f64; 2],
    /// Its direction from the first corner to the second.
    t: [f64; 2],
    /// Its length (m).
    length: f64,
}

impl Line {
    fn of(own: &At, e: usize) -> Line {
        let (c0, c1) = (own.corners[e], own.corners[(e + 1) % 4]);
        let length = (c1[0] - c0[0]).hypot(c1[1] - c0[1]);
        Line {
            c0,
            n: normal(own, e),
            t: [(c1[0] - c0[0]) / length, (c1[1] - c0[1]) / length],
            length,
        }
    }

    /// How far point p stands outside the edge's line, and how far along it from the first
    /// corner (m).
    fn place(&self, p: &[f64; 2]) -> (f64, f64) {
        let r = [p[0] - self.c0[0], p[1] - self.c0[1]];
        (
            r[0] * self.n[0] + r[1] * self.n[1],
            r[0] * self.t[0] + r[1] * self.t[1],
        )
    }
}

/// The outward normal of edge e of `own`, turned with it, at one instant.
fn normal(own: &At, e: usize) -> [f64; 2] {
    let [n0x, n0y] = NORMALS[e];
    [
        own.cos * n0x + own.sin * n0y,
        -own.sin * n0x + own.cos * n0y,
    ]
}

/// The least distance of `other`'s corners outside edge e of `own`, at one instant.
fn least_outside(own: &At, e: usize, other: &At) -> f64 {
    let n = normal(own, e);
    let c = own.corners[e];
    other
        .corners
        .iter()
        .map(|p| (p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1])
        .fold(f64::INFINITY, f64::min)
}

/// The edge of either block that keeps them apart by most, with that margin (m).
fn widest(a: &At, b: &At) -> ((bool, usize), f64) {
    (0..8)
        .map(|k| {
            let of_b = k >= 4;
            let d = if of_b {
                least_outside(b, k % 4, a)
            } else {
                least_outside(a, k % 4, b)
            };
            ((of_b, k % 4), d)
        })
        .fold(((false, 0), f64::NEG_INFINITY), |best, x| {
            if x.1 > best.1 {
                x
            } else {
                best
            }
        })
}

impl Clearance {
    /// The pairs of a wall's columns (one watch each): every block a body moves against every
    /// block of another column and every fixed block. Blocks of one column, and a column's
    /// blocks and the fixed blocks it stands on (its plinth), are the column model's own.
    pub(super) fn of<'w>(
        wall: &Wall,
        topo: &Topology,
        watches: impl IntoIterator<Item = &'w Watch>,
    ) -> Clearance {
        let watches: Vec<&Watch> = watches.into_iter().collect();
        let n = wall.blocks.len();
        let mut column = vec![None; n];
        let mut body = vec![None; n];
        for (i, w) in watches.iter().enumerate() {
            for o in &w.outputs {
                column[o.block] = Some(i);
                if o.moving {
                    body[o.block] = Some((i, o.x0, o.y0));
                }
            }
        }
        let pieces: Vec<Piece> = (0..n)
            .filter(|&k| column[k].is_some() || wall.blocks[k].fixed)
            .map(|k| {
                let b = &wall.blocks[k];
                let (x, y) = (b.x.to_f64(), b.y.to_f64());
                let (w, h) = (b.width.to_f64(), b.height.to_f64());
                let box_of =
                    |x0: f64, y0: f64| [[x0, y0], [x0 + w, y0], [x0 + w, y0 + h], [x0, y0 + h]];
                Piece {
                    output: k,
                    body: body[k].map(|(i, x0, y0)| (i, box_of(x0 - w / 2.0, y0))),
                    corners: box_of(x, y),
                    size_m: w.hypot(h),
                    fixed: b.fixed,
                }
            })
            .collect();
        // (column, fixed block it stands on)
        let plinths: Vec<(usize, usize)> = topo
            .horizontal
            .iter()
            .filter_map(|j| match (column[j.upper.0], j.lower) {
                (Some(i), Base::Block(BlockId(l))) if wall.blocks[l].fixed => Some((i, l)),
                _ => None,
            })
            .collect();
        let mut pairs = Vec::new();
        for a in 0..pieces.len() {
            for b in a + 1..pieces.len() {
                let (pa, pb) = (&pieces[a], &pieces[b]);
                let same = column[pa.output].is_some() && column[pa.output] == column[pb.output];
                let on_plinth = [(pa.output, pb.output), (pb.output, pa.output)]
                    .iter()
                    .any(|&(k, l)| column[k].is_some_and(|i| plinths.contains(&(i, l))));
                if !same && !on_plinth && (pa.body.is_some() || pb.body.is_some()) {
                    pairs.push(Pair {
                        a,
                        b,
                        edge: (false, 0),
                        struck: false,
                        leaning: false,
                        held: None,
                        lies: None,
                    });
                }
            }
        }
        Clearance {
            pieces,
            pairs,
            half_bases: watches.iter().map(|w| w.pivot_half_base_m()).collect(),
        }
    }

    /// No pair to watch.
    pub(super) fn is_empty(&self) -> bool {
        self.pairs.is_empty()
    }

    /// Whether a block of body i is kept apart from another block: what it may run into.
    pub(super) fn watches(&self, i: usize) -> bool {
        let moves = |p: usize| self.pieces[p].body.is_some_and(|(b, _)| b == i);
        self.pairs.iter().any(|pair| moves(pair.a) || moves(pair.b))
    }

    /// Piece p over the step, its body on `trajs` (none where its body lies fallen).
    fn placed(
        &self,
        p: usize,
        bodies: &[RockingBody],
        trajs: &[Option<&Trajectory>],
    ) -> Option<Placed> {
        let piece = &self.pieces[p];
        let Some((i, frame)) = piece.body else {
            return Some(Placed {
                corners: piece.corners.map(|c| c.map(series::constant)),
                sin: ZERO,
                cos: series::constant(1.0),
            });
        };
        let traj = trajs[i]?;
        let mut turn = (ZERO, ZERO);
        let mut corners = [[ZERO; 2]; 4];
        for (j, corner) in corners.iter_mut().enumerate() {
            let (d, t) = point_series(
                &bodies[i],
                traj,
                self.half_bases[i],
                frame[j][0],
                frame[j][1],
            );
            *corner = [
                series::plus(&d[0], piece.corners[j][0]),
                series::plus(&d[1], piece.corners[j][1]),
            ];
            turn = t;
        }
        Some(Placed {
            corners,
            sin: turn.0,
            cos: turn.1,
        })
    }

    /// The shortest time scale of the bodies that move pair k's blocks (s).
    fn time_scale_s(&self, k: usize, bodies: &[RockingBody]) -> f64 {
        let pair = &self.pairs[k];
        [pair.a, pair.b]
            .iter()
            .filter_map(|&p| self.pieces[p].body.map(|(i, _)| bodies[i].time_scale_s()))
            .fold(f64::INFINITY, f64::min)
    }

    /// The size (m) and time (s) scales by which a distance between pair k's blocks is told
    /// from zero in the sense of the tie ([`series::leading`]): every decision on that
    /// distance, here or in the engine, takes these, or two of them may read one contact
    /// differently (one finding it closing, the other opening, at one instant).
    pub(super) fn scales(&self, k: usize, bodies: &[RockingBody]) -> (f64, f64) {
        (self.size_m(k), self.time_scale_s(k, bodies))
    }

    /// The larger of pair k's blocks' sizes (m).
    fn size_m(&self, k: usize) -> f64 {
        let pair = &self.pairs[k];
        self.pieces[pair.a].size_m.max(self.pieces[pair.b].size_m)
    }

    /// The tie tolerance of pair k's distances (m).
    fn tie_m(&self, k: usize) -> f64 {
        TIE * self.size_m(k)
    }

    /// Each pair's edge from where the bodies start: the one that keeps it apart by most. Two
    /// blocks moved by bodies that stand side by side, upright, their faces touching (the
    /// columns let only blocks alone in their columns do) lie on each other from the start:
    /// the ends of their overlap are returned. An error names two blocks that no edge keeps
    /// apart by more than the tie tolerance otherwise (they touch, or lie inside one another).
    pub(super) fn start(
        &mut self,
        bodies: &[RockingBody],
        trajs: &[Option<&Trajectory>],
        names: &[String],
    ) -> Result<Vec<[Touch; 2]>, SimulationError> {
        let mut lying = Vec::new();
        for k in 0..self.pairs.len() {
            match self.seated(k, bodies, trajs) {
                None => {}
                Some(Seated::FaceOnFace(ends)) => {
                    self.lie(k, Some(&ends));
                    lying.push(*ends);
                }
                Some(Seated::Apart(edge)) => self.pairs[k].edge = edge,
                Some(Seated::Touching) => {
                    let (a, b) = (self.pairs[k].a, self.pairs[k].b);
                    return Err(SimulationError::NotApplicable(format!(
                        "{} and {} touch (or lie inside one another) where the run starts: the \
                         exact rocking model follows blocks of different columns only while they \
                         stand apart; run this wall sliding exactly (--model slide) or on time \
                         stepping (--model slide-rock --method moreau --dt S)",
                        names[self.pieces[a].output], names[self.pieces[b].output]
                    )));
                }
            }
        }
        Ok(lying)
    }

    /// Pair k's blocks where the bodies' trajectories `trajs` start (none where a body of theirs
    /// lies fallen): apart by more than the tie tolerance (the edge that keeps them apart by
    /// most), upright side by side with a face of each on the other's (the ends of their
    /// overlap), or touching otherwise.
    fn seated(
        &self,
        k: usize,
        bodies: &[RockingBody],
        trajs: &[Option<&Trajectory>],
    ) -> Option<Seated> {
        let (pa, pb) = (
            self.placed(self.pairs[k].a, bodies, trajs)?,
            self.placed(self.pairs[k].b, bodies, trajs)?,
        );
        let (at_a, at_b) = (pa.at(0.0), pb.at(0.0));
        let (edge, margin) = widest(&at_a, &at_b);
        Some(if margin > self.tie_m(k) {
            Seated::Apart(edge)
        } else if let Some(ends) = self.face_on_face(k, (&at_a, &at_b), bodies) {
            Seated::FaceOnFace(Box::new(ends))
        } else {
            Seated::Touching
        })
    }

    /// The pair of blocks `blocks` (outputs, either order), and the bodies that move its blocks
    /// (in the pair's order; none for a block that stays with the ground).
    pub(super) fn pair_of(&self, blocks: (usize, usize)) -> Option<(usize, [Option<usize>; 2])> {
        let outputs = |pair: &Pair| (self.pieces[pair.a].output, self.pieces[pair.b].output);
        let k = self.pairs.iter().position(|pair| {
            let (a, b) = outputs(pair);
            (a, b) == blocks || (b, a) == blocks
        })?;
        let body = |p: usize| self.pieces[p].body.map(|(i, _)| i);
        Some((k, [body(self.pairs[k].a), body(self.pairs[k].b)]))
    }

    /// Pair k's blocks, both bodies set down seated where `trajs` start, as [`Clearance::start`]
    /// finds a pair (none where a body lies fallen): lying face on face from here, or apart,
    /// watched from the edge that keeps them apart by most; whatever the pair was held in
    /// (a couple, faces lying on each other) has ended. Where they touch otherwise nothing is
    /// changed and none is returned.
    pub(super) fn set_down(
        &mut self,
        k: usize,
        bodies: &[RockingBody],
        trajs: &[Option<&Trajectory>],
    ) -> Option<Seated> {
        let seated = self.seated(k, bodies, trajs)?;
        match &seated {
            Seated::Touching => return None,
            Seated::FaceOnFace(ends) => self.lie(k, Some(ends)),
            Seated::Apart(edge) => {
                self.lie(k, None);
                self.pairs[k].edge = *edge;
            }
        }
        (self.pairs[k].held, self.pairs[k].leaning) = (None, false);
        Some(seated)
    }

    /// Pair k's blocks (placed as `at_a` and `at_b`), both moved by bodies, upright side by
    /// side with a face of each on the other's along a height: the contacts at the ends of
    /// that overlap, the lower then the upper, each the corner of the block whose end of the
    /// face is nearer the overlap's middle on the other's face; none otherwise.
    fn face_on_face(
        &self,
        k: usize,
        (at_a, at_b): (&At, &At),
        bodies: &[RockingBody],
    ) -> Option<[Touch; 2]> {
        let pair = &self.pairs[k];
        let tie = self.tie_m(k);
        let moved = |p: usize| self.pieces[p].body.is_some();
        if !moved(pair.a) || !moved(pair.b) || at_a.sin != 0.0 || at_b.sin != 0.0 {
            return None;
        }
        // (piece, corners) on the left, then on the right.
        let (a, b) = ((pair.a, &at_a.corners), (pair.b, &at_b.corners));
        let [left, right] = if (a.1[1][0] - b.1[0][0]).abs() <= tie {
            [a, b]
        } else if (b.1[1][0] - a.1[0][0]).abs() <= tie {
            [b, a]
        } else {
            return None;
        };
        let (bottoms, tops) = ([left.1[0][1], right.1[0][1]], [left.1[3][1], right.1[3][1]]);
        if tops[0].min(tops[1]) - bottoms[0].max(bottoms[1]) <= tie {
            return None;
        }
        // The right block's corner j on the left one's right face (edge 1, normal +x), or the
        // left block's corner j on the right one's left face (edge 3, normal -x).
        let end = |on_left: bool, j: usize| {
            let t = match on_left {
                true => self.contact(k, [right.0, left.0], (j, 1), right.1[j], [1.0, 0.0], bodies),
                false => self.contact(k, [left.0, right.0], (j, 3), left.1[j], [-1.0, 0.0], bodies),
            };
            Touch { stays: true, ..t }
        };
        Some([
            match bottoms[1] >= bottoms[0] {
                true => end(true, 0),
                false => end(false, 1),
            },
            match tops[1] <= tops[0] {
                true => end(true, 3),
                false => end(false, 2),
            },
        ])
    }

    /// The first instant within (from, h] at which a corner reaches the edge that keeps its
    /// pair apart, and the pair.
    fn first(
        &self,
        placed: &[Option<Placed>],
        bodies: &[RockingBody],
        from: f64,
        h: f64,
    ) -> Option<(f64, usize)> {
        let mut best: Option<(f64, usize)> = None;
        for (k, pair) in self.pairs.iter().enumerate() {
            let (Some(pa), Some(pb), false) = (&placed[pair.a], &placed[pair.b], pair.leaning)
            else {
                continue;
            };
            let (scale, ts) = self.scales(k, bodies);
            let mut consider = |g: &Coeffs| {
                let g = if from > 0.0 {
                    series::shifted(g, from)
                } else {
                    *g
                };
                if let Some(x) = series::first_fall(&g, scale, ts, h - from) {
                    if best.is_none_or(|(b, _)| from + x < b) {
                        best = Some((from + x, k));
                    }
                }
            };
            if let Some(lies) = &pair.lies {
                // Faces on each other: where an end of the overlap reaches an end of the face
                // it is on.
                for end in lies.ends {
                    for x in self.along_ends(pair, lies, end, pa, pb) {
                        consider(&x);
                    }
                }
                continue;
            }
            let (of_b, e) = pair.edge;
            let (own, other) = if of_b { (pb, pa) } else { (pa, pb) };
            // A corner held on the edge stays on the edge's line: where it reaches either end.
            let ends = pair.held.map(|j| {
                let [p0, p1] = [e, (e + 1) % 4]
                    .map(|c| self.pieces[if of_b { pair.b } else { pair.a }].corners[c]);
                let length = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
                let x = along(own, e, other, j);
                [x, series::plus(&series::scaled(&x, -1.0), length)]
            });
            let gaps = distances(own, e, other);
            let gaps = (gaps.iter().enumerate())
                .filter(|(c, _)| pair.held != Some(*c))
                .map(|(_, g)| g)
                .chain(ends.iter().flatten());
            for g in gaps {
                consider(g);
            }
        }
        best
    }

    /// How far the corner of an end of lying faces (`end`) lies along the face it is on from
    /// that face's first corner, and from its second: both stay positive while the end lies
    /// on the face.
    fn along_ends(
        &self,
        pair: &Pair,
        lies: &Lies,
        (of_b, j): (bool, usize),
        pa: &Placed,
        pb: &Placed,
    ) -> [Coeffs; 2] {
        let (corner, face, piece) = match of_b {
            true => (pb, pa, pair.a),
            false => (pa, pb, pair.b),
        };
        let e = lies.edges[usize::from(!of_b)];
        let [p0, p1] = [e, (e + 1) % 4].map(|c| self.pieces[piece].corners[c]);
        let length = (p1[0] - p0[0]).hypot(p1[1] - p0[1]);
        let x = along(face, e, corner, j);
        [x, series::plus(&series::scaled(&x, -1.0), length)]
    }

    /// An edge of either block of pair k with every corner of the other block outside it
    /// just after tau, where the blocks touch at tau: each corner's distance from it is
    /// outside by more than the tie tolerance, or within it and growing (its first term that
    /// is not zero in the sense of the tie positive). The blocks touch without meeting: a
    /// corner that slides off the end of a face, or grazes a corner, and moves away. Of
    /// several, the one that keeps them apart by most at tau.
    fn opening(
        &self,
        k: usize,
        (pa, pb): (&Placed, &Placed),
        tau: f64,
        bodies: &[RockingBody],
    ) -> Option<(bool, usize)> {
        let (scale, ts) = self.scales(k, bodies);
        let (at_a, at_b) = (pa.at(tau), pb.at(tau));
        (0..8)
            .filter_map(|m| {
                let (of_b, e) = (m >= 4, m % 4);
                let (own, other, at_own, at_other) = if of_b {
                    (pb, pa, &at_b, &at_a)
                } else {
                    (pa, pb, &at_a, &at_b)
                };
                distances(own, e, other)
                    .iter()
                    .all(|g| series::sign_after(&series::shifted(g, tau), scale, ts) > 0)
                    .then(|| ((of_b, e), least_outside(at_own, e, at_other)))
            })
            .fold(None, |best: Option<((bool, usize), f64)>, x| match best {
                Some(b) if b.1 >= x.1 => Some(b),
                _ => Some(x),
            })
            .map(|(edge, _)| edge)
    }

    /// What moves piece p.
    fn side(&self, p: usize) -> Side {
        let piece = &self.pieces[p];
        match piece.body {
            Some((i, frame)) => Side::Body(
                i,
                [
                    piece.corners[0][0] - frame[0][0],
                    piece.corners[0][1] - frame[0][1],
                ],
            ),
            None if piece.fixed => Side::Fixed,
            None => Side::Held,
        }
    }

    /// The contact of pair k where corner `j` of piece `of` lies on the face (`edge`) of piece
    /// `on`, at `point`, the face's normal `normal`.
    fn contact(
        &self,
        k: usize,
        [of, on]: [usize; 2],
        (j, edge): (usize, usize),
        point: [f64; 2],
        normal: [f64; 2],
        bodies: &[RockingBody],
    ) -> Touch {
        Touch {
            pair: k,
            corner: j,
            edge,
            stays: false,
            blocks: [self.pieces[of].output, self.pieces[on].output],
            sides: [self.side(of), self.side(on)],
            point,
            normal,
            scales: self.scales(k, bodies),
        }
    }

    /// Where an end of pair k's lying faces reaches an end of the face it is on, at tau on the
    /// placed blocks `pa` and `pb`, and goes past it just after (an end that only touches the
    /// end of its face and comes back, its distance from there growing again, stays: none):
    /// that end passes to the face's corner there, on the other block's face (the faces slide
    /// along each other), and the two ends are returned; where the new end is the other end's
    /// corner, the overlap is gone, and the faces slide off each other corner on corner.
    fn slides(
        &self,
        k: usize,
        (pa, pb): (&Placed, &Placed),
        tau: f64,
        bodies: &[RockingBody],
    ) -> Option<Meeting> {
        let pair = &self.pairs[k];
        let lies = pair.lies.expect("lying faces");
        let piece = |of_b: bool| if of_b { pair.b } else { pair.a };
        let (scale, ts) = self.scales(k, bodies);
        let (at_a, at_b) = (&pa.at(tau), &pb.at(tau));
        // The end nearest an end of its face of those that go past it, and the corner of the
        // face there.
        let mut nearest: Option<(f64, usize, (bool, usize))> = None;
        for (n, &(of_b, j)) in lies.ends.iter().enumerate() {
            let e = lies.edges[usize::from(!of_b)];
            let gaps = self.along_ends(pair, &lies, (of_b, j), pa, pb);
            for (gap, c) in gaps.iter().zip([e, (e + 1) % 4]) {
                let past = series::sign_after(&series::shifted(gap, tau), scale, ts) < 0;
                let size = series::eval(gap, tau).abs();
                if past && nearest.is_none_or(|(d, ..)| size < d) {
                    nearest = Some((size, n, (!of_b, c)));
                }
            }
        }
        let (_, n, new) = nearest?;
        let mut ends = lies.ends;
        ends[n] = new;
        if ends[0] == ends[1] {
            return Some(Meeting::Corners);
        }
        Some(Meeting::Faces(ends.map(|(of_b, j)| {
            let (corner, face) = if of_b { (at_b, at_a) } else { (at_a, at_b) };
            let e = lies.edges[usize::from(!of_b)];
            let pieces = [piece(of_b), piece(!of_b)];
            let t = self.contact(
                k,
                pieces,
                (j, e),
                corner.corners[j],
                normal(face, e),
                bodies,
            );
            Touch { stays: true, ..t }
        })))
    }

    /// How pair k meets at tau, its blocks placed as `pa` and `pb` ([`Clearance::on_edge`]);
    /// where that finds no corner strictly inside the edge that kept them apart and the pair is
    /// not held in contact, the contacts they strike at elsewhere ([`Clearance::elsewhere`]).
    fn touch(
        &self,
        k: usize,
        (pa, pb): (&Placed, &Placed),
        tau: f64,
        bodies: &[RockingBody],
    ) -> Meeting {
        let ats = (&pa.at(tau), &pb.at(tau));
        match self.on_edge(k, ats.0, ats.1, bodies) {
            Meeting::Corners if self.pairs[k].held.is_none() => self
                .elsewhere(k, ((pa, pb), ats), tau, bodies)
                .unwrap_or(Meeting::Corners),
            meeting => meeting,
        }
    }

    /// Where pair k's blocks strike at tau (placed as `pa` and `pb`, there `at_a` and `at_b`)
    /// when the corner that reached the line of the edge that kept them apart lies within the
    /// tie tolerance of an end of that edge, or beyond it (the line crossed past the face
    /// touches nothing there).
    /// A contact is a corner of either block on the line of a face of the other and between the
    /// face's ends (each within the tie tolerance) that, just after, goes across the line and
    /// lies between the ends (the first terms of its distances from the line and from each end
    /// that are not zero in the sense of the tie: negative, positive): where two corners meet,
    /// the one that moves in along the other's face, not the one that goes past its end; and of
    /// a corner's faces so met, the one whose line it crosses last. One such contact strikes;
    /// two that are the ends of two faces' overlap (both corners of one block, ending one of its
    /// faces, on a face of the other, or a corner of each on the other's face ending the face
    /// the other corner lies on) meet as faces; of any other set (corners at one point, each on
    /// the other's faces), the one [`Crossing::first`] picks strikes, and where it picks none,
    /// none does (corner on corner). Where no contact is found, a corner at the end of a face,
    /// that goes across the face's line before it moves out past the end (its distance from the
    /// end zero to the tie until an order above the crossing's), strikes that face if it lies
    /// inside the face at the instant and no other such corner does (the top corners of two
    /// blocks of one height, one tilting onto the other: its corner lies h (1 - cos theta) below
    /// the other's, within any tie, and the other's corner beyond the end of its face).
    fn elsewhere(
        &self,
        k: usize,
        ((pa, pb), (at_a, at_b)): ((&Placed, &Placed), (&At, &At)),
        tau: f64,
        bodies: &[RockingBody],
    ) -> Option<Meeting> {
        let pair = &self.pairs[k];
        let ((scale, ts), tie) = (self.scales(k, bodies), self.tie_m(k));
        // Each contact's face (true: of b; its edge), corner, distance from the face's line
        // (m), contact, and how its corner crosses the line and moves in from the nearer end.
        type Found = ((bool, usize), usize, f64, Touch, Crossing);
        let mut found: Vec<Found> = Vec::new();
        // Corners that cross a face's line at an end they do not move in from (to the tie), and
        // leave later if at all, with their distance inside the face from that end (m).
        let mut at_ends: Vec<(Touch, f64)> = Vec::new();
        for (of_b, e) in (0..8).map(|m| (m >= 4, m % 4)) {
            let (face, corner, at_face, at_corner, pieces) = match of_b {
                true => (pb, pa, at_b, at_a, [pair.a, pair.b]),
                false => (pa, pb, at_a, at_b, [pair.b, pair.a]),
            };
            let line = Line::of(at_face, e);
            let (n, length) = (line.n, line.length);
            let gaps = distances(face, e, corner);
            let after = |c: &Coeffs| series::sign_after(&series::shifted(c, tau), scale, ts);
            let lead = |c: &Coeffs| series::leading(&series::shifted(c, tau), scale, ts);
            let off = |p: &[f64; 2]| line.place(p).0;
            // A block touching a face lies wholly outside its line (a corner inside it, the
            // contact strictly within the face, would be inside the other block); at the face's
            // end, a block that reaches inside the line touches the other face there instead.
            if at_corner.corners.iter().any(|p| off(p) < -tie) {
                continue;
            }
            for (j, p) in at_corner.corners.iter().enumerate() {
                let (d, x) = line.place(p);
                if d.abs() > tie || x < -tie || x > length + tie || after(&gaps[j]) >= 0 {
                    continue;
                }
                let from_start = along(face, e, corner, j);
                let from_end = series::plus(&series::scaled(&from_start, -1.0), length);
                let (start, end) = (lead(&from_start), lead(&from_end));
                let across = lead(&gaps[j]);
                let moves_in = |l: Option<(usize, f64)>| l.is_some_and(|(_, v)| v > 0.0);
                // It goes across the line before it leaves the end, if it does.
                let stays = |l: Option<(usize, f64)>| {
                    l.is_none_or(|(o, v)| v > 0.0 || across.is_some_and(|(a, _)| o > a))
                };
                if !stays(start) || !stays(end) {
                    continue;
                }
                let touch = self.contact(k, pieces, (j, e), *p, n, bodies);
                if !moves_in(start) || !moves_in(end) {
                    at_ends.push((touch, x.min(length - x)));
                } else {
                    let inward = if x < 0.5 * length {
                        from_start
                    } else {
                        from_end
                    };
                    let crossing = Crossing {
                        across,
                        inward: lead(&inward),
                    };
                    found.push(((of_b, e), j, d, touch, crossing));
                }
            }
        }
        if found.is_empty() {
            let mut inside = at_ends.iter().filter(|(_, x)| *x > 0.0);
            return match (inside.next(), inside.next()) {
                (Some((touch, _)), None) => Some(Meeting::Strikes(*touch)),
                _ => None,
            };
        }
        // A corner at the other block's corner lies between the ends of both its faces: it
        // goes in across the line it crosses last, the one it lies furthest outside of.
        let outermost =
            |&(f, j, d, ..): &Found| !found.iter().any(|g| g.0 .0 == f.0 && g.1 == j && g.2 > d);
        let found: Vec<_> = found.iter().filter(|c| outermost(c)).collect();
        let ends = |c: usize, e: usize| c == e || c == (e + 1) % 4;
        match found.as_slice() {
            [(_, _, _, t, _)] => return Some(Meeting::Strikes(*t)),
            [((f, e), j, _, s, _), ((g, m), i, _, t, _)] => {
                let same = f == g && e == m && (*i == (j + 1) % 4 || *j == (i + 1) % 4);
                // Corners of each at one point end no overlap of faces.
                let apart = (s.point[0] - t.point[0]).hypot(s.point[1] - t.point[1]) > tie;
                let crossed = f != g && ends(*j, *m) && ends(*i, *e) && apart;
                if same || crossed {
                    return Some(Meeting::Faces([*s, *t]));
                }
            }
            _ => {}
        }
        let first = Crossing::first(&found.iter().map(|c| c.4).collect::<Vec<_>>())?;
        Some(Meeting::Strikes(found[first].3))
    }

    /// How pair k meets at the instant its blocks are `at_a` and `at_b`: the one corner on
    /// the edge that kept them apart, strictly inside that edge; else two corners on it (a
    /// face on a face), or the corner at an end of the edge (on a corner). Where a face comes
    /// down flat on the face a held corner is on, also the edge that keeps the pair apart from
    /// there: the corner's block's own face, where the contact at the other end of the faces'
    /// overlap is the other block's corner on it.
    fn on_edge(&self, k: usize, at_a: &At, at_b: &At, bodies: &[RockingBody]) -> Meeting {
        let pair = &self.pairs[k];
        let tie = self.tie_m(k);
        let ((of_b, e), [own, other]) = (
            pair.edge,
            if pair.edge.0 {
                [pair.b, pair.a]
            } else {
                [pair.a, pair.b]
            },
        );
        let (face, corner) = if of_b { (at_b, at_a) } else { (at_a, at_b) };
        let n = normal(face, e);
        let (c0, c1) = (face.corners[e], face.corners[(e + 1) % 4]);
        let along = [c1[0] - c0[0], c1[1] - c0[1]];
        let length = along[0].hypot(along[1]);
        let on: Vec<(usize, &[f64; 2])> = corner
            .corners
            .iter()
            .enumerate()
            .filter(|(_, p)| (p[0] - c0[0]) * n[0] + (p[1] - c0[1]) * n[1] <= tie)
            .collect();
        let x = |p: &[f64; 2]| ((p[0] - c0[0]) * along[0] + (p[1] - c0[1]) * along[1]) / length;
        let contact =
            |pieces, at, point, normal| self.contact(k, pieces, at, point, normal, bodies);
        let (j, point) = match on.as_slice() {
            [one] => *one,
            [] => return Meeting::Corners,
            _ => {
                // Each end of the faces' overlap is a corner of the corner's block where it
                // lies inside the face, else the face's end beyond which it lies, on the face of
                // the corner's block between its two corners on the face (`h` the other).
                let end = |(j, p): (usize, &[f64; 2]), h: usize| {
                    let x = x(p);
                    if x > tie && x < length - tie {
                        return contact([other, own], (j, e), *p, n);
                    }
                    let end = if x >= length - tie { (e + 1) % 4 } else { e };
                    let m = if j == (h + 1) % 4 { h } else { j };
                    contact([own, other], (end, m), face.corners[end], normal(corner, m))
                };
                // A held corner stays inside the face: the other end strikes.
                if let Some(h) = pair.held {
                    return match on.iter().find(|(c, _)| *c != h) {
                        Some(&other_end) => Meeting::Flat(Some(end(other_end, h))),
                        None => Meeting::Flat(None),
                    };
                }
                let [a, b] = on.as_slice() else {
                    return Meeting::Flat(None);
                };
                let ends = [end(*a, b.0), end(*b, a.0)];
                // Both beyond one end of the face: the blocks touch corner on corner.
                if ends[0].point == ends[1].point {
                    return Meeting::Corners;
                }
                return Meeting::Faces(ends);
            }
        };
        let x = x(point);
        if x <= tie || x >= length - tie {
            return Meeting::Corners;
        }
        Meeting::Strikes(contact([other, own], (j, e), *point, n))
    }

    /// The least distance of pair k's blocks outside the edge that keeps them apart, at tau.
    fn gap(&self, k: usize, pa: &Placed, pb: &Placed, tau: f64) -> f64 {
        let (of_b, e) = self.pairs[k].edge;
        let (at_a, at_b) = (pa.at(tau), pb.at(tau));
        if of_b {
            least_outside(&at_b, e, &at_a)
        } else {
            least_outside(&at_a, e, &at_b)
        }
    }

    /// How far the corner of `t` stands outside the face of `t` at tau (m), the blocks of pair
    /// k placed as `pa` and `pb`.
    fn end_gap(&self, k: usize, t: &Touch, (pa, pb): (&Placed, &Placed), tau: f64) -> f64 {
        let (at_a, at_b) = (pa.at(tau), pb.at(tau));
        let (face, corner) = match self.pieces[self.pairs[k].a].output == t.blocks[1] {
            true => (&at_a, &at_b),
            false => (&at_b, &at_a),
        };
        let (n, c, p) = (
            normal(face, t.edge),
            face.corners[t.edge],
            corner.corners[t.corner],
        );
        (p[0] - c[0]) * n[0] + (p[1] - c[1]) * n[1]
    }

    /// Pairs struck at an impact that stand apart by more than the tie tolerance at the end
    /// of a step (h) have parted.
    fn part(&mut self, placed: &[Option<Placed>], h: f64) {
        for k in 0..self.pairs.len() {
            let pair = &self.pairs[k];
            if let (true, Some(pa), Some(pb)) = (pair.struck, &placed[pair.a], &placed[pair.b]) {
                if h.is_finite() && self.gap(k, pa, pb, h) > self.tie_m(k) {
                    self.pairs[k].struck = false;
                }
            }
        }
    }

    /// The contacts of body i's blocks with the other blocks at the instant the bodies'
    /// trajectories `trajs` start from: each corner of one block of a pair (one of its blocks
    /// moved by body i, the other not) within the tie of the line of a face of the other and
    /// between that face's ends, to the tie. What a body set down from a tilt of a tie must not
    /// move into.
    pub(super) fn touching(
        &self,
        i: usize,
        bodies: &[RockingBody],
        trajs: &[Option<&Trajectory>],
    ) -> Vec<Touch> {
        let moved_by_i = |p: usize| self.pieces[p].body.is_some_and(|(b, _)| b == i);
        let mut found = Vec::new();
        for (k, pair) in self.pairs.iter().enumerate() {
            if moved_by_i(pair.a) == moved_by_i(pair.b) {
                continue;
            }
            let (Some(pa), Some(pb)) = (
                self.placed(pair.a, bodies, trajs),
                self.placed(pair.b, bodies, trajs),
            ) else {
                continue;
            };
            let (at_a, at_b, tie) = (pa.at(0.0), pb.at(0.0), self.tie_m(k));
            for (face, corner, pieces) in [
                (&at_a, &at_b, [pair.b, pair.a]),
                (&at_b, &at_a, [pair.a, pair.b]),
            ] {
                for e in 0..4 {
                    let line = Line::of(face, e);
                    for (j, p) in corner.corners.iter().enumerate() {
                        let (d, x) = line.place(p);
                        if d.abs() <= tie && x >= -tie && x <= line.length + tie {
                            found.push(self.contact(k, pieces, (j, e), *p, line.n, bodies));
                        }
                    }
                }
            }
        }
        found
    }

    /// The blocks of `pair` took an impact: they must part before they may strike again.
    pub(super) fn strike(&mut self, pair: usize) {
        self.pairs[pair].struck = true;
    }

    /// The blocks of `pair` turn in contact (`touch`, whose face becomes the pair's edge), or
    /// (none) that contact has just ended: they must part before they may strike again.
    pub(super) fn hold(&mut self, pair: usize, touch: Option<&Touch>) {
        if let Some(t) = touch {
            let b = self.pairs[pair].b;
            self.pairs[pair].edge = (self.pieces[b].output == t.blocks[1], t.edge);
        }
        self.pairs[pair].held = touch.map(|t| t.corner);
        self.pairs[pair].struck = true;
    }

    /// The faces of `pair` lie on each other, the ends of their overlap the contacts `ends`
    /// (each a corner of one block on the other's face), or (none) they no longer do: from the
    /// face of the first end they must part before they may strike again.
    pub(super) fn lie(&mut self, pair: usize, ends: Option<&[Touch; 2]>) {
        let b = self.pieces[self.pairs[pair].b].output;
        self.pairs[pair].struck = true;
        let Some(ends) = ends else {
            self.pairs[pair].lies = None;
            return;
        };
        let [first, second] = ends;
        self.pairs[pair].edge = (first.blocks[1] == b, first.edge);
        // Each block's edge on the other: the edge of a face an end lies on, or, where both
        // ends are corners of one block, the edge between them.
        let mut edges = [0; 2];
        for t in ends {
            edges[usize::from(t.blocks[1] == b)] = t.edge;
        }
        if first.blocks == second.blocks {
            let (j0, j1) = (first.corner, second.corner);
            edges[usize::from(first.blocks[0] == b)] = if j1 == (j0 + 1) % 4 { j0 } else { j1 };
        }
        self.pairs[pair].lies = Some(Lies {
            edges,
            ends: ends.map(|t| (t.blocks[0] == b, t.corner)),
        });
    }

    /// The blocks of `pair` stay in contact, one leaning on the other (`leaning`), or their
    /// contact has just ended: from their touching edge they must part before they may strike
    /// again.
    pub(super) fn lean(&mut self, pair: usize, leaning: bool) {
        self.pairs[pair].leaning = leaning;
        self.pairs[pair].struck = true;
    }

    /// Follows every pair over a step of the bodies on `trajs` from t0 up to h: where a corner
    /// reaches the edge that kept its pair apart, the pair takes another edge that keeps it
    /// apart by more than the tie tolerance, or one that opens just after where the blocks
    /// touch ([`Clearance::opening`]; not a pair held in contact, which parts only as the
    /// engine decides), and the search goes on from there within the same step
    /// (no step is cut for it: a run whose blocks never meet is the run without them, to the
    /// bit); where no edge does, the blocks meet: the instant and the pair's two outputs.
    pub(super) fn follow(
        &mut self,
        bodies: &[RockingBody],
        trajs: &[Option<&Trajectory>],
        t0: f64,
        h: f64,
    ) -> Result<Option<Meet>, SimulationError> {
        let placed: Vec<Option<Placed>> = (0..self.pieces.len())
            .map(|p| self.placed(p, bodies, trajs))
            .collect();
        let mut from = 0.0;
        for _ in 0..=PASSES {
            let Some((x, k)) = self.first(&placed, bodies, from, h) else {
                self.part(&placed, h);
                return Ok(None);
            };
            let (a, b) = (self.pairs[k].a, self.pairs[k].b);
            let (Some(pa), Some(pb)) = (&placed[a], &placed[b]) else {
                return Ok(None);
            };
            if self.pairs[k].lies.is_some() {
                let outputs = (self.pieces[a].output, self.pieces[b].output);
                match self.slides(k, (pa, pb), x, bodies) {
                    Some(meeting) => return Ok(Some((x, outputs, meeting))),
                    None => {
                        from = x;
                        continue;
                    }
                }
            }
            let (at_a, at_b) = (pa.at(x), pb.at(x));
            let (mut edge, margin) = widest(&at_a, &at_b);
            // A pair in contact (`held`) parts only as the engine decides: what the search
            // finds for it (its corner at an end of the face, another corner at the face) is
            // the engine's to meet, even where round-off has left the held corner a tie off it.
            let touches = margin <= self.tie_m(k) || self.pairs[k].held.is_some();
            let opens = (touches && self.pairs[k].held.is_none())
                .then(|| self.opening(k, (pa, pb), x, bodies))
                .flatten();
            if let Some(e) = opens {
                edge = e;
            } else if touches {
                let outputs = (self.pieces[a].output, self.pieces[b].output);
                // Where a pair meets again after an impact, the gap between is an arc whose
                // top lies near its middle.
                let stays = self.pairs[k].struck && self.gap(k, pa, pb, 0.5 * x) <= self.tie_m(k);
                let meeting = match self.touch(k, (pa, pb), x, bodies) {
                    Meeting::Strikes(t) => Meeting::Strikes(Touch { stays, ..t }),
                    Meeting::Faces(ends) => Meeting::Faces(ends.map(|t| Touch { stays, ..t })),
                    // In contact, what has parted is the end that strikes, not the held corner.
                    Meeting::Flat(Some(t)) => {
                        let stays = self.end_gap(k, &t, (pa, pb), 0.5 * x) <= self.tie_m(k);
                        Meeting::Flat(Some(Touch { stays, ..t }))
                    }
                    other => other,
                };
                return Ok(Some((x, outputs, meeting)));
            }
            self.pairs[k].edge = edge;
            from = x;
        }
        Err(SimulationError::TooManyEvents {
            time_s: t0 + from,
            count: PASSES,
            detail: "changes of the edge that keeps two blocks apart within one step".into(),
            limit: "blocks that graze each other this often without meeting are beyond the \
                    rocking model; please report the wall and the motion",
        })
    }
}
