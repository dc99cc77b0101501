//! The wall: a checked set of rectangular blocks with exact geometry and material, built from a
//! RON description (courses or rectangles; both give the same model). The support and contact
//! graph built on top of it lives in [`crate::topology`].

mod description;
mod generate;
pub mod survey;

pub use description::{
    BlockDescription, RectangleDescription, RowDescription, WallDescription, WALL_FORMAT_VERSION,
};
pub use generate::RunningBond;

use crate::bounds;
use crate::error::{Error, WallError};
use crate::exact::Q;
use std::cmp::Reverse;
use std::collections::{BTreeMap, BinaryHeap, HashMap};
use std::path::Path;

/// A block of the wall; geometry in metres, exact.
#[derive(Debug, Clone, PartialEq)]
pub struct Block {
    /// Name (`B1`... by default).
    pub name: String,
    /// Where it was described ("row 2, block 1", "rectangle 3"), for messages.
    pub origin: String,
    /// Left edge (m).
    pub x: Q,
    /// Bottom edge (m).
    pub y: Q,
    /// Width (m).
    pub width: Q,
    /// Height (m).
    pub height: Q,
    /// Moves with the ground (an abutment).
    pub fixed: bool,
    /// Its own density (kg/m3) when it differs from the wall's.
    pub density_kg_m3: Option<Q>,
}

impl Block {
    /// Right edge (m).
    pub fn right(&self) -> Q {
        &self.x + &self.width
    }
    /// Top edge (m).
    pub fn top(&self) -> Q {
        &self.y + &self.height
    }
    /// Horizontal position of the centroid (m).
    pub fn centroid_x(&self) -> Q {
        &self.x + &self.width * Q::frac(1, 2)
    }
    /// Area in elevation (m2).
    pub fn area(&self) -> Q {
        &self.width * &self.height
    }
}

/// A friction override as written in the file, resolved against the support graph later.
#[derive(Debug, Clone, PartialEq)]
pub struct FrictionOverride {
    /// The key as written (`"B3/B1"`).
    pub key: String,
    /// Friction coefficient.
    pub value: Q,
}

/// A checked wall.
#[derive(Debug, Clone, PartialEq)]
pub struct Wall {
    /// Name shown in output.
    pub name: String,
    /// Out-of-plane thickness (m).
    pub thickness_m: Q,
    /// Density (kg/m3); derived from the unit weight when that is what the file gave.
    pub density_kg_m3: Q,
    /// Gravity (m/s2).
    pub g_m_s2: Q,
    /// Coefficient of restitution of vertical joints.
    pub restitution: Q,
    /// Factor on Housner's coefficient of restitution of rocking landings.
    pub rocking_restitution_factor: f64,
    /// Default friction coefficient of horizontal joints.
    pub friction: Q,
    /// Per-joint friction overrides.
    pub joint_friction: Vec<FrictionOverride>,
    /// Blocks, numbered bottom course first, left to right.
    pub blocks: Vec<Block>,
}

fn exact(x: f64) -> Q {
    Q::from_decimal(x).expect("finite values are checked before conversion")
}

fn field(field: &str, value: f64, ok: bool, rule: &'static str) -> Result<Q, WallError> {
    if ok && value.is_finite() {
        Ok(exact(value))
    } else {
        Err(WallError::Field {
            field: field.to_string(),
            value,
            rule,
        })
    }
}

fn block_number(
    name: &Option<String>,
    origin: &str,
    field: &'static str,
    value: f64,
    ok: bool,
    rule: &'static str,
) -> Result<Q, WallError> {
    if ok && value.is_finite() {
        Ok(exact(value))
    } else {
        Err(WallError::BlockField {
            block: name.clone(),
            origin: origin.to_string(),
            field,
            value,
            rule,
        })
    }
}

