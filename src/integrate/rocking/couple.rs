//! Two rocking bodies in contact. Where an impact between two bodies, each rocking on a pivot
//! (stuck or slipping) or flying off the ground, leaves no speed to part (no restitution, or
//! elastic bounces that accumulate to round-off), the corner of one stays on the face of the other:
//! two columns leaning together. They move as one mechanism (one degree of freedom, one more for
//! each pivot that slips, two more for a body in flight), the contact (frictionless, as at every
//! face between blocks) pushing them apart. This module owns that mechanism's motion: both
//! rotations, the slipping pivots' displacements and the contact's push as series over a step, and
//! the condition that ends it, the push falling to zero (the bodies part). The pivots' conditions
//! (slip, stick, lift) are the rocking modes', on the forces with the push; where the corner
//! reaches an end of the face (it slides off: the bodies part), or another corner the face, is the
//! pair's (`clearance`). A landing of either body ends the couple; the engine resolves the
//! landing's impulses and the contact's at once (`collision::resolve_landing`) and may start
//! another. A body resting against a fixed block whose pivot slips is a couple too, the block its
//! second side, fixed: the body slides down the block's face as a ladder down a wall.
//!
//! With the push P along the face's normal n (into the corner's body), body k's equation about
//! its pivot is I_O,k theta_k'' + m_k G_y,k u_k'' = Q_k + J_k P, Q_k the rocking one (I_O
//! theta'' = -m (G_y a_g + dx g lambda)), u_k'' the pivot's acceleration along the ground (zero
//! while it sticks) and J_k the push's arm: J_1 = -(r_1 x n) for the corner's body, J_2 = r_2 x
//! n for the face's, r_k from pivot k to the corner. A slipping pivot adds the body's two
//! equations of translation, m (u'' + G_y theta'' + dx theta'^2 + a_g) = -mu sigma N + s_k P n_x
//! and m (dx theta'' - G_y theta'^2 + g lambda) = N + s_k P n_y (s_1 = 1, s_2 = -1), with N its
//! normal force and sigma its slip's sign, as in slide-rock. The same J_k give the rate at
//! which the corner leaves the face, J_1 theta_1' + J_2 theta_2' + n_x (u_1' - u_2'), which stays
//! zero: order by order in the series, each body's accelerations are linear in P, and that
//! rate gives P. A body in flight (its pivot's height lift above the ground) is pushed only:
//! I_G theta'' = J_G P about its centroid, the push's arm there J_G = J_k - s_k (dx n_y + G_y
//! n_x), and its centroid accelerates by s_k P n / m beside gravity and the ground's inertial
//! force; the corner's rate gains n_y (lift_1' - lift_2').

use super::body::RockingBody;
use super::clearance::{Side, Touch};
use super::modes::{
    self, arms, Constraint, Corner, Equations, Guard, Inputs, Mode, Scales, Slip, State, Trajectory,
};
use super::series::{mul_at, sign_after, sin_cos_at, Coeffs, ORDER, TIE, ZERO};
use super::{breaks, tie_speed};

/// Two bodies in contact, the corner of the first on a face of the second: the geometry in
/// each body's frame upright (theta = 0), from its pivot, which moves along the ground with
/// the body's u.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Couple {
    /// The contact as the impact that started the couple found it: the corner's block, then
    /// the face's, their pair, and what moves them.
    pub(super) touch: Touch,
    /// The corner's body, then the face's; none for a fixed block (a body resting against it
    /// whose pivot slips).
    pub(super) bodies: [Option<usize>; 2],
    /// Their pivots where u = 0 (m).
    homes: [[f64; 2]; 2],
    /// The corner, from its body's pivot (m).
    corner: [f64; 2],
    /// The face's normal, pointing into the corner's body.
    normal: [f64; 2],
    /// The corner of each body's base its pivot's home is (a seated body's too: it turns on
    /// that corner if it lifts), and the middle of that base from there (m).
    pub(super) pivots: [Corner; 2],
    middles: [[f64; 2]; 2],
    /// The push's arm about each body's pivot where the couple was placed (m; zero for a
    /// fixed block).
    reach: [f64; 2],
}

/// The clockwise rotation by theta of r: (r_x cos + r_y sin, -r_x sin + r_y cos).
fn turned(r: [f64; 2], (sin, cos): (f64, f64)) -> [f64; 2] {
    [r[0] * cos + r[1] * sin, -r[0] * sin + r[1] * cos]
}

/// Its inverse.
fn upright(r: [f64; 2], (sin, cos): (f64, f64)) -> [f64; 2] {
    turned(r, (-sin, cos))
}

fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// The rotations' sines and cosines over a step, the corner from each pivot, the face's
/// normal and the push's arms J_1, J_2, as series.
#[derive(Default)]
struct Geometry {
    sin: [Coeffs; 2],
    cos: [Coeffs; 2],
    r1: [Coeffs; 2],
    r2: [Coeffs; 2],
    n: [Coeffs; 2],
    arm: [Coeffs; 2],
}

