//! Exact solutions of a basis's square systems by p-adic lifting (Dixon 1982), for the check of
//! a basis (`certify`). Why: on sampled friction the vertex and multipliers of a 315-row basis
//! are fractions of thousands of bits, and solving for them in rationals reduces every
//! intermediate value by a gcd of that size. Here B is scaled to integers, factorised once
//! modulo a prime of one word, and the solution's p-adic digits found one word at a time, each
//! from a solve in words and an update of an integer residual that stays as short as B's
//! entries; the fraction is rebuilt from enough digits (rational reconstruction, Wang 1981)
//! and kept only where B times it gives the right-hand side exactly, so a wrong guess of how
//! many digits suffice costs time, never exactness.

use super::factors::{Factors, Field};
use crate::exact::Q;
use num_bigint::{BigInt, Sign};
use num_integer::Integer;
use num_traits::{One, Signed, Zero};
use std::cmp::Ordering;
use std::collections::BTreeMap;

/// The Mersenne prime 2^61 - 1: a product of two residues reduces by a shift and an add.
const PRIME: u64 = (1 << 61) - 1;

/// A residue modulo [`PRIME`], in [0, PRIME).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
struct Residue(u64);

impl Residue {
    /// x mod PRIME for x < 2^64.
    fn reduce(x: u64) -> Residue {
        let folded = (x & PRIME) + (x >> 61);
        Residue(if folded >= PRIME {
            folded - PRIME
        } else {
            folded
        })
    }

    /// v mod PRIME: the words of |v| from the most significant, 2^64 being 8 modulo PRIME.
    fn of(v: &BigInt) -> Residue {
        let magnitude = v.magnitude().iter_u64_digits().rev().fold(0, |acc, word| {
            let high = Residue(acc).mul(&Residue(8)).0;
            Residue::reduce(high + Residue::reduce(word).0).0
        });
        let r = Residue(magnitude);
        match v.sign() {
            Sign::Minus => Residue::zero().sub(&r),
            _ => r,
        }
    }

    /// The inverse of a nonzero residue, by Fermat: x^(p - 2).
    fn inverse(self) -> Residue {
        let (mut base, mut exponent, mut result) = (self, PRIME - 2, Residue(1));
        while exponent > 0 {
            if exponent & 1 == 1 {
                result = result.mul(&base);
            }
            base = base.mul(&base);
            exponent >>= 1;
        }
        result
    }
}

impl Field for Residue {
    fn zero() -> Residue {
        Residue(0)
    }
    fn is_zero(&self) -> bool {
        self.0 == 0
    }
    fn sub(&self, other: &Residue) -> Residue {
        Residue(if self.0 >= other.0 {
            self.0 - other.0
        } else {
            self.0 + PRIME - other.0
        })
    }
    fn mul(&self, other: &Residue) -> Residue {
        let product = u128::from(self.0) * u128::from(other.0);
        let (low, high) = ((product as u64) & PRIME, (product >> 61) as u64);
        Residue::reduce(low + high)
    }
    fn recip(&self) -> Residue {
        self.inverse()
    }
}

/// A square rational B ready for p-adic solves in B and in B^T: M = S B with S the diagonal
/// of each row's least common denominator, and M's factors modulo [`PRIME`].
pub(super) struct Lifting {
    /// M's rows.
    rows: Vec<Vec<(usize, BigInt)>>,
    /// S's diagonal.
    scales: Vec<BigInt>,
    factors: Factors<Residue>,
    /// Hadamard's bound on |det M| in bits, from M's rows and from its columns: the sum of
    /// bounds on the lengths' bits (the widest entry's bits and those of the count). Whence
    /// how many digits suffice at worst: by Cramer's rule a solution's denominator is at most
    /// |det M| and its numerators the determinants of M with a column (M^T: a row) replaced by
    /// the right-hand side.
    hadamard_bits: [u64; 2],
}

