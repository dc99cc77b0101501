//! Elevation drawings of a wall: block names, joint friction, the support graph, and a
//! displaced or collapsed state from a run.

use super::svg::{Style, Svg};
use crate::topology::{Base, Topology};
use crate::wall::Wall;

/// What to draw on top of the blocks.
#[derive(Debug, Clone, Default)]
pub struct WallDrawing {
    /// Title line.
    pub title: String,
    /// Horizontal displacement of each block relative to the ground (m); `None` draws the wall
    /// as built.
    pub displacement_m: Option<Vec<f64>>,
    /// Each block's rotation (rad, clockwise positive) and the vertical displacement of the
    /// middle of its base (m), for a run that rotated blocks: the blocks are drawn turned about
    /// the middle of their base, moved by (u, w).
    pub pose: Option<(Vec<f64>, Vec<f64>)>,
    /// Blocks that fell (drawn hatched red at their last position).
    pub fallen: Vec<bool>,
    /// Label each horizontal joint with its friction coefficient.
    pub friction_labels: bool,
    /// Draw the support graph: a line from each block's centroid to each of its supports.
    pub support_graph: bool,
    /// A note under the drawing (what it shows, which command made it).
    pub note: Option<String>,
}

const MARGIN_PX: f64 = 40.0;
const MAX_W_PX: f64 = 960.0;
const MAX_H_PX: f64 = 560.0;

