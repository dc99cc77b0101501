//! Two bodies whose faces lie on each other, pressed at both ends of the faces' overlap. Where a
//! face comes down flat on another and both ends of their overlap are left at rest on each
//! other, pressing (the contact problem at the level of accelerations says so), the faces move
//! together: the relative rotation is locked, the normal distance too, and the one relative
//! motion left is the faces sliding along each other (frictionless, as at every face between
//! blocks). This module owns that mechanism: the two contacts as couples ([`Couple`], the
//! corner of one block on the face of the other at each end of the overlap), both bodies'
//! motion with the two pushes as series over a step ([`couple::pushed`]: each order's pushes
//! solve a 2x2 system), and the conditions that end it, either push falling to zero (the
//! faces turn apart at that end, or part). Where an end of the overlap reaches a corner of
//! the other face (the faces slide along each other) is the pair's (`clearance`), and the
//! end passes to that corner. A body may stay on the ground, rocking on its pivot, slipping or
//! seated: which ends press is then decided together with how each pivot moves
//! ([`Lying::decide`], friction at a pivot making it a problem that may have no answer or
//! several, said by name); a landing of either body takes the ground's impulses with both
//! ends' at once (the engine's `lying_lands`), and the faces lie on each other on where both
//! ends still press after it.

use super::abutting::{self, Abutting, Together};
use super::clearance::{Side, Touch};
use super::couple::{self, Couple, Member, Pushed};
use super::modes::{self, Constraint, Equations, Guard, Inputs, Mode, Scales, State, Trajectory};
use super::series::{self, Coeffs};

/// What the contact problem of two faces lying on each other decides: each body's mode (in
/// the first contact's order) and which ends press.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Decision {
    pub(super) modes: [Mode; 2],
    pub(super) pressed: [bool; 2],
}

/// Two faces lying on each other: the contact at each end of their overlap, the first's sides
/// giving the bodies' order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Lying {
    pub(super) ends: [Couple; 2],
}

impl Lying {
    /// The faces lying on each other at the contacts `ends` (each a corner of one body on the
    /// other's face), the bodies (`bodies`, in the first contact's order, with their pivots'
    /// homes and their states). A push whose arms are not zero but too short to turn the
    /// bodies leaves the decision's matrix singular, and [`Lying::decide`] says so; where an
    /// end's push moves neither body in its mode, both arms zero to the bit ([`Lying::turns`]),
    /// only ways in which a body slips, flies, or both stay seated face on face can hold.
    pub(super) fn new(
        ends: [&Touch; 2],
        bodies: [usize; 2],
        homes: [[f64; 2]; 2],
        states: [&State; 2],
    ) -> Lying {
        let couple = |t: &Touch| {
            let side = |s: Side| match s {
                Side::Body(k, _) => bodies.iter().position(|&b| b == k),
                _ => None,
            };
            let order = [side(t.sides[0]), side(t.sides[1])]
                .map(|k| k.expect("an end of lying faces is between their bodies"));
            let placed = order.map(|k| Some(states[k]));
            let (ids, homes) = (order.map(|k| Some(bodies[k])), order.map(|k| homes[k]));
            Couple::placed(t, ids, homes, placed)
        };
        Lying {
            ends: [couple(ends[0]), couple(ends[1])],
        }
    }

    /// Whether each end's push moves a body in its mode (`members`): a body whose pivot slips,
    /// or that is in flight or slides seated, moves under any push; one that rocks on a stuck
    /// pivot or rests, only under a push with an arm about its pivot (an end at both pivots, as
    /// where two blocks' bottom corners are together, turns neither).
    pub(super) fn turns(&self, members: [Member; 2]) -> bool {
        members.iter().any(Member::translates) || self.ends.iter().all(|end| end.turns(0.0))
    }

    /// The bodies, in the first contact's order.
    pub(super) fn bodies(&self) -> [Option<usize>; 2] {
        self.ends[0].bodies
    }

    /// Both bodies' motion from their states in their modes (`members`, in the first
    /// contact's order), and the two pushes. Two seated bodies face on face rest each on its
    /// own (the push left open), or slide together on the first contact's one push
    /// ([`abutting`]).
    pub(super) fn motion(&self, members: [Member; 2], inputs: &Inputs) -> Pushed {
        match self.abutting(members) {
            Some((_, Together::Rest)) => abutting::resting(members, inputs),
            Some((_, Together::Slide(_))) => abutting::sliding(&self.ends[0], members, inputs),
            None => couple::pushed(&[&self.ends[0], &self.ends[1]], members, inputs),
        }
    }

    /// Both bodies seated face on face in `members`, moving together: the pair and how.
    pub(super) fn abutting(&self, members: [Member; 2]) -> Option<(Abutting, Together)> {
        Some((Abutting::of(&self.ends, members)?, Together::of(members)?))
    }

