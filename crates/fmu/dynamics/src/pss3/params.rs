//! Geometric parameters of the 3-PSS robot and the fixed geometry derived from them.

use super::error::ParamError;
use nalgebra::Vector3;

/// Geometric parameters (SI: m, rad). `Params::default()` is the spec's set,
/// reconstructed from the thesis's CAD appendix and trajectory tables.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Params {
    /// Height of the platform centre P above the base origin C, m.
    pub lp: f64,
    /// Radius of the platform joints around P, m.
    pub ld: f64,
    /// Angle of platform joint 1 in {B}, rad.
    pub gamma: f64,
    /// Distance from C to the slider joints at l = 0, m.
    pub lb: f64,
    /// Azimuth offset of the slider joints, rad.
    pub alpha: f64,
    /// Polar angle of h_i from Z, rad.
    pub beta: f64,
    /// Leg length, joint centre to joint centre, m.
    pub a: f64,
    /// Lower end of the usable actuator travel, m.
    pub stroke_min: f64,
    /// Upper end of the usable actuator travel, m.
    pub stroke_max: f64,
}

impl Default for Params {
    fn default() -> Self {
        Self {
            lp: 0.632187,
            ld: 0.245396,
            gamma: (-150.0f64).to_radians(),
            lb: 0.344098,
            alpha: 8.674f64.to_radians(),
            beta: 66.242f64.to_radians(),
            a: 0.619598,
            stroke_min: 0.002,
            stroke_max: 0.152,
        }
    }
}

/// Azimuths k_i of the slider joints h_i, rad.
const SLIDER_AZIMUTH_DEG: [f64; 3] = [-120.0, 0.0, 120.0];
/// Azimuths m_i of the platform joints b_i in {B}, rad.
const PLATFORM_AZIMUTH_DEG: [f64; 3] = [0.0, 120.0, -120.0];
/// Directions of the actuators in the base plane, deg from +X.
const ACTUATOR_AZIMUTH_DEG: [f64; 3] = [0.0, 120.0, -120.0];

/// The fixed vectors of a validated parameter set: everything kinematics needs.
#[derive(Debug, Clone, PartialEq)]
pub struct Geometry {
    /// The parameters this geometry was built from.
    pub params: Params,
    /// Centre of the spherical joint, P = (0, 0, lp), in {A}.
    pub p: Vector3<f64>,
    /// Slider joint centres at l = 0, in {A}.
    pub h: [Vector3<f64>; 3],
    /// Unit directions of the actuators, in {A}.
    pub u: [Vector3<f64>; 3],
    /// Platform joint centres relative to P, in {B}.
    pub b: [Vector3<f64>; 3],
}

impl Geometry {
    /// Validates `params` and derives the fixed vectors.
    pub fn new(params: Params) -> Result<Self, ParamError> {
        validate(&params)?;
        let Params {
            lp,
            ld,
            gamma,
            lb,
            alpha,
            beta,
            ..
        } = params;
        let h = SLIDER_AZIMUTH_DEG.map(|k| {
            let az = alpha + k.to_radians();
            lb * Vector3::new(beta.sin() * az.cos(), beta.sin() * az.sin(), beta.cos())
        });
        let u = ACTUATOR_AZIMUTH_DEG.map(|d| {
            let az = d.to_radians();
            Vector3::new(az.cos(), az.sin(), 0.0)
        });
        let b = PLATFORM_AZIMUTH_DEG.map(|m| {
            let az = gamma + m.to_radians();
            ld * Vector3::new(az.cos(), az.sin(), 0.0)
        });
        let geometry = Self {
            params,
            p: Vector3::new(0.0, 0.0, lp),
            h,
            u,
            b,
        };
        geometry.check_legs_reach()?;
        Ok(geometry)
    }

    /// Slider joint centre M_i = h_i + l u_i for actuator displacement `l`.
    pub fn slider_joint(&self, leg: usize, l: f64) -> Vector3<f64> {
        self.h[leg] + l * self.u[leg]
    }

