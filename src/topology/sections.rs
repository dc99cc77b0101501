//! The wall across its plane: above each bed joint that runs through the whole wall, the part of
//! the wall on it is one rigid body of the wall's thickness that can rock about the joint's edge
//! (out-of-plane). This module owns those sections, their static thresholds (the ground
//! acceleration, in g, that starts them rocking) and their capacity curves lambda(theta), for a
//! wall free at its top (a cantilever) or held at its top (a one-way spanning wall), with an
//! overburden on top.
//!
//! Every threshold and curve comes from one principle, virtual work on the exact kinematics of
//! the mechanism: lambda(theta) = (d/dtheta of the raised weight) / (d/dtheta of the horizontal
//! displacement of the masses), with every mass at the middle of the thickness and the
//! overburden at the middle of the top, carried down without inertia of its own (a floor or a
//! roof held sideways by other walls). Free top: the body pivots on the joint's edge, lambda0
//! = (b / h_c)(1 + P / W) and lambda = tan(alpha - theta) without overburden (Housner). Held
//! top: the lower half pivots on the joint's edge, the upper half on the top's edge (which may
//! rise), and they hinge at mid-height on the other face; lambda0 = 4 t / H for a uniform wall
//! (Doherty et al. 2002), more with overburden.

use super::{Base, Topology};
use crate::wall::Wall;

/// How the top of the wall is held across its plane.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
#[serde(rename_all = "lowercase")]
pub enum Top {
    /// Free: each section is a cantilever rocking on its bed joint.
    #[default]
    Free,
    /// Held sideways (a floor or roof): each section spans one way, hinging at mid-height.
    Restrained,
}

/// The part of a wall above one bed joint, as one body across the wall's plane.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Section {
    /// `above_<level>m`.
    pub name: String,
    /// Height of the bed joint (m).
    pub level_m: f64,
    /// Blocks in the section.
    pub blocks: usize,
    /// Its length along the wall, from the leftmost to the rightmost block (m).
    pub length_m: f64,
    /// Height from the joint to the highest top (m).
    pub height_m: f64,
    /// Thickness of the wall (m).
    pub thickness_m: f64,
    /// Mass (kg).
    pub mass_kg: f64,
    /// Height of the centroid above the joint (m).
    pub centroid_height_m: f64,
    /// Moment of inertia about the centroid for rotation about the wall's axis (kg m2).
    pub inertia_kg_m2: f64,
    /// Friction of the bed joint, weighted by the loads its contacts carry.
    pub friction: f64,
    /// Mass and first moment about the joint (kg, kg m) of the part below mid-height.
    lower_half: (f64, f64),
    /// The same above mid-height.
    upper_half: (f64, f64),
    /// Gravity (m/s2).
    pub g_m_s2: f64,
}

/// Bed joints that were not checked, and why (a block crosses the level, or an abutment stands
/// in the part above).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Skipped {
    /// Height of the level (m).
    pub level_m: f64,
    /// Why.
    pub why: String,
}

/// A level written as in names and tables: to the micrometre, without trailing zeros.
fn level_text(y: f64) -> String {
    let s = format!("{:.6}", y);
    let s = s.trim_end_matches('0').trim_end_matches('.');
    s.to_string()
}

/// The sections of a wall: one for every level where blocks rest (the ground and every bed
/// joint) that no block crosses and no abutment stands above.
pub fn sections(wall: &Wall, topo: &Topology) -> (Vec<Section>, Vec<Skipped>) {
    let t = wall.thickness_m.to_f64();
    let mut levels: Vec<_> = wall.blocks.iter().map(|b| b.y.clone()).collect();
    levels.sort();
    levels.dedup();
    let mut out = Vec::new();
    let mut skipped = Vec::new();
    for level in levels {
        let y = level.to_f64();
        if let Some(b) = wall.blocks.iter().find(|b| b.y < level && b.top() > level) {
            skipped.push(Skipped {
                level_m: y,
                why: format!(
                    "block {} crosses it: the joint does not run through the wall",
                    b.name
                ),
            });
            continue;
        }
        let above: Vec<usize> = (0..wall.blocks.len())
            .filter(|&i| wall.blocks[i].y >= level)
            .collect();
        if let Some(&i) = above.iter().find(|&&i| wall.blocks[i].fixed) {
            skipped.push(Skipped {
                level_m: y,
                why: format!(
                    "abutment {} stands above it and holds it",
                    wall.blocks[i].name
                ),
            });
            continue;
        }
        out.push(section(wall, topo, &level, &above, t));
    }
    (out, skipped)
}

