//! The wall's graph: horizontal joints (who rests on whom, with which overlap, load and friction
//! capacity) and vertical joints (who can hit whom, across which gap). Loads follow the
//! tributary rule of the paper's eq. (3); everything here is exact.
//!
//! One vocabulary throughout the code: a *joint* is a contact between two blocks (or a block and
//! the ground); a *horizontal joint* ([`HorizontalJoint`], [`HorizontalId`],
//! [`Topology::horizontal`]) is where a block rests on another and friction acts; a *vertical
//! joint* ([`VerticalJoint`], [`VerticalId`], [`Topology::vertical`]) is where neighbours can
//! collide; [`JointRef`] names either. *Support* is the relation (the lower block supports the
//! upper one: the support graph, a block's support span), not an edge.

mod lists;
pub mod sections;

pub use lists::Lists;

use crate::error::WallError;
use crate::exact::Q;
use crate::wall::Wall;
use std::collections::{BTreeMap, HashMap};

/// Index of a block in [`Wall::blocks`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub struct BlockId(pub usize);

/// Index of a horizontal joint in [`Topology::horizontal`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct HorizontalId(pub usize);

/// Index of a vertical joint in [`Topology::vertical`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct VerticalId(pub usize);

/// A joint of the wall, either kind: a horizontal joint (where a block rests on another and friction acts) or
/// a vertical joint between neighbours (where they collide).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum JointRef {
    /// A horizontal joint.
    Horizontal(HorizontalId),
    /// A vertical joint.
    Vertical(VerticalId),
}

/// What a block rests on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Base {
    /// The foundation.
    Ground,
    /// Another block (possibly a fixed abutment).
    Block(BlockId),
}

/// A horizontal joint: `upper` rests on `lower` along `overlap_m`.
#[derive(Debug, Clone, PartialEq)]
pub struct HorizontalJoint {
    /// The block on top.
    pub upper: BlockId,
    /// What it rests on.
    pub lower: Base,
    /// Length of the contact (m).
    pub overlap_m: Q,
    /// Normal load carried (N): the upper block's load P times its share of the contact length.
    pub load_n: Q,
    /// Friction coefficient.
    pub friction: Q,
    /// Friction capacity F = friction * load (N).
    pub capacity_n: Q,
}

/// A vertical joint: `left`'s right face looks at `right`'s left face across `gap_m`.
#[derive(Debug, Clone, PartialEq)]
pub struct VerticalJoint {
    /// Block on the left.
    pub left: BlockId,
    /// Block on the right.
    pub right: BlockId,
    /// Open gap (m, 0 = touching).
    pub gap_m: Q,
    /// Height the two faces share (m).
    pub height_m: Q,
}

/// Per-block data derived from the wall.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockData {
    /// Mass (kg).
    pub mass_kg: Q,
    /// Own weight (N).
    pub weight_n: Q,
    /// Total load P passed to its supports: own weight plus what rests on it (N).
    pub load_n: Q,
}

/// The support and vertical-joint graph of a wall.
#[derive(Debug, Clone, PartialEq)]
pub struct Topology {
    /// Per block, in wall order.
    pub blocks: Vec<BlockData>,
    /// Horizontal joints, ordered by upper block then by position.
    pub horizontal: Vec<HorizontalJoint>,
    /// Vertical joints, ordered by left block then by position.
    pub vertical: Vec<VerticalJoint>,
    /// Per block: the supports it rests on.
    pub below: Lists<HorizontalId>,
    /// Per block: the supports resting on it.
    pub above: Lists<HorizontalId>,
    /// Per block: vertical joints on its left and right faces.
    pub sides: Lists<VerticalId>,
}

