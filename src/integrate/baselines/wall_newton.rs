//! The contact problem of one Moreau-Jean step solved on the whole wall at once: every block's
//! velocity is found together by Newton's method, the contacts being stiff but not rigid.
//!
//! Projected Gauss-Seidel passes load from contact to contact; in a tall stack a change of load
//! needs many sweeps to reach the ground, and blocks resting on two others leave the rigid
//! problem's impulses undetermined, so that it converges slowly or not at all. Here each contact
//! point has a compliance eps (m/s per N s): its normal impulse is p_n = max(0, -(u_n -
//! target) / eps) and its tangential one -u_t / eps within +- b. With the friction bounds b
//! fixed (Tresca's law) the step's velocities minimise a convex, piecewise quadratic potential,
//! 1/2 (v - v_free)' M (v - v_free) plus each contact's; Newton's method with an exact line
//! search finds that minimum whatever the start, each step a sparse symmetric positive definite
//! system M + sum H' D H / eps (a block couples to the blocks it touches) solved by faer's sparse
//! Cholesky factorisation, whose symbolic part is made once per run over every pair of blocks
//! that can touch. Coulomb's law is the fixed point b = mu p_n: once Tresca's problem is solved
//! the bounds move to mu p_n and Newton goes on, until a step with fresh bounds changes nothing.
//! That fixed point can cycle or creep (in a running bond whose blocks turn, the bounds move by
//! millions of their round-off from one update to the next); where it first stalls, semismooth
//! Newton on Coulomb's law itself is tried from its iterate: the Jacobian is then unsymmetric (a
//! sliding contact's friction follows its normal impulse), solved by faer's sparse LU on the
//! same pattern, with a backtracking line search on the residual's size. Where that does not
//! converge in a few steps, the fixed point goes on from where it stalled, and Newton on
//! Coulomb's law takes its last iterate again if it never settles. Where neither this nor the
//! same problem in the contacts' impulses (`wall_dual.rs`) converges, each Tresca problem is
//! solved by a primal-dual interior point in the velocities (its barrier smooths every kink at
//! once) and finished by Newton, the bounds updated as in the fixed point for a few updates and
//! then by Anderson's mix of the last few, where the plain update cycles (`anderson.rs`).
//!
//! With eps small the answer is the rigid one to a relative O(eps): a resting contact closes at
//! a speed of eps p_n (about [`COMPLIANCE`] times g dt). Where rigid blocks leave the split
//! undetermined (a block on two others) the compliance decides it: the impulses are those of
//! springs of one stiffness per metre of joint, each corner standing for half its joint's
//! length, in the limit of infinite stiffness, the split of least complementary energy (the
//! elastic answer). docs/rocking-walls.md compares it with eq. 3's tributary split.

use super::anderson::Anderson;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, CholeskySymbolicParams, LltRef, SymbolicCholesky,
    SymmetricOrdering,
};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuSymbolicParams, NumericLu, SymbolicLu};
use faer::sparse::linalg::SupernodalThreshold;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat, SymbolicSparseColMatRef};
use faer::{ColMut, Conj, Par, Side};
use nalgebra::{Matrix3, Vector2, Vector3};

/// A contact's compliance relative to the wall's mean inverse mass (for a contact of the mean
/// length): small enough that a resting contact's closing speed (this times g dt) is far below
/// what the outputs show, large enough that the Jacobian's condition number (about its
/// inverse) leaves Newton's steps eight good digits.
pub const COMPLIANCE: f64 = 1e-8;

/// Newton steps allowed per time step, the bounds' updates included; a time step that needs
/// more is counted as unconverged.
pub(super) const MAX_ITERATIONS: usize = 200;

/// Updates of the friction bounds that have not halved the best step since, after which the
/// bounds are taken as at their fixed point if that step is within [`ROUND_OFF_FLOOR`] times
/// the tolerance: on heavy blocks moving fast the round-off of the normal impulses (an ulp of
/// the contact's velocity over its compliance) stops the fixed point a few times above the
/// tolerance (the Ollantaytambo wall's fillers: 2e-12 to 5e-11 m/s against 5e-13 at dt =
/// 5e-4 s).
pub(super) const STALLED_UPDATES: usize = 4;

/// How far above the tolerance a stalled fixed point is still accepted: with the time-stepped
/// model's 1e-10 g dt, 1e-8 g dt, no more than the error the compliance itself makes.
pub(super) const ROUND_OFF_FLOOR: f64 = 100.0;

/// Coulomb's Newton steps tried where the fixed point on the bounds first stalls. Where it
/// converges from there it takes 2 or 3 steps in most cases, up to 20 in a few (the 2 x 8
/// running bond of docs/rocking-walls.md at dt = 1.25e-4 s); a failed try costs its steps, and
/// the fixed point's iterate is given back. 10 and 40 left more steps to the slower solvers.
const EARLY_NEWTON: usize = 20;

/// How the fixed point on the bounds ended.
enum FixedPoint {
    /// Settled in these Newton steps.
    Settled(usize),
    /// Stalled above the round-off floor after these steps.
    Stalled(usize),
    /// Used its budget.
    Exhausted,
}

/// Interior-point iterations allowed for one Tresca problem.
const MAX_INTERIOR_ITERATIONS: usize = 100;

/// Updates of the friction bounds allowed to the interior point's fixed point. On the uniform
/// 976-block wall of docs/rocking-walls.md, of the 18 steps it settled in its first 0.05 s, 16
/// took at most 9 updates and two took 12 and 20; the one it left cycles (the step after each
/// update back at 6e-4 m/s every third update) through all 30.
const MAX_INTERIOR_UPDATES: usize = 30;

/// Newton steps that finish each of the interior point's Tresca problems.
const MAX_POLISH: usize = 60;

/// The interior point's updates of the bounds taken plainly, b = mu p_n; from the next on,
/// each is Anderson's mix of the last [`ANDERSON_DEPTH`] + 1 (on the uniform 976-block wall
/// from the first update, 6 steps of its first 0.05 s were left unsolved, from the fifth or
/// ninth none, from the sixteenth one: docs/rocking-walls.md).
const PLAIN_UPDATES: usize = 4;

/// Residual differences the interior point's updates of the bounds are accelerated with
/// ([`Anderson`]).
const ANDERSON_DEPTH: usize = 3;

/// One contact's slack variables in the interior point: s (normal), z and r (tangential), and
/// for its constraints g_i >= 0 (s + u_n - target, s, r - u_t + z, r + u_t - z) their
/// slacks w_i and multipliers l_i; the last two only where the contact has friction.
struct Slacks {
    s: f64,
    z: f64,
    r: f64,
    bound: f64,
    w: [f64; 4],
    l: [f64; 4],
    /// g(x) - w, the constraints' residual (round-off: w is stepped, not recomputed).
    residual: [f64; 4],
    /// The complementarity each direction aims at.
    target: [f64; 4],
    /// The current direction: slacks' and multipliers' parts, and the local variables'.
    dw: [f64; 4],
    dl: [f64; 4],
    d_local: [f64; 3],
    /// Condensed right-hand sides of the local equations, and the force they add to the
    /// blocks' equations, kept between condense and expand.
    rhs_s: f64,
    tangent_rhs: [f64; 2],
    force: Vector2<f64>,
}

impl Slacks {
    /// A start inside the constraints by `margin` (m/s), every multiplier at `impulse` (N s)
    /// in the normal rows and at half the bound in the tangential ones.
    fn start(c: &Contact, bound: f64, u: Vector2<f64>, margin: f64, impulse: f64) -> Slacks {
        let mut k = Slacks {
            s: (c.target_m_s - u.x).max(0.0) + margin,
            z: 0.0,
            r: u.y.abs() + margin,
            bound,
            w: [0.0; 4],
            l: [impulse, impulse, 0.5 * bound, 0.5 * bound],
            residual: [0.0; 4],
            target: [0.0; 4],
            dw: [0.0; 4],
            dl: [0.0; 4],
            d_local: [0.0; 3],
            rhs_s: 0.0,
            tangent_rhs: [0.0; 2],
            force: Vector2::zeros(),
        };
        k.w = k.constraint_values(c, u);
        if !k.tangential() {
            k.l[2] = 0.0;
            k.l[3] = 0.0;
        }
        k
    }

    fn tangential(&self) -> bool {
        self.bound > 0.0
    }

    fn constraints(&self) -> usize {
        if self.tangential() {
            4
        } else {
            2
        }
    }

