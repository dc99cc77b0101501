//! Exact rational numbers: the wall's geometry, masses, loads and friction capacities, and every
//! mode decision of the event-driven integrator are computed with them.
//!
//! Why: a joint exactly at its friction limit (the paper's uniform-friction wall) is a tie that
//! floating point decides at random; in exact arithmetic it is an equality. Inputs written as
//! decimals (`0.3`, `1.2`) are read back to the decimal the user wrote ([`Q::from_decimal`]), so
//! `0.1 + 0.2 == 0.3` holds here.
//!
//! `Q` keeps numerator and denominator in `i128` while they fit and moves to big integers when an
//! operation would overflow, so results are always exact; the representation is canonical
//! (reduced, positive denominator, small whenever it fits), so `==` and `Hash` are structural.

use num_bigint::{BigInt, BigUint, Sign};
use num_integer::Integer;
use num_traits::{One, Signed, ToPrimitive, Zero};
use std::borrow::Cow;
use std::cmp::Ordering;
use std::fmt;
use std::ops::{Add, Div, Mul, Neg, Sub};

/// An exact rational number.
#[derive(Clone, PartialEq, Eq, Hash)]
pub struct Q(Repr);

#[derive(Clone, PartialEq, Eq, Hash)]
enum Repr {
    /// Reduced, denominator > 0, numerator != i128::MIN.
    Small(i128, i128),
    /// Reduced, denominator > 0, does not fit `Small`.
    Big(Box<(BigInt, BigInt)>),
}

/// Stein's binary gcd, one function for the two widths it runs in (64 bits when both numbers
/// fit, else 128).
fn binary_gcd<T: num_traits::PrimInt>(mut a: T, mut b: T) -> T {
    if a.is_zero() {
        return b;
    }
    if b.is_zero() {
        return a;
    }
    let shift = (a | b).trailing_zeros() as usize;
    a = a >> a.trailing_zeros() as usize;
    loop {
        b = b >> b.trailing_zeros() as usize;
        if a > b {
            std::mem::swap(&mut a, &mut b);
        }
        b = b - a;
        if b.is_zero() {
            return a << shift;
        }
    }
}

/// n / g for a divisor g > 0 of n. Why not `/`: 128-bit division is a library call many times
/// slower than the 64-bit instruction, and the numbers here nearly always fit 64 bits.
pub(crate) fn div(n: i128, g: i128) -> i128 {
    match (i64::try_from(n), i64::try_from(g)) {
        (Ok(n), Ok(g)) => (n / g) as i128,
        _ => n / g,
    }
}

/// The greatest common divisor, binary (no 128-bit division), in 64 bits when both fit.
pub(crate) fn gcd_i128(a: i128, b: i128) -> i128 {
    // Callers never pass i128::MIN, so unsigned_abs fits and the result fits i128.
    let (a, b) = (a.unsigned_abs(), b.unsigned_abs());
    match (u64::try_from(a), u64::try_from(b)) {
        (Ok(a), Ok(b)) => binary_gcd(a, b) as i128,
        _ => binary_gcd(a, b) as i128,
    }
}

/// The greatest common divisor of two big integers (not both zero), as its power of two and
/// its odd part. num-bigint's own is Stein's algorithm, which shifts the larger number once per
/// bit of it even where the other's odd part is 1: the velocities of a long lossy impact chain
/// are dyadic numbers of thousands of bits (each collision of equal blocks with e = 1/2 adds
/// two), and reducing them that way took 80 % of such a run. Here the twos come off at once, an
/// odd part 1 ends it, and Euclid's steps shrink the larger while the two differ in size (one
/// division each, linear in the larger), leaving Stein's algorithm only operands of like size.
fn gcd_big(a: &BigInt, b: &BigInt) -> (u64, BigInt) {
    let (a, b) = (a.magnitude(), b.magnitude());
    let twos = |x: &BigUint| x.trailing_zeros().unwrap_or(u64::MAX);
    let shift = twos(a).min(twos(b));
    let odd = |x: &BigUint| {
        let t = twos(x);
        if t == u64::MAX {
            BigUint::zero()
        } else {
            x >> t
        }
    };
    let (mut a, mut b) = (odd(a), odd(b));
    loop {
        if a < b {
            std::mem::swap(&mut a, &mut b);
        }
        if b.is_zero() || b.is_one() {
            let g = if b.is_zero() { a } else { b };
            return (shift, BigInt::from(g));
        }
        if a.bits() <= b.bits() + 64 {
            return (shift, BigInt::from(lehmer_gcd(a, b)));
        }
        a %= &b;
    }
}