impl Topology {
    /// Builds the graph and checks what needs it: every movable block rests on something, no
    /// block would topple at rest, abutments stand on fixed ground, and every friction override
    /// names a real horizontal joint. The wall is one [`Wall::from_description`] accepted (no two
    /// blocks overlap, which the searches here rely on).
    pub fn new(wall: &Wall) -> Result<Topology, WallError> {
        let n = wall.blocks.len();
        let rights: Vec<Q> = wall.blocks.iter().map(|b| b.right()).collect();
        // The blocks whose top is at each height, left to right: blocks with one top do not
        // overlap, so a block's supports are a run of them found by bisection.
        let mut by_top: BTreeMap<Q, Vec<usize>> = BTreeMap::new();
        for (i, b) in wall.blocks.iter().enumerate() {
            by_top.entry(b.top()).or_default().push(i);
        }
        for row in by_top.values_mut() {
            row.sort_by(|&p, &q| wall.blocks[p].x.cmp(&wall.blocks[q].x));
        }

        let mut horizontal = Vec::new();
        let mut below = vec![Vec::new(); n];
        let mut above = vec![Vec::new(); n];
        for (i, b) in wall.blocks.iter().enumerate() {
            let mut found: Vec<(Base, Q)> = Vec::new();
            if b.y.is_zero() {
                found.push((Base::Ground, b.width.clone()));
            } else if let Some(row) = by_top.get(&b.y) {
                let first = row.partition_point(|&j| rights[j] <= b.x);
                for &j in row[first..]
                    .iter()
                    .take_while(|&&j| wall.blocks[j].x < rights[i])
                {
                    let l = &wall.blocks[j];
                    let overlap =
                        rights[j].clone().min(rights[i].clone()) - l.x.clone().max(b.x.clone());
                    if overlap.is_positive() {
                        if b.fixed && !l.fixed {
                            return Err(WallError::FixedOnMovable {
                                fixed: b.name.clone(),
                                movable: l.name.clone(),
                            });
                        }
                        found.push((Base::Block(BlockId(j)), overlap));
                    }
                }
            }
            if b.fixed {
                continue;
            }
            if found.is_empty() {
                return Err(WallError::Floating {
                    block: b.name.clone(),
                    origin: b.origin.clone(),
                    y_m: b.y.to_f64(),
                    x0_m: b.x.to_f64(),
                    x1_m: b.right().to_f64(),
                });
            }
            for (lower, overlap_m) in found {
                let id = HorizontalId(horizontal.len());
                below[i].push(id);
                if let Base::Block(j) = lower {
                    above[j.0].push(id);
                }
                horizontal.push(HorizontalJoint {
                    upper: BlockId(i),
                    lower,
                    overlap_m,
                    load_n: Q::zero(),
                    friction: wall.friction.clone(),
                    capacity_n: Q::zero(),
                });
            }
        }

        let mut blocks: Vec<BlockData> = (0..n)
            .map(|i| {
                let mass_kg = wall.mass_kg(i);
                let weight_n = &mass_kg * &wall.g_m_s2;
                BlockData {
                    mass_kg,
                    load_n: weight_n.clone(),
                    weight_n,
                }
            })
            .collect();
        // Tributary rule: top down, each block passes its load P to its supports in proportion
        // to contact length (eq. 3).
        let mut order: Vec<usize> = (0..n).filter(|&i| !wall.blocks[i].fixed).collect();
        order.sort_by(|&a, &b| wall.blocks[b].y.cmp(&wall.blocks[a].y));
        for &i in &order {
            let p = blocks[i].weight_n.clone()
                + above[i]
                    .iter()
                    .map(|s| horizontal[s.0].load_n.clone())
                    .sum::<Q>();
            blocks[i].load_n = p.clone();
            let total: Q = below[i]
                .iter()
                .map(|s| horizontal[s.0].overlap_m.clone())
                .sum();
            for s in &below[i] {
                horizontal[s.0].load_n = &p * &horizontal[s.0].overlap_m / &total;
            }
        }

        // Names looked up in a table (a friction sample overrides every joint), built only
        // where there are overrides.
        let index: HashMap<&str, usize> = if wall.joint_friction.is_empty() {
            HashMap::new()
        } else {
            wall.blocks
                .iter()
                .enumerate()
                .map(|(i, b)| (b.name.as_str(), i))
                .collect()
        };
        for o in &wall.joint_friction {
            let (upper, lower) = resolve_key(wall, &index, &horizontal, &below, &o.key)?;
            let s = below[upper]
                .iter()
                .find(|s| horizontal[s.0].lower == lower)
                .expect("resolve_key checks the edge exists");
            horizontal[s.0].friction = o.value.clone();
        }
        for s in &mut horizontal {
            s.capacity_n = &s.friction * &s.load_n;
        }

        for (i, b) in wall.blocks.iter().enumerate() {
            if b.fixed
                || below[i]
                    .iter()
                    .any(|s| horizontal[s.0].lower == Base::Ground)
            {
                continue;
            }
            let (lo, hi) = contact_hull(wall, &horizontal, &below[i], &Q::zero(), |_| Q::zero())
                .expect("a movable block has supports");
            let c = b.centroid_x();
            if c < lo || c > hi {
                return Err(WallError::Topples {
                    block: b.name.clone(),
                    origin: b.origin.clone(),
                    centroid_m: c.to_f64(),
                    lo_m: lo.to_f64(),
                    hi_m: hi.to_f64(),
                });
            }
        }

        let vertical = vertical_joints(wall);
        let mut sides = vec![Vec::new(); n];
        for (k, j) in vertical.iter().enumerate() {
            sides[j.left.0].push(VerticalId(k));
            sides[j.right.0].push(VerticalId(k));
        }
        Ok(Topology {
            blocks,
            horizontal,
            vertical,
            below: below.into(),
            above: above.into(),
            sides: sides.into(),
        })
    }