impl Geometry {
    /// Order j, the rotations and the pivots' displacements known to order j.
    fn place(&mut self, couple: &Couple, t: [&Trajectory; 2], j: usize) {
        for (k, body) in t.iter().enumerate() {
            sin_cos_at(&body.theta, &mut self.sin[k], &mut self.cos[k], j);
        }
        let one = if j == 0 { 1.0 } else { 0.0 };
        let (c, q) = (couple.corner, couple.normal);
        let (sin, cos) = (&self.sin, &self.cos);
        self.r1[0][j] = c[0] * cos[0][j] + c[1] * sin[0][j];
        self.r1[1][j] = -c[0] * sin[0][j] + c[1] * cos[0][j];
        self.n[0][j] = q[0] * cos[1][j] + q[1] * sin[1][j];
        self.n[1][j] = -q[0] * sin[1][j] + q[1] * cos[1][j];
        let [h1, h2] = couple.homes;
        self.r2[0][j] = self.r1[0][j] + (h1[0] - h2[0]) * one + t[0].u[j] - t[1].u[j];
        self.r2[1][j] = self.r1[1][j] + (h1[1] - h2[1]) * one + t[0].lift[j] - t[1].lift[j];
        let n = &self.n;
        let crossed = |r: &[Coeffs; 2]| mul_at(&r[0], &n[1], j) - mul_at(&r[1], &n[0], j);
        self.arm[0][j] = -crossed(&self.r1);
        self.arm[1][j] = crossed(&self.r2);
    }
}

/// Each body of a couple over a step, and the push (N).
pub(super) struct Motion {
    pub(super) bodies: [Trajectory; 2],
    pub(super) push: Coeffs,
    /// How fast the corner's acceleration away from the face grows with the push (1/kg):
    /// positive for every couple whose pivots stick; where a pivot slips, friction can make it
    /// zero or negative, and the push is then indeterminate (Painleve's paradox for the
    /// mechanism).
    pub(super) compliance: f64,
    /// The corner's acceleration away from the face were the push zero (m/s2): the bodies'
    /// own motion at the instant, which parts them where it is positive.
    pub(super) leaving: f64,
}

/// A side of a couple as its motion needs it: a body in its mode (rocking on a pivot, or in
/// flight) and state, or a fixed block.
#[derive(Clone, Copy)]
pub(super) enum Member<'a> {
    Moves(&'a RockingBody, Mode, &'a State),
    Fixed,
}

impl Member<'_> {
    /// Whether any push moves it along the contact's normal without turning it: a body that
    /// slides seated, rocks on a slipping pivot or flies.
    pub(super) fn translates(&self) -> bool {
        matches!(
            self,
            Member::Moves(_, Mode::Slide(_) | Mode::SlideRock(..) | Mode::Flight(_), _)
        )
    }
}

/// The state of a fixed block's side: never moved.
const UNMOVED: State = State {
    theta: 0.0,
    omega: 0.0,
    u: 0.0,
    v: 0.0,
    lift: 0.0,
    lift_v: 0.0,
};

/// A body's accelerations at one order of the series, affine in the pushes there: theta'' =
/// a.0 + a.1[0] P_0 + a.1[1] P_1, u'' = p.0 + ... and, in flight, lift'' = l.0 + ....
#[derive(Default, Clone, Copy)]
struct Affine {
    a: (f64, [f64; 2]),
    p: (f64, [f64; 2]),
    l: (f64, [f64; 2]),
}

impl Couple {
    /// The couple of the bodies whose pivots are where `homes` say at u = 0 (the corner's body
    /// first; a fixed block's home is any point of it, its state none), in `states`, in
    /// contact at `touch`; none where the push would turn neither body (to a tie of the arms).
    pub(super) fn new(
        touch: &Touch,
        bodies: [Option<usize>; 2],
        homes: [[f64; 2]; 2],
        states: [Option<&State>; 2],
        tie_m: f64,
    ) -> Option<Couple> {
        let couple = Couple::placed(touch, bodies, homes, states);
        couple.turns(tie_m).then_some(couple)
    }

    /// Whether the push turns either body about its pivot, its arm there longer than `tie_m`
    /// where the couple was placed.
    pub(super) fn turns(&self, tie_m: f64) -> bool {
        (0..2).any(|k| self.bodies[k].is_some() && self.reach[k].abs() > tie_m)
    }

    /// Whether the push moves a body in its mode (`members`): one that slides, flies or rocks
    /// on a slipping pivot moves under any push; one that rests or rocks on a stuck pivot, only
    /// under a push whose arm about its pivot is longer than `tie_m`.
    pub(super) fn moves(&self, members: [Member; 2], tie_m: f64) -> bool {
        members.iter().any(Member::translates) || self.turns(tie_m)
    }

    /// The same couple whether or not its push turns a body: the end of two faces lying on
    /// each other at both bodies' pivots (seated blocks face on face, their bottom corners
    /// together) is one.
    pub(super) fn placed(
        touch: &Touch,
        bodies: [Option<usize>; 2],
        homes: [[f64; 2]; 2],
        states: [Option<&State>; 2],
    ) -> Couple {
        let (point, normal) = (touch.point, touch.normal);
        let states = states.map(|s| s.unwrap_or(&UNMOVED));
        let pivots = [0, 1].map(|k| [homes[k][0] + states[k].u, homes[k][1] + states[k].lift]);
        let p1 = pivots[0];
        let couple = Couple {
            touch: Touch {
                stays: true,
                ..*touch
            },
            bodies,
            homes,
            corner: upright(
                [point[0] - p1[0], point[1] - p1[1]],
                states[0].theta.sin_cos(),
            ),
            normal: upright(normal, states[1].theta.sin_cos()),
            pivots: [Corner::Right; 2],
            middles: [[0.0; 2]; 2],
            reach: pivots.map(|p| cross([point[0] - p[0], point[1] - p[1]], normal)),
        };
        let (mut corners, mut middles) = ([Corner::Right; 2], [[0.0; 2]; 2]);
        for k in 0..2 {
            if let Side::Body(_, origin) = touch.sides[k] {
                corners[k] = Corner::of_sign(homes[k][0] - origin[0]);
                middles[k] = [origin[0] - homes[k][0], origin[1] - homes[k][1]];
            }
        }
        Couple {
            pivots: corners,
            middles,
            ..couple
        }
    }

