//! Event functions of the current mode and their next roots.
//!
//! - A stuck cluster: a_g leaving its stick interval [lo, hi] (per segment: a_g is monotone on
//!   one, so one comparison per bound and segment is all a stuck wall costs).
//! - A sliding cluster against the ground side (ground, abutments, stuck blocks): its velocity
//!   reaching zero where it slides on them, its displacement reaching a gap or a collapse
//!   threshold (per segment: these involve a_g).
//! - Two sliding clusters: their relative velocity reaching zero where one slides on the other,
//!   their relative displacement reaching a gap or collapse threshold. a_g cancels: these are
//!   polynomials, found once per mode, whatever the segments.

use super::cluster::ClusterId;
use super::cluster::{GroundHits, Mode, Slide};
use super::queue::{Constraint, Ev};
use super::roots::{first_violation, polish, sign_changes, valid_after, Counter, Fun};
use super::Engine;
use crate::motion::Segment;

/// The first instant of [t0, t1], within the segment `seg` and from the current time t0, at
/// which a_g / lambda passes `limit` on the side of `s` (+1: above it): a_g - limit lambda changes
/// sign (linear with a vertical component, a_g alone otherwise, monotone on a segment either
/// way). At t0 itself only where it is leaving, not where it touches and turns back.
pub(super) fn limit_passed(
    seg: &Segment,
    limit: f64,
    s: f64,
    (t0, t1): (f64, f64),
    count: &mut Counter,
) -> Option<f64> {
    let (r1, r2) = seg.accel_rates(t0 - seg.t0);
    let f = |x: f64| s * (limit * seg.lambda_at(x - seg.t0) - seg.accel(x - seg.t0));
    if !valid_after(f(t0), 0.0, &[s * (limit * seg.lambda.1 - r1), -s * r2]) {
        Some(t0)
    } else if f(t1) <= 0.0 {
        let guess = seg
            .time_of_ratio(limit, t0 - seg.t0, t1 - seg.t0)
            .map_or(t1, |x| seg.t0 + x);
        Some(polish(&f, guess, t0, t1, count))
    } else {
        None
    }
}

fn constraint_bits(c: Constraint) -> u64 {
    match c {
        Constraint::Gap(j) => 2 * j as u64,
        Constraint::Collapse(s) => 2 * s as u64 + 1,
    }
}

/// Bounds on a relative displacement, each with what it stands for.
#[derive(Default)]
struct Bounds {
    lo: Option<(f64, Constraint)>,
    hi: Option<(f64, Constraint)>,
}

impl Bounds {
    // Of bounds at the same value, the one with the smaller key stands, whatever the order
    // they come in.
    fn lower(&mut self, value: f64, c: Constraint) {
        let key = constraint_bits(c);
        if self
            .lo
            .is_none_or(|(v, o)| value > v || (value == v && key < constraint_bits(o)))
        {
            self.lo = Some((value, c));
        }
    }
    fn upper(&mut self, value: f64, c: Constraint) {
        let key = constraint_bits(c);
        if self
            .hi
            .is_none_or(|(v, o)| value < v || (value == v && key < constraint_bits(o)))
        {
            self.hi = Some((value, c));
        }
    }
    /// A collapse threshold on the relative displacement r (now `r_now`): whichever side of
    /// `r_now` it lies on bounds r there. Thresholds at the current value were just checked.
    fn threshold(&mut self, value: f64, r_now: f64, tol: f64, s: usize) {
        if value > r_now + tol {
            self.upper(value, Constraint::Collapse(s));
        } else if value < r_now - tol {
            self.lower(value, Constraint::Collapse(s));
        }
    }
}

