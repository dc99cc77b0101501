//! Maximum flow and minimum cuts with exact capacities. The mode decision reduces every question
//! it asks — which blocks break away, which stay stuck — to a minimum cut: the one closest to the
//! source and the one closest to the sink. Small networks use Dinic's algorithm; large ones
//! push-relabel (active nodes in first-in first-out order, with global relabelling and the gap
//! heuristic), which moves a whole wall's load down in a few sweeps where Dinic needs a phase
//! per course.

use crate::exact::{div, gcd_i128, Q};
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

thread_local! {
    /// Set when integer flow arithmetic overflowed: the caller then redoes the cut exactly.
    static OVERFLOW: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
    /// Nodes of the maximum-flow passes run on this thread since it was last read: the work
    /// counter of the exact decisions (decisions are pure functions of their problems, so the
    /// count cannot travel through them).
    static PASS_NODES: std::cell::Cell<u64> = const { std::cell::Cell::new(0) };
}

/// The nodes of the maximum-flow passes run on this thread since the last call, and a fresh
/// count.
pub fn take_pass_nodes() -> u64 {
    PASS_NODES.with(|c| c.replace(0))
}

/// The nodes of the maximum-flow passes run on this thread since the last
/// [`take_pass_nodes`], the count left as it is.
pub fn pass_nodes() -> u64 {
    PASS_NODES.with(|c| c.get())
}

fn count_passes(nodes: usize, passes: u64) {
    PASS_NODES.with(|c| c.set(c.get() + nodes as u64 * passes));
}

/// Clears the overflow flag of this thread and returns what it was.
pub fn take_overflow() -> bool {
    OVERFLOW.with(|f| f.replace(false))
}

/// Integers as flow amounts: an overflow sets the flag ([`take_overflow`]) and gives zero.
macro_rules! integer_amount {
    ($($int:ty),*) => {$(
        impl Amount for $int {
            fn zero() -> $int {
                0
            }
            fn unit() -> $int {
                1
            }
            fn plus(&self, o: &$int) -> $int {
                self.checked_add(*o).unwrap_or_else(overflowed)
            }
            fn minus(&self, o: &$int) -> $int {
                self.checked_sub(*o).unwrap_or_else(overflowed)
            }
        }
    )*};
}

integer_amount!(i64, i128);

fn overflowed<I: Default>() -> I {
    OVERFLOW.with(|f| f.set(true));
    I::default()
}

