//! The variable table of Pss3Plant, declared once (a `static` slice, see
//! `robofmu_fmi::core::declare`): the inputs, outputs and state derivatives here, the
//! parameters in `parameters.rs`. Every value reference is pinned (`.at`) at the one
//! it has always had: a vector variable's group (the macros' second argument) plus
//! i = 1..3.

use super::initial_dependencies as init;
use super::output_rates::{Output, output_derivative};
use super::{Pss3Plant, parameters};
use robofmu_dynamics::pss3::dynamics::PlantInputs;
use robofmu_fmi::prelude::*;

type Decl = Declaration<Pss3Plant>;

// What outputs and state derivatives depend on (ModelStructure dependencies).
/// The continuous states (pose and angular velocity).
static STATES: [Var; 2] = [THETA.var(), OMEGA.var()];
/// The pose and the actuator commands (the realised actuator force).
static THETA_AND_COMMANDS: [Var; 4] =
    [THETA.var(), ACTUATOR_FORCE.var(), TORQUE_COMMAND.var(), GENERALIZED_FORCE_COMMAND.var()];
/// The states and every input (through the accelerations).
static STATES_AND_INPUTS: [Var; 6] = [
    THETA.var(),
    OMEGA.var(),
    ACTUATOR_FORCE.var(),
    TORQUE_COMMAND.var(),
    GENERALIZED_FORCE_COMMAND.var(),
    DISTURBANCE_TORQUE.var(),
];
/// A state as an output: element i is the state's element i.
static THETA_ITSELF: [Var; 1] = [THETA.same()];
static OMEGA_ITSELF: [Var; 1] = [OMEGA.same()];

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

pub const ACTUATOR_FORCE: Decl =
    input!("actuatorForce", 0, "N", "Force applied by actuator i along its axis u_i", forces);
pub const TORQUE_COMMAND: Decl = input!(
    "torqueCommand",
    10,
    "N.m",
    "Commanded moment about P in {A}, realised by the actuators (f = J^-T tau)",
    commanded_torque
);
pub const GENERALIZED_FORCE_COMMAND: Decl = input!(
    "generalizedForceCommand",
    20,
    "N.m",
    "Commanded generalized force in Euler-angle coordinates (thx, thy, thz), \
     realised by the actuators (tau = E^-T Q, f = J^-T tau)",
    generalized_force
);
pub const DISTURBANCE_TORQUE: Decl = input!(
    "disturbanceTorque",
    30,
    "N.m",
    "External moment on the platform about P in {A} (not through the actuators)",
    disturbance_torque
);
// A declaration's own list cannot name it (a const that refers to itself): theta and
// omega reach their lists through a function.
pub const THETA: Decl = vector!(
    "theta",
    100,
    Theta,
    "Euler angle (thx, thy, thz) of R = Rz Ry Rx (continuous state)",
    |m, i| euler(m, i, 1.0)
)
.unit("rad", Some("deg"))
.depends_on_each(|_| &THETA_ITSELF)
.initial_depends_on_each(|i| &init::THETA[i]);
pub const OMEGA: Decl = vector!(
    "omega",
    110,
    Omega,
    "Angular velocity of the platform in {A} (continuous state)",
    |m, i| m.current_state().map_or(f64::NAN, |s| s.omega[i])
)
.unit("rad/s", Some("deg/s"))
.depends_on_each(|_| &OMEGA_ITSELF)
.initial_depends_on(&init::OMEGA);
pub const THETA_DOT: Decl = vector!("thetaDot", 120, ThetaDot, "Euler-angle rate", |m, i| m
    .computed(|c| c.euler_rates[i]))
.unit("rad/s", Some("deg/s"))
.depends_on(&STATES)
.initial_depends_on_each(init::theta_dot);
pub const OMEGA_DOT: Decl =
    vector!("omegaDot", 130, OmegaDot, "Angular acceleration of the platform in {A}", |m, i| m
        .output(|o| o.omega_dot[i]))
    .unit("rad/s2", Some("deg/s2"))
    .depends_on(&STATES_AND_INPUTS)
    .initial_depends_on(&init::ACCELERATION);
pub const YAW: Decl = scalar!(
    "yaw",
    141,
    YawPitchRoll[0],
    "Yaw: thx, the Euler angle about X of R = Rz(thz) Ry(thy) Rx(thx) (the source thesis's name, docs/3pss-model.md)",
    |m| euler(m, 0, 1.0)
)
.unit("rad", Some("deg"))
.depends_on(&[THETA.item(0)])
.initial_depends_on(&init::THETA[0]);
pub const PITCH: Decl = scalar!(
    "pitch",
    142,
    YawPitchRoll[1],
    "Pitch: -thy, the Euler angle about Y of R = Rz(thz) Ry(thy) Rx(thx) with its sign flipped (as the source thesis's tables print it, docs/3pss-model.md)",
    |m| euler(m, 1, -1.0)
)
.unit("rad", Some("deg"))
.depends_on(&[THETA.item(1)])
.initial_depends_on(&init::THETA[1]);
pub const ROLL: Decl = scalar!(
    "roll",
    143,
    YawPitchRoll[2],
    "Roll: thz, the Euler angle about Z of R = Rz(thz) Ry(thy) Rx(thx) (the source thesis's name, docs/3pss-model.md)",
    |m| euler(m, 2, 1.0)
)
.unit("rad", Some("deg"))
.depends_on(&[THETA.item(2)])
.initial_depends_on(&init::THETA[2]);
const L: Decl = vector!("l", 150, L, "Actuator displacement", |m, i| m
    .output(|o| o.actuator_displacements[i]))