/// The gcd by Lehmer's algorithm (Knuth, TAOCP vol. 2, 4.5.2, Algorithm L), for operands of
/// like size: Euclid's quotients are found from the leading 64 bits of both, in machine words,
/// as long as they are certain, and applied to the whole numbers at once through their
/// cofactors. Stein's binary algorithm (num-integer's) shifts the whole numbers once per bit
/// they lose: it took half of an uplift check's time, in the exact check of each basis, where
/// sampled frictions make fractions of hundreds of bits.
fn lehmer_gcd(mut a: BigUint, mut b: BigUint) -> BigUint {
    loop {
        if a < b {
            std::mem::swap(&mut a, &mut b);
        }
        if b.is_zero() {
            return a;
        }
        if let (Some(x), Some(y)) = (a.to_u128(), b.to_u128()) {
            return BigUint::from(binary_gcd(x, y));
        }
        // The leading 64 bits of a and the same bits of b: a in [2^63, 2^64), b below.
        let shift = a.bits() - 64;
        let lead = |v: &BigUint| i128::from((v >> shift).to_u64().expect("at most 64 bits"));
        let (mut x, mut y) = (lead(&a), lead(&b));
        // Cofactors: the leading parts are (x, y) = (ca x0 + cb y0, cc x0 + cd y0), each pair
        // of opposite signs (or a zero).
        let (mut ca, mut cb, mut cc, mut cd) = (1_i128, 0_i128, 0_i128, 1_i128);
        // The quotient is certain where both ends of the range the whole numbers' ratio can
        // take give it (step L2); x + ca, y + cc, x + cb, y + cd stay within [0, 2^64].
        while y + cc != 0 && y + cd != 0 {
            let q = quotient(x + ca, y + cc);
            if q != quotient(x + cb, y + cd) {
                break;
            }
            (ca, cc) = (cc, ca - q * cc);
            (cb, cd) = (cd, cb - q * cd);
            (x, y) = (y, x - q * y);
        }
        if cb == 0 {
            // Not one quotient certain: one step of Euclid on the whole numbers.
            let r = &a % &b;
            a = std::mem::replace(&mut b, r);
        } else {
            let combine = |p: i128, q: i128| {
                let (pa, qb) = (&a * p.unsigned_abs(), &b * q.unsigned_abs());
                match (p < 0) == (q < 0) {
                    true => pa + qb,
                    false if pa >= qb => pa - qb,
                    false => qb - pa,
                }
            };
            (a, b) = (combine(ca, cb), combine(cc, cd));
        }
    }
}

/// floor(n / d) for 0 <= n <= 2^64 and 0 < d <= 2^64, in a 64-bit division where both fit
/// (a 128-bit one is a library call, and took a third of Lehmer's time).
fn quotient(n: i128, d: i128) -> i128 {
    match (u64::try_from(n), u64::try_from(d)) {
        (Ok(n), Ok(d)) => i128::from(n / d),
        _ => n / d,
    }
}

impl Q {
    /// One word that equal numbers share (the representation is canonical), for hashing many
    /// numbers at once: a decision memo hashes dozens per lookup, and feeding each through the
    /// hasher cost more than the rest of the lookup.
    pub fn hash_word(&self) -> u64 {
        let fold = |x: i128| (x as u64) ^ ((x >> 64) as u64).rotate_left(29);
        match &self.0 {
            Repr::Small(n, d) => fold(*n) ^ fold(*d).rotate_left(32),
            Repr::Big(b) => {
                use std::hash::{Hash, Hasher};
                let mut h = std::collections::hash_map::DefaultHasher::new();
                b.hash(&mut h);
                h.finish()
            }
        }
    }

    /// Zero.
    pub fn zero() -> Q {
        Q(Repr::Small(0, 1))
    }

    /// One.
    pub fn one() -> Q {
        Q(Repr::Small(1, 1))
    }

    /// An integer.
    pub fn int(n: i64) -> Q {
        Q(Repr::Small(n as i128, 1))
    }

    /// The fraction `n / d` (d != 0).
    pub fn frac(n: i128, d: i128) -> Q {
        assert!(d != 0, "Q::frac with zero denominator");
        Q::from_parts(n, d)
    }