    /// Side k's pivot's home (m).
    pub(super) fn home(&self, k: usize) -> [f64; 2] {
        self.homes[k]
    }

    /// Half the width of side k's base (m): from its pivot's home to the base's middle.
    pub(super) fn half_base_m(&self, k: usize) -> f64 {
        self.middles[k][0].abs()
    }

    /// The bodies of the couple (one where the other side is a fixed block).
    pub(super) fn moving(&self) -> impl Iterator<Item = usize> {
        self.bodies.into_iter().flatten()
    }

    /// The contact where the bodies are in `states` (none for a fixed block), as a touch of
    /// blocks that have not parted.
    pub(super) fn touch_at(&self, states: [Option<&State>; 2]) -> Touch {
        let states = states.map(|s| s.unwrap_or(&UNMOVED));
        let r = turned(self.corner, states[0].theta.sin_cos());
        let p = [
            self.homes[0][0] + states[0].u,
            self.homes[0][1] + states[0].lift,
        ];
        Touch {
            point: [p[0] + r[0], p[1] + r[1]],
            normal: turned(self.normal, states[1].theta.sin_cos()),
            ..self.touch
        }
    }

    /// Both sides' motion from their states in their modes (each body rocking on a pivot that
    /// sticks or slips, or in flight; a fixed block's trajectory stays zero) under `inputs`, to
    /// order [`ORDER`], and the push.
    pub(super) fn motion(&self, members: [Member; 2], inputs: &Inputs) -> Motion {
        let both = pushed(&[self], members, inputs);
        Motion {
            bodies: both.bodies,
            push: both.pushes[0],
            compliance: both.compliance[0][0],
            leaving: both.leaving[0],
        }
    }

    /// How far the corner stands outside the face over the step on which the sides move as `t`
    /// says (m), the corner on the face at its start with no normal velocity there (what is
    /// left of it is a landing's round-off, below the tie the caller found it at rest by):
    /// r_2 . n less its value there, the face's own points at a fixed distance along the normal
    /// that turns with it. Where the corner's acceleration away from the face is zero to a tie
    /// (a push that falls to zero at the instant the corner would stop leaving), the orders
    /// after it say whether the corner leaves.
    pub(super) fn gap(&self, t: &[Trajectory; 2]) -> Coeffs {
        self.distance(t, 2)
    }

    /// The same distance where the corner may move along the normal at the start: its rate
    /// there kept.
    pub(super) fn approach(&self, t: &[Trajectory; 2]) -> Coeffs {
        self.distance(t, 1)
    }

    /// r_2 . n less its value at the start, from order `first` on.
    fn distance(&self, t: &[Trajectory; 2], first: usize) -> Coeffs {
        let mut at = Geometry::default();
        let mut gap = ZERO;
        for (j, g) in gap.iter_mut().enumerate() {
            at.place(self, [&t[0], &t[1]], j);
            if j >= first {
                *g = mul_at(&at.r2[0], &at.n[0], j) + mul_at(&at.r2[1], &at.n[1], j);
            }
        }
        gap
    }