    fn constraint_values(&self, c: &Contact, u: Vector2<f64>) -> [f64; 4] {
        let g = [
            self.s + u.x - c.target_m_s,
            self.s,
            self.r - u.y + self.z,
            self.r + u.y - self.z,
        ];
        std::array::from_fn(|i| if i < self.constraints() { g[i] } else { 0.0 })
    }

    /// The constraints' total w l (divided by their count by the caller: the barrier's mu).
    fn gap(&self) -> f64 {
        (0..self.constraints()).map(|i| self.w[i] * self.l[i]).sum()
    }

    fn gap_after(&self, alpha: f64) -> f64 {
        (0..self.constraints())
            .map(|i| (self.w[i] + alpha * self.dw[i]) * (self.l[i] + alpha * self.dl[i]))
            .sum()
    }

    /// The impulse (normal, tangential) the multipliers put on the blocks.
    fn impulse(&self) -> Vector2<f64> {
        Vector2::new(self.l[0], self.l[3] - self.l[2])
    }

    /// The barrier's curvatures l / w, zero for constraints the contact does not have.
    fn curvatures(&self) -> [f64; 4] {
        std::array::from_fn(|i| {
            if i < self.constraints() {
                self.l[i] / self.w[i]
            } else {
                0.0
            }
        })
    }

    /// The contact's normal and tangential stiffness once its slacks are eliminated, in the
    /// closed forms that do not subtract (d1 (1 + eps d2) / (1 + eps (d1 + d2)) and 4 d3 d4 /
    /// (d3 + d4 + 4 eps d3 d4)).
    fn stiffness(&self, eps: f64) -> (f64, f64) {
        let [d1, d2, d3, d4] = self.curvatures();
        let kn = d1 * (1.0 + eps * d2) / (1.0 + eps * (d1 + d2));
        let kt = if self.tangential() {
            4.0 * d3 * d4 / (d3 + d4 + 4.0 * eps * d3 * d4)
        } else {
            0.0
        };
        (kn, kt)
    }

    /// Eliminates the local variables from this direction's equations: returns the force
    /// (normal, tangential) they add to the blocks' right-hand side.
    ///
    /// Written so that no curvature l / w multiplies a computed quantity: deep in the path
    /// they pass 1e19 while the blocks' rows stay near 1 / eps, and a product such as
    /// d3 dg3 would carry d3 times dg3's round-off into the impulses. With e_i = (target_i -
    /// l_i residual_i) / w_i, the normal force is (e1 (1/eps + d2) - d1 (R_s + e2)) / a_s
    /// (R_s = l1 + l2 - s / eps the balance of s, a_s = 1/eps + d1 + d2); the tangential one
    /// is R_z - X / (1 + eps H) (R_z = l3 - l4 - z / eps, H = 4 d3 d4 / (d3 + d4), X = R_z -
    /// (d3 - d4) / (d3 + d4) R_r + 2 d4 e3 / (d3 + d4) - 2 d3 e4 / (d3 + d4), R_r = l3 + l4 -
    /// b the balance of r), each e_i / (d3 + d4) formed as (target_i - l_i residual_i) /
    /// (l_i + w_i d_j), j the other tangential constraint.
    fn condense(&mut self, eps: f64) -> Vector2<f64> {
        let d = self.curvatures();
        let n = self.constraints();
        let lifted: [f64; 4] = std::array::from_fn(|i| {
            if i < n {
                self.target[i] - self.l[i] * self.residual[i]
            } else {
                0.0
            }
        });
        let e: [f64; 4] = std::array::from_fn(|i| if i < n { lifted[i] / self.w[i] } else { 0.0 });
        let a_s = 1.0 / eps + d[0] + d[1];
        let r_s = self.l[0] + self.l[1] - self.s / eps;
        self.rhs_s = r_s + e[0] + e[1];
        let normal = (e[0] * (1.0 / eps + d[1]) - d[0] * (r_s + e[1])) / a_s;
        if !self.tangential() {
            self.force = Vector2::new(normal, 0.0);
            return self.force;
        }
        let (sum, h) = tangential_sum_and_harmonic(d);
        // e_3 / (d3 + d4) and e_4 / (d3 + d4).
        let (e3_share, e4_share) = (
            lifted[2] / (self.l[2] + self.w[2] * d[3]),
            lifted[3] / (self.l[3] + self.w[3] * d[2]),
        );
        let r_z = self.l[2] - self.l[3] - self.z / eps;
        let r_r = self.l[2] + self.l[3] - self.bound;
        let x = r_z - (d[2] - d[3]) / sum * r_r + 2.0 * d[3] * e3_share - 2.0 * d[2] * e4_share;
        self.tangent_rhs = [x, r_r / sum + e3_share + e4_share];
        self.force = Vector2::new(normal, r_z - x / (1.0 + eps * h));
        self.force
    }

    /// Recovers the local variables' and the constraints' parts of the direction from the
    /// contact's relative velocity along it, `du`. The impulse changes by the f - K du that
    /// the blocks' system assumed; each multiplier comes from its complementarity (its change
    /// good to l / w times its slack's round-off) only where l / w is under 1 / eps, the
    /// stiffest the blocks' rows get, and from the balances of s and r elsewhere.
    fn expand(&mut self, eps: f64, du: Vector2<f64>) {
        let d = self.curvatures();
        let (kn, kt) = self.stiffness(eps);
        let dp = self.force - Vector2::new(kn * du.x, kt * du.y);
        let ds = (self.rhs_s - d[0] * du.x) / (1.0 / eps + d[0] + d[1]);
        let (mut dz, mut dr) = (0.0, 0.0);
        if self.tangential() {
            let (sum, h) = tangential_sum_and_harmonic(d);
            let [x, r0] = self.tangent_rhs;
            dz = eps * (x + h * du.y) / (1.0 + eps * h);
            dr = r0 + (d[2] - d[3]) / sum * (du.y - dz);
        }
        self.d_local = [ds, dz, dr];
        let dg = [ds + du.x, ds, dr - du.y + dz, dr + du.y - dz];
        let n = self.constraints();
        self.dw = std::array::from_fn(|i| if i < n { dg[i] + self.residual[i] } else { 0.0 });
        let complementary = |k: &Slacks, i: usize| (k.target[i] - k.l[i] * k.dw[i]) / k.w[i];
        let stiff = |i: usize| d[i] * eps > 1.0;
        self.dl = [0.0; 4];
        self.dl[0] = dp.x;
        self.dl[1] = if stiff(1) {
            // s's balance: ds / eps - dl1 - dl2 = l1 + l2 - s / eps.
            ds / eps - dp.x - (self.l[0] + self.l[1] - self.s / eps)
        } else {
            complementary(self, 1)
        };
        if self.tangential() {
            if stiff(2) && stiff(3) {
                // r's balance: dl3 + dl4 = b - l3 - l4.
                let r_balance = self.bound - self.l[2] - self.l[3];
                self.dl[2] = 0.5 * (r_balance - dp.y);
                self.dl[3] = 0.5 * (r_balance + dp.y);
            } else if d[2] <= d[3] {
                self.dl[2] = complementary(self, 2);
                self.dl[3] = self.dl[2] + dp.y;
            } else {
                self.dl[3] = complementary(self, 3);
                self.dl[2] = self.dl[3] - dp.y;
            }
        }
    }

    /// The longest step along every contact's direction that keeps every slack and
    /// multiplier positive, at most 1.
    fn step_to_boundary(slacks: &[Slacks]) -> f64 {
        let mut alpha: f64 = 1.0;
        for k in slacks {
            for i in 0..k.constraints() {
                if k.dw[i] < 0.0 {
                    alpha = alpha.min(-k.w[i] / k.dw[i]);
                }
                if k.dl[i] < 0.0 {
                    alpha = alpha.min(-k.l[i] / k.dl[i]);
                }
            }
        }
        alpha
    }

    fn take(&mut self, alpha: f64) {
        self.s += alpha * self.d_local[0];
        self.z += alpha * self.d_local[1];
        self.r += alpha * self.d_local[2];
        for i in 0..self.constraints() {
            self.w[i] += alpha * self.dw[i];
            self.l[i] += alpha * self.dl[i];
        }
    }
}

/// Of the tangential curvatures d3, d4 (`d[2]`, `d[3]`): their sum and H = 4 d3 d4 / (d3 +
/// d4), the curvature r's elimination leaves on u_t - z.
fn tangential_sum_and_harmonic(d: [f64; 4]) -> (f64, f64) {
    let sum = d[2] + d[3];
    (sum, 4.0 * d[2] * d[3] / sum)
}

