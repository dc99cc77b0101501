//! Minimum cuts: the level sets of a decision and the weakest sets of a stick interval are
//! each a minimum cut over the blocks, made in integers over a common denominator where the
//! amounts fit and in exact rationals otherwise.

use super::super::flow::{
    over_common_denominator, take_overflow, Amount, Network, PUSH_RELABEL_FROM,
};
use super::{End, Problem};
use crate::exact::{div, gcd_i128, Q};
use std::cmp::Ordering;

/// Minimum cuts over at most this many blocks try every set too (see [`Cut::by_enumeration`]):
/// below it that costs less than building a flow network and pushing a flow through it.
const CUT_ENUMERATE_UP_TO: usize = 6;

/// Which minimisers of a cut problem a caller needs: each costs its own pass on large networks.
#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Want {
    /// The smallest (the level set {b > theta}).
    Smallest,
    /// The largest (the level set {b >= theta}).
    Largest,
    /// Both.
    Both,
}

#[derive(Clone, Copy, PartialEq, Eq)]
pub(super) enum Side {
    /// Super-level set {b > theta}: a contact (l, r) forces r in when l is in.
    Upper,
    /// Sub-level set {b < theta}: a contact (l, r) forces l in when r is in.
    Lower,
}

impl Problem {
    /// For each node of `set`, "in S implies that node in S" arcs and nodes that may not be in S
    /// (they would have to push into the ground), for the given side. Faces against the ground
    /// only constrain the cut where the ground is pinned at theta (`pinned`); inside a part
    /// already known to move away from the ground they are slack.
    pub(super) fn constraints(
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
    pub(super) fn min_cut(
        &self,
        set: &[bool],
        weight: &[Q],
        side: Side,
        pinned: bool,
        want: Want,
    ) -> Sides {
        // Only the amounts the cut uses go over the common denominator: a decision's recursion
        // cuts small parts of a large problem, and each should cost its part.
        let members: Vec<usize> = (0..self.n()).filter(|&i| set[i]).collect();
        let inside: Vec<usize> = (0..self.friction.len())
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
            .chain(inside.iter().map(|&k| &self.friction[k].2));
        if let Some((ints, _)) = over_common_denominator(amounts) {
            let mut w = vec![0i128; self.n()];
            let mut caps = vec![0i128; self.friction.len()];
            for (&i, &x) in members.iter().zip(&ints) {
                w[i] = x;
            }
            for (&k, &x) in inside.iter().zip(&ints[members.len()..]) {
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
    pub(super) fn min_cut_in_integers(
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

    /// The smallest and the largest minimiser of a free problem's cut at its mean acceleration.
    /// The weights sum to zero over `set` and no joint leaves it, so the empty set is a
    /// minimiser exactly when the whole set is: then the set moves as one body, the common case
    /// when a block comes to rest on a large sliding cluster. Where each minimiser costs a pass
    /// of its own (push-relabel), the largest alone shows that case.
    pub(super) fn level_cuts(&self, set: &[bool], weight: &[Q]) -> (Vec<bool>, Vec<bool>) {
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
}

/// A problem's joint capacities, one side's external forces and its masses as integers over
/// common denominators ([`over_common_denominator`]).
pub(super) struct Integral {
    /// Capacities, over `force_den`.
    pub(super) capacity: Vec<i128>,
    /// External forces, over `force_den`.
    pub(super) external: Vec<i128>,
    force_den: i128,
    /// Masses, over `mass_den`.
    pub(super) mass: Vec<i128>,
    mass_den: i128,
}

impl Integral {
    /// `None` when the numbers do not fit.
    pub(super) fn new(p: &Problem, external: &[Q]) -> Option<Integral> {
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
    pub(super) fn at(&self, lambda: &Q) -> Option<(Vec<i128>, Vec<i128>)> {
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
    pub(super) fn ratio(&self, force: i128, mass: i128) -> Option<Q> {
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
    use proptest::prelude::*;

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
    }
}