    /// The modes of a couple's bodies (`members`, each rocking on the pivot of its mode, or in
    /// flight): every way their pivots may stick, slip (a pivot slipping now keeps its
    /// direction) or leave the ground is checked against the bodies' conditions just after now
    /// (none for a fixed block's side; a body off the ground stays in flight; a pivot leaves
    /// the ground only where its height grows just after now, not where it stays zero to a
    /// tie). A way whose push moves neither body (its compliance zero to a tie of a free body's,
    /// as on stuck pivots both on the push's line) cannot hold the contact closed; it counts
    /// only as one that opens it. Where every other way's effective mass is positive (each
    /// slipping body's D and the push's compliance), exactly one must hold with the contact
    /// closed, the push's own condition not among them: where it falls at once, the blocks
    /// part at this instant. Where friction leaves one not positive (Painleve), the law may
    /// have no motion or several, so every way counts twice, with the contact closed and
    /// pressing and with it open (each body alone, the corner leaving the face), and exactly
    /// one must hold: closed, it is taken; open, the one way that holds closed is, and parts
    /// them at once. Else why not, in words, naming each way and what breaks it.
    pub(super) fn decide(
        &self,
        members: [Member; 2],
        now: &Inputs,
    ) -> Result<[Option<Mode>; 2], String> {
        // The push at the instant, against the first moving body's weight.
        let pressing = |motion: &Motion| {
            members.iter().find_map(|m| match m {
                Member::Moves(body, ..) => {
                    Some(sign_after(&motion.push, Scales::of(body).force, body.time_scale_s()) >= 0)
                }
                Member::Fixed => None,
            }) == Some(true)
        };
        let tie_accel = members.iter().find_map(|m| match m {
            Member::Moves(body, ..) => Some(TIE * body.g_m_s2),
            Member::Fixed => None,
        });
        let tie_compliance = tie_compliance(members);
        // Each way with the contact closed and its pivots' conditions met (and whether the push
        // presses), the others with what breaks; each way met with the contact open, the
        // bodies alone and the corner leaving the face; the ways whose effective mass is not
        // positive.
        let (mut holding, mut broken, mut opening, mut paradox) =
            (Vec::new(), Vec::new(), Vec::new(), Vec::new());
        for (modes, trial) in self.trials(members) {
            let named = || -> String {
                let each = trial.iter().filter_map(|m| match m {
                    Member::Moves(body, mode, _) => Some(format!("{} {}", body.name, mode.name())),
                    Member::Fixed => None,
                });
                each.collect::<Vec<_>>().join(" with ")
            };
            let motion = self.motion(trial, now);
            // No push moves either body this way (its arm about each stuck pivot zero, as
            // where the contact is on the line through both pivots).
            let unmoved = motion.compliance.abs() <= tie_compliance;
            if (!unmoved && motion.compliance < 0.0)
                || (motion.bodies.iter()).any(|t| t.denominator.is_some_and(|d| d <= 0.0))
            {
                paradox.push(named());
            }
            let (_, alone) = alone(trial, now);
            if alone && tie_accel.is_some_and(|tie| motion.leaving > tie) {
                opening.push(named());
            }
            if unmoved {
                broken.push(format!(
                    "{}: no push on the contact would move either block",
                    named()
                ));
                continue;
            }
            match (0..2).find_map(|k| broken_by(trial[k], &motion.bodies[k])) {
                None => holding.push((modes, named(), pressing(&motion))),
                Some((body, guard)) => {
                    broken.push(format!("{}: {body} would {}", named(), breaks(guard)));
                }
            }
        }
        let names = |ways: &[&String]| {
            (ways.iter())
                .map(|n| n.as_str())
                .collect::<Vec<_>>()
                .join("; ")
        };
        if paradox.is_empty() {
            // Every way's effective mass positive: at most one holds with the contact (a push
            // that falls at once parts the bodies at this instant).
            return match &holding[..] {
                [(modes, ..)] => Ok(*modes),
                [] => Err(format!(
                    "no mode of the pivots holds with the contact ({})",
                    broken.join("; ")
                )),
                _ => Err(format!(
                    "several modes of the pivots hold with the contact ({}): the rigid model \
                     with Coulomb friction does not say which",
                    names(&holding.iter().map(|(_, n, _)| n).collect::<Vec<_>>())
                )),
            };
        }
        // Friction leaves some way's effective mass not positive (Painleve): the law may then
        // have no motion or several, so every way counts, the contact closed and pressing or
        // open and parting.
        let closed: Vec<_> = holding.iter().filter(|(.., presses)| *presses).collect();
        let paradox = names(&paradox.iter().collect::<Vec<_>>());
        match (&closed[..], &opening[..], &holding[..]) {
            ([(modes, ..)], [], _) => Ok(*modes),
            // The contact opens at once: the one way that holds with it parts the bodies now.
            ([], [_], [(modes, ..)]) => Ok(*modes),
            ([], [], _) => Err(format!(
                "Painleve's paradox: no mode of the pivots holds, with the contact pressing or \
                 parting, friction making the effective mass of {paradox} not positive ({}): the \
                 rigid model with Coulomb friction has no motion here",
                broken.join("; ")
            )),
            ([], [open], _) => Err(format!(
                "Painleve's paradox: only {open}, the contact parting, holds, friction making the \
                 effective mass of {paradox} not positive, and no way of the pivots with the \
                 contact leads there"
            )),
            _ => Err(format!(
                "Painleve's paradox: several motions hold ({}{}), friction making the effective \
                 mass of {paradox} not positive: the rigid model with Coulomb friction does not \
                 determine the motion",
                names(&closed.iter().map(|(_, n, _)| n).collect::<Vec<_>>()),
                opening
                    .iter()
                    .map(|n| format!("; {n}, the contact parting"))
                    .collect::<String>()
            )),
        }
    }

    /// Whether the bodies (`members`), each alone in its mode, close the contact just after
    /// (its distance falls below zero beyond a tie).
    pub(super) fn closed_alone(&self, members: [Member; 2], now: &Inputs) -> bool {
        self.closes(&alone(members, now).0)
    }

    /// Whether the sides moving as `t` say close the contact just after.
    fn closes(&self, t: &[Trajectory; 2]) -> bool {
        let (size, scale_t) = self.touch.scales;
        sign_after(&self.gap(t), size, scale_t) < 0
    }

