//! The plant's parameters as FMU variables (fixed, defaults from the library's
//! `PlantParams::default()`, i.e. the spec) and the translation of the library's
//! parameter errors into messages that name the FMU parameter.

use super::Pss3Plant;
use nalgebra::Vector3;
use robofmu::pss3::ParamError;
use robofmu::pss3::dynamics::{EndStopMode, PlantParamError};
use robofmu_fmi::core::{Variability, Variable};

/// First value reference of the parameters.
pub const FIRST_VR: u32 = 1000;

/// Library parameter names and their FMU names (the geometric ones are equal).
const NAMES: [(&str, &str); 14] = [
    ("stroke_min", "strokeMin"),
    ("stroke_max", "strokeMax"),
    ("platform_mass", "platformMass"),
    ("platform_com", "platformCom"),
    ("platform_inertia", "platformInertia"),
    ("leg_mass", "legMass"),
    ("leg_com_fraction", "legComFraction"),
    ("leg_transverse_inertia", "legTransverseInertia"),
    ("slider_mass", "sliderMass"),
    ("slider_friction", "sliderFriction"),
    ("pivot_friction", "pivotFriction"),
    ("end_stop_stiffness", "endStopStiffness"),
    ("end_stop_damping", "endStopDamping"),
    ("gravity", "g"),
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
            "parameters strokeMin = {min} and strokeMax = {max}: strokeMin must be below strokeMax"
        ),
        E::Geometry(inner @ ParamError::LegCannotAssemble { .. }) => {
            format!("parameter a (with lp, ld, lb, alpha, beta and the stroke): {inner}")
        }
        E::InertiaNotPhysical(reason) => format!("parameter platformInertia: {reason}"),
    }
}

type Get = fn(&Pss3Plant) -> f64;
type Set = fn(&mut Pss3Plant, f64);

/// One scalar Real parameter: name, unit, display unit, description, get, set.
struct Scalar(
    &'static str,
    Option<&'static str>,
    Option<&'static str>,
    &'static str,
    Get,
    Set,
);

