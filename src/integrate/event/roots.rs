//! Locating events to round-off.
//!
//! An event function f is valid while f > 0. On an interval it is cut into pieces on which it
//! is monotone (at the roots of its derivative, found the same way one order down), so each piece
//! holds at most one crossing and none is missed. A crossing is returned as the first float time
//! at which f <= 0 holds in floating point: the state handed to the mode decision then satisfies
//! the event's condition, and the decision cannot undo it at the same instant. A local minimum
//! within the round-off of zero is a grazing contact and is reported as such.

use smallvec::SmallVec;

/// The crossings of a function found on an interval, one per monotone piece: the engine cuts an
/// interval into at most two pieces, so they are held inline.
pub type Zeros = SmallVec<[f64; 2]>;

/// Where a function first stops being valid.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hit {
    /// Time (s).
    pub t: f64,
    /// The function touched zero at a local minimum instead of crossing it.
    pub graze: bool,
}

/// Counts function evaluations for the run's statistics.
#[derive(Debug, Default)]
pub struct Counter(pub u64);

/// Direction in which a function leaves zero, from its value and first derivatives: +1 into the
/// valid side, -1 into violation, 0 if all vanish (it stays at zero: valid).
pub fn leaves_zero(derivatives: &[f64]) -> i32 {
    for &d in derivatives {
        if d > 0.0 {
            return 1;
        }
        if d < 0.0 {
            return -1;
        }
    }
    0
}

/// Is f valid just after `t_a`? `value` = f(t_a), `tol` the round-off of f, `derivatives` f', f''...
pub fn valid_after(value: f64, tol: f64, derivatives: &[f64]) -> bool {
    if value > tol {
        true
    } else if value < -tol {
        false
    } else {
        leaves_zero(derivatives) >= 0
    }
}

/// A function with, where it is cheap, its derivative (Newton steps then replace secant ones).
#[derive(Clone, Copy)]
pub struct Fun<'a> {
    /// The function.
    pub f: &'a dyn Fn(f64) -> f64,
    /// The function and its derivative, evaluated together.
    pub fd: Option<&'a dyn Fn(f64) -> (f64, f64)>,
}

impl<'a> Fun<'a> {
    /// A function without a known derivative.
    pub fn plain(f: &'a dyn Fn(f64) -> f64) -> Fun<'a> {
        Fun { f, fd: None }
    }
    /// A function, and the function with its derivative.
    pub fn with(f: &'a dyn Fn(f64) -> f64, fd: &'a dyn Fn(f64) -> (f64, f64)) -> Fun<'a> {
        Fun { f, fd: Some(fd) }
    }
}

/// The first float time in (lo, hi] where f <= 0, given f(lo) > 0 >= f(hi): safeguarded Newton
/// (or Illinois regula falsi without a derivative), bisection when a step does not shrink the
/// bracket enough, down to adjacent floats — or to a bracket of width `tol` when only the place
/// matters to first order (extremes).
pub fn refine(fun: Fun, lo: f64, hi: f64, tol: f64, count: &mut Counter) -> f64 {
    let (flo, fhi) = ((fun.f)(lo), (fun.f)(hi));
    count.0 += 2;
    refine_from(fun, (lo, flo), (hi, fhi), tol, count)
}

