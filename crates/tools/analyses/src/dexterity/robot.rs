//! The three manipulators of the comparison behind one type.

use super::layout::Reading;
use super::parallel_2rrr::Parallel2Rrr;
use super::parallel_3rrr::Parallel3Rrr;
use super::serial_1rrr::Serial1Rrr;
use super::{DexterityError, Joints, Manipulator, Pose};
use nalgebra::Matrix3;
use std::fmt;
use std::str::FromStr;

/// Which manipulator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum RobotKind {
    Serial1Rrr,
    Parallel2Rrr,
    Parallel3Rrr,
}

impl RobotKind {
    pub const ALL: [RobotKind; 3] = [Self::Serial1Rrr, Self::Parallel2Rrr, Self::Parallel3Rrr];

    /// The working mode a machine of this kind is assumed assembled in when none is
    /// named: a parallel manipulator cannot change mode without passing through a
    /// singularity (nor the serial arm change elbow without stretching or folding), so
    /// every figure refers to one fixed mode. The choice, argued in docs/dexterity.md:
    /// the mode with the largest GCI over the paper's orientation range (all modes of a
    /// manipulator reach the same poses): 3-RRR mode 7, 2-RRR mode 3; the 1-RRR's two
    /// elbow modes have equal GCI and equal largest LCI, mode 0 is taken.
    pub fn default_mode(self) -> usize {
        match self {
            Self::Serial1Rrr => 0,
            Self::Parallel2Rrr => 3,
            Self::Parallel3Rrr => 7,
        }
    }

    /// Short name used on the command line and in file names.
    pub fn name(self) -> &'static str {
        match self {
            Self::Serial1Rrr => "1rrr",
            Self::Parallel2Rrr => "2rrr",
            Self::Parallel3Rrr => "3rrr",
        }
    }
}

impl fmt::Display for RobotKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for RobotKind {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Self::ALL
            .into_iter()
            .find(|k| k.name().eq_ignore_ascii_case(s))
            .ok_or_else(|| format!("unknown robot '{s}' (expected 1rrr, 2rrr or 3rrr)"))
    }
}

/// One of the three manipulators with its geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Robot {
    Serial1Rrr(Serial1Rrr),
    Parallel2Rrr(Parallel2Rrr),
    Parallel3Rrr(Parallel3Rrr),
}

impl Robot {
    /// The manipulator of kind `kind` with the paper's dimensions (default reading).
    pub fn paper(kind: RobotKind) -> Self {
        Self::with_reading(kind, Reading::default())
    }

    /// The paper's manipulator of kind `kind` in a reading of the parallel layouts
    /// (the serial arm has a single layout).
    pub fn with_reading(kind: RobotKind, reading: Reading) -> Self {
        match kind {
            RobotKind::Serial1Rrr => Self::Serial1Rrr(Serial1Rrr::default()),
            RobotKind::Parallel2Rrr => Self::Parallel2Rrr(Parallel2Rrr::paper(reading)),
            RobotKind::Parallel3Rrr => Self::Parallel3Rrr(Parallel3Rrr::paper(reading)),
        }
    }

    pub fn kind(&self) -> RobotKind {
        match self {
            Self::Serial1Rrr(_) => RobotKind::Serial1Rrr,
            Self::Parallel2Rrr(_) => RobotKind::Parallel2Rrr,
            Self::Parallel3Rrr(_) => RobotKind::Parallel3Rrr,
        }
    }

    fn inner(&self) -> &dyn Manipulator {
        match self {
            Self::Serial1Rrr(r) => r,
            Self::Parallel2Rrr(r) => r,
            Self::Parallel3Rrr(r) => r,
        }
    }
}

impl Manipulator for Robot {
    fn working_modes(&self) -> usize {
        self.inner().working_modes()
    }

    fn inverse_kinematics(&self, pose: Pose, mode: usize) -> Result<Joints, DexterityError> {
        self.inner().inverse_kinematics(pose, mode)
    }

    fn jacobian(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError> {
        self.inner().jacobian(pose, mode)
    }

    fn homogeneous_gram(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError> {
        self.inner().homogeneous_gram(pose, mode)
    }

    fn best_lci_mode(&self, pose: Pose) -> Option<(f64, usize)> {
        self.inner().best_lci_mode(pose)
    }

    fn reach(&self) -> f64 {
        self.inner().reach()
    }
}
