//! Impacts at vertical joints: instantaneous, frictionless, pairwise, Newton's restitution e.
//! A chain of touching blocks is resolved by successive pairwise collisions, largest approach
//! speed first (ties: the leftmost face), until no touching pair approaches. Computed in exact
//! arithmetic, so momentum is conserved exactly, energy too when e = 1, and equal blocks exchange
//! velocities exactly (Newton's cradle).

use super::cycle::Cycle;
use crate::exact::Q;
use std::cmp::Reverse;
use std::collections::BinaryHeap;

/// A body in an impact: a block (finite mass) or the ground and its abutments (infinite mass,
/// velocity zero relative to the ground).
#[derive(Debug, Clone, PartialEq)]
pub struct Body {
    /// Mass (kg); `None` for the ground.
    pub mass: Option<Q>,
    /// Velocity relative to the ground (m/s).
    pub velocity: Q,
}

/// One collision of a chain.
#[derive(Debug, Clone, PartialEq)]
pub struct Collision {
    /// Face index (into the faces given).
    pub face: usize,
    /// Approach speed before the collision (m/s).
    pub approach: Q,
    /// Velocities of the left and right body before (m/s).
    pub before: [Q; 2],
    /// Velocities of the left and right body after (m/s).
    pub after: [Q; 2],
}

/// Why a chain was given up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unsettled {
    /// The bodies' velocities came back to the same values, again and again, every `period`
    /// collisions: the chain would never settle.
    Cycle {
        /// Collisions between two visits of one state.
        period: usize,
    },
    /// The backstop on the number of collisions was reached without a repeated state.
    Backstop,
}

/// Resolves a chain. `faces` are (left body, right body) pairs that touch, ordered left to
/// right. Faces approaching at `negligible` or less are left alone: with e < 1 a chain settles
/// only geometrically, so its last approach speeds fall below round-off after a few dozen
/// collisions and are touches from then on. Returns the collisions and the kinetic energy lost
/// (J), or why the chain was given up after the collisions it had (their count beside it).
///
/// The next collision is a function of the velocities alone, so velocities seen again mean a
/// chain that never ends ([`Cycle`]); a long chain is not one (n equal blocks with e = 1 sort
/// their velocities by exchanges, up to n (n - 1) / 2 of them), and only `max_collisions`, a
/// backstop the caller sizes to the chain, ends it.
pub fn resolve(
    bodies: &mut [Body],
    faces: &[(usize, usize)],
    e: &Q,
    negligible: &Q,
    max_collisions: usize,
) -> Result<(Vec<Collision>, Q), (Unsettled, usize)> {
    let mut collisions = Vec::new();
    let mut loss = Q::zero();
    // A collision changes the approach of its two bodies' faces only: the faces approaching,
    // fastest first (ties: the leftmost), are kept in a queue, and only those faces are looked
    // at again. A course of touching blocks with e < 1 takes many collisions per face to
    // settle, and looking at every face after each cost the chain's length per collision.
    // The faces of each block (the ground side's velocity never changes, so it has none here).
    let mut at: Vec<Vec<usize>> = vec![Vec::new(); bodies.len()];
    for (k, &(l, r)) in faces.iter().enumerate() {
        for b in [l, r].into_iter().filter(|&b| bodies[b].mass.is_some()) {
            at[b].push(k);
        }
    }
    let mut queue = Approaching {
        heap: BinaryHeap::new(),
        stamp: vec![0; faces.len()],
    };
    for k in 0..faces.len() {
        queue.look(k, faces, bodies, negligible);
    }
    // The state's key is a sum of one term per body, so a collision updates it in O(1); a
    // term mixes the body's index into its velocity's word (splitmix64's finaliser).
    let term = |i: usize, v: &Q| {
        let mut z = v.hash_word() ^ (i as u64).wrapping_mul(0x9e37_79b9_7f4a_7c15);
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    };
    let mut key = bodies
        .iter()
        .enumerate()
        .fold(0u64, |s, (i, b)| s.wrapping_add(term(i, &b.velocity)));
    let mut cycle = Cycle::default();
    while let Some((approach, k)) = queue.pop() {
        if collisions.len() >= max_collisions {
            return Err((Unsettled::Backstop, collisions.len()));
        }
        let (l, r) = faces[k];
        let before = [bodies[l].velocity.clone(), bodies[r].velocity.clone()];
        loss = loss + collide(bodies, faces[k], &approach, e);
        let after = [bodies[l].velocity.clone(), bodies[r].velocity.clone()];
        key = key
            .wrapping_sub(term(l, &before[0]))
            .wrapping_sub(term(r, &before[1]))
            .wrapping_add(term(l, &after[0]))
            .wrapping_add(term(r, &after[1]));
        if let Some(period) = cycle.step(key, || {
            bodies
                .iter()
                .map(|b| b.velocity.clone())
                .collect::<Vec<Q>>()
        }) {
            return Err((Unsettled::Cycle { period }, collisions.len() + 1));
        }
        collisions.push(Collision {
            face: k,
            approach,
            before,
            after,
        });
        for &j in at[l].iter().chain(&at[r]) {
            queue.look(j, faces, bodies, negligible);
        }
    }
    Ok((collisions, loss))
}

