//! Setting a time-stepped wall down for the exact sliding engine (`--after-uplift
//! moreau-while-rocking`): when every block is seated again and calm (it has stopped turning,
//! or turns with too little energy to lift a corner more than a micrometre), its rotation and
//! vertical motion are dropped, faces the stepper holds together are closed
//! exactly, and blocks it moves together within its tolerance are given one velocity, so that
//! the exact engine finds stuck and touching the joints that the stepper held so.

use crate::sets::DisjointSets;
use crate::topology::{Base, Topology};
use nalgebra::{Vector2, Vector3};

/// A block is seated when every corner of its horizontal joints is within this of the face it
/// rests on (m), or inside it: Moreau-Jean projects no position back, so a block lands up to a
/// step's travel inside its support and stays there, and a block on two supports that sank
/// unequally stands off one of them (by 1e-5 m on the Ollantaytambo wall at dt = 1e-3 s). A
/// tenth of a millimetre is above that drift and below any rocking that matters: what setting
/// the wall down flat moves a corner by at most.
pub const SEATED_M: f64 = 1e-4;

/// ... and its corners move at most this fast (m/s); horizontal velocities closer than this are
/// one (joints the stepper holds stuck differ by the round-off of its sweeps, near 1e-14 m/s).
pub const SEATED_M_S: f64 = 1e-6;

/// A block is calm when its energy above its seat could lift a corner of its base no higher
/// than this (m), a hundredth of [`SEATED_M`]: rocking that small, handed to the sliding model
/// as its seated state, changes where blocks end by micrometres (the slab beside a block under a
/// sine, docs/rocking-walls.md), while a slab that rattles between two monoliths at a few
/// micrometres, which the stepper never stills, is calm.
pub const CALM_M: f64 = 1e-6;

/// Steps in a row for which every block must be seated and calm before the wall is set down:
/// a block that rocks passes through its seat at speed, and one step can be a transient of the
/// solver.
pub const SEATED_STEPS: u32 = 10;

/// A block `half`-sized, of radius of gyration squared `gyration_m2` (its moment of inertia
/// over its mass, m2), turned by `theta` (rad) and moving at `v` (its centre's velocity and its
/// rotation's) under gravity `g_m_s2`, is calm: it neither turns nor rises or sinks faster than
/// [`SEATED_M_S`] (a pose the stepper froze slightly turned, within [`SEATED_M`], is kept as
/// seated), or its energy above its seat (of its turning, of its vertical motion and of its
/// tilt: at the top of a rocking swing it hardly turns) could lift a corner of its base no
/// higher than [`CALM_M`] on still ground.
pub fn calm(
    half: Vector2<f64>,
    gyration_m2: f64,
    theta: f64,
    v: &Vector3<f64>,
    g_m_s2: f64,
) -> bool {
    let still = v.y.abs() + v.z.abs() * half.norm() <= SEATED_M_S;
    let energy_j_kg =
        0.5 * (v.y * v.y + gyration_m2 * v.z * v.z) + g_m_s2 * rise_m(half, theta).max(0.0);
    let bound_j_kg = g_m_s2 * rise_m(half, (CALM_M / (2.0 * half.x)).min(1.0).asin());
    still || energy_j_kg <= bound_j_kg
}

/// How far the centre of a block `half`-sized rises when it turns by `theta` about a corner of
/// its base (m); negative for a block so slender that it sinks first.
pub fn rise_m(half: Vector2<f64>, theta: f64) -> f64 {
    half.x * theta.abs().sin() - half.y * (1.0 - theta.cos())
}

