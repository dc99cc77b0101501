//! A column's body rocking while the stack under it slides: a held joint below the body that
//! gave way by slipping. The blocks between that joint and the body's move as one rigid stack of
//! mass M, translating on the joint with friction mu_s against its slip (sigma its sign). Where
//! the body's pivot sticks, the body rocks on the stack's top as it rocks on a held base, the
//! stack's acceleration and the joint's friction coupling the two, and the body's u (its pivot's
//! displacement relative to the ground) is the stack's too, up to a constant; where the pivot
//! slips on the stack, the body slide-rocks as on a held base and the stack has its own state.
//! A joint inside or below the sliding stack that slips too makes stacks slide on stacks, each
//! below the top one with its own state. The body landing on them is one impact of body and
//! stacks, each joint's slip going on through it or stopped by it. A stack stops where its slip
//! on what is under it returns to zero: it slides on with the stack under it (or slips back at
//! once), or is held again, displaced; the displacement stays with its blocks and the joints in
//! it (their contacts move with them: the overlaps of seated blocks are those of the initial
//! configuration, docs/rocking-walls.md).

use super::body::RockingBody;
use super::modes::{
    self, arms, Constraint, Corner, Equations, Guard, Inputs, Mode, Scales, Slip, State, Trajectory,
};
use super::series::{self, div_at, mul_at, sin_cos_at, Coeffs, ORDER, ZERO};
use super::Engine;
use crate::error::SimulationError;
use crate::response::EventKind;

/// A stack sliding under a body.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stack {
    /// The joint it slides on: its index among the watch's held joints.
    pub joint: usize,
    /// Its lowest block (index in the column, bottom first); it reaches up to the body's.
    pub first: usize,
    /// M (kg).
    pub mass_kg: f64,
    /// mu_s, the joint's friction.
    pub friction: f64,
    /// Its slip's direction (sigma).
    pub slip: Slip,
    /// The body's u when it began (m): while the body's pivot sticks on it, the stack has
    /// moved by u - this since.
    pub u_start_m: f64,
    /// While the body's pivot slips on it (the body slide-rocks on the stack): the stack's own
    /// displacement since it began (m) and velocity (m/s); `None` while the pivot sticks.
    pub apart: Option<[f64; 2]>,
}

impl Stack {
    /// How far it has slid (m) where the body's u is `u_m`.
    pub fn moved_m(&self, u_m: f64) -> f64 {
        match self.apart {
            Some([moved, _]) => moved,
            None => u_m - self.u_start_m,
        }
    }

    /// Its slip velocity (m/s) where the body's pivot slips at `v_m_s`.
    pub fn velocity_m_s(&self, v_m_s: f64) -> f64 {
        match self.apart {
            Some([_, v]) => v,
            None => v_m_s,
        }
    }
}

/// Where a column's held blocks are: each block's displacement (m, bottom first; a stack that
/// slid and was held again), the stack sliding now under the body, and the stacks sliding
/// under that one, each on the next (a held joint inside a sliding stack that slipped too).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Displaced {
    /// Per block of the column; empty while nothing has moved.
    pub by_m: Vec<f64>,
    /// The stack sliding now under the body.
    pub sliding: Option<Stack>,
    /// The stacks sliding under it, top first, each with its own state (`Stack::apart`), each
    /// slipping on the next (the last on a held joint).
    pub beneath: Vec<Stack>,
}

/// Which stack carries a held block.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Owner {
    /// The stack under the body.
    Top,
    /// A stack beneath it (index in `Displaced::beneath`).
    Beneath(usize),
}

impl Displaced {
    /// The stack block p slides with, if any.
    fn owner(&self, p: usize) -> Option<Owner> {
        if p >= self.sliding?.first {
            return Some(Owner::Top);
        }
        (self.beneath.iter())
            .position(|st| p >= st.first)
            .map(Owner::Beneath)
    }

    /// Block p's displacement as a series along `traj`, and whether it slides with a stack
    /// now (its acceleration then the stack's, [`Displaced::acceleration`]).
    pub fn block(&self, p: usize, traj: &Trajectory) -> (Coeffs, bool) {
        let owner = self.owner(p);
        let mut out = match (owner, &traj.stack) {
            (None, _) => ZERO,
            // A trajectory without the stacks' series (the body fallen) leaves them where they
            // are.
            (Some(Owner::Beneath(k)), _) => traj.beneath.get(k).map_or(ZERO, |[u, _]| *u),
            (Some(Owner::Top), Some([moved, _])) => *moved,
            (Some(Owner::Top), None) => traj.u,
        };
        out[0] = self.at(p, traj.u[0]);
        (out, owner.is_some())
    }

    /// The absolute acceleration of block p along `traj` where it slides with a stack that
    /// moves on its own (the body's pivot slipping on it, or a stack beneath); `None` where it
    /// slides with the body's pivot or does not slide.
    pub fn acceleration(&self, p: usize, traj: &Trajectory, inputs: &Inputs) -> Option<Coeffs> {
        let v = match self.owner(p)? {
            Owner::Beneath(k) => &traj.beneath.get(k)?[1],
            Owner::Top => &traj.stack.as_ref()?[1],
        };
        let mut acc = series::derivative(v);
        series::add_to(&mut acc, &inputs.accel, 1.0);
        Some(acc)
    }

    /// Whether block p slides with a stack now.
    pub fn slides(&self, p: usize) -> bool {
        self.owner(p).is_some()
    }

    /// Whether a stack slides on joint j (its index among the watch's held joints).
    pub fn slides_on(&self, j: usize) -> bool {
        (self.sliding.iter().chain(&self.beneath)).any(|st| st.joint == j)
    }

    /// Block p's displacement (m) where the body's u is `u_m`.
    pub fn at(&self, p: usize, u_m: f64) -> f64 {
        let moved = self.by_m.get(p).copied().unwrap_or(0.0);
        match (self.owner(p), self.sliding) {
            (Some(Owner::Beneath(k)), _) => moved + self.beneath[k].moved_m(u_m),
            // (moved + u) - u_start: the rounding of every run before stacks had their own
            // state, kept so that their displacements stay the same to the bit.
            (Some(Owner::Top), Some(st @ Stack { apart: None, .. })) => moved + u_m - st.u_start_m,
            (Some(Owner::Top), Some(st)) => moved + st.moved_m(u_m),
            _ => moved,
        }
    }

    /// Block p's velocity (m/s) where the body's pivot slips at `v_m_s`.
    pub fn velocity_m_s(&self, p: usize, v_m_s: f64) -> f64 {
        match (self.owner(p), self.sliding) {
            (Some(Owner::Beneath(k)), _) => self.beneath[k].velocity_m_s(v_m_s),
            (Some(Owner::Top), Some(st)) => st.velocity_m_s(v_m_s),
            _ => 0.0,
        }
    }

    /// Each block displaced by `moved` more (m, from the bottom).
    pub fn shift(&mut self, moved: &[f64]) {
        if moved.iter().any(|&d| d != 0.0) {
            self.by_m.resize(self.by_m.len().max(moved.len()), 0.0);
            self.by_m.iter_mut().zip(moved).for_each(|(b, d)| *b += d);
        }
    }

    /// Whether any stack slides now.
    pub fn any_slides(&self) -> bool {
        self.sliding.is_some() || !self.beneath.is_empty()
    }