impl Lifting {
    /// B given by its sparse rows; `None` where M is singular modulo the prime (B may be
    /// singular or not: the rational elimination must tell).
    pub(super) fn of(rows: &[BTreeMap<usize, Q>]) -> Option<Lifting> {
        let mut scales = Vec::with_capacity(rows.len());
        let mut integer_rows = Vec::with_capacity(rows.len());
        let mut columns = vec![(0, 0_usize); rows.len()];
        let length_bits =
            |widest: u64, count: usize| widest + u64::from(usize::BITS - count.leading_zeros());
        let mut row_bits = 0;
        for row in rows {
            let scale = row
                .values()
                .fold(BigInt::one(), |l, a| l.lcm(a.parts().1.as_ref()));
            let entries: Vec<(usize, BigInt)> = row
                .iter()
                .map(|(&k, a)| {
                    let (n, d) = a.parts();
                    (k, n.as_ref() * (&scale / d.as_ref()))
                })
                .collect();
            let widest = entries.iter().map(|(_, a)| a.bits()).max().unwrap_or(0);
            row_bits += length_bits(widest, entries.len());
            for (k, a) in &entries {
                columns[*k] = (columns[*k].0.max(a.bits()), columns[*k].1 + 1);
            }
            scales.push(scale);
            integer_rows.push(entries);
        }
        let residues = integer_rows
            .iter()
            .map(|row| {
                let residues = row.iter().map(|(k, a)| (*k, Residue::of(a)));
                // An entry that is a multiple of the prime is no entry to the elimination.
                residues.filter(|(_, a)| !a.is_zero()).collect()
            })
            .collect();
        let factors = Factors::of(residues)?;
        Some(Lifting {
            rows: integer_rows,
            scales,
            factors,
            hadamard_bits: [
                row_bits,
                columns.iter().map(|&(w, c)| length_bits(w, c)).sum(),
            ],
        })
    }

    /// z with B z = r: M z = S r, solved over the common denominator of S r; `None` where the
    /// lifting gave up (it cannot, by the bound, but a caller falls back all the same).
    pub(super) fn solve(&self, r: &[Q]) -> Option<Vec<Q>> {
        let (numerators, denominator) = self.solve_over(r)?;
        Some(
            numerators
                .into_iter()
                .map(|n| Q::from_big(n, denominator.clone()))
                .collect(),
        )
    }

    /// The signs of z with B z = r, without the gcd that would reduce each of its fractions
    /// (thousands of bits on sampled friction): all a check of a vertex needs.
    pub(super) fn signs(&self, r: &[Q]) -> Option<Vec<Ordering>> {
        let (numerators, denominator) = self.solve_over(r)?;
        let flip = denominator.is_negative();
        let signs = numerators.iter().map(|n| {
            let s = n.sign().cmp(&Sign::NoSign);
            if flip {
                s.reverse()
            } else {
                s
            }
        });
        Some(signs.collect())
    }

    /// z with B z = r as integer numerators over one denominator, not reduced.
    fn solve_over(&self, r: &[Q]) -> Option<(Vec<BigInt>, BigInt)> {
        let scaled: Vec<Q> = r
            .iter()
            .zip(&self.scales)
            .map(|(r, s)| r * &Q::from_big(s.clone(), BigInt::one()))
            .collect();
        let (rhs, common) = integers(&scaled);
        let (numerators, denominator) = self.lift(rhs, false)?;
        Some((numerators, denominator * common))
    }

    /// y with B^T y = d: M^T w = d and y = S w.
    pub(super) fn solve_transposed(&self, d: &[Q]) -> Option<Vec<Q>> {
        let (rhs, common) = integers(d);
        let (numerators, denominator) = self.lift(rhs, true)?;
        let denominator = denominator * common;
        Some(
            numerators
                .into_iter()
                .zip(&self.scales)
                .map(|(n, s)| Q::from_big(n * s, denominator.clone()))
                .collect(),
        )
    }

