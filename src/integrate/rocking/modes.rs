//! The modes of one rocking body and how the next one is decided. A body rests, slides, rocks
//! about a base corner whose contact sticks, rocks while that corner slips (slide-rock), or
//! flies with both corners off the ground. In a
//! mode its motion is a Taylor series ([`Trajectory`]); the contact conditions of the mode are
//! series too ([`Constraint`]): each must stay non-negative, and the first to fall is the next
//! event. Deciding a mode is checking every mode the contacts allow against all of its
//! conditions just after the instant (the sign of the first coefficient that is not zero: the
//! next derivative decides a tie), and requiring exactly one answer in accelerations.
//!
//! Conventions (Housner 1963): theta > 0 when the body rocks about its right corner (clockwise);
//! u is the horizontal displacement, relative to the ground, of the pivot while rocking and of
//! the base while seated (they agree at theta = 0); a positive ground acceleration pushes the
//! body to the left, so it drives theta negative.

use super::body::RockingBody;
use super::series::{
    self, add, div_at, mul_at, plus, scaled, sign_after, sin_cos_at, Coeffs, ORDER, ZERO,
};
use crate::error::SimulationError;

/// A base corner in the plane of motion.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Corner {
    /// The corner at -b.
    Left,
    /// The corner at +b.
    Right,
}

impl Corner {
    /// -1 for the left corner, +1 for the right one: the sign of theta while rocking on it.
    pub fn sign(self) -> f64 {
        match self {
            Corner::Left => -1.0,
            Corner::Right => 1.0,
        }
    }

    /// The corner of the sign of x (x != 0).
    pub fn of_sign(x: f64) -> Corner {
        if x > 0.0 {
            Corner::Right
        } else {
            Corner::Left
        }
    }

    /// The other corner.
    pub fn other(self) -> Corner {
        match self {
            Corner::Left => Corner::Right,
            Corner::Right => Corner::Left,
        }
    }

    /// "left" or "right", for logs.
    pub fn name(self) -> &'static str {
        match self {
            Corner::Left => "left",
            Corner::Right => "right",
        }
    }
}

/// Which way a contact slips relative to the ground.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slip {
    /// Towards +x.
    Forward,
    /// Towards -x.
    Backward,
}

impl Slip {
    /// +1 forward, -1 backward.
    pub fn sign(self) -> f64 {
        match self {
            Slip::Forward => 1.0,
            Slip::Backward => -1.0,
        }
    }

    /// The slip of a velocity's sign (v != 0).
    pub fn of_sign(v: f64) -> Slip {
        if v > 0.0 {
            Slip::Forward
        } else {
            Slip::Backward
        }
    }
}

/// The inputs at time t of the sine (3 m/s2, 1.3 Hz) that the watches' tests step along.
#[cfg(test)]
pub(super) fn test_inputs_at(t: f64) -> Inputs {
    let motion = crate::motion::Motion::sine(crate::motion::Sine {
        amplitude_m_s2: 3.0,
        frequency_hz: 1.3,
        duration_s: 10.0,
        ..crate::motion::Sine::default()
    })
    .unwrap();
    let seg = motion.segment_at(t);
    inputs(&seg, t - seg.t0)
}

/// A body's velocity at theta = 0: the corner it turns on (none: seated), its angular velocity
/// (rad/s) and the slip velocity of that corner (or of its base) relative to the ground (m/s).
pub(crate) type Velocity = (Option<Corner>, f64, f64);

/// What a body does between two events.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Seated, its base stuck to the ground.
    Rest,
    /// Seated, its base slipping.
    Slide(Slip),
    /// Rocking about a corner that sticks.
    Rock(Corner),
    /// Rocking about a corner that slips (slide-rock).
    SlideRock(Corner, Slip),
    /// Both corners off the ground (free flight): the centroid falls under gravity and the
    /// ground's inertial force, the rotation keeps its rate. The corner is the one the state's
    /// u and lift follow (the pivot it left, or the right corner when it left seated).
    Flight(Corner),
}

impl Mode {
    /// The pivot while rocking.
    pub fn pivot(self) -> Option<Corner> {
        match self {
            Mode::Rock(c) | Mode::SlideRock(c, _) => Some(c),
            _ => None,
        }
    }

    /// The corner the state's u (and in flight its lift) follows: the pivot while rocking, the
    /// corner it left in flight; none while seated.
    pub fn corner(self) -> Option<Corner> {
        match self {
            Mode::Flight(c) => Some(c),
            other => other.pivot(),
        }
    }