    /// Whether no held block has moved or moves.
    pub fn is_still(&self) -> bool {
        self.sliding.is_none() && self.by_m.iter().all(|&x| x == 0.0)
    }

    /// The stack stops at the body's displacement `u_m`: its blocks (up to the body's lowest,
    /// `body_first`) keep what it slid.
    pub fn stops(&mut self, u_m: f64, body_first: usize) {
        let Some(st) = self.sliding.take() else {
            return;
        };
        self.by_m.resize(body_first, 0.0);
        for d in &mut self.by_m[st.first..] {
            *d += st.moved_m(u_m);
        }
    }

    /// The stacks after a landing on them ([`landing`]): each at its velocity in `v` (the one
    /// under the body first, whose own is the body's pivot's), and where the impact stopped a
    /// joint's slip (`stuck`), the stack on it sliding on with the one under it as one, or, the
    /// lowest, held again; each block keeps its place.
    pub fn landed(&mut self, u_m: f64, v: &[f64], stuck: &[bool], body_first: usize) {
        for (st, &v) in self.beneath.iter_mut().zip(&v[1..]) {
            st.apart = Some([st.moved_m(u_m), v]);
        }
        if stuck == [true] {
            // The one stack held: what every run before stacks on stacks did, to the bit.
            self.stops(u_m, body_first);
            return;
        }
        if !stuck.contains(&true) {
            return;
        }
        self.settle(u_m, v[0], body_first);
        let mut stacks: Vec<Stack> = (self.sliding.take().into_iter())
            .chain(self.beneath.drain(..))
            .collect();
        for k in (0..stacks.len()).rev().filter(|&k| stuck[k]) {
            let upper = stacks.remove(k);
            if let Some(under) = stacks.get_mut(k) {
                under.mass_kg += upper.mass_kg;
                if k == 0 {
                    // Under the body now: its pivot sticks on it.
                    (under.apart, under.u_start_m) = (None, u_m);
                }
            }
        }
        let mut rest = stacks.into_iter();
        self.sliding = rest.next();
        self.beneath = rest.collect();
    }

    /// Every stack's blocks keep what it has slid (the body's u `u_m` and its pivot's slip
    /// velocity `v_m_s` now), and every stack goes on from there, moving as it moves: where
    /// stacks split or join, each block keeps its place.
    pub fn settle(&mut self, u_m: f64, v_m_s: f64, body_first: usize) {
        self.by_m.resize(body_first, 0.0);
        for p in 0..body_first {
            self.by_m[p] = self.at(p, u_m);
        }
        if let Some(top) = &mut self.sliding {
            match top.apart {
                None => top.u_start_m = u_m,
                Some([_, v]) => top.apart = Some([0.0, v]),
            }
        }
        for st in &mut self.beneath {
            st.apart = Some([0.0, st.velocity_m_s(v_m_s)]);
        }
    }
}

/// The series of the stacks beneath the top one along `traj` (the top one's, the body's and
/// its pivot's forces already in it): each is driven by the friction of the stack above
/// slipping on it at its limit, +mu_a sigma_a L_a, and held back by its own joint's,
/// -mu sigma L (L the normal load each joint carries: the body's N and the weight of the
/// stacks above it), so M (u'' + a_g) = mu_a sigma_a L_a - mu sigma L; none depends on the
/// accelerations below it.
pub fn beneath_series(
    body: &RockingBody,
    displaced: &Displaced,
    traj: &mut Trajectory,
    inputs: &Inputs,
) {
    let Some(top) = displaced.sliding else {
        return;
    };
    let g = body.g_m_s2;
    let load = |above: &Coeffs, mass: f64| series::add(above, &inputs.lambda, mass * g);
    let mut carried = load(&traj.normal, top.mass_kg);
    let mut passed = series::scaled(&carried, top.friction * top.slip.sign());
    traj.beneath.clear();
    for st in &displaced.beneath {
        let [moved, v] = st.apart.expect("a stack beneath moves on its own");
        carried = load(&carried, st.mass_kg);
        let held = series::scaled(&carried, st.friction * st.slip.sign());
        let force = series::add(&passed, &held, -1.0);
        traj.beneath
            .push(slid([moved, v], &force, st.mass_kg, inputs));
        passed = held;
    }
}

/// The body's motion on the sliding stack from `state`, rocking on corner `c`, as series.
///
/// With slide-rock's terms (G_y, dx, w = theta'^2, e = g lambda - G_y w; N and F the pivot's
/// normal and horizontal forces on the body): I_G theta'' = -dx N - G_y F, N = m (dx theta'' +
/// e); the stack's balance (m + M) A + m (G_y theta'' + dx w) = f, A = u'' + a_g its absolute
/// acceleration and f = -mu_s sigma (N + M g lambda) the joint's friction, gives F = m (A +
/// G_y theta'' + dx w) and theta'' = num / den with, rho = m / (m + M),
/// den = I_G + m dx^2 + (1 - rho) m G_y^2 - rho mu_s sigma m G_y dx,
/// num = -m dx e + rho mu_s sigma G_y (m e + M g lambda) - (1 - rho) m G_y dx w:
/// slide-rock's own equation as M -> 0. `tangential` and `normal` are the pivot's F and N.
pub fn trajectory(
    body: &RockingBody,
    stack: &Stack,
    c: Corner,
    state: &State,
    inputs: &Inputs,
) -> Trajectory {
    let (m, big, g) = (body.mass_kg, stack.mass_kg, body.g_m_s2);
    let (mu, sigma) = (stack.friction, stack.slip.sign());
    let rho = m / (m + big);
    let (a, lam) = (&inputs.accel, &inputs.lambda);
    let s = c.sign();
    let mut t = Trajectory::start(Mode::Rock(c), Equations::Exact, state);
    let (mut sin, mut cos, mut w, mut e) = (ZERO, ZERO, ZERO, ZERO);
    let (mut gy_dx, mut num, mut den, mut acc_theta) = (ZERO, ZERO, ZERO, ZERO);
    for k in 0..=ORDER {
        sin_cos_at(&t.theta, &mut sin, &mut cos, k);
        (t.gy[k], t.dx[k]) = arms(body, s, &sin, &cos, k);
        w[k] = mul_at(&t.omega, &t.omega, k);
        e[k] = g * lam[k] - mul_at(&t.gy, &w, k);
        gy_dx[k] = mul_at(&t.gy, &t.dx, k);
        den[k] = if k == 0 { body.inertia_kg_m2 } else { 0.0 }
            + m * mul_at(&t.dx, &t.dx, k)
            + (1.0 - rho) * m * mul_at(&t.gy, &t.gy, k)
            - rho * mu * sigma * m * gy_dx[k];
        num[k] = -m * mul_at(&t.dx, &e, k)
            + rho * mu * sigma * (m * mul_at(&t.gy, &e, k) + big * g * mul_at(&t.gy, lam, k))
            - (1.0 - rho) * m * mul_at(&gy_dx, &w, k);
        acc_theta[k] = div_at(&num, &den, &acc_theta, k);
        t.normal[k] = m * (mul_at(&t.dx, &acc_theta, k) + e[k]);
        let reach = mul_at(&t.gy, &acc_theta, k) + mul_at(&t.dx, &w, k);
        let friction = -mu * sigma * (t.normal[k] + big * g * lam[k]);
        let absolute = (friction - m * reach) / (m + big);
        t.tangential[k] = m * (absolute + reach);
        t.integrate(k, acc_theta[k], absolute - a[k], 0.0);
    }
    t.denominator_series = Some(den);
    t
}

