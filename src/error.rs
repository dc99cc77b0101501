//! Typed errors. Every error names what to fix: the file, the line or block, the rule broken.
//! The library never prints; the binary turns these into messages.

use std::path::PathBuf;

/// Any error pirqa's library returns.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{}: {source}{}", path.display(), io_advice(source))]
    Io {
        /// The file.
        path: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// A wall description is malformed or describes an impossible wall.
    #[error("{}: {source}", path.display())]
    Wall {
        /// The wall file (or `<string>`).
        path: PathBuf,
        /// What is wrong.
        #[source]
        source: WallError,
    },
    /// A survey (block outlines) cannot be made into a wall.
    #[error("{}: {source}", path.display())]
    Survey {
        /// The survey file.
        path: PathBuf,
        /// What is wrong (boxed: it is the largest error, and `Error` travels in every
        /// `Result`).
        #[source]
        source: Box<SurveyError>,
    },
    /// A quantity with units could not be read (command-line values such as `400gal`).
    #[error(transparent)]
    Unit(#[from] UnitError),
    /// A ground motion built in code is unusable (a sine or pulse of impossible numbers).
    #[error("ground motion: {0}")]
    InvalidMotion(#[from] MotionError),
    /// A wall written in code or text is unusable.
    #[error("wall: {0}")]
    InvalidWall(#[from] WallError),
    /// A ground-motion file or description is unusable.
    #[error("{}: {source}", path.display())]
    Motion {
        /// The record file (or the option that described the motion).
        path: PathBuf,
        /// What is wrong.
        #[source]
        source: MotionError,
    },
    /// A command-line option (or the setting it stands for) is missing, unreadable or out of
    /// range, or does not go with the others.
    #[error("{option}: {rule}")]
    Option {
        /// The option (`--freq`), or what the options describe (`motion`).
        option: String,
        /// What is wrong, and what to give.
        rule: String,
    },
    /// A sweep file is malformed or names something unusable.
    #[error("{}: {source}", path.display())]
    Sweep {
        /// The sweep file (or `<string>`).
        path: PathBuf,
        /// What is wrong (boxed, as a survey's error is: it is larger than most).
        #[source]
        source: Box<SweepError>,
    },
    /// The simulation could not continue.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
    /// The wall where a saved run left it cannot stand as a wall.
    #[error("{}: the wall where this run left it, at t = {time_s} s: {source}", dir.display())]
    Moved {
        /// The run's directory.
        dir: PathBuf,
        /// The instant (s).
        time_s: f64,
        /// What is wrong with the moved wall (boxed, as a sweep's error is).
        #[source]
        source: Box<WallError>,
    },
    /// The simulation could not continue after it had written part of its results as it went
    /// (the history and the event log, under their partial names): they are kept.
    #[error(
        "{source}\n  what the run had met up to then is kept in {}",
        kept_list(kept)
    )]
    Stopped {
        /// Why it stopped.
        source: SimulationError,
        /// The partial files it leaves.
        kept: Vec<PathBuf>,
    },
    /// A table of study results read back (a CSV pirqa wrote) is malformed.
    #[error("{}: line {line}: {message}", path.display())]
    Table {
        /// The file.
        path: PathBuf,
        /// 1-based line.
        line: usize,
        /// What was expected.
        message: String,
    },
}

/// What is wrong with a sweep file.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// Not RON, or not the sweep format (an unknown key, a missing field).
    #[error("line {line}, column {col}: {message}")]
    Syntax {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// What the parser expected.
        message: String,
    },
    /// Written for another version of the format.
    #[error("version {found}: this pirqa reads sweep files of version {supported}")]
    Version {
        /// The file's version.
        found: u32,
        /// The version this pirqa reads.
        supported: u32,
    },
    /// A file the sweep names cannot be read.
    #[error("{what} \"{name}\": cannot read {}: {source} (relative paths start in {})", file.display(), start.display())]
    File {
        /// What the file is (`wall`, `record`).
        what: &'static str,
        /// The path as the sweep file writes it.
        name: String,
        /// Where it was looked for.
        file: PathBuf,
        /// The folder relative paths start in.
        start: PathBuf,
        /// What the operating system said.
        #[source]
        source: std::io::Error,
    },
    /// An acceleration it gives cannot be read.
    #[error(transparent)]
    Unit(#[from] UnitError),
    /// A field's value breaks a rule of the format (an empty list, a frequency of zero).
    #[error("{field}: {rule}")]
    Field {
        /// The field, as the file writes it.
        field: String,
        /// The rule and the value that breaks it.
        rule: String,
    },
}

/// What is wrong with a wall description.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WallError {
    /// RON syntax error or a field serde rejects (unknown field, wrong type).
    #[error("line {line}, column {col}: {message}")]
    Syntax {
        /// 1-based line.
        line: usize,
        /// 1-based column.
        col: usize,
        /// RON's message.
        message: String,
    },
    /// The `version` field names a format this pirqa does not read.
    #[error(
        "version {found} is not supported: this pirqa reads wall files of version {supported}"
    )]
    Version {
        /// Version in the file.
        found: u32,
        /// Version this build reads.
        supported: u32,
    },
    /// A wall-level number is out of range.
    #[error("{field} = {}: {rule}", crate::units::shown(.value))]
    Field {
        /// Field name.
        field: String,
        /// Offending value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// Density and unit weight: exactly one must be given.
    #[error(
        "give the material as either density_kg_m3 or unit_weight_kn_m3 (exactly one of them)"
    )]
    Material,
    /// The wall has no blocks.
    #[error("the wall has no blocks: give `rows` or `rectangles`")]
    Empty,
    /// A block's number is out of range.
    #[error("{}: {field} = {}: {rule}", block_place(.block, .origin), crate::units::shown(.value))]
    BlockField {
        /// Block name, if the file gave one (the default names are given after the checks).
        block: Option<String>,
        /// Where it is in the file.
        origin: String,
        /// Field name.
        field: &'static str,
        /// Offending value.
        value: f64,
        /// The rule it breaks.
        rule: &'static str,
    },
    /// A block's name cannot be told from a joint key.
    #[error("block name \"{name}\" ({origin}): a block name must not be empty, contain '/', or be \"ground\"")]
    BlockName {
        /// The name as written.
        name: String,
        /// Where it is in the file.
        origin: String,
    },
    /// Two blocks share a name.
    #[error("block name {name} is used twice: by {first} and by {second}")]
    DuplicateName {
        /// The name.
        name: String,
        /// Where it is first used.
        first: String,
        /// Where it is used again.
        second: String,
    },
    /// Two blocks overlap.
    #[error("blocks {a} and {b} overlap by {dx_m} m x {dy_m} m: move or resize one of them")]
    Overlap {
        /// First block.
        a: String,
        /// Second block.
        b: String,
        /// Horizontal overlap (m).
        dx_m: f64,
        /// Vertical overlap (m).
        dy_m: f64,
    },
    /// A block rests on nothing.
    #[error(
        "block {block} ({origin}) has no support: nothing ends at its bottom y = {y_m} m under \
         x = {x0_m}..{x1_m} m; lower it onto a block top, or mark it `fixed: true`"
    )]
    Floating {
        /// Block.
        block: String,
        /// Where it is in the file.
        origin: String,
        /// Bottom of the block (m).
        y_m: f64,
        /// Left edge (m).
        x0_m: f64,
        /// Right edge (m).
        x1_m: f64,
    },
    /// A block's centroid is outside the stretch its supports give it: it would topple at rest.
    #[error(
        "block {block} ({origin}) would topple at rest: its centroid x = {centroid_m} m lies \
         outside its support span {lo_m}..{hi_m} m"
    )]
    Topples {
        /// Block.
        block: String,
        /// Where it is in the file.
        origin: String,
        /// Centroid (m).
        centroid_m: f64,
        /// Left end of the support span (m).
        lo_m: f64,
        /// Right end of the support span (m).
        hi_m: f64,
    },
    /// An abutment rests on a block that can move.
    #[error("fixed block {fixed} rests on movable block {movable}: an abutment must stand on the ground or on another fixed block")]
    FixedOnMovable {
        /// The fixed block.
        fixed: String,
        /// The block under it.
        movable: String,
    },
    /// A `joint_friction` key is not of the form `"upper/lower"`.
    #[error("joint_friction key \"{key}\": write it as \"upper/lower\", e.g. \"B3/B1\" or \"B1/ground\"")]
    JointKeyForm {
        /// The key.
        key: String,
    },
    /// A `joint_friction` key names a block that does not exist.
    #[error("joint_friction key \"{key}\": there is no block named {name} (blocks: {known})")]
    JointKeyUnknownBlock {
        /// The key.
        key: String,
        /// The unknown name.
        name: String,
        /// Names that exist.
        known: String,
    },
    /// A `joint_friction` key names two blocks that do not rest on one another.
    #[error("joint_friction key \"{key}\": {upper} does not rest on {lower} ({upper} rests on {actual})")]
    JointKeyNotSupport {
        /// The key.
        key: String,
        /// Upper block of the key.
        upper: String,
        /// Lower block of the key.
        lower: String,
        /// What the upper block does rest on.
        actual: String,
    },
}