    /// Name for logs and summaries.
    pub fn name(self) -> String {
        match self {
            Mode::Rest => "rest".into(),
            Mode::Slide(s) => format!("slide {}", slip_name(s)),
            Mode::Rock(c) => format!("rock on the {} corner", c.name()),
            Mode::SlideRock(c, s) => {
                format!(
                    "slide-rock on the {} corner, slipping {}",
                    c.name(),
                    slip_name(s)
                )
            }
            Mode::Flight(_) => "free flight".into(),
        }
    }
}

fn slip_name(s: Slip) -> &'static str {
    match s {
        Slip::Forward => "+x",
        Slip::Backward => "-x",
    }
}

/// The equations between events.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Equations {
    /// The exact nonlinear equations, with sliding, slide-rock and free flight.
    #[default]
    Exact,
    /// Housner's slender-block linearisation on a base that never slips (the classical model,
    /// for comparison with the literature): theta'' = -p^2 (lambda (alpha sgn theta - theta) +
    /// a_g / g). It lifts at |a_g| = alpha g lambda, where its own equation changes sign.
    Linearised,
}

/// The state of a body: rotation (rad), angular velocity (rad/s), and the horizontal
/// displacement (m) and velocity (m/s) of its pivot (or base), relative to the ground; in free
/// flight also the height of that corner above the ground (m) and its rate (m/s), zero
/// otherwise.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct State {
    /// theta (rad).
    pub theta: f64,
    /// theta' (rad/s).
    pub omega: f64,
    /// u (m).
    pub u: f64,
    /// u' (m/s).
    pub v: f64,
    /// The corner's height in flight (m).
    pub lift: f64,
    /// Its rate (m/s).
    pub lift_v: f64,
}

/// The ground motion over a step as series: horizontal acceleration a_g (m/s2) and the vertical
/// load factor lambda = 1 + a_v / g.
#[derive(Debug, Clone, PartialEq)]
pub struct Inputs {
    /// a_g.
    pub accel: Coeffs,
    /// lambda.
    pub lambda: Coeffs,
}

/// A mode's motion from the current state, as series in tau.
#[derive(Debug, Clone)]
pub struct Trajectory {
    /// The mode.
    pub mode: Mode,
    /// The equations it follows.
    pub equations: Equations,
    /// theta.
    pub theta: Coeffs,
    /// theta'.
    pub omega: Coeffs,
    /// u.
    pub u: Coeffs,
    /// u'.
    pub v: Coeffs,
    /// The height of the corner u follows (zero but in flight).
    pub lift: Coeffs,
    /// Its rate.
    pub lift_v: Coeffs,
    /// Horizontal force of the ground on the body, summed over its contacts (N).
    pub tangential: Coeffs,
    /// Vertical force of the ground on the body, summed (N).
    pub normal: Coeffs,
    /// Seated: the normal force at each corner (left, right), from the moment balance.
    pub corners: Option<(Coeffs, Coeffs)>,
    /// Slide-rock: I_G + m dx^2 - m mu sigma G_y dx at the start, which must be positive
    /// (where it is not, friction makes the acceleration indeterminate: Painleve's paradox).
    pub denominator: Option<f64>,
    /// Where friction enters the denominator of theta'' (slide-rock; a body on a sliding
    /// stack, `stack`): that denominator as a series, which must stay positive along the
    /// motion ([`Guard::Indeterminate`]).
    pub denominator_series: Option<Coeffs>,
    /// A body slide-rocking on a sliding stack (`stack`): the stack's displacement since it
    /// began (m) and its velocity (m/s), as series.
    pub stack: Option<[Coeffs; 2]>,
    /// The stacks sliding beneath that one (`stack::Displaced::beneath`): each one's
    /// displacement since it began and its velocity, as series.
    pub beneath: Vec<[Coeffs; 2]>,
    /// G_y = height of the centroid above the pivot while rocking (h_c seated).
    pub gy: Coeffs,
    /// dx = dG_y/dtheta: horizontal arm of the pivot's normal force about the centroid.
    pub dx: Coeffs,
}

