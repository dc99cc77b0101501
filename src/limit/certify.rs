//! The answers of the limit programs: a floating-point simplex run's answer, proved exactly,
//! or the exact run where the proof fails. A basis (m columns of [A | I])
//! determines everything the simplex method would report from it: the vertex B^-1 b, the
//! multipliers B^-T c_B, and for an unbounded run the edge B^-1 A_j. Solving those few square
//! systems exactly and checking every constraint on the results proves the answer as firmly as
//! an exact run, at the cost of a few solves (p-adic, `padic`, or by one rational elimination,
//! `factors`) instead of every pivot of a dense tableau.

use super::crash;
use super::factors::Factors;
use super::padic::Lifting;
use super::revised;
use super::simplex::{self, Ending, Outcome, Program};
use crate::exact::Q;
use std::cell::OnceCell;
use std::cmp::Ordering;
use std::collections::BTreeMap;

/// Solves the program: the floating-point run's basis certified exactly, or the exact run;
/// `None` where `stop` asked them to stop (both look at it at every pivot: the exact run of a
/// large program with sampled friction can take hours). The floating-point runs start from the
/// crash basis of `groups` ([`crash`]; none: from the artificial basis).
pub(crate) fn solve(
    program: &Program,
    groups: &[crash::Group],
    stop: &dyn Fn() -> bool,
) -> Option<Outcome> {
    certified(program, groups, stop).or_else(|| simplex::exact(program, stop))
}

/// The answer of a floating-point run whose last basis proves it exactly, the runs of
/// [`revised::RUNS`] tried in turn; `None` where each gave up or its basis proves nothing, or
/// where `stop` said so (no run is tried after that).
pub(crate) fn certified(
    program: &Program,
    groups: &[crash::Group],
    stop: &dyn Fn() -> bool,
) -> Option<Outcome> {
    watched(program, groups, stop).0
}

/// No floating-point run ended on a basis that proves its answer.
#[derive(Debug, PartialEq)]
pub(crate) struct NotProved;

/// [`certified`], telling a stop from runs that all failed: `Ok(None)` where `stop` said so,
/// `Err(NotProved)` where no run's basis proved the answer (for programs too large for the
/// exact run to follow).
pub(crate) fn proved(
    program: &Program,
    groups: &[crash::Group],
    stop: &dyn Fn() -> bool,
) -> Result<Option<Outcome>, NotProved> {
    match watched(program, groups, stop) {
        (Some(outcome), _) => Ok(Some(outcome)),
        (None, true) => Ok(None),
        (None, false) => Err(NotProved),
    }
}

/// What [`solve_below`] shows.
#[derive(Debug)]
pub(crate) enum Against {
    /// A feasible vertex that costs less than the value asked about: the program's optimum is
    /// lower, or it is unbounded (not solved for).
    Below,
    /// The program's outcome.
    Solved(Outcome),
}

/// Whether `program` has a feasible point that costs less than `value`, or else its outcome:
/// [`solve`], its first floating-point run started from `start` (a basis of `program`, column
/// `n + k` row k's artificial variable) and stopped at the first vertex below `value` (see
/// [`revised::floating_from`]), that vertex shown feasible and below exactly; where the start
/// is not feasible, or where what the run ends on proves nothing, [`solve`] answers from the
/// crash. `None` where `stop` said so.
pub(crate) fn solve_below(
    program: &Program,
    start: Vec<usize>,
    value: &Q,
    groups: &[crash::Group],
    stop: &dyn Fn() -> bool,
) -> Option<Against> {
    // Stopped a little below `value` in floating point, so that the exact check rarely finds
    // the vertex at `value` after all.
    let v = value.to_f64();
    let below = v - 1e-9 * (1.0 + v.abs());
    let shown = match revised::floating_from(program, start, below, revised::RUNS[0], stop) {
        Some(revised::Warm::Below(basis)) => {
            below_vertex(program, &basis, value).then_some(Against::Below)
        }
        Some(revised::Warm::Ended(ending, last, scales)) => {
            proved_run(program, (ending, last, scales)).map(Against::Solved)
        }
        None => None,
    };
    shown.or_else(|| solve(program, groups, stop).map(Against::Solved))
}

/// Whether the vertex of `basis` is feasible and costs less than `value`, exactly.
fn below_vertex(program: &Program, basis: &[usize], value: &Q) -> bool {
    let negated = Negated::new(program);
    let vertex = (negated.systems(basis)).and_then(|s| negated.costed(program, &s, basis));
    vertex.is_some_and(|(_, cost)| cost < *value)
}

/// The certified runs' answer, and whether `stop` said to stop.
fn watched(
    program: &Program,
    groups: &[crash::Group],
    stop: &dyn Fn() -> bool,
) -> (Option<Outcome>, bool) {
    let stopped = std::cell::Cell::new(false);
    let ask = || {
        let asked = stop();
        stopped.set(stopped.get() || asked);
        asked
    };
    let outcome = revised::RUNS
        .iter()
        .take_while(|_| !stopped.get())
        .find_map(|&rules| certified_by(program, groups, rules, &ask));
    (outcome, stopped.get())
}

