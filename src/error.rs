//! Typed errors. Every error names what to fix: the file, the line or block, the rule broken.
//! The library never prints; the binary turns these into messages.

use std::path::PathBuf;

/// Any error pirqa's library returns.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be read or written.
    #[error("{}: {source}", path.display())]
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
    /// The simulation could not continue.
    #[error(transparent)]
    Simulation(#[from] SimulationError),
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
    #[error("{field} = {value}: {rule}")]
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
    #[error("{}: {field} = {value}: {rule}", block_place(.block, .origin))]
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
    /// An import option is out of range.
    #[error("{0}")]
    Invalid(String),
}

/// A quantity with units could not be read.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum UnitError {
    /// Not a number followed by a known unit.
    #[error("cannot read {what} \"{text}\": write a number and a unit, one of {units}")]
    Unreadable {
        /// What was expected (acceleration, length...).
        what: &'static str,
        /// The text given.
        text: String,
        /// The units accepted.
        units: &'static str,
    },
}

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
    /// The record or motion as a whole is unusable.
    #[error("{0}")]
    Invalid(String),
}

/// The simulation stopped with an error (a model-validity limit or an internal inconsistency).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimulationError {
    /// The integrator found events piling up at one instant without progress.
    #[error("at t = {time_s} s: {count} events at one instant without progress ({detail})")]
    NoProgress {
        /// Time (s).
        time_s: f64,
        /// Events processed at that instant.
        count: usize,
        /// The last event.
        detail: String,
    },
    /// A chain of impacts did not settle.
    #[error("at t = {time_s} s: the impact chain among {blocks} did not settle after {count} pairwise collisions")]
    ImpactChain {
        /// Time (s).
        time_s: f64,
        /// Blocks involved.
        blocks: String,
        /// Collisions resolved.
        count: usize,
    },
    /// The scenario asks for something the model cannot represent.
    #[error("{0}")]
    Invalid(String),
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
