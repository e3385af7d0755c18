//! Typed failures of the kinematic computations.

use std::fmt;

/// Why a kinematic quantity could not be computed at a pose.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DexterityError {
    /// No joint solution reaches the pose in the requested working mode.
    Unreachable,
    /// The pose is a singular configuration: the Jacobian does not exist there.
    Singular,
    /// A pose coordinate is NaN or infinite.
    NonFinitePose,
    /// A working-mode index beyond the manipulator's number of modes.
    NoSuchMode { mode: usize, modes: usize },
    /// A geometric parameter is not a positive finite length.
    InvalidGeometry(&'static str),
}

impl fmt::Display for DexterityError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Unreachable => write!(f, "pose is outside the reachable workspace"),
            Self::Singular => write!(f, "pose is a singular configuration"),
            Self::NonFinitePose => write!(f, "pose has a NaN or infinite coordinate"),
            Self::NoSuchMode { mode, modes } => {
                write!(f, "working mode {mode} does not exist (modes 0..{modes})")
            }
            Self::InvalidGeometry(what) => write!(f, "invalid geometry: {what}"),
        }
    }
}

impl std::error::Error for DexterityError {}
