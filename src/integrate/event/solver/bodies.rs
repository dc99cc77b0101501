//! Decisions with large bodies held together: a body that slid as one is contracted to one
//! node, the small problem left is decided, and a cut per body shows it still holds (or where
//! it breaks, to split it and try again), instead of the general decision's cuts over all of it.

use super::cut::{Side, Want};
use super::{End, Group, Lex, Problem};
use crate::exact::Q;
use std::cmp::Ordering;

/// A large body that breaks is split and its problem solved again at most this many times
/// before the general decision takes over ([`Problem::solve_by_bodies`]).
const BODY_SPLITS: usize = 16;

/// [`Problem::solve_by_bodies`] holds bodies together only where that leaves at most this many
/// nodes, or a quarter of the problem: each try solves the contracted problem by the general
/// decision, and tries over a large one cost more than the general decision over all of it
/// (a 4,413-block part holding a 2,247-block body: 56 flows against 16).
const CONTRACTED_UP_TO: usize = 64;

impl Problem {
    /// A part of a decision at the ground that moves away from it (its joints to the ground
    /// slide, their forces in `external`), solved with the bodies inside it held together
    /// ([`Problem::solve_by_bodies`]) and its groups added to `out`: the upper part of a wall
    /// sliding on its lower courses is a free problem as large as itself, which the general
    /// decision would cut again at every level of its recursion. `false` (nothing added) where
    /// no body lies in the part or the general decision is needed.
    pub(super) fn solve_part_by_bodies(
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

    /// A problem away from the ground solved with `bodies` held together
    /// ([`Problem::solve_contracted`]); where a group holding bodies cannot stay whole, the part
    /// of it that would move ahead splits the bodies it cuts, and the problem is solved again,
    /// at most [`BODY_SPLITS`] times. Each try costs a small contracted problem and a cut per
    /// group holding a body, where the general decision would cut the whole problem again at
    /// every level of its recursion. `None`: the general decision is needed.
    pub(super) fn solve_by_bodies(&self, bodies: &[Vec<usize>]) -> Option<Vec<Group>> {
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
}

/// How a problem solved with bodies held together came out ([`Problem::solve_contracted`]).
pub(super) enum Held {
    /// Every body held: the groups of the full problem.
    Groups(Vec<Group>),
    /// Some groups cannot stay whole: the parts of them that would move ahead.
    Breaks(Vec<bool>),
    /// A group touches another moving at its own acceleration.
    Undetermined,
}

#[cfg(test)]
mod tests {
    use super::super::testing::*;
    use super::*;
    use crate::integrate::event::flow;
    use proptest::prelude::*;

    /// Up to two bodies among the first n nodes: those labelled 1, those labelled 2 (a body of
    /// one node is none).
    fn labelled_bodies(labels: &[usize], n: usize) -> Vec<Vec<usize>> {
        [1, 2]
            .iter()
            .map(|&b| (0..n).filter(|&i| labels[i] == b).collect::<Vec<usize>>())
            .filter(|body| body.len() >= 2)
            .collect()
    }

    proptest! {
        #![proptest_config(crate::integrate::event::many_cheap_cases())]

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
}
