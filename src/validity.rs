//! Is the sliding-only model valid for this run? A rigid block rocks rather than slides when
//! its absolute acceleration exceeds g b/h (Housner 1963; b width, h height); with friction,
//! Shenton (1996) shows sliding starts first when mu < b/h and rocking first when mu > b/h.
//! pirqa only slides blocks, so every run compares each block's peak absolute acceleration with
//! these limits and warns. The check treats each block as free-standing: neighbours and blocks
//! above resist rocking, so it errs on the side of warning.

use crate::response::Warning;
use crate::topology::{BlockId, Topology};
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
