//! Which walls rock and how: the rocking integrator of a wall that is one free-standing block,
//! made of free columns or a trilith ([`Rocking`]), whether a run rocks ([`rocks_in_plane`], [`can_lift`]),
//! and the sections of a wall across its plane run as rocking bodies ([`out_of_plane`]).

use super::column::face_on_face;
use super::{columns, run, Column, Equations, Finished, RockingBody, Scene};
use crate::error::SimulationError;
use crate::integrate::Settings;
use crate::motion::Motion;
use crate::response::{Response, Warning};

/// The rocking model on a wall that is one free-standing block on the ground, made of free
/// columns ([`columns`]: each moves on one of its joints, the others held and watched), or a
/// trilith (its three blocks rocking as a parallelogram, every joint watched). (Blocks that
/// rock inside other walls are not modelled exactly yet; time stepping runs them.)
#[derive(Debug, Clone, Default)]
pub struct Rocking {
    /// The equations between events.
    pub equations: Equations,
    /// Initial rotation of the block, or of the body of a wall of one column (rad; 0: seated
    /// at rest).
    pub initial_rotation_rad: f64,
}

impl crate::integrate::Integrator for Rocking {
    fn method(&self) -> &'static str {
        "event"
    }

    fn run(&self, sc: &crate::integrate::Scenario) -> Result<Response, SimulationError> {
        let response = self.with_scene(sc, super::run)?;
        Ok(self.named(sc, response))
    }
}

impl Rocking {
    /// As [`Rocking::run`] (the `Integrator`'s), but where the exact model stops before the
    /// end (a held joint gives way, a column's body or a trilith's frame would fly), the state
    /// of every block there instead of the end of the run.
    pub(crate) fn run_to_stop(
        &self,
        sc: &crate::integrate::Scenario,
    ) -> Result<Finished, SimulationError> {
        Ok(match self.with_scene(sc, super::run_to_stop)? {
            Finished::Ended(r) => Finished::Ended(Box::new(self.named(sc, *r))),
            stopped => stopped,
        })
    }

    /// `f` on the scene of the wall: its one free-standing block, or its columns.
    fn with_scene<T>(
        &self,
        sc: &crate::integrate::Scenario,
        f: impl FnOnce(&Scene) -> Result<T, SimulationError>,
    ) -> Result<T, SimulationError> {
        let (bodies, watches) = if sc.wall.blocks.len() == 1 {
            (vec![free_standing(sc.wall, sc.topology)?], Vec::new())
        } else {
            let columns = columns(sc.wall, sc.topology)?;
            if self.initial_rotation_rad != 0.0 && columns.len() != 1 {
                return Err(SimulationError::Incompatible {
                    asked: "an initial rotation is given to a wall of one column",
                    fix: "leave --initial-rotation out",
                });
            }
            columns.into_iter().map(|c| (c.body, c.watch)).unzip()
        };
        f(&Scene {
            initial_rotation_rad: &vec![self.initial_rotation_rad; bodies.len()],
            bodies: &bodies,
            watches: &watches,
            wall: (!watches.is_empty()).then_some((sc.wall, sc.topology)),
            equations: self.equations,
            motion: sc.motion,
            settings: sc.settings,
        })
    }

    /// The response of a run of the wall: the wall's name and the model, asked for.
    fn named(&self, sc: &crate::integrate::Scenario, mut response: Response) -> Response {
        response.summary.wall = sc.wall.name.clone();
        response.summary.model = crate::response::ModelUsed {
            name: "slide-rock".into(),
            equations: Some(equations_name(self.equations).into()),
            direction: "in-plane".into(),
            why: "asked for (--model slide-rock)".into(),
        };
        response
    }
}

/// `"exact"` or `"linearised"`.
pub fn equations_name(e: Equations) -> &'static str {
    match e {
        Equations::Exact => "exact",
        Equations::Linearised => "linearised",
    }
}

