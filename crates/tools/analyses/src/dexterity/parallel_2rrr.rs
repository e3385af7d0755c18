//! The 2-RRR parallel manipulator. Leg 1 is a two-link chain O1 -> A1 -> B1 with both
//! joints actuated (base `theta1`, elbow `theta2`), so B1 follows from leg 1 alone;
//! leg 2 is O2 -> A2 -> B2 with actuated base joint `theta3` and a passive distal link,
//! which fixes the orientation `phi` through the closure `|B2 - A2| = l2`.
//!
//! Jacobian, derived from that closure: with `n2` the unit vector from A2 to B2 and
//! `k = n2 . E R s'2 - n2 . E R s'1`, differentiating `n2 . (B2 - A2) = l2` gives
//! `k phidot = -n2 . v_B1 + l1 (n2 . E e(theta3)) theta3dot`, while
//! `v_P = [l1 E e1 + l2 E e12, l2 E e12] (theta1dot, theta2dot)` for the point P = B1
//! and `v = v_B1 - phidot E R s'1` for the frame origin.

use super::dyad;
use super::layout::{BaseDirection, Origin, Reading, perp, rotation, triangle, two_point_matrix};
use super::manipulator::check_request;
use super::{DexterityError, Joints, Manipulator, Pose};
use nalgebra::{Matrix3, Matrix4x3, Vector2};

/// Geometry of the 2-RRR manipulator (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parallel2Rrr {
    /// Base joints O1, O2 in the base frame.
    pub base: [Vector2<f64>; 2],
    /// Platform vertices B1, B2, B3 in the moving frame.
    pub platform: [Vector2<f64>; 3],
    /// Proximal link length `l1` (O_i to A_i) of both legs.
    pub proximal: f64,
    /// Distal link length `l2` (A_i to B_i) of both legs.
    pub distal: f64,
}

impl Default for Parallel2Rrr {
    /// The paper's manipulator in the straightforward reading.
    fn default() -> Self {
        Self::paper(Reading::default())
    }
}

impl Parallel2Rrr {
    /// The paper's dimensions (`|O1O2| = 30 cm`, platform side 15 cm, links 15 cm) in
    /// the given reading of its layout.
    pub fn paper(reading: Reading) -> Self {
        let sign = match reading.base_direction {
            BaseDirection::PlusX => 1.0,
            BaseDirection::MinusX => -1.0,
        };
        let o2 = Vector2::new(sign * 0.30, 0.0);
        // The centroid reading puts the origin at the midpoint of O1O2.
        let shift = match reading.base_origin {
            Origin::FirstVertex => Vector2::zeros(),
            Origin::Centroid => o2 / 2.0,
        };
        Self {
            base: [-shift, o2 - shift],
            platform: triangle(0.15, reading.platform_apex, reading.frame),
            proximal: 0.15,
            distal: 0.15,
        }
    }

    /// Position of platform vertex `i` at `pose`.
    pub fn vertex(&self, pose: Pose, i: usize) -> Vector2<f64> {
        Vector2::new(pose.x, pose.y) + rotation(pose.phi) * self.platform[i]
    }

    /// Jacobian of the velocities of B1 and B3, `J'' = R2 J` (4x3).
    pub fn homogeneous_jacobian(
        &self,
        pose: Pose,
        mode: usize,
    ) -> Result<Matrix4x3<f64>, DexterityError> {
        let r2 = two_point_matrix(pose.phi, self.platform[0], self.platform[2]);
        Ok(r2 * self.jacobian(pose, mode)?)
    }

    /// The two dyads of a working mode: leg 1 (bit 0) and leg 2 (bit 1).
    fn legs(&self, pose: Pose, mode: usize) -> Result<[dyad::Dyad; 2], DexterityError> {
        check_request(pose, mode, 4)?;
        let solve = |leg: usize| {
            let r = self.vertex(pose, leg) - self.base[leg];
            dyad::solve(r, self.proximal, self.distal, dyad::branch(mode, leg))
                .ok_or(DexterityError::Unreachable)
        };
        Ok([solve(0)?, solve(1)?])
    }
}

impl Manipulator for Parallel2Rrr {
    /// Four modes: bit 0 is the branch of leg 1, bit 1 that of leg 2.
    fn working_modes(&self) -> usize {
        4
    }

    fn inverse_kinematics(&self, pose: Pose, mode: usize) -> Result<Joints, DexterityError> {
        let [leg1, leg2] = self.legs(pose, mode)?;
        // Elbow angle: from the proximal to the distal direction of leg 1.
        let (p, d) = (leg1.proximal, leg1.distal);
        let elbow = p.perp(&d).atan2(p.dot(&d));
        Ok(Joints::new(leg1.angle(), elbow, leg2.angle()))
    }

    fn jacobian(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError> {
        let [leg1, leg2] = self.legs(pose, mode)?;
        let (l1, l2) = (self.proximal, self.distal);
        // Velocity of B1 per unit theta1dot and per unit theta2dot.
        let b1_per_theta2 = l2 * perp(leg1.distal);
        let b1_per_theta1 = l1 * perp(leg1.proximal) + b1_per_theta2;
        let rot = rotation(pose.phi);
        let (arm1, arm2) = (perp(rot * self.platform[0]), perp(rot * self.platform[1]));
        let n2 = leg2.distal;
        let k = n2.dot(&arm2) - n2.dot(&arm1);
        if k.abs() < 1e-12 * self.distal {
            return Err(DexterityError::Singular);
        }
        let phi_row = [
            -n2.dot(&b1_per_theta1) / k,
            -n2.dot(&b1_per_theta2) / k,
            l1 * n2.dot(&perp(leg2.proximal)) / k,
        ];
        let mut j = Matrix3::zeros();
        for c in 0..3 {
            let b1 = match c {
                0 => b1_per_theta1,
                1 => b1_per_theta2,
                _ => Vector2::zeros(),
            };
            let origin = b1 - phi_row[c] * arm1;
            j[(0, c)] = origin.x;
            j[(1, c)] = origin.y;
            j[(2, c)] = phi_row[c];
        }
        Ok(j)
    }

    fn homogeneous_gram(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError> {
        let j = self.homogeneous_jacobian(pose, mode)?;
        Ok(j.transpose() * j)
    }

    fn reach(&self) -> f64 {
        let frame_offset = self.platform[0].norm();
        self.base[0].norm() + self.proximal + self.distal + frame_offset
    }
}
