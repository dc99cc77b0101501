//! Two seated bodies face on face. Where faces lie on each other ([`Lying`]) and both bodies
//! stand on their bases, resting or sliding, the push between them turns neither body, and the
//! rigid model does not fix how it is shared between the two ends of the faces' overlap: only
//! its resultant and the height of its line of action matter, and at rest not even the
//! resultant (the blocks' frictions may share the ground's inertial force in many ways). This
//! module owns what the rigid model does fix: whether the pair can rest, slide together or
//! stay seated, from the existence of a push that balances both blocks (the limit analysis of
//! two blocks, Livesley 1978, read as a mode's conditions).
//!
//! With P >= 0 the push on the right block (+x; -x on the left one), Q = P y its moment about
//! the ground (y within the overlap: P y_lo <= Q <= P y_hi), A = a_g + u'' each block's
//! absolute acceleration and G = g lambda, block k (mass m, half base b, centroid height h,
//! friction mu) is seated while both corners of its base press, |Q + h m A| <= b m G on the
//! left and |Q - h m A| <= b m G on the right (the moment about its centroid: b (N_R - N_L) =
//! y F_x - h m A), and at rest its friction holds, |m a_g + P| <= mu m G on the left and
//! |m a_g - P| <= mu m G on the right. Every condition is linear and homogeneous in (a_g, P, Q)
//! and G, so the pair rests exactly while a_g / G stays within a fixed interval: the least and
//! the most a_g / G over the polytope in (a_g/G, P/G, Q/G), found at its vertices. Sliding
//! together, both frictions are spent and the push is the one that keeps the blocks together
//! ([`couple::pushed`] with one contact: a seated block's push moves it only along the
//! ground); the pair stays seated while an admissible Q exists, a condition per pair of the
//! bounds on Q.

use super::clearance::{Side, Touch};
use super::couple::{self, Couple, Member, Pushed};
use super::modes::{self, Constraint, Corner, Equations, Guard, Inputs, Mode, Slip};
use super::series::{self, add, add_to, scaled, ZERO};

/// A block of the pair as its balance needs it.
#[derive(Debug, Clone, Copy)]
struct Block {
    mass_kg: f64,
    half_base_m: f64,
    centroid_m: f64,
    friction: f64,
}

/// Two seated bodies whose faces lie on each other: each block's data in the order of the
/// faces' first contact, which of them is on the right, and the overlap's heights.
#[derive(Debug, Clone, Copy)]
pub(super) struct Abutting {
    blocks: [Block; 2],
    /// The side (0 or 1, the first contact's order) on the right (+x).
    right: usize,
    /// The lowest and highest point of the faces' overlap above the ground (m).
    span_m: [f64; 2],
    g_m_s2: f64,
}

/// The pair's limits at rest: the ground accelerations over g lambda between which it rests,
/// and what each limit is (friction spent: the pair slides; else a corner unloaded: a block
/// lifts).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct RestLimits {
    pub(super) ratios: [f64; 2],
    pub(super) guards: [Guard; 2],
}

impl Abutting {
    /// The pair of faces lying on each other at the contacts `ends` where both bodies
    /// (`members`, the first contact's order) are seated on one level with vertical faces
    /// between them; none otherwise.
    pub(super) fn of(ends: &[Couple; 2], members: [Member; 2]) -> Option<Abutting> {
        let first = &ends[0];
        let (mut blocks, mut base, mut g_m_s2) = ([None; 2], [0.0; 2], 0.0);
        for k in 0..2 {
            let Member::Moves(body, Mode::Rest | Mode::Slide(_), _) = members[k] else {
                return None;
            };
            let Side::Body(_, origin) = first.touch.sides[k] else {
                return None;
            };
            (base[k], g_m_s2) = (origin[1], body.g_m_s2);
            blocks[k] = Some(Block {
                mass_kg: body.mass_kg,
                half_base_m: first.half_base_m(k),
                centroid_m: body.centroid_height_m,
                friction: body.friction,
            });
        }
        let tie = series::TIE * members_size(members);
        let normal = first.touch.normal;
        if (base[0] - base[1]).abs() > tie || normal[1].abs() > series::TIE {
            return None;
        }
        let heights = ends.map(|e| e.touch.point[1] - base[0]);
        Some(Abutting {
            blocks: blocks.map(|b| b.expect("both sides are seated bodies")),
            // The normal points into the first contact's corner's body, side 0.
            right: usize::from(normal[0] < 0.0),
            span_m: [heights[0].min(heights[1]), heights[0].max(heights[1])],
            g_m_s2,
        })
    }

