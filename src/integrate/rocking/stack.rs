//! A column's body rocking on its stuck pivot while the stack under it slides: a held joint
//! below the body that gave way by slipping. The blocks between that joint and the body's move
//! as one rigid stack of mass M, translating on the joint with friction mu_s against its slip
//! (sigma its sign); the body rocks on the stack's top as it rocks on a held base, the stack's
//! acceleration and the joint's friction coupling the two. From here the body's u (its pivot's
//! displacement relative to the ground) is the stack's too, up to a constant: the pivot sticks.
//! The stack stops where its slip velocity returns to zero, and is held again, displaced; the
//! displacement stays with its blocks and the joints in it (their contacts move with them: the
//! overlaps of seated blocks are those of the initial configuration, docs/rocking-walls.md).

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
/// slid and was held again), and the stack sliding now.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Displaced {
    /// Per block of the column; empty while nothing has moved.
    pub by_m: Vec<f64>,
    /// The stack sliding now.
    pub sliding: Option<Stack>,
}

impl Displaced {
    /// Block p's displacement as a series along `traj`, and whether it slides with the stack
    /// now (its acceleration then the stack's).
    pub fn block(&self, p: usize, traj: &Trajectory) -> (Coeffs, bool) {
        let slides = self.slides(p);
        let mut out = match (slides, &traj.stack) {
            (false, _) => ZERO,
            (true, Some([moved, _])) => *moved,
            (true, None) => traj.u,
        };
        out[0] = self.at(p, traj.u[0]);
        (out, slides)
    }

    /// Whether block p slides with the stack now.
    pub fn slides(&self, p: usize) -> bool {
        self.sliding.is_some_and(|st| p >= st.first)
    }

    /// Block p's displacement (m) where the body's u is `u_m`.
    pub fn at(&self, p: usize, u_m: f64) -> f64 {
        let moved = self.by_m.get(p).copied().unwrap_or(0.0);
        match self.sliding {
            Some(st @ Stack { apart: None, .. }) if p >= st.first => moved + u_m - st.u_start_m,
            Some(
                st @ Stack {
                    apart: Some([d, _]),
                    ..
                },
            ) if p >= st.first => moved + d,
            _ => moved,
        }
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
    let [moved, v] = stack.apart.expect("a stack apart from the body's pivot");
    let (big, mu, sigma) = (stack.mass_kg, stack.friction, stack.slip.sign());
    let g = body.g_m_s2;
    let (mut u_s, mut v_s) = (ZERO, ZERO);
    (u_s[0], v_s[0]) = (moved, v);
    for k in 0..ORDER {
        let load = t.normal[k] + big * g * inputs.lambda[k];
        let acc = (-t.tangential[k] - mu * sigma * load) / big - inputs.accel[k];
        let kk = (k + 1) as f64;
        u_s[k + 1] = v_s[k] / kk;
        v_s[k + 1] = acc / kk;
    }
    t.stack = Some([u_s, v_s]);
    t
}

/// The stack's velocity along `traj` as a series: its own where the body's pivot slips on it,
/// else the body's pivot's.
fn velocity(traj: &Trajectory) -> &Coeffs {
    traj.stack.as_ref().map_or(&traj.v, |[_, v]| v)
}

/// The stack's own conditions along `traj`, added to the body's in `out`: its slip goes on
/// (sigma u_s' > 0, strict: a stack whose slip would not begin does not slide); where the
/// body's pivot slips on it ([`slide_rocking`]) that slip's condition is relative to the
/// stack, sigma_r (u' - u_s') > 0. That the coupled motion stays determinate (the denominator
/// positive: where it falls to zero friction makes the acceleration indeterminate, Painleve's
/// paradox) is among the body's conditions (`modes::constraints`, from the denominator's
/// series).
pub fn conditions(body: &RockingBody, stack: &Stack, traj: &Trajectory, out: &mut Vec<Constraint>) {
    if let (Mode::SlideRock(_, relative), Some([_, v_s])) = (traj.mode, &traj.stack) {
        for c in out.iter_mut().filter(|c| c.guard == Guard::PivotStick) {
            c.series = series::scaled(&series::add(&traj.v, v_s, -1.0), relative.sign());
        }
    }
    out.push(Constraint {
        series: series::scaled(velocity(traj), stack.slip.sign()),
        scale: Scales::of(body).velocity,
        guard: Guard::Stop,
        strict: true,
    });
}

/// The work rates of body and stack together: the input (the body's, and -M a_g u_s' on the
/// stack) and the friction dissipated on the joint the stack slides on (-f u_s'), and where
/// the body's pivot slips on the stack, on the pivot (-F (u' - u_s')). Where the pivot sticks
/// its force is inside the system: its work on the body and on the stack cancel.
pub fn power_series(
    body: &RockingBody,
    stack: &Stack,
    traj: &Trajectory,
    inputs: &Inputs,
) -> (Coeffs, Coeffs) {
    let v_s = velocity(traj);
    let (input, pivot) = modes::power_series(body, traj, inputs);
    let input = series::add(&input, &series::product(&inputs.accel, v_s), -stack.mass_kg);
    let mut load = traj.normal;
    series::add_to(&mut load, &inputs.lambda, stack.mass_kg * body.g_m_s2);
    let mut friction = series::scaled(
        &series::product(&load, v_s),
        stack.friction * stack.slip.sign(),
    );
    if traj.stack.is_some() {
        series::add_to(&mut friction, &pivot, 1.0);
        series::add_to(&mut friction, &series::product(&traj.tangential, v_s), 1.0);
    }
    (input, friction)
}

/// What a body's landing on the stack sliding under it leaves: its angular velocity and the
/// stack's velocity after (rad/s, m/s; 0 where the stack stops), and the kinetic energy lost
/// (J).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Landing {
    pub omega: f64,
    pub v: f64,
    pub loss_j: f64,
}

