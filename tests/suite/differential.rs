//! Differential test of the exact integrator (issue 34): random small walls (2-6 blocks in 1-3
//! courses, open and closed vertical joints, e in {0, 0.5, 1}, friction joint by joint) under
//! a sine, against a reference simulator written here from the model's statement alone. The
//! reference shares none of the engine's decision code: at every event it enumerates every mode
//! (each horizontal joint at rest stuck, slipping forward or back; each touching vertical joint
//! pressed or free), keeps the modes whose motion is consistent (slips in the direction of
//! their relative acceleration, free faces not closing, and the stuck joints and pressed faces
//! able to carry the forces the motion needs, checked cut by cut over every subset of each rigid
//! group: Hoffman's condition for a feasible flow), and checks that every consistent mode gives
//! the same accelerations. Between events the motion is in closed form; events are found by
//! sampling every 0.5 ms and bisection. Both must agree on every history row to 1e-9 m.

use crate::engine;
use pirqa::integrate::Settings;
use pirqa::rng::Rng;
use pirqa::{Base, Topology, Wall};

/// Agreement asked of the displacements (m).
const AGREE_M: f64 = 1e-9;
/// Sampling step of the event search (s).
const SCAN_S: f64 = 5e-4;
/// Velocities (m/s) and gaps (m) this small are zero; approaches below the first are touches.
const ZERO_V: f64 = 1e-10;
const ZERO_GAP: f64 = 1e-12;

/// The wall as the reference sees it: masses, horizontal joints (upper, lower or the ground,
/// friction capacity), vertical joints (left, right, gap at rest).
struct Reference {
    mass: Vec<f64>,
    horizontal: Vec<(usize, Option<usize>, f64)>,
    vertical: Vec<(usize, usize, f64)>,
    e: f64,
    /// The sine: amplitude (m/s2), circular frequency (rad/s), phase (rad).
    sine: (f64, f64, f64),
}

/// A decided mode: each block's acceleration alpha + beta a_g, the conditions under which it
/// holds (each p + q a_g >= 0), and the joints slipping between two groups with their
/// direction.
struct Mode {
    alpha: Vec<f64>,
    beta: Vec<f64>,
    conds: Vec<(f64, f64)>,
    slips: Vec<(usize, f64)>,
}

/// One stretch of motion in one mode: each block's u, v at `t0` and its acceleration
/// alpha + beta a_g(t).
#[derive(Clone)]
struct Stretch {
    t0: f64,
    u: Vec<f64>,
    v: Vec<f64>,
    alpha: Vec<f64>,
    beta: Vec<f64>,
}

impl Reference {
    fn ag(&self, t: f64) -> f64 {
        let (a, w, p) = self.sine;
        a * (w * t + p).sin()
    }

    fn ag_rate(&self, t: f64) -> f64 {
        let (a, w, p) = self.sine;
        a * w * (w * t + p).cos()
    }

    /// Velocity and displacement gained from t0 to t0 + tau by a unit coefficient on a_g.
    fn ground_integrals(&self, t0: f64, tau: f64) -> (f64, f64) {
        let (a, w, p) = self.sine;
        let th0 = w * t0 + p;
        let th = th0 + w * tau;
        let vel = a / w * (th0.cos() - th.cos());
        let disp = a / w * th0.cos() * tau - a / (w * w) * (th.sin() - th0.sin());
        (vel, disp)
    }

    fn at(&self, s: &Stretch, t: f64) -> (Vec<f64>, Vec<f64>) {
        let tau = t - s.t0;
        let (gv, gd) = self.ground_integrals(s.t0, tau);
        let n = self.mass.len();
        let u = (0..n)
            .map(|i| s.u[i] + s.v[i] * tau + 0.5 * s.alpha[i] * tau * tau + s.beta[i] * gd)
            .collect();
        let v = (0..n)
            .map(|i| s.v[i] + s.alpha[i] * tau + s.beta[i] * gv)
            .collect();
        (u, v)
    }

