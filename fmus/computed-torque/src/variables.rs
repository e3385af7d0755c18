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

type Fmu = ComputedTorqueFmu;
type Decl = Declaration<Fmu>;

/// The default gains: a triple pole at -30 rad/s of the error dynamics.
const GAINS: AxisGains = match pole_placement(DEFAULT_BANDWIDTH, true) {
    Ok(gains) => gains,
    Err(_) => panic!("the default bandwidth is positive"),
};

/// The default inputs: measured at rest in the start pose (path 1's start), planned
/// 0.5, -0.5 and 1 deg away, so that the default run's output moves.
const MEASURED: [f64; 3] = [0.0, 0.0, START_ROLL_DEG.to_radians()];
const PLANNED: [f64; 3] = [
    0.5f64.to_radians(),
    -0.5f64.to_radians(),
    START_ROLL_DEG.to_radians() + 1f64.to_radians(),
];

/// The per-axis array at `vr`, "Axis k: ..." in FMI 2.0.
const fn axes(d: Decl, vr: u32) -> Decl {
    d.array(AXES).at(vr).label("Axis")
}

/// A tunable parameter per axis: the law is rebuilt before its next use.
const fn tunable(d: Decl, vr: u32) -> Decl {
    let d = axes(d, vr).parameter(Variability::Tunable);
    d.after_set(ComputedTorqueFmu::rebuild_law)
}

/// A tunable Real parameter per axis.
const fn gain(name: &'static str, vr: u32, start: &'static [f64], place: Place<Fmu, f64>) -> Decl {
    tunable(Decl::real_in(name, place), vr).start_real(start)
}

/// An input per axis, `unit` rad-based and displayed in degrees.
const fn input(
    name: &'static str,
    vr: u32,
    unit: [&'static str; 2],
    place: Place<Fmu, f64>,
) -> Decl {
    let d = axes(Decl::real_in(name, place), vr).input();
    d.unit(unit[0], Some(unit[1])).start_real(&[0.0])
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
        .after_set(ComputedTorqueFmu::rebuild_law)
        .parameter(Variability::Fixed)
        .start_real(specs(K, length))
        .real_range(p.min, p.max);
    if let Some(unit) = p.unit {
        d = d.unit(unit, p.display_unit);
    }
    d
}

pub const KP: Decl = gain("Kp", 1, &[GAINS.kp], |m, k| &mut m.gains[k].kp)
    .describe("acceleration per angle error, 1/s2");
pub const KD: Decl = gain("Kd", 11, &[GAINS.kd], |m, k| &mut m.gains[k].kd)
    .describe("acceleration per rate error")
    .unit("1/s", None);
pub const KI: Decl = gain("Ki", 21, &[GAINS.ki], |m, k| &mut m.gains[k].ki)
    .describe("acceleration per integrated error, 1/s3");
pub const LIMIT: Decl = tunable(
    Decl::boolean_in("limitOutput", |m, k| &mut m.limited[k]),
    31,
)
.describe("clamp the output to [uMin, uMax]")
.start_boolean(&[false]);
pub const U_MIN: Decl = gain("uMin", 41, &[-1.0], |m, k| &mut m.limits[k].0)
    .describe("lower output limit (used when limitOutput)")
    .unit("N.m", None);
pub const U_MAX: Decl = gain("uMax", 51, &[1.0], |m, k| &mut m.limits[k].1)
    .describe("upper output limit (used when limitOutput)")
    .unit("N.m", None);
pub const SETPOINT: Decl = input("setpoint", 101, ["rad", "deg"], |m, k| {
    &mut m.inputs.setpoint[k]
})
.describe("planned Euler angle q")
.start_real(&PLANNED);
pub const SETPOINT_RATE: Decl = input("setpointRate", 111, ["rad/s", "deg/s"], |m, k| {
    &mut m.inputs.setpoint_rate[k]
})
.describe("planned Euler-angle rate qdot");
pub const SETPOINT_ACCELERATION: Decl =
    input("setpointAcceleration", 121, ["rad/s2", "deg/s2"], |m, k| {
        &mut m.inputs.setpoint_acceleration[k]
    })
    .describe("planned Euler-angle acceleration qddot");
pub const MEASUREMENT: Decl = input("measurement", 131, ["rad", "deg"], |m, k| {
    &mut m.inputs.measurement[k]
})
.describe("measured Euler angle theta")
.start_real(&MEASURED);
pub const MEASURED_RATE: Decl = input("measuredRate", 141, ["rad/s", "deg/s"], |m, k| {
    &mut m.inputs.measured_rate[k]
})
.describe("measured Euler-angle rate thetaDot");
pub const U: Decl = Decl::real(
    "u",
    "Euler-angle generalized force (plant generalizedForceCommand)",
    |m, k| m.u(k),
)
.array(AXES)
.at(201)
.label("Axis")
.output()
.unit("N.m", None)
.initial_depends_on_each(initial_dependencies::of_axis);
pub const INTEGRAL: Decl = axes(Decl::real_in("integral", |m, k| &mut m.integral[k]), 301)
    .describe("integral of the angle error (state)")
    .state()
    .start_real(&[0.0]);
pub const DER_INTEGRAL: Decl = Decl::real(
    "der(integral)",
    "Time derivative of the error integral",
    |m, k| m.integral_rate(k),
)
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
pub const LEGS_AND_SLIDERS: [Decl; 4] = [
    model::<17>(1),
    model::<18>(1),
    model::<19>(1),
    model::<20>(1),
];
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
