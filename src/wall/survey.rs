//! Surveyed walls: block outlines from a CSV (a total station, photogrammetry, a measured
//! drawing) made into a wall description. Surveyed edges never line up exactly, so edges
//! within a tolerance of each other are snapped to one level (a bottom onto the top it rests
//! on) or one face (two blocks that touch); wider gaps are kept as measured. Every snap is
//! reported, and data that no snap within the tolerance can reconcile is an error naming the
//! blocks and the distance in mm.

use super::{RectangleDescription, WallDescription, WALL_FORMAT_VERSION};
use crate::error::SurveyError;
use crate::sets::DisjointSets;
use std::collections::{BTreeMap, HashMap};

/// Snapped coordinates are whole multiples of this (m): 0.01 mm, far below any survey's
/// precision, and short decimals keep the wall's geometry exact (a block's y + height is
/// exactly the level of the blocks it carries).
pub const RESOLUTION_M: f64 = 1.0 / TICKS_PER_M;

/// Typical densities (kg/m3) of the stones of Andean masonry, for the survey's `material`
/// column; a number there is taken as a measured density instead.
pub const MATERIALS: [(&str, f64); 7] = [
    ("andesite", 2650.0),
    ("granite", 2650.0),
    ("diorite", 2850.0),
    ("basalt", 2900.0),
    ("limestone", 2600.0),
    ("rhyolite", 2500.0),
    ("sandstone", 2350.0),
];

const COLUMNS: &str = "id, x, y, width, height (required), material, friction, fixed (optional)";

/// One surveyed block, in metres, as read.
#[derive(Debug, Clone, PartialEq)]
pub struct SurveyBlock {
    /// Its id in the survey (the block's name in the wall).
    pub id: String,
    /// Line of the CSV.
    pub line: usize,
    /// Left edge (m).
    pub x_m: f64,
    /// Bottom edge (m).
    pub y_m: f64,
    /// Width (m).
    pub width_m: f64,
    /// Height (m).
    pub height_m: f64,
    /// Density from the material column (kg/m3).
    pub density_kg_m3: Option<f64>,
    /// Friction coefficient of the joints it rests on.
    pub friction: Option<f64>,
    /// An abutment that moves with the ground.
    pub fixed: bool,
}

/// The wall-level values a survey does not give.
#[derive(Debug, Clone, PartialEq)]
pub struct SurveyOptions {
    /// Snap tolerance (m).
    pub snap_m: f64,
    /// Wall name.
    pub name: String,
    /// Out-of-plane thickness (m).
    pub thickness_m: f64,
    /// Density of blocks without a material (kg/m3).
    pub density_kg_m3: f64,
    /// Friction of joints under blocks without their own.
    pub friction: f64,
    /// Coefficient of restitution.
    pub restitution: f64,
}

/// A block edge.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Edge {
    /// Bottom (y).
    Bottom,
    /// Top (y + height).
    Top,
    /// Left face (x).
    Left,
    /// Right face (x + width).
    Right,
}

/// One edge moved by the import.
#[derive(Debug, Clone, PartialEq)]
pub struct Snap {
    /// Block id.
    pub block: String,
    /// Which edge.
    pub edge: Edge,
    /// Where the survey put it (m, levels measured from the lowest bottom).
    pub from_m: f64,
    /// Where the wall has it (m).
    pub to_m: f64,
    /// The edges it was snapped to ("ground", "top of B3", ...).
    pub onto: String,
}

/// A survey made into a wall.
#[derive(Debug, Clone, PartialEq)]
pub struct Imported {
    /// The wall (rectangles named by survey id, in survey order).
    pub description: WallDescription,
    /// Every edge that moved by more than [`RESOLUTION_M`].
    pub snaps: Vec<Snap>,
    /// The survey's y of the ground (the lowest bottom), which becomes y = 0.
    pub ground_y_m: f64,
}

impl Imported {
    /// The largest adjustment.
    pub fn largest_snap(&self) -> Option<&Snap> {
        self.snaps.iter().max_by(|a, b| {
            (a.to_m - a.from_m)
                .abs()
                .total_cmp(&(b.to_m - b.from_m).abs())
        })
    }
}

fn line_error(line: usize, message: String) -> SurveyError {
    SurveyError::Line { line, message }
}

