//! What each initial unknown of Pss3Plant depends on at initialization
//! (ModelStructure InitialUnknowns `dependencies`): the knowns there are the inputs and
//! the parameters (all initial = "exact").
//!
//! The initial state is theta0 (or, with initFromActuators, the forward kinematics of l0
//! in the geometry) and omega0; every output is then a function of that state, the
//! inputs and the parameters its formula reads. Checked against finite differences at
//! initialization in tests/python/test_initial_dependencies.py. Not listed because no
//! initial value depends on them: tolerance and maxStep (integration only) and
//! endStopMode (it decides whether a pose beyond a stroke end is accepted, not a
//! value).

use super::parameters::{
    END_STOP_DAMPING, END_STOP_STIFFNESS, G, GEOMETRY, INIT_FROM_ACTUATORS, L0, LEG_COM_FRACTION,
    LEG_MASS, LEG_TRANSVERSE_INERTIA, OMEGA0, PIVOT_FRICTION, PLATFORM_COM, PLATFORM_INERTIA,
    PLATFORM_MASS, SLIDER_FRICTION, SLIDER_MASS, STROKE_MAX, STROKE_MIN, THETA0,
};
use super::variables::{
    ACTUATOR_FORCE, DISTURBANCE_TORQUE, GENERALIZED_FORCE_COMMAND, TORQUE_COMMAND,
};
use robofmu_fmi::prelude::{Var, concat, every};

/// The pose source besides theta0: l0 and, for its forward kinematics, the geometry.
const FROM_ACTUATORS: [Var; 9] = concat(
    &[&[INIT_FROM_ACTUATORS.var(), L0.var()], &every(&GEOMETRY)],
    Var::Time,
);
/// The whole initial pose.
pub const POSE: [Var; 10] = concat(&[&[THETA0.var()], &FROM_ACTUATORS], Var::Time);
/// The pose and the initial angular velocity.
pub const MOTION: [Var; 11] = concat(&[&POSE, &[OMEGA0.var()]], Var::Time);
/// The end-stop constants.
const STOPS: [Var; 4] = [
    STROKE_MIN.var(),
    STROKE_MAX.var(),
    END_STOP_STIFFNESS.var(),
    END_STOP_DAMPING.var(),
];
/// Masses and inertias of the kinetic energy.
const INERTIA: [Var; 10] = concat(
    &[
        &every(&PLATFORM_INERTIA),
        &[
            LEG_MASS.var(),
            LEG_COM_FRACTION.var(),
            LEG_TRANSVERSE_INERTIA.var(),
            SLIDER_MASS.var(),
        ],
    ],
    Var::Time,
);
/// What the gravity moment reads (the sliders run on fixed rails: their weight turns
/// no pose coordinate).
const GRAVITY: [Var; 3] = [G.var(), PLATFORM_MASS.var(), PLATFORM_COM.var()];
/// The commands mapped to actuator forces through J^-T and E^-T at the pose.
const COMMANDS: [Var; 2] = [TORQUE_COMMAND.var(), GENERALIZED_FORCE_COMMAND.var()];

/// Element i of theta (and yaw, pitch, roll): theta0[i] or the pose from l0.
pub static THETA: [[Var; 10]; 3] = [
    concat(&[&[THETA0.item(0)], &FROM_ACTUATORS], Var::Time),
    concat(&[&[THETA0.item(1)], &FROM_ACTUATORS], Var::Time),
    concat(&[&[THETA0.item(2)], &FROM_ACTUATORS], Var::Time),
];
pub static OMEGA: [Var; 1] = [OMEGA0.same()];
// thetaDot = E^-1(thy, thz) omega, row by row (R = Rz Ry Rx: no row reads thx, row 2
// neither thy nor omega_z).
static THETA_DOT_1: [Var; 13] = concat(
    &[
        &[
            THETA0.item(1),
            THETA0.item(2),
            OMEGA0.item(0),
            OMEGA0.item(1),
        ],
        &FROM_ACTUATORS,
    ],
    Var::Time,
);
static THETA_DOT_2: [Var; 12] = concat(
    &[
        &[THETA0.item(2), OMEGA0.item(0), OMEGA0.item(1)],
        &FROM_ACTUATORS,
    ],
    Var::Time,
);
static THETA_DOT_3: [Var; 12] = concat(
    &[
        &[THETA0.item(1), THETA0.item(2), OMEGA0.var()],
        &FROM_ACTUATORS,
    ],
    Var::Time,
);
pub static ACCELERATION: [Var; 34] = concat(
    &[
        &MOTION,
        &COMMANDS,
        &[ACTUATOR_FORCE.var(), DISTURBANCE_TORQUE.var()],
        &INERTIA,
        &GRAVITY,
        &[SLIDER_FRICTION.var(), PIVOT_FRICTION.var()],
        &STOPS,
    ],
    Var::Time,
);
/// Element i of force: the pose, actuatorForce[i] and the commands.
pub static FORCE: [Var; 13] = concat(&[&POSE, &[ACTUATOR_FORCE.same()], &COMMANDS], Var::Time);
/// A pose from l0 lies within the strokes (forward kinematics refuses any other), where
/// the stops act on no actuator: l0 moves no stop force or flag.
const POSE_IN_A_STOP: [Var; 9] = concat(
    &[
        &[THETA0.var(), INIT_FROM_ACTUATORS.var()],
        &every(&GEOMETRY),
    ],
    Var::Time,
);
pub static STOP_FORCE: [Var; 14] = concat(&[&POSE_IN_A_STOP, &[OMEGA0.var()], &STOPS], Var::Time);
pub static AT_STOP: [Var; 11] = concat(
    &[&POSE_IN_A_STOP, &[STROKE_MIN.var(), STROKE_MAX.var()]],
    Var::Time,
);
pub static KINETIC_ENERGY: [Var; 21] = concat(&[&MOTION, &INERTIA], Var::Time);
pub static POTENTIAL_ENERGY: [Var; 19] = concat(
    &[
        &POSE,
        &GRAVITY,
        &[
            LEG_MASS.var(),
            LEG_COM_FRACTION.var(),
            SLIDER_MASS.var(),
            STROKE_MIN.var(),
            STROKE_MAX.var(),
            END_STOP_STIFFNESS.var(),
        ],
    ],
    Var::Time,
);
static GRAVITY_COMPENSATION: [Var; 15] = concat(
    &[&POSE, &GRAVITY, &[LEG_MASS.var(), LEG_COM_FRACTION.var()]],
    Var::Time,
);

/// Element i of thetaDot and der(theta).
pub fn theta_dot(i: usize) -> &'static [Var] {
    [&THETA_DOT_1[..], &THETA_DOT_2, &THETA_DOT_3][i]
}

/// Element i of gravityCompensation; the third depends on none: the moment of gravity
/// about the vertical axis of {A} (E's third column is that axis) is 0 in every pose.
pub fn gravity_compensation(i: usize) -> &'static [Var] {
    if i == 2 { &[] } else { &GRAVITY_COMPENSATION }
}
