//! The contact problem of one Moreau-Jean step solved in the contacts' impulses instead of the
//! blocks' velocities: the last resort of the whole-wall Newton solver (`wall_newton.rs`) for
//! the steps its iterations in velocities leave unsolved.
//!
//! With the friction bounds b fixed, the velocities minimising the potential of
//! `wall_newton.rs` are v = v_free + M^-1 H' p, p the impulses minimising the dual problem
//! 1/2 p' (W + E) p + p' (H v_free - target) over the box p_n >= 0, |p_t| <= b, with W = H
//! M^-1 H' (the Delassus operator: contacts sharing a block couple) and E the contacts'
//! compliances on the diagonal. The two have one answer (each is the other's convex dual);
//! what differs is how an iteration moves. In velocities each Newton step assumes the
//! contacts' states where it starts and its line search is one length for the whole wall; in
//! impulses the states are the bounds of a box, and projected Newton (Bertsekas 1982) takes
//! its step along the projection on the box, so that any number of contacts may reach or
//! leave a bound in one step. W + E is positive definite (E > 0), so each Tresca problem is
//! strictly convex and the method converges from any start; Coulomb's law is, as in
//! velocities, the fixed point b = mu p_n, and where the velocity-space fixed point cycles
//! this one often settles (docs/rocking-walls.md: every step the velocities leave on a
//! turning running bond, 1 to 20 of 1,000 to 8,000). It does not rescue the 976-block wall:
//! W has rank at most three per block, so W + E has thousands of eigenvalues of the size of
//! the compliance, along which only the box decides, and its projected steps stay short
//! there.
//!
//! Each step factorises W + E with the rows and columns of the unknowns held at a bound
//! replaced by the identity's, so the pattern (every pair of contacts sharing a block) and its
//! symbolic factorisation are made once per time step. The system is larger than the one in
//! velocities (two unknowns per contact point against three per block), which is why this
//! comes last.

use super::wall_newton::{
    Cholesky, Contact, Stall, StepProblem, MAX_ITERATIONS, ROUND_OFF_FLOOR, STALLED_UPDATES,
};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use nalgebra::{Vector2, Vector3};

/// Armijo's fraction along the projection arc.
const SUFFICIENT_DECREASE: f64 = 1e-4;

/// Shortest step tried along the projection arc, as a fraction of Newton's.
const SHORTEST: f64 = 1e-12;

/// One step's dual problem and the working memory of its solution.
#[derive(Default)]
pub struct WallDual {
    /// For each contact, the contacts sharing a block with it, itself included, sorted.
    neighbours: Vec<Vec<usize>>,
    /// For each block, the (contact, part) pairs it takes part in.
    on_block: Vec<Vec<(usize, usize)>>,
    /// The pattern of `neighbours`, unknowns 2k (normal) and 2k + 1 (tangential).
    pattern: Option<SymbolicSparseColMat<usize>>,
    /// W + E on it.
    matrix: Vec<f64>,
    /// Where each unknown's diagonal entry is in `matrix`.
    diagonal: Vec<usize>,
    /// The same with the rows and columns of the unknowns at a bound made the identity's.
    reduced: Vec<f64>,
    /// H v_free - target, per unknown.
    linear: Vec<f64>,
    /// The impulses, per unknown.
    p: Vec<f64>,
    /// Lower and upper bounds, per unknown.
    lower: Vec<f64>,
    upper: Vec<f64>,
    gradient: Vec<f64>,
    step: Vec<f64>,
    trial: Vec<f64>,
    held: Vec<bool>,
    /// H' p per block.
    r: Vec<Vector3<f64>>,
}