    /// Contact e's sides as the first contact's order numbers them (an involution).
    pub(super) fn order(&self, e: usize) -> [usize; 2] {
        self.ends[e]
            .bodies
            .map(|b| usize::from(b != self.bodies()[0]))
    }

    /// Trajectories in the first contact's order, in contact e's (or back).
    fn ordered(&self, t: &[Trajectory; 2], e: usize) -> [Trajectory; 2] {
        self.order(e).map(|k| t[k].clone())
    }

    /// The contact problem at the level of accelerations, for faces at rest on each other at both
    /// ends (`members`: the bodies in their modes and states, the first contact's order). Every way
    /// each body's pivot may stick, slip or leave the ground, or a seated body stay seated or turn
    /// on its pivot ([`couple::ways`]), is tried with each set of pressing ends: both (the two
    /// pushes of [`Lying::motion`] >= 0), one (its push >= 0, the couple's motion on it alone, the
    /// other end's corner leaving its face: its distance outside grows just after now,
    /// [`Couple::gap`], the orders after the acceleration deciding where that is zero to a tie),
    /// none (the bodies alone, both corners leaving); a way holds where, besides, no condition of
    /// either body's mode breaks just after now ([`couple::broken_by`]). For bodies in flight the
    /// matrix W that takes the pushes to the ends' accelerations away is positive definite (each
    /// body's mass matrix is, and two points of one face constrain independently), and exactly one
    /// holds; with a body on the ground, Coulomb friction at its pivot makes the problem one with
    /// friction, which may have no solution or several (Painleve), so exactly one must hold: else
    /// why not, in words, naming the ways that hold or saying that none does and which ways
    /// friction leaves without a positive effective mass.
    pub(super) fn decide(&self, members: [Member; 2], now: &Inputs) -> Result<Decision, String> {
        let Member::Moves(first, ..) = members[0] else {
            unreachable!("the bodies of lying faces move");
        };
        // A corner leaves its face where its distance outside grows just after now, the orders
        // after the acceleration saying so where that is zero to a tie.
        let leaves = |e: usize, t: &[Trajectory; 2]| {
            let gap = self.ends[e].gap(&self.ordered(t, e));
            let (size, scale_t) = self.ends[e].touch.scales;
            series::sign_after(&gap, size, scale_t) > 0
        };
        // A push that W leaves undetermined (a singular matrix: no arm turns either body
        // about its pivot) presses nowhere.
        let presses = |push: &Coeffs| {
            push.iter().all(|x| x.is_finite())
                && series::sign_after(push, Scales::of(first).force, first.time_scale_s()) >= 0
        };
        let ways = [0, 1].map(|k| couple::ways(members[k], self.ends[0].pivots[k]));
        let (mut holding, mut paradox, mut tried) = (Vec::new(), Vec::new(), 0);
        for a in &ways[0] {
            for b in &ways[1] {
                let picked = [*a, *b].map(|m| m.expect("a body's way is a mode"));
                let trial = [0, 1].map(|k| match members[k] {
                    Member::Moves(body, _, state) => Member::Moves(body, picked[k], state),
                    Member::Fixed => unreachable!("the bodies of lying faces move"),
                });
                let named = |pressed: [bool; 2]| {
                    let each = trial.iter().map(|m| match m {
                        Member::Moves(body, mode, _) => format!("{} {}", body.name, mode.name()),
                        Member::Fixed => unreachable!("the bodies of lying faces move"),
                    });
                    let ends = match pressed {
                        [true, true] => "pressing at both ends".to_string(),
                        [false, false] => "parting at both ends".to_string(),
                        _ => {
                            let e = usize::from(pressed[1]);
                            let corner = match trial[self.order(e)[0]] {
                                Member::Moves(body, ..) => body.name.as_str(),
                                Member::Fixed => unreachable!("the bodies of lying faces move"),
                            };
                            format!("pressing at {corner}'s corner alone")
                        }
                    };
                    format!("{} {ends}", each.collect::<Vec<_>>().join(" with "))
                };
                let kept = |t: &[Trajectory; 2]| {
                    (0..2).all(|k| couple::broken_by(trial[k], &t[k]).is_none())
                };
                let slips =
                    |t: &[Trajectory; 2]| t.iter().any(|t| t.denominator.is_some_and(|d| d <= 0.0));
                let alone = [0, 1].map(|k| match trial[k] {
                    Member::Moves(body, mode, state) => {
                        modes::trajectory(body, Equations::Exact, mode, state, now)
                    }
                    Member::Fixed => unreachable!("the bodies of lying faces move"),
                });
                let apart = (0..2).all(|e| leaves(e, &alone)) && kept(&alone);
                if let Some(pair) = Abutting::of(&self.ends, trial) {
                    // Two seated bodies stay face on face resting or sliding together, on the
                    // pair's conditions (and a sliding pair's stop); else they part.
                    let holds = |c: &Constraint| c.holds_after(first.time_scale_s());
                    let together = match Together::of(trial) {
                        Some(Together::Rest) => Some(pair.rest_conditions(now).iter().all(holds)),
                        Some(Together::Slide(_)) => {
                            let moved = abutting::sliding(&self.ends[0], trial, now);
                            let stops = (0..2).all(|k| stop_kept(trial[k], &moved.bodies[k]));
                            Some(stops && pair.sliding_conditions(&moved, now).iter().all(holds))
                        }
                        None => None,
                    };
                    tried += 1 + usize::from(together.is_some());
                    if together == Some(true) {
                        holding.push((picked, [true, true], named([true, true])));
                    }
                    if apart {
                        holding.push((picked, [false, false], named([false, false])));
                    }
                    continue;
                }
                tried += 4;
                let both = self.motion(trial, now);
                let [[w00, w01], [w10, w11]] = both.compliance;
                let det = w00 * w11 - w01 * w10;
                if w00 <= 0.0 || w11 <= 0.0 || det <= 0.0 || slips(&both.bodies) {
                    paradox.push(named([true, true]));
                }
                // A matrix singular to a tie (the two ends constrain one motion, as on a body
                // at rest and one on a stuck pivot) leaves the pushes undetermined, whatever
                // its round-off solves them to: they press nowhere.
                let determined = det > series::TIE * w00 * w11;
                if determined && both.pushes.iter().all(&presses) && kept(&both.bodies) {
                    holding.push((picked, [true, true], named([true, true])));
                }
                for e in 0..2 {
                    let one = self.ends[e].motion(self.order(e).map(|k| trial[k]), now);
                    let moved = self.ordered(&one.bodies, e);
                    if presses(&one.push) && leaves(1 - e, &moved) && kept(&moved) {
                        let mut pressed = [false; 2];
                        pressed[e] = true;
                        holding.push((picked, pressed, named(pressed)));
                    }
                }
                if apart {
                    holding.push((picked, [false, false], named([false, false])));
                }
            }
        }
        let friction = match paradox.is_empty() {
            true => String::new(),
            false => format!(
                ", friction making the effective mass of {} not positive (Painleve's paradox)",
                paradox.join("; ")
            ),
        };
        match &holding[..] {
            [(modes, pressed, _)] => Ok(Decision {
                modes: *modes,
                pressed: *pressed,
            }),
            [] if !self.turns(members) => Err(format!(
                "none of the {tried} ways of the pivots and the ends holds, an end of the faces' \
                 overlap at both bodies' pivots, where its push would turn neither{friction}"
            )),
            [] => Err(format!(
                "none of the {tried} ways of the pivots and the ends holds{friction}: the rigid \
                 model with Coulomb friction has no motion here"
            )),
            _ => Err(format!(
                "several ways of the pivots and the ends hold ({}){friction}: the rigid model \
                 with Coulomb friction does not say which",
                (holding.iter().map(|(.., n)| n.as_str()))
                    .collect::<Vec<_>>()
                    .join("; ")
            )),
        }
    }

