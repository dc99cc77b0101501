//! What the clusters do between events, accounted when their mode changes: the ground's
//! energy input and the friction work, displacement and velocity extremes, and the sampled
//! history.

use super::cluster::ClusterId;
use super::roots::{self, Fun};
use super::{cluster, Engine};
use crate::integrate::Progress;

impl Engine<'_> {
    /// Energy input and displacement/velocity extremes of every sliding cluster up to t.
    pub(super) fn account_all(&mut self, t: f64) {
        for k in self.clusters.ids() {
            if !self.clusters[k].blocks.is_empty() {
                self.account(k, t);
            }
        }
    }

    /// Energy input and extremes of cluster k from where it was accounted to t (same segment).
    pub(super) fn account(&mut self, k: ClusterId, t: f64) {
        let t_a = self.clusters[k].accounted_to;
        self.clusters[k].accounted_to = t;
        let Some(sl) = self.clusters[k].slide().cloned() else {
            // Stuck blocks move with the ground.
            if t > t_a {
                let (lo, hi) = self.given.motion.accel_range(t_a, t);
                let peak = &mut self.clusters[k].extremes.accel_m_s2;
                *peak = peak.max(lo.abs().max(hi.abs()));
            }
            return;
        };
        let peak = sl.absolute_accel(t_a).abs().max(sl.absolute_accel(t).abs());
        let accel = &mut self.clusters[k].extremes.accel_m_s2;
        *accel = accel.max(peak);
        if t <= t_a {
            return;
        }
        self.rec.energy.input_j += self.clusters[k].mass * sl.input_work_per_kg(t_a, t);
        // The cluster's zeros, found when it was scheduled on this segment (kept for later
        // accounts), or found now.
        let cached = self.clusters[k].roots.take();
        let fresh = match &cached {
            Some(r) if r.from <= t_a && t <= r.to => None,
            _ => Some(self.zeros(&sl, t_a, t)),
        };
        let roots = fresh.as_ref().or(cached.as_ref()).expect("found or cached");
        let inside = |x: &&f64| **x > t_a && **x < t;
        let vel = |x: f64| sl.vel(x);
        let (d_a, d_t) = (sl.disp(t_a), sl.disp(t));
        let (mut lo, mut hi) = (d_a.min(d_t), d_a.max(d_t));
        for &r in roots.v_zero.iter().filter(inside) {
            let x = sl.disp(r);
            lo = lo.min(x);
            hi = hi.max(x);
        }
        let mut vmax = vel(t_a).abs().max(vel(t).abs());
        for &r in roots.a_zero.iter().filter(inside) {
            vmax = vmax.max(vel(r).abs());
        }
        self.clusters[k].roots = cached;
        let e = &mut self.clusters[k].extremes;
        e.disp_m = Some(e.disp_m.map_or((lo, hi), |(a, b)| (a.min(lo), b.max(hi))));
        e.vel_m_s = e.vel_m_s.max(vmax);
    }

    /// Hands cluster k's extremes to its blocks: before their references change, and at the end.
    pub(super) fn record_extremes(&mut self, k: ClusterId) {
        let e = std::mem::take(&mut self.clusters[k].extremes);
        for &i in &self.clusters[k].blocks {
            self.rec.block_accel(i, e.accel_m_s2);
            if let Some((lo, hi)) = e.disp_m {
                let u = (self.u_ref[i] + lo).abs().max((self.u_ref[i] + hi).abs());
                self.rec.block_extremes(i, u, e.vel_m_s);
            }
        }
    }

    /// Zeros of a sliding cluster's relative acceleration and velocity in [t_a, t_b], to the last
    /// bit (they are split points of its event functions).
    pub(super) fn zeros(&mut self, sl: &cluster::Slide, t_a: f64, t_b: f64) -> cluster::Roots {
        let acc = |x: f64| sl.acc(x);
        let vel = |x: f64| sl.vel(x);
        let vel_acc = |x: f64| {
            let (_, v, a) = sl.state(x);
            (v, a)
        };
        // The relative acceleration c - a_g vanishes where a_g = c: closed form on the
        // monotone arc, then the exact float.
        let (fa, fb) = (acc(t_a), acc(t_b));
        let mut a_zero = None;
        if (fa > 0.0 && fb <= 0.0) || (fa < 0.0 && fb >= 0.0) {
            let seg = &sl.anchor;
            let guess = seg
                .time_of_ratio(sl.c, t_a - seg.t0, t_b - seg.t0)
                .map_or(0.5 * (t_a + t_b), |s| seg.t0 + s);
            let t = if fa > 0.0 {
                roots::polish(&acc, guess, t_a, t_b, &mut self.count)
            } else {
                roots::polish(&|x| -acc(x), guess, t_a, t_b, &mut self.count)
            };
            if t < t_b {
                a_zero = Some(t);
            }
        }
        let v_zero = roots::sign_changes(
            Fun::with(&vel, &vel_acc),
            t_a,
            t_b,
            a_zero.as_slice(),
            0.0,
            &mut self.count,
        );
        cluster::Roots {
            from: t_a,
            to: t_b,
            a_zero,
            v_zero,
        }
    }

    /// Friction work of every joint above or below cluster k's blocks, booked up to now.
    pub(super) fn account_joints_of(&mut self, k: ClusterId) {
        let topo = self.given.topo;
        let blocks = std::mem::take(&mut self.clusters[k].blocks);
        for &i in &blocks {
            for s in topo.below[i].iter().chain(&topo.above[i]) {
                self.account_horizontal(s.0);
            }
        }
        self.clusters[k].blocks = blocks;
    }

    /// Friction work on horizontal joint s since it was last accounted, and its displacement extreme.
    /// With vertical shaking the capacity is F lambda(t): the work is F sigma (lambda d |_a^b -
    /// lambda' integral d dt) over the stretch (within one segment).
    pub(super) fn account_horizontal(&mut self, s: usize) {
        if !self.live_horizontal(s) {
            return;
        }
        let d = self.horizontal_d(s);
        let t_a = self.t_fric[s];
        if self.seg.has_vertical() && !self.slip[s].is_stuck() {
            let seg = self.seg;
            let (la, lb) = (seg.lambda_at(t_a - seg.t0), seg.lambda_at(self.t - seg.t0));
            let integral = self.block_disp_integral(self.given.topo.horizontal[s].upper.0, t_a)
                - self
                    .lower_block(s)
                    .map_or(0.0, |l| self.block_disp_integral(l, t_a));
            let work = f64::from(self.slip[s].sign())
                * (lb * d - la * self.d_last[s] - seg.lambda.1 * integral);
            self.rec.energy.friction_j += self.given.cap[s] * work;
        } else {
            self.rec.energy.friction_j += self.given.cap[s] * (d - self.d_last[s]).abs();
        }
        self.d_last[s] = d;
        self.t_fric[s] = self.t;
        self.rec.horizontal_extreme(s, d);
    }

    /// Integral of block i's displacement from t_a to now (m s), within the current segment.
    fn block_disp_integral(&self, i: usize, t_a: f64) -> f64 {
        let span = self.t - t_a;
        match self.of[i] {
            ClusterId::NONE => self.u_ref[i] * span,
            k => {
                self.u_ref[i] * span
                    + self.clusters[k]
                        .slide()
                        .map_or(0.0, |sl| sl.disp_integral(t_a, self.t))
            }
        }
    }

    /// History samples at every output instant up to t (when the run keeps a history).
    /// False when the run was asked to stop while writing them (a fine history between two
    /// far events is most of a run's time): the run then ends at the last row written.
    pub(super) fn output_until(&mut self, t: f64) -> bool {
        let Some(dt) = self.given.output_dt else {
            return true;
        };
        loop {
            let tk = self.output_k as f64 * dt;
            if tk > t || tk > self.given.t_end {
                return true;
            }
            let saved = self.t;
            self.t = tk;
            self.sample();
            self.output_k += 1;
            if self.output_k.is_multiple_of(Progress::EVERY_EVENTS) && !self.keep_going() {
                return false;
            }
            self.t = saved;
        }
    }

    /// One history sample at the current time.
    pub(super) fn sample(&mut self) {
        if !self.rec.wants_history() {
            return;
        }
        let (u, v) = self.state_now();
        self.rec.sample(self.t, &u, &v);
    }

    /// Every block's displacement and velocity now (m, m/s; a fallen block's velocity is zero).
    pub(super) fn state_now(&self) -> (Vec<f64>, Vec<f64>) {
        let u = (0..self.given.n).map(|i| self.block_disp(i)).collect();
        let v = (0..self.given.n)
            .map(|i| {
                if self.fallen[i] {
                    0.0
                } else {
                    self.block_vel(i)
                }
            })
            .collect();
        (u, v)
    }
}
