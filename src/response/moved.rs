//! The wall where a saved run left it: each block moved by its displacement, the fallen ones
//! taken out, the faces the run left touching set touching exactly, each joint keeping the
//! friction it had. Checked like any wall, its limit at rest is what is left of the wall's
//! capacity after the shaking, on the geometry the run moved (the run itself kept the overlaps
//! at rest: small displacements).

use super::saved::SavedState;
use crate::error::WallError;
use crate::exact::Q;
use crate::topology::Topology;
use crate::wall::{FrictionOverride, Wall};
use serde::Serialize;
use std::collections::HashSet;

/// Faces of a vertical joint closer than this (m) are touching in the moved wall. The run
/// computes displacements in floats: faces it brought together stand apart or overlap by its
/// round-off (about 1e-16 m per metre of wall), which the rigid check must not read as a gap
/// to cross first or as blocks inside one another; a nanometre is a million times that and far
/// below anything a survey sees.
pub const TOUCHING_M: f64 = 1e-9;

/// What moving the wall changed, for the report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Moves {
    /// The largest displacement of a block left standing (m).
    pub largest_displacement_m: f64,
    /// The blocks that had fallen by then, taken out.
    pub fallen: Vec<String>,
    /// Horizontal joints of the wall as built that the moved wall no longer has
    /// (`"upper/lower"`): one face slid off the other.
    pub joints_lost: Vec<String>,
    /// Horizontal joints the moved wall has and the wall as built did not: a block slid onto
    /// another. Their friction is the wall's default.
    pub joints_new: Vec<String>,
    /// Vertical joints whose faces the run left touching, set touching exactly.
    pub faces_set_touching: usize,
}

