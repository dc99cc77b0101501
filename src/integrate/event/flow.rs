//! Maximum flow and minimum cuts with exact capacities (Dinic's algorithm). The mode decision
//! reduces every question it asks — which blocks break away, which stay stuck — to a minimum cut.

use crate::exact::Q;
use std::cmp::Ordering;
use std::collections::VecDeque;

/// Numbers a flow can carry: an ordered group (addition, subtraction, comparison). Exact types
/// only: the whole point is that ties compare equal.
pub trait Amount: Clone + Ord + std::fmt::Debug {
    /// Zero.
    fn zero() -> Self;
    /// Sum.
    fn plus(&self, o: &Self) -> Self;
    /// Difference.
    fn minus(&self, o: &Self) -> Self;
    /// Embeds an exact rational.
    fn from_q(q: Q) -> Self;
    /// True when strictly positive.
    fn positive(&self) -> bool {
        *self > Self::zero()
    }
}

impl Amount for Q {
    fn zero() -> Q {
        Q::zero()
    }
    fn plus(&self, o: &Q) -> Q {
        self + o
    }
    fn minus(&self, o: &Q) -> Q {
        self - o
    }
    fn from_q(q: Q) -> Q {
        q
    }
    fn positive(&self) -> bool {
        self.is_positive()
    }
}

/// c0 + c1 eps + c2 eps^2 for an infinitesimal eps > 0, ordered lexicographically: the value of a
/// ground acceleration "just after" an instant, a_g(t) + a_g'(t) eps + a_g''(t) eps^2 / 2.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Lex(pub [Q; 3]);

impl Lex {
    /// A plain number.
    pub fn constant(q: Q) -> Lex {
        Lex([q, Q::zero(), Q::zero()])
    }
    /// The same value times an exact factor.
    pub fn scale(&self, k: &Q) -> Lex {
        Lex([&self.0[0] * k, &self.0[1] * k, &self.0[2] * k])
    }
}

impl Ord for Lex {
    fn cmp(&self, o: &Lex) -> Ordering {
        self.0[0]
            .cmp(&o.0[0])
            .then_with(|| self.0[1].cmp(&o.0[1]))
            .then_with(|| self.0[2].cmp(&o.0[2]))
    }
}

impl PartialOrd for Lex {
    fn partial_cmp(&self, o: &Lex) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}

impl Amount for Lex {
    fn zero() -> Lex {
        Lex::constant(Q::zero())
    }
    fn plus(&self, o: &Lex) -> Lex {
        Lex([
            &self.0[0] + &o.0[0],
            &self.0[1] + &o.0[1],
            &self.0[2] + &o.0[2],
        ])
    }
    fn minus(&self, o: &Lex) -> Lex {
        Lex([
            &self.0[0] - &o.0[0],
            &self.0[1] - &o.0[1],
            &self.0[2] - &o.0[2],
        ])
    }
    fn from_q(q: Q) -> Lex {
        Lex::constant(q)
    }
}

struct Arc<T> {
    to: usize,
    residual: T,
    rev: usize,
}

/// A flow network.
pub struct Network<T: Amount> {
    arcs: Vec<Arc<T>>,
    adj: Vec<Vec<usize>>,
}

impl<T: Amount> Network<T> {
    /// A network with `n` nodes and no arcs.
    pub fn new(n: usize) -> Network<T> {
        Network {
            arcs: Vec::new(),
            adj: vec![Vec::new(); n],
        }
    }

    /// An arc u -> v of capacity `cap` (and its zero-capacity reverse).
    pub fn arc(&mut self, u: usize, v: usize, cap: T) {
        self.pair(u, v, cap, T::zero());
    }

    /// An undirected edge: capacity `cap` each way.
    pub fn edge(&mut self, u: usize, v: usize, cap: T) {
        self.pair(u, v, cap.clone(), cap);
    }

    fn pair(&mut self, u: usize, v: usize, forward: T, backward: T) {
        let k = self.arcs.len();
        self.arcs.push(Arc {
            to: v,
            residual: forward,
            rev: k + 1,
        });
        self.arcs.push(Arc {
            to: u,
            residual: backward,
            rev: k,
        });
        self.adj[u].push(k);
        self.adj[v].push(k + 1);
    }

