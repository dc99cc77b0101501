//! Deciding the mode at an event, exactly.
//!
//! At an event some blocks move with equal velocity across some joints (relative velocity zero):
//! those joints may stick or slip, those touching faces may press or open. Their accelerations
//! solve Gauss' principle with Coulomb friction (design note, section 4):
//!
//!   minimise  sum_i m_i/2 (b_i - e_i/m_i)^2 + sum_joints F |b_p - b_q|
//!   subject to b_right >= b_left at touching faces, b_ground = a_g,
//!
//! where b_i is block i's absolute acceleration and e_i the constant friction of joints that
//! already slide. This is a total-variation problem on the joint graph; its solution is constant
//! on clusters (blocks that stick together move as one body). Its level sets {b > theta} are
//! minimum cuts, so the clusters are found by divide and conquer: cut at the mean acceleration,
//! recurse on both sides. Everything is exact rational arithmetic; at the ground, theta is the
//! ground acceleration "just after" the instant ([`Lex`]), which decides joints exactly at their
//! limit by what happens next.

use super::flow::{over_common_denominator, take_overflow, Amount, Network, PUSH_RELABEL_FROM};
use crate::exact::{div, gcd_i128, Q};
use crate::sets::DisjointSets;
use std::cmp::Ordering;
use std::collections::VecDeque;

/// Stick intervals of problems of at most this many blocks try every set (at most 255, in
/// integers) instead of searching with minimum cuts: each cut builds a flow network, and a few
/// cost more than all the sets of a small problem.
const ENUMERATE_UP_TO: usize = 8;

/// A large body that breaks is split and its problem solved again at most this many times
/// before the general decision takes over ([`Problem::solve_by_bodies`]).
const BODY_SPLITS: usize = 16;

/// [`Problem::solve_by_bodies`] holds bodies together only where that leaves at most this many
/// nodes, or a quarter of the problem: each try solves the contracted problem by the general
/// decision, and tries over a large one cost more than the general decision over all of it
/// (a 4,413-block part holding a 2,247-block body: 56 flows against 16).
const CONTRACTED_UP_TO: usize = 64;

/// Minimum cuts over at most this many blocks try every set too (see [`Cut::by_enumeration`]):
/// below it that costs less than building a flow network and pushing a flow through it.
const CUT_ENUMERATE_UP_TO: usize = 6;

/// c0 + c1 eps + c2 eps^2 for an infinitesimal eps > 0, ordered lexicographically: the value of a
/// ground acceleration "just after" an instant, a_g(t) + a_g'(t) eps + a_g''(t) eps^2 / 2.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Lex(pub [Q; 3]);

impl Lex {
    /// A plain number.
    pub fn constant(q: Q) -> Lex {
        Lex([q, Q::zero(), Q::zero()])
    }
    /// Zero.
    pub fn zero() -> Lex {
        Lex::constant(Q::zero())
    }
}

impl Ord for Lex {
    fn cmp(&self, o: &Lex) -> Ordering {
        self.0[0]
            .cmp(&o.0[0])
            .then_with(|| self.0[1].cmp(&o.0[1]))
            .then_with(|| self.0[2].cmp(&o.0[2]))
    }
}

impl PartialOrd for Lex {
    fn partial_cmp(&self, o: &Lex) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

/// The other end of a joint: a block of the problem, or the ground (and fixed blocks).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum End {
    /// Local index of a block in the problem.
    Node(usize),
    /// The ground, moving with a_g.
    Ground,
}

/// Entries of each of a problem's lists that its hash takes in ([`Problem`]'s `Hash`).
const HASHED_PER_LIST: usize = 64;

/// One decision problem: the blocks whose joints are undecided, and those joints. Problems are
/// compared and hashed as values, so a run can remember the answers it has already worked out.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Problem {
    /// Mass of each block (kg).
    pub mass: Vec<Q>,
    /// Constant horizontal force on each block from joints that slide (N, +x positive).
    pub external: Vec<Q>,
    /// Undecided friction joints: (block, other end, capacity N).
    pub friction: Vec<(usize, End, Q)>,
    /// Touching faces with zero relative velocity: (left, right); the right face may not
    /// accelerate into the left one.
    pub contacts: Vec<(End, End)>,
}

/// A problem mixed into one word for the hasher: its sizes and at most `HASHED_PER_LIST`
/// entries of each list, evenly spread (equal problems mix alike, and the memo's equality
/// decides between problems that mix alike). A run looks a problem up at every event, and a
/// large problem is seldom met again: hashing all of it cost a pass over the problem per
/// lookup that misses.
impl std::hash::Hash for Problem {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        fn spread<T>(list: &[T]) -> impl Iterator<Item = &T> {
            list.iter()
                .step_by(list.len().div_ceil(HASHED_PER_LIST).max(1))
        }
        let end = |e: &End| match e {
            End::Node(i) => *i as u64,
            End::Ground => u64::MAX,
        };
        let sizes = [self.mass.len(), self.friction.len(), self.contacts.len()];
        let mut words = sizes
            .into_iter()
            .map(|n| n as u64)
            .chain(spread(&self.mass).map(Q::hash_word))
            .chain(spread(&self.external).map(Q::hash_word))
            .chain(spread(&self.friction).flat_map(|(i, j, f)| [*i as u64, end(j), f.hash_word()]))
            .chain(spread(&self.contacts).flat_map(|(l, r)| [end(l), end(r)]));
        let first = words.next().unwrap_or(0);
        state.write_u64(words.fold(first, |h, w| {
            (h.rotate_left(5) ^ w).wrapping_mul(0x51_7c_c1_b7_27_22_0a_95)
        }));
    }
}

/// A cluster in the solution.
#[derive(Debug, Clone, PartialEq)]
pub struct Group {
    /// Local block indices.
    pub nodes: Vec<usize>,
    /// Absolute acceleration (m/s2); for a grounded group, a_g at the instant.
    pub accel: Q,
    /// Stuck to the ground.
    pub grounded: bool,
}

/// Adjacency lists of a problem's nodes, stored flat: the neighbours of node i are
/// `next[start[i]..start[i + 1]]`.
struct Adjacency {
    start: Vec<usize>,
    next: Vec<usize>,
}

impl Adjacency {
    fn of(&self, i: usize) -> &[usize] {
        &self.next[self.start[i]..self.start[i + 1]]
    }
}

/// Which minimisers of a cut problem a caller needs: each costs its own pass on large networks.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Want {
    /// The smallest (the level set {b > theta}).
    Smallest,
    /// The largest (the level set {b >= theta}).
    Largest,
    /// Both.
    Both,
}

/// What a sub-problem makes of the nodes left out of it.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Outside {
    /// Nothing: no joint may reach them.
    Absent,
    /// The ground, reached through joints only.
    GroundWithoutFaces,
    /// The ground, reached through joints and faces.
    Ground,
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Side {
    /// Super-level set {b > theta}: a contact (l, r) forces r in when l is in.
    Upper,
    /// Sub-level set {b < theta}: a contact (l, r) forces l in when r is in.
    Lower,
}

impl Problem {
    fn n(&self) -> usize {
        self.mass.len()
    }

    /// Touches the ground through an undecided joint or face.
    pub fn touches_ground(&self) -> bool {
        self.friction.iter().any(|(_, j, _)| *j == End::Ground)
            || self
                .contacts
                .iter()
                .any(|(l, r)| *l == End::Ground || *r == End::Ground)
    }

    /// The problem emptied, its memory kept for the next.
    pub fn cleared(mut self) -> Problem {
        self.mass.clear();
        self.external.clear();
        self.friction.clear();
        self.contacts.clear();
        self
    }

    /// The same problem with its joint lists in a canonical order.
    pub fn canonical(mut self) -> Problem {
        self.friction.sort();
        self.contacts.sort();
        self
    }

    /// The sub-problem of `nodes` (renumbered in the order given): their undecided joints among
    /// themselves and with the ground. Joints to other nodes must not exist (callers split along
    /// the pieces of the joint graph).
    pub fn restrict(&self, nodes: &[usize]) -> Problem {
        self.sub_problem(nodes, Outside::Absent)
    }

    /// The sub-problem of `nodes` (renumbered in the order given) with every other node held
    /// as the ground: their joints to other nodes join them to the ground, their faces against
    /// other nodes are dropped (a bound on the sub-problem's stick interval from inside, as
    /// `Engine::kept_limits` needs).
    pub fn with_ground(&self, nodes: &[usize]) -> Problem {
        self.sub_problem(nodes, Outside::GroundWithoutFaces)
    }

    /// The sub-problem of `nodes` (renumbered in the order given) with every other node moving
    /// with the ground: their joints and faces against other nodes are joints and faces against
    /// the ground. Its decision is the full problem's for these nodes wherever the other nodes
    /// do stay at a_g.
    pub fn beside_ground(&self, nodes: &[usize]) -> Problem {
        self.sub_problem(nodes, Outside::Ground)
    }

    /// The sub-problem of `nodes` (renumbered in the order given) with the other nodes sliding
    /// past them: `ahead[i]` is +1 for a node moving ahead of them, -1 for one falling behind,
    /// 0 for one in `nodes` or in no joint with them. Joints to a sliding node carry their full
    /// capacity in its direction (external forces), faces against it open.
    pub fn beside_sliding(&self, nodes: &[usize], ahead: &[i8]) -> Problem {
        let mut q = self.sub_problem(nodes, Outside::Absent);
        let mut index = vec![usize::MAX; self.n()];
        for (k, &i) in nodes.iter().enumerate() {
            index[i] = k;
        }
        for (i, j, f) in &self.friction {
            let End::Node(j) = *j else { continue };
            for (a, b) in [(*i, j), (j, *i)] {
                if index[a] != usize::MAX && ahead[b] != 0 {
                    let e = &mut q.external[index[a]];
                    *e = if ahead[b] > 0 { &*e + f } else { &*e - f };
                }
            }
        }
        q
    }

    fn sub_problem(&self, nodes: &[usize], outside: Outside) -> Problem {
        let mut index = vec![usize::MAX; self.n()];
        for (k, &i) in nodes.iter().enumerate() {
            index[i] = k;
        }
        let map = |e: End| match e {
            End::Ground => Some(End::Ground),
            End::Node(i) => (index[i] != usize::MAX).then(|| End::Node(index[i])),
        };
        let joint = |e: End| map(e).or((outside != Outside::Absent).then_some(End::Ground));
        let face = |e: End| map(e).or((outside == Outside::Ground).then_some(End::Ground));
        Problem {
            mass: nodes.iter().map(|&i| self.mass[i].clone()).collect(),
            external: nodes.iter().map(|&i| self.external[i].clone()).collect(),
            friction: self
                .friction
                .iter()
                .filter_map(|(i, j, f)| match (joint(End::Node(*i))?, joint(*j)?) {
                    (End::Ground, End::Ground) => None,
                    (End::Node(a), b) => Some((a, b, f.clone())),
                    (End::Ground, End::Node(b)) => Some((b, End::Ground, f.clone())),
                })
                .collect(),
            contacts: self
                .contacts
                .iter()
                .filter_map(|(l, r)| match (face(*l)?, face(*r)?) {
                    (End::Ground, End::Ground) => None,
                    pair => Some(pair),
                })
                .collect(),
        }
        .canonical()
    }

    /// Connected pieces of the joint graph without passing through the ground, each sorted, and
    /// whether each touches the ground.
    pub fn ground_pieces(&self) -> Vec<(Vec<usize>, bool)> {
        let n = self.n();
        let mut sets = DisjointSets::new(n);
        let mut on_ground = vec![false; n];
        for &(i, j, _) in &self.friction {
            match j {
                End::Node(j) => sets.join(i, j),
                End::Ground => on_ground[i] = true,
            }
        }
        for &(l, r) in &self.contacts {
            match (l, r) {
                (End::Node(a), End::Node(b)) => sets.join(a, b),
                (End::Ground, End::Node(i)) | (End::Node(i), End::Ground) => on_ground[i] = true,
                _ => {}
            }
        }
        // Pieces in the order of their first block, each block in order.
        let mut piece_of = vec![usize::MAX; n];
        let mut out: Vec<(Vec<usize>, bool)> = Vec::new();
        for (i, grounded) in on_ground.into_iter().enumerate() {
            let root = sets.find(i);
            if piece_of[root] == usize::MAX {
                piece_of[root] = out.len();
                out.push((Vec::new(), false));
            }
            let piece = &mut out[piece_of[root]];
            piece.0.push(i);
            piece.1 |= grounded;
        }
        out
    }

    /// The blocks joined by each undecided joint or face between blocks.
    fn adjacency(&self) -> Adjacency {
        let pairs = || {
            let joints = self.friction.iter().filter_map(|&(i, j, _)| match j {
                End::Node(j) => Some((i, j)),
                End::Ground => None,
            });
            let faces = self.contacts.iter().filter_map(|&(l, r)| match (l, r) {
                (End::Node(l), End::Node(r)) => Some((l, r)),
                _ => None,
            });
            joints.chain(faces)
        };
        // Counting sort: each node's neighbours end at start[i + 1], then fill backwards.
        let mut start = vec![0; self.n() + 1];
        for (a, b) in pairs() {
            start[a + 1] += 1;
            start[b + 1] += 1;
        }
        for i in 0..self.n() {
            start[i + 1] += start[i];
        }
        let mut next = vec![0; start[self.n()]];
        let mut end = start[1..].to_vec();
        for (a, b) in pairs() {
            end[a] -= 1;
            next[end[a]] = b;
            end[b] -= 1;
            next[end[b]] = a;
        }
        Adjacency { start, next }
    }

