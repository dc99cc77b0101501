//! Step 4 of a regrouping: the component's problem solved, stuck pieces by their stick
//! intervals and the rest by the general decision (remembered per run where it can be met
//! again), at the exact ground acceleration of the instant.

use super::scratch::Decided;
use super::scratch::NONE;
use crate::exact::Q;
use crate::integrate::event::slip::Slip;
use crate::integrate::event::solver::{End, Group, Lex, Problem};
use crate::integrate::event::Engine;
use std::rc::Rc;

/// A ground acceleration within rounding of a breakpoint of the decision is snapped to it; the
/// set_vel can move the breakpoint that matters at most this many times.
const MAX_SNAPS: usize = 8;

/// Ground accelerations remembered per decision problem (the oldest is forgotten first): a
/// problem is met again at the few stick thresholds of its neighbourhood, or away from the
/// ground at none.
const THETAS_KEPT: usize = 16;

impl Engine<'_> {
    /// The ground acceleration just after now, divided by the vertical load factor (every
    /// friction force scales with it, so the decision at lambda is the decision at 1 with
    /// a_g/lambda): exact value (or `snapped`, already divided) with its derivatives.
    pub(super) fn ground_lex(&self, snapped: Option<Q>) -> Lex {
        let s = self.s();
        let q = |x: f64| Q::from_f64_exact(x).expect("finite value");
        let (a, (r1, r2)) = (self.seg.accel(s), self.seg.accel_rates(s));
        let (l, dl) = (self.seg.lambda_at(s), self.seg.lambda.1);
        if !self.seg.has_vertical() {
            let a0 = snapped.unwrap_or_else(|| q(a));
            return Lex([a0, q(r1), q(r2)]);
        }
        // (a/l)' = (a' l - a l')/l^2; (a/l)'' = -2 l' (a' l - a l')/l^3 (a'' = l'' = 0).
        let a0 = snapped.unwrap_or_else(|| q(a) / q(l));
        let num = r1 * l - a * dl;
        Lex([a0, q(num / (l * l)), q(-2.0 * dl * num / (l * l * l))])
    }

    /// Step 4 of [`Engine::regroup`]: the groups of the component's problem `p` and the stick
    /// intervals of those found stuck by their pieces (`None` for the others), into `out` (empty
    /// when called); returns the ground acceleration they were decided at. Pieces joined to the
    /// ground with the ground acceleration strictly inside their stick intervals stay stuck
    /// (the common case); the other pieces get the general decision, with the sliding `bodies`
    /// of the component (worked out only then). Pieces meet only through the ground, whose
    /// motion is given, so each is decided on its own: a block knocked out of a large stuck
    /// cluster costs that cluster a stick interval, not a general decision over all of it.
    pub(super) fn solve_component(
        &mut self,
        p: &Problem,
        blocks: &[usize],
        bodies: impl FnOnce(&Self) -> Vec<Vec<usize>>,
        theta: Option<&Q>,
        out: &mut Decided,
    ) -> Lex {
        let mut theta_lex = self.ground_lex(theta.cloned());
        self.stuck_pieces(p, blocks, &theta_lex, theta.is_some(), out);
        if out.rest.is_empty() {
            return theta_lex;
        }
        let bodies = bodies(self);
        if out.rest.len() == blocks.len() {
            let groups = self.decide_general(p, &mut theta_lex, theta.is_some(), &bodies);
            out.push_decided(&groups);
            return theta_lex;
        }
        let rest = std::mem::take(&mut out.rest);
        let mut index = vec![NONE; blocks.len()];
        for (k, &i) in rest.iter().enumerate() {
            index[i] = k;
        }
        // What is left of each body in the rest (an impact can have knocked some of its blocks
        // into other pieces).
        let rest_bodies: Vec<Vec<usize>> = bodies
            .iter()
            .map(|b| {
                b.iter()
                    .filter(|&&i| index[i] != NONE)
                    .map(|&i| index[i])
                    .collect::<Vec<usize>>()
            })
            .filter(|b| !b.is_empty())
            .collect();
        let q = p.restrict(&rest);
        let before = theta_lex.clone();
        let found = self.decide_general(&q, &mut theta_lex, theta.is_some(), &rest_bodies);
        if theta_lex == before {
            for g in found.iter() {
                let nodes = g.nodes.iter().map(|&k| rest[k]);
                out.push(nodes, g.accel.clone(), g.grounded, None);
            }
            out.rest = rest;
        } else {
            // A hidden breakpoint moved the ground acceleration, at which the stuck pieces were
            // not decided: decide everything there (rare).
            theta_lex = before;
            let groups = self.decide_general(p, &mut theta_lex, theta.is_some(), &bodies);
            out.clear();
            out.push_decided(&groups);
        }
        theta_lex
    }

    /// Constant friction on block i from its joints that slide, by their recorded directions.
    pub(in crate::integrate::event) fn external_force(&self, i: usize) -> Q {
        self.external_force_by(i, |s| self.slip[s])
    }

    /// The same with each horizontal joint's state given by `slip`.
    pub(in crate::integrate::event) fn external_force_by(
        &self,
        i: usize,
        slip: impl Fn(usize) -> Slip,
    ) -> Q {
        let mut e = Q::zero();
        for &s in &self.given.topo.below[i] {
            let state = slip(s.0);
            if self.live_horizontal(s.0) && !state.is_stuck() {
                e = e + state.on_upper(&self.given.cap_q[s.0]);
            }
        }
        for &s in &self.given.topo.above[i] {
            let state = slip(s.0);
            if self.live_horizontal(s.0) && !state.is_stuck() {
                e = e - state.on_upper(&self.given.cap_q[s.0]);
            }
        }
        e
    }

    /// The general decision. Only the signs of the ground acceleration's derivatives matter
    /// (they order ties, and every tie compares the same mass combination), so theta is
    /// normalised to them; decisions away from the ground, or at a stick threshold (an exact
    /// value met again cycle after cycle), are remembered per run ([`Memo`](super::memo::Memo)).
    pub(super) fn solve(
        &mut self,
        p: &Problem,
        theta: &Lex,
        remember: bool,
        bodies: &[Vec<usize>],
    ) -> Rc<[Group]> {
        let sign = |q: &Q| Q::int(i64::from(q.signum()));
        let theta = if p.touches_ground() {
            let second = if theta.0[1].is_zero() {
                sign(&theta.0[2])
            } else {
                Q::zero()
            };
            Lex([theta.0[0].clone(), sign(&theta.0[1]), second])
        } else {
            Lex::zero()
        };
        if !remember && p.touches_ground() {
            return self.solve_anew(p, &theta, bodies).into();
        }
        let known = self.caches.free_memo.get(p);
        if let Some((_, found)) = known.and_then(|k| k.iter().find(|(at, _)| *at == theta)) {
            return Rc::clone(found);
        }
        let found: Rc<[Group]> = self.solve_anew(p, &theta, bodies).into();
        match self.caches.free_memo.get_mut(p) {
            Some(known) => {
                if known.len() == THETAS_KEPT {
                    known.remove(0);
                }
                known.push((theta, Rc::clone(&found)));
            }
            None => self.caches.free_memo.insert(
                p.clone(),
                vec![(theta, Rc::clone(&found))],
                p.mass.len(),
            ),
        }
        found
    }

    /// Problem p decided at `theta`; at a limit of its own remembered stick interval (a stuck
    /// cluster reaching it), without the two cuts at the ground ([`Problem::solve_past_limit`]).
    pub(super) fn solve_anew(&self, p: &Problem, theta: &Lex, bodies: &[Vec<usize>]) -> Vec<Group> {
        p.touches_ground()
            .then(|| self.caches.stick_memo.get(p))
            .flatten()
            .and_then(|stick| p.solve_past_limit(theta, bodies, stick))
            .unwrap_or_else(|| p.solve(theta, bodies))
    }

    /// The general decision of problem p at the ground acceleration `theta`, snapping theta to
    /// a breakpoint that rounding hides: the motion will start from the float c lambda - a_g
    /// (`Slide::formed`), and if rounding gives it no sign, or the wrong one, the group's
    /// breakpoint is in fact where the ground is. `theta` comes back snapped.
    pub(in crate::integrate::event) fn decide_general(
        &mut self,
        p: &Problem,
        theta: &mut Lex,
        remember: bool,
        bodies: &[Vec<usize>],
    ) -> Rc<[Group]> {
        let mut groups = self.solve(p, theta, remember, bodies);
        for _ in 0..MAX_SNAPS {
            let (lambda, ag) = (self.seg.lambda_at(self.s()), self.seg.accel(self.s()));
            let hidden = groups.iter().find(|g| {
                let rel = g.accel.to_f64() * lambda - ag;
                let exact = (&g.accel - &theta.0[0]).signum();
                !g.grounded
                    && exact != 0
                    && (rel == 0.0 || (rel > 0.0) != (exact > 0))
                    && touches_ground(p, &groups, g)
            });
            match hidden {
                Some(g) => {
                    theta.0[0] = g.accel.clone();
                    groups = self.solve(p, theta, false, bodies);
                }
                None => break,
            }
        }
        groups
    }
}

/// Does group g share an undecided joint with the ground or a stuck group?
fn touches_ground(p: &Problem, groups: &[Group], g: &Group) -> bool {
    let grounded_node = |n: usize| groups.iter().any(|h| h.grounded && h.nodes.contains(&n));
    let inside = |n: usize| g.nodes.contains(&n);
    p.friction.iter().any(|(i, j, _)| match j {
        End::Ground => inside(*i),
        End::Node(j) => (inside(*i) && grounded_node(*j)) || (inside(*j) && grounded_node(*i)),
    }) || p.contacts.iter().any(|(l, r)| match (l, r) {
        (End::Ground, End::Node(n)) | (End::Node(n), End::Ground) => inside(*n),
        (End::Node(a), End::Node(b)) => {
            (inside(*a) && grounded_node(*b)) || (inside(*b) && grounded_node(*a))
        }
        _ => false,
    })
}
