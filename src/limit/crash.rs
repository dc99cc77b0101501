//! The starting basis of a feasibility run (`revised::feasible`), built the way a wall carries
//! its loads: blocks top down, each block's balances, with what the blocks above pass down,
//! carried by a few of the forces on its base. The groups of rows are listed so that the
//! entries of a group's columns outside its rows lie in the rows of later groups (a block's
//! base forces also load the blocks under it), so the basis is block-triangular and each
//! group's part of it is solved alone. It only chooses where phase 1 starts: what the run ends
//! on is proved exactly, and a start that is singular or below zero is not used.
//!
//! A block's balances fix the resultant of its base forces, so a block on one support passes
//! the same loads down whichever of them carry it; a block on two chooses how to split them,
//! and a split that loads a support beyond what that support's own base can carry (the cone
//! its base forces span) leaves the support to artificial variables. So each choice is also
//! judged by the supports it leaves outside their cones, with what has reached them so far.

use super::{PIVOT, ROWS};
use nalgebra::{Matrix3, Vector3};

/// Candidate columns (its base's corner forces and its rows' artificial variables) above which
/// a group keeps its artificial variables: a block's three balances take every choice of
/// three, 455 of 15.
const MOST: usize = 15;

/// Rows whose balance a few columns may carry: a block's balances and the corner forces of its
/// base.
pub(crate) struct Group {
    /// The rows.
    pub(crate) rows: std::ops::Range<usize>,
    /// The columns that may carry them.
    pub(crate) columns: Vec<usize>,
}

impl Group {
    /// Whether the crash chooses this group's columns: a block's balances, and candidates
    /// few enough to try every choice of.
    fn chosen(&self) -> bool {
        self.rows.len() == ROWS && self.columns.len() + ROWS <= MOST
    }

    /// Column j's entries in the group's rows.
    fn local(&self, column: &[(usize, f64)]) -> Vector3<f64> {
        let mut v = Vector3::zeros();
        for &(i, a) in column.iter().filter(|(i, _)| self.rows.contains(i)) {
            v[i - self.rows.start] = a;
        }
        v
    }
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
    let mut group_of = vec![None; m];
    for (g, group) in groups.iter().enumerate() {
        group.rows.clone().for_each(|r| group_of[r] = Some(g));
    }
    let cones = groups.iter().map(|g| Cone::of_base(columns, g)).collect();
    let supports = Supports {
        groups,
        group_of,
        cones,
    };
    for group in groups {
        for ((j, x), row) in carry(columns, group, &left, &supports).zip(group.rows.clone()) {
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

/// What a choice is judged by below it: each row's group and each group's cone.
struct Supports<'a> {
    groups: &'a [Group],
    group_of: Vec<Option<usize>>,
    cones: Vec<Option<Cone>>,
}

impl Supports<'_> {
    /// How many groups other than `group` the `chosen` columns, at their values, leave with
    /// what is `left` of their rows outside their cones.
    fn strained(
        &self,
        columns: &[Vec<(usize, f64)>],
        group: &Group,
        left: &[f64],
        chosen: impl Iterator<Item = (usize, f64)>,
    ) -> usize {
        // A base force loads at most one block besides its own.
        let mut loaded: Vec<(usize, Vector3<f64>)> = Vec::with_capacity(ROWS);
        for (j, x) in chosen.filter(|&(j, _)| j < columns.len()) {
            for &(i, a) in &columns[j] {
                let Some(g) = self.group_of[i].filter(|_| !group.rows.contains(&i)) else {
                    continue;
                };
                let rows = self.groups[g].rows.clone();
                let at = match loaded.iter().position(|&(h, _)| h == g) {
                    Some(at) => at,
                    None if rows.len() == ROWS => {
                        loaded.push((g, Vector3::from_column_slice(&left[rows.clone()])));
                        loaded.len() - 1
                    }
                    None => continue,
                };
                loaded[at].1[i - rows.start] -= a * x;
            }
        }
        (loaded.iter())
            .filter(|(g, rest)| self.cones[*g].as_ref().is_some_and(|c| !c.holds(rest)))
            .count()
    }
}

/// The cone the local columns of a group span, as the inward normals of its faces (none where
/// the columns span every direction); a flat cone as its plane, both ways, and in it the
/// normals of its two edges.
struct Cone {
    faces: Vec<Vector3<f64>>,
}

impl Cone {
    /// The rows are scaled to entries of at most 1: a normal shorter than this, or a column
    /// this far on a face's wrong side, is round-off.
    const ROUND_OFF: f64 = 1e-12;

