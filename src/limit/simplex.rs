//! Linear programs: minimise c x subject to A x = b, x >= 0, by the dense two-phase simplex
//! method with Bland's rule, answered exactly. Exact answers make every result a vertex of the
//! problem to the last digit (a limit load that is a tie stays one), and Bland's rule ends every
//! run, however degenerate (limit analysis of block walls is: most contact forces of a mechanism
//! are zero).
//!
//! Why two arithmetics: pivoting a dense tableau in rationals grows the fractions with every
//! pivot (sampled friction coefficients carry sixteen digits each), so the same method first
//! runs in floating point, and only its last basis is worked out in rationals (`certify`): the
//! primal and dual solutions of that basis, checked to satisfy every constraint exactly, prove
//! the answer as the exact run would (or the Farkas vector an infeasible program, or the ray an
//! unbounded one). Where the check fails (round-off chose a basis that is not optimal), the exact
//! tableau answers from the start; floating point never decides anything.

use crate::exact::Q;
use std::cmp::Ordering;

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

/// The arithmetic a tableau runs in: exact rationals, or floating point with its signs read
/// past a tolerance.
trait Number: Clone {
    fn zero() -> Self;
    fn one() -> Self;
    /// -1, 0 or 1.
    fn sign(&self) -> i32;
    /// Whether `self` is below `o` (beyond round-off, in floating point).
    fn below(&self, o: &Self) -> bool;
    fn times(&self, o: &Self) -> Self;
    fn over(&self, o: &Self) -> Self;
    /// self - f x.
    fn less(&self, f: &Self, x: &Self) -> Self;
    fn negated(&self) -> Self;
    fn is_zero(&self) -> bool {
        self.sign() == 0
    }
    fn is_negative(&self) -> bool {
        self.sign() < 0
    }
    fn is_positive(&self) -> bool {
        self.sign() > 0
    }
}

impl Number for Q {
    fn zero() -> Self {
        Q::zero()
    }
    fn one() -> Self {
        Q::one()
    }
    fn sign(&self) -> i32 {
        self.signum()
    }
    fn below(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Less
    }
    fn times(&self, o: &Self) -> Self {
        self * o
    }
    fn over(&self, o: &Self) -> Self {
        self / o
    }
    fn less(&self, f: &Self, x: &Self) -> Self {
        self - &(f * x)
    }
    fn negated(&self) -> Self {
        -self
    }
}

/// A float whose sign is zero within `TOLERANCE` (the rows are scaled to entries of at most 1),
/// and a difference that cancels to round-off is zero, so the tableau keeps its zeros.
#[derive(Clone, Copy)]
struct Float(f64);

const TOLERANCE: f64 = 1e-9;

impl Number for Float {
    fn zero() -> Self {
        Float(0.0)
    }
    fn one() -> Self {
        Float(1.0)
    }
    fn sign(&self) -> i32 {
        if self.0 > TOLERANCE {
            1
        } else if self.0 < -TOLERANCE {
            -1
        } else {
            0
        }
    }
    fn below(&self, o: &Self) -> bool {
        self.0 < o.0 - TOLERANCE * (1.0 + self.0.abs().max(o.0.abs()))
    }
    fn times(&self, o: &Self) -> Self {
        Float(self.0 * o.0)
    }
    fn over(&self, o: &Self) -> Self {
        Float(self.0 / o.0)
    }
    fn less(&self, f: &Self, x: &Self) -> Self {
        let p = f.0 * x.0;
        let d = self.0 - p;
        Float(if d.abs() <= 1e-12 * (self.0.abs() + p.abs()) {
            0.0
        } else {
            d
        })
    }
    fn negated(&self) -> Self {
        Float(-self.0)
    }
}

/// The tableau: B^-1 [A | I] with B^-1 b after it, the basic column of each row, and the
/// reduced costs of every column. Rows with b < 0 are negated first, so that the artificial
/// basis starts feasible.
struct Tableau<T> {
    rows: Vec<Vec<T>>,
    rhs: Vec<T>,
    basis: Vec<usize>,
    reduced: Vec<T>,
    /// Columns of A (the artificial ones follow).
    n: usize,
    /// The rows negated.
    flipped: Vec<bool>,
    /// Pivots left before the run gives up (round-off can make Bland's rule cycle; exact
    /// arithmetic cannot).
    budget: usize,
}

/// Why a phase stopped.
enum Stop {
    Optimal,
    Unbounded { entering: usize },
    GaveUp,
}

impl<T: Number> Tableau<T> {
    fn new(a: Vec<Vec<T>>, b: Vec<T>, budget: usize) -> Self {
        let (m, n) = (b.len(), a.first().map_or(0, Vec::len));
        let flipped: Vec<bool> = b.iter().map(T::is_negative).collect();
        let mut rows = Vec::with_capacity(m);
        let mut rhs = Vec::with_capacity(m);
        for (k, (row, b)) in a.into_iter().zip(b).enumerate() {
            let s = |x: T| if flipped[k] { x.negated() } else { x };
            let mut r: Vec<T> = row.into_iter().map(s).collect();
            r.extend((0..m).map(|i| if i == k { T::one() } else { T::zero() }));
            rows.push(r);
            rhs.push(s(b));
        }
        Tableau {
            rows,
            rhs,
            basis: (n..n + m).collect(),
            reduced: Vec::new(),
            n,
            flipped,
            budget,
        }
    }