/// Whether `program` (its costs zero) has a solution that a floating-point phase 1 started
/// from the crash basis of `groups` finds, its last basis proved exactly (B^-1 b at least zero,
/// every artificial variable at zero). False where it finds none, gives up, `stop` says so, or
/// its basis proves nothing: no program is shown infeasible here (the caller's full program
/// does that, with its Farkas vector), so floating point still decides nothing.
pub(crate) fn feasible(
    program: &Program,
    groups: &[crash::Group],
    stop: &dyn Fn() -> bool,
) -> bool {
    // Asked before the run too: from a good crash it may take no pivot at which to ask.
    if stop() {
        return false;
    }
    let Some(last) = revised::feasible(program, groups, revised::RUNS[0], stop) else {
        return false;
    };
    // Its vertex's signs alone: with no costs every feasible basis is optimal.
    let negated = Negated::new(program);
    let signs = (negated.systems(&last)).and_then(|systems| systems.signs(negated.b.clone()));
    signs.is_some_and(|signs| negated.feasible(&signs, &last))
}

/// What [`spanned`] shows.
#[derive(Debug, PartialEq)]
pub(crate) enum Span {
    /// The admitted columns span every column: shown by this basis, the one given with some
    /// artificial variables replaced by admitted columns (degenerate pivots: the vertex and the
    /// multipliers are the same), those left each on a row the others determine.
    All(Vec<usize>),
    /// Some column lies outside the admitted columns' span.
    Short,
}

/// Whether the columns of the program that `within` admits span all its columns, shown from
/// `basis` (of [A | I], its columns of A among those admitted, at a vertex whose artificial
/// variables are zero): each artificial variable left in it either sits on a row the others
/// determine (row k of B^-1 vanishes on every column), or is replaced by an admitted column on
/// which that row does not vanish; where only columns not admitted have such an entry, they
/// leave the admitted columns' span. `None` where `basis` is no basis.
pub(crate) fn spanned(
    program: &Program,
    basis: &[usize],
    within: impl Fn(usize) -> bool,
) -> Option<Span> {
    let n = program.c.len();
    if basis.iter().all(|&j| j < n) {
        // A basis of columns of A alone spans them all: no factorisation needed to show it.
        return Some(Span::All(basis.to_vec()));
    }
    let negated = Negated::new(program);
    let mut basis = basis.to_vec();
    // Each pass puts one more admitted column in an artificial variable's place, or ends.
    'passes: loop {
        let systems = negated.systems(&basis)?;
        for k in (0..basis.len()).filter(|&k| basis[k] >= n) {
            let w = systems.solve_transposed(unit(basis.len(), k))?;
            let row = Reduced::new(&w);
            let off = |j: &usize| row.sign(&Q::zero(), &negated.columns[*j]) != Ordering::Equal;
            if let Some(j) = (0..n).filter(|&j| within(j)).find(off) {
                basis[k] = j;
                continue 'passes;
            }
            if (0..n).any(|j| off(&j)) {
                return Some(Span::Short);
            }
        }
        return Some(Span::All(basis));
    }
}

/// The most degenerate rows [`Degenerate::moves_off`] tries: on the generated running bonds (one
/// friction everywhere, 105 to 976 blocks, a third of their rows degenerate) and the shipped
/// walls whose limit is one of several, the first row that shows a direction came within the
/// first 30 tried, each an exact solve in B^T (about 5 ms at 976 blocks); a wall whose
/// mechanism is unique would try every degenerate row before it, a thousand at that size.
const ROWS_TRIED: usize = 64;

/// What the questions about a degenerate optimum read from its basis: asked one after the
/// other of one basis ([`Degenerate::moves_off`], then [`Degenerate::directions`]), they share
/// its factorisation and the solves in B^T of the rows both take.
pub(crate) struct Degenerate {
    negated: Negated,
    systems: Systems,
    /// The basis's size: the program's rows.
    m: usize,
    /// The degenerate rows: the places of the basic columns of A at zero.
    rows: Vec<usize>,
    /// The nonbasic columns that the question's `tight` admits.
    others: Vec<usize>,
    /// B^-T e_k for the first of `rows`, as far as they were solved.
    solved: Vec<Vec<Q>>,
}

impl Degenerate {
    /// Those of `basis` at the vertex `x` (per column of A); `None` where it is no basis.
    pub(crate) fn of(
        program: &Program,
        basis: &[usize],
        x: &[Q],
        tight: impl Fn(usize) -> bool,
    ) -> Option<Degenerate> {
        let n = program.c.len();
        let negated = Negated::new(program);
        let systems = negated.systems(basis)?;
        let mut basic = vec![false; n];
        basis
            .iter()
            .filter(|&&j| j < n)
            .for_each(|&j| basic[j] = true);
        let rows = (0..basis.len())
            .filter(|&k| basis[k] < n && x[basis[k]].is_zero())
            .collect();
        let others = (0..n).filter(|&j| !basic[j] && tight(j)).collect();
        Some(Degenerate {
            negated,
            systems,
            m: basis.len(),
            rows,
            others,
            solved: Vec::new(),
        })
    }

    /// B^-T e_k for the `i`-th degenerate row k, solved once.
    fn row(&mut self, i: usize) -> Option<&[Q]> {
        while self.solved.len() <= i {
            let k = self.rows[self.solved.len()];
            let w = self.systems.solve_transposed(unit(self.m, k))?;
            self.solved.push(w);
        }
        Some(&self.solved[i])
    }