impl Trajectory {
    /// A trajectory of `mode` whose series hold only the state they start from.
    pub(super) fn start(mode: Mode, equations: Equations, state: &State) -> Trajectory {
        let mut t = Trajectory {
            mode,
            equations,
            theta: ZERO,
            omega: ZERO,
            u: ZERO,
            v: ZERO,
            lift: ZERO,
            lift_v: ZERO,
            tangential: ZERO,
            normal: ZERO,
            corners: None,
            denominator: None,
            denominator_series: None,
            stack: None,
            beneath: Vec::new(),
            gy: ZERO,
            dx: ZERO,
        };
        t.theta[0] = state.theta;
        t.omega[0] = state.omega;
        t.u[0] = state.u;
        t.v[0] = state.v;
        t.lift[0] = state.lift;
        t.lift_v[0] = state.lift_v;
        t
    }
}

impl Trajectory {
    /// Coefficient k + 1 of each position and velocity from coefficient k of the velocities and
    /// of the accelerations (theta'', u'', lift''): the series integrated one order on.
    pub(super) fn integrate(&mut self, k: usize, acc_theta: f64, acc_u: f64, acc_lift: f64) {
        if k < ORDER {
            let kk = (k + 1) as f64;
            self.theta[k + 1] = self.omega[k] / kk;
            self.omega[k + 1] = acc_theta / kk;
            self.u[k + 1] = self.v[k] / kk;
            self.v[k + 1] = acc_u / kk;
            self.lift[k + 1] = self.lift_v[k] / kk;
            self.lift_v[k + 1] = acc_lift / kk;
        }
    }
}

/// Coefficient k of s b sin(theta) + h_c cos(theta) and s b cos(theta) - h_c sin(theta).
pub(super) fn arms(body: &RockingBody, s: f64, sin: &Coeffs, cos: &Coeffs, k: usize) -> (f64, f64) {
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    (s * b * sin[k] + h * cos[k], s * b * cos[k] - h * sin[k])
}