    /// Reduced costs for `cost` (one per column, artificial ones included).
    fn price(&mut self, cost: &[T]) {
        self.reduced = cost.to_vec();
        for (i, row) in self.rows.iter().enumerate() {
            let cb = &cost[self.basis[i]];
            if cb.is_zero() {
                continue;
            }
            for (r, t) in self.reduced.iter_mut().zip(row) {
                if !t.is_zero() {
                    *r = r.less(cb, t);
                }
            }
        }
    }

    /// Makes column j basic in row p (Gauss-Jordan on the rows and the reduced costs).
    fn pivot(&mut self, p: usize, j: usize) {
        let inv = T::one().over(&self.rows[p][j]);
        for t in self.rows[p].iter_mut() {
            if !t.is_zero() {
                *t = t.times(&inv);
            }
        }
        self.rhs[p] = self.rhs[p].times(&inv);
        let (row_p, rhs_p) = (self.rows[p].clone(), self.rhs[p].clone());
        let nonzero: Vec<usize> = (0..row_p.len()).filter(|&k| !row_p[k].is_zero()).collect();
        let eliminate = |row: &mut Vec<T>, rhs: &mut T, f: &T| {
            for &k in &nonzero {
                row[k] = row[k].less(f, &row_p[k]);
            }
            *rhs = rhs.less(f, &rhs_p);
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
            let mut ignored = T::zero();
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
            let mut leave: Option<(usize, T)> = None;
            for i in 0..self.rows.len() {
                let t = &self.rows[i][j];
                if !t.is_positive() {
                    continue;
                }
                let ratio = self.rhs[i].over(t);
                let better = match &leave {
                    None => true,
                    Some((l, r)) => {
                        ratio.below(r) || (!r.below(&ratio) && self.basis[i] < self.basis[*l])
                    }
                };
                if better {
                    leave = Some((i, ratio));
                }
            }
            let Some((p, _)) = leave else {
                return Stop::Unbounded { entering: j };
            };
            if self.budget == 0 || stop() {
                return Stop::GaveUp;
            }
            self.budget -= 1;
            self.pivot(p, j);
        }
    }

    /// The multipliers of the rows for the costs last priced: the artificial column of row k
    /// started as e_k, so its reduced cost is its cost less y_k.
    fn multipliers(&self, cost: &[T]) -> Vec<T> {
        (0..self.rows.len())
            .map(|k| {
                let y = cost[self.n + k].less(&T::one(), &self.reduced[self.n + k]);
                if self.flipped[k] {
                    y.negated()
                } else {
                    y
                }
            })
            .collect()
    }

    /// Both phases; the costs are `c` followed by zeros for the artificial columns. `None`
    /// where the run ran out of pivots or `stop` said so.
    fn run(&mut self, c: Vec<T>, stop: &dyn Fn() -> bool) -> Option<(Ending, Vec<T>)> {
        let (m, n) = (self.rows.len(), self.n);
        // Phase 1: the sum of the artificial variables to zero.
        let phase1: Vec<T> = (0..n + m)
            .map(|j| if j < n { T::zero() } else { T::one() })
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
        let cost: Vec<T> = c.into_iter().chain((0..m).map(|_| T::zero())).collect();
        self.price(&cost);
        match self.optimise(|j| j < n, stop) {
            Stop::GaveUp => None,
            Stop::Unbounded { entering } => Some((Ending::Unbounded { entering }, cost)),
            Stop::Optimal => Some((Ending::Optimal, cost)),
        }
    }
}

/// Solves the program in exact arithmetic alone; `None` where `stop` asked it to stop (it
/// looks at every pivot: a run of a large program can take hours).
pub(super) fn exact(program: &Program, stop: &dyn Fn() -> bool) -> Option<Outcome> {
    let mut t = Tableau::new(program.a.clone(), program.b.clone(), usize::MAX);
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
            }
        }
    })
}

/// Runs the program in floating point, each row divided by its largest entry (the scaling
/// changes no x, and the basis is all that is kept): how it ended, its last basis (columns
/// `n..n + m` are the rows' artificial variables) and the rows' divisors, or `None` where it
/// ran out of pivots or `stop` said so.
pub(super) fn floating(
    program: &Program,
    stop: &dyn Fn() -> bool,
) -> Option<(Ending, Vec<usize>, Vec<f64>)> {
    let (mut a, mut b, mut scales) = (Vec::with_capacity(program.b.len()), Vec::new(), Vec::new());
    for (row, rhs) in program.a.iter().zip(&program.b) {
        let row: Vec<f64> = row.iter().map(Q::to_f64).collect();
        let scale = row.iter().fold(rhs.to_f64().abs(), |s, x| s.max(x.abs()));
        let scale = if scale > 0.0 { scale } else { 1.0 };
        a.push(row.into_iter().map(|x| Float(x / scale)).collect());
        b.push(Float(rhs.to_f64() / scale));
        scales.push(scale);
    }
    let c = program.c.iter().map(|x| Float(x.to_f64())).collect();
    let (m, n) = (program.b.len(), program.c.len());
    let mut t = Tableau::new(a, b, 50 * (m + n) + 1000);
    let (ending, _) = t.run(c, stop)?;
    Some((ending, t.basis, scales))
}
