//! The variable table of Pss3Plant, declared once (a `static` slice, see
//! `robofmu_fmi::core::declare`): the inputs, outputs and state derivatives here, the
//! parameters in `parameters.rs`. Every value reference is pinned (`.at`) at the one
//! it has always had: a vector variable's group below plus i = 1..3.

use super::initial_dependencies as init;
use super::output_rates::{Output, output_derivative};
use super::{Pss3Plant, parameters};
use robofmu_dynamics::pss3::dynamics::PlantInputs;
use robofmu_fmi::prelude::*;

pub const ACTUATOR_FORCE: u32 = 0;
pub const TORQUE_COMMAND: u32 = 10;
pub const GENERALIZED_FORCE_COMMAND: u32 = 20;
pub const DISTURBANCE_TORQUE: u32 = 30;
pub const THETA: u32 = 100;
pub const OMEGA: u32 = 110;
pub const THETA_DOT: u32 = 120;
pub const OMEGA_DOT: u32 = 130;
pub const YAW_PITCH_ROLL: u32 = 140;
pub const L: u32 = 150;
pub const L_DOT: u32 = 160;
pub const FORCE: u32 = 170;
pub const STOP_FORCE: u32 = 180;
pub const AT_STOP: u32 = 190;
pub const DET_J: u32 = 201;
pub const COND_J: u32 = 202;
pub const KINETIC_ENERGY: u32 = 203;
pub const POTENTIAL_ENERGY: u32 = 204;
pub const GRAVITY_COMPENSATION: u32 = 210;
pub const DER_THETA: u32 = 300;
pub const DER_OMEGA: u32 = 310;

type Decl = Declaration<Pss3Plant>;

/// The elements `base[1]`, `base[2]`, `base[3]` of a literal `base`.
macro_rules! elements {
    ($base:literal) => {
        [
            Var::Named(concat!($base, "[1]")),
            Var::Named(concat!($base, "[2]")),
            Var::Named(concat!($base, "[3]")),
        ]
    };
}

/// The parts one after the other, in a static table (`fill` only fills the array
/// before it is overwritten).
pub const fn concat<T: Copy, const N: usize>(parts: &[&[T]], fill: T) -> [T; N] {
    let mut out = [fill; N];
    let (mut k, mut p) = (0, 0);
    while p < parts.len() {
        let mut i = 0;
        while i < parts[p].len() {
            out[k] = parts[p][i];
            (k, i) = (k + 1, i + 1);
        }
        p += 1;
    }
    assert!(k == N, "the parts do not fill the table");
    out
}

// What outputs and state derivatives depend on (ModelStructure dependencies).
static THETA_NAMES: [Var; 3] = elements!("theta");
static OMEGA_NAMES: [Var; 3] = elements!("omega");
static COMMAND_NAMES: [Var; 9] = concat(
    &[
        &elements!("actuatorForce"),
        &elements!("torqueCommand"),
        &elements!("generalizedForceCommand"),
    ],
    Var::Time,
);
/// The continuous states (pose and angular velocity).
static STATES: [Var; 6] = concat(&[&THETA_NAMES, &OMEGA_NAMES], Var::Time);
/// The pose and the actuator commands (the realised actuator force).
static THETA_AND_COMMANDS: [Var; 12] = concat(&[&THETA_NAMES, &COMMAND_NAMES], Var::Time);
/// The states and every input (through the accelerations).
static STATES_AND_INPUTS: [Var; 18] = concat(
    &[&STATES, &COMMAND_NAMES, &elements!("disturbanceTorque")],
    Var::Time,
);

/// Where the model keeps the input derivatives of order `order`.
fn ramp(m: &mut Pss3Plant, order: u32) -> Option<&mut PlantInputs> {
    match order {
        1 => Some(&mut m.ramp.rate),
        2 => Some(&mut m.ramp.acceleration),
        _ => None,
    }
}

/// An input `m.inputs.$field` of three elements at `$group + 1..3`, held or ramped
/// over a step (input derivatives up to order 2).
macro_rules! input {
    ($name:literal, $group:expr, $unit:literal, $what:literal, $field:ident) => {
        Decl::real($name, $what, |m, i| m.inputs.$field[i])
            .array(3)
            .at($group + 1)
            .set_real(|m, i, v| {
                m.inputs.$field[i] = v;
                Ok(())
            })
            .input()
            .unit($unit, None)
            .start_real(&[0.0])
            .input_derivative(|m, i, order| Some(&mut ramp(m, order)?.$field[i]))
    };
}

/// The output-derivative hook of element `i` of `$output` (`output_rates` serves
/// orders 1 and 2 of every Real output); `$i` fixes the element of a scalar.
macro_rules! rates {
    ($output:ident) => {
        |m, i, order| output_derivative(m, Output::$output, i, order)
    };
    ($output:ident[$i:expr]) => {
        |m, _, order| output_derivative(m, Output::$output, $i, order)
    };
}

