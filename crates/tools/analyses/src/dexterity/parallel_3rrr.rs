//! The 3-RRR parallel manipulator: three legs O_i -> A_i -> B_i with actuated base
//! joints `theta_i` and passive elbows and platform joints.
//!
//! Leg i, with `r_i = v + R s'_i - O_i`, `u_i = l1 (cos theta_i, sin theta_i)` and the
//! unit distal direction `n_i = (r_i - u_i) / l2`: differentiating `|r_i - u_i| = l2`
//! gives `l2 n_i . (vdot + phidot E R s'_i) + l1 delta_i sqrt(Gamma_i) theta_idot = 0`,
//! i.e. `J_q qdot + l1 J_theta Thetadot = 0` and `J = -l1 J_q^-1 J_theta`.

use super::dyad;
use super::indices;
use super::layout::{Reading, base_triangle, perp, rotation, triangle, two_point_matrix};
use super::manipulator::check_request;
use super::{DexterityError, Joints, Manipulator, Pose};
use nalgebra::{Matrix3, Matrix4x3, Vector2};

/// Geometry of the 3-RRR manipulator (m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parallel3Rrr {
    /// Base joints O1, O2, O3 in the base frame.
    pub base: [Vector2<f64>; 3],
    /// Platform vertices B1, B2, B3 in the moving frame.
    pub platform: [Vector2<f64>; 3],
    /// Proximal link length `l1`.
    pub proximal: f64,
    /// Distal link length `l2`.
    pub distal: f64,
}

impl Default for Parallel3Rrr {
    /// The paper's manipulator in the straightforward reading.
    fn default() -> Self {
        Self::paper(Reading::default())
    }
}

impl Parallel3Rrr {
    /// The paper's dimensions (base side 30 cm, platform side 15 cm, links 15 cm) in the
    /// given reading of its layout.
    pub fn paper(reading: Reading) -> Self {
        Self {
            base: base_triangle(0.30, &reading),
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

    /// `J = -l1 J_q^-1 J_theta` for the dyads `legs` of one working mode.
    fn jacobian_of_legs(
        &self,
        pose: Pose,
        legs: &[dyad::Dyad; 3],
    ) -> Result<Matrix3<f64>, DexterityError> {
        let rot = rotation(pose.phi);
        let mut jq = Matrix3::zeros();
        for (i, leg) in legs.iter().enumerate() {
            let n = leg.distal * self.distal;
            jq[(i, 0)] = n.x;
            jq[(i, 1)] = n.y;
            jq[(i, 2)] = n.dot(&perp(rot * self.platform[i]));
        }
        let scale = jq.abs().max();
        let jq_inv = jq
            .try_inverse()
            .filter(|inv| inv.abs().max() * scale < 1e12)
            .ok_or(DexterityError::Singular)?;
        let jtheta = Matrix3::from_diagonal(&Joints::from_fn(|i, _| legs[i].root));
        Ok(-self.proximal * jq_inv * jtheta)
    }

    /// The three dyads of a working mode (bit i of `mode`: branch of leg i).
    fn legs(&self, pose: Pose, mode: usize) -> Result<[dyad::Dyad; 3], DexterityError> {
        check_request(pose, mode, 8)?;
        let solve = |leg: usize| {
            let r = self.vertex(pose, leg) - self.base[leg];
            dyad::solve(r, self.proximal, self.distal, dyad::branch(mode, leg))
                .ok_or(DexterityError::Unreachable)
        };
        Ok([solve(0)?, solve(1)?, solve(2)?])
    }
}

impl Manipulator for Parallel3Rrr {
    /// Eight modes: bit i is the branch `delta_i` of leg i (`0`: +1, `1`: -1).
    fn working_modes(&self) -> usize {
        8
    }

    fn inverse_kinematics(&self, pose: Pose, mode: usize) -> Result<Joints, DexterityError> {
        let legs = self.legs(pose, mode)?;
        Ok(Joints::from_fn(|i, _| legs[i].angle()))
    }

    fn jacobian(&self, pose: Pose, mode: usize) -> Result<Matrix3<f64>, DexterityError> {
        self.jacobian_of_legs(pose, &self.legs(pose, mode)?)
    }

    /// Solves each leg's two branches once and combines them into the eight modes.
    fn best_lci_mode(&self, pose: Pose) -> Option<(f64, usize)> {
        check_request(pose, 0, 8).ok()?;
        let mut branches = [[None; 2]; 3];
        for (leg, pair) in branches.iter_mut().enumerate() {
            let r = self.vertex(pose, leg) - self.base[leg];
            for (b, slot) in pair.iter_mut().enumerate() {
                *slot = dyad::solve(r, self.proximal, self.distal, dyad::branch(b, 0));
            }
        }
        let r2 = two_point_matrix(pose.phi, self.platform[0], self.platform[2]);
        (0..8)
            .filter_map(|mode| {
                let legs = [0, 1, 2].map(|leg| branches[leg][mode >> leg & 1]);
                let legs = [legs[0]?, legs[1]?, legs[2]?];
                let lci = match self.jacobian_of_legs(pose, &legs) {
                    Ok(j) => {
                        let jh = r2 * j;
                        indices::lci_from_gram(&(jh.transpose() * jh))
                    }
                    Err(_) => 0.0,
                };
                Some((lci, mode))
            })
            .max_by(|a, b| a.0.total_cmp(&b.0))
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