    /// Every way of the couple's bodies (`members`): each side's mode in it (none for a fixed
    /// block's) and the members in those modes.
    fn trials<'m>(
        &self,
        members: [Member<'m>; 2],
    ) -> impl Iterator<Item = ([Option<Mode>; 2], [Member<'m>; 2])> {
        let seconds = ways(members[1], self.pivots[1]);
        ways(members[0], self.pivots[0])
            .into_iter()
            .flat_map(move |first| seconds.clone().into_iter().map(move |s| [first, s]))
            .map(move |modes| {
                let trial = [0, 1].map(|k| match (members[k], modes[k]) {
                    (Member::Moves(body, _, state), Some(mode)) => Member::Moves(body, mode, state),
                    _ => Member::Fixed,
                });
                (modes, trial)
            })
    }

    /// The one way of the bodies (`members`) in which no push on the contact moves either
    /// body (its compliance zero to a tie, as on stuck pivots both on the push's line) while
    /// each body alone meets its conditions and their motions alone do not close the contact:
    /// there it carries nothing, and each body goes on alone. None where no way, or more than
    /// one, is so.
    pub(super) fn unpushed(&self, members: [Member; 2], now: &Inputs) -> Option<[Option<Mode>; 2]> {
        let tie = tie_compliance(members);
        let mut found = self.trials(members).filter(|&(_, trial)| {
            if self.motion(trial, now).compliance.abs() > tie {
                return false;
            }
            let (trajectories, holds) = alone(trial, now);
            holds && !self.closes(&trajectories)
        });
        match (found.next(), found.next()) {
            (Some((modes, _)), None) => Some(modes),
            _ => None,
        }
    }

    /// The contact lasts while the push stays >= 0.
    pub(super) fn condition(&self, body: &RockingBody, motion: &Motion) -> Constraint {
        Constraint {
            series: motion.push,
            scale: Scales::of(body).force,
            guard: Guard::Parts,
            strict: false,
        }
    }
}

/// Each side of a way (`trial`) moving alone, without the contact, and whether each body's
/// conditions hold so.
fn alone(trial: [Member; 2], now: &Inputs) -> ([Trajectory; 2], bool) {
    let trajectories = trial.map(|m| match m {
        Member::Moves(body, mode, state) => {
            modes::trajectory(body, Equations::Exact, mode, state, now)
        }
        Member::Fixed => Trajectory::start(Mode::Rest, Equations::Exact, &UNMOVED),
    });
    let holds = (0..2).all(|k| broken_by(trial[k], &trajectories[k]).is_none());
    (trajectories, holds)
}

/// The compliance of a push (1/kg) told from zero: a tie of a free body's, 1/m, the lightest
/// moving body's.
fn tie_compliance(members: [Member; 2]) -> f64 {
    TIE * (members.iter())
        .map(|m| match m {
            Member::Moves(body, ..) => 1.0 / body.mass_kg,
            Member::Fixed => 0.0,
        })
        .fold(0.0, f64::max)
}

/// The sides' motion where one or two contacts (`ends`) hold them together, and each
/// contact's push.
pub(super) struct Pushed {
    /// Each side's trajectory, in the order of the first contact's sides.
    pub(super) bodies: [Trajectory; 2],
    /// Each contact's push (N); the second zero where there is one contact.
    pub(super) pushes: [Coeffs; 2],
    /// How fast each contact's acceleration away from its face grows with each push (1/kg): W
    /// of the contact problem at the start of the step, W[e][f] for contact e and push f.
    pub(super) compliance: [[f64; 2]; 2],
    /// Each contact's acceleration away from its face were the pushes zero (m/s2).
    pub(super) leaving: [f64; 2],
}

/// The motion of two sides held together by one contact, or two (the two ends of two faces
/// lying on each other): the couple's equations with one push per contact. Each body's
/// accelerations are affine in the pushes order by order, and each contact's rate of leaving
/// its face stays zero, so each order's pushes solve a system of one or two equations whose
/// matrix is W. The sides are in the order of `ends[0]`; a second contact's corner may be on
/// either side.
pub(super) fn pushed(ends: &[&Couple], members: [Member; 2], inputs: &Inputs) -> Pushed {
    let count = ends.len();
    // Side b of the first contact is side slot[e][b] of contact e.
    let slot: Vec<[usize; 2]> = (ends.iter())
        .map(|c| match c.bodies == ends[0].bodies {
            true => [0, 1],
            false => [1, 0],
        })
        .collect();
    let (a, lam) = (&inputs.accel, &inputs.lambda);
    let mut t = members.map(|m| match m {
        Member::Moves(_, mode, state) => Trajectory::start(mode, Equations::Exact, state),
        Member::Fixed => Trajectory::start(Mode::Rest, Equations::Exact, &UNMOVED),
    });
    let mut at: [Geometry; 2] = Default::default();
    let (mut acc, mut acc_u, mut acc_lift) = ([ZERO; 2], [ZERO; 2], [ZERO; 2]);
    let mut w = [ZERO; 2];
    // The push's arm about each body's centroid, per contact (a body in flight).
    let mut arm_g = [[ZERO; 2]; 2];
    let mut push = [ZERO; 2];
    let (mut compliance, mut leaving) = ([[0.0; 2]; 2], [0.0; 2]);
    let io = members.map(|m| match m {
        Member::Moves(body, ..) => body.corner_inertia_kg_m2(),
        Member::Fixed => 0.0,
    });
    let place = |at: &mut [Geometry; 2], t: &[Trajectory; 2], j: usize| {
        for e in 0..count {
            let [p, q] = slot[e];
            at[e].place(ends[e], [&t[p], &t[q]], j);
        }
    };
    place(&mut at, &t, 0);
    for k in 0..=ORDER {
        if k < ORDER {
            for tk in t.iter_mut() {
                tk.theta[k + 1] = tk.omega[k] / (k + 1) as f64;
                tk.u[k + 1] = tk.v[k] / (k + 1) as f64;
                tk.lift[k + 1] = tk.lift_v[k] / (k + 1) as f64;
            }
            place(&mut at, &t, k + 1);
        }
        let mut affine = [Affine::default(); 2];
        for (b, member) in members.iter().enumerate() {
            let Member::Moves(body, mode, _) = *member else {
                continue;
            };
            let (m, g) = (body.mass_kg, body.g_m_s2);
            // The push of contact e on body b: +n on its corner's body, -n on its face's.
            let on = |e: usize| if slot[e][b] == 0 { 1.0 } else { -1.0 };
            let earlier =
                |x: &Coeffs, y: &Coeffs| -> f64 { (1..=k).map(|j| x[j] * y[k - j]).sum() };
            if let Mode::Rest | Mode::Slide(_) = mode {
                // Seated: it does not turn; a slipping base moves by m (u'' + a_g) = -mu
                // sigma N + s_k P n_x with N = m g lambda - s_k P n_y.
                t[b].gy[k] = if k == 0 { body.centroid_height_m } else { 0.0 };
                affine[b] = match mode {
                    Mode::Slide(sl) => {
                        let f = body.friction * sl.sign();
                        let mut p = (-a[k] - f * g * lam[k], [0.0; 2]);
                        for e in 0..count {
                            let n = &at[e].n;
                            let known = earlier(&n[0], &push[e]) + f * earlier(&n[1], &push[e]);
                            p.0 += on(e) * known / m;
                            p.1[e] = on(e) * (n[0][0] + f * n[1][0]) / m;
                        }
                        Affine {
                            p,
                            ..Affine::default()
                        }
                    }
                    _ => Affine::default(),
                };
                continue;
            }
            let s = mode
                .corner()
                .expect("a body of a couple is seated, rocks on a pivot or flies from one")
                .sign();
            (t[b].gy[k], t[b].dx[k]) =
                arms(body, s, &at[0].sin[slot[0][b]], &at[0].cos[slot[0][b]], k);
            w[b][k] = mul_at(&t[b].omega, &t[b].omega, k);
            let tb = &t[b];
            let q = -m * (mul_at(&tb.gy, a, k) + g * mul_at(&tb.dx, lam, k));
            let mut rm = q - m * earlier(&tb.gy, &acc_u[b]);
            for e in 0..count {
                rm += earlier(&at[e].arm[slot[e][b]], &push[e]);
            }
            let j0 = [0, 1].map(|e| {
                if e < count {
                    at[e].arm[slot[e][b]][0]
                } else {
                    0.0
                }
            });
            let (gy0, dx0) = (tb.gy[0], tb.dx[0]);
            affine[b] = match mode {
                Mode::Flight(_) => {
                    // Pushed only: about the centroid I_G theta'' = J_G P, J_G = J - s_k
                    // (dx n_y + G_y n_x) the push's arm there, and the centroid's
                    // accelerations (u'' + G_y theta'' + dx w + a_g, lift'' + dx theta'' -
                    // G_y w + g lambda) are s_k P n / m.
                    let ig = body.inertia_kg_m2;
                    // The sum over the contacts starts from the first one's term, so that one
                    // contact's arithmetic is the couple's to the bit.
                    let mut turn = (0.0, [0.0; 2]);
                    let mut rh = -a[k] - earlier(&tb.gy, &acc[b]) - mul_at(&tb.dx, &w[b], k);
                    let mut rv = -g * lam[k] - earlier(&tb.dx, &acc[b]) + mul_at(&tb.gy, &w[b], k);
                    for e in 0..count {
                        let n = &at[e].n;
                        arm_g[e][b][k] = at[e].arm[slot[e][b]][k]
                            - on(e) * (mul_at(&tb.dx, &n[1], k) + mul_at(&tb.gy, &n[0], k));
                        let x = earlier(&arm_g[e][b], &push[e]) / ig;
                        turn.0 = if e == 0 { x } else { turn.0 + x };
                        turn.1[e] = arm_g[e][b][0] / ig;
                        rh += on(e) * earlier(&n[0], &push[e]) / m;
                        rv += on(e) * earlier(&n[1], &push[e]) / m;
                    }
                    let per = |e: usize, n: usize| {
                        if e < count {
                            on(e) * at[e].n[n][0] / m
                        } else {
                            0.0
                        }
                    };
                    Affine {
                        a: turn,
                        p: (
                            rh - gy0 * turn.0,
                            [0, 1].map(|e| per(e, 0) - gy0 * turn.1[e]),
                        ),
                        l: (
                            rv - dx0 * turn.0,
                            [0, 1].map(|e| per(e, 1) - dx0 * turn.1[e]),
                        ),
                    }
                }
                Mode::SlideRock(_, slip) => {
                    let f = body.friction * slip.sign();
                    let mut rh = -m * (earlier(&tb.gy, &acc[b]) + mul_at(&tb.dx, &w[b], k) + a[k]);
                    let mut rv =
                        -m * (earlier(&tb.dx, &acc[b]) - mul_at(&tb.gy, &w[b], k) + g * lam[k]);
                    let mut along = [0.0; 2];
                    for e in 0..count {
                        let n = &at[e].n;
                        rh += on(e) * earlier(&n[0], &push[e]);
                        rv += on(e) * earlier(&n[1], &push[e]);
                        along[e] = on(e) * (n[0][0] + f * n[1][0]);
                    }
                    // Slide-rock's denominator I_G + m dx^2 - m mu sigma G_y dx.
                    let d = io[b] - m * gy0 * (gy0 + f * dx0);
                    if k == 0 {
                        t[b].denominator = Some(d);
                    }
                    // N from the vertical equation into the horizontal one gives u'', and
                    // that into the moment about the pivot theta'', each affine in P.
                    let turn = (
                        (rm - gy0 * (rh + f * rv)) / d,
                        [0, 1].map(|e| (j0[e] - gy0 * along[e]) / d),
                    );
                    let lever = gy0 + f * dx0;
                    Affine {
                        a: turn,
                        p: (
                            (rh + f * rv) / m - lever * turn.0,
                            [0, 1].map(|e| along[e] / m - lever * turn.1[e]),
                        ),
                        l: (0.0, [0.0; 2]),
                    }
                }
                _ => Affine {
                    a: (rm / io[b], j0.map(|j| j / io[b])),
                    ..Affine::default()
                },
            };
        }
        // The rate at which each contact's corner leaves its face, at order k + 1, but for
        // the accelerations at order k: J_1 theta_1'' + J_2 theta_2'' + n_x (u_1'' - u_2'') +
        // n_y (lift_1'' - lift_2'') = c (at the last order, whose accelerations give only
        // forces, the rate's term lies beyond the series).
        let mut rhs = [0.0; 2];
        let mut matrix = [[0.0; 2]; 2];
        for e in 0..count {
            let [p, q] = slot[e];
            let (t0, t1) = (&t[p], &t[q]);
            let g = &at[e];
            let c = if k < ORDER {
                let dv = |j: usize| t0.v[j] - t1.v[j];
                let dl = |j: usize| t0.lift_v[j] - t1.lift_v[j];
                let known: f64 = (1..=k + 1)
                    .map(|j| {
                        g.arm[0][j] * t0.omega[k + 1 - j]
                            + g.arm[1][j] * t1.omega[k + 1 - j]
                            + g.n[0][j] * dv(k + 1 - j)
                            + g.n[1][j] * dl(k + 1 - j)
                    })
                    .sum();
                -((k + 1) as f64) * known
            } else {
                0.0
            };
            let (j1, j2) = (g.arm[0][0], g.arm[1][0]);
            let (nx, ny) = (g.n[0][0], g.n[1][0]);
            let [f1, f2] = [&affine[p], &affine[q]];
            let free = j1 * f1.a.0 + j2 * f2.a.0 + nx * (f1.p.0 - f2.p.0) + ny * (f1.l.0 - f2.l.0);
            for (f, entry) in matrix[e].iter_mut().enumerate().take(count) {
                *entry = j1 * f1.a.1[f]
                    + j2 * f2.a.1[f]
                    + nx * (f1.p.1[f] - f2.p.1[f])
                    + ny * (f1.l.1[f] - f2.l.1[f]);
            }
            if k == 0 {
                leaving[e] = free - c;
            }
            rhs[e] = c - free;
        }
        if k == 0 {
            compliance = matrix;
        }
        let solved = match count {
            1 => [rhs[0] / matrix[0][0], 0.0],
            _ => {
                let [[w00, w01], [w10, w11]] = matrix;
                let det = w00 * w11 - w01 * w10;
                [
                    (rhs[0] * w11 - w01 * rhs[1]) / det,
                    (w00 * rhs[1] - w10 * rhs[0]) / det,
                ]
            }
        };
        for e in 0..count {
            push[e][k] = solved[e];
        }
        for (b, member) in members.iter().enumerate() {
            let Member::Moves(body, ..) = *member else {
                continue;
            };
            let by = |x: (f64, [f64; 2])| (0..count).fold(x.0, |sum, e| sum + x.1[e] * push[e][k]);
            acc[b][k] = by(affine[b].a);
            acc_u[b][k] = by(affine[b].p);
            acc_lift[b][k] = by(affine[b].l);
            if let Member::Moves(_, Mode::Flight(_), _) = member {
                continue;
            }
            // The ground's forces: what moves the body, less the pushes on it (+n on a
            // contact's corner's body, -n on its face's).
            let (m, g) = (body.mass_kg, body.g_m_s2);
            let (tb, ab, wb) = (&t[b], &acc[b], &w[b]);
            let mut fx = m * (mul_at(&tb.gy, ab, k) + mul_at(&tb.dx, wb, k) + a[k] + acc_u[b][k]);
            let mut fy = m * (mul_at(&tb.dx, ab, k) - mul_at(&tb.gy, wb, k) + g * lam[k]);
            for e in 0..count {
                let on = if slot[e][b] == 0 { 1.0 } else { -1.0 };
                fx -= on * mul_at(&push[e], &at[e].n[0], k);
                fy -= on * mul_at(&push[e], &at[e].n[1], k);
            }
            t[b].tangential[k] = fx;
            t[b].normal[k] = fy;
        }
        if k < ORDER {
            for b in 0..2 {
                t[b].omega[k + 1] = acc[b][k] / (k + 1) as f64;
                t[b].v[k + 1] = acc_u[b][k] / (k + 1) as f64;
                t[b].lift_v[k + 1] = acc_lift[b][k] / (k + 1) as f64;
            }
        }
    }
    for (b, member) in members.iter().enumerate() {
        if let Member::Moves(body, Mode::Rest | Mode::Slide(_), _) = *member {
            let loads: Vec<(usize, &Couple, &Coeffs, &Geometry)> = (0..count)
                .map(|e| (slot[e][b], ends[e], &push[e], &at[e]))
                .collect();
            t[b].corners = Some(seated_corners(body, &t[b], &loads));
        }
    }
    Pushed {
        bodies: t,
        pushes: push,
        compliance,
        leaving,
    }
}

/// A seated body's normal forces at its base's corners (left, right) with the pushes on it
/// (`loads`: for each contact, the body's side in it, the contact, its push and geometry): its
/// moments about the centroid, b (N_R - N_L) + h_c F + sum of r x Q = 0, Q = s P n at r from
/// the centroid (the seated trajectory's N_R - N_L = -h_c F / b, and the pushes').
fn seated_corners(
    body: &RockingBody,
    t: &Trajectory,
    loads: &[(usize, &Couple, &Coeffs, &Geometry)],
) -> (Coeffs, Coeffs) {
    let (bb, h) = (body.half_base_m, body.centroid_height_m);
    let arms: Vec<([Coeffs; 2], [Coeffs; 2])> = (loads.iter())
        .map(|&(b, couple, push, at)| {
            let on = if b == 0 { 1.0 } else { -1.0 };
            let contact = if b == 0 { &at.r1 } else { &at.r2 };
            let centre = [couple.middles[b][0], couple.middles[b][1] + h];
            let (mut q, mut r) = ([ZERO; 2], *contact);
            for ((q, r), (n, c)) in q.iter_mut().zip(&mut r).zip(at.n.iter().zip(centre)) {
                for (k, x) in q.iter_mut().enumerate() {
                    *x = on * mul_at(push, n, k);
                }
                r[0] -= c;
            }
            (q, r)
        })
        .collect();
    let (mut left, mut right) = (ZERO, ZERO);
    for k in 0..=ORDER {
        let moment = (arms.iter())
            .map(|(q, r)| mul_at(&r[0], &q[1], k) - mul_at(&r[1], &q[0], k))
            .reduce(|sum, x| sum + x)
            .unwrap_or(0.0);
        let diff = -(h * t.tangential[k] + moment) / bb;
        right[k] = 0.5 * (t.normal[k] + diff);
        left[k] = 0.5 * (t.normal[k] - diff);
    }
    (left, right)
}

/// The modes a side of a contact may take just after now (`member`; a fixed block's side, none),
/// on the pivot of its mode or, seated, on `pivot`: every way its pivot may stick, slip (a pivot
/// slipping now keeps its direction) or leave the ground; a body off the ground stays in flight,
/// and a pivot leaves the ground only where its height grows just after now.
pub(super) fn ways(member: Member, pivot: Corner) -> Vec<Option<Mode>> {
    let Member::Moves(body, mode, state) = member else {
        return vec![None];
    };
    let c = mode.corner().unwrap_or(pivot);
    // A pivot that an impulse leaves rising, or slipping, at a tie's rate may stay on the
    // ground, or stick.
    if state.lift != 0.0 || !tie_speed(body, state.lift_v) {
        return vec![Some(Mode::Flight(c))];
    }
    let still = tie_speed(body, state.v);
    let slips = if still {
        vec![Slip::Forward, Slip::Backward]
    } else {
        vec![Slip::of_sign(state.v)]
    };
    // Seated (turning at a tie's rate: an impact law's round-off), it may stay so, the push
    // passing to the ground through its base, or turn on its pivot's corner.
    let tie = TIE * body.slenderness_rad() * body.frequency_parameter_rad_s();
    let seated = state.theta == 0.0 && state.omega.abs() <= tie;
    let rest = (seated && still).then_some(Mode::Rest);
    let slides = slips.iter().filter(|_| seated).map(|&s| Mode::Slide(s));
    let stuck = still.then_some(Mode::Rock(c));
    (rest.into_iter().chain(slides).chain(stuck))
        .chain(slips.iter().map(|&s| Mode::SlideRock(c, s)))
        .chain([Mode::Flight(c)])
        .map(Some)
        .collect()
}

/// The first condition of the mode of `member` (a body's; a fixed block's side has none) that
/// `traj` breaks just after now: the body's name and the condition's guard.
pub(super) fn broken_by(member: Member, traj: &Trajectory) -> Option<(String, Guard)> {
    let Member::Moves(body, mode, _) = member else {
        return None;
    };
    let mut conditions = modes::constraints(body, Equations::Exact, traj);
    if let Mode::Flight(c) = mode {
        // Off the ground strictly: a pivot whose height stays zero to a tie stays on it.
        conditions.push(modes::Constraint {
            series: traj.lift,
            scale: body.size_m(),
            guard: Guard::Land(c),
            strict: true,
        });
    }
    let scale_t = body.time_scale_s();
    (conditions.into_iter())
        .find(|c| !c.holds_after(scale_t))
        .map(|c| (body.name.clone(), c.guard))
}
