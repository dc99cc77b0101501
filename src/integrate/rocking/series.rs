//! Truncated Taylor series in local time tau = t - t0, built order by order (automatic
//! differentiation of the equations of motion), and what the rocking engine asks of them: the
//! value and integral at a point, the sign just after tau = 0 (the "next derivative" rule for
//! ties), a step size that keeps the truncation at round-off, and the first root in a step,
//! located by Bernstein subdivision so that no sign change is missed.
//!
//! Why series: the rocking equations have closed forms only for piecewise-constant ground
//! acceleration; a record is piecewise linear and a sine is a sine. A series of order
//! [`ORDER`] reproduces every closed form to round-off (tests/suite/rocking.rs checks them), gives
//! dense output for free (the polynomial is the solution between events), and turns every event
//! into a polynomial root.

/// Order of the series. With steps chosen by [`step_size`], the first neglected term is below
/// round-off of the state; order 24 lets steps span a good part of a rocking half-cycle.
pub const ORDER: usize = 24;

/// Coefficients c_0..c_ORDER of a series in tau.
pub type Coeffs = [f64; ORDER + 1];

/// A series of zeros.
pub const ZERO: Coeffs = [0.0; ORDER + 1];

/// Coefficient k of the product a b.
pub fn mul_at(a: &[f64], b: &[f64], k: usize) -> f64 {
    (0..=k).map(|j| a[j] * b[k - j]).sum()
}

/// Coefficient k of q = a / b, given q's coefficients below k.
pub fn div_at(a: &[f64], b: &[f64], q: &[f64], k: usize) -> f64 {
    let lower: f64 = (1..=k).map(|j| b[j] * q[k - j]).sum();
    (a[k] - lower) / b[0]
}

/// Coefficient k of sin x and cos x, given x up to k and sin, cos below k.
pub fn sin_cos_at(x: &[f64], s: &mut [f64], c: &mut [f64], k: usize) {
    if k == 0 {
        let (sn, cs) = x[0].sin_cos();
        s[0] = sn;
        c[0] = cs;
        return;
    }
    let (mut ds, mut dc) = (0.0, 0.0);
    for j in 1..=k {
        let jx = j as f64 * x[j];
        ds += jx * c[k - j];
        dc += jx * s[k - j];
    }
    s[k] = ds / k as f64;
    c[k] = -dc / k as f64;
}

/// The series' value at tau (Horner).
pub fn eval(c: &[f64], tau: f64) -> f64 {
    c.iter().rev().fold(0.0, |acc, &x| acc * tau + x)
}

/// The series re-centred at x: the coefficients of c(x + s) in s (repeated synthetic
/// division; its constant term is Horner's value at x).
pub fn shifted(c: &Coeffs, x: f64) -> Coeffs {
    let mut b = *c;
    for i in 0..ORDER {
        for j in (i..ORDER).rev() {
            b[j] += x * b[j + 1];
        }
    }
    b
}

/// The series' derivative in tau.
pub fn derivative(c: &Coeffs) -> Coeffs {
    let mut d = ZERO;
    for k in 1..=ORDER {
        d[k - 1] = k as f64 * c[k];
    }
    d
}

/// The integral of the series from 0 to tau.
pub fn integral(c: &[f64], tau: f64) -> f64 {
    let mut acc = 0.0;
    for k in (0..c.len()).rev() {
        acc = acc * tau + c[k] / (k + 1) as f64;
    }
    acc * tau
}

/// Product series (all coefficients).
pub fn product(a: &Coeffs, b: &Coeffs) -> Coeffs {
    let mut p = ZERO;
    for (k, x) in p.iter_mut().enumerate() {
        *x = mul_at(a, b, k);
    }
    p
}

/// The constant series x.
pub fn constant(x: f64) -> Coeffs {
    let mut c = ZERO;
    c[0] = x;
    c
}

/// c + x.
pub fn plus(c: &Coeffs, x: f64) -> Coeffs {
    let mut out = *c;
    out[0] += x;
    out
}

/// k c.
pub fn scaled(c: &Coeffs, k: f64) -> Coeffs {
    let mut out = *c;
    out.iter_mut().for_each(|x| *x *= k);
    out
}

/// a + k b.
pub fn add(a: &Coeffs, b: &Coeffs, k: f64) -> Coeffs {
    let mut out = *a;
    add_to(&mut out, b, k);
    out
}

/// a += k b.
pub fn add_to(a: &mut Coeffs, b: &Coeffs, k: f64) {
    a.iter_mut().zip(b).for_each(|(x, y)| *x += k * y);
}

/// Ties: a coefficient c_k counts as zero when |c_k| T^k is below `TIE` times the quantity's
/// scale (T the body's time scale). What is left of a function at its own event is round-off
/// of its scale (some 1e-16: events are located to the last bit of a step, and values that must
/// be zero are set to zero), and the ground acceleration read at a rounded instant differs by
/// its rate times an ulp of the time (below 1e-13 g at t = 1000 s); 1e-11 keeps clear of both,
/// while a real value within 1e-11 of a threshold changes the answer by a time shift of 1e-11
/// T at most.
pub const TIE: f64 = 1e-11;

