//! Triliths: a lintel resting on two equal columns that stand on the ground (Andreaus and
//! Casini 1999; Makris and Vassiliou 2013). While the lintel stays on both columns and the
//! columns' feet hold, the three blocks rock as a parallelogram of one degree of freedom: the
//! columns turn equally about their feet, the lintel translates with the corners of their tops
//! opposite the feet. Every point of the frame then moves with the vector from a foot to a
//! column's centroid (the lintel's corners at twice it), so its kinetic and potential energy and
//! the work of the ground are those of one rigid body: the frame's mass 2m + M, its centroid on
//! the column's diagonal at R (2m + 2M) / (2m + M) from the foot, its inertia about the foot
//! 2 I_O + 4 M R^2. The exact engine runs that body through rest, sliding, rocking and landings
//! (its uplift at g tan alpha whatever the lintel: Makris and Vassiliou's result), with the
//! frame's coefficient of restitution, and this module's [`Frame`] watches each joint with the
//! forces of the mechanism: the lintel's load on each column (its moment balance), each
//! column's foot (its own moment balance about the foot). What the one-body picture cannot
//! carry ends the exact model at that instant, as a column's held joint does: a foot or the
//! lintel slipping, the lintel leaving a column, the feet slipping while the frame rocks (the
//! columns would then turn unequally: slide-rock of a trilith has three degrees of freedom) or
//! through a landing, and, seated, a slip that how the load divides between two faces could
//! allow (the lintel's two joints, or feet of different friction, from the smaller friction).

use super::body::RockingBody;
use super::modes::{Constraint, Corner, Guard, Inputs, Mode, Trajectory, Velocity};
use super::series::{
    add, add_to, derivative, div_at, product, scaled, sin_cos_at, Coeffs, ORDER, TIE, ZERO,
};
use crate::error::SimulationError;
use crate::exact::Q;
use crate::topology::{Base, BlockId, Topology};
use crate::wall::Wall;

/// The joints of a trilith and the forces the mechanism asks of them.
#[derive(Debug, Clone)]
pub(crate) struct Frame {
    /// Mass (kg) of a column, its inertia about its centroid (kg m2), half its width b and half
    /// its height h (m).
    column_kg: f64,
    column_inertia: f64,
    b: f64,
    h: f64,
    /// The lintel's mass (kg) and its centroid at rest (m, m).
    lintel_kg: f64,
    lintel: (f64, f64),
    /// The middle of each column's foot at rest (m), left column first.
    feet_x: [f64; 2],
    /// The outer ends of the lintel's contacts on the columns' tops at rest (m).
    ends: [f64; 2],
    /// Friction under each column's foot and of the lintel on each column, left first.
    ground_friction: [f64; 2],
    top_friction: [f64; 2],
    /// `column/ground` for each column, then `lintel/column`.
    feet: [String; 2],
    tops: [String; 2],
    /// Places in the column's outputs: the columns, left first, and the lintel.
    columns: [usize; 2],
    lintel_output: usize,
    pub(super) g_m_s2: f64,
    /// Forces (N) and moments (N m) are measured against the trilith's weight and its weight
    /// times its height.
    pub(super) force_scale: f64,
    pub(super) moment_scale: f64,
}

/// How a trilith's joint gives way, for the conditions of [`Frame::conditions`] by their index
/// mod 4 (0-7: rocking, per column the lintel's contact and the foot; 8-11: seated, the
/// lintel on both), then what the one-body picture cannot follow.
const SLIPS: [&str; 2] = [
    "would slip, the block on it towards -x (it needs more friction towards +x than the joint \
     holds)",
    "would slip, the block on it towards +x (it needs more friction towards -x than the joint \
     holds)",
];
const TIPS: [&str; 2] = [
    "would open at its right end (the lintel would tip about the left end of its supports)",
    "would open at its left end (the lintel would tip about the right end of its supports)",
];
const SLIDE_ROCK: &str = "would slip while the trilith rocks: the columns would then turn \
                          unequally (slide-rock of a trilith), beyond the exact model";
const SLIPPED_LANDING: &str = "would slip through a landing of the rocking trilith, beyond the \
                               exact model";
const SEATED_FEET: &str = "could slip: the seated trilith's feet hold with different friction and \
                           how its weight divides between them is not determined, so from the \
                           smaller friction on a slip cannot be ruled out (beyond the exact \
                           model)";