    /// For each node of `set`, "in S implies that node in S" arcs and nodes that may not be in S
    /// (they would have to push into the ground), for the given side. Faces against the ground
    /// only constrain the cut where the ground is pinned at theta (`pinned`); inside a part
    /// already known to move away from the ground they are slack.
    fn constraints(
        &self,
        set: &[bool],
        side: Side,
        pinned: bool,
    ) -> (Vec<(usize, usize)>, Vec<usize>) {
        let mut implies = Vec::new();
        let mut forbidden = Vec::new();
        for &(l, r) in &self.contacts {
            let (from, to) = match side {
                Side::Upper => (l, r),
                Side::Lower => (r, l),
            };
            match (from, to) {
                (End::Node(a), End::Node(b)) if set[a] && set[b] => implies.push((a, b)),
                (End::Node(a), End::Ground) if set[a] && pinned => forbidden.push(a),
                _ => {}
            }
        }
        (implies, forbidden)
    }

    /// Minimises sum_{i in S} w_i + cut(S) over S within `set` (subject to the side's contact
    /// constraints) and returns the smallest and the largest minimiser, those `want` asks for.
    /// `cut` counts joints with both ends in `set` and, when the ground is `pinned` at theta,
    /// joints to the ground; joints to blocks outside `set` already slide and are in the weights.
    /// Integer arithmetic when the weights and capacities fit over a common denominator
    /// (scaling changes no minimiser, and skips a gcd at every operation); exact rationals
    /// otherwise or on overflow.
    fn min_cut(&self, set: &[bool], weight: &[Q], side: Side, pinned: bool, want: Want) -> Sides {
        // Only the amounts the cut uses go over the common denominator: a decision's recursion
        // cuts small parts of a large problem, and each should cost its part.
        let members: Vec<usize> = (0..self.n()).filter(|&i| set[i]).collect();
        let joints: Vec<usize> = (0..self.friction.len())
            .filter(|&k| {
                let (i, j, _) = &self.friction[k];
                set[*i]
                    && match j {
                        End::Node(j) => set[*j],
                        End::Ground => pinned,
                    }
            })
            .collect();
        let amounts = members
            .iter()
            .map(|&i| &weight[i])
            .chain(joints.iter().map(|&k| &self.friction[k].2));
        if let Some((ints, _)) = over_common_denominator(amounts) {
            let mut w = vec![0i128; self.n()];
            let mut caps = vec![0i128; self.friction.len()];
            for (&i, &x) in members.iter().zip(&ints) {
                w[i] = x;
            }
            for (&k, &x) in joints.iter().zip(&ints[members.len()..]) {
                caps[k] = x;
            }
            if let Some(sides) = self.min_cut_in_integers(set, &w, &caps, side, pinned, want) {
                return sides;
            }
        }
        let caps: Vec<Q> = self.friction.iter().map(|j| j.2.clone()).collect();
        self.min_cut_of(set, weight, &caps, side, pinned, want)
    }

    /// [`Problem::min_cut`] with the weights and the joints' capacities (in the order of
    /// `friction`) given as integers over one denominator; `None` when they could overflow.
    fn min_cut_in_integers(
        &self,
        set: &[bool],
        weight: &[i128],
        caps: &[i128],
        side: Side,
        pinned: bool,
        want: Want,
    ) -> Option<Sides> {
        // Every excess and residual of a flow is at most twice the sum of all capacities plus
        // one (the constraint arcs' capacity): if four times that sum fits, nothing overflows.
        // (An overflow inside a flow would leave amounts that no longer add up, and the flow
        // might never end.)
        let total = weight
            .iter()
            .zip(set)
            .filter(|(_, &inside)| inside)
            .map(|(w, _)| w)
            .chain(caps)
            .try_fold(0i128, |sum, x| sum.checked_add(x.checked_abs()?))?;
        if total > i128::MAX >> 2 {
            return None;
        }
        take_overflow();
        let sides = if total <= i128::from(i64::MAX >> 2) {
            // The same bound in 64 bits, which most of a wall's cuts meet: half the memory and
            // one-word arithmetic (the block-count study's 10,050-block case 34: 5.3 -> 5.1 s).
            let narrow = |v: &[i128]| v.iter().map(|&x| x as i64).collect::<Vec<i64>>();
            self.min_cut_of(set, &narrow(weight), &narrow(caps), side, pinned, want)
        } else {
            self.min_cut_of(set, weight, caps, side, pinned, want)
        };
        (!take_overflow()).then_some(sides)
    }

    /// [`Problem::min_cut`] in any exact amount: `caps` are the joints' capacities, in the
    /// order of `friction`.
    fn min_cut_of<A: Amount>(
        &self,
        set: &[bool],
        weight: &[A],
        caps: &[A],
        side: Side,
        pinned: bool,
        want: Want,
    ) -> Sides {
        // The network has a node for each member of `set` only: the recursion of a decision
        // cuts ever smaller parts of one large problem, and each cut should cost its part.
        let members: Vec<usize> = (0..self.n()).filter(|&i| set[i]).collect();
        let mut local = vec![usize::MAX; self.n()];
        for (k, &i) in members.iter().enumerate() {
            local[i] = k;
        }
        let n = members.len();
        let (s, t) = (n, n + 1);
        // The arcs, as (from, to, both ways), and their capacities.
        let mut arcs: Vec<(usize, usize, bool)> = Vec::new();
        let mut amounts: Vec<A> = Vec::new();
        for (k, &i) in members.iter().enumerate() {
            let w = &weight[i];
            if w.positive() {
                arcs.push((k, t, false));
                amounts.push(w.clone());
            } else if *w != A::zero() {
                arcs.push((s, k, false));
                amounts.push(A::zero().minus(w));
            }
        }
        for ((i, j, _), cap) in self.friction.iter().zip(caps) {
            if !set[*i] {
                continue;
            }
            match j {
                End::Node(j) if set[*j] => arcs.push((local[*i], local[*j], true)),
                // Joint to the pinned ground: cut whenever i is in S.
                End::Ground if pinned => arcs.push((local[*i], t, false)),
                _ => continue,
            }
            amounts.push(cap.clone());
        }
        let (implies, forbidden) = self.constraints(set, side, pinned);
        let implies: Vec<(usize, usize)> =
            implies.iter().map(|&(a, b)| (local[a], local[b])).collect();
        let forbidden: Vec<usize> = forbidden.iter().map(|&a| local[a]).collect();
        let question = Cut {
            n,
            arcs: &arcs,
            implies: &implies,
            forbidden: &forbidden,
        };
        let (minimal, reach_t) = question.minimum(&amounts, want);
        let back = |inside: &dyn Fn(usize) -> bool| {
            let mut out = vec![false; self.n()];
            for (k, &i) in members.iter().enumerate() {
                out[i] = inside(k);
            }
            out
        };
        (
            minimal.map(|m| back(&|k| m[k])),
            reach_t.map(|r| back(&|k| !r[k])),
        )
    }

    /// Connected pieces of `members` through undecided joints between members.
    fn pieces(&self, members: &[usize], adj: &Adjacency) -> Vec<Vec<usize>> {
        let mut inside = vec![false; self.n()];
        for &i in members {
            inside[i] = true;
        }
        let mut seen = vec![false; self.n()];
        let mut out = Vec::new();
        for &i in members {
            if seen[i] {
                continue;
            }
            seen[i] = true;
            // Breadth first, the piece itself the queue (its order does not matter: it is
            // sorted below).
            let mut piece = vec![i];
            let mut k = 0;
            while let Some(&u) = piece.get(k) {
                k += 1;
                for &v in adj.of(u) {
                    if inside[v] && !seen[v] {
                        seen[v] = true;
                        piece.push(v);
                    }
                }
            }
            piece.sort_unstable();
            out.push(piece);
        }
        out
    }

    /// External force on each member of `part` once the joints between it and the rest of `set`
    /// slide: a part above the rest is pulled down by F, below it pushed up. Joints to the
    /// ground count only where the ground belongs to the set (the top split); joints leaving
    /// `set` are already in `external`.
    fn boundary_forces(
        &self,
        set: &[bool],
        part: &[bool],
        ground_in_set: bool,
        external: &[Q],
        upper: bool,
    ) -> Vec<Q> {
        let mut e = external.to_vec();
        let pull = |x: &Q, f: &Q| if upper { x - f } else { x + f };
        for (i, j, f) in &self.friction {
            match *j {
                End::Node(j) => {
                    if part[*i] && set[j] && !part[j] {
                        e[*i] = pull(&e[*i], f);
                    } else if part[j] && set[*i] && !part[*i] {
                        e[j] = pull(&e[j], f);
                    }
                }
                End::Ground => {
                    if ground_in_set && part[*i] {
                        e[*i] = pull(&e[*i], f);
                    }
                }
            }
        }
        e
    }

    /// The smallest and the largest minimiser of a free problem's cut at its mean acceleration.
    /// The weights sum to zero over `set` and no joint leaves it, so the empty set is a
    /// minimiser exactly when the whole set is: then the set moves as one body, the common case
    /// when a block comes to rest on a large sliding cluster. Where each minimiser costs a pass
    /// of its own (push-relabel), the largest alone shows that case.
    fn level_cuts(&self, set: &[bool], weight: &[Q]) -> (Vec<bool>, Vec<bool>) {
        if self.n() + 2 < PUSH_RELABEL_FROM {
            let (upper, at_or_above) = self.min_cut(set, weight, Side::Upper, false, Want::Both);
            return (upper.expect("asked for"), at_or_above.expect("asked for"));
        }
        let at_or_above = self
            .min_cut(set, weight, Side::Upper, false, Want::Largest)
            .1;
        let at_or_above = at_or_above.expect("asked for");
        if at_or_above == set {
            return (vec![false; self.n()], at_or_above);
        }
        let upper = self
            .min_cut(set, weight, Side::Upper, false, Want::Smallest)
            .0;
        (upper.expect("asked for"), at_or_above)
    }

    /// Clusters of blocks that share no joint with the ground (the ground does not appear).
    fn solve_free(&self, set: &[bool], external: &[Q], adj: &Adjacency, out: &mut Vec<Group>) {
        let members: Vec<usize> = (0..self.n()).filter(|&i| set[i]).collect();
        let mass: Q = members.iter().map(|&i| self.mass[i].clone()).sum();
        let total: Q = members.iter().map(|&i| external[i].clone()).sum();
        let theta = total / mass;
        let weight: Vec<Q> = (0..self.n())
            .map(|i| {
                if set[i] {
                    &self.mass[i] * &theta - &external[i]
                } else {
                    Q::zero()
                }
            })
            .collect();
        let (upper, at_or_above) = self.level_cuts(set, &weight);
        let lower: Vec<bool> = (0..self.n()).map(|i| set[i] && !at_or_above[i]).collect();
        let level: Vec<usize> = (0..self.n())
            .filter(|&i| at_or_above[i] && !upper[i])
            .collect();
        for piece in self.pieces(&level, adj) {
            out.push(Group {
                nodes: piece,
                accel: theta.clone(),
                grounded: false,
            });
        }
        for (part, is_upper) in [(upper, true), (lower, false)] {
            if part.iter().any(|&b| b) {
                let e = self.boundary_forces(set, &part, false, external, is_upper);
                self.solve_free(&part, &e, adj, out);
            }
        }
    }

    /// Solves the decision problem. `ground` is the ground acceleration just after the instant
    /// (exact, with its derivatives) when some joint reaches the ground; it is ignored otherwise.
    /// `bodies` are disjoint sets of nodes that moved as rigid bodies until now (large sliding
    /// clusters); away from the ground they make the work proportional to the cut that shows
    /// each still holds, instead of the cuts that would find their groups anew
    /// (`Problem::solve_by_bodies`). The answer does not depend on them.
    pub fn solve(&self, ground: &Lex, bodies: &[Vec<usize>]) -> Vec<Group> {
        if !self.touches_ground() {
            if !bodies.is_empty() {
                if let Some(groups) = self.solve_by_bodies(bodies) {
                    return groups;
                }
            }
            let mut out = Vec::new();
            let all = vec![true; self.n()];
            self.solve_free(&all, &self.external, &self.adjacency(), &mut out);
            return out;
        }
        // {b > a_g} and {b < a_g}: two cuts, the ground pinned at a_g and never in either set.
        let at_ground = self.integral_at(&ground.0[0]);
        let upper = self.split_at_ground(ground, Side::Upper, at_ground.as_ref());
        let lower = self.split_at_ground(ground, Side::Lower, at_ground.as_ref());
        self.solve_split(ground, bodies, upper, lower)
    }

    /// A decision at the ground acceleration `ground` exactly at a limit of this problem's own
    /// stick interval `stick`, passing it outward: the blocks that move are the largest minimiser
    /// that the interval's last cut found, which is the split at the ground
    /// (`Problem::split_at_ground`: the same weights, constraints and minimiser), and no block
    /// moves the other way when the interval is more than a point, so the decision needs
    /// neither of the two cuts over the whole problem. `None` anywhere else, and where the
    /// interval is a point or empty (a problem that cannot be stuck). Most decisions at
    /// the ground of a large wall are of this kind: a stuck cluster reaching its limit.
    pub fn solve_past_limit(
        &self,
        ground: &Lex,
        bodies: &[Vec<usize>],
        stick: &Stick,
    ) -> Option<Vec<Group>> {
        let a0 = &ground.0[0];
        if let (Some(lo), Some(hi)) = (&stick.lo, &stick.hi) {
            // At a_g = hi, a set T moving ahead of the ground would need a_g <= lo (its amount
            // is m(T) (a_g - lo_T), lo_T <= lo): none does when lo < hi.
            if lo >= hi {
                return None;
            }
        }
        let rising = match ground.0[1].signum() {
            0 => ground.0[2].signum(),
            rate => rate,
        };
        let (leaving, up) = if rising > 0 && stick.hi.as_ref() == Some(a0) && !stick.bound_only[1] {
            (stick.leaving_hi.as_ref()?, false)
        } else if rising < 0 && stick.lo.as_ref() == Some(a0) && !stick.bound_only[0] {
            (stick.leaving_lo.as_ref()?, true)
        } else {
            return None;
        };
        let none = vec![false; self.n()];
        let mut moving = none.clone();
        for &i in leaving {
            moving[i] = true;
        }
        let (upper, lower) = if up { (moving, none) } else { (none, moving) };
        Some(self.solve_split(ground, bodies, upper, lower))
    }