/// Rationals over their least common denominator: the numerators and the denominator, if all
/// fit.
pub(super) fn over_common_denominator<'a>(
    values: impl Iterator<Item = &'a Q> + Clone,
) -> Option<(Vec<i128>, i128)> {
    let mut lcm: i128 = 1;
    for v in values.clone() {
        let (_, d) = v.small_parts()?;
        let g = gcd_i128(lcm, d);
        if g != d {
            lcm = lcm.checked_mul(div(d, g))?;
        }
    }
    // Keep a factor 2^8 of headroom below i128::MAX for the sums a flow forms; the overflow
    // flag catches anything beyond.
    const LIMIT: i128 = i128::MAX >> 8;
    let numerators = values
        .map(|v| {
            let (n, d) = v.small_parts()?;
            let x = n.checked_mul(div(lcm, d))?;
            (x.checked_abs()? <= LIMIT).then_some(x)
        })
        .collect::<Option<Vec<i128>>>()?;
    Some((numerators, lcm))
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

/// Node and arc indices in 32 bits: a flow's inner loop reads arcs one after another, and a
/// network of a wall has far fewer than 2^32 of either.
struct Arc<T> {
    head: u32,
    residual: T,
    back: u32,
}

impl<T> Arc<T> {
    /// The node it enters.
    fn to(&self) -> usize {
        self.head as usize
    }

    /// Its reverse arc.
    fn rev(&self) -> usize {
        self.back as usize
    }
}

/// An index in 32 bits ([`Arc`]).
fn narrow(i: usize) -> u32 {
    u32::try_from(i).expect("a network of fewer than 2^32 nodes and arcs")
}

/// Below this many nodes Dinic's lower overhead wins, and it gives both cuts from one flow;
/// from it on, Dinic's phase count (the number of distinct augmenting path lengths, about one
/// per course of a wall) dominates: eight 976-block cases run in 3.5 s with push-relabel from 32
/// nodes against 5.7 s from 2,048 (docs/performance.md).
pub const PUSH_RELABEL_FROM: usize = 32;

/// A flow network. Arcs are added in any order; before the first flow they are laid out by the
/// node they leave (`first[u]..first[u + 1]`), so scanning a node's arcs reads one stretch of
/// memory.
pub struct Network<T: Amount> {
    n: usize,
    arcs: Vec<Arc<T>>,
    /// While arcs are being added: the node each leaves.
    tails: Vec<usize>,
    /// Once laid out: where each node's arcs start (n + 1 entries).
    first: Vec<usize>,
}

impl<T: Amount> Network<T> {
    /// A network with `n` nodes and no arcs.
    pub fn new(n: usize) -> Network<T> {
        Network {
            n,
            arcs: Vec::new(),
            tails: Vec::new(),
            first: Vec::new(),
        }
    }

    /// Lays the arcs out by the node they leave (a counting sort), once.
    fn lay_out(&mut self) {
        if self.first.len() == self.n + 1 {
            return;
        }
        let mut first = vec![0; self.n + 1];
        for &u in &self.tails {
            first[u + 1] += 1;
        }
        for u in 0..self.n {
            first[u + 1] += first[u];
        }
        let mut next = first.clone();
        let place: Vec<usize> = self
            .tails
            .iter()
            .map(|&u| {
                next[u] += 1;
                next[u] - 1
            })
            .collect();
        // The arc at each place, read in place order: one pass writing the new list in order.
        let mut at = vec![0; place.len()];
        for (a, &p) in place.iter().enumerate() {
            at[p] = a;
        }
        let arcs = std::mem::take(&mut self.arcs);
        self.arcs = at
            .iter()
            .map(|&a| Arc {
                head: arcs[a].head,
                residual: arcs[a].residual.clone(),
                back: narrow(place[arcs[a].rev()]),
            })
            .collect();
        self.first = first;
        self.tails = Vec::new();
    }

    /// The arcs leaving u (once laid out).
    fn out(&self, u: usize) -> std::ops::Range<usize> {
        self.first[u]..self.first[u + 1]
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
            head: narrow(v),
            residual: forward,
            back: narrow(k + 1),
        });
        self.arcs.push(Arc {
            head: narrow(u),
            residual: backward,
            back: narrow(k),
        });
        self.tails.push(u);
        self.tails.push(v);
    }

    /// Residual distances from s, up to t's: once t is reached every node nearer than t has
    /// its level (breadth first), and nodes as far as t or further cannot lie on a shortest
    /// path to it, so the search stops there (most of a decision's network is one or two steps
    /// from the source, and t is two or three).
    fn levels(&self, s: usize, t: usize) -> Vec<usize> {
        let mut level = vec![usize::MAX; self.n];
        level[s] = 0;
        let mut queue = VecDeque::from([s]);
        while let Some(u) = queue.pop_front() {
            for a in self.out(u) {
                let arc = &self.arcs[a];
                if level[arc.to()] == usize::MAX && arc.residual.positive() {
                    level[arc.to()] = level[u] + 1;
                    if arc.to() == t {
                        return level;
                    }
                    queue.push_back(arc.to());
                }
            }
        }
        level
    }

    fn push(&mut self, u: usize, t: usize, limit: &T, level: &[usize], next: &mut [usize]) -> T {
        if u == t {
            return limit.clone();
        }
        while next[u] < self.first[u + 1] {
            let a = next[u];
            let (to, ok) = {
                let arc = &self.arcs[a];
                (
                    arc.to(),
                    arc.residual.positive()
                        && level[arc.to()] == level[u] + 1
                        && (arc.to() == t || level[arc.to()] < level[t]),
                )
            };
            if ok {
                let cap = self.arcs[a].residual.clone();
                let want = if cap < *limit { cap } else { limit.clone() };
                let got = self.push(to, t, &want, level, next);
                if got.positive() {
                    self.arcs[a].residual = self.arcs[a].residual.minus(&got);
                    let r = self.arcs[a].rev();
                    self.arcs[r].residual = self.arcs[r].residual.plus(&got);
                    return got;
                }
            }
            next[u] += 1;
        }
        T::zero()
    }

    /// Pushes a maximum flow from s to t and returns its value. Afterwards the residual network
    /// gives the minimum cuts (`Network::reachable_from`, `Network::reaching`).
    pub fn max_flow(&mut self, s: usize, t: usize, unbounded: &T) -> T {
        self.lay_out();
        let mut total = T::zero();
        loop {
            let level = self.levels(s, t);
            if level[t] == usize::MAX {
                return total;
            }
            let mut next = self.first[..self.n].to_vec();
            loop {
                let f = self.push(s, t, unbounded, &level, &mut next);
                if !f.positive() {
                    break;
                }
                total = total.plus(&f);
            }
        }
    }

    /// Both minimum s-t cuts: the source side of the cut closest to the source, and the nodes
    /// that reach `t` in every maximum flow (the sink side of the cut closest to the sink).
    /// `unbounded` exceeds every cut.
    pub fn minimum_cuts(self, s: usize, t: usize, unbounded: &T) -> (Vec<bool>, Vec<bool>) {
        if self.n < PUSH_RELABEL_FROM {
            count_passes(self.n, 1);
            self.cuts_by_dinic(s, t, unbounded)
        } else {
            count_passes(self.n, 2);
            self.cuts_by_push_relabel(s, t)
        }
    }

    /// The source side of the minimum s-t cut closest to the source (half the work of
    /// [`Network::minimum_cuts`] for large networks).
    pub fn source_side(mut self, s: usize, t: usize, unbounded: &T) -> Vec<bool> {
        count_passes(self.n, 1);
        if self.n < PUSH_RELABEL_FROM {
            self.max_flow(s, t, unbounded);
            self.reachable_from(s)
        } else {
            self.source_side_by_push_relabel(s, t)
        }
    }

    /// The nodes that reach `t` in every maximum flow: the sink side of the minimum s-t cut
    /// closest to the sink.
    pub fn sink_side(mut self, s: usize, t: usize, unbounded: &T) -> Vec<bool> {
        count_passes(self.n, 1);
        if self.n < PUSH_RELABEL_FROM {
            self.max_flow(s, t, unbounded);
            self.reaching(t)
        } else {
            self.sink_side_of_max_preflow(s, t)
        }
    }

    fn cuts_by_dinic(mut self, s: usize, t: usize, unbounded: &T) -> (Vec<bool>, Vec<bool>) {
        self.max_flow(s, t, unbounded);
        (self.reachable_from(s), self.reaching(t))
    }

    /// The sink side from a maximum preflow of this network, the source side from one of the
    /// reversed network. No second phase turning preflows into flows is needed.
    fn cuts_by_push_relabel(mut self, s: usize, t: usize) -> (Vec<bool>, Vec<bool>) {
        self.lay_out();
        let source_side = self.source_side_by_push_relabel(s, t);
        (source_side, self.sink_side_of_max_preflow(s, t))
    }

    /// The nodes that reach s in the reversed network (t to s) after a maximum preflow there:
    /// the source side of the cut closest to the source here. Leaves this network's flow untouched.
    fn source_side_by_push_relabel(&mut self, s: usize, t: usize) -> Vec<bool> {
        self.lay_out();
        let mut reversed = Network::new(self.n);
        // Each pair once, from its first arc: u -> v (u is where its reverse points) becomes
        // v -> u with the same residual, and its reverse u -> v.
        for (a, arc) in self.arcs.iter().enumerate() {
            if a > arc.rev() {
                continue;
            }
            let back = &self.arcs[arc.rev()];
            let (u, v) = (back.to(), arc.to());
            reversed.pair(v, u, arc.residual.clone(), back.residual.clone());
        }
        reversed.sink_side_of_max_preflow(t, s)
    }

    /// Shortest residual distance of every node to `t` (`n` where `t` cannot be reached).
    fn distances_to(&self, t: usize) -> Vec<usize> {
        let n = self.n;
        let mut dist = vec![n; n];
        dist[t] = 0;
        let mut queue = VecDeque::from([t]);
        while let Some(v) = queue.pop_front() {
            for a in self.out(v) {
                let u = self.arcs[a].to();
                if dist[u] == n && self.arcs[self.arcs[a].rev()].residual.positive() {
                    dist[u] = dist[v] + 1;
                    queue.push_back(u);
                }
            }
        }
        dist
    }

    /// Pushes a maximum preflow from s (push-relabel: active nodes discharged first in, first
    /// out, queued highest label first at every reset; labels reset to exact distances every
    /// `n` relabels) and returns the nodes that reach t: every node left with excess has a label
    /// of at least n, so it cannot reach t, and the flow into the nodes that can is maximum
    /// (Goldberg and Tarjan 1988, first phase). First
    /// in, first out rather than highest label first: the networks of a wall's decisions take
    /// fewer relabels that way (the block-count study's 10,050-block cases 9.3 -> 8.0 s,
    /// docs/performance.md).
    fn sink_side_of_max_preflow(&mut self, s: usize, t: usize) -> Vec<bool> {
        self.lay_out();
        let n = self.n;
        let mut excess = vec![T::zero(); n];
        for a in self.out(s) {
            let r = std::mem::replace(&mut self.arcs[a].residual, T::zero());
            if r.positive() {
                let (v, rev) = (self.arcs[a].to(), self.arcs[a].rev());
                self.arcs[rev].residual = self.arcs[rev].residual.plus(&r);
                excess[v] = excess[v].plus(&r);
            }
        }
        let mut labels = Labels::new(n);
        let mut fifo: VecDeque<usize> = VecDeque::new();
        let mut queued = vec![false; n];
        let mut current = self.first[..n].to_vec();
        let mut relabels = n;
        loop {
            if relabels >= n {
                // Global relabelling: exact distances, and the active nodes queued afresh.
                relabels = 0;
                let mut height = self.distances_to(t);
                height[s] = n;
                labels.reset(height);
                current.copy_from_slice(&self.first[..n]);
                fifo.clear();
                queued.iter_mut().for_each(|q| *q = false);
                // Highest label first (s is at n and t at 0, neither listed): what a node
                // pushes reaches the nodes below it before their turn in the same round, so one
                // round carries a wall's load from its top course down (case 34 4.95 -> 4.86 s).
                for h in (1..=labels.top).rev() {
                    let mut v = labels.head[h];
                    while v != NONE {
                        if excess[v].positive() {
                            fifo.push_back(v);
                            queued[v] = true;
                        }
                        v = labels.next[v];
                    }
                }
            }
            let Some(u) = fifo.pop_front() else {
                break;
            };
            queued[u] = false;
            // Discharge u: push along admissible arcs, relabel when none is left.
            while excess[u].positive() && labels.height[u] < n {
                if current[u] == self.first[u + 1] {
                    // The new label is one above the lowest residual neighbour, whose arc is
                    // then the first admissible one: the scan goes on from it.
                    let lowest = self
                        .out(u)
                        .filter(|&a| self.arcs[a].residual.positive())
                        .min_by_key(|&a| labels.height[self.arcs[a].to()]);
                    let (to, arc) = match lowest {
                        Some(a) => ((labels.height[self.arcs[a].to()] + 1).min(n), a),
                        None => (n, self.first[u]),
                    };
                    labels.relabel(u, to);
                    current[u] = arc;
                    relabels += 1;
                    continue;
                }
                let a = current[u];
                let v = self.arcs[a].to();
                if self.arcs[a].residual.positive() && labels.height[u] == labels.height[v] + 1 {
                    let amount = if excess[u] < self.arcs[a].residual {
                        excess[u].clone()
                    } else {
                        self.arcs[a].residual.clone()
                    };
                    self.arcs[a].residual = self.arcs[a].residual.minus(&amount);
                    let rev = self.arcs[a].rev();
                    self.arcs[rev].residual = self.arcs[rev].residual.plus(&amount);
                    excess[u] = excess[u].minus(&amount);
                    excess[v] = excess[v].plus(&amount);
                    if v != s && v != t && !queued[v] {
                        fifo.push_back(v);
                        queued[v] = true;
                    }
                    if !self.arcs[a].residual.positive() {
                        current[u] += 1;
                    }
                } else {
                    current[u] += 1;
                }
            }
        }
        self.reaching(t)
    }

    /// Nodes reachable from `s` through arcs with residual capacity: the source side of the
    /// minimum cut closest to the source.
    fn reachable_from(&self, s: usize) -> Vec<bool> {
        let mut seen = vec![false; self.n];
        seen[s] = true;
        let mut stack = vec![s];
        while let Some(u) = stack.pop() {
            for a in self.out(u) {
                let arc = &self.arcs[a];
                if !seen[arc.to()] && arc.residual.positive() {
                    seen[arc.to()] = true;
                    stack.push(arc.to());
                }
            }
        }
        seen
    }

    /// Nodes from which `t` is reachable through arcs with residual capacity: the sink side of
    /// the minimum cut closest to the sink.
    fn reaching(&self, t: usize) -> Vec<bool> {
        let mut seen = vec![false; self.n];
        seen[t] = true;
        let mut stack = vec![t];
        while let Some(v) = stack.pop() {
            for a in self.out(v) {
                // Arc a goes v -> u; its reverse u -> v carries residual into v.
                let u = self.arcs[a].to();
                let into_v = &self.arcs[self.arcs[a].rev()];
                if !seen[u] && into_v.residual.positive() {
                    seen[u] = true;
                    stack.push(u);
                }
            }
        }
        seen
    }
}

