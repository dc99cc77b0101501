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
    /// The body's u when it began (m): the stack has moved by u - this since.
    pub u_start_m: f64,
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
        let mut out = series::constant(self.by_m.get(p).copied().unwrap_or(0.0));
        match self.sliding {
            Some(st) if p >= st.first => {
                series::add_to(&mut out, &traj.u, 1.0);
                out[0] -= st.u_start_m;
                (out, true)
            }
            _ => (out, false),
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
            *d += u_m - st.u_start_m;
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
    t.stack_denominator = Some(den);
    t
}

/// The stack's own conditions along `traj` (its [`trajectory`]): its slip goes on (sigma u' > 0,
/// strict: a stack whose slip would not begin does not slide) and the coupled motion stays
/// determinate (the denominator positive: where it falls to zero friction makes the
/// acceleration indeterminate, Painleve's paradox).
pub fn constraints(body: &RockingBody, stack: &Stack, traj: &Trajectory) -> Vec<Constraint> {
    let sc = Scales::of(body);
    let slips = Constraint {
        series: series::scaled(&traj.v, stack.slip.sign()),
        scale: sc.velocity,
        guard: Guard::Stop,
        strict: true,
    };
    let determinate = traj.stack_denominator.map(|den| Constraint {
        series: den,
        scale: body.inertia_kg_m2,
        guard: Guard::Indeterminate,
        strict: true,
    });
    std::iter::once(slips).chain(determinate).collect()
}

/// The work rates of body and stack together: the input (the body's, and -M a_g u' on the
/// stack) and the friction dissipated on the joint the stack slides on (-f u'). The force at
/// the pivot is inside the system: its work on the body and on the stack cancel.
pub fn power_series(
    body: &RockingBody,
    stack: &Stack,
    traj: &Trajectory,
    inputs: &Inputs,
) -> (Coeffs, Coeffs) {
    let (input, _) = modes::power_series(body, traj, inputs);
    let input = series::add(
        &input,
        &series::product(&inputs.accel, &traj.v),
        -stack.mass_kg,
    );
    let mut load = series::scaled(&traj.normal, 1.0);
    series::add_to(&mut load, &inputs.lambda, stack.mass_kg * body.g_m_s2);
    let friction = series::scaled(
        &series::product(&load, &traj.v),
        stack.friction * stack.slip.sign(),
    );
    (input, friction)
}

/// The stack's kinetic energy (J) at tau along `traj`.
pub fn kinetic_j(stack: &Stack, traj: &Trajectory, tau: f64) -> f64 {
    let v = series::eval(&traj.v, tau);
    0.5 * stack.mass_kg * v * v
}

#[cfg(test)]
#[path = "stack_tests.rs"]
mod tests;

impl Engine<'_> {
    /// Condition k of body i's watch falls: where it is a held joint below the body that
    /// slips, and the body rocks on its stuck pivot (one column, exact equations, nothing
    /// beside it), the stack above that joint slides from here, if every condition of that
    /// motion holds just after now; else `false` (the run stops as before).
    pub(super) fn stack_slides(&mut self, i: usize, k: usize, now: &Inputs) -> bool {
        let tr = &self.tracks[i];
        let (Mode::Rock(c), None) = (tr.mode, &tr.displaced.sliding) else {
            return false;
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
        let body = self.body(i);
        let traj = trajectory(body, &stack, c, &tr.state, now);
        let mut shift = tr.displaced.clone();
        shift.sliding = Some(stack);
        let scale_t = body.time_scale_s();
        let own = constraints(body, &stack, &traj);
        let rocking = modes::constraints(body, Equations::Exact, &traj);
        let held = watch.conditions(&traj, now, &shift);
        if !own
            .iter()
            .chain(&rocking)
            .chain(&held)
            .all(|c| c.holds_after(scale_t))
        {
            return false;
        }
        self.tracks[i].displaced = shift;
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
            "{} slide on {joint} towards {}x (M = {} kg, mu = {}) under {} rocking on its {} \
             corner",
            names.join("+"),
            if stack.slip == Slip::Forward {
                "+"
            } else {
                "-"
            },
            stack.mass_kg,
            stack.friction,
            body.name,
            c.name()
        );
        blocks.extend(self.layout.outputs(i));
        self.rec.transitions += 1;
        self.rec
            .rocking_event(self.t, EventKind::Slip, &blocks, None, what);
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
        let moved = tr.state.u - stack.u_start_m;
        let held = watch.held_blocks().count();
        let tr = &mut self.tracks[i];
        tr.displaced.stops(tr.state.u, held);
        tr.state.v = 0.0;
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
                "slides while the corner {name} rocks on would slip on the stack it carries \
                 (two joints slipping at once are not followed)"
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