.unit("m", Some("mm"))
.depends_on(&[THETA.var()])
.initial_depends_on(&init::POSE);
const L_DOT: Decl = vector!("lDot", 160, LDot, "Actuator velocity", |m, i| m
    .output(|o| o.actuator_velocities[i]))
.unit("m/s", None)
.depends_on(&STATES)
.initial_depends_on(&init::MOTION);
const FORCE: Decl = vector!(
    "force",
    170,
    Force,
    "Total actuator force from the inputs (actuatorForce plus the mapped commands), \
     without end-stop forces",
    |m, i| m.output(|o| o.actuator_forces[i])
)
.unit("N", None)
.depends_on(&THETA_AND_COMMANDS)
.initial_depends_on(&init::FORCE);
const STOP_FORCE: Decl =
    vector!("stopForce", 180, StopForce, "End-stop force on the actuator along u_i", |m, i| m
        .output(|o| o.end_stop_forces[i]))
    .unit("N", None)
    .depends_on(&STATES)
    .initial_depends_on(&init::STOP_FORCE);
const AT_STOP: Decl = Decl::integer(
    "atStop",
    "End-stop contact: -1 lower stop, 0 free, +1 upper stop (changes at events)",
    |m, i| m.contact(i),
)
.array(3)
.at(191)
.output()
.depends_on(&[THETA.var()])
.initial_depends_on(&init::AT_STOP);
const DET_J: Decl =
    scalar!("detJ", 201, DetJ, "Determinant of the actuator Jacobian J (lDot = J omega)", |m| m
        .output(|o| o.jacobian_det))
    .unit("m3", None)
    .depends_on(&[THETA.var()])
    .initial_depends_on(&init::POSE);
const COND_J: Decl = scalar!("condJ", 202, CondJ, "2-norm condition number of J", |m| m
    .output(|o| o.jacobian_cond))
.depends_on(&[THETA.var()])
.initial_depends_on(&init::POSE);
const KINETIC_ENERGY: Decl = scalar!(
    "kineticEnergy",
    203,
    KineticEnergy,
    "Kinetic energy of platform, legs and sliders",
    |m| m.output(|o| o.kinetic_energy)
)
.unit("J", None)
.depends_on(&STATES)
.initial_depends_on(&init::KINETIC_ENERGY);
const POTENTIAL_ENERGY: Decl = scalar!(
    "potentialEnergy",
    204,
    PotentialEnergy,
    "Potential energy of gravity (zero at the height of C) plus the energy in the \
     end-stop springs",
    |m| m.output(|o| o.potential_energy + o.end_stop_energy)
)
.unit("J", None)
.depends_on(&[THETA.var()])
.initial_depends_on(&init::POTENTIAL_ENERGY);
const GRAVITY_COMPENSATION: Decl = vector!(
    "gravityCompensation",
    210,
    GravityCompensation,
    "Euler-angle generalized force G = E^T g(theta) that holds the current pose at \
     rest against gravity (feedforward for generalizedForceCommand)",
    |m, i| m.computed(|c| c.gravity_compensation[i])
)
.unit("N.m", None)
.depends_on(&[THETA.var()])
.initial_depends_on_each(init::gravity_compensation);
pub const DER_THETA: Decl =
    Decl::real("der(theta)", "Euler-angle rate", |m, i| m.computed(|c| c.euler_rates[i]))
        .array(3)
        .at(301)
        .derivative_of(THETA.name)
        .unit("rad/s", Some("deg/s"))
        .depends_on(&STATES)
        .initial_depends_on_each(init::theta_dot);
pub const DER_OMEGA: Decl =
    Decl::real("der(omega)", "Angular acceleration in {A}", |m, i| m.output(|o| o.omega_dot[i]))
        .array(3)
        .at(311)
        .derivative_of(OMEGA.name)
        .unit("rad/s2", Some("deg/s2"))
        .depends_on(&STATES_AND_INPUTS)
        .initial_depends_on(&init::ACCELERATION);

const INPUTS_OUTPUTS: [Decl; 23] = [
    ACTUATOR_FORCE,
    TORQUE_COMMAND,
    GENERALIZED_FORCE_COMMAND,
    DISTURBANCE_TORQUE,
    THETA,
    OMEGA,
    THETA_DOT,
    OMEGA_DOT,
    YAW,
    PITCH,
    ROLL,
    L,
    L_DOT,
    FORCE,
    STOP_FORCE,
    AT_STOP,
    DET_J,
    COND_J,
    KINETIC_ENERGY,
    POTENTIAL_ENERGY,
    GRAVITY_COMPENSATION,
    DER_THETA,
    DER_OMEGA,
];

/// The whole table: inputs, outputs, state derivatives, parameters (value references
/// increasing).
pub static VARIABLES: [Decl; 23 + parameters::COUNT] =
    concat(&[&INPUTS_OUTPUTS, &parameters::PARAMETERS], INPUTS_OUTPUTS[0]);

/// The getter of the Real declaration `name`, if there is one.
pub fn real_getter(name: &str) -> Option<fn(&Pss3Plant, usize) -> f64> {
    VARIABLES.iter().find(|d| d.name == name).and_then(|d| match d.value {
        robofmu_fmi::core::declare::Value::Real { get, .. } => Some(get),
        _ => None,
    })
}