/// The landing of a body rocking on `pivot` that reaches theta = 0 at `omega`, the stack under
/// it sliding at `v_s`: Housner's assumption on a base that moves (the impulse (P_t, P_n) at the
/// new corner alone, plastic in its normal, the corner sticking on the stack within mu P_n;
/// the stack's joint passing P_n, its friction impulse P_f within mu_s P_n). Either the stack
/// slides on through the impact, P_f = -mu_s sigma P_n: with Delta = omega' - omega and
/// P_n = -m s b (2 omega + Delta), I_O Delta + m h_c dv = -2 m b^2 omega and (m + M) dv =
/// -m h_c Delta + mu_s sigma m s b (2 omega + Delta), Housner's law as M grows without bound;
/// or the impact stops it: the body lands as on a held base moving at v_s (its angular momentum
/// about the new corner kept), and P_f = P_t - M v_s. The first that holds is the landing.
/// `None` where neither does (the corner pushed apart or slipping, the stack turning within
/// the impact, the body landing flat) or the wall's restitution factor is not 1: the landings
/// the model does not follow on a sliding stack.
pub fn landing(
    body: &RockingBody,
    stack: &Stack,
    pivot: Corner,
    omega: f64,
    v_s: f64,
) -> Option<Landing> {
    if body.restitution_factor != 1.0 {
        return None;
    }
    let (m, big, ig) = (body.mass_kg, stack.mass_kg, body.inertia_kg_m2);
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    let (s, sigma, mu_s) = (pivot.sign(), stack.slip.sign(), stack.friction);
    let io = body.corner_inertia_kg_m2();
    let energy =
        |c: f64, omega: f64, v: f64| super::impact::kinetic(body, c, omega, v) + 0.5 * big * v * v;
    // The impulses at the new corner for omega' and the stack's velocity after, and whether
    // they press, stick and carry the rotation onto it.
    let lands = |w: f64, v: f64| {
        let normal = -m * s * b * (w + omega);
        let tangential = m * (v - v_s + h * (w - omega));
        let holds = normal >= 0.0 && tangential.abs() <= body.friction * normal && w * -s > 0.0;
        (holds, tangential, normal)
    };
    let share = m / (m + big);
    let lhs = io - h * share * (m * h - mu_s * sigma * m * s * b);
    let delta = -2.0 * m * b * omega * (b + share * h * mu_s * sigma * s) / lhs;
    let dv = share * (-h * delta + mu_s * sigma * s * b * (2.0 * omega + delta));
    let (w, v) = (omega + delta, v_s + dv);
    if lhs > 0.0 && sigma * v > 0.0 && lands(w, v).0 {
        return Some(Landing {
            omega: w,
            v,
            loss_j: energy(s, omega, v_s) - energy(-s, w, v),
        });
    }
    let w = ((ig + m * (h * h - b * b)) * omega + m * h * v_s) / io;
    let (holds, tangential, normal) = lands(w, 0.0);
    (holds && (tangential - big * v_s).abs() <= mu_s * normal).then(|| Landing {
        omega: w,
        v: 0.0,
        loss_j: energy(s, omega, v_s) - energy(-s, w, 0.0),
    })
}

