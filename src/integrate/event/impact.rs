//! Impacts at vertical joints: instantaneous, frictionless, pairwise, Newton's restitution e.
//! A chain of touching blocks is resolved by successive pairwise collisions, largest approach
//! speed first (ties: the leftmost face), until no touching pair approaches. Computed in exact
//! arithmetic, so momentum is conserved exactly, energy too when e = 1, and equal blocks exchange
//! velocities exactly (Newton's cradle).

use crate::exact::Q;

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

/// Resolves a chain. `faces` are (left body, right body) pairs that touch, ordered left to
/// right. Faces approaching at `negligible` or less are left alone: with e < 1 a chain settles
/// only geometrically, so its last approach speeds fall below round-off after a few dozen
/// collisions and are touches from then on. Returns the collisions and the kinetic energy lost
/// (J), or `None` if the chain has not settled after `max_collisions`.
pub fn resolve(
    bodies: &mut [Body],
    faces: &[(usize, usize)],
    e: &Q,
    negligible: &Q,
    max_collisions: usize,
) -> Option<(Vec<Collision>, Q)> {
    let mut collisions = Vec::new();
    let mut loss = Q::zero();
    let half = Q::frac(1, 2);
    let one_e = Q::one() + e;
    let lossy = Q::one() - e * e;
    loop {
        let mut best: Option<(usize, Q)> = None;
        for (k, &(l, r)) in faces.iter().enumerate() {
            let approach = &bodies[l].velocity - &bodies[r].velocity;
            if approach > *negligible && best.as_ref().is_none_or(|(_, b)| approach > *b) {
                best = Some((k, approach));
            }
        }
        let Some((k, approach)) = best else {
            return Some((collisions, loss));
        };
        if collisions.len() >= max_collisions {
            return None;
        }
        let (l, r) = faces[k];
        let before = [bodies[l].velocity.clone(), bodies[r].velocity.clone()];
        match (bodies[l].mass.clone(), bodies[r].mass.clone()) {
            (Some(ml), Some(mr)) => {
                let total = &ml + &mr;
                let impulse = &one_e * &ml * &mr / &total * &approach;
                bodies[l].velocity = &bodies[l].velocity - &impulse / &ml;
                bodies[r].velocity = &bodies[r].velocity + &impulse / &mr;
                loss = loss + &half * &ml * &mr / &total * &lossy * &approach * &approach;
            }
            (None, Some(mr)) => {
                // Rebound off the ground side: v_r' = v_l + e (v_l - v_r) with v_l = 0.
                bodies[r].velocity = e * &approach;
                loss = loss + &half * &mr * &lossy * &approach * &approach;
            }
            (Some(ml), None) => {
                bodies[l].velocity = -(e * &approach);
                loss = loss + &half * &ml * &lossy * &approach * &approach;
            }
            (None, None) => unreachable!("two ground bodies never approach"),
        }
        let after = [bodies[l].velocity.clone(), bodies[r].velocity.clone()];
        collisions.push(Collision {
            face: k,
            approach,
            before,
            after,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