impl WallDual {
    /// Solves the step in impulses: `impulses` comes in as the first guess (the last step's)
    /// and leaves as the answer, `v` as the velocities v_free + M^-1 H' p. The iteration stops
    /// as the velocity-space solver's does: once a step under bounds fresh from the impulses
    /// moves no block's velocity by more than the step's tolerance. Returns the projected
    /// Newton steps used, or why it stalled.
    pub fn solve(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
        impulses: &mut [Vector2<f64>],
    ) -> Result<usize, Stall> {
        let StepProblem {
            mass,
            reach,
            v_free,
            contacts,
            tolerance_m_s,
        } = *step;
        if contacts.is_empty() {
            v.copy_from_slice(v_free);
            return Ok(0);
        }
        let mut cholesky = self.assemble(mass, v_free, contacts);
        let unknowns = 2 * contacts.len();
        self.p.clear();
        self.p
            .extend(impulses.iter().flat_map(|p| [p.x.max(0.0), p.y]));
        self.lower.resize(unknowns, 0.0);
        self.upper.resize(unknowns, 0.0);
        let (mut best, mut stalled) = (f64::INFINITY, 0);
        let mut used = 0;
        let mut fresh = true;
        while used < MAX_ITERATIONS {
            if fresh {
                self.bound(contacts);
            }
            used += 1;
            let change = self.projected_newton_step(mass, reach, contacts, &mut cholesky)?;
            let settled = change <= tolerance_m_s;
            if fresh {
                if settled {
                    self.finish(mass, v_free, contacts, v, impulses);
                    return Ok(used);
                }
                if change < 0.5 * best {
                    (best, stalled) = (change, 0);
                } else {
                    stalled += 1;
                }
                if stalled >= STALLED_UPDATES && best <= ROUND_OFF_FLOOR * tolerance_m_s {
                    self.finish(mass, v_free, contacts, v, impulses);
                    return Ok(used);
                }
            }
            fresh = settled;
        }
        Err(Stall::Iterations)
    }

