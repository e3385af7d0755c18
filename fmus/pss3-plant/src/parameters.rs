//! The plant's parameters as FMU variables (fixed; their start values are the spec's,
//! `PlantParams::default()`, checked by a test) and the translation of the library's
//! parameter errors into messages that name the FMU parameter.
//!
//! The robot model's parameters (geometry, masses, inertias, gravity, friction) are
//! the entries of the library's `MODEL_PARAMETERS`, which also give the ComputedTorque
//! FMU its model under the same names; the end stops, the integrator settings and the
//! initial state are the plant's own.

use super::{Pss3Plant, START_DISPLACEMENT, START_POSE};
use robofmu_dynamics::computed_torque::{MODEL_PARAMETER_SPECS, MODEL_PARAMETERS};
use robofmu_dynamics::pss3::ParamError;
use robofmu_dynamics::pss3::dynamics::{EndStopMode, PlantParamError};
use robofmu_fmi::prelude::*;

/// Library parameter names and their FMU names (the geometric ones are equal).
const NAMES: [(&str, &str); 14] = [
    ("stroke_min", STROKE_MIN.name),
    ("stroke_max", STROKE_MAX.name),
    ("platform_mass", PLATFORM_MASS.name),
    ("platform_com", PLATFORM_COM.name),
    ("platform_inertia", "platformInertia"),
    ("leg_mass", LEG_MASS.name),
    ("leg_com_fraction", LEG_COM_FRACTION.name),
    ("leg_transverse_inertia", LEG_TRANSVERSE_INERTIA.name),
    ("slider_mass", SLIDER_MASS.name),
    ("slider_friction", SLIDER_FRICTION.name),
    ("pivot_friction", PIVOT_FRICTION.name),
    ("end_stop_stiffness", END_STOP_STIFFNESS.name),
    ("end_stop_damping", END_STOP_DAMPING.name),
    ("gravity", G.name),
];

fn fmu_name(library: &str) -> &str {
    NAMES
        .iter()
        .find(|(l, _)| *l == library)
        .map_or(library, |(_, fmu)| fmu)
}

/// The library's parameter error as a message that names the FMU parameter.
pub fn fmu_message(e: &PlantParamError) -> String {
    use PlantParamError as E;
    match e {
        E::Geometry(ParamError::NotFinite(name)) | E::NotFinite(name) => {
            format!("parameter {} is not a finite number", fmu_name(name))
        }
        E::Geometry(ParamError::NotPositive(name, v)) | E::NotPositive(name, v) => {
            format!("parameter {} = {v} must be positive", fmu_name(name))
        }
        E::Negative(name, v) => format!("parameter {} = {v} must not be negative", fmu_name(name)),
        E::OutsideUnitInterval(name, v) => {
            format!(
                "parameter {} = {v} must lie between 0 and 1",
                fmu_name(name)
            )
        }
        E::Geometry(ParamError::EmptyStroke(min, max)) => format!(
            "parameters strokeMin = {min} and strokeMax = {max}: strokeMin must be below \
         strokeMax"
        ),
        E::Geometry(inner @ ParamError::LegCannotAssemble { .. }) => {
            format!("parameter a (with lp, ld, lb, alpha, beta and the stroke): {inner}")
        }
        E::InertiaNotPhysical(reason) => format!("parameter platformInertia: {reason}"),
    }
}

type Decl = Declaration<Pss3Plant>;

fn get_model<const K: usize>(m: &Pss3Plant, i: usize) -> f64 {
    (MODEL_PARAMETERS[K + i].get)(&m.params)
}

fn set_model<const K: usize>(m: &mut Pss3Plant, i: usize, v: f64) -> Result<(), String> {
    (MODEL_PARAMETERS[K + i].set)(&mut m.params, v);
    Ok(())
}

/// The robot-model parameter `MODEL_PARAMETERS[K]` at `vr` (with `length` 3: the array
/// `name[1..3]` of three consecutive entries, named and described without the index).
const fn model<const K: usize>(vr: u32, length: usize) -> Decl {
    let p = &MODEL_PARAMETERS[K];
    let specs: &'static [f64] = &MODEL_PARAMETER_SPECS;
    let start = specs.split_at(K).1.split_at(length).0;
    let mut d = if length > 1 {
        let name = p.name.split_at(p.name.len() - 3).0; // "name[1]" -> "name"
        let description = p.description.split_at(p.description.len() - 3).0; // ", x"
        Decl::real(name, description, get_model::<K>).array(length)
    } else {
        Decl::real(p.name, p.description, get_model::<K>)
    };
    d = d
        .at(vr)
        .set_real(set_model::<K>)
        .after_set(Pss3Plant::changed)
        .parameter(Variability::Fixed)
        .start_real(start)
        .real_range(p.min, p.max);
    match p.unit {
        Some(unit) => d.unit(unit, p.display_unit),
        None => d,
    }
}

