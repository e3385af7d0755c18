//! Workspace of the 3-PSS robot: a forward-kinematics scan over the stroke box and an
//! inverse-kinematics scan over an orientation grid, with the reachable ranges, the
//! tilt-versus-roll envelope and the Jacobian's determinant and condition number.
//!
//! "Tilt" is the angle between the platform normal R ez and the base Z axis,
//! acos(cos thx cos thy); "roll" is thz.

mod envelope;
mod orientation;
mod stroke_box;
mod summary;

pub use envelope::{EnvelopeBin, tilt_envelope};
pub use orientation::{OrientationGrid, OrientationScan, scan_orientations};
pub use stroke_box::{StrokeScan, scan_stroke_box};
pub use summary::{Range, Summary, summarize};

use super::{Assembly, Geometry, KinematicsError, jacobian};
use nalgebra::Vector3;

/// One reachable pose with its Jacobian measures.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorkspacePoint {
    /// Actuator displacements, m.
    pub l: Vector3<f64>,
    /// Euler angles (thx, thy, thz), rad.
    pub euler: Vector3<f64>,
    /// Angle between the platform normal and the base Z axis, rad.
    pub tilt: f64,
    /// det J, m^3.
    pub det_j: f64,
    /// 2-norm condition number of J.
    pub cond_j: f64,
    /// min_i |n_i.u_i|: zero at a leg singularity.
    pub min_leg_projection: f64,
}

impl WorkspacePoint {
    /// Measures the pose `assembly`; an error when the Jacobian is singular there.
    pub fn measure(geometry: &Geometry, assembly: &Assembly) -> Result<Self, KinematicsError> {
        let j = jacobian(geometry, assembly)?;
        Ok(Self {
            l: assembly.l,
            euler: assembly.euler,
            tilt: tilt(&assembly.euler),
            det_j: j.det(),
            cond_j: j.cond(),
            min_leg_projection: j.leg_projection.abs().min(),
        })
    }
}

/// Tilt of the platform normal R ez from the base Z axis for Euler angles `euler`, rad.
pub fn tilt(euler: &Vector3<f64>) -> f64 {
    // R ez = (cz sy cx + sz sx, sz sy cx - cz sx, cy cx): its horizontal part has length
    // |(sy cx, -sx)| (Rz keeps lengths), its vertical part is cy cx.
    let (sx, cx) = euler.x.sin_cos();
    let (sy, cy) = euler.y.sin_cos();
    (sy * cx).hypot(sx).atan2(cy * cx)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::pss3::rotation::rotation;

    #[test]
    fn tilt_is_the_angle_of_the_platform_normal_from_z() {
        // Truth: acos of the z component of R ez, straight from the rotation matrix.
        for euler in [
            Vector3::new(0.1, -0.2, 2.3),
            Vector3::new(-0.3, 0.05, -1.0),
            Vector3::new(0.0, 0.0, 2.1),
        ] {
            let normal = rotation(&euler) * Vector3::z();
            assert!((tilt(&euler) - normal.z.clamp(-1.0, 1.0).acos()).abs() < 1e-7);
        }
    }
}
