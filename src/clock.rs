//! The CPU time of the calling thread: what one case of a sweep or one mode decision costs,
//! whatever else shares the cores (wall-clock time would count the other threads' work when
//! cases run in parallel).

/// A stopwatch of the calling thread's CPU time (wall-clock time where the platform has no
/// per-thread clock).
pub struct ThreadClock {
    start_s: f64,
}

impl ThreadClock {
    /// Starts now.
    pub fn start() -> ThreadClock {
        ThreadClock { start_s: now_s() }
    }

    /// CPU seconds of this thread since [`ThreadClock::start`].
    pub fn seconds(&self) -> f64 {
        now_s() - self.start_s
    }
}

#[cfg(unix)]
fn now_s() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid, writable timespec; the clock id is a constant every POSIX system
    // with threads defines.
    let rc = unsafe { libc::clock_gettime(libc::CLOCK_THREAD_CPUTIME_ID, &mut t) };
    if rc == 0 {
        t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
    } else {
        fallback_s()
    }
}

#[cfg(not(unix))]
fn now_s() -> f64 {
    fallback_s()
}

fn fallback_s() -> f64 {
    use std::sync::OnceLock;
    static ORIGIN: OnceLock<std::time::Instant> = OnceLock::new();
    ORIGIN
        .get_or_init(std::time::Instant::now)
        .elapsed()
        .as_secs_f64()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[cfg(unix)]
    #[test]
    fn a_sleeping_thread_uses_almost_no_cpu_and_a_thread_never_beats_the_wall_clock() {
        let clock = ThreadClock::start();
        std::thread::sleep(std::time::Duration::from_millis(300));
        let slept = clock.seconds();
        assert!((0.0..0.1).contains(&slept), "slept {slept} s of CPU");
        // Spin until the thread has used 0.1 s of CPU: at least as much wall-clock time passed.
        let clock = ThreadClock::start();
        let wall = std::time::Instant::now();
        let mut x = 0u64;
        while clock.seconds() < 0.1 {
            x = std::hint::black_box(x.wrapping_add(1));
        }
        assert!(wall.elapsed().as_secs_f64() >= 0.1 - 1e-3);
    }
}