/// One moving block's share of a contact: the rows of the contact's (normal, tangential)
/// relative velocity for that block's (x, y, rotation) velocity.
#[derive(Debug, Clone, Copy)]
pub struct Part {
    /// The block.
    pub body: usize,
    /// Normal and tangential rows.
    pub rows: [Vector3<f64>; 2],
}

/// A contact of the step: the moving blocks it involves, the normal velocity its restitution
/// law asks for, its friction coefficient and its compliance.
#[derive(Debug, Clone)]
pub struct Contact {
    /// One or two moving blocks.
    pub parts: [Option<Part>; 2],
    /// Normal relative velocity wanted after the step, -e times the approach (m/s).
    pub target_m_s: f64,
    /// Coulomb coefficient (0: frictionless).
    pub friction: f64,
    /// eps (m/s per N s).
    pub compliance: f64,
}

impl Contact {
    /// The contact's (normal, tangential) relative velocity when the blocks move at `v`.
    pub(super) fn velocity(&self, v: &[Vector3<f64>]) -> Vector2<f64> {
        let mut u = Vector2::zeros();
        for p in self.parts.iter().flatten() {
            u += Vector2::new(p.rows[0].dot(&v[p.body]), p.rows[1].dot(&v[p.body]));
        }
        u
    }

    /// The normal impulse (N s) at velocities `v`.
    fn normal_impulse(&self, v: &[Vector3<f64>]) -> f64 {
        (-(self.velocity(v).x - self.target_m_s) / self.compliance).max(0.0)
    }

    /// The impulse (normal, tangential; N s) where the contact's relative velocity is `u`,
    /// the tangential one within +- `bound`, and whether it sticks (within the bound).
    fn impulse_at(&self, u: Vector2<f64>, bound: f64) -> (Vector2<f64>, bool) {
        let pn = (-(u.x - self.target_m_s) / self.compliance).max(0.0);
        let trial = -u.y / self.compliance;
        if trial.abs() <= bound {
            (Vector2::new(pn, trial), true)
        } else {
            (Vector2::new(pn, trial.signum() * bound), false)
        }
    }
}

/// Each contact's impulse at the velocities `v`, under the bounds they give.
fn impulses_at(contacts: &[Contact], v: &[Vector3<f64>], impulses: &mut [Vector2<f64>]) {
    for (c, p) in contacts.iter().zip(impulses.iter_mut()) {
        let bound = c.friction * c.normal_impulse(v);
        *p = c.impulse_at(c.velocity(v), bound).0;
    }
}

/// One step's contact problem, as both of its solvers take it (this one and `wall_dual.rs`).
pub struct StepProblem<'a> {
    /// Each block's (m, m, I); a block that does not move has no part in any contact and keeps
    /// its free velocity.
    pub mass: &'a [Vector3<f64>],
    /// Turns a change of a block's velocity into one of its points': (1, 1, its half
    /// diagonal).
    pub reach: &'a [Vector3<f64>],
    /// The blocks' velocities without contacts.
    pub v_free: &'a [Vector3<f64>],
    /// The step's contacts.
    pub contacts: &'a [Contact],
    /// The iteration stops once no block's velocity (through `reach`) changes by more than
    /// this under the friction bounds those velocities give (m/s).
    pub tolerance_m_s: f64,
}

/// Which Jacobian a Newton step solves.
#[derive(Clone, Copy)]
enum Jacobian {
    /// Tresca's, symmetric (the friction bounds fixed).
    Tresca,
    /// Coulomb's, unsymmetric (the bounds following the normal impulses).
    Coulomb,
}

/// Why a step's Newton iteration stopped without converging.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stall {
    /// It used its iterations.
    Iterations,
    /// The Jacobian could not be factorised.
    Singular,
}

/// A sparse Cholesky factorisation, supernodal: faer would pick its simplicial form for
/// Tresca's Jacobian of walls of a hundred blocks, whose scalar loops took nearly half of a run
/// (docs/rocking-walls.md). Its values and working memory are made once per pattern (per run
/// here, per step in `wall_dual.rs`).
pub(super) struct Cholesky {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    memory: MemBuffer,
}

impl Cholesky {
    pub(super) fn new(pattern: SymbolicSparseColMatRef<'_, usize>) -> Cholesky {
        let symbolic = factorize_symbolic_cholesky(
            pattern,
            Side::Lower,
            SymmetricOrdering::Amd,
            CholeskySymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .expect("a symbolic Cholesky factorisation of a pattern that holds its diagonal");
        let memory = MemBuffer::new(
            symbolic
                .factorize_numeric_llt_scratch::<f64>(Par::Seq, Default::default())
                .or(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq)),
        );
        Cholesky {
            values: vec![0.0; symbolic.len_val()],
            symbolic,
            memory,
        }
    }

    /// Factorises `matrix` (its lower triangle); false if it is not positive definite.
    pub(super) fn factorise(&mut self, matrix: SparseColMatRef<'_, usize, f64>) -> bool {
        self.symbolic
            .factorize_numeric_llt(
                &mut self.values,
                matrix,
                Side::Lower,
                Default::default(),
                Par::Seq,
                MemStack::new(&mut self.memory),
                Default::default(),
            )
            .is_ok()
    }

    /// Solves the last factorised system in place.
    pub(super) fn solve(&mut self, rhs: &mut [f64]) {
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            ColMut::from_slice_mut(rhs).as_mat_mut(),
            Par::Seq,
            MemStack::new(&mut self.memory),
        );
    }
}

/// A sparse LU factorisation with partial pivoting, supernodal, for Coulomb's unsymmetric
/// Jacobian: as for [`Cholesky`], faer picks its simplicial form on walls of a hundred blocks,
/// where Coulomb's Newton factorises hundreds of times a step in the steps that are hard (0.77
/// ms a factorisation against 0.25 ms supernodal on a 105-block wall, docs/rocking-walls.md).
/// Its numeric part and working memory are made once per run.
struct SparseLu {
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    memory: MemBuffer,
}

impl SparseLu {
    fn new(pattern: SymbolicSparseColMatRef<'_, usize>) -> SparseLu {
        let symbolic = factorize_symbolic_lu(
            pattern,
            LuSymbolicParams {
                supernodal_flop_ratio_threshold: SupernodalThreshold::FORCE_SUPERNODAL,
                ..Default::default()
            },
        )
        .expect("a symbolic LU factorisation of a pattern that holds its diagonal");
        let memory = MemBuffer::new(
            symbolic
                .factorize_numeric_lu_scratch::<f64>(Par::Seq, Default::default())
                .or(symbolic.solve_in_place_scratch::<f64>(1, Par::Seq)),
        );
        SparseLu {
            symbolic,
            numeric: NumericLu::new(),
            memory,
        }
    }

    /// Factorises `matrix` and solves it in place for `rhs`; false if it is singular.
    fn solve(&mut self, matrix: SparseColMatRef<'_, usize, f64>, rhs: &mut [f64]) -> bool {
        let Ok(lu) = self.symbolic.factorize_numeric_lu(
            &mut self.numeric,
            matrix,
            Par::Seq,
            MemStack::new(&mut self.memory),
            Default::default(),
        ) else {
            return false;
        };
        lu.solve_in_place_with_conj(
            Conj::No,
            ColMut::from_slice_mut(rhs).as_mat_mut(),
            Par::Seq,
            MemStack::new(&mut self.memory),
        );
        true
    }
}

/// The solver of a run: the wall's sparsity pattern and its symbolic factorisation, and the
/// working memory kept from one step to the next.
pub struct WallNewton {
    /// For each block, the blocks it can touch and itself, sorted: block b's columns hold the
    /// rows of these blocks in this order.
    neighbours: Vec<Vec<usize>>,
    symbolic: SymbolicSparseColMat<usize>,
    cholesky: Cholesky,
    lu: SparseLu,
    start: Vec<Vector3<f64>>,
    stalled_at: Vec<Vector3<f64>>,
    values: Vec<f64>,
    step: Vec<Vector3<f64>>,
    rhs: Vec<f64>,
    gradient: Vec<Vector3<f64>>,
    bounds: Vec<f64>,
    lines: Vec<(Vector2<f64>, Vector2<f64>)>,
}

