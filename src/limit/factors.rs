//! Sparse LU factors of a square basis over a field: exact rationals for the check of a
//! basis, residues modulo a prime for its p-adic solves (`padic`). One elimination serves the
//! systems in B and in B^T (the vertex and the multipliers of a basis).

use crate::exact::Q;
use std::collections::{BTreeMap, BTreeSet};

/// The arithmetic the elimination needs, exact in both of its fields.
pub(super) trait Field: Clone {
    fn zero() -> Self;
    fn is_zero(&self) -> bool;
    fn sub(&self, other: &Self) -> Self;
    fn mul(&self, other: &Self) -> Self;
    /// `1 / self`, `self` nonzero.
    fn recip(&self) -> Self;
}

impl Field for Q {
    fn zero() -> Q {
        Q::zero()
    }
    fn is_zero(&self) -> bool {
        Q::is_zero(self)
    }
    fn sub(&self, other: &Q) -> Q {
        self - other
    }
    fn mul(&self, other: &Q) -> Q {
        self * other
    }
    fn recip(&self) -> Q {
        Q::recip(self)
    }
}

/// B = E^-1 U, B square and given by its sparse rows: Gaussian elimination that takes at each
/// step the column held by the fewest rows and, in it, the shortest row (a Markowitz-like order
/// that keeps a wall's block-by-joint structure from filling in). In rationals, on sampled
/// friction, the solves cost more than the elimination: their values reach thousands of bits,
/// and each step through the factors reduces them by a gcd (docs/rocking-walls.md); modulo a
/// prime every value is one word.
pub(super) struct Factors<F> {
    /// The elimination in order: row `i` less `f` times pivot row `p`.
    steps: Vec<(usize, usize, F)>,
    /// The pivots in order: row `p` pivots on column `c`, with its value's reciprocal (a solve
    /// multiplies by it: modulo a prime an inverse costs about 120 products, by Fermat, and a
    /// p-adic solve takes each pivot's at every digit).
    order: Vec<(usize, usize, F)>,
    /// U: each pivot row as elimination left it, but its pivot (columns of later pivots).
    rows: Vec<Vec<(usize, F)>>,
}

impl<F: Field> Factors<F> {
    /// The factors of B, or `None` where B is singular (in the field: modulo a prime, a matrix
    /// singular there may not be singular in rationals).
    pub(super) fn of(mut rows: Vec<BTreeMap<usize, F>>) -> Option<Factors<F>> {
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
        let mut steps = Vec::new();
        for _ in 0..size {
            let c = (0..size)
                .filter(|&c| open[c])
                .min_by_key(|&c| holders[c].len())?;
            let p = *holders[c].iter().min_by_key(|&&i| rows[i].len())?;
            open[c] = false;
            for k in rows[p].keys() {
                holders[*k].remove(&p);
            }
            let pivot_row = rows[p].clone();
            let reciprocal = pivot_row[&c].recip();
            for i in std::mem::take(&mut holders[c]) {
                let f = rows[i][&c].mul(&reciprocal);
                for (k, v) in &pivot_row {
                    let e = rows[i].entry(*k).or_insert_with(F::zero);
                    *e = e.sub(&f.mul(v));
                    if e.is_zero() {
                        rows[i].remove(k);
                        holders[*k].remove(&i);
                    } else {
                        holders[*k].insert(i);
                    }
                }
                steps.push((i, p, f));
            }
            order.push((p, c, reciprocal));
        }
        let mut pivot_of = vec![0; size];
        order.iter().for_each(|(p, c, _)| pivot_of[*p] = *c);
        let rows = rows
            .into_iter()
            .zip(pivot_of)
            .map(|(row, c)| row.into_iter().filter(|(k, _)| *k != c).collect())
            .collect();
        Some(Factors { steps, order, rows })
    }