/// Reads a survey CSV: a header naming the columns, then one block per line; `#` starts a
/// comment line. Lengths are multiplied by `unit_m` (0.001 for millimetres).
pub fn parse_survey(text: &str, unit_m: f64) -> Result<Vec<SurveyBlock>, SurveyError> {
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(k, l)| (k + 1, l.trim()))
        .filter(|(_, l)| !l.is_empty() && !l.starts_with('#'));
    let (header_line, header) = lines.next().ok_or_else(|| {
        line_error(
            1,
            format!("the survey is empty: give a header ({COLUMNS}) and one block per line"),
        )
    })?;
    let names: Vec<String> = header
        .split(',')
        .map(|c| c.trim().to_ascii_lowercase())
        .collect();
    let mut column = HashMap::new();
    for (k, name) in names.iter().enumerate() {
        let known = [
            "id", "x", "y", "width", "height", "material", "friction", "fixed",
        ];
        if !known.contains(&name.as_str()) {
            return Err(line_error(
                header_line,
                format!("unknown column `{name}`: the columns are {COLUMNS}"),
            ));
        }
        if column.insert(name.as_str(), k).is_some() {
            return Err(line_error(
                header_line,
                format!("column `{name}` appears twice"),
            ));
        }
    }
    for required in ["id", "x", "y", "width", "height"] {
        if !column.contains_key(required) {
            return Err(line_error(
                header_line,
                format!("the header has no `{required}` column: the columns are {COLUMNS}"),
            ));
        }
    }
    let mut blocks: Vec<SurveyBlock> = Vec::new();
    let mut seen: HashMap<String, usize> = HashMap::new();
    for (line, text) in lines {
        let fields: Vec<&str> = text.split(',').map(str::trim).collect();
        if fields.len() != names.len() {
            return Err(line_error(
                line,
                format!(
                    "{} fields, but the header names {} columns",
                    fields.len(),
                    names.len()
                ),
            ));
        }
        let get = |name: &str| {
            column
                .get(name)
                .map(|&k| fields[k])
                .filter(|f| !f.is_empty())
        };
        let number = |name: &str| -> Result<f64, SurveyError> {
            let f =
                get(name).ok_or_else(|| line_error(line, format!("column `{name}` is empty")))?;
            f.parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| line_error(line, format!("column `{name}`: `{f}` is not a number")))
        };
        let id = get("id").ok_or_else(|| line_error(line, "the block has no id".into()))?;
        if id == "ground" || id.contains('/') {
            return Err(line_error(
                line,
                format!("block id `{id}`: an id must not contain '/' or be \"ground\""),
            ));
        }
        if let Some(first) = seen.insert(id.to_string(), line) {
            return Err(line_error(
                line,
                format!("block id `{id}` is used twice: on line {first} and here"),
            ));
        }
        let (width_m, height_m) = (number("width")? * unit_m, number("height")? * unit_m);
        for (name, v) in [("width", width_m), ("height", height_m)] {
            if v <= 0.0 {
                return Err(line_error(
                    line,
                    format!("block {id}: {name} must be positive, found {v} m"),
                ));
            }
        }
        let friction = match get("friction") {
            None => None,
            Some(_) => {
                let mu = number("friction")?;
                if !(mu > 0.0 && mu <= 2.0) {
                    return Err(line_error(
                        line,
                        format!("block {id}: friction {mu} must lie in (0, 2]"),
                    ));
                }
                Some(mu)
            }
        };
        let density_kg_m3 = match get("material") {
            None => None,
            Some(m) => Some(material_density(m).ok_or_else(|| {
                let known: Vec<&str> = MATERIALS.iter().map(|m| m.0).collect();
                line_error(
                    line,
                    format!(
                        "block {id}: material `{m}` is unknown: write one of {} or a density in kg/m3",
                        known.join(", ")
                    ),
                )
            })?),
        };
        let fixed = match get("fixed").map(str::to_ascii_lowercase).as_deref() {
            None | Some("false" | "no" | "0") => false,
            Some("true" | "yes" | "1") => true,
            Some(other) => {
                return Err(line_error(
                    line,
                    format!("block {id}: fixed `{other}` must be true or false (yes/no, 1/0)"),
                ))
            }
        };
        blocks.push(SurveyBlock {
            id: id.to_string(),
            line,
            x_m: number("x")? * unit_m,
            y_m: number("y")? * unit_m,
            width_m,
            height_m,
            density_kg_m3,
            friction,
            fixed,
        });
    }
    if blocks.is_empty() {
        return Err(line_error(
            header_line,
            "the survey has a header but no blocks".into(),
        ));
    }
    Ok(blocks)
}

