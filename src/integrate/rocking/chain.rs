//! Columns whose joints open one above another (Psycharis 1990's third pattern: the blocks of a
//! column rocking on different joints at once). While a column's body rocks on its joint, a
//! held joint above or below it can open too; the column is then a chain of rigid bodies, each
//! turning on a corner of the one below it (the lowest on a corner of the blocks held to the
//! ground), with one degree of freedom per open joint and a mass matrix that depends on the
//! configuration. Between events the chain follows Taylor series of its equations, the moment
//! balance of the part above each open joint about its pivot (no moment of the pivot's force),
//! built order by order like a single body's: each order's angular accelerations solve one small
//! linear system whose matrix is the mass matrix of the instant. Landings keep the angular
//! momentum of the part above each open joint about its pivot after the landing (the new
//! corner for the joint that lands: Housner's law for a single body, Psycharis's for two), a
//! closed joint opening through the impact where its impulse must. One joint may slip at a time
//! ([`Slide`]): the lowest pivot or a held joint below it, everything above the joint then
//! translating on it, or a joint inside the chain (a closed joint above the lowest open one, or
//! a higher pivot on a corner of the block on it), the blocks above it translating along the
//! turned face of the body under it; either way one more unknown of each order and one more
//! equation, the joint's friction at its limit. Where a second joint would slip, a pivot lift
//! off, or a landing come while a joint inside the chain slips, the exact model ends the run
//! there and says so, as a column's held joints do (docs/rocking-walls.md).
//!
//! The engine hands the column to the chain when a held joint opens under a rocking body, or a
//! landing's impulse would break one, and takes it back when the chain is down to the body's own
//! joint again (on a stack sliding under it where the body has a way on it), or seated.

use nalgebra::{DMatrix, DVector};

use super::column::{Held, Watch};
use super::modes::{Corner, Inputs, Mode, Scales, Slip, State};
use super::series::{
    self, derivative, eval, integral, mul_at, sign_after, sin_cos_at, Coeffs, ORDER, TIE, ZERO,
};
use super::stack::Stack;
use super::{Engine, ZENO_ROTATION};
use crate::error::SimulationError;
use crate::integrate::event::Turned;
use crate::response::{Collapse, CollapseCause, EventKind};

/// An open joint: the block on it (index in the column, bottom first) and the sign of the end
/// the part above turns on (+1: its right end, the part turning clockwise).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Open {
    pub(super) joint: usize,
    pub(super) s: f64,
}

/// The chain's state: its open joints, bottom first, and each body's rotation from rest
/// (clockwise, rad) and its rate; body c is the blocks from open joint c up to the next one.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Pose {
    pub(super) open: Vec<Open>,
    pub(super) phi: Vec<f64>,
    pub(super) omega: Vec<f64>,
    /// A joint at or below the lowest open one that slips now, if one does.
    pub(super) slide: Option<Slide>,
    /// What each block (from the bottom) has slid since the chain began, with slips that
    /// stopped (m; empty while none has).
    pub(super) moved: Vec<f64>,
}

/// A joint of the column that slips: a held joint below the lowest open joint (the blocks
/// between them sliding on it as one stack that carries the chain), the lowest open joint
/// itself (its pivot, a corner of the block on it, slipping on the face under it), or a joint
/// inside the chain (a closed joint above the lowest open one, or a higher open joint's pivot
/// on a corner of the block on it), along the turned face of the body under it. Everything
/// above the joint translates with the slip; the joint passes the limit of its friction against
/// it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Slide {
    /// The joint (the index of the block on it).
    pub(super) joint: usize,
    /// The slip's sign (+1: towards +x).
    pub(super) sigma: f64,
    /// How far the blocks above the joint have slid since the slip began (m), and their
    /// velocity relative to the ground (m/s).
    pub(super) u: f64,
    pub(super) v: f64,
}

/// A column as the chain moves it: the watch's blocks and joints at rest, those on and above the
/// body's own joint displaced by the slip `shift` the body had when the chain began, those
/// below it by what they slid with stacks that were held again (`held`, per block from the
/// bottom; none: they did not move). No joint slips while the chain runs.
pub(super) struct Links<'w> {
    watch: &'w Watch,
    joints: Vec<&'w Held>,
    /// The joint the column's body moves on.
    body_joint: usize,
    shift: f64,
    held: Vec<f64>,
}

/// A chain's motion over a step, as series: per body its rotation, rate, angular acceleration,
/// sine and cosine and its pivot's position; per block its centroid's position and absolute
/// acceleration (horizontal with the ground's, vertical with gravity's: a_y + g lambda) and the
/// middle of its base. Positions are relative to the ground, in the watch's frame.
pub(super) struct Path {
    body: Vec<Option<usize>>,
    /// Each body's arm to the next pivot at rest, and each block's to its centroid from its
    /// body's pivot (m).
    link: Vec<[f64; 2]>,
    arm: Vec<[f64; 2]>,
    phi: Vec<Coeffs>,
    omega: Vec<Coeffs>,
    alpha: Vec<Coeffs>,
    sin: Vec<Coeffs>,
    cos: Vec<Coeffs>,
    pivot: Vec<[Coeffs; 2]>,
    centroid: Vec<[Coeffs; 2]>,
    accel: Vec<[Coeffs; 2]>,
    base: Vec<[Coeffs; 2]>,
    /// The slipping joint, and the slip's displacement and velocity.
    slide: Option<(usize, Coeffs, Coeffs)>,
    /// The body whose face the slip runs along where it is inside the chain (none: on the
    /// ground or held blocks, along x).
    inner: Option<usize>,
}

/// What ends a chain's step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Cut {
    /// Open joint c comes back to its seat.
    Land(usize),
    /// Open joint c's pivot: condition 0 (mu N - T), 1 (mu N + T).
    Pivot(usize, usize),
    /// Closed joint j (block index): its conditions in the order of the watch's (slip each way,
    /// open at its right end, at its left end).
    Closed(usize, usize),
    /// Open joint c turns to a right angle: the part above it has fallen.
    Overturn(usize),
    /// The slipping joint's slip stops.
    Stop,
    /// The slipping pivot's normal force falls to zero.
    Lift,
}

/// A condition of the chain: a series that must stay non-negative, its scale, what it guards.
struct Condition {
    series: Coeffs,
    scale: f64,
    cut: Cut,
}

/// Rotates (x, y) clockwise by the angle whose sine and cosine are given, coefficient k.
fn turned(x: f64, y: f64, sin: &Coeffs, cos: &Coeffs, k: usize) -> [f64; 2] {
    [x * cos[k] + y * sin[k], -x * sin[k] + y * cos[k]]
}