/// The trajectory of `mode` from `state` under `inputs`, to order [`ORDER`].
pub fn trajectory(
    body: &RockingBody,
    equations: Equations,
    mode: Mode,
    state: &State,
    inputs: &Inputs,
) -> Trajectory {
    let m = body.mass_kg;
    let g = body.g_m_s2;
    let mu = body.friction;
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    let io = body.corner_inertia_kg_m2();
    let ig = body.inertia_kg_m2;
    let (a, lam) = (&inputs.accel, &inputs.lambda);
    let mut t = Trajectory::start(mode, equations, state);
    let (mut sin, mut cos, mut w) = (ZERO, ZERO, ZERO);
    let (mut acc_theta, mut acc_u, mut acc_lift) = (ZERO, ZERO, ZERO);
    // Slide-rock: theta'' = num / den with num = m X e, X = mu sigma G_y - dx,
    // e = g lambda - G_y w, den = I_G - m dx X.
    let (mut x, mut e, mut num, mut den) = (ZERO, ZERO, ZERO, ZERO);
    let mut lin = ZERO; // linearised: alpha s - theta
    for k in 0..=ORDER {
        match mode {
            Mode::Rest => {
                t.gy[k] = if k == 0 { h } else { 0.0 };
            }
            Mode::Flight(c) => {
                // The centroid at (x_c - s b cos + h sin, lift + G_y) from the corner's place:
                // G_x'' = -a_g, G_y'' = -g lambda and theta'' = 0 give the corner's
                // u'' = -a_g - dx w and lift'' = -g lambda + G_y w (w = theta'^2).
                sin_cos_at(&t.theta, &mut sin, &mut cos, k);
                (t.gy[k], t.dx[k]) = arms(body, c.sign(), &sin, &cos, k);
                w[k] = mul_at(&t.omega, &t.omega, k);
                acc_u[k] = -a[k] - mul_at(&t.dx, &w, k);
                acc_lift[k] = -g * lam[k] + mul_at(&t.gy, &w, k);
            }
            Mode::Slide(sl) => {
                t.gy[k] = if k == 0 { h } else { 0.0 };
                acc_u[k] = -a[k] - mu * sl.sign() * g * lam[k];
            }
            Mode::Rock(c) if equations == Equations::Linearised => {
                let s = c.sign();
                lin[k] = if k == 0 {
                    s * body.slenderness_rad() - t.theta[0]
                } else {
                    -t.theta[k]
                };
                let p2 = body.frequency_parameter_rad_s().powi(2);
                acc_theta[k] = -p2 * (mul_at(lam, &lin, k) + a[k] / g);
                sin_cos_at(&t.theta, &mut sin, &mut cos, k);
                (t.gy[k], t.dx[k]) = arms(body, s, &sin, &cos, k);
            }
            Mode::Rock(c) => {
                let s = c.sign();
                sin_cos_at(&t.theta, &mut sin, &mut cos, k);
                (t.gy[k], t.dx[k]) = arms(body, s, &sin, &cos, k);
                // I_O theta'' = -m (G_y a_g + dx g lambda).
                acc_theta[k] = -m / io * (mul_at(&t.gy, a, k) + g * mul_at(&t.dx, lam, k));
                w[k] = mul_at(&t.omega, &t.omega, k);
                // F = m (G_y theta'' + dx w + a_g), N = m (dx theta'' - G_y w + g lambda).
                t.tangential[k] = m * (mul_at(&t.gy, &acc_theta, k) + mul_at(&t.dx, &w, k) + a[k]);
                t.normal[k] =
                    m * (mul_at(&t.dx, &acc_theta, k) - mul_at(&t.gy, &w, k) + g * lam[k]);
            }
            Mode::SlideRock(c, sl) => {
                let (s, sigma) = (c.sign(), sl.sign());
                sin_cos_at(&t.theta, &mut sin, &mut cos, k);
                (t.gy[k], t.dx[k]) = arms(body, s, &sin, &cos, k);
                w[k] = mul_at(&t.omega, &t.omega, k);
                x[k] = mu * sigma * t.gy[k] - t.dx[k];
                e[k] = g * lam[k] - mul_at(&t.gy, &w, k);
                num[k] = m * mul_at(&x, &e, k);
                den[k] = if k == 0 { ig } else { 0.0 } - m * mul_at(&t.dx, &x, k);
                acc_theta[k] = div_at(&num, &den, &acc_theta, k);
                t.normal[k] =
                    m * (mul_at(&t.dx, &acc_theta, k) - mul_at(&t.gy, &w, k) + g * lam[k]);
                t.tangential[k] = -mu * sigma * t.normal[k];
                acc_u[k] = t.tangential[k] / m
                    - mul_at(&t.gy, &acc_theta, k)
                    - mul_at(&t.dx, &w, k)
                    - a[k];
            }
        }
        t.integrate(k, acc_theta[k], acc_u[k], acc_lift[k]);
    }
    if let Mode::SlideRock(..) = mode {
        (t.denominator, t.denominator_series) = (Some(den[0]), Some(den));
    }
    if matches!(mode, Mode::Rest | Mode::Slide(_)) {
        // Seated: F = m (u'' + a_g), N = m g lambda; the moment about the centroid gives
        // N_R - N_L = -h_c F / b.
        for k in 0..=ORDER {
            t.tangential[k] = match mode {
                Mode::Slide(sl) => -mu * sl.sign() * m * g * lam[k],
                _ => m * a[k],
            };
            t.normal[k] = m * g * lam[k];
        }
        let (mut left, mut right) = (ZERO, ZERO);
        for k in 0..=ORDER {
            let diff = -h * t.tangential[k] / b;
            right[k] = 0.5 * (t.normal[k] + diff);
            left[k] = 0.5 * (t.normal[k] - diff);
        }
        t.corners = Some((left, right));
    }
    t
}

/// What a condition of a mode guards: the event when it fails.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Guard {
    /// Seated and stuck: the friction the base needs reaches its capacity.
    StickLimit,
    /// Seated: the normal force at a corner falls to zero (the resultant reaches the corner).
    Uplift,
    /// A slipping base comes to rest relative to the ground.
    Stop,
    /// Rocking: theta returns to zero, the other corner lands.
    Impact,
    /// Rocking on a stuck corner: the friction it needs reaches its capacity.
    PivotSlip,
    /// Rocking on a slipping corner: its slip stops.
    PivotStick,
    /// The pivot's normal force falls to zero: the body would leave the ground.
    Flight,
    /// In flight, this corner reaches the ground.
    Land(Corner),
    /// The body reaches pi/2 (lies on its face), or, with the ground at rest from now on,
    /// passes alpha with energy to spare (it can only fall).
    Overturn,
    /// A held joint of a column gives way: condition k of its `column::Watch`.
    Held(usize),
    /// The series of landings a body's last landing started has summed to its end: it is
    /// seated from here (in a scene of several bodies, which go on meanwhile).
    Settled,
    /// A body resting against a fixed block (`lean`), or two bodies turning together
    /// (`couple`): the contact's push falls to zero, the bodies parting.
    Parts,
    /// A stack beneath the one under a body (`stack::Displaced::beneath`, its index there)
    /// stops slipping on what is under it.
    Beneath(usize),
    /// A slide-rocking body, or a body rocking on a sliding stack (`stack`): the effective mass
    /// of the motion (the denominator of theta'') falls to zero, friction making the
    /// accelerations indeterminate (Painleve's paradox).
    Indeterminate,
}

