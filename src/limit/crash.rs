//! The starting basis of a feasibility run (`revised::feasible`), built the way a wall carries
//! its loads: blocks top down, each block's balances, with what the blocks above pass down,
//! carried by a few of the forces on its base. The groups of rows are listed so that the
//! entries of a group's columns outside its rows lie in the rows of later groups (a block's
//! base forces also load the blocks under it), so the basis is block-triangular and each
//! group's part of it is solved alone. It only chooses where phase 1 starts: what the run ends
//! on is proved exactly, and a start that is singular or below zero is not used.

use super::revised::PIVOT;
use nalgebra::{DMatrix, DVector};

/// Candidate columns (its base's corner forces and its rows' artificial variables) above which
/// a group keeps its artificial variables: a block's three balances take every
/// choice of three, 455 of 15.
const MOST: usize = 15;

/// Rows whose balance a few columns may carry: a block's balances and the corner forces of its
/// base.
pub(crate) struct Group {
    /// The rows.
    pub(crate) rows: std::ops::Range<usize>,
    /// The columns that may carry them.
    pub(crate) columns: Vec<usize>,
}

/// The crash basis of `groups` over the rows' `columns` and right-hand side `b` (columns `n..n +
/// m` the rows' artificial variables), and what is left of each row once the columns chosen
/// carry their values: an artificial variable's value, where it is basic.
pub(super) fn basis(
    columns: &[Vec<(usize, f64)>],
    b: &[f64],
    groups: &[Group],
) -> (Vec<usize>, Vec<f64>) {
    let (m, n) = (b.len(), columns.len());
    let mut left = b.to_vec();
    let mut basis: Vec<usize> = (n..n + m).collect();
    for group in groups {
        for ((j, x), row) in carry(columns, group, &left).zip(group.rows.clone()) {
            basis[row] = j;
            if j < n {
                for &(i, a) in &columns[j] {
                    left[i] -= a * x;
                }
            }
        }
    }
    (basis, left)
}

/// The columns (artificial ones `n + row`) of `group`'s crash basis and their values: one
/// column per row of the group, those of A at values of at least zero, carrying what is `left`
/// of its rows, with the fewest artificial variables and, among those, the smallest largest
/// value (a choice near singular carries its rows with huge opposing forces, which the blocks
/// below must then take). A group of more candidates than [`MOST`] keeps its artificial
/// variables.
fn carry(
    columns: &[Vec<(usize, f64)>],
    group: &Group,
    left: &[f64],
) -> impl Iterator<Item = (usize, f64)> {
    let n = columns.len();
    let k = group.rows.len();
    let artificial: Vec<(usize, f64)> = group.rows.clone().map(|r| (n + r, left[r])).collect();
    let candidates: Vec<usize> = (group.columns.iter().copied())
        .chain(group.rows.clone().map(|r| n + r))
        .collect();
    if candidates.len() > MOST {
        return artificial.into_iter();
    }
    // Each candidate restricted to the group's rows.
    let local = |j: usize| -> Vec<f64> {
        let mut v = vec![0.0; k];
        if j < n {
            for &(i, a) in &columns[j] {
                if group.rows.contains(&i) {
                    v[i - group.rows.start] = a;
                }
            }
        } else {
            v[j - n - group.rows.start] = 1.0;
        }
        v
    };
    let local: Vec<Vec<f64>> = candidates.iter().map(|&j| local(j)).collect();
    let rhs: Vec<f64> = left[group.rows.clone()].to_vec();
    // The best choice's artificial variables and largest value, and its columns with values.
    let mut best_by: Option<(usize, f64)> = None;
    let mut best = Vec::new();
    let mut pick = Vec::with_capacity(k);
    subsets(candidates.len(), k, &mut pick, &mut |pick: &[usize]| {
        let artificial = pick.iter().filter(|&&p| candidates[p] >= n).count();
        let Some(x) = solve_small(pick.iter().map(|&p| &local[p][..]), &rhs) else {
            return;
        };
        let structural = pick.iter().zip(&x).filter(|(&p, _)| candidates[p] < n);
        if structural.clone().any(|(_, &v)| v < 0.0) {
            return;
        }
        let largest = x.iter().map(|v| v.abs()).fold(0.0, f64::max);
        let better =
            best_by.is_none_or(|(a, l)| artificial < a || (artificial == a && largest < l));
        if better {
            best_by = Some((artificial, largest));
            best = pick.iter().map(|&p| candidates[p]).zip(x).collect();
        }
    });
    // The artificial variables alone always carry the rows.
    match best_by {
        Some(_) => best.into_iter(),
        None => artificial.into_iter(),
    }
}

/// Calls `each` with every increasing choice of `k` of `0..len`.
fn subsets(len: usize, k: usize, pick: &mut Vec<usize>, each: &mut dyn FnMut(&[usize])) {
    if pick.len() == k {
        each(pick);
        return;
    }
    let from = pick.last().map_or(0, |&p| p + 1);
    for p in from..len {
        if len - p < k - pick.len() {
            break;
        }
        pick.push(p);
        subsets(len, k, pick, each);
        pick.pop();
    }
}

/// x with sum_c x_c col_c = rhs for a few columns as many as the rows (nalgebra's LU, partial
/// pivoting); `None` where a pivot is below [`PIVOT`] times its column's size (the choice is
/// singular, or too close to it to start a basis from).
fn solve_small<'a>(cols: impl Iterator<Item = &'a [f64]>, rhs: &[f64]) -> Option<Vec<f64>> {
    let k = rhs.len();
    let cols: Vec<&[f64]> = cols.collect();
    let matrix = DMatrix::from_fn(k, k, |i, c| cols[c][i]);
    let sizes: Vec<f64> = matrix.column_iter().map(|c| c.amax()).collect();
    let lu = matrix.lu();
    let u = lu.u();
    if (0..k).any(|c| u[(c, c)].abs() <= PIVOT * sizes[c]) {
        return None;
    }
    let x = lu.solve(&DVector::from_column_slice(rhs))?;
    x.iter()
        .all(|v| v.is_finite())
        .then(|| x.as_slice().to_vec())
}