/// What is wrong with a survey of block outlines.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurveyError {
    /// A line of the CSV cannot be read.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line.
        line: usize,
        /// What was expected.
        message: String,
    },
    /// Two blocks overlap by more than the snap tolerance.
    #[error("blocks {a} and {b} overlap by {dx_mm:.1} mm x {dy_mm:.1} mm, more than the snap tolerance of {snap_mm} mm: correct one outline (or raise --snap)")]
    Overlap {
        /// One block id.
        a: String,
        /// The other.
        b: String,
        /// Horizontal overlap (mm), as surveyed.
        dx_mm: f64,
        /// Vertical overlap (mm), as surveyed.
        dy_mm: f64,
        /// The tolerance (mm).
        snap_mm: f64,
    },
    /// A block rests on nothing within the tolerance.
    #[error(
        "block {block} has nothing under it within the snap tolerance of {snap_mm} mm: {below}"
    )]
    Floating {
        /// The block id.
        block: String,
        /// What is nearest below it, and how far.
        below: String,
        /// The tolerance (mm).
        snap_mm: f64,
    },
    /// Snapping would chain edges farther apart than the tolerance into one level or face.
    #[error("the {what} of blocks {a} and {b} are {spread_mm:.1} mm apart but are joined through neighbours each within {snap_mm} mm: survey them again or lower --snap")]
    Chain {
        /// "bottoms and tops" or "faces".
        what: &'static str,
        /// One block id.
        a: String,
        /// The other.
        b: String,
        /// How far apart the extreme edges are (mm).
        spread_mm: f64,
        /// The tolerance (mm).
        snap_mm: f64,
    },
    /// Snapping leaves a block with no height or width.
    #[error("block {block}: snapping within {snap_mm} mm leaves it {size_mm:.2} mm {what}: the tolerance is too large for this block")]
    Collapsed {
        /// The block id.
        block: String,
        /// "high" or "wide".
        what: &'static str,
        /// What is left (mm).
        size_mm: f64,
        /// The tolerance (mm).
        snap_mm: f64,
    },
    /// The imported wall fails the wall checks.
    #[error("the imported wall: {0}")]
    Wall(#[from] WallError),
    /// The snap tolerance is negative or not a number.
    #[error("the snap tolerance must be 0 or more, found {snap_m} m")]
    Tolerance {
        /// The tolerance given (m).
        snap_m: f64,
    },
}