impl<'w> Links<'w> {
    /// The chain of a column's watch, its body displaced by `shift` and its held blocks by
    /// `held` (none for a trilith).
    pub(super) fn of(watch: &'w Watch, shift: f64, held: Vec<f64>) -> Option<Links<'w>> {
        let body_joint = watch.moving.as_ref()?.upper;
        Some(Links {
            joints: watch.all_joints(),
            watch,
            body_joint,
            shift,
            held,
        })
    }

    fn blocks(&self) -> usize {
        self.watch.pieces.len()
    }

    fn dx(&self, index: usize) -> f64 {
        if index >= self.body_joint {
            self.shift
        } else {
            self.held.get(index).copied().unwrap_or(0.0)
        }
    }

    /// Block p's centroid at rest (displaced with the body).
    fn centroid(&self, p: usize) -> [f64; 2] {
        let q = &self.watch.pieces[p];
        [q.x0 + self.dx(p), q.y0]
    }

    /// The middle of block p's base at rest (displaced with the body).
    fn base(&self, p: usize) -> [f64; 2] {
        let o = &self.watch.outputs[p];
        [o.x0 + self.dx(p), o.y0]
    }

    /// The end of joint j on side s at rest (displaced with the body).
    fn end(&self, j: usize, s: f64) -> [f64; 2] {
        let (x, y) = self.joints[j].ends[usize::from(s > 0.0)];
        [x + self.dx(j), y]
    }

    /// The end of joint j on side s at rest, moved with what the block on it has slid in the
    /// chain's slips that stopped.
    fn end_in(&self, moved: &[f64], j: usize, s: f64) -> [f64; 2] {
        let [x, y] = self.end(j, s);
        [x + moved.get(j).copied().unwrap_or(0.0), y]
    }

    /// The body each block belongs to (none: held to the ground below every open joint).
    fn bodies(&self, open: &[Open]) -> Vec<Option<usize>> {
        (0..self.blocks())
            .map(|p| open.iter().rposition(|o| o.joint <= p))
            .collect()
    }

    /// The chain's motion from `pose` under `inputs`.
    pub(super) fn path(&self, pose: &Pose, inputs: &Inputs) -> Result<Path, SimulationError> {
        let w = self.watch;
        let n = pose.open.len();
        let nb = self.blocks();
        let body = self.bodies(&pose.open);
        let moved = |p: usize| pose.moved.get(p).copied().unwrap_or(0.0);
        let rest: Vec<[f64; 2]> = (pose.open.iter())
            .map(|o| self.end_in(&pose.moved, o.joint, o.s))
            .collect();
        // Blocks from the slipping joint up translate with the slip, u_s'' = a_s, one more
        // unknown of each order, and the joint's friction at its limit one more equation:
        // sum m a_x = -mu sigma sum m (a_y + g lambda) over those blocks.
        let slide = pose
            .slide
            .map(|sl| (sl, self.joints[sl.joint].friction * sl.sigma));
        let (mut us, mut vs) = (ZERO, ZERO);
        if let Some((sl, _)) = slide {
            us[0] = sl.u;
            us[1] = sl.v;
            vs[0] = sl.v;
        }
        // A slip inside the chain (a closed joint above its lowest open one, or the pivot of a
        // higher open joint) carries the blocks above it along the face of the body under it,
        // `inner`: by u_s along x in that body's frame at rest, so the link from its pivot to
        // the next and the arms of its blocks above the joint lengthen by u_s, turned with it.
        let inner = slide.and_then(|(sl, _)| {
            let lowest = pose.open.first()?;
            (sl.joint > lowest.joint).then(|| body[sl.joint - 1].expect("a body under the slip"))
        });
        let carried = |p: usize| inner.is_some() && slide.is_some_and(|(sl, _)| p >= sl.joint);
        let slides = |p: usize| inner.is_none() && slide.is_some_and(|(sl, _)| p >= sl.joint);
        let mut accs = ZERO;
        let mut along = [ZERO; 2];
        let unknowns = n + usize::from(slide.is_some());
        // Each body's arm to the next pivot, and each block's arms to its centroid and the
        // middle of its base, from the body's pivot at rest.
        let link: Vec<[f64; 2]> = (1..n)
            .map(|c| [rest[c][0] - rest[c - 1][0], rest[c][1] - rest[c - 1][1]])
            .collect();
        let arms: Vec<[[f64; 2]; 2]> = (0..nb)
            .map(|p| {
                let r = body[p].map_or([0.0; 2], |c| rest[c]);
                let (g, b) = (self.centroid(p), self.base(p));
                let dx = moved(p);
                [
                    [g[0] + dx - r[0], g[1] - r[1]],
                    [b[0] + dx - r[0], b[1] - r[1]],
                ]
            })
            .collect();
        let mut phi = vec![ZERO; n];
        let mut omega = vec![ZERO; n];
        let mut alpha = vec![ZERO; n];
        let (mut sin, mut cos) = (vec![ZERO; n], vec![ZERO; n]);
        let mut w2 = vec![ZERO; n];
        let mut links = vec![[ZERO; 2]; n.saturating_sub(1)];
        let mut pivot = vec![[ZERO; 2]; n];
        let mut rho = vec![[ZERO; 2]; nb];
        let mut centroid = vec![[ZERO; 2]; nb];
        let mut base = vec![[ZERO; 2]; nb];
        let mut accel = vec![[ZERO; 2]; nb];
        for c in 0..n {
            phi[c][0] = pose.phi[c];
            phi[c][1] = pose.omega[c];
            omega[c][0] = pose.omega[c];
        }
        let glam: Coeffs = inputs.lambda.map(|x| x * w.g_m_s2);
        let mut solver = None;
        for k in 0..=ORDER {
            for c in 0..n {
                sin_cos_at(&phi[c], &mut sin[c], &mut cos[c], k);
                w2[c][k] = mul_at(&omega[c], &omega[c], k);
            }
            // The inner slip's displacement along the turned face, u_s (cos, -sin), and its
            // velocity there, u_s' (cos, -sin).
            let slid = inner.map(|b| [mul_at(&us, &cos[b], k), -mul_at(&us, &sin[b], k)]);
            if let Some(b) = inner {
                along[0][k] = mul_at(&vs, &cos[b], k);
                along[1][k] = -mul_at(&vs, &sin[b], k);
            }
            for (c, l) in links.iter_mut().enumerate() {
                let [x, y] = turned(link[c][0], link[c][1], &sin[c], &cos[c], k);
                let [dx, dy] = slid.filter(|_| inner == Some(c)).unwrap_or([0.0; 2]);
                l[0][k] = x + dx;
                l[1][k] = y + dy;
            }
            for c in 0..n {
                let mut start = if k == 0 { rest[0] } else { [0.0; 2] };
                if inner.is_none() {
                    start[0] += us[k];
                }
                for a in 0..2 {
                    pivot[c][a][k] = if c == 0 {
                        start[a]
                    } else {
                        pivot[c - 1][a][k] + links[c - 1][a][k]
                    };
                }
            }
            // Positions, and accelerations without this order's angular accelerations.
            for p in 0..nb {
                let Some(cp) = body[p] else {
                    let (mut g, mut b) = (self.centroid(p), self.base(p));
                    g[0] += moved(p);
                    b[0] += moved(p);
                    let slip = if slides(p) { us[k] } else { 0.0 };
                    for a in 0..2 {
                        centroid[p][a][k] = if k == 0 { g[a] } else { 0.0 };
                        base[p][a][k] = if k == 0 { b[a] } else { 0.0 };
                    }
                    centroid[p][0][k] += slip;
                    base[p][0][k] += slip;
                    accel[p][0][k] = inputs.accel[k];
                    accel[p][1][k] = glam[k];
                    continue;
                };
                let [mut rx, mut ry] = turned(arms[p][0][0], arms[p][0][1], &sin[cp], &cos[cp], k);
                let [mut bx, mut by] = turned(arms[p][1][0], arms[p][1][1], &sin[cp], &cos[cp], k);
                if let Some([dx, dy]) = slid.filter(|_| carried(p) && inner == Some(cp)) {
                    (rx, ry, bx, by) = (rx + dx, ry + dy, bx + dx, by + dy);
                }
                rho[p][0][k] = rx;
                rho[p][1][k] = ry;
                centroid[p][0][k] = pivot[cp][0][k] + rx;
                centroid[p][1][k] = pivot[cp][1][k] + ry;
                base[p][0][k] = pivot[cp][0][k] + bx;
                base[p][1][k] = pivot[cp][1][k] + by;
                // a = a_pivot + alpha x r - omega^2 r along the chain (clockwise: alpha x r =
                // alpha (r_y, -r_x)).
                let (mut ax, mut ay) = (inputs.accel[k], glam[k]);
                for c in 0..=cp {
                    let r = if c < cp { &links[c] } else { &rho[p] };
                    ax += mul_at(&alpha[c], &r[1], k) - mul_at(&w2[c], &r[0], k);
                    ay += -mul_at(&alpha[c], &r[0], k) - mul_at(&w2[c], &r[1], k);
                }
                // Carried by the inner slip: its acceleration along the turned face, u_s''
                // (cos, -sin), and Coriolis's, 2 omega (along_y, -along_x).
                if let Some(b) = inner.filter(|_| carried(p)) {
                    ax += mul_at(&accs, &cos[b], k) + 2.0 * mul_at(&omega[b], &along[1], k);
                    ay += -mul_at(&accs, &sin[b], k) - 2.0 * mul_at(&omega[b], &along[0], k);
                }
                accel[p][0][k] = ax;
                accel[p][1][k] = ay;
            }
            // How this order's angular accelerations enter block p's acceleration: body c's
            // turns the arm from its pivot (the link to the next pivot below p's body).
            let arm0 = |p: usize, c: usize| -> [f64; 2] {
                let r = if Some(c) == body[p] {
                    &rho[p]
                } else {
                    &links[c]
                };
                [r[0][0], r[1][0]]
            };
            if solver.is_none() {
                // The inner slip's direction and the face's normal at the instant.
                let face = inner.map(|b| ([cos[b][0], -sin[b][0]], [sin[b][0], cos[b][0]]));
                let mass = DMatrix::from_fn(unknowns, unknowns, |b, c| {
                    let mut x = 0.0;
                    if let (true, Some((sl, mu_sigma)), Some((t, nn))) = (b == n, slide, face) {
                        // The inner slip's equation, in the face's frame: sum m (a . t + mu
                        // sigma a . n) over the blocks above the joint.
                        for p in (sl.joint..nb).filter(|&p| c == n || body[p] >= Some(c)) {
                            let v = if c == n {
                                t
                            } else {
                                let r = arm0(p, c);
                                [r[1], -r[0]]
                            };
                            let along = v[0] * t[0] + v[1] * t[1];
                            let across = v[0] * nn[0] + v[1] * nn[1];
                            x += w.pieces[p].mass_kg * (along + mu_sigma * across);
                        }
                        return x;
                    }
                    if let (true, Some((t, _))) = (c == n, face) {
                        // a_s moves the blocks it carries along the face.
                        for p in (0..nb).filter(|&p| carried(p) && body[p] >= Some(b)) {
                            let d = [
                                centroid[p][0][0] - pivot[b][0][0],
                                centroid[p][1][0] - pivot[b][1][0],
                            ];
                            x += w.pieces[p].mass_kg * (d[0] * t[1] - d[1] * t[0]);
                        }
                        return x;
                    }
                    if let (true, Some((sl, mu_sigma))) = (b == n, slide) {
                        // The slip's equation: how each unknown moves the blocks above the
                        // joint, sum m (a_x + mu sigma a_y).
                        for p in (sl.joint..nb).filter(|&p| c == n || body[p] >= Some(c)) {
                            let r = if c == n { [0.0, 1.0] } else { arm0(p, c) };
                            x += w.pieces[p].mass_kg * (r[1] - mu_sigma * r[0]);
                        }
                        return x;
                    }
                    if c == n {
                        // a_s moves every block above pivot b along x.
                        for p in (0..nb).filter(|&p| body[p].is_some_and(|cp| cp >= b)) {
                            x -= w.pieces[p].mass_kg * (centroid[p][1][0] - pivot[b][1][0]);
                        }
                        return x;
                    }
                    for p in (0..nb).filter(|&p| body[p].is_some_and(|cp| cp >= b && cp >= c)) {
                        let q = &w.pieces[p];
                        let d = [
                            centroid[p][0][0] - pivot[b][0][0],
                            centroid[p][1][0] - pivot[b][1][0],
                        ];
                        let r = arm0(p, c);
                        x -= q.mass_kg * (d[0] * r[0] + d[1] * r[1]);
                        if body[p] == Some(c) {
                            x -= q.inertia_kg_m2;
                        }
                    }
                    x
                });
                solver = Some(mass.lu());
            }
            // The moment about each pivot of what the part above it needs, without this
            // order's angular accelerations: sum m ((x - P_x) (a_y + g lambda) - (y - P_y) a_x).
            let rhs = DVector::from_fn(unknowns, |b, _| {
                if let (true, Some((sl, mu_sigma)), Some(f)) = (b == n, slide, inner) {
                    let (sin, cos) = (&sin[f], &cos[f]);
                    let known = (sl.joint..nb).map(|p| {
                        let a = &accel[p];
                        let along = mul_at(&a[0], cos, k) - mul_at(&a[1], sin, k);
                        let across = mul_at(&a[0], sin, k) + mul_at(&a[1], cos, k);
                        w.pieces[p].mass_kg * (along + mu_sigma * across)
                    });
                    return -known.sum::<f64>();
                }
                if let (true, Some((sl, mu_sigma))) = (b == n, slide) {
                    let known = (sl.joint..nb).map(|p| {
                        w.pieces[p].mass_kg * (accel[p][0][k] + mu_sigma * accel[p][1][k])
                    });
                    return -known.sum::<f64>();
                }
                let mut m = 0.0;
                for p in (0..nb).filter(|&p| body[p].is_some_and(|cp| cp >= b)) {
                    let (g, a) = (&centroid[p], &accel[p]);
                    let moment = mul_at(&g[0], &a[1], k)
                        - mul_at(&pivot[b][0], &a[1], k)
                        - mul_at(&g[1], &a[0], k)
                        + mul_at(&pivot[b][1], &a[0], k);
                    m += w.pieces[p].mass_kg * moment;
                }
                -m
            });
            let lu = solver.as_ref().expect("factorised at order 0");
            // Nothing open (a chain seated by its last landing): every block rests.
            let a = if unknowns == 0 {
                Some(rhs)
            } else {
                lu.solve(&rhs)
            };
            let a = a.ok_or_else(|| {
                SimulationError::Bug(format!(
                    "the mass matrix of the chain of open joints {:?} is singular",
                    pose.open
                ))
            })?;
            for c in 0..n {
                alpha[c][k] = a[c];
                if k < ORDER {
                    omega[c][k + 1] = a[c] / (k + 1) as f64;
                }
                if k + 2 <= ORDER {
                    phi[c][k + 2] = a[c] / ((k + 1) * (k + 2)) as f64;
                }
            }
            if slide.is_some() {
                let a_s = a[n];
                if k < ORDER {
                    vs[k + 1] = a_s / (k + 1) as f64;
                }
                if k + 2 <= ORDER {
                    us[k + 2] = a_s / ((k + 1) * (k + 2)) as f64;
                }
                for p in (0..nb).filter(|&p| slides(p)) {
                    accel[p][0][k] += a_s;
                }
                if let Some(b) = inner {
                    accs[k] = a_s;
                    for p in (0..nb).filter(|&p| carried(p)) {
                        accel[p][0][k] += a_s * cos[b][0];
                        accel[p][1][k] -= a_s * sin[b][0];
                    }
                }
            }
            for p in 0..nb {
                let Some(cp) = body[p] else { continue };
                for c in 0..=cp {
                    let r = arm0(p, c);
                    accel[p][0][k] += a[c] * r[1];
                    accel[p][1][k] -= a[c] * r[0];
                }
            }
        }
        Ok(Path {
            body,
            link,
            arm: arms.iter().map(|a| a[0]).collect(),
            phi,
            omega,
            alpha,
            sin,
            cos,
            pivot,
            centroid,
            accel,
            base,
            slide: slide.map(|(sl, _)| (sl.joint, us, vs)),
            inner,
        })
    }

    /// Every condition of the chain along `path`: each open joint's landing, overturning and
    /// pivot, each closed joint's friction and contact (as the watch's held joints').
    fn conditions(&self, pose: &Pose, path: &Path, sc: &Scales) -> Vec<Condition> {
        let angle = sc.angle;
        let w = self.watch;
        let nb = self.blocks();
        let mut out = Vec::new();
        for (c, o) in pose.open.iter().enumerate() {
            let mut theta = path.phi[c];
            if c > 0 {
                theta
                    .iter_mut()
                    .zip(&path.phi[c - 1])
                    .for_each(|(x, y)| *x -= y);
            }
            let seated = theta.map(|x| o.s * x);
            let mut upright = seated.map(|x| -x);
            upright[0] += std::f64::consts::FRAC_PI_2;
            out.push(Condition {
                series: seated,
                scale: angle,
                cut: Cut::Land(c),
            });
            out.push(Condition {
                series: upright,
                scale: angle,
                cut: Cut::Overturn(c),
            });
        }
        for j in 0..nb {
            let joint = self.joints[j];
            let (h, v) = self.passed(path, j);
            let open = pose.open.iter().position(|o| o.joint == j);
            // The face the joint's force is normal to: an open joint's, the face its pivot
            // corner presses on; a closed joint's, its blocks' (turned with their body).
            let face = match open {
                Some(c) => {
                    let end = usize::from(pose.open[c].s > 0.0);
                    if joint.upper_corner[end] {
                        c.checked_sub(1)
                    } else {
                        Some(c)
                    }
                }
                None => path.body[j],
            };
            let (n, t) = match face {
                Some(c) => {
                    let (sin, cos) = (&path.sin[c], &path.cos[c]);
                    let mut n = series::product(&h, sin);
                    series::add_to(&mut n, &series::product(&v, cos), 1.0);
                    let mut t = series::product(&h, cos);
                    series::add_to(&mut t, &series::product(&v, sin), -1.0);
                    (n, t)
                }
                None => (v, h),
            };
            let mu = joint.friction;
            let cone = [
                series::add(&series::scaled(&n, mu), &t, -1.0),
                series::add(&series::scaled(&n, mu), &t, 1.0),
            ];
            let slipping = pose.slide.is_some_and(|sl| sl.joint == j);
            if let (Some(_), true) = (open, slipping) {
                // Its pivot slips, the force at its friction's limit: it must stay pressed.
                out.push(Condition {
                    series: n,
                    scale: w.force_scale,
                    cut: Cut::Lift,
                });
                continue;
            }
            if let Some(c) = open {
                for (i, series) in cone.into_iter().enumerate() {
                    out.push(Condition {
                        series,
                        scale: w.force_scale,
                        cut: Cut::Pivot(c, i),
                    });
                }
                continue;
            }
            // A joint the inner slip carries has its ends moved along the turned face.
            let carried = (path.slide.as_ref())
                .filter(|sl| path.inner.is_some() && path.inner == path.body[j] && j >= sl.0)
                .map(|(_, u, _)| u);
            let ends = [-1.0, 1.0].map(|s| {
                let e = self.end_in(&pose.moved, j, s);
                match path.body[j] {
                    Some(c) => {
                        let r = self.end_in(&pose.moved, pose.open[c].joint, pose.open[c].s);
                        let (dx, dy) = (e[0] - r[0], e[1] - r[1]);
                        let (sin, cos) = (&path.sin[c], &path.cos[c]);
                        [0, 1].map(|a| {
                            let mut x = path.pivot[c][a];
                            for (k, x) in x.iter_mut().enumerate() {
                                *x += turned(dx, dy, sin, cos, k)[a];
                                if let Some(u) = carried {
                                    *x += [mul_at(u, cos, k), -mul_at(u, sin, k)][a];
                                }
                            }
                            x
                        })
                    }
                    None => {
                        let mut e = e.map(series::constant);
                        if let Some((_, u, _)) = path.slide.as_ref().filter(|sl| j >= sl.0) {
                            series::add_to(&mut e[0], u, 1.0);
                        }
                        e
                    }
                }
            });
            let [left, right] = ends.map(|e| self.moment(path, j, &e));
            for (i, series) in cone
                .into_iter()
                .chain([left, right.map(|x| -x)])
                .enumerate()
                .skip(if slipping { 2 } else { 0 })
            {
                out.push(Condition {
                    series,
                    scale: if i < 2 { w.force_scale } else { w.moment_scale },
                    cut: Cut::Closed(j, i),
                });
            }
        }
        if let (Some(sl), Some((_, _, v))) = (pose.slide, &path.slide) {
            out.push(Condition {
                series: v.map(|x| sl.sigma * x),
                scale: sc.velocity,
                cut: Cut::Stop,
            });
        }
        out
    }

    /// The power the slipping joint's friction dissipates, mu N |u_s'|, as a series (zero
    /// where nothing slips).
    fn friction_power(&self, pose: &Pose, path: &Path) -> Coeffs {
        let (Some(sl), Some((j, _, v))) = (pose.slide, &path.slide) else {
            return ZERO;
        };
        let (h, v_passed) = self.passed(path, *j);
        let normal = match path.inner {
            // Normal to the face the slip runs along.
            Some(b) => {
                let mut n = series::product(&h, &path.sin[b]);
                series::add_to(&mut n, &series::product(&v_passed, &path.cos[b]), 1.0);
                n
            }
            None => v_passed,
        };
        series::scaled(
            &series::product(&normal, v),
            self.joints[*j].friction * sl.sigma,
        )
    }

    /// The force joint j passes up (H, V): what the blocks above it need, sum m (a_x, a_y + g
    /// lambda).
    fn passed(&self, path: &Path, j: usize) -> (Coeffs, Coeffs) {
        let (mut h, mut v) = (ZERO, ZERO);
        for p in j..self.blocks() {
            let m = self.watch.pieces[p].mass_kg;
            series::add_to(&mut h, &path.accel[p][0], m);
            series::add_to(&mut v, &path.accel[p][1], m);
        }
        (h, v)
    }

    /// The counter-clockwise moment about the point `e` of the forces joint j passes up: the
    /// d'Alembert balance of the blocks above it.
    fn moment(&self, path: &Path, j: usize, e: &[Coeffs; 2]) -> Coeffs {
        let mut m = ZERO;
        for p in j..self.blocks() {
            let q = &self.watch.pieces[p];
            let dx = series::add(&path.centroid[p][0], &e[0], -1.0);
            let dy = series::add(&path.centroid[p][1], &e[1], -1.0);
            series::add_to(&mut m, &series::product(&dx, &path.accel[p][1]), q.mass_kg);
            series::add_to(&mut m, &series::product(&dy, &path.accel[p][0]), -q.mass_kg);
            if let Some(c) = path.body[p] {
                series::add_to(&mut m, &path.alpha[c], -q.inertia_kg_m2);
            }
        }
        m
    }

    /// The kinetic and potential energy (J) of every block at tau: relative to the ground, the
    /// potential above rest. A centroid's rise is summed over the arms that carry it, each
    /// (x, y) turned by phi rising by -x sin phi - 2 y sin^2(phi / 2): taken from its height
    /// now less its height at rest it would keep only what the height's last bit holds.
    fn energies(&self, path: &Path, tau: f64) -> Vec<(f64, f64)> {
        let g = self.watch.g_m_s2;
        let phi: Vec<f64> = path.phi.iter().map(|c| eval(c, tau)).collect();
        let rise = |[x, y]: [f64; 2], phi: f64| {
            let half = (0.5 * phi).sin();
            -x * phi.sin() - 2.0 * y * half * half
        };
        (0..self.blocks())
            .map(|p| {
                let q = &self.watch.pieces[p];
                let Some(c) = path.body[p] else {
                    let Some((_, _, v)) = path.slide.as_ref().filter(|sl| p >= sl.0) else {
                        return (0.0, 0.0);
                    };
                    let v = eval(v, tau);
                    return (0.5 * q.mass_kg * v * v, 0.0);
                };
                let vx = eval(&derivative(&path.centroid[p][0]), tau);
                let vy = eval(&derivative(&path.centroid[p][1]), tau);
                let w = eval(&path.omega[c], tau);
                // An inner slip lengthens the link and the arms it carries along x at rest.
                let lengthened = |[x, y]: [f64; 2], b: usize| match (&path.slide, path.inner) {
                    (Some((j, u, _)), Some(f)) if f == b && p >= *j => [x + eval(u, tau), y],
                    _ => [x, y],
                };
                let dy = (0..c)
                    .map(|b| rise(lengthened(path.link[b], b), phi[b]))
                    .sum::<f64>()
                    + rise(lengthened(path.arm[p], c), phi[c]);
                (
                    0.5 * q.mass_kg * (vx * vx + vy * vy) + 0.5 * q.inertia_kg_m2 * w * w,
                    q.mass_kg * g * dy,
                )
            })
            .collect()
    }

    /// The power of the ground's inertial forces on the blocks, -m a_g v_x - m g (lambda - 1)
    /// v_y, as a series.
    fn input_power(&self, path: &Path, inputs: &Inputs) -> Coeffs {
        let g = self.watch.g_m_s2;
        let mut power = ZERO;
        let extra = series::plus(&inputs.lambda, -1.0);
        let slides = |p: usize| path.slide.as_ref().is_some_and(|sl| p >= sl.0);
        for p in (0..self.blocks()).filter(|&p| path.body[p].is_some() || slides(p)) {
            let m = self.watch.pieces[p].mass_kg;
            let vx = derivative(&path.centroid[p][0]);
            let vy = derivative(&path.centroid[p][1]);
            series::add_to(&mut power, &series::product(&inputs.accel, &vx), -m);
            series::add_to(&mut power, &series::product(&extra, &vy), -m * g);
        }
        power
    }

    /// The post-landing rates of the bodies of `open` (positions those of the instant, the
    /// blocks' velocities `before`, each body's rate `before_omega` by block): the angular
    /// momentum of the part above each open joint about its pivot is kept. Where `slide` names
    /// a joint (its index and the sign of its slip), everything above it leaves with one more
    /// unknown horizontal velocity w, and that joint passes its friction's limit against the slip
    /// (the momentum the blocks above it gain, sum m dv_x = -mu sigma sum m dv_y); else the
    /// joints below the chain hold (w = 0). Also w and each block's velocity after.
    fn momentum_balance(
        &self,
        open: &[Open],
        slide: Option<(usize, f64)>,
        at: &Instant,
        before: &[[f64; 2]],
        spin_before: &[f64],
    ) -> Option<(Vec<f64>, f64, Vec<[f64; 2]>)> {
        let nb = self.blocks();
        let n = open.len();
        let body = self.bodies(open);
        let pivots: Vec<[f64; 2]> = open.iter().map(|o| at.point(self, o.joint, o.s)).collect();
        // Block p's velocity per unit rate of body c: c turns p about c's pivot, carrying it
        // with the next pivot when p lies above c; per unit w, every block above the slipping
        // joint moves along x.
        let jacobian = |p: usize, c: usize| -> [f64; 2] {
            if c == n {
                return [1.0, 0.0];
            }
            let cp = body[p].expect("a moving block");
            let r = if c < cp {
                [
                    pivots[c + 1][0] - pivots[c][0],
                    pivots[c + 1][1] - pivots[c][1],
                ]
            } else {
                [
                    at.centroid[p][0] - pivots[c][0],
                    at.centroid[p][1] - pivots[c][1],
                ]
            };
            [r[1], -r[0]]
        };
        let cross = |r: [f64; 2], v: [f64; 2]| r[1] * v[0] - r[0] * v[1];
        let body = &body;
        let above = |b: usize| (0..nb).filter(move |&p| body[p].is_some_and(|cp| cp >= b));
        let moves = |p: usize, c: usize| c == n || body[p].is_some_and(|cp| cp >= c);
        let unknowns = n + usize::from(slide.is_some());
        let mu_sigma = slide.map_or(0.0, |(j, sigma)| self.joints[j].friction * sigma);
        let sliding = slide.map_or(nb, |(j, _)| j)..nb;
        let matrix = DMatrix::from_fn(unknowns, unknowns, |b, c| {
            if b == n {
                return (sliding.clone().filter(|&p| moves(p, c)))
                    .map(|p| {
                        let v = jacobian(p, c);
                        self.watch.pieces[p].mass_kg * (v[0] + mu_sigma * v[1])
                    })
                    .sum();
            }
            let mut x = 0.0;
            for p in above(b).filter(|&p| moves(p, c)) {
                let q = &self.watch.pieces[p];
                let d = [
                    at.centroid[p][0] - pivots[b][0],
                    at.centroid[p][1] - pivots[b][1],
                ];
                x += q.mass_kg * cross(d, jacobian(p, c));
                if body[p] == Some(c) {
                    x += q.inertia_kg_m2;
                }
            }
            x
        });
        let rhs = DVector::from_fn(unknowns, |b, _| {
            if b == n {
                return (sliding.clone())
                    .map(|p| {
                        self.watch.pieces[p].mass_kg * (before[p][0] + mu_sigma * before[p][1])
                    })
                    .sum();
            }
            above(b)
                .map(|p| {
                    let q = &self.watch.pieces[p];
                    let d = [
                        at.centroid[p][0] - pivots[b][0],
                        at.centroid[p][1] - pivots[b][1],
                    ];
                    q.mass_kg * cross(d, before[p]) + q.inertia_kg_m2 * spin_before[p]
                })
                .sum()
        });
        let x = if unknowns == 0 {
            rhs
        } else {
            matrix.lu().solve(&rhs)?
        };
        let w = if slide.is_some() { x[n] } else { 0.0 };
        let after = (0..nb)
            .map(|p| {
                let base = if sliding.contains(&p) {
                    [w, 0.0]
                } else {
                    [0.0; 2]
                };
                match body[p] {
                    None => base,
                    Some(cp) => (0..=cp).fold(base, |v, c| {
                        let j = jacobian(p, c);
                        [v[0] + x[c] * j[0], v[1] + x[c] * j[1]]
                    }),
                }
            })
            .collect();
        Some((x.iter().take(n).copied().collect(), w, after))
    }
}

/// The chain's geometry at one instant: each body's rotation and pivot, each block's centroid.
struct Instant {
    open: Vec<Open>,
    moved: Vec<f64>,
    /// The joint that slips, and how far the blocks above it have slid (m).
    slid: Option<(usize, f64)>,
    phi: Vec<f64>,
    pivot: Vec<[f64; 2]>,
    centroid: Vec<[f64; 2]>,
}

impl Instant {
    fn of(pose: &Pose, path: &Path, tau: f64) -> Instant {
        Instant {
            open: pose.open.clone(),
            moved: pose.moved.clone(),
            slid: pose.slide.map(|sl| (sl.joint, sl.u)),
            phi: path.phi.iter().map(|c| eval(c, tau)).collect(),
            pivot: path
                .pivot
                .iter()
                .map(|p| p.map(|c| eval(&c, tau)))
                .collect(),
            centroid: path
                .centroid
                .iter()
                .map(|p| p.map(|c| eval(&c, tau)))
                .collect(),
        }
    }

