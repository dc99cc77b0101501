//! Telling a process that repeats itself from one that is only long: Brent's cycle detection
//! on the states a deterministic process goes through (the velocities of an impact chain, the
//! engine's modes and velocities at one instant). A run is stopped for lack of progress only
//! when its state came back, the same, three times at the same period; a long chain of
//! collisions or of events at one instant that keeps changing the state is left to finish.

/// Times a state must come back at one period before the process is called a cycle: a state
/// that repeats once might be a coincidence of a state that leaves out some of the process
/// (the event queue), one that repeats three times at the same period is not.
const CONFIRMATIONS: usize = 3;

/// Brent's algorithm: one state kept, replaced after 1, 2, 4, ... steps, so a cycle of period
/// p entered after m steps is seen within about 2 (m + p) steps, in O(1) memory of states.
#[derive(Debug, Clone)]
pub(super) struct Cycle<S> {
    /// The kept state and a cheap key of it (compared first).
    kept: Option<(u64, S)>,
    /// Steps after which the kept state is replaced.
    power: usize,
    /// Steps since the kept state was taken or last seen again.
    steps: usize,
    /// The period of the last repetition and how many times in a row it was seen.
    period: usize,
    seen: usize,
}

impl<S: PartialEq> Default for Cycle<S> {
    fn default() -> Cycle<S> {
        Cycle {
            kept: None,
            power: 1,
            steps: 0,
            period: 0,
            seen: 0,
        }
    }
}

impl<S: PartialEq> Cycle<S> {
    /// One more step of the process, in a state whose cheap `key` is given and whose full
    /// value `state` builds (called only when the key matches or the state is kept). Returns
    /// the period once the state has come back [`CONFIRMATIONS`] times at one period.
    pub(super) fn step(&mut self, key: u64, state: impl FnOnce() -> S) -> Option<usize> {
        self.steps += 1;
        if let Some((kept_key, kept)) = &self.kept {
            if *kept_key == key {
                let now = state();
                if now == *kept {
                    if self.steps == self.period {
                        self.seen += 1;
                    } else {
                        (self.period, self.seen) = (self.steps, 1);
                    }
                    self.steps = 0;
                    return (self.seen >= CONFIRMATIONS).then_some(self.period);
                }
                if self.steps >= self.power {
                    self.keep(key, now);
                }
                return None;
            }
        }
        if self.steps >= self.power {
            self.keep(key, state());
        }
        None
    }

    fn keep(&mut self, key: u64, state: S) {
        self.kept = Some((key, state));
        self.power *= 2;
        self.steps = 0;
        self.seen = 0;
    }
}

/// A key of a sequence of words, for [`Cycle::step`] (FNV-1a: cheap and order-sensitive).
pub(super) fn key_of(words: &[u64]) -> u64 {
    words.iter().fold(0xcbf2_9ce4_8422_2325, |h, w| {
        (h ^ w).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs `next` from `x0` until the detector reports; returns (steps, period).
    fn run(x0: u64, next: impl Fn(u64) -> u64, limit: usize) -> Option<(usize, usize)> {
        let mut c = Cycle::default();
        let mut x = x0;
        for n in 1..=limit {
            x = next(x);
            if let Some(p) = c.step(key_of(&[x]), || x) {
                return Some((n, p));
            }
        }
        None
    }

    #[test]
    fn a_cycle_is_found_with_its_period_after_a_lead_in() {
        // 0, 1, ..., 99, then 100..107 round and round: period 8 after a lead-in of 100.
        let next = |x: u64| if x < 107 { x + 1 } else { 100 };
        let (n, p) = run(0, next, 10_000).expect("a cycle");
        assert_eq!(p, 8);
        // Brent's bound plus the confirmations: within 2 (lead-in + period) + 3 periods.
        assert!(
            n <= 2 * (100 + 8) + CONFIRMATIONS * 8,
            "found after {n} steps"
        );
    }

    #[test]
    fn a_long_process_that_never_repeats_is_left_alone() {
        assert_eq!(run(0, |x| x + 1, 1_000_000), None);
    }

    #[test]
    fn equal_keys_of_different_states_are_not_a_cycle() {
        // Every state has the same key; only the states tell them apart.
        let mut c = Cycle::default();
        for x in 0..10_000u64 {
            assert_eq!(c.step(7, || x), None);
        }
    }

    #[test]
    fn a_fixed_point_is_a_cycle_of_period_one() {
        assert_eq!(run(5, |_| 5, 100), Some((CONFIRMATIONS + 1, 1)));
    }
}