    fn from_parts(n: i128, d: i128) -> Q {
        if n == i128::MIN || d == i128::MIN {
            return Q::from_big(BigInt::from(n), BigInt::from(d));
        }
        let (n, d) = if d < 0 { (-n, -d) } else { (n, d) };
        if d == 1 {
            return Q(Repr::Small(n, 1));
        }
        let g = gcd_i128(n, d);
        if g <= 1 {
            return Q(Repr::Small(n, d));
        }
        Q(Repr::Small(div(n, g), div(d, g)))
    }

    /// n / d for big integers, d nonzero.
    pub(crate) fn from_big(n: BigInt, d: BigInt) -> Q {
        let (n, d) = if d.is_negative() { (-n, -d) } else { (n, d) };
        let (twos, odd) = gcd_big(&n, &d);
        let (n, d) = (n >> twos, d >> twos);
        let (n, d) = if odd.is_one() {
            (n, d)
        } else {
            (n / &odd, d / &odd)
        };
        Q::from_reduced(n, d)
    }

    /// n / d for n and d > 0 already without a common factor: no gcd to take (a negation or a
    /// reciprocal of big numbers took a gcd of their thousands of bits that could only be 1).
    fn from_reduced(n: BigInt, d: BigInt) -> Q {
        match (n.to_i128(), d.to_i128()) {
            (Some(a), Some(b)) if a != i128::MIN => Q(Repr::Small(a, b)),
            _ => Q(Repr::Big(Box::new((n, d)))),
        }
    }

    /// Numerator and denominator as big integers, borrowed where they are big already: the
    /// numbers of a long lossy impact chain run to thousands of bits, and copying both operands
    /// of every operation cost a third of such a run.
    pub(crate) fn parts(&self) -> (Cow<'_, BigInt>, Cow<'_, BigInt>) {
        match &self.0 {
            Repr::Small(n, d) => (Cow::Owned(BigInt::from(*n)), Cow::Owned(BigInt::from(*d))),
            Repr::Big(b) => (Cow::Borrowed(&b.0), Cow::Borrowed(&b.1)),
        }
    }

    /// The exact value of a binary floating-point number; `None` for NaN or infinity.
    pub fn from_f64_exact(x: f64) -> Option<Q> {
        if !x.is_finite() {
            return None;
        }
        if x == 0.0 {
            return Some(Q::zero());
        }
        let bits = x.to_bits();
        let negative = bits >> 63 == 1;
        let exp_bits = ((bits >> 52) & 0x7ff) as i32;
        let frac = bits & ((1u64 << 52) - 1);
        let (mut mantissa, mut exp) = if exp_bits == 0 {
            (frac, -1074)
        } else {
            (frac | (1u64 << 52), exp_bits - 1075)
        };
        let tz = mantissa.trailing_zeros() as i32;
        if exp < 0 {
            let s = tz.min(-exp);
            mantissa >>= s;
            exp += s;
        }
        let m = if negative {
            -(mantissa as i128)
        } else {
            mantissa as i128
        };
        Some(if exp >= 0 {
            if exp <= 70 {
                Q(Repr::Small(m << exp, 1))
            } else {
                Q::from_big(BigInt::from(m) << exp as usize, BigInt::one())
            }
        } else if -exp <= 126 {
            Q(Repr::Small(m, 1i128 << (-exp)))
        } else {
            Q::from_big(BigInt::from(m), BigInt::one() << (-exp) as usize)
        })
    }

    /// The decimal a person meant when they wrote `x`: the shortest decimal that reads back as
    /// `x` (so `0.3` gives 3/10, not the binary value nearest to it). `None` for NaN or infinity.
    pub fn from_decimal(x: f64) -> Option<Q> {
        if !x.is_finite() {
            return None;
        }
        Q::parse_decimal(&format!("{x:e}"))
    }