/// The scalar Real parameters in table order.
fn scalars() -> Vec<Scalar> {
    vec![
        Scalar(
            "lp",
            Some("m"),
            Some("mm"),
            "Height of the platform centre P above the base origin C",
            |m| m.params.geometry.lp,
            |m, v| m.params.geometry.lp = v,
        ),
        Scalar(
            "ld",
            Some("m"),
            Some("mm"),
            "Radius of the platform joints around P",
            |m| m.params.geometry.ld,
            |m, v| m.params.geometry.ld = v,
        ),
        Scalar(
            "gamma",
            Some("rad"),
            Some("deg"),
            "Angle of platform joint 1 in {B}",
            |m| m.params.geometry.gamma,
            |m, v| m.params.geometry.gamma = v,
        ),
        Scalar(
            "lb",
            Some("m"),
            Some("mm"),
            "Distance from C to the slider joints at l = 0",
            |m| m.params.geometry.lb,
            |m, v| m.params.geometry.lb = v,
        ),
        Scalar(
            "alpha",
            Some("rad"),
            Some("deg"),
            "Azimuth offset of the slider joints",
            |m| m.params.geometry.alpha,
            |m, v| m.params.geometry.alpha = v,
        ),
        Scalar(
            "beta",
            Some("rad"),
            Some("deg"),
            "Polar angle of the slider joints h_i from Z",
            |m| m.params.geometry.beta,
            |m, v| m.params.geometry.beta = v,
        ),
        Scalar(
            "a",
            Some("m"),
            Some("mm"),
            "Leg length, joint centre to joint centre",
            |m| m.params.geometry.a,
            |m, v| m.params.geometry.a = v,
        ),
        Scalar(
            "strokeMin",
            Some("m"),
            Some("mm"),
            "Lower end of the actuator stroke (lower end stop)",
            |m| m.params.geometry.stroke_min,
            |m, v| m.params.geometry.stroke_min = v,
        ),
        Scalar(
            "strokeMax",
            Some("m"),
            Some("mm"),
            "Upper end of the actuator stroke (upper end stop)",
            |m| m.params.geometry.stroke_max,
            |m, v| m.params.geometry.stroke_max = v,
        ),
        Scalar(
            "platformMass",
            Some("kg"),
            None,
            "Platform mass",
            |m| m.params.inertia.platform_mass,
            |m, v| m.params.inertia.platform_mass = v,
        ),
        Scalar(
            "legMass",
            Some("kg"),
            None,
            "Mass of each leg",
            |m| m.params.inertia.leg_mass,
            |m, v| m.params.inertia.leg_mass = v,
        ),
        Scalar(
            "legComFraction",
            None,
            None,
            "Leg centre of mass along the leg from the slider joint, as a fraction of a",
            |m| m.params.inertia.leg_com_fraction,
            |m, v| m.params.inertia.leg_com_fraction = v,
        ),
        Scalar(
            "legTransverseInertia",
            Some("kg.m2"),
            None,
            "Leg inertia about its centre of mass, perpendicular to the leg",
            |m| m.params.inertia.leg_transverse_inertia,
            |m, v| m.params.inertia.leg_transverse_inertia = v,
        ),
        Scalar(
            "sliderMass",
            Some("kg"),
            None,
            "Mass of each slider (rod and stud)",
            |m| m.params.inertia.slider_mass,
            |m, v| m.params.inertia.slider_mass = v,
        ),
        Scalar(
            "g",
            Some("m/s2"),
            None,
            "Gravitational acceleration, acting along -Z of {A}",
            |m| -m.params.gravity.z,
            |m, v| m.params.gravity = Vector3::new(0.0, 0.0, -v),
        ),
        Scalar(
            "sliderFriction",
            Some("N.s/m"),
            None,
            "Viscous friction on each slider, force -c lDot",
            |m| m.params.friction.slider,
            |m, v| m.params.friction.slider = v,
        ),
        Scalar(
            "pivotFriction",
            Some("N.m.s/rad"),
            None,
            "Viscous friction at the spherical joint P, moment -c omega",
            |m| m.params.friction.pivot,
            |m, v| m.params.friction.pivot = v,
        ),
        Scalar(
            "endStopStiffness",
            Some("N/m"),
            None,
            "Stiffness of the end-stop springs (endStopMode 1)",
            |m| m.params.end_stops.stiffness,
            |m, v| m.params.end_stops.stiffness = v,
        ),
        Scalar(
            "endStopDamping",
            Some("N.s/m"),
            None,
            "Damping of the end stops (endStopMode 1); the stop pushes, never pulls",
            |m| m.params.end_stops.damping,
            |m, v| m.params.end_stops.damping = v,
        ),
        Scalar(
            "tolerance",
            None,
            None,
            "Relative and absolute tolerance of the co-simulation integrator (Dormand-Prince 5(4))",
            |m| m.settings.tolerance,
            |m, v| m.settings.tolerance = v,
        ),
        Scalar(
            "maxStep",
            Some("s"),
            None,
            "Largest internal step of the co-simulation integrator",
            |m| m.settings.max_step,
            |m, v| m.settings.max_step = v,
        ),
    ]
}

/// One vector parameter: name, unit, display unit, description, component access.
type Component = fn(&mut Pss3Plant) -> &mut Vector3<f64>;

fn vectors() -> [(
    &'static str,
    &'static str,
    Option<&'static str>,
    &'static str,
    Component,
); 4] {
    [
        (
            "platformCom",
            "m",
            Some("mm"),
            "Platform centre of mass relative to P, in {B}",
            |m| &mut m.params.inertia.platform_com,
        ),
        (
            "theta0",
            "rad",
            Some("deg"),
            "Initial Euler angles (thx, thy, thz), used unless initFromActuators",
            |m| &mut m.initial.theta0,
        ),
        (
            "l0",
            "m",
            Some("mm"),
            "Initial actuator displacements, used when initFromActuators",
            |m| &mut m.initial.l0,
        ),
        (
            "omega0",
            "rad/s",
            Some("deg/s"),
            "Initial angular velocity of the platform in {A}",
            |m| &mut m.initial.omega0,
        ),
    ]
}