/// The horizontal displacements (m) and velocities (m/s) of the blocks set down flat from those
/// of the middles of their bases, `u` and `v` (a block turns back about it: where it rests is
/// kept, not where its centroid was; abutments (`free` false) and blocks `gone` (fallen) are
/// left where they are, at rest, and a block gone touches nothing, as in the exact engine):
/// faces of vertical joints within [`SEATED_M`] of touching closed exactly, moving the blocks
/// of each group of touching blocks from its abutment or, where it has none, from its first
/// block (faces apart that approach faster than [`SEATED_M_S`] are left apart, for the
/// exact engine to find their impact, unless the placing pushed them into each other); blocks
/// joined by joints that slip at most [`SEATED_M_S`] given their common velocity (momentum
/// kept), zero where the group reaches the ground or an abutment.
pub fn set_down(
    topo: &Topology,
    u: &[f64],
    v: &[f64],
    free: &[bool],
    gone: &[bool],
) -> (Vec<f64>, Vec<f64>) {
    let n = u.len();
    let moves: Vec<bool> = (0..n).map(|i| free[i] && !gone[i]).collect();
    let gap = |u: &[f64], j: usize| {
        let jt = &topo.vertical[j];
        jt.gap_m.to_f64() + u[jt.right.0] - u[jt.left.0]
    };
    let live = |j: usize| {
        let (l, r) = (topo.vertical[j].left.0, topo.vertical[j].right.0);
        !gone[l] && !gone[r] && (moves[l] || moves[r])
    };
    let vx = |i: usize| if moves[i] { v[i] } else { 0.0 };
    let closing = |j: usize| {
        let jt = &topo.vertical[j];
        let g = gap(u, j);
        g <= 0.0 || (g <= SEATED_M && vx(jt.left.0) - vx(jt.right.0) <= SEATED_M_S)
    };
    let mut is_closed: Vec<bool> = (0..topo.vertical.len())
        .map(|j| live(j) && closing(j))
        .collect();
    // Placing a group moves its blocks by the stepper's gaps along it (hundredths of a
    // millimetre over a course), which can push faces left apart into each other: those touch
    // after all, and the groups they join are placed again as one. The exact engine refuses
    // faces that overlap (it would find them closing at every event of its first instant); a
    // course between two abutments is never pushed so, placed from either it fits the other.
    let (u, closed) = loop {
        let closed: Vec<usize> = (0..is_closed.len()).filter(|&j| is_closed[j]).collect();
        let placed = place(topo, u, &moves, &closed);
        let mut pushed = false;
        for (j, closed) in is_closed.iter_mut().enumerate() {
            if !*closed && live(j) && gap(&placed, j) < 0.0 {
                *closed = true;
                pushed = true;
            }
        }
        if !pushed {
            break (placed, closed);
        }
    };
    // Velocities: the ground is element n.
    let mut together = DisjointSets::new(n + 1);
    for j in &topo.horizontal {
        let lower = match j.lower {
            Base::Ground => n,
            Base::Block(b) => b.0,
        };
        let v_lower = if lower == n { 0.0 } else { vx(lower) };
        if (vx(j.upper.0) - v_lower).abs() <= SEATED_M_S {
            together.join(j.upper.0, lower);
        }
    }
    for &j in &closed {
        let (l, r) = (topo.vertical[j].left.0, topo.vertical[j].right.0);
        if (vx(l) - vx(r)).abs() <= SEATED_M_S {
            together.join(l, r);
        }
    }
    for i in (0..n).filter(|&i| !moves[i]) {
        together.join(i, n);
    }
    let mass: Vec<f64> = topo.blocks.iter().map(|b| b.mass_kg.to_f64()).collect();
    let mut momentum = vec![(0.0, 0.0); n + 1];
    for (i, m) in mass.iter().enumerate() {
        let root = together.find(i);
        momentum[root].0 += m * vx(i);
        momentum[root].1 += m;
    }
    let ground = together.find(n);
    let vel = (0..n)
        .map(|i| match together.find(i) {
            root if root == ground => 0.0,
            root => momentum[root].0 / momentum[root].1,
        })
        .collect();
    (u, vel)
}

