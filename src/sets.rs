//! Disjoint sets (union-find with path halving): which blocks move as one at an event, which
//! surveyed edges are one edge.

/// A partition of `0..n`, refined by joining.
#[derive(Debug, Clone, Default)]
pub struct DisjointSets(Vec<usize>);

impl DisjointSets {
    /// Every element alone.
    pub fn new(n: usize) -> DisjointSets {
        DisjointSets((0..n).collect())
    }

    /// Every element of `0..n` alone again, in the memory already held (the event-driven
    /// integrator partitions a few blocks at every event).
    pub fn reset(&mut self, n: usize) {
        self.0.clear();
        self.0.extend(0..n);
    }

    /// The representative of `a`'s set.
    pub fn find(&mut self, mut a: usize) -> usize {
        while self.0[a] != a {
            self.0[a] = self.0[self.0[a]];
            a = self.0[a];
        }
        a
    }

    /// Merges the sets of `a` and `b`.
    pub fn join(&mut self, a: usize, b: usize) {
        let (a, b) = (self.find(a), self.find(b));
        self.0[a.max(b)] = a.min(b);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn joined_elements_share_a_representative_and_others_do_not() {
        let mut s = DisjointSets::new(6);
        s.join(0, 3);
        s.join(4, 3);
        s.join(1, 2);
        assert_eq!(s.find(4), s.find(0));
        assert_eq!(s.find(2), s.find(1));
        assert_ne!(s.find(0), s.find(1));
        assert_eq!(s.find(5), 5);
    }

    #[test]
    fn a_reset_partition_has_every_element_alone() {
        let mut s = DisjointSets::new(3);
        s.join(0, 2);
        s.reset(5);
        assert_eq!(
            (0..5).map(|i| s.find(i)).collect::<Vec<_>>(),
            [0, 1, 2, 3, 4]
        );
    }
}
