//! Is the sliding-only model valid for this run? A rigid block rocks rather than slides when
//! its absolute acceleration exceeds g b/h (Housner 1963; b width, h height); with friction,
//! Shenton (1996) shows sliding starts first when mu < b/h and rocking first when mu > b/h.
//! pirqa only slides blocks, so every run compares each block's peak absolute acceleration with
//! these limits and warns. The check treats each block as free-standing: neighbours and blocks
//! above resist rocking, so it errs on the side of warning.
//!
//! The sliding model is also one of small displacements: its loads and friction capacities are
//! those of the overlaps at rest (eq. 3), so every sliding run also says how much of a joint's
//! overlap sliding took away, and warns where it is no longer small.

use crate::response::{Recorder, Warning};
use crate::topology::{Base, BlockId, HorizontalId, Topology};
use crate::wall::{Block, Wall};

/// The absolute acceleration at which block i, standing free, would start to tip: g b/h
/// (Housner 1963), b/h the ratio of its width to its height (m/s2).
pub fn tipping_accel_m_s2(wall: &Wall, i: usize) -> f64 {
    wall.g_m_s2.to_f64() * width_over_height(&wall.blocks[i])
}

fn width_over_height(b: &Block) -> f64 {
    (b.width.clone() / b.height.clone()).to_f64()
}

/// The largest ratio of a movable block's peak absolute acceleration (m/s2, one per block of
/// the wall) to its tipping acceleration ([`tipping_accel_m_s2`]): below 1, no block of the
/// run could have started to rock, even standing free.
pub fn max_accel_over_tipping(wall: &Wall, peak_accel_m_s2: &[f64]) -> f64 {
    (0..wall.blocks.len())
        .filter(|&i| !wall.blocks[i].fixed)
        .map(|i| peak_accel_m_s2[i] / tipping_accel_m_s2(wall, i))
        .fold(0.0, f64::max)
}

/// Warnings for blocks whose peak absolute acceleration (m/s2) reaches the rocking limit.
pub fn rocking_warnings(wall: &Wall, topo: &Topology, peak_accel_m_s2: &[f64]) -> Vec<Warning> {
    let mut warnings = Vec::new();
    for (i, b) in wall.blocks.iter().enumerate() {
        if b.fixed {
            continue;
        }
        let ratio = width_over_height(b);
        let limit = tipping_accel_m_s2(wall, i);
        let peak = peak_accel_m_s2[i];
        if peak < limit {
            continue;
        }
        let friction = topo.below[i]
            .iter()
            .map(|s| topo.horizontal[s.0].friction.to_f64())
            .fold(f64::INFINITY, f64::min);
        warnings.push(Warning::CouldRock {
            block: BlockId(i),
            name: b.name.clone(),
            peak_accel_m_s2: peak,
            limit_m_s2: limit,
            friction,
            ratio,
        });
    }
    const SHOWN: usize = 12;
    if warnings.len() > SHOWN {
        let more = warnings.len() - SHOWN;
        warnings.truncate(SHOWN);
        warnings.push(Warning::MoreCouldRock { more });
    }
    warnings
}

/// A share of a joint's overlap at rest lost to sliding from which the sliding model's answer
/// is no longer one of small displacements: it keeps the loads and friction capacities that
/// eq. 3 gives the overlaps at rest, and these change in proportion to the overlap. A tenth is
/// this project's choice (docs/model.md, small displacements).
pub const SMALL_OVERLAP_LOSS: f64 = 0.1;

/// The joint of a sliding run that lost the largest share of its overlap at rest.
#[derive(Debug, Clone, PartialEq)]
pub struct OverlapLoss {
    /// The joint.
    pub joint: HorizontalId,
    /// Its overlap at rest (m).
    pub at_rest_m: f64,
    /// Its least overlap along the run (m).
    pub least_m: f64,
    /// The relative displacement u_upper - u_lower at which it was least (m).
    pub slip_m: f64,
}

impl OverlapLoss {
    /// The share of the overlap at rest lost (0 to 1).
    pub fn share(&self) -> f64 {
        (self.at_rest_m - self.least_m) / self.at_rest_m
    }
}