/// [`refine`] on a bracket whose ends' values the caller has already: f is evaluated the same
/// way wherever it is, so the search and its answer are those of [`refine`], two evaluations
/// fewer.
fn refine_from(
    fun: Fun,
    (mut lo, mut flo): (f64, f64),
    (mut hi, mut fhi): (f64, f64),
    tol: f64,
    count: &mut Counter,
) -> f64 {
    let f = fun.f;
    if let Some(fd) = fun.fd {
        // Newton from the end nearer the root, bisecting whenever a step would leave the
        // bracket; then the last few floats one by one.
        let x0 = if flo.abs() < fhi.abs() { lo } else { hi };
        let (mut fx, mut d) = fd(x0);
        let mut x = x0;
        count.0 += 1;
        for _ in 0..100 {
            let newton = x - fx / d;
            // Newton lands within a few floats of x: x is the root to round-off. (At an end
            // of the bracket the step would fall outside it; bisecting from there would take
            // fifty steps to get back.)
            if (newton - x).abs() <= 4.0 * f64::EPSILON * x.abs() {
                return if tol > 0.0 {
                    x
                } else {
                    polish(f, x, lo, hi, count)
                };
            }
            let next = if newton > lo && newton < hi {
                newton
            } else {
                lo + 0.5 * (hi - lo)
            };
            if !(next > lo && next < hi) {
                break;
            }
            let step = (next - x).abs();
            x = next;
            (fx, d) = fd(x);
            count.0 += 1;
            if fx > 0.0 {
                lo = x;
            } else {
                hi = x;
            }
            if step <= tol || step <= 4.0 * f64::EPSILON * x.abs() || hi <= lo.next_up() {
                return if tol > 0.0 {
                    x
                } else {
                    polish(f, x, lo, hi, count)
                };
            }
        }
        flo = f(lo);
        fhi = f(hi);
        count.0 += 2;
    }
    let mut side = 0i8;
    let mut stalled = 0;
    for _ in 0..300 {
        if hi <= lo.next_up() || hi - lo <= tol {
            return hi;
        }
        let width = hi - lo;
        let mut m = if stalled >= 2 {
            stalled = 0;
            lo + 0.5 * width
        } else {
            lo + width * (flo / (flo - fhi))
        };
        if !(m > lo && m < hi) {
            m = lo + 0.5 * width;
            if !(m > lo && m < hi) {
                m = lo.next_up();
            }
        }
        let fm = f(m);
        count.0 += 1;
        if fm > 0.0 {
            lo = m;
            flo = fm;
            if side == 1 {
                fhi *= 0.5;
            }
            side = 1;
        } else {
            hi = m;
            fhi = fm;
            if side == -1 {
                flo *= 0.5;
            }
            side = -1;
        }
        if hi - lo > 0.5 * width {
            stalled += 1;
        }
    }
    hi
}

/// Moves an approximate root x (from a closed form) to the first float where f <= 0, given that
/// f is valid at `lo` and not at `hi`, both bracketing x.
pub fn polish(f: &dyn Fn(f64) -> f64, x: f64, lo: f64, hi: f64, count: &mut Counter) -> f64 {
    let x = x.clamp(lo.next_up().min(hi), hi);
    let fx = f(x);
    count.0 += 1;
    // Step a few floats towards the crossing; far off means the closed form lost accuracy.
    let mut y = x;
    for _ in 0..16 {
        let z = if fx <= 0.0 {
            y.next_down()
        } else {
            y.next_up()
        };
        if z <= lo || z > hi {
            break;
        }
        let fz = f(z);
        count.0 += 1;
        match (fx <= 0.0, fz <= 0.0) {
            (true, true) => y = z,
            (true, false) => return y,
            (false, true) => return z,
            (false, false) => y = z,
        }
    }
    if fx <= 0.0 {
        refine(Fun::plain(f), lo, y, 0.0, count)
    } else {
        refine(Fun::plain(f), y, hi, 0.0, count)
    }
}

/// The first time in [t_a, t_b] where f stops being valid. `splits` are the interior points of
/// [t_a, t_b] at which f may change monotonicity (sorted); `start_valid` says whether f is valid
/// just after t_a (see [`valid_after`]); `graze_tol` is the round-off of f, below which a local
/// minimum counts as touching zero.
pub fn first_violation(
    fun: Fun,
    t_a: f64,
    t_b: f64,
    splits: &[f64],
    start_valid: bool,
    graze_tol: f64,
    count: &mut Counter,
) -> Option<Hit> {
    if !start_valid {
        return Some(Hit {
            t: t_a,
            graze: false,
        });
    }
    if t_b <= t_a {
        return None;
    }
    let f = fun.f;
    let mut p = t_a;
    // Just after t_a the function is valid, whatever round-off says at t_a itself.
    let mut fp = f64::INFINITY;
    let inner = splits.iter().copied().filter(|&s| s > t_a && s < t_b);
    for q in inner.chain(std::iter::once(t_b)) {
        let fq = f(q);
        count.0 += 1;
        // A local minimum within round-off of zero touches zero, on whichever side rounding
        // puts it: report the touch at the minimum, not a crossing an ulp-level dip before it.
        if q < t_b && fp > 0.0 && fq.abs() <= graze_tol && graze_tol > 0.0 {
            return Some(Hit { t: q, graze: true });
        }
        if fp > 0.0 && fq <= 0.0 {
            if p == t_a {
                // The piece starts at the zero it is leaving; its crossing is strictly later.
                let start = f(p);
                count.0 += 1;
                if start > 0.0 {
                    return Some(Hit {
                        t: refine_from(fun, (p, start), (q, fq), 0.0, count),
                        graze: false,
                    });
                }
                return Some(match scan_past_zero(fun, p, (q, fq), count) {
                    Some(t) => Hit { t, graze: false },
                    // Valid for less than one float step of time: it touches zero here.
                    None => Hit { t: p, graze: true },
                });
            }
            return Some(Hit {
                t: refine_from(fun, (p, fp), (q, fq), 0.0, count),
                graze: false,
            });
        }
        p = q;
        fp = fq;
    }
    None
}