    /// Parses a decimal such as `-12.5`, `.1181069E-02` or `3e-1` exactly.
    pub fn parse_decimal(s: &str) -> Option<Q> {
        let s = s.trim();
        let (mantissa, exponent) = match s.find(['e', 'E']) {
            Some(i) => (&s[..i], s[i + 1..].parse::<i32>().ok()?),
            None => (s, 0),
        };
        let (negative, digits) = match mantissa.as_bytes().first()? {
            b'-' => (true, &mantissa[1..]),
            b'+' => (false, &mantissa[1..]),
            _ => (false, mantissa),
        };
        let (int_part, frac_part) = match digits.find('.') {
            Some(i) => (&digits[..i], &digits[i + 1..]),
            None => (digits, ""),
        };
        if int_part.is_empty() && frac_part.is_empty() {
            return None;
        }
        if !int_part
            .bytes()
            .chain(frac_part.bytes())
            .all(|c| c.is_ascii_digit())
        {
            return None;
        }
        let all: String = format!("{int_part}{frac_part}");
        let mut n: BigInt = all.parse().ok()?;
        if negative {
            n = -n;
        }
        let scale = exponent - frac_part.len() as i32;
        let ten = BigInt::from(10);
        Some(if scale >= 0 {
            Q::from_big(n * num_traits::pow(ten, scale as usize), BigInt::one())
        } else {
            Q::from_big(n, num_traits::pow(ten, (-scale) as usize))
        })
    }

    /// Numerator and denominator when both fit in `i128` (the common case), else `None`.
    pub fn small_parts(&self) -> Option<(i128, i128)> {
        match &self.0 {
            Repr::Small(n, d) => Some((*n, *d)),
            Repr::Big(_) => None,
        }
    }

    /// Bits of its numerator and denominator together: the size its arithmetic costs.
    pub fn bits(&self) -> u64 {
        match &self.0 {
            Repr::Small(n, d) => {
                u64::from(128 - n.unsigned_abs().leading_zeros())
                    + u64::from(128 - d.leading_zeros())
            }
            Repr::Big(b) => b.0.bits() + b.1.bits(),
        }
    }

    /// The nearest number m 2^k with an integer m of at most `significant` bits (ties away from
    /// zero): for keeping a computation that would otherwise grow without end (a long chain of
    /// impacts) at a size, with a relative error of at most 2^-significant.
    pub fn rounded(&self, significant: u64) -> Q {
        if self.is_zero() {
            return Q::zero();
        }
        let (n, d) = self.parts();
        // |n / d| lies within a factor of two of 2^(bits n - bits d): start from the shift
        // that gives `significant` bits or one more, and take one more if it did.
        let mut shift = n.bits() as i64 - d.bits() as i64 - significant as i64;
        loop {
            let (num, den) = if shift < 0 {
                (n.as_ref() << (-shift) as usize, d.as_ref().clone())
            } else {
                (n.as_ref().clone(), d.as_ref() << shift as usize)
            };
            // Round half away from zero: (2 num + sign den) / (2 den), truncated.
            let two = BigInt::from(2);
            let m = (&two * &num + num.signum() * &den) / (&two * &den);
            if m.bits() > significant {
                shift += 1;
                continue;
            }
            return if shift < 0 {
                Q::from_big(m, BigInt::one() << (-shift) as usize)
            } else {
                Q::from_big(m << shift as usize, BigInt::one())
            };
        }
    }

    /// The nearest `f64` (round half to even).
    pub fn to_f64(&self) -> f64 {
        const EXACT: i128 = 1 << 53;
        match &self.0 {
            // Both fit 64 bits: one instruction each, where i128 to f64 is a library call.
            Repr::Small(n, d) if n.abs() <= EXACT && *d <= EXACT => {
                (*n as i64) as f64 / (*d as i64) as f64
            }
            _ => {
                let (n, d) = self.parts();
                big_ratio_to_f64(&n, &d)
            }
        }
    }

    /// True for zero.
    pub fn is_zero(&self) -> bool {
        matches!(self.0, Repr::Small(0, _))
    }

    /// The sign: -1, 0 or 1.
    pub fn signum(&self) -> i32 {
        match &self.0 {
            Repr::Small(n, _) => n.signum() as i32,
            Repr::Big(b) => match b.0.sign() {
                Sign::Minus => -1,
                Sign::NoSign => 0,
                Sign::Plus => 1,
            },
        }
    }

    /// True when strictly positive.
    pub fn is_positive(&self) -> bool {
        self.signum() > 0
    }

    /// True when strictly negative.
    pub fn is_negative(&self) -> bool {
        self.signum() < 0
    }

    /// Absolute value.
    pub fn abs(&self) -> Q {
        if self.is_negative() {
            -self
        } else {
            self.clone()
        }
    }

    /// The smaller of two values.
    pub fn min(self, other: Q) -> Q {
        if other < self {
            other
        } else {
            self
        }
    }

