//! Long calls that Ctrl-C, or a notebook's "interrupt the kernel", can stop. Python runs its
//! signal handlers only on its main thread and only when some code there asks
//! (`PyErr_CheckSignals`), and a run holds no GIL while it works, so pirqa asks: at most every
//! [`POLL`], from the run's own stop checks (a single run, on the calling thread) or from the
//! calling thread while the work runs on another (a sweep, whose rayon pool blocks the caller).
//! A run shorter than [`POLL`] never takes the GIL back. The signal's exception (usually
//! `KeyboardInterrupt`) is what the call then raises, once what it had reached is stored.

use pyo3::prelude::*;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex, OnceLock};
use std::thread::ThreadId;
use std::time::{Duration, Instant};

/// How often a long call looks at Python's signals: well under the half second after which a
/// user presses Ctrl-C again, and rare enough that taking the GIL costs nothing measurable.
pub const POLL: Duration = Duration::from_millis(50);

/// Python's main thread, once a call came from it.
static MAIN: OnceLock<ThreadId> = OnceLock::new();

/// A call's stop request and the exception a signal's handler raised, if one did.
#[derive(Clone)]
pub struct Interrupt {
    stop: Arc<AtomicBool>,
    raised: Arc<Mutex<Option<PyErr>>>,
    /// Called from Python's main thread: elsewhere no handler runs, and taking the GIL to ask
    /// would only slow a thread pool of runs.
    main: bool,
}

impl Interrupt {
    /// For a call made from the thread `py` is held on.
    pub fn new(py: Python<'_>) -> PyResult<Interrupt> {
        let here = std::thread::current().id();
        let main = match MAIN.get() {
            Some(&main) => main == here,
            // Asked of Python until a call comes from its main thread (a run costs about a
            // millisecond, and asking costs microseconds).
            None => {
                let threading = py.import("threading")?;
                let main = threading
                    .call_method0("current_thread")?
                    .is(&threading.call_method0("main_thread")?);
                if main {
                    let _ = MAIN.set(here);
                }
                main
            }
        };
        Ok(Interrupt {
            stop: Arc::default(),
            raised: Arc::default(),
            main,
        })
    }

    /// Runs Python's pending signal handlers; true (and the stop flag set) when one raised.
    fn signalled(&self) -> bool {
        if self.stop.load(Ordering::Relaxed) || !self.main {
            return self.stop.load(Ordering::Relaxed);
        }
        match Python::attach(|py| py.check_signals()) {
            Ok(()) => false,
            Err(e) => {
                *self.raised.lock().unwrap_or_else(|p| p.into_inner()) = Some(e);
                self.stop.store(true, Ordering::Relaxed);
                true
            }
        }
    }

    /// A stop check for `pirqa::integrate::Progress::with_stop_when`, cheap between polls:
    /// the run calls it at every report and before every pivot of the uplift check.
    pub fn check(&self) -> impl Fn() -> bool + Send + Sync + 'static {
        let this = self.clone();
        let start = Instant::now();
        let last_ns = AtomicU64::new(0);
        move || {
            if this.stop.load(Ordering::Relaxed) || !this.main {
                return this.stop.load(Ordering::Relaxed);
            }
            let now_ns = u64::try_from(start.elapsed().as_nanos()).unwrap_or(u64::MAX);
            if now_ns.saturating_sub(last_ns.load(Ordering::Relaxed)) < POLL.as_nanos() as u64 {
                return false;
            }
            last_ns.store(now_ns, Ordering::Relaxed);
            this.signalled()
        }
    }

    /// Runs `work` on a thread of its own while the calling thread (Python's main one) looks at
    /// the signals every [`POLL`]; the work is given the flag a signal sets.
    pub fn around<T: Send>(&self, work: impl FnOnce(&AtomicBool) -> T + Send) -> T {
        let caller = std::thread::current();
        std::thread::scope(|scope| {
            let worker = scope.spawn(|| {
                let out = work(&self.stop);
                caller.unpark();
                out
            });
            while !worker.is_finished() {
                std::thread::park_timeout(POLL);
                if !worker.is_finished() {
                    self.signalled();
                }
            }
            match worker.join() {
                Ok(out) => out,
                Err(panic) => std::panic::resume_unwind(panic),
            }
        })
    }

    /// The exception a signal's handler raised during the call, if one did.
    pub fn raised(&self) -> Option<PyErr> {
        self.raised.lock().unwrap_or_else(|p| p.into_inner()).take()
    }
}