/// Condition indices past the joints' own: the feet slipping while rocking, or in a landing;
/// then a seated trilith's feet of different friction (towards +x, -x).
const K_SLIDE_ROCK: usize = 12;
const K_SLIPPED_LANDING: usize = 13;
const K_SEATED_FEET: usize = 14;

impl Frame {
    /// The joint, how it gives way and the block on it (place in the column's outputs) for
    /// condition `k`.
    pub(crate) fn describe(&self, k: usize) -> (String, &'static str, usize) {
        let both = |names: &[String; 2]| format!("{} and {}", names[0], names[1]);
        match k {
            0..8 => {
                let (i, c) = (k / 4, k % 4);
                if c < 2 {
                    (self.tops[i].clone(), SLIPS[c], self.lintel_output)
                } else {
                    (self.feet[i].clone(), SLIPS[c - 2], self.columns[i])
                }
            }
            8 | 9 => (both(&self.tops), SLIPS[k - 8], self.lintel_output),
            10 | 11 => (both(&self.tops), TIPS[k - 10], self.lintel_output),
            K_SLIDE_ROCK => (both(&self.feet), SLIDE_ROCK, self.columns[0]),
            K_SLIPPED_LANDING => (both(&self.feet), SLIPPED_LANDING, self.columns[0]),
            _ => (both(&self.feet), SEATED_FEET, self.columns[0]),
        }
    }

    /// The condition that a mode of the one-body picture breaks, if it is one the trilith cannot
    /// follow: slide-rock, and sliding seated on feet of different friction.
    pub(crate) fn forbids(&self, mode: Mode) -> Option<usize> {
        match mode {
            Mode::SlideRock(..) => Some(K_SLIDE_ROCK),
            Mode::Slide(_) if self.unequal_feet() => Some(K_SEATED_FEET),
            _ => None,
        }
    }

    /// The contacts a landing strikes at once: both feet and both of the lintel's contacts.
    pub(crate) fn landing_contacts(&self) -> String {
        format!(
            "{}, {}, {} and {} at once",
            self.feet[0], self.feet[1], self.tops[0], self.tops[1]
        )
    }

    fn unequal_feet(&self) -> bool {
        self.ground_friction[0] != self.ground_friction[1]
    }

    /// The joints' conditions along a trajectory of the frame's body, each to stay
    /// non-negative. Rocking: per column, the lintel's contact on its top corner and its foot,
    /// each within its friction cone (which keeps their normal forces non-negative). Seated
    /// (the trilith rigid, its faces in contact): the lintel's friction on both columns
    /// together and its tipping about the outer ends of its supports; how the load of a seated
    /// lintel divides between two faces is not determined, so only the sums are watched, with
    /// the smaller friction of the two joints (the only one that holds whatever the split);
    /// likewise the feet together when their friction differs.
    pub(crate) fn conditions(&self, traj: &Trajectory, inputs: &Inputs) -> Vec<Constraint> {
        let mut base_acc = derivative(&traj.v);
        add_to(&mut base_acc, &inputs.accel, 1.0);
        let glam = scaled(&inputs.lambda, self.g_m_s2);
        // Rocking: conditions 0-7; seated: 8-11, then 14 and 15 (feet of different friction).
        let (margins, index): (Vec<(Coeffs, f64)>, &[usize]) = match traj.mode.pivot() {
            Some(c) => (
                self.rocking_margins(traj, &base_acc, &glam, c.sign()),
                &[0, 1, 2, 3, 4, 5, 6, 7],
            ),
            None => (
                self.seated_margins(traj, &base_acc, &glam),
                &[8, 9, 10, 11, K_SEATED_FEET, K_SEATED_FEET + 1],
            ),
        };
        margins
            .into_iter()
            .zip(index)
            .map(|((series, scale), &k)| Constraint {
                series,
                scale,
                guard: Guard::Held(k),
                strict: false,
            })
            .collect()
    }