/// One condition of a mode: a series that must stay non-negative (positive just after the
/// start, when strict), its scale, and what it guards.
#[derive(Debug, Clone)]
pub struct Constraint {
    /// The series.
    pub series: Coeffs,
    /// Its size (for ties).
    pub scale: f64,
    /// What it guards.
    pub guard: Guard,
    /// Must be positive just after the start (a mode whose motion would not begin is not it).
    pub strict: bool,
}

impl Constraint {
    /// Does it hold just after the start (the sign of its first coefficient that is not zero
    /// at `scale_t`, s, deciding)?
    pub fn holds_after(&self, scale_t: f64) -> bool {
        let sign = sign_after(&self.series, self.scale, scale_t);
        if self.strict {
            sign > 0
        } else {
            sign >= 0
        }
    }
}

/// Scales for ties: forces (N), velocities (m/s), angles (rad).
pub struct Scales {
    /// m g.
    pub force: f64,
    /// p R.
    pub velocity: f64,
    /// alpha.
    pub angle: f64,
}

impl Scales {
    /// The body's scales.
    pub fn of(body: &RockingBody) -> Scales {
        Scales {
            force: body.mass_kg * body.g_m_s2,
            velocity: body.frequency_parameter_rad_s() * body.size_m(),
            angle: body.slenderness_rad(),
        }
    }
}

/// mu N - F and mu N + F: what friction has to spare each way where a contact sticks.
fn friction_margins(t: &Trajectory, mu: f64) -> [Coeffs; 2] {
    let cap = scaled(&t.normal, mu);
    [
        add(&cap, &t.tangential, -1.0),
        add(&cap, &t.tangential, 1.0),
    ]
}

/// The conditions of a trajectory's mode. (With the ground at rest for good, the engine adds
/// the overturning that follows from energy alone.)
pub fn constraints(body: &RockingBody, equations: Equations, t: &Trajectory) -> Vec<Constraint> {
    let sc = Scales::of(body);
    let mu = body.friction;
    let mut out = Vec::new();
    let mut push = |series: Coeffs, scale: f64, guard: Guard, strict: bool| {
        out.push(Constraint {
            series,
            scale,
            guard,
            strict,
        })
    };
    match t.mode {
        Mode::Rest if equations == Equations::Linearised => {
            // The linearised equation lifts where alpha g lambda -+ a_g changes sign.
            let alpha = body.slenderness_rad();
            let gl = scaled(&t.normal, alpha / body.mass_kg);
            let a = scaled(&t.tangential, 1.0 / body.mass_kg);
            push(add(&gl, &a, -1.0), body.g_m_s2, Guard::Uplift, false);
            push(add(&gl, &a, 1.0), body.g_m_s2, Guard::Uplift, false);
        }
        Mode::Rest | Mode::Slide(_) => {
            if let Mode::Slide(sl) = t.mode {
                push(scaled(&t.v, sl.sign()), sc.velocity, Guard::Stop, true);
            } else {
                for margin in friction_margins(t, mu) {
                    push(margin, sc.force, Guard::StickLimit, false);
                }
            }
            let (left, right) = t.corners.as_ref().expect("a seated trajectory has corners");
            push(*left, sc.force, Guard::Uplift, false);
            push(*right, sc.force, Guard::Uplift, false);
        }
        Mode::Rock(c) | Mode::SlideRock(c, _) => {
            let s = c.sign();
            push(scaled(&t.theta, s), sc.angle, Guard::Impact, true);
            let fall = plus(&scaled(&t.theta, -s), std::f64::consts::FRAC_PI_2);
            push(fall, 1.0, Guard::Overturn, false);
            if equations == Equations::Exact {
                push(t.normal, sc.force, Guard::Flight, false);
                match t.mode {
                    Mode::SlideRock(_, sl) => push(
                        scaled(&t.v, sl.sign()),
                        sc.velocity,
                        Guard::PivotStick,
                        true,
                    ),
                    _ => {
                        for margin in friction_margins(t, mu) {
                            push(margin, sc.force, Guard::PivotSlip, false);
                        }
                    }
                }
            }
        }
        Mode::Flight(c) => {
            // Each corner's height: the corner followed, and the other, 2 s b sin theta above
            // it; and the body lying on a face.
            let s = c.sign();
            let b = body.half_base_m;
            let (mut sin, mut cos) = (ZERO, ZERO);
            for k in 0..=ORDER {
                sin_cos_at(&t.theta, &mut sin, &mut cos, k);
            }
            let other = add(&t.lift, &sin, 2.0 * s * b);
            push(t.lift, body.size_m(), Guard::Land(c), false);
            push(other, body.size_m(), Guard::Land(c.other()), false);
            let half_pi = std::f64::consts::FRAC_PI_2;
            push(plus(&t.theta, half_pi), 1.0, Guard::Overturn, false);
            push(
                plus(&scaled(&t.theta, -1.0), half_pi),
                1.0,
                Guard::Overturn,
                false,
            );
        }
    }
    if let Some(den) = t.denominator_series {
        push(den, body.inertia_kg_m2, Guard::Indeterminate, true);
    }
    out
}