/// The body slide-rocking on corner `c` on the sliding stack, its pivot slipping on the stack
/// towards `relative`, from `state` (the stack's own in `stack.apart`). The pivot's force on the
/// body is F = -mu sigma_r N (sigma_r the sign of its slip relative to the stack), so the
/// body's motion is slide-rock's as on a held base (the stack's acceleration does not enter
/// it); the stack moves by M (u_s'' + a_g) = -F - mu_s sigma (N + M g lambda), its slip
/// stopping where u_s' reaches zero.
pub fn slide_rocking(
    body: &RockingBody,
    stack: &Stack,
    c: Corner,
    relative: Slip,
    state: &State,
    inputs: &Inputs,
) -> Trajectory {
    let mode = Mode::SlideRock(c, relative);
    let mut t = modes::trajectory(body, Equations::Exact, mode, state, inputs);
    let start = stack.apart.expect("a stack apart from the body's pivot");
    let mut load = t.normal;
    series::add_to(&mut load, &inputs.lambda, stack.mass_kg * body.g_m_s2);
    let mut force = series::scaled(&t.tangential, -1.0);
    series::add_to(&mut force, &load, -stack.friction * stack.slip.sign());
    t.stack = Some(slid(start, &force, stack.mass_kg, inputs));
    t
}

/// A stack of mass `mass_kg` from `start` (how far it has slid, m, and its velocity, m/s)
/// under the horizontal force `force` (N, a series) in the ground's frame, M (u'' + a_g) = force:
/// its displacement and velocity as series.
fn slid(start: [f64; 2], force: &Coeffs, mass_kg: f64, inputs: &Inputs) -> [Coeffs; 2] {
    let (mut u, mut v) = (ZERO, ZERO);
    (u[0], v[0]) = (start[0], start[1]);
    for k in 0..ORDER {
        let kk = (k + 1) as f64;
        u[k + 1] = v[k] / kk;
        v[k + 1] = (force[k] / mass_kg - inputs.accel[k]) / kk;
    }
    [u, v]
}

/// Body's motion in `mode` from `state` on the stacks `displaced` has sliding (rocking on its
/// pivot stuck on the stack under it, [`trajectory`], or slipping on it, [`slide_rocking`]),
/// with the series of the stacks beneath ([`beneath_series`]); `None` in another mode.
pub fn on(
    body: &RockingBody,
    displaced: &Displaced,
    mode: Mode,
    state: &State,
    inputs: &Inputs,
) -> Option<Trajectory> {
    let top = displaced.sliding.as_ref()?;
    let mut traj = match mode {
        Mode::Rock(c) => trajectory(body, top, c, state, inputs),
        Mode::SlideRock(c, relative) => slide_rocking(body, top, c, relative, state, inputs),
        _ => return None,
    };
    beneath_series(body, displaced, &mut traj, inputs);
    Some(traj)
}

/// The stack's velocity along `traj` as a series: its own where the body's pivot slips on it,
/// else the body's pivot's.
fn velocity(traj: &Trajectory) -> &Coeffs {
    traj.stack.as_ref().map_or(&traj.v, |[_, v]| v)
}

/// The stacks' own conditions along `traj`, added to the body's in `out`: each stack's slip
/// on what is under it goes on (sigma (u_s' - u_b') > 0, strict: a slip that would not begin
/// does not happen; u_b' the velocity of the stack beneath, zero on a held joint), guarded by
/// `Stop` for the stack under the body and `Beneath(k)` for the k-th beneath it; where the
/// body's pivot slips on the stack ([`slide_rocking`]) that slip's condition is relative to the
/// stack, sigma_r (u' - u_s') > 0. That the coupled motion stays determinate (the denominator
/// positive: where it falls to zero friction makes the acceleration indeterminate, Painleve's
/// paradox) is among the body's conditions (`modes::constraints`, from the denominator's
/// series).
pub fn conditions(
    body: &RockingBody,
    displaced: &Displaced,
    traj: &Trajectory,
    out: &mut Vec<Constraint>,
) {
    let Some(top) = displaced.sliding else {
        return;
    };
    if let (Mode::SlideRock(_, relative), Some([_, v_s])) = (traj.mode, &traj.stack) {
        for c in out.iter_mut().filter(|c| c.guard == Guard::PivotStick) {
            c.series = series::scaled(&series::add(&traj.v, v_s, -1.0), relative.sign());
        }
    }
    let scale = Scales::of(body).velocity;
    let velocities: Vec<&Coeffs> = std::iter::once(velocity(traj))
        .chain(traj.beneath.iter().map(|[_, v]| v))
        .collect();
    let stacks = std::iter::once(&top).chain(&displaced.beneath);
    for (k, st) in stacks.enumerate() {
        let slip = match velocities.get(k + 1) {
            Some(under) => series::add(velocities[k], under, -1.0),
            None => *velocities[k],
        };
        out.push(Constraint {
            series: series::scaled(&slip, st.slip.sign()),
            scale,
            guard: if k == 0 {
                Guard::Stop
            } else {
                Guard::Beneath(k - 1)
            },
            strict: true,
        });
    }
}

/// The work rates of body and stacks together: the input (the body's, and -M a_g u_s' on each
/// stack) and the friction dissipated on each joint a stack slides on (mu sigma L times its
/// slip velocity on what is under it), and where the body's pivot slips on the stack, on the
/// pivot (-F (u' - u_s')). Where the pivot sticks its force is inside the system: its work on
/// the body and on the stack cancel; so does each stack joint's between the two stacks it
/// joins, but for what its slip dissipates.
pub fn power_series(
    body: &RockingBody,
    displaced: &Displaced,
    traj: &Trajectory,
    inputs: &Inputs,
) -> (Coeffs, Coeffs) {
    let top = displaced.sliding.expect("a stack that slides");
    let v_s = velocity(traj);
    let (input, pivot) = modes::power_series(body, traj, inputs);
    let mut input = series::add(&input, &series::product(&inputs.accel, v_s), -top.mass_kg);
    let mut load = traj.normal;
    series::add_to(&mut load, &inputs.lambda, top.mass_kg * body.g_m_s2);
    let slip = match traj.beneath.first() {
        Some([_, under]) => series::add(v_s, under, -1.0),
        None => *v_s,
    };
    let mut friction = series::scaled(
        &series::product(&load, &slip),
        top.friction * top.slip.sign(),
    );
    if traj.stack.is_some() {
        series::add_to(&mut friction, &pivot, 1.0);
        series::add_to(&mut friction, &series::product(&traj.tangential, v_s), 1.0);
    }
    for (k, st) in displaced.beneath.iter().enumerate() {
        let v = &traj.beneath[k][1];
        series::add_to(&mut input, &series::product(&inputs.accel, v), -st.mass_kg);
        series::add_to(&mut load, &inputs.lambda, st.mass_kg * body.g_m_s2);
        let slip = match traj.beneath.get(k + 1) {
            Some([_, under]) => series::add(v, under, -1.0),
            None => *v,
        };
        let work = series::product(&load, &slip);
        series::add_to(&mut friction, &work, st.friction * st.slip.sign());
    }
    (input, friction)
}