    /// Rocking on the corners of sign s: each column's centroid r_G from its foot, the lintel
    /// at 2 r_G; the lintel's vertical loads on the two columns from its balance of moments
    /// (it does not turn), each column's horizontal load from its own balance about its foot,
    /// its foot's forces from its momentum.
    fn rocking_margins(
        &self,
        traj: &Trajectory,
        base_acc: &Coeffs,
        glam: &Coeffs,
        s: f64,
    ) -> Vec<(Coeffs, f64)> {
        let (b, h, m) = (self.b, self.h, self.column_kg);
        let (mut sin, mut cos) = (ZERO, ZERO);
        for k in 0..=ORDER {
            sin_cos_at(&traj.theta, &mut sin, &mut cos, k);
        }
        let alpha = derivative(&traj.omega);
        let w2 = product(&traj.omega, &traj.omega);
        // r_G turned clockwise by theta from (-s b, h), and the centroid's acceleration.
        let rx = add(&scaled(&cos, -s * b), &sin, h);
        let ry = add(&scaled(&sin, s * b), &cos, h);
        let mut ax = add(base_acc, &product(&alpha, &ry), 1.0);
        add_to(&mut ax, &product(&w2, &rx), -1.0);
        let mut ay = scaled(&product(&alpha, &rx), -1.0);
        add_to(&mut ay, &product(&w2, &ry), -1.0);
        let lintel_ax = add(&scaled(&ax, 2.0), base_acc, -1.0);
        let lintel_ay = scaled(&ay, 2.0);
        // V1 + V2 = M (g lambda + a_y), e1 V1 + e2 V2 = e_y M a_x (e: the contacts' offsets from
        // the lintel's centroid, fixed while it translates).
        let mk = self.lintel_kg;
        let w = scaled(&add(glam, &lintel_ay, 1.0), mk);
        let lever = scaled(&lintel_ax, mk * (2.0 * h - self.lintel.1));
        let e = self.feet_x.map(|x| x - s * b - self.lintel.0);
        let span = e[1] - e[0];
        let loads = [
            scaled(&add(&scaled(&w, e[1]), &lever, -1.0), 1.0 / span),
            scaled(&add(&lever, &w, -e[0]), 1.0 / span),
        ];
        // 2 r_Gy H = -I_G theta'' + m (r_Gx a_y - r_Gy a_x) + r_Gx (m g lambda + 2 V).
        let mut common = scaled(&alpha, -self.column_inertia);
        add_to(&mut common, &product(&rx, &ay), m);
        add_to(&mut common, &product(&ry, &ax), -m);
        add_to(&mut common, &product(&rx, glam), m);
        let twice_ry = scaled(&ry, 2.0);
        let mut out = Vec::with_capacity(8);
        for (i, v) in loads.iter().enumerate() {
            let numerator = add(&common, &product(&rx, v), 2.0);
            let mut hz = ZERO;
            for k in 0..=ORDER {
                hz[k] = div_at(&numerator, &twice_ry, &hz, k);
            }
            let foot_t = add(&hz, &ax, m);
            let mut foot_n = add(v, glam, m);
            add_to(&mut foot_n, &ay, m);
            let (mu, mu_top) = (self.ground_friction[i], self.top_friction[i]);
            for (n, t, mu) in [(v, &hz, mu_top), (&foot_n, &foot_t, mu)] {
                out.push((add(&scaled(n, mu), t, -1.0), self.force_scale));
                out.push((add(&scaled(n, mu), t, 1.0), self.force_scale));
            }
        }
        out
    }

    /// Seated: the lintel moves with the trilith, at base_acc.
    fn seated_margins(
        &self,
        traj: &Trajectory,
        base_acc: &Coeffs,
        glam: &Coeffs,
    ) -> Vec<(Coeffs, f64)> {
        let mk = self.lintel_kg;
        let (xl, yl) = self.lintel;
        let hy = yl - 2.0 * self.h;
        let least = |mu: [f64; 2]| mu[0].min(mu[1]);
        let weight = scaled(glam, mk * least(self.top_friction));
        let pull = scaled(base_acc, mk);
        let moment = |end: f64| {
            let mut m = scaled(glam, mk * (xl - end));
            add_to(&mut m, base_acc, -mk * hy);
            m
        };
        let mut out = vec![
            (add(&weight, &pull, -1.0), self.force_scale),
            (add(&weight, &pull, 1.0), self.force_scale),
            (moment(self.ends[0]), self.moment_scale),
            (scaled(&moment(self.ends[1]), -1.0), self.moment_scale),
        ];
        if self.unequal_feet() {
            let cap = scaled(&traj.normal, least(self.ground_friction));
            out.push((add(&cap, &traj.tangential, -1.0), self.force_scale));
            out.push((add(&cap, &traj.tangential, 1.0), self.force_scale));
        }
        out
    }

