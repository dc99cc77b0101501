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
//!
//! This module holds the problem and its sub-problems; `solve` decides the accelerations at an
//! event (with `bodies` holding large sliding bodies together where that saves cuts), `stick`
//! the stick intervals of blocks stuck to the ground, `cut` the minimum cuts they are made of.

use crate::exact::Q;
use crate::sets::DisjointSets;
use std::cmp::Ordering;

mod bodies;
mod cut;
mod solve;
mod stick;
#[cfg(test)]
mod testing;

pub use stick::{weaker_limit, Stick};

/// Sliding clusters of at least this many blocks are held together in a decision's first try
/// (`Problem::solve` with bodies); below it the general decision costs no more.
pub const BODY_FROM: usize = 32;

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

/// The connected pieces of a problem's joint graph without the ground
/// ([`Problem::ground_pieces_in`]), with the working memory that finds them.
#[derive(Default)]
pub struct Pieces {
    /// The blocks of every piece, piece after piece, each piece sorted.
    nodes: Vec<usize>,
    /// Where each piece ends in `nodes`, and whether it touches the ground.
    ends: Vec<(usize, bool)>,
    sets: DisjointSets,
    on_ground: Vec<bool>,
    piece_of: Vec<usize>,
}

impl Pieces {
    /// Each piece's blocks, and whether it touches the ground.
    pub fn iter(&self) -> impl Iterator<Item = (&[usize], bool)> + '_ {
        let starts = std::iter::once(0).chain(self.ends.iter().map(|e| e.0));
        starts
            .zip(&self.ends)
            .map(|(from, &(to, grounded))| (&self.nodes[from..to], grounded))
    }
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
        let mut pieces = Pieces::default();
        self.ground_pieces_in(&mut pieces);
        pieces.iter().map(|(p, g)| (p.to_vec(), g)).collect()
    }

    /// [`Problem::ground_pieces`] in memory kept from one call to the next (a decision runs
    /// this each time).
    pub fn ground_pieces_in(&self, out: &mut Pieces) {
        let n = self.n();
        let Pieces {
            nodes,
            ends,
            sets,
            on_ground,
            piece_of,
        } = out;
        nodes.clear();
        ends.clear();
        sets.reset(n);
        on_ground.clear();
        on_ground.resize(n, false);
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
        // One piece, the usual case, needs no bookkeeping.
        if (1..n).all(|i| sets.find(i) == 0) {
            nodes.extend(0..n);
            ends.push((n, on_ground.contains(&true)));
            return;
        }
        // Pieces in the order of their first block, each block in order: count each piece's
        // blocks, then place them (piece_of: a root's piece, then each piece's next place).
        piece_of.clear();
        piece_of.resize(n, usize::MAX);
        for (i, &grounded) in on_ground.iter().enumerate() {
            let root = sets.find(i);
            if piece_of[root] == usize::MAX {
                piece_of[root] = ends.len();
                ends.push((0, false));
            }
            let piece = &mut ends[piece_of[root]];
            piece.0 += 1;
            piece.1 |= grounded;
        }
        let mut end = 0;
        for piece in ends.iter_mut() {
            end += piece.0;
            piece.0 = end;
        }
        nodes.resize(n, 0);
        for i in (0..n).rev() {
            let place = &mut ends[piece_of[sets.find(i)]].0;
            *place -= 1;
            nodes[*place] = i;
        }
        // Each piece's count has come down to its start, which is where the one before ends.
        for p in 0..ends.len() {
            ends[p].0 = ends.get(p + 1).map_or(n, |next| next.0);
        }
    }

    /// The blocks joined by each undecided friction link or contact between blocks.
    fn adjacency(&self) -> Adjacency {
        let pairs = || {
            let friction = self.friction.iter().filter_map(|&(i, j, _)| match j {
                End::Node(j) => Some((i, j)),
                End::Ground => None,
            });
            let contacts = self.contacts.iter().filter_map(|&(l, r)| match (l, r) {
                (End::Node(l), End::Node(r)) => Some((l, r)),
                _ => None,
            });
            friction.chain(contacts)
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
}

#[cfg(test)]
mod tests {
    use super::testing::*;
    use super::*;

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

    /// The pieces of p by their definition: breadth-first from each block not yet reached, in
    /// order, over the joints and faces between blocks.
    fn pieces_by_definition(p: &Problem) -> Vec<(Vec<usize>, bool)> {
        let n = p.n();
        let mut next = vec![Vec::new(); n];
        let mut grounded = vec![false; n];
        let links = p.friction.iter().map(|&(i, j, _)| (End::Node(i), j));
        for (a, b) in links.chain(p.contacts.iter().copied()) {
            match (a, b) {
                (End::Node(a), End::Node(b)) => {
                    next[a].push(b);
                    next[b].push(a);
                }
                (End::Node(i), End::Ground) | (End::Ground, End::Node(i)) => grounded[i] = true,
                (End::Ground, End::Ground) => {}
            }
        }
        let mut seen = vec![false; n];
        let mut pieces = Vec::new();
        for start in 0..n {
            if seen[start] {
                continue;
            }
            seen[start] = true;
            let mut piece = vec![start];
            let mut k = 0;
            while k < piece.len() {
                for &o in &next[piece[k]] {
                    if !seen[o] {
                        seen[o] = true;
                        piece.push(o);
                    }
                }
                k += 1;
            }
            piece.sort_unstable();
            let on_ground = piece.iter().any(|&i| grounded[i]);
            pieces.push((piece, on_ground));
        }
        pieces
    }

    proptest::proptest! {
        #[test]
        fn pieces_found_in_kept_memory_are_those_of_the_definition(
            problems in proptest::collection::vec(
                proptest::prop_oneof![free_problem(), abutted_problem()],
                1..5,
            )
        ) {
            let mut pieces = Pieces::default();
            for p in &problems {
                p.ground_pieces_in(&mut pieces);
                let found: Vec<(Vec<usize>, bool)> =
                    pieces.iter().map(|(s, g)| (s.to_vec(), g)).collect();
                proptest::prop_assert_eq!(found, pieces_by_definition(p));
            }
        }
    }
}
