//! A saved run played back: one self-contained HTML page (no network, no external script) that
//! draws the blocks moved and rotated at every history sample, with a magnification for the
//! displacements, play and pause, a time slider, and the ground acceleration beside it with a
//! cursor and the run's events marked. `#t=2.5` in the page's address opens it at that time;
//! the state drawn is also written, as JSON, into the page's `#state` element, which is how the
//! tests read what a browser drew.

use crate::response::saved::{SavedEvent, SavedHistory};
use crate::wall::Wall;
use serde::Serialize;

/// One block as built (m).
#[derive(Debug, Clone, Serialize)]
struct Rect {
    name: String,
    x: f64,
    y: f64,
    w: f64,
    h: f64,
}

/// What the page's script reads.
#[derive(Debug, Clone, Serialize)]
struct Data<'a> {
    title: &'a str,
    blocks: Vec<Rect>,
    time_s: &'a [f64],
    u_m: &'a [Vec<f64>],
    theta_rad: &'a [Vec<f64>],
    w_m: &'a [Vec<f64>],
    ground: &'a [(f64, f64)],
    events: Vec<(f64, &'a str, String)>,
    fell_s: Vec<Option<f64>>,
}

/// The page for `wall`'s run: its history, the ground acceleration (t, m/s2) and its events.
pub fn html(
    wall: &Wall,
    title: &str,
    history: &SavedHistory,
    ground: &[(f64, f64)],
    events: &[SavedEvent],
) -> String {
    let blocks = wall
        .blocks
        .iter()
        .map(|b| Rect {
            name: b.name.clone(),
            x: b.x.to_f64(),
            y: b.y.to_f64(),
            w: b.width.to_f64(),
            h: b.height.to_f64(),
        })
        .collect::<Vec<_>>();
    let fell_s = blocks
        .iter()
        .map(|b| {
            events
                .iter()
                .find(|e| e.kind == "collapse" && e.blocks.contains(&b.name))
                .map(|e| e.time_s)
        })
        .collect();
    // Each event as (t, kind, what it concerns: its joint, else its blocks).
    let events = events
        .iter()
        .map(|e| {
            let what = e.joint.clone().unwrap_or_else(|| e.blocks.join(", "));
            (e.time_s, e.kind.as_str(), what)
        })
        .collect();
    let data = Data {
        title,
        blocks,
        time_s: &history.time_s,
        u_m: &history.displacement_m,
        theta_rad: &history.rotation_rad,
        w_m: &history.lift_m,
        ground,
        events,
        fell_s,
    };
    // Inside a script element only "</" could end it early: JSON allows "<\/" for it.
    let json = serde_json::to_string(&data)
        .expect("numbers and names serialise")
        .replace("</", "<\\/");
    PAGE.replace("{{TITLE}}", &escape(title))
        .replace("{{DATA}}", &json)
}

/// Text for HTML.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

const PAGE: &str = include_str!("animation.html");