/// The wall as `state` left it, with its graph: blocks moved by their displacements (exact
/// rationals from the floats' shortest decimals), fallen blocks out, faces within
/// [`TOUCHING_M`] of touching set touching (along each group of such faces, every block's
/// displacement follows from the first's exactly), each joint that stays with the friction it
/// had, new joints with the default. An error where that wall cannot stand as a wall: blocks
/// inside one another, a block with nothing under it, or one whose centroid has left its
/// support.
pub fn moved(
    wall: &Wall,
    topo: &Topology,
    state: &SavedState,
) -> Result<(Wall, Topology, Moves), WallError> {
    let n = wall.blocks.len();
    let lengths = [state.displacement_m.len(), state.fallen.len()];
    let poses = (state.pose.iter()).flat_map(|(theta, w)| [theta.len(), w.len()]);
    if let Some(len) = lengths.into_iter().chain(poses).find(|&len| len != n) {
        return Err(WallError::Field {
            field: "displacement_m".into(),
            value: len as f64,
            rule: "a state of the wall gives one value per block of the wall, in its order",
        });
    }
    // A turned block is not a rectangle on the wall's courses: its wall is the time stepper's.
    if let Some((theta, w)) = &state.pose {
        let turned = (0..n).find(|&i| !state.fallen[i] && (theta[i] != 0.0 || w[i] != 0.0));
        if let Some(i) = turned {
            let b = &wall.blocks[i];
            return Err(WallError::BlockField {
                block: Some(b.name.clone()),
                origin: b.origin.clone(),
                field: "rotation_rad",
                value: theta[i],
                rule: "the run turned or lifted this block: the wall where a run left it is \
                       built for runs whose blocks slide",
            });
        }
    }
    let (u, touching) = exact_displacements(wall, topo, state)?;
    let standing: Vec<usize> = (0..n).filter(|&i| !state.fallen[i]).collect();
    let mut blocks = Vec::with_capacity(standing.len());
    for &i in &standing {
        let mut b = wall.blocks[i].clone();
        b.x = &b.x + &u[i];
        blocks.push(b);
    }
    crate::wall::check_overlaps(&blocks)?;
    let key = |wall: &Wall, topo: &Topology, s: &crate::topology::HorizontalJoint| {
        format!(
            "{}/{}",
            wall.blocks[s.upper.0].name,
            topo.base_name(wall, s.lower)
        )
    };
    let built: Vec<(String, &Q)> = (topo.horizontal.iter())
        .map(|s| (key(wall, topo, s), &s.friction))
        .collect();
    // Found by their names once the graph of the moved wall is built; every joint that stays
    // keeps its friction (an override, or a sample's), so the overrides are given again for
    // exactly those.
    let mut moved_wall = Wall {
        blocks,
        joint_friction: Vec::new(),
        ..wall.clone()
    };
    let bare = Topology::new(&moved_wall)?;
    let now: Vec<String> = (bare.horizontal.iter())
        .map(|s| key(&moved_wall, &bare, s))
        .collect();
    let (in_built, in_now): (HashSet<&str>, HashSet<&str>) = (
        built.iter().map(|(k, _)| k.as_str()).collect(),
        now.iter().map(String::as_str).collect(),
    );
    let overrides: Vec<FrictionOverride> = (built.iter())
        .filter(|(key, mu)| **mu != wall.friction && in_now.contains(key.as_str()))
        .map(|(key, mu)| FrictionOverride {
            key: key.clone(),
            value: (*mu).clone(),
        })
        .collect();
    let fallen: Vec<String> = (0..n)
        .filter(|&i| state.fallen[i])
        .map(|i| wall.blocks[i].name.clone())
        .collect();
    let gone: HashSet<&str> = fallen.iter().map(String::as_str).collect();
    let moves = Moves {
        largest_displacement_m: standing
            .iter()
            .fold(0.0_f64, |m, &i| m.max(state.displacement_m[i].abs())),
        joints_lost: (built.iter())
            .map(|(key, _)| key)
            .filter(|key| {
                let gone = |p: &str| gone.contains(p);
                !in_now.contains(key.as_str()) && !key.split('/').any(gone)
            })
            .cloned()
            .collect(),
        joints_new: (now.iter())
            .filter(|key| !in_built.contains(key.as_str()))
            .cloned()
            .collect(),
        faces_set_touching: touching,
        fallen,
    };
    moved_wall.joint_friction = overrides;
    let topology = if moved_wall.joint_friction.is_empty() {
        bare
    } else {
        Topology::new(&moved_wall)?
    };
    Ok((moved_wall, topology, moves))
}