/// Where the state stands: seated (both corners on the ground, at rest in rotation) or on one
/// corner.
fn is_seated(state: &State) -> bool {
    state.theta == 0.0 && state.omega == 0.0
}

/// Modes the contacts allow from `state`, with `pivot` the corner it rocks on when not seated.
fn candidates(equations: Equations, state: &State, pivot: Option<Corner>) -> Vec<Mode> {
    let corners = [Corner::Left, Corner::Right];
    let slips: Vec<Slip> = if state.v == 0.0 {
        vec![Slip::Forward, Slip::Backward]
    } else {
        vec![Slip::of_sign(state.v)]
    };
    let mut out = Vec::new();
    match (equations, is_seated(state), pivot) {
        (Equations::Linearised, true, _) => {
            out.push(Mode::Rest);
            out.extend(corners.map(Mode::Rock));
        }
        (Equations::Linearised, false, Some(c)) => out.push(Mode::Rock(c)),
        (Equations::Exact, true, _) => {
            if state.v == 0.0 {
                out.push(Mode::Rest);
            }
            out.extend(slips.iter().map(|&s| Mode::Slide(s)));
            if state.v == 0.0 {
                out.extend(corners.map(Mode::Rock));
            }
            for c in corners {
                out.extend(slips.iter().map(|&s| Mode::SlideRock(c, s)));
            }
            out.push(Mode::Flight(Corner::Right));
        }
        (Equations::Exact, false, Some(c)) => {
            if state.v == 0.0 {
                out.push(Mode::Rock(c));
            }
            out.extend(slips.iter().map(|&s| Mode::SlideRock(c, s)));
            out.push(Mode::Flight(c));
        }
        (_, false, None) => {}
    }
    out
}

/// Does free flight lift every corner on the ground just after now? The centroid falls with
/// g lambda, the rotation keeps its rate; a corner's height is Y_G - (c b sin theta + h_c cos
/// theta) for the corner of sign c.
fn flight_lifts(body: &RockingBody, state: &State, pivot: Option<Corner>, inputs: &Inputs) -> bool {
    let (b, h, g) = (body.half_base_m, body.centroid_height_m, body.g_m_s2);
    let on_ground: Vec<f64> = match pivot {
        Some(c) if !is_seated(state) => vec![c.sign()],
        _ => vec![-1.0, 1.0],
    };
    let s = pivot.map_or(1.0, Corner::sign);
    let (mut theta, mut sin, mut cos) = (ZERO, ZERO, ZERO);
    theta[0] = state.theta;
    theta[1] = state.omega;
    for k in 0..=ORDER {
        sin_cos_at(&theta, &mut sin, &mut cos, k);
    }
    let (sn, cs) = state.theta.sin_cos();
    let mut yg = ZERO;
    yg[0] = s * b * sn + h * cs;
    yg[1] = (s * b * cs - h * sn) * state.omega;
    for k in 0..ORDER - 1 {
        yg[k + 2] = -g * inputs.lambda[k] / ((k + 1) * (k + 2)) as f64;
    }
    on_ground.iter().all(|&c| {
        let mut height = yg;
        for k in 0..=ORDER {
            height[k] -= c * b * sin[k] + h * cos[k];
        }
        sign_after(&height, body.size_m(), body.time_scale_s()) > 0
    })
}