    /// Each end's contact where the bodies are in `states` (first contact's order), as touches
    /// of blocks that have not parted.
    pub(super) fn touches_at(&self, states: [&State; 2]) -> [Touch; 2] {
        self.ends.map(|end| {
            let order = end.bodies.map(|b| usize::from(b != self.bodies()[0]));
            end.touch_at(order.map(|k| Some(states[k])))
        })
    }

    /// The faces lie on each other while both pushes stay >= 0 (scaled by the weight of the
    /// first body of `members`, their modes giving `motion`); two seated bodies face on face,
    /// while the pair can rest, or, sliding together, while its push stays >= 0 and both stay
    /// seated ([`Abutting`]).
    pub(super) fn conditions(
        &self,
        members: [Member; 2],
        motion: &Pushed,
        inputs: &Inputs,
    ) -> Vec<Constraint> {
        match self.abutting(members) {
            Some((pair, Together::Rest)) => pair.rest_conditions(inputs).to_vec(),
            Some((pair, Together::Slide(_))) => pair.sliding_conditions(motion, inputs),
            None => {
                let Member::Moves(body, ..) = members[0] else {
                    unreachable!("the bodies of lying faces move");
                };
                (motion.pushes.iter())
                    .map(|&push| Constraint {
                        series: push,
                        scale: Scales::of(body).force,
                        guard: Guard::Parts,
                        strict: false,
                    })
                    .collect()
            }
        }
    }
}

/// Whether a seated body sliding in `member`'s mode keeps sliding just after now on `traj` (a
/// resting body has no such condition).
fn stop_kept(member: Member, traj: &Trajectory) -> bool {
    let Member::Moves(body, ..) = member else {
        return true;
    };
    (modes::constraints(body, Equations::Exact, traj).iter())
        .filter(|c| c.guard == Guard::Stop)
        .all(|c| c.holds_after(body.time_scale_s()))
}