/// The stack's kinetic energy (J) at tau along `traj`.
pub fn kinetic_j(stack: &Stack, traj: &Trajectory, tau: f64) -> f64 {
    let v = series::eval(velocity(traj), tau);
    0.5 * stack.mass_kg * v * v
}

#[cfg(test)]
#[path = "stack_tests.rs"]
mod tests;

impl Engine<'_> {
    /// Condition k of body i's watch falls: where it is a held joint below the body that
    /// slips, and the body rocks on its pivot, stuck or slipping (one column, exact equations,
    /// nothing beside it), the stack above that joint slides from here, the body on it as the
    /// one way that holds says ([`Engine::stack_ways`]); else `false` (the run stops as
    /// before).
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
        // The stack at rest as it begins.
        let stack = Stack {
            apart: Some([0.0, 0.0]),
            ..stack
        };
        let [way] = self.stack_ways(i, stack, c, slipping, now)[..] else {
            return false;
        };
        let (stack, mode, _) = way;
        let (joint, _, _) = watch.describe(4 * stack.joint);
        let mut blocks: Vec<usize> = watch
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
        blocks.extend(self.layout.outputs(i));
        self.rec.transitions += 1;
        self.rec
            .rocking_event(self.t, EventKind::Slip, &blocks, None, what);
        self.stack_switches(i, way, now);
        true
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
            modes::kinetic_j(body, &t, 0.0) + kinetic_j(&stack, &t, 0.0)
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
        let apart = Stack {
            apart: Some([stack.moved_m(tr.state.u), tr.state.v]),
            ..stack
        };
        match self.stack_ways(i, apart, c, Some(relative), now)[..] {
            [way] => self.stack_switches(i, way, now),
            _ => self.stack_gives(i, Guard::PivotSlip),
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
        match self.stack_ways(i, stack, c, None, now)[..] {
            [way] => self.stack_switches(i, way, now),
            _ => self.stack_gives(i, Guard::PivotStick),
        }
    }

    /// The ways body i can move on the sliding `stack` (its own state in `apart`: how far it
    /// has slid and its velocity now) that meet every condition just after now (the body's,
    /// the stack's and the held joints'): rocking on its pivot stuck on the stack, where the
    /// pivot moves with it (`slipping` none; the body's slip velocity then the stack's), and
    /// slide-rocking on it, the pivot slipping on the stack the way `slipping` says, or either
    /// way from relative rest. Where the effective masses are positive at most one holds (a
    /// stuck pivot within its friction cone, or the slip its limit force drives); several, or
    /// none, stop the run.
    fn stack_ways(
        &self,
        i: usize,
        stack: Stack,
        c: Corner,
        slipping: Option<Slip>,
        now: &Inputs,
    ) -> Vec<(Stack, Mode, State)> {
        let tr = &self.tracks[i];
        let [moved, v_s] = stack.apart.expect("the stack's own state");
        let mut ways = Vec::with_capacity(3);
        if slipping.is_none() {
            let joined = Stack {
                apart: None,
                u_start_m: tr.state.u - moved,
                ..stack
            };
            ways.push((joined, Mode::Rock(c), State { v: v_s, ..tr.state }));
        }
        let slips = match slipping {
            Some(relative) => vec![relative],
            None => vec![Slip::Forward, Slip::Backward],
        };
        ways.extend(
            (slips.into_iter()).map(|relative| (stack, Mode::SlideRock(c, relative), tr.state)),
        );
        ways.retain(|(stack, mode, state)| self.stack_motion_holds(i, stack, *mode, state, now));
        ways
    }

    /// Whether body i in `mode` from `state` on `stack` meets every condition of that motion
    /// (its own, the stack's and the held joints') just after now.
    fn stack_motion_holds(
        &self,
        i: usize,
        stack: &Stack,
        mode: Mode,
        state: &State,
        now: &Inputs,
    ) -> bool {
        let body = self.body(i);
        let traj = match mode {
            Mode::SlideRock(c, relative) => slide_rocking(body, stack, c, relative, state, now),
            Mode::Rock(c) => trajectory(body, stack, c, state, now),
            _ => return false,
        };
        let mut shift = self.tracks[i].displaced.clone();
        shift.sliding = Some(*stack);
        let mut all = modes::constraints(body, Equations::Exact, &traj);
        conditions(body, stack, &traj, &mut all);
        all.extend(self.scene.watches[i].conditions(&traj, now, &shift));
        let scale_t = body.time_scale_s();
        all.iter().all(|c| c.holds_after(scale_t))
    }

    /// Body i goes on in `way` (the stack, the body's mode and state) on the sliding stack,
    /// a change of its mode logged; what its state changes by (a relative slip of round-off
    /// where its pivot sticks on the stack), with its energy, goes with the impact losses, as
    /// where the stack stops.
    fn stack_switches(
        &mut self,
        i: usize,
        (stack, mode, state): (Stack, Mode, State),
        now: &Inputs,
    ) {
        let body = self.body(i);
        let energy = |engine: &Self| {
            let t = engine.trajectory(i, now);
            let on = engine.tracks[i].displaced.sliding;
            modes::kinetic_j(body, &t, 0.0) + on.map_or(0.0, |st| kinetic_j(&st, &t, 0.0))
        };
        let changed = self.tracks[i].state != state;
        let before = if changed { energy(self) } else { 0.0 };
        let old = self.tracks[i].mode;
        let tr = &mut self.tracks[i];
        (tr.displaced.sliding, tr.mode, tr.state) = (Some(stack), mode, state);
        if changed {
            self.rec.energy.impact_loss_j += before - energy(self);
        }
        if let Some(kind) = super::transition(old, mode, false) {
            let what = format!("{} on the stack", mode.name());
            self.rec
                .rocking_event(self.t, kind, &self.layout.outputs(i), None, what);
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
    /// Body i lands on the stack sliding under it: where the new corner sticks and the stack
    /// slides on ([`landing`]) and every held joint passes the impulses (the stack's blocks
    /// jumping with it), the body rocks on on its new corner, the stack still sliding; any
    /// other landing stops the run just before the impact.
    pub(super) fn stack_lands(&mut self, i: usize, now: &Inputs) {
        let body = self.body(i);
        let scene = self.scene;
        let watch = &scene.watches[i];
        let tr = &self.tracks[i];
        let stack = tr.displaced.sliding.expect("a stack that slides");
        let Mode::Rock(pivot) = tr.mode else {
            self.stack_gives(i, Guard::Impact);
            return;
        };
        let (omega, v) = (tr.state.omega, tr.state.v);
        let Some(l) = landing(body, &stack, pivot, omega, v) else {
            self.stack_gives(i, Guard::Impact);
            return;
        };
        let next = pivot.other();
        let before = (Some(pivot), omega, v);
        let after = (Some(next), l.omega, l.v);
        if let Some(k) = watch.landing(tr.state.u, before, after, &tr.displaced) {
            self.gives(i, k, true);
            return;
        }
        // Found at theta = 0 to a tie and seated at 0 on the new corner: the potential energy
        // of that tilt goes with the landing's loss, as at a landing on a held base.
        let dropped = modes::potential_j(body, &self.trajectory(i, now), 0.0);
        self.rec.energy.impact_loss_j += l.loss_j + dropped;
        for k in self.layout.outputs(i) {
            self.rec.rocking_impact(k);
        }
        self.rec.impacts += 1;
        let held = watch.held_blocks().count();
        let tr = &mut self.tracks[i];
        (tr.state.theta, tr.state.omega, tr.state.v) = (0.0, l.omega, l.v);
        tr.mode = Mode::Rock(next);
        if l.v == 0.0 {
            // The impact stopped the stack: held again where it is.
            tr.displaced.stops(tr.state.u, held);
            self.rec.transitions += 1;
        }
        self.rec.rocking_event(
            self.t,
            EventKind::RockingImpact,
            &self.layout.outputs(i),
            Some((omega, l.omega)),
            format!(
                "on the {} corner, on the sliding stack (its velocity {v:.6e} -> {:.6e} m/s{})",
                next.name(),
                l.v,
                if l.v == 0.0 { ": it stops" } else { "" }
            ),
        );
    }
}