fn section(wall: &Wall, topo: &Topology, level: &crate::Q, above: &[usize], t: f64) -> Section {
    let y0 = level.to_f64();
    let mut mass = 0.0;
    let mut moment = 0.0;
    let mut top = f64::NEG_INFINITY;
    let (mut left, mut right) = (f64::INFINITY, f64::NEG_INFINITY);
    for &i in above {
        let b = &wall.blocks[i];
        let m = topo.blocks[i].mass_kg.to_f64();
        mass += m;
        moment += m * (b.y.to_f64() + 0.5 * b.height.to_f64() - y0);
        top = top.max(b.top().to_f64() - y0);
        left = left.min(b.x.to_f64());
        right = right.max(b.right().to_f64());
    }
    let hc = moment / mass;
    let mid = 0.5 * top;
    let (mut inertia, mut lower, mut upper) = (0.0, (0.0, 0.0), (0.0, 0.0));
    for &i in above {
        let b = &wall.blocks[i];
        let m = topo.blocks[i].mass_kg.to_f64();
        let (lo, h) = (b.y.to_f64() - y0, b.height.to_f64());
        let d = lo + 0.5 * h - hc;
        inertia += m * (t * t + h * h) / 12.0 + m * d * d;
        // The block's mass split at mid-height, uniform over its height.
        let (below, beyond) = ((lo, (lo + h).min(mid)), (lo.max(mid), lo + h));
        for (part, (a, z)) in [(&mut lower, below), (&mut upper, beyond)] {
            if z > a {
                let share = m * (z - a) / h;
                part.0 += share;
                part.1 += share * 0.5 * (a + z);
            }
        }
    }
    // Friction of the bed joint: the contacts of the blocks resting at this level, weighted by
    // the loads they carry.
    let (mut weighted, mut load) = (0.0, 0.0);
    for s in &topo.horizontal {
        let upper_block = &wall.blocks[s.upper.0];
        let here = &upper_block.y == level
            && match s.lower {
                Base::Ground => true,
                Base::Block(l) => !above.contains(&l.0),
            };
        if here {
            weighted += s.friction.to_f64() * s.load_n.to_f64();
            load += s.load_n.to_f64();
        }
    }
    Section {
        name: format!("above_{}m", level_text(y0)),
        level_m: y0,
        blocks: above.len(),
        length_m: right - left,
        height_m: top,
        thickness_m: t,
        mass_kg: mass,
        centroid_height_m: hc,
        inertia_kg_m2: inertia,
        friction: if load > 0.0 {
            weighted / load
        } else {
            wall.friction.to_f64()
        },
        lower_half: lower,
        upper_half: upper,
        g_m_s2: wall.g_m_s2.to_f64(),
    }
}

impl Section {
    /// The ground acceleration (in g) that starts the section rocking, with an overburden of
    /// `overburden_n` (N) on its top.
    pub fn threshold_g(&self, top: Top, overburden_n: f64) -> f64 {
        self.capacity(top, overburden_n, 0.0)
    }

    /// lambda(theta): the ground acceleration (in g) that holds the mechanism in equilibrium
    /// at rotation theta (rad), by virtual work on its exact kinematics (module notes).
    pub fn capacity(&self, top: Top, overburden_n: f64, theta: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        let t = self.thickness_m;
        let h = self.height_m;
        // Weights enter divided by g: the overburden as the mass it weighs.
        let p = overburden_n / self.g_m_s2;
        match top {
            Top::Free => {
                let (m, first) = (self.mass_kg, self.mass_kg * self.centroid_height_m);
                let raised = m * (0.5 * t * c) - first * s + p * (0.5 * t * c - h * s);
                let moved = m * 0.5 * t * s + first * c;
                raised / moved
            }
            Top::Restrained => {
                let (mb, sb) = self.lower_half;
                let (mt, st) = self.upper_half;
                let raised = mb * 0.5 * t * c - sb * s + mt * 1.5 * t * c - st * s
                    + p * (1.5 * t * c - h * s);
                let moved = mb * 0.5 * t * s + sb * c + mt * 0.5 * t * s + (mt * h - st) * c;
                raised / moved
            }
        }
    }