    /// The integer numerators and common denominator of u with M u = rhs (M^T where
    /// `transposed`): p-adic digits until their fraction, rebuilt, solves the system exactly.
    fn lift(&self, mut residual: Vec<BigInt>, transposed: bool) -> Option<(Vec<BigInt>, BigInt)> {
        let size = residual.len();
        let rhs = residual.clone();
        let rhs_bits = rhs.iter().map(BigInt::bits).max().unwrap_or(0);
        // Replacing a column of M (a row, for M^T) by the right-hand side: Hadamard's bound
        // over the columns (rows), that one's length traded for the right-hand side's.
        let hadamard = self.hadamard_bits[usize::from(!transposed)];
        let numerator_bits = hadamard + rhs_bits + u64::from(usize::BITS - size.leading_zeros());
        // The reconstruction is certain once both are below the square root of half the
        // modulus (the denominator's bound, Hadamard's, is the smaller).
        let enough_bits = 2 * numerator_bits + 2;
        let prime = BigInt::from(PRIME);
        let (mut value, mut power) = (vec![BigInt::zero(); size], BigInt::one());
        let mut next_try = 4;
        for digits in 1.. {
            let residues = residual.iter().map(Residue::of).collect();
            let digit = match transposed {
                false => self.factors.solve(residues),
                true => self.factors.solve_transposed(residues),
            };
            for (v, x) in value.iter_mut().zip(&digit) {
                *v += &power * x.0;
            }
            power *= PRIME;
            // residual = (residual - M digit) / p, exact: M digit = residual modulo p.
            let product = self.times(transposed, |a, k| a * digit[k].0);
            for (r, p) in residual.iter_mut().zip(product) {
                *r = (std::mem::take(r) - p) / &prime;
            }
            let last = power.bits() > enough_bits;
            if digits == next_try || last {
                if let Some(solution) = self.rebuilt(&value, &power, &rhs, transposed) {
                    return Some(solution);
                }
                next_try += next_try / 2;
            }
            if last {
                return None;
            }
        }
        None
    }

    /// The fraction whose p-adic expansion `value` begins (modulo `modulus`), where it solves
    /// M u = rhs exactly.
    fn rebuilt(
        &self,
        value: &[BigInt],
        modulus: &BigInt,
        rhs: &[BigInt],
        transposed: bool,
    ) -> Option<(Vec<BigInt>, BigInt)> {
        let bound = (modulus >> 1u32).sqrt();
        let mut denominator = BigInt::one();
        let mut numerators = Vec::with_capacity(value.len());
        let half = modulus >> 1u32;
        for v in value {
            let mut guess = (&denominator * v).mod_floor(modulus);
            if guess > half {
                guess -= modulus;
            }
            if guess.abs() >= bound {
                // Another factor of the denominator, found from this entry.
                let (n, d) = reconstruct(&guess, modulus, &bound)?;
                numerators.iter_mut().for_each(|x| *x *= &d);
                denominator *= d;
                guess = n;
            }
            numerators.push(guess);
        }
        let product = self.times(transposed, |a, k| a * &numerators[k]);
        let exact = product.iter().zip(rhs).all(|(p, r)| *p == &denominator * r);
        exact.then_some((numerators, denominator))
    }

    /// M x (M^T x where `transposed`), `term(a, k)` giving entry a of M times x_k.
    fn times(&self, transposed: bool, term: impl Fn(&BigInt, usize) -> BigInt) -> Vec<BigInt> {
        let mut product = vec![BigInt::zero(); self.rows.len()];
        for (i, row) in self.rows.iter().enumerate() {
            for (k, a) in row {
                match transposed {
                    false => product[i] += term(a, *k),
                    true => product[*k] += term(a, i),
                }
            }
        }
        product
    }
}

/// The integer vector and common denominator L of `values` (values = integers / L).
fn integers(values: &[Q]) -> (Vec<BigInt>, BigInt) {
    let common = values
        .iter()
        .fold(BigInt::one(), |l, v| l.lcm(v.parts().1.as_ref()));
    let scaled = values
        .iter()
        .map(|v| {
            let (n, d) = v.parts();
            n.as_ref() * (&common / d.as_ref())
        })
        .collect();
    (scaled, common)
}