/// Numbers of a chain larger than this many bits are rounded to [`KEPT_BITS`] significant
/// bits: a course of touching blocks with e < 1 settles only after hundreds of collisions, and
/// each adds the bits of the masses and of e to the velocities, until the arithmetic of one
/// collision takes seconds (a fuzzed course of six blocks: 510 impacts in 37 s). Rounding the
/// impulse keeps momentum exact (each block gets it divided by its own mass) and moves the
/// velocities by 2^-256 of themselves, 10^-61 of what f64 resolves; short chains (Newton's
/// cradle, every shipped wall's) never reach the size and stay exact to the last bit.
const ROUND_FROM_BITS: u64 = 1024;

/// Significant bits kept where a chain's numbers are rounded.
const KEPT_BITS: u64 = 256;

fn kept(x: Q) -> Q {
    if x.bits() > ROUND_FROM_BITS {
        x.rounded(KEPT_BITS)
    } else {
        x
    }
}

/// One collision at the face (l, r) approaching at `approach`: the bodies' velocities after it
/// (Newton's restitution e, momentum conserved), and the kinetic energy it loses (J), exactly
/// the kinetic energy before less after.
fn collide(bodies: &mut [Body], (l, r): (usize, usize), approach: &Q, e: &Q) -> Q {
    let half = Q::frac(1, 2);
    match (bodies[l].mass.clone(), bodies[r].mass.clone()) {
        (Some(ml), Some(mr)) => {
            let total = &ml + &mr;
            let impulse = kept((Q::one() + e) * &ml * &mr / &total * approach);
            let (vl, vr) = (bodies[l].velocity.clone(), bodies[r].velocity.clone());
            bodies[l].velocity = &vl - &impulse / &ml;
            bodies[r].velocity = &vr + &impulse / &mr;
            let (nl, nr) = (&bodies[l].velocity, &bodies[r].velocity);
            half * (ml * (&vl * &vl - nl * nl) + mr * (&vr * &vr - nr * nr))
        }
        (None, Some(mr)) => {
            // Rebound off the ground side: v_r' = v_l + e (v_l - v_r) with v_l = 0.
            let before = bodies[r].velocity.clone();
            bodies[r].velocity = kept(e * approach);
            let after = &bodies[r].velocity;
            half * mr * (&before * &before - after * after)
        }
        (Some(ml), None) => {
            let before = bodies[l].velocity.clone();
            bodies[l].velocity = kept(-(e * approach));
            let after = &bodies[l].velocity;
            half * ml * (&before * &before - after * after)
        }
        (None, None) => unreachable!("two ground bodies never approach"),
    }
}

/// The faces of a chain that approach, fastest first (ties: the leftmost face). Entries are
/// (approach, face, stamp); one whose stamp is not its face's latest is stale.
struct Approaching {
    heap: BinaryHeap<(Q, Reverse<usize>, usize)>,
    stamp: Vec<usize>,
}

impl Approaching {
    /// Face k's approach, looked at again (its bodies' velocities have changed).
    fn look(&mut self, k: usize, faces: &[(usize, usize)], bodies: &[Body], negligible: &Q) {
        self.stamp[k] += 1;
        let (l, r) = faces[k];
        let approach = &bodies[l].velocity - &bodies[r].velocity;
        if approach > *negligible {
            self.heap.push((approach, Reverse(k), self.stamp[k]));
        }
    }