impl WallNewton {
    /// A solver for `n` blocks of which the pairs in `touching` can share a contact.
    pub fn new(n: usize, touching: impl IntoIterator<Item = (usize, usize)>) -> WallNewton {
        let mut neighbours: Vec<Vec<usize>> = (0..n).map(|b| vec![b]).collect();
        for (a, b) in touching {
            if a != b {
                neighbours[a].push(b);
                neighbours[b].push(a);
            }
        }
        for list in &mut neighbours {
            list.sort_unstable();
            list.dedup();
        }
        let mut col_ptr = Vec::with_capacity(3 * n + 1);
        let mut row_idx = Vec::new();
        col_ptr.push(0);
        for list in &neighbours {
            for _ in 0..3 {
                for &a in list {
                    row_idx.extend(3 * a..3 * a + 3);
                }
                col_ptr.push(row_idx.len());
            }
        }
        let nnz = row_idx.len();
        let symbolic = SymbolicSparseColMat::new_checked(3 * n, 3 * n, col_ptr, None, row_idx);
        let cholesky = Cholesky::new(symbolic.as_ref());
        let lu = SparseLu::new(symbolic.as_ref());
        WallNewton {
            neighbours,
            symbolic,
            cholesky,
            lu,
            start: Vec::new(),
            stalled_at: Vec::new(),
            values: vec![0.0; nnz],
            step: vec![Vector3::zeros(); n],
            rhs: vec![0.0; 3 * n],
            gradient: vec![Vector3::zeros(); n],
            bounds: Vec::new(),
            lines: Vec::new(),
        }
    }

    /// Adds a 3 x 3 block at (row block a, column block b).
    fn add(&mut self, a: usize, b: usize, m: &Matrix3<f64>) {
        let col = &self.neighbours[b];
        let ia = col
            .binary_search(&a)
            .expect("a pair of blocks that can touch");
        let stride = 3 * col.len();
        let start = self.symbolic.col_ptr()[3 * b] + 3 * ia;
        for c in 0..3 {
            for r in 0..3 {
                self.values[start + c * stride + r] += m[(r, c)];
            }
        }
    }

    /// Fills the matrix with M + sum over contacts of n n' k_n + t t' k_t - t n' k_s (n, t a
    /// contact's normal and tangential rows), each contact's stiffnesses (k_n, k_t, k_s) from
    /// `stiffness` given its index (`None`: the contact adds nothing). Tresca's Jacobian, the
    /// interior point's system and, with k_s the coupling of a sliding contact's friction to
    /// its normal velocity, Coulomb's Jacobian.
    fn assemble(
        &mut self,
        mass: &[Vector3<f64>],
        contacts: &[Contact],
        mut stiffness: impl FnMut(usize, &Contact) -> Option<(f64, f64, f64)>,
    ) {
        self.values.iter_mut().for_each(|x| *x = 0.0);
        for (i, m) in mass.iter().enumerate() {
            self.add(i, i, &Matrix3::from_diagonal(m));
        }
        for (s, c) in contacts.iter().enumerate() {
            let Some((kn, kt, ks)) = stiffness(s, c) else {
                continue;
            };
            for a in c.parts.iter().flatten() {
                for b in c.parts.iter().flatten() {
                    let block = a.rows[0] * b.rows[0].transpose() * kn
                        + a.rows[1] * b.rows[1].transpose() * kt
                        - a.rows[1] * b.rows[0].transpose() * ks;
                    self.add(a.body, b.body, &block);
                }
            }
        }
    }

    /// The friction bounds mu p_n that the velocities `v` give.
    fn bounds_from(&mut self, contacts: &[Contact], v: &[Vector3<f64>]) {
        self.bounds.clear();
        self.bounds
            .extend(contacts.iter().map(|c| c.friction * c.normal_impulse(v)));
    }

    /// The potential's gradient M (v - v_free) - sum H' p(v) under the current bounds.
    fn gradient_at(&mut self, step: &StepProblem<'_>, v: &[Vector3<f64>]) {
        let StepProblem {
            mass,
            v_free,
            contacts,
            ..
        } = *step;
        for (i, g) in self.gradient.iter_mut().enumerate() {
            *g = mass[i].component_mul(&(v[i] - v_free[i]));
        }
        for (c, &bound) in contacts.iter().zip(&self.bounds) {
            let (p, _) = c.impulse_at(c.velocity(v), bound);
            for part in c.parts.iter().flatten() {
                self.gradient[part.body] -= part.rows[0] * p.x + part.rows[1] * p.y;
            }
        }
    }

    /// The Jacobian of the gradient at `v` (the contacts closing or at rest add their normal
    /// stiffness, those sticking their tangential one), factorised in `self.cholesky`; false
    /// if it is not positive definite.
    fn jacobian(&mut self, step: &StepProblem<'_>, v: &[Vector3<f64>]) -> bool {
        let StepProblem { mass, contacts, .. } = *step;
        // The bounds lent out while the blocks are added to the matrix beside them.
        let bounds = std::mem::take(&mut self.bounds);
        self.assemble(mass, contacts, |s, c| {
            let u = c.velocity(v);
            // At rest (u_n exactly on its target) the contact counts as closed: a resting
            // wall's first step starts there, and an open Jacobian would send it into free fall.
            let closed = u.x <= c.target_m_s;
            let (_, sticks) = c.impulse_at(u, bounds[s]);
            let stiffness = 1.0 / c.compliance;
            (closed || sticks).then_some((
                if closed { stiffness } else { 0.0 },
                if sticks { stiffness } else { 0.0 },
                0.0,
            ))
        });
        self.bounds = bounds;
        let matrix = SparseColMatRef::new(self.symbolic.as_ref(), &self.values);
        self.cholesky.factorise(matrix)
    }

    /// The step length along `self.step` from `v` that minimises the potential: the root of
    /// its derivative, piecewise linear and increasing in the length, by Newton's method on
    /// that derivative safeguarded by bisection (exact in a few steps: a full step where the
    /// contacts' states it assumed hold), stopping where the derivative is zero within the
    /// round-off of its sum.
    fn line_minimum(&mut self, step: &StepProblem<'_>, v: &[Vector3<f64>]) -> f64 {
        let StepProblem {
            mass,
            v_free,
            contacts,
            ..
        } = *step;
        let (mut a, mut b) = (0.0, 0.0);
        for (i, d) in self.step.iter().enumerate() {
            let md = mass[i].component_mul(d);
            a += md.dot(&(v[i] - v_free[i]));
            b += md.dot(d);
        }
        // A contact's velocity is linear in the blocks': along the step it is u + alpha w,
        // w the contact's velocity for the step itself.
        self.lines.clear();
        self.lines.extend(
            contacts
                .iter()
                .map(|c| (c.velocity(v), c.velocity(&self.step))),
        );
        let derivative = |alpha: f64| {
            let (mut g, mut h) = (a + b * alpha, b);
            let mut scale = a.abs() + (b * alpha).abs();
            for ((c, &bound), (u, w)) in contacts.iter().zip(&self.bounds).zip(&self.lines) {
                let (p, sticks) = c.impulse_at(u + alpha * w, bound);
                g -= p.dot(w);
                scale += (p.x * w.x).abs() + (p.y * w.y).abs();
                if p.x > 0.0 {
                    h += w.x * w.x / c.compliance;
                }
                if sticks {
                    h += w.y * w.y / c.compliance;
                }
            }
            (g, h, scale)
        };
        let (mut lo, mut hi) = (0.0, f64::INFINITY);
        let mut alpha = 1.0;
        for _ in 0..100 {
            let (g, h, scale) = derivative(alpha);
            // Zero within the round-off of its own sum: the minimum, as far as the derivative
            // can tell. Going on would follow the round-off (on a 105-block running bond a
            // third of the line searches went on for 40 to 100 steps of it).
            if g.abs() <= f64::EPSILON * scale {
                break;
            }
            if g < 0.0 {
                lo = alpha;
            } else {
                hi = alpha;
            }
            let mut next = alpha - g / h;
            if !(next > lo && next < hi) {
                next = if hi.is_finite() {
                    0.5 * (lo + hi)
                } else {
                    2.0 * alpha
                };
            }
            if next == alpha || hi - lo <= 4.0 * f64::EPSILON * hi {
                break;
            }
            alpha = next;
        }
        alpha
    }

    /// Coulomb's residual at `v`, the gradient with the bounds taken from `v` itself (left in
    /// `self.gradient`), and its size 1/2 F' M^-1 F.
    fn residual(&mut self, step: &StepProblem<'_>, v: &[Vector3<f64>]) -> f64 {
        self.bounds_from(step.contacts, v);
        self.gradient_at(step, v);
        0.5 * self
            .gradient
            .iter()
            .zip(step.mass)
            .map(|(g, m)| g.component_div(m).dot(g))
            .sum::<f64>()
    }