/// n / d with n = d u modulo `modulus`, |n| and 0 < d below `bound`: the remainder and cofactor
/// of the extended Euclidean algorithm on (modulus, u) where the remainder first falls below
/// the bound (Wang 1981); `None` where the cofactor is not below it too (no such fraction).
fn reconstruct(u: &BigInt, modulus: &BigInt, bound: &BigInt) -> Option<(BigInt, BigInt)> {
    let (mut r0, mut r1) = (modulus.clone(), u.mod_floor(modulus));
    let (mut t0, mut t1) = (BigInt::zero(), BigInt::one());
    while &r1 >= bound {
        let (q, r) = r0.div_rem(&r1);
        (r0, r1) = (r1, r);
        let t = &t0 - &q * &t1;
        (t0, t1) = (t1, t);
    }
    if t1.is_zero() || &t1.abs() >= bound {
        return None;
    }
    Some(if t1.is_negative() {
        (-r1, -t1)
    } else {
        (r1, t1)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// B's sparse rows from dense ones.
    fn sparse(b: &[Vec<Q>]) -> Vec<BTreeMap<usize, Q>> {
        let entries = |row: &Vec<Q>| {
            let nonzero = row.iter().enumerate().filter(|(_, a)| !a.is_zero());
            nonzero.map(|(k, a)| (k, a.clone())).collect()
        };
        b.iter().map(entries).collect()
    }

    #[test]
    fn residues_of_big_integers_of_either_sign_match_their_remainder() {
        let prime = BigInt::from(PRIME);
        let mut rng = crate::rng::Rng::new(5);
        for words in 0..6 {
            for _ in 0..20 {
                let mut v = BigInt::from(rng.next_u64());
                for _ in 0..words {
                    v = (v << 64u32) + rng.next_u64();
                }
                for v in [v.clone(), -v] {
                    let expected = v.mod_floor(&prime);
                    assert_eq!(BigInt::from(Residue::of(&v).0), expected, "{v}");
                }
            }
        }
        let a = Residue::of(&BigInt::from(123_456_789_u64));
        assert_eq!(a.mul(&a.inverse()), Residue(1));
        assert_eq!(Residue::of(&prime), Residue(0));
    }

    #[test]
    fn a_fraction_comes_back_from_its_residue() {
        let modulus = BigInt::from(PRIME).pow(4);
        let bound = (&modulus >> 1u32).sqrt();
        for (n, d) in [
            (0, 1),
            (1, 1),
            (-7, 3),
            (1_000_003, 999_999_937),
            (-1, 1_i64 << 40),
        ] {
            let (n, d) = (BigInt::from(n), BigInt::from(d));
            let inverse = d.extended_gcd(&modulus).x;
            let u = (&n * inverse).mod_floor(&modulus);
            assert_eq!(reconstruct(&u, &modulus, &bound), Some((n, d)));
        }
    }

    /// The lifted solutions of B z = r and B^T y = r equal the rational elimination's, on
    /// sparse random matrices of entries with fifty-three-bit binary fractions (as sampled
    /// friction gives) and small decimals, whose solutions run to hundreds of bits.
    #[test]
    fn lifted_solutions_and_their_signs_equal_the_rational_elimination() {
        let mut rng = crate::rng::Rng::new(11);
        let mut solved = 0;
        for trial in 0..60 {
            let m = 2 + trial % 25;
            let mut entry = || match rng.next_u64() % 6 {
                0..=2 => Q::zero(),
                3 => Q::from_f64_exact(rng.uniform() * 2.0 - 0.5).expect("finite"),
                _ => Q::frac(
                    (rng.next_u64() % 41) as i128 - 20,
                    1 + (rng.next_u64() % 20) as i128,
                ),
            };
            let mut b: Vec<Vec<Q>> = (0..m).map(|_| (0..m).map(|_| entry()).collect()).collect();
            for (i, row) in b.iter_mut().enumerate() {
                row[i] = &row[i] + &Q::int(3);
            }
            let r: Vec<Q> = (0..m).map(|_| entry()).collect();
            let rows = sparse(&b);
            let Some(rational) = Factors::of(rows.clone()) else {
                continue;
            };
            let lifting = Lifting::of(&rows).expect("nonsingular modulo the prime");
            let z = rational.solve(r.clone());
            let signs: Vec<Ordering> = z.iter().map(|z| z.signum().cmp(&0)).collect();
            assert_eq!(lifting.signs(&r), Some(signs), "{b:?}");
            assert_eq!(lifting.solve(&r), Some(z), "{b:?}");
            let transposed = Some(rational.solve_transposed(r.clone()));
            assert_eq!(lifting.solve_transposed(&r), transposed, "{b:?}");
            solved += 1;
        }
        assert!(solved > 50, "{solved} of 60 nonsingular");
    }

    /// A matrix singular modulo the prime but not in rationals has no lifting: its checks fall
    /// back to rational elimination.
    #[test]
    fn a_matrix_singular_modulo_the_prime_is_refused() {
        let p = Q::from_big(BigInt::from(PRIME), BigInt::one());
        let b = vec![vec![p.clone(), Q::one()], vec![Q::zero(), Q::one()]];
        assert!(Lifting::of(&sparse(&b)).is_none());
        assert!(Factors::of(sparse(&b)).is_some());
        let doubled = vec![vec![p.clone(), Q::one()], vec![&p * &Q::int(2), Q::int(2)]];
        assert!(Lifting::of(&sparse(&doubled)).is_none());
    }
}
