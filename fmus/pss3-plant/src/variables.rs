//! The variable table of Pss3Plant, declared once (a `static` slice, see
//! `robofmu_fmi::core::declare`): the inputs, outputs and state derivatives here, the
//! parameters in `parameters.rs`. Every value reference is pinned (`.at`) at the one
//! it has always had: a vector variable's group (the second argument of `input` and
//! `vector`) plus i = 1..3.

use super::initial_dependencies as init;
use super::output_rates::{Output, output_derivative};
use super::{Pss3Plant, parameters};
use robofmu_dynamics::pss3::dynamics::PlantInputs;
use robofmu_fmi::core::declare::Access;
use robofmu_fmi::prelude::*;

type Decl = Declaration<Pss3Plant>;

// What outputs and state derivatives depend on (ModelStructure dependencies).
/// The continuous states (pose and angular velocity).
static STATES: [Var; 2] = [THETA.var(), OMEGA.var()];
/// The pose and the actuator commands (the realised actuator force).
static THETA_AND_COMMANDS: [Var; 4] = [
    THETA.var(),
    ACTUATOR_FORCE.var(),
    TORQUE_COMMAND.var(),
    GENERALIZED_FORCE_COMMAND.var(),
];
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

/// An input of three elements at `group + 1..3`, held or ramped over a step (input
/// derivatives up to order 2, kept where `ramp` says); its writer given after it.
const fn input(d: Decl, group: u32, unit: &'static str, ramp: InputDerivative<Pss3Plant>) -> Decl {
    let d = d.array(3).at(group + 1).input().unit(unit, None);
    d.start_real(&[0.0]).input_derivative(ramp)
}

/// A Real output of three elements at `group + 1..3`, its time derivatives of orders 1
/// and 2 from `rates` (`output_rates` serves every Real output).
const fn vector(d: Decl, group: u32, rates: OutputDerivative<Pss3Plant>) -> Decl {
    d.array(3)
        .at(group + 1)
        .output()
        .output_derivative(2, rates)
}

/// A scalar Real output at `vr`, its time derivatives of orders 1 and 2 from `rates`.
const fn scalar(d: Decl, vr: u32, rates: OutputDerivative<Pss3Plant>) -> Decl {
    d.at(vr).output().output_derivative(2, rates)
}

/// Euler angle `axis` of the current state times `sign` (the thesis's yaw, pitch, roll).
fn euler(m: &Pss3Plant, axis: usize, sign: f64) -> f64 {
    m.current_state().map_or(f64::NAN, |s| sign * s.euler[axis])
}