/// What a body's landing on the stacks sliding under it leaves: its angular velocity, each
/// stack's velocity after (m/s, the one under the body first; 0 where it stops), whether the
/// impact stopped the slip of each stack's joint, and the kinetic energy lost (J).
#[derive(Debug, Clone, PartialEq)]
pub struct Landing {
    pub omega: f64,
    pub v: Vec<f64>,
    pub stuck: Vec<bool>,
    pub loss_j: f64,
}

/// The landing of a body rocking on `pivot` that reaches theta = 0 at `omega` on the stacks
/// `stacks` sliding under it (the one under the body first, each slipping on the next, the
/// last on a held joint) at velocities `v`: Housner's assumption on bases that move (the
/// impulse (P_t, P_n) at the new corner alone, plastic in its normal, the corner sticking on
/// the stack under it within mu P_n; every joint passing P_n and a friction impulse P_f,k
/// within mu_k P_n). Each joint either slides on through the impact, P_f,k = -mu_k sigma_k P_n
/// with sigma_k (v_k' - v_k+1') > 0, or the impact stops its slip, v_k' = v_k+1' (v' = 0
/// under the lowest) with |P_f,k| <= mu_k P_n: of the 2^n choices exactly one must meet every
/// condition. A choice makes clusters of stacks that leave at one velocity. The one under the
/// body, of mass M and momentum p before, slides on the joint under it (mu, sigma) or stops:
/// with Delta = omega' - omega and dv = V - v_1, P_n = -m s b (2 omega + Delta), the angular
/// momentum about the new corner kept, I_O Delta + m h_c dv = -2 m b^2 omega, and
/// (m + M) dv = -m h_c Delta + mu sigma m s b (2 omega + Delta) + (p - M v_1), Housner's law
/// as M grows without bound, the choice taken only where the factor of Delta, I_O - h_c m
/// (m h_c - mu sigma m s b) / (m + M), is positive; where it stops, the body lands as on a
/// held base moving at v_1.
/// Each cluster below takes its momentum and the two joints' impulses at their limits. `None`
/// where no choice holds, or several (the corner pushed apart or slipping, a stack turning
/// within the impact, the body landing flat), the wall's restitution factor is not 1, or more
/// than 16 stacks slide (2^n choices): the landings the model does not follow on sliding
/// stacks.
pub fn landing(
    body: &RockingBody,
    stacks: &[Stack],
    v: &[f64],
    pivot: Corner,
    omega: f64,
) -> Option<Landing> {
    let n = stacks.len();
    if body.restitution_factor != 1.0 || n == 0 || n != v.len() || n > 16 {
        return None;
    }
    let (m, ig) = (body.mass_kg, body.inertia_kg_m2);
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    let s = pivot.sign();
    let io = body.corner_inertia_kg_m2();
    let energy = |c: f64, omega: f64, v: &[f64]| {
        let carried = (stacks.iter().zip(v)).map(|(st, v)| 0.5 * st.mass_kg * v * v);
        super::impact::kinetic(body, c, omega, v[0]) + carried.sum::<f64>()
    };
    // Mass and momentum of stacks from..=to.
    let cluster = |from: usize, to: usize| {
        (stacks[from..=to].iter().zip(&v[from..=to])).fold((0.0, 0.0), |(mass, p), (st, v)| {
            (mass + st.mass_kg, p + st.mass_kg * v)
        })
    };
    // mu sigma of joint k.
    let limit = |k: usize| stacks[k].friction * stacks[k].slip.sign();
    let mut holding = Vec::new();
    for choice in 0..1u32 << n {
        let stuck: Vec<bool> = (0..n).map(|k| choice >> k & 1 == 1).collect();
        let mut after = vec![0.0; n];
        // The joint the body's cluster slides on, if any.
        let slides_on = stuck.iter().position(|&stuck| !stuck);
        let w = match slides_on {
            // Stopped: the body lands as on a held base moving at v_1.
            None => ((ig + m * (h * h - b * b)) * omega + m * h * v[0]) / io,
            Some(a) => {
                let (big, p) = cluster(0, a);
                let (mu_sigma, share) = (limit(a), m / (m + big));
                let lhs = io - h * share * (m * h - mu_sigma * m * s * b);
                if lhs <= 0.0 {
                    continue;
                }
                let q = (p - big * v[0]) / (m + big);
                let delta =
                    (-2.0 * m * b * omega * (b + share * h * mu_sigma * s) - m * h * q) / lhs;
                let dv = share * (-h * delta + mu_sigma * s * b * (2.0 * omega + delta)) + q;
                after[..=a].fill(v[0] + dv);
                omega + delta
            }
        };
        let normal = -m * s * b * (w + omega);
        // Each cluster below the body's: its momentum and its joints' impulses at their limits.
        let mut from = slides_on.map_or(n, |a| a + 1);
        while from < n {
            let Some(to) = (from..n).find(|&k| !stuck[k]) else {
                break;
            };
            let (mass, p) = cluster(from, to);
            after[from..=to].fill((p + (limit(from - 1) - limit(to)) * normal) / mass);
            from = to + 1;
        }
        let tangential = m * (after[0] - v[0] + h * (w - omega));
        let lands = normal >= 0.0 && tangential.abs() <= body.friction * normal && w * -s > 0.0;
        // The friction impulse joint k passes: P_t and the momentum the stacks above it gained.
        let mut passed = tangential;
        let joints = (0..n).all(|k| {
            passed += stacks[k].mass_kg * (after[k] - v[k]);
            let under = after.get(k + 1).copied().unwrap_or(0.0);
            if stuck[k] {
                passed.abs() <= stacks[k].friction * normal
            } else {
                stacks[k].slip.sign() * (after[k] - under) > 0.0
            }
        });
        if lands && joints {
            holding.push(Landing {
                omega: w,
                loss_j: energy(s, omega, v) - energy(-s, w, &after),
                v: after,
                stuck,
            });
        }
    }
    let [one] = <[Landing; 1]>::try_from(holding).ok()?;
    Some(one)
}

/// The stacks' kinetic energy (J) at tau along `traj`.
pub fn kinetic_j(displaced: &Displaced, traj: &Trajectory, tau: f64) -> f64 {
    let Some(top) = displaced.sliding else {
        return 0.0;
    };
    let v = series::eval(velocity(traj), tau);
    let beneath = (displaced.beneath.iter().zip(&traj.beneath)).map(|(st, [_, v])| {
        let v = series::eval(v, tau);
        0.5 * st.mass_kg * v * v
    });
    0.5 * top.mass_kg * v * v + beneath.sum::<f64>()
}

#[cfg(test)]
#[path = "stack_tests.rs"]
mod tests;

