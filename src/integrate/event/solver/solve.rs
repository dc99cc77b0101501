//! The mode decision: the accelerations of the blocks whose joints are undecided, found by
//! divide and conquer on minimum cuts (design note, section 4), at the ground or away from it.

use super::cut::{Integral, Side, Want};
use super::{Adjacency, End, Group, Lex, Problem, Stick};
use crate::exact::Q;
use std::collections::VecDeque;

impl Problem {
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
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn one_block_sticks_within_mu_g_and_slides_beyond() {
        let p = one_block(0.3);
        let mug = q(0.3) * q(9.81);
        let stick = p.stick_sides(&[], [true, true]);
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

    #[test]
    fn uniform_wall_breaks_away_as_one_body() {
        let p = five_block([0.3; 6]);
        let mug = q(0.3) * q(9.81);
        let stick = p.stick_sides(&[], [true, true]);
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

    proptest! {
        #![proptest_config(crate::integrate::event::many_cheap_cases())]

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
                let stick = q.stick_sides(&[], [true, true]);
                let a0 = &theta.0[0];
                let inside = stick.lo.as_ref().is_none_or(|lo| a0 > lo)
                    && stick.hi.as_ref().is_none_or(|hi| a0 < hi);
                if on_ground && inside {
                    prop_assert!(piece.iter().all(|i| whole.0.contains(i)));
                }
            }
            prop_assert_eq!(split(alone), whole);
        }
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
        let Stick { lo, hi, .. } = p.stick_sides(&[], [true, true]);
        assert_eq!(hi, None, "lagging behind means pushing into the abutment");
        assert_eq!(lo, Some(-(q(0.3) * q(9.81))));
        let g = p.solve(&just_after(q(50.0), 0), &[]);
        assert!(g[0].grounded);
    }
}