/// The displacements `u` (m) with the faces of the `closed` vertical joints made to touch:
/// each group of touching blocks placed outward from its anchor, a block that does not move
/// (`moves` false: an abutment; a block gone is in no closed joint, so anchors only itself), or
/// else from its first block.
fn place(topo: &Topology, u: &[f64], moves: &[bool], closed: &[usize]) -> Vec<f64> {
    let n = u.len();
    let mut u = u.to_vec();
    let mut placed: Vec<bool> = moves.iter().map(|m| !m).collect();
    let mut touching = DisjointSets::new(n);
    for &j in closed {
        touching.join(topo.vertical[j].left.0, topo.vertical[j].right.0);
    }
    let anchored: Vec<bool> = {
        let mut a = vec![false; n];
        for i in (0..n).filter(|&i| !moves[i]) {
            a[touching.find(i)] = true;
        }
        a
    };
    for (i, placed) in placed.iter_mut().enumerate() {
        let root = touching.find(i);
        if !anchored[root] && root == i {
            *placed = true;
        }
    }
    let mut changed = true;
    while changed {
        changed = false;
        for &j in closed {
            let jt = &topo.vertical[j];
            let (l, r, gap0) = (jt.left.0, jt.right.0, jt.gap_m.to_f64());
            match (placed[l], placed[r]) {
                (true, false) => u[r] = u[l] - gap0,
                (false, true) => u[l] = u[r] + gap0,
                _ => continue,
            }
            placed[l] = true;
            placed[r] = true;
            changed = true;
        }
    }
    u
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::SimulationError;
    use crate::integrate::event::EventDriven;
    use crate::integrate::{Scenario, Settings};
    use crate::motion::{Motion, Sine};
    use crate::wall::Wall;

    fn row_of_three() -> Wall {
        Wall::from_ron_str(
            "(version: 1, name: \"row\", thickness_m: 1, density_kg_m3: 2000, friction: 0.5,
              restitution: 1, rows: [(height_m: 1, blocks: [(width_m: 1), (width_m: 1),
              (width_m: 1)])])",
        )
        .unwrap()
    }

    /// A block 0.3 m by 1.2 m: calm at rest; turning with the energy that lifts a corner
    /// [`CALM_M`], calm below it and not above, by a part in a million; at the top of a rocking
    /// swing (turned, hardly turning) calm only while its tilt lifts a corner less than that.
    #[test]
    fn a_block_is_calm_while_its_energy_lifts_a_corner_less_than_the_bound() {
        let (half, g) = (Vector2::new(0.15, 0.6), 9.81);
        let gyration = (0.3f64.powi(2) + 1.2f64.powi(2)) / 12.0;
        assert!(calm(half, gyration, 0.0, &Vector3::zeros(), g));
        // The tilt that lifts a corner CALM_M, and the rate of turning with that energy.
        let tilt = (CALM_M / 0.3).asin();
        let omega = (2.0 * g * rise_m(half, tilt) / gyration).sqrt();
        for (scale, is_calm) in [(1.0 - 1e-6, true), (1.0 + 1e-6, false)] {
            let turning = Vector3::new(0.0, 0.0, omega * scale);
            assert_eq!(calm(half, gyration, 0.0, &turning, g), is_calm);
        }
        // Turning just faster than stillness allows: an energy a ten-millionth of the bound.
        let barely = Vector3::new(0.0, 0.0, 2.0 * SEATED_M_S / half.norm());
        for (scale, is_calm) in [(1.0 - 1e-3, true), (1.0 + 1e-3, false)] {
            assert_eq!(calm(half, gyration, -tilt * scale, &barely, g), is_calm);
        }
        // A pose the stepper froze turned is still, so calm (whether it is seated is the
        // position check's, SEATED_M).
        assert!(calm(half, gyration, 1e-4, &Vector3::zeros(), g));
    }

    /// Three blocks in a row on the ground, the middle 1e-6 m into the left and the right 3e-6 m
    /// into the middle; the right one sliding at 0.1 m/s, the two others stuck but for round-off.
    #[test]
    fn touching_faces_close_and_stuck_blocks_stop() {
        let wall = row_of_three();
        let topo = Topology::new(&wall).unwrap();
        let (u, vel) = set_down(
            &topo,
            &[0.01, 0.01 - 1e-6, 0.01 - 4e-6],
            &[1e-14, -1e-14, 0.1],
            &[true; 3],
            &[false; 3],
        );
        assert_eq!(u[0], 0.01);
        // Closed to the bit from A: B's and C's left faces at A's right.
        assert_eq!(u[1], u[0]);
        assert_eq!(u[2], u[1]);
        assert_eq!(vel, vec![0.0, 0.0, 0.1]);
        // C 2e-6 m clear of B and closing on it at 0.1 m/s: left apart, its impact to come.
        let (u, _) = set_down(
            &topo,
            &[0.01, 0.01, 0.01 + 2e-6],
            &[0.0, 0.0, -0.1],
            &[true; 3],
            &[false; 3],
        );
        assert_eq!(u, vec![0.01, 0.01, 0.01 + 2e-6]);
    }

    /// A and B slide at 0.1 m/s, B 3e-6 m into A; C stands 2e-6 m clear of B, which closes on
    /// it: left apart. Placing B at A's face moves it 1e-6 m into C, so B and C touch after all
    /// and C is placed too, every face closed to the bit. Left overlapping, the exact engine
    /// found the faces closing at every event of its first instant and stopped with "no
    /// progress" (F3 and M4 of the Ollantaytambo wall under El Centro at 0.4 g); now it
    /// refuses such a state, and set down closed it resolves B's impact on C and goes on.
    #[test]
    fn faces_that_placing_pushes_into_each_other_touch() {
        let wall = row_of_three();
        let topology = Topology::new(&wall).unwrap();
        let (u, vel) = set_down(
            &topology,
            &[0.01, 0.01 - 3e-6, 0.01 - 1e-6],
            &[0.1, 0.1, 0.0],
            &[true; 3],
            &[false; 3],
        );
        assert_eq!(u, vec![0.01; 3]);
        assert_eq!(vel, vec![0.1, 0.1, 0.0]);
        let motion = Motion::sine(Sine {
            amplitude_m_s2: 0.1,
            frequency_hz: 1.0,
            phase_rad: 0.0,
            duration_s: 1.0,
        })
        .unwrap();
        let settings = Settings::summary_only(1.0);
        let sc = Scenario {
            wall: &wall,
            topology: &topology,
            motion: &motion,
            settings: &settings,
        };
        let check =
            |u: &[f64]| EventDriven::default().lifts_within(&sc, (0.0, u, &vel, &[false; 3]), 0.01);
        assert_eq!(check(&u), Ok(false));
        // Set down overlapping, the state is refused by name, as a bug of the set-down.
        match check(&[0.01, 0.01, 0.01 - 1e-6]) {
            Err(SimulationError::Bug(why)) => assert!(
                why.contains("at t = 0 s has B2 and B3 overlapping by 9.99"),
                "{why}"
            ),
            other => panic!("{other:?}"),
        }
    }

    /// C fell, and lies where it went 1e-6 m into B's place: A and B are set down where they
    /// are, as the exact engine sees them (a block gone touches nothing), not placed against C.
    #[test]
    fn a_block_gone_anchors_nothing() {
        let topo = Topology::new(&row_of_three()).unwrap();
        let u = [0.01, 0.01, 0.01 - 1e-6];
        let (set, vel) = set_down(
            &topo,
            &u,
            &[0.05, 0.05, 0.3],
            &[true; 3],
            &[false, false, true],
        );
        assert_eq!(set, u);
        assert_eq!(vel, vec![0.05, 0.05, 0.0]);
    }
}