/// Decides the mode from `state` (with `pivot` the corner it rocks on, when it is not seated):
/// every mode the contacts allow is checked against all its conditions just after now, and
/// exactly one must hold (or several with one motion). Errors name the body and what failed:
/// no mode holds (Painleve's inconsistency), several with different motions, or a slipping
/// mode whose corner's effective mass is not positive meets its conditions (Painleve's
/// indeterminacy: with a single contact the rigid model then has a second motion too, or
/// none).
pub fn decide(
    body: &RockingBody,
    equations: Equations,
    state: &State,
    pivot: Option<Corner>,
    inputs: &Inputs,
    time_s: f64,
) -> Result<Trajectory, SimulationError> {
    let scale_t = body.time_scale_s();
    let sc = Scales::of(body);
    let mut holding: Vec<Trajectory> = Vec::new();
    let (mut paradox, mut paradox_holds) = (Vec::new(), Vec::new());
    for mode in candidates(equations, state, pivot) {
        if let Mode::Flight(_) = mode {
            if flight_lifts(body, state, pivot, inputs) {
                holding.push(trajectory(body, equations, mode, state, inputs));
            }
            continue;
        }
        let t = trajectory(body, equations, mode, state, inputs);
        // The denominator at the start is judged below, as the paradox it would be.
        let ok = constraints(body, equations, &t)
            .iter()
            .filter(|c| c.guard != Guard::Indeterminate)
            .all(|c| c.holds_after(scale_t));
        if t.denominator.is_some_and(|d| d <= 0.0) {
            if ok {
                paradox_holds.push(mode.name());
            } else {
                paradox.push(mode.name());
            }
        } else if ok {
            holding.push(t);
        }
    }
    let where_ = || {
        format!(
            "{} at t = {time_s} s (theta = {} rad, theta' = {} rad/s, slip velocity {} m/s)",
            body.name, state.theta, state.omega, state.v
        )
    };
    if !paradox_holds.is_empty() {
        let others: Vec<String> = holding.iter().map(|t| t.mode.name()).collect();
        return Err(SimulationError::RigidModel {
            at: where_(),
            why: format!(
                "Painleve's paradox: {} meets every condition with friction {} making the \
                 effective mass of its slipping corner not positive{}: the rigid model with \
                 Coulomb friction does not determine the motion",
                paradox_holds.join(", "),
                body.friction,
                if others.is_empty() {
                    String::new()
                } else {
                    format!(", and {} holds too", others.join(", "))
                }
            ),
        });
    }
    match holding.len() {
        0 => Err(SimulationError::RigidModel {
            at: where_(),
            why: if paradox.is_empty() {
                "no mode of the contacts holds (rest, slide, rock, slide-rock and flight all \
                 break a contact condition): the rigid model with Coulomb friction has no \
                 solution here"
                    .into()
            } else {
                format!(
                    "Painleve's paradox: friction {} makes the acceleration of {} indeterminate \
                     (the effective mass of the slipping corner is not positive); the rigid \
                     model with Coulomb friction cannot go on",
                    body.friction,
                    paradox.join(", ")
                )
            },
        }),
        1 => Ok(holding.pop().expect("one")),
        _ => {
            // Several modes hold: they must be one motion (the same series), else the decision
            // is not unique.
            let first = &holding[0];
            let same = holding[1..].iter().all(|t| {
                let d_theta = add(&t.theta, &first.theta, -1.0);
                let d_u = add(&t.u, &first.u, -1.0);
                sign_after(&d_theta, sc.angle, scale_t) == 0
                    && sign_after(&d_u, body.size_m(), scale_t) == 0
            });
            if same {
                Ok(holding.swap_remove(0))
            } else {
                let names: Vec<String> = holding.iter().map(|t| t.mode.name()).collect();
                Err(SimulationError::RigidModel {
                    at: where_(),
                    why: format!(
                        "the contact conditions allow several motions ({}): Painleve-type \
                         indeterminacy of the rigid model with Coulomb friction",
                        names.join(", ")
                    ),
                })
            }
        }
    }
}

