//! Problems the decision's tests share.

use super::{End, Group, Lex, Problem};
use crate::exact::Q;
use proptest::prelude::*;

pub(super) fn q(x: f64) -> Q {
    Q::from_decimal(x).unwrap()
}

/// One block of 1 kg on the ground with capacity mu g.
pub(super) fn one_block(mu: f64) -> Problem {
    Problem {
        mass: vec![Q::one()],
        external: vec![Q::zero()],
        friction: vec![(0, End::Ground, q(mu) * q(9.81))],
        contacts: vec![],
    }
}

pub(super) fn just_after(a: Q, rate: i64) -> Lex {
    Lex([a, Q::int(rate), Q::zero()])
}

/// The paper's wall with uniform friction: B1..B5, masses in units of B3's mass.
pub(super) fn five_block(mu: [f64; 6]) -> Problem {
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

/// Random problems away from the ground: masses, sliding forces, joints and faces.
pub(super) fn free_problem() -> impl Strategy<Value = Problem> {
    (2usize..9).prop_flat_map(|n| {
        (
            prop::collection::vec(1i64..6, n),
            prop::collection::vec(-12i64..13, n),
            prop::collection::vec((0..n, 0..n, 1i64..9), 1..2 * n),
            prop::collection::vec((0..n, 0..n), 0..n),
        )
            .prop_map(|(mass, external, friction, contacts)| Problem {
                mass: mass.into_iter().map(Q::int).collect(),
                external: external.into_iter().map(Q::int).collect(),
                friction: friction
                    .into_iter()
                    .filter(|(i, j, _)| i != j)
                    .map(|(i, j, f)| (i, End::Node(j), Q::int(f)))
                    .collect(),
                contacts: contacts
                    .into_iter()
                    .filter(|(l, r)| l != r)
                    .map(|(l, r)| (End::Node(l), End::Node(r)))
                    .collect(),
            })
    })
}

/// Random problems on the ground: `free_problem` with some blocks resting on it.
pub(super) fn ground_problem() -> impl Strategy<Value = Problem> {
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

/// `ground_problem` with some blocks' faces against an abutment, on either side.
pub(super) fn abutted_problem() -> impl Strategy<Value = Problem> {
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

pub(super) fn sorted(mut groups: Vec<Group>) -> Vec<Group> {
    groups.sort_by(|a, b| a.nodes.cmp(&b.nodes));
    groups
}