    /// The motion from rest over [0, duration]: the stretches, in order.
    fn simulate(&self, duration: f64) -> Vec<Stretch> {
        let n = self.mass.len();
        let (mut t, mut u, mut v) = (0.0, vec![0.0; n], vec![0.0; n]);
        let mut out = Vec::new();
        for _ in 0..100_000 {
            // Any touching faces that approach collide first (not only the face whose gap
            // closed: faces can bounce apart by less than the gap taken as closed).
            self.collide(&u, &mut v);
            let mode = self.decide(t, &u, &mut v);
            let s = Stretch {
                t0: t,
                u: u.clone(),
                v: v.clone(),
                alpha: mode.alpha.clone(),
                beta: mode.beta.clone(),
            };
            let t_next = self.next_event(&s, &mode, duration);
            out.push(s.clone());
            if t_next >= duration {
                return out;
            }
            (u, v) = self.at(&s, t_next);
            t = t_next;
        }
        panic!("the reference met 100,000 events");
    }

    fn touching(&self, j: usize, u: &[f64]) -> bool {
        let (l, r, g0) = self.vertical[j];
        g0 + u[r] - u[l] <= ZERO_GAP
    }

    /// Impacts: pairwise, the fastest approaching touching face first (ties: the first in the
    /// wall's order), Newton's restitution, until none approaches.
    fn collide(&self, u: &[f64], v: &mut [f64]) {
        loop {
            let mut best: Option<(f64, usize)> = None;
            for (j, &(l, r, _)) in self.vertical.iter().enumerate() {
                let approach = v[l] - v[r];
                if self.touching(j, u) && approach > ZERO_V && best.is_none_or(|b| approach > b.0) {
                    best = Some((approach, j));
                }
            }
            let Some((approach, j)) = best else { return };
            let (l, r, _) = self.vertical[j];
            let (ml, mr) = (self.mass[l], self.mass[r]);
            let impulse = (1.0 + self.e) * ml * mr / (ml + mr) * approach;
            v[l] -= impulse / ml;
            v[r] += impulse / mr;
        }
    }

    /// The mode at time t: every candidate enumerated, the consistent ones kept, their
    /// accelerations compared. Equalises the velocities of each rigid group (momentum kept) and
    /// stops the ground's.
    fn decide(&self, t: f64, u: &[f64], v: &mut [f64]) -> Mode {
        let (ag, rate) = (self.ag(t), self.ag_rate(t));
        let rel = |j: usize, v: &[f64]| {
            let (a, b, _) = self.horizontal[j];
            v[a] - b.map_or(0.0, |b| v[b])
        };
        // Joints at rest choose among three states, touching faces with no relative velocity
        // between pressed and free; the others are what their velocities say.
        let free_h: Vec<usize> = (0..self.horizontal.len())
            .filter(|&j| rel(j, v).abs() <= ZERO_V)
            .collect();
        let free_v: Vec<usize> = (0..self.vertical.len())
            .filter(|&j| {
                let (l, r, _) = self.vertical[j];
                self.touching(j, u) && (v[r] - v[l]).abs() <= ZERO_V
            })
            .collect();
        let mut found: Option<(Mode, Vec<i8>, Vec<bool>)> = None;
        let total = 3usize.pow(free_h.len() as u32) << free_v.len();
        for code in 0..total {
            let mut c = code;
            let mut hs: Vec<i8> = (0..self.horizontal.len())
                .map(|j| rel(j, v).signum() as i8)
                .collect();
            for &j in &free_h {
                hs[j] = (c % 3) as i8 - 1;
                c /= 3;
            }
            let mut pressed = vec![false; self.vertical.len()];
            for &j in &free_v {
                pressed[j] = c % 2 == 1;
                c /= 2;
            }
            let Some(mode) = self.mode(&hs, &pressed, &free_h, &free_v, ag, rate) else {
                continue;
            };
            match &found {
                None => found = Some((mode, hs, pressed)),
                Some((first, ..)) => {
                    for i in 0..mode.alpha.len() {
                        let x = mode.alpha[i] + mode.beta[i] * ag;
                        let y = first.alpha[i] + first.beta[i] * ag;
                        assert!(
                            (x - y).abs() <= 1e-8 * (1.0 + x.abs()),
                            "two consistent modes at t = {t} give block {i} accelerations {x} and {y}"
                        );
                    }
                }
            }
        }
        let (mut mode, hs, pressed) =
            found.unwrap_or_else(|| panic!("no consistent mode at t = {t}"));
        // Rigid groups move with one velocity: the momentum-weighted mean, zero with the ground.
        let groups = self.groups(&hs, &pressed);
        let n = self.mass.len();
        for g in 0..=n {
            let members: Vec<usize> = (0..n).filter(|&i| groups[i] == g).collect();
            if members.is_empty() {
                continue;
            }
            let common = if g == n {
                0.0
            } else {
                let m: f64 = members.iter().map(|&i| self.mass[i]).sum();
                members.iter().map(|&i| self.mass[i] * v[i]).sum::<f64>() / m
            };
            for &i in &members {
                v[i] = common;
            }
        }
        // The joints that slip between two groups, with their direction: the mode's, not the
        // sign of a relative velocity that may be round-off.
        let group_of = |b: Option<usize>| b.map_or(n, |b| groups[b]);
        mode.slips = self
            .horizontal
            .iter()
            .enumerate()
            .filter(|&(j, &(a, b, _))| hs[j] != 0 && groups[a] != group_of(b))
            .map(|(j, _)| (j, f64::from(hs[j])))
            .collect();
        mode
    }