    /// Whether the optimal multipliers y of the basis move off along a direction that keeps
    /// them optimal, shown one degenerate row at a time (the first [`ROWS_TRIED`]): for a
    /// basic column r at zero, d = -B^-T e_r keeps a_k d = 0 on the other basic columns and
    /// a_r d = -1, and b d = -x_r = 0, so y + t d stays optimal for small t > 0 exactly where
    /// a_j d <= 0 on every nonbasic column that `tight` admits (zero reduced cost; the others
    /// have room). Such a d is no motion that no force does work on (a_r d is not zero). False
    /// where no row tried shows one, which proves nothing; `None` where a solve fails.
    pub(crate) fn moves_off(&mut self) -> Option<bool> {
        for i in 0..self.rows.len().min(ROWS_TRIED) {
            self.row(i)?;
            let row = Reduced::new(&self.solved[i]);
            // a_j d = -a_j w <= 0: the sign of 0 - a_j w is not above zero.
            let column = |j: &usize| &self.negated.columns[*j];
            let off = |j: &usize| row.sign(&Q::zero(), column(j)) == Ordering::Greater;
            if !self.others.iter().any(off) {
                return Some(true);
            }
        }
        Some(false)
    }

    /// The program of the directions in which the optimal multipliers y of the basis (its
    /// artificial variables, if any, on rows the others determine, as [`spanned`] leaves
    /// them) can move and stay optimal, in the coordinates v = -B^T d: v = 0 on the basic
    /// columns above zero (a_k d = 0), v >= 0 on those at zero (the degenerate rows D: a_k d
    /// <= 0), and a_j d = -(B^-1 a_j)_D v <= 0 on every nonbasic column that `tight` admits
    /// (zero reduced cost; the others have room); v on an artificial variable's row moves y
    /// along a motion no force does work on, and is left out. Normalised by the sum of v: a
    /// feasibility program, feasible exactly where another optimal y (not by such a motion
    /// alone) exists. `None` where a solve fails or the basis has more than `most` degenerate
    /// rows (a solve in B^T each).
    pub(crate) fn directions(&mut self, most: usize) -> Option<Program> {
        if self.rows.len() > most {
            return None;
        }
        let n_others = self.others.len();
        // Rows: (B^-1 a_j)_D v - s_j = 0 for each of `others`, then the sum of v = 1.
        let mut columns: Vec<Vec<(usize, Q)>> = Vec::new();
        for i in 0..self.rows.len() {
            self.row(i)?;
            let w = &self.solved[i];
            let mut column: Vec<(usize, Q)> = (self.others.iter().enumerate())
                .map(|(r, &j)| {
                    let a = &self.negated.columns[j];
                    (r, a.iter().map(|(t, a)| a * &w[*t]).sum::<Q>())
                })
                .filter(|(_, a)| !a.is_zero())
                .collect();
            column.push((n_others, Q::one()));
            columns.push(column);
        }
        columns.extend((0..n_others).map(|r| vec![(r, -Q::one())]));
        let mut b = vec![Q::zero(); n_others + 1];
        b[n_others] = Q::one();
        let costs = vec![Q::zero(); columns.len()];
        Some(Program::new(columns, b, costs))
    }
}

/// e_k of length m.
fn unit(m: usize, k: usize) -> Vec<Q> {
    let mut e = vec![Q::zero(); m];
    e[k] = Q::one();
    e
}

/// The answer of the floating-point run under `rules`, where its last basis proves it.
pub(super) fn certified_by(
    program: &Program,
    groups: &[crash::Group],
    rules: revised::Rules,
    stop: &dyn Fn() -> bool,
) -> Option<Outcome> {
    proved_run(program, revised::floating(program, groups, rules, stop)?)
}