    fn levels(&self, s: usize) -> Vec<usize> {
        let mut level = vec![usize::MAX; self.adj.len()];
        level[s] = 0;
        let mut queue = VecDeque::from([s]);
        while let Some(u) = queue.pop_front() {
            for &a in &self.adj[u] {
                let arc = &self.arcs[a];
                if level[arc.to] == usize::MAX && arc.residual.positive() {
                    level[arc.to] = level[u] + 1;
                    queue.push_back(arc.to);
                }
            }
        }
        level
    }

    fn push(&mut self, u: usize, t: usize, limit: &T, level: &[usize], next: &mut [usize]) -> T {
        if u == t {
            return limit.clone();
        }
        while next[u] < self.adj[u].len() {
            let a = self.adj[u][next[u]];
            let (to, ok) = {
                let arc = &self.arcs[a];
                (
                    arc.to,
                    arc.residual.positive() && level[arc.to] == level[u] + 1,
                )
            };
            if ok {
                let cap = self.arcs[a].residual.clone();
                let want = if cap < *limit { cap } else { limit.clone() };
                let got = self.push(to, t, &want, level, next);
                if got.positive() {
                    self.arcs[a].residual = self.arcs[a].residual.minus(&got);
                    let r = self.arcs[a].rev;
                    self.arcs[r].residual = self.arcs[r].residual.plus(&got);
                    return got;
                }
            }
            next[u] += 1;
        }
        T::zero()
    }

    /// Pushes a maximum flow from s to t and returns its value. Afterwards the residual network
    /// gives the minimum cuts ([`Network::reachable_from`], [`Network::reaching`]).
    pub fn max_flow(&mut self, s: usize, t: usize, unbounded: &T) -> T {
        let mut total = T::zero();
        loop {
            let level = self.levels(s);
            if level[t] == usize::MAX {
                return total;
            }
            let mut next = vec![0; self.adj.len()];
            loop {
                let f = self.push(s, t, unbounded, &level, &mut next);
                if !f.positive() {
                    break;
                }
                total = total.plus(&f);
            }
        }
    }

    /// Nodes reachable from `s` through arcs with residual capacity: the source side of the
    /// minimum cut closest to the source.
    pub fn reachable_from(&self, s: usize) -> Vec<bool> {
        let mut seen = vec![false; self.adj.len()];
        seen[s] = true;
        let mut stack = vec![s];
        while let Some(u) = stack.pop() {
            for &a in &self.adj[u] {
                let arc = &self.arcs[a];
                if !seen[arc.to] && arc.residual.positive() {
                    seen[arc.to] = true;
                    stack.push(arc.to);
                }
            }
        }
        seen
    }

    /// Nodes from which `t` is reachable through arcs with residual capacity: the sink side of
    /// the minimum cut closest to the sink.
    pub fn reaching(&self, t: usize) -> Vec<bool> {
        let mut seen = vec![false; self.adj.len()];
        seen[t] = true;
        let mut stack = vec![t];
        while let Some(v) = stack.pop() {
            for &a in &self.adj[v] {
                // Arc a goes v -> u; its reverse u -> v carries residual into v.
                let u = self.arcs[a].to;
                let into_v = &self.arcs[self.arcs[a].rev];
                if !seen[u] && into_v.residual.positive() {
                    seen[u] = true;
                    stack.push(u);
                }
            }
        }
        seen
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn max_flow_and_both_minimum_cuts() {
        // s=0, t=3; two parallel paths with a tie: cuts {s} and {s,1,2} both have value 2.
        let mut net: Network<Q> = Network::new(4);
        net.arc(0, 1, Q::int(1));
        net.arc(0, 2, Q::int(1));
        net.arc(1, 3, Q::int(1));
        net.arc(2, 3, Q::int(1));
        let f = net.max_flow(0, 3, &Q::int(100));
        assert_eq!(f, Q::int(2));
        assert_eq!(net.reachable_from(0), vec![true, false, false, false]);
        assert_eq!(net.reaching(3), vec![false, false, false, true]);
    }

    #[test]
    fn lexicographic_capacities() {
        let eps = |c0: i64, c1: i64| Lex([Q::int(c0), Q::int(c1), Q::zero()]);
        let mut net: Network<Lex> = Network::new(3);
        net.arc(0, 1, eps(1, 1));
        net.arc(1, 2, eps(1, 0));
        let f = net.max_flow(0, 2, &eps(100, 0));
        assert_eq!(f, eps(1, 0));
        // The bottleneck is 1 -> 2 (1 < 1 + eps).
        assert_eq!(net.reachable_from(0), vec![true, true, false]);
    }
}