    /// Each block's group: blocks joined by stuck joints and pressed faces, `n` for the
    /// ground's.
    fn groups(&self, hs: &[i8], pressed: &[bool]) -> Vec<usize> {
        let n = self.mass.len();
        let mut parent: Vec<usize> = (0..=n).collect();
        fn root(p: &mut [usize], mut i: usize) -> usize {
            while p[i] != i {
                i = p[i];
            }
            i
        }
        let mut join = |a: usize, b: usize| {
            let (ra, rb) = (root(&mut parent, a), root(&mut parent, b));
            // The ground stays its group's root.
            let (lo, hi) = if ra == n { (rb, ra) } else { (ra, rb) };
            parent[lo] = hi;
        };
        for (j, &(a, b, _)) in self.horizontal.iter().enumerate() {
            if hs[j] == 0 {
                join(a, b.unwrap_or(n));
            }
        }
        for (j, &(l, r, _)) in self.vertical.iter().enumerate() {
            if pressed[j] {
                join(l, r);
            }
        }
        (0..n)
            .map(|i| root(&mut parent, i))
            .map(|r| if r == n { n } else { r })
            .collect()
    }

    /// A candidate mode's accelerations (alpha + beta a_g per block) and the conditions for it
    /// to hold, each p + q a_g >= 0 (its slips left for the caller); `None` if one fails at a_g
    /// (changing at `rate`), where a condition met with equality must not be about to fail.
    fn mode(
        &self,
        hs: &[i8],
        pressed: &[bool],
        free_h: &[usize],
        free_v: &[usize],
        ag: f64,
        rate: f64,
    ) -> Option<Mode> {
        let holds = |conds: &[(f64, f64)]| {
            conds.iter().all(|&(p, q)| {
                let value = p + q * ag;
                let scale = 1e-9 * (p.abs() + (q * ag).abs() + 1.0);
                value > scale || (value >= -scale && q * rate >= -scale)
            })
        };
        let n = self.mass.len();
        let groups = self.groups(hs, pressed);
        // Friction of slipping joints on each block (N): against the upper block's slip.
        let mut slip_force = vec![0.0; n];
        for (j, &(a, b, cap)) in self.horizontal.iter().enumerate() {
            let s = f64::from(hs[j]);
            slip_force[a] -= s * cap;
            if let Some(b) = b {
                slip_force[b] += s * cap;
            }
        }
        let (mut alpha, mut beta) = (vec![0.0; n], vec![0.0; n]);
        for g in 0..n {
            let members: Vec<usize> = (0..n).filter(|&i| groups[i] == g).collect();
            if members.is_empty() {
                continue;
            }
            let m: f64 = members.iter().map(|&i| self.mass[i]).sum();
            let f: f64 = members.iter().map(|&i| slip_force[i]).sum();
            for &i in &members {
                alpha[i] = f / m;
                beta[i] = -1.0;
            }
        }
        let mut conds = Vec::new();
        // Slips at rest go the way their relative acceleration does; free faces do not close.
        let accel = |i: Option<usize>| i.map_or((0.0, 0.0), |i| (alpha[i], beta[i]));
        for &j in free_h {
            let (a, b, _) = self.horizontal[j];
            if hs[j] != 0 {
                let (pa, qa) = accel(Some(a));
                let (pb, qb) = accel(b);
                let s = f64::from(hs[j]);
                conds.push((s * (pa - pb), s * (qa - qb)));
            }
        }
        for &j in free_v {
            let (l, r, _) = self.vertical[j];
            if !pressed[j] {
                conds.push((alpha[r] - alpha[l], beta[r] - beta[l]));
            }
        }
        // The slips and free faces first: most candidates fail there, before the cuts.
        if !holds(&conds) {
            return None;
        }
        // The forces each block needs from its group's links, r_i = m_i (a_i + a_g) - slip_i,
        // affine in a_g; every subset of a group must get its sum across the links that leave
        // it (Hoffman). The ground's group supplies whatever its blocks need.
        for g in 0..=n {
            let members: Vec<usize> = (0..n).filter(|&i| groups[i] == g).collect();
            if members.is_empty() {
                continue;
            }
            let need: Vec<(f64, f64)> = members
                .iter()
                .map(|&i| {
                    (
                        self.mass[i] * alpha[i] - slip_force[i],
                        self.mass[i] * (beta[i] + 1.0),
                    )
                })
                .collect();
            let whole = (1usize << members.len()) - 1;
            for subset in 1..=whole {
                if subset == whole && g != n {
                    continue;
                }
                let inside = |i: usize| {
                    members
                        .iter()
                        .position(|&x| x == i)
                        .is_some_and(|k| subset >> k & 1 == 1)
                };
                let (mut p, mut q) = (0.0, 0.0);
                for (k, &(pk, qk)) in need.iter().enumerate() {
                    if subset >> k & 1 == 1 {
                        p += pk;
                        q += qk;
                    }
                }
                // What the links crossing the subset's boundary can bring into it.
                let (mut lo, mut hi) = (0.0, 0.0);
                for (j, &(a, b, cap)) in self.horizontal.iter().enumerate() {
                    let b_in = b.is_some_and(inside);
                    if hs[j] == 0 && inside(a) != b_in {
                        lo -= cap;
                        hi += cap;
                    }
                }
                for (j, &(l, r, _)) in self.vertical.iter().enumerate() {
                    if pressed[j] && inside(l) != inside(r) {
                        if inside(r) {
                            hi = f64::INFINITY;
                        } else {
                            lo = f64::NEG_INFINITY;
                        }
                    }
                }
                if hi.is_finite() {
                    conds.push((hi - p, -q));
                }
                if lo.is_finite() {
                    conds.push((p - lo, q));
                }
            }
        }
        holds(&conds).then_some(Mode {
            alpha,
            beta,
            conds,
            slips: Vec::new(),
        })
    }

