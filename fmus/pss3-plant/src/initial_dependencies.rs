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

use super::variables::concat;
use robofmu_fmi::prelude::Var;

/// Geometry, and with it the forward kinematics of l0.
const GEOMETRY: [Var; 7] = [
    Var::Named("lp"),
    Var::Named("ld"),
    Var::Named("gamma"),
    Var::Named("lb"),
    Var::Named("alpha"),
    Var::Named("beta"),
    Var::Named("a"),
];
/// The pose source besides theta0.
const FROM_ACTUATORS: [Var; 11] = concat(
    &[
        &[
            Var::Named("initFromActuators"),
            Var::Named("l0[1]"),
            Var::Named("l0[2]"),
            Var::Named("l0[3]"),
        ],
        &GEOMETRY,
    ],
    Var::Time,
);
/// The whole initial pose.
pub const POSE: [Var; 14] = concat(
    &[
        &[
            Var::Named("theta0[1]"),
            Var::Named("theta0[2]"),
            Var::Named("theta0[3]"),
        ],
        &FROM_ACTUATORS,
    ],
    Var::Time,
);
/// The pose and the initial angular velocity.
pub const MOTION: [Var; 17] = concat(
    &[
        &POSE,
        &[
            Var::Named("omega0[1]"),
            Var::Named("omega0[2]"),
            Var::Named("omega0[3]"),
        ],
    ],
    Var::Time,
);
/// The end-stop constants.
const STOPS: [Var; 4] = [
    Var::Named("strokeMin"),
    Var::Named("strokeMax"),
    Var::Named("endStopStiffness"),
    Var::Named("endStopDamping"),
];
/// Masses and inertias of the kinetic energy.
const INERTIA: [Var; 10] = [
    Var::Named("platformInertia[1,1]"),
    Var::Named("platformInertia[2,2]"),
    Var::Named("platformInertia[3,3]"),
    Var::Named("platformInertia[1,2]"),
    Var::Named("platformInertia[1,3]"),
    Var::Named("platformInertia[2,3]"),
    Var::Named("legMass"),
    Var::Named("legComFraction"),
    Var::Named("legTransverseInertia"),
    Var::Named("sliderMass"),
];
/// What the gravity moment reads (the sliders run on fixed rails: their weight turns
/// no pose coordinate).
const GRAVITY: [Var; 5] = [
    Var::Named("g"),
    Var::Named("platformMass"),
    Var::Named("platformCom[1]"),
    Var::Named("platformCom[2]"),
    Var::Named("platformCom[3]"),
];
/// The commands mapped to actuator forces through J^-T and E^-T at the pose.
const COMMANDS: [Var; 6] = [
    Var::Named("torqueCommand[1]"),
    Var::Named("torqueCommand[2]"),
    Var::Named("torqueCommand[3]"),
    Var::Named("generalizedForceCommand[1]"),
    Var::Named("generalizedForceCommand[2]"),
    Var::Named("generalizedForceCommand[3]"),
];
const OTHER_INPUTS: [Var; 6] = [
    Var::Named("actuatorForce[1]"),
    Var::Named("actuatorForce[2]"),
    Var::Named("actuatorForce[3]"),
    Var::Named("disturbanceTorque[1]"),
    Var::Named("disturbanceTorque[2]"),
    Var::Named("disturbanceTorque[3]"),
];

pub static THETA: [[Var; 12]; 3] = [
    concat(&[&[Var::Named("theta0[1]")], &FROM_ACTUATORS], Var::Time),
    concat(&[&[Var::Named("theta0[2]")], &FROM_ACTUATORS], Var::Time),
    concat(&[&[Var::Named("theta0[3]")], &FROM_ACTUATORS], Var::Time),
];
pub static OMEGA: [[Var; 1]; 3] = [
    [Var::Named("omega0[1]")],
    [Var::Named("omega0[2]")],
    [Var::Named("omega0[3]")],
];
// thetaDot = E^-1(thy, thz) omega, row by row (R = Rz Ry Rx: no row reads thx, row 2
// neither thy nor omega_z).
static THETA_DOT_1: [Var; 15] = concat(
    &[
        &[
            Var::Named("theta0[2]"),
            Var::Named("theta0[3]"),
            Var::Named("omega0[1]"),
            Var::Named("omega0[2]"),
        ],
        &FROM_ACTUATORS,
    ],
    Var::Time,
);
static THETA_DOT_2: [Var; 14] = concat(
    &[
        &[
            Var::Named("theta0[3]"),
            Var::Named("omega0[1]"),
            Var::Named("omega0[2]"),
        ],
        &FROM_ACTUATORS,
    ],
    Var::Time,
);
static THETA_DOT_3: [Var; 16] = concat(
    &[
        &[
            Var::Named("theta0[2]"),
            Var::Named("theta0[3]"),
            Var::Named("omega0[1]"),
            Var::Named("omega0[2]"),
            Var::Named("omega0[3]"),
        ],
        &FROM_ACTUATORS,
    ],
    Var::Time,
);
pub static ACCELERATION: [Var; 50] = concat(
    &[
        &MOTION,
        &COMMANDS,
        &OTHER_INPUTS,
        &INERTIA,
        &GRAVITY,
        &[Var::Named("sliderFriction"), Var::Named("pivotFriction")],
        &STOPS,
    ],
    Var::Time,
);
pub static FORCE: [[Var; 21]; 3] = [
    concat(
        &[&POSE, &[Var::Named("actuatorForce[1]")], &COMMANDS],
        Var::Time,
    ),
    concat(
        &[&POSE, &[Var::Named("actuatorForce[2]")], &COMMANDS],
        Var::Time,
    ),
    concat(
        &[&POSE, &[Var::Named("actuatorForce[3]")], &COMMANDS],
        Var::Time,
    ),
];
/// A pose from l0 lies within the strokes (forward kinematics refuses any other), where
/// the stops act on no actuator: l0 moves no stop force or flag.
const POSE_IN_A_STOP: [Var; 11] = concat(
    &[
        &[
            Var::Named("theta0[1]"),
            Var::Named("theta0[2]"),
            Var::Named("theta0[3]"),
            Var::Named("initFromActuators"),
        ],
        &GEOMETRY,
    ],
    Var::Time,
);
pub static STOP_FORCE: [Var; 18] = concat(
    &[
        &POSE_IN_A_STOP,
        &[
            Var::Named("omega0[1]"),
            Var::Named("omega0[2]"),
            Var::Named("omega0[3]"),
        ],
        &STOPS,
    ],
    Var::Time,
);
pub static AT_STOP: [Var; 13] = concat(
    &[
        &POSE_IN_A_STOP,
        &[Var::Named("strokeMin"), Var::Named("strokeMax")],
    ],
    Var::Time,
);
pub static KINETIC_ENERGY: [Var; 27] = concat(&[&MOTION, &INERTIA], Var::Time);
pub static POTENTIAL_ENERGY: [Var; 25] = concat(
    &[
        &POSE,
        &GRAVITY,
        &[
            Var::Named("legMass"),
            Var::Named("legComFraction"),
            Var::Named("sliderMass"),
            Var::Named("strokeMin"),
            Var::Named("strokeMax"),
        ],
        &[Var::Named("endStopStiffness")],
    ],
    Var::Time,
);
static GRAVITY_COMPENSATION: [Var; 21] = concat(
    &[
        &POSE,
        &GRAVITY,
        &[Var::Named("legMass"), Var::Named("legComFraction")],
    ],
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