impl Engine<'_> {
    /// Condition k of body i's watch falls: where it is a held joint below the body that
    /// slips, and the body rocks on its pivot, stuck or slipping (one column, exact equations,
    /// nothing beside it), the stack above that joint slides from here, alone or on a stack
    /// that starts to slide at the same instant on a joint below it, or the stack on that
    /// joint below slides instead (the force that broke the condition is the one of the motion
    /// before, with every joint held), the body on it as the one way of all these that holds
    /// says ([`Engine::stack_ways`]); else `false` (the run stops as before).
    pub(super) fn stack_slides(&mut self, i: usize, k: usize, now: &Inputs) -> bool {
        let tr = &self.tracks[i];
        let (c, slipping) = match (tr.mode, &tr.displaced.sliding) {
            (Mode::Rock(c), None) => (c, None),
            (Mode::SlideRock(c, relative), None) => (c, (tr.state.v != 0.0).then_some(relative)),
            _ => return false,
        };
        if self.tracks.len() != 1
            || !self.clearance.is_empty()
            || self.scene.equations != Equations::Exact
        {
            return false;
        }
        let scene = self.scene;
        let Some(watch) = scene.watches.get(i) else {
            return false;
        };
        let Some(stack) = watch.stack_on(k, tr.state.u) else {
            return false;
        };
        // Each stack at rest as it begins, sliding alone on the column's held blocks.
        let alone = |stack: Stack| Displaced {
            sliding: Some(Stack {
                apart: Some([0.0, 0.0]),
                ..stack
            }),
            ..tr.displaced.clone()
        };
        let base = alone(stack);
        let mut ways = self.stack_ways(i, &base, c, slipping, now);
        // Or a joint inside it slipping at the same instant: the blocks above that joint
        // sliding on the rest of the stack.
        let body_first = watch.held_blocks().count();
        for inside in watch.slips_under(stack.first + 1..body_first) {
            let Some(upper) = watch.stack_on(inside, tr.state.u) else {
                continue;
            };
            let split = Displaced {
                beneath: vec![Stack {
                    mass_kg: stack.mass_kg - upper.mass_kg,
                    apart: Some([0.0, 0.0]),
                    ..stack
                }],
                ..alone(upper)
            };
            ways.extend(self.stack_ways(i, &split, c, slipping, now));
            // Or that joint alone slipping: the joint whose condition fell, no longer passing
            // the inertia of the blocks above it, holding after all.
            ways.extend(self.stack_ways(i, &alone(upper), c, slipping, now));
        }
        for low in watch.slips_under(0..stack.first) {
            let Some(all) = watch.stack_on(low, tr.state.u) else {
                continue;
            };
            let bottom = Stack {
                mass_kg: all.mass_kg - stack.mass_kg,
                apart: Some([0.0, 0.0]),
                ..all
            };
            let with = Displaced {
                beneath: vec![bottom],
                ..base.clone()
            };
            ways.extend(self.stack_ways(i, &with, c, slipping, now));
            // Or that joint alone slipping, the one whose condition fell holding after all.
            ways.extend(self.stack_ways(i, &alone(all), c, slipping, now));
        }
        let [way] = &ways[..] else {
            return false;
        };
        if let Some(bottom) = way.0.beneath.first() {
            self.stack_under(i, bottom);
        }
        let (stack, mode) = (way.0.sliding.expect("a stack that slides"), way.1);
        let (joint, _, _) = watch.describe(4 * stack.joint);
        let blocks: Vec<usize> = watch
            .held_blocks()
            .filter(|&p| p >= stack.first)
            .map(|p| self.layout.column_output(i, p))
            .collect();
        let names: Vec<&str> = blocks
            .iter()
            .map(|&b| self.layout.names[b].as_str())
            .collect();
        let what = format!(
            "{} slide on {joint} towards {}x (M = {} kg, mu = {}) under {} {} on its {} corner",
            names.join("+"),
            if stack.slip == Slip::Forward {
                "+"
            } else {
                "-"
            },
            stack.mass_kg,
            stack.friction,
            self.body(i).name,
            match mode {
                Mode::SlideRock(..) => "slide-rocking",
                _ => "rocking",
            },
            c.name()
        );
        self.stack_starts(i, blocks, what, way.clone(), now);
        true
    }

    /// Body i, rocking on corner `c` with its state set (its u' the stack's), takes over from a
    /// chain of open joints that ends on `stack` sliding under it, slid by `slid` (m) since it
    /// began: its way on the stack (its pivot stuck on it, or slipping either way) that holds
    /// just after now goes on; false where none or several do, the body left stuck on the
    /// stack as the chain left it.
    /// How many ways body i would have on `stack` sliding under it (slid by `slid`), rocking
    /// on corner `c` from `state` with its held blocks displaced by `moved` more: those
    /// [`Engine::stack_carries`] would choose from, none taken.
    pub(super) fn stack_would_carry(
        &self,
        i: usize,
        (state, c): (&State, Corner),
        moved: &[f64],
        (stack, slid): (Stack, f64),
        now: &Inputs,
    ) -> usize {
        let mut displaced = self.tracks[i].displaced.clone();
        displaced.shift(moved);
        let base = Displaced {
            sliding: Some(Stack {
                apart: Some([slid, state.v]),
                ..stack
            }),
            ..displaced
        };
        self.ways_from(i, state, &base, c, None, now).len()
    }

    pub(super) fn stack_carries(
        &mut self,
        i: usize,
        (stack, slid): (Stack, f64),
        c: Corner,
        now: &Inputs,
    ) -> bool {
        let v_s = self.tracks[i].state.v;
        let base = Displaced {
            sliding: Some(Stack {
                apart: Some([slid, v_s]),
                ..stack
            }),
            ..self.tracks[i].displaced.clone()
        };
        let ways = self.stack_ways(i, &base, c, None, now);
        if let [way] = &ways[..] {
            self.stack_switches(i, way.clone(), now);
            return true;
        }
        let u = self.tracks[i].state.u;
        self.tracks[i].displaced.sliding = Some(Stack {
            apart: None,
            u_start_m: u - slid,
            ..stack
        });
        false
    }

    /// The stack under body i stops sliding: held again where it is, the body decided anew on
    /// it (a slip velocity of round-off left, with its energy, goes with the impact losses).
    pub(super) fn stack_stops(&mut self, i: usize, now: &Inputs) -> Result<(), SimulationError> {
        let body = self.body(i);
        let scene = self.scene;
        let watch = &scene.watches[i];
        let tr = &self.tracks[i];
        let stack = tr.displaced.sliding.expect("a stack that slides");
        let before = {
            let t = self.trajectory(i, now);
            modes::kinetic_j(body, &t, 0.0) + kinetic_j(&tr.displaced, &t, 0.0)
        };
        let (joint, _, _) = watch.describe(4 * stack.joint);
        let moved = stack.moved_m(tr.state.u);
        let held = watch.held_blocks().count();
        let tr = &mut self.tracks[i];
        tr.displaced.stops(tr.state.u, held);
        if stack.apart.is_none() {
            // The pivot stuck on the stack: the body's slip was the stack's.
            tr.state.v = 0.0;
        }
        let after = modes::kinetic_j(body, &self.trajectory(i, now), 0.0);
        self.rec.energy.impact_loss_j += before - after;
        let mut blocks: Vec<usize> = watch
            .held_blocks()
            .filter(|&p| p >= stack.first)
            .map(|p| self.layout.column_output(i, p))
            .collect();
        blocks.extend(self.layout.outputs(i));
        self.rec.transitions += 1;
        self.rec.rocking_event(
            self.t,
            EventKind::Stick,
            &blocks,
            None,
            format!("stops on {joint}, having slid {moved:.6e} m"),
        );
        self.decide(i, now, false)
    }

    /// The pivot of body i, rocking on the sliding stack, reaches the limit of its friction:
    /// it slips on the stack from here (the body slide-rocks on it, [`slide_rocking`]) where
    /// that motion holds just after now; else the run stops there.
    pub(super) fn stack_parts(&mut self, i: usize, now: &Inputs) {
        let tr = &self.tracks[i];
        let stack = tr.displaced.sliding.expect("a stack that slides");
        let Mode::Rock(c) = tr.mode else {
            self.stack_gives(i, Guard::PivotSlip);
            return;
        };
        // F = -mu sigma_r N at the limit: the pivot slips against the force it needed.
        let needed = self.trajectory(i, now).tangential[0];
        let relative = if needed > 0.0 {
            Slip::Backward
        } else {
            Slip::Forward
        };
        let base = Displaced {
            sliding: Some(Stack {
                apart: Some([stack.moved_m(tr.state.u), tr.state.v]),
                ..stack
            }),
            ..tr.displaced.clone()
        };
        match <[_; 1]>::try_from(self.stack_ways(i, &base, c, Some(relative), now)) {
            Ok([way]) => self.stack_switches(i, way, now),
            Err(_) => self.stack_gives(i, Guard::PivotSlip),
        }
    }

    /// The pivot of body i, slide-rocking on the sliding stack, stops slipping on it: the one
    /// way that holds from there ([`Engine::stack_ways`]: rocking on the pivot stuck on the
    /// stack, or slipping on it either way) goes on; else the run stops there.
    pub(super) fn stack_rejoins(&mut self, i: usize, now: &Inputs) {
        let tr = &self.tracks[i];
        let stack = tr.displaced.sliding.expect("a stack that slides");
        let (Mode::SlideRock(c, _), Some(_)) = (tr.mode, stack.apart) else {
            self.stack_gives(i, Guard::PivotStick);
            return;
        };
        let base = tr.displaced.clone();
        match <[_; 1]>::try_from(self.stack_ways(i, &base, c, None, now)) {
            Ok([way]) => self.stack_switches(i, way, now),
            Err(_) => self.stack_gives(i, Guard::PivotStick),
        }
    }

    /// The ways body i can move on the stacks `base` has sliding (the stack under the body
    /// with its own state in `apart`: how far it has slid and its velocity now) that meet every
    /// condition just after now (the body's, the stacks' and the held joints'): rocking on its
    /// pivot stuck on the stack, where the pivot moves with it (`slipping` none; the body's slip
    /// velocity then the stack's), and slide-rocking on it, the pivot slipping on the stack the
    /// way `slipping` says, or either way from relative rest. Where the effective masses are
    /// positive at most one holds (a stuck pivot within its friction cone, or the slip its
    /// limit force drives); several, or none, stop the run.
    fn stack_ways(
        &self,
        i: usize,
        base: &Displaced,
        c: Corner,
        slipping: Option<Slip>,
        now: &Inputs,
    ) -> Vec<(Displaced, Mode, State)> {
        self.ways_from(i, &self.tracks[i].state, base, c, slipping, now)
    }

    /// [`Engine::stack_ways`] from `state` rather than body i's own.
    fn ways_from(
        &self,
        i: usize,
        state: &State,
        base: &Displaced,
        c: Corner,
        slipping: Option<Slip>,
        now: &Inputs,
    ) -> Vec<(Displaced, Mode, State)> {
        let stack = base.sliding.expect("a stack that slides");
        let [moved, v_s] = stack.apart.expect("the stack's own state");
        let mut ways = Vec::with_capacity(3);
        if slipping.is_none() {
            let joined = Stack {
                apart: None,
                u_start_m: state.u - moved,
                ..stack
            };
            let on = Displaced {
                sliding: Some(joined),
                ..base.clone()
            };
            ways.push((on, Mode::Rock(c), State { v: v_s, ..*state }));
        }
        let slips = match slipping {
            Some(relative) => vec![relative],
            None => vec![Slip::Forward, Slip::Backward],
        };
        ways.extend(
            (slips.into_iter())
                .map(|relative| (base.clone(), Mode::SlideRock(c, relative), *state)),
        );
        ways.retain(|(on, mode, state)| self.holds_on(i, on, *mode, state, now));
        ways
    }

    /// Whether body i in `mode` from `state`, its column's held blocks as `displaced` has them
    /// (its stacks sliding), meets every condition of that motion just after now.
    fn holds_on(
        &self,
        i: usize,
        displaced: &Displaced,
        mode: Mode,
        state: &State,
        now: &Inputs,
    ) -> bool {
        self.breaks_on(i, displaced, mode, state, now)
            .is_some_and(|broken| broken.is_empty())
    }

    /// The conditions of that motion (as [`Engine::holds_on`]) that do not hold just after
    /// now; `None` where body i has no such motion.
    fn breaks_on(
        &self,
        i: usize,
        displaced: &Displaced,
        mode: Mode,
        state: &State,
        now: &Inputs,
    ) -> Option<Vec<Guard>> {
        let body = self.body(i);
        let traj = on(body, displaced, mode, state, now)?;
        let mut all = modes::constraints(body, Equations::Exact, &traj);
        conditions(body, displaced, &traj, &mut all);
        all.extend(self.scene.watches[i].conditions(&traj, now, displaced));
        let scale_t = body.time_scale_s();
        Some(
            (all.iter())
                .filter(|c| !c.holds_after(scale_t))
                .map(|c| c.guard)
                .collect(),
        )
    }

    /// A stack starts to slide under the stacks on it, at the bottom of body i's column: a
    /// `slip` event naming it.
    fn stack_under(&mut self, i: usize, bottom: &Stack) {
        let watch = &self.scene.watches[i];
        let (joint, _, _) = watch.describe(4 * bottom.joint);
        let blocks: Vec<usize> = (watch.held_blocks())
            .filter(|&p| p >= bottom.first)
            .map(|p| self.layout.column_output(i, p))
            .collect();
        let what =
            format!(
            "{} slide on {joint} towards {}x (M = {} kg, mu = {}) under the stacks sliding on it",
            self.layout.names[blocks[0]],
            if bottom.slip == Slip::Forward { "+" } else { "-" },
            bottom.mass_kg,
            bottom.friction
        );
        self.rec.transitions += 1;
        self.rec
            .rocking_event(self.t, EventKind::Slip, &blocks, None, what);
    }

    /// A stack starts to slide under body i: a `slip` event naming it (`blocks`, with the
    /// body's, and `what`), then the body goes on in `way` ([`Engine::stack_switches`]).
    fn stack_starts(
        &mut self,
        i: usize,
        mut blocks: Vec<usize>,
        what: String,
        way: (Displaced, Mode, State),
        now: &Inputs,
    ) {
        blocks.extend(self.layout.outputs(i));
        self.rec.transitions += 1;
        self.rec
            .rocking_event(self.t, EventKind::Slip, &blocks, None, what);
        self.stack_switches(i, way, now);
    }

    /// Body i goes on in `way` (its column's held blocks, the body's mode and state) on the
    /// sliding stacks,
    /// a change of its mode logged; what its state changes by (a relative slip of round-off
    /// where its pivot sticks on the stack), with its energy, goes with the impact losses, as
    /// where the stack stops.
    fn stack_switches(
        &mut self,
        i: usize,
        (displaced, mode, state): (Displaced, Mode, State),
        now: &Inputs,
    ) {
        let body = self.body(i);
        let energy = |engine: &Self| {
            let t = engine.trajectory(i, now);
            modes::kinetic_j(body, &t, 0.0) + kinetic_j(&engine.tracks[i].displaced, &t, 0.0)
        };
        let changed = self.tracks[i].state != state;
        let before = if changed { energy(self) } else { 0.0 };
        let old = self.tracks[i].mode;
        let tr = &mut self.tracks[i];
        (tr.displaced, tr.mode, tr.state) = (displaced, mode, state);
        if changed {
            self.rec.energy.impact_loss_j += before - energy(self);
        }
        if let Some(kind) = super::transition(old, mode, false) {
            let what = format!("{} on the stack", mode.name());
            self.rec
                .rocking_event(self.t, kind, &self.layout.outputs(i), None, what);
        }
    }

    /// Condition k of body i's watch falls while a stack slides under it: a held joint below
    /// the body that slips, inside a sliding stack (which splits: the blocks above the joint
    /// slide on those below it, each part with its own state) or below every sliding stack (a
    /// new stack at the bottom, starting from rest), if every condition of that motion holds
    /// just after now; else `false` (the run stops as before). The blocks keep their places:
    /// what each stack slid so far stays with its blocks.
    pub(super) fn stack_splits(&mut self, i: usize, k: usize, now: &Inputs) -> bool {
        let scene = self.scene;
        let watch = &scene.watches[i];
        let tr = &self.tracks[i];
        let Some(new) = watch.stack_on(k, tr.state.u) else {
            return false;
        };
        let mut shift = tr.displaced.clone();
        shift.settle(tr.state.u, tr.state.v, watch.held_blocks().count());
        let top = shift.sliding.expect("a stack that slides");
        let stacks: Vec<Stack> = std::iter::once(top).chain(shift.beneath.clone()).collect();
        let above = |s: usize| stacks[..s].iter().map(|st| st.mass_kg).sum::<f64>();
        // The stack that starts to slip, and the one under it (none on a held joint).
        let (moving, under) = match stacks.iter().position(|st| st.first < new.first) {
            Some(s) => {
                let whole = stacks[s];
                let upper = Stack {
                    joint: new.joint,
                    first: new.first,
                    mass_kg: new.mass_kg - above(s),
                    friction: new.friction,
                    slip: new.slip,
                    ..whole
                };
                let lower = Stack {
                    mass_kg: whole.mass_kg - upper.mass_kg,
                    apart: Some([0.0, whole.velocity_m_s(tr.state.v)]),
                    ..whole
                };
                match s {
                    0 => shift.sliding = Some(upper),
                    _ => shift.beneath[s - 1] = upper,
                }
                shift.beneath.insert(s, lower);
                (upper, Some(lower))
            }
            None => {
                let bottom = Stack {
                    mass_kg: new.mass_kg - above(stacks.len()),
                    apart: Some([0.0, 0.0]),
                    ..new
                };
                shift.beneath.push(bottom);
                (bottom, None)
            }
        };
        // The body on the stack under it, its pivot stuck or slipping on it, the joint slipping
        // or, the body's pivot slipping instead, not: as the one way that holds says.
        let (Mode::Rock(c) | Mode::SlideRock(c, _)) = tr.mode else {
            return false;
        };
        let top = shift.sliding.expect("a stack that slides");
        let v_top = top.velocity_m_s(tr.state.v);
        let slipping = match tr.mode {
            Mode::SlideRock(_, relative) if tr.state.v != v_top => Some(relative),
            _ => None,
        };
        let own = |d: &Displaced| {
            let top = d.sliding.expect("a stack that slides");
            Displaced {
                sliding: Some(Stack {
                    apart: Some([top.moved_m(tr.state.u), v_top]),
                    ..top
                }),
                ..d.clone()
            }
        };
        let mut ways = self.stack_ways(i, &own(&shift), c, slipping, now);
        ways.extend(self.stack_ways(i, &own(&tr.displaced), c, slipping, now));
        let [way] = &ways[..] else {
            return false;
        };
        if way.0.beneath.len() == tr.displaced.beneath.len() {
            self.stack_switches(i, way.clone(), now);
            return true;
        }
        let (joint, _, _) = watch.describe(4 * new.joint);
        let body_first = watch.held_blocks().count();
        let firsts: Vec<usize> = (shift.sliding.iter().chain(&shift.beneath))
            .map(|st| st.first)
            .collect();
        let names = |from: usize| {
            // A stack's blocks reach up to the next stack's, or to the body's.
            let to = (firsts.iter().copied())
                .filter(|&f| f > from)
                .min()
                .unwrap_or(body_first);
            (from..to)
                .map(|p| self.layout.names[self.layout.column_output(i, p)].as_str())
                .collect::<Vec<_>>()
                .join("+")
        };
        let what = format!(
            "{} slide on {joint} towards {}x (M = {} kg, mu = {}) {}",
            names(new.first),
            if new.slip == Slip::Forward { "+" } else { "-" },
            moving.mass_kg,
            new.friction,
            match under {
                Some(lower) => format!("on {}, sliding too", names(lower.first)),
                None => "under the stacks sliding on it".to_string(),
            }
        );
        let blocks: Vec<usize> = (watch.held_blocks())
            .filter(|&p| p >= new.first)
            .map(|p| self.layout.column_output(i, p))
            .collect();
        self.stack_starts(i, blocks, what, way.clone(), now);
        true
    }

    /// A stack under body i stops slipping on the stack beneath it (`which`: none for the stack
    /// under the body, else the k-th beneath it, [`Guard::Beneath`]): the two slide on as one
    /// from here at the lower one's velocity (the body's pivot, where it sticks on the upper,
    /// with them), or, for the lowest, it stops on its held joint; where a held joint of that
    /// motion breaks at once it slips ([`Engine::stack_splits`]: the stack that stopped slips
    /// back), and where another of its conditions does not hold just after now the run stops.
    /// The velocity of round-off between them, with its energy, goes with the impact losses,
    /// as where a stack stops.
    pub(super) fn stack_joins(&mut self, i: usize, which: Option<usize>, now: &Inputs) {
        let scene = self.scene;
        let watch = &scene.watches[i];
        let tr = &self.tracks[i];
        let mut shift = tr.displaced.clone();
        shift.settle(tr.state.u, tr.state.v, watch.held_blocks().count());
        let mut state = tr.state;
        let top = shift.sliding.expect("a stack that slides");
        let (stopped, on) = match which {
            None => {
                let b = shift.beneath.remove(0);
                let v_b = b.velocity_m_s(0.0);
                shift.sliding = Some(Stack {
                    joint: b.joint,
                    first: b.first,
                    mass_kg: top.mass_kg + b.mass_kg,
                    friction: b.friction,
                    slip: b.slip,
                    u_start_m: state.u,
                    apart: top.apart.map(|_| [0.0, v_b]),
                });
                if top.apart.is_none() {
                    state.v = v_b;
                }
                (top, Some(b))
            }
            Some(k) => {
                let b = shift.beneath.remove(k);
                let under = shift.beneath.get_mut(k).map(|under| {
                    under.mass_kg += b.mass_kg;
                    *under
                });
                (b, under)
            }
        };
        let body = self.body(i);
        let given = which.map_or(Guard::Stop, Guard::Beneath);
        // A held joint of the stacks as one that breaks at once: the stack that stopped slips
        // again (the other way), or another joint does, as that joint's slip decides
        // ([`Engine::stack_splits`], which tries the body's ways on the stacks split and not).
        let Some(broken) = self.breaks_on(i, &shift, tr.mode, &state, now) else {
            self.stack_gives(i, given);
            return;
        };
        let slips = broken.iter().find_map(|g| match g {
            Guard::Held(k) => Some(*k),
            _ => None,
        });
        if slips.is_none() && !broken.is_empty() {
            self.stack_gives(i, given);
            return;
        }
        let energy = |engine: &Self| {
            let t = engine.trajectory(i, now);
            modes::kinetic_j(body, &t, 0.0) + kinetic_j(&engine.tracks[i].displaced, &t, 0.0)
        };
        let before = energy(self);
        let tr = &mut self.tracks[i];
        (tr.displaced, tr.state) = (shift, state);
        self.rec.energy.impact_loss_j += before - energy(self);
        let (joint, _, _) = watch.describe(4 * stopped.joint);
        let blocks: Vec<usize> = (watch.held_blocks())
            .filter(|&p| p >= stopped.first)
            .map(|p| self.layout.column_output(i, p))
            .chain(self.layout.outputs(i))
            .collect();
        let what = match on {
            Some(_) => format!("stops slipping on {joint}, sliding on with the stack under it"),
            None => format!("stops on {joint}"),
        };
        self.rec.transitions += 1;
        self.rec
            .rocking_event(self.t, EventKind::Stick, &blocks, None, what);
        if slips.is_some_and(|k| !self.stack_splits(i, k, now)) {
            self.stack_gives(i, given);
        }
    }

    /// Body i on its sliding stack meets `guard`, which the exact model does not follow there:
    /// the run stops, saying what and where.
    pub(super) fn stack_gives(&mut self, i: usize, guard: Guard) {
        let stack = self.tracks[i]
            .displaced
            .sliding
            .expect("a stack that slides");
        if let Guard::Held(k) = guard {
            self.gives(i, k, false);
            return;
        }
        let name = &self.body(i).name;
        let how = match guard {
            Guard::Impact => format!(
                "slides while {name} lands on the stack it carries (a landing on a sliding \
                 stack, an impact of two bodies with the joint's friction impulse, is not \
                 followed)"
            ),
            Guard::PivotSlip => format!(
                "slides while the corner {name} rocks on would slip on the stack it carries, \
                 and that slip's conditions do not hold (a second joint slipping, a flight off \
                 the stack: not followed)"
            ),
            Guard::PivotStick => format!(
                "slides while the corner {name} slide-rocks on stops slipping on the stack it \
                 carries, and no way on holds (stuck on it, slipping either way: a second joint \
                 slipping, a flight off the stack, are not followed)"
            ),
            Guard::Flight => format!("slides while {name} would leave the stack it carries"),
            Guard::Stop | Guard::Beneath(_) => format!(
                "slides while a stack on it stops slipping, and the stacks cannot go on as one \
                 under {name} (their conditions do not hold just after)"
            ),
            Guard::Indeterminate => format!(
                "slides while friction makes the accelerations of {name} and the stack it \
                 carries indeterminate (the effective mass of their motion is not positive: \
                 Painleve's paradox)"
            ),
            _ => format!("slides while {name} changes its mode on the stack it carries"),
        };
        let (joint, _, upper) = self.scene.watches[i].describe(4 * stack.joint);
        let mut blocks = vec![self.layout.column_output(i, upper)];
        blocks.extend(self.layout.outputs(i));
        // A landing stops with the state just before the impact, which it does not resolve.
        self.held_joint_gives(i, &blocks, joint, &how, guard == Guard::Impact);
    }
}

