//! Linear programs: minimise c x subject to A x = b, x >= 0, by the dense two-phase simplex
//! method with Bland's rule, answered exactly. Exact answers make every result a vertex of the
//! problem to the last digit (a limit load that is a tie stays one), and Bland's rule ends every
//! run, however degenerate (limit analysis of block walls is: most contact forces of a mechanism
//! are zero).
//!
//! This tableau is the fallback: pivoting in rationals grows the fractions with every pivot
//! (sampled friction coefficients carry sixteen digits each), so the program first runs in
//! floating point (`revised`), and only its last basis is worked out in rationals (`certify`):
//! the primal and dual solutions of that basis, checked to satisfy every constraint exactly,
//! prove the answer as this run would (or the Farkas vector an infeasible program, or the ray an
//! unbounded one). Where the check fails (round-off chose a basis that is not optimal), this
//! tableau answers from the start; floating point never decides anything.

use crate::exact::Q;

/// A linear program in standard form: minimise `c x` subject to `A x = b`, `x >= 0`. A is kept
/// by columns, sparse: a contact force enters the balances of at most two blocks, six entries
/// in a column of thousands of rows (dense, the program of 600 blocks took half a gigabyte).
pub(crate) struct Program {
    /// The columns of A (one per cost), each its nonzero entries `(row, value)` by row.
    columns: Vec<Vec<(usize, Q)>>,
    /// The right-hand side, one per row.
    pub(crate) b: Vec<Q>,
    /// The costs, one per column.
    pub(crate) c: Vec<Q>,
}

impl Program {
    /// The program of A's `columns` (entries in any order, zeros allowed; a row given twice in
    /// a column is a mistake), `b` and `c`.
    pub(crate) fn new(columns: Vec<Vec<(usize, Q)>>, b: Vec<Q>, c: Vec<Q>) -> Program {
        debug_assert_eq!(columns.len(), c.len());
        let columns = columns
            .into_iter()
            .map(|mut column| {
                column.retain(|(i, a)| {
                    debug_assert!(*i < b.len());
                    !a.is_zero()
                });
                column.sort_unstable_by_key(|&(i, _)| i);
                debug_assert!(column.windows(2).all(|w| w[0].0 < w[1].0));
                column
            })
            .collect();
        Program { columns, b, c }
    }

    /// Column j of A: its nonzero entries by row.
    pub(crate) fn column(&self, j: usize) -> &[(usize, Q)] {
        &self.columns[j]
    }

    /// Every nonzero entry of A, `(row, column, value)`.
    pub(crate) fn entries(&self) -> impl Iterator<Item = (usize, usize, &Q)> {
        self.columns
            .iter()
            .enumerate()
            .flat_map(|(j, column)| column.iter().map(move |(i, a)| (*i, j, a)))
    }

    /// The product A^T y of column j with the row multipliers `y`.
    pub(crate) fn dot(&self, j: usize, y: &[Q]) -> Q {
        self.columns[j].iter().map(|(i, a)| a * &y[*i]).sum()
    }
}

/// What a program has.
#[derive(Debug, PartialEq)]
pub(crate) enum Outcome {
    /// An optimal vertex `x`, its value, the multipliers `y` of the rows (c - A^T y >= 0, zero
    /// where x > 0; b y is the value), and the basis they were read from (column `n + k`: row
    /// k's artificial variable).
    Optimal {
        x: Vec<Q>,
        value: Q,
        y: Vec<Q>,
        basis: Vec<usize>,
    },
    /// No x satisfies the constraints: `y` with A^T y <= 0 and b y > 0 shows it (Farkas).
    Infeasible { y: Vec<Q> },
    /// The cost falls without bound.
    Unbounded,
}

/// How a run ended: the basis it ends with says the rest.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Ending {
    /// Phase 2 ended: the basis is optimal.
    Optimal,
    /// Phase 1 ended with artificial variables above zero: the basis's phase-1 multipliers
    /// are the Farkas vector.
    Infeasible,
    /// Phase 2 found column `entering` with a negative reduced cost and nothing to stop it.
    Unbounded { entering: usize },
}

/// The tableau: B^-1 [A | I] with B^-1 b after it, the basic column of each row, and the
/// reduced costs of every column. Rows with b < 0 are negated first, so that the artificial
/// basis starts feasible.
struct Tableau {
    rows: Vec<Vec<Q>>,
    rhs: Vec<Q>,
    basis: Vec<usize>,
    reduced: Vec<Q>,
    /// Columns of A (the artificial ones follow).
    n: usize,
    /// The rows negated.
    flipped: Vec<bool>,
}

/// Why a phase of a run stopped (this tableau's or the floating-point run's in `revised`).
pub(super) enum Stop {
    Optimal,
    Unbounded {
        entering: usize,
    },
    /// Asked to stop, or (in floating point) out of pivots or of a factorisable basis.
    GaveUp,
    /// (In floating point, given a bound) at a vertex that costs less than the bound.
    Below,
}