    /// The cone of `group`'s base forces; `None` for a group whose columns the crash does not
    /// choose (it keeps its artificial variables whatever reaches it).
    fn of_base(columns: &[Vec<(usize, f64)>], group: &Group) -> Option<Cone> {
        let generators: Vec<Vector3<f64>> = (group.columns.iter())
            .map(|&j| group.local(&columns[j]))
            .collect();
        group.chosen().then(|| Cone::of(&generators))
    }

    fn of(generators: &[Vector3<f64>]) -> Cone {
        let mut faces = Vec::new();
        for (a, u) in generators.iter().enumerate() {
            for v in &generators[a + 1..] {
                let Some(normal) = unit(u.cross(v)) else {
                    continue;
                };
                match sides(generators, &normal) {
                    (true, true) => {
                        // Flat: every pair gives this plane.
                        let mut faces = vec![normal, -normal];
                        for w in generators {
                            let Some(inward) = unit(normal.cross(w)) else {
                                continue;
                            };
                            match sides(generators, &inward) {
                                (true, _) => faces.push(inward),
                                (_, true) => faces.push(-inward),
                                _ => {}
                            }
                        }
                        return Cone { faces };
                    }
                    (true, false) => faces.push(normal),
                    (false, true) => faces.push(-normal),
                    (false, false) => {}
                }
            }
        }
        Cone { faces }
    }