    /// The first condition a landing breaks, if any: from `before` (rocking) to `after` at
    /// theta = 0. The impulses act at the new contacts only (the feet on the landing side and
    /// the lintel on the columns' other top corners), as in the frame's coefficient of
    /// restitution; each must lie in its friction cone. A landing whose feet slip, and a flat
    /// landing's split of the lintel's impulse between two faces, are treated as above.
    pub(crate) fn landing(&self, before: Velocity, after: Velocity) -> Option<usize> {
        if after.2 != before.2 {
            return Some(K_SLIPPED_LANDING);
        }
        let (b, h, m, mk) = (self.b, self.h, self.column_kg, self.lintel_kg);
        // Velocities at theta = 0 of a column's centroid and of the lintel.
        let speeds = |(pivot, w, v): Velocity| {
            let s = pivot.map_or(0.0, Corner::sign);
            ((v + w * h, w * s * b), (v + 2.0 * w * h, 2.0 * w * s * b))
        };
        let ((g0, l0), (g1, l1)) = (speeds(before), speeds(after));
        let dg = (g1.0 - g0.0, g1.1 - g0.1);
        let dl = (mk * (l1.0 - l0.0), mk * (l1.1 - l0.1));
        let total = 2.0 * m + mk;
        let height = self.moment_scale / self.force_scale;
        let impulse = total * (before.1.abs() + after.1.abs()) * height;
        let tol = TIE * impulse;
        let (xl, yl) = self.lintel;
        let Some(new) = after.0 else {
            let moment = |end: f64| (xl - end) * dl.1 - (yl - 2.0 * h) * dl.0;
            let mu = self.top_friction[0].min(self.top_friction[1]);
            let margins = [
                (mu * dl.1 - dl.0, tol),
                (mu * dl.1 + dl.0, tol),
                (moment(self.ends[0]), tol * height),
                (-moment(self.ends[1]), tol * height),
            ];
            return margins.iter().position(|&(x, t)| x < -t).map(|c| 8 + c);
        };
        let s = new.sign();
        let spin = after.1 - before.1;
        let turn = -self.column_inertia * spin + m * (-s * b * dg.1 - h * dg.0);
        let e = self.feet_x.map(|x| x - s * b - xl);
        let k = (2.0 * h - yl) * dl.0;
        let span = e[1] - e[0];
        let loads = [(e[1] * dl.1 - k) / span, (k - e[0] * dl.1) / span];
        (0..2).find_map(|i| {
            let jy = loads[i];
            let jx = (turn - 2.0 * s * b * jy) / (2.0 * h);
            let (fx, fy) = (m * dg.0 + jx, m * dg.1 + jy);
            let (mu, mu_top) = (self.ground_friction[i], self.top_friction[i]);
            let margins = [
                mu_top * jy - jx,
                mu_top * jy + jx,
                mu * fy - fx,
                mu * fy + fx,
            ];
            margins.iter().position(|&x| x < -tol).map(|c| 4 * i + c)
        })
    }

    /// Where each block is once the frame is turned by `theta_rad` about the feet on that
    /// side: (output place, displacement of its centroid (m, m), counter-clockwise rotation).
    pub(crate) fn released(&self, theta_rad: f64) -> Vec<(usize, f64, f64, f64)> {
        let s = if theta_rad > 0.0 { 1.0 } else { -1.0 };
        let (sin, cos) = theta_rad.sin_cos();
        let (b, h) = (self.b, self.h);
        // The centroid from the foot's corner, (-s b, h), turned clockwise.
        let (gx, gy) = (-s * b * cos + h * sin, s * b * sin + h * cos);
        let column = (s * b + gx, gy - h, -theta_rad);
        let lintel = (2.0 * (s * b + gx), 2.0 * (gy - h), 0.0);
        let mut out: Vec<(usize, f64, f64, f64)> = self
            .columns
            .iter()
            .map(|&k| (k, column.0, column.1, column.2))
            .collect();
        out.push((self.lintel_output, lintel.0, lintel.1, lintel.2));
        out
    }
}