const POSITIVE_M: &str = "must be a length from 0.001 to 10000 m (docs/reliability.md: bounds)";
const DENSITY: &str = "must lie from 1 to 100000 kg/m3 (docs/reliability.md: bounds)";

/// A length within the bounds of a block, course or wall.
fn length(x: f64) -> bool {
    bounds::within(x, (bounds::MIN_LENGTH_M, bounds::MAX_LENGTH_M))
}

impl Wall {
    /// Reads and checks a wall file.
    pub fn load(path: &Path) -> Result<Wall, Error> {
        let text = crate::text::read(path, "wall")?;
        let mut wall = Wall::from_ron_str(&text).map_err(|source| Error::Wall {
            path: path.to_path_buf(),
            source,
        })?;
        if wall.name.is_empty() {
            wall.name = path
                .file_stem()
                .map_or_else(|| "wall".to_string(), |s| s.to_string_lossy().into_owned());
        }
        Ok(wall)
    }

    /// Parses and checks a wall written in RON. The name stays empty when the file gives none.
    pub fn from_ron_str(text: &str) -> Result<Wall, WallError> {
        let description = parse_description(text)?;
        Wall::from_description(&description)
    }

    /// Checks a description and builds the model: numbers in range, material given once, names
    /// unique, no two blocks overlapping.
    pub fn from_description(d: &WallDescription) -> Result<Wall, WallError> {
        if d.version != WALL_FORMAT_VERSION {
            return Err(WallError::Version {
                found: d.version,
                supported: WALL_FORMAT_VERSION,
            });
        }
        let thickness_m = field(
            "thickness_m",
            d.thickness_m,
            length(d.thickness_m),
            POSITIVE_M,
        )?;
        let g_m_s2 = field(
            "g_m_s2",
            d.g_m_s2,
            bounds::within(d.g_m_s2, bounds::GRAVITY_M_S2),
            "gravity must lie from 0.1 to 100 m/s2",
        )?;
        let restitution = field(
            "restitution",
            d.restitution,
            (0.0..=1.0).contains(&d.restitution),
            "the coefficient of restitution must lie in [0, 1]",
        )?;
        field(
            "rocking_restitution_factor",
            d.rocking_restitution_factor,
            (0.0..=1.0).contains(&d.rocking_restitution_factor),
            "the factor on Housner's restitution must lie in [0, 1]",
        )?;
        let friction = field(
            "friction",
            d.friction,
            d.friction > 0.0 && d.friction <= 2.0,
            "a friction coefficient must lie in (0, 2]",
        )?;
        let density_kg_m3 = match (d.density_kg_m3, d.unit_weight_kn_m3) {
            (Some(rho), None) => field(
                "density_kg_m3",
                rho,
                bounds::within(rho, bounds::DENSITY_KG_M3),
                DENSITY,
            )?,
            (None, Some(gamma)) => {
                field(
                    "unit_weight_kn_m3",
                    gamma,
                    bounds::within(gamma, (0.01, 1000.0)),
                    "must lie from 0.01 to 1000 kN/m3",
                )? * Q::int(1000)
                    / &g_m_s2
            }
            _ => return Err(WallError::Material),
        };
        let mut joint_friction = Vec::with_capacity(d.joint_friction.len());
        for (key, &value) in &d.joint_friction {
            let value = field(
                &format!("joint_friction \"{key}\""),
                value,
                value > 0.0 && value <= 2.0,
                "a friction coefficient must lie in (0, 2]",
            )?;
            joint_friction.push(FrictionOverride {
                key: key.clone(),
                value,
            });
        }

        let mut blocks = Vec::new();
        let mut y = Q::zero();
        for (r, row) in d.rows.iter().enumerate() {
            let row_name = format!("row {}", r + 1);
            let row_height = field(
                &format!("{row_name}: height_m"),
                row.height_m,
                length(row.height_m),
                POSITIVE_M,
            )?;
            let mut x = field(
                &format!("{row_name}: x_m"),
                row.x_m,
                row.x_m.abs() <= bounds::MAX_POSITION_M,
                "must be a number of metres within 1000 km of the origin",
            )?;
            for (k, spec) in row.blocks.iter().enumerate() {
                let origin = format!("{row_name}, block {}", k + 1);
                let num = |f, v: f64, ok, rule| block_number(&spec.name, &origin, f, v, ok, rule);
                let width = num("width_m", spec.width_m, length(spec.width_m), POSITIVE_M)?;
                let gap = num(
                    "gap_m",
                    spec.gap_m,
                    (0.0..=bounds::MAX_LENGTH_M).contains(&spec.gap_m),
                    "must be a number of metres from 0 to 10000",
                )?;
                let height = match spec.height_m {
                    Some(h) => num("height_m", h, length(h), POSITIVE_M)?,
                    None => row_height.clone(),
                };
                let density_kg_m3 = spec
                    .density_kg_m3
                    .map(|rho| {
                        let ok = bounds::within(rho, bounds::DENSITY_KG_M3);
                        num("density_kg_m3", rho, ok, DENSITY)
                    })
                    .transpose()?;
                let left = x + gap;
                x = &left + &width;
                blocks.push(Block {
                    name: spec.name.clone().unwrap_or_default(),
                    origin,
                    x: left,
                    y: y.clone(),
                    width,
                    height,
                    fixed: spec.fixed,
                    density_kg_m3,
                });
            }
            y = y + row_height;
        }
        for (k, rect) in d.rectangles.iter().enumerate() {
            let origin = format!("rectangle {}", k + 1);
            let num = |f, v: f64, ok, rule| block_number(&rect.name, &origin, f, v, ok, rule);
            blocks.push(Block {
                name: rect.name.clone().unwrap_or_default(),
                x: num(
                    "x_m",
                    rect.x_m,
                    rect.x_m.abs() <= bounds::MAX_POSITION_M,
                    "must be a number of metres within 1000 km of the origin",
                )?,
                y: num(
                    "y_m",
                    rect.y_m,
                    (0.0..=bounds::MAX_POSITION_M).contains(&rect.y_m),
                    "must be a number of metres from 0 (on the ground) to 1000 km",
                )?,
                width: num("width_m", rect.width_m, length(rect.width_m), POSITIVE_M)?,
                height: num("height_m", rect.height_m, length(rect.height_m), POSITIVE_M)?,
                fixed: rect.fixed,
                density_kg_m3: rect
                    .density_kg_m3
                    .map(|rho| {
                        let ok = bounds::within(rho, bounds::DENSITY_KG_M3);
                        num("density_kg_m3", rho, ok, DENSITY)
                    })
                    .transpose()?,
                origin,
            });
        }
        if blocks.is_empty() {
            return Err(WallError::Empty);
        }

        // Paper numbering: bottom course first, left to right.
        blocks.sort_by(|a, b| a.y.cmp(&b.y).then_with(|| a.x.cmp(&b.x)));
        let explicit: Vec<bool> = blocks.iter().map(|b| !b.name.is_empty()).collect();
        for (i, b) in blocks.iter_mut().enumerate() {
            if b.name.is_empty() {
                b.name = format!("B{}", i + 1);
            }
        }
        let mut seen: HashMap<&str, usize> = HashMap::new();
        for (i, b) in blocks.iter().enumerate() {
            if b.name == "ground" || b.name.contains('/') || b.name.trim().is_empty() {
                return Err(WallError::BlockName {
                    name: b.name.clone(),
                    origin: b.origin.clone(),
                });
            }
            if let Some(&j) = seen.get(b.name.as_str()) {
                let describe = |k: usize| {
                    let how = if explicit[k] { "named" } else { "numbered" };
                    format!("{} ({how})", blocks[k].origin)
                };
                return Err(WallError::DuplicateName {
                    name: b.name.clone(),
                    first: describe(j),
                    second: describe(i),
                });
            }
            seen.insert(&b.name, i);
        }
        check_overlaps(&blocks)?;

        Ok(Wall {
            name: d.name.clone().unwrap_or_default(),
            thickness_m,
            density_kg_m3,
            g_m_s2,
            restitution,
            rocking_restitution_factor: d.rocking_restitution_factor,
            friction,
            joint_friction,
            blocks,
        })
    }