/// Push-relabel's labels, with the nodes at each label below n in a list of its own: when a
/// label's list empties, every node above it is cut off from t (a path to t steps down one label
/// at a time) and goes to n at once, instead of climbing there relabel by relabel (the gap
/// heuristic), at a cost of the nodes it moves rather than a scan of every node.
struct Labels {
    height: Vec<usize>,
    /// Doubly linked lists, one per label below n (`NONE` ends them).
    head: Vec<usize>,
    next: Vec<usize>,
    prev: Vec<usize>,
    /// The highest label below n that has nodes (0 when none).
    top: usize,
}

const NONE: usize = usize::MAX;

impl Labels {
    /// Lists for `n` nodes; the labels come with the first [`Labels::reset`].
    fn new(n: usize) -> Labels {
        Labels {
            height: Vec::new(),
            head: vec![NONE; n],
            next: vec![NONE; n],
            prev: vec![NONE; n],
            top: 0,
        }
    }

    /// Takes `height` as the labels and lists every node below n.
    fn reset(&mut self, height: Vec<usize>) {
        let n = height.len();
        self.head.iter_mut().for_each(|h| *h = NONE);
        self.top = 0;
        self.height = height;
        for v in 0..n {
            let h = self.height[v];
            if h < n {
                self.link(v, h);
            }
        }
    }