/// The sign of a series just after tau = 0: that of its first coefficient that is not zero in
/// the sense of [`TIE`] (`scale` the quantity's size, `time_s` the time scale). Zero when every
/// coefficient is.
pub fn sign_after(c: &[f64], scale: f64, time_s: f64) -> i8 {
    leading(c, scale, time_s).map_or(0, |(_, x)| if x > 0.0 { 1 } else { -1 })
}

/// Index and value of the first coefficient that is not zero in the sense of [`TIE`]. The last
/// one, c_N, does not decide: a series built from a derivative lacks it ([`derivative`] has no
/// c_{N+1} to take it from), so where the conditions of a motion hold with equality for good
/// (a joint exactly at its friction limit as the motion goes on) c_N is the truncation of one
/// term against the whole of another, of any sign and size, and not the motion's.
pub fn leading(c: &[f64], scale: f64, time_s: f64) -> Option<(usize, f64)> {
    let mut tk = 1.0;
    for (k, &x) in c.iter().take(ORDER).enumerate() {
        if x.abs() * tk > TIE * scale {
            return Some((k, x));
        }
        tk *= time_s;
    }
    None
}

/// A step [0, h] over which every series in `series` (each with its scale) is accurate to
/// round-off: the last two terms, c_{N-1} h^{N-1} and c_N h^N, stay below 1e-17 of the scale
/// (Jorba and Zou 2005). Infinite when the series are polynomials of lower degree.
pub fn step_size(series: &[(&Coeffs, f64)]) -> f64 {
    const EPS: f64 = 1e-17;
    let mut h = f64::INFINITY;
    for &(c, scale) in series {
        for k in [ORDER - 1, ORDER] {
            let x = c[k].abs() / scale;
            if x > 0.0 {
                h = h.min((EPS / x).powf(1.0 / k as f64));
            }
        }
    }
    h
}

/// The first tau in (0, h] where a function that is positive just after 0 comes down to zero:
/// its leading coefficients that are zero in the sense of [`TIE`] are dropped (f = tau^m q,
/// the decision that started the mode made q(0) > 0), and q's first root is located by
/// Bernstein subdivision, then refined to round-off. A function that is negative just after 0
/// gives 0 (an event at once); one that is zero throughout gives none.
pub fn first_fall(c: &[f64], scale: f64, time_s: f64, h: f64) -> Option<f64> {
    let (m, lead) = leading(c, scale, time_s)?;
    if lead < 0.0 {
        return Some(0.0);
    }
    let q = &c[m..];
    first_root(q, h, scale / time_s.powi(m as i32))
}

/// The first tau in (0, h] at which q changes sign or touches zero (q(0) > 0), to round-off.
fn first_root(q: &[f64], h: f64, scale: f64) -> Option<f64> {
    let n = q.len() - 1;
    // Power coefficients on s in [0, 1] (tau = h s), then Bernstein coefficients.
    let mut a = vec![0.0; n + 1];
    let mut hk = 1.0;
    for k in 0..=n {
        a[k] = q[k] * hk;
        hk *= h;
    }
    // Most conditions stay far from their limits: when q(0) exceeds every other term's
    // largest size over the step together, q has no root in it.
    let rest: f64 = a[1..].iter().map(|x| x.abs()).sum();
    if a[0] > rest * (1.0 + 1e-12) {
        return None;
    }
    let mut b = vec![0.0; n + 1];
    for (i, bi) in b.iter_mut().enumerate() {
        // b_i = sum_{j <= i} C(i, j) / C(n, j) a_j
        let mut ratio = 1.0; // C(i, j) / C(n, j) at j = 0
        let mut sum = 0.0;
        for (j, aj) in a.iter().enumerate().take(i + 1) {
            sum += ratio * aj;
            ratio *= (i - j) as f64 / (n - j) as f64;
        }
        *bi = sum;
    }
    let touch = scale * 1e-14;
    let value = |s: f64| eval(q, s * h);
    // Depth-first over the subintervals, left first: the first root is in the leftmost
    // subinterval whose Bernstein coefficients change sign.
    let mut stack = vec![(0.0f64, 1.0f64, b, 0u32)];
    while let Some((lo, hi, b, depth)) = stack.pop() {
        let changes = b
            .windows(2)
            .filter(|w| (w[0] > 0.0) != (w[1] > 0.0))
            .count();
        if b.iter().all(|&x| x > touch) {
            continue;
        }
        let (first, last) = (b[0], b[n]);
        if changes == 1 && first > 0.0 && last <= 0.0 {
            return Some(h * refine(&value, lo, hi));
        }
        if depth >= 60 || hi - lo < 1e-15 {
            // A touching zero (a double root within round-off): an event where q meets 0.
            if value(0.5 * (lo + hi)).abs() <= touch || first <= 0.0 {
                return Some(h * lo.max(f64::MIN_POSITIVE));
            }
            continue;
        }
        let (left, right) = de_casteljau_halves(&b);
        let mid = 0.5 * (lo + hi);
        stack.push((mid, hi, right, depth + 1));
        stack.push((lo, mid, left, depth + 1));
    }
    None
}