    /// The rest of a decision at the ground once the blocks faster than the ground (`upper`)
    /// and slower (`lower`) are known: those left at a_g, and the free parts.
    fn solve_split(
        &self,
        ground: &Lex,
        bodies: &[Vec<usize>],
        upper: Vec<bool>,
        lower: Vec<bool>,
    ) -> Vec<Group> {
        let n = self.n();
        let adj = self.adjacency();
        let all = vec![true; n];
        let mut out = Vec::new();
        let level: Vec<usize> = (0..n).filter(|&i| !upper[i] && !lower[i]).collect();
        // The blocks left at a_g: those joined to the ground through undecided joints are stuck;
        // any other piece moves freely with acceleration a_g (possible only when a_g is locally
        // constant).
        let mut grounded = vec![false; n];
        let mut queue: VecDeque<usize> = VecDeque::new();
        let on_level: Vec<bool> = (0..n).map(|i| !upper[i] && !lower[i]).collect();
        for (i, j, _) in &self.friction {
            if *j == End::Ground && on_level[*i] && !grounded[*i] {
                grounded[*i] = true;
                queue.push_back(*i);
            }
        }
        for (l, r) in &self.contacts {
            for (a, b) in [(l, r), (r, l)] {
                if let (End::Node(a), End::Ground) = (a, b) {
                    if on_level[*a] && !grounded[*a] {
                        grounded[*a] = true;
                        queue.push_back(*a);
                    }
                }
            }
        }
        while let Some(u) = queue.pop_front() {
            for &v in adj.of(u) {
                if on_level[v] && !grounded[v] {
                    grounded[v] = true;
                    queue.push_back(v);
                }
            }
        }
        let stuck: Vec<usize> = level.iter().copied().filter(|&i| grounded[i]).collect();
        for piece in self.pieces(&stuck, &adj) {
            out.push(Group {
                nodes: piece,
                accel: ground.0[0].clone(),
                grounded: true,
            });
        }
        let floating: Vec<usize> = level.iter().copied().filter(|&i| !grounded[i]).collect();
        for piece in self.pieces(&floating, &adj) {
            out.push(Group {
                nodes: piece,
                accel: ground.0[0].clone(),
                grounded: false,
            });
        }
        for (part, is_upper) in [(upper, true), (lower, false)] {
            if part.iter().any(|&b| b) {
                let e = self.boundary_forces(&all, &part, true, &self.external, is_upper);
                if !self.solve_part_by_bodies(&part, &e, bodies, &mut out) {
                    self.solve_free(&part, &e, &adj, &mut out);
                }
            }
        }
        out
    }

    /// A part of a decision at the ground that moves away from it (its joints to the ground
    /// slide, their forces in `external`), solved with the bodies inside it held together
    /// ([`Problem::solve_by_bodies`]) and its groups added to `out`: the upper part of a wall
    /// sliding on its lower courses is a free problem as large as itself, which the general
    /// decision would cut again at every level of its recursion. `false` (nothing added) where
    /// no body lies in the part or the general decision is needed.
    fn solve_part_by_bodies(
        &self,
        part: &[bool],
        external: &[Q],
        bodies: &[Vec<usize>],
        out: &mut Vec<Group>,
    ) -> bool {
        let nodes: Vec<usize> = (0..self.n()).filter(|&i| part[i]).collect();
        let mut index = vec![usize::MAX; self.n()];
        for (k, &i) in nodes.iter().enumerate() {
            index[i] = k;
        }
        let inner: Vec<Vec<usize>> = bodies
            .iter()
            .map(|b| b.iter().filter(|&&i| part[i]).map(|&i| index[i]).collect())
            .filter(|b: &Vec<usize>| b.len() >= 2)
            .collect();
        if inner.is_empty() {
            return false;
        }
        let mut free = self.restrict(&nodes);
        free.external = nodes.iter().map(|&i| external[i].clone()).collect();
        free.friction.retain(|(_, j, _)| *j != End::Ground);
        free.contacts
            .retain(|(l, r)| *l != End::Ground && *r != End::Ground);
        let Some(groups) = free.solve_by_bodies(&inner) else {
            return false;
        };
        out.extend(groups.into_iter().map(|g| Group {
            nodes: g.nodes.iter().map(|&k| nodes[k]).collect(),
            ..g
        }));
        true
    }

    /// The weights e_i - lambda m_i (this problem's external forces) and the joints'
    /// capacities as integers over one denominator ([`Integral::at`]), where they fit.
    fn integral_at(&self, lambda: &Q) -> Option<(Vec<i128>, Vec<i128>)> {
        Integral::new(self, &self.external)?.at(lambda)
    }

    /// The blocks that accelerate faster than the ground just after the instant, {b > a_g}
    /// (`Side::Upper`), or slower, {b < a_g} (`Side::Lower`): the smallest set S minimising
    /// sum_{i in S} (m_i a_g - e_i) + cut(S) (mirrored for the lower side), joints to the ground
    /// cut. With a_g = a0 + a1 eps + a2 eps^2, a set's amount is (c0(S), a1 m(S), a2 m(S)) up to
    /// constants: capacities are plain numbers, and only the weights carry eps, in proportion to
    /// the mass. So the minimisers are those of c0 alone, in plain rationals, and among them the
    /// lightest (the smallest) when a_g is rising (a1 > 0, or a1 = 0 < a2) and the heaviest (the
    /// largest) when it is falling; all of them tie when it is steady, and the smallest is the
    /// answer. No flow in lexicographic amounts is needed (several times slower on a large wall).
    ///
    /// `at_ground`: the weights e_i - a0 m_i and the capacities in integers
    /// ([`Problem::integral_at`]), worked out once for both sides.
    fn split_at_ground(
        &self,
        ground: &Lex,
        side: Side,
        at_ground: Option<&(Vec<i128>, Vec<i128>)>,
    ) -> Vec<bool> {
        let rising = match ground.0[1].signum() {
            0 => ground.0[2].signum(),
            rate => rate,
        };
        let lightest = match side {
            Side::Upper => rising >= 0,
            Side::Lower => rising <= 0,
        };
        let want = if lightest {
            Want::Smallest
        } else {
            Want::Largest
        };
        let all = vec![true; self.n()];
        // The weights e_i - a0 m_i (lower side), negated on the upper side: in integers
        // without a rational operation where they fit.
        let in_integers = at_ground.and_then(|(weight, caps)| {
            let weight = match side {
                Side::Upper => weight
                    .iter()
                    .map(|w| w.checked_neg())
                    .collect::<Option<_>>()?,
                Side::Lower => weight.clone(),
            };
            self.min_cut_in_integers(&all, &weight, caps, side, true, want)
        });
        let (smallest, largest) = in_integers.unwrap_or_else(|| {
            let weight: Vec<Q> = (0..self.n())
                .map(|i| {
                    let w = &self.external[i] - &ground.0[0] * &self.mass[i];
                    if side == Side::Upper {
                        -w
                    } else {
                        w
                    }
                })
                .collect();
            self.min_cut(&all, &weight, side, true, want)
        });
        if lightest { smallest } else { largest }.expect("asked for")
    }

    /// A problem away from the ground solved with `bodies` held together
    /// ([`Problem::solve_contracted`]); where a group holding bodies cannot stay whole, the part
    /// of it that would move ahead splits the bodies it cuts, and the problem is solved again,
    /// at most [`BODY_SPLITS`] times. Each try costs a small contracted problem and a cut per
    /// group holding a body, where the general decision would cut the whole problem again at
    /// every level of its recursion. `None`: the general decision is needed.
    fn solve_by_bodies(&self, bodies: &[Vec<usize>]) -> Option<Vec<Group>> {
        let contracted = self.n()
            - bodies
                .iter()
                .map(|b| b.len().saturating_sub(1))
                .sum::<usize>();
        if contracted > CONTRACTED_UP_TO && 4 * contracted > self.n() {
            return None;
        }
        let mut bodies = bodies.to_vec();
        let mut held = Vec::new();
        for _ in 0..=BODY_SPLITS {
            let ahead = match self.solve_contracted(&bodies, &mut held) {
                Held::Groups(groups) => return Some(groups),
                Held::Undetermined => return None,
                Held::Breaks(ahead) => ahead,
            };
            // The part ahead cannot be a union of whole contracted nodes (the contracted
            // optimum would have split it off), so it cuts some body; a body of one block is no
            // body.
            let mut split = Vec::new();
            let mut cut_one = false;
            for body in &bodies {
                let (front, back): (Vec<usize>, Vec<usize>) = body.iter().partition(|&&i| ahead[i]);
                cut_one |= !front.is_empty() && !back.is_empty();
                split.extend([front, back].into_iter().filter(|part| part.len() >= 2));
            }
            if !cut_one {
                return None;
            }
            bodies = split;
        }
        None
    }

    /// A problem away from the ground solved with each of `bodies` held together: contracted to
    /// one node (its mass, its external force, its joints to the rest) the problem is small.
    /// Holding bodies together is a constraint, so this is the answer to the full problem exactly
    /// when the full problem's optimality conditions also hold inside every group that holds a
    /// body: with the forces the other groups now put on it (sliding joints at capacity), its
    /// weights sum to zero at its acceleration, and it stays whole exactly when its largest
    /// minimum cut is all of it. The minimiser being unique, the groups are then the full
    /// problem's. Otherwise the parts of the groups that cannot stay whole that would move
    /// ahead (their largest minimum cuts) come back; undetermined where a group touches another
    /// moving at its own acceleration (the force between them is not known). `held`: groups
    /// (their nodes and weights) shown to stay whole by earlier tries, which need no cut again
    /// (a try after a body broke meets the others as they were), and those shown now.
    fn solve_contracted(
        &self,
        bodies: &[Vec<usize>],
        held: &mut Vec<(Vec<usize>, Vec<Q>)>,
    ) -> Held {
        let n = self.n();
        let mut node = vec![usize::MAX; n];
        let mut members: Vec<Vec<usize>> = Vec::new();
        for body in bodies {
            for &i in body {
                node[i] = members.len();
            }
            members.push(body.clone());
        }
        for (i, c) in node.iter_mut().enumerate() {
            if *c == usize::MAX {
                *c = members.len();
                members.push(vec![i]);
            }
        }
        let end = |e: &End| match e {
            End::Node(i) => End::Node(node[*i]),
            End::Ground => End::Ground,
        };
        let sum = |values: &[Q], of: &[usize]| -> Q { of.iter().map(|&i| values[i].clone()).sum() };
        let small = Problem {
            mass: members.iter().map(|m| sum(&self.mass, m)).collect(),
            external: members.iter().map(|m| sum(&self.external, m)).collect(),
            friction: self
                .friction
                .iter()
                .filter(|(i, j, _)| end(j) != End::Node(node[*i]))
                .map(|(i, j, f)| (node[*i], end(j), f.clone()))
                .collect(),
            contacts: self
                .contacts
                .iter()
                .map(|(l, r)| (end(l), end(r)))
                .filter(|(l, r)| l != r)
                .collect(),
        }
        .canonical();
        let mut groups = small.solve(&Lex::zero(), &[]);
        let mut group_of = vec![0; n];
        for (g, group) in groups.iter_mut().enumerate() {
            let mut nodes: Vec<usize> = group
                .nodes
                .iter()
                .flat_map(|&c| members[c].iter().copied())
                .collect();
            nodes.sort_unstable();
            for &i in &nodes {
                group_of[i] = g;
            }
            group.nodes = nodes;
        }
        let holds_a_body = |g: usize| {
            bodies
                .iter()
                .any(|b| b.first().is_some_and(|&i| group_of[i] == g))
        };
        // The parts ahead of every group that cannot stay whole.
        let mut ahead: Option<Vec<bool>> = None;
        for (g, group) in groups.iter().enumerate() {
            if !holds_a_body(g) {
                continue;
            }
            let a = &group.accel;
            let mut set = vec![false; n];
            for &i in &group.nodes {
                set[i] = true;
            }
            let mut external = self.external.clone();
            for (i, j, f) in &self.friction {
                let End::Node(j) = j else { continue };
                let (inside, other) = match (set[*i], set[*j]) {
                    (true, false) => (*i, *j),
                    (false, true) => (*j, *i),
                    _ => continue,
                };
                // The other group pulls this one its own way, with the joint's whole capacity.
                match groups[group_of[other]].accel.cmp(a) {
                    Ordering::Greater => external[inside] = &external[inside] + f,
                    Ordering::Less => external[inside] = &external[inside] - f,
                    Ordering::Equal => return Held::Undetermined,
                }
            }
            let touching_a_twin = self.contacts.iter().any(|(l, r)| match (l, r) {
                (End::Node(l), End::Node(r)) if set[*l] != set[*r] => {
                    groups[group_of[*l]].accel == groups[group_of[*r]].accel
                }
                _ => false,
            });
            if touching_a_twin {
                return Held::Undetermined;
            }
            let weight: Vec<Q> = (0..n)
                .map(|i| {
                    if set[i] {
                        &self.mass[i] * a - &external[i]
                    } else {
                        Q::zero()
                    }
                })
                .collect();
            let total: Q = weight.iter().cloned().sum();
            if !total.is_zero() {
                return Held::Undetermined;
            }
            // The cut depends on the group's nodes and weights alone (the joints and faces are
            // the problem's).
            let key = (
                group.nodes.clone(),
                group.nodes.iter().map(|&i| weight[i].clone()).collect(),
            );
            if held.contains(&key) {
                continue;
            }
            let largest = self
                .min_cut(&set, &weight, Side::Upper, false, Want::Largest)
                .1
                .expect("asked for");
            if largest != set {
                let ahead = ahead.get_or_insert_with(|| vec![false; n]);
                for (a, &l) in ahead.iter_mut().zip(&largest) {
                    *a |= l;
                }
            } else {
                held.push(key);
            }
        }
        if let Some(ahead) = ahead {
            return Held::Breaks(ahead);
        }
        // A group is one connected piece of the joint graph (a body given in pieces would
        // otherwise hold them together).
        let adj = self.adjacency();
        Held::Groups(
            groups
                .into_iter()
                .flat_map(|g| {
                    let accel = g.accel;
                    self.pieces(&g.nodes, &adj)
                        .into_iter()
                        .map(move |nodes| Group {
                            nodes,
                            accel: accel.clone(),
                            grounded: false,
                        })
                })
                .collect(),
        )
    }