/// A fixed Real parameter of the plant's own at `vr`: the plant is rebuilt from it.
const fn own(d: Decl, vr: u32, start: &'static [f64]) -> Decl {
    let d = d.at(vr).parameter(Variability::Fixed).start_real(start);
    d.after_set(Pss3Plant::changed)
}

/// A part of the initial state, three elements at `vr`.
const fn initial(d: Decl, vr: u32, start: &'static [f64]) -> Decl {
    d.array(3)
        .at(vr)
        .parameter(Variability::Fixed)
        .start_real(start)
}

/// The geometry: lp, ld, gamma, lb, alpha, beta, a.
pub const GEOMETRY: [Decl; 7] = [
    model::<0>(1001, 1),
    model::<1>(1002, 1),
    model::<2>(1003, 1),
    model::<3>(1004, 1),
    model::<4>(1005, 1),
    model::<5>(1006, 1),
    model::<6>(1007, 1),
];
pub const STROKE_MIN: Decl = own(
    Decl::real_in("strokeMin", |m, _| &mut m.params.geometry.stroke_min)
        .describe("Lower end of the actuator stroke (lower end stop)"),
    1008,
    &[0.002],
)
.unit("m", Some("mm"));
pub const STROKE_MAX: Decl = own(
    Decl::real_in("strokeMax", |m, _| &mut m.params.geometry.stroke_max)
        .describe("Upper end of the actuator stroke (upper end stop)"),
    1009,
    &[0.152],
)
.unit("m", Some("mm"));
pub const PLATFORM_MASS: Decl = model::<7>(1010, 1);
pub const LEG_MASS: Decl = model::<17>(1011, 1);
pub const LEG_COM_FRACTION: Decl = model::<18>(1012, 1);
pub const LEG_TRANSVERSE_INERTIA: Decl = model::<19>(1013, 1);
pub const SLIDER_MASS: Decl = model::<20>(1014, 1);
pub const G: Decl = model::<21>(1015, 1);
pub const SLIDER_FRICTION: Decl = model::<22>(1016, 1);
pub const PIVOT_FRICTION: Decl = model::<23>(1017, 1);
pub const END_STOP_STIFFNESS: Decl = own(
    Decl::real_in("endStopStiffness", |m, _| &mut m.params.end_stops.stiffness)
        .describe("Stiffness of the end-stop springs (endStopMode 1: positive)"),
    1018,
    &[1e6],
)
.real_range(Some(0.0), None)
.unit("N/m", None);
pub const END_STOP_DAMPING: Decl = own(
    Decl::real_in("endStopDamping", |m, _| &mut m.params.end_stops.damping)
        .describe("Damping of the end stops (endStopMode 1); the stop pushes, never pulls"),
    1019,
    &[2000.0],
)
.real_range(Some(0.0), None)
.unit("N.s/m", None);
const TOLERANCE: Decl = own(
    Decl::real_in("tolerance", |m, _| &mut m.settings.tolerance).describe(
        "Relative and absolute tolerance of the co-simulation integrator \
     (Dormand-Prince 5(4)), positive",
    ),
    1020,
    &[1e-8],
)
.real_range(Some(0.0), None);
const MAX_STEP: Decl = own(
    Decl::real_in("maxStep", |m, _| &mut m.settings.max_step)
        .describe("Largest internal step of the co-simulation integrator, positive"),
    1021,
    &[1e-3],
)
.real_range(Some(0.0), None)
.unit("s", None);
/// platformInertia[1,1], [2,2], [3,3], [1,2], [1,3], [2,3].
pub const PLATFORM_INERTIA: [Decl; 6] = [
    model::<11>(1022, 1),
    model::<12>(1023, 1),
    model::<13>(1024, 1),
    model::<14>(1025, 1),
    model::<15>(1026, 1),
    model::<16>(1027, 1),
];
pub const PLATFORM_COM: Decl = model::<8>(1028, 3);
pub const THETA0: Decl = initial(
    Decl::real_in("theta0", |m, i| &mut m.initial.theta0[i])
        .describe("Initial Euler angles (thx, thy, thz), used unless initFromActuators"),
    1031,
    &START_POSE,
)
.unit("rad", Some("deg"));
pub const L0: Decl = initial(
    Decl::real_in("l0", |m, i| &mut m.initial.l0[i])
        .describe("Initial actuator displacements, used when initFromActuators"),
    1034,
    &[START_DISPLACEMENT],
)
.unit("m", Some("mm"));
pub const OMEGA0: Decl = initial(
    Decl::real_in("omega0", |m, i| &mut m.initial.omega0[i])
        .describe("Initial angular velocity of the platform in {A}"),
    1037,
    &[0.0],
)
.unit("rad/s", Some("deg/s"));
pub const INIT_FROM_ACTUATORS: Decl =
    Decl::boolean_in("initFromActuators", |m, _| &mut m.initial.from_actuators)
        .describe("Initial pose from l0 by forward kinematics instead of theta0")
        .at(1040)
        .parameter(Variability::Fixed)
        .start_boolean(&[false]);