/// The Bernstein coefficients of the two halves of an interval.
fn de_casteljau_halves(b: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = b.len() - 1;
    let mut work = b.to_vec();
    let mut left = Vec::with_capacity(n + 1);
    let mut right = vec![0.0; n + 1];
    left.push(work[0]);
    right[n] = work[n];
    for r in 1..=n {
        for i in 0..=n - r {
            work[i] = 0.5 * (work[i] + work[i + 1]);
        }
        left.push(work[0]);
        right[n - r] = work[n - r];
    }
    (left, right)
}

/// The crossing of a function positive at lo and not positive at hi, by bisection to the last
/// bit (the bracket keeps f(lo) > 0 >= f(hi), so the answer is the first s where f <= 0, to
/// round-off).
fn refine(f: &dyn Fn(f64) -> f64, mut lo: f64, mut hi: f64) -> f64 {
    if f(hi) > 0.0 {
        // The Bernstein bound said one sign change; round-off in the conversion can leave the
        // end value just positive: the crossing is at the end.
        return hi;
    }
    loop {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            return hi;
        }
        if f(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// exp, sin and cos from their recurrences equal their Taylor coefficients.
    #[test]
    fn recurrences_give_the_taylor_coefficients() {
        let mut x = ZERO;
        x[0] = 0.3;
        x[1] = 2.0; // x = 0.3 + 2 tau
        let (mut s, mut c) = (ZERO, ZERO);
        for k in 0..=ORDER {
            sin_cos_at(&x, &mut s, &mut c, k);
        }
        for tau in [0.0, 0.01, 0.1] {
            assert!((eval(&s, tau) - (0.3 + 2.0 * tau).sin()).abs() < 1e-15);
            assert!((eval(&c, tau) - (0.3 + 2.0 * tau).cos()).abs() < 1e-15);
        }
        // q = 1 / (1 - tau) = sum tau^k.
        let mut one = ZERO;
        one[0] = 1.0;
        let mut b = ZERO;
        b[0] = 1.0;
        b[1] = -1.0;
        let mut q = ZERO;
        for k in 0..=ORDER {
            q[k] = div_at(&one, &b, &q, k);
        }
        assert!(q.iter().all(|&x| (x - 1.0).abs() < 1e-15));
        assert!((integral(&q, 0.5) - 2f64.ln()).abs() < 1e-8);
    }

    /// The first root of (tau - 0.3)(tau - 0.31)(tau - 2), to the last bits, and none where
    /// a function only comes near zero.
    #[test]
    fn a_shifted_series_is_the_same_function_from_there() {
        let mut c = ZERO;
        for (k, x) in c.iter_mut().enumerate().take(6) {
            *x = [2.0, -3.0, 0.5, 4.0, -1.0, 0.25][k];
        }
        let x = 0.3;
        let b = shifted(&c, x);
        for s in [0.0, 0.1, 0.7] {
            assert!((eval(&b, s) - eval(&c, x + s)).abs() < 1e-14, "at {s}");
        }
        assert_eq!(b[0], eval(&c, x));
        assert_eq!(b[5], 0.25);
    }

    #[test]
    fn first_root_is_the_first_and_exact() {
        let mut c = ZERO;
        // (tau - 0.3)(tau - 0.31)(tau - 2) = tau^3 - 2.61 tau^2 + 1.313 tau - 0.186; negated so
        // that it is positive at 0.
        c[0] = 0.186;
        c[1] = -1.313;
        c[2] = 2.61;
        c[3] = -1.0;
        let r = first_fall(&c, 1.0, 1.0, 1.0).unwrap();
        assert!((r - 0.3).abs() < 1e-15, "{r}");
        // (tau - 0.5)^2 + 1e-6: no root.
        let mut d = ZERO;
        d[0] = 0.25 + 1e-6;
        d[1] = -1.0;
        d[2] = 1.0;
        assert_eq!(first_fall(&d, 1.0, 1.0, 1.0), None);
        // A leading zero coefficient (a function that starts at zero and rises) is not a root
        // at 0: tau (0.7 - tau) falls to zero at 0.7.
        let mut e = ZERO;
        e[1] = 0.7;
        e[2] = -1.0;
        let r = first_fall(&e, 1.0, 1.0, 1.0).unwrap();
        assert!((r - 0.7).abs() < 1e-15, "{r}");
    }
}