    /// Where the end of joint j on side s is now: a point of the body below the joint (or of
    /// the blocks held to the ground, with the slip under them).
    fn point(&self, links: &Links, j: usize, s: f64) -> [f64; 2] {
        let e = links.end_in(&self.moved, j, s);
        let Some(c) = self.open.iter().rposition(|o| o.joint < j) else {
            // The end moves with the slip where the block on the slipping joint carries it.
            let carried = |joint: usize| {
                joint < j || (joint == j && links.joints[j].upper_corner[usize::from(s > 0.0)])
            };
            let slip = (self.slid.filter(|&(joint, _)| carried(joint))).map_or(0.0, |(_, u)| u);
            return [e[0] + slip, e[1]];
        };
        let o = self.open[c];
        let r = links.end_in(&self.moved, o.joint, o.s);
        let (sin, cos) = self.phi[c].sin_cos();
        let (dx, dy) = (e[0] - r[0], e[1] - r[1]);
        [
            self.pivot[c][0] + dx * cos + dy * sin,
            self.pivot[c][1] - dx * sin + dy * cos,
        ]
    }
}

/// Whether the joint that slips in `pose` is inside the chain: above its lowest open joint.
fn inside(pose: &Pose) -> bool {
    let lowest = pose.open.first().map(|o| o.joint);
    pose.slide
        .is_some_and(|sl| lowest.is_some_and(|j| sl.joint > j))
}

/// How a chain's run goes on after an event.
enum Next {
    /// In the chain, from this pose.
    Chain(Pose),
    /// Back to the column's body (its state and mode, what its held blocks slid, and the stack
    /// that slides under it with how far it has slid).
    Body(State, Mode, Vec<f64>, Option<(Stack, f64)>),
    /// The run ends here.
    End,
}

/// "+x" or "-x", the direction of a slip of sign `sigma`.
fn towards(sigma: f64) -> &'static str {
    if sigma > 0.0 {
        "+x"
    } else {
        "-x"
    }
}

