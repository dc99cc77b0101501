//! Stick intervals: the ground accelerations over which blocks stuck to the ground stay stuck,
//! each limit the least ratio (cut(S) + e(S)) / m(S) over the sets S that could break away,
//! found by Dinkelbach's iteration on minimum cuts.

use super::super::flow::PUSH_RELABEL_FROM;
use super::cut::{Integral, Side, Want};
use super::{End, Problem};
use crate::exact::Q;

/// Stick intervals of problems of at most this many blocks try every set (at most 255, in
/// integers) instead of searching with minimum cuts: each cut builds a flow network, and a few
/// cost more than all the sets of a small problem.
const ENUMERATE_UP_TO: usize = 8;

impl Problem {
    /// For blocks that are all stuck to the ground: the interval of ground accelerations
    /// [a_lo, a_hi] over which they can stay stuck, `None` where no ground acceleration would
    /// move them (a block wedged against an abutment). a_hi is the smallest ratio
    /// (cut(S) + e(S)) / m(S) over the sets S that could lag behind the ground (Dinkelbach's
    /// iteration on minimum cuts, exact, a few cuts); a_lo the mirror image. `hints` are sets
    /// (local indices) that broke away from earlier intervals of the same blocks: the iteration
    /// starts from the best of them that could break away here, so when the weakest set has not
    /// changed one cut confirms it instead of several finding it again. Problems of at most
    /// `ENUMERATE_UP_TO` blocks try every set instead. `want` ([lo, hi]) asks for one side or both: a side
    /// not wanted comes back as no limit, for the caller to fill in.
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
    pub(super) fn stick_sides_by(
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
    pub(super) fn leaving(&self, domain: &[bool]) -> Vec<(usize, usize)> {
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

/// Where blocks stuck to the ground stop being stuck ([`Problem::stick_sides`]).
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

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use super::super::Group;
    use super::*;
    use crate::integrate::event::flow;
    use proptest::prelude::*;

    #[test]
    fn variable_wall_first_break_is_the_weakest_set() {
        let p = five_block([0.29, 0.31, 0.28, 0.30, 0.30, 0.28]);
        let Stick { lo, hi, .. } = p.stick_sides(&[], [true, true]);
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

    proptest! {
        #![proptest_config(crate::integrate::event::many_cheap_cases())]

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
                    let c = q.with_ground(&joined).stick_sides(&[], [true, true]);
                    if side == 1 { c.hi } else { c.lo }
                };
                let (new, old) = (q.stick_sides(&[], [true, true]), old.stick_sides(&[], [true, true]));
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
    }
}