/// The overlap of the joint's upper block on its lower one when the upper has moved by
/// `slip_m` relative to it (m; 0 once it has slid off). Concave in the slip, so its least value
/// over a range of slips is at one of the range's ends.
fn overlap_at_m(upper: &Block, lower: &Block, slip_m: f64) -> f64 {
    let right = (upper.right().to_f64() + slip_m).min(lower.right().to_f64());
    let left = (upper.x.to_f64() + slip_m).max(lower.x.to_f64());
    (right - left).max(0.0)
}

/// Of the joints where a block rests on another (sliding on the ground loses no overlap), the
/// one that lost the largest share of its overlap at rest, given each horizontal joint's
/// least and greatest u_upper - u_lower along the run (m); `None` where no block rests on
/// another.
pub fn largest_overlap_loss(
    wall: &Wall,
    topo: &Topology,
    relative_ranges_m: &[(f64, f64)],
) -> Option<OverlapLoss> {
    let lost = topo.horizontal.iter().zip(relative_ranges_m).enumerate();
    lost.filter_map(|(k, (joint, &(lo, hi)))| {
        let Base::Block(lower) = joint.lower else {
            return None;
        };
        let (upper, lower) = (&wall.blocks[joint.upper.0], &wall.blocks[lower.0]);
        let (at_lo, at_hi) = (
            overlap_at_m(upper, lower, lo),
            overlap_at_m(upper, lower, hi),
        );
        let (least_m, slip_m) = if at_lo <= at_hi {
            (at_lo, lo)
        } else {
            (at_hi, hi)
        };
        Some(OverlapLoss {
            joint: HorizontalId(k),
            // The same float formula at rest, so that a joint that never slid loses exactly 0.
            at_rest_m: overlap_at_m(upper, lower, 0.0),
            least_m,
            slip_m,
        })
    })
    .max_by(|a, b| a.share().total_cmp(&b.share()))
}

/// At the end of a sliding run (blocks that do not turn, on the overlaps at rest): notes in
/// `rec` the largest share of a joint's overlap that sliding took away, and warns where it is
/// no longer small.
pub fn note_overlap_loss(wall: &Wall, topo: &Topology, rec: &mut Recorder) {
    let loss = largest_overlap_loss(wall, topo, rec.relative_ranges());
    rec.overlap_loss = Some(loss.as_ref().map_or(0.0, OverlapLoss::share));
    // A run handed from model to model notes it at each hand-over: the last one holds.
    rec.warnings
        .retain(|w| !matches!(w, Warning::OverlapLost { .. }));
    let warning = loss.and_then(|loss| overlap_warning(wall, topo, &loss));
    rec.warnings.extend(warning);
}