    /// The Jacobian of Coulomb's residual at `v`, into `self.values` (the step factorises it):
    /// Tresca's, plus at each contact that slides the dependence of its friction, s mu p_n, on
    /// its normal velocity (which makes it unsymmetric).
    fn coulomb_jacobian(&mut self, step: &StepProblem<'_>, v: &[Vector3<f64>]) {
        self.assemble(step.mass, step.contacts, |_, c| {
            let u = c.velocity(v);
            let closed = u.x <= c.target_m_s;
            let (_, sticks) = c.impulse_at(u, c.friction * c.normal_impulse(v));
            let stiffness = 1.0 / c.compliance;
            // Sliding in direction s = sign(u_t): p_t = s mu (u_n - target) / eps.
            (closed || sticks).then(|| {
                (
                    if closed { stiffness } else { 0.0 },
                    if sticks { stiffness } else { 0.0 },
                    if closed && !sticks {
                        u.y.signum() * c.friction * stiffness
                    } else {
                        0.0
                    },
                )
            })
        });
    }

    /// Solves `self.step` from the gradient and the Jacobian just made: Tresca's, already
    /// factorised in `self.cholesky`, or Coulomb's, factorised here; false if Coulomb's is
    /// singular or the step is not finite.
    fn newton_step(&mut self, jacobian: Jacobian) -> bool {
        for (i, g) in self.gradient.iter().enumerate() {
            for k in 0..3 {
                self.rhs[3 * i + k] = -g[k];
            }
        }
        match jacobian {
            Jacobian::Coulomb => {
                let matrix = SparseColMatRef::new(self.symbolic.as_ref(), &self.values);
                if !self.lu.solve(matrix, &mut self.rhs) {
                    return false;
                }
            }
            Jacobian::Tresca => self.cholesky.solve(&mut self.rhs),
        }
        if self.rhs.iter().any(|x| !x.is_finite()) {
            return false;
        }
        for (d, s) in self.step.iter_mut().zip(self.rhs.chunks_exact(3)) {
            *d = Vector3::new(s[0], s[1], s[2]);
        }
        true
    }

    /// One Newton step on Tresca's problem under the current bounds, from `v` with its
    /// gradient already in `self.gradient`, taken to the exact minimum along it: `v` moves by
    /// the returned length times `self.step`.
    fn tresca_step(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
    ) -> Result<f64, Stall> {
        if !self.jacobian(step, v) || !self.newton_step(Jacobian::Tresca) {
            return Err(Stall::Singular);
        }
        let alpha = self.line_minimum(step, v);
        for (vi, d) in v.iter_mut().zip(&self.step) {
            *vi += alpha * d;
        }
        Ok(alpha)
    }

    /// Coulomb's fixed point on Tresca's problems, the first way a step is solved (see the
    /// module's comment), within `budget` Newton steps; with `stop_at_stall` it ends where it
    /// first stalls above its round-off floor.
    fn bounds_fixed_point(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
        budget: usize,
        stop_at_stall: bool,
    ) -> Result<FixedPoint, Stall> {
        let tolerance_m_s = step.tolerance_m_s;
        let mut keep_bounds = false;
        // The smallest step seen right after the bounds moved, and how many such steps since
        // have not halved it.
        let (mut best, mut stalled) = (f64::INFINITY, 0);
        for iteration in 1..=budget {
            if !keep_bounds {
                self.bounds_from(step.contacts, v);
            }
            self.gradient_at(step, v);
            let change = self.tresca_change(step, v)?;
            // A small step under bounds just taken from the velocities: Coulomb's fixed point.
            // A small step under older bounds: Tresca's problem solved, the bounds move.
            let settled = change <= tolerance_m_s;
            if !keep_bounds {
                if settled {
                    return Ok(FixedPoint::Settled(iteration));
                }
                // The bounds' fixed point converges linearly until the round-off of p_n =
                // -u_n / eps (an ulp of u_n over eps) moves the bounds by as much as it gains;
                // near the tolerance that floor is where the iteration stops.
                if change < 0.5 * best {
                    (best, stalled) = (change, 0);
                } else {
                    stalled += 1;
                }
                if stalled >= STALLED_UPDATES {
                    if best <= ROUND_OFF_FLOOR * tolerance_m_s {
                        return Ok(FixedPoint::Settled(iteration));
                    }
                    if stop_at_stall {
                        return Ok(FixedPoint::Stalled(iteration));
                    }
                }
            }
            keep_bounds = !settled;
        }
        Ok(FixedPoint::Exhausted)
    }

    /// Semismooth Newton on Coulomb's law itself, F(v) = 0 with the bounds following the
    /// normal impulses, from where the fixed point stopped: each step solves the unsymmetric
    /// Jacobian (faer's sparse LU on the same pattern) and backtracks until 1/2 F' M^-1 F falls
    /// (Armijo). Where no step along Newton's direction lowers it (a kink of some contact's
    /// law lies within 1e-10 of the step), the iteration ends if Newton's step is within
    /// [`ROUND_OFF_FLOOR`] times the tolerance (the round-off floor, as for the fixed point),
    /// and otherwise takes one step of Tresca's problem under the current bounds instead,
    /// which moves the iterate off the kink. Returns the Newton steps used (at most `budget`),
    /// or why it stalled.
    fn coulomb(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
        budget: usize,
    ) -> Result<usize, Stall> {
        let (reach, tolerance_m_s) = (step.reach, step.tolerance_m_s);
        let mut size_now = self.residual(step, v);
        for iteration in 1..=budget {
            self.coulomb_jacobian(step, v);
            if !self.newton_step(Jacobian::Coulomb) {
                return Err(Stall::Singular);
            }
            let change = self
                .step
                .iter()
                .zip(reach)
                .map(|(d, r)| d.component_mul(r).abs().max())
                .fold(0.0, f64::max);
            if change <= tolerance_m_s {
                for (vi, d) in v.iter_mut().zip(&self.step) {
                    *vi += d;
                }
                return Ok(iteration);
            }
            self.start.clear();
            self.start.extend_from_slice(v);
            let mut alpha = 1.0;
            loop {
                for ((vi, s), d) in v.iter_mut().zip(&self.start).zip(&self.step) {
                    *vi = s + alpha * d;
                }
                let size = self.residual(step, v);
                // Armijo's condition: along Newton's direction 1/2 F' M^-1 F falls at twice
                // its value per unit step where F is smooth.
                if size <= (1.0 - 2e-4 * alpha) * size_now {
                    size_now = size;
                    break;
                }
                alpha *= 0.5;
                if alpha >= 1e-10 {
                    continue;
                }
                v.copy_from_slice(&self.start);
                if change <= ROUND_OFF_FLOOR * tolerance_m_s {
                    return Ok(iteration);
                }
                // Tresca's step under the bounds of `v`, as `residual` leaves them.
                self.residual(step, v);
                self.tresca_step(step, v)?;
                size_now = self.residual(step, v);
                break;
            }
        }
        Err(Stall::Iterations)
    }

