//! Linear programs in exact rationals: minimise c x subject to A x = b, x >= 0, by the dense
//! two-phase simplex method with Bland's rule. Exact arithmetic makes every answer a vertex
//! of the problem to the last digit (a limit load that is a tie stays one) and Bland's rule
//! ends every run, however degenerate (limit analysis of block walls is: most contact forces
//! of a mechanism are zero); the price is a dense tableau, so this serves small problems.

use crate::exact::Q;

/// A linear program in standard form: minimise `c x` subject to `a x = b`, `x >= 0`.
pub(crate) struct Program {
    /// The rows of A (each as long as `c`).
    pub(crate) a: Vec<Vec<Q>>,
    /// The right-hand side, one per row.
    pub(crate) b: Vec<Q>,
    /// The costs, one per column.
    pub(crate) c: Vec<Q>,
}

/// What a program has.
#[derive(Debug, PartialEq)]
pub(crate) enum Outcome {
    /// An optimal vertex `x`, its value, and the multipliers `y` of the rows (c - A^T y >= 0,
    /// zero where x > 0; b y is the value).
    Optimal { x: Vec<Q>, value: Q, y: Vec<Q> },
    /// No x satisfies the constraints: `y` with A^T y <= 0 and b y > 0 shows it (Farkas).
    Infeasible { y: Vec<Q> },
    /// The cost falls without bound.
    Unbounded,
}

/// The tableau: B^-1 [A | I] with B^-1 b after it, the basic column of each row, and the
/// reduced costs of every column.
struct Tableau {
    rows: Vec<Vec<Q>>,
    rhs: Vec<Q>,
    basis: Vec<usize>,
    reduced: Vec<Q>,
    /// Columns of A (the artificial ones follow).
    n: usize,
}

impl Tableau {
    /// Reduced costs for `cost` (one per column, artificial ones included).
    fn price(&mut self, cost: &[Q]) {
        self.reduced = cost.to_vec();
        for (i, row) in self.rows.iter().enumerate() {
            let cb = &cost[self.basis[i]];
            if cb.is_zero() {
                continue;
            }
            for (r, t) in self.reduced.iter_mut().zip(row) {
                if !t.is_zero() {
                    *r = &*r - cb * t;
                }
            }
        }
    }

    /// Makes column j basic in row p (Gauss-Jordan on the rows and the reduced costs).
    fn pivot(&mut self, p: usize, j: usize) {
        let inv = self.rows[p][j].recip();
        for t in self.rows[p].iter_mut() {
            if !t.is_zero() {
                *t = &*t * &inv;
            }
        }
        self.rhs[p] = &self.rhs[p] * &inv;
        let (row_p, rhs_p) = (self.rows[p].clone(), self.rhs[p].clone());
        let nonzero: Vec<usize> = (0..row_p.len()).filter(|&k| !row_p[k].is_zero()).collect();
        let eliminate = |row: &mut Vec<Q>, rhs: &mut Q, f: &Q| {
            for &k in &nonzero {
                row[k] = &row[k] - f * &row_p[k];
            }
            *rhs = &*rhs - f * &rhs_p;
        };
        for i in 0..self.rows.len() {
            if i == p || self.rows[i][j].is_zero() {
                continue;
            }
            let f = self.rows[i][j].clone();
            let (row, rhs) = (&mut self.rows[i], &mut self.rhs[i]);
            eliminate(row, rhs, &f);
        }
        if !self.reduced[j].is_zero() {
            let f = self.reduced[j].clone();
            let mut ignored = Q::zero();
            eliminate(&mut self.reduced, &mut ignored, &f);
        }
        self.basis[p] = j;
    }

    /// Runs Bland's rule over the columns `allowed` admits; false when the cost is unbounded.
    /// (Dantzig's rule of the most negative reduced cost, tried on the Inca walls, took longer
    /// by far: its pivots grew the fractions.)
    fn optimise(&mut self, allowed: impl Fn(usize) -> bool) -> bool {
        loop {
            let Some(j) =
                (0..self.reduced.len()).find(|&j| allowed(j) && self.reduced[j].is_negative())
            else {
                return true;
            };
            let mut leave: Option<(usize, Q)> = None;
            for i in 0..self.rows.len() {
                let t = &self.rows[i][j];
                if !t.is_positive() {
                    continue;
                }
                let ratio = &self.rhs[i] / t;
                let better = match &leave {
                    None => true,
                    Some((l, r)) => ratio < *r || (ratio == *r && self.basis[i] < self.basis[*l]),
                };
                if better {
                    leave = Some((i, ratio));
                }
            }
            let Some((p, _)) = leave else {
                return false;
            };
            self.pivot(p, j);
        }
    }