/// The rocking body of a wall that is one movable block standing on the ground, with nothing
/// beside it or on it; an error says why another wall is not one.
pub fn free_standing(
    wall: &crate::wall::Wall,
    topo: &crate::topology::Topology,
) -> Result<RockingBody, SimulationError> {
    let [block] = wall.blocks.as_slice() else {
        return Err(SimulationError::NotApplicable(format!(
            "the exact rocking model runs walls of one free-standing block (this one has {} \
             blocks); blocks that rock inside walls run on time stepping (--method moreau --dt \
             S), or run the wall sliding exactly (--model slide), or across its plane \
             (--direction out-of-plane)",
            wall.blocks.len()
        )));
    };
    if block.fixed || !block.y.is_zero() {
        return Err(SimulationError::NotApplicable(format!(
            "{}: the rocking model needs a movable block standing on the ground",
            block.name
        )));
    }
    let density = block
        .density_kg_m3
        .as_ref()
        .unwrap_or(&wall.density_kg_m3)
        .to_f64();
    let (w, h) = (block.width.to_f64(), block.height.to_f64());
    let mass = density * w * h * wall.thickness_m.to_f64();
    let friction = topo.horizontal[0].friction.to_f64();
    let mut body = RockingBody::rectangle(&block.name, w, h, mass, friction, wall.g_m_s2.to_f64());
    body.restitution_factor = wall.rocking_restitution_factor;
    Ok(body)
}

/// Whether a seated body can lift at all under a motion, and why: it lifts only if friction can
/// carry the moment (mu >= b / h_c: a base that slips first never lifts, the friction moment
/// mu m g h_c staying below m g b) and the ground acceleration reaches g lambda b / h_c.
pub fn can_lift(body: &RockingBody, motion: &Motion, duration_s: f64) -> (bool, String) {
    let ratio = body.uplift_ratio();
    if body.friction < ratio {
        return (
            false,
            format!(
                "{} cannot lift: its friction {} is below b/h = {ratio:.4}, so its base slips \
                 before the resultant reaches a corner (Shenton 1996)",
                body.name, body.friction
            ),
        );
    }
    let (lo, hi) = motion.accel_range(0.0, duration_s);
    let peak = lo.abs().max(hi.abs());
    let lambda_min = vertical_minimum(motion, duration_s);
    let limit = ratio * body.g_m_s2 * lambda_min;
    if peak < limit {
        return (
            false,
            format!(
                "{} cannot lift: the peak ground acceleration {peak:.4} m/s2 stays below g b/h = \
                 {limit:.4} m/s2 (Housner 1963)",
                body.name
            ),
        );
    }
    (
        true,
        format!(
            "{} can lift: the peak ground acceleration {peak:.4} m/s2 reaches g b/h = {limit:.4} \
             m/s2 and its friction {} is at least b/h = {ratio:.4}",
            body.name, body.friction
        ),
    )
}

/// The smallest vertical load factor 1 + a_v/g over the run (1 without a vertical component).
fn vertical_minimum(motion: &Motion, duration_s: f64) -> f64 {
    match motion {
        Motion::Record(r) => r.lambda().map_or(1.0, |l| {
            let n = ((duration_s / r.dt_s()).ceil() as usize + 1).min(l.len());
            l[..n].iter().copied().fold(1.0, f64::min)
        }),
        _ => 1.0,
    }
}