const END_STOP_MODE: Decl = Decl::integer(
    "endStopMode",
    "End stops: 1 = spring-damper (contacts flagged in atStop), 2 = error (a step \
     that leaves the stroke is discarded)",
    |m, _| mode_code(m.params.end_stops.mode),
)
.at(1041)
.set_integer(|m, _, v| {
    let mode = if v == 2 {
        EndStopMode::Error
    } else {
        EndStopMode::Spring
    };
    m.params.end_stops.mode = mode;
    Ok(())
})
.after_set(Pss3Plant::changed)
.parameter(Variability::Fixed)
.integer_range(1, 2)
.start_integer(&[1]);

/// Number of parameter declarations.
pub const COUNT: usize = 33;

/// The parameters, value references 1001 to 1041.
pub const PARAMETERS: [Decl; COUNT] = concat(
    &[
        &GEOMETRY,
        &[
            STROKE_MIN,
            STROKE_MAX,
            PLATFORM_MASS,
            LEG_MASS,
            LEG_COM_FRACTION,
            LEG_TRANSVERSE_INERTIA,
            SLIDER_MASS,
            G,
            SLIDER_FRICTION,
            PIVOT_FRICTION,
            END_STOP_STIFFNESS,
            END_STOP_DAMPING,
            TOLERANCE,
            MAX_STEP,
        ],
        &PLATFORM_INERTIA,
        &[
            PLATFORM_COM,
            THETA0,
            L0,
            OMEGA0,
            INIT_FROM_ACTUATORS,
            END_STOP_MODE,
        ],
    ],
    STROKE_MIN,
);

fn mode_code(mode: EndStopMode) -> i32 {
    match mode {
        EndStopMode::Spring => 1,
        EndStopMode::Error => 2,
    }
}

#[cfg(test)]
mod tests {
    use super::super::{START_POSE, default_start_pose, variables::VARIABLES};
    use super::*;
    use robofmu_fmi::core::declare::Value;

    #[test]
    fn the_start_pose_is_the_forward_kinematics_of_the_start_displacement() {
        // Truth: forward kinematics of the default geometry with every actuator at
        // START_DISPLACEMENT (computed, not the constant).
        let pose = default_start_pose();
        for k in 0..3 {
            assert!((START_POSE[k] - pose[k]).abs() <= 1e-12, "{k}: {pose}");
        }
    }

    #[test]
    fn every_start_value_is_the_library_default() {
        // Truth: a model built from the library's defaults (PlantParams::default(),
        // StepSettings::default().tolerance, the start pose by forward kinematics),
        // read through each declaration's accessor.
        let mut m = Pss3Plant::default();
        m.initial.theta0 = default_start_pose();
        let mut checked = 0;
        for d in &VARIABLES {
            for i in 0..d.size() {
                let pick = |s: &[f64]| s.get(i).or(s.first()).copied();
                match d.value {
                    Value::Real { get, start, .. } => {
                        if let Some(s) = pick(start) {
                            assert!((get.read(&mut m, i) - s).abs() <= 1e-12, "{}[{i}]", d.name);
                            checked += 1;
                        }
                    }
                    Value::Integer { get, start, .. } => {
                        if let [s] = start {
                            assert_eq!(get.read(&mut m, i), *s, "{}", d.name);
                            checked += 1;
                        }
                    }
                    Value::Boolean { get, start, .. } => {
                        if let [s] = start {
                            assert_eq!(get.read(&mut m, i), *s, "{}", d.name);
                            checked += 1;
                        }
                    }
                }
            }
        }
        // 12 input elements, 29 scalar parameters, 4 parameter arrays of 3.
        assert_eq!(checked, 12 + 29 + 12);
    }
}