    /// For blocks that are all stuck to the ground: the interval of ground accelerations
    /// [a_lo, a_hi] over which they can stay stuck, `None` where no ground acceleration would
    /// move them (a block wedged against an abutment). a_hi is the smallest ratio
    /// (cut(S) + e(S)) / m(S) over the sets S that could lag behind the ground (Dinkelbach's
    /// iteration on minimum cuts, exact, a few cuts); a_lo the mirror image. `hints` are sets
    /// (local indices) that broke away from earlier intervals of the same blocks: the iteration
    /// starts from the best of them that could break away here, so when the weakest set has not
    /// changed one cut confirms it instead of several finding it again. Problems of at most
    /// `ENUMERATE_UP_TO` blocks try every set instead.
    pub fn stick_interval(&self, hints: &[Vec<usize>]) -> Stick {
        self.stick_sides(hints, [true, true])
    }

    /// [`Problem::stick_interval`] for the sides `want` ([lo, hi]) only: a side not wanted comes
    /// back as no limit, for the caller to fill in.
    pub fn stick_sides(&self, hints: &[Vec<usize>], want: [bool; 2]) -> Stick {
        self.stick_sides_beyond(hints, want, [None, None])
    }

    /// [`Problem::stick_sides`] where each limit is known to lie at or beyond `bounds` ([lo, hi],
    /// a limit kept as a bound): the search first cuts at the bound, and where a set attains
    /// it that one cut is the answer (a limit that has not moved), instead of the several that
    /// would come down to it from above.
    pub fn stick_sides_beyond(
        &self,
        hints: &[Vec<usize>],
        want: [bool; 2],
        bounds: [Option<&Q>; 2],
    ) -> Stick {
        self.stick_sides_by(hints, want, bounds, ENUMERATE_UP_TO, None)
            .expect("a search asked about no ground acceleration runs to its end")
    }

    /// [`Problem::stick_sides_beyond`] for a caller that needs the limits only if the ground
    /// acceleration `a0` lies strictly between them: `None`, without the rest of the search,
    /// as soon as a set is found that breaks away before a0 (on either side). A stuck piece
    /// that a change leaves beyond its limit is then decided at once, where its limits would
    /// have cost their searches to the end and been thrown away.
    pub fn stick_sides_inside(
        &self,
        hints: &[Vec<usize>],
        want: [bool; 2],
        bounds: [Option<&Q>; 2],
        a0: &Q,
    ) -> Option<Stick> {
        self.stick_sides_by(hints, want, bounds, ENUMERATE_UP_TO, Some(a0))
    }

    /// [`Problem::stick_sides_inside`] (all the way where `a0` is not given), trying every set
    /// for problems of at most `enumerate_up_to` blocks (tests pin the search with 0).
    fn stick_sides_by(
        &self,
        hints: &[Vec<usize>],
        want: [bool; 2],
        bounds: [Option<&Q>; 2],
        enumerate_up_to: usize,
        a0: Option<&Q>,
    ) -> Option<Stick> {
        // a0 lies beyond hi when a set's ratio is below it; beyond lo when a set's ratio on
        // the mirrored side is below -a0.
        let hi = want[1]
            .then(|| {
                let floor = bounds[1].cloned();
                self.min_ratio(
                    &self.external,
                    Side::Lower,
                    hints,
                    floor,
                    enumerate_up_to,
                    a0,
                )
            })
            .flatten();
        if hi
            .as_ref()
            .is_some_and(|(r, _, _)| a0.is_some_and(|a0| r < a0))
        {
            return None;
        }
        let neg: Vec<Q> = self.external.iter().map(|e| -e).collect();
        let minus_a0 = a0.map(|a0| -a0);
        let lo = want[0]
            .then(|| {
                let floor = bounds[0].map(|b| -b);
                self.min_ratio(
                    &neg,
                    Side::Upper,
                    hints,
                    floor,
                    enumerate_up_to,
                    minus_a0.as_ref(),
                )
            })
            .flatten();
        if lo
            .as_ref()
            .is_some_and(|(r, _, _)| minus_a0.as_ref().is_some_and(|m| r < m))
        {
            return None;
        }
        let mut breaking = Vec::new();
        let (mut leaving_lo, mut leaving_hi) = (None, None);
        let hi = hi.map(|(r, set, leaving)| {
            breaking.push(set);
            leaving_hi = leaving;
            r
        });
        let lo = lo.map(|(r, set, leaving)| {
            breaking.push(set);
            leaving_lo = leaving;
            -r
        });
        Some(Stick {
            lo,
            hi,
            breaking,
            leaving_lo,
            leaving_hi,
            bound_only: [false, false],
        })
    }

    /// The least ratio (cut(S) + e(S)) / m(S), and a set S that attains it, over every set of
    /// `allowed` blocks closed under `implies`, tried one by one in integers; `None` if a sum
    /// or a comparison does not fit. For at most [`ENUMERATE_UP_TO`] blocks.
    fn weakest_set(
        &self,
        z: &Integral,
        implies: &[(usize, usize)],
        allowed: &[bool],
    ) -> Option<(Q, Vec<usize>)> {
        let n = self.n();
        let allowed_mask = (0..n).filter(|&i| allowed[i]).fold(0u32, |m, i| m | 1 << i);
        // (force numerator, mass numerator, set) of the weakest set so far.
        let mut best: Option<(i128, i128, u32)> = None;
        for set in 1..1u32 << n {
            let inside = |i: usize| set >> i & 1 == 1;
            if set & !allowed_mask != 0 || implies.iter().any(|&(a, b)| inside(a) && !inside(b)) {
                continue;
            }
            let mut force = 0i128;
            for (k, (i, j, _)) in self.friction.iter().enumerate() {
                let j_inside = matches!(j, End::Node(j) if inside(*j));
                if inside(*i) != j_inside {
                    force = force.checked_add(z.capacity[k])?;
                }
            }
            let mut mass = 0i128;
            for i in (0..n).filter(|&i| inside(i)) {
                force = force.checked_add(z.external[i])?;
                mass = mass.checked_add(z.mass[i])?;
            }
            let weaker = match best {
                None => true,
                Some((f, m, _)) => force.checked_mul(m)? < f.checked_mul(mass)?,
            };
            if weaker {
                best = Some((force, mass, set));
            }
        }
        let (force, mass, set) = best?;
        let members = (0..n).filter(|&i| set >> i & 1 == 1).collect();
        Some((z.ratio(force, mass)?, members))
    }

    /// The undecided joints from a block inside `domain` to a block outside it, as (the block
    /// inside, the joint's index).
    fn leaving(&self, domain: &[bool]) -> Vec<(usize, usize)> {
        let mut out = Vec::new();
        for (k, (i, j, _)) in self.friction.iter().enumerate() {
            if let End::Node(j) = *j {
                if domain[*i] != domain[j] {
                    out.push((if domain[*i] { *i } else { j }, k));
                }
            }
        }
        out
    }

    /// Calls `f` with each undecided joint (its index) that leaves the set `members` (marked in
    /// `inside`) for the ground or a block outside; `at` lists each block's joints.
    fn for_each_cut(
        &self,
        at: &[Vec<usize>],
        members: &[usize],
        inside: &[bool],
        mut f: impl FnMut(usize),
    ) {
        for &i in members {
            for &k in &at[i] {
                let (a, b, _) = &self.friction[k];
                let other_inside = match (*a == i, b) {
                    (true, End::Node(o)) => inside[*o],
                    (true, End::Ground) => false,
                    (false, _) => inside[*a],
                };
                if !other_inside {
                    f(k);
                }
            }
        }
    }

    /// The smallest ratio (cut(S) + e(S)) / m(S) over the sets S that may move the side's way,
    /// a set that attains it, and, where the search ended with a cut, the largest set that
    /// does (the union of all: the blocks that move when a_g passes the limit outward).
    /// `floor`, where given, is known to be at or below the smallest ratio (a kept bound).
    /// `stop`, where given, ends the search at the first set whose ratio lies below it (the
    /// caller only asks whether the smallest ratio does): a ratio below `stop` may be any such
    /// set's, an upper bound on the smallest.
    fn min_ratio(
        &self,
        external: &[Q],
        side: Side,
        hints: &[Vec<usize>],
        floor: Option<Q>,
        enumerate_up_to: usize,
        stop: Option<&Q>,
    ) -> Option<(Q, Vec<usize>, Option<Vec<usize>>)> {
        let n = self.n();
        let all = vec![true; n];
        // Start from every block that may move this way at all.
        let (implies, forbidden) = self.constraints(&all, side, true);
        let mut allowed = vec![true; n];
        let mut stack = forbidden;
        while let Some(b) = stack.pop() {
            if !allowed[b] {
                continue;
            }
            allowed[b] = false;
            for &(x, y) in &implies {
                if y == b && allowed[x] {
                    stack.push(x);
                }
            }
        }
        // The joints at each block, so a set's ratio costs only its own joints.
        let mut at: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (k, (i, j, _)) in self.friction.iter().enumerate() {
            at[*i].push(k);
            if let End::Node(j) = j {
                at[*j].push(k);
            }
        }
        // A set's ratio sums integers over common denominators and reduces once, where they
        // fit: a rational sum reduces at every addition, most of the cost of a search.
        let integral = Integral::new(self, external);
        let ratio = |members: &[usize], inside: &[bool]| -> Q {
            let fast = integral.as_ref().and_then(|z| {
                let mut cut = Some(0i128);
                self.for_each_cut(&at, members, inside, |k| {
                    cut = cut.and_then(|c| c.checked_add(z.capacity[k]));
                });
                let (f, m) = members.iter().try_fold((cut?, 0i128), |(f, m), &i| {
                    Some((f.checked_add(z.external[i])?, m.checked_add(z.mass[i])?))
                })?;
                z.ratio(f, m)
            });
            fast.unwrap_or_else(|| {
                let mut cut = Q::zero();
                self.for_each_cut(&at, members, inside, |k| cut = &cut + &self.friction[k].2);
                let e: Q = members.iter().map(|&i| external[i].clone()).sum();
                let m: Q = members.iter().map(|&i| self.mass[i].clone()).sum();
                (cut + e) / m
            })
        };
        let everything: Vec<usize> = (0..n).filter(|&i| allowed[i]).collect();
        if everything.is_empty() {
            return None;
        }
        if n <= enumerate_up_to {
            let weakest = integral.as_ref();
            if let Some((r, set)) = weakest.and_then(|z| self.weakest_set(z, &implies, &allowed)) {
                return Some((r, set, None));
            }
        }
        let mut lambda = ratio(&everything, &allowed);
        let mut best = everything;
        // Start from the best single block as well: one block breaking away is the usual
        // answer, and starting at it the loop usually needs one cut to confirm it instead of
        // several to find it (each cut costs a maximum flow over the whole problem).
        let mut dragged = vec![false; n];
        for &(a, b) in &implies {
            dragged[a] |= a != b;
        }
        let mut inside = vec![false; n];
        for i in (0..n).filter(|&i| allowed[i] && !dragged[i]) {
            inside[i] = true;
            let r = ratio(&[i], &inside);
            inside[i] = false;
            if r < lambda {
                lambda = r;
                best = vec![i];
            }
        }
        // And from the hints that are sets this side allows (any such set bounds the minimum
        // from above, which is all the iteration needs to be exact).
        for hint in hints.iter().filter(|h| !h.is_empty()) {
            for &i in hint {
                inside[i] = true;
            }
            let possible = hint.iter().all(|&i| allowed[i])
                && implies.iter().all(|&(a, b)| !inside[a] || inside[b]);
            if possible {
                let r = ratio(hint, &inside);
                if r < lambda {
                    lambda = r;
                    best = hint.clone();
                }
            }
            for &i in hint {
                inside[i] = false;
            }
        }
        // Each cut's smallest minimiser S gives the next ratio lambda + f(lambda) / m(S), f < 0
        // the least amount: the lightest minimiser steps furthest, and at the least ratio it is
        // empty. Where both minimisers cost one flow (Dinic, on the smallest networks) it is
        // used; with push-relabel each side is a pass of its own, and the largest alone serves.
        let below_stop = |lambda: &Q| stop.is_some_and(|stop| lambda < stop);
        if below_stop(&lambda) {
            return Some((lambda, best, None));
        }
        let want = if n + 2 < PUSH_RELABEL_FROM {
            Want::Both
        } else {
            Want::Largest
        };
        // Each cut is over a domain of blocks, the rest held still: a joint from the domain to a
        // block outside is cut whenever its block inside moves, a weight of that block's own.
        let cut_at = |lambda: &Q, want: Want, domain: &[bool]| {
            let leaving = self.leaving(domain);
            // The weights come straight in integers where they fit.
            let in_integers = integral.as_ref().and_then(|z| {
                let (mut weight, caps) = z.at(lambda)?;
                for &(i, k) in &leaving {
                    weight[i] = weight[i].checked_add(caps[k])?;
                }
                self.min_cut_in_integers(domain, &weight, &caps, side, true, want)
            });
            in_integers.unwrap_or_else(|| {
                let mut weight: Vec<Q> = (0..n)
                    .map(|i| &external[i] - &self.mass[i] * lambda)
                    .collect();
                for &(i, k) in &leaving {
                    weight[i] = &weight[i] + &self.friction[k].2;
                }
                self.min_cut(domain, &weight, side, true, want)
            })
        };
        // At a floor (a kept bound, at or below the least ratio) every set's amount is at least
        // zero; a set that reaches zero attains the floor, which is then the least ratio, and
        // the largest such set is the cut's largest minimiser. Otherwise the least ratio lies
        // above it, and the search goes on from above.
        if let Some(floor) = floor.filter(|f| *f < lambda) {
            let largest = cut_at(&floor, Want::Largest, &allowed)
                .1
                .expect("asked for");
            let members: Vec<usize> = (0..n).filter(|&i| largest[i]).collect();
            if !members.is_empty() {
                return Some((floor, members.clone(), Some(members)));
            }
        }
        // The largest minimiser grows with lambda (the lemma in docs/model.md, section 5): every
        // minimiser at a lower lambda, the only way the search steps, lies within this cut's
        // largest minimiser, so the next cut need only take that in. Blocks that may not move
        // this way start outside.
        let mut domain = allowed;
        let mut adjacency = None;
        loop {
            let (smallest, largest) = cut_at(&lambda, want, &domain);
            let largest = largest.expect("asked for");
            let members: Vec<usize> = (0..n).filter(|&i| largest[i]).collect();
            if members.is_empty() {
                return Some((lambda, best, None));
            }
            let (step, inside) = match &smallest {
                Some(smallest) => ((0..n).filter(|&i| smallest[i]).collect(), smallest),
                None => (members.clone(), &largest),
            };
            if step.is_empty() {
                return Some((lambda, best, Some(members)));
            }
            // A minimiser in pieces (weak spots apart in the wall, no joint or face between
            // them) has the ratio of their mass-weighted mean: the weakest piece steps further,
            // often to the least ratio at once. Each piece is a set that may move (faces join
            // a piece's blocks), and no joint of it leads to another piece, so `inside` serves.
            let adj = adjacency.get_or_insert_with(|| self.adjacency());
            let (r, step) = self
                .pieces(&step, adj)
                .into_iter()
                .map(|piece| (ratio(&piece, inside), piece))
                .min_by(|a, b| a.0.cmp(&b.0))
                .expect("a step is not empty");
            if r < lambda {
                lambda = r;
                best = step;
                if below_stop(&lambda) {
                    return Some((lambda, best, None));
                }
                domain = largest;
            } else {
                // The cut at the least ratio: its largest minimiser is the union of every set
                // that attains it.
                return Some((lambda, best, Some(members)));
            }
        }
    }
}