/// A quantity with units could not be read (defined beside the units it reads).
pub use crate::units::UnitError;

/// What is wrong with a ground motion.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MotionError {
    /// A value in a record file is not a number.
    #[error("line {line}: {message}")]
    Line {
        /// 1-based line.
        line: usize,
        /// What was expected.
        message: String,
    },
    /// A parameter of a motion (a sine's, a pulse's, a window, a scale, a time step) is out of
    /// its range.
    #[error("{what}: {rule}")]
    Parameter {
        /// The parameter and its value as given.
        what: String,
        /// The range it must lie in.
        rule: String,
    },
    /// Fewer than two samples.
    #[error("found {found} {counted}; a record needs at least two")]
    TooFewSamples {
        /// Samples found.
        found: usize,
        /// What was counted ("data lines", "samples").
        counted: &'static str,
    },
    /// A file cut short before its data.
    #[error(
        "an {format} file has {header} header lines and then data; this one has {lines} lines"
    )]
    Truncated {
        /// The format.
        format: &'static str,
        /// Its header lines.
        header: usize,
        /// Lines found.
        lines: usize,
    },
    /// The file leaves out something a record needs, and no option gave it.
    #[error("{missing}: {fix}")]
    Missing {
        /// What is missing.
        missing: &'static str,
        /// How to give it.
        fix: &'static str,
    },
    /// The component or channel asked for is not in the file.
    #[error("{asked}: {available}")]
    NoComponent {
        /// What was asked for.
        asked: String,
        /// What the file has, and what to do.
        available: String,
    },
    /// The file's own description contradicts itself or an option (a channel that is not an
    /// acceleration, a time column spaced otherwise than the interval given, an option the
    /// format decides itself).
    #[error("{0}")]
    Contradiction(String),
    /// A name that names none of the choices.
    #[error("unknown {what} \"{given}\": use {choices}")]
    Unknown {
        /// What was named (units, format).
        what: &'static str,
        /// The name given.
        given: String,
        /// The names accepted.
        choices: &'static str,
    },
}