    /// The larger of two values.
    pub fn max(self, other: Q) -> Q {
        if other > self {
            other
        } else {
            self
        }
    }

    fn add_impl(&self, o: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            // Sums start from zero: nothing to reduce.
            if *a == 0 {
                return o.clone();
            }
            if *c == 0 {
                return self.clone();
            }
            if *b == *d {
                if let Some(n) = a.checked_add(*c) {
                    return Q::from_parts(n, *b);
                }
            } else {
                let g = gcd_i128(*b, *d);
                let (bg, dg) = (div(*b, g), div(*d, g));
                if let (Some(x), Some(y), Some(den)) =
                    (a.checked_mul(dg), c.checked_mul(bg), bg.checked_mul(*d))
                {
                    if let Some(n) = x.checked_add(y) {
                        return Q::from_parts(n, den);
                    }
                }
            }
        }
        let (a, b) = self.parts();
        let (c, d) = o.parts();
        // Over the least common denominator: a chain's dyadic denominators divide one another,
        // and their product would double the bits the reduction then takes off again.
        let (twos, odd) = gcd_big(&b, &d);
        let part = |x: &BigInt| {
            let x = x >> twos;
            if odd.is_one() {
                x
            } else {
                x / &odd
            }
        };
        let (bg, dg) = (part(&b), part(&d));
        Q::from_big(&*a * &dg + &*c * &bg, bg * &*d)
    }

    fn mul_impl(&self, o: &Q) -> Q {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            if *a == 0 || *c == 0 {
                return Q::zero();
            }
            let g1 = gcd_i128(*a, *d);
            let g2 = gcd_i128(*c, *b);
            if let (Some(n), Some(den)) = (
                div(*a, g1).checked_mul(div(*c, g2)),
                div(*b, g2).checked_mul(div(*d, g1)),
            ) {
                if n != i128::MIN {
                    return Q(Repr::Small(n, den));
                }
            }
        }
        let (a, b) = self.parts();
        let (c, d) = o.parts();
        if a.is_zero() || c.is_zero() {
            return Q::zero();
        }
        // Each numerator reduced against the other's denominator (Knuth, TAOCP vol. 2, 4.5.1):
        // the product is then reduced already, and a small factor against a big one makes
        // both gcds short, where the gcd of the two products ran over all their bits.
        let without = |x: &BigInt, (twos, odd): &(u64, BigInt)| {
            let x = x >> *twos;
            if odd.is_one() {
                x
            } else {
                x / odd
            }
        };
        let (ad, cb) = (gcd_big(&a, &d), gcd_big(&c, &b));
        Q::from_reduced(
            without(&a, &ad) * without(&c, &cb),
            without(&b, &cb) * without(&d, &ad),
        )
    }

    /// The reciprocal (panics on zero, which callers exclude).
    pub fn recip(&self) -> Q {
        match &self.0 {
            Repr::Small(n, d) => {
                assert!(*n != 0, "reciprocal of zero");
                Q::from_parts(*d, *n)
            }
            Repr::Big(b) if b.0.is_negative() => Q::from_reduced(-&b.1, -&b.0),
            Repr::Big(b) => Q::from_reduced(b.1.clone(), b.0.clone()),
        }
    }
}

fn big_ratio_to_f64(n: &BigInt, d: &BigInt) -> f64 {
    if n.is_zero() {
        return 0.0;
    }
    let negative = n.is_negative();
    let n = n.abs();
    // Scale so the integer quotient carries 54 or 55 bits: 53 for the mantissa, one to round.
    let mut shift = 54 + d.bits() as i64 - n.bits() as i64;
    let (num, den) = if shift >= 0 {
        (n << shift as usize, d.clone())
    } else {
        (n, d << (-shift) as usize)
    };
    let (mut q, r) = num.div_rem(&den);
    let mut sticky = !r.is_zero();
    if q.bits() > 54 {
        sticky |= q.bit(0);
        q >>= 1;
        shift -= 1;
    }
    let round = q.bit(0);
    q >>= 1;
    let mut m = q.to_u64().unwrap_or(u64::MAX);
    if round && (sticky || m & 1 == 1) {
        m += 1;
    }
    let value = scale_by_power_of_two(m as f64, 1 - shift);
    if negative {
        -value
    } else {
        value
    }
}