    /// The fastest approaching face and its approach speed.
    fn pop(&mut self) -> Option<(Q, usize)> {
        while let Some((approach, Reverse(k), stamp)) = self.heap.pop() {
            if stamp == self.stamp[k] {
                return Some((approach, k));
            }
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fuzzer's slow chain, in small: six touching blocks of unequal masses given as
    /// decimals, e = 0.1623056291686158 (a float's exact value), the first one pushed. It
    /// settles after hundreds of collisions; its numbers stay at the size the rounding keeps
    /// them, momentum is exact and the loss is exactly the kinetic energy lost.
    #[test]
    fn a_long_chain_of_unequal_blocks_keeps_its_numbers_small_and_momentum_exact() {
        let masses = [
            2_233_715, 582_071, 1_113_489, 1_803_307, 1_203_883, 2_048_239,
        ];
        let mut b: Vec<Body> = masses
            .iter()
            .enumerate()
            .map(|(k, &m)| Body {
                mass: Some(Q::frac(m, 1000)),
                velocity: Q::frac(if k == 0 { 7 } else { 1 }, 100),
            })
            .collect();
        let momentum = |b: &[Body]| -> Q {
            b.iter()
                .map(|x| x.mass.clone().unwrap() * &x.velocity)
                .fold(Q::zero(), |s, p| s + p)
        };
        let energy = |b: &[Body]| -> Q {
            b.iter()
                .map(|x| Q::frac(1, 2) * x.mass.clone().unwrap() * &x.velocity * &x.velocity)
                .fold(Q::zero(), |s, p| s + p)
        };
        let (p0, k0) = (momentum(&b), energy(&b));
        let faces: Vec<(usize, usize)> = (0..5).map(|k| (k, k + 1)).collect();
        let e = Q::from_f64_exact(0.1623056291686158).unwrap();
        let tiny = Q::frac(1, 1 << 100);
        let (collisions, loss) = resolve(&mut b, &faces, &e, &tiny, 1_000_000).unwrap();
        assert!(collisions.len() > 100, "{} collisions", collisions.len());
        assert_eq!(momentum(&b), p0);
        assert_eq!(&k0 - energy(&b), loss);
        for x in &b {
            assert!(
                x.velocity.bits() < 2 * ROUND_FROM_BITS,
                "{}",
                x.velocity.bits()
            );
        }
    }

    fn body(m: i64, v: i64) -> Body {
        Body {
            mass: Some(Q::int(m)),
            velocity: Q::int(v),
        }
    }

    #[test]
    fn newtons_cradle() {
        let mut b = vec![body(1, 1), body(1, 0), body(1, 0)];
        let (c, loss) = resolve(&mut b, &[(0, 1), (1, 2)], &Q::one(), &Q::zero(), 100).unwrap();
        assert_eq!(c.len(), 2);
        assert_eq!(
            b.iter().map(|b| b.velocity.clone()).collect::<Vec<_>>(),
            vec![Q::zero(), Q::zero(), Q::one()]
        );
        assert!(loss.is_zero());
    }

    #[test]
    fn momentum_is_exact_and_energy_lost_matches() {
        let mut b = vec![body(3, 2), body(1, -1)];
        let e = Q::frac(1, 2);
        let before: Q = b
            .iter()
            .map(|b| b.mass.clone().unwrap() * &b.velocity)
            .sum();
        let ke = |b: &[Body]| -> Q {
            b.iter()
                .map(|b| Q::frac(1, 2) * b.mass.clone().unwrap() * &b.velocity * &b.velocity)
                .sum()
        };
        let k0 = ke(&b);
        let (_, loss) = resolve(&mut b, &[(0, 1)], &e, &Q::zero(), 10).unwrap();
        let after: Q = b
            .iter()
            .map(|b| b.mass.clone().unwrap() * &b.velocity)
            .sum();
        assert_eq!(before, after);
        assert_eq!(k0 - ke(&b), loss);
        // Separation speed is e times the approach speed.
        assert_eq!(&b[1].velocity - &b[0].velocity, Q::frac(3, 2));
    }

    #[test]
    fn a_lossy_chain_stops_at_negligible_speeds() {
        // Three equal blocks, e = 0.1: sequential collisions only converge geometrically.
        let mut b = vec![body(1, 1), body(1, 0), body(1, 0)];
        let tiny = Q::frac(1, 1_000_000_000_000);
        let (c, _) = resolve(&mut b, &[(0, 1), (1, 2)], &Q::frac(1, 10), &tiny, 1000).unwrap();
        assert!(c.len() < 100, "{} collisions", c.len());
        let momentum: Q = b.iter().map(|b| b.velocity.clone()).sum();
        assert_eq!(momentum, Q::one());
        assert!(
            (&b[0].velocity - &b[1].velocity) <= tiny && (&b[1].velocity - &b[2].velocity) <= tiny
        );
    }

    /// The resolution the queue replaces: every face looked at after each collision, the fastest
    /// approach taken, the leftmost of equals.
    fn by_scan(
        bodies: &mut [Body],
        faces: &[(usize, usize)],
        e: &Q,
        negligible: &Q,
    ) -> (Vec<usize>, Q) {
        let (mut order, mut loss) = (Vec::new(), Q::zero());
        loop {
            let mut best: Option<(usize, Q)> = None;
            for (k, &(l, r)) in faces.iter().enumerate() {
                let approach = &bodies[l].velocity - &bodies[r].velocity;
                if approach > *negligible && best.as_ref().is_none_or(|(_, b)| approach > *b) {
                    best = Some((k, approach));
                }
            }
            let Some((k, approach)) = best else {
                return (order, loss);
            };
            loss = loss + collide(bodies, faces[k], &approach, e);
            order.push(k);
        }
    }

    proptest::proptest! {
        // Lossy chains take hundreds of exact collisions each: fewer cases than the cheap tests.
        #![proptest_config(proptest::test_runner::Config {
            cases: 300,
            ..crate::integrate::event::many_cheap_cases()
        })]
        /// Chains of 2 to 7 bodies, an abutment at one end or none (with both, e = 1 bounces
        /// forever), equal or unequal masses,
        /// e from 0 to 1: the queue makes the same collisions in the same order as a scan of every
        /// face, to the same velocities and loss, exactly.
        #[test]
        fn the_queue_collides_as_a_scan_of_every_face(
            masses in proptest::collection::vec(1i64..4, 2..8),
            speeds in proptest::collection::vec(-3i64..4, 7),
            quarters in 0i128..5,
            walls in 0usize..3,
        ) {
            let mut bodies: Vec<Body> = masses.iter().zip(&speeds).map(|(&m, &v)| body(m, v)).collect();
            let ground = || Body { mass: None, velocity: Q::zero() };
            if walls & 1 == 1 {
                bodies.insert(0, ground());
            }
            if walls & 2 == 2 {
                bodies.push(ground());
            }
            let faces: Vec<(usize, usize)> = (1..bodies.len()).map(|r| (r - 1, r)).collect();
            let (e, tiny) = (Q::frac(quarters, 4), Q::frac(1, 1_000_000));
            let mut scanned = bodies.clone();
            let (order, loss) = by_scan(&mut scanned, &faces, &e, &tiny);
            let (collisions, queued_loss) = resolve(&mut bodies, &faces, &e, &tiny, 100_000).unwrap();
            let queued: Vec<usize> = collisions.iter().map(|c| c.face).collect();
            proptest::prop_assert_eq!(queued, order);
            proptest::prop_assert_eq!(queued_loss, loss);
            proptest::prop_assert_eq!(bodies, scanned);
        }
    }

    #[test]
    fn rebound_from_an_abutment() {
        let mut b = vec![
            Body {
                mass: None,
                velocity: Q::zero(),
            },
            body(2, -3),
        ];
        let (c, loss) = resolve(&mut b, &[(0, 1)], &Q::frac(1, 2), &Q::zero(), 10).unwrap();
        assert_eq!(c.len(), 1);
        assert_eq!(b[1].velocity, Q::frac(3, 2));
        assert_eq!(loss, Q::frac(1, 2) * Q::int(2) * Q::frac(3, 4) * Q::int(9));
    }
}
