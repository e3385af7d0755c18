//! The variable table of the ComputedTorque FMU, declared once (a static table, see
//! `robofmu_fmi::core::declare`): gains and limits per axis (tunable), the
//! controller's model (fixed, one declaration per entry of the robot library's
//! `computed_torque::MODEL_PARAMETERS`), the inputs, the output and the error integral
//! (state).

use super::{AXES, ComputedTorqueFmu, DEFAULT_BANDWIDTH, initial_dependencies};
use robofmu_dynamics::computed_torque::{
    AxisGains, MODEL_PARAMETER_SPECS, MODEL_PARAMETERS, pole_placement,
};
use robofmu_dynamics::pss3::START_ROLL_DEG;
use robofmu_fmi::prelude::*;

type Decl = Declaration<ComputedTorqueFmu>;

/// The default gains: a triple pole at -30 rad/s of the error dynamics.
const GAINS: AxisGains = match pole_placement(DEFAULT_BANDWIDTH, true) {
    Ok(gains) => gains,
    Err(_) => panic!("the default bandwidth is positive"),
};

/// The default inputs: measured at rest in the start pose (path 1's start), planned
/// 0.5, -0.5 and 1 deg away, so that the default run's output moves.
const MEASURED: [f64; 3] = [0.0, 0.0, START_ROLL_DEG.to_radians()];
const PLANNED: [f64; 3] =
    [0.5f64.to_radians(), -0.5f64.to_radians(), START_ROLL_DEG.to_radians() + 1f64.to_radians()];

/// The per-axis array of `m.$($place)+[k]`-like fields, at `vr`, "Axis k: ..." in FMI
/// 2.0; writing it rebuilds the law before its next use.
macro_rules! axes {
    ($ty:ident, $set:ident, $name:literal, $vr:literal, $what:literal,
     |$m:ident, $k:ident| $($place:tt)+) => {
        Decl::$ty($name, $what, |$m, $k| $($place)+)
            .array(AXES)
            .at($vr)
            .label("Axis")
            .$set(|$m, $k, v| {
                $($place)+ = v;
                $m.changed();
                Ok(())
            })
    };
}

/// A tunable Real parameter per axis.
macro_rules! gain {
    ($name:literal, $vr:literal, $what:literal, $start:expr, $($place:tt)+) => {
        axes!(real, set_real, $name, $vr, $what, $($place)+)
            .parameter(Variability::Tunable)
            .start_real(&[$start])
    };
}

/// An input per axis (rad-based unit, display in degrees).
macro_rules! input {
    ($name:literal, $vr:literal, $what:literal, $unit:literal, $display:literal, $start:expr,
     $field:ident) => {
        Decl::real($name, $what, |m, k| m.inputs.$field[k])
            .array(AXES)
            .at($vr)
            .label("Axis")
            .set_real(|m, k, v| {
                m.inputs.$field[k] = v;
                Ok(())
            })
            .input()
            .unit($unit, Some($display))
            .start_real($start)
    };
}

/// `length` spec values from entry `k` on.
const fn specs(k: usize, length: usize) -> &'static [f64] {
    let all: &'static [f64] = &MODEL_PARAMETER_SPECS;
    all.split_at(k).1.split_at(length).0
}

fn get_model<const K: usize>(m: &ComputedTorqueFmu, i: usize) -> f64 {
    (MODEL_PARAMETERS[K + i].get)(&m.model)
}

fn set_model<const K: usize>(m: &mut ComputedTorqueFmu, i: usize, v: f64) -> Result<(), String> {
    (MODEL_PARAMETERS[K + i].set)(&mut m.model, v);
    m.changed();
    Ok(())
}

/// The model parameter `MODEL_PARAMETERS[K]` (with `length` > 1: the array `name[1..]`
/// of that many consecutive entries), fixed, at value reference 1001 + K.
const fn model<const K: usize>(length: usize) -> Decl {
    let p = &MODEL_PARAMETERS[K];
    let (name, description) = if length > 1 {
        let base = p.name.split_at(p.name.len() - 3).0; // "name[1]" -> "name"
        (base, p.description.split_at(p.description.len() - 3).0) // ", x"
    } else {
        (p.name, p.description)
    };
    let mut d = Decl::real(name, description, get_model::<K>).at(1001 + K as u32);
    if length > 1 {
        d = d.array(length);
    }
    d = d
        .set_real(set_model::<K>)
        .parameter(Variability::Fixed)
        .start_real(specs(K, length))
        .real_range(p.min, p.max);
    if let Some(unit) = p.unit {
        d = d.unit(unit, p.display_unit);
    }
    d
}

pub const KP: Decl =
    gain!("Kp", 1, "acceleration per angle error, 1/s2", GAINS.kp, |m, k| m.gains[k].kp);
