//! Clusters: blocks that move as one rigid body in the current mode, and their motion in closed
//! form. A cluster is either stuck to the ground (its blocks do not move relative to it) or slides
//! with a constant absolute acceleration c, so relative to the ground on a segment
//!
//!   v(s) = v0 + c s - dv(s),     du(s) = x0 + v0 s + c s^2/2 - dd(s),
//!
//! with dv, dd the ground's velocity and displacement gained since the segment start (eq. 1 with
//! constant friction forces).

use super::roots::Zeros;
use super::solver::Stick;
use crate::exact::Q;
use crate::motion::Segment;
use smallvec::SmallVec;
use std::cell::{Cell, OnceCell};

/// A cluster's mode: stuck to the ground within its stick interval, or sliding in closed
/// form ("motion" is the ground's, everywhere else).
#[derive(Debug, Clone)]
pub enum Mode {
    /// Stuck to the ground while lo <= a_g <= hi (m/s2; infinite where no a_g would move it).
    Stuck {
        /// Lower limit of a_g, rounded to the nearest float.
        lo: f64,
        /// Upper limit of a_g, rounded to the nearest float.
        hi: f64,
        /// Exact lower limit.
        lo_q: Option<Q>,
        /// Exact upper limit.
        hi_q: Option<Q>,
        /// Per side ([lo, hi]): the limit is only a bound from inside, worked out exactly when
        /// a_g reaches it (`solver::Stick::bound_only`).
        bound_only: [bool; 2],
    },
    /// Sliding with constant absolute acceleration.
    Sliding(Slide),
}

/// Closed-form motion of a sliding cluster, measured from an anchor instant (its formation, or
/// the start of the current segment): with sigma = t - anchor, absolute acceleration
/// c lambda(t) (c: with unit vertical load factor; lambda = 1 without vertical shaking),
///
///   v = v_a + (c lambda_a - a_a) sigma + c lambda' sigma^2/2 - dv_beyond(sigma),
///   u = u_a + v_a sigma + (c lambda_a - a_a) sigma^2/2 + c lambda' sigma^3/6 - dd_beyond(sigma),
///
/// where a_a is a_g at the anchor. Every term is small near the anchor, so the velocity of a
/// cluster that has just formed at rest is computed without cancellation noise.
#[derive(Debug, Clone)]
pub struct Slide {
    /// The ground motion, re-described from the anchor instant on.
    pub anchor: Segment,
    /// Displacement gained since formation, at the anchor (m).
    pub x_a: f64,
    /// Velocity relative to the ground at the anchor (m/s).
    pub v_a: f64,
    /// Absolute acceleration at unit vertical load factor (m/s2), the nearest float to `c_q`.
    pub c: f64,
    /// The same, exact.
    pub c_q: Q,
    /// c lambda - a_g at the anchor (m/s2).
    rel: f64,
    /// c lambda' (m/s3).
    grow: f64,
    /// The last displacement and velocity asked for, each with its time (NaN: none): a decision
    /// asks for the state of a cluster at one instant many times, and each answer costs a sine.
    last_disp: Cell<(f64, f64)>,
    last_vel: Cell<(f64, f64)>,
}

impl Slide {
    /// A cluster formed at time t with velocity v relative to the ground.
    pub fn formed(seg: &Segment, t: f64, v: f64, c_q: Q) -> Slide {
        let anchor = seg.anchored(t);
        let c = c_q.to_f64();
        Slide {
            rel: c * anchor.lambda.0 - anchor.start_accel(),
            grow: c * anchor.lambda.1,
            anchor,
            x_a: 0.0,
            v_a: v,
            c,
            c_q,
            last_disp: Cell::new((f64::NAN, 0.0)),
            last_vel: Cell::new((f64::NAN, 0.0)),
        }
    }

    /// Displacement gained since formation at time t (m).
    pub fn disp(&self, t: f64) -> f64 {
        let (at, d) = self.last_disp.get();
        if at == t {
            return d;
        }
        let s = t - self.anchor.t0;
        let d = self.x_a + s * (self.v_a + s * (0.5 * self.rel + self.grow * s / 6.0))
            - self.anchor.dd_beyond(s);
        self.last_disp.set((t, d));
        d
    }

    /// Velocity relative to the ground at time t (m/s).
    pub fn vel(&self, t: f64) -> f64 {
        let (at, v) = self.last_vel.get();
        if at == t {
            return v;
        }
        let s = t - self.anchor.t0;
        let v = self.v_a + s * (self.rel + 0.5 * self.grow * s) - self.anchor.dv_beyond(s);
        self.last_vel.set((t, v));
        v
    }

    /// Acceleration relative to the ground at time t (m/s2).
    pub fn acc(&self, t: f64) -> f64 {
        let s = t - self.anchor.t0;
        self.rel + self.grow * s - self.anchor.da(s)
    }