/// The outcome that a floating-point run's last basis proves (its ending, that basis and the
/// divisors of its rows), if it proves one.
fn proved_run(
    program: &Program,
    (ending, last, scales): (Ending, Vec<usize>, Vec<f64>),
) -> Option<Outcome> {
    // Phase 1 of the scaled rows costs each artificial variable 1 / scale in the rows as given.
    let weights: Option<Vec<Q>> = scales
        .iter()
        .map(|&s| Q::from_f64_exact(s).map(|s| s.recip()))
        .collect();
    basis(program, &last, ending, &weights?)
}

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
    if weights.len() != m {
        return None;
    }
    let negated = Negated::new(program);
    let systems = negated.systems(basis)?;
    let artificial = |k: usize| basis[k] >= n;
    let columns = &negated.columns;
    // Negated, not multiplied by -1: a product of big rationals reduces by their gcd.
    let unflipped = |y: Vec<Q>| -> Vec<Q> {
        let flip = |(y, s): (Q, &Q)| if s.is_negative() { -y } else { y };
        y.into_iter().zip(&negated.sign).map(flip).collect()
    };
    match ending {
        Ending::Optimal => {
            let (x, value) = negated.costed(program, &systems, basis)?;
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
            let y = systems.solve_transposed(c_b)?;
            // A basic column's reduced cost is zero: B^T y = c_B holds exactly.
            let mut basic = vec![false; n + m];
            basis.iter().for_each(|&j| basic[j] = true);
            let reduced = Reduced::new(&y);
            let dual_feasible = (0..n)
                .filter(|&j| !basic[j])
                .all(|j| reduced.sign(&program.c[j], &columns[j]) != Ordering::Less);
            if !dual_feasible {
                return None;
            }
            Some(Outcome::Optimal {
                x,
                value,
                y: unflipped(y),
                basis: basis.to_vec(),
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
            let y = systems.solve_transposed(c_b)?;
            let reduced = Reduced::new(&y);
            let farkas = (0..n).all(|j| reduced.sign(&Q::zero(), &columns[j]) != Ordering::Less)
                && (negated.b.iter())
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
            for (i, a) in negated.column(entering) {
                a_j[i] = a;
            }
            let (x_b, w) = (systems.solve(negated.b.clone())?, systems.solve(a_j)?);
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

/// A program's rows negated where b < 0, as in the tableau, so that every artificial variable
/// starts at b >= 0; column `n + k` is row k's artificial variable.
struct Negated {
    /// Each row's sign.
    sign: Vec<Q>,
    b: Vec<Q>,
    /// The columns of A.
    columns: Vec<Vec<(usize, Q)>>,
}

impl Negated {
    fn new(program: &Program) -> Negated {
        let sign: Vec<Q> = (program.b.iter())
            .map(|b| if b.is_negative() { -Q::one() } else { Q::one() })
            .collect();
        let b = program.b.iter().zip(&sign).map(|(b, s)| b * s).collect();
        let columns = (0..program.c.len())
            .map(|j| {
                let column = program.column(j).iter();
                column.map(|(i, a)| (*i, a * &sign[*i])).collect()
            })
            .collect();
        Negated { sign, b, columns }
    }

    /// Column j of [A | I].
    fn column(&self, j: usize) -> Vec<(usize, Q)> {
        match self.columns.get(j) {
            Some(column) => column.clone(),
            None => vec![(j - self.columns.len(), Q::one())],
        }
    }

    /// The systems of `basis`, `None` where it is no basis (its length is not the rows' count,
    /// or it names a column that is not there).
    fn systems(&self, basis: &[usize]) -> Option<Systems> {
        let (m, n) = (self.b.len(), self.columns.len());
        if basis.len() != m || basis.iter().any(|&j| j >= n + m) {
            return None;
        }
        let mut rows = vec![BTreeMap::new(); m];
        for (k, &j) in basis.iter().enumerate() {
            for (i, a) in self.column(j) {
                rows[i].insert(k, a);
            }
        }
        Some(Systems::new(rows))
    }

    /// The basis's vertex B^-1 b, where it is at least zero with every artificial variable at
    /// zero.
    fn vertex(&self, systems: &Systems, basis: &[usize]) -> Option<Vec<Q>> {
        let x_b = systems.solve(self.b.clone())?;
        let signs: Vec<Ordering> = x_b.iter().map(|x| x.signum().cmp(&0)).collect();
        self.feasible(&signs, basis).then_some(x_b)
    }

    /// The basis's vertex as the program's x (per column of A) and its cost, where it is at
    /// least zero with every artificial variable at zero.
    fn costed(&self, program: &Program, systems: &Systems, basis: &[usize]) -> Option<(Vec<Q>, Q)> {
        let x_b = self.vertex(systems, basis)?;
        let n = program.c.len();
        let mut x = vec![Q::zero(); n];
        for (k, &j) in basis.iter().enumerate() {
            if j < n {
                x[j] = x_b[k].clone();
            }
        }
        let value = (0..n).map(|j| &program.c[j] * &x[j]).sum::<Q>();
        Some((x, value))
    }

    /// Whether the vertex whose entries have `signs` is at least zero with every artificial
    /// variable of `basis` at zero.
    fn feasible(&self, signs: &[Ordering], basis: &[usize]) -> bool {
        let artificial = |k: usize| basis[k] >= self.columns.len();
        (signs.iter().enumerate())
            .all(|(k, &s)| s != Ordering::Less && (!artificial(k) || s == Ordering::Equal))
    }
}

/// The systems in a basis B and in B^T, solved exactly: by p-adic lifting where B is
/// nonsingular modulo its prime (`padic`), else by rational elimination, factorised only then
/// and alone able to tell that B is singular.
struct Systems {
    rows: Vec<BTreeMap<usize, Q>>,
    lifting: Option<Lifting>,
    rational: OnceCell<Option<Factors<Q>>>,
}

impl Systems {
    fn new(rows: Vec<BTreeMap<usize, Q>>) -> Systems {
        Systems {
            lifting: Lifting::of(&rows),
            rows,
            rational: OnceCell::new(),
        }
    }

    /// B's rational factors, `None` where B is singular.
    fn rational(&self) -> Option<&Factors<Q>> {
        let factors = || Factors::of(self.rows.clone());
        self.rational.get_or_init(factors).as_ref()
    }

    /// z with B z = r, `None` where B is singular.
    fn solve(&self, r: Vec<Q>) -> Option<Vec<Q>> {
        let lifted = self.lifting.as_ref().and_then(|l| l.solve(&r));
        lifted.or_else(|| Some(self.rational()?.solve(r)))
    }

    /// The signs of z with B z = r, `None` where B is singular.
    fn signs(&self, r: Vec<Q>) -> Option<Vec<Ordering>> {
        let lifted = self.lifting.as_ref().and_then(|l| l.signs(&r));
        let sign = |z: Vec<Q>| z.iter().map(|z| z.signum().cmp(&0)).collect();
        lifted.or_else(|| Some(sign(self.rational()?.solve(r))))
    }

    /// y with B^T y = d, `None` where B is singular.
    fn solve_transposed(&self, d: Vec<Q>) -> Option<Vec<Q>> {
        let lifted = self.lifting.as_ref().and_then(|l| l.solve_transposed(&d));
        lifted.or_else(|| Some(self.rational()?.solve_transposed(d)))
    }
}

/// Signs of reduced costs c_j - a_j . y for exact multipliers `y`, summed in floating point
/// where that decides them and in rationals where it cannot. Why: y's entries run to thousands
/// of bits on sampled friction, and every rational product and sum of them reduces by a gcd
/// of that size, for each of the program's columns; most reduced costs are far from zero and
/// a float sum with its error bound shows their sign.
struct Reduced<'a> {
    y: &'a [Q],
    /// y in floating point, or `None` where some entry leaves the range in which rounding is
    /// relative (the bound below would not hold).
    near: Option<Vec<f64>>,
}

impl<'a> Reduced<'a> {
    fn new(y: &'a [Q]) -> Reduced<'a> {
        let near: Vec<f64> = y.iter().map(Q::to_f64).collect();
        let normal = near
            .iter()
            .zip(y)
            .all(|(f, q)| f.is_finite() && (q.is_zero() || (1e-200..=1e200).contains(&f.abs())));
        Reduced {
            y,
            near: normal.then_some(near),
        }
    }

    /// The sign of c - a . y, `a` a sparse column.
    fn sign(&self, c: &Q, a: &[(usize, Q)]) -> Ordering {
        if let Some(sum) = self.near.as_ref().and_then(|near| certain(c, a, near)) {
            return sum;
        }
        let dot: Q = a.iter().map(|(i, a)| a * &self.y[*i]).sum();
        (c - &dot).signum().cmp(&0)
    }
}

/// The sign of c - a . y from the floating-point sum, where its error bound decides it. Each
/// conversion to floating point is rounded once (exact numerators and denominators divided, or
/// a big ratio rounded to nearest) and each product once, so a term is within 3 u of its value
/// (u = 2^-53) and the sum of k + 1 terms within (k + 3) u times the sum of their sizes, while
/// every number is of normal size: the factors are kept within 1e-100..1e100 and 1e-200..1e200
/// (zeros aside), so no product under- or overflows. The bound taken, (4 k + 16) u, leaves room
/// for the sizes' own sum rounded.
fn certain(c: &Q, a: &[(usize, Q)], near: &[f64]) -> Option<Ordering> {
    let normal =
        |x: f64, range: std::ops::RangeInclusive<f64>| x == 0.0 || range.contains(&x.abs());
    let c = c.to_f64();
    normal(c, 1e-200..=1e200).then_some(())?;
    let (mut sum, mut size) = (c, c.abs());
    for (i, a) in a {
        let a = a.to_f64();
        normal(a, 1e-100..=1e100).then_some(())?;
        let term = a * near[*i];
        sum -= term;
        size += term.abs();
    }
    let bound = (2 * a.len() + 8) as f64 * f64::EPSILON * size;
    (sum.abs() > bound).then(|| sum.partial_cmp(&0.0).unwrap_or(Ordering::Equal))
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// The exact run, never stopped.
    fn exact(p: &Program) -> Outcome {
        simplex::exact(p, &|| false).expect("not stopped")
    }

    fn q(n: i128) -> Q {
        Q::frac(n, 1)
    }

    /// [`Degenerate::moves_off`] of a fresh basis's questions.
    fn moves_off(p: &Program, basis: &[usize], x: &[Q], tight: fn(usize) -> bool) -> Option<bool> {
        Degenerate::of(p, basis, x, tight)?.moves_off()
    }

    /// [`Degenerate::directions`] of a fresh basis's questions.
    fn directions(p: &Program, basis: &[usize], x: &[Q], most: usize) -> Option<Program> {
        Degenerate::of(p, basis, x, |_| true)?.directions(most)
    }

    fn program(a: &[&[i128]], b: &[i128], c: &[i128]) -> Program {
        let rows: Vec<Vec<Q>> = a
            .iter()
            .map(|r| r.iter().map(|&v| q(v)).collect())
            .collect();
        from_rows(
            &rows,
            b.iter().map(|&v| q(v)).collect(),
            c.iter().map(|&v| q(v)).collect(),
        )
    }

    /// The program of A's dense `rows` (each as long as `c`).
    pub(in crate::limit) fn from_rows(rows: &[Vec<Q>], b: Vec<Q>, c: Vec<Q>) -> Program {
        let columns = (0..c.len())
            .map(|j| rows.iter().map(|r| r[j].clone()).enumerate().collect())
            .collect();
        Program::new(columns, b, c)
    }

    /// Checks an optimum's certificate: A x = b, x >= 0, c - A^T y >= 0 with complementary
    /// slackness, and b y equal to c x (strong duality).
    fn optimal(p: &Program, out: &Outcome) {
        let Outcome::Optimal { x, value, y, .. } = out else {
            panic!("not optimal: {out:?}");
        };
        let mut ax = vec![Q::zero(); p.b.len()];
        for (i, j, a) in p.entries() {
            ax[i] = &ax[i] + &(a * &x[j]);
        }
        assert_eq!(ax, p.b);
        for (j, (x, c)) in x.iter().zip(&p.c).enumerate() {
            assert!(!x.is_negative());
            let slack = c - &p.dot(j, y);
            assert!(!slack.is_negative(), "dual infeasible in column {j}");
            assert!(x.is_zero() || slack.is_zero(), "not complementary in {j}");
        }
        let by: Q = p.b.iter().zip(y).map(|(b, y)| b * y).sum();
        assert_eq!(&by, value);
    }

    /// The floating-point run's basis is certified, and proves what the exact run finds: the
    /// same kind of outcome and the same optimal value (the vertex may differ where optima tie).
    fn agrees(p: &Program) -> Outcome {
        let fast =
            certified(p, &[], &|| false).expect("the floating-point basis proves the answer");
        match (&fast, &exact(p)) {
            (Outcome::Optimal { value: a, .. }, Outcome::Optimal { value: b, .. }) => {
                assert_eq!(a, b)
            }
            (Outcome::Infeasible { .. }, Outcome::Infeasible { .. })
            | (Outcome::Unbounded, Outcome::Unbounded) => {}
            (fast, slow) => panic!("certified {fast:?}, exact {slow:?}"),
        }
        fast
    }

    /// max 3 x1 + 5 x2 with x1 <= 4, 2 x2 <= 12, 3 x1 + 2 x2 <= 18 (slacks x3..x5): 36 at
    /// (2, 6).
    fn textbook() -> Program {
        program(
            &[&[1, 0, 1, 0, 0], &[0, 2, 0, 1, 0], &[3, 2, 0, 0, 1]],
            &[4, 12, 18],
            &[-3, -5, 0, 0, 0],
        )
    }

    #[test]
    fn a_stop_request_ends_both_runs_at_their_next_pivot() {
        let p = textbook();
        let asked = std::cell::Cell::new(0);
        // Asked before each pivot, stop from the second question on: the floating-point run
        // stops after one pivot (the textbook takes more), the exact run before its first.
        let stop = || {
            asked.set(asked.get() + 1);
            asked.get() > 1
        };
        assert_eq!(solve(&p, &[], &stop), None);
        assert_eq!(asked.get(), 3);
        assert!(solve(&p, &[], &|| false).is_some());
    }

    /// Rows that differ below the last bit of a float: every floating-point run sees the
    /// same row twice, and no basis it ends on holds up in rationals. The exact run finds the
    /// optimum; without it the program is not proved, which a stop is told from.
    #[test]
    fn a_program_whose_rows_round_alike_is_not_proved_by_floating_point() {
        let e = Q::frac(1, 1_000_000_000_000_000_000);
        let p = from_rows(
            &[vec![q(1), q(1)], vec![q(1), &q(1) + &e]],
            vec![q(1), &q(1) + &(&e * &Q::frac(1, 2))],
            vec![q(1), q(1)],
        );
        assert_eq!(proved(&p, &[], &|| false), Err(NotProved));
        assert_eq!(proved(&p, &[], &|| true), Ok(None));
        let half = Q::frac(1, 2);
        let Some(Outcome::Optimal { x, value, .. }) = solve(&p, &[], &|| false) else {
            panic!("the exact run solves it");
        };
        assert_eq!((x, value), (vec![half.clone(), half], q(1)));
    }

    #[test]
    fn a_textbook_program_reaches_its_optimum_with_its_certificate() {
        let p = textbook();
        let out = agrees(&p);
        optimal(&p, &out);
        optimal(&p, &exact(&p));
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
        let out = agrees(&p);
        optimal(&p, &out);
        optimal(&p, &exact(&p));
        assert!(matches!(out, Outcome::Optimal { value, .. } if value == q(3)));
    }

    #[test]
    fn an_infeasible_program_comes_with_a_farkas_certificate() {
        // x1 + x2 = 1 and x1 + x2 = 2.
        let p = program(&[&[1, 1], &[1, 1]], &[1, 2], &[0, 0]);
        for out in [agrees(&p), exact(&p)] {
            let Outcome::Infeasible { y } = out else {
                panic!("feasible?")
            };
            for j in 0..2 {
                assert!(!p.dot(j, &y).is_positive());
            }
            let by: Q = p.b.iter().zip(&y).map(|(b, y)| b * y).sum();
            assert!(by.is_positive());
        }
    }

    #[test]
    fn an_unbounded_program_says_so() {
        // min -x1 with x1 - x2 = 1.
        let p = program(&[&[1, -1]], &[1], &[-1, 0]);
        assert_eq!(agrees(&p), Outcome::Unbounded);
    }

    #[test]
    fn a_degenerate_program_that_cycles_without_blands_rule_ends() {
        // Beale's example (max 3/4 x4 - 150 x5 + 1/50 x6 - 6 x7), which cycles under the
        // largest-coefficient rule; optimum 1/20.
        let r = |v: &[(i128, i128)]| v.iter().map(|&(n, d)| Q::frac(n, d)).collect::<Vec<_>>();
        let p = from_rows(
            &[
                r(&[(1, 4), (-60, 1), (-1, 25), (9, 1), (1, 1), (0, 1), (0, 1)]),
                r(&[(1, 2), (-90, 1), (-1, 50), (3, 1), (0, 1), (1, 1), (0, 1)]),
                r(&[(0, 1), (0, 1), (1, 1), (0, 1), (0, 1), (0, 1), (1, 1)]),
            ],
            r(&[(0, 1), (0, 1), (1, 1)]),
            r(&[(-3, 4), (150, 1), (-1, 50), (6, 1), (0, 1), (0, 1), (0, 1)]),
        );
        let out = agrees(&p);
        optimal(&p, &out);
        assert!(matches!(out, Outcome::Optimal { value, .. } if value == Q::frac(-1, 20)));
    }

    /// A reduced cost's sign is the exact one whether the float sum decides it or not: at a tie
    /// (c = a . y exactly), a hair either side of it (1e-40 of the terms, past the float sum's
    /// reach) and well clear of it, with multipliers of hundreds of bits.
    #[test]
    fn reduced_costs_take_the_exact_sign_also_at_ties() {
        let mut rng = crate::rng::Rng::new(3);
        let mut big = || {
            let mut q = Q::frac(
                (rng.next_u64() >> 1) as i128 + 1,
                (rng.next_u64() >> 1) as i128 + 1,
            );
            for _ in 0..6 {
                let f = Q::frac(
                    (rng.next_u64() >> 2) as i128 - (1 << 61),
                    (rng.next_u64() >> 1) as i128 + 1,
                );
                q = &(&q * &f) + &Q::frac(1, 3);
            }
            q
        };
        let y: Vec<Q> = (0..8).map(|_| big()).collect();
        let reduced = Reduced::new(&y);
        assert!(reduced.near.is_some());
        let hair = Q::frac(1, 10_000_000_000_000_000_000_000_000_000_000_000_000);
        let mut decided_in_floats = 0;
        for j in 0..40 {
            let a: Vec<(usize, Q)> = (0..1 + j % 5)
                .map(|k| ((j + 3 * k) % 8, Q::frac(2 * j as i128 - 39, 7 + k as i128)))
                .collect();
            let dot: Q = a.iter().map(|(i, a)| a * &y[*i]).sum();
            let size: Q = a.iter().map(|(i, a)| (a * &y[*i]).abs()).sum();
            for c in [
                dot.clone(),
                &dot + &(&size * &hair),
                &dot - &(&size * &hair),
                &dot + &size,
                &dot - &size,
            ] {
                let exact = (&c - &dot).signum().cmp(&0);
                assert_eq!(reduced.sign(&c, &a), exact, "column {j}");
                decided_in_floats +=
                    usize::from(certain(&c, &a, reduced.near.as_ref().unwrap()).is_some());
            }
        }
        // The clear cases (two of five) in floats, the ties and hairs in rationals.
        assert_eq!(decided_in_floats, 80);
    }

    #[test]
    fn a_basis_that_proves_nothing_is_refused() {
        // The textbook program: its optimal basis {x1, x2, x3} (in any order) proves
        // -36; the slack basis is feasible but not optimal, {x1, x2, x5} is not even feasible
        // (x5 = -6), a feasible program has no Farkas vector, and x1 meets a bound.
        let p = textbook();
        let ones = [q(1), q(1), q(1)];
        let out = basis(&p, &[2, 0, 1], Ending::Optimal, &ones);
        assert!(matches!(out, Some(Outcome::Optimal { value, .. }) if value == q(-36)));
        assert_eq!(basis(&p, &[2, 3, 4], Ending::Optimal, &ones), None);
        assert_eq!(basis(&p, &[0, 1, 4], Ending::Optimal, &ones), None);
        assert_eq!(basis(&p, &[2, 3, 4], Ending::Infeasible, &ones), None);
        let unbounded = Ending::Unbounded { entering: 0 };
        assert_eq!(basis(&p, &[2, 3, 4], unbounded, &ones), None);
        // A singular basis (x1 twice) and one of the wrong size prove nothing either.
        assert_eq!(basis(&p, &[0, 0, 4], Ending::Optimal, &ones), None);
        assert_eq!(basis(&p, &[2, 3], Ending::Optimal, &ones), None);
    }

    #[test]
    fn admitted_columns_span_where_each_artificial_sits_on_a_dependent_row_or_gives_way() {
        let all = |_: usize| true;
        // Rows x1 + x2 + x3 and twice that: the second is the first's, so x1 with row 1's
        // artificial shows that x1 alone spans every column.
        let dependent = program(&[&[1, 1, 1], &[2, 2, 2]], &[1, 2], &[0, 0, 0]);
        assert_eq!(
            spanned(&dependent, &[0, 4], |j| j == 0),
            Some(Span::All(vec![0, 4]))
        );
        assert_eq!(
            spanned(&dependent, &[3, 3], all),
            None,
            "singular: no basis"
        );
        // Rows x1 + x2 and x2 + x3: x1 alone does not span (x2 and x3 leave its span); x1 and
        // x3 do, reached from row 1's artificial replaced by x3, or by x2 where it is admitted.
        let independent = program(&[&[1, 1, 0], &[0, 1, 1]], &[1, 1], &[0, 0, 0]);
        assert_eq!(
            spanned(&independent, &[0, 4], |j| j == 0),
            Some(Span::Short)
        );
        assert_eq!(
            spanned(&independent, &[0, 4], |j| j != 1),
            Some(Span::All(vec![0, 2]))
        );
        assert!(
            matches!(spanned(&independent, &[3, 4], all), Some(Span::All(b)) if b.iter().all(|&j| j < 3))
        );
        assert_eq!(
            spanned(&independent, &[0, 2], |j| j != 1),
            Some(Span::All(vec![0, 2])),
            "no artificial"
        );
    }

    #[test]
    fn a_degenerate_row_shows_another_optimum_where_no_tight_column_blocks_it() {
        // min -x1 + x3 over x1 + x2 = 1 and x2 + x3 = 0: x = (1, 0, 0), in the basis {x1, x2}
        // with x2 at zero; y = (-1, 1), and x3 is tight. Along row 1, d = (0, -1): y + t d
        // keeps x1 tight, x2 and x3 within their costs, and b y: another optimum.
        let p = program(&[&[1, 1, 0], &[0, 1, 1]], &[1, 0], &[-1, 0, 1]);
        assert_eq!(
            moves_off(&p, &[0, 1], &[q(1), q(0), q(0)], |_| true),
            Some(true)
        );
        // A fourth column -x4 in row 1 at cost -1, tight too, holds y1 at 1: y is unique, and
        // the row shows nothing; left out of the tight ones, it blocks nothing.
        let p = program(&[&[1, 1, 0, 0], &[0, 1, 1, -1]], &[1, 0], &[-1, 0, 1, -1]);
        let x = [q(1), q(0), q(0), q(0)];
        assert_eq!(moves_off(&p, &[0, 1], &x, |_| true), Some(false));
        assert_eq!(moves_off(&p, &[0, 1], &x, |j| j != 3), Some(true));
        // Nondegenerate: no row to try.
        let p = program(&[&[1, 0], &[0, 1]], &[1, 1], &[-1, -1]);
        assert_eq!(moves_off(&p, &[0, 1], &[q(1), q(1)], |_| true), Some(false));
    }

    #[test]
    fn the_program_of_directions_is_feasible_exactly_where_another_optimum_exists() {
        let feasible = |p: &Program| !matches!(exact(p), Outcome::Infeasible { .. });
        // The first program of the test above: its degenerate row shows another optimum.
        let p = program(&[&[1, 1, 0], &[0, 1, 1]], &[1, 0], &[-1, 0, 1]);
        let x = [q(1), q(0), q(0)];
        let d = directions(&p, &[0, 1], &x, 8).unwrap();
        assert!(feasible(&d));
        // With -x4 tight in row 1, y is unique: no direction.
        let p = program(&[&[1, 1, 0, 0], &[0, 1, 1, -1]], &[1, 0], &[-1, 0, 1, -1]);
        let x = [q(1), q(0), q(0), q(0)];
        let d = directions(&p, &[0, 1], &x, 8).unwrap();
        assert!(!feasible(&d));
        let not_asked = directions(&p, &[0, 1], &x, 0);
        assert!(not_asked.is_none(), "more rows than asked");
        // Two degenerate rows (x2, x3 basic at zero), each blocked alone by a tight column (x4
        // by row 1, x5 by row 2) but not together: v = (1, 1) keeps both. The rows tried one
        // at a time show nothing; the program of directions shows another optimum.
        let p = program(
            &[&[1, 0, 0, 0, 0], &[0, 1, 0, -1, 2], &[0, 0, 1, 2, -1]],
            &[1, 0, 0],
            &[-1, 0, 0, 0, 0],
        );
        let x = [q(1), q(0), q(0), q(0), q(0)];
        assert_eq!(moves_off(&p, &[0, 1, 2], &x, |_| true), Some(false));
        let d = directions(&p, &[0, 1, 2], &x, 8).unwrap();
        assert!(feasible(&d));
    }

    #[test]
    fn random_programs_get_the_exact_answer_from_their_floating_point_basis() {
        // Dense programs with small integer data, a third of them infeasible or unbounded by
        // construction of signs: every floating-point basis must be certified here, since
        // round-off cannot mislead a run on such well-scaled numbers.
        let mut rng = crate::rng::Rng::new(37);
        let mut small = |span: i128| (rng.next_u64() % (2 * span as u64 + 1)) as i128 - span;
        let mut kinds = [0; 3];
        for _ in 0..200 {
            let (m, n) = (2 + small(2).unsigned_abs() as usize, 6 + small(3) as usize);
            let a: Vec<Vec<i128>> = (0..m).map(|_| (0..n).map(|_| small(4)).collect()).collect();
            let b: Vec<i128> = (0..m).map(|_| small(6)).collect();
            let c: Vec<i128> = (0..n).map(|_| small(3)).collect();
            let rows: Vec<&[i128]> = a.iter().map(Vec::as_slice).collect();
            let p = program(&rows, &b, &c);
            let out = agrees(&p);
            if matches!(out, Outcome::Optimal { .. }) {
                optimal(&p, &out);
            }
            kinds[match out {
                Outcome::Optimal { .. } => 0,
                Outcome::Infeasible { .. } => 1,
                Outcome::Unbounded => 2,
            }] += 1;
        }
        assert!(kinds.iter().all(|&k| k > 10), "outcomes by kind: {kinds:?}");
    }
}