/// The series of a ground motion's segment from `s` after its start.
pub fn inputs(segment: &crate::motion::Segment, s: f64) -> Inputs {
    use crate::motion::Shape;
    let mut accel = ZERO;
    match segment.shape {
        Shape::Linear { a0, slope } => {
            accel[0] = a0 + slope * s;
            accel[1] = slope;
        }
        Shape::Sine {
            amplitude,
            omega,
            theta0,
            ..
        } => {
            let (sn, cs) = (theta0 + omega * s).sin_cos();
            let cycle = [sn, cs, -sn, -cs];
            let mut factor = amplitude;
            for (k, c) in accel.iter_mut().enumerate() {
                *c = factor * cycle[k % 4];
                factor *= omega / (k + 1) as f64;
            }
        }
    }
    let mut lambda = ZERO;
    lambda[0] = segment.lambda.0 + segment.lambda.1 * s;
    lambda[1] = segment.lambda.1;
    Inputs { accel, lambda }
}

/// The kinetic energy (J) of a trajectory at tau. The linearised equations conserve their own
/// energy, 1/2 I_O theta'^2 + m g R (alpha |theta| - theta^2 / 2): a run with them balances
/// that one.
pub fn kinetic_j(body: &RockingBody, t: &Trajectory, tau: f64) -> f64 {
    let omega = series::eval(&t.omega, tau);
    if t.equations == Equations::Linearised {
        return 0.5 * body.corner_inertia_kg_m2() * omega * omega;
    }
    let v = series::eval(&t.v, tau);
    let gy = series::eval(&t.gy, tau);
    let dx = series::eval(&t.dx, tau);
    let (xg, mut yg) = (v + gy * omega, dx * omega);
    if let Mode::Flight(_) = t.mode {
        yg += series::eval(&t.lift_v, tau);
    }
    0.5 * body.mass_kg * (xg * xg + yg * yg) + 0.5 * body.inertia_kg_m2 * omega * omega
}

/// The potential energy (J) above the seated position at tau: m g (G_y - h_c), with G_y - h_c
/// = s b sin theta - 2 h_c sin^2(theta / 2) computed from theta itself. (G_y - h_c from G_y
/// would cancel: near theta = 0 it keeps only what h_c's last bit can hold, some 1e-12 J for
/// a block of a few tonnes, and a landing found at a tie of 1e-17 rad would lose the energy of
/// that tilt.)
pub fn potential_j(body: &RockingBody, t: &Trajectory, tau: f64) -> f64 {
    let theta = series::eval(&t.theta, tau);
    if t.equations == Equations::Linearised {
        return body.mass_kg
            * body.g_m_s2
            * body.size_m()
            * (body.slenderness_rad() * theta.abs() - 0.5 * theta * theta);
    }
    let Some(pivot) = t.mode.corner() else {
        return body.mass_kg * body.g_m_s2 * (series::eval(&t.gy, tau) - body.centroid_height_m);
    };
    let (b, h) = (body.half_base_m, body.centroid_height_m);
    let half = (0.5 * theta).sin();
    let rise = pivot.sign() * b * theta.sin() - 2.0 * h * half * half;
    let rise = match t.mode {
        Mode::Flight(_) => rise + series::eval(&t.lift, tau),
        _ => rise,
    };
    body.mass_kg * body.g_m_s2 * rise
}

/// Power series of the work rates: input (the inertial forces -m a_g on the centroid's
/// horizontal velocity, and -m g (lambda - 1) on its vertical one) and friction dissipation
/// (-F times the slip velocity).
pub fn power_series(body: &RockingBody, t: &Trajectory, inputs: &Inputs) -> (Coeffs, Coeffs) {
    let m = body.mass_kg;
    if t.equations == Equations::Linearised {
        // Input of the linearised equation: -m R (a_g + g (lambda - 1) (alpha s - theta))
        // theta', with s the side it rocks on.
        let s = t.mode.pivot().map_or(0.0, Corner::sign);
        let lin = plus(&scaled(&t.theta, -1.0), s * body.slenderness_rad());
        let extra = plus(&inputs.lambda, -1.0);
        let load = add(&inputs.accel, &series::product(&extra, &lin), body.g_m_s2);
        let input = scaled(&series::product(&load, &t.omega), -m * body.size_m());
        return (input, ZERO);
    }
    let xg = add(&t.v, &series::product(&t.gy, &t.omega), 1.0);
    let mut yg = series::product(&t.dx, &t.omega);
    if let Mode::Flight(_) = t.mode {
        yg = add(&yg, &t.lift_v, 1.0);
    }
    let extra = plus(&inputs.lambda, -1.0);
    let input = add(
        &scaled(&series::product(&inputs.accel, &xg), -m),
        &series::product(&extra, &yg),
        -m * body.g_m_s2,
    );
    let friction = scaled(&series::product(&t.tangential, &t.v), -1.0);
    (input, friction)
}