/// x * 2^e in steps that stay exact while the result is a normal number (powi alone under- or
/// overflows its intermediate for |e| > 1022).
fn scale_by_power_of_two(mut x: f64, mut e: i64) -> f64 {
    while e > 1000 {
        x *= 2f64.powi(1000);
        e -= 1000;
    }
    while e < -1000 {
        x *= 2f64.powi(-1000);
        e += 1000;
    }
    x * 2f64.powi(e as i32)
}

impl Ord for Q {
    fn cmp(&self, o: &Q) -> Ordering {
        if let (Repr::Small(a, b), Repr::Small(c, d)) = (&self.0, &o.0) {
            if b == d {
                return a.cmp(c);
            }
            if let (Some(x), Some(y)) = (a.checked_mul(*d), c.checked_mul(*b)) {
                return x.cmp(&y);
            }
        }
        let (a, b) = self.parts();
        let (c, d) = o.parts();
        (&*a * &*d).cmp(&(&*c * &*b))
    }
}

impl PartialOrd for Q {
    fn partial_cmp(&self, o: &Q) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

macro_rules! binop {
    ($tr:ident, $method:ident, $body:expr) => {
        impl $tr<&Q> for &Q {
            type Output = Q;
            fn $method(self, o: &Q) -> Q {
                let f: fn(&Q, &Q) -> Q = $body;
                f(self, o)
            }
        }
        impl $tr<Q> for Q {
            type Output = Q;
            fn $method(self, o: Q) -> Q {
                (&self).$method(&o)
            }
        }
        impl $tr<&Q> for Q {
            type Output = Q;
            fn $method(self, o: &Q) -> Q {
                (&self).$method(o)
            }
        }
        impl $tr<Q> for &Q {
            type Output = Q;
            fn $method(self, o: Q) -> Q {
                self.$method(&o)
            }
        }
    };
}

binop!(Add, add, |a, b| a.add_impl(b));
binop!(Sub, sub, |a, b| a.add_impl(&-b));
binop!(Mul, mul, |a, b| a.mul_impl(b));
binop!(Div, div, |a, b| a.mul_impl(&b.recip()));

impl Neg for &Q {
    type Output = Q;
    fn neg(self) -> Q {
        match &self.0 {
            Repr::Small(n, d) => Q(Repr::Small(-n, *d)),
            Repr::Big(b) => Q::from_reduced(-&b.0, b.1.clone()),
        }
    }
}

impl Neg for Q {
    type Output = Q;
    fn neg(self) -> Q {
        -&self
    }
}

impl std::iter::Sum for Q {
    /// Terms over the same denominator as the one before add their numerators, and the run is
    /// reduced once when it ends: a body's masses mostly share one denominator, and a sum that
    /// reduced after every addition took a gcd per block.
    fn sum<I: Iterator<Item = Q>>(iter: I) -> Q {
        let mut total = Q::zero();
        // The current run: its numerator, unreduced, and its denominator.
        let mut run: Option<(i128, i128)> = None;
        for q in iter {
            if let (Repr::Small(n, d), Some((acc, den))) = (&q.0, &mut run) {
                if d == den {
                    if let Some(sum) = acc.checked_add(*n) {
                        *acc = sum;
                        continue;
                    }
                }
            }
            if let Some((acc, den)) = run.take() {
                total = total + Q::from_parts(acc, den);
            }
            match q.0 {
                Repr::Small(n, d) => run = Some((n, d)),
                Repr::Big(_) => total = total + q,
            }
        }
        match run {
            Some((acc, den)) => total + Q::from_parts(acc, den),
            None => total,
        }
    }
}

impl fmt::Debug for Q {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match &self.0 {
            Repr::Small(n, 1) => write!(f, "{n}"),
            Repr::Small(n, d) => write!(f, "{n}/{d}"),
            Repr::Big(b) => write!(f, "{}/{}", b.0, b.1),
        }
    }
}