impl Engine<'_> {
    /// Schedules the next events of the given clusters and of every pair of sliding clusters
    /// among them and their neighbours.
    pub(super) fn schedule(&mut self, ks: impl IntoIterator<Item = ClusterId>) {
        let mut pairs = std::mem::take(&mut self.scratch.pairs);
        for k in ks {
            if self.clusters[k].blocks.is_empty() {
                continue;
            }
            self.schedule_segment(k);
            if self.clusters[k].slide().is_some() {
                self.sliding_neighbours(k, |m| pairs.push((k.min(m), k.max(m))));
            }
        }
        // Each pair once, in order.
        pairs.sort_unstable();
        pairs.dedup();
        for &(a, b) in &pairs {
            self.schedule_pair(a, b);
        }
        pairs.clear();
        self.scratch.pairs = pairs;
    }

    /// Events of cluster k that involve a_g, up to the end of the current segment.
    pub(super) fn schedule_segment(&mut self, k: ClusterId) {
        let seg = self.seg;
        let (t0, t1) = (self.t, seg.t1.min(self.given.t_end));
        let ver = self.clusters[k].version;
        let (r1, r2) = seg.accel_rates(self.s());
        match &self.clusters[k].mode {
            Mode::Stuck { lo, hi, .. } => {
                let (lo, hi) = (*lo, *hi);
                for (limit, upper) in [(hi, true), (lo, false)] {
                    if !limit.is_finite() {
                        continue;
                    }
                    let s = if upper { 1.0 } else { -1.0 };
                    if let Some(t) = limit_passed(&seg, limit, s, (t0, t1), &mut self.count) {
                        self.queue
                            .push(t, Ev::Threshold { k, ver, upper }, &self.clusters);
                    }
                }
            }
            Mode::Sliding(sl) => {
                let sl = sl.clone();
                let (sigma, bounds) = self.ground_constraints(k);
                let key = (
                    sigma,
                    bounds.lo.map(|(v, c)| (v.to_bits(), constraint_bits(c))),
                    bounds.hi.map(|(v, c)| (v.to_bits(), constraint_bits(c))),
                );
                let hits = match &self.clusters[k].ground_hits {
                    Some(g)
                        if g.key == key
                            && g.from <= t0
                            && g.hits.iter().flatten().all(|&h| h >= t0) =>
                    {
                        g.hits
                    }
                    _ => {
                        let hits = self.ground_hits(k, &sl, sigma, &bounds, t0, t1, (r1, r2));
                        self.clusters[k].ground_hits = Some(GroundHits {
                            key,
                            from: t0,
                            hits,
                        });
                        hits
                    }
                };
                let ground = self.clusters[k].ground_version;
                if let Some(t) = hits[0] {
                    self.queue
                        .push(t, Ev::Stop { k, ver, ground }, &self.clusters);
                }
                for (hit, bound) in [(hits[1], bounds.lo), (hits[2], bounds.hi)] {
                    if let (Some(t), Some((_, c))) = (hit, bound) {
                        self.queue
                            .push(t, Ev::GroundBound { k, ver, ground, c }, &self.clusters);
                    }
                }
            }
        }
    }

    /// Roots of sliding cluster k's functions against the ground side in [t0, t1]: its stop,
    /// and its displacement reaching the lower and upper bounds.
    #[allow(clippy::too_many_arguments)]
    fn ground_hits(
        &mut self,
        k: ClusterId,
        sl: &Slide,
        sigma: i8,
        bounds: &Bounds,
        t0: f64,
        t1: f64,
        (r1, r2): (f64, f64),
    ) -> [Option<f64>; 3] {
        let acc = |x: f64| sl.acc(x);
        let vel = |x: f64| sl.vel(x);
        let disp = |x: f64| sl.disp(x);
        let zeros = match self.clusters[k].roots.take() {
            Some(r) if r.from <= t0 && t1 <= r.to => r,
            _ => self.zeros(sl, t0, t1),
        };
        let v_roots = &zeros.v_zero;
        let mut hits = [None; 3];
        if sigma != 0 {
            // The stop is the first zero of the velocity: the same function, found on the same
            // pieces, so a touch at the velocity's zero and the stop agree to the bit.
            let s = f64::from(sigma);
            let start = valid_after(
                s * vel(t0),
                0.0,
                &[s * acc(t0), s * sl.acc_rate(r1), -s * r2],
            );
            hits[0] = if start {
                v_roots.iter().copied().find(|&t| t > t0)
            } else {
                Some(t0)
            };
        }
        let tol = self.len_tol(disp(t0), 0.0);
        if let Some((lo, _)) = bounds.lo {
            let f = |x: f64| disp(x) - lo;
            let df = |x: f64| {
                let (u, v, _) = sl.state(x);
                (u - lo, v)
            };
            let start = valid_after(f(t0), tol, &[vel(t0), acc(t0), sl.acc_rate(r1)]);
            hits[1] = first_violation(
                Fun::with(&f, &df),
                t0,
                t1,
                v_roots,
                start,
                tol,
                &mut self.count,
            )
            .map(|h| h.t);
        }
        if let Some((hi, _)) = bounds.hi {
            let f = |x: f64| hi - disp(x);
            let df = |x: f64| {
                let (u, v, _) = sl.state(x);
                (hi - u, -v)
            };
            let start = valid_after(f(t0), tol, &[-vel(t0), -acc(t0), -sl.acc_rate(r1)]);
            hits[2] = first_violation(
                Fun::with(&f, &df),
                t0,
                t1,
                v_roots,
                start,
                tol,
                &mut self.count,
            )
            .map(|h| h.t);
        }
        self.clusters[k].roots = Some(zeros);
        hits
    }

    /// Calls `f` with each sliding cluster sharing a joint with cluster k (once per joint).
    fn sliding_neighbours(&self, k: ClusterId, mut f: impl FnMut(ClusterId)) {
        for &i in self.boundary(k) {
            let others = self.live_neighbours(i).flatten();
            let sides = self.given.topo.sides[i]
                .iter()
                .filter(|j| self.live_vertical(j.0))
                .map(|j| self.across_vertical(j.0, i));
            for o in others.chain(sides) {
                let m = self.of[o];
                if m != ClusterId::NONE && m != k && self.clusters[m].slide().is_some() {
                    f(m);
                }
            }
        }
    }

    /// The four relative displacements d = u_upper - u_lower at which the standing of `upper`
    /// on `lower` can change: its centroid passing either end of the lower block, or the contact
    /// ending on either side.
    fn collapse_thresholds(&self, upper: usize, lower: usize) -> [f64; 4] {
        [
            self.given.xl[lower] - self.given.xc[upper],
            self.given.xr[lower] - self.given.xc[upper],
            self.given.xr[lower] - self.given.xl[upper],
            self.given.xl[lower] - self.given.xr[upper],
        ]
    }

    /// For sliding cluster k against the ground side: the direction it slides on it (0 if it
    /// slides on nothing grounded) and the bounds on its displacement since formation.
    fn ground_constraints(&self, k: ClusterId) -> (i8, Bounds) {
        let du = self.cluster_disp(k);
        let tol = self.len_tol(du, 0.0);
        let mut sigma = 0i8;
        let mut b = Bounds::default();
        for &i in self.boundary(k) {
            for &s in &self.given.topo.below[i] {
                if !self.live_horizontal(s.0) {
                    continue;
                }
                match self.lower_block(s.0) {
                    None => {
                        if !self.slip[s.0].is_stuck() {
                            sigma = self.slip[s.0].sign();
                        }
                    }
                    Some(j) if self.grounded(j) => {
                        if !self.slip[s.0].is_stuck() {
                            sigma = self.slip[s.0].sign();
                        }
                        for th in self.collapse_thresholds(i, j) {
                            b.threshold(th - self.u_ref[i] + self.u_ref[j], du, tol, s.0);
                        }
                    }
                    Some(_) => {}
                }
            }
            for &s in &self.given.topo.above[i] {
                let up = self.given.topo.horizontal[s.0].upper.0;
                if !self.live_horizontal(s.0) || !self.grounded(up) {
                    continue;
                }
                if !self.slip[s.0].is_stuck() {
                    sigma = -self.slip[s.0].sign();
                }
                for th in self.collapse_thresholds(up, i) {
                    b.threshold(self.u_ref[up] - self.u_ref[i] - th, du, tol, s.0);
                }
            }
            for &j in &self.given.topo.sides[i] {
                let jt = &self.given.topo.vertical[j.0];
                if !self.live_vertical(j.0) {
                    continue;
                }
                let (o, left) = if jt.left.0 == i {
                    (jt.right.0, true)
                } else {
                    (jt.left.0, false)
                };
                if !self.grounded(o) {
                    continue;
                }
                if left {
                    b.upper(
                        self.given.gap0[j.0] + self.u_ref[o] - self.u_ref[i],
                        Constraint::Gap(j.0),
                    );
                } else {
                    b.lower(
                        -(self.given.gap0[j.0] + self.u_ref[i] - self.u_ref[o]),
                        Constraint::Gap(j.0),
                    );
                }
            }
        }
        (sigma, b)
    }

    /// Events between sliding clusters a and b: polynomials in time, found once for the mode.
    fn schedule_pair(&mut self, a: ClusterId, b: ClusterId) {
        let (ca, cb) = (&self.clusters[a], &self.clusters[b]);
        let (Some(sa), Some(sb)) = (ca.slide(), cb.slide()) else {
            return;
        };
        let (va, vb) = (ca.version, cb.version);
        self.rec.stats.pair_schedules += 1;
        let r0 = self.cluster_disp(b) - self.cluster_disp(a);
        let r1 = self.cluster_vel(b) - self.cluster_vel(a);
        let r2 = sb.c - sa.c;
        let tol = self.len_tol(r0, self.cluster_disp(a));
        let mut bounds = Bounds::default();
        let mut slides_on = false;
        // The sign of r1 = v_b - v_a that the friction forces assume (from the joints' recorded
        // directions): the pair meets when r1 leaves it, even if rounding put r1 a hair past 0.
        let mut assumed = 0.0;
        let (in_a, in_b) = (|x: usize| self.of[x] == a, |x: usize| self.of[x] == b);
        // The joints between the two, found from the smaller: a block sliding against a large
        // body costs a pass over its own blocks, not over the body's.
        let smaller = if self.clusters[a].blocks.len() <= self.clusters[b].blocks.len() {
            a
        } else {
            b
        };
        for &i in self.boundary(smaller) {
            for &s in self.given.topo.below[i]
                .iter()
                .chain(&self.given.topo.above[i])
            {
                if !self.live_horizontal(s.0) {
                    continue;
                }
                let sup = &self.given.topo.horizontal[s.0];
                let (up, low) = (sup.upper.0, self.lower_block(s.0));
                let Some(low) = low else { continue };
                if in_a(up) && in_b(low) {
                    slides_on = true;
                    // w = v_up - v_low = -r1.
                    assumed = -f64::from(self.slip[s.0].sign());
                    // d = u_up - u_low = (u_ref[up] - u_ref[low]) - r.
                    for th in self.collapse_thresholds(up, low) {
                        bounds.threshold(self.u_ref[up] - self.u_ref[low] - th, r0, tol, s.0);
                    }
                } else if in_a(low) && in_b(up) {
                    slides_on = true;
                    assumed = f64::from(self.slip[s.0].sign());
                    for th in self.collapse_thresholds(up, low) {
                        bounds.threshold(th - (self.u_ref[up] - self.u_ref[low]), r0, tol, s.0);
                    }
                }
            }
            for &j in &self.given.topo.sides[i] {
                let jt = &self.given.topo.vertical[j.0];
                if !self.live_vertical(j.0) {
                    continue;
                }
                let (l, r) = (jt.left.0, jt.right.0);
                if in_a(l) && in_b(r) {
                    bounds.lower(
                        -(self.given.gap0[j.0] + self.u_ref[r] - self.u_ref[l]),
                        Constraint::Gap(j.0),
                    );
                } else if in_a(r) && in_b(l) {
                    bounds.upper(
                        self.given.gap0[j.0] + self.u_ref[r] - self.u_ref[l],
                        Constraint::Gap(j.0),
                    );
                }
            }
        }
        // Relative acceleration (c_b - c_a) lambda(t): constant without vertical shaking (the
        // events hold for the whole mode), linear in time on a segment with it (found again on
        // each segment).
        let vertical = self.given.motion.has_vertical();
        let (t0, t1) = (
            self.t,
            if vertical {
                self.seg.t1.min(self.given.t_end)
            } else {
                self.given.t_end
            },
        );
        let (lt, dl) = (self.seg.lambda_at(self.s()), self.seg.lambda.1);
        let rel = |x: f64| {
            let tau = x - t0;
            r0 + tau * (r1 + r2 * tau * (0.5 * lt + dl * tau / 6.0))
        };
        let w = |x: f64| {
            let tau = x - t0;
            r1 + r2 * tau * (lt + 0.5 * dl * tau)
        };
        let (changes, single);
        let vertex: &[f64] = if vertical {
            let wfd = |x: f64| (w(x), r2 * (lt + dl * (x - t0)));
            changes = sign_changes(Fun::with(&w, &wfd), t0, t1, &[], 0.0, &mut self.count);
            &changes
        } else if r2 != 0.0 {
            single = [t0 - r1 / r2];
            &single
        } else {
            &[]
        };
        if slides_on {
            let sigma = if assumed != 0.0 {
                assumed
            } else if r1 != 0.0 {
                r1.signum()
            } else {
                r2.signum()
            };
            if sigma != 0.0 {
                let f = |x: f64| sigma * w(x);
                let df = |x: f64| (sigma * w(x), sigma * r2 * (lt + dl * (x - t0)));
                let start = valid_after(sigma * r1, 0.0, &[sigma * r2]);
                if let Some(h) =
                    first_violation(Fun::with(&f, &df), t0, t1, &[], start, 0.0, &mut self.count)
                {
                    self.queue
                        .push(h.t, Ev::Meet { a, va, b, vb }, &self.clusters);
                }
            }
        }
        if let Some((lo, c)) = bounds.lo {
            let f = |x: f64| rel(x) - lo;
            let df = |x: f64| (rel(x) - lo, w(x));
            let start = valid_after(r0 - lo, tol, &[r1, r2]);
            if let Some(h) = first_violation(
                Fun::with(&f, &df),
                t0,
                t1,
                vertex,
                start,
                tol,
                &mut self.count,
            ) {
                self.queue
                    .push(h.t, Ev::PairBound { a, va, b, vb, c }, &self.clusters);
            }
        }
        if let Some((hi, c)) = bounds.hi {
            let f = |x: f64| hi - rel(x);
            let df = |x: f64| (hi - rel(x), -w(x));
            let start = valid_after(hi - r0, tol, &[-r1, -r2]);
            if let Some(h) = first_violation(
                Fun::with(&f, &df),
                t0,
                t1,
                vertex,
                start,
                tol,
                &mut self.count,
            ) {
                self.queue
                    .push(h.t, Ev::PairBound { a, va, b, vb, c }, &self.clusters);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Bounds at the same value (equal blocks make equal thresholds) keep the same constraint
    /// in whatever order they come, so a pair's events do not depend on which side is scanned.
    #[test]
    fn tied_bounds_do_not_depend_on_their_order() {
        let cs = [
            (0.25, Constraint::Collapse(3)),
            (0.25, Constraint::Gap(1)),
            (0.5, Constraint::Gap(0)),
            (0.25, Constraint::Collapse(0)),
        ];
        for rotation in 0..cs.len() {
            for reversed in [false, true] {
                let mut order: Vec<_> = cs.iter().cycle().skip(rotation).take(cs.len()).collect();
                if reversed {
                    order.reverse();
                }
                let mut b = Bounds::default();
                for &&(v, c) in &order {
                    b.lower(v, c);
                    b.upper(v, c);
                }
                assert_eq!(b.lo, Some((0.5, Constraint::Gap(0))));
                assert_eq!(b.hi, Some((0.25, Constraint::Collapse(0))));
            }
        }
    }
}