    /// The first event after the stretch starts: a slipping joint stopping, a gap closing, or
    /// a condition of the mode failing; `duration` if none.
    fn next_event(&self, s: &Stretch, mode: &Mode, duration: f64) -> f64 {
        let rel_v = |j: usize, v: &[f64]| {
            let (a, b, _) = self.horizontal[j];
            v[a] - b.map_or(0.0, |b| v[b])
        };
        let slipping = &mode.slips;
        // Conditions that do not depend on a_g hold for the whole stretch.
        let conds: Vec<(f64, f64)> = mode.conds.iter().copied().filter(|c| c.1 != 0.0).collect();
        let open: Vec<usize> = (0..self.vertical.len())
            .filter(|&j| {
                let (l, r, _) = self.vertical[j];
                !self.touching(j, &s.u) || s.v[r] - s.v[l] > ZERO_V
            })
            .collect();
        // Each watched quantity, > 0 while nothing happens.
        let watch = |t: f64| -> Vec<f64> {
            let (u, v) = self.at(s, t);
            // A slip stops when its velocity has turned by half of what counts as zero (a slip
            // decided at rest may start a few 1e-12 m/s the wrong way; the decision at the stop
            // then sees a velocity that is zero).
            let mut w: Vec<f64> = slipping
                .iter()
                .map(|&(j, d)| d * rel_v(j, &v) + 0.5 * ZERO_V)
                .collect();
            w.extend(open.iter().map(|&j| {
                let (l, r, g0) = self.vertical[j];
                g0 + u[r] - u[l]
            }));
            let ag = self.ag(t);
            w.extend(conds.iter().map(|&(p, q)| {
                let value = p + q * ag;
                value + 1e-9 * (p.abs() + (q * ag).abs() + 1.0)
            }));
            w
        };
        let mut t_prev = s.t0;
        let mut prev = watch(s.t0 + 1e-12);
        loop {
            let t = (t_prev + SCAN_S).min(duration);
            let now = watch(t);
            // Every quantity that crossed in this step, each bisected to the float between two
            // neighbours; the earliest is the event.
            let crossed = (0..now.len()).filter(|&k| now[k] <= 0.0 && prev[k] > 0.0);
            let first = crossed
                .map(|k| {
                    let (mut lo, mut hi) = (t_prev, t);
                    loop {
                        let mid = 0.5 * (lo + hi);
                        if mid <= lo || mid >= hi {
                            return hi;
                        }
                        if watch(mid)[k] > 0.0 {
                            lo = mid;
                        } else {
                            hi = mid;
                        }
                    }
                })
                .fold(f64::INFINITY, f64::min);
            if first.is_finite() {
                return first;
            }
            if t >= duration {
                return duration;
            }
            (t_prev, prev) = (t, now);
        }
    }
}