/// How a chain's condition reads in the event log and warning.
fn how(cut: Cut, n_positive: bool) -> &'static str {
    match cut {
        Cut::Pivot(..) if !n_positive => {
            "would lift off the corner it turns on (the exact model follows the chain while its \
             pivots stay pressed)"
        }
        Cut::Pivot(_, 0) => "would slip at the corner it turns on, the block on it towards -x",
        Cut::Pivot(..) => "would slip at the corner it turns on, the block on it towards +x",
        Cut::Closed(_, 0) => {
            "would slip, the block on it towards -x (it needs more friction towards +x than the \
             joint holds)"
        }
        Cut::Closed(_, 1) => {
            "would slip, the block on it towards +x (it needs more friction towards -x than the \
             joint holds)"
        }
        Cut::Land(_) => {
            "would open and close at once (its opening and its landing conditions contradict \
             each other: the rigid model cannot decide it)"
        }
        Cut::Overturn(_) => "has turned to a right angle on its joint",
        Cut::Closed(..) => "gives way",
        Cut::Stop => {
            "would stop slipping and slip again at once, or hold, both or neither (beyond the \
             chain)"
        }
        Cut::Lift => {
            "would lift off the corner it turns on as that corner slips (the exact model follows \
             the chain while its pivots stay pressed)"
        }
    }
}

impl<'a> Engine<'a> {
    /// Whether condition k of the watch, falling under body i, opens a joint the chain can
    /// follow: the body rocks on a sticking pivot, alone in the scene with nothing standing
    /// apart from it, on exact equations.
    pub(super) fn chain_can_follow(&self, i: usize, k: usize) -> bool {
        self.tracks.len() == 1
            && self.clearance.is_empty()
            && !self.tracks[i].displaced.any_slides()
            && k % 4 >= 2
            && matches!(self.tracks[i].mode, Mode::Rock(_))
            && self.scene.equations == super::Equations::Exact
            && self
                .scene
                .watches
                .get(i)
                .is_some_and(|w| w.moving.is_some())
    }

    /// Held joint of condition k opens under the body rocking now: the column runs as a chain
    /// from here until it is back to the body alone, seated, or the run ends.
    pub(super) fn open_chain(&mut self, k: usize) -> Result<(), SimulationError> {
        let watch: &Watch = &self.scene.watches[0];
        let (_, _, upper) = watch.describe(k);
        let st = self.tracks[0].state;
        let held = self.tracks[0].displaced.by_m.clone();
        let links = Links::of(watch, st.u, held).expect("a column's watch");
        let pivot = self.tracks[0].mode.pivot().expect("a rocking body");
        let body = Open {
            joint: links.body_joint,
            s: pivot.sign(),
        };
        let new = Open {
            joint: upper,
            s: if k % 4 == 2 { -1.0 } else { 1.0 },
        };
        let pose = if upper > body.joint {
            Pose {
                open: vec![body, new],
                phi: vec![st.theta; 2],
                omega: vec![st.omega; 2],
                slide: None,
                moved: Vec::new(),
            }
        } else {
            Pose {
                open: vec![new, body],
                phi: vec![0.0, st.theta],
                omega: vec![0.0, st.omega],
                slide: None,
                moved: Vec::new(),
            }
        };
        self.opened(&links, upper, "opens");
        let (_, now) = self.inputs_at(self.t);
        let next = self.settle(&links, pose, &now)?;
        self.go_on(&links, next)
    }

    /// The column goes on as `next` says: as the chain, back to its body, or not at all.
    fn go_on(&mut self, links: &Links, next: Next) -> Result<(), SimulationError> {
        match next {
            Next::Chain(pose) => self.run_chain(links, pose),
            Next::Body(state, mode, moved, stack) => self.resume((state, mode), moved, stack),
            Next::End => Ok(()),
        }
    }

    /// Body 0 lands where the impulses of its landing would break a held joint of its column
    /// (the column held, or a stack sliding under the body on its corner): the landing is then
    /// the chain's, with the joints under the body holding, slipping or opening through the
    /// impact as the one way that holds says ([`Engine::chain_lands`]). False where the chain
    /// cannot take the column (the caller stops the run there).
    pub(super) fn lands_as_chain(&mut self, now: &Inputs) -> Result<bool, SimulationError> {
        let Some((links, pose)) = self.as_chain() else {
            return Ok(false);
        };
        let path = links.path(&pose, now)?;
        let next = self.chain_lands(&links, pose, &path, 0.0, 0, now)?;
        self.go_on(&links, next)?;
        Ok(true)
    }

