//! The exact proof of a floating-point simplex run's answer. A basis (m columns of [A | I])
//! determines everything the simplex method would report from it: the vertex B^-1 b, the
//! multipliers B^-T c_B, and for an unbounded run the edge B^-1 A_j. Solving those few square
//! systems in rationals and checking every constraint on the results proves the answer as
//! firmly as an exact run, at the cost of one sparse elimination instead of every pivot of a
//! dense tableau.

use super::simplex::{Ending, Outcome, Program};
use crate::exact::Q;
use std::collections::{BTreeMap, BTreeSet};

/// The outcome `basis` proves for `program` when the run ended with `ending`; `None` where it
/// proves nothing (round-off chose it) and the exact run must answer.
///
/// As in the tableau, rows with b < 0 are negated (so every artificial variable starts at
/// b >= 0) and column `n + k` is row k's artificial variable. Phase 1 minimised the artificial
/// variables weighted by `weights` (positive; the run scaled its rows): any positive weights
/// give a Farkas vector from a phase-1 optimum, but only the run's own make its basis optimal.
pub(super) fn basis(
    program: &Program,
    basis: &[usize],
    ending: Ending,
    weights: &[Q],
) -> Option<Outcome> {
    let (m, n) = (program.b.len(), program.c.len());
    if basis.len() != m || weights.len() != m || basis.iter().any(|&j| j >= n + m) {
        return None;
    }
    let sign: Vec<Q> = program
        .b
        .iter()
        .map(|b| if b.is_negative() { -Q::one() } else { Q::one() })
        .collect();
    let b: Vec<Q> = program.b.iter().zip(&sign).map(|(b, s)| b * s).collect();
    // The columns of A with the rows negated, sparse.
    let mut columns: Vec<Vec<(usize, Q)>> = vec![Vec::new(); n];
    for (i, row) in program.a.iter().enumerate() {
        for (j, a) in row.iter().enumerate() {
            if !a.is_zero() {
                columns[j].push((i, a * &sign[i]));
            }
        }
    }
    let column = |j: usize| -> Vec<(usize, Q)> {
        if j < n {
            columns[j].clone()
        } else {
            vec![(j - n, Q::one())]
        }
    };
    let dot = |col: &[(usize, Q)], y: &[Q]| col.iter().map(|(i, a)| a * &y[*i]).sum::<Q>();
    let artificial = |k: usize| basis[k] >= n;
    // B's rows and B^T's rows (B's columns).
    let mut rows = vec![BTreeMap::new(); m];
    let mut transposed = vec![BTreeMap::new(); m];
    for (k, &j) in basis.iter().enumerate() {
        for (i, a) in column(j) {
            rows[i].insert(k, a.clone());
            transposed[k].insert(i, a);
        }
    }
    let unflipped = |y: Vec<Q>| -> Vec<Q> { y.iter().zip(&sign).map(|(y, s)| y * s).collect() };
    match ending {
        Ending::Optimal => {
            let x_b = solve(rows, b)?;
            let feasible =
                (0..m).all(|k| !x_b[k].is_negative() && (!artificial(k) || x_b[k].is_zero()));
            if !feasible {
                return None;
            }
            let c_b: Vec<Q> = basis
                .iter()
                .map(|&j| {
                    if j < n {
                        program.c[j].clone()
                    } else {
                        Q::zero()
                    }
                })
                .collect();
            let y = solve(transposed, c_b)?;
            let dual_feasible =
                (0..n).all(|j| !(&program.c[j] - &dot(&columns[j], &y)).is_negative());
            if !dual_feasible {
                return None;
            }
            let mut x = vec![Q::zero(); n];
            for (k, &j) in basis.iter().enumerate() {
                if j < n {
                    x[j] = x_b[k].clone();
                }
            }
            let value = (0..n).map(|j| &program.c[j] * &x[j]).sum::<Q>();
            Some(Outcome::Optimal {
                x,
                value,
                y: unflipped(y),
            })
        }
        Ending::Infeasible => {
            let c_b: Vec<Q> = basis
                .iter()
                .map(|&j| {
                    if j >= n {
                        weights[j - n].clone()
                    } else {
                        Q::zero()
                    }
                })
                .collect();
            let y = solve(transposed, c_b)?;
            let farkas = (0..n).all(|j| !dot(&columns[j], &y).is_positive())
                && b.iter()
                    .zip(&y)
                    .map(|(b, y)| b * y)
                    .sum::<Q>()
                    .is_positive();
            farkas.then(|| Outcome::Infeasible { y: unflipped(y) })
        }
        Ending::Unbounded { entering } => {
            if entering >= n || basis.contains(&entering) {
                return None;
            }
            // A feasible vertex, and the edge that leaves it along `entering`: x_B - t w.
            let mut a_j: Vec<Q> = vec![Q::zero(); m];
            for (i, a) in column(entering) {
                a_j[i] = a;
            }
            let x_b = solve(rows.clone(), b)?;
            let w = solve(rows, a_j)?;
            let ray = (0..m).all(|k| {
                !x_b[k].is_negative()
                    && if artificial(k) {
                        x_b[k].is_zero() && w[k].is_zero()
                    } else {
                        !w[k].is_positive()
                    }
            });
            let c_b_w: Q = basis
                .iter()
                .zip(&w)
                .filter(|(&j, _)| j < n)
                .map(|(&j, w)| &program.c[j] * w)
                .sum();
            let falls = (&program.c[entering] - &c_b_w).is_negative();
            (ray && falls).then_some(Outcome::Unbounded)
        }
    }
}

/// Solves B z = r exactly, B square and given by its sparse rows; `None` where B is singular.
/// Gaussian elimination that takes at each step the column held by the fewest rows and, in it,
/// the shortest row (a Markowitz-like order that keeps a wall's block-by-joint structure from
/// filling in).
fn solve(mut rows: Vec<BTreeMap<usize, Q>>, mut r: Vec<Q>) -> Option<Vec<Q>> {
    let size = rows.len();
    // For each column, the rows not yet eliminated that hold it.
    let mut holders: Vec<BTreeSet<usize>> = vec![BTreeSet::new(); size];
    for (i, row) in rows.iter().enumerate() {
        for &k in row.keys() {
            holders[k].insert(i);
        }
    }
    let mut open = vec![true; size];
    let mut order = Vec::with_capacity(size);
    for _ in 0..size {
        let c = (0..size)
            .filter(|&c| open[c])
            .min_by_key(|&c| holders[c].len())?;
        let p = *holders[c].iter().min_by_key(|&&i| rows[i].len())?;
        open[c] = false;
        for k in rows[p].keys() {
            holders[*k].remove(&p);
        }
        let (pivot_row, pivot_r) = (rows[p].clone(), r[p].clone());
        let pivot = pivot_row[&c].clone();
        for i in std::mem::take(&mut holders[c]) {
            let f = &rows[i][&c] / &pivot;
            for (k, v) in &pivot_row {
                let e = rows[i].entry(*k).or_insert_with(Q::zero);
                *e = &*e - &(&f * v);
                if e.is_zero() {
                    rows[i].remove(k);
                    holders[*k].remove(&i);
                } else {
                    holders[*k].insert(i);
                }
            }
            r[i] = &r[i] - &(&f * &pivot_r);
        }
        order.push((p, c));
    }
    let mut z = vec![Q::zero(); size];
    for &(p, c) in order.iter().rev() {
        let mut v = r[p].clone();
        for (k, a) in &rows[p] {
            if *k != c {
                v = &v - &(a * &z[*k]);
            }
        }
        z[c] = &v / &rows[p][&c];
    }
    Some(z)
}