    fn link(&mut self, v: usize, h: usize) {
        let first = self.head[h];
        self.next[v] = first;
        self.prev[v] = NONE;
        if first != NONE {
            self.prev[first] = v;
        }
        self.head[h] = v;
        self.top = self.top.max(h);
    }

    fn unlink(&mut self, v: usize, h: usize) {
        let (p, q) = (self.prev[v], self.next[v]);
        if p == NONE {
            self.head[h] = q;
        } else {
            self.next[p] = q;
        }
        if q != NONE {
            self.prev[q] = p;
        }
    }

    /// Moves u (below n) to label `to` (above its own, at most n), and applies the gap
    /// heuristic if u's old label is left empty.
    fn relabel(&mut self, u: usize, to: usize) {
        let n = self.height.len();
        let old = self.height[u];
        self.unlink(u, old);
        self.height[u] = to;
        if to < n {
            self.link(u, to);
        }
        if self.head[old] == NONE {
            for h in old + 1..=self.top.max(old) {
                let mut v = std::mem::replace(&mut self.head[h], NONE);
                while v != NONE {
                    self.height[v] = n;
                    v = self.next[v];
                }
            }
            self.top = old.saturating_sub(1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

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

    /// A random network as (u, v, capacity, undirected) arcs on `n` nodes, s = 0, t = n - 1.
    fn random_arcs() -> impl Strategy<Value = (usize, Vec<(usize, usize, i128, bool)>)> {
        (3usize..40).prop_flat_map(|n| {
            let arc = (0..n, 0..n, 0i128..20, any::<bool>());
            (Just(n), proptest::collection::vec(arc, 0..4 * n))
        })
    }

    fn build<T: Amount>(
        n: usize,
        arcs: &[(usize, usize, i128, bool)],
        cap: impl Fn(i128) -> T,
    ) -> Network<T> {
        let mut net = Network::new(n);
        for &(u, v, c, both) in arcs.iter().filter(|a| a.0 != a.1) {
            if both {
                net.edge(u, v, cap(c));
            } else {
                net.arc(u, v, cap(c));
            }
        }
        net
    }

    proptest! {
        #![proptest_config(crate::integrate::event::many_cheap_cases())]

        /// Push-relabel and Dinic find the same two minimum cuts (both are unique), in integers
        /// of both widths and rationals, ties (zero and equal capacities) included.
        #[test]
        fn push_relabel_and_dinic_find_the_same_cuts((n, arcs) in random_arcs()) {
            let (s, t) = (0, n - 1);
            let big = arcs.iter().map(|a| a.2).sum::<i128>() * 2 + 1;
            let ints = |c: i128| c;
            let dinic = build(n, &arcs, ints).cuts_by_dinic(s, t, &big);
            let pr = build(n, &arcs, ints).cuts_by_push_relabel(s, t);
            prop_assert_eq!(&dinic, &pr);
            let narrow = build(n, &arcs, |c: i128| c as i64).cuts_by_push_relabel(s, t);
            prop_assert_eq!(&dinic, &narrow);
            let rational = |c: i128| Q::frac(c, 7);
            let qr = build(n, &arcs, rational).cuts_by_push_relabel(s, t);
            prop_assert_eq!(&dinic, &qr);
        }
    }
}