    /// Rate of the relative acceleration (m/s3) where the ground's acceleration changes at
    /// `ground_rate`: the friction term changes with the vertical load factor too (`grow`),
    /// so a block balanced at its friction limit under vertical shaking leaves zero the way
    /// the stick decision says it does, not the way a_g alone would.
    pub fn acc_rate(&self, ground_rate: f64) -> f64 {
        self.grow - ground_rate
    }

    /// Displacement, velocity and acceleration at time t, from one evaluation of the ground
    /// motion (bit for bit what `disp`, `vel` and `acc` give).
    pub fn state(&self, t: f64) -> (f64, f64, f64) {
        let s = t - self.anchor.t0;
        let (da, dv, dd) = self.anchor.beyond(s);
        (
            self.x_a + s * (self.v_a + s * (0.5 * self.rel + self.grow * s / 6.0)) - dd,
            self.v_a + s * (self.rel + 0.5 * self.grow * s) - dv,
            self.rel + self.grow * s - da,
        )
    }

    /// Absolute acceleration at time t (m/s2).
    pub fn absolute_accel(&self, t: f64) -> f64 {
        self.c * self.anchor.lambda_at(t - self.anchor.t0)
    }

    /// Re-anchors at the start of the next segment.
    pub fn rebase(&mut self, next: &Segment) {
        let t = next.t0;
        let (x, v) = (self.disp(t), self.vel(t));
        self.anchor = *next;
        self.x_a = x;
        self.v_a = v;
        self.rel = self.c * next.lambda.0 - next.start_accel();
        self.grow = self.c * next.lambda.1;
        self.last_disp.set((f64::NAN, 0.0));
        self.last_vel.set((f64::NAN, 0.0));
    }

    /// Work of the inertial forces -m a_g on the cluster from t_a to t_b, per unit mass (J/kg):
    /// minus the integral of a_g v, in closed form.
    pub fn input_work_per_kg(&self, t_a: f64, t_b: f64) -> f64 {
        let seg = &self.anchor;
        let (l0, l1) = seg.lambda;
        let i = |t: f64| {
            let s = t - seg.t0;
            let dv = seg.dv(s);
            self.v_a * dv + self.c * (l0 * seg.moment(s) + l1 * seg.moment2(s)) - 0.5 * dv * dv
        };
        -(i(t_b) - i(t_a))
    }

    /// Integral of the displacement gained since formation from t_a to t_b (m s); only needed
    /// with vertical shaking, which comes with piecewise-linear records.
    pub fn disp_integral(&self, t_a: f64, t_b: f64) -> f64 {
        let slope = match self.anchor.shape {
            crate::motion::Shape::Linear { slope, .. } => slope,
            crate::motion::Shape::Sine { .. } => 0.0,
        };
        let f = |t: f64| {
            let s = t - self.anchor.t0;
            s * (self.x_a + s * (0.5 * self.v_a + s * (self.rel / 6.0 + self.grow * s / 24.0)))
                - slope * s.powi(4) / 24.0
        };
        f(t_b) - f(t_a)
    }
}

/// Where, on the current segment from `from` on, a sliding cluster's acceleration relative to
/// the ground vanishes (`a_zero`) and its velocity does (`v_zero`): found once when its events are
/// scheduled, reused for its energy and extremes.
#[derive(Debug, Clone, Default)]
pub struct Roots {
    /// Start of the interval searched (s).
    pub from: f64,
    /// End of the interval searched (s).
    pub to: f64,
    /// The zero of the relative acceleration (s): c - a_g is monotone on a segment's arc.
    pub a_zero: Option<f64>,
    /// Zeros of the relative velocity (s): one on each side of `a_zero` at most.
    pub v_zero: Zeros,
}

/// A stuck cluster's limits of a_g, exact or bounds from inside ([`Stick::bound_only`]): what
/// its [`Mode::Stuck`] is made from.
#[derive(Debug, Clone, Default)]
pub struct Limits {
    pub lo: Option<Q>,
    pub hi: Option<Q>,
    pub bound_only: [bool; 2],
}

impl Limits {
    /// The limits of a stick interval worked out or remembered.
    pub fn of(s: &Stick) -> Limits {
        Limits {
            lo: s.lo.clone(),
            hi: s.hi.clone(),
            bound_only: s.bound_only,
        }
    }
}

/// A bound on a relative displacement as bits: value and what it stands for.
pub type BoundKey = Option<(u64, u64)>;

/// The roots of a sliding cluster's event functions against the ground side on the current
/// segment, and what they were computed for: a neighbour re-deciding its mode changes nothing
/// here unless it changes the sliding direction or the bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundHits {
    /// Direction of sliding on the ground side, and the bounds with their bit patterns.
    pub key: (i8, BoundKey, BoundKey),
    /// Earliest start time the hits are valid from (s).
    pub from: f64,
    /// Stop time, and the times the lower and upper bounds are reached.
    pub hits: [Option<f64>; 3],
}

/// Index of a cluster in the engine's [`Clusters`] (the slot of a dissolved cluster is reused,
/// so an id names a cluster only with its version).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ClusterId(pub usize);