    /// The left and the right block.
    fn left_right(&self) -> (Block, Block) {
        (self.blocks[1 - self.right], self.blocks[self.right])
    }

    /// The interval of a_g / (g lambda) within which the pair rests: the extremes of the first
    /// coordinate over the polytope of (a_g/G, P/G, Q/G) the balances allow, found among the
    /// points where three of its faces meet. The polytope holds the origin (no ground
    /// acceleration, no push) and is bounded (friction bounds a_g and P, the span Q).
    pub(super) fn rest_limits(&self) -> RestLimits {
        let rows = self.rest_rows();
        let (mut lo, mut hi) = (
            (f64::INFINITY, Guard::StickLimit),
            (f64::NEG_INFINITY, Guard::StickLimit),
        );
        let scale = rows.iter().map(|(r, _)| r[3].abs()).fold(0.0, f64::max);
        for i in 0..rows.len() {
            for j in i + 1..rows.len() {
                for k in j + 1..rows.len() {
                    let Some(x) = solve3([&rows[i].0, &rows[j].0, &rows[k].0]) else {
                        continue;
                    };
                    let slack =
                        |row: &[f64; 4]| row[0] * x[0] + row[1] * x[1] + row[2] * x[2] + row[3];
                    if rows.iter().any(|(row, _)| slack(row) < -1e-12 * scale) {
                        continue;
                    }
                    // An unloaded corner among the faces met says a block lifts there.
                    let lifts = [i, j, k].iter().any(|&n| rows[n].1 == Guard::Uplift);
                    let guard = if lifts {
                        Guard::Uplift
                    } else {
                        Guard::StickLimit
                    };
                    if x[0] < lo.0 || (x[0] == lo.0 && lifts) {
                        lo = (x[0], guard);
                    }
                    if x[0] > hi.0 || (x[0] == hi.0 && lifts) {
                        hi = (x[0], guard);
                    }
                }
            }
        }
        RestLimits {
            ratios: [lo.0, hi.0],
            guards: [lo.1, hi.1],
        }
    }

    /// The balances at rest as rows c . (r, p, q) + c_3 >= 0 in r = a_g/G, p = P/G, q = Q/G,
    /// with what each guards (friction, or a corner's load).
    fn rest_rows(&self) -> Vec<([f64; 4], Guard)> {
        let (l, r) = self.left_right();
        let [y_lo, y_hi] = self.span_m;
        let (f, u) = (Guard::StickLimit, Guard::Uplift);
        vec![
            ([0.0, 1.0, 0.0, 0.0], f),
            ([0.0, -y_lo, 1.0, 0.0], f),
            ([0.0, y_hi, -1.0, 0.0], f),
            // Friction: |m_L r + p| <= mu_L m_L, |m_R r - p| <= mu_R m_R.
            ([-l.mass_kg, -1.0, 0.0, l.friction * l.mass_kg], f),
            ([l.mass_kg, 1.0, 0.0, l.friction * l.mass_kg], f),
            ([-r.mass_kg, 1.0, 0.0, r.friction * r.mass_kg], f),
            ([r.mass_kg, -1.0, 0.0, r.friction * r.mass_kg], f),
            // Corners: |q + h_L m_L r| <= b_L m_L, |q - h_R m_R r| <= b_R m_R.
            (
                [
                    -l.centroid_m * l.mass_kg,
                    0.0,
                    -1.0,
                    l.half_base_m * l.mass_kg,
                ],
                u,
            ),
            (
                [
                    l.centroid_m * l.mass_kg,
                    0.0,
                    1.0,
                    l.half_base_m * l.mass_kg,
                ],
                u,
            ),
            (
                [
                    r.centroid_m * r.mass_kg,
                    0.0,
                    -1.0,
                    r.half_base_m * r.mass_kg,
                ],
                u,
            ),
            (
                [
                    -r.centroid_m * r.mass_kg,
                    0.0,
                    1.0,
                    r.half_base_m * r.mass_kg,
                ],
                u,
            ),
        ]
    }