/// A wall run across its plane: the part above every bed joint that runs through it (the ground
/// included) rocks as one body on the joint's edges, each on a base that moves with the ground
/// (the wall below it taken as rigid), side by side under the same motion. `initial` gives
/// sections a starting rotation by name. The summary names the section nearest to overturning
/// (`worst`; none when no section lifts).
pub fn out_of_plane(
    wall: &crate::wall::Wall,
    topo: &crate::topology::Topology,
    motion: &Motion,
    settings: &Settings,
    equations: Equations,
    initial: &[(String, f64)],
) -> Result<Response, SimulationError> {
    let (sections, skipped) = crate::topology::sections::sections(wall, topo);
    if sections.is_empty() {
        return Err(SimulationError::NotApplicable(format!(
            "{}: no bed joint runs through the wall without an abutment above it, so no part \
             of it can rock across its plane",
            wall.name
        )));
    }
    let bodies: Vec<RockingBody> = sections
        .iter()
        .map(|s| RockingBody::section(s, wall.rocking_restitution_factor))
        .collect();
    let mut rotations = vec![0.0; bodies.len()];
    for (name, theta) in initial {
        let Some(i) = bodies.iter().position(|b| &b.name == name) else {
            let known: Vec<&str> = bodies.iter().map(|b| b.name.as_str()).collect();
            return Err(SimulationError::UnknownName {
                option: "--initial-rotation",
                name: name.clone(),
                known: format!(
                    "no section of that name across the plane (sections: {})",
                    known.join(", ")
                ),
            });
        };
        rotations[i] = *theta;
    }
    let mut response = run(&Scene {
        bodies: &bodies,
        watches: &[],
        wall: None,
        initial_rotation_rad: &rotations,
        equations,
        motion,
        settings,
    })?;
    let s = &mut response.summary;
    s.wall = wall.name.clone();
    s.model = crate::response::ModelUsed {
        name: "slide-rock".into(),
        equations: Some(equations_name(equations).into()),
        direction: "out-of-plane".into(),
        why: format!(
            "across the wall's plane the part above each of {} bed joints rocks as one body of \
             the wall's thickness ({} m) on a base moving with the ground",
            bodies.len(),
            wall.thickness_m.to_f64()
        ),
    };
    for k in skipped {
        s.warnings.push(Warning::LevelSkipped {
            level_m: k.level_m,
            why: k.why,
        });
    }
    let first_fall = s.collapse.as_ref().map(|c| c.block.clone());
    s.worst = s
        .blocks
        .iter()
        .zip(&bodies)
        .filter(|(b, _)| b.uplift_time_s.is_some())
        .map(|(b, body)| crate::response::Worst {
            block: b.name.clone(),
            rotation_over_alpha: b.max_abs_rotation_rad / body.slenderness_rad(),
            overturned: b.fell,
        })
        .max_by(|a, b| {
            let first = |w: &crate::response::Worst| Some(&w.block) == first_fall.as_ref();
            first(a)
                .cmp(&first(b))
                .then(a.rotation_over_alpha.total_cmp(&b.rotation_over_alpha))
        });
    Ok(response)
}

/// The model a run asks for (`model:` of a sweep file: `Slide`, `SlideRock`, `Auto`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize, serde::Deserialize)]
#[cfg_attr(feature = "cli", derive(clap::ValueEnum))]
pub enum ModelChoice {
    /// Blocks slide only (one degree of freedom each).
    Slide,
    /// Blocks may also lift, rock and overturn.
    SlideRock,
    /// Sliding while no block can lift, rocking from the first uplift.
    #[default]
    Auto,
}

/// Whether a run of `wall` in its own plane rocks, and why. The rocking model runs walls of one
/// free-standing block and walls made of free columns or a trilith ([`columns`]); `auto` gives it to them
/// when a block (a column's moving part) can lift at all ([`can_lift`]) or starts from a
/// rotation. Other walls of several blocks slide (rocking inside them is modelled on time
/// stepping only: their warnings name the blocks that could rock).
pub fn rocks_in_plane(
    choice: ModelChoice,
    wall: &crate::wall::Wall,
    topo: &crate::topology::Topology,
    motion: &Motion,
    duration_s: f64,
    initial: &[(String, f64)],
) -> Result<(bool, String), SimulationError> {
    for (name, _) in initial {
        if wall.block_index(name).is_none() {
            return Err(SimulationError::UnknownName {
                option: "--initial-rotation",
                name: name.clone(),
                known: "the wall has no block of that name".into(),
            });
        }
    }
    match choice {
        ModelChoice::Slide if !initial.is_empty() => Err(SimulationError::Incompatible {
            asked: "--initial-rotation needs a model that rotates blocks",
            fix: "--model slide-rock or auto",
        }),
        ModelChoice::Slide => Ok((false, "asked for (--model slide)".into())),
        ModelChoice::SlideRock | ModelChoice::Auto
            if wall.blocks.len() > 1 && !initial.is_empty() =>
        {
            let columns = columns(wall, topo)?;
            let body = released_body(&columns, initial)?;
            let asked = match choice {
                ModelChoice::Auto => "auto",
                _ => "asked for (--model slide-rock)",
            };
            Ok((
                true,
                format!(
                    "{asked}: {body} starts from a rotation; {}",
                    moving_parts(wall, topo, &columns)
                ),
            ))
        }
        ModelChoice::SlideRock if wall.blocks.len() > 1 => {
            let columns = columns(wall, topo)?;
            Ok((
                true,
                format!(
                    "asked for (--model slide-rock): {}",
                    moving_parts(wall, topo, &columns)
                ),
            ))
        }
        ModelChoice::SlideRock => {
            free_standing(wall, topo)?;
            Ok((true, "asked for (--model slide-rock)".into()))
        }
        ModelChoice::Auto if wall.blocks.len() > 1 => {
            if let (Some((a, b)), Ok(_)) = (face_on_face(wall, topo), columns(wall, topo)) {
                // Seated face on face the exact model follows them where asked; by default,
                // until it follows what their rocking meets (docs/rocking-walls.md), they slide.
                return Ok((
                    false,
                    format!(
                        "auto: {a} and {b} touch face on face, which the exact model follows \
                         where asked (--model slide-rock); by default such walls slide, and the \
                         warnings name the blocks that could rock"
                    ),
                ));
            }
            let columns = match columns(wall, topo) {
                Ok(columns) => columns,
                // A trilith the exact frame cannot take says why it slides.
                Err(e) if super::frame::trilith(wall, topo).is_err() => {
                    return Ok((false, format!("auto: {e}")));
                }
                Err(_) => {
                    return Ok((
                        false,
                        format!(
                            "auto: inside walls the exact model rocks blocks that stand in free \
                             columns, and this wall of {} blocks is not made of them, so it \
                             slides; the warnings name the blocks that could rock",
                            wall.blocks.len()
                        ),
                    ))
                }
            };
            let checks: Vec<(bool, String)> = columns
                .iter()
                .map(|c| can_lift(&c.body, motion, duration_s))
                .collect();
            let lifts = checks.iter().any(|c| c.0);
            let why: Vec<&str> = checks.iter().map(|c| c.1.as_str()).collect();
            Ok((
                lifts,
                if lifts {
                    format!(
                        "auto: {}; {}",
                        why.join("; "),
                        moving_parts(wall, topo, &columns)
                    )
                } else {
                    format!("auto: {}", why.join("; "))
                },
            ))
        }
        ModelChoice::Auto => match free_standing(wall, topo) {
            Err(e) if !initial.is_empty() => Err(e),
            Err(e) => Ok((false, format!("auto: {e}"))),
            Ok(_) if !initial.is_empty() => {
                Ok((true, "auto: the block starts from a rotation".into()))
            }
            Ok(body) => {
                let (lifts, why) = can_lift(&body, motion, duration_s);
                Ok((lifts, format!("auto: {why}")))
            }
        },
    }
}