/// Draws the wall as an SVG document.
pub fn draw_wall(wall: &Wall, topo: &Topology, d: &WallDrawing) -> String {
    let du = |i: usize| d.displacement_m.as_ref().map_or(0.0, |u| u[i]);
    let fallen = |i: usize| d.fallen.get(i).copied().unwrap_or(false);
    // Where the run put the point (px, py) of block i as built: turned about the middle of its
    // base and moved by (u, w); moved by u alone when nothing turned.
    let moved = |i: usize, px: f64, py: f64| -> (f64, f64) {
        let Some((theta, w)) = d.pose.as_ref().map(|(t, w)| (t[i], w[i])) else {
            return (px + du(i), py);
        };
        let b = &wall.blocks[i];
        let (mx, y) = (b.x.to_f64() + b.width.to_f64() / 2.0, b.y.to_f64());
        let (sin, cos) = theta.sin_cos();
        let (rx, ry) = (px - mx, py - y);
        (
            mx + du(i) + cos * rx + sin * ry,
            y + w - sin * rx + cos * ry,
        )
    };
    // Each block's corners where the run put it, when blocks turned.
    let corners = |i: usize| -> Option<[(f64, f64); 4]> {
        d.pose.as_ref()?;
        let b = &wall.blocks[i];
        let (x, y, bw, bh) = (
            b.x.to_f64(),
            b.y.to_f64(),
            b.width.to_f64(),
            b.height.to_f64(),
        );
        let at = |px: f64, py: f64| moved(i, px, py);
        Some([at(x, y), at(x + bw, y), at(x + bw, y + bh), at(x, y + bh)])
    };
    let (mut x0, mut x1, mut top) = (f64::INFINITY, f64::NEG_INFINITY, 0.0f64);
    for (i, b) in wall.blocks.iter().enumerate() {
        for x in [b.x.to_f64(), b.right().to_f64()] {
            x0 = x0.min(x).min(x + du(i));
            x1 = x1.max(x).max(x + du(i));
        }
        top = top.max(b.top().to_f64());
        for (x, y) in corners(i).into_iter().flatten() {
            (x0, x1, top) = (x0.min(x), x1.max(x), top.max(y));
        }
    }
    let span = (x1 - x0).max(1e-9);
    let scale = (MAX_W_PX / span).min(MAX_H_PX / top.max(1e-9));
    let header = if d.title.is_empty() { 0.0 } else { 28.0 };
    let footer = if d.note.is_some() { 26.0 } else { 0.0 };
    // Wide enough for the title and the note on a narrow wall (a column, a block on a ledge):
    // sans-serif text is about 0.55 of its size wide per character.
    let text_px = |text: &str, size: f64| text.chars().count() as f64 * 0.55 * size;
    let words = text_px(&d.title, 16.0).max(d.note.as_deref().map_or(0.0, |n| text_px(n, 12.0)));
    let width = (span * scale).max(words) + 2.0 * MARGIN_PX;
    let height = top * scale + 2.0 * MARGIN_PX + header + footer;
    let px = |x: f64| MARGIN_PX + (x - x0) * scale;
    let py = |y: f64| MARGIN_PX + header + (top - y) * scale;
    let mut svg = Svg::new(width, height);
    if !d.title.is_empty() {
        svg.text(MARGIN_PX, 26.0, 16.0, "start", "#222", &d.title);
    }
    let ground_y = py(0.0);
    let ground = Style {
        fill: "none",
        stroke: "#553",
        width: 3.0,
        dash: "",
    };
    svg.line(
        (px(x0) - 20.0, ground_y),
        (px(x1) + 20.0, ground_y),
        &ground,
    );
    let name_size = (scale * 0.12).clamp(9.0, 18.0);
    for (i, b) in wall.blocks.iter().enumerate() {
        let (bx, by, bw, bh) = (
            b.x.to_f64() + du(i),
            b.y.to_f64(),
            b.width.to_f64(),
            b.height.to_f64(),
        );
        let style = if fallen(i) {
            Style {
                fill: "#f4c7c3",
                stroke: "#b3261e",
                width: 2.0,
                dash: "6 3",
            }
        } else if b.fixed {
            Style {
                fill: "#b8b8b8",
                stroke: "#333",
                width: 1.5,
                dash: "",
            }
        } else {
            Style {
                fill: "#e9dcc3",
                stroke: "#5b4a2f",
                width: 1.5,
                dash: "",
            }
        };
        let (cx, cy) = match corners(i) {
            Some(c) => {
                let points = c.map(|(x, y)| (px(x), py(y)));
                svg.polygon(&points, &style);
                (
                    c.iter().map(|p| p.0).sum::<f64>() / 4.0,
                    c.iter().map(|p| p.1).sum::<f64>() / 4.0,
                )
            }
            None => {
                svg.rect(px(bx), py(by + bh), bw * scale, bh * scale, &style);
                (bx + bw / 2.0, by + bh / 2.0)
            }
        };
        let mut label = b.name.clone();
        if fallen(i) {
            label.push_str(" (fell)");
        } else if b.fixed {
            label.push_str(" (fixed)");
        }
        svg.text(
            px(cx),
            py(cy) + name_size * 0.35,
            name_size,
            "middle",
            "#222",
            &label,
        );
    }
    if d.support_graph {
        for s in &topo.horizontal {
            let u = s.upper.0;
            let b = &wall.blocks[u];
            let (cx, cy) = (
                b.centroid_x().to_f64() + du(u),
                (b.y.to_f64() + b.top().to_f64()) / 2.0,
            );
            let (lx, ly) = match s.lower {
                Base::Ground => (cx, 0.0),
                Base::Block(l) => {
                    let lb = &wall.blocks[l.0];
                    (
                        lb.centroid_x().to_f64() + du(l.0),
                        (lb.y.to_f64() + lb.top().to_f64()) / 2.0,
                    )
                }
            };
            let edge = Style {
                fill: "none",
                stroke: "#1f5fa8",
                width: 1.5,
                dash: "",
            };
            svg.line((px(cx), py(cy)), (px(lx), py(ly)), &edge);
            svg.circle(px(cx), py(cy), 3.0, "#1f5fa8");
        }
        for j in &topo.vertical {
            let (l, r) = (&wall.blocks[j.left.0], &wall.blocks[j.right.0]);
            let y = (l.y.clone().max(r.y.clone()).to_f64() + l.top().min(r.top()).to_f64()) / 2.0;
            let (xa, xb) = (
                l.right().to_f64() + du(j.left.0),
                r.x.to_f64() + du(j.right.0),
            );
            let joint = Style {
                fill: "none",
                stroke: "#c2571a",
                width: 2.5,
                dash: "",
            };
            svg.line((px(xa) - 6.0, py(y)), (px(xb) + 6.0, py(y)), &joint);
        }
    }
    if d.friction_labels {
        let size = (name_size * 0.75).max(8.0);
        for s in &topo.horizontal {
            let u = s.upper.0;
            let b = &wall.blocks[u];
            let (lo, hi) = match s.lower {
                Base::Ground => (b.x.to_f64(), b.right().to_f64()),
                Base::Block(l) => {
                    let lb = &wall.blocks[l.0];
                    (
                        b.x.to_f64().max(lb.x.to_f64()),
                        b.right().to_f64().min(lb.right().to_f64()),
                    )
                }
            };
            // On the upper block's base, where the run put it.
            let (x, y) = moved(u, (lo + hi) / 2.0, b.y.to_f64());
            svg.text(
                px(x),
                py(y) - 4.0,
                size,
                "middle",
                "#1f5fa8",
                &format!("\u{3bc} {}", s.friction),
            );
        }
        for j in &topo.vertical {
            if j.gap_m.is_positive() {
                let l = &wall.blocks[j.left.0];
                let (x, y) = moved(
                    j.left.0,
                    l.right().to_f64(),
                    l.y.to_f64() + l.height.to_f64() * 0.8,
                );
                svg.text(
                    px(x) + 2.0,
                    py(y),
                    size,
                    "start",
                    "#c2571a",
                    &format!("gap {} m", j.gap_m),
                );
            }
        }
    }
    if let Some(note) = &d.note {
        svg.text(MARGIN_PX, height - 12.0, 12.0, "start", "#555", note);
    }
    svg.finish()
}