    /// The same graph with other friction coefficients, one per horizontal joint (a friction-variability
    /// sample): capacities follow as mu x load.
    pub fn with_frictions(&self, friction: Vec<Q>) -> Topology {
        assert_eq!(
            friction.len(),
            self.horizontal.len(),
            "one coefficient per horizontal joint"
        );
        let mut t = self.clone();
        for (s, mu) in t.horizontal.iter_mut().zip(friction) {
            s.capacity_n = &mu * &s.load_n;
            s.friction = mu;
        }
        t
    }

    /// Support loads (N) once the `removed` blocks are gone: the tributary rule applied to what
    /// is left. Supports touching a removed block carry nothing.
    pub fn loads_without(&self, wall: &Wall, removed: &[bool]) -> Vec<Q> {
        let n = wall.blocks.len();
        let gone = |s: &HorizontalJoint| {
            removed[s.upper.0] || matches!(s.lower, Base::Block(b) if removed[b.0])
        };
        let mut loads = vec![Q::zero(); self.horizontal.len()];
        let mut order: Vec<usize> = (0..n)
            .filter(|&i| !wall.blocks[i].fixed && !removed[i])
            .collect();
        order.sort_by(|&a, &b| wall.blocks[b].y.cmp(&wall.blocks[a].y));
        for &i in &order {
            let p = self.blocks[i].weight_n.clone()
                + self.above[i].iter().map(|s| loads[s.0].clone()).sum::<Q>();
            let live: Vec<HorizontalId> = self.below[i]
                .iter()
                .copied()
                .filter(|s| !gone(&self.horizontal[s.0]))
                .collect();
            let total: Q = live
                .iter()
                .map(|s| self.horizontal[s.0].overlap_m.clone())
                .sum();
            for s in live {
                loads[s.0] = &p * &self.horizontal[s.0].overlap_m / &total;
            }
        }
        loads
    }

    /// The wall's height in blocks: the longest chain of blocks resting on one another, from a
    /// block on the ground up (a coursed wall's number of courses).
    pub fn courses(&self, wall: &Wall) -> usize {
        let mut order: Vec<usize> = (0..wall.blocks.len()).collect();
        order.sort_by(|&a, &b| wall.blocks[a].y.cmp(&wall.blocks[b].y));
        let mut depth = vec![0; wall.blocks.len()];
        for &i in &order {
            depth[i] = 1 + self.below[i]
                .iter()
                .filter_map(|s| match self.horizontal[s.0].lower {
                    Base::Block(b) => Some(depth[b.0]),
                    Base::Ground => None,
                })
                .max()
                .unwrap_or(0);
        }
        depth.into_iter().max().unwrap_or(0)
    }

    /// Name of a base: the block's name or `ground`.
    pub fn base_name<'a>(&self, wall: &'a Wall, base: Base) -> &'a str {
        match base {
            Base::Ground => "ground",
            Base::Block(b) => &wall.blocks[b.0].name,
        }
    }

    /// True when the base cannot move relative to the ground (the ground or a fixed block).
    pub fn is_grounded(&self, wall: &Wall, base: Base) -> bool {
        match base {
            Base::Ground => true,
            Base::Block(b) => wall.blocks[b.0].fixed,
        }
    }
}

/// The support span of a block whose supports are displaced: from the leftmost to the rightmost
/// point where its bottom face touches a support's top face. `du` is the block's own horizontal
/// displacement and `du_of` gives each support's. `None` when no support touches any more.
pub fn contact_hull(
    wall: &Wall,
    horizontal: &[HorizontalJoint],
    below: &[HorizontalId],
    du: &Q,
    du_of: impl Fn(BlockId) -> Q,
) -> Option<(Q, Q)> {
    let mut hull: Option<(Q, Q)> = None;
    for s in below {
        let sup = &horizontal[s.0];
        let b = &wall.blocks[sup.upper.0];
        let (x0, x1) = (&b.x + du, b.right() + du);
        let (l0, l1) = match sup.lower {
            Base::Ground => return Some((x0, x1)),
            Base::Block(j) => {
                let l = &wall.blocks[j.0];
                let d = du_of(j);
                (&l.x + &d, l.right() + &d)
            }
        };
        let lo = x0.clone().max(l0);
        let hi = x1.clone().min(l1);
        if hi > lo {
            hull = Some(match hull {
                None => (lo, hi),
                Some((a, b)) => (a.min(lo), b.max(hi)),
            });
        }
    }
    hull
}