    /// Tresca's problem under `self.bounds` by a primal-dual interior point in the blocks'
    /// velocities (Mehrotra's predictor-corrector), from `v`, which it leaves near the minimum
    /// for Newton to finish. Each contact's terms of the potential become slack variables with
    /// linear constraints: the normal one s^2 / (2 eps) with s >= target - u_n and s >= 0, the
    /// tangential one z^2 / (2 eps) + b r with r >= |u_t - z| (its inf-convolution form). The
    /// barrier smooths every kink at once, so the number of iterations does not grow with the
    /// contacts that change state within a step, where Newton's exact line search crawls from
    /// kink to kink; each iteration eliminates a contact's slacks on the spot and solves one
    /// system of Tresca's pattern, M + sum k_n n n' + k_t t t'. It stops once the barrier's
    /// mean complementarity is 1e-10 of its start and the blocks balance to 1e-9 g dt (or the
    /// complementarity is at 1e-14), or at its last iteration if that is within 1e-8 of its
    /// start: beyond that the curvatures outrun the factorisation's digits. Returns its
    /// iterations.
    fn tresca_interior(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
        g_dt: f64,
    ) -> Result<usize, Stall> {
        let StepProblem {
            mass,
            v_free,
            contacts,
            ..
        } = *step;
        let mean_mass = mass.iter().map(|m| m.x).sum::<f64>() / mass.len() as f64;
        let mut slacks: Vec<Slacks> = contacts
            .iter()
            .zip(&self.bounds)
            .map(|(c, &b)| Slacks::start(c, b, c.velocity(v), g_dt, mean_mass * g_dt))
            .collect();
        let count: f64 = slacks.iter().map(|k| k.constraints() as f64).sum();
        let mut direction = vec![Vector3::zeros(); v.len()];
        let (mut first_gap, mut last_gap) = (0.0, f64::INFINITY);
        for iteration in 1..=MAX_INTERIOR_ITERATIONS {
            let gap = slacks.iter().map(Slacks::gap).sum::<f64>() / count;
            // The balance of the blocks under the impulses the multipliers give.
            for (i, g) in self.gradient.iter_mut().enumerate() {
                *g = mass[i].component_mul(&(v[i] - v_free[i]));
            }
            for (c, k) in contacts.iter().zip(&slacks) {
                let p = k.impulse();
                for part in c.parts.iter().flatten() {
                    self.gradient[part.body] -= part.rows[0] * p.x + part.rows[1] * p.y;
                }
            }
            let imbalance = self
                .gradient
                .iter()
                .zip(mass)
                .map(|(g, m)| g.component_div(m).abs().max())
                .fold(0.0, f64::max);
            if iteration == 1 {
                first_gap = gap;
            } else if gap <= 1e-10 * first_gap
                && (imbalance <= 1e-9 * g_dt || gap <= 1e-14 * first_gap)
            {
                return Ok(iteration);
            }
            for (c, k) in contacts.iter().zip(slacks.iter_mut()) {
                let g = k.constraint_values(c, c.velocity(v));
                k.residual = std::array::from_fn(|i| g[i] - k.w[i]);
            }
            self.assemble(mass, contacts, |s, c| {
                let (kn, kt) = slacks[s].stiffness(c.compliance);
                Some((kn, kt, 0.0))
            });
            let matrix = SparseColMatRef::new(self.symbolic.as_ref(), &self.values);
            if !self.cholesky.factorise(matrix) {
                // Deep in the path the barrier's curvatures span more than the factorisation's
                // digits; Newton finishes from there.
                return if gap <= 1e-10 * first_gap {
                    Ok(iteration)
                } else {
                    Err(Stall::Singular)
                };
            }
            // Predictor: the affine direction, complementarity aimed at zero.
            for k in slacks.iter_mut() {
                k.target = std::array::from_fn(|i| -k.w[i] * k.l[i]);
            }
            self.interior_direction(contacts, &mut slacks, &mut direction);
            let affine = Slacks::step_to_boundary(&slacks);
            let gap_affine = slacks.iter().map(|k| k.gap_after(affine)).sum::<f64>() / count;
            let sigma = (gap_affine / gap).powi(3).min(1.0);
            // Corrector: centred, with the predictor's second-order term.
            for k in slacks.iter_mut() {
                k.target =
                    std::array::from_fn(|i| sigma * gap - k.w[i] * k.l[i] - k.dw[i] * k.dl[i]);
            }
            self.interior_direction(contacts, &mut slacks, &mut direction);
            let alpha = (0.995 * Slacks::step_to_boundary(&slacks)).min(1.0);
            for (vi, d) in v.iter_mut().zip(&direction) {
                *vi += alpha * d;
            }
            for k in slacks.iter_mut() {
                k.take(alpha);
            }
            last_gap = gap;
        }
        if last_gap <= 1e-8 * first_gap {
            return Ok(MAX_INTERIOR_ITERATIONS);
        }
        Err(Stall::Iterations)
    }

    /// The interior point's direction for the complementarity targets in `slacks`: the
    /// blocks' part in `direction`, each contact's in its slacks.
    fn interior_direction(
        &mut self,
        contacts: &[Contact],
        slacks: &mut [Slacks],
        direction: &mut [Vector3<f64>],
    ) {
        for (i, g) in self.gradient.iter().enumerate() {
            for q in 0..3 {
                self.rhs[3 * i + q] = -g[q];
            }
        }
        for (c, k) in contacts.iter().zip(slacks.iter_mut()) {
            let force = k.condense(c.compliance);
            for part in c.parts.iter().flatten() {
                let f = part.rows[0] * force.x + part.rows[1] * force.y;
                for q in 0..3 {
                    self.rhs[3 * part.body + q] += f[q];
                }
            }
        }
        self.cholesky.solve(&mut self.rhs);
        for (d, x) in direction.iter_mut().zip(self.rhs.chunks_exact(3)) {
            *d = Vector3::new(x[0], x[1], x[2]);
        }
        for (c, k) in contacts.iter().zip(slacks.iter_mut()) {
            k.expand(c.compliance, c.velocity(direction));
        }
    }

    /// Coulomb's law with each Tresca problem solved by the interior point and finished by
    /// Newton, the bounds then moved to mu p_n (for the first [`PLAIN_UPDATES`] updates, then
    /// by Anderson's mix of the last few: the plain update can cycle), until a Newton step
    /// under fresh bounds is within the fixed point's round-off floor, or Coulomb's Newton
    /// converges from there in [`EARLY_NEWTON`] steps: the last way a step is solved before
    /// Gauss-Seidel (docs/rocking-walls.md). Returns the Newton and interior iterations used.
    pub(super) fn solve_interior(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
        impulses: &mut [Vector2<f64>],
    ) -> Result<usize, Stall> {
        let StepProblem {
            contacts,
            tolerance_m_s,
            ..
        } = *step;
        // The tolerance is 1e-10 g dt (`moreau_wall.rs`): the velocity a step's gravity gives
        // sets the slacks' first margins.
        let g_dt = tolerance_m_s * 1e10;
        let mut used = 0;
        let mut anderson = Anderson::new(ANDERSON_DEPTH);
        let mut tried = Vec::with_capacity(contacts.len());
        self.bounds_from(contacts, v);
        for update in 1..=MAX_INTERIOR_UPDATES {
            tried.clone_from(&self.bounds);
            used += self.tresca_interior(step, v, g_dt)?;
            for _ in 0..MAX_POLISH {
                self.gradient_at(step, v);
                used += 1;
                if self.tresca_change(step, v)? <= tolerance_m_s {
                    break;
                }
            }
            self.bounds_from(contacts, v);
            anderson.push(&tried, &self.bounds);
            self.gradient_at(step, v);
            used += 1;
            let fresh = self.tresca_change(step, v)?;
            let mut done = fresh <= ROUND_OFF_FLOOR * tolerance_m_s;
            if !done {
                // As after the fixed point's stall: Coulomb's Newton from this iterate.
                if let Some(n) = self.try_coulomb(step, v) {
                    used += n;
                    done = true;
                }
            }
            if done {
                impulses_at(contacts, v, impulses);
                return Ok(used);
            }
            if update <= PLAIN_UPDATES {
                self.bounds_from(contacts, v);
            } else {
                anderson.next(&mut self.bounds);
                for b in &mut self.bounds {
                    *b = b.max(0.0);
                }
            }
        }
        Err(Stall::Iterations)
    }

    /// Coulomb's Newton from `v` for at most [`EARLY_NEWTON`] steps, and the steps it took;
    /// where it does not converge, `v` is given back as it came (Newton's last iterate may
    /// lie far from any answer).
    fn try_coulomb(&mut self, step: &StepProblem<'_>, v: &mut [Vector3<f64>]) -> Option<usize> {
        self.stalled_at.clear();
        self.stalled_at.extend_from_slice(v);
        let tried = self.coulomb(step, v, EARLY_NEWTON);
        if tried.is_err() {
            v.copy_from_slice(&self.stalled_at);
        }
        tried.ok()
    }

    /// One Newton step on Tresca's problem (see [`WallNewton::tresca_step`]), and how far it
    /// moved the blocks' points (m/s).
    fn tresca_change(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
    ) -> Result<f64, Stall> {
        let alpha = self.tresca_step(step, v)?;
        Ok(self
            .step
            .iter()
            .zip(step.reach)
            .map(|(d, r)| (alpha * d).component_mul(r).abs().max())
            .fold(0.0, f64::max))
    }

    /// The fixed point on the bounds, and where it stalls, Coulomb's Newton from its iterate
    /// for at most [`EARLY_NEWTON`] steps; where that fails, the fixed point goes on from where
    /// it stalled for the rest of its iterations, then Coulomb's Newton for its own.
    fn settle(&mut self, step: &StepProblem<'_>, v: &mut [Vector3<f64>]) -> Result<usize, Stall> {
        let mut used = 0;
        let mut stop_at_stall = true;
        loop {
            let budget = MAX_ITERATIONS - used;
            match self.bounds_fixed_point(step, v, budget, stop_at_stall)? {
                FixedPoint::Settled(n) => return Ok(used + n),
                FixedPoint::Exhausted => {
                    return self
                        .coulomb(step, v, MAX_ITERATIONS)
                        .map(|n| n + MAX_ITERATIONS);
                }
                FixedPoint::Stalled(n) => {
                    used += n;
                    stop_at_stall = false;
                    if let Some(k) = self.try_coulomb(step, v) {
                        return Ok(used + k);
                    }
                }
            }
        }
    }