    /// The conditions of the pair at rest: a_g within its limits times g lambda.
    pub(super) fn rest_conditions(&self, inputs: &Inputs) -> [Constraint; 2] {
        let limits = self.rest_limits();
        let gl = scaled(&inputs.lambda, self.g_m_s2);
        let [lo, hi] = limits.ratios;
        [
            Constraint {
                series: add(&inputs.accel, &gl, -lo),
                scale: self.g_m_s2,
                guard: limits.guards[0],
                strict: false,
            },
            Constraint {
                series: add(&scaled(&inputs.accel, -1.0), &gl, hi),
                scale: self.g_m_s2,
                guard: limits.guards[1],
                strict: false,
            },
        ]
    }

    /// The conditions of the pair sliding together (`motion`, from [`Abutting::sliding`]):
    /// the push stays >= 0 (else the blocks part), and a line of action within the overlap
    /// keeps both seated, each pair of a lower and an upper bound on Q ordered.
    pub(super) fn sliding_conditions(&self, motion: &Pushed, inputs: &Inputs) -> Vec<Constraint> {
        let (l, r) = self.left_right();
        let force = (l.mass_kg + r.mass_kg) * self.g_m_s2;
        // The push is +n on the first contact's corner's body, the normal pointing into it:
        // on the right block it is +x either way.
        let push = motion.pushes[0];
        let right = &motion.bodies[self.right];
        let gl = scaled(&inputs.lambda, self.g_m_s2);
        let absolute = add(&inputs.accel, &series::derivative(&right.v), 1.0);
        let [y_lo, y_hi] = self.span_m;
        let moment = |b: Block, h_sign: f64, b_sign: f64| {
            let mut s = scaled(&absolute, h_sign * b.centroid_m * b.mass_kg);
            add_to(&mut s, &gl, b_sign * b.half_base_m * b.mass_kg);
            s
        };
        let lower = [
            scaled(&push, y_lo),
            moment(l, -1.0, -1.0),
            moment(r, 1.0, -1.0),
        ];
        let upper = [
            scaled(&push, y_hi),
            moment(l, -1.0, 1.0),
            moment(r, 1.0, 1.0),
        ];
        let mut out = vec![Constraint {
            series: motion.pushes[0],
            scale: force,
            guard: Guard::Parts,
            strict: false,
        }];
        for (i, lo) in lower.iter().enumerate() {
            for (j, hi) in upper.iter().enumerate() {
                if i != j {
                    out.push(Constraint {
                        series: add(hi, lo, -1.0),
                        scale: force * self.span_m[1].max(l.centroid_m).max(r.centroid_m),
                        guard: Guard::Uplift,
                        strict: false,
                    });
                }
            }
        }
        out
    }

    /// The corner both blocks would turn on where the pair stops being seated: the side the
    /// ground's inertial force on them points to, -(a_g + u'') (`absolute`).
    pub(super) fn tipping_corner(absolute: f64) -> Corner {
        Corner::of_sign(-absolute)
    }
}

