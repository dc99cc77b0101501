//! Stuck clusters: the interval of ground accelerations each stays stuck over, worked out,
//! remembered or kept as bounds from inside after a change, and the pieces of a decision whose
//! clusters it shows stuck without the general decision.

use super::cluster::ClusterId;
use super::cluster::{Limits, Mode};
use super::regroup::scratch::{Before, Decided, Local};
use super::solver::{weaker_limit, End, Group, Lex, Problem, Stick, BODY_FROM};
use super::Engine;
use crate::exact::Q;
use crate::topology::Base;

/// Sets that broke away at earlier stick limits, kept as hints for the next intervals (a hint
/// costs a pass over its blocks, a search over a large group a cut over all of it for every
/// step a good hint would have saved: 32 against 8 saves 2-9 % of the flow nodes).
const BREAKING_HINTS: usize = 32;

impl Engine<'_> {
    /// The exact stick interval of stuck cluster k (a_g has reached a bound of it).
    pub(super) fn set_exact_thresholds(&mut self, k: ClusterId) {
        self.set_thresholds(k, None);
    }

    /// The stick interval of stuck cluster k after a decision that changed `before` (limits
    /// it cannot have narrowed are kept as bounds, [`Engine::kept_limits`]); without it, exact
    /// (no limit is a bound, [`Stick::bound_only`]).
    pub(super) fn set_thresholds(&mut self, k: ClusterId, before: Option<&Before>) {
        self.clusters[k].blocks.sort_unstable();
        // In the memory of the decisions, unless one is under way.
        let mut members = std::mem::take(&mut self.scratch.decisions.blocks);
        members.extend_from_slice(&self.clusters[k].blocks);
        let mut local = Local::reuse(
            std::mem::take(&mut self.scratch.decisions.local),
            self.given.n,
        );
        for (n, &b) in members.iter().enumerate() {
            local.insert(b, n);
        }
        let mut p = std::mem::take(&mut self.scratch.decisions.problem);
        p.mass
            .extend(members.iter().map(|&i| self.given.mass_q[i].clone()));
        p.external
            .extend(members.iter().map(|&i| self.external_force(i)));
        for &i in &members {
            for &s in &self.given.topo.below[i] {
                if !self.live_horizontal(s.0) || !self.slip[s.0].is_stuck() {
                    continue;
                }
                let end = match self.given.topo.horizontal[s.0].lower {
                    Base::Ground => End::Ground,
                    Base::Block(b) if self.given.fixed[b.0] => End::Ground,
                    Base::Block(b) => match local.get(&b.0) {
                        Some(&n) => End::Node(n),
                        None => continue,
                    },
                };
                p.friction
                    .push((local[&i], end, self.given.cap_q[s.0].clone()));
            }
            for &j in &self.given.topo.sides[i] {
                let jt = &self.given.topo.vertical[j.0];
                if jt.left.0 != i || !self.live_vertical(j.0) || !self.is_touching(j.0) {
                    continue;
                }
                let end = |b: usize| {
                    if self.given.fixed[b] {
                        Some(End::Ground)
                    } else {
                        local.get(&b).map(|&n| End::Node(n))
                    }
                };
                if let (Some(l), Some(r)) = (end(jt.left.0), end(jt.right.0)) {
                    p.contacts.push((l, r));
                }
            }
            // Faces against an abutment on the block's left.
            for &j in &self.given.topo.sides[i] {
                let jt = &self.given.topo.vertical[j.0];
                if jt.right.0 == i
                    && self.given.fixed[jt.left.0]
                    && self.live_vertical(j.0)
                    && self.is_touching(j.0)
                {
                    p.contacts.push((End::Ground, End::Node(local[&i])));
                }
            }
        }
        self.scratch.decisions.local = local.release(&members);
        let p = p.canonical();
        let change = before.map_or(Change::Exact, |b| Change::After(Some(b)));
        let limits = self.stick_interval(&p, &members, change);
        self.clusters[k].mode = stuck(limits);
        members.clear();
        self.scratch.decisions.blocks = members;
        self.scratch.decisions.problem = p.cleared();
    }

    /// The stick interval of a problem whose blocks (`members`: global indices, sorted, in the
    /// problem's order) are all stuck, remembered per run. The sets that broke away at earlier
    /// limits are the hints ([`Problem::stick_sides`]): a block joining or leaving a large
    /// stuck cluster seldom changes its weakest set. After a `change`, a bound the run already
    /// holds for the same problem stands, and a side the change cannot have narrowed is kept as
    /// a bound ([`Engine::kept_limits`], worked out only for the sides the run does not know).
    fn stick_interval(&mut self, p: &Problem, members: &[usize], change: Change) -> Limits {
        self.stick_interval_inside(p, members, change, None)
            .expect("a search asked about no ground acceleration runs to its end")
    }

    /// [`Engine::stick_interval`] for a caller that needs it only if the ground acceleration
    /// `a0` (where given) lies strictly inside: `None` where a search shows it does not
    /// ([`Problem::stick_sides_inside`]); nothing is then remembered.
    fn stick_interval_inside(
        &mut self,
        p: &Problem,
        members: &[usize],
        change: Change,
        a0: Option<&Q>,
    ) -> Option<Limits> {
        let known = self.caches.stick_memo.get(p);
        let exact = matches!(change, Change::Exact);
        let usable = |side: usize| known.is_some_and(|s| !(exact && s.bound_only[side]));
        if let (Some(s), true) = (known, usable(0) && usable(1)) {
            return Some(Limits::of(s));
        }
        let kept = match change {
            Change::After(before) => self.kept_limits(p, members, before),
            Change::Exact => [None, None],
        };
        let want = [0, 1].map(|side| !usable(side) && kept[side].is_none());
        let hints: Vec<Vec<usize>> = self
            .caches
            .breaking
            .iter()
            .map(|set| {
                set.iter()
                    .filter_map(|b| members.binary_search(b).ok())
                    .collect()
            })
            .collect();
        let mut found = if want == [false, false] {
            Stick::default()
        } else {
            // A side remembered as a bound only: the exact limit is at it or beyond.
            let bounds = [0, 1].map(|side| {
                known
                    .filter(|s| s.bound_only[side])
                    .and_then(|s| [&s.lo, &s.hi][side].as_ref())
            });
            match a0 {
                Some(a0) => p.stick_sides_inside(&hints, want, bounds, a0)?,
                None => p.stick_sides_beyond(&hints, want, bounds),
            }
        };
        for set in std::mem::take(&mut found.breaking) {
            let global: Vec<usize> = set.into_iter().map(|k| members[k]).collect();
            self.caches.breaking.retain(|known| *known != global);
            self.caches.breaking.push_front(global);
            self.caches.breaking.truncate(BREAKING_HINTS);
        }
        // Each side not worked out now is known exactly, kept as a bound, or a bound known.
        let mut known = self.caches.stick_memo.get_mut(p);
        for side in (0..2).filter(|&side| !want[side]) {
            let (limit, leaving) = match side {
                0 => (&mut found.lo, &mut found.leaving_lo),
                _ => (&mut found.hi, &mut found.leaving_hi),
            };
            let before = known.as_deref_mut();
            match (before, &kept[side]) {
                (Some(s), kept) if !s.bound_only[side] || kept.is_none() => {
                    let (l, v) = match side {
                        0 => (&s.lo, &mut s.leaving_lo),
                        _ => (&s.hi, &mut s.leaving_hi),
                    };
                    *limit = l.clone();
                    *leaving = std::mem::take(v);
                    found.bound_only[side] = s.bound_only[side];
                }
                (_, kept) => {
                    *limit = kept.clone().expect("kept where not known");
                    found.bound_only[side] = limit.is_some();
                }
            }
        }
        let limits = Limits::of(&found);
        match known {
            Some(s) => *s = found,
            None => self
                .caches
                .stick_memo
                .insert(p.clone(), found, members.len()),
        }
        Some(limits)
    }

    /// The pieces of p (its joint graph without the ground) that are joined to the ground with
    /// the ground acceleration strictly inside their stick intervals: they stay stuck, and go
    /// into `out` as groups with their intervals. The other blocks (local indices, sorted) are
    /// left in `out.rest` for the general decision: pieces not joined to the ground or at or
    /// beyond a limit, and every block at a threshold (theta `snapped` to the exact limit) or
    /// when nothing touches the ground.
    pub(super) fn stuck_pieces(
        &mut self,
        p: &Problem,
        blocks: &[usize],
        theta: &Lex,
        snapped: bool,
        out: &mut Decided,
    ) {
        if snapped || !p.touches_ground() {
            out.rest.extend(0..blocks.len());
            return;
        }
        let a0 = &theta.0[0];
        let mut pieces = std::mem::take(&mut out.pieces);
        p.ground_pieces_in(&mut pieces);
        for (piece, on_ground) in pieces.iter() {
            if on_ground {
                if let Some((stuck, limits, moving)) = self.beside_stuck(p, blocks, piece, theta) {
                    out.push(stuck.nodes, stuck.accel, true, Some(limits));
                    for g in moving {
                        out.push(g.nodes, g.accel, g.grounded, None);
                    }
                    continue;
                }
                // p is canonical: a piece that is all of it needs no copy.
                let limits = if piece.len() == blocks.len() {
                    self.stick_interval_inside(p, blocks, Change::After(None), Some(a0))
                } else {
                    let members: Vec<usize> = piece.iter().map(|&k| blocks[k]).collect();
                    let q = p.restrict(piece);
                    self.stick_interval_inside(&q, &members, Change::After(None), Some(a0))
                };
                let inside = |limits: &Limits| {
                    limits.lo.as_ref().is_none_or(|lo| a0 > lo)
                        && limits.hi.as_ref().is_none_or(|hi| a0 < hi)
                };
                if let Some(limits) = limits.filter(inside) {
                    out.push(piece.iter().copied(), a0.clone(), true, Some(limits));
                    continue;
                }
            }
            out.rest.extend_from_slice(piece);
        }
        out.pieces = pieces;
        out.rest.sort_unstable();
    }

    /// A piece of p (local indices, sorted) made of a large cluster K that was stuck and a few
    /// blocks X beside it (fewer than a body, [`BODY_FROM`]: a block that came to rest against
    /// it, one that a collision stopped on it), decided without a cut over K where that can be
    /// shown: X is decided with K held at a_g ([`Problem::beside_ground`]), and K with the
    /// blocks of X that stay at a_g is one stuck group if a_g lies strictly inside its stick
    /// interval (remembered, or kept as a bound, as after any change), with the rest of X
    /// sliding past it ([`Problem::beside_sliding`]). Every block's forces then balance at
    /// these accelerations, which are unique (Gauss' principle), so they are the full
    /// decision's. `None` (nothing decided) where K is small
    /// ([`Params::beside_stuck_from`](super::Params)), X is empty or holds a body (a cluster
    /// that came to rest on K mostly stays, which the piece's own interval shows at less cost
    /// than a decision over X), the ground acceleration had to be snapped, a block of X would
    /// float at a_g, all of X would stay (the piece's own interval is then the question), the
    /// stuck blocks are not one piece or a_g is not inside: the caller then decides the piece
    /// whole.
    fn beside_stuck(
        &mut self,
        p: &Problem,
        blocks: &[usize],
        piece: &[usize],
        theta: &Lex,
    ) -> Option<(Group, Limits, Vec<Group>)> {
        if piece.len() <= self.given.params.beside_stuck_from {
            return None;
        }
        let mut count: Vec<(ClusterId, usize)> = Vec::new();
        for &k in piece {
            let c = self.of[blocks[k]];
            if c == ClusterId::NONE || self.clusters[c].slide().is_some() {
                continue;
            }
            match count.iter_mut().find(|(d, _)| *d == c) {
                Some((_, n)) => *n += 1,
                None => count.push((c, 1)),
            }
        }
        let (held, size) = count.into_iter().max_by_key(|&(_, n)| n)?;
        let few = piece.len() - size;
        if size < self.given.params.beside_stuck_from || few == 0 || few >= BODY_FROM {
            return None;
        }
        let beside: Vec<usize> = piece
            .iter()
            .copied()
            .filter(|&k| self.of[blocks[k]] != held)
            .collect();
        let mut at = theta.clone();
        let found = self.decide_general(&p.beside_ground(&beside), &mut at, false, &[]);
        if at != *theta {
            return None;
        }
        let mut ahead = vec![0_i8; p.mass.len()];
        let mut moving = Vec::new();
        for g in found.iter() {
            let nodes: Vec<usize> = g.nodes.iter().map(|&k| beside[k]).collect();
            if !g.grounded {
                let dir = match Lex::constant(g.accel.clone()).cmp(theta) {
                    std::cmp::Ordering::Greater => 1,
                    std::cmp::Ordering::Less => -1,
                    std::cmp::Ordering::Equal => return None,
                };
                for &k in &nodes {
                    ahead[k] = dir;
                }
                moving.push(Group {
                    nodes,
                    accel: g.accel.clone(),
                    grounded: false,
                });
            }
        }
        if moving.is_empty() {
            // The whole piece is to stay: its own interval, which the caller works out, decides.
            return None;
        }
        let stuck: Vec<usize> = piece.iter().copied().filter(|&k| ahead[k] == 0).collect();
        let q = p.beside_sliding(&stuck, &ahead);
        if !matches!(q.ground_pieces().as_slice(), [(_, true)]) {
            return None;
        }
        let members: Vec<usize> = stuck.iter().map(|&k| blocks[k]).collect();
        let a0 = &theta.0[0];
        let limits = self.stick_interval_inside(&q, &members, Change::After(None), Some(a0))?;
        let inside = limits.lo.as_ref().is_none_or(|lo| a0 > lo)
            && limits.hi.as_ref().is_none_or(|hi| a0 < hi);
        inside.then(|| {
            let group = Group {
                nodes: stuck,
                accel: a0.clone(),
                grounded: true,
            };
            (group, limits, moving)
        })
    }

    /// Bounds from inside on the stick interval of problem q, whose blocks (`members`: global
    /// indices, sorted, in q's order) are to stay stuck, per side ([lo, hi]); `None` where the
    /// bound cannot be shown, or q is too small to be worth it
    /// ([`Params::kept_limits_from`](super::Params)).
    ///
    /// q is a stuck cluster K that lost the blocks L and took in the blocks C of clusters that
    /// came to rest on it. A side's limit is the least ratio (cut(S) + e(S)) / m(S) over the sets
    /// S that may break away that way (mirrored for lo). Write S = A + B, A in K, B in C:
    ///
    ///   num_q(S) = num_K(A) + sum over A of (c_i - l_i + d_i) + num_q(B) - 2 cap(A, B),
    ///
    /// with c_i, l_i the capacities of block i's joints to C and to L, and d_i the change of its
    /// sliding friction (its sign flipped for lo). Where d_i >= c_i + l_i for every block of
    /// K, the sum is at least 2 cap(A, C) >= 2 cap(A, B), so num_q(S) >= lambda_K m(A) +
    /// lambda_C m(B): S is no weaker than the weaker of K's limit and C's own, with K as its
    /// ground (faces against K dropped, which only widens the sets tried). Every set q allows
    /// restricts to a set K allowed, unless a face against a block of L held it back. A block
    /// knocked out of a stuck group drags the rest its way and holds it back the other, a
    /// cluster coming to rest stops dragging it one way: one side passes the test, and a flow
    /// over C replaces one over the whole group.
    ///
    /// The engine's state is the one before the change, except what `before` holds (when the
    /// change is already installed).
    fn kept_limits(
        &self,
        q: &Problem,
        members: &[usize],
        before: Option<&Before>,
    ) -> [Option<Option<Q>>; 2] {
        let none = [None, None];
        if members.len() < self.given.params.kept_limits_from {
            return none;
        }
        let of = |b: usize| {
            before
                .and_then(|x| x.of.get(&b).copied())
                .unwrap_or(self.of[b])
        };
        let slip = |s: usize| {
            before
                .and_then(|x| x.slip.get(&s).copied())
                .unwrap_or(self.slip[s])
        };
        // The limits of cluster k as it was (`None`: it slid, or there is none).
        let limits = |k: ClusterId| -> Option<[&Option<Q>; 2]> {
            match before.and_then(|x| x.limits.get(&k)) {
                Some(kept) => kept.as_ref().map(|[lo, hi]| [lo, hi]),
                None if k == ClusterId::NONE => None,
                None => match &self.clusters[k].mode {
                    Mode::Stuck { lo_q, hi_q, .. } => Some([lo_q, hi_q]),
                    Mode::Sliding(_) => None,
                },
            }
        };
        let mut of_k = members
            .iter()
            .map(|&i| of(i))
            .filter(|&k| limits(k).is_some());
        let Some(k) = of_k.next() else {
            return none;
        };
        if of_k.any(|other| other != k) {
            return none;
        }
        let Some([lo_q, hi_q]) = limits(k) else {
            return none;
        };
        let mut in_q = vec![false; self.given.n];
        for &i in members {
            in_q[i] = true;
        }
        let mut holds = [true, true];
        let mut joined = Vec::new();
        for (n, &i) in members.iter().enumerate() {
            if of(i) != k {
                joined.push(n);
                continue;
            }
            // Capacity of i's sticking joints to the blocks that left and that joined; a block
            // whose joints all stick within K and q (most of a large group) changed in nothing.
            let mut c = Q::zero();
            let mut changed = false;
            for s in self.given.topo.below[i]
                .iter()
                .chain(&self.given.topo.above[i])
            {
                let s = s.0;
                if !self.live_horizontal(s) {
                    continue;
                }
                changed |= !slip(s).is_stuck();
                let Some(b) = self
                    .across_horizontal(s, i)
                    .filter(|&b| !self.given.fixed[b])
                else {
                    continue;
                };
                let (in_k, in_q) = (of(b) == k, in_q[b]);
                changed |= !(in_k && in_q);
                if (in_k && !in_q && slip(s).is_stuck()) || (!in_k && in_q) {
                    c = c + &self.given.cap_q[s];
                }
            }
            for &j in &self.given.topo.sides[i] {
                let d = self.across_vertical(j.0, i);
                if !self.given.fixed[d]
                    && of(d) == k
                    && !in_q[d]
                    && self.live_vertical(j.0)
                    && self.is_touching(j.0)
                {
                    // The face held i back from moving towards d: lagging (hi) if d is on
                    // its left, running ahead (lo) if on its right.
                    holds[usize::from(self.given.topo.vertical[j.0].left.0 == d)] = false;
                }
            }
            if !changed {
                continue;
            }
            let d = &q.external[n] - &self.external_force_by(i, slip);
            if !c.is_zero() || !d.is_zero() {
                holds[1] &= !(&d - &c).is_negative();
                holds[0] &= !(&d + &c).is_positive();
            }
            if holds == [false, false] {
                return none;
            }
        }
        let (mut lo, mut hi) = (lo_q.clone(), hi_q.clone());
        if !joined.is_empty() {
            let own = q.with_ground(&joined).stick_sides(&[], holds);
            lo = weaker_limit(lo, own.lo, false);
            hi = weaker_limit(hi, own.hi, true);
        }
        [holds[0].then_some(lo), holds[1].then_some(hi)]
    }
}

/// How far a stick interval may rest on bounds ([`Engine::stick_interval`]).
#[derive(Clone, Copy)]
enum Change<'a> {
    /// a_g has reached a bound: every limit is worked out.
    Exact,
    /// After a change: the engine's state is the one before it, except what the decision that
    /// made it has already installed (`Before`).
    After(Option<&'a Before>),
}

pub(super) fn stuck(limits: Limits) -> Mode {
    let Limits { lo, hi, bound_only } = limits;
    Mode::Stuck {
        lo: lo.as_ref().map_or(f64::NEG_INFINITY, Q::to_f64),
        hi: hi.as_ref().map_or(f64::INFINITY, Q::to_f64),
        lo_q: lo,
        hi_q: hi,
        bound_only,
    }
}