impl Tableau {
    /// The tableau of `program`, dense, with an artificial column per row.
    fn new(program: &Program) -> Self {
        let (m, n) = (program.b.len(), program.c.len());
        let flipped: Vec<bool> = program.b.iter().map(Q::is_negative).collect();
        let s = |k: usize, x: Q| if flipped[k] { -x } else { x };
        let mut rows: Vec<Vec<Q>> = (0..m)
            .map(|k| {
                let mut r = vec![Q::zero(); n + m];
                r[n + k] = Q::one();
                r
            })
            .collect();
        for (i, j, a) in program.entries() {
            rows[i][j] = s(i, a.clone());
        }
        let rhs = (0..m).map(|k| s(k, program.b[k].clone())).collect();
        Tableau {
            rows,
            rhs,
            basis: (n..n + m).collect(),
            reduced: Vec::new(),
            n,
            flipped,
        }
    }

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
                    *r = &*r - &(cb * t);
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
                row[k] = &row[k] - &(f * &row_p[k]);
            }
            *rhs = &*rhs - &(f * &rhs_p);
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

    /// Runs Bland's rule over the columns `allowed` admits, until `stop` says so. (Dantzig's
    /// rule of the most negative reduced cost took longer by far in exact arithmetic, its
    /// pivots growing the fractions, and longer in floating point too: docs/rocking-walls.md,
    /// the limit at rest's cost.)
    fn optimise(&mut self, allowed: impl Fn(usize) -> bool, stop: &dyn Fn() -> bool) -> Stop {
        loop {
            let Some(j) =
                (0..self.reduced.len()).find(|&j| allowed(j) && self.reduced[j].is_negative())
            else {
                return Stop::Optimal;
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
                    Some((l, r)) => (&ratio, self.basis[i]) < (r, self.basis[*l]),
                };
                if better {
                    leave = Some((i, ratio));
                }
            }
            let Some((p, _)) = leave else {
                return Stop::Unbounded { entering: j };
            };
            if stop() {
                return Stop::GaveUp;
            }
            self.pivot(p, j);
        }
    }

    /// The multipliers of the rows for the costs last priced: the artificial column of row k
    /// started as e_k, so its reduced cost is its cost less y_k.
    fn multipliers(&self, cost: &[Q]) -> Vec<Q> {
        (0..self.rows.len())
            .map(|k| {
                let y = &cost[self.n + k] - &self.reduced[self.n + k];
                if self.flipped[k] {
                    -y
                } else {
                    y
                }
            })
            .collect()
    }

    /// Both phases; the costs are `c` followed by zeros for the artificial columns. `None`
    /// where `stop` said so.
    fn run(&mut self, c: Vec<Q>, stop: &dyn Fn() -> bool) -> Option<(Ending, Vec<Q>)> {
        let (m, n) = (self.rows.len(), self.n);
        // Phase 1: the sum of the artificial variables to zero.
        let phase1: Vec<Q> = (0..n + m)
            .map(|j| if j < n { Q::zero() } else { Q::one() })
            .collect();
        self.price(&phase1);
        if let Stop::GaveUp = self.optimise(|_| true, stop) {
            return None;
        }
        let infeasible = (0..m).any(|i| self.basis[i] >= n && self.rhs[i].is_positive());
        if infeasible {
            return Some((Ending::Infeasible, phase1));
        }
        // Artificial variables left in the basis at zero: swap each for a column of A where its
        // row has one; a row with none is a combination of the others and stays as it is.
        for i in 0..m {
            if self.basis[i] >= n {
                if let Some(j) = (0..n).find(|&j| !self.rows[i][j].is_zero()) {
                    self.pivot(i, j);
                }
            }
        }
        // Phase 2: the program's costs, artificial columns barred.
        let cost: Vec<Q> = c.into_iter().chain((0..m).map(|_| Q::zero())).collect();
        self.price(&cost);
        match self.optimise(|j| j < n, stop) {
            // The tableau is given no bound to pass.
            Stop::GaveUp | Stop::Below => None,
            Stop::Unbounded { entering } => Some((Ending::Unbounded { entering }, cost)),
            Stop::Optimal => Some((Ending::Optimal, cost)),
        }
    }
}

/// Solves the program in exact arithmetic alone; `None` where `stop` asked it to stop (it
/// looks at every pivot: a run of a large program can take hours).
pub(super) fn exact(program: &Program, stop: &dyn Fn() -> bool) -> Option<Outcome> {
    let mut t = Tableau::new(program);
    let (ending, cost) = t.run(program.c.clone(), stop)?;
    Some(match ending {
        Ending::Infeasible => Outcome::Infeasible {
            y: t.multipliers(&cost),
        },
        Ending::Unbounded { .. } => Outcome::Unbounded,
        Ending::Optimal => {
            let mut x = vec![Q::zero(); t.n];
            for (i, &j) in t.basis.iter().enumerate() {
                if j < t.n {
                    x[j] = t.rhs[i].clone();
                }
            }
            let value = (0..t.n).map(|j| &program.c[j] * &x[j]).sum::<Q>();
            Outcome::Optimal {
                y: t.multipliers(&cost),
                x,
                value,
                basis: t.basis.clone(),
            }
        }
    })
}