/// The contact `t` of two blocks side by side, where a bottom corner of one is on the other's
/// face, as the corner of the block that turning on `pivot` would lift there: the left block's
/// where both turn to the left (its right corner rises off the ground), the right block's
/// where they turn to the right. Where the bottom corners are together the contact is either,
/// and only that one's corner moves off the face as the block lifts it.
pub(super) fn lifting_corner(t: &Touch, pivot: Corner) -> Touch {
    // The normal points into the corner's block: +x where it is the right one.
    let of_right = t.normal[0] > 0.0;
    let bottom = t.corner <= 1;
    if !bottom || of_right == (pivot == Corner::Right) {
        return *t;
    }
    Touch {
        blocks: [t.blocks[1], t.blocks[0]],
        sides: [t.sides[1], t.sides[0]],
        normal: [-t.normal[0], -t.normal[1]],
        // Bottom left (0) and bottom right (1) swap, and so do the right face (1) and the left
        // one (3).
        corner: 1 - t.corner,
        edge: 4 - t.edge,
        ..*t
    }
}

/// Both bodies' motion where they rest face on face: each at rest, the push left undetermined
/// (zero in the series; the conditions are the pair's).
pub(super) fn resting(members: [Member; 2], inputs: &Inputs) -> Pushed {
    let bodies = members.map(|m| match m {
        Member::Moves(body, mode, state) => {
            modes::trajectory(body, Equations::Exact, mode, state, inputs)
        }
        Member::Fixed => unreachable!("a pair face on face is of two bodies"),
    });
    Pushed {
        bodies,
        pushes: [ZERO; 2],
        compliance: [[0.0; 2]; 2],
        leaving: [0.0; 2],
    }
}

/// Both bodies' motion where they slide together face on face: the first contact `first`
/// keeps them together (its push moves a seated block only along the ground).
pub(super) fn sliding(first: &Couple, members: [Member; 2], inputs: &Inputs) -> Pushed {
    couple::pushed(&[first], members, inputs)
}

/// How two seated bodies move face on face: both at rest, or both sliding one way; none where
/// their modes part them.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Together {
    Rest,
    Slide(Slip),
}

impl Together {
    /// The pair's motion in the bodies' modes (`members`), if they move together.
    pub(super) fn of(members: [Member; 2]) -> Option<Together> {
        let modes = members.map(|m| match m {
            Member::Moves(_, mode, _) => Some(mode),
            Member::Fixed => None,
        });
        match modes {
            [Some(Mode::Rest), Some(Mode::Rest)] => Some(Together::Rest),
            [Some(Mode::Slide(a)), Some(Mode::Slide(b))] if a == b => Some(Together::Slide(a)),
            _ => None,
        }
    }
}

/// The larger of the two bodies' sizes (m), for ties of lengths.
fn members_size(members: [Member; 2]) -> f64 {
    members
        .iter()
        .map(|m| match m {
            Member::Moves(body, ..) => body.size_m(),
            Member::Fixed => 0.0,
        })
        .fold(0.0, f64::max)
}