    /// Solves the step: `v` comes in as the first guess (the velocities before the step) and
    /// leaves as the solution; `impulses[k]` is contact k's impulse there, by
    /// [`WallNewton::settle`]. Returns the Newton steps used, or why the step stalled.
    pub fn solve(
        &mut self,
        step: &StepProblem<'_>,
        v: &mut [Vector3<f64>],
        impulses: &mut [Vector2<f64>],
    ) -> Result<usize, Stall> {
        let outcome = self.settle(step, v);
        impulses_at(step.contacts, v, impulses);
        outcome
    }
}

/// The test blocks of this solver's and the impulse solver's tests: 1 x 0.5 m, 1,300 kg,
/// their steps at g dt = 9.81e-3 m/s and the runs' tolerance.
#[cfg(test)]
pub(super) mod test_blocks {
    use super::{Contact, Part, StepProblem};
    use nalgebra::Vector3;

    /// g dt (m/s) of the tests' steps.
    pub(in crate::integrate::baselines) const G_DT: f64 = 9.81e-3;

    /// A test block's (m, m, I).
    pub(in crate::integrate::baselines) const MASS: Vector3<f64> =
        Vector3::new(1300.0, 1300.0, 1300.0 * (1.0 + 0.25) / 12.0);

    /// Each test block's points through its half diagonal (as many as the step has blocks).
    pub(in crate::integrate::baselines) const REACH: [Vector3<f64>; 2] =
        [Vector3::new(1.0, 1.0, 0.56), Vector3::new(1.0, 1.0, 0.56)];

    /// The point of `body`'s base at `x` from its centroid on what lies under it (normal (0, 1)
    /// and tangent (1, 0) at r = (x, -h): (d, r x d)), the other side fixed.
    pub(in crate::integrate::baselines) fn seated(
        body: usize,
        x: f64,
        friction: f64,
        compliance: f64,
    ) -> Contact {
        Contact {
            parts: [
                Some(Part {
                    body,
                    rows: [Vector3::new(0.0, 1.0, x), Vector3::new(1.0, 0.0, 0.25)],
                }),
                None,
            ],
            target_m_s: 0.0,
            friction,
            compliance,
        }
    }