impl fmt::Display for Q {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.to_f64())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    impl Q {
        fn big_parts(&self) -> (BigInt, BigInt) {
            let (n, d) = self.parts();
            (n.into_owned(), d.into_owned())
        }
    }

    #[test]
    fn rounding_keeps_the_bits_asked_for_and_the_nearest_value() {
        // 1/3 to 64 bits: a dyadic within 2^-64 of it, relative.
        for x in [
            Q::frac(1, 3),
            Q::frac(-1, 3),
            Q::frac(22, 7) * Q::frac(1, 1 << 70),
        ] {
            let r = x.rounded(64);
            let err = ((&r - &x) / &x).abs();
            assert!(err <= Q::frac(1, 1 << 64), "{x:?} -> {r:?}");
            assert_eq!(r.signum(), x.signum());
            let (_, d) = r.big_parts();
            assert_eq!(
                d.clone() & (d - 1u8),
                BigInt::zero(),
                "a power of two below"
            );
        }
        // A number of fewer bits comes back as it was.
        assert_eq!(Q::frac(3, 8).rounded(64), Q::frac(3, 8));
        assert_eq!(Q::int(-5).rounded(3), Q::int(-5));
        assert_eq!(Q::zero().rounded(8), Q::zero());
        // Ties away from zero: 5 to 2 bits is 6, -5 is -6.
        assert_eq!(Q::int(5).rounded(2), Q::int(6));
        assert_eq!(Q::int(-5).rounded(2), Q::int(-6));
        assert!(Q::frac(1, 3).bits() == 3 && Q::frac(1, 3).rounded(200).bits() > 200);
    }

    /// Numerators and denominators of every size that matters: zero and small values, values
    /// whose products overflow 64 bits, and values whose products overflow 128 bits.
    fn part() -> impl Strategy<Value = i128> {
        prop_oneof![
            Just(0i128),
            -30i128..30,
            (-(1i128 << 62))..(1i128 << 62),
            (-(1i128 << 120))..(1i128 << 120),
        ]
    }

    fn rational() -> impl Strategy<Value = Q> {
        (
            part(),
            part().prop_filter("non-zero denominator", |d| *d != 0),
        )
            .prop_map(|(n, d)| Q::frac(n, d))
    }

    /// `rational()`'s values and fractions of up to 608 bits over up to 288 with a common
    /// factor taken out, of either sign, and their products with small ones.
    fn operand() -> impl Strategy<Value = Q> {
        let big = (
            proptest::collection::vec(any::<u32>(), 1..20),
            proptest::collection::vec(any::<u32>(), 0..10),
            any::<bool>(),
        )
            .prop_map(|(n, d, negative)| {
                let n = BigInt::from(BigUint::new(n));
                let d = BigInt::from(BigUint::new(d) + 1u32);
                Q::from_big(if negative { -n } else { n }, d)
            });
        prop_oneof![
            rational(),
            big.clone(),
            (big, -30i128..30).prop_map(|(q, k)| q * Q::frac(k, 7))
        ]
    }

    /// Reduced, positive denominator, in 128 bits whenever it fits: what `==` and `Hash` need.
    fn canonical(q: &Q) -> bool {
        let (n, d) = q.big_parts();
        let fits = n.to_i128().is_some_and(|n| n != i128::MIN) && d.to_i128().is_some();
        d.is_positive() && n.gcd(&d).is_one() && fits == matches!(q.0, Repr::Small(..))
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 5000, failure_persistence: None, ..Default::default() })]

        /// The reduction's gcd against num-bigint's, over operands of very different sizes
        /// and with many factors of two (the shape of a long lossy impact chain's velocities).
        #[test]
        fn gcd_big_agrees_with_num_bigint(
            a in proptest::collection::vec(any::<u32>(), 0..80),
            b in proptest::collection::vec(any::<u32>(), 0..6),
            common in 1u32..,
            (twos_a, twos_b) in (0usize..400, 0usize..400),
            negative in any::<bool>(),
        ) {
            let a = BigInt::from(BigUint::new(a) * common) << twos_a;
            let a = if negative { -a } else { a };
            let b = BigInt::from((BigUint::new(b) + 1u32) * common) << twos_b;
            let (twos, odd) = gcd_big(&a, &b);
            prop_assert_eq!(odd << twos, a.gcd(&b));
        }

        /// Lehmer's gcd against num-bigint's over operands of like size, with a common factor
        /// of any size (nothing, words, or most of both), zero and one-word operands included.
        #[test]
        fn lehmer_gcd_agrees_with_num_bigint(
            a in proptest::collection::vec(any::<u32>(), 0..40),
            b in proptest::collection::vec(any::<u32>(), 0..40),
            common in proptest::collection::vec(any::<u32>(), 0..12),
        ) {
            let common = BigUint::new(common) + 1u32;
            let (a, b) = (BigUint::new(a) * &common, BigUint::new(b) * &common);
            prop_assert_eq!(lehmer_gcd(a.clone(), b.clone()), a.gcd(&b));
        }

        /// Every operation against big-integer arithmetic on numerators and denominators.
        #[test]
        fn arithmetic_is_exact_and_canonical(a in operand(), b in operand()) {
            let ((an, ad), (bn, bd)) = (a.big_parts(), b.big_parts());
            let is = |q: &Q, n: BigInt, d: BigInt| {
                let (qn, qd) = q.big_parts();
                canonical(q) && qn * d == n * qd
            };
            prop_assert!(canonical(&a) && canonical(&b));
            prop_assert!(is(&(&a + &b), &an * &bd + &bn * &ad, &ad * &bd));
            prop_assert!(is(&(&a - &b), &an * &bd - &bn * &ad, &ad * &bd));
            prop_assert!(is(&(&a * &b), &an * &bn, &ad * &bd));
            if !b.is_zero() {
                prop_assert!(is(&(&a / &b), &an * &bd, &ad * &bn));
            }
            prop_assert!(is(&-&a, -&an, ad.clone()));
            if !a.is_zero() {
                prop_assert!(is(&a.recip(), ad.clone(), an.clone()));
            }
            prop_assert_eq!(a.cmp(&b), (&an * &bd).cmp(&(&bn * &ad)));
            prop_assert_eq!(a == b, an == bn && ad == bd);
        }

        /// A sum equals the additions one by one, canonical: runs over one denominator (small
        /// numerators, and numerators whose running sum overflows), mixed with any rationals.
        #[test]
        fn sums_are_the_additions(
            terms in proptest::collection::vec(
                prop_oneof![rational(), part().prop_map(|n| Q::frac(n, 1000)), (-30i128..30).prop_map(|n| Q::frac(n, 7))],
                0..40,
            ),
        ) {
            let one_by_one = terms.iter().fold(Q::zero(), |a, b| &a + b);
            let sum: Q = terms.into_iter().sum();
            prop_assert!(canonical(&sum));
            prop_assert_eq!(sum, one_by_one);
        }
    }

    #[test]
    fn decimals_are_read_as_written() {
        let a = Q::from_decimal(0.1).unwrap() + Q::from_decimal(0.2).unwrap();
        assert_eq!(a, Q::from_decimal(0.3).unwrap());
        assert_eq!(
            Q::parse_decimal(".1181069E-02").unwrap(),
            Q::frac(1181069, 1_000_000_000)
        );
        assert_eq!(Q::parse_decimal("-12.5").unwrap(), Q::frac(-25, 2));
        assert!(Q::parse_decimal("1.2.3").is_none());
        assert!(Q::parse_decimal("").is_none());
        assert!(Q::from_decimal(f64::NAN).is_none());
    }

    #[test]
    fn binary_values_round_trip_exactly() {
        for x in [0.1, -2.5e-300, 1e300, 3.0, f64::MIN_POSITIVE, 0.0] {
            assert_eq!(Q::from_f64_exact(x).unwrap().to_f64(), x);
        }
    }

    #[test]
    fn conversion_to_f64_is_correctly_rounded() {
        // 1/3 and 2/3 and large ratios that force the big-integer path.
        assert_eq!(Q::frac(1, 3).to_f64(), 1.0 / 3.0);
        let big = Q::from_f64_exact(1e200).unwrap() / Q::from_f64_exact(3e-150).unwrap();
        assert_eq!(big.to_f64(), 1e200 / 3e-150);
        let third = Q::from_big(
            BigInt::from(10).pow(40),
            BigInt::from(3) * BigInt::from(10).pow(40),
        );
        assert_eq!(third.to_f64(), 1.0 / 3.0);
    }

    #[test]
    fn overflow_moves_to_big_integers_and_back() {
        let big = Q::from_parts(i128::MAX / 3, 7);
        let sq = &big * &big;
        let back = &sq / &big;
        assert_eq!(back, big);
        assert!(matches!(back.0, Repr::Small(..)));
        assert!(sq > big);
        assert_eq!((&sq - &sq), Q::zero());
    }

    #[test]
    fn ordering_and_arithmetic() {
        let a = Q::frac(3, 10);
        let b = Q::frac(981, 100);
        assert_eq!(&a * &b, Q::frac(2943, 1000));
        assert!(Q::frac(-1, 2) < Q::zero());
        assert_eq!(Q::frac(6, -4), Q::frac(-3, 2));
        assert_eq!(Q::frac(1, 2).min(Q::frac(1, 3)), Q::frac(1, 3));
    }
}