    /// The rotation (rad) at which the capacity falls to zero: past it the section falls under
    /// its own weight.
    pub fn zero_capacity_rotation_rad(&self, top: Top, overburden_n: f64) -> f64 {
        let (mut lo, mut hi) = (0.0, std::f64::consts::FRAC_PI_2);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid <= lo || mid >= hi {
                break;
            }
            if self.capacity(top, overburden_n, mid) > 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        lo
    }

    /// The capacity curve: `points` rotations from 0 to the zero-capacity rotation, with
    /// lambda at each.
    pub fn capacity_curve(&self, top: Top, overburden_n: f64, points: usize) -> Vec<(f64, f64)> {
        let end = self.zero_capacity_rotation_rad(top, overburden_n);
        (0..points)
            .map(|k| {
                let theta = end * k as f64 / (points - 1) as f64;
                (theta, self.capacity(top, overburden_n, theta).max(0.0))
            })
            .collect()
    }
}

/// One point of a capacity curve.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct CapacityPoint {
    /// Rotation (rad).
    pub theta_rad: f64,
    /// Ground acceleration in equilibrium there (g).
    pub lambda_g: f64,
}

/// A section's static check across the plane.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct SectionCheck {
    /// The section.
    #[serde(flatten)]
    pub section: Section,
    /// The overburden on its top (N).
    pub overburden_n: f64,
    /// The ground acceleration that starts it rocking (g).
    pub threshold_g: f64,
    /// The same in m/s2.
    pub threshold_m_s2: f64,
    /// The rotation at which its capacity falls to zero (rad).
    pub zero_capacity_rotation_rad: f64,
    /// lambda(theta) from 0 to that rotation.
    pub capacity_curve: Vec<CapacityPoint>,
}

/// The static check of a whole wall across its plane (`pirqa check --out-of-plane`).
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct OutOfPlaneCheck {
    /// Wall name.
    pub wall: String,
    /// How the top is held.
    pub top: Top,
    /// Load on top (kN per metre of wall).
    pub overburden_kn_m: f64,
    /// Gravity (m/s2).
    pub g_m_s2: f64,
    /// Every section checked.
    pub sections: Vec<SectionCheck>,
    /// The section with the lowest threshold.
    pub lowest_threshold: Option<String>,
    /// Levels not checked, and why.
    pub skipped: Vec<Skipped>,
}

/// Points of each capacity curve.
pub const CURVE_POINTS: usize = 41;

/// Checks every section of a wall across its plane, with the top held as `top` and a line
/// load of `overburden_kn_m` on it.
pub fn check(wall: &Wall, topo: &Topology, top: Top, overburden_kn_m: f64) -> OutOfPlaneCheck {
    let (all, skipped) = sections(wall, topo);
    let g = wall.g_m_s2.to_f64();
    let checks: Vec<SectionCheck> = all
        .into_iter()
        .map(|s| {
            let p = overburden_kn_m * 1e3 * s.length_m;
            let threshold_g = s.threshold_g(top, p);
            let capacity_curve = s
                .capacity_curve(top, p, CURVE_POINTS)
                .into_iter()
                .map(|(theta_rad, lambda_g)| CapacityPoint {
                    theta_rad,
                    lambda_g,
                })
                .collect();
            SectionCheck {
                overburden_n: p,
                threshold_g,
                threshold_m_s2: threshold_g * g,
                zero_capacity_rotation_rad: s.zero_capacity_rotation_rad(top, p),
                capacity_curve,
                section: s,
            }
        })
        .collect();
    let lowest_threshold = checks
        .iter()
        .min_by(|a, b| a.threshold_g.total_cmp(&b.threshold_g))
        .map(|c| c.section.name.clone());
    OutOfPlaneCheck {
        wall: wall.name.clone(),
        top,
        overburden_kn_m,
        g_m_s2: g,
        sections: checks,
        lowest_threshold,
        skipped,
    }
}