/// Each block's displacement as an exact rational, and how many vertical joints were set
/// touching: the float's shortest decimal, but along the joints whose faces the run left
/// within [`TOUCHING_M`] the blocks follow the first one reached (an abutment where the group
/// has one) with those faces exactly together. Fallen blocks stay where they were: they are
/// taken out.
fn exact_displacements(
    wall: &Wall,
    topo: &Topology,
    state: &SavedState,
) -> Result<(Vec<Q>, usize), WallError> {
    let n = wall.blocks.len();
    let standing = |i: usize| !state.fallen[i];
    let mut touching: Vec<Vec<(usize, Q)>> = vec![Vec::new(); n];
    let mut count = 0;
    for j in &topo.vertical {
        let (l, r) = (j.left.0, j.right.0);
        if !(standing(l) && standing(r)) {
            continue;
        }
        let gap = j.gap_m.to_f64() + state.displacement_m[r] - state.displacement_m[l];
        if gap.abs() <= TOUCHING_M {
            // u_r - u_l = -gap at rest closes the faces.
            touching[l].push((r, -j.gap_m.clone()));
            touching[r].push((l, j.gap_m.clone()));
            count += 1;
        }
    }
    let mut u: Vec<Option<Q>> = vec![None; n];
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by_key(|&i| !wall.blocks[i].fixed);
    let mut queue = Vec::new();
    for root in order {
        if u[root].is_some() {
            continue;
        }
        let b = &wall.blocks[root];
        u[root] = Some(if b.fixed || !standing(root) {
            Q::zero()
        } else {
            let value = state.displacement_m[root];
            Q::from_decimal(value).ok_or_else(|| WallError::BlockField {
                block: Some(b.name.clone()),
                origin: b.origin.clone(),
                field: "displacement_m",
                value,
                rule: "a saved run's displacement must be a finite number",
            })?
        });
        queue.push(root);
        while let Some(i) = queue.pop() {
            for (k, shift) in &touching[i] {
                if u[*k].is_none() {
                    u[*k] = Some(u[i].as_ref().expect("set before queued") + shift);
                    queue.push(*k);
                }
            }
        }
    }
    let u = u
        .into_iter()
        .map(|v| v.expect("every block reached"))
        .collect();
    Ok((u, count))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limit::{self, Limit};

    fn q(text: &str) -> Q {
        Q::from_decimal(text.parse().unwrap()).unwrap()
    }

    fn state(displacement_m: Vec<f64>, fallen: Vec<bool>) -> SavedState {
        SavedState {
            time_s: 0.5,
            displacement_m,
            fallen,
            pose: None,
        }
    }

    fn exact_g(l: &Limit) -> String {
        match l {
            Limit::Holds { exact_g, .. } => exact_g.clone(),
            Limit::Unlimited => "unlimited".into(),
        }
    }

    /// A 0.3 x 1.2 m block U of friction 0.15 on a fixed ledge L from x = 0 to 1, standing at
    /// 0.1..0.4: at rest it slides at 0.15 g either way (it would tip at b/h = 0.25). Slid by u
    /// towards -x past the ledge's edge it rests on 0..0.4 + u, and tips about the edge at
    /// (0.25 + u) / 0.6 (its centroid's distance from the edge over its height above it):
    /// Shenton's lone block, min(mu, that), on the moved geometry; the other way it keeps 0.15.
    #[test]
    fn a_block_slid_past_a_ledges_edge_tips_about_it() {
        let wall = Wall::from_ron_str(
            r#"(version: 1, name: "ledge", thickness_m: 0.5, density_kg_m3: 2500,
                friction: 0.8, joint_friction: {"U/L": 0.15},
                rows: [(height_m: 0.5, blocks: [(width_m: 1.0, name: "L", fixed: true)]),
                       (height_m: 1.2, x_m: 0.1, blocks: [(width_m: 0.3, name: "U")])])"#,
        )
        .unwrap();
        let topo = Topology::new(&wall).unwrap();
        for u in ["-0.05", "-0.1496", "-0.16", "-0.2235", "-0.249"] {
            let (moved_wall, moved_topo, moves) = moved(
                &wall,
                &topo,
                &state(vec![0.0, u.parse().unwrap()], vec![false; 2]),
            )
            .unwrap();
            assert_eq!(moved_wall.blocks[1].x, q("0.1") + q(u));
            let overlap = (q("0.4") + q(u)).min(Q::one()) - (q("0.1") + q(u)).max(Q::zero());
            assert_eq!(moved_topo.horizontal[0].overlap_m, overlap);
            // The joint keeps its friction (an override given again by its name).
            assert_eq!(moved_topo.horizontal[0].friction, q("0.15"));
            assert!(moves.joints_lost.is_empty() && moves.joints_new.is_empty());
            let limits = limit::at_rest(&moved_wall, &moved_topo).unwrap();
            let tips = (q("0.25") + q(u)) / q("0.6");
            let expected = tips.min(q("0.15"));
            assert_eq!(
                exact_g(&limits.towards_plus_x),
                format!("{expected:?}"),
                "u = {u}"
            );
            assert_eq!(exact_g(&limits.towards_minus_x), "3/20", "u = {u}");
        }
    }

    /// Two blocks side by side that the run left touching within its round-off touch
    /// exactly; left overlapping by more than a nanometre they are refused by name.
    #[test]
    fn faces_left_touching_within_round_off_touch_exactly() {
        let wall = Wall::from_ron_str(
            r#"(version: 1, name: "pair", thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
                rows: [(height_m: 1.0, blocks: [(width_m: 1.0, name: "A"),
                                                  (width_m: 1.0, name: "B")])])"#,
        )
        .unwrap();
        let topo = Topology::new(&wall).unwrap();
        for b in [0.3 - 5e-17, 0.3 + 5e-17, 0.3 - 4e-10] {
            let (moved_wall, moved_topo, moves) =
                moved(&wall, &topo, &state(vec![0.3, b], vec![false; 2])).unwrap();
            assert_eq!(moves.faces_set_touching, 1);
            assert_eq!(moved_wall.blocks[1].x, q("1.3"));
            assert!(moved_topo.vertical[0].gap_m.is_zero());
        }
        let (_, moved_topo, moves) =
            moved(&wall, &topo, &state(vec![0.3, 0.3 + 2e-9], vec![false; 2])).unwrap();
        assert_eq!(moves.faces_set_touching, 0);
        assert_eq!(moved_topo.vertical[0].gap_m, q("1.300000002") - q("1.3"));
        let err = moved(&wall, &topo, &state(vec![0.3, 0.3 - 1e-6], vec![false; 2])).unwrap_err();
        assert!(
            matches!(&err, WallError::Overlap { a, b, .. } if a == "A" && b == "B"),
            "{err}"
        );
    }

    /// A block on two others slid off one and onto a third: the joint it left is gone, the
    /// one it kept keeps its friction, the new one takes the wall's default; a fallen block
    /// is taken out; a turned one is refused by name.
    #[test]
    fn joints_slid_apart_and_onto_are_named_and_fallen_blocks_taken_out() {
        let wall = Wall::from_ron_str(
            r#"(version: 1, name: "bond", thickness_m: 0.5, density_kg_m3: 2500, friction: 0.6,
                joint_friction: {"U/L2": 0.4, "U/L1": 0.5},
                rows: [(height_m: 0.5, blocks: [(width_m: 1.0, name: "L1"),
                                                  (width_m: 1.0, name: "L2"),
                                                  (width_m: 1.0, name: "L3")]),
                       (height_m: 0.5, x_m: 0.5, blocks: [(width_m: 1.0, name: "U")])])"#,
        )
        .unwrap();
        let topo = Topology::new(&wall).unwrap();
        let (moved_wall, moved_topo, moves) = moved(
            &wall,
            &topo,
            &state(vec![0.0, 0.0, 0.0, 0.8], vec![false; 4]),
        )
        .unwrap();
        assert_eq!(moves.joints_lost, ["U/L1"]);
        assert_eq!(moves.joints_new, ["U/L3"]);
        let friction = |lower: usize| {
            let s = (moved_topo.horizontal.iter())
                .find(|s| {
                    s.upper.0 == 3
                        && s.lower == crate::topology::Base::Block(crate::topology::BlockId(lower))
                })
                .unwrap();
            (s.friction.clone(), s.overlap_m.clone())
        };
        assert_eq!(friction(1), (q("0.4"), q("0.7")));
        assert_eq!(friction(2), (q("0.6"), q("0.3")));
        assert_eq!(moved_wall.joint_friction.len(), 1);

        let (moved_wall, _, moves) = moved(
            &wall,
            &topo,
            &state(vec![0.0, 0.0, 0.0, 0.8], vec![false, false, false, true]),
        )
        .unwrap();
        assert_eq!(moved_wall.blocks.len(), 3);
        assert_eq!(moves.fallen, ["U"]);
        assert!(moves.joints_lost.is_empty(), "{:?}", moves.joints_lost);

        let short = moved(&wall, &topo, &state(vec![0.0; 3], vec![false; 4])).unwrap_err();
        assert!(short.to_string().contains("one value per block"), "{short}");

        let mut turned = state(vec![0.0; 4], vec![false; 4]);
        turned.pose = Some((vec![0.0, 0.0, 0.0, 1e-3], vec![0.0; 4]));
        let err = moved(&wall, &topo, &turned).unwrap_err();
        assert!(err.to_string().contains("block U"), "{err}");
    }
}