pub const KD: Decl = gain!("Kd", 11, "acceleration per rate error", GAINS.kd, |m, k| m.gains[k].kd)
    .unit("1/s", None);
pub const KI: Decl =
    gain!("Ki", 21, "acceleration per integrated error, 1/s3", GAINS.ki, |m, k| m.gains[k].ki);
pub const LIMIT: Decl =
    axes!(boolean, set_boolean, "limitOutput", 31, "clamp the output to [uMin, uMax]", |m, k| m
        .limited[k])
    .parameter(Variability::Tunable)
    .start_boolean(&[false]);
pub const U_MIN: Decl =
    gain!("uMin", 41, "lower output limit (used when limitOutput)", -1.0, |m, k| m.limits[k].0)
        .unit("N.m", None);
pub const U_MAX: Decl =
    gain!("uMax", 51, "upper output limit (used when limitOutput)", 1.0, |m, k| m.limits[k].1)
        .unit("N.m", None);
pub const SETPOINT: Decl =
    input!("setpoint", 101, "planned Euler angle q", "rad", "deg", &PLANNED, setpoint);
pub const SETPOINT_RATE: Decl = input!(
    "setpointRate",
    111,
    "planned Euler-angle rate qdot",
    "rad/s",
    "deg/s",
    &[0.0],
    setpoint_rate
);
pub const SETPOINT_ACCELERATION: Decl = input!(
    "setpointAcceleration",
    121,
    "planned Euler-angle acceleration qddot",
    "rad/s2",
    "deg/s2",
    &[0.0],
    setpoint_acceleration
);
pub const MEASUREMENT: Decl =
    input!("measurement", 131, "measured Euler angle theta", "rad", "deg", &MEASURED, measurement);
pub const MEASURED_RATE: Decl = input!(
    "measuredRate",
    141,
    "measured Euler-angle rate thetaDot",
    "rad/s",
    "deg/s",
    &[0.0],
    measured_rate
);
pub const U: Decl =
    Decl::real("u", "Euler-angle generalized force (plant generalizedForceCommand)", |m, k| m.u(k))
        .array(AXES)
        .at(201)
        .label("Axis")
        .output()
        .unit("N.m", None)
        .initial_depends_on_each(initial_dependencies::of_axis);
pub const INTEGRAL: Decl =
    axes!(real, set_real, "integral", 301, "integral of the angle error (state)", |m, k| m
        .integral[k])
    .state()
    .start_real(&[0.0]);
pub const DER_INTEGRAL: Decl =
    Decl::real("der(integral)", "Time derivative of the error integral", |m, k| m.integral_rate(k))
        .array(AXES)
        .at(311)
        .derivative_of(INTEGRAL.name)
        .initial_depends_on_each(initial_dependencies::of_axis);

/// The model's geometry: lp, ld, gamma, lb, alpha, beta, a.
pub const GEOMETRY: [Decl; 7] = [
    model::<0>(1),
    model::<1>(1),
    model::<2>(1),
    model::<3>(1),
    model::<4>(1),
    model::<5>(1),
    model::<6>(1),
];
pub const PLATFORM_MASS: Decl = model::<7>(1);
pub const PLATFORM_COM: Decl = model::<8>(3);
/// platformInertia[1,1], [2,2], [3,3], [1,2], [1,3], [2,3].
pub const PLATFORM_INERTIA: [Decl; 6] = [
    model::<11>(1),
    model::<12>(1),
    model::<13>(1),
    model::<14>(1),
    model::<15>(1),
    model::<16>(1),
];
/// legMass, legComFraction, legTransverseInertia, sliderMass.
pub const LEGS_AND_SLIDERS: [Decl; 4] =
    [model::<17>(1), model::<18>(1), model::<19>(1), model::<20>(1)];
pub const G: Decl = model::<21>(1);
/// sliderFriction, pivotFriction.
pub const FRICTION: [Decl; 2] = [model::<22>(1), model::<23>(1)];

/// The law's variables.
const LAW: [Decl; 14] = [
    KP,
    KD,
    KI,
    LIMIT,
    U_MIN,
    U_MAX,
    SETPOINT,
    SETPOINT_RATE,
    SETPOINT_ACCELERATION,
    MEASUREMENT,
    MEASURED_RATE,
    U,
    INTEGRAL,
    DER_INTEGRAL,
];

/// The law's variables, then the model's (one declaration per entry of
/// `MODEL_PARAMETERS`, in its order).
pub static VARIABLES: [Decl; 36] = concat(
    &[
        &LAW,
        &GEOMETRY,
        &[PLATFORM_MASS, PLATFORM_COM],
        &PLATFORM_INERTIA,
        &LEGS_AND_SLIDERS,
        &[G],
        &FRICTION,
    ],
    KP,
);
