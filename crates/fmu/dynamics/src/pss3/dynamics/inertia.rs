//! Inertial parameters of the moving bodies, with the spec's defaults and validation.

use super::error::PlantParamError;
use nalgebra::{Matrix3, SymmetricEigen, Vector3};

/// Mass properties of the platform, the three legs and the three sliders (SI).
/// `Inertia::default()` is the spec's set (docs/3pss-model.md, "Inertia").
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inertia {
    /// Platform mass, kg.
    pub platform_mass: f64,
    /// Platform centre of mass relative to P, in {B}, m.
    pub platform_com: Vector3<f64>,
    /// Platform inertia tensor about P (not about its centre of mass), in {B}, kg m^2.
    pub platform_inertia: Matrix3<f64>,
    /// Mass of each leg, kg.
    pub leg_mass: f64,
    /// Position of the leg's centre of mass along the leg, as a fraction of `a` from
    /// the slider joint (0.5: the middle).
    pub leg_com_fraction: f64,
    /// Inertia of each leg about its centre of mass for rotations perpendicular to the
    /// leg, kg m^2. The spin about the leg axis is a free, decoupled motion of an S-S
    /// leg and carries no inertia in this model (see docs/3pss-dynamics.md).
    pub leg_transverse_inertia: f64,
    /// Mass of each slider (rod and stud), kg.
    pub slider_mass: f64,
}

impl Default for Inertia {
    fn default() -> Self {
        Self {
            platform_mass: 0.80057,
            platform_com: Vector3::new(0.0, 0.0, 0.01955),
            platform_inertia: Matrix3::from_diagonal(&Vector3::new(0.011824, 0.011824, 0.022886)),
            leg_mass: 0.94670,
            leg_com_fraction: 0.5,
            leg_transverse_inertia: 0.036458,
            slider_mass: 0.26272,
        }
    }
}

/// Relative tolerance of the symmetry and triangle-inequality checks of a tensor.
const TENSOR_TOLERANCE: f64 = 1e-9;

impl Inertia {
    /// Checks that every value is finite and physical: non-negative masses and leg
    /// inertia, a leg centre of mass on the leg, and a platform tensor that is
    /// symmetric, positive definite about P and realisable about the centre of mass
    /// (principal moments non-negative and obeying the triangle inequality).
    pub fn validate(&self) -> Result<(), PlantParamError> {
        let scalars = [
            ("platform_mass", self.platform_mass),
            ("leg_mass", self.leg_mass),
            ("leg_com_fraction", self.leg_com_fraction),
            ("leg_transverse_inertia", self.leg_transverse_inertia),
            ("slider_mass", self.slider_mass),
        ];
        if let Some((name, _)) = scalars.iter().find(|(_, v)| !v.is_finite()) {
            return Err(PlantParamError::NotFinite(name));
        }
        if self.platform_com.iter().any(|v| !v.is_finite()) {
            return Err(PlantParamError::NotFinite("platform_com"));
        }
        if self.platform_inertia.iter().any(|v| !v.is_finite()) {
            return Err(PlantParamError::NotFinite("platform_inertia"));
        }
        for (name, v) in scalars {
            if name != "leg_com_fraction" && v < 0.0 {
                return Err(PlantParamError::Negative(name, v));
            }
        }
        if !(0.0..=1.0).contains(&self.leg_com_fraction) {
            return Err(PlantParamError::OutsideUnitInterval(
                "leg_com_fraction",
                self.leg_com_fraction,
            ));
        }
        self.validate_platform_tensor()
    }

    /// Platform inertia about its own centre of mass, in {B} (parallel-axis theorem).
    pub fn platform_inertia_about_com(&self) -> Matrix3<f64> {
        let c = self.platform_com;
        self.platform_inertia
            - self.platform_mass * (Matrix3::identity() * c.norm_squared() - c * c.transpose())
    }

    fn validate_platform_tensor(&self) -> Result<(), PlantParamError> {
        let i = self.platform_inertia;
        let scale = i.amax();
        if (i - i.transpose()).amax() > TENSOR_TOLERANCE * scale {
            return Err(PlantParamError::InertiaNotPhysical(
                "the tensor is not symmetric",
            ));
        }
        if SymmetricEigen::new(i).eigenvalues.min() <= 0.0 {
            return Err(PlantParamError::InertiaNotPhysical(
                "the tensor about P is not positive definite",
            ));
        }
        let mut about_com = SymmetricEigen::new(self.platform_inertia_about_com()).eigenvalues;
        about_com.as_mut_slice().sort_by(f64::total_cmp);
        let slack = TENSOR_TOLERANCE * scale;
        if about_com[0] < -slack {
            return Err(PlantParamError::InertiaNotPhysical(
                "a principal moment about the centre of mass is negative",
            ));
        }
        if about_com[2] > about_com[0] + about_com[1] + slack {
            return Err(PlantParamError::InertiaNotPhysical(
                "the principal moments about the centre of mass violate the triangle inequality",
            ));
        }
        Ok(())
    }
}
