//! The controller's model of the robot as named parameters: the plant FMU's names,
//! units and meanings, so that a scenario sets the controller's model with the same
//! names as the plant's and a model mismatch is one differing value. One table, read
//! by the ComputedTorque FMU (its parameter variables) and by the Rust reference loop
//! (its scenario reading). End stops and the stroke are not part of the controller's
//! model (they protect the plant; the law does not plan for them).

use super::ControllerError;
use crate::pss3::ParamError;
use crate::pss3::dynamics::{PlantParamError, PlantParams};

/// One scalar model parameter.
#[derive(Clone, Copy)]
pub struct ModelParameter {
    /// Name, as the plant FMU's parameter.
    pub name: &'static str,
    /// The name the robot library's parameter errors use for it.
    pub library_name: &'static str,
    /// SI unit and display unit, as the plant FMU declares them.
    pub unit: Option<&'static str>,
    pub display_unit: Option<&'static str>,
    pub description: &'static str,
    /// The bounds the robot model enforces (FMU `min`/`max`, inclusive; `None`: only
    /// finite). A quantity that must be positive has `min` 0: the model refuses 0
    /// itself when it is built.
    pub min: Option<f64>,
    pub max: Option<f64>,
    /// The spec's value (`PlantParams::default()`, checked by a test), as a constant for
    /// the FMU's static variable table.
    pub spec: f64,
    pub get: fn(&PlantParams) -> f64,
    pub set: fn(&mut PlantParams, f64),
}

/// `parameter!(name, library name, unit, display unit, description, spec value, field
/// path)`.
macro_rules! parameter {
    ($name:literal, $library:literal, $unit:expr, $display:expr, $description:literal,
     $spec:expr, $($field:tt).+) => {
        ModelParameter {
            name: $name,
            library_name: $library,
            unit: $unit,
            display_unit: $display,
            description: $description,
            min: None,
            max: None,
            spec: $spec,
            get: |p| p.$($field).+,
            set: |p, v| p.$($field).+ = v,
        }
    };
}

impl ModelParameter {
    /// These bounds instead of none.
    const fn bounded(mut self, min: Option<f64>, max: Option<f64>) -> Self {
        self.min = min;
        self.max = max;
        self
    }

    /// Bounded below by 0 (a length, mass, inertia or friction coefficient).
    const fn non_negative(self) -> Self {
        self.bounded(Some(0.0), None)
    }
}

/// `inertia!(name, row, column, spec value)`: an entry of the symmetric platform inertia tensor
/// (setting an off-diagonal entry sets both).
macro_rules! inertia {
    ($name:literal, $r:literal, $c:literal, $spec:expr) => {
        ModelParameter {
            name: $name,
            library_name: "platform_inertia",
            unit: Some("kg.m2"),
            display_unit: None,
            description: "Platform inertia tensor about the fixed point P, in the platform \
                          frame {B} (symmetric: sets both entries)",
            min: if $r == $c { Some(0.0) } else { None },
            max: None,
            spec: $spec,
            get: |p| p.inertia.platform_inertia[($r, $c)],
            set: |p, v| {
                p.inertia.platform_inertia[($r, $c)] = v;
                p.inertia.platform_inertia[($c, $r)] = v;
            },
        }
    };
}

const M: Option<&str> = Some("m");
const MM: Option<&str> = Some("mm");
const RAD: Option<&str> = Some("rad");
const DEG: Option<&str> = Some("deg");
const KG: Option<&str> = Some("kg");