/// What moves in each column and what is held, for the summary's word on the model.
fn moving_parts(
    wall: &crate::wall::Wall,
    topo: &crate::topology::Topology,
    columns: &[Column],
) -> String {
    let watches = columns.iter().map(|c| &c.watch);
    let apart = if super::clearance::Clearance::of(wall, topo, watches).is_empty() {
        ""
    } else {
        "; blocks of different columns, and fixed blocks, watched while they stand apart, \
         through the impact where a corner of one strikes a face of the other, and while a \
         column rests against or slides along a fixed block or two columns turn together, their \
         pivots stuck or slipping (the exact model stops at any other meeting)"
    };
    let parts = columns
        .iter()
        .map(|c| {
            if c.watch.is_frame() {
                return format!(
                    "{} rocks as a frame on the ground (its columns turn equally, its lintel \
                     translates on their tops), every joint watched",
                    c.body.name
                );
            }
            let held = if c.held.is_empty() {
                String::new()
            } else {
                format!(" ({} held to the ground)", c.held.join(", "))
            };
            format!(
                "{} moves as one body on {}{held}, the column's other joints held and watched",
                c.body.name, c.watch.base
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    format!("{parts}{apart}")
}

/// The body that an initial rotation of a wall of columns releases, or why it cannot: the wall
/// is one column, one block is named, and it moves with the column's body (a held block stays
/// seated by definition).
pub fn released_body(
    columns: &[Column],
    initial: &[(String, f64)],
) -> Result<String, SimulationError> {
    let not = |why: String| {
        SimulationError::NotApplicable(format!("--initial-rotation in a wall of columns: {why}"))
    };
    let [column] = columns else {
        return Err(not(format!(
            "the wall has {} columns; a release is given to a wall of one column",
            columns.len()
        )));
    };
    let [(name, _)] = initial else {
        return Err(not(format!(
            "{} rotations given; the column's body turns as one, so give one",
            initial.len()
        )));
    };
    if !column.moves(name) {
        return Err(not(format!(
            "{name} does not move with the column's body {} (the column moves on the joint \
             that gives way first, and {name} is held below it)",
            column.body.name
        )));
    }
    Ok(column.body.name.clone())
}
