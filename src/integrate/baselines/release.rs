//! Where the time-stepped wall with rotations starts when a block is released from a rotation
//! (`--initial-rotation NAME=RAD`): the body of a wall of one column turned about the end of
//! its base (as the exact column model starts), or, in any other wall, a block and the blocks
//! resting on it alone (directly or on one another) turned as one about the corner of its base
//! on the side it leans to, wherever that moves them clear of every other block.

use crate::error::SimulationError;
use crate::integrate::rocking;
use crate::topology::{Base, Topology};
use crate::wall::Wall;
use nalgebra::Vector3;

/// The blocks a release moves, each with its centroid's displacement (m, m) and its
/// counter-clockwise rotation (rad), for `name` turned by `theta_rad` (clockwise positive).
pub fn released(
    wall: &Wall,
    topo: &Topology,
    name: &str,
    theta_rad: f64,
) -> Result<Vec<(usize, Vector3<f64>)>, SimulationError> {
    let Some(named) = wall.block_index(name) else {
        return Err(SimulationError::UnknownName {
            option: "--initial-rotation",
            name: name.to_string(),
            known: "the wall has no block of that name".into(),
        });
    };
    let index = |block: &str| {
        wall.block_index(block)
            .expect("a column's block is the wall's")
    };
    let initial = [(name.to_string(), theta_rad)];
    let moved = match rocking::columns(wall, topo) {
        Ok(columns) if columns.len() == 1 => {
            rocking::released_body(&columns, &initial)?;
            columns[0]
                .released(theta_rad)
                .into_iter()
                .map(|(block, dx, dy, phi)| (index(&block), Vector3::new(dx, dy, phi)))
                .collect()
        }
        _ => released_group(wall, topo, named, theta_rad)?,
    };
    Ok(moved)
}

/// Block `i` and everything resting on it, turned as one by `theta_rad` (clockwise positive)
/// about the corner of `i`'s base on the side it leans to: each moved block's centroid
/// displacement and counter-clockwise rotation, or why they cannot start there (a block they
/// carry rests also on a block outside them, the corner does not rest on a support, or a
/// turned block would overlap another).
fn released_group(
    wall: &Wall,
    topo: &Topology,
    i: usize,
    theta_rad: f64,
) -> Result<Vec<(usize, Vector3<f64>)>, SimulationError> {
    let block = &wall.blocks[i];
    let not = |why: String| {
        SimulationError::NotApplicable(format!("--initial-rotation {}: {why}", block.name))
    };
    let (group, member) = carried_group(topo, i);
    let in_group = |j: usize| member[j];
    if let Some(&fixed) = group.iter().find(|&&j| wall.blocks[j].fixed) {
        return Err(not(format!(
            "{} is an abutment, which moves with the ground and cannot be released",
            wall.blocks[fixed].name
        )));
    }
    // A block of the group resting also on one outside it would be torn from that support
    // or pushed into it: the group turns rigidly only if it rests on nothing else.
    for &j in &group[1..] {
        for s in topo.below[j].iter() {
            if let Base::Block(k) = topo.horizontal[s.0].lower {
                if !in_group(k.0) {
                    return Err(not(format!(
                        "{} rests on it and also on {}, which would not turn with it; a \
                         release turns a block with the blocks that rest on it alone",
                        wall.blocks[j].name, wall.blocks[k.0].name
                    )));
                }
            }
        }
    }
    let (x, y) = (block.x.to_f64(), block.y.to_f64());
    let w = block.width.to_f64();
    // Clockwise (positive) leans to the right and turns about the base's right end.
    let right = theta_rad > 0.0;
    let pivot_x = if right { x + w } else { x };
    let pivot = &if right {
        block.right()
    } else {
        block.x.clone()
    };
    let supported = topo.below[i]
        .iter()
        .any(|s| match topo.horizontal[s.0].lower {
            Base::Ground => true,
            Base::Block(j) => {
                let support = &wall.blocks[j.0];
                &support.x <= pivot && pivot <= &support.right()
            }
        });
    if !supported {
        return Err(not(format!(
            "the {} end of its base overhangs its supports, so it would turn about a support's \
             edge, not its own corner; release it the other way (a rotation of the other sign)",
            if right { "right" } else { "left" }
        )));
    }
    let (sin, cos) = theta_rad.sin_cos();
    let turned = |(px, py): (f64, f64)| {
        let (rx, ry) = (px - pivot_x, py - y);
        (pivot_x + rx * cos + ry * sin, y - rx * sin + ry * cos)
    };
    let mut moved = Vec::with_capacity(group.len());
    for &j in &group {
        let b = &wall.blocks[j];
        let (bx, by) = (b.x.to_f64(), b.y.to_f64());
        let (bw, bh) = (b.width.to_f64(), b.height.to_f64());
        let corners = [(bx, by), (bx + bw, by), (bx + bw, by + bh), (bx, by + bh)].map(turned);
        let (mut lo, mut hi) = (
            (f64::INFINITY, f64::INFINITY),
            (f64::NEG_INFINITY, f64::NEG_INFINITY),
        );
        for (cx, cy) in corners {
            lo = (lo.0.min(cx), lo.1.min(cy));
            hi = (hi.0.max(cx), hi.1.max(cy));
        }
        // A turned block lies within its corners' box; a block clear of the box is clear of it.
        for (k, other) in wall.blocks.iter().enumerate() {
            let (ox, oy) = (other.x.to_f64(), other.y.to_f64());
            let (ow, oh) = (other.width.to_f64(), other.height.to_f64());
            if !in_group(k) && lo.0 < ox + ow && ox < hi.0 && lo.1 < oy + oh && oy < hi.1 {
                let whose = if j == i {
                    "it".to_string()
                } else {
                    format!("{}, which rests on it,", b.name)
                };
                return Err(not(format!(
                    "turned by {theta_rad} rad about its {} base corner {whose} would reach into \
                     {} (its corners span x {:.4}..{:.4} m, y {:.4}..{:.4} m); release it the \
                     other way or by less",
                    if right { "right" } else { "left" },
                    other.name,
                    lo.0,
                    hi.0,
                    lo.1,
                    hi.1
                )));
            }
        }
        let centroid = (bx + 0.5 * bw, by + 0.5 * bh);
        let to = turned(centroid);
        moved.push((
            j,
            Vector3::new(to.0 - centroid.0, to.1 - centroid.1, -theta_rad),
        ));
    }
    Ok(moved)
}

/// Block `i` first, then every block resting on it or on one of those, each once; and for
/// every block of the wall, whether it is one of them.
fn carried_group(topo: &Topology, i: usize) -> (Vec<usize>, Vec<bool>) {
    let mut member = vec![false; topo.blocks.len()];
    member[i] = true;
    let mut group = vec![i];
    let mut next = 0;
    while next < group.len() {
        for s in topo.above[group[next]].iter() {
            let upper = topo.horizontal[s.0].upper.0;
            if !member[upper] {
                member[upper] = true;
                group.push(upper);
            }
        }
        next += 1;
    }
    (group, member)
}