/// What a trilith's rocking depends on: its columns' half width b and half height h, a
/// column's mass m and the lintel's M.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Trilith {
    /// b (m).
    pub half_width_m: f64,
    /// h (m).
    pub half_height_m: f64,
    /// m (kg).
    pub column_kg: f64,
    /// M (kg).
    pub lintel_kg: f64,
}

impl Trilith {
    /// A column's moment of inertia about its centroid, m (b^2 + h^2) / 3 (kg m2).
    fn column_inertia_kg_m2(&self) -> f64 {
        let (b, h) = (self.half_width_m, self.half_height_m);
        self.column_kg * (b * b + h * h) / 3.0
    }

    /// The frame's moment of inertia about its feet, 2 I_O + 4 M R^2 (kg m2).
    fn inertia_kg_m2(&self) -> f64 {
        let (b, h) = (self.half_width_m, self.half_height_m);
        let r2 = b * b + h * h;
        2.0 * (self.column_inertia_kg_m2() + self.column_kg * r2) + 4.0 * self.lintel_kg * r2
    }

    /// Makris and Vassiliou's (2013) coefficient of restitution: the generalised momentum along
    /// the mechanism after the landing is kept, each column bringing (I_O - 2 m b^2) and the
    /// lintel 4 M (h^2 - b^2) per unit of angular velocity; (1 - 1.5 sin^2 alpha + 3 gamma cos
    /// 2 alpha) / (1 + 3 gamma) with gamma = M / 2m.
    pub fn restitution(&self) -> f64 {
        let (b, h, m, mk) = (
            self.half_width_m,
            self.half_height_m,
            self.column_kg,
            self.lintel_kg,
        );
        let io = self.column_inertia_kg_m2() + m * (b * b + h * h);
        (2.0 * io - 4.0 * m * b * b + 4.0 * mk * (h * h - b * b)) / self.inertia_kg_m2()
    }

    /// The rigid body whose motion on one corner is the frame's (module docs): mass 2m + M,
    /// centroid on the column's diagonal at R (2m + 2M) / (2m + M) from the corner, inertia
    /// about it the frame's, and a factor on its Housner coefficient that makes it the frame's
    /// (times `restitution_factor`). `None` when the frame could not rock on after a landing
    /// (a coefficient below zero: columns far squatter than any trilith).
    pub fn body(
        &self,
        name: &str,
        friction: f64,
        g_m_s2: f64,
        restitution_factor: f64,
    ) -> Option<RockingBody> {
        let (m, mk) = (self.column_kg, self.lintel_kg);
        let total = 2.0 * m + mk;
        let k = (2.0 * m + 2.0 * mk) / total;
        let (b, h) = (k * self.half_width_m, k * self.half_height_m);
        let inertia = self.inertia_kg_m2();
        let housner = 1.0 - 2.0 * total * b * b / inertia;
        let r = self.restitution();
        (r >= 0.0 && housner > 0.0).then(|| RockingBody {
            name: name.to_string(),
            mass_kg: total,
            inertia_kg_m2: inertia - total * (b * b + h * h),
            half_base_m: b,
            centroid_height_m: h,
            friction,
            restitution_factor: restitution_factor * r / housner,
            g_m_s2,
        })
    }
}

/// A trilith found in a wall: what the column model needs to run it.
pub(crate) struct Recognised {
    /// Its joints' watch.
    pub frame: Frame,
    /// The rigid body its mechanism moves as.
    pub body: RockingBody,
    /// Each joint: its name, friction, tipping ratios (left, right) and whether the body moves
    /// on it, as `pirqa check` lists them.
    pub limits: Vec<(String, f64, [f64; 2], bool)>,
    /// Its blocks in the wall's order: index in the wall, height of the point each follows
    /// above its base's middle (the lintel: the columns' tops), and whether it turns.
    pub blocks: Vec<(usize, f64, bool)>,
    /// Half the width of a column's foot (m).
    pub half_base_m: f64,
}