/// The weaker of two limits on one side of a stick interval (`hi`: the lower of two upper
/// limits, else the higher of two lower ones); `None` is no limit that way.
pub fn weaker_limit(a: Option<Q>, b: Option<Q>, hi: bool) -> Option<Q> {
    match (a, b) {
        (Some(a), Some(b)) => Some(if hi { a.min(b) } else { a.max(b) }),
        (a, b) => a.or(b),
    }
}

/// How a problem solved with bodies held together came out ([`Problem::solve_contracted`]).
enum Held {
    /// Every body held: the groups of the full problem.
    Groups(Vec<Group>),
    /// Some groups cannot stay whole: the parts of them that would move ahead.
    Breaks(Vec<bool>),
    /// A group touches another moving at its own acceleration.
    Undetermined,
}

/// Where blocks stuck to the ground stop being stuck ([`Problem::stick_interval`]).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stick {
    /// The lowest ground acceleration they stay stuck at (m/s2); `None`: no limit.
    pub lo: Option<Q>,
    /// The highest (m/s2); `None`: no limit.
    pub hi: Option<Q>,
    /// Sets (local indices, sorted) that break away at the finite limits.
    pub breaking: Vec<Vec<usize>>,
    /// The blocks (local indices, sorted) that move when a_g falls through `lo`, where the
    /// search ended with a cut at it ([`Problem::solve_past_limit`]).
    pub leaving_lo: Option<Vec<usize>>,
    /// The same for a_g rising through `hi`.
    pub leaving_hi: Option<Vec<usize>>,
    /// Per side ([lo, hi]): the limit is a bound from inside that a change of the blocks could
    /// not have narrowed, kept instead of worked out again (the exact limit lies at it or
    /// beyond); it is worked out when a_g reaches it.
    pub bound_only: [bool; 2],
}

/// A problem's joint capacities, one side's external forces and its masses as integers over
/// common denominators ([`over_common_denominator`]).
struct Integral {
    /// Capacities, over `force_den`.
    capacity: Vec<i128>,
    /// External forces, over `force_den`.
    external: Vec<i128>,
    force_den: i128,
    /// Masses, over `mass_den`.
    mass: Vec<i128>,
    mass_den: i128,
}

impl Integral {
    /// `None` when the numbers do not fit.
    fn new(p: &Problem, external: &[Q]) -> Option<Integral> {
        let forces = p.friction.iter().map(|j| &j.2).chain(external);
        let (mut capacity, force_den) = over_common_denominator(forces)?;
        let external = capacity.split_off(p.friction.len());
        let (mass, mass_den) = over_common_denominator(p.mass.iter())?;
        Some(Integral {
            capacity,
            external,
            force_den,
            mass,
            mass_den,
        })
    }

    /// The weights e_i - lambda m_i and the joints' capacities as integers over one denominator
    /// (lcm(F, M q) for lambda = p / q, F and M the force and mass denominators), for a cut in
    /// integers without a rational operation; `None` when they do not fit.
    fn at(&self, lambda: &Q) -> Option<(Vec<i128>, Vec<i128>)> {
        let (p, q) = lambda.small_parts()?;
        // Over lcm(F, M q): forces scale by lcm / F, masses times p by lcm / (M q).
        let mass_q = self.mass_den.checked_mul(q)?;
        let g = gcd_i128(self.force_den, mass_q);
        let per_force = div(mass_q, g);
        let per_mass = div(self.force_den, g).checked_mul(p)?;
        let weight = self
            .external
            .iter()
            .zip(&self.mass)
            .map(|(e, m)| {
                e.checked_mul(per_force)?
                    .checked_sub(m.checked_mul(per_mass)?)
            })
            .collect::<Option<Vec<i128>>>()?;
        let caps = self
            .capacity
            .iter()
            .map(|c| c.checked_mul(per_force))
            .collect::<Option<Vec<i128>>>()?;
        Some((weight, caps))
    }

    /// The exact ratio of a sum of force numerators to a (positive) sum of mass numerators, if
    /// it fits.
    fn ratio(&self, force: i128, mass: i128) -> Option<Q> {
        Some(Q::frac(
            force.checked_mul(self.mass_den)?,
            mass.checked_mul(self.force_den)?,
        ))
    }
}

/// The sides of the minimum cuts a caller asked for ([`Want`]): the source side of the
/// smallest, the sink side of the largest.
type Sides = (Option<Vec<bool>>, Option<Vec<bool>>);

/// A minimum-cut question on n blocks plus source n and sink n + 1: `arcs` (from, to, both
/// ways), `implies` (a on the source side puts b there) and `forbidden` blocks (never on the
/// source side); each answer takes the arcs' capacities.
struct Cut<'a> {
    n: usize,
    arcs: &'a [(usize, usize, bool)],
    implies: &'a [(usize, usize)],
    forbidden: &'a [usize],
}

impl Cut<'_> {
    /// The minimum cuts the caller wants, each as its side of the network: the source side of
    /// the smallest, the sink side of the largest.
    fn minimum<A: Amount>(&self, caps: &[A], want: Want) -> Sides {
        if self.n <= CUT_ENUMERATE_UP_TO && self.arcs.len() <= 64 {
            let (source_side, sink_side) = sides(self.n, self.by_enumeration(caps));
            return (
                (want != Want::Largest).then_some(source_side),
                (want != Want::Smallest).then_some(sink_side),
            );
        }
        self.by_flow(caps, want)
    }

    /// [`Cut::minimum`] by a maximum flow: the network from `arcs`, the constraint arcs with a
    /// capacity above every cut; the source side of the minimal minimum cut, the nodes that
    /// reach the sink in every maximum flow.
    fn by_flow<A: Amount>(&self, caps: &[A], want: Want) -> Sides {
        let Cut {
            n,
            arcs,
            implies,
            forbidden,
        } = *self;
        let (s, t) = (n, n + 1);
        // Every capacity is positive, so their sum (plus one) exceeds every cut.
        let big = caps.iter().fold(A::unit(), |b, c| b.plus(c));
        let big = &big;
        let mut net: Network<A> = Network::new(n + 2);
        for (k, &(u, v, both)) in arcs.iter().enumerate() {
            if both {
                net.edge(u, v, caps[k].clone());
            } else {
                net.arc(u, v, caps[k].clone());
            }
        }
        for &(a, b) in implies {
            net.arc(a, b, big.clone());
        }
        for &a in forbidden {
            net.arc(a, t, big.clone());
        }
        match want {
            Want::Both => {
                let (source_side, sink_side) = net.minimum_cuts(s, t, big);
                (Some(source_side), Some(sink_side))
            }
            Want::Smallest => (Some(net.source_side(s, t, big)), None),
            Want::Largest => (None, Some(net.sink_side(s, t, big))),
        }
    }

    /// [`Cut::minimum`] by trying every source side allowed (n < 32, at most 64 arcs), as bit
    /// sets: the smallest and the largest minimiser (the minimisers are closed under
    /// intersection and union). The sets are visited in Gray-code order, so each step moves one
    /// block and changes the cut by its own arcs only.
    fn by_enumeration<A: Amount>(&self, caps: &[A]) -> (u32, u32) {
        let Cut {
            n,
            arcs,
            implies,
            forbidden,
        } = *self;
        let s = n;
        let mut at = vec![0u64; n];
        for (k, &(u, v, _)) in arcs.iter().enumerate() {
            for x in [u, v].into_iter().filter(|&x| x < n) {
                at[x] |= 1 << k;
            }
        }
        let mut needs = vec![0u32; n];
        for &(a, b) in implies {
            needs[a] |= 1 << b;
        }
        let banned = forbidden.iter().fold(0u32, |m, &a| m | 1 << a);
        let cuts = |k: usize, set: u32| {
            let inside = |x: usize| x == s || (x < n && set >> x & 1 == 1);
            let (u, v, both) = arcs[k];
            (inside(u) && !inside(v)) || (both && inside(v) && !inside(u))
        };
        let mut set = 0u32;
        let mut cut = (0..arcs.len())
            .filter(|&k| cuts(k, set))
            .fold(A::zero(), |c, k| c.plus(&caps[k]));
        // The empty set is always allowed.
        let (mut best, mut smallest, mut largest) = (cut.clone(), 0u32, 0u32);
        for step in 1u32..1 << n {
            let x = step.trailing_zeros() as usize;
            let moved = set ^ 1 << x;
            let mut arcs_at = at[x];
            while arcs_at != 0 {
                let k = arcs_at.trailing_zeros() as usize;
                arcs_at &= arcs_at - 1;
                match (cuts(k, set), cuts(k, moved)) {
                    (true, false) => cut = cut.minus(&caps[k]),
                    (false, true) => cut = cut.plus(&caps[k]),
                    _ => {}
                }
            }
            set = moved;
            let allowed =
                set & banned == 0 && (0..n).all(|a| set >> a & 1 == 0 || needs[a] & !set == 0);
            if !allowed {
                continue;
            }
            match cut.cmp(&best) {
                Ordering::Less => (best, smallest, largest) = (cut.clone(), set, set),
                Ordering::Equal => (smallest, largest) = (smallest & set, largest | set),
                Ordering::Greater => {}
            }
        }
        (smallest, largest)
    }
}