/// On a piece that starts at a zero of f and is valid just after it but invalid at its end q:
/// find a point where f is positive, then refine. `None` when f is <= 0 at every float time
/// after p that was sampled, down to the next float: the stretch where it is valid is shorter
/// than one float step of time (two faces that part at 1e-13 m/s and are pushed back together
/// at once), so it touches zero at p.
fn scan_past_zero(fun: Fun, p: f64, (q, fq): (f64, f64), count: &mut Counter) -> Option<f64> {
    let f = fun.f;
    let mut step = (q - p) * 0.5;
    let mut best = None;
    for _ in 0..60 {
        let x = p + step;
        if x <= p {
            break;
        }
        let fx = f(x);
        count.0 += 1;
        if fx > 0.0 {
            best = Some((x, fx));
            break;
        }
        step *= 0.5;
    }
    let start = best.or_else(|| {
        let next = p.next_up();
        count.0 += 1;
        if next >= q {
            return None;
        }
        let f_next = f(next);
        (f_next > 0.0).then_some((next, f_next))
    })?;
    Some(refine_from(fun, start, (q, fq), 0.0, count))
}

/// All points in (t_a, t_b) where f changes sign, given the same monotone pieces, each located
/// to within `tol` (0: to adjacent floats).
pub fn sign_changes(
    fun: Fun,
    t_a: f64,
    t_b: f64,
    splits: &[f64],
    tol: f64,
    count: &mut Counter,
) -> Zeros {
    let f = fun.f;
    let mut out = Zeros::new();
    let mut p = t_a;
    let mut fp = f(p);
    count.0 += 1;
    let inner = splits.iter().copied().filter(|&s| s > t_a && s < t_b);
    for q in inner.chain(std::iter::once(t_b)) {
        let fq = f(q);
        count.0 += 1;
        if (fp > 0.0 && fq <= 0.0) || (fp < 0.0 && fq >= 0.0) {
            let t = if fp > 0.0 {
                refine_from(fun, (p, fp), (q, fq), tol, count)
            } else {
                let neg = |x: f64| -f(x);
                let neg_fd = fun.fd.map(|fd| {
                    move |x: f64| {
                        let (v, d) = fd(x);
                        (-v, -d)
                    }
                });
                let ends = ((p, -fp), (q, -fq));
                match &neg_fd {
                    Some(nfd) => refine_from(Fun::with(&neg, nfd), ends.0, ends.1, tol, count),
                    None => refine_from(Fun::plain(&neg), ends.0, ends.1, tol, count),
                }
            };
            if t < t_b {
                out.push(t);
            }
        } else if fq == 0.0 && q < t_b {
            out.push(q);
        }
        p = q;
        fp = fq;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refine_returns_the_first_float_past_the_root() {
        let mut c = Counter::default();
        let root = 2f64.sqrt();
        let f = |x: f64| 2.0 - x * x;
        let fd = |x: f64| (2.0 - x * x, -2.0 * x);
        for fun in [Fun::plain(&f), Fun::with(&f, &fd)] {
            let mut c = Counter::default();
            let t = refine(fun, 1.0, 2.0, 0.0, &mut c);
            assert!(2.0 - t * t <= 0.0);
            assert!(2.0 - t.next_down() * t.next_down() > 0.0);
            assert!((t - root).abs() <= 2.0 * f64::EPSILON);
            assert!(c.0 < 40, "{} evaluations", c.0);
        }
        let x = polish(&f, root + 3e-16, 1.0, 2.0, &mut c);
        assert_eq!(x, refine(Fun::plain(&f), 1.0, 2.0, 0.0, &mut c));
    }

    #[test]
    fn newton_landing_on_the_root_stops_there() {
        // From 0 Newton lands exactly on the root at 1, which becomes the end of the bracket:
        // done, not fifty bisections back towards it.
        let f = |x: f64| 1.0 - x;
        let fd = |x: f64| (1.0 - x, -1.0);
        let mut c = Counter::default();
        assert_eq!(refine(Fun::with(&f, &fd), 0.0, 3.0, 0.0, &mut c), 1.0);
        assert!(c.0 <= 8, "{} evaluations", c.0);
    }

    #[test]
    fn crossings_and_grazes_on_monotone_pieces() {
        let mut c = Counter::default();
        // (x - 1)^2 - 0.25: valid, then crosses at 0.5.
        let f = |x: f64| (x - 1.0) * (x - 1.0) - 0.25;
        let hit = first_violation(Fun::plain(&f), 0.0, 2.0, &[1.0], true, 0.0, &mut c).unwrap();
        assert!((hit.t - 0.5).abs() < 1e-15 && !hit.graze);
        // (x - 1)^2 touches zero at 1: a graze, found at the split point.
        let g = |x: f64| (x - 1.0) * (x - 1.0);
        let hit = first_violation(Fun::plain(&g), 0.0, 2.0, &[1.0], true, 1e-12, &mut c).unwrap();
        assert_eq!(
            hit,
            Hit {
                t: 1.0,
                graze: true
            }
        );
        // Starting at zero and moving into the valid side is not an event.
        let h = |x: f64| x * (1.0 - x);
        let hit = first_violation(Fun::plain(&h), 0.0, 2.0, &[0.5], true, 0.0, &mut c).unwrap();
        assert_eq!(hit.t, 1.0);
        assert!(first_violation(Fun::plain(&h), 0.0, 0.9, &[0.5], true, 0.0, &mut c).is_none());
    }

    #[test]
    fn a_stretch_of_validity_shorter_than_a_float_step_touches_at_its_start() {
        // Two faces parting at 1.8e-13 m/s, pushed back at 429 m/s2: open for 8.5e-16 s, less
        // than one float step at t = 4.86 s (8.9e-16 s). The event is now, not at the horizon.
        let mut c = Counter::default();
        let t0 = 4.864661376259848;
        let f = |x: f64| {
            let tau = x - t0;
            1.8e-13 * tau - 214.5 * tau * tau
        };
        let hit = first_violation(Fun::plain(&f), t0, 39.99, &[], true, 0.0, &mut c);
        assert_eq!(hit, Some(Hit { t: t0, graze: true }));
        // Open for longer than a float step: the crossing is found where it is.
        let g = |x: f64| {
            let tau = x - t0;
            1.8e-9 * tau - 214.5 * tau * tau
        };
        let hit = first_violation(Fun::plain(&g), t0, 39.99, &[], true, 0.0, &mut c).unwrap();
        assert!(!hit.graze && g(hit.t) <= 0.0 && g(hit.t.next_down()) > 0.0);
        assert!((hit.t - t0 - 1.8e-9 / 214.5).abs() < 1e-14);
    }

    #[test]
    fn the_ends_of_a_bracket_are_evaluated_once() {
        // What the scan evaluated at a piece's ends is handed to the refinement, which used to
        // evaluate both again (a tenth of the README run's evaluations).
        let seen = std::cell::RefCell::new(Vec::new());
        let f = |x: f64| {
            seen.borrow_mut().push(x);
            0.3 - x
        };
        // Newton's steps evaluate the function with its derivative: not counted here.
        let fd = |x: f64| (0.3 - x, -1.0);
        let times = |x: f64| seen.borrow().iter().filter(|&&y| y == x).count();
        let mut c = Counter::default();
        let zeros = sign_changes(Fun::with(&f, &fd), 0.0, 1.0, &[], 0.0, &mut c);
        assert_eq!(zeros.as_slice(), &[0.3]);
        assert_eq!((times(0.0), times(1.0)), (1, 1));
        seen.borrow_mut().clear();
        let hit = first_violation(Fun::plain(&f), 0.0, 1.0, &[0.2], true, 0.0, &mut c).unwrap();
        assert!(f(hit.t) <= 0.0 && f(hit.t.next_down()) > 0.0);
        assert_eq!((times(0.2), times(1.0)), (1, 1));
    }

    #[test]
    fn sign_changes_finds_every_root() {
        let mut c = Counter::default();
        let f = |x: f64| (x - 0.3) * (x - 0.7);
        let r = sign_changes(Fun::plain(&f), 0.0, 1.0, &[0.5], 0.0, &mut c);
        assert_eq!(r.len(), 2);
        assert!((r[0] - 0.3).abs() < 1e-15 && (r[1] - 0.7).abs() < 1e-15);
    }
}