/// The point where three planes c . x + c_3 = 0 meet, or none where they do not meet in one.
fn solve3(rows: [&[f64; 4]; 3]) -> Option<[f64; 3]> {
    let m = rows.map(|r| [r[0], r[1], r[2]]);
    let b = rows.map(|r| -r[3]);
    let det = |m: [[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(m);
    let size = m.iter().flatten().map(|x| x.abs()).fold(0.0, f64::max);
    if d.abs() <= 1e-12 * size * size * size {
        return None;
    }
    let mut x = [0.0; 3];
    for (c, xc) in x.iter_mut().enumerate() {
        let mut mc = m;
        for r in 0..3 {
            mc[r][c] = b[r];
        }
        *xc = det(mc) / d;
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A block `width` x `height` m, 0.5 m thick at 2,500 kg/m3.
    fn block(width: f64, height: f64, friction: f64) -> Block {
        Block {
            mass_kg: width * height * 0.5 * 2500.0,
            half_base_m: width / 2.0,
            centroid_m: height / 2.0,
            friction,
        }
    }

    fn pair(left: Block, right: Block, span_m: [f64; 2]) -> Abutting {
        Abutting {
            blocks: [right, left],
            right: 0,
            span_m,
            g_m_s2: 9.81,
        }
    }

    /// Two squat blocks (b/h = 1) with friction 0.4: neither can lift before it slides, and the
    /// push cannot help either hold more than its own friction, so the pair rests while
    /// |a_g| <= 0.4 g, the limits friction's, to round-off.
    #[test]
    fn squat_blocks_rest_while_friction_holds_each() {
        let p = pair(block(1.2, 1.2, 0.4), block(0.8, 0.8, 0.4), [0.0, 0.8]);
        let limits = p.rest_limits();
        for (x, want) in limits.ratios.iter().zip([-0.4, 0.4]) {
            assert!((x - want).abs() <= 1e-15, "{limits:?}");
        }
        assert_eq!(limits.guards, [Guard::StickLimit; 2]);
    }

    /// A slab 0.3 x 1.2 m (b/h = 1/4) left of a block 1.2 x 1.2 m, friction 0.6. The ground
    /// accelerating to +x tips the slab left, away from the block, which cannot hold it: it
    /// lifts at its own b/h. Accelerating to -x tips it onto the block, which holds it with a
    /// push Q = P y at most P y_hi = 1.2 P, P no more than the block's spare friction
    /// m_W (0.6 - x): the slab needs Q >= m_S (h_S x - b_S), so it rests while
    /// 450 (0.6 x - 0.15) <= 1.2 * 1800 (0.6 - x), x <= 1363.5 / 2430, before the block would
    /// tip (x <= 0.85) or the pair slide (x <= 0.6). Each limit is an unloaded corner's.
    #[test]
    fn a_block_holds_a_slab_leaning_on_it_until_its_friction_is_spent() {
        let p = pair(block(0.3, 1.2, 0.6), block(1.2, 1.2, 0.6), [0.0, 1.2]);
        let limits = p.rest_limits();
        let [lo, hi] = limits.ratios;
        assert!((hi - 0.25).abs() <= 1e-15, "{limits:?}");
        assert!((lo + 1363.5 / 2430.0).abs() <= 1e-15, "{limits:?}");
        assert_eq!(limits.guards, [Guard::Uplift; 2]);
        // Mirrored, the slab on the right (listed second), the limits swap sides.
        let mirrored = Abutting {
            right: 1,
            blocks: [block(1.2, 1.2, 0.6), block(0.3, 1.2, 0.6)],
            ..p
        };
        let flipped = mirrored.rest_limits();
        assert!((flipped.ratios[0] + 0.25).abs() <= 1e-15, "{flipped:?}");
        assert!(
            (flipped.ratios[1] - 1363.5 / 2430.0).abs() <= 1e-15,
            "{flipped:?}"
        );
    }

    /// Where the bottom corners of two blocks side by side are together, the contact there is
    /// the corner of the block that turning on the pivot would lift: the left block's bottom
    /// right corner on the right block's left face where they turn left, the right block's
    /// bottom left corner on the left block's right face where they turn right.
    #[test]
    fn the_bottom_contact_is_the_corner_a_turn_lifts() {
        let right_on_left = Touch {
            blocks: [1, 0],
            sides: [Side::Body(1, [0.9, 0.0]), Side::Body(0, [0.3, 0.0])],
            point: [0.6, 0.0],
            normal: [1.0, 0.0],
            scales: (0.1, 1.0),
            pair: 0,
            corner: 0,
            edge: 1,
            stays: true,
        };
        assert_eq!(lifting_corner(&right_on_left, Corner::Right), right_on_left);
        let left_on_right = lifting_corner(&right_on_left, Corner::Left);
        assert_eq!(left_on_right.blocks, [0, 1]);
        assert_eq!((left_on_right.corner, left_on_right.edge), (1, 3));
        assert_eq!(left_on_right.normal, [-1.0, 0.0]);
        assert_eq!(left_on_right.point, right_on_left.point);
        assert_eq!(lifting_corner(&left_on_right, Corner::Right), right_on_left);
        // A top corner is left as it is.
        let top = Touch {
            corner: 3,
            point: [0.6, 1.2],
            ..right_on_left
        };
        assert_eq!(lifting_corner(&top, Corner::Left), top);
    }
}
