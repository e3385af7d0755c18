//! The plant's parameters as FMU variables (fixed, defaults from the library's
//! `PlantParams::default()`, i.e. the spec) and the translation of the library's
//! parameter errors into messages that name the FMU parameter.

use super::Pss3Plant;
use nalgebra::Vector3;
use robofmu::pss3::ParamError;
use robofmu::pss3::dynamics::{EndStopMode, PlantParamError};
use robofmu_fmi::prelude::*;

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

/// `scalar!(name, unit, display unit, description, field.path)`: the `Scalar` that
/// reads and writes `m.field.path`.
macro_rules! scalar {
    ($name:literal, $unit:expr, $display:expr, $description:literal, $($field:ident).+) => {
        Scalar(
            $name,
            $unit,
            $display,
            $description,
            |m| m.$($field).+,
            |m, v| m.$($field).+ = v,
        )
    };
}

/// The scalar Real parameters in table order.
fn scalars() -> Vec<Scalar> {
    vec![
        scalar!(
            "lp",
            Some("m"),
            Some("mm"),
            "Height of the platform centre P above the base origin C",
            params.geometry.lp
        ),
        scalar!(
            "ld",
            Some("m"),
            Some("mm"),
            "Radius of the platform joints around P",
            params.geometry.ld
        ),
        scalar!(
            "gamma",
            Some("rad"),
            Some("deg"),
            "Angle of platform joint 1 in {B}",
            params.geometry.gamma
        ),
        scalar!(
            "lb",
            Some("m"),
            Some("mm"),
            "Distance from C to the slider joints at l = 0",
            params.geometry.lb
        ),
        scalar!(
            "alpha",
            Some("rad"),
            Some("deg"),
            "Azimuth offset of the slider joints",
            params.geometry.alpha
        ),
        scalar!(
            "beta",
            Some("rad"),
            Some("deg"),
            "Polar angle of the slider joints h_i from Z",
            params.geometry.beta
        ),
        scalar!(
            "a",
            Some("m"),
            Some("mm"),
            "Leg length, joint centre to joint centre",
            params.geometry.a
        ),
        scalar!(
            "strokeMin",
            Some("m"),
            Some("mm"),
            "Lower end of the actuator stroke (lower end stop)",
            params.geometry.stroke_min
        ),
        scalar!(
            "strokeMax",
            Some("m"),
            Some("mm"),
            "Upper end of the actuator stroke (upper end stop)",
            params.geometry.stroke_max
        ),
        scalar!(
            "platformMass",
            Some("kg"),
            None,
            "Platform mass",
            params.inertia.platform_mass
        ),
        scalar!(
            "legMass",
            Some("kg"),
            None,
            "Mass of each leg",
            params.inertia.leg_mass
        ),
        scalar!(
            "legComFraction",
            None,
            None,
            "Leg centre of mass along the leg from the slider joint, as a fraction of a",
            params.inertia.leg_com_fraction
        ),
        scalar!(
            "legTransverseInertia",
            Some("kg.m2"),
            None,
            "Leg inertia about its centre of mass, perpendicular to the leg",
            params.inertia.leg_transverse_inertia
        ),
        scalar!(
            "sliderMass",
            Some("kg"),
            None,
            "Mass of each slider (rod and stud)",
            params.inertia.slider_mass
        ),
        Scalar(
            "g",
            Some("m/s2"),
            None,
            "Gravitational acceleration, acting along -Z of {A}",
            |m| -m.params.gravity.z,
            |m, v| m.params.gravity = Vector3::new(0.0, 0.0, -v),
        ),
        scalar!(
            "sliderFriction",
            Some("N.s/m"),
            None,
            "Viscous friction on each slider, force -c lDot",
            params.friction.slider
        ),
        scalar!(
            "pivotFriction",
            Some("N.m.s/rad"),
            None,
            "Viscous friction at the spherical joint P, moment -c omega",
            params.friction.pivot
        ),
        scalar!(
            "endStopStiffness",
            Some("N/m"),
            None,
            "Stiffness of the end-stop springs (endStopMode 1)",
            params.end_stops.stiffness
        ),
        scalar!(
            "endStopDamping",
            Some("N.s/m"),
            None,
            "Damping of the end stops (endStopMode 1); the stop pushes, never pulls",
            params.end_stops.damping
        ),
        scalar!(
            "tolerance",
            None,
            None,
            "Relative and absolute tolerance of the co-simulation integrator (Dormand-Prince 5(4))",
            settings.tolerance
        ),
        scalar!(
            "maxStep",
            Some("s"),
            None,
            "Largest internal step of the co-simulation integrator",
            settings.max_step
        ),
    ]
}

/// One vector parameter `name[1..3]`: name, unit, display unit, description, read and
/// write access to the vector.
struct VectorParameter {
    name: &'static str,
    unit: &'static str,
    display: Option<&'static str>,
    description: &'static str,
    read: fn(&Pss3Plant) -> &Vector3<f64>,
    write: fn(&mut Pss3Plant) -> &mut Vector3<f64>,
}

/// `vector!(name, unit, display unit, description, field.path)`: the
/// `VectorParameter` of `m.field.path`.
macro_rules! vector {
    ($name:literal, $unit:literal, $display:expr, $description:literal, $($field:ident).+) => {
        VectorParameter {
            name: $name,
            unit: $unit,
            display: $display,
            description: $description,
            read: |m| &m.$($field).+,
            write: |m| &mut m.$($field).+,
        }
    };
}

const VECTORS: [VectorParameter; 4] = [
    vector!(
        "platformCom",
        "m",
        Some("mm"),
        "Platform centre of mass relative to P, in {B}",
        params.inertia.platform_com
    ),
    vector!(
        "theta0",
        "rad",
        Some("deg"),
        "Initial Euler angles (thx, thy, thz), used unless initFromActuators",
        initial.theta0
    ),
    vector!(
        "l0",
        "m",
        Some("mm"),
        "Initial actuator displacements, used when initFromActuators",
        initial.l0
    ),
    vector!(
        "omega0",
        "rad/s",
        Some("deg/s"),
        "Initial angular velocity of the platform in {A}",
        initial.omega0
    ),
];

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
    for p in &VECTORS {
        let (read, write) = (p.read, p.write);
        let start = *read(defaults);
        let array = RealArray::new(next(), p.name, 3, p.description, move |m, i| read(m)[i])
            .set(move |m, i, x| {
                write(m)[i] = x;
                m.rebuild();
                Ok(())
            })
            .each(move |v, i| fixed(v.unit(p.unit, p.display), start[i]));
        next();
        next();
        table.extend(array.variables());
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