/// Every model parameter, in the order of the FMU's variable table.
pub const MODEL_PARAMETERS: [ModelParameter; 24] = [
    parameter!(
        "lp",
        "lp",
        M,
        MM,
        "Height of the fixed point P (the platform's spherical joint) above the base origin C",
        0.632187,
        geometry.lp
    )
    .non_negative(),
    parameter!(
        "ld",
        "ld",
        M,
        MM,
        "Radius of the circle of the platform joints around P",
        0.245396,
        geometry.ld
    )
    .non_negative(),
    parameter!(
        "gamma",
        "gamma",
        RAD,
        DEG,
        "Azimuth of platform joint 1 in the platform frame {B} (joints 2 and 3 at +120 and -120 deg from it)",
        (-150.0f64).to_radians(),
        geometry.gamma
    ),
    parameter!(
        "lb",
        "lb",
        M,
        MM,
        "Distance from the base origin C to each slider joint at actuator displacement l = 0",
        0.344098,
        geometry.lb
    )
    .non_negative(),
    parameter!(
        "alpha",
        "alpha",
        RAD,
        DEG,
        "Azimuth offset of the slider joints: h_i lies at azimuth alpha + (-120, 0, +120) deg about Z of the base frame {A}",
        8.674f64.to_radians(),
        geometry.alpha
    ),
    parameter!(
        "beta",
        "beta",
        RAD,
        DEG,
        "Polar angle of the slider joints h_i from Z of the base frame {A}",
        66.242f64.to_radians(),
        geometry.beta
    ),
    parameter!(
        "a",
        "a",
        M,
        MM,
        "Leg length, slider joint centre to platform joint centre",
        0.619598,
        geometry.a
    )
    .non_negative(),
    parameter!(
        "platformMass",
        "platform_mass",
        KG,
        None,
        "Mass of the platform",
        0.80057,
        inertia.platform_mass
    )
    .non_negative(),
    parameter!(
        "platformCom[1]",
        "platform_com",
        M,
        MM,
        "Platform centre of mass relative to P, in the platform frame {B}, x",
        0.0,
        inertia.platform_com.x
    ),
    parameter!(
        "platformCom[2]",
        "platform_com",
        M,
        MM,
        "Platform centre of mass relative to P, in the platform frame {B}, y",
        0.0,
        inertia.platform_com.y
    ),
    parameter!(
        "platformCom[3]",
        "platform_com",
        M,
        MM,
        "Platform centre of mass relative to P, in the platform frame {B}, z",
        0.01955,
        inertia.platform_com.z
    ),
    inertia!("platformInertia[1,1]", 0, 0, 0.011824),
    inertia!("platformInertia[2,2]", 1, 1, 0.011824),
    inertia!("platformInertia[3,3]", 2, 2, 0.022886),
    inertia!("platformInertia[1,2]", 0, 1, 0.0),
    inertia!("platformInertia[1,3]", 0, 2, 0.0),
    inertia!("platformInertia[2,3]", 1, 2, 0.0),
    parameter!(
        "legMass",
        "leg_mass",
        KG,
        None,
        "Mass of each leg",
        0.9467,
        inertia.leg_mass
    )
    .non_negative(),
    parameter!(
        "legComFraction",
        "leg_com_fraction",
        None,
        None,
        "Leg centre of mass along the leg from the slider joint, as a fraction of a",
        0.5,
        inertia.leg_com_fraction
    )
    .bounded(Some(0.0), Some(1.0)),
    parameter!(
        "legTransverseInertia",
        "leg_transverse_inertia",
        Some("kg.m2"),
        None,
        "Leg inertia about its centre of mass, perpendicular to the leg",
        0.036458,
        inertia.leg_transverse_inertia
    )
    .non_negative(),
    parameter!(
        "sliderMass",
        "slider_mass",
        KG,
        None,
        "Mass of each slider (rod and stud)",
        0.26272,
        inertia.slider_mass
    )
    .non_negative(),
    ModelParameter {
        name: "g",
        library_name: "gravity",
        unit: Some("m/s2"),
        display_unit: None,
        description: "Gravitational acceleration, acting along -Z of the base frame {A}",
        min: None,
        max: None,
        spec: 9.81,
        get: |p| -p.gravity.z,
        set: |p, v| p.gravity = nalgebra::Vector3::new(0.0, 0.0, -v),
    },
    parameter!(
        "sliderFriction",
        "slider_friction",
        Some("N.s/m"),
        None,
        "Viscous friction on each slider, force -c lDot",
        0.0,
        friction.slider
    )
    .non_negative(),
    parameter!(
        "pivotFriction",
        "pivot_friction",
        Some("N.m.s/rad"),
        None,
        "Viscous friction at the spherical joint P, moment -c omega",
        0.0,
        friction.pivot
    )
    .non_negative(),
];

/// The spec value of every entry of [`MODEL_PARAMETERS`], in its order (the start
/// values an FMU declares its model parameters with).
pub const MODEL_PARAMETER_SPECS: [f64; MODEL_PARAMETERS.len()] = {
    let mut specs = [0.0; MODEL_PARAMETERS.len()];
    let mut k = 0;
    while k < specs.len() {
        specs[k] = MODEL_PARAMETERS[k].spec;
        k += 1;
    }
    specs
};

/// The model parameter named `name`, if any.
pub fn model_parameter(name: &str) -> Option<&'static ModelParameter> {
    MODEL_PARAMETERS.iter().find(|p| p.name == name)
}