pub const ACTUATOR_FORCE: Decl = input(
    Decl::real_in("actuatorForce", |m, i| &mut m.inputs.forces[i])
        .describe("Force applied by actuator i along its axis u_i"),
    0,
    "N",
    |m, i, order| Some(&mut ramp(m, order)?.forces[i]),
);
pub const TORQUE_COMMAND: Decl = input(
    Decl::real_in("torqueCommand", |m, i| &mut m.inputs.commanded_torque[i])
        .describe("Commanded moment about P in {A}, realised by the actuators (f = J^-T tau)"),
    10,
    "N.m",
    |m, i, order| Some(&mut ramp(m, order)?.commanded_torque[i]),
);
pub const GENERALIZED_FORCE_COMMAND: Decl = input(
    Decl::real_in("generalizedForceCommand", |m, i| {
        &mut m.inputs.generalized_force[i]
    })
    .describe(
        "Commanded generalized force in Euler-angle coordinates (thx, thy, thz), \
         realised by the actuators (tau = E^-T Q, f = J^-T tau)",
    ),
    20,
    "N.m",
    |m, i, order| Some(&mut ramp(m, order)?.generalized_force[i]),
);
pub const DISTURBANCE_TORQUE: Decl = input(
    Decl::real_in("disturbanceTorque", |m, i| {
        &mut m.inputs.disturbance_torque[i]
    })
    .describe("External moment on the platform about P in {A} (not through the actuators)"),
    30,
    "N.m",
    |m, i, order| Some(&mut ramp(m, order)?.disturbance_torque[i]),
);
// A declaration's own list cannot name it (a const that refers to itself): theta and
// omega reach their lists through a function.
pub const THETA: Decl = vector(
    Decl::real(
        "theta",
        "Euler angle (thx, thy, thz) of R = Rz Ry Rx (continuous state)",
        |m, i| euler(m, i, 1.0),
    ),
    100,
    |m, i, n| output_derivative(m, Output::Theta, i, n),
)
.unit("rad", Some("deg"))
.depends_on_each(|_| &THETA_ITSELF)
.initial_depends_on_each(|i| &init::THETA[i]);
pub const OMEGA: Decl = vector(
    Decl::real(
        "omega",
        "Angular velocity of the platform in {A} (continuous state)",
        |m, i| m.current_state().map_or(f64::NAN, |s| s.omega[i]),
    ),
    110,
    |m, i, n| output_derivative(m, Output::Omega, i, n),
)
.unit("rad/s", Some("deg/s"))
.depends_on_each(|_| &OMEGA_ITSELF)
.initial_depends_on(&init::OMEGA);
pub const THETA_DOT: Decl = vector(
    Decl::real("thetaDot", "Euler-angle rate", |m, i| {
        m.computed(|c| c.euler_rates[i])
    }),
    120,
    |m, i, n| output_derivative(m, Output::ThetaDot, i, n),
)
.unit("rad/s", Some("deg/s"))
.depends_on(&STATES)
.initial_depends_on_each(init::theta_dot);
pub const OMEGA_DOT: Decl = vector(
    Decl::real(
        "omegaDot",
        "Angular acceleration of the platform in {A}",
        |m, i| m.output(|o| o.omega_dot[i]),
    ),
    130,
    |m, i, n| output_derivative(m, Output::OmegaDot, i, n),
)
.unit("rad/s2", Some("deg/s2"))
.depends_on(&STATES_AND_INPUTS)
.initial_depends_on(&init::ACCELERATION);
pub const YAW: Decl = scalar(
    Decl::real(
        "yaw",
        "Yaw: thx, the Euler angle about X of R = Rz(thz) Ry(thy) Rx(thx) (the source thesis's name, docs/3pss-model.md)",
        |m, _| euler(m, 0, 1.0),
    ),
    141,
    |m, _, n| output_derivative(m, Output::YawPitchRoll, 0, n),
)
.unit("rad", Some("deg"))
.depends_on(&[THETA.item(0)])
.initial_depends_on(&init::THETA[0]);
pub const PITCH: Decl = scalar(
    Decl::real(
        "pitch",
        "Pitch: -thy, the Euler angle about Y of R = Rz(thz) Ry(thy) Rx(thx) with its sign flipped (as the source thesis's tables print it, docs/3pss-model.md)",
        |m, _| euler(m, 1, -1.0),
    ),
    142,
    |m, _, n| output_derivative(m, Output::YawPitchRoll, 1, n),
)
.unit("rad", Some("deg"))
.depends_on(&[THETA.item(1)])
.initial_depends_on(&init::THETA[1]);
pub const ROLL: Decl = scalar(
    Decl::real(
        "roll",
        "Roll: thz, the Euler angle about Z of R = Rz(thz) Ry(thy) Rx(thx) (the source thesis's name, docs/3pss-model.md)",
        |m, _| euler(m, 2, 1.0),
    ),
    143,
    |m, _, n| output_derivative(m, Output::YawPitchRoll, 2, n),
)
.unit("rad", Some("deg"))
.depends_on(&[THETA.item(2)])
.initial_depends_on(&init::THETA[2]);
const L: Decl = vector(
    Decl::real("l", "Actuator displacement", |m, i| {
        m.output(|o| o.actuator_displacements[i])
    }),
    150,
    |m, i, n| output_derivative(m, Output::L, i, n),
)
.unit("m", Some("mm"))
.depends_on(&[THETA.var()])
.initial_depends_on(&init::POSE);
const L_DOT: Decl = vector(
    Decl::real("lDot", "Actuator velocity", |m, i| {
        m.output(|o| o.actuator_velocities[i])
    }),
    160,
    |m, i, n| output_derivative(m, Output::LDot, i, n),
)
.unit("m/s", None)
.depends_on(&STATES)
.initial_depends_on(&init::MOTION);
const FORCE: Decl = vector(
    Decl::real(
        "force",
        "Total actuator force from the inputs (actuatorForce plus the mapped commands), \
         without end-stop forces",
        |m, i| m.output(|o| o.actuator_forces[i]),
    ),
    170,
    |m, i, n| output_derivative(m, Output::Force, i, n),
)
.unit("N", None)
.depends_on(&THETA_AND_COMMANDS)
.initial_depends_on(&init::FORCE);
const STOP_FORCE: Decl = vector(
    Decl::real(
        "stopForce",
        "End-stop force on the actuator along u_i",
        |m, i| m.output(|o| o.end_stop_forces[i]),
    ),
    180,
    |m, i, n| output_derivative(m, Output::StopForce, i, n),
)
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
const DET_J: Decl = scalar(
    Decl::real(
        "detJ",
        "Determinant of the actuator Jacobian J (lDot = J omega)",
        |m, _| m.output(|o| o.jacobian_det),
    ),
    201,
    |m, _, n| output_derivative(m, Output::DetJ, 0, n),
)
.unit("m3", None)
.depends_on(&[THETA.var()])
.initial_depends_on(&init::POSE);
const COND_J: Decl = scalar(
    Decl::real("condJ", "2-norm condition number of J", |m, _| {
        m.output(|o| o.jacobian_cond)
    }),
    202,
    |m, _, n| output_derivative(m, Output::CondJ, 0, n),
)
.depends_on(&[THETA.var()])
.initial_depends_on(&init::POSE);
const KINETIC_ENERGY: Decl = scalar(
    Decl::real(
        "kineticEnergy",
        "Kinetic energy of platform, legs and sliders",
        |m, _| m.output(|o| o.kinetic_energy),
    ),
    203,
    |m, _, n| output_derivative(m, Output::KineticEnergy, 0, n),
)
.unit("J", None)
.depends_on(&STATES)
.initial_depends_on(&init::KINETIC_ENERGY);
const POTENTIAL_ENERGY: Decl = scalar(
    Decl::real(
        "potentialEnergy",
        "Potential energy of gravity (zero at the height of C) plus the energy in the \
         end-stop springs",
        |m, _| m.output(|o| o.potential_energy + o.end_stop_energy),
    ),
    204,
    |m, _, n| output_derivative(m, Output::PotentialEnergy, 0, n),
)
.unit("J", None)
.depends_on(&[THETA.var()])
.initial_depends_on(&init::POTENTIAL_ENERGY);
const GRAVITY_COMPENSATION: Decl = vector(
    Decl::real(
        "gravityCompensation",
        "Euler-angle generalized force G = E^T g(theta) that holds the current pose at \
         rest against gravity (feedforward for generalizedForceCommand)",
        |m, i| m.computed(|c| c.gravity_compensation[i]),
    ),
    210,
    |m, i, n| output_derivative(m, Output::GravityCompensation, i, n),
)
.unit("N.m", None)
.depends_on(&[THETA.var()])
.initial_depends_on_each(init::gravity_compensation);
pub const DER_THETA: Decl = Decl::real("der(theta)", "Euler-angle rate", |m, i| {
    m.computed(|c| c.euler_rates[i])
})
.array(3)
.at(301)
.derivative_of(THETA.name)
.unit("rad/s", Some("deg/s"))
.depends_on(&STATES)
.initial_depends_on_each(init::theta_dot);
pub const DER_OMEGA: Decl = Decl::real("der(omega)", "Angular acceleration in {A}", |m, i| {
    m.output(|o| o.omega_dot[i])
})
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
pub static VARIABLES: [Decl; 23 + parameters::COUNT] = concat(
    &[&INPUTS_OUTPUTS, &parameters::PARAMETERS],
    INPUTS_OUTPUTS[0],
);

/// The accessor of the Real declaration `name`, if there is one.
pub fn real_getter(name: &str) -> Option<Access<Pss3Plant, f64>> {
    VARIABLES
        .iter()
        .find(|d| d.name == name)
        .and_then(|d| match d.value {
            robofmu_fmi::core::declare::Value::Real { get, .. } => Some(get),
            _ => None,
        })
}