/// The trilith a wall is, if it is one: three movable blocks, two standing on the ground and
/// carrying only the third, which rests on them and nothing else, with nothing beside the
/// lintel (the columns face only each other). `None` when the wall has another shape; an
/// error when it is a trilith the exact model cannot take (unequal columns, a lintel that does
/// not cover a column's top).
pub(crate) fn trilith(wall: &Wall, topo: &Topology) -> Result<Option<Recognised>, SimulationError> {
    if wall.blocks.len() != 3 || wall.blocks.iter().any(|b| b.fixed) {
        return Ok(None);
    }
    let Some(l) = (0..3).find(|&b| topo.below[b].len() == 2) else {
        return Ok(None);
    };
    // The columns may face each other across a gap that their equal turns never close.
    if !topo.sides[l].is_empty() {
        return Ok(None);
    }
    let mut cols = Vec::new();
    for j in topo.below[l].iter() {
        let Base::Block(BlockId(c)) = topo.horizontal[j.0].lower else {
            return Ok(None);
        };
        let on_ground =
            matches!(&topo.below[c], [g] if matches!(topo.horizontal[g.0].lower, Base::Ground));
        if !on_ground || topo.above[c].len() != 1 {
            return Ok(None);
        }
        cols.push((c, j.0));
    }
    if !topo.above[l].is_empty() {
        return Ok(None);
    }
    cols.sort_by(|a, b| wall.blocks[a.0].x.cmp(&wall.blocks[b.0].x));
    let [(c1, t1), (c2, t2)] = [cols[0], cols[1]];
    let blk = |i: usize| &wall.blocks[i];
    let name = |i: usize| blk(i).name.clone();
    let not = |why: String| {
        SimulationError::NotApplicable(format!(
            "{}: {why}; the exact model rocks a trilith whose two columns are equal, with the \
             lintel covering both tops. Run it with rotations on time stepping (--model slide-rock --method \
             moreau --dt S) or sliding exactly (--model slide)",
            wall.name
        ))
    };
    let (a, c) = (blk(c1), blk(c2));
    if a.width != c.width || a.height != c.height || wall.mass_kg(c1) != wall.mass_kg(c2) {
        return Err(not(format!(
            "its columns {} ({} x {} m, {} kg) and {} ({} x {} m, {} kg) differ",
            a.name,
            a.width.to_f64(),
            a.height.to_f64(),
            wall.mass_kg(c1).to_f64(),
            c.name,
            c.width.to_f64(),
            c.height.to_f64(),
            wall.mass_kg(c2).to_f64()
        )));
    }
    let lin = blk(l);
    for col in [a, c] {
        if lin.x > col.x || lin.right() < col.right() {
            return Err(not(format!(
                "the lintel {} does not cover the whole top of {}",
                lin.name, col.name
            )));
        }
    }
    let foot = |c: usize| &topo.horizontal[topo.below[c][0].0];
    let (f1, f2) = (foot(c1), foot(c2));
    let (top1, top2) = (&topo.horizontal[t1], &topo.horizontal[t2]);
    let two = Q::int(2);
    let half = |x: &Q| (x / &two).to_f64();
    let (b, h) = (half(&a.width), half(&a.height));
    let (m, mk) = (wall.mass_kg(c1).to_f64(), wall.mass_kg(l).to_f64());
    let g = wall.g_m_s2.to_f64();
    let shape = Trilith {
        half_width_m: b,
        half_height_m: h,
        column_kg: m,
        lintel_kg: mk,
    };
    let mut order = [c1, c2, l];
    order.sort_unstable();
    let Some(body) = shape.body(
        &order.map(name).join("+"),
        // The larger: while it rocks each foot's own friction is watched, and a seated trilith
        // on feet of different friction is watched from the smaller.
        f1.friction.clone().max(f2.friction.clone()).to_f64(),
        g,
        wall.rocking_restitution_factor,
    ) else {
        return Err(not(format!(
            "its columns are so squat (b/h = {:.3}) that a rocking trilith could not land on its \
             other corners and rock on (its coefficient of restitution {:.3})",
            b / h,
            shape.restitution()
        )));
    };
    let names = [name(c1), name(c2), name(l)];
    let place = |i: usize| {
        order
            .iter()
            .position(|&o| o == i)
            .expect("a block of the trilith")
    };
    let lintel_y = ((&lin.y + &lin.top()) / &two).to_f64();
    let lintel_x = ((&lin.x + &lin.right()) / &two).to_f64();
    let ends = [a.x.to_f64(), c.right().to_f64()];
    let lintel_tips = [
        (lintel_x - ends[0]) / (lintel_y - 2.0 * h),
        (ends[1] - lintel_x) / (lintel_y - 2.0 * h),
    ];
    let limit = |joint: String, friction: &Q, tips: [f64; 2], moves: bool| {
        (joint, friction.to_f64(), tips, moves)
    };
    let feet = [
        format!("{}/ground", names[0]),
        format!("{}/ground", names[1]),
    ];
    let tops = [
        format!("{}/{}", names[2], names[0]),
        format!("{}/{}", names[2], names[1]),
    ];
    let limits = vec![
        limit(feet[0].clone(), &f1.friction, [b / h; 2], true),
        limit(feet[1].clone(), &f2.friction, [b / h; 2], true),
        limit(tops[0].clone(), &top1.friction, lintel_tips, false),
        limit(tops[1].clone(), &top2.friction, lintel_tips, false),
    ];
    let blocks = order
        .iter()
        .map(|&i| (i, if i == l { 2.0 * h } else { 0.0 }, i != l))
        .collect();
    let feet_x = [half(&(&a.x + &a.right())), half(&(&c.x + &c.right()))];
    let height = lin.top().to_f64();
    let total = 2.0 * m + mk;
    let frame = Frame {
        column_kg: m,
        column_inertia: shape.column_inertia_kg_m2(),
        b,
        h,
        lintel_kg: mk,
        lintel: (lintel_x, lintel_y),
        feet_x,
        ends,
        ground_friction: [f1.friction.to_f64(), f2.friction.to_f64()],
        top_friction: [top1.friction.to_f64(), top2.friction.to_f64()],
        feet,
        tops,
        columns: [place(c1), place(c2)],
        lintel_output: place(l),
        g_m_s2: g,
        force_scale: total * g,
        moment_scale: total * g * height,
    };
    Ok(Some(Recognised {
        frame,
        body,
        limits,
        blocks,
        half_base_m: b,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::integrate::rocking::modes::{self, Equations, State};
    use crate::integrate::rocking::series::eval;

    /// Columns of 0.5 x 2.5 m, 1.5 m apart, under a lintel of 3.5 x 0.8 m that reaches 0.3 m
    /// past the left column and 0.7 m past the right one: heavier than a column (gamma =
    /// M / 2m = 1.12) and off the columns' middle.
    fn trilith_of(friction: f64) -> Recognised {
        let model = crate::model::Model::from_ron_str(&format!(
            "(version: 1, thickness_m: 0.5, density_kg_m3: 2650, friction: {friction},
              rows: [(height_m: 2.5, x_m: 0.3, blocks: [(width_m: 0.5, name: \"L\"),
                                                       (width_m: 0.5, gap_m: 1.5, name: \"R\")]),
                     (height_m: 0.8, blocks: [(width_m: 3.5, name: \"T\")])])"
        ))
        .unwrap();
        trilith(model.wall(), model.topology()).unwrap().unwrap()
    }

    /// The body of the mechanism has Makris and Vassiliou's (2013) frequency parameter
    /// p^2 (1 + 2 gamma) / (1 + 3 gamma) and coefficient of restitution (1 - 1.5 sin^2 alpha +
    /// 3 gamma cos 2 alpha) / (1 + 3 gamma) (p and alpha of one column), and lifts at a column's
    /// g b / h.
    #[test]
    fn the_frame_has_makris_and_vassilious_numbers() {
        let c = trilith_of(0.7);
        let (m, mk) = (0.5 * 2.5 * 0.5 * 2650.0, 3.5 * 0.8 * 0.5 * 2650.0);
        let gamma = mk / (2.0 * m);
        let (b, h) = (0.25f64, 1.25f64);
        let (r, alpha) = (b.hypot(h), b.atan2(h));
        let p2 = 3.0 * 9.81 / (4.0 * r) * (1.0 + 2.0 * gamma) / (1.0 + 3.0 * gamma);
        let restitution = (1.0 - 1.5 * alpha.sin().powi(2) + 3.0 * gamma * (2.0 * alpha).cos())
            / (1.0 + 3.0 * gamma);
        let body = &c.body;
        assert!((body.frequency_parameter_rad_s().powi(2) / p2 - 1.0).abs() < 1e-14);
        let r_body = body.housner_restitution() * body.restitution_factor;
        assert!(
            (r_body / restitution - 1.0).abs() < 1e-14,
            "{r_body} {restitution}"
        );
        assert!((body.uplift_ratio() / (b / h) - 1.0).abs() < 1e-14);
        assert!((body.slenderness_rad() / alpha - 1.0).abs() < 1e-14);
        assert!((body.mass_kg / (2.0 * m + mk) - 1.0).abs() < 1e-14);
    }

    /// While the trilith rocks, the forces the watch gives each column's foot sum to the
    /// contact forces of the body's own equations of motion (which know nothing of how they
    /// divide), and the lintel's loads on the columns balance its moments about either contact
    /// (from the contacts' places worked out from theta afresh); on both corners, along a
    /// step, to round-off.
    #[test]
    fn the_watch_divides_the_bodys_own_contact_forces() {
        let c = trilith_of(0.7);
        let frame = &c.frame;
        let inputs = modes::test_inputs_at(0.37);
        let weight = c.body.mass_kg * c.body.g_m_s2;
        for (corner, theta) in [(Corner::Right, 0.06), (Corner::Left, -0.06)] {
            let state = State {
                theta,
                omega: -0.4,
                ..State::default()
            };
            let t = modes::trajectory(
                &c.body,
                Equations::Exact,
                Mode::Rock(corner),
                &state,
                &inputs,
            );
            let cond = frame.conditions(&t, &inputs);
            assert_eq!(cond.len(), 8);
            for tau in [0.0, 0.01, 0.03] {
                let at = |k: usize| eval(&cond[k].series, tau);
                // Per column: the lintel's (H, V) and the foot's (F, N), from the margins.
                let forces: Vec<[f64; 4]> = (0..2)
                    .map(|i| {
                        let (mu, mu_top) = (frame.ground_friction[i], frame.top_friction[i]);
                        let (a, b, c, d) = (at(4 * i), at(4 * i + 1), at(4 * i + 2), at(4 * i + 3));
                        [
                            (b - a) / 2.0,
                            (a + b) / (2.0 * mu_top),
                            (d - c) / 2.0,
                            (c + d) / (2.0 * mu),
                        ]
                    })
                    .collect();
                let close = |a: f64, b: f64, what: &str| {
                    assert!(
                        (a - b).abs() <= 1e-12 * weight,
                        "{corner:?} tau {tau}: {what} {a} against {b}"
                    )
                };
                close(
                    forces[0][2] + forces[1][2],
                    eval(&t.tangential, tau),
                    "tangential",
                );
                close(forces[0][3] + forces[1][3], eval(&t.normal, tau), "normal");
                // The lintel's contacts: each column's corner opposite its foot, the foot at
                // the column's side s b from its middle, turned by theta.
                let (th, s) = (eval(&t.theta, tau), corner.sign());
                let (b, h) = (frame.b, frame.h);
                let corner_of = |foot: f64| {
                    let (rx, ry) = (-2.0 * s * b, 2.0 * h);
                    let (sin, cos) = th.sin_cos();
                    (foot + s * b + rx * cos + ry * sin, -rx * sin + ry * cos)
                };
                let p = frame.feet_x.map(corner_of);
                // The lintel's centroid keeps its offset from the left contact.
                let rest = (frame.feet_x[0] - s * b, 2.0 * h);
                let l = (
                    p[0].0 + frame.lintel.0 - rest.0,
                    p[0].1 + frame.lintel.1 - rest.1,
                );
                // Its loads from the columns (H1 + H2, V1 + V2) equal its mass times its
                // acceleration plus its weight; balance of moments about each contact.
                let (hs, vs) = (forces[0][0] + forces[1][0], forces[0][1] + forces[1][1]);
                for (j, other) in [(0, 1), (1, 0)] {
                    let (px, py) = p[j];
                    let arm = |x: f64, y: f64, fx: f64, fy: f64| (x - px) * fy - (y - py) * fx;
                    let from_other =
                        arm(p[other].0, p[other].1, forces[other][0], forces[other][1]);
                    // The resultant of the lintel's loads acts through its centroid.
                    let load = arm(l.0, l.1, hs, vs);
                    close(
                        from_other / 3.0,
                        load / 3.0,
                        "moments of the lintel's loads",
                    );
                }
            }
        }
    }
}