/// A message about the controller's model (a library error) with the parameters under
/// their FMU names (the library's error messages use the library's field names).
pub fn with_fmu_names(message: &str) -> String {
    let mut message = message.to_string();
    for p in &MODEL_PARAMETERS {
        let fmu_name = p.name.split('[').next().unwrap_or(p.name);
        if p.library_name != fmu_name {
            message = message.replace(p.library_name, fmu_name);
        }
    }
    message
}

/// The geometry parameters, which together decide whether the legs assemble.
pub const GEOMETRY: &str = "the geometry lp, ld, gamma, lb, alpha, beta, a";

/// Why a controller cannot be built, with its parameters under their FMU names (a
/// geometry or inertia-tensor error names every parameter that takes part).
pub fn controller_message(e: &ControllerError) -> String {
    match e {
        ControllerError::Model(PlantParamError::Geometry(
            inner @ ParamError::LegCannotAssemble { .. },
        )) => {
            format!("controller model: {GEOMETRY}: {inner}")
        }
        ControllerError::Model(PlantParamError::InertiaNotPhysical(reason)) => {
            format!("controller model: parameter platformInertia: {reason}")
        }
        other => with_fmu_names(&other.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_parameter_reads_back_what_it_sets() {
        // Truth: a set followed by a get of the same name returns the value, and no
        // other parameter changes (except the symmetric inertia entry, not listed).
        for p in &MODEL_PARAMETERS {
            let mut params = PlantParams::default();
            let before: Vec<f64> = MODEL_PARAMETERS.iter().map(|q| (q.get)(&params)).collect();
            let value = (p.get)(&params) + 0.125;
            (p.set)(&mut params, value);
            assert_eq!((p.get)(&params), value, "{}", p.name);
            for (q, old) in MODEL_PARAMETERS.iter().zip(before) {
                if q.name != p.name {
                    assert_eq!((q.get)(&params), old, "{} changed {}", p.name, q.name);
                }
            }
        }
        let mut params = PlantParams::default();
        (model_parameter("platformInertia[1,3]").unwrap().set)(&mut params, 0.01);
        assert_eq!(params.inertia.platform_inertia[(2, 0)], 0.01);
        assert_eq!((model_parameter("g").unwrap().get)(&params), 9.81);
    }

    #[test]
    fn every_declared_bound_is_one_the_model_enforces() {
        // Truth: the library's own validation (Plant::new). A value just outside a
        // declared bound is refused by the model, the bound itself is accepted unless
        // the quantity must be positive (then the model refuses it, which the FMU
        // description says by min = 0 and the parameter's refusal at build time).
        use crate::pss3::dynamics::Plant;
        let build = |p: &ModelParameter, v: f64| {
            let mut params = PlantParams::default();
            (p.set)(&mut params, v);
            Plant::new(params)
        };
        let mut bounded = 0;
        for p in &MODEL_PARAMETERS {
            if let Some(min) = p.min {
                assert!(build(p, min - 1e-6).is_err(), "{} below {min}", p.name);
                bounded += 1;
            }
            if let Some(max) = p.max {
                assert!(build(p, max + 1e-6).is_err(), "{} above {max}", p.name);
                assert!(build(p, max).is_ok(), "{} at {max}", p.name);
                bounded += 1;
            }
        }
        // lp, ld, lb, a, three masses, legComFraction (both ends), legTransverseInertia,
        // the three diagonal inertias and the two frictions.
        assert_eq!(bounded, 15);
        // Unbounded ones take a value far out (angles, centre of mass, gravity).
        for name in ["gamma", "platformCom[1]", "g"] {
            let p = model_parameter(name).unwrap();
            assert!(build(p, p.spec - 0.01).is_ok(), "{name}");
        }
    }

    #[test]
    fn the_spec_values_are_the_library_defaults() {
        // Truth: PlantParams::default(), the spec's robot (docs/3pss-model.md).
        let spec = PlantParams::default();
        for p in &MODEL_PARAMETERS {
            assert_eq!(p.spec, (p.get)(&spec), "{}", p.name);
        }
    }

    #[test]
    fn messages_use_the_fmu_names() {
        assert_eq!(
            with_fmu_names("parameter leg_mass = -1 must not be negative"),
            "parameter legMass = -1 must not be negative"
        );
        assert_eq!(
            with_fmu_names("parameter gravity is not"),
            "parameter g is not"
        );
    }
}