    /// Column 0 as a chain of one open joint, its body's, rocking on a stuck pivot on a held
    /// base or on a stack that slides under it (a slip under the chain); none where the chain
    /// cannot take it (several bodies, neighbours, stacks on stacks, a slipping pivot, the
    /// linearised equations, no column).
    fn as_chain(&self) -> Option<(Links<'a>, Pose)> {
        let (tr, scene) = (&self.tracks[0], self.scene);
        let (Some(watch), Mode::Rock(pivot)) = (scene.watches.first(), tr.mode) else {
            return None;
        };
        let follows = self.tracks.len() == 1
            && self.clearance.is_empty()
            && tr.displaced.beneath.is_empty()
            && self.scene.equations == super::Equations::Exact;
        let st = tr.state;
        let (slide, slid) = match tr.displaced.sliding {
            _ if !follows => return None,
            None => (None, 0.0),
            Some(stack @ Stack { apart: None, .. }) => {
                let slid = stack.moved_m(st.u);
                let sigma = stack.slip.sign();
                let (joint, v) = (stack.first, st.v);
                (
                    Some(Slide {
                        joint,
                        sigma,
                        u: slid,
                        v,
                    }),
                    slid,
                )
            }
            Some(_) => return None,
        };
        let links = Links::of(watch, st.u - slid, tr.displaced.by_m.clone())?;
        let pose = Pose {
            open: vec![Open {
                joint: links.body_joint,
                s: pivot.sign(),
            }],
            phi: vec![st.theta],
            omega: vec![st.omega],
            slide,
            moved: Vec::new(),
        };
        Some((links, pose))
    }

    /// A slip begins under the chain, which goes from `pose` to `way` (condition i of joint j
    /// having fallen): its event, and that of a joint opening with it.
    fn slip_begins(&mut self, links: &Links, pose: &Pose, way: &Pose, (j, i): (usize, usize)) {
        let sl = way.slide.expect("a slip");
        let lowest = way.open[0].joint;
        let pieces = &links.watch.pieces[sl.joint..lowest];
        let what = if pieces.is_empty() {
            "the chain's lowest pivot slips".to_string()
        } else {
            let names: Vec<&str> = (sl.joint..lowest)
                .map(|p| links.watch.outputs[p].name.as_str())
                .collect();
            let mass: f64 = pieces.iter().map(|q| q.mass_kg).sum();
            let verb = if names.len() == 1 { "slides" } else { "slide" };
            format!(
                "{} (M = {mass:.0} kg) {verb} under the chain",
                names.join("+")
            )
        };
        let why = if sl.joint == j && i == usize::from(sl.sigma > 0.0) {
            ""
        } else {
            ", the joint whose condition fell holding"
        };
        let what = format!(
            "{what} on {} towards {} (mu = {}){why}",
            links.joints[sl.joint].name,
            towards(sl.sigma),
            links.joints[sl.joint].friction,
        );
        self.slide_event(links, sl.joint, EventKind::Slip, what);
        for new in way.open.iter().filter(|x| !pose.open.contains(x)) {
            self.opened(links, new.joint, "opens as the slip begins");
        }
    }

    /// Condition k of the watch (a held joint below body 0 that would slip) falls where the
    /// sliding stack above it has no way: where the chain, the body its one open joint, has
    /// exactly one way of a joint under it slipping (a joint opening with it, or not), the
    /// column runs as that chain from here. False where it has none or several (the caller
    /// stops the run there).
    pub(super) fn slips_as_chain(
        &mut self,
        k: usize,
        now: &Inputs,
    ) -> Result<bool, SimulationError> {
        let Some((links, pose)) = self.as_chain() else {
            return Ok(false);
        };
        let body = &self.scene.bodies[0];
        let (sc, ts) = (Scales::of(body), body.time_scale_s());
        let ways = links.slide_ways(&pose, now, &sc, ts)?;
        let [way] = &ways[..] else {
            return Ok(false);
        };
        let (_, _, upper) = links.watch.describe(k);
        self.rec.stats.mode_decisions += 1;
        self.slip_begins(&links, &pose, way, (upper, k % 4));
        let next = self.settle(&links, way.clone(), now)?;
        self.go_on(&links, next)?;
        Ok(true)
    }

    /// Logs the opening of joint j: the part above it lifts (`how`: "opens", or how else).
    fn opened(&mut self, links: &Links, j: usize, how: &str) {
        let blocks = self.chain_outputs(j, links.blocks());
        for &b in &blocks {
            self.rec.uplift(b, self.t);
        }
        self.rec.rocking_event(
            self.t,
            EventKind::Uplift,
            &blocks,
            None,
            format!("{how}: {}", links.joints[j].name),
        );
    }

    /// Logs an event of the joint j that slips under the chain (its blocks and those above).
    fn slide_event(&mut self, links: &Links, j: usize, kind: EventKind, what: String) {
        let blocks = self.chain_outputs(j, links.blocks());
        self.rec.rocking_event(self.t, kind, &blocks, None, what);
    }

    /// The outputs of blocks j and above of the column.
    fn chain_outputs(&self, j: usize, blocks: usize) -> Vec<usize> {
        (j..blocks)
            .map(|p| self.layout.column_output(0, p))
            .collect()
    }

    /// The chain's configuration now: every closed joint that must open opens; a condition
    /// that falls at once otherwise ends the run (the event and warning say which and how).
    fn settle(
        &mut self,
        links: &Links,
        mut pose: Pose,
        now: &Inputs,
    ) -> Result<Next, SimulationError> {
        let body = &self.scene.bodies[0];
        let (sc, ts) = (Scales::of(body), body.time_scale_s());
        for _ in 0..=2 * links.blocks() {
            let back = self.handed_back(links, &pose);
            // Where the body on the stack would have no way, the chain goes on with it.
            let stranded = match &back {
                Some(Some(Next::Body(state, mode, moved, Some(stack)))) => {
                    let c = mode.pivot().expect("a rocking body");
                    self.stack_would_carry(0, (state, c), moved, *stack, now) == 0
                }
                _ => false,
            };
            if let Some(back) = back.filter(|_| !stranded) {
                if let Some(next) = back {
                    return Ok(next);
                }
                let path = links.path(&pose, now)?;
                let how =
                    "slips as the chain ends, the column seated or on no stack the model slides \
                           (beyond the chain)";
                let j = pose.slide.map_or(0, |sl| sl.joint);
                self.chain_ends_at(links, (&path, 0.0), j, how, None);
                return Ok(Next::End);
            }
            let path = links.path(&pose, now)?;
            let falls = links
                .conditions(&pose, &path, &sc)
                .into_iter()
                .find(|c| sign_after(&c.series, c.scale, ts) < 0);
            let Some(cond) = falls else {
                return Ok(Next::Chain(pose));
            };
            self.rec.stats.mode_decisions += 1;
            let lowest = pose.open.first().map_or(0, |o| o.joint);
            let slips = match cond.cut {
                Cut::Closed(j, i @ (0 | 1)) if j < lowest => Some((j, i)),
                Cut::Pivot(0, i) if eval(&links.passed(&path, lowest).1, 0.0) > 0.0 => {
                    Some((lowest, i))
                }
                _ => None,
            };
            // A closed joint above the lowest open one, or a pressed pivot above it on a corner
            // of the block on it, that would slip: the chain goes on with it slipping.
            let inner = match cond.cut {
                Cut::Closed(j, 0 | 1) if !pose.open.is_empty() && j > lowest => Some(j),
                Cut::Pivot(c, _) if links.inner_pivot(&pose, &path, (c, 0.0)) => {
                    Some(pose.open[c].joint)
                }
                _ => None,
            };
            if let (Some(j), None) = (inner, pose.slide) {
                let ways = links.inner_ways(&pose, j, now, &sc, ts)?;
                let [way] = &ways[..] else {
                    let how = if ways.is_empty() {
                        "would slip inside the chain, and neither way of its slipping holds \
                         (beyond the chain)"
                    } else {
                        "would slip inside the chain, and both ways of its slipping hold \
                         (beyond the chain)"
                    };
                    self.chain_ends_at(links, (&path, 0.0), j, how, None);
                    return Ok(Next::End);
                };
                let sigma = way.slide.expect("a slip").sigma;
                let what = format!(
                    "{} slip on {} inside the chain towards {} (mu = {})",
                    links.watch.outputs[j..]
                        .iter()
                        .map(|o| o.name.as_str())
                        .collect::<Vec<_>>()
                        .join("+"),
                    links.joints[j].name,
                    towards(sigma),
                    links.joints[j].friction,
                );
                self.slide_event(links, j, EventKind::Slip, what);
                pose = way.clone();
                continue;
            }
            if let (Some((j, i)), None) = (slips, pose.slide) {
                let ways = links.slide_ways(&pose, now, &sc, ts)?;
                let [way] = &ways[..] else {
                    let how = if ways.is_empty() {
                        "would slip, and no way of a joint under the chain slipping holds \
                         (beyond the chain)"
                    } else {
                        "would slip, and several ways of the joints under the chain slipping \
                         hold (beyond the chain)"
                    };
                    self.chain_ends_at(links, (&path, 0.0), j, how, None);
                    return Ok(Next::End);
                };
                self.slip_begins(links, &pose, way, (j, i));
                pose = way.clone();
                continue;
            }
            match cond.cut {
                Cut::Closed(j, i @ (2 | 3)) => {
                    let c = pose
                        .open
                        .iter()
                        .rposition(|o| o.joint < j)
                        .map_or(0, |c| c + 1);
                    let (phi, omega) = match c {
                        0 => (0.0, 0.0),
                        _ => (pose.phi[c - 1], pose.omega[c - 1]),
                    };
                    let s = if i == 2 { -1.0 } else { 1.0 };
                    pose.open.insert(c, Open { joint: j, s });
                    pose.phi.insert(c, phi);
                    pose.omega.insert(c, omega);
                    self.opened(links, j, "opens");
                }
                cut => {
                    self.chain_stops(links, (&pose, &path, 0.0), cut, None);
                    return Ok(Next::End);
                }
            }
        }
        Err(SimulationError::Bug(
            "the chain opened more joints than its column has".into(),
        ))
    }

    /// The engine takes the column back when the chain is down to the body's own joint, or
    /// seated: its body's state is then the chain's (`Some`), and where a joint slips under it,
    /// the body rocking on the stack that slides (or, its own joint slipping, slide-rocking);
    /// `Some(None)` where the engine cannot take it so (a seated column riding a slip).
    fn handed_back(&self, links: &Links, pose: &Pose) -> Option<Option<Next>> {
        // A slip inside the chain, or blocks of the body that slid on each other in one, are
        // not the body's: the chain goes on.
        let body_moved = pose.moved.get(links.body_joint..).unwrap_or(&[]);
        if inside(pose) || body_moved.windows(2).any(|w| w[0] != w[1]) {
            return None;
        }
        let slid = pose.slide.map_or(0.0, |sl| sl.u);
        let state = State {
            u: links.shift + pose.moved.get(links.body_joint).copied().unwrap_or(0.0) + slid,
            v: pose.slide.map_or(0.0, |sl| sl.v),
            ..State::default()
        };
        // What the held blocks slid in the chain (a slip going on is the stack's own).
        let mut held = pose.moved.clone();
        held.resize(links.body_joint, 0.0);
        let corner = match pose.open.as_slice() {
            [] if pose.slide.is_none() => {
                return Some(Some(Next::Body(state, Mode::Rest, held, None)))
            }
            [] => return Some(None),
            [o] if o.joint == links.body_joint => Corner::of_sign(o.s),
            _ => return None,
        };
        let state = State {
            theta: pose.phi[0],
            omega: pose.omega[0],
            ..state
        };
        let Some(sl) = pose.slide else {
            return Some(Some(Next::Body(state, Mode::Rock(corner), held, None)));
        };
        let slip = Slip::of_sign(sl.sigma);
        if sl.joint == links.body_joint {
            return Some(Some(Next::Body(
                state,
                Mode::SlideRock(corner, slip),
                held,
                None,
            )));
        }
        // The stack from the slipping joint up to the body slides on under it.
        let k = (links.watch.slips_under(sl.joint..sl.joint + 1)).nth(usize::from(sl.sigma > 0.0));
        let stack = k.and_then(|k| links.watch.stack_on(k, state.u - slid));
        Some(stack.map(|stack| Next::Body(state, Mode::Rock(corner), held, Some((stack, slid)))))
    }

