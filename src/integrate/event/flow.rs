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
    /// One unit (any positive amount).
    fn unit() -> Self;
    /// Sum.
    fn plus(&self, o: &Self) -> Self;
    /// Difference.
    fn minus(&self, o: &Self) -> Self;
    /// True when strictly positive.
    fn positive(&self) -> bool {
        *self > Self::zero()
    }
}

/// The rational amounts the mode decisions compute with, and their integer form: the same
/// numbers times one positive common denominator (per component), when they fit in `i128`.
/// Scaling by a positive constant changes neither the order nor which cuts are minimal, and
/// integer arithmetic skips the gcd of every rational operation, the cost of large walls.
pub trait Exact: Amount {
    /// The integer form.
    type Int: Amount;
    /// Embeds an exact rational.
    fn from_q(q: Q) -> Self;
    /// All of `values` over one common denominator (per component), or `None` when a
    /// numerator or the denominator does not fit `i128` with room for sums.
    fn integers(values: &[Self]) -> Option<Vec<Self::Int>>;
}

thread_local! {
    /// Set when integer flow arithmetic overflowed: the caller then redoes the cut exactly.
    static OVERFLOW: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Clears the overflow flag of this thread and returns what it was.
pub fn take_overflow() -> bool {
    OVERFLOW.with(|f| f.replace(false))
}

fn checked(x: Option<i128>) -> i128 {
    x.unwrap_or_else(|| {
        OVERFLOW.with(|f| f.set(true));
        0
    })
}

impl Amount for i128 {
    fn zero() -> i128 {
        0
    }
    fn unit() -> i128 {
        1
    }
    fn plus(&self, o: &i128) -> i128 {
        checked(self.checked_add(*o))
    }
    fn minus(&self, o: &i128) -> i128 {
        checked(self.checked_sub(*o))
    }
}

/// Lexicographic integer triples ([i128; 3] orders lexicographically).
impl Amount for [i128; 3] {
    fn zero() -> [i128; 3] {
        [0; 3]
    }
    fn unit() -> [i128; 3] {
        [1, 0, 0]
    }
    fn plus(&self, o: &[i128; 3]) -> [i128; 3] {
        [0, 1, 2].map(|k| checked(self[k].checked_add(o[k])))
    }
    fn minus(&self, o: &[i128; 3]) -> [i128; 3] {
        [0, 1, 2].map(|k| checked(self[k].checked_sub(o[k])))
    }
}

/// Rationals over their least common denominator: the numerators, if all fit.
fn over_common_denominator<'a>(values: impl Iterator<Item = &'a Q> + Clone) -> Option<Vec<i128>> {
    let mut lcm: i128 = 1;
    for v in values.clone() {
        let (_, d) = v.small_parts()?;
        // Denominators repeat: most already divide the running multiple (one i128 division
        // instead of a gcd).
        if lcm % d != 0 {
            lcm = lcm.checked_mul(d / gcd(lcm, d))?;
        }
    }
    // Keep a factor 2^8 of headroom below i128::MAX for the sums a flow forms; the overflow
    // flag catches anything beyond.
    const LIMIT: i128 = i128::MAX >> 8;
    values
        .map(|v| {
            let (n, d) = v.small_parts()?;
            let x = n.checked_mul(lcm / d)?;
            (x.checked_abs()? <= LIMIT).then_some(x)
        })
        .collect()
}

fn gcd(mut a: i128, mut b: i128) -> i128 {
    while b != 0 {
        (a, b) = (b, a % b);
    }
    a.abs()
}

impl Amount for Q {
    fn zero() -> Q {
        Q::zero()
    }
    fn unit() -> Q {
        Q::one()
    }
    fn plus(&self, o: &Q) -> Q {
        self + o
    }
    fn minus(&self, o: &Q) -> Q {
        self - o
    }
    fn positive(&self) -> bool {
        self.is_positive()
    }
}

impl Exact for Q {
    type Int = i128;
    fn from_q(q: Q) -> Q {
        q
    }
    fn integers(values: &[Q]) -> Option<Vec<i128>> {
        over_common_denominator(values.iter())
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
    fn unit() -> Lex {
        Lex::constant(Q::one())
    }
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
}

impl Exact for Lex {
    type Int = [i128; 3];
    fn from_q(q: Q) -> Lex {
        Lex::constant(q)
    }
    fn integers(values: &[Lex]) -> Option<Vec<[i128; 3]>> {
        let parts: Vec<Vec<i128>> = (0..3)
            .map(|k| over_common_denominator(values.iter().map(|v| &v.0[k])))
            .collect::<Option<_>>()?;
        Some(
            (0..values.len())
                .map(|i| [parts[0][i], parts[1][i], parts[2][i]])
                .collect(),
        )
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