/// A material name of [`MATERIALS`] (any case) or a positive density in kg/m3.
fn material_density(text: &str) -> Option<f64> {
    if let Ok(rho) = text.parse::<f64>() {
        return (rho.is_finite() && rho > 0.0).then_some(rho);
    }
    MATERIALS
        .iter()
        .find(|m| m.0.eq_ignore_ascii_case(text))
        .map(|m| m.1)
}

/// Ticks of [`RESOLUTION_M`] per metre.
const TICKS_PER_M: f64 = 1e5;

fn ticks(x_m: f64) -> i64 {
    (x_m * TICKS_PER_M).round() as i64
}

/// A whole number of ticks in metres, as the nearest double to the decimal (a division by an
/// exact power of ten is correctly rounded), which the wall reads back as that exact decimal.
fn metres(t: i64) -> f64 {
    t as f64 / TICKS_PER_M
}

/// One coordinate per edge after snapping: the midpoint of each group of joined edges (so no
/// edge moves by more than the tolerance), `fixed` for a group holding edge `anchor`.
/// `owner(e)` names the block of edge e, for the error when a group spreads too far.
fn snap_groups(
    sets: &mut DisjointSets,
    values: &[f64],
    anchor: Option<(usize, f64)>,
    tol: f64,
    what: &'static str,
    owner: &dyn Fn(usize) -> String,
) -> Result<Vec<i64>, SurveyError> {
    let mut range: HashMap<usize, (usize, usize)> = HashMap::new();
    for e in 0..values.len() {
        let r = sets.find(e);
        let entry = range.entry(r).or_insert((e, e));
        if values[e] < values[entry.0] {
            entry.0 = e;
        }
        if values[e] > values[entry.1] {
            entry.1 = e;
        }
    }
    let anchored = anchor.map(|(e, v)| (sets.find(e), v));
    (0..values.len())
        .map(|e| {
            let r = sets.find(e);
            let (lo, hi) = range[&r];
            let value = match anchored {
                Some((a, v)) if a == r => v,
                _ => {
                    // A group may chain edges, but each must stay within the tolerance of where it
                    // ends up: the midpoint serves every edge of a group up to twice the tolerance.
                    if values[hi] - values[lo] > 2.0 * tol * (1.0 + 1e-12) {
                        return Err(SurveyError::Chain {
                            what,
                            a: owner(lo),
                            b: owner(hi),
                            spread_mm: (values[hi] - values[lo]) * 1e3,
                            snap_mm: tol * 1e3,
                        });
                    }
                    0.5 * (values[lo] + values[hi])
                }
            };
            Ok(ticks(value))
        })
        .collect()
}

/// What edge `edge` was snapped to: the other edges of its group.
fn group_names(
    sets: &mut DisjointSets,
    edge: usize,
    count: usize,
    name: &dyn Fn(usize) -> String,
) -> String {
    let r = sets.find(edge);
    let others: Vec<String> = (0..count)
        .filter(|&e| e != edge && sets.find(e) == r)
        .map(name)
        .collect();
    if others.is_empty() {
        "its own position (rounded)".to_string()
    } else {
        others.join(", ")
    }
}