    /// Index of the block with this name.
    pub fn block_index(&self, name: &str) -> Option<usize> {
        self.blocks.iter().position(|b| b.name == name)
    }

    /// Mass of block `i` (kg), of its own density or the wall's.
    pub fn mass_kg(&self, i: usize) -> Q {
        let b = &self.blocks[i];
        b.area() * &self.thickness_m * b.density_kg_m3.as_ref().unwrap_or(&self.density_kg_m3)
    }

    /// The wall mirrored left to right about x = 0 (blocks keep their names).
    pub fn mirrored(&self) -> Wall {
        let mut w = self.clone();
        for b in &mut w.blocks {
            b.x = -b.right();
        }
        w
    }
}

/// Parses RON into a description, with the extension that lets optional fields be written bare.
pub fn parse_description(text: &str) -> Result<WallDescription, WallError> {
    ron::Options::default()
        .with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME)
        .from_str(text)
        .map_err(|e| WallError::Syntax {
            line: e.span.start.line,
            col: e.span.start.col,
            message: e.code.to_string(),
        })
}

/// Writes a description as RON that [`parse_description`] reads back.
pub fn to_ron_string(d: &WallDescription) -> String {
    let config = ron::ser::PrettyConfig::new()
        .struct_names(false)
        .extensions(ron::extensions::Extensions::IMPLICIT_SOME);
    ron::ser::to_string_pretty(d, config).expect("a wall description always serialises")
}

