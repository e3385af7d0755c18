//! What every planar 3-DOF manipulator of this module provides.

use super::DexterityError;
use super::indices;
use nalgebra::{Matrix3, Vector3};

/// Pose of the end-effector frame: position (m) and orientation `phi` (rad) to the x axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Pose {
    pub x: f64,
    pub y: f64,
    pub phi: f64,
}

impl Pose {
    pub fn new(x: f64, y: f64, phi: f64) -> Self {
        Self { x, y, phi }
    }

    /// The pose as the vector `q = (x, y, phi)`.
    pub fn to_vector(self) -> Vector3<f64> {
        Vector3::new(self.x, self.y, self.phi)
    }

    pub fn from_vector(q: &Vector3<f64>) -> Self {
        Self::new(q[0], q[1], q[2])
    }
}

/// Joint angles `Theta` (rad) of the three actuated joints.
pub type Joints = Vector3<f64>;

/// A planar manipulator with three actuated joints, analysed at poses `q = (x, y, phi)`.
pub trait Manipulator: Sync {
    /// Number of working modes (branches of the inverse kinematics).
    fn working_modes(&self) -> usize;

    /// Actuated joint angles reaching `pose` in working mode `mode`.
    fn inverse_kinematics(&self, pose: Pose, mode: usize) -> Result<Joints, DexterityError>;

    /// Jacobian `J` of `qdot = J Thetadot` at `pose` in working mode `mode`.
    fn jacobian(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError>;

    /// Gram matrix `Jh^T Jh` of the dimensionally homogeneous Jacobian `Jh` (all entries
    /// lengths): its eigenvalues are the squared singular values of `Jh`.
    fn homogeneous_gram(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError>;

    /// Half-width of a square centred on the origin that holds the reachable positions.
    fn reach(&self) -> f64;

    /// Local condition index `1 / kappa(Jh)` in `[0, 1]`; `0` at a singular pose.
    fn lci(&self, pose: Pose, mode: usize) -> Result<f64, DexterityError> {
        match self.homogeneous_gram(pose, mode) {
            Ok(gram) => Ok(indices::lci_from_gram(&gram)),
            Err(DexterityError::Singular) => Ok(0.0),
            Err(e) => Err(e),
        }
    }

    /// Largest LCI over the working modes that reach `pose`, and that mode; `None` if
    /// no mode reaches it.
    fn best_lci_mode(&self, pose: Pose) -> Option<(f64, usize)> {
        (0..self.working_modes())
            .filter_map(|mode| Some((self.lci(pose, mode).ok()?, mode)))
            .max_by(|a, b| a.0.total_cmp(&b.0))
    }

    /// Largest LCI over the working modes that reach `pose`; `None` if none reaches it.
    fn best_lci(&self, pose: Pose) -> Option<f64> {
        self.best_lci_mode(pose).map(|(lci, _)| lci)
    }

    /// Whether any working mode reaches `pose`.
    fn reaches(&self, pose: Pose) -> bool {
        (0..self.working_modes()).any(|mode| self.inverse_kinematics(pose, mode).is_ok())
    }

    /// Load index `sqrt(min |lambda|)` of `(Jh^T Jh)^-1` (1/m): the smallest force per
    /// unit actuator torque that the end-effector points can resist.
    fn load_index(&self, pose: Pose, mode: usize) -> Result<f64, DexterityError> {
        match self.homogeneous_gram(pose, mode) {
            Ok(gram) => Ok(indices::load_index_from_gram(&gram)),
            Err(DexterityError::Singular) => Ok(0.0),
            Err(e) => Err(e),
        }
    }
}

/// Checks that a working-mode index exists and that the pose is finite.
pub(crate) fn check_request(pose: Pose, mode: usize, modes: usize) -> Result<(), DexterityError> {
    if mode >= modes {
        Err(DexterityError::NoSuchMode { mode, modes })
    } else if !(pose.x.is_finite() && pose.y.is_finite() && pose.phi.is_finite()) {
        Err(DexterityError::NonFinitePose)
    } else {
        Ok(())
    }
}