    /// Each leg must be able to span from its slider joint (somewhere in the stroke) to
    /// its platform joint (somewhere on the sphere of radius ld about P).
    fn check_legs_reach(&self) -> Result<(), ParamError> {
        let Params {
            ld,
            a,
            stroke_min,
            stroke_max,
            ..
        } = self.params;
        for leg in 0..3 {
            // Distance from P to the stroke segment: closest point by projection.
            let along = (self.p - self.h[leg])
                .dot(&self.u[leg])
                .clamp(stroke_min, stroke_max);
            let nearest = (self.p - self.slider_joint(leg, along)).norm();
            let farthest = [stroke_min, stroke_max]
                .map(|l| (self.p - self.slider_joint(leg, l)).norm())
                .into_iter()
                .fold(0.0, f64::max);
            let (min, max) = ((nearest - ld).max(0.0), farthest + ld);
            if !(min..=max).contains(&a) {
                return Err(ParamError::LegCannotAssemble {
                    leg: leg + 1,
                    a,
                    min,
                    max,
                });
            }
        }
        Ok(())
    }
}

impl Default for Geometry {
    fn default() -> Self {
        Self::new(Params::default()).expect("the default parameter set is valid")
    }
}

fn validate(p: &Params) -> Result<(), ParamError> {
    let all = [
        ("lp", p.lp),
        ("ld", p.ld),
        ("gamma", p.gamma),
        ("lb", p.lb),
        ("alpha", p.alpha),
        ("beta", p.beta),
        ("a", p.a),
        ("stroke_min", p.stroke_min),
        ("stroke_max", p.stroke_max),
    ];
    if let Some((name, _)) = all.iter().find(|(_, v)| !v.is_finite()) {
        return Err(ParamError::NotFinite(name));
    }
    for (name, v) in [("lp", p.lp), ("ld", p.ld), ("lb", p.lb), ("a", p.a)] {
        if v <= 0.0 {
            return Err(ParamError::NotPositive(name, v));
        }
    }
    if p.stroke_min >= p.stroke_max {
        return Err(ParamError::EmptyStroke(p.stroke_min, p.stroke_max));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn default_vectors_match_the_spec_table() {
        // Expected values: docs/3pss-model.md, "Default parameters" (table of h_i, b_i).
        let g = Geometry::default();
        let close = |v: Vector3<f64>, w: [f64; 3]| (v - Vector3::from(w)).amax() < 6e-6;
        assert!(
            close(g.h[0], [-0.11453, -0.29337, 0.13863]),
            "h_1 = {}",
            g.h[0]
        );
        assert!(close(g.b[0], [-0.21252, -0.12270, 0.0]), "b_1 = {}", g.b[0]);
        assert_eq!(g.p, Vector3::new(0.0, 0.0, 0.632187));
        // u_2 = (-cos 60, sin 60, 0) and the 3-fold symmetry of h about Z.
        assert!((g.u[1] - Vector3::new(-0.5, 0.75f64.sqrt(), 0.0)).norm() < 1e-15);
        let rz = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), 120f64.to_radians());
        assert!((rz * g.h[0] - g.h[1]).norm() < 1e-15);
    }

    #[test]
    fn invalid_parameters_are_typed_errors() {
        let with = |f: fn(&mut Params)| {
            let mut p = Params::default();
            f(&mut p);
            Geometry::new(p).unwrap_err()
        };
        assert_eq!(with(|p| p.ld = -0.1), ParamError::NotPositive("ld", -0.1));
        assert_eq!(with(|p| p.alpha = f64::NAN), ParamError::NotFinite("alpha"));
        assert_eq!(
            with(|p| p.stroke_max = 0.001),
            ParamError::EmptyStroke(0.002, 0.001)
        );
        assert!(matches!(
            with(|p| p.a = 0.1),
            ParamError::LegCannotAssemble { leg: 1, .. }
        ));
        assert!(matches!(
            with(|p| p.a = 5.0),
            ParamError::LegCannotAssemble { leg: 1, .. }
        ));
    }
}