/// The warning for the joint that lost the largest share of its overlap, where that share
/// reaches [`SMALL_OVERLAP_LOSS`].
pub fn overlap_warning(wall: &Wall, topo: &Topology, loss: &OverlapLoss) -> Option<Warning> {
    let joint = &topo.horizontal[loss.joint.0];
    (loss.share() >= SMALL_OVERLAP_LOSS).then(|| Warning::OverlapLost {
        upper: wall.blocks[joint.upper.0].name.clone(),
        lower: topo.base_name(wall, joint.lower).to_string(),
        at_rest_m: loss.at_rest_m,
        least_m: loss.least_m,
        slip_m: loss.slip_m,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A block 0.5 m wide centred on one 1 m wide, beside a bridge of 1.25 m over two
    /// abutments, on 0.75 m of the left one and 0.25 m of the right (sizes in binary fractions,
    /// so every overlap below is exact).
    fn wall() -> (Wall, Topology) {
        let wall = Wall::from_ron_str(
            r#"(version: 1, thickness_m: 1, density_kg_m3: 2000, friction: 0.5, rectangles: [
                (x_m: 0, y_m: 0, width_m: 1, height_m: 0.5, name: "Base"),
                (x_m: 0.25, y_m: 0.5, width_m: 0.5, height_m: 0.5, name: "Narrow"),
                (x_m: 3, y_m: 0, width_m: 1, height_m: 0.5, fixed: true, name: "L"),
                (x_m: 4.25, y_m: 0, width_m: 1, height_m: 0.5, fixed: true, name: "R"),
                (x_m: 3.25, y_m: 0.5, width_m: 1.25, height_m: 0.5, name: "Bridge"),
            ])"#,
        )
        .unwrap();
        let topo = Topology::new(&wall).unwrap();
        (wall, topo)
    }

    /// Horizontal joint k as `upper/lower`.
    fn name(wall: &Wall, topo: &Topology, k: usize) -> String {
        let s = &topo.horizontal[k];
        format!(
            "{}/{}",
            wall.blocks[s.upper.0].name,
            topo.base_name(wall, s.lower)
        )
    }

    /// The joints' ranges of u_upper - u_lower, named `upper/lower`, the rest at rest.
    fn ranges(topo: &Topology, wall: &Wall, given: &[(&str, (f64, f64))]) -> Vec<(f64, f64)> {
        let found = |k| given.iter().find(|(n, _)| *n == name(wall, topo, k));
        (0..topo.horizontal.len())
            .map(|k| found(k).map_or((0.0, 0.0), |(_, r)| *r))
            .collect()
    }

    fn joint_name(wall: &Wall, topo: &Topology, loss: &OverlapLoss) -> String {
        name(wall, topo, loss.joint.0)
    }

    #[test]
    fn a_block_on_a_wider_one_loses_overlap_only_once_its_edge_passes_the_supports() {
        let (wall, topo) = wall();
        // Within the 0.25 m either side nothing is lost, whatever the ground joints did.
        let within = ranges(
            &topo,
            &wall,
            &[("Narrow/Base", (-0.25, 0.25)), ("Base/ground", (-3.0, 7.0))],
        );
        let loss = largest_overlap_loss(&wall, &topo, &within).unwrap();
        assert_eq!(loss.share(), 0.0);
        assert!(overlap_warning(&wall, &topo, &loss).is_none());
        // 0.375 m to the right: 0.125 m of its 0.5 m hangs over the edge.
        let past = ranges(&topo, &wall, &[("Narrow/Base", (-0.125, 0.375))]);
        let loss = largest_overlap_loss(&wall, &topo, &past).unwrap();
        assert_eq!(joint_name(&wall, &topo, &loss), "Narrow/Base");
        assert_eq!(
            (loss.at_rest_m, loss.least_m, loss.slip_m),
            (0.5, 0.375, 0.375)
        );
        assert_eq!(loss.share(), 0.25);
        assert!(matches!(
            overlap_warning(&wall, &topo, &loss),
            Some(Warning::OverlapLost { ref upper, ref lower, .. }) if upper == "Narrow" && lower == "Base"
        ));
    }

    #[test]
    fn a_block_on_two_loses_on_the_support_it_leaves_and_may_leave_it_whole() {
        let (wall, topo) = wall();
        // Moving right by 0.125 m it loses that much of its 0.75 m on L and gains on R.
        let right = ranges(
            &topo,
            &wall,
            &[("Bridge/L", (0.0, 0.125)), ("Bridge/R", (0.0, 0.125))],
        );
        let loss = largest_overlap_loss(&wall, &topo, &right).unwrap();
        assert_eq!(joint_name(&wall, &topo, &loss), "Bridge/L");
        assert_eq!(loss.least_m, 0.625);
        assert_eq!(loss.share(), 0.125 / 0.75);
        // Left by 0.25 m it no longer rests on R: all of that joint's overlap is lost.
        let left = ranges(
            &topo,
            &wall,
            &[("Bridge/L", (-0.25, 0.0)), ("Bridge/R", (-0.25, 0.0))],
        );
        let loss = largest_overlap_loss(&wall, &topo, &left).unwrap();
        assert_eq!(joint_name(&wall, &topo, &loss), "Bridge/R");
        assert_eq!((loss.least_m, loss.share()), (0.0, 1.0));
        let text = overlap_warning(&wall, &topo, &loss).unwrap().to_string();
        assert!(text.contains("Bridge no longer rested on R"), "{text}");
    }

    #[test]
    fn a_wall_on_the_ground_alone_loses_no_overlap() {
        let wall = Wall::from_ron_str(
            r#"(version: 1, thickness_m: 1, density_kg_m3: 2000, friction: 0.5, rectangles: [
                (x_m: 0, y_m: 0, width_m: 1, height_m: 0.5),
            ])"#,
        )
        .unwrap();
        let topo = Topology::new(&wall).unwrap();
        assert_eq!(largest_overlap_loss(&wall, &topo, &[(-5.0, 5.0)]), None);
    }
}