/// A random whole number in 0..k.
fn below(rng: &mut Rng, k: usize) -> usize {
    ((rng.uniform() * k as f64) as usize).min(k - 1)
}

/// A random wall of 2-6 blocks in 1-3 courses as RON, with friction joint by joint and gaps in
/// some vertical joints.
fn random_wall(rng: &mut Rng) -> String {
    let courses = 1 + below(rng, 3);
    let mut rects = Vec::new();
    let (mut x0, mut x1, mut y) = (0.0f64, 3.0f64, 0.0f64);
    let mut left = 6;
    for c in 0..courses {
        let most = (left - (courses - c - 1)).min(3);
        let k = if c == 0 {
            2.max(1 + below(rng, most))
        } else {
            1 + below(rng, most)
        };
        let k = k.min(left);
        left -= k;
        let h = 0.3 + 0.4 * rng.uniform();
        let span = x1 - x0;
        let mut x = x0
            + if c == 0 {
                0.0
            } else {
                0.1 * span * rng.uniform()
            };
        let mut row = Vec::new();
        for _ in 0..k {
            let w = (0.7 + 0.6 * rng.uniform()) * span / (k as f64 + 0.5);
            row.push((x, w));
            x += w;
            if rng.uniform() < 0.5 {
                x += 0.002 + 0.02 * rng.uniform();
            }
        }
        // Upper courses stay inside the one below, so every block rests.
        let end = row.last().map(|&(x, w)| x + w).unwrap();
        if c > 0 && end > x1 - 0.05 {
            let shrink = (x1 - 0.05 - row[0].0) / (end - row[0].0);
            row = row
                .iter()
                .map(|&(x, w)| (row[0].0 + (x - row[0].0) * shrink, w * shrink))
                .collect();
        }
        x0 = row[0].0;
        x1 = row.last().map(|&(x, w)| x + w).unwrap();
        // Edges on whole millimetres, so touching faces touch exactly.
        let mm = |x: f64| (x * 1000.0).round() as i64;
        for &(x, w) in &row {
            let (a, b, y0, y1) = (mm(x), mm(x + w), mm(y), mm(y + h));
            rects.push(format!(
                "(x_m: {}, y_m: {}, width_m: {}, height_m: {})",
                a as f64 / 1000.0,
                y0 as f64 / 1000.0,
                (b - a) as f64 / 1000.0,
                (y1 - y0) as f64 / 1000.0
            ));
        }
        y += h;
        if left == 0 {
            break;
        }
    }
    let e = [0.0, 0.5, 1.0][below(rng, 3)];
    format!(
        "(version: 1, thickness_m: 0.8, density_kg_m3: 2650, friction: {}, restitution: {e}, \
         rectangles: [{}])",
        0.2 + 0.3 * rng.uniform(),
        rects.join(", ")
    )
}

