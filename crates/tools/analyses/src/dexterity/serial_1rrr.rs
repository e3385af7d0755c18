//! The serial 1-RRR arm: links `l1`, `l2` and a third member `l3` (one side of the
//! platform triangle) whose tip is the end-effector point O'; base joint at the origin.

use super::manipulator::check_request;
use super::{DexterityError, Joints, Manipulator, Pose};
use nalgebra::{Matrix3, Vector2};

/// Relative rounding tolerated at the workspace boundary.
const ROUNDING: f64 = 1e-12;

/// Geometry of the 1-RRR arm (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Serial1Rrr {
    pub l1: f64,
    pub l2: f64,
    pub l3: f64,
    /// Half the distance `e/2` between the points A and B that homogenise the Jacobian.
    pub half_spacing: f64,
}

impl Default for Serial1Rrr {
    /// The paper's arm: `l1 = l2 = l3 = 15 cm`, `e/2 = 2 cm`.
    fn default() -> Self {
        Self {
            l1: 0.15,
            l2: 0.15,
            l3: 0.15,
            half_spacing: 0.02,
        }
    }
}

impl Serial1Rrr {
    /// Pose of the end effector for joint angles `theta` (forward kinematics).
    pub fn forward_kinematics(&self, theta: &Joints) -> Pose {
        let t12 = theta[0] + theta[1];
        let phi = t12 + theta[2];
        Pose::new(
            self.l1 * theta[0].cos() + self.l2 * t12.cos() + self.l3 * phi.cos(),
            self.l1 * theta[0].sin() + self.l2 * t12.sin() + self.l3 * phi.sin(),
            phi,
        )
    }

    /// Jacobian `qdot = J Thetadot` at joint angles `theta`.
    pub fn jacobian_at(&self, theta: &Joints) -> Matrix3<f64> {
        let t1 = theta[0];
        let t12 = t1 + theta[1];
        let phi = t12 + theta[2];
        let (s1, c1) = t1.sin_cos();
        let (s12, c12) = t12.sin_cos();
        let (sp, cp) = phi.sin_cos();
        let (l1, l2, l3) = (self.l1, self.l2, self.l3);
        Matrix3::new(
            -(l1 * s1 + l2 * s12 + l3 * sp),
            -(l2 * s12 + l3 * sp),
            -l3 * sp,
            l1 * c1 + l2 * c12 + l3 * cp,
            l2 * c12 + l3 * cp,
            l3 * cp,
            1.0,
            1.0,
            1.0,
        )
    }

    /// Homogenising matrix `R1`: `(v_Au, v_Av, v_Bv) = R1 (xdot, ydot, phidot)`.
    pub fn homogenising_matrix(&self, phi: f64) -> Matrix3<f64> {
        let (s, c) = phi.sin_cos();
        let h = self.half_spacing;
        Matrix3::new(s, -c, 0.0, c, s, h, c, s, -h)
    }

    /// Homogeneous Jacobian `J' = R1 J` at `pose` in working mode `mode`.
    pub fn homogeneous_jacobian(
        &self,
        pose: Pose,
        mode: usize,
    ) -> Result<Matrix3<f64>, DexterityError> {
        Ok(self.homogenising_matrix(pose.phi) * self.jacobian(pose, mode)?)
    }
}

impl Manipulator for Serial1Rrr {
    /// Two modes: elbow angle `theta2 = +acos(d)` (mode 0) and `-acos(d)` (mode 1).
    fn working_modes(&self) -> usize {
        2
    }

    fn inverse_kinematics(&self, pose: Pose, mode: usize) -> Result<Joints, DexterityError> {
        check_request(pose, mode, 2)?;
        let (sp, cp) = pose.phi.sin_cos();
        let wrist = Vector2::new(pose.x - self.l3 * cp, pose.y - self.l3 * sp);
        let d =
            (wrist.norm_squared() - self.l1.powi(2) - self.l2.powi(2)) / (2.0 * self.l1 * self.l2);
        // Rounding may put a boundary pose (stretched or folded arm) just past |d| = 1.
        if d.abs() > 1.0 + ROUNDING {
            return Err(DexterityError::Unreachable);
        }
        let d = d.clamp(-1.0, 1.0);
        let sign = if mode == 0 { 1.0 } else { -1.0 };
        let theta2 = sign * d.acos();
        let theta1 = wrist.y.atan2(wrist.x)
            - (self.l2 * theta2.sin()).atan2(self.l1 + self.l2 * theta2.cos());
        Ok(Joints::new(theta1, theta2, pose.phi - theta1 - theta2))
    }

    fn jacobian(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError> {
        Ok(self.jacobian_at(&self.inverse_kinematics(pose, mode)?))
    }

    fn homogeneous_gram(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError> {
        let j = self.homogeneous_jacobian(pose, mode)?;
        Ok(j.transpose() * j)
    }

    fn reach(&self) -> f64 {
        self.l1 + self.l2 + self.l3
    }
}