    /// The multipliers of the rows for the costs last priced: the artificial column of row k
    /// started as e_k, so its reduced cost is its cost less y_k.
    fn multipliers(&self, cost: &[Q], flipped: &[bool]) -> Vec<Q> {
        (0..self.rows.len())
            .map(|k| {
                let y = &cost[self.n + k] - &self.reduced[self.n + k];
                if flipped[k] {
                    -y
                } else {
                    y
                }
            })
            .collect()
    }
}

/// Solves the program.
pub(crate) fn solve(program: &Program) -> Outcome {
    let (m, n) = (program.b.len(), program.c.len());
    // Rows with b >= 0, so that the artificial basis starts feasible.
    let flipped: Vec<bool> = program.b.iter().map(Q::is_negative).collect();
    let mut rows = Vec::with_capacity(m);
    let mut rhs = Vec::with_capacity(m);
    for (k, (row, b)) in program.a.iter().zip(&program.b).enumerate() {
        let s = |x: &Q| if flipped[k] { -x } else { x.clone() };
        let mut r: Vec<Q> = row.iter().map(s).collect();
        r.extend((0..m).map(|i| if i == k { Q::one() } else { Q::zero() }));
        rows.push(r);
        rhs.push(s(b));
    }
    let mut t = Tableau {
        rows,
        rhs,
        basis: (n..n + m).collect(),
        reduced: Vec::new(),
        n,
    };
    // Phase 1: the sum of the artificial variables to zero.
    let phase1: Vec<Q> = (0..n + m)
        .map(|j| if j < n { Q::zero() } else { Q::one() })
        .collect();
    t.price(&phase1);
    t.optimise(|_| true);
    let infeasibility: Q = (0..m)
        .filter(|&i| t.basis[i] >= n)
        .map(|i| t.rhs[i].clone())
        .sum();
    if infeasibility.is_positive() {
        return Outcome::Infeasible {
            y: t.multipliers(&phase1, &flipped),
        };
    }
    // Artificial variables left in the basis at zero: swap each for a column of A where its
    // row has one; a row with none is a combination of the others and stays as it is.
    for i in 0..m {
        if t.basis[i] >= n {
            if let Some(j) = (0..n).find(|&j| !t.rows[i][j].is_zero()) {
                t.pivot(i, j);
            }
        }
    }
    // Phase 2: the program's costs, artificial columns barred.
    let cost: Vec<Q> = program
        .c
        .iter()
        .cloned()
        .chain((0..m).map(|_| Q::zero()))
        .collect();
    t.price(&cost);
    if !t.optimise(|j| j < n) {
        return Outcome::Unbounded;
    }
    let mut x = vec![Q::zero(); n];
    for (i, &j) in t.basis.iter().enumerate() {
        if j < n {
            x[j] = t.rhs[i].clone();
        }
    }
    let value = (0..n).map(|j| &program.c[j] * &x[j]).sum::<Q>();
    Outcome::Optimal {
        y: t.multipliers(&cost, &flipped),
        x,
        value,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn q(n: i128) -> Q {
        Q::frac(n, 1)
    }

    fn program(a: &[&[i128]], b: &[i128], c: &[i128]) -> Program {
        Program {
            a: a.iter()
                .map(|r| r.iter().map(|&v| q(v)).collect())
                .collect(),
            b: b.iter().map(|&v| q(v)).collect(),
            c: c.iter().map(|&v| q(v)).collect(),
        }
    }

    /// Checks an optimum's certificate: A x = b, x >= 0, c - A^T y >= 0 with complementary
    /// slackness, and b y equal to c x (strong duality).
    fn certified(p: &Program, out: &Outcome) {
        let Outcome::Optimal { x, value, y } = out else {
            panic!("not optimal: {out:?}");
        };
        for (row, b) in p.a.iter().zip(&p.b) {
            let ax: Q = row.iter().zip(x).map(|(a, x)| a * x).sum();
            assert_eq!(&ax, b);
        }
        for j in 0..p.c.len() {
            assert!(!x[j].is_negative());
            let slack = &p.c[j] - p.a.iter().zip(y).map(|(r, y)| &r[j] * y).sum::<Q>();
            assert!(!slack.is_negative(), "dual infeasible in column {j}");
            assert!(
                x[j].is_zero() || slack.is_zero(),
                "not complementary in {j}"
            );
        }
        let by: Q = p.b.iter().zip(y).map(|(b, y)| b * y).sum();
        assert_eq!(&by, value);
    }

    #[test]
    fn a_textbook_program_reaches_its_optimum_with_its_certificate() {
        // max 3 x1 + 5 x2 with x1 <= 4, 2 x2 <= 12, 3 x1 + 2 x2 <= 18 (slacks x3..x5): 36 at
        // (2, 6).
        let p = program(
            &[&[1, 0, 1, 0, 0], &[0, 2, 0, 1, 0], &[3, 2, 0, 0, 1]],
            &[4, 12, 18],
            &[-3, -5, 0, 0, 0],
        );
        let out = solve(&p);
        certified(&p, &out);
        let Outcome::Optimal { x, value, .. } = out else {
            unreachable!()
        };
        assert_eq!(value, q(-36));
        assert_eq!((x[0].clone(), x[1].clone()), (q(2), q(6)));
    }

    #[test]
    fn negative_right_hand_sides_and_redundant_rows_keep_the_multipliers_right() {
        // x1 + x2 = 2 written twice (once negated), x1 - x2 = 0: min x1 + 2 x2 = 3 at (1, 1).
        let p = program(&[&[1, 1], &[-1, -1], &[1, -1]], &[2, -2, 0], &[1, 2]);
        let out = solve(&p);
        certified(&p, &out);
        assert!(matches!(out, Outcome::Optimal { value, .. } if value == q(3)));
    }

    #[test]
    fn an_infeasible_program_comes_with_a_farkas_certificate() {
        // x1 + x2 = 1 and x1 + x2 = 2.
        let p = program(&[&[1, 1], &[1, 1]], &[1, 2], &[0, 0]);
        let Outcome::Infeasible { y } = solve(&p) else {
            panic!("feasible?")
        };
        for j in 0..2 {
            let aty: Q = p.a.iter().zip(&y).map(|(r, y)| &r[j] * y).sum();
            assert!(!aty.is_positive());
        }
        let by: Q = p.b.iter().zip(&y).map(|(b, y)| b * y).sum();
        assert!(by.is_positive());
    }

    #[test]
    fn an_unbounded_program_says_so() {
        // min -x1 with x1 - x2 = 1.
        let p = program(&[&[1, -1]], &[1], &[-1, 0]);
        assert_eq!(solve(&p), Outcome::Unbounded);
    }

    #[test]
    fn a_degenerate_program_that_cycles_without_blands_rule_ends() {
        // Beale's example (max 3/4 x4 - 150 x5 + 1/50 x6 - 6 x7), which cycles under the
        // largest-coefficient rule; optimum 1/20.
        let r = |v: &[(i128, i128)]| v.iter().map(|&(n, d)| Q::frac(n, d)).collect::<Vec<_>>();
        let p = Program {
            a: vec![
                r(&[(1, 4), (-60, 1), (-1, 25), (9, 1), (1, 1), (0, 1), (0, 1)]),
                r(&[(1, 2), (-90, 1), (-1, 50), (3, 1), (0, 1), (1, 1), (0, 1)]),
                r(&[(0, 1), (0, 1), (1, 1), (0, 1), (0, 1), (0, 1), (1, 1)]),
            ],
            b: r(&[(0, 1), (0, 1), (1, 1)]),
            c: r(&[(-3, 4), (150, 1), (-1, 50), (6, 1), (0, 1), (0, 1), (0, 1)]),
        };
        let out = solve(&p);
        certified(&p, &out);
        assert!(matches!(out, Outcome::Optimal { value, .. } if value == Q::frac(-1, 20)));
    }
}