fn resolve_key(
    wall: &Wall,
    index: &HashMap<&str, usize>,
    horizontal: &[HorizontalJoint],
    below: &[Vec<HorizontalId>],
    key: &str,
) -> Result<(usize, Base), WallError> {
    let parts: Vec<&str> = key.split('/').map(str::trim).collect();
    let [upper_name, lower_name] = parts[..] else {
        return Err(WallError::JointKeyForm { key: key.into() });
    };
    let known = || {
        let names: Vec<&str> = wall.blocks.iter().map(|b| b.name.as_str()).collect();
        if names.len() > 12 {
            format!("{}, ... {}", names[..10].join(", "), names[names.len() - 1])
        } else {
            names.join(", ")
        }
    };
    let upper = index
        .get(upper_name)
        .copied()
        .ok_or_else(|| WallError::JointKeyUnknownBlock {
            key: key.into(),
            name: upper_name.into(),
            known: known(),
        })?;
    let lower = if lower_name == "ground" {
        Base::Ground
    } else {
        Base::Block(BlockId(index.get(lower_name).copied().ok_or_else(
            || WallError::JointKeyUnknownBlock {
                key: key.into(),
                name: lower_name.into(),
                known: known(),
            },
        )?))
    };
    if below[upper].iter().any(|s| horizontal[s.0].lower == lower) {
        return Ok((upper, lower));
    }
    let actual: Vec<String> = below[upper]
        .iter()
        .map(|s| match horizontal[s.0].lower {
            Base::Ground => "ground".to_string(),
            Base::Block(b) => wall.blocks[b.0].name.clone(),
        })
        .collect();
    Err(WallError::JointKeyNotSupport {
        key: key.into(),
        upper: upper_name.into(),
        lower: lower_name.into(),
        actual: if actual.is_empty() {
            "nothing: it is fixed".into()
        } else {
            actual.join(" and ")
        },
    })
}

/// Pairs of blocks that face each other: `i` can hit `j` if a horizontal line through both meets
/// no other block between them. Found by walking right from each block in order of left edges and
/// removing from its height band whatever each block met covers.
fn vertical_joints(wall: &Wall) -> Vec<VerticalJoint> {
    let blocks = &wall.blocks;
    let tops: Vec<Q> = blocks.iter().map(|b| b.top()).collect();
    let mut order: Vec<usize> = (0..blocks.len()).collect();
    order.sort_by(|&a, &b| {
        blocks[a]
            .x
            .cmp(&blocks[b].x)
            .then(blocks[a].y.cmp(&blocks[b].y))
    });
    // Runs of blocks with one left edge, bottom to top: they overlap one another
    // horizontally, so their vertical extents are disjoint and those a block faces are a
    // stretch of the run found by bisection, not a scan of every course.
    let runs: Vec<&[usize]> = order
        .chunk_by(|&a, &b| blocks[a].x == blocks[b].x)
        .collect();
    let mut joints = Vec::new();
    for (i, b) in blocks.iter().enumerate() {
        let right = b.right();
        let start = runs.partition_point(|run| blocks[run[0]].x < right);
        let mut band: Vec<(Q, Q)> = vec![(b.y.clone(), tops[i].clone())];
        for run in &runs[start..] {
            if band.is_empty() {
                break;
            }
            let first = run.partition_point(|&j| tops[j] <= b.y);
            for &j in run[first..].iter().take_while(|&&j| blocks[j].y < tops[i]) {
                let o = &blocks[j];
                let (o0, o1) = (o.y.clone(), tops[j].clone());
                if !band.iter().any(|(a, c)| o1 > *a && o0 < *c) {
                    continue;
                }
                if !(b.fixed && o.fixed) {
                    joints.push(VerticalJoint {
                        left: BlockId(i),
                        right: BlockId(j),
                        gap_m: &o.x - &right,
                        height_m: tops[i].clone().min(o1.clone()) - b.y.clone().max(o0.clone()),
                    });
                }
                band = band
                    .into_iter()
                    .flat_map(|(a, c)| {
                        let mut pieces = Vec::with_capacity(2);
                        if o0 > a {
                            pieces.push((a.clone(), o0.clone().min(c.clone())));
                        }
                        if o1 < c {
                            pieces.push((o1.clone().max(a), c));
                        }
                        pieces.into_iter().filter(|(p, q)| q > p)
                    })
                    .collect();
            }
        }
    }
    joints.sort_by(|p, q| {
        p.left
            .cmp(&q.left)
            .then(blocks[p.right.0].y.cmp(&blocks[q.right.0].y))
    });
    joints
}

