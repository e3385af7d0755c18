//! Options shared by the `dexterity` subcommands.

use clap::{Args, ValueEnum};
use robofmu_analyses::dexterity::layout::{ApexSide, BaseDirection, Origin, Reading};
use robofmu_analyses::dexterity::sweep::Region;
use robofmu_analyses::dexterity::workspace::ModeChoice;
use robofmu_analyses::dexterity::{Manipulator, Robot, RobotKind};

/// Side of a triangle's first edge on which its third vertex lies.
#[derive(Clone, Copy, ValueEnum)]
pub enum Side {
    Left,
    Right,
}

impl From<Side> for ApexSide {
    fn from(side: Side) -> Self {
        match side {
            Side::Left => ApexSide::Left,
            Side::Right => ApexSide::Right,
        }
    }
}

/// Origin of a frame: the first vertex (O1, B1) or the centroid.
#[derive(Clone, Copy, ValueEnum)]
pub enum FrameOrigin {
    First,
    Centroid,
}

impl From<FrameOrigin> for Origin {
    fn from(origin: FrameOrigin) -> Self {
        match origin {
            FrameOrigin::First => Origin::FirstVertex,
            FrameOrigin::Centroid => Origin::Centroid,
        }
    }
}

/// Direction of the base edge O1 -> O2.
#[derive(Clone, Copy, ValueEnum)]
pub enum Direction {
    PlusX,
    MinusX,
}

impl From<Direction> for BaseDirection {
    fn from(d: Direction) -> Self {
        match d {
            Direction::PlusX => BaseDirection::PlusX,
            Direction::MinusX => BaseDirection::MinusX,
        }
    }
}

/// Reading of the paper's layout of the parallel manipulators (defaults: the
/// straightforward reading).
#[derive(Args, Clone, Copy)]
pub struct ReadingArgs {
    /// Base frame origin: at O1 or at the centroid of the base joints.
    #[arg(long, value_enum, default_value = "first")]
    pub base_origin: FrameOrigin,
    /// Direction of O1 -> O2 along the x axis.
    #[arg(long, value_enum, default_value = "plus-x")]
    pub base_direction: Direction,
    /// Side of O1O2 on which O3 lies (3-RRR).
    #[arg(long, value_enum, default_value = "left")]
    pub base_apex: Side,
    /// Side of B1B2 on which B3 lies (platform vertex order).
    #[arg(long, value_enum, default_value = "left")]
    pub platform_apex: Side,
    /// Origin of the moving frame whose position is (x, y): B1 or the platform centroid.
    #[arg(long, value_enum, default_value = "first")]
    pub frame: FrameOrigin,
}

impl ReadingArgs {
    pub fn reading(&self) -> Reading {
        Reading {
            base_origin: self.base_origin.into(),
            base_direction: self.base_direction.into(),
            base_apex: self.base_apex.into(),
            platform_apex: self.platform_apex.into(),
            frame: self.frame.into(),
        }
    }

    /// The three manipulators in this reading.
    pub fn robots(&self) -> Vec<Robot> {
        RobotKind::ALL
            .iter()
            .map(|&k| Robot::with_reading(k, self.reading()))
            .collect()
    }
}

/// Where the largest LCI is sought.
#[derive(Clone, Copy, ValueEnum)]
pub enum Workspace {
    /// The paper's square x, y in [-20, 20] cm.
    Paper,
    /// The manipulator's own reachable workspace.
    Own,
    /// The workspace common to the three manipulators.
    Common,
}

impl From<Workspace> for Region {
    fn from(w: Workspace) -> Self {
        match w {
            Workspace::Paper => Region::Paper,
            Workspace::Own => Region::Own,
            Workspace::Common => Region::Common,
        }
    }
}

/// A `--mode` value: one working mode, the best over the modes at each pose, every mode
/// in turn, or (absent) the manipulator's default mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ModeOption {
    Choice(ModeChoice),
    All,
}

/// Help text of every `--mode` option.
pub const MODE_HELP: &str = "Working mode: a mode index, `best` (largest over the modes \
    at each pose, no real machine) or `all` (one line per mode and one for the best); \
    default: the fixed mode of docs/dexterity.md (1rrr 0, 2rrr 3, 3rrr 7)";

/// Parses `best`, `all` or a working-mode index.
pub fn parse_mode_option(s: &str) -> Result<ModeOption, String> {
    if s.eq_ignore_ascii_case("all") {
        return Ok(ModeOption::All);
    }
    parse_mode(s).map(ModeOption::Choice)
}

/// Parses `best` or a working-mode index.
pub fn parse_mode(s: &str) -> Result<ModeChoice, String> {
    if s.eq_ignore_ascii_case("best") {
        return Ok(ModeChoice::Best);
    }
    s.parse()
        .map(ModeChoice::Only)
        .map_err(|_| format!("'{s}' is neither 'best', 'all' nor a mode index"))
}

/// The mode choice of an optional `--mode` for `kind`: its default mode when absent.
pub fn mode_or_default(mode: Option<ModeChoice>, kind: RobotKind) -> ModeChoice {
    mode.unwrap_or(ModeChoice::Only(kind.default_mode()))
}

/// How a mode choice is named in every printed figure and plot title.
pub fn mode_label(choice: ModeChoice, kind: RobotKind) -> String {
    match choice {
        ModeChoice::Best => "best over modes".into(),
        ModeChoice::Only(mode) if mode == kind.default_mode() => {
            format!("mode {mode} (default)")
        }
        ModeChoice::Only(mode) => format!("mode {mode}"),
    }
}

/// Rejects a working-mode index the manipulator does not have.
pub fn check_mode(robot: &Robot, choice: ModeChoice) -> Result<(), crate::cli::CliError> {
    match choice {
        ModeChoice::Only(mode) if mode >= robot.working_modes() => {
            Err(crate::cli::report::usage(format!(
                "--mode: {} has working modes 0 to {}, not {mode}",
                robot.kind(),
                robot.working_modes() - 1
            )))
        }
        _ => Ok(()),
    }
}

/// Index of `kind` in `RobotKind::ALL` (and in `ReadingArgs::robots`).
pub fn index_of(kind: RobotKind) -> usize {
    RobotKind::ALL.iter().position(|&k| k == kind).unwrap_or(0)
}