/// Random friction joint by joint, as a new graph.
fn with_random_friction(topo: &Topology, rng: &mut Rng) -> Topology {
    let mus = topo
        .horizontal
        .iter()
        .map(|_| pirqa::Q::from_f64_exact(0.15 + 0.35 * rng.uniform()).unwrap())
        .collect();
    topo.with_frictions(mus)
}

#[test]
fn random_small_walls_agree_with_a_brute_force_enumeration_of_modes() {
    let mut rng = Rng::new(20261126);
    let mut compared = 0;
    let mut kinds = [0usize; 3];
    let (mut slid, mut struck) = (0, 0);
    let mut skipped = [0usize; 3];
    for case in 0..40 {
        let text = random_wall(&mut rng);
        let Ok(wall) = Wall::from_ron_str(&text) else {
            skipped[0] += 1;
            continue;
        };
        let Ok(topo) = Topology::new(&wall) else {
            skipped[1] += 1;
            continue;
        };
        let topo = with_random_friction(&topo, &mut rng);
        let (amp, freq, phase) = (
            2.0 + 3.0 * rng.uniform(),
            1.0 + 2.0 * rng.uniform(),
            360.0 * rng.uniform(),
        );
        let duration = 2.0;
        let motion = engine::sine(amp, freq, phase, duration);
        let settings = Settings {
            output_dt_s: Some(0.01),
            log_events: true,
            ..Settings::summary_only(duration)
        };
        let r = engine::exact_on(&wall, &topo, &motion, &settings);
        if r.summary.collapse.is_some() {
            skipped[2] += 1;
            continue;
        }
        let reference = Reference {
            mass: topo.blocks.iter().map(|b| b.mass_kg.to_f64()).collect(),
            horizontal: topo
                .horizontal
                .iter()
                .map(|h| {
                    let lower = match h.lower {
                        Base::Ground => None,
                        Base::Block(b) => Some(b.0),
                    };
                    (h.upper.0, lower, h.capacity_n.to_f64())
                })
                .collect(),
            vertical: topo
                .vertical
                .iter()
                .map(|j| (j.left.0, j.right.0, j.gap_m.to_f64()))
                .collect(),
            e: wall.restitution.to_f64(),
            sine: (amp, 2.0 * std::f64::consts::PI * freq, phase.to_radians()),
        };
        for t in [0.1, 0.77, 1.5] {
            assert!((reference.ag(t) - motion.accel(t)).abs() <= 1e-12 * amp);
        }
        let stretches = reference.simulate(duration);
        let h = r.history.as_ref().unwrap();
        for (k, &t) in h.time_s.iter().enumerate() {
            let s = stretches.iter().rev().find(|s| s.t0 <= t).unwrap();
            let (u, _) = reference.at(s, t);
            for (i, (&ui, &ei)) in u.iter().zip(&h.displacement_m[k]).enumerate() {
                assert!(
                    (ui - ei).abs() <= AGREE_M,
                    "case {case}, block {i}, t = {t}: reference {ui} m, engine {ei} m\n{text}\n\
                     sine {amp} m/s2, {freq} Hz, {phase} deg; friction {:?}",
                    topo.horizontal
                        .iter()
                        .map(|h| (h.upper.0, h.lower, h.friction.to_f64()))
                        .collect::<Vec<_>>()
                );
            }
        }
        compared += 1;
        kinds[(wall.restitution.to_f64() * 2.0) as usize] += 1;
        slid += usize::from(r.summary.stick_slip_transitions > 0);
        struck += usize::from(r.summary.impacts > 0);
    }
    assert!(
        compared >= 30,
        "{compared} walls compared, skipped {skipped:?}"
    );
    assert!(
        slid >= 20 && struck >= 5,
        "{slid} walls slid, {struck} met impacts"
    );
    assert!(kinds.iter().all(|&k| k > 0), "every e met: {kinds:?}");
}