    /// z with B z = r: E r, then U back to front.
    pub(super) fn solve(&self, mut r: Vec<F>) -> Vec<F> {
        for (i, p, f) in &self.steps {
            r[*i] = r[*i].sub(&f.mul(&r[*p]));
        }
        let mut z = vec![F::zero(); r.len()];
        for (p, c, reciprocal) in self.order.iter().rev() {
            let mut v = r[*p].clone();
            for (k, a) in &self.rows[*p] {
                v = v.sub(&a.mul(&z[*k]));
            }
            z[*c] = v.mul(reciprocal);
        }
        z
    }

    /// y with B^T y = d: w with U^T w = d front to back (pivot row p's entries lie in its own
    /// pivot's column and later ones), then y = E^T w, the elimination's steps transposed and
    /// taken back to front.
    pub(super) fn solve_transposed(&self, mut d: Vec<F>) -> Vec<F> {
        let mut w = vec![F::zero(); d.len()];
        for (p, c, reciprocal) in &self.order {
            let wp = d[*c].mul(reciprocal);
            for (k, a) in &self.rows[*p] {
                d[*k] = d[*k].sub(&a.mul(&wp));
            }
            w[*p] = wp;
        }
        for (i, p, f) in self.steps.iter().rev() {
            w[*p] = w[*p].sub(&f.mul(&w[*i]));
        }
        w
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One factorisation solves B z = r and B^T y = d exactly, on sparse random matrices whose
    /// elimination fills in and whose entries are fractions; a singular B has none.
    #[test]
    fn one_factorisation_solves_a_basis_and_its_transpose() {
        let mut rng = crate::rng::Rng::new(7);
        let mut small = |span: u64| (rng.next_u64() % (2 * span + 1)) as i128 - span as i128;
        let mut solved = 0;
        for _ in 0..200 {
            let m = 2 + small(3).unsigned_abs() as usize;
            let b: Vec<Vec<Q>> = (0..m)
                .map(|_| {
                    (0..m)
                        .map(|_| match small(2) {
                            0 | 1 => Q::zero(),
                            _ => Q::frac(small(9), 1 + small(4).abs()),
                        })
                        .collect()
                })
                .collect();
            let rows = b
                .iter()
                .map(|row| {
                    let entries = row.iter().enumerate().filter(|(_, a)| !a.is_zero());
                    entries.map(|(k, a)| (k, a.clone())).collect()
                })
                .collect();
            let r: Vec<Q> = (0..m)
                .map(|_| Q::frac(small(7), 1 + small(3).abs()))
                .collect();
            let Some(factors) = Factors::of(rows) else {
                // Refused only where dense elimination finds it singular too.
                assert!(
                    rank(&mut b.clone()) < m,
                    "a nonsingular matrix refused: {b:?}"
                );
                continue;
            };
            let z = factors.solve(r.clone());
            let y = factors.solve_transposed(r.clone());
            for i in 0..m {
                let bz: Q = (0..m).map(|k| &b[i][k] * &z[k]).sum();
                let bty: Q = (0..m).map(|k| &b[k][i] * &y[k]).sum();
                assert_eq!((bz, bty), (r[i].clone(), r[i].clone()), "{b:?}");
            }
            solved += 1;
        }
        assert!(solved > 100, "{solved} of 200 nonsingular");
    }

    /// The rank of a dense rational matrix (its rows reduced in place).
    fn rank(rows: &mut [Vec<Q>]) -> usize {
        let mut rank = 0;
        for c in 0..rows.first().map_or(0, Vec::len) {
            let Some(p) = (rank..rows.len()).find(|&i| !rows[i][c].is_zero()) else {
                continue;
            };
            rows.swap(rank, p);
            for i in rank + 1..rows.len() {
                let f = &rows[i][c] / &rows[rank][c];
                for k in c..rows[i].len() {
                    rows[i][k] = &rows[i][k] - &(&f * &rows[rank][k]);
                }
            }
            rank += 1;
        }
        rank
    }
}