    /// The body takes over again from `state` in `mode`, its mode decided now; its column's
    /// held blocks keep what they slid in the chain (`moved`, from the bottom).
    fn resume(
        &mut self,
        (state, mode): (State, Mode),
        moved: Vec<f64>,
        stack: Option<(Stack, f64)>,
    ) -> Result<(), SimulationError> {
        let tr = &mut self.tracks[0];
        tr.displaced.shift(&moved);
        tr.state = state;
        tr.mode = mode;
        let (_, now) = self.inputs_at(self.t);
        let (Some((stack, slid)), Some(c)) = (stack, mode.pivot()) else {
            return self.decide(0, &now, false);
        };
        if !self.stack_carries(0, (stack, slid), c, &now) {
            let watch = &self.scene.watches[0];
            let (joint, _, _) = watch.describe(4 * stack.joint);
            let blocks = self.chain_outputs(stack.first, watch.pieces.len());
            self.held_joint_gives(
                0,
                &blocks,
                joint,
                "slips under the body as the chain ends, where several ways of the body on \
                 the sliding stack hold",
                false,
            );
        }
        Ok(())
    }

    /// The chain's condition `cut` of `pose` falls at tau on `path`: the exact model ends
    /// there, its blocks where `path` has them, or, where the condition is a landing's
    /// impulse, where `landing` (the path and the time into it just before the impact) has
    /// them. The event and warning name the joint and how it gives way.
    fn chain_stops(
        &mut self,
        links: &Links,
        (pose, path, tau): (&Pose, &Path, f64),
        cut: Cut,
        landing: Option<(&Path, f64)>,
    ) {
        let j = match cut {
            Cut::Land(c) | Cut::Pivot(c, _) | Cut::Overturn(c) => pose.open[c].joint,
            Cut::Closed(j, _) => j,
            Cut::Stop | Cut::Lift => pose.slide.map_or(pose.open[0].joint, |sl| sl.joint),
        };
        let pressed = match cut {
            Cut::Pivot(..) => eval(&links.passed(path, j).1, tau) > 0.0,
            _ => true,
        };
        let how = match cut {
            Cut::Closed(_, 2) => {
                "would open at its right end while the column turns on another corner below \
                 it (beyond the chain)"
            }
            Cut::Closed(_, 3) => {
                "would open at its left end while the column turns on another corner below it \
                 (beyond the chain)"
            }
            _ => how(cut, pressed),
        };
        self.chain_ends_at(links, (path, tau), j, how, landing);
    }

    /// The exact model ends the run at tau on `path` (or just before a landing's impact,
    /// `landing`), joint j giving way as `how` says.
    fn chain_ends_at(
        &mut self,
        links: &Links,
        (path, tau): (&Path, f64),
        j: usize,
        how: &str,
        landing: Option<(&Path, f64)>,
    ) {
        let blocks = self.chain_outputs(j, links.blocks());
        let joint = links.joints[j].name.clone();
        self.held_joint_gives(0, &blocks, joint, how, landing.is_some());
        let (end, at) = landing.unwrap_or((path, tau));
        self.end_chain(links, end, at, &[]);
    }

    /// The run ends in the chain at tau on `path`: its last row, and the energies left, minus
    /// those of the blocks of `fallen`.
    fn end_chain(&mut self, links: &Links, path: &Path, tau: f64, fallen: &[usize]) {
        self.t_end = self.t;
        let (_, now) = self.inputs_at(self.t);
        self.chain_row(links, path, tau, self.t, now.accel[0], true);
        let mut kinetic = 0.0;
        let mut potential = 0.0;
        for (p, (ke, pe)) in links.energies(path, tau).into_iter().enumerate() {
            if fallen.contains(&p) {
                self.rec.energy.fallen_j += ke + pe;
            } else {
                kinetic += ke;
                potential += pe;
            }
        }
        let n = self.layout.len();
        let (mut u, mut v) = (vec![0.0; n], vec![0.0; n]);
        let mut placed = vec![(0.0, 0.0, Turned::default()); n];
        for p in 0..links.blocks() {
            let o = self.layout.column_output(0, p);
            let x = &path.base[p][0];
            u[o] = eval(x, tau) - links.watch.outputs[p].x0;
            v[o] = eval(&derivative(x), tau);
            // The centroid, from its place at rest (not shifted with the body's slip); the
            // rotation counter-clockwise.
            let (rest, [gx, gy]) = (&links.watch.pieces[p], &path.centroid[p]);
            let (phi, omega) = path.body[p].map_or((0.0, 0.0), |c| {
                (eval(&path.phi[c], tau), eval(&path.omega[c], tau))
            });
            placed[o] = (
                eval(gx, tau) - rest.x0,
                eval(&derivative(gx), tau),
                Turned {
                    rise_m: eval(gy, tau) - rest.y0,
                    phi_rad: -phi,
                    rise_m_s: eval(&derivative(gy), tau),
                    omega_rad_s: -omega,
                },
            );
        }
        self.chain_end = Some(super::ChainEnd {
            u,
            v,
            kinetic_j: kinetic,
            potential_j: potential,
            placed,
        });
    }

    /// Extremes and, when `row`, a history row at t, tau into the step of `path`.
    fn chain_row(&mut self, links: &Links, path: &Path, tau: f64, t: f64, a_g: f64, row: bool) {
        let mut r = super::Row::at_rest(self.layout.len(), a_g);
        for p in 0..links.blocks() {
            let o = self.layout.column_output(0, p);
            let rest = &links.watch.outputs[p];
            let [x, y] = &path.base[p];
            let vx = derivative(x);
            r.u[o] = eval(x, tau) - rest.x0;
            r.v[o] = eval(&vx, tau);
            r.w[o] = eval(y, tau) - rest.y0;
            r.accel[o] = Some(a_g + eval(&derivative(&vx), tau));
            if let Some(c) = path.body[p] {
                r.theta[o] = eval(&path.phi[c], tau);
                r.omega[o] = eval(&path.omega[c], tau);
            }
        }
        self.record(&r, t, row);
    }

    /// Runs the chain from `pose` until the engine takes it back or the run ends.
    fn run_chain(&mut self, links: &Links, mut pose: Pose) -> Result<(), SimulationError> {
        let body = &self.scene.bodies[0];
        let sc = Scales::of(body);
        let (p, ts) = (body.frequency_parameter_rad_s(), body.time_scale_s());
        let size = body.size_m();
        let dt = self.scene.settings.output_dt_s;
        let mut row = true;
        let mut stalled = 0usize;
        loop {
            let (seg, inputs) = self.inputs_at(self.t);
            let path = links.path(&pose, &inputs)?;
            if self.t >= self.t_end {
                self.end_chain(links, &path, 0.0, &[]);
                return Ok(());
            }
            let limit = seg.t1.min(self.t_end);
            let span = limit - self.t;
            let mut steps: Vec<(&Coeffs, f64)> = Vec::new();
            for c in 0..pose.open.len() {
                steps.push((&path.phi[c], 1.0));
                steps.push((&path.omega[c], p));
            }
            for b in &path.base {
                steps.push((&b[0], size));
            }
            if let Some((_, u, _)) = &path.slide {
                steps.push((u, size));
            }
            let h = series::step_size(&steps).min(span);
            let mut best: Option<(f64, Option<Cut>)> = None;
            let mut consider = |x: Option<f64>, what: Option<Cut>| {
                if let Some(x) = x.filter(|&x| x <= h) {
                    if best.is_none_or(|(b, _)| x < b) {
                        best = Some((x, what));
                    }
                }
            };
            for c in links.conditions(&pose, &path, &sc) {
                consider(series::first_fall(&c.series, c.scale, ts, h), Some(c.cut));
            }
            // Extremes of each body's rotation and of each block's u and u'.
            let mut extreme = |d: &Coeffs, scale: f64| {
                let sign = sign_after(d, scale, ts);
                if sign != 0 {
                    let f = d.map(|x| x * f64::from(sign));
                    consider(series::first_fall(&f, scale, ts, h), None);
                }
            };
            for c in 0..pose.open.len() {
                extreme(&path.omega[c], sc.angle * p);
            }
            for (b, body) in path.base.iter().zip(&path.body) {
                if body.is_some() {
                    let v = derivative(&b[0]);
                    extreme(&v, sc.velocity);
                    extreme(&derivative(&v), sc.velocity * p);
                }
            }
            self.chain_row(links, &path, 0.0, self.t, inputs.accel[0], row);
            self.rec.stats.steps += 1;
            if !self.keep_going() {
                self.end_chain(links, &path, 0.0, &[]);
                return Ok(());
            }
            let tau = best.map_or(h, |(x, _)| x);
            let t_new = if tau >= span { limit } else { self.t + tau };
            if t_new > self.t {
                stalled = 0;
            } else {
                stalled += 1;
                if stalled > super::STALL_STOPS {
                    return Err(SimulationError::TooManyEvents {
                        time_s: self.t,
                        count: stalled,
                        detail: "a rocking column's events".into(),
                        limit: "a chain of rocking blocks that changes its configuration this \
                                often without time passing is beyond the rocking model; please \
                                report the wall and the motion",
                    });
                }
            }
            while self.next_out < t_new {
                let tau_out = self.next_out - self.t;
                let a_g = eval(&inputs.accel, tau_out);
                self.chain_row(links, &path, tau_out, self.next_out, a_g, true);
                self.outputs += 1;
                self.next_out = (self.outputs + 1) as f64 * dt.unwrap_or(f64::INFINITY);
            }
            self.rec.energy.input_j += integral(&links.input_power(&path, &inputs), tau);
            self.rec.energy.friction_j += integral(&links.friction_power(&pose, &path), tau);
            pose.phi = path.phi.iter().map(|c| eval(c, tau)).collect();
            pose.omega = path.omega.iter().map(|c| eval(c, tau)).collect();
            if let (Some(sl), Some((_, u, v))) = (&mut pose.slide, &path.slide) {
                sl.u = eval(u, tau);
                sl.v = eval(v, tau);
            }
            self.t = t_new;
            if self.t >= self.next_out {
                self.outputs += 1;
                self.next_out = (self.outputs + 1) as f64 * dt.unwrap_or(f64::INFINITY);
                row = true;
            } else {
                row = false;
            }
            let (_, now) = self.inputs_at(self.t);
            let event = best.filter(|(x, _)| *x == tau).and_then(|(_, cut)| cut);
            let next = match event {
                Some(cut) => {
                    self.rec.stats.events += 1;
                    row = true;
                    self.chain_event(links, pose, &path, tau, cut, &now)?
                }
                None if self.t == seg.t1 && self.t < self.t_end => {
                    self.rec.stats.segments += 1;
                    self.settle(links, pose, &now)?
                }
                None => Next::Chain(pose),
            };
            match next {
                Next::Chain(next) => pose = next,
                Next::Body(state, mode, moved, stack) => {
                    return self.resume((state, mode), moved, stack)
                }
                Next::End => return Ok(()),
            }
        }
    }