/// Makes surveyed blocks into a wall: snaps levels and faces within `options.snap_m`, measures
/// levels from the lowest bottom (the ground), keeps x as surveyed (a battered wall's
/// offsets stay), and checks what no snap can fix.
pub fn import(blocks: &[SurveyBlock], options: &SurveyOptions) -> Result<Imported, SurveyError> {
    let n = blocks.len();
    if !(options.snap_m.is_finite() && options.snap_m >= 0.0) {
        return Err(SurveyError::Tolerance {
            snap_m: options.snap_m,
        });
    }
    // Edges that agree to the resolution are one edge even with --snap 0: the survey's units
    // (mm times 0.001) leave round-off in the metres compared here.
    let tol = options.snap_m.max(RESOLUTION_M / 2.0);
    let snap_mm = tol * 1e3;
    let ground_y_m = blocks.iter().map(|b| b.y_m).fold(f64::INFINITY, f64::min);
    let left: Vec<f64> = blocks.iter().map(|b| b.x_m).collect();
    let right: Vec<f64> = blocks.iter().map(|b| b.x_m + b.width_m).collect();
    let bottom: Vec<f64> = blocks.iter().map(|b| b.y_m - ground_y_m).collect();
    let top: Vec<f64> = blocks
        .iter()
        .map(|b| b.y_m + b.height_m - ground_y_m)
        .collect();
    let overlap = |a0: f64, a1: f64, b0: f64, b1: f64| a1.min(b1) - a0.max(b0);

    // Levels: edge i is block i's bottom, n + i its top, 2n the ground.
    let mut levels = DisjointSets::new(2 * n + 1);
    for i in 0..n {
        if bottom[i] <= tol {
            levels.join(i, 2 * n);
        }
        for j in (0..n).filter(|&j| j != i) {
            if (bottom[i] - top[j]).abs() <= tol
                && overlap(left[i], right[i], left[j], right[j]) > tol
            {
                levels.join(i, n + j);
            }
        }
    }
    let mut level_values: Vec<f64> = bottom.iter().chain(&top).copied().collect();
    level_values.push(0.0);
    // Levels within the tolerance of each other that no contact joined (a free crown, the two
    // sides of a window) become one too, so that noise does not let a block "see" its
    // neighbour's neighbour across a sliver of shared height. Groups are merged in order of
    // height while the merged group stays within twice the tolerance; nothing rests on these
    // joins, so a level that wanders further is left as surveyed rather than refused.
    let mut groups: BTreeMap<usize, (f64, f64)> = BTreeMap::new();
    for (e, &v) in level_values.iter().enumerate() {
        let g = groups.entry(levels.find(e)).or_insert((v, v));
        *g = (g.0.min(v), g.1.max(v));
    }
    let mut by_height: Vec<(usize, (f64, f64))> = groups.into_iter().collect();
    by_height.sort_by(|a, b| (a.1 .0 + a.1 .1).total_cmp(&(b.1 .0 + b.1 .1)));
    let ground = levels.find(2 * n);
    let mut current: Option<(usize, (f64, f64), bool)> = None;
    for (root, (lo, hi)) in by_height {
        let on_ground = root == ground;
        current = match current {
            // The ground stays at 0: a level joins it only if no edge moves more than the
            // tolerance.
            Some((r, (clo, chi), g))
                if hi.max(chi) - lo.min(clo) <= if g || on_ground { tol } else { 2.0 * tol } =>
            {
                levels.join(r, root);
                Some((r, (lo.min(clo), hi.max(chi)), g || on_ground))
            }
            _ => Some((root, (lo, hi), on_ground)),
        };
    }
    let owner = |e: usize| {
        if e == 2 * n {
            "ground".to_string()
        } else {
            blocks[e % n].id.clone()
        }
    };
    let y = snap_groups(
        &mut levels,
        &level_values,
        Some((2 * n, 0.0)),
        tol,
        "bottoms and tops",
        &owner,
    )?;

    // Faces of blocks that share height after snapping: edge i is block i's left face, n + i
    // its right face.
    let mut faces = DisjointSets::new(2 * n);
    for i in 0..n {
        for j in 0..n {
            let shared = y[n + i].min(y[n + j]) - y[i].max(y[j]);
            if i == j || shared <= 0 || left[i] + right[i] > left[j] + right[j] {
                continue;
            }
            let gap = left[j] - right[i];
            if gap.abs() <= tol {
                faces.join(n + i, j);
            } else if gap < -tol && overlap(bottom[i], top[i], bottom[j], top[j]) > tol {
                return Err(SurveyError::Overlap {
                    a: blocks[i].id.clone(),
                    b: blocks[j].id.clone(),
                    dx_mm: -gap * 1e3,
                    dy_mm: overlap(bottom[i], top[i], bottom[j], top[j]) * 1e3,
                    snap_mm,
                });
            }
        }
    }
    let face_values: Vec<f64> = left.iter().chain(&right).copied().collect();
    let x = snap_groups(&mut faces, &face_values, None, tol, "faces", &|e| {
        blocks[e % n].id.clone()
    })?;

    for (i, b) in blocks.iter().enumerate() {
        for (what, size) in [("high", y[n + i] - y[i]), ("wide", x[n + i] - x[i])] {
            if size <= 0 {
                return Err(SurveyError::Collapsed {
                    block: b.id.clone(),
                    what,
                    size_mm: metres(size) * 1e3,
                    snap_mm,
                });
            }
        }
    }
    // What no snap fixed: blocks that still overlap, blocks with nothing under them.
    for i in 0..n {
        for j in i + 1..n {
            let dx = x[n + i].min(x[n + j]) - x[i].max(x[j]);
            let dy = y[n + i].min(y[n + j]) - y[i].max(y[j]);
            if dx > 0 && dy > 0 {
                return Err(SurveyError::Overlap {
                    a: blocks[i].id.clone(),
                    b: blocks[j].id.clone(),
                    dx_mm: overlap(left[i], right[i], left[j], right[j]).max(0.0) * 1e3,
                    dy_mm: overlap(bottom[i], top[i], bottom[j], top[j]).max(0.0) * 1e3,
                    snap_mm,
                });
            }
        }
    }
    let supports = |i: usize| -> Vec<usize> {
        (0..n)
            .filter(|&j| y[n + j] == y[i] && x[n + i].min(x[n + j]) > x[i].max(x[j]))
            .collect()
    };
    let mut under: Vec<Vec<String>> = Vec::with_capacity(n);
    for i in 0..n {
        if y[i] == 0 {
            under.push(vec!["ground".into()]);
            continue;
        }
        let s = supports(i);
        if s.is_empty() {
            let nearest = (0..n)
                .filter(|&j| {
                    overlap(left[i], right[i], left[j], right[j]) > 0.0 && top[j] <= bottom[i]
                })
                .max_by(|&a, &b| top[a].total_cmp(&top[b]));
            let below = match nearest {
                Some(j) => format!(
                    "the nearest top below it is block {}'s, {:.1} mm lower",
                    blocks[j].id,
                    (bottom[i] - top[j]) * 1e3
                ),
                None => format!(
                    "no block is below it, and the ground is {:.1} mm lower",
                    bottom[i] * 1e3
                ),
            };
            return Err(SurveyError::Floating {
                block: blocks[i].id.clone(),
                below,
                snap_mm,
            });
        }
        under.push(s.iter().map(|&j| blocks[j].id.clone()).collect());
    }

    let level_name = |e: usize| match e {
        e if e == 2 * n => "ground".to_string(),
        e if e < n => format!("bottom of {}", blocks[e].id),
        e => format!("top of {}", blocks[e - n].id),
    };
    let face_name = |e: usize| {
        if e < n {
            format!("left face of {}", blocks[e].id)
        } else {
            format!("right face of {}", blocks[e - n].id)
        }
    };
    let mut snaps = Vec::new();
    for (i, b) in blocks.iter().enumerate() {
        for (edge, from, to, onto) in [
            (Edge::Bottom, bottom[i], metres(y[i]), (true, i)),
            (Edge::Top, top[i], metres(y[n + i]), (true, n + i)),
            (Edge::Left, left[i], metres(x[i]), (false, i)),
            (Edge::Right, right[i], metres(x[n + i]), (false, n + i)),
        ] {
            if (to - from).abs() > RESOLUTION_M {
                let onto = if onto.0 {
                    group_names(&mut levels, onto.1, 2 * n + 1, &level_name)
                } else {
                    group_names(&mut faces, onto.1, 2 * n, &face_name)
                };
                snaps.push(Snap {
                    block: b.id.clone(),
                    edge,
                    from_m: from,
                    to_m: to,
                    onto,
                });
            }
        }
    }

    let mut joint_friction = BTreeMap::new();
    for (i, b) in blocks.iter().enumerate() {
        if let Some(mu) = b.friction.filter(|&mu| mu != options.friction) {
            for lower in &under[i] {
                joint_friction.insert(format!("{}/{lower}", b.id), mu);
            }
        }
    }
    let description = WallDescription {
        version: WALL_FORMAT_VERSION,
        name: Some(options.name.clone()),
        thickness_m: options.thickness_m,
        density_kg_m3: Some(options.density_kg_m3),
        unit_weight_kn_m3: None,
        friction: options.friction,
        restitution: options.restitution,
        rocking_restitution_factor: 1.0,
        g_m_s2: 9.81,
        rows: Vec::new(),
        rectangles: blocks
            .iter()
            .enumerate()
            .map(|(i, b)| RectangleDescription {
                x_m: metres(x[i]),
                y_m: metres(y[i]),
                width_m: metres(x[n + i] - x[i]),
                height_m: metres(y[n + i] - y[i]),
                name: Some(b.id.clone()),
                density_kg_m3: b.density_kg_m3.filter(|&rho| rho != options.density_kg_m3),
                fixed: b.fixed,
            })
            .collect(),
        joint_friction,
    };
    let wall = super::Wall::from_description(&description)?;
    crate::topology::Topology::new(&wall)?;
    Ok(Imported {
        description,
        snaps,
        ground_y_m,
    })
}