/// The simulation stopped with an error (a model-validity limit or an internal inconsistency).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimulationError {
    /// The state at one instant came back, the same, every `period` events: the run would
    /// never leave that instant.
    #[error(
        "at t = {time_s} s: no progress: the blocks' modes and velocities came back to the same \
         values every {period} events, {count} events at this instant (last: {detail}); please \
         report the wall and the motion"
    )]
    NoProgress {
        /// Time (s).
        time_s: f64,
        /// Events handled at that instant.
        count: usize,
        /// Events between two visits of one state.
        period: usize,
        /// The last event, in words.
        detail: String,
    },
    /// Events at one instant reached the backstop without a repeated state.
    #[error(
        "at t = {time_s} s: {count} events at one instant ({detail}), the most allowed: {limit}"
    )]
    TooManyEvents {
        /// Time (s).
        time_s: f64,
        /// Events handled at that instant.
        count: usize,
        /// The last event, in words.
        detail: String,
        /// Which limit, and what to do about it.
        limit: &'static str,
    },
    /// Steps of a rocking run crowded in, each far shorter than the bodies' motion, until the
    /// backstop: events at the scale of round-off that would go on for ever.
    #[error(
        "at t = {time_s} s: {count} steps in a row, each shorter than {step_s:.3e} s (a \
         millionth of the bodies' shortest time scale), the most allowed: events that crowd in \
         this closely (blocks rattling at the scale of round-off) are beyond the rocking model; \
         please report the wall and the motion"
    )]
    EventsCrowd {
        /// Time (s).
        time_s: f64,
        /// Steps in a row that short.
        count: usize,
        /// The longest step that counts (s).
        step_s: f64,
    },
    /// A chain of impacts came back to the same velocities again and again.
    #[error(
        "at t = {time_s} s: the impact chain among {blocks} came back to the same velocities every \
         {period} pairwise collisions ({count} so far) and would never settle"
    )]
    ImpactCycle {
        /// Time (s).
        time_s: f64,
        /// Blocks involved (at most a few named).
        blocks: String,
        /// Collisions resolved.
        count: usize,
        /// Collisions between two visits of one state.
        period: usize,
    },
    /// A chain of impacts reached the backstop on its collisions without a repeated state.
    #[error(
        "at t = {time_s} s: the impact chain among {blocks} had not settled after {count} \
         pairwise collisions, the most allowed for a chain of its size; raise \
         `Params::max_collisions_per_chain` if it needs more"
    )]
    ImpactChain {
        /// Time (s).
        time_s: f64,
        /// Blocks involved (at most a few named).
        blocks: String,
        /// Collisions resolved.
        count: usize,
    },
    /// A setting of the run is out of its range.
    #[error("{what} {}{unit}: {rule}", crate::units::shown(.value))]
    Setting {
        /// The setting (duration, output interval, a method's step or tolerance).
        what: String,
        /// Its value.
        value: f64,
        /// Its unit, with a leading space (or empty).
        unit: &'static str,
        /// The range it must lie in.
        rule: &'static str,
    },
    /// A rocking body's size or property is out of its range.
    #[error("{body}: {what} {}: {rule}", crate::units::shown(.value))]
    Body {
        /// The body.
        body: String,
        /// The property.
        what: &'static str,
        /// Its value.
        value: f64,
        /// The range it must lie in.
        rule: &'static str,
    },
    /// The model asked for does not apply to this wall or motion.
    #[error("{0}")]
    NotApplicable(String),
    /// An option names a block or section the wall does not have.
    #[error("{option} {name}: {known}")]
    UnknownName {
        /// The option.
        option: &'static str,
        /// The name given.
        name: String,
        /// What the wall has.
        known: String,
    },
    /// Two choices that do not go together.
    #[error("{asked}: {fix}")]
    Incompatible {
        /// What was asked for.
        asked: &'static str,
        /// What to do instead.
        fix: &'static str,
    },
    /// The rigid model with Coulomb friction has no motion, or no unique one, here
    /// (Painleve-type paradoxes, a landing no impulse fits).
    #[error("{at}: {why}")]
    RigidModel {
        /// The body, the time and its state.
        at: String,
        /// What fails.
        why: String,
    },
    /// A time-stepping method's step fell below its floor.
    #[error("{method}: the step fell below {min_step_s} s at t = {time_s} s ({detail})")]
    StepTooSmall {
        /// The method.
        method: &'static str,
        /// The floor (s).
        min_step_s: f64,
        /// When (s).
        time_s: f64,
        /// The method's parameters.
        detail: String,
    },
    /// A bug in pirqa stopped the run (caught so that a sweep's other cases still finish).
    #[error("internal error ({0}): a bug in pirqa, please report it with this case")]
    Bug(String),
}