    /// Handles the chain's event `cut`, reached tau into the step of `path`.
    fn chain_event(
        &mut self,
        links: &Links,
        pose: Pose,
        path: &Path,
        tau: f64,
        cut: Cut,
        now: &Inputs,
    ) -> Result<Next, SimulationError> {
        match cut {
            Cut::Land(c) => self.chain_lands(links, pose, path, tau, c, now),
            Cut::Closed(..) => self.settle(links, pose, now),
            Cut::Pivot(c, _)
                if c == 0 && eval(&links.passed(path, pose.open[0].joint).1, tau) > 0.0 =>
            {
                self.settle(links, pose, now)
            }
            Cut::Pivot(c, _) if links.inner_pivot(&pose, path, (c, tau)) => {
                self.settle(links, pose, now)
            }
            Cut::Stop => {
                let mut pose = pose;
                let place = if inside(&pose) { "inside" } else { "under" };
                let sl = pose.slide.take().expect("a slip that stops");
                // What it slid stays with the blocks above it, in the frame of the body under
                // the joint.
                pose.moved.resize(links.blocks(), 0.0);
                pose.moved[sl.joint..].iter_mut().for_each(|d| *d += sl.u);
                let what = format!(
                    "stops on {} {place} the chain, having slid {:.6e} m",
                    links.joints[sl.joint].name, sl.u
                );
                self.slide_event(links, sl.joint, EventKind::Stick, what);
                self.settle(links, pose, now)
            }
            Cut::Overturn(c) => {
                let j = pose.open[c].joint;
                let blocks = self.chain_outputs(j, links.blocks());
                for &b in &blocks {
                    self.rec.fell(b);
                }
                self.rec.rocking_event(
                    self.t,
                    EventKind::Overturning,
                    &blocks,
                    None,
                    format!(
                        "overturned on {} (the run ends here: the exact model does not follow \
                         the blocks that stay)",
                        links.joints[j].name
                    ),
                );
                if self.rec.collapse.is_none() {
                    self.rec.collapse = Some(Collapse {
                        time_s: self.t,
                        block: links.watch.outputs[j].name.clone(),
                        cause: CollapseCause::Overturning,
                    });
                }
                let fallen: Vec<usize> = (j..links.blocks()).collect();
                self.end_chain(links, path, tau, &fallen);
                Ok(Next::End)
            }
            cut => {
                self.chain_stops(links, (&pose, path, tau), cut, None);
                Ok(Next::End)
            }
        }
    }

    /// Open joint c lands: on its other corner if the part above it turns on onto it after the
    /// impulse, else seated; the momentum balance decides the rates after, and the impulses
    /// every joint passes are checked against its friction and contact. The joints under the
    /// chain either hold through the impact (a slip before it stopped by it) or one slips at its
    /// friction's limit (the one slipping before, on; or, where none did, one that can slip
    /// under the chain, either way; a restitution factor of 1): exactly one way must hold.
    fn chain_lands(
        &mut self,
        links: &Links,
        pose: Pose,
        path: &Path,
        tau: f64,
        c: usize,
        now: &Inputs,
    ) -> Result<Next, SimulationError> {
        if inside(&pose) {
            let how = "lands while a joint inside the chain slips (beyond the chain)";
            let j = pose.open[c].joint;
            self.chain_ends_at(links, (path, tau), j, how, Some((path, tau)));
            return Ok(Next::End);
        }
        let body = &self.scene.bodies[0];
        let energy_before: f64 = links.energies(path, tau).iter().map(|(k, p)| k + p).sum();
        let at = Instant::of(&pose, path, tau);
        let velocity: Vec<[f64; 2]> = path
            .centroid
            .iter()
            .map(|g| g.map(|x| eval(&derivative(&x), tau)))
            .collect();
        let spin: Vec<f64> = path
            .body
            .iter()
            .map(|b| b.map_or(0.0, |b| eval(&path.omega[b], tau)))
            .collect();
        // A rise after the landing below ZENO_ROTATION alpha ends the series of landings there
        // (seated), as a single body's does.
        let zeno = ZENO_ROTATION.sqrt()
            * 2f64.sqrt()
            * Scales::of(body).angle
            * body.frequency_parameter_rad_s();
        let f = body.restitution_factor;
        let land = |way| links.landed(&pose, c, way, (&at, &velocity, &spin), (zeno, f));
        let held = land((None, None)).ok_or_else(|| {
            SimulationError::Bug("a chain's landing has no momentum balance".into())
        })?;
        let j = pose.open[c].joint;
        let bases: Vec<(usize, f64)> = match pose.slide {
            _ if f != 1.0 => Vec::new(),
            Some(sl) => vec![(sl.joint, sl.sigma)],
            None => (0..=pose.open[0].joint)
                .flat_map(|k| [(k, -1.0), (k, 1.0)])
                .collect(),
        };
        // Every closed joint may open through the impact at either end, the joints under the
        // chain holding or slipping (a restitution factor of 1, as for slips).
        let opens: Vec<Open> = (0..links.blocks())
            .filter(|&k| f == 1.0 && pose.open.iter().all(|o| o.joint != k))
            .flat_map(|joint| [-1.0, 1.0].map(|s| Open { joint, s }))
            .collect();
        let bases_or_held = || std::iter::once(None).chain(bases.iter().copied().map(Some));
        let others = (bases.iter().map(|&b| (Some(b), None))).chain(
            opens
                .iter()
                .flat_map(|&o| bases_or_held().map(move |b| (b, Some(o)))),
        );
        // A landing that starts a series that accumulates is taken seated, the joints under
        // the chain held, as every landing of the series was.
        let slips: Vec<Landed> = others
            .filter(|_| !held.accumulates)
            .filter_map(land)
            .filter(|way| way.breaks.is_none())
            .collect();
        let held_holds = held.breaks.is_none() || held.accumulates;
        let way = match (held_holds, slips.len()) {
            (true, 0) => held,
            (false, 1) => slips.into_iter().next().expect("one way"),
            (false, 0) => {
                // The landing's impulses would break a joint, so the impact is not the one the
                // model has: the run stops at the instant before it (where a hand-off's time
                // stepping resolves it), not after an impact it does not believe.
                let new_path = links.path(&held.next, now)?;
                let cut = held.breaks.expect("a broken condition");
                self.chain_stops(links, (&held.next, &new_path, 0.0), cut, Some((path, tau)));
                return Ok(Next::End);
            }
            _ => {
                let how = "lands where the joints under the chain could hold, slip or open in \
                           several ways (beyond the chain)";
                self.chain_ends_at(links, (path, tau), j, how, Some((path, tau)));
                return Ok(Next::End);
            }
        };
        let Landed {
            next, accumulates, ..
        } = way;
        let new_path = links.path(&next, now)?;
        let o = pose.open[c];
        let rel = |omega: &[f64], c: usize| omega[c] - if c > 0 { omega[c - 1] } else { 0.0 };
        let before = rel(&pose.omega, c);
        let nb = links.blocks();
        let blocks = self.chain_outputs(j, nb);
        for &b in &blocks {
            self.rec.rocking_impact(b);
        }
        self.rec.impacts += 1;
        let landed = next.open.iter().position(|x| x.joint == j);
        let after_rel = landed.map_or(0.0, |c| rel(&next.omega, c));
        self.rec.rocking_event(
            self.t,
            EventKind::RockingImpact,
            &blocks,
            Some((before, after_rel)),
            if landed.is_some() {
                format!(
                    "{} lands on its {} corner",
                    links.joints[j].name,
                    Corner::of_sign(-o.s).name()
                )
            } else if accumulates {
                format!(
                    "{} lands seated: its landings accumulate",
                    links.joints[j].name
                )
            } else {
                format!("{} lands seated", links.joints[j].name)
            },
        );
        for new in next
            .open
            .iter()
            .filter(|x| !pose.open.iter().any(|o| o.joint == x.joint))
        {
            self.opened(links, new.joint, "opens through the landing");
        }
        match (pose.slide, next.slide) {
            (Some(sl), None) => {
                let what = format!(
                    "the landing stops the slip on {} under the chain, having slid {:.6e} m",
                    links.joints[sl.joint].name, sl.u
                );
                self.slide_event(links, sl.joint, EventKind::Stick, what);
            }
            (None, Some(sl)) => {
                let what = format!(
                    "{} slips under the chain through the landing, towards {} at {:.6e} m/s",
                    links.joints[sl.joint].name,
                    towards(sl.sigma),
                    sl.v
                );
                self.slide_event(links, sl.joint, EventKind::Slip, what);
            }
            _ => {}
        }
        let energy_after: f64 = links
            .energies(&new_path, 0.0)
            .iter()
            .map(|(k, p)| k + p)
            .sum();
        self.rec.energy.impact_loss_j += energy_before - energy_after;
        if accumulates {
            // Every landing of the series kept its impulses in the joint's cone and contact;
            // the seat they end in is their limit, not one impulse.
            self.rec.zeno += 1;
        }
        self.settle(links, next, now)
    }
}

/// One way a chain's landing can go (`Links::landed`).
struct Landed {
    /// The chain after the impact.
    next: Pose,
    /// The landing joint's landings accumulate: it lands seated, its impulses not checked.
    accumulates: bool,
    /// The first condition the impulses break, if one does.
    breaks: Option<Cut>,
}

