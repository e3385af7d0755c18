//! Inverse kinematics in closed form: actuator displacements and leg vectors for a
//! given orientation.
//!
//! With d_i = P + R b_i - h_i, the leg constraint |d_i - l_i u_i| = a gives
//! l_i = d_i.u_i - sqrt((d_i.u_i)^2 - |d_i|^2 + a^2) (the minus root is this robot's
//! assembly; a negative discriminant means the leg cannot reach).

use super::error::KinematicsError;
use super::params::Geometry;
use super::rotation::rotation;
use nalgebra::{Matrix3, Vector3};

/// The mechanism assembled at one orientation.
#[derive(Debug, Clone, PartialEq)]
pub struct Assembly {
    /// Euler angles (thx, thy, thz), rad.
    pub euler: Vector3<f64>,
    /// Rotation of {B} in {A}.
    pub rotation: Matrix3<f64>,
    /// Actuator displacements l_i, m.
    pub l: Vector3<f64>,
    /// Platform joints relative to P in {A}: r_i = R b_i, m.
    pub r: [Vector3<f64>; 3],
    /// Unit leg directions from the slider joint M_i to the platform joint P + r_i.
    pub n: [Vector3<f64>; 3],
}

impl Assembly {
    /// Checks that every actuator lies within the stroke of `geometry`.
    pub fn check_stroke(&self, geometry: &Geometry) -> Result<(), KinematicsError> {
        let (min, max) = (geometry.params.stroke_min, geometry.params.stroke_max);
        match self.l.iter().position(|l| !(min..=max).contains(l)) {
            Some(i) => Err(KinematicsError::OutsideStroke {
                leg: i + 1,
                l: self.l[i],
                min,
                max,
            }),
            None => Ok(()),
        }
    }
}

/// Assembles the mechanism at orientation `euler` without checking the stroke (for
/// models with end stops, which may run past it).
pub fn assemble(geometry: &Geometry, euler: &Vector3<f64>) -> Result<Assembly, KinematicsError> {
    if euler.iter().any(|v| !v.is_finite()) {
        return Err(KinematicsError::NotFinite("orientation"));
    }
    let rotation = rotation(euler);
    let a = geometry.params.a;
    let mut l = Vector3::zeros();
    let mut r = [Vector3::zeros(); 3];
    let mut n = [Vector3::zeros(); 3];
    for i in 0..3 {
        r[i] = rotation * geometry.b[i];
        let d = geometry.p + r[i] - geometry.h[i];
        let along = d.dot(&geometry.u[i]);
        let discriminant = along * along - d.norm_squared() + a * a;
        if discriminant < 0.0 {
            return Err(KinematicsError::CannotAssemble { leg: i + 1 });
        }
        l[i] = along - discriminant.sqrt();
        n[i] = (d - l[i] * geometry.u[i]) / a;
    }
    Ok(Assembly {
        euler: *euler,
        rotation,
        l,
        r,
        n,
    })
}

/// Inverse kinematics: the assembly at `euler`, or an error when a leg cannot reach or
/// an actuator leaves its stroke.
pub fn inverse_kinematics(
    geometry: &Geometry,
    euler: &Vector3<f64>,
) -> Result<Assembly, KinematicsError> {
    let assembly = assemble(geometry, euler)?;
    assembly.check_stroke(geometry)?;
    Ok(assembly)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn start_pose_of_the_spec_has_all_actuators_at_2_mm() {
        // docs/3pss-model.md: at l = (2, 2, 2) mm the platform is at thx = thy = 0,
        // thz = 122.07 deg (rounded to 0.01 deg, i.e. l within about 0.1 mm).
        let g = Geometry::default();
        let asm = inverse_kinematics(&g, &Vector3::new(0.0, 0.0, 122.07f64.to_radians())).unwrap();
        for l in asm.l.iter() {
            assert!((l - 0.002).abs() < 1e-4, "l = {l}");
        }
        assert!((asm.l[0] - asm.l[1]).abs() < 1e-15 && (asm.l[0] - asm.l[2]).abs() < 1e-15);
    }

    #[test]
    fn legs_have_length_a_and_unit_directions() {
        let g = Geometry::default();
        let asm = assemble(&g, &Vector3::new(0.05, -0.08, 2.3)).unwrap();
        for i in 0..3 {
            let leg = g.p + asm.r[i] - g.slider_joint(i, asm.l[i]);
            assert!((leg.norm() - g.params.a).abs() < 1e-14);
            assert!((leg / g.params.a - asm.n[i]).norm() < 1e-14);
        }
    }

    #[test]
    fn unreachable_and_out_of_stroke_poses_are_errors() {
        let g = Geometry::default();
        // Tilting the platform by 60 deg pulls the legs apart beyond their length.
        let tilted = Vector3::new(1.05, 0.0, 2.3);
        assert!(matches!(
            assemble(&g, &tilted),
            Err(KinematicsError::CannotAssemble { .. })
        ));
        // thz = 100 deg needs actuators below the 2 mm stop (the start pose is 122 deg).
        let low = Vector3::new(0.0, 0.0, 100f64.to_radians());
        assert!(assemble(&g, &low).is_ok());
        assert!(matches!(
            inverse_kinematics(&g, &low),
            Err(KinematicsError::OutsideStroke { leg: 1, .. })
        ));
        let nan = Vector3::new(f64::NAN, 0.0, 0.0);
        assert_eq!(
            assemble(&g, &nan),
            Err(KinematicsError::NotFinite("orientation"))
        );
    }
}