/// Convenience alias.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// "block B7 (row 2, block 3)", or "the block at row 2, block 3" when it has no name yet.
fn block_place(block: &Option<String>, origin: &str) -> String {
    match block {
        Some(name) => format!("block {name} ({origin})"),
        None => format!("the block at {origin}"),
    }
}

/// What to do about a failed read or write, where the system's words alone do not say it.
fn io_advice(e: &std::io::Error) -> &'static str {
    use std::io::ErrorKind;
    match e.kind() {
        ErrorKind::StorageFull | ErrorKind::QuotaExceeded => {
            ": the disk is full; free some space or give another folder (--out), and resume a \
             sweep with --resume: its finished cases are kept"
        }
        ErrorKind::PermissionDenied | ErrorKind::ReadOnlyFilesystem => {
            ": this folder cannot be written; give one you can write (--out)"
        }
        ErrorKind::NotADirectory => ": a file stands where a folder is needed; give another path",
        _ => "",
    }
}

/// A list of names for a message: all of them up to `most`, else the first `most` and how many
/// more (a chain of thousands of blocks is not spelled out).
pub(crate) fn name_list<'a>(names: impl ExactSizeIterator<Item = &'a str>, most: usize) -> String {
    let n = names.len();
    let shown: Vec<&str> = names.take(most).collect();
    if n > most {
        format!("{} and {} more ({n} blocks)", shown.join(", "), n - most)
    } else {
        shown.join(", ")
    }
}

/// Files, by path, joined with "and".
fn kept_list(files: &[PathBuf]) -> String {
    let names: Vec<String> = files.iter().map(|f| f.display().to_string()).collect();
    names.join(" and ")
}

#[cfg(test)]
mod tests {
    use super::{name_list, Error};
    use std::io::ErrorKind;

    #[test]
    fn a_full_disk_and_an_unwritable_folder_say_what_to_do() {
        let say = |kind: ErrorKind| {
            Error::Io {
                path: "out/summary.json".into(),
                source: kind.into(),
            }
            .to_string()
        };
        assert!(say(ErrorKind::StorageFull).contains("the disk is full"));
        assert!(say(ErrorKind::StorageFull).starts_with("out/summary.json: "));
        assert!(say(ErrorKind::PermissionDenied).contains("give one you can write"));
        assert!(!say(ErrorKind::NotFound).contains("; "));
    }

    #[test]
    fn long_name_lists_are_cut_with_a_count() {
        let names = ["B1", "B2", "B3", "B4"];
        assert_eq!(name_list(names.iter().copied(), 4), "B1, B2, B3, B4");
        assert_eq!(
            name_list(names.iter().copied(), 2),
            "B1, B2 and 2 more (4 blocks)"
        );
    }
}