/// A Real output of three elements at `$group + 1..3`, element i read by `$get`.
macro_rules! vector {
    ($name:literal, $group:expr, $output:ident, $what:literal, |$m:ident, $i:ident| $get:expr) => {
        Decl::real($name, $what, |$m, $i| $get)
            .array(3)
            .at($group + 1)
            .output()
            .output_derivative(2, rates!($output))
    };
}

/// A scalar Real output at `$vr` read by `$get`, element `$i` of `$output` (0 unless
/// given).
macro_rules! scalar {
    ($name:literal, $vr:expr, $output:ident $([$i:literal])?, $what:literal, |$m:ident| $get:expr) => {
        Decl::real($name, $what, |$m, _| $get)
            .at($vr)
            .output()
            .output_derivative(2, rates!($output[0 $(+ $i)?]))
    };
}

/// Euler angle `axis` of the current state times `sign` (the thesis's yaw, pitch, roll).
fn euler(m: &Pss3Plant, axis: usize, sign: f64) -> f64 {
    m.current_state().map_or(f64::NAN, |s| sign * s.euler[axis])
}

const INPUTS_OUTPUTS: [Decl; 23] = [
    input!(
        "actuatorForce",
        ACTUATOR_FORCE,
        "N",
        "Force applied by actuator i along its axis u_i",
        forces
    ),
    input!(
        "torqueCommand",
        TORQUE_COMMAND,
        "N.m",
        "Commanded moment about P in {A}, realised by the actuators (f = J^-T tau)",
        commanded_torque
    ),
    input!(
        "generalizedForceCommand",
        GENERALIZED_FORCE_COMMAND,
        "N.m",
        "Commanded generalized force in Euler-angle coordinates (thx, thy, thz), \
         realised by the actuators (tau = E^-T Q, f = J^-T tau)",
        generalized_force
    ),
    input!(
        "disturbanceTorque",
        DISTURBANCE_TORQUE,
        "N.m",
        "External moment on the platform about P in {A} (not through the actuators)",
        disturbance_torque
    ),
    vector!(
        "theta",
        THETA,
        Theta,
        "Euler angle (thx, thy, thz) of R = Rz Ry Rx (continuous state)",
        |m, i| euler(m, i, 1.0)
    )
    .unit("rad", Some("deg"))
    .depends_on_each(|i| &THETA_NAMES[i..=i])
    .initial_depends_on_each(|i| &init::THETA[i]),
    vector!(
        "omega",
        OMEGA,
        Omega,
        "Angular velocity of the platform in {A} (continuous state)",
        |m, i| m.current_state().map_or(f64::NAN, |s| s.omega[i])
    )
    .unit("rad/s", Some("deg/s"))
    .depends_on_each(|i| &OMEGA_NAMES[i..=i])
    .initial_depends_on_each(|i| &init::OMEGA[i]),
    vector!(
        "thetaDot",
        THETA_DOT,
        ThetaDot,
        "Euler-angle rate",
        |m, i| m.computed(|c| c.euler_rates[i])
    )
    .unit("rad/s", Some("deg/s"))
    .depends_on(&STATES)
    .initial_depends_on_each(init::theta_dot),
    vector!(
        "omegaDot",
        OMEGA_DOT,
        OmegaDot,
        "Angular acceleration of the platform in {A}",
        |m, i| m.output(|o| o.omega_dot[i])
    )
    .unit("rad/s2", Some("deg/s2"))
    .depends_on(&STATES_AND_INPUTS)
    .initial_depends_on(&init::ACCELERATION),
    scalar!(
        "yaw",
        YAW_PITCH_ROLL + 1,
        YawPitchRoll[0],
        "Yaw: thx, the Euler angle about X of R = Rz(thz) Ry(thy) Rx(thx) (the source thesis's name, docs/3pss-model.md)",
        |m| euler(m, 0, 1.0)
    )
    .unit("rad", Some("deg"))
    .depends_on(&[Var::Named("theta[1]")])
    .initial_depends_on(&init::THETA[0]),
    scalar!(
        "pitch",
        YAW_PITCH_ROLL + 2,
        YawPitchRoll[1],
        "Pitch: -thy, the Euler angle about Y of R = Rz(thz) Ry(thy) Rx(thx) with its sign flipped (as the source thesis's tables print it, docs/3pss-model.md)",
        |m| euler(m, 1, -1.0)
    )
    .unit("rad", Some("deg"))
    .depends_on(&[Var::Named("theta[2]")])
    .initial_depends_on(&init::THETA[1]),
    scalar!(
        "roll",
        YAW_PITCH_ROLL + 3,
        YawPitchRoll[2],
        "Roll: thz, the Euler angle about Z of R = Rz(thz) Ry(thy) Rx(thx) (the source thesis's name, docs/3pss-model.md)",
        |m| euler(m, 2, 1.0)
    )
    .unit("rad", Some("deg"))
    .depends_on(&[Var::Named("theta[3]")])
    .initial_depends_on(&init::THETA[2]),
    vector!("l", L, L, "Actuator displacement", |m, i| m
        .output(|o| o.actuator_displacements[i]))
    .unit("m", Some("mm"))
    .depends_on(&THETA_NAMES)
    .initial_depends_on(&init::POSE),
    vector!("lDot", L_DOT, LDot, "Actuator velocity", |m, i| m
        .output(|o| o.actuator_velocities[i]))
    .unit("m/s", None)
    .depends_on(&STATES)
    .initial_depends_on(&init::MOTION),
    vector!(
        "force",
        FORCE,
        Force,
        "Total actuator force from the inputs (actuatorForce plus the mapped commands), \
         without end-stop forces",
        |m, i| m.output(|o| o.actuator_forces[i])
    )
    .unit("N", None)
    .depends_on(&THETA_AND_COMMANDS)
    .initial_depends_on_each(|i| &init::FORCE[i]),
    vector!(
        "stopForce",
        STOP_FORCE,
        StopForce,
        "End-stop force on the actuator along u_i",
        |m, i| m.output(|o| o.end_stop_forces[i])
    )
    .unit("N", None)
    .depends_on(&STATES)
    .initial_depends_on(&init::STOP_FORCE),
    Decl::integer(
        "atStop",
        "End-stop contact: -1 lower stop, 0 free, +1 upper stop (changes at events)",
        |m, i| m.contact(i),
    )
    .array(3)
    .at(AT_STOP + 1)
    .output()
    .depends_on(&THETA_NAMES)
    .initial_depends_on(&init::AT_STOP),
    scalar!(
        "detJ",
        DET_J,
        DetJ,
        "Determinant of the actuator Jacobian J (lDot = J omega)",
        |m| m.output(|o| o.jacobian_det)
    )
    .unit("m3", None)
    .depends_on(&THETA_NAMES)
    .initial_depends_on(&init::POSE),
    scalar!(
        "condJ",
        COND_J,
        CondJ,
        "2-norm condition number of J",
        |m| m.output(|o| o.jacobian_cond)
    )
    .depends_on(&THETA_NAMES)
    .initial_depends_on(&init::POSE),
    scalar!(
        "kineticEnergy",
        KINETIC_ENERGY,
        KineticEnergy,
        "Kinetic energy of platform, legs and sliders",
        |m| m.output(|o| o.kinetic_energy)
    )
    .unit("J", None)
    .depends_on(&STATES)
    .initial_depends_on(&init::KINETIC_ENERGY),
    scalar!(
        "potentialEnergy",
        POTENTIAL_ENERGY,
        PotentialEnergy,
        "Potential energy of gravity (zero at the height of C) plus the energy in the \
         end-stop springs",
        |m| m.output(|o| o.potential_energy + o.end_stop_energy)
    )
    .unit("J", None)
    .depends_on(&THETA_NAMES)
    .initial_depends_on(&init::POTENTIAL_ENERGY),
    vector!(
        "gravityCompensation",
        GRAVITY_COMPENSATION,
        GravityCompensation,
        "Euler-angle generalized force G = E^T g(theta) that holds the current pose at \
         rest against gravity (feedforward for generalizedForceCommand)",
        |m, i| m.computed(|c| c.gravity_compensation[i])
    )
    .unit("N.m", None)
    .depends_on(&THETA_NAMES)
    .initial_depends_on_each(init::gravity_compensation),
    Decl::real("der(theta)", "Euler-angle rate", |m, i| {
        m.computed(|c| c.euler_rates[i])
    })
    .array(3)
    .at(DER_THETA + 1)
    .derivative_of("theta")
    .unit("rad/s", Some("deg/s"))
    .depends_on(&STATES)
    .initial_depends_on_each(init::theta_dot),
    Decl::real("der(omega)", "Angular acceleration in {A}", |m, i| {
        m.output(|o| o.omega_dot[i])
    })
    .array(3)
    .at(DER_OMEGA + 1)
    .derivative_of("omega")
    .unit("rad/s2", Some("deg/s2"))
    .depends_on(&STATES_AND_INPUTS)
    .initial_depends_on(&init::ACCELERATION),
];

/// The whole table: inputs, outputs, state derivatives, parameters (value references
/// increasing).
pub static VARIABLES: [Decl; 23 + parameters::COUNT] = concat(
    &[&INPUTS_OUTPUTS, &parameters::PARAMETERS],
    INPUTS_OUTPUTS[0],
);

/// The getter of the Real declaration `name`, if there is one.
pub fn real_getter(name: &str) -> Option<fn(&Pss3Plant, usize) -> f64> {
    VARIABLES
        .iter()
        .find(|d| d.name == name)
        .and_then(|d| match d.value {
            robofmu_fmi::core::declare::Value::Real { get, .. } => Some(get),
            _ => None,
        })
}