/// The smallest and the largest minimiser over n blocks, as bit sets, written as the sides of
/// the network that [`Cut::minimum`] returns.
fn sides(n: usize, (smallest, largest): (u32, u32)) -> (Vec<bool>, Vec<bool>) {
    let (s, t) = (n, n + 1);
    (
        (0..n + 2)
            .map(|i| i == s || (i < n && smallest >> i & 1 == 1))
            .collect(),
        (0..n + 2)
            .map(|i| i == t || (i < n && largest >> i & 1 == 0))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::event::flow;
    use proptest::prelude::*;

    fn q(x: f64) -> Q {
        Q::from_decimal(x).unwrap()
    }

    /// One block of 1 kg on the ground with capacity mu g.
    fn one_block(mu: f64) -> Problem {
        Problem {
            mass: vec![Q::one()],
            external: vec![Q::zero()],
            friction: vec![(0, End::Ground, q(mu) * q(9.81))],
            contacts: vec![],
        }
    }

    /// Three blocks in a row, each resting on the one to its left (the first on the ground),
    /// touching face to face.
    fn three_in_a_row() -> Problem {
        Problem {
            mass: vec![Q::one(); 3],
            external: vec![q(0.5), Q::zero(), Q::zero()],
            friction: vec![
                (0, End::Ground, q(1.0)),
                (1, End::Node(0), q(2.0)),
                (2, End::Node(1), q(3.0)),
            ],
            contacts: vec![(End::Node(0), End::Node(1)), (End::Node(1), End::Node(2))],
        }
    }

    #[test]
    fn neighbours_held_at_the_ground_keep_their_joints_and_faces_as_the_grounds() {
        let p = three_in_a_row();
        let beside = p.beside_ground(&[1]);
        assert_eq!(beside.mass, vec![Q::one()]);
        assert_eq!(
            beside.friction,
            vec![(0, End::Ground, q(2.0)), (0, End::Ground, q(3.0))]
        );
        assert_eq!(
            beside.contacts,
            vec![(End::Node(0), End::Ground), (End::Ground, End::Node(0))]
        );
        // Held as the ground for a bound from inside, faces against the others are dropped.
        assert!(p.with_ground(&[1]).contacts.is_empty());
    }

    #[test]
    fn neighbours_sliding_past_pull_with_their_joints_capacity_and_their_faces_open() {
        let p = three_in_a_row();
        let ahead = p.beside_sliding(&[0, 1], &[0, 0, 1]);
        assert_eq!(ahead.external, vec![q(0.5), q(3.0)]);
        assert_eq!(
            ahead.friction,
            vec![(0, End::Ground, q(1.0)), (1, End::Node(0), q(2.0))]
        );
        assert_eq!(ahead.contacts, vec![(End::Node(0), End::Node(1))]);
        let behind = p.beside_sliding(&[1, 2], &[-1, 0, 0]);
        assert_eq!(behind.external, vec![q(-2.0), Q::zero()]);
        assert_eq!(behind.friction, vec![(1, End::Node(0), q(3.0))]);
        assert_eq!(behind.contacts, vec![(End::Node(0), End::Node(1))]);
    }

    #[test]
    fn equal_problems_hash_alike_whatever_their_memory() {
        use std::hash::BuildHasher;
        let hash = |p: &Problem| rustc_hash::FxBuildHasher.hash_one(p);
        let p = five_block([0.3; 6]);
        // The same numbers reached another way, in vectors with room to spare.
        let mut twin = Problem::default();
        twin.mass.reserve(64);
        twin.mass
            .extend(p.mass.iter().map(|m| m * &Q::int(3) / Q::int(3)));
        twin.external.extend(p.external.iter().cloned());
        twin.friction.extend(p.friction.iter().cloned());
        twin.contacts.extend(p.contacts.iter().cloned());
        assert_eq!(twin, p);
        assert_eq!(hash(&twin), hash(&p));
        // One capacity, one end or one face changed: another problem, another hash.
        let mut other = p.clone();
        other.friction[0].2 = &other.friction[0].2 + &Q::frac(1, 1000);
        assert_ne!(hash(&other), hash(&p));
        let mut other = p.clone();
        other.friction[0].1 = End::Node(4);
        assert_ne!(hash(&other), hash(&p));
        let mut other = p.clone();
        other.contacts.pop();
        assert_ne!(hash(&other), hash(&p));
    }

    #[test]
    fn large_problems_that_hash_alike_are_told_apart() {
        use super::super::memo::Memo;
        use std::hash::BuildHasher;
        let hash = |p: &Problem| rustc_hash::FxBuildHasher.hash_one(p);
        // A chain of 300 blocks: its hash takes in every fifth block, so the second block's
        // mass is not in it.
        let n = 300;
        let p = Problem {
            mass: vec![Q::int(2); n],
            external: vec![Q::zero(); n],
            friction: (1..n).map(|i| (i, End::Node(i - 1), Q::int(1))).collect(),
            contacts: Vec::new(),
        };
        let mut other = p.clone();
        other.mass[1] = Q::int(3);
        assert_eq!(hash(&other), hash(&p));
        assert_ne!(other, p);
        let mut memo = Memo::new();
        memo.insert(p.clone(), 1, n);
        assert_eq!(memo.get(&other), None);
        memo.insert(other.clone(), 2, n);
        assert_eq!((memo.get(&p), memo.get(&other)), (Some(&1), Some(&2)));
    }

    fn just_after(a: Q, rate: i64) -> Lex {
        Lex([a, Q::int(rate), Q::zero()])
    }

    #[test]
    fn one_block_sticks_within_mu_g_and_slides_beyond() {
        let p = one_block(0.3);
        let mug = q(0.3) * q(9.81);
        let stick = p.stick_interval(&[]);
        assert_eq!((stick.lo, stick.hi), (Some(-&mug), Some(mug.clone())));
        let g = p.solve(&just_after(q(1.0), 0), &[]);
        assert_eq!(
            g,
            vec![Group {
                nodes: vec![0],
                accel: q(1.0),
                grounded: true
            }]
        );
        // Exactly at the limit: rising ground acceleration makes it slide, falling keeps it.
        let g = p.solve(&just_after(mug.clone(), 1), &[]);
        assert_eq!(
            g,
            vec![Group {
                nodes: vec![0],
                accel: mug.clone(),
                grounded: false
            }]
        );
        let g = p.solve(&just_after(mug.clone(), -1), &[]);
        assert!(g[0].grounded);
        // The mirror image, and a steady ground (a record's constant stretch): exactly the
        // capacity holds it.
        let g = p.solve(&just_after(-&mug, -1), &[]);
        assert_eq!((g[0].accel.clone(), g[0].grounded), (-&mug, false));
        for at in [mug.clone(), -&mug] {
            assert!(p.solve(&just_after(at.clone(), 1), &[])[0].grounded != at.is_positive());
            assert!(p.solve(&just_after(at, 0), &[])[0].grounded);
        }
        // Beyond: slides with friction mu g pulling it along.
        let g = p.solve(&just_after(q(5.0), 0), &[]);
        assert_eq!(g[0].accel, mug);
        assert!(!g[0].grounded);
    }

    /// The paper's wall with uniform friction: B1..B5, masses in units of B3's mass.
    fn five_block(mu: [f64; 6]) -> Problem {
        let g = q(9.81);
        let m = [Q::int(2), Q::int(2), Q::int(1), Q::int(2), Q::int(1)];
        let load = [
            Q::int(4),
            Q::int(4),
            Q::int(1),
            Q::int(1),
            Q::int(1),
            Q::int(1),
        ];
        let cap = |k: usize| q(mu[k]) * &load[k] * &g;
        Problem {
            mass: m.to_vec(),
            external: vec![Q::zero(); 5],
            friction: vec![
                (0, End::Ground, cap(0)),
                (1, End::Ground, cap(1)),
                (2, End::Node(0), cap(2)),
                (3, End::Node(0), cap(3)),
                (3, End::Node(1), cap(4)),
                (4, End::Node(1), cap(5)),
            ],
            contacts: vec![
                (End::Node(0), End::Node(1)),
                (End::Node(2), End::Node(3)),
                (End::Node(3), End::Node(4)),
            ],
        }
    }

    #[test]
    fn uniform_wall_breaks_away_as_one_body() {
        let p = five_block([0.3; 6]);
        let mug = q(0.3) * q(9.81);
        let stick = p.stick_interval(&[]);
        assert_eq!((stick.lo, stick.hi), (Some(-&mug), Some(mug.clone())));
        // At the threshold, rising: the whole wall moves, every upper joint exactly at its limit
        // and sticking.
        let g = p.solve(&just_after(mug.clone(), 1), &[]);
        assert_eq!(
            g,
            vec![Group {
                nodes: vec![0, 1, 2, 3, 4],
                accel: mug.clone(),
                grounded: false
            }]
        );
        // Falling back: everything stuck, one cluster through the touching faces.
        let g = p.solve(&just_after(mug.clone(), -1), &[]);
        assert_eq!(g.len(), 1);
        assert!(g[0].grounded);
        // Well beyond: still one body.
        let g = p.solve(&just_after(q(-7.0), 0), &[]);
        assert_eq!(
            g,
            vec![Group {
                nodes: vec![0, 1, 2, 3, 4],
                accel: -mug,
                grounded: false
            }]
        );
    }

    #[test]
    fn cuts_whose_flows_could_overflow_are_made_in_rationals() {
        // Two free blocks joined by a joint of capacity b = 2^123, weights -3b and 2b: the
        // least amount is {0} (-3b + b). The amounts sum to 6b, above a quarter of i128's range
        // though no flow through this network would overflow: the integer cut refuses, lest a
        // larger network overflow inside its flow, and the rational cut gives the answer.
        let b = 1i128 << 123;
        let p = Problem {
            mass: vec![Q::one(), Q::one()],
            external: vec![Q::zero(), Q::zero()],
            friction: vec![(0, End::Node(1), Q::frac(b, 1))],
            contacts: Vec::new(),
        };
        let all = [true, true];
        let refused =
            p.min_cut_in_integers(&all, &[-3 * b, 2 * b], &[b], Side::Upper, false, Want::Both);
        assert_eq!(refused, None);
        let weight = [Q::frac(-3 * b, 1), Q::frac(2 * b, 1)];
        let (smallest, largest) = p.min_cut(&all, &weight, Side::Upper, false, Want::Both);
        assert_eq!(smallest, Some(vec![true, false]));
        assert_eq!(largest, Some(vec![true, false]));
        // Scaled down by 2^50 the integer cut takes it in 128 bits, by 2^100 in 64 (its total
        // below 2^61), with the same answer.
        for shift in [50, 100] {
            let small = [-3 * (b >> shift), 2 * (b >> shift)];
            let taken =
                p.min_cut_in_integers(&all, &small, &[b >> shift], Side::Upper, false, Want::Both);
            assert_eq!(taken, Some((smallest.clone(), largest.clone())));
        }
    }

    #[test]
    fn variable_wall_first_break_is_the_weakest_set() {
        let p = five_block([0.29, 0.31, 0.28, 0.30, 0.30, 0.28]);
        let Stick { lo, hi, .. } = p.stick_interval(&[]);
        // B3 and B5 on 0.28 go first: a_hi = 0.28 g; leftward the faces hold B3 against B4 and
        // B5 is the one that lags: also 0.28 g.
        assert_eq!(hi, Some(q(0.28) * q(9.81)));
        assert_eq!(lo, Some(-(q(0.28) * q(9.81))));
        let a = q(0.28) * q(9.81);
        let g = p.solve(&just_after(a.clone(), 1), &[]);
        // Pushed rightward by the ground, B3 lags behind (moves -x relative) and opens from B4;
        // B5 would have to push B4: it stays.
        let moving: Vec<&Group> = g.iter().filter(|g| !g.grounded).collect();
        assert_eq!(moving.len(), 1);
        assert_eq!(moving[0].nodes, vec![2]);
        assert_eq!(moving[0].accel, a);
    }

    /// 40 blocks in a row on the ground (push-relabel's size), two weak runs of 8 far apart, each
    /// held together by strong joints: A = 5..13 (ratio (8 x 3 + 1 + 1) / 8 = 3.25, the limit
    /// a_hi) and B = 30..38 (3.45; both together 3.35).
    const RUN: usize = 8;
    const ROW: usize = 40;

    /// The limit a_hi's search finds from `hints` and the `bound` it is known to lie at or
    /// beyond, and the work it took, in flow-network nodes.
    fn cuts_between_two_weak_runs(hints: &[Vec<usize>], bound: Option<&Q>) -> u64 {
        let (in_a, in_b) = (
            |i: usize| (5..5 + RUN).contains(&i),
            |i: usize| (30..30 + RUN).contains(&i),
        );
        let weak = |i: usize| in_a(i) || in_b(i);
        let mut friction: Vec<(usize, End, Q)> = (0..ROW)
            .map(|i| {
                let cap = match i {
                    _ if in_a(i) => Q::int(3),
                    _ if in_b(i) => q(3.2),
                    _ => Q::int(10),
                };
                (i, End::Ground, cap)
            })
            .collect();
        for i in 0..ROW - 1 {
            let strong = weak(i) && weak(i + 1);
            friction.push((i, End::Node(i + 1), Q::int(if strong { 100 } else { 1 })));
        }
        let p = Problem {
            mass: vec![Q::one(); ROW],
            external: vec![Q::zero(); ROW],
            friction,
            contacts: vec![],
        };
        let from = flow::pass_nodes();
        let stick = p
            .stick_sides_by(hints, [false, true], [None, bound], 0, None)
            .unwrap();
        assert_eq!(stick.hi, Some(Q::frac(13, 4)));
        assert_eq!(stick.leaving_hi, Some((5..5 + RUN).collect()));
        flow::pass_nodes() - from
    }

    /// A cut over the whole row, and one over both runs (each a flow network with a source and
    /// a sink).
    const WHOLE_ROW: u64 = ROW as u64 + 2;
    const BOTH_RUNS: u64 = 2 * RUN as u64 + 2;

    #[test]
    fn a_minimiser_in_pieces_steps_to_its_weakest_piece() {
        // From a hint naming run A, one cut over the row confirms it. From the whole row
        // (289.6 / 40 = 7.24) the first cut's minimiser is both runs, whose ratio 3.35 would
        // take a second cut to reach 3.25; its weakest piece is the answer, and one more cut
        // confirms it. That cut takes in only the first's minimiser, both runs: without the
        // step to the piece, a third would take in run A.
        assert_eq!(
            cuts_between_two_weak_runs(&[(5..5 + RUN).collect()], None),
            WHOLE_ROW
        );
        assert_eq!(cuts_between_two_weak_runs(&[], None), WHOLE_ROW + BOTH_RUNS);
    }

    #[test]
    fn a_bound_at_the_limit_is_confirmed_by_one_cut() {
        // At the limit, one cut shows a set attains it; below it, that cut finds none, and the
        // search goes on from above as without it.
        assert_eq!(
            cuts_between_two_weak_runs(&[], Some(&Q::frac(13, 4))),
            WHOLE_ROW
        );
        assert_eq!(
            cuts_between_two_weak_runs(&[], Some(&Q::frac(16, 5))),
            2 * WHOLE_ROW + BOTH_RUNS
        );
    }

    #[test]
    fn hints_change_the_work_not_the_interval() {
        // Every subset of the five blocks as a hint, valid or not (a set whose faces would have
        // to pull is no candidate): the same interval, and the sets returned attain it.
        for p in [
            five_block([0.29, 0.31, 0.28, 0.30, 0.30, 0.28]),
            five_block([0.3; 6]),
            five_block([0.35, 0.2, 0.5, 0.1, 0.4, 0.3]),
        ] {
            // The search with minimum cuts (small problems would try every set instead).
            let plain = p
                .stick_sides_by(&[], [true, true], [None, None], 0, None)
                .unwrap();
            for mask in 1..32usize {
                let hint: Vec<usize> = (0..5).filter(|i| mask >> i & 1 == 1).collect();
                let hinted = p
                    .stick_sides_by(&[hint, vec![]], [true, true], [None, None], 0, None)
                    .unwrap();
                assert_eq!((&hinted.lo, &hinted.hi), (&plain.lo, &plain.hi), "{mask}");
                let sets: Vec<&Vec<usize>> = hinted.breaking.iter().collect();
                assert_eq!(sets.len(), 2);
                let ratio = |set: &[usize], external: &dyn Fn(usize) -> Q| {
                    let mut cut = Q::zero();
                    for (i, j, f) in &p.friction {
                        let j_in = matches!(j, End::Node(j) if set.contains(j));
                        if set.contains(i) != j_in {
                            cut = cut + f;
                        }
                    }
                    let e: Q = set.iter().map(|&i| external(i)).sum();
                    let m: Q = set.iter().map(|&i| p.mass[i].clone()).sum();
                    (cut + e) / m
                };
                let hi = hinted.hi.clone().unwrap();
                let lo = hinted.lo.clone().unwrap();
                assert_eq!(ratio(sets[0], &|i| p.external[i].clone()), hi);
                assert_eq!(-ratio(sets[1], &|i| -&p.external[i]), lo);
            }
        }
    }

    /// Random problems away from the ground: masses, sliding forces, joints and faces.
    fn free_problem() -> impl Strategy<Value = Problem> {
        (2usize..9).prop_flat_map(|n| {
            (
                prop::collection::vec(1i64..6, n),
                prop::collection::vec(-12i64..13, n),
                prop::collection::vec((0..n, 0..n, 1i64..9), 1..2 * n),
                prop::collection::vec((0..n, 0..n), 0..n),
            )
                .prop_map(|(mass, external, joints, faces)| Problem {
                    mass: mass.into_iter().map(Q::int).collect(),
                    external: external.into_iter().map(Q::int).collect(),
                    friction: joints
                        .into_iter()
                        .filter(|(i, j, _)| i != j)
                        .map(|(i, j, f)| (i, End::Node(j), Q::int(f)))
                        .collect(),
                    contacts: faces
                        .into_iter()
                        .filter(|(l, r)| l != r)
                        .map(|(l, r)| (End::Node(l), End::Node(r)))
                        .collect(),
                })
        })
    }

    /// Random problems on the ground: `free_problem` with some blocks resting on it.
    fn ground_problem() -> impl Strategy<Value = Problem> {
        (
            free_problem(),
            prop::collection::vec((0usize..8, 1i64..9), 1..5),
        )
            .prop_map(|(mut p, on)| {
                let n = p.mass.len();
                for (i, f) in on {
                    p.friction.push((i % n, End::Ground, Q::int(f)));
                }
                p
            })
    }

    /// The stick interval by enumeration: the least ratio (cut(S) + e(S)) / m(S) over every set
    /// S that may move each way (closed under its faces, none pushed into the ground).
    fn stick_by_enumeration(p: &Problem) -> (Option<Q>, Option<Q>) {
        let n = p.n();
        let best = |external: &[Q], side: Side| -> Option<Q> {
            let (implies, forbidden) = p.constraints(&vec![true; n], side, true);
            (1..1u32 << n)
                .filter_map(|mask| {
                    let inside = |i: usize| mask >> i & 1 == 1;
                    let admissible = forbidden.iter().all(|&a| !inside(a))
                        && implies.iter().all(|&(a, b)| !inside(a) || inside(b));
                    admissible.then(|| {
                        let mut cut = Q::zero();
                        for (i, j, f) in &p.friction {
                            let j_in = matches!(j, End::Node(j) if inside(*j));
                            if inside(*i) != j_in {
                                cut = cut + f;
                            }
                        }
                        let set = (0..n).filter(|&i| inside(i));
                        let e: Q = set.clone().map(|i| external[i].clone()).sum();
                        let m: Q = set.map(|i| p.mass[i].clone()).sum();
                        (cut + e) / m
                    })
                })
                .min()
        };
        let neg: Vec<Q> = p.external.iter().map(|e| -e).collect();
        (
            best(&neg, Side::Upper).map(|r| -r),
            best(&p.external, Side::Lower),
        )
    }

    /// The same problem with every capacity and mass off by a fraction with a large prime
    /// denominator (Mersenne primes, pairwise coprime): over a common denominator they no
    /// longer fit 128 bits, and the exact rational path is taken.
    fn with_coprime_denominators(mut p: Problem) -> Problem {
        const PRIMES: [i128; 5] = [
            (1i128 << 61) - 1,
            (1 << 31) - 1,
            (1 << 19) - 1,
            8191,
            131_071,
        ];
        for (k, joint) in p.friction.iter_mut().enumerate() {
            joint.2 = &joint.2 + &Q::frac(1, PRIMES[k % PRIMES.len()]);
        }
        for (k, m) in p.mass.iter_mut().enumerate() {
            *m = &*m + &Q::frac(1, PRIMES[(k + 1) % PRIMES.len()]);
        }
        p
    }

    /// `ground_problem` with some blocks' faces against an abutment, on either side.
    fn abutted_problem() -> impl Strategy<Value = Problem> {
        (
            ground_problem(),
            prop::collection::vec((0usize..8, any::<bool>()), 0..3),
        )
            .prop_map(|(mut p, faces)| {
                let n = p.mass.len();
                for (i, abutment_left) in faces {
                    p.contacts.push(if abutment_left {
                        (End::Ground, End::Node(i % n))
                    } else {
                        (End::Node(i % n), End::Ground)
                    });
                }
                p
            })
    }

    /// The sub-problem of the nodes whose label is `kept`, each joint to a node of another label
    /// turned into a sliding force of its full capacity, of sign `towards[label]`, on the kept
    /// end; faces to other labels dropped.
    fn sliding_against(
        p: &Problem,
        labels: &[usize],
        kept: [bool; 3],
        towards: [i64; 3],
    ) -> Problem {
        let nodes: Vec<usize> = (0..p.n()).filter(|&i| kept[labels[i]]).collect();
        let mut q = p.restrict(&nodes);
        for (i, j, f) in &p.friction {
            let End::Node(j) = *j else { continue };
            for (a, b) in [(*i, j), (j, *i)] {
                if kept[labels[a]] && !kept[labels[b]] {
                    let k = nodes.binary_search(&a).expect("kept");
                    q.external[k] = &q.external[k] + &(Q::int(towards[labels[b]]) * f);
                }
            }
        }
        q
    }

    /// Up to two bodies among the first n nodes: those labelled 1, those labelled 2 (a body of
    /// one node is none).
    fn labelled_bodies(labels: &[usize], n: usize) -> Vec<Vec<usize>> {
        [1, 2]
            .iter()
            .map(|&b| (0..n).filter(|&i| labels[i] == b).collect::<Vec<usize>>())
            .filter(|body| body.len() >= 2)
            .collect()
    }

    fn sorted(mut groups: Vec<Group>) -> Vec<Group> {
        groups.sort_by(|a, b| a.nodes.cmp(&b.nodes));
        groups
    }

    /// A small cut problem: n blocks plus source n and sink n + 1, arcs (one way or both) with
    /// capacities from 0 (ties) up, blocks implying others and blocks kept off the source side.
    #[allow(clippy::type_complexity)]
    fn cut_problem() -> impl Strategy<
        Value = (
            usize,
            Vec<(usize, usize, i128, bool)>,
            Vec<(usize, usize)>,
            Vec<usize>,
        ),
    > {
        (1usize..8).prop_flat_map(|n| {
            let arc = (0..n + 2, 0..n + 2, 0i128..6, any::<bool>());
            let arcs = prop::collection::vec(arc, 0..3 * n + 2)
                .prop_map(|arcs| arcs.into_iter().filter(|a| a.0 != a.1).collect::<Vec<_>>());
            let implies = prop::collection::vec((0..n, 0..n), 0..n);
            let forbidden = prop::collection::vec(0..n, 0..2);
            (Just(n), arcs, implies, forbidden)
        })
    }

    proptest! {
        #![proptest_config(crate::integrate::event::many_cheap_cases())]

        /// Trying every set finds the same smallest and largest minimum cuts as a maximum flow.
        #[test]
        fn enumerated_cuts_are_the_flow_cuts((n, arcs, implies, forbidden) in cut_problem()) {
            let ints: Vec<i128> = arcs.iter().map(|a| a.2).collect();
            let arcs: Vec<(usize, usize, bool)> = arcs.iter().map(|a| (a.0, a.1, a.3)).collect();
            let question = Cut { n, arcs: &arcs, implies: &implies, forbidden: &forbidden };
            let flow = question.by_flow(&ints, Want::Both);
            let tried = sides(n, question.by_enumeration(&ints));
            prop_assert_eq!((flow.0.unwrap(), flow.1.unwrap()), tried);
        }

        /// The split at the ground is the smallest set minimising the amount in lexicographic
        /// triples, (c0, c1, c2) with the weights' terms in eps and eps^2, tried set by set.
        #[test]
        fn the_ground_splits_where_triples_are_least(
            p in abutted_problem(),
            a0 in -12i64..13,
            rates in (-1i64..2, -1i64..2),
        ) {
            let theta = Lex([Q::int(a0), Q::int(rates.0), Q::int(rates.1)]);
            let n = p.mass.len();
            for (side, sign) in [(Side::Upper, 1), (Side::Lower, -1)] {
                let (implies, forbidden) = p.constraints(&vec![true; n], side, true);
                let sign = Q::int(sign);
                let mut least: Option<(Lex, u32)> = None;
                for set in 0u32..1 << n {
                    let inside = |i: usize| set >> i & 1 == 1;
                    let closed = implies.iter().all(|&(a, b)| !inside(a) || inside(b))
                        && forbidden.iter().all(|&a| !inside(a));
                    if !closed {
                        continue;
                    }
                    let mut amount = [Q::zero(), Q::zero(), Q::zero()];
                    for i in (0..n).filter(|&i| inside(i)) {
                        let w = &theta.0[0] * &p.mass[i] - &p.external[i];
                        amount[0] = &amount[0] + &sign * &w;
                        for (a, rate) in amount.iter_mut().zip(&theta.0).skip(1) {
                            *a = &*a + &sign * &(rate * &p.mass[i]);
                        }
                    }
                    for (i, j, f) in &p.friction {
                        let crosses = match j {
                            End::Node(j) => inside(*i) != inside(*j),
                            End::Ground => inside(*i),
                        };
                        if crosses {
                            amount[0] = &amount[0] + f;
                        }
                    }
                    let amount = Lex(amount);
                    least = match least {
                        Some((best, _)) if amount < best => Some((amount, set)),
                        Some((best, smallest)) if amount == best => Some((best, smallest & set)),
                        Some(kept) => Some(kept),
                        None => Some((amount, set)),
                    };
                }
                let (_, smallest) = least.expect("the empty set is allowed");
                let expected: Vec<bool> = (0..n).map(|i| smallest >> i & 1 == 1).collect();
                // In integers where they fit, and in rationals.
                let at_ground = p.integral_at(&theta.0[0]);
                prop_assert!(at_ground.is_some());
                prop_assert_eq!(&p.split_at_ground(&theta, side, at_ground.as_ref()), &expected);
                prop_assert_eq!(p.split_at_ground(&theta, side, None), expected);
            }
        }

        /// The stick interval is the weakest set's ratio, whether the search sums integers over
        /// common denominators or, where they do not fit, exact rationals.
        #[test]
        fn stick_intervals_are_the_weakest_sets(p in abutted_problem()) {
            // Both ways: every set tried in integers, and the search with minimum cuts.
            let interval = |p: &Problem, enumerate_up_to: usize| {
                let Stick { lo, hi, .. } = p.stick_sides_by(&[], [true, true], [None, None], enumerate_up_to, None).unwrap();
                (lo, hi)
            };
            let want = stick_by_enumeration(&p);
            prop_assert_eq!(interval(&p, ENUMERATE_UP_TO), want.clone());
            let plain = p.stick_sides_by(&[], [true, true], [None, None], 0, None).unwrap();
            prop_assert_eq!((plain.lo.clone(), plain.hi.clone()), want);
            // From a bound at or inside each limit (a limit kept as a bound): the same interval,
            // and the same blocks leaving at each limit.
            for inside in [Q::zero(), Q::frac(1, 3), Q::int(2)] {
                let lo = plain.lo.as_ref().map(|l| l + &inside);
                let hi = plain.hi.as_ref().map(|h| h - &inside);
                let from = p.stick_sides_by(&[], [true, true], [lo.as_ref(), hi.as_ref()], 0, None).unwrap();
                prop_assert_eq!((&from.lo, &from.hi), (&plain.lo, &plain.hi));
                for (a, b) in [(&from.leaving_lo, &plain.leaving_lo), (&from.leaving_hi, &plain.leaving_hi)] {
                    if let (Some(a), Some(b)) = (a, b) {
                        prop_assert_eq!(a, b);
                    }
                }
            }
            // Asked only whether a_g lies inside: the whole interval where it is not beyond a
            // limit (at one included), nothing where it is, at the limits, between and beyond.
            let mut at: Vec<Q> = [&plain.lo, &plain.hi].into_iter().flatten().cloned().collect();
            let near = at.clone();
            for a in near {
                at.extend([&a - &Q::frac(1, 7), &a + &Q::frac(1, 7)]);
            }
            at.push(Q::zero());
            for a0 in &at {
                let beyond = plain.lo.as_ref().is_some_and(|lo| a0 < lo)
                    || plain.hi.as_ref().is_some_and(|hi| a0 > hi);
                let asked = p.stick_sides_by(&[], [true, true], [None, None], 0, Some(a0));
                match asked {
                    Some(s) => {
                        prop_assert!(!beyond, "a0 {:?} beyond {:?}", a0, (&plain.lo, &plain.hi));
                        prop_assert_eq!((&s.lo, &s.hi), (&plain.lo, &plain.hi));
                        prop_assert_eq!((&s.leaving_lo, &s.leaving_hi), (&plain.leaving_lo, &plain.leaving_hi));
                    }
                    None => prop_assert!(beyond, "a0 {:?} inside {:?}", a0, (&plain.lo, &plain.hi)),
                }
            }
            let q = with_coprime_denominators(p);
            if q.friction.len() >= 4 {
                prop_assert!(Integral::new(&q, &q.external).is_none());
            }
            let want = stick_by_enumeration(&q);
            prop_assert_eq!(interval(&q, ENUMERATE_UP_TO), want.clone());
            prop_assert_eq!(interval(&q, 0), want);
        }

        /// `Engine::kept_limits`: blocks labelled 0 stay stuck, those labelled 2 left (their
        /// joints now slide, their friction dragging the rest towards the side tested), those
        /// labelled 1 came to rest on the group (their friction had dragged it away from that
        /// side). The new interval's limit on that side is at or beyond the weaker of the old
        /// group's and the newcomers' own, with the old group as their ground.
        #[test]
        fn kept_limits_bound_the_interval_from_inside(
            p in abutted_problem(),
            labels in prop::collection::vec(0usize..3, 8),
        ) {
            let labels = &labels[..p.n()];
            prop_assume!(labels.contains(&0));
            // No face between the blocks that stay and those that left: kept_limits declines
            // the side such a face held back.
            let mut p = p;
            p.contacts.retain(|pair| match pair {
                (End::Node(a), End::Node(b)) => labels[*a].min(labels[*b]) != 0
                    || labels[*a].max(labels[*b]) != 2,
                _ => true,
            });
            let joined: Vec<usize> = (0..p.n())
                .filter(|&i| labels[i] != 2)
                .enumerate()
                .filter(|&(_, i)| labels[i] == 1)
                .map(|(k, _)| k)
                .collect();
            for (side, sign) in [(1, 1), (0, -1)] {
                let q = sliding_against(&p, labels, [true, true, false], [0, 0, sign]);
                let old = sliding_against(&p, labels, [true, false, true], [0, -sign, 0]);
                let own = if joined.is_empty() {
                    None
                } else {
                    let c = q.with_ground(&joined).stick_interval(&[]);
                    if side == 1 { c.hi } else { c.lo }
                };
                let (new, old) = (q.stick_interval(&[]), old.stick_interval(&[]));
                let (new, old) = if side == 1 { (new.hi, old.hi) } else { (new.lo, old.lo) };
                let bound = if joined.is_empty() { old } else { weaker_limit(old, own, side == 1) };
                let inside = match (&new, &bound) {
                    (None, _) => true,
                    (Some(_), None) => false,
                    (Some(new), Some(bound)) => i64::from((new - bound).signum()) * sign >= 0,
                };
                prop_assert!(inside, "side {}: {:?} beyond {:?}", side, new, bound);
            }
        }

        /// At a limit of a problem's own stick interval, passing it outward, the blocks the
        /// interval's last cut found leaving are the decision's, without its cuts; anywhere
        /// else the shortcut declines.
        #[test]
        fn decisions_past_a_stick_limit_need_no_cut(p in abutted_problem()) {
            let stick = p.stick_sides_by(&[], [true, true], [None, None], 0, None).unwrap();
            let point = matches!((&stick.lo, &stick.hi), (Some(lo), Some(hi)) if lo >= hi);
            for (limit, outward, leaving) in [
                (&stick.hi, 1, &stick.leaving_hi),
                (&stick.lo, -1, &stick.leaving_lo),
            ] {
                let Some(limit) = limit else { continue };
                let past = Lex([limit.clone(), Q::int(outward), Q::zero()]);
                let fast = p.solve_past_limit(&past, &[], &stick);
                prop_assert_eq!(fast.is_some(), leaving.is_some() && !point);
                if let Some(fast) = fast {
                    prop_assert_eq!(sorted(fast), sorted(p.solve(&past, &[])));
                }
                let back = Lex([limit.clone(), Q::int(-outward), Q::zero()]);
                prop_assert!(p.solve_past_limit(&back, &[], &stick).is_none());
                let beyond = Lex([limit + &Q::int(outward), Q::int(outward), Q::zero()]);
                prop_assert!(p.solve_past_limit(&beyond, &[], &stick).is_none());
            }
        }

        /// Pieces of the joint graph meet only through the ground: decided one by one they
        /// give the groups of the whole (grounded blocks may be grouped differently), and a
        /// piece with the ground acceleration strictly inside its stick interval is grounded.
        /// The event loop relies on both to decide a large stuck cluster by its interval.
        #[test]
        fn pieces_are_decided_alone_as_together(p in ground_problem(), a in -12i64..13) {
            let theta = Lex([Q::int(a), Q::zero(), Q::zero()]);
            let split = |groups: Vec<Group>| {
                let mut grounded: Vec<usize> = Vec::new();
                let mut free = Vec::new();
                for g in groups {
                    if g.grounded {
                        grounded.extend(g.nodes);
                    } else {
                        free.push(g);
                    }
                }
                grounded.sort_unstable();
                (grounded, sorted(free))
            };
            let whole = split(p.solve(&theta, &[]));
            let mut alone = Vec::new();
            for (piece, on_ground) in p.ground_pieces() {
                let q = p.restrict(&piece);
                for g in q.solve(&theta, &[]) {
                    alone.push(Group {
                        nodes: g.nodes.iter().map(|&k| piece[k]).collect(),
                        ..g
                    });
                }
                let stick = q.stick_interval(&[]);
                let a0 = &theta.0[0];
                let inside = stick.lo.as_ref().is_none_or(|lo| a0 > lo)
                    && stick.hi.as_ref().is_none_or(|hi| a0 < hi);
                if on_ground && inside {
                    prop_assert!(piece.iter().all(|i| whole.0.contains(i)));
                }
            }
            prop_assert_eq!(split(alone), whole);
        }

        /// Holding bodies together first changes the work, never the answer; and it is used
        /// whenever the bodies do hold.
        #[test]
        fn bodies_held_together_give_the_same_groups(
            p in free_problem(),
            labels in prop::collection::vec(0usize..3, 8),
        ) {
            let bodies = labelled_bodies(&labels, p.mass.len());
            let plain = sorted(p.solve(&Lex::zero(), &[]));
            prop_assert_eq!(&sorted(p.solve(&Lex::zero(), &bodies)), &plain);
            let whole = |body: &Vec<usize>| {
                let group = plain.iter().find(|g| g.nodes.contains(&body[0])).unwrap();
                body.iter().all(|i| group.nodes.contains(i))
            };
            let connected = |body: &Vec<usize>| p.pieces(body, &p.adjacency()).len() == 1;
            if bodies.iter().all(|b| whole(b) && connected(b)) {
                prop_assert!(matches!(p.solve_contracted(&bodies, &mut Vec::new()), Held::Groups(_)));
            }
        }
    }

    proptest! {
        /// At the ground too: the parts that move away from it are decided with the bodies
        /// inside them held together, and the answer is the same.
        #[test]
        fn bodies_held_together_at_the_ground_give_the_same_groups(
            p in ground_problem(),
            labels in prop::collection::vec(0usize..3, 8),
            a in -12i64..13,
            rate in -1i64..2,
        ) {
            let bodies = labelled_bodies(&labels, p.mass.len());
            let theta = Lex([Q::int(a), Q::int(rate), Q::zero()]);
            prop_assert_eq!(
                sorted(p.solve(&theta, &bodies)),
                sorted(p.solve(&theta, &[]))
            );
        }
    }

    #[test]
    fn a_body_that_breaks_is_split_until_its_parts_hold() {
        // A stack of four 1 kg blocks that slid as one body, 12 N now on the bottom one. As one
        // body it would go at 3 m/s2, the bottom joint passing 9 N of its 4 N capacity: the
        // three above break away (4 N: 4/3 m/s2), and of those the lowest cannot pass the
        // 8/3 N the top two need through its 2 N joint: 0 at 8, 1 at 2, {2, 3} at 1 m/s2, the
        // top joint passing 1 N of 5. Two splits, then every part holds.
        let p = Problem {
            mass: vec![Q::one(); 4],
            external: vec![Q::int(12), Q::zero(), Q::zero(), Q::zero()],
            friction: vec![
                (1, End::Node(0), Q::int(4)),
                (2, End::Node(1), Q::int(2)),
                (3, End::Node(2), Q::int(5)),
            ],
            contacts: vec![],
        };
        let body = vec![vec![0, 1, 2, 3]];
        assert!(matches!(
            p.solve_contracted(&body, &mut Vec::new()),
            Held::Breaks(_)
        ));
        let by_accel = |mut g: Vec<Group>| {
            g.sort_by(|a, b| a.accel.cmp(&b.accel));
            g
        };
        let group = |nodes: Vec<usize>, a: i64| Group {
            nodes,
            accel: Q::int(a),
            grounded: false,
        };
        let want = vec![group(vec![2, 3], 1), group(vec![1], 2), group(vec![0], 8)];
        let split = p.solve_by_bodies(&body).expect("its parts hold once split");
        assert_eq!(by_accel(split), want);
        assert_eq!(by_accel(p.solve(&Lex::zero(), &[])), want);
    }

    #[test]
    fn a_body_that_held_is_not_cut_again_when_another_breaks() {
        // The four-block stack above (three tries: it splits twice) beside a row of eight 1 kg
        // blocks that slid as one body, 8 N on the first and 10 N joints: it holds (each joint
        // passes at most 7 N). Its group is the same in every try, so it is cut once.
        let mut friction = vec![
            (1, End::Node(0), Q::int(4)),
            (2, End::Node(1), Q::int(2)),
            (3, End::Node(2), Q::int(5)),
        ];
        let mut external = vec![Q::int(12), Q::zero(), Q::zero(), Q::zero()];
        for i in 4..12 {
            if i > 4 {
                friction.push((i, End::Node(i - 1), Q::int(10)));
            }
            external.push(if i == 4 { Q::int(8) } else { Q::zero() });
        }
        let both = Problem {
            mass: vec![Q::one(); 12],
            external,
            friction,
            contacts: vec![],
        };
        let row = both.restrict(&(4..12).collect::<Vec<_>>());
        let work = |p: &Problem, bodies: &[Vec<usize>]| {
            let from = flow::pass_nodes();
            let groups = p.solve_by_bodies(bodies).expect("the parts hold");
            (flow::pass_nodes() - from, groups.len())
        };
        let (alone, groups) = work(&row, &[(0..8).collect()]);
        assert!(alone > 0);
        assert_eq!(groups, 1);
        let (beside, groups) = work(&both, &[vec![0, 1, 2, 3], (4..12).collect()]);
        assert_eq!(groups, 4, "the stack's three parts and the row");
        assert_eq!(
            beside, alone,
            "the stack's cuts try every set; the row is cut once"
        );
    }

    #[test]
    fn a_free_stack_splits_where_friction_cannot_hold() {
        // Two blocks sliding on a moving base: lower one (1 kg) gets +10 N, upper one (1 kg) is
        // held by a joint of capacity 2 N: it lags at 2 m/s2 while the lower goes at 8 m/s2.
        let p = Problem {
            mass: vec![Q::one(), Q::one()],
            external: vec![Q::int(10), Q::zero()],
            friction: vec![(1, End::Node(0), Q::int(2))],
            contacts: vec![],
        };
        let mut g = p.solve(&Lex::zero(), &[]);
        g.sort_by(|a, b| a.accel.cmp(&b.accel));
        assert_eq!(
            g[0],
            Group {
                nodes: vec![1],
                accel: Q::int(2),
                grounded: false
            }
        );
        assert_eq!(
            g[1],
            Group {
                nodes: vec![0],
                accel: Q::int(8),
                grounded: false
            }
        );
        // With capacity 6 N it holds: one body at 5 m/s2, the joint needing 5 N.
        let mut p = p;
        p.friction[0].2 = Q::int(6);
        assert_eq!(
            p.solve(&Lex::zero(), &[]),
            vec![Group {
                nodes: vec![0, 1],
                accel: Q::int(5),
                grounded: false
            }]
        );
    }

    #[test]
    fn a_stack_on_the_ground_splits_with_each_joint_counted_once() {
        // 1000 kg each, ground joint 9810 N, top joint 1962 N, a_g = 8: the bottom block lags
        // at 7.848 m/s2 absolute, the top at 1.962.
        let p = Problem {
            mass: vec![Q::int(1000), Q::int(1000)],
            external: vec![Q::zero(), Q::zero()],
            friction: vec![
                (0, End::Ground, Q::int(9810)),
                (1, End::Node(0), Q::int(1962)),
            ],
            contacts: vec![],
        };
        let mut g = p.solve(&just_after(Q::int(8), 0), &[]);
        g.sort_by(|a, b| a.nodes.cmp(&b.nodes));
        assert_eq!(
            g[0],
            Group {
                nodes: vec![0],
                accel: q(7.848),
                grounded: false
            }
        );
        assert_eq!(
            g[1],
            Group {
                nodes: vec![1],
                accel: q(1.962),
                grounded: false
            }
        );
    }

    #[test]
    fn faces_push_but_never_pull() {
        // Two blocks side by side, left pushed +10 N, right free: pressing, they move together.
        let mut p = Problem {
            mass: vec![Q::one(), Q::one()],
            external: vec![Q::int(10), Q::zero()],
            friction: vec![],
            contacts: vec![(End::Node(0), End::Node(1))],
        };
        assert_eq!(
            p.solve(&Lex::zero(), &[]),
            vec![Group {
                nodes: vec![0, 1],
                accel: Q::int(5),
                grounded: false
            }]
        );
        // Pushed the other way they separate.
        p.external[0] = Q::int(-10);
        let mut g = p.solve(&Lex::zero(), &[]);
        g.sort_by(|a, b| a.accel.cmp(&b.accel));
        assert_eq!(g[0].accel, Q::int(-10));
        assert_eq!(g[1].accel, Q::zero());
    }

    #[test]
    fn a_block_against_an_abutment_cannot_be_pushed_into_it() {
        // Block on the ground, abutment (ground) on its left, face touching.
        let mut p = one_block(0.3);
        p.contacts.push((End::Ground, End::Node(0)));
        let Stick { lo, hi, .. } = p.stick_interval(&[]);
        assert_eq!(hi, None, "lagging behind means pushing into the abutment");
        assert_eq!(lo, Some(-(q(0.3) * q(9.81))));
        let g = p.solve(&just_after(q(50.0), 0), &[]);
        assert!(g[0].grounded);
    }
}