impl Engine<'_> {
    /// Body i lands on the stacks sliding under it: where the new corner sticks and each stack
    /// slides on or is stopped by the impact as the one landing that holds says ([`landing`]),
    /// and every held joint passes the impulses (the stacks' blocks jumping with them), the
    /// body rocks on on its new corner, the stacks whose slip the impact stopped joined to the
    /// one under them or held ([`Displaced::landed`]); any other landing stops the run just
    /// before the impact.
    pub(super) fn stack_lands(&mut self, i: usize, now: &Inputs) -> Result<(), SimulationError> {
        let body = self.body(i);
        let scene = self.scene;
        let watch = &scene.watches[i];
        let tr = &self.tracks[i];
        let Mode::Rock(pivot) = tr.mode else {
            self.stack_gives(i, Guard::Impact);
            return Ok(());
        };
        let (omega, v, u) = (tr.state.omega, tr.state.v, tr.state.u);
        let stacks: Vec<Stack> = (tr.displaced.sliding.iter())
            .chain(&tr.displaced.beneath)
            .copied()
            .collect();
        let before: Vec<f64> = stacks.iter().map(|st| st.velocity_m_s(v)).collect();
        // Where the body's law on the stacks finds no landing, or one whose impulses break a
        // held joint, the chain's law takes it (the joints holding, slipping or opening
        // through the impact), or the run stops just before it.
        let Some(l) = landing(body, &stacks, &before, pivot, omega) else {
            if !self.lands_as_chain(now)? {
                self.stack_gives(i, Guard::Impact);
            }
            return Ok(());
        };
        let held = watch.held_blocks().count();
        let mut after = tr.displaced.clone();
        after.landed(u, &l.v, &l.stuck, held);
        let next = pivot.other();
        let velocities = ((Some(pivot), omega, v), (Some(next), l.omega, l.v[0]));
        if let Some(k) = watch.landing(u, velocities.0, velocities.1, &tr.displaced, &after) {
            if !self.lands_as_chain(now)? {
                self.gives(i, k, true);
            }
            return Ok(());
        }
        // Found at theta = 0 to a tie and seated at 0 on the new corner: the potential energy
        // of that tilt goes with the landing's loss, as at a landing on a held base.
        let dropped = modes::potential_j(body, &self.trajectory(i, now), 0.0);
        self.rec.energy.impact_loss_j += l.loss_j + dropped;
        for k in self.layout.outputs(i) {
            self.rec.rocking_impact(k);
        }
        self.rec.impacts += 1;
        self.rec.transitions += l.stuck.iter().filter(|&&s| s).count() as u64;
        let stopped: Vec<String> = (stacks.iter().zip(&l.stuck))
            .filter(|(_, &stuck)| stuck)
            .map(|(st, _)| watch.describe(4 * st.joint).0)
            .collect();
        let tr = &mut self.tracks[i];
        (tr.state.theta, tr.state.omega, tr.state.v) = (0.0, l.omega, l.v[0]);
        tr.mode = Mode::Rock(next);
        tr.displaced = after;
        let list = |v: &[f64]| {
            v.iter()
                .map(|v| format!("{v:.6e}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        let what = match (&l.stuck[..], &stopped[..]) {
            ([stuck], _) => format!(
                "on the {} corner, on the sliding stack (its velocity {v:.6e} -> {:.6e} m/s{})",
                next.name(),
                l.v[0],
                if *stuck { ": it stops" } else { "" }
            ),
            (_, stopped) => format!(
                "on the {} corner, on the sliding stacks (their velocities {} -> {} m/s{})",
                next.name(),
                list(&before),
                list(&l.v),
                if stopped.is_empty() {
                    String::new()
                } else {
                    format!(": the slip on {} stops", stopped.join(" and "))
                }
            ),
        };
        self.rec.rocking_event(
            self.t,
            EventKind::RockingImpact,
            &self.layout.outputs(i),
            Some((omega, l.omega)),
            what,
        );
        Ok(())
    }
}