/// Reads a wall file and builds its graph; errors name the file.
pub fn load(path: &std::path::Path) -> Result<(Wall, Topology), crate::Error> {
    let wall = Wall::load(path)?;
    let topo = Topology::new(&wall).map_err(|source| crate::Error::Wall {
        path: path.to_path_buf(),
        source,
    })?;
    Ok((wall, topo))
}

/// The topology as plain numbers, for `pirqa check --json` and for people.
#[derive(Debug, Clone, serde::Serialize)]
pub struct TopologyReport {
    /// Wall name.
    pub name: String,
    /// Gravity (m/s2).
    pub g_m_s2: f64,
    /// Thickness (m).
    pub thickness_m: f64,
    /// Density (kg/m3).
    pub density_kg_m3: f64,
    /// Restitution of vertical joints.
    pub restitution: f64,
    /// Blocks.
    pub blocks: Vec<BlockReport>,
    /// Horizontal joints (`supports` in the JSON, the name it had before issue 33).
    #[serde(rename = "supports")]
    pub horizontal: Vec<HorizontalJointReport>,
    /// Vertical joints (`joints` in the JSON).
    #[serde(rename = "joints")]
    pub vertical: Vec<VerticalJointReport>,
}

/// One block in a [`TopologyReport`].
#[derive(Debug, Clone, serde::Serialize)]
pub struct BlockReport {
    /// Name.
    pub name: String,
    /// Mass (kg).
    pub mass_kg: f64,
    /// Left edge (m).
    pub x_m: f64,
    /// Bottom edge (m).
    pub y_m: f64,
    /// Width (m).
    pub width_m: f64,
    /// Height (m).
    pub height_m: f64,
    /// Abutment moving with the ground.
    pub fixed: bool,
    /// Own weight (N).
    pub weight_n: f64,
    /// Load passed to its supports (N).
    pub load_n: f64,
}

/// One horizontal joint in a [`TopologyReport`].
#[derive(Debug, Clone, serde::Serialize)]
pub struct HorizontalJointReport {
    /// Upper block.
    pub upper: String,
    /// Lower block or `ground`.
    pub lower: String,
    /// Contact length (m).
    pub overlap_m: f64,
    /// Normal load (N).
    pub load_n: f64,
    /// Friction coefficient.
    pub friction: f64,
    /// Friction capacity (N).
    pub capacity_n: f64,
}

/// One vertical joint in a [`TopologyReport`].
#[derive(Debug, Clone, serde::Serialize)]
pub struct VerticalJointReport {
    /// Left block.
    pub left: String,
    /// Right block.
    pub right: String,
    /// Gap (m).
    pub gap_m: f64,
    /// Shared height (m).
    pub height_m: f64,
}

impl Topology {
    /// Plain-number report of the graph.
    pub fn report(&self, wall: &Wall) -> TopologyReport {
        let name = |b: BlockId| wall.blocks[b.0].name.clone();
        TopologyReport {
            name: wall.name.clone(),
            g_m_s2: wall.g_m_s2.to_f64(),
            thickness_m: wall.thickness_m.to_f64(),
            density_kg_m3: wall.density_kg_m3.to_f64(),
            restitution: wall.restitution.to_f64(),
            blocks: wall
                .blocks
                .iter()
                .zip(&self.blocks)
                .map(|(b, d)| BlockReport {
                    name: b.name.clone(),
                    mass_kg: d.mass_kg.to_f64(),
                    x_m: b.x.to_f64(),
                    y_m: b.y.to_f64(),
                    width_m: b.width.to_f64(),
                    height_m: b.height.to_f64(),
                    fixed: b.fixed,
                    weight_n: d.weight_n.to_f64(),
                    load_n: if b.fixed { 0.0 } else { d.load_n.to_f64() },
                })
                .collect(),
            horizontal: self
                .horizontal
                .iter()
                .map(|s| HorizontalJointReport {
                    upper: name(s.upper),
                    lower: self.base_name(wall, s.lower).to_string(),
                    overlap_m: s.overlap_m.to_f64(),
                    load_n: s.load_n.to_f64(),
                    friction: s.friction.to_f64(),
                    capacity_n: s.capacity_n.to_f64(),
                })
                .collect(),
            vertical: self
                .vertical
                .iter()
                .map(|j| VerticalJointReport {
                    left: name(j.left),
                    right: name(j.right),
                    gap_m: j.gap_m.to_f64(),
                    height_m: j.height_m.to_f64(),
                })
                .collect(),
        }
    }
}
