//! A horizontal joint's state, stuck or slipping one way, and the friction a slipping joint
//! passes: the one place where a slip direction becomes the sign of a force (eq. 2,
//! F = -mu N sgn(v)).

use crate::exact::Q;
use std::cmp::Ordering;

/// The state of a horizontal joint: stuck, or slipping with its upper block moving
/// forward (+x) or backward (-x) relative to the lower one (or to the ground).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(super) enum Slip {
    /// Both sides move together; friction is whatever holds them (a decision's unknown).
    #[default]
    Stuck,
    /// The upper side moves in +x relative to the lower.
    Forward,
    /// The upper side moves in -x relative to the lower.
    Backward,
}

impl Slip {
    /// The slip that the upper side's velocity (or, where velocities are equal, acceleration)
    /// compared with the lower side's gives; `Equal` is no slip.
    pub(super) fn of(upper_vs_lower: Ordering) -> Slip {
        match upper_vs_lower {
            Ordering::Greater => Slip::Forward,
            Ordering::Less => Slip::Backward,
            Ordering::Equal => Slip::Stuck,
        }
    }

    /// sgn(v_upper - v_lower): +1, -1, or 0 when stuck.
    pub(super) fn sign(self) -> i8 {
        match self {
            Slip::Stuck => 0,
            Slip::Forward => 1,
            Slip::Backward => -1,
        }
    }

    pub(super) fn is_stuck(self) -> bool {
        self == Slip::Stuck
    }

    /// The friction force on the upper block of a joint of capacity `capacity` (mu N, N):
    /// -capacity sgn(v_upper - v_lower), eq. (2); the lower block takes its opposite. Zero when
    /// stuck, where friction is not given but decided.
    pub(super) fn on_upper(self, capacity: &Q) -> Q {
        match self {
            Slip::Stuck => Q::zero(),
            Slip::Forward => -capacity.clone(),
            Slip::Backward => capacity.clone(),
        }
    }
}
