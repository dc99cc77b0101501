//! The wall file as written by hand: RON structures, their defaults, and nothing else.
//! Turning a description into a checked model is [`super::Wall::from_description`]'s job.

use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

/// Wall-file format version this pirqa reads and writes.
pub const WALL_FORMAT_VERSION: u32 = 1;

/// A wall file. Only `version`, `thickness_m`, the material, `friction` and the blocks are
/// required; everything else has the default written beside it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallDescription {
    /// Format version (currently 1).
    pub version: u32,
    /// Name shown in output (default: the file name).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Out-of-plane thickness (m).
    pub thickness_m: f64,
    /// Density (kg/m3); give this or `unit_weight_kn_m3`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density_kg_m3: Option<f64>,
    /// Unit weight (kN/m3); give this or `density_kg_m3`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub unit_weight_kn_m3: Option<f64>,
    /// Friction coefficient of every horizontal joint not listed in `joint_friction`.
    pub friction: f64,
    /// Coefficient of restitution of the vertical joints (default 1: the paper's elastic impacts).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub restitution: f64,
    /// Factor on Housner's coefficient of restitution when a block rocks and lands on its
    /// other corner (default 1: Housner's law as it is; measured values are often lower).
    #[serde(default = "one", skip_serializing_if = "is_one")]
    pub rocking_restitution_factor: f64,
    /// Gravity (m/s2, default 9.81).
    #[serde(default = "default_g", skip_serializing_if = "is_default_g")]
    pub g_m_s2: f64,
    /// Courses, bottom to top.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rows: Vec<RowDescription>,
    /// Blocks given as rectangles, for walls whose courses do not line up.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub rectangles: Vec<RectangleDescription>,
    /// Friction per horizontal joint, keyed `"upper/lower"` (`"B3/B1"`, `"B1/ground"`).
    #[serde(
        default,
        skip_serializing_if = "BTreeMap::is_empty",
        deserialize_with = "unique_keys"
    )]
    pub joint_friction: BTreeMap<String, f64>,
}

/// A map whose keys are each given once: a second value for a joint is an error, not a silent
/// replacement of the first (which of two differing frictions did the author mean?).
fn unique_keys<'de, D: serde::Deserializer<'de>>(d: D) -> Result<BTreeMap<String, f64>, D::Error> {
    struct Unique;
    impl<'de> serde::de::Visitor<'de> for Unique {
        type Value = BTreeMap<String, f64>;
        fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
            f.write_str("a map from joints (\"upper/lower\") to friction coefficients")
        }
        fn visit_map<A: serde::de::MapAccess<'de>>(
            self,
            mut map: A,
        ) -> Result<Self::Value, A::Error> {
            let mut out = BTreeMap::new();
            while let Some((key, value)) = map.next_entry::<String, f64>()? {
                if out.insert(key.clone(), value).is_some() {
                    return Err(serde::de::Error::custom(format!(
                        "joint_friction key \"{key}\" is given twice: give each joint once"
                    )));
                }
            }
            Ok(out)
        }
    }
    d.deserialize_map(Unique)
}

/// One course: blocks laid left to right from `x_m`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RowDescription {
    /// Height of the course (m); the next course starts on top of it.
    pub height_m: f64,
    /// Left end of the first block (m, default 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub x_m: f64,
    /// Blocks, left to right.
    pub blocks: Vec<BlockDescription>,
}

/// A block in a course.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BlockDescription {
    /// Width (m).
    pub width_m: f64,
    /// Open gap before the block (m, default 0: ashlar fits snugly).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub gap_m: f64,
    /// Name (default B1, B2, ... bottom course first, left to right).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Height (m) when it differs from the course's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_m: Option<f64>,
    /// Density (kg/m3) when this stone differs from the wall's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density_kg_m3: Option<f64>,
    /// An abutment that moves with the ground (default false).
    #[serde(default, skip_serializing_if = "is_false")]
    pub fixed: bool,
}

/// A block given by its rectangle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RectangleDescription {
    /// Left edge (m).
    pub x_m: f64,
    /// Bottom edge (m, 0 = on the ground).
    pub y_m: f64,
    /// Width (m).
    pub width_m: f64,
    /// Height (m).
    pub height_m: f64,
    /// Name (default as for course blocks).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// Density (kg/m3) when this stone differs from the wall's.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density_kg_m3: Option<f64>,
    /// An abutment that moves with the ground (default false).
    #[serde(default, skip_serializing_if = "is_false")]
    pub fixed: bool,
}

fn one() -> f64 {
    1.0
}
fn is_one(x: &f64) -> bool {
    *x == 1.0
}
fn default_g() -> f64 {
    9.81
}
fn is_default_g(x: &f64) -> bool {
    *x == 9.81
}
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}
fn is_false(b: &bool) -> bool {
    !*b
}
