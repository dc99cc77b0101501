//! Where the time-stepped wall with rotations starts when a block is released from a rotation
//! (`--initial-rotation NAME=RAD`): the body of a wall of one column turned about the end of
//! its base (as the exact column model starts), or, in any other wall, one block that carries
//! nothing turned about the corner of its base on the side it leans to, wherever that moves
//! it clear of every other block.

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
        _ => vec![(named, released_block(wall, topo, named, theta_rad)?)],
    };
    Ok(moved)
}

/// Block `i` turned by `theta_rad` (clockwise positive) about the corner of its base on the
/// side it leans to: its centroid's displacement and counter-clockwise rotation, or why it
/// cannot start there (it carries a block, the corner does not rest on a support, or the
/// turned block would overlap another).
fn released_block(
    wall: &Wall,
    topo: &Topology,
    i: usize,
    theta_rad: f64,
) -> Result<Vector3<f64>, SimulationError> {
    let block = &wall.blocks[i];
    let not = |why: String| {
        SimulationError::NotApplicable(format!("--initial-rotation {}: {why}", block.name))
    };
    if block.fixed {
        return Err(not(
            "an abutment moves with the ground and cannot be released".into(),
        ));
    }
    if let Some(s) = topo.above[i].first() {
        let carried = &wall.blocks[topo.horizontal[s.0].upper.0].name;
        return Err(not(format!(
            "{carried} rests on it; in a wall of several columns or of blocks beside others a \
             release turns one block that carries nothing (a block of the top course, or a \
             wall of one column)"
        )));
    }
    let (x, y) = (block.x.to_f64(), block.y.to_f64());
    let (w, h) = (block.width.to_f64(), block.height.to_f64());
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
    let corners = [(x, y), (x + w, y), (x + w, y + h), (x, y + h)].map(turned);
    let (mut lo, mut hi) = (
        (f64::INFINITY, f64::INFINITY),
        (f64::NEG_INFINITY, f64::NEG_INFINITY),
    );
    for (cx, cy) in corners {
        lo = (lo.0.min(cx), lo.1.min(cy));
        hi = (hi.0.max(cx), hi.1.max(cy));
    }
    // The turned block lies within its corners' box; a block clear of the box is clear of it.
    for (j, other) in wall.blocks.iter().enumerate() {
        let (ox, oy) = (other.x.to_f64(), other.y.to_f64());
        let (ow, oh) = (other.width.to_f64(), other.height.to_f64());
        if j != i && lo.0 < ox + ow && ox < hi.0 && lo.1 < oy + oh && oy < hi.1 {
            return Err(not(format!(
                "turned by {theta_rad} rad about its {} base corner it would reach into {} \
                 (its corners span x {:.4}..{:.4} m, y {:.4}..{:.4} m); release it the other \
                 way or by less",
                if right { "right" } else { "left" },
                other.name,
                lo.0,
                hi.0,
                lo.1,
                hi.1
            )));
        }
    }
    let centroid = (x + 0.5 * w, y + 0.5 * h);
    let moved = turned(centroid);
    Ok(Vector3::new(
        moved.0 - centroid.0,
        moved.1 - centroid.1,
        -theta_rad,
    ))
}