impl Links<'_> {
    /// The joints that can start to slip under `pose`'s chain: each held joint below the
    /// lowest open one, and that joint where its pivot is a corner of the block on it.
    fn slip_joints(&self, pose: &Pose) -> impl Iterator<Item = usize> {
        let lowest = pose.open[0];
        let pivot_slips = self.joints[lowest.joint].upper_corner[usize::from(lowest.s > 0.0)];
        (0..lowest.joint).chain(pivot_slips.then_some(lowest.joint))
    }

    /// Open joint c of `pose` lands at `at` (the blocks' velocities and spins before), the
    /// joints under the chain held (`base` none) or joint `base.0` slipping at its friction's
    /// limit against the sign `base.1`, and a closed joint opening through the impact where
    /// `opens` names it: the chain after (on the other corner where the part above turns on
    /// onto it, else seated; rates times the restitution factor `f` on the other corner), and
    /// what its impulses break. A slip that would not go the way it is assumed to breaks
    /// `Cut::Stop`; a joint that would not open the way it is assumed to, `Cut::Closed` with
    /// its condition. None where the momentum balance has no solution.
    fn landed(
        &self,
        pose: &Pose,
        c: usize,
        (base, opens): (Option<(usize, f64)>, Option<Open>),
        (at, velocity, spin): (&Instant, &[[f64; 2]], &[f64]),
        (zeno, f): (f64, f64),
    ) -> Option<Landed> {
        let nb = self.blocks();
        let rel = |omega: &[f64], c: usize| omega[c] - if c > 0 { omega[c - 1] } else { 0.0 };
        let o = pose.open[c];
        // The other corner, seated at theta = 0 exactly.
        let mut flipped = pose.clone();
        flipped.open[c].s = -o.s;
        flipped.phi[c] = if c > 0 { pose.phi[c - 1] } else { 0.0 };
        // The joint that opens turns from the rotation of the body it belonged to.
        let opened = |mut p: Pose| {
            if let Some(new) = opens {
                let k = p.open.partition_point(|x| x.joint < new.joint);
                let phi = if k > 0 { p.phi[k - 1] } else { 0.0 };
                p.open.insert(k, new);
                p.phi.insert(k, phi);
                p.omega.insert(k, 0.0);
            }
            p
        };
        let flipped = opened(flipped);
        let shift = usize::from(opens.is_some_and(|new| new.joint < o.joint));
        let on_corner = self
            .momentum_balance(&flipped.open, base, at, velocity, spin)
            .filter(|(rates, ..)| -o.s * rel(rates, c + shift) > 0.0);
        // The landings of a joint accumulate: what the sum leaves out, the rest of the series
        // (its duration, which is of the order of the rate over the joint's angular
        // acceleration, under a microsecond at this size, is not added), is counted as lost.
        let accumulates = on_corner
            .as_ref()
            .is_some_and(|(rates, ..)| -o.s * rel(rates, c + shift) <= zeno);
        let (mut next, rates, w, after) = match on_corner.filter(|_| !accumulates) {
            Some((rates, w, after)) => {
                let rates = rates.iter().map(|w| w * f).collect();
                let after = after.iter().map(|v| v.map(|x| x * f)).collect();
                (flipped, rates, w * f, after)
            }
            None => {
                let mut seated = pose.clone();
                seated.open.remove(c);
                seated.phi.remove(c);
                seated.omega.remove(c);
                let seated = opened(seated);
                let (rates, w, after) =
                    self.momentum_balance(&seated.open, base, at, velocity, spin)?;
                (seated, rates, w, after)
            }
        };
        next.omega = rates;
        // A joint opened by the impulse leaves its seat: the part above it turns onto its pivot.
        let opening = opens.and_then(|new| {
            let k = next.open.iter().position(|x| *x == new)?;
            (new.s * rel(&next.omega, k) <= 0.0)
                .then_some(Cut::Closed(new.joint, 2 + usize::from(new.s > 0.0)))
        });
        // A joint slips under the chain after the impact only where one can (its lowest pivot
        // the landing's new corner, where the joint that lands is the lowest).
        if let Some((joint, _)) = base {
            if next.open.is_empty() || !self.slip_joints(&next).any(|k| k == joint) {
                return None;
            }
        }
        // The joints under the chain after the impact: a slip on, or begun, or stopped (the
        // blocks keeping what it slid).
        next.slide = base.map(|(joint, sigma)| match pose.slide {
            Some(sl) if sl.joint == joint => Slide { v: w, ..sl },
            _ => Slide {
                joint,
                sigma,
                u: 0.0,
                v: w,
            },
        });
        if let (Some(sl), None) = (pose.slide, base) {
            next.moved.resize(nb, 0.0);
            next.moved[sl.joint..].iter_mut().for_each(|d| *d += sl.u);
        }
        // The impulses: each joint passes up what the blocks above it gain.
        let gain: Vec<[f64; 2]> = (0..nb)
            .map(|p| {
                let m = self.watch.pieces[p].mass_kg;
                [
                    m * (after[p][0] - velocity[p][0]),
                    m * (after[p][1] - velocity[p][1]),
                ]
            })
            .collect();
        let new_body = self.bodies(&next.open);
        let spin_gain: Vec<f64> = (0..nb)
            .map(|p| {
                let w = new_body[p].map_or(0.0, |b| next.omega[b]);
                self.watch.pieces[p].inertia_kg_m2 * (w - spin[p])
            })
            .collect();
        let scale: f64 = gain.iter().map(|g| g[0].abs() + g[1].abs()).sum::<f64>()
            + spin_gain.iter().map(|x| x.abs()).sum::<f64>() / self.height();
        let goes = base.is_none_or(|(_, sigma)| sigma * w > 0.0);
        let breaks = if !goes {
            Some(Cut::Stop)
        } else {
            opening.or_else(|| self.impulse_breaks(&next, at, &gain, &spin_gain, scale))
        };
        Some(Landed {
            next,
            accumulates,
            breaks,
        })
    }

    /// Whether open joint c (above the lowest) turns on a corner of the block on it that
    /// presses the face under it at tau on `path` (its normal force, in that face's frame,
    /// positive): a pivot that can slip inside the chain.
    fn inner_pivot(&self, pose: &Pose, path: &Path, (c, tau): (usize, f64)) -> bool {
        let Some(b) = c.checked_sub(1) else {
            return false;
        };
        let o = pose.open[c];
        let (h, v) = self.passed(path, o.joint);
        let (sin, cos) = (eval(&path.sin[b], tau), eval(&path.cos[b], tau));
        self.joints[o.joint].upper_corner[usize::from(o.s > 0.0)]
            && eval(&h, tau) * sin + eval(&v, tau) * cos > 0.0
    }

    /// Whether every condition of the chain in `way` holds just after now.
    fn holds_after(
        &self,
        way: &Pose,
        now: &Inputs,
        (sc, ts): (&Scales, f64),
    ) -> Result<bool, SimulationError> {
        let path = self.path(way, now)?;
        let conditions = self.conditions(way, &path, sc);
        Ok((conditions.iter()).all(|c| sign_after(&c.series, c.scale, ts) >= 0))
    }

    /// The ways joint j inside `pose`'s chain (a closed joint above the lowest open one, or a
    /// higher open joint's pivot) can start to slip, either way: those whose every condition
    /// holds just after now.
    fn inner_ways(
        &self,
        pose: &Pose,
        j: usize,
        now: &Inputs,
        sc: &Scales,
        ts: f64,
    ) -> Result<Vec<Pose>, SimulationError> {
        let mut ways = Vec::new();
        for sigma in [-1.0, 1.0] {
            let way = Pose {
                slide: Some(Slide {
                    joint: j,
                    sigma,
                    u: 0.0,
                    v: 0.0,
                }),
                ..pose.clone()
            };
            if self.holds_after(&way, now, (sc, ts))? {
                ways.push(way);
            }
        }
        Ok(ways)
    }

    /// The ways a joint under `pose`'s chain can start to slip, each the chain with that slip
    /// whose every condition holds just after now: a held joint below the lowest open one, or
    /// that joint's pivot where it is a corner of the block on it, either way, with the chain as
    /// it is or with one closed joint opening at either end at the same instant.
    fn slide_ways(
        &self,
        pose: &Pose,
        now: &Inputs,
        sc: &Scales,
        ts: f64,
    ) -> Result<Vec<Pose>, SimulationError> {
        // A closed joint may open as the slip begins: its part turns from the rotation of the
        // body it belonged to, at its rate.
        let opened = |new: Open| {
            let mut p = pose.clone();
            let k = p.open.partition_point(|x| x.joint < new.joint);
            let (phi, omega) = match k {
                0 => (0.0, 0.0),
                _ => (p.phi[k - 1], p.omega[k - 1]),
            };
            p.open.insert(k, new);
            p.phi.insert(k, phi);
            p.omega.insert(k, omega);
            p
        };
        let poses = std::iter::once(pose.clone()).chain(
            (0..self.blocks())
                .filter(|&j| pose.open.iter().all(|o| o.joint != j))
                .flat_map(|joint| [-1.0, 1.0].map(|s| opened(Open { joint, s }))),
        );
        let mut ways = Vec::new();
        for p in poses {
            for joint in self.slip_joints(&p) {
                for sigma in [-1.0, 1.0] {
                    let way = Pose {
                        slide: Some(Slide {
                            joint,
                            sigma,
                            u: 0.0,
                            v: 0.0,
                        }),
                        ..p.clone()
                    };
                    if self.holds_after(&way, now, (sc, ts))? {
                        ways.push(way);
                    }
                }
            }
        }
        Ok(ways)
    }

    /// The column's height (m): the moment scale over the force scale.
    fn height(&self) -> f64 {
        self.watch.moment_scale / self.watch.force_scale
    }

    /// The first joint condition a landing's impulses break: the linear impulse each joint
    /// passes up (what the blocks above it gain, `gain`, with their angular impulses
    /// `spin_gain`) must lie in its friction cone, pressing; a closed joint's resultant within
    /// its contact.
    fn impulse_breaks(
        &self,
        pose: &Pose,
        at: &Instant,
        gain: &[[f64; 2]],
        spin_gain: &[f64],
        scale: f64,
    ) -> Option<Cut> {
        let tol = TIE * scale;
        let nb = self.blocks();
        let body = self.bodies(&pose.open);
        for (j, joint) in self.joints.iter().enumerate() {
            let (jx, jy) = (j..nb).fold((0.0, 0.0), |(x, y), p| (x + gain[p][0], y + gain[p][1]));
            let open = pose.open.iter().position(|o| o.joint == j);
            let face = match open {
                Some(c) if joint.upper_corner[usize::from(pose.open[c].s > 0.0)] => {
                    c.checked_sub(1)
                }
                Some(c) => Some(c),
                None => body[j],
            };
            let (sin, cos) = face.map_or((0.0, 1.0), |c| at.phi[c].sin_cos());
            let (n, t) = (jx * sin + jy * cos, jx * cos - jy * sin);
            let mu = joint.friction;
            let cone = [mu * n - t, mu * n + t];
            // A joint that slips passes its friction's limit by its law; it must press.
            let slipping = pose.slide.is_some_and(|sl| sl.joint == j);
            if slipping && n < -tol {
                return Some(Cut::Lift);
            }
            if let Some(i) = cone.iter().position(|&x| x < -tol).filter(|_| !slipping) {
                return Some(match open {
                    Some(c) => Cut::Pivot(c, i),
                    None => Cut::Closed(j, i),
                });
            }
            if open.is_some() {
                continue;
            }
            let height = self.height();
            let moments = [-1.0, 1.0].map(|s| {
                let e = at.point(self, j, s);
                (j..nb)
                    .map(|p| {
                        let (dx, dy) = (at.centroid[p][0] - e[0], at.centroid[p][1] - e[1]);
                        dx * gain[p][1] - dy * gain[p][0] - spin_gain[p]
                    })
                    .sum::<f64>()
            });
            if moments[0] < -tol * height {
                return Some(Cut::Closed(j, 2));
            }
            if -moments[1] < -tol * height {
                return Some(Cut::Closed(j, 3));
            }
        }
        None
    }
}

#[cfg(test)]
#[path = "chain_tests.rs"]
mod tests;