    /// Whether `r` lies in the cone, to round-off relative to its size.
    fn holds(&self, r: &Vector3<f64>) -> bool {
        let size = r.amax();
        (self.faces.iter()).all(|f| f.dot(r) >= -Self::ROUND_OFF * size)
    }
}

/// Whether every generator lies on the side of `normal` (first) or against it (second), to
/// round-off.
fn sides(generators: &[Vector3<f64>], normal: &Vector3<f64>) -> (bool, bool) {
    let dots = generators.iter().map(|g| normal.dot(g));
    let above = dots.clone().all(|d| d >= -Cone::ROUND_OFF);
    let below = dots.into_iter().all(|d| d <= Cone::ROUND_OFF);
    (above, below)
}

/// `v` over its length, or `None` where that is round-off.
fn unit(v: Vector3<f64>) -> Option<Vector3<f64>> {
    let length = v.norm();
    (length > Cone::ROUND_OFF).then(|| v / length)
}

/// The columns (artificial ones `n + row`) of `group`'s crash basis and their values: one
/// column per row of the group, those of A at values of at least zero, carrying what is `left`
/// of its rows, with the fewest artificial variables; among those, the fewest supports
/// strained ([`Supports::strained`]); then the smallest largest value (a choice near singular
/// carries its rows with huge opposing forces, which the blocks below must then take). A group
/// whose columns the crash does not choose ([`Group::chosen`]) keeps its artificial variables.
fn carry(
    columns: &[Vec<(usize, f64)>],
    group: &Group,
    left: &[f64],
    supports: &Supports,
) -> impl Iterator<Item = (usize, f64)> {
    let n = columns.len();
    let artificial: Vec<(usize, f64)> = group.rows.clone().map(|r| (n + r, left[r])).collect();
    if !group.chosen() {
        return artificial.into_iter();
    }
    let candidates: Vec<usize> = (group.columns.iter().copied())
        .chain(group.rows.clone().map(|r| n + r))
        .collect();
    let local: Vec<Vector3<f64>> = (candidates.iter())
        .map(|&j| match columns.get(j) {
            Some(column) => group.local(column),
            None => Vector3::ith(j - n - group.rows.start, 1.0),
        })
        .collect();
    let rhs = Vector3::from_column_slice(&left[group.rows.clone()]);
    // The best choice's artificial variables, supports strained and largest value, and its
    // columns with values.
    let mut best_by: Option<(usize, usize, f64)> = None;
    let mut best = Vec::new();
    let count = candidates.len();
    for a in 0..count {
        for b in a + 1..count {
            for c in b + 1..count {
                let pick = [a, b, c];
                let artificial = pick.iter().filter(|&&p| candidates[p] >= n).count();
                if best_by.is_some_and(|(fewest, ..)| fewest < artificial) {
                    continue;
                }
                let Some(x) = solve_small(&pick.map(|p| local[p]), &rhs) else {
                    continue;
                };
                let chosen = pick.iter().map(|&p| candidates[p]).zip(x.iter().copied());
                if chosen.clone().any(|(j, v)| j < n && v < 0.0) {
                    continue;
                }
                let largest = x.amax();
                let strained = supports.strained(columns, group, left, chosen.clone());
                let better = best_by.is_none_or(|(fewest, least, smallest)| {
                    (artificial, strained) < (fewest, least)
                        || ((artificial, strained) == (fewest, least) && largest < smallest)
                });
                if better {
                    best_by = Some((artificial, strained, largest));
                    best = chosen.collect();
                }
            }
        }
    }
    // The artificial variables alone always carry the rows.
    match best_by {
        Some(_) => best.into_iter(),
        None => artificial.into_iter(),
    }
}

/// x with sum_c x_c col_c = rhs for three columns (nalgebra's LU, partial pivoting); `None`
/// where a pivot is below [`PIVOT`] times its column's size (the choice is singular, or too
/// close to it to start a basis from).
fn solve_small(cols: &[Vector3<f64>; 3], rhs: &Vector3<f64>) -> Option<Vector3<f64>> {
    let matrix = Matrix3::from_columns(cols);
    let lu = matrix.lu();
    let u = lu.u();
    if (0..ROWS).any(|c| u[(c, c)].abs() <= PIVOT * matrix.column(c).amax()) {
        return None;
    }
    let x = lu.solve(rhs)?;
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_split_that_leaves_a_support_unable_to_carry_its_load_is_not_chosen() {
        // A block (rows 0-2) on a support (rows 3-5) carried by three forces of its own (the
        // orthant). Two of the block's candidates carry its third balance alike; the first
        // loads the support beyond its orthant, the second not. The largest values tie, so
        // only the support's cone tells them apart: the crash then needs no artificial variable.
        let columns: Vec<Vec<(usize, f64)>> = vec![
            vec![(0, 1.0)],
            vec![(1, 1.0)],
            vec![(2, 1.0), (3, 2.0)],
            vec![(2, 1.0), (3, 0.5)],
            vec![(3, 1.0)],
            vec![(4, 1.0)],
            vec![(5, 1.0)],
        ];
        let groups = [
            Group {
                rows: 0..3,
                columns: vec![0, 1, 2, 3],
            },
            Group {
                rows: 3..6,
                columns: vec![4, 5, 6],
            },
        ];
        let (basis, left) = super::basis(&columns, &[1.0; 6], &groups);
        assert_eq!(basis, [0, 1, 3, 4, 5, 6]);
        assert_eq!(left, [0.0; 6]);
        // The first candidate alone: the support keeps an artificial variable for its first row.
        let groups = [
            Group {
                rows: 0..3,
                columns: vec![0, 1, 2],
            },
            Group {
                rows: 3..6,
                columns: vec![4, 5, 6],
            },
        ];
        let (basis, left) = super::basis(&columns, &[1.0; 6], &groups);
        // (A group's columns take its rows in the order chosen: a basis is a set.)
        assert_eq!(basis, [0, 1, 2, 5, 6, 7 + 3]);
        assert_eq!(left[3], -1.0);
    }

    #[test]
    fn a_cone_holds_what_its_generators_carry_and_nothing_else() {
        let v = |x: f64, y: f64, z: f64| Vector3::new(x, y, z);
        // A stuck joint's two corners, each on the two edges of its friction cone (friction
        // 0.5; rows: horizontal, vertical, moment about the centroid, corners at -0.3 and 0.3).
        let stuck = Cone::of(&[
            v(0.5, 1.0, -0.3),
            v(-0.5, 1.0, -0.3),
            v(0.5, 1.0, 0.3),
            v(-0.5, 1.0, 0.3),
        ]);
        assert!(stuck.holds(&v(0.0, 1.0, 0.0)));
        assert!(stuck.holds(&v(0.5, 1.0, 0.3)));
        assert!(stuck.holds(&v(0.25, 1.0, -0.2)));
        assert!(!stuck.holds(&v(0.0, 1.0, 0.31)), "past a corner");
        assert!(!stuck.holds(&v(0.6, 1.0, 0.0)), "outside friction");
        assert!(!stuck.holds(&v(0.0, -1.0, 0.0)), "pulling");
        // A slipping joint: one edge at each corner, a flat cone.
        let slipping = Cone::of(&[v(-0.5, 1.0, -0.3), v(-0.5, 1.0, 0.3)]);
        assert!(slipping.holds(&v(-0.5, 1.0, 0.1)));
        assert!(!slipping.holds(&v(-0.4, 1.0, 0.1)), "off its plane");
        assert!(
            !slipping.holds(&v(-0.5, 1.0, 0.4)),
            "in its plane, past an edge"
        );
        // Columns that span every direction hold everything.
        let all = Cone::of(&[
            v(1.0, 0.0, 0.0),
            v(0.0, 1.0, 0.0),
            v(0.0, 0.0, 1.0),
            v(-1.0, -1.0, -1.0),
        ]);
        assert!(all.holds(&v(-3.0, 2.0, -7.0)));
    }
}