/// (row, column) pairs of the platform inertia tensor that are parameters; the
/// off-diagonal ones set both symmetric entries.
const INERTIA_ENTRIES: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (0, 2), (1, 2)];

fn fixed(variable: Variable<Pss3Plant>, start: f64) -> Variable<Pss3Plant> {
    variable.parameter(Variability::Fixed).start_real(start)
}

/// The parameter variables, value references from `FIRST_VR` on; start values are the
/// values of `defaults`.
pub fn variables(defaults: &Pss3Plant) -> Vec<Variable<Pss3Plant>> {
    let mut vr = FIRST_VR;
    let mut next = || {
        vr += 1;
        vr
    };
    let mut table = Vec::new();
    for Scalar(name, unit, display, description, get, set) in scalars() {
        let mut v = Variable::real(next(), name, description, get).set_real(move |m, x| {
            set(m, x);
            m.rebuild();
            Ok(())
        });
        if let Some(unit) = unit {
            v = v.unit(unit, display);
        }
        table.push(fixed(v, get(defaults)));
    }
    for (row, col) in INERTIA_ENTRIES {
        let name = format!("platformInertia[{},{}]", row + 1, col + 1);
        let v = Variable::real(
            next(),
            name,
            "Platform inertia tensor about P in {B} (symmetric: sets both entries)",
            move |m: &Pss3Plant| m.params.inertia.platform_inertia[(row, col)],
        )
        .unit("kg.m2", None)
        .set_real(move |m, x| {
            m.params.inertia.platform_inertia[(row, col)] = x;
            m.params.inertia.platform_inertia[(col, row)] = x;
            m.rebuild();
            Ok(())
        });
        table.push(fixed(
            v,
            defaults.params.inertia.platform_inertia[(row, col)],
        ));
    }
    for (name, unit, display, description, component) in vectors() {
        for i in 0..3 {
            let v = Variable::real(
                next(),
                format!("{name}[{}]", i + 1),
                description,
                move |m: &Pss3Plant| component(&mut m.clone())[i],
            )
            .unit(unit, display)
            .set_real(move |m, x| {
                component(m)[i] = x;
                m.rebuild();
                Ok(())
            });
            table.push(fixed(v, component(&mut defaults.clone())[i]));
        }
    }
    table.push(
        Variable::boolean(
            next(),
            "initFromActuators",
            "Initial pose from l0 by forward kinematics instead of theta0",
            |m: &Pss3Plant| m.initial.from_actuators,
        )
        .parameter(Variability::Fixed)
        .start_boolean(defaults.initial.from_actuators)
        .set_boolean(|m, v| {
            m.initial.from_actuators = v;
            Ok(())
        }),
    );
    table.push(
        Variable::integer(
            next(),
            "endStopMode",
            "End stops: 1 = spring-damper (contacts flagged in atStop), 2 = error (a \
             step that leaves the stroke is discarded)",
            |m: &Pss3Plant| mode_code(m.params.end_stops.mode),
        )
        .parameter(Variability::Fixed)
        .start_integer(mode_code(defaults.params.end_stops.mode))
        .integer_range(1, 2)
        .set_integer(|m, v| {
            m.params.end_stops.mode = if v == 2 {
                EndStopMode::Error
            } else {
                EndStopMode::Spring
            };
            m.rebuild();
            Ok(())
        }),
    );
    table
}

fn mode_code(mode: EndStopMode) -> i32 {
    match mode {
        EndStopMode::Spring => 1,
        EndStopMode::Error => 2,
    }
}