    /// The step's pattern, W + E on it and H v_free - target; the symbolic factorisation of
    /// the pattern.
    fn assemble(
        &mut self,
        mass: &[Vector3<f64>],
        v_free: &[Vector3<f64>],
        contacts: &[Contact],
    ) -> Cholesky {
        let m = contacts.len();
        self.on_block.iter_mut().for_each(Vec::clear);
        self.on_block.resize(mass.len(), Vec::new());
        for (k, c) in contacts.iter().enumerate() {
            for (j, part) in c.parts.iter().enumerate() {
                if let Some(part) = part {
                    self.on_block[part.body].push((k, j));
                }
            }
        }
        self.neighbours.iter_mut().for_each(Vec::clear);
        self.neighbours.resize(m, Vec::new());
        for (k, c) in contacts.iter().enumerate() {
            let list = &mut self.neighbours[k];
            list.push(k);
            for part in c.parts.iter().flatten() {
                list.extend(self.on_block[part.body].iter().map(|&(other, _)| other));
            }
            list.sort_unstable();
            list.dedup();
        }
        let mut col_ptr = Vec::with_capacity(2 * m + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for list in &self.neighbours {
            for _ in 0..2 {
                for &other in list {
                    row_idx.extend([2 * other, 2 * other + 1]);
                }
                col_ptr.push(row_idx.len());
            }
        }
        self.matrix.clear();
        self.matrix.resize(row_idx.len(), 0.0);
        self.diagonal.clear();
        for (k, c) in contacts.iter().enumerate() {
            let list = &self.neighbours[k];
            let stride = 2 * list.len();
            let start = col_ptr[2 * k];
            for part in c.parts.iter().flatten() {
                let inverse = mass[part.body].map(|x| 1.0 / x);
                for &(other, j) in &self.on_block[part.body] {
                    let rows = contacts[other].parts[j]
                        .as_ref()
                        .expect("a part listed on its block")
                        .rows;
                    let at = start + 2 * list.binary_search(&other).expect("a neighbour");
                    for col in 0..2 {
                        let scaled = part.rows[col].component_mul(&inverse);
                        for (row, r) in rows.iter().enumerate() {
                            self.matrix[at + col * stride + row] += r.dot(&scaled);
                        }
                    }
                }
            }
            let at = start + 2 * list.binary_search(&k).expect("itself");
            self.matrix[at] += c.compliance;
            self.matrix[at + stride + 1] += c.compliance;
            self.diagonal.extend([at, at + stride + 1]);
        }
        self.linear.clear();
        for c in contacts {
            let u = c.velocity(v_free);
            self.linear.extend([u.x - c.target_m_s, u.y]);
        }
        let pattern = SymbolicSparseColMat::new_checked(2 * m, 2 * m, col_ptr, None, row_idx);
        let cholesky = Cholesky::new(pattern.as_ref());
        self.reduced.resize(self.matrix.len(), 0.0);
        self.pattern = Some(pattern);
        cholesky
    }

    /// The box of the impulses, the tangential bounds mu p_n from the current impulses, and
    /// the impulses moved into it.
    fn bound(&mut self, contacts: &[Contact]) {
        for (k, c) in contacts.iter().enumerate() {
            let b = c.friction * self.p[2 * k];
            self.lower[2 * k] = 0.0;
            self.upper[2 * k] = f64::INFINITY;
            self.lower[2 * k + 1] = -b;
            self.upper[2 * k + 1] = b;
            self.p[2 * k + 1] = self.p[2 * k + 1].clamp(-b, b);
        }
    }

    /// H' x per block, into `self.r`.
    fn on_blocks(&mut self, contacts: &[Contact], x: &[f64], blocks: usize) {
        self.r.clear();
        self.r.resize(blocks, Vector3::zeros());
        for (k, c) in contacts.iter().enumerate() {
            for part in c.parts.iter().flatten() {
                self.r[part.body] += part.rows[0] * x[2 * k] + part.rows[1] * x[2 * k + 1];
            }
        }
    }

    /// 1/2 d' (W + E) d for the unknowns' change `d` (its H' d left in `self.r`).
    fn curvature(&mut self, mass: &[Vector3<f64>], contacts: &[Contact], d: &[f64]) -> f64 {
        self.on_blocks(contacts, d, mass.len());
        let blocks: f64 = self
            .r
            .iter()
            .zip(mass)
            .map(|(r, m)| r.component_div(m).dot(r))
            .sum();
        let springs: f64 = contacts
            .iter()
            .enumerate()
            .map(|(k, c)| c.compliance * (d[2 * k] * d[2 * k] + d[2 * k + 1] * d[2 * k + 1]))
            .sum();
        0.5 * (blocks + springs)
    }

    /// One projected Newton step (Bertsekas 1982) from the current impulses under the current
    /// box: the unknowns at a bound whose gradient pushes them out of the box are held, Newton's
    /// step is taken in the others and a scaled gradient step in those, and the step is
    /// projected on the box and shortened until Armijo's condition holds along the projection.
    /// Returns the largest change of a block's velocity (through `reach`) the step made.
    fn projected_newton_step(
        &mut self,
        mass: &[Vector3<f64>],
        reach: &[Vector3<f64>],
        contacts: &[Contact],
        cholesky: &mut Cholesky,
    ) -> Result<f64, Stall> {
        let unknowns = self.p.len();
        // The gradient (W + E) p + H v_free - target: each contact's velocity at v_free + M^-1
        // H' p, less its target, plus its compliance times its impulse.
        let p = std::mem::take(&mut self.p);
        self.on_blocks(contacts, &p, mass.len());
        for (r, m) in self.r.iter_mut().zip(mass) {
            *r = r.component_div(m);
        }
        self.gradient.clear();
        for (k, c) in contacts.iter().enumerate() {
            let u = c.velocity(&self.r);
            for j in 0..2 {
                let i = 2 * k + j;
                self.gradient
                    .push(u[j] + c.compliance * p[i] + self.linear[i]);
            }
        }
        self.p = p;
        // Held: within the distance of a scaled projected gradient step of a bound, and pushed
        // out of the box there.
        let diagonal = |i: usize| self.matrix[self.diagonal[i]];
        let width = (0..unknowns)
            .map(|i| {
                let moved = (self.p[i] - self.gradient[i] / diagonal(i))
                    .clamp(self.lower[i], self.upper[i]);
                (self.p[i] - moved).abs()
            })
            .fold(0.0, f64::max);
        self.held.clear();
        for i in 0..unknowns {
            let g = self.gradient[i];
            self.held.push(
                (self.p[i] - self.lower[i] <= width && g > 0.0)
                    || (self.upper[i] - self.p[i] <= width && g < 0.0),
            );
        }
        let pattern = self.pattern.as_ref().expect("assembled");
        let (col_ptr, row_idx) = (pattern.col_ptr(), pattern.row_idx());
        for col in 0..unknowns {
            let (from, to) = (col_ptr[col], col_ptr[col + 1]);
            for ((reduced, &full), &row) in self.reduced[from..to]
                .iter_mut()
                .zip(&self.matrix[from..to])
                .zip(&row_idx[from..to])
            {
                let kept = row == col || !(self.held[row] || self.held[col]);
                *reduced = if kept { full } else { 0.0 };
            }
        }
        if !cholesky.factorise(SparseColMatRef::new(pattern.as_ref(), &self.reduced)) {
            return Err(Stall::Singular);
        }
        self.step.clear();
        self.step
            .extend((0..unknowns).map(|i| if self.held[i] { 0.0 } else { -self.gradient[i] }));
        cholesky.solve(&mut self.step);
        for i in 0..unknowns {
            if self.held[i] {
                self.step[i] = -self.gradient[i] / diagonal(i);
            }
        }
        if self.step.iter().any(|x| !x.is_finite()) {
            return Err(Stall::Singular);
        }
        let mut alpha = 1.0;
        loop {
            self.trial.clear();
            self.trial.extend((0..unknowns).map(|i| {
                (self.p[i] + alpha * self.step[i]).clamp(self.lower[i], self.upper[i]) - self.p[i]
            }));
            // The change of the potential, g' d + 1/2 d' (W + E) d, without forming it at
            // either end (which would lose the change to the round-off of its size).
            let trial = std::mem::take(&mut self.trial);
            let change_of_potential = trial
                .iter()
                .zip(&self.gradient)
                .map(|(d, g)| d * g)
                .sum::<f64>()
                + self.curvature(mass, contacts, &trial);
            let velocity_change = self
                .r
                .iter()
                .zip(mass)
                .zip(reach)
                .map(|((r, m), reach)| r.component_div(m).component_mul(reach).abs().max())
                .fold(0.0, f64::max);
            let predicted: f64 = (0..unknowns)
                .map(|i| {
                    if self.held[i] {
                        -self.gradient[i] * trial[i]
                    } else {
                        -alpha * self.gradient[i] * self.step[i]
                    }
                })
                .sum();
            let accepted = change_of_potential <= -SUFFICIENT_DECREASE * predicted;
            self.trial = trial;
            if accepted || alpha == 1.0 && velocity_change == 0.0 {
                for (p, d) in self.p.iter_mut().zip(&self.trial) {
                    *p += d;
                }
                return Ok(velocity_change);
            }
            alpha *= 0.5;
            if alpha < SHORTEST {
                return Err(Stall::Iterations);
            }
        }
    }

    /// The velocities v_free + M^-1 H' p and the impulses of the answer.
    fn finish(
        &mut self,
        mass: &[Vector3<f64>],
        v_free: &[Vector3<f64>],
        contacts: &[Contact],
        v: &mut [Vector3<f64>],
        impulses: &mut [Vector2<f64>],
    ) {
        let p = std::mem::take(&mut self.p);
        self.on_blocks(contacts, &p, mass.len());
        for (i, vi) in v.iter_mut().enumerate() {
            *vi = v_free[i] + self.r[i].component_div(&mass[i]);
        }
        for (k, impulse) in impulses.iter_mut().enumerate() {
            *impulse = Vector2::new(p[2 * k], p[2 * k + 1]);
        }
        self.p = p;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::baselines::wall_newton::test_blocks::{seated, step, G_DT, MASS};
    use crate::integrate::baselines::wall_newton::{Part, WallNewton};

    /// Two test blocks, block 1 on block 0 and block 0 on the ground, each joint's two corners
    /// a contact (compliance 1e-11 m/s per N s), friction `mu_ground` and `mu_joint`.
    fn stack(mu_ground: f64, mu_joint: f64) -> (Vec<Contact>, [Vector3<f64>; 2]) {
        let mut contacts = Vec::new();
        for x in [-0.5, 0.5] {
            contacts.push(seated(0, x, mu_ground, 1e-11));
            // Block 1's corner (x, -h from its centroid) on block 0's top face (x, +h from
            // block 0's): the relative velocity of the two points.
            let mut on_block = seated(1, x, mu_joint, 1e-11);
            on_block.parts[1] = Some(Part {
                body: 0,
                rows: [Vector3::new(0.0, -1.0, -x), Vector3::new(-1.0, 0.0, 0.25)],
            });
            contacts.push(on_block);
        }
        (contacts, [MASS, MASS])
    }

    /// The dual's answer from the given first impulses, and the steps it used.
    fn dual(
        contacts: &[Contact],
        mass: &[Vector3<f64>; 2],
        v_free: &[Vector3<f64>; 2],
        first: Vector2<f64>,
    ) -> ([Vector3<f64>; 2], Vec<Vector2<f64>>, usize) {
        let mut v = [Vector3::zeros(); 2];
        let mut p = vec![first; contacts.len()];
        let used = WallDual::default()
            .solve(&step(mass, v_free, contacts), &mut v, &mut p)
            .expect("solved");
        (v, p, used)
    }

    /// The upper block thrown at 2 m/s on the lower, which the ground's greater friction holds
    /// back (and, second, the two at rest): the impulses solve the problem the velocity-space
    /// solver solves, to its tolerance, from rest and from far off alike; they balance the
    /// step exactly (v = v_free + M^-1 H' p by construction) and meet Signorini's and
    /// Coulomb's laws at every contact to round-off.
    #[test]
    fn the_impulses_answer_the_velocity_space_solvers_problem() {
        let (contacts, mass) = stack(0.8, 0.3);
        for v_free in [
            [Vector3::new(0.0, -G_DT, 0.0), Vector3::new(2.0, -G_DT, 0.0)],
            [Vector3::new(0.0, -G_DT, 0.0), Vector3::new(0.0, -G_DT, 0.0)],
        ] {
            let mut expected = [Vector3::zeros(); 2];
            let mut unused = vec![Vector2::zeros(); contacts.len()];
            WallNewton::new(2, [(0, 1)])
                .solve(&step(&mass, &v_free, &contacts), &mut expected, &mut unused)
                .expect("the velocity-space solver converges here");
            for first in [Vector2::zeros(), Vector2::new(1e3, -1e3)] {
                let (v, p, used) = dual(&contacts, &mass, &v_free, first);
                assert!(used <= 40, "{used}");
                for i in 0..2 {
                    assert!(
                        (v[i] - expected[i]).abs().max() < 1e-10 * G_DT,
                        "{v:?} {expected:?}"
                    );
                }
                for (c, p) in contacts.iter().zip(&p) {
                    let u = c.velocity(&v);
                    // Signorini with the compliance: p_n >= 0 and u_n + eps p_n >= 0, one of
                    // them zero.
                    let gap = u.x - c.target_m_s + c.compliance * p.x;
                    assert!(p.x >= 0.0 && gap > -1e-12 * G_DT, "{p:?} {u:?}");
                    assert!(
                        p.x * gap.abs() < 1e-9 * mass[0].x * G_DT * G_DT,
                        "{p:?} {gap}"
                    );
                    // Coulomb: within mu p_n where it sticks (u_t + eps p_t = 0), on the bound
                    // opposite the slip where it slides.
                    let bound = c.friction * p.x;
                    assert!(p.y.abs() <= bound * (1.0 + 1e-12), "{p:?}");
                    let slip = u.y + c.compliance * p.y;
                    if slip.abs() > 1e-9 * G_DT {
                        assert!((p.y + slip.signum() * bound).abs() <= 1e-9 * bound, "{p:?}");
                    }
                }
                let sliding = v_free[1].x > 1.0;
                let relative = contacts[1].velocity(&v).y;
                assert_eq!(relative > 1e-6, sliding, "{relative}");
                assert!(v[0].x.abs() < 1e-8 * G_DT, "{v:?}");
            }
        }
    }
}