/// A limit's mechanism as a pose to draw ([`WallDrawing::displacement_m`] and
/// [`WallDrawing::pose`]): each block that moves turned about its point at rest, or moved
/// without turning, by one exaggerated step of the mechanism (its largest turn 0.1 rad, or its
/// fastest block moved by a twentieth of the wall's height, whichever is smaller).
pub fn mechanism_pose(
    wall: &Wall,
    mechanism: &[crate::limit::Moves],
) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let n = wall.blocks.len();
    let (mut u, mut theta, mut w) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let height = wall
        .blocks
        .iter()
        .map(|b| b.top().to_f64())
        .fold(0.0, f64::max);
    let turn = mechanism
        .iter()
        .map(|m| m.omega_rad_s.abs())
        .fold(0.0, f64::max);
    let speed = mechanism
        .iter()
        .map(|m| m.u.hypot(m.v))
        .fold(0.0, f64::max)
        .max(1e-300);
    let k = (0.05 * height / speed).min(if turn > 0.0 {
        0.1 / turn
    } else {
        f64::INFINITY
    });
    for m in mechanism {
        let Some(i) = wall.blocks.iter().position(|b| b.name == m.block) else {
            continue;
        };
        let b = &wall.blocks[i];
        let (cx, cy) = (
            b.centroid_x().to_f64(),
            b.y.to_f64() + b.height.to_f64() / 2.0,
        );
        let (mx, my) = (b.x.to_f64() + b.width.to_f64() / 2.0, b.y.to_f64());
        if m.omega_rad_s == 0.0 {
            (u[i], w[i]) = (k * m.u, k * m.v);
            continue;
        }
        // Turned about the point the mechanism holds still, counterclockwise by k omega.
        let (ix, iy) = (cx - m.v / m.omega_rad_s, cy + m.u / m.omega_rad_s);
        let phi = k * m.omega_rad_s;
        let (sin, cos) = phi.sin_cos();
        let (rx, ry) = (mx - ix, my - iy);
        u[i] = ix + cos * rx - sin * ry - mx;
        w[i] = iy + sin * rx + cos * ry - my;
        theta[i] = -phi;
    }
    (u, theta, w)
}
