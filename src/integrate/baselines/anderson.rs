//! Anderson acceleration of a fixed-point iteration x -> g(x): the next iterate mixes the last
//! few images so that their residuals g(x) - x cancel as far as a least-squares fit of them
//! can tell (Walker and Ni 2011, "Anderson acceleration for fixed-point iterations", the form
//! without damping). The whole-wall solver's Coulomb friction bounds are such an iteration
//! (b -> mu p_n of the Tresca problem under b), and on large walls it can cycle where each of
//! its Tresca problems solves (docs/rocking-walls.md).

use nalgebra::{DMatrix, DVector};
use std::collections::VecDeque;

/// The last iterates and their images, at most `depth + 1` of each.
pub(super) struct Anderson {
    depth: usize,
    x: VecDeque<Vec<f64>>,
    g: VecDeque<Vec<f64>>,
}

impl Anderson {
    /// An accelerator fitting the last `depth` differences of residuals.
    pub(super) fn new(depth: usize) -> Anderson {
        Anderson {
            depth,
            x: VecDeque::new(),
            g: VecDeque::new(),
        }
    }

    /// Remembers that `x` was mapped to `g`, in the memory of the oldest pair once `depth + 1`
    /// are kept (the caller's buffers change at every iteration, so the pair is copied).
    pub(super) fn push(&mut self, x: &[f64], g: &[f64]) {
        let full = self.x.len() > self.depth;
        for (kept, new) in [(&mut self.x, x), (&mut self.g, g)] {
            let mut memory = if full { kept.pop_front() } else { None }.unwrap_or_default();
            memory.clear();
            memory.extend_from_slice(new);
            kept.push_back(memory);
        }
    }

    /// The next iterate into `next`: the last image less the combination of the images'
    /// differences whose residual differences best cancel the last residual (the plain image
    /// while only one is known). Differences the fit cannot tell apart (singular values below
    /// 1e-10 of the largest) are left out, so a repeated iterate does not blow it up.
    pub(super) fn next(&self, next: &mut Vec<f64>) {
        let last = self.x.len() - 1;
        next.clone_from(&self.g[last]);
        if last == 0 || next.is_empty() {
            return;
        }
        let n = next.len();
        let residual = |k: usize, i: usize| self.g[k][i] - self.x[k][i];
        let df = DMatrix::from_fn(n, last, |i, j| residual(j + 1, i) - residual(j, i));
        let f = DVector::from_fn(n, |i, _| residual(last, i));
        let svd = df.svd(true, true);
        let floor = 1e-10 * svd.singular_values.max();
        // Every difference zero (the same iterate again): nothing to fit.
        if floor <= 0.0 {
            return;
        }
        let Ok(gamma) = svd.solve(&f, floor) else {
            return;
        };
        for (i, x) in next.iter_mut().enumerate() {
            *x -= (0..last)
                .map(|j| gamma[j] * (self.g[j + 1][i] - self.g[j][i]))
                .sum::<f64>();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Matrix3, Vector3};

    /// A linear map whose plain iteration cycles with period three for ever (a turn by 120
    /// degrees in one plane) and contracts slowly across it: Anderson with three differences
    /// finds its fixed point, (I - A)^-1 c, to round-off in at most four maps, one more than
    /// the space has dimensions (on a linear map it is GMRES in disguise).
    #[test]
    fn a_map_whose_iteration_cycles_reaches_its_fixed_point() {
        let (c, s) = (
            (2.0 * std::f64::consts::PI / 3.0).cos(),
            (2.0 * std::f64::consts::PI / 3.0).sin(),
        );
        let a = Matrix3::new(c, -s, 0.0, s, c, 0.0, 0.0, 0.0, 0.9);
        let shift = Vector3::new(1.0, -2.0, 0.5);
        let map = |x: &Vector3<f64>| a * x + shift;
        let fixed = (Matrix3::identity() - a).lu().solve(&shift).unwrap();

        // Plain iteration from the origin comes back to where it was three steps before, in
        // the plane of the turn.
        let mut x = Vector3::zeros();
        for _ in 0..3 {
            x = map(&x);
        }
        assert!((x.xy() - Vector3::<f64>::zeros().xy()).norm() < 1e-14);

        let mut anderson = Anderson::new(3);
        let mut x = vec![0.0; 3];
        let mut next = Vec::new();
        let mut iterations = 0;
        while (Vector3::from_column_slice(&x) - fixed).norm() > 1e-13 * fixed.norm() {
            iterations += 1;
            assert!(iterations <= 4, "{x:?} against {fixed:?}");
            let g = map(&Vector3::from_column_slice(&x));
            anderson.push(&x, g.as_slice());
            anderson.next(&mut next);
            x.clone_from(&next);
        }
    }

    /// With one iterate known, the next is its image; an iterate repeated (no new direction
    /// for the fit) leaves the image too, not a division by zero.
    #[test]
    fn without_differences_the_next_iterate_is_the_image() {
        let mut anderson = Anderson::new(3);
        let mut next = Vec::new();
        anderson.push(&[1.0, 2.0], &[3.0, 5.0]);
        anderson.next(&mut next);
        assert_eq!(next, [3.0, 5.0]);
        anderson.push(&[1.0, 2.0], &[3.0, 5.0]);
        anderson.next(&mut next);
        assert_eq!(next, [3.0, 5.0]);
    }
}