/// Finds two blocks that overlap, sweeping left to right: the blocks the sweep line crosses
/// overlap one another horizontally, so their vertical extents are disjoint (or the sweep has
/// already stopped), and the only one a new block can overlap is the one starting last below
/// its top. A lookup per block instead of a comparison with every block the line crosses
/// (one per course): large walls load in n log n.
pub(crate) fn check_overlaps(blocks: &[Block]) -> Result<(), WallError> {
    let rights: Vec<Q> = blocks.iter().map(Block::right).collect();
    let tops: Vec<Q> = blocks.iter().map(Block::top).collect();
    let mut order: Vec<usize> = (0..blocks.len()).collect();
    order.sort_by(|&a, &b| blocks[a].x.cmp(&blocks[b].x));
    // The blocks the sweep line crosses, by their bottom edge, and by their right edge to let
    // them go.
    let mut crossed: BTreeMap<&Q, usize> = BTreeMap::new();
    let mut ending: BinaryHeap<Reverse<(&Q, usize)>> = BinaryHeap::new();
    for &i in &order {
        let b = &blocks[i];
        while let Some(&Reverse((right, a))) = ending.peek() {
            if *right > b.x {
                break;
            }
            ending.pop();
            crossed.remove(&blocks[a].y);
        }
        if let Some((_, &a)) = crossed.range::<&Q, _>(..&tops[i]).next_back() {
            if tops[a] > b.y {
                let o = &blocks[a];
                let dy = tops[a].clone().min(tops[i].clone()) - o.y.clone().max(b.y.clone());
                let dx = rights[a].clone().min(rights[i].clone()) - o.x.clone().max(b.x.clone());
                let (first, second) = if a < i { (o, b) } else { (b, o) };
                return Err(WallError::Overlap {
                    a: first.name.clone(),
                    b: second.name.clone(),
                    dx_m: dx.to_f64(),
                    dy_m: dy.to_f64(),
                });
            }
        }
        crossed.insert(&b.y, i);
        ending.push(Reverse((&rights[i], i)));
    }
    Ok(())
}