    /// The step of the test blocks of masses `mass` under `v_free` on `contacts`, at the
    /// runs' tolerance.
    pub(in crate::integrate::baselines) fn step<'a>(
        mass: &'a [Vector3<f64>],
        v_free: &'a [Vector3<f64>],
        contacts: &'a [Contact],
    ) -> StepProblem<'a> {
        StepProblem {
            mass,
            reach: &REACH[..mass.len()],
            v_free,
            contacts,
            tolerance_m_s: 1e-10 * G_DT,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::test_blocks::{seated, step, G_DT, MASS, REACH};
    use super::*;

    /// A test block (its centroid at the origin) on points of its base at `xs`, each with its
    /// compliance: the contacts and the block's (m, m, I).
    fn block_on(xs: &[f64], eps: &[f64], friction: f64) -> (Vec<Contact>, Vector3<f64>) {
        let contacts = xs
            .iter()
            .zip(eps)
            .map(|(&x, &compliance)| seated(0, x, friction, compliance))
            .collect();
        (contacts, MASS)
    }

    /// Deep in the interior point's path a contact's constraints sit within 1e-21 m/s of their
    /// bounds, where l / w reaches 1e19: a multiplier's change read from its complementarity
    /// is then off by that times the round-off of its slack's change (about 1e3 N s here),
    /// and a force condensed through such a curvature likewise. The direction must still solve
    /// every one of the contact's linear equations to round-off of its terms: the blocks' (the
    /// impulse changes by the f - K du their condensed system assumed), the balances of s, z
    /// and r, and each constraint's linearised complementarity, or the blocks stop balancing
    /// (the uniform 976-block wall of docs/rocking-walls.md). Closed and sliding forward, then
    /// closed and sticking.
    #[test]
    fn a_contact_at_its_bounds_solves_its_linear_equations() {
        let eps = 1e-8;
        let (contacts, _) = block_on(&[0.0], &[eps], 0.6);
        let b = 0.018;
        let holds = |what: &str, terms: &[f64]| {
            let (sum, size) = terms
                .iter()
                .fold((0.0, 0.0), |(s, a), t| (s + t, a + t.abs()));
            assert!(
                sum.abs() <= 1e-12 * size,
                "{what}: off by {sum:e} in terms of {size:e}"
            );
        };
        for (w, l) in [
            ([1e-22, 3e-10, 1e-21, 2e-2], [0.03, 1e-19, 0.018, 1e-20]),
            ([1e-22, 3e-10, 1e-21, 3e-21], [0.03, 1e-19, 0.012, 0.006]),
        ] {
            let mut k = Slacks::start(&contacts[0], b, Vector2::zeros(), 1.0, 0.03);
            (k.s, k.z, k.r) = (3e-10, 1e-10, 1e-2);
            (k.w, k.l) = (w, l);
            k.residual = [2e-23, -1e-23, 5e-22, 0.0];
            k.target = [1e-24; 4];
            let f = k.condense(eps);
            let du = Vector2::new(2.5e-12, -1.5e-12);
            k.expand(eps, du);
            let (kn, kt) = k.stiffness(eps);
            let ([ds, dz, dr], dl, dw) = (k.d_local, k.dl, k.dw);
            holds("normal impulse", &[dl[0], -f.x, kn * du.x]);
            holds("tangential impulse", &[dl[3], -dl[2], -f.y, kt * du.y]);
            holds("s", &[ds / eps, -dl[0], -dl[1], -l[0], -l[1], k.s / eps]);
            holds("z", &[dz / eps, -dl[2], dl[3], -l[2], l[3], k.z / eps]);
            holds("r", &[dl[2], dl[3], l[2], l[3], -b]);
            // Each constraint's change term by term: dw is good to their round-off only.
            let dg = [
                vec![ds, du.x],
                vec![ds],
                vec![dr, -du.y, dz],
                vec![dr, du.y, -dz],
            ];
            for i in 0..4 {
                let mut slack = vec![dw[i], -k.residual[i]];
                slack.extend(dg[i].iter().map(|t| -t));
                holds("slack", &slack);
                let mut complementarity = vec![w[i] * dl[i], l[i] * k.residual[i], -k.target[i]];
                complementarity.extend(dg[i].iter().map(|t| l[i] * t));
                holds("complementarity", &complementarity);
            }
        }
    }

    fn solve(
        contacts: &[Contact],
        mass: Vector3<f64>,
        v_free: Vector3<f64>,
        start: Vector3<f64>,
    ) -> (Vector3<f64>, Vec<Vector2<f64>>) {
        let mut solver = WallNewton::new(1, []);
        let mut v = [start];
        let mut p = vec![Vector2::zeros(); contacts.len()];
        let (mass, v_free) = ([mass], [v_free]);
        let step = step(&mass, &v_free, contacts);
        let used = solver.solve(&step, &mut v, &mut p);
        assert!(used.is_ok(), "{used:?}");
        (v[0], p)
    }

    /// A block at rest on four points of unequal compliance: every contact closed and
    /// sticking, so the step's velocity solves one linear system, M + sum (n n' + t t') / eps,
    /// which nalgebra's dense LU solves independently; the two agree to round-off.
    #[test]
    fn a_resting_block_solves_the_linear_system_of_its_springs() {
        let eps = [2e-11, 1e-11, 3e-11, 1.5e-11];
        let (contacts, mass) = block_on(&[-0.5, -0.2, 0.1, 0.5], &eps, 0.6);
        let v_free = Vector3::new(0.0, -G_DT, 0.0);
        let (v, p) = solve(&contacts, mass, v_free, Vector3::zeros());
        let mut k = Matrix3::from_diagonal(&mass);
        for c in &contacts {
            let [n, t] = c.parts[0].unwrap().rows;
            k += (n * n.transpose() + t * t.transpose()) / c.compliance;
        }
        let expected = k.lu().solve(&mass.component_mul(&v_free)).unwrap();
        for (c, p) in contacts.iter().zip(&p) {
            assert!(p.x > 0.0 && p.y.abs() < c.friction * p.x, "{p:?}");
        }
        // The velocities are of the size of eps p_n; they agree to a few ulps of themselves.
        assert!(
            (v - expected).abs().max() < 1e-13 * expected.abs().max(),
            "{v:?} {expected:?}"
        );
        // The weight's impulse is carried but for what the block sinks by: the stiff contacts
        // close at eps p_n, here a few billionths of g dt.
        let carried: f64 = p.iter().map(|p| p.x).sum();
        let weight = mass.x * G_DT;
        assert!((carried - mass.x * (v.y + G_DT)).abs() < 1e-12 * weight);
        assert!(v.y < 0.0 && -v.y < 1e-8 * G_DT, "{}", v.y);
    }

    /// A block sliding at 2 m/s on two points: every contact slips, and the answer satisfies
    /// the balance of the step and Coulomb's law at every contact to round-off, whether Newton
    /// starts from rest or from the free velocity.
    #[test]
    fn a_sliding_block_meets_coulomb_and_the_balance_from_any_start() {
        let (contacts, mass) = block_on(&[-0.5, 0.5], &[1e-11, 1e-11], 0.3);
        let v_free = Vector3::new(2.0, -G_DT, 0.0);
        let (from_rest, _) = solve(&contacts, mass, v_free, Vector3::zeros());
        let (v, p) = solve(&contacts, mass, v_free, v_free);
        assert!(
            (v - from_rest).abs().max() < 1e-9 * G_DT,
            "{v:?} {from_rest:?}"
        );
        let mut balance = mass.component_mul(&(v - v_free));
        for (c, p) in contacts.iter().zip(&p) {
            let [n, t] = c.parts[0].unwrap().rows;
            balance -= n * p.x + t * p.y;
            let u = c.velocity(&[v]);
            assert!(p.x > 0.0 && u.y > 0.0, "{p:?} {u:?}");
            assert!((p.y + c.friction * p.x).abs() <= 1e-15 * p.x, "{p:?}");
        }
        let force = mass.x * G_DT;
        assert!(balance.abs().max() < 1e-9 * force, "{balance:?}");
        // It slows by mu g dt, as a sliding block does, less the share its slight turn takes.
        assert!(
            (v.x - (2.0 - 0.3 * G_DT)).abs() < 1e-3 * 0.3 * G_DT,
            "{}",
            v.x
        );
    }

    /// Semismooth Newton on Coulomb's law, run alone from rest, reaches the answer of the
    /// fixed point on the bounds (to the tolerance both stop at) in a few steps, whether the
    /// block slides (the friction moment shifting its load to the front contact, the coupling
    /// the fixed point needs its updates for) or is brought to rest (every contact sticking).
    #[test]
    fn newton_on_coulombs_law_reaches_the_fixed_points_answer() {
        let (contacts, mass) = block_on(&[-0.5, 0.5], &[1e-11, 1e-11], 0.8);
        for v_free in [
            Vector3::new(2.0, -G_DT, 0.0),
            Vector3::new(0.5 * 0.8 * G_DT, -G_DT, 0.0),
        ] {
            let (expected, _) = solve(&contacts, mass, v_free, Vector3::zeros());
            let mut solver = WallNewton::new(1, []);
            let mut v = [Vector3::zeros()];
            let (m, free) = ([mass], [v_free]);
            let step = step(&m, &free, &contacts);
            let used = solver.coulomb(&step, &mut v, MAX_ITERATIONS);
            assert!(matches!(used, Ok(1..=8)), "{used:?}");
            assert!(
                (v[0] - expected).abs().max() < 2e-10 * G_DT,
                "{:?} {expected:?}",
                v[0]
            );
            let slides = v_free.x > 1.0;
            let mut balance = mass.component_mul(&(v[0] - v_free));
            for c in &contacts {
                let (p, sticks) = c.impulse_at(c.velocity(&v), c.friction * c.normal_impulse(&v));
                assert_eq!(sticks, !slides, "{p:?}");
                let [n, t] = c.parts[0].unwrap().rows;
                balance -= n * p.x + t * p.y;
            }
            // The balance of the step at the answer, to the tolerance times the mass.
            assert!(balance.abs().max() < 1e-9 * mass.x * G_DT, "{balance:?}");
        }
    }

    /// Coulomb's LU keeps its numeric part and working memory from one factorisation to the
    /// next: two unsymmetric matrices of a wall's pattern in turn are each solved to round-off
    /// (nothing of the first leaks into the second), and a singular one is refused.
    #[test]
    fn coulombs_lu_solves_each_matrix_it_is_given() {
        let mut solver = WallNewton::new(3, [(0, 1), (1, 2)]);
        let mut rng = crate::rng::Rng::new(11);
        let (col_ptr, row_idx) = (solver.symbolic.col_ptr(), solver.symbolic.row_idx());
        let columns: Vec<(usize, usize)> = (0..9)
            .flat_map(|j| (col_ptr[j]..col_ptr[j + 1]).map(move |k| (j, k)))
            .collect();
        for _ in 0..2 {
            // Unsymmetric: 10 on the diagonal, off it random entries up to 0.1, 1 or 10 in size
            // by column.
            let values: Vec<f64> = columns
                .iter()
                .map(|&(j, k)| {
                    let off = 2.0 * rng.uniform() - 1.0;
                    if row_idx[k] == j {
                        10.0 + off
                    } else {
                        off * 10f64.powi((j % 3) as i32 - 1)
                    }
                })
                .collect();
            let x: Vec<f64> = (0..9).map(|_| 2.0 * rng.uniform() - 1.0).collect();
            let mut rhs = vec![0.0; 9];
            for (&(j, k), a) in columns.iter().zip(&values) {
                rhs[row_idx[k]] += a * x[j];
            }
            let matrix = SparseColMatRef::new(solver.symbolic.as_ref(), &values);
            assert!(solver.lu.solve(matrix, &mut rhs));
            for (got, want) in rhs.iter().zip(&x) {
                assert!((got - want).abs() < 1e-14, "{got} against {want}");
            }
        }
        // A singular Jacobian (every entry zero): the step is refused.
        solver.values.fill(0.0);
        solver.gradient = vec![Vector3::new(1.0, 0.0, 0.0); 3];
        assert!(!solver.newton_step(Jacobian::Coulomb));
    }

    /// The interior point in the velocities, followed by Newton and the bounds' updates,
    /// reaches the answer of the fixed point on the bounds, from rest, on a block at rest, one
    /// sliding, one brought to rest by friction, one thrown up off its supports and one turning
    /// onto a corner: each stops within the fixed point's round-off floor (1e-8 g dt) of
    /// Coulomb's answer, so they agree within twice that (the turning block, whose bounds'
    /// fixed point stalls at that floor: 1.1e-10 m/s apart, both with Coulomb's residual 1/2
    /// F' M^-1 F near 1.2e-16; the others to round-off).
    #[test]
    fn the_interior_point_reaches_the_fixed_points_answer() {
        let (contacts, mass) = block_on(&[-0.5, -0.1, 0.5], &[1e-11, 2e-11, 1e-11], 0.6);
        for v_free in [
            Vector3::new(0.0, -G_DT, 0.0),
            Vector3::new(2.0, -G_DT, 0.0),
            Vector3::new(0.5 * 0.6 * G_DT, -G_DT, 0.0),
            Vector3::new(0.3, 0.5, 0.0),
            Vector3::new(0.05, -G_DT, 0.4),
        ] {
            let (expected, expected_p) = solve(&contacts, mass, v_free, Vector3::zeros());
            let mut solver = WallNewton::new(1, []);
            let mut v = [Vector3::zeros()];
            let mut p = vec![Vector2::zeros(); contacts.len()];
            let (m, free) = ([mass], [v_free]);
            let step = step(&m, &free, &contacts);
            let used = solver.solve_interior(&step, &mut v, &mut p);
            assert!(used.is_ok(), "{used:?}");
            let apart = (v[0] - expected).component_mul(&REACH[0]).abs().max();
            assert!(
                apart <= 2.0 * ROUND_OFF_FLOOR * 1e-10 * G_DT,
                "{v_free:?}: {:?} against {expected:?}",
                v[0]
            );
            for (a, b) in p.iter().zip(&expected_p) {
                assert!((a - b).abs().max() <= 1e-6 * mass.x * G_DT, "{a:?} {b:?}");
            }
        }
    }
}