impl ClusterId {
    /// No cluster: a fixed or fallen block's.
    pub const NONE: ClusterId = ClusterId(usize::MAX);
}

/// The clusters of a run, indexed by [`ClusterId`].
#[derive(Debug, Clone, Default)]
pub struct Clusters(Vec<Cluster>);

impl Clusters {
    /// Every slot's id, live or emptied.
    pub fn ids(&self) -> impl Iterator<Item = ClusterId> + use<> {
        (0..self.0.len()).map(ClusterId)
    }

    /// The cluster in slot k, if there is such a slot.
    pub fn get(&self, k: ClusterId) -> Option<&Cluster> {
        self.0.get(k.0)
    }

    /// Every cluster, emptied slots included.
    pub fn iter_mut(&mut self) -> std::slice::IterMut<'_, Cluster> {
        self.0.iter_mut()
    }

    /// A new slot.
    pub fn push(&mut self, c: Cluster) -> ClusterId {
        self.0.push(c);
        ClusterId(self.0.len() - 1)
    }
}

impl std::ops::Index<ClusterId> for Clusters {
    type Output = Cluster;
    fn index(&self, k: ClusterId) -> &Cluster {
        &self.0[k.0]
    }
}

impl std::ops::IndexMut<ClusterId> for Clusters {
    fn index_mut(&mut self, k: ClusterId) -> &mut Cluster {
        &mut self.0[k.0]
    }
}

/// A cluster.
#[derive(Debug, Clone)]
pub struct Cluster {
    /// Its blocks.
    pub blocks: Vec<usize>,
    /// Total mass (kg).
    pub mass: f64,
    /// Total mass, exact.
    pub mass_q: Q,
    /// Changes whenever its motion changes; events computed for an older version are stale.
    pub version: u64,
    /// Changes whenever what it slides against changes and its motion does not: its events
    /// against the ground side computed for an older one are stale, its events with other
    /// sliding clusters stand.
    pub ground_version: u64,
    /// How it moves.
    pub mode: Mode,
    /// Energy and extremes are accounted up to this time (s).
    pub accounted_to: f64,
    /// Zeros found on the current segment; `None` until scheduled, and whenever the motion
    /// changes.
    pub roots: Option<Roots>,
    /// Event times against the ground side on the current segment (reset with `roots`).
    pub ground_hits: Option<GroundHits>,
    /// What its blocks reached since their reference displacements were last set.
    pub extremes: Extremes,
    /// Its blocks with a support or a face to the ground or to a block outside it: the only
    /// ones where it can meet anything else. Worked out at the first need (`Engine::boundary`)
    /// and kept, since a cluster's blocks never change; a few are held inline (a cluster is
    /// made at most events).
    pub boundary: OnceCell<SmallVec<[usize; 4]>>,
}

/// Peaks a cluster's blocks reached, kept for the cluster as a whole and handed to the recorder
/// block by block only when the blocks' references change (or at the end): a large cluster then
/// costs nothing per segment of the ground motion. The peaks are the same: each block's
/// displacement is its reference plus the cluster's, and the largest |reference + d| over a
/// stretch of d is at its least or greatest d.
#[derive(Debug, Clone, Default)]
pub struct Extremes {
    /// Peak |absolute acceleration| (m/s2).
    pub accel_m_s2: f64,
    /// Least and greatest displacement of the cluster relative to its blocks' references (m);
    /// `None` while it has not slid.
    pub disp_m: Option<(f64, f64)>,
    /// Peak |velocity| relative to the ground (m/s).
    pub vel_m_s: f64,
}

impl Cluster {
    /// The sliding motion, if sliding.
    pub fn slide(&self) -> Option<&Slide> {
        match &self.mode {
            Mode::Sliding(s) => Some(s),
            Mode::Stuck { .. } => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::motion::{Motion, Sine};

    /// The displacement and velocity remembered are those computed (bit for bit what `state`
    /// gives), whatever the order of the times asked for, before and after re-anchoring.
    #[test]
    fn remembered_states_are_the_computed_ones() {
        let motion = Motion::sine(Sine {
            amplitude_m_s2: 4.0,
            frequency_hz: 1.0,
            phase_rad: 30.0,
            duration_s: 20.0,
        })
        .unwrap();
        let seg = motion.segment_at(0.1);
        let mut sl = Slide::formed(&seg, 0.1, 0.05, Q::frac(-3, 2));
        let check = |sl: &Slide, t: f64| {
            let (u, v, _) = sl.state(t);
            assert_eq!(sl.disp(t).to_bits(), u.to_bits(), "u at {t}");
            assert_eq!(sl.vel(t).to_bits(), v.to_bits(), "v at {t}");
        };
        for t in [0.2, 0.2, 0.13, 0.2, 0.37, 0.37] {
            check(&sl, t);
        }
        // Re-anchored later on: the times asked for before are measured from the new anchor.
        let next = motion.segment_at(0.45);
        sl.rebase(&next);
        for t in [0.37, 0.2, 0.5, 0.37] {
            check(&sl, t);
        }
    }
}
