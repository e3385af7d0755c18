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

/// Geometry, and with it the forward kinematics of l0.
const GEOMETRY: [&str; 7] = ["lp", "ld", "gamma", "lb", "alpha", "beta", "a"];
/// The pose source besides theta0.
const FROM_ACTUATORS: [&str; 11] = concat(
    &[&["initFromActuators", "l0[1]", "l0[2]", "l0[3]"], &GEOMETRY],
    "",
);
/// The whole initial pose.
pub const POSE: [&str; 14] = concat(
    &[&["theta0[1]", "theta0[2]", "theta0[3]"], &FROM_ACTUATORS],
    "",
);
/// The pose and the initial angular velocity.
pub const MOTION: [&str; 17] = concat(&[&POSE, &["omega0[1]", "omega0[2]", "omega0[3]"]], "");
/// The end-stop constants.
const STOPS: [&str; 4] = [
    "strokeMin",
    "strokeMax",
    "endStopStiffness",
    "endStopDamping",
];
/// Masses and inertias of the kinetic energy.
const INERTIA: [&str; 10] = [
    "platformInertia[1,1]",
    "platformInertia[2,2]",
    "platformInertia[3,3]",
    "platformInertia[1,2]",
    "platformInertia[1,3]",
    "platformInertia[2,3]",
    "legMass",
    "legComFraction",
    "legTransverseInertia",
    "sliderMass",
];
/// What the gravity moment reads (the sliders run on fixed rails: their weight turns
/// no pose coordinate).
const GRAVITY: [&str; 5] = [
    "g",
    "platformMass",
    "platformCom[1]",
    "platformCom[2]",
    "platformCom[3]",
];
/// The commands mapped to actuator forces through J^-T and E^-T at the pose.
const COMMANDS: [&str; 6] = [
    "torqueCommand[1]",
    "torqueCommand[2]",
    "torqueCommand[3]",
    "generalizedForceCommand[1]",
    "generalizedForceCommand[2]",
    "generalizedForceCommand[3]",
];
const OTHER_INPUTS: [&str; 6] = [
    "actuatorForce[1]",
    "actuatorForce[2]",
    "actuatorForce[3]",
    "disturbanceTorque[1]",
    "disturbanceTorque[2]",
    "disturbanceTorque[3]",
];

pub static THETA: [[&str; 12]; 3] = [
    concat(&[&["theta0[1]"], &FROM_ACTUATORS], ""),
    concat(&[&["theta0[2]"], &FROM_ACTUATORS], ""),
    concat(&[&["theta0[3]"], &FROM_ACTUATORS], ""),
];
pub static OMEGA: [[&str; 1]; 3] = [["omega0[1]"], ["omega0[2]"], ["omega0[3]"]];
// thetaDot = E^-1(thy, thz) omega, row by row (R = Rz Ry Rx: no row reads thx, row 2
// neither thy nor omega_z).
static THETA_DOT_1: [&str; 15] = concat(
    &[
        &["theta0[2]", "theta0[3]", "omega0[1]", "omega0[2]"],
        &FROM_ACTUATORS,
    ],
    "",
);
static THETA_DOT_2: [&str; 14] = concat(
    &[&["theta0[3]", "omega0[1]", "omega0[2]"], &FROM_ACTUATORS],
    "",
);
static THETA_DOT_3: [&str; 16] = concat(
    &[
        &[
            "theta0[2]",
            "theta0[3]",
            "omega0[1]",
            "omega0[2]",
            "omega0[3]",
        ],
        &FROM_ACTUATORS,
    ],
    "",
);
pub static ACCELERATION: [&str; 50] = concat(
    &[
        &MOTION,
        &COMMANDS,
        &OTHER_INPUTS,
        &INERTIA,
        &GRAVITY,
        &["sliderFriction", "pivotFriction"],
        &STOPS,
    ],
    "",
);
pub static FORCE: [[&str; 21]; 3] = [
    concat(&[&POSE, &["actuatorForce[1]"], &COMMANDS], ""),
    concat(&[&POSE, &["actuatorForce[2]"], &COMMANDS], ""),
    concat(&[&POSE, &["actuatorForce[3]"], &COMMANDS], ""),
];
/// A pose from l0 lies within the strokes (forward kinematics refuses any other), where
/// the stops act on no actuator: l0 moves no stop force or flag.
const POSE_IN_A_STOP: [&str; 11] = concat(
    &[
        &["theta0[1]", "theta0[2]", "theta0[3]", "initFromActuators"],
        &GEOMETRY,
    ],
    "",
);
pub static STOP_FORCE: [&str; 18] = concat(
    &[
        &POSE_IN_A_STOP,
        &["omega0[1]", "omega0[2]", "omega0[3]"],
        &STOPS,
    ],
    "",
);
pub static AT_STOP: [&str; 13] = concat(&[&POSE_IN_A_STOP, &["strokeMin", "strokeMax"]], "");
pub static KINETIC_ENERGY: [&str; 27] = concat(&[&MOTION, &INERTIA], "");
pub static POTENTIAL_ENERGY: [&str; 25] = concat(
    &[
        &POSE,
        &GRAVITY,
        &[
            "legMass",
            "legComFraction",
            "sliderMass",
            "strokeMin",
            "strokeMax",
        ],
        &["endStopStiffness"],
    ],
    "",
);
static GRAVITY_COMPENSATION: [&str; 21] =
    concat(&[&POSE, &GRAVITY, &["legMass", "legComFraction"]], "");

/// Element i of thetaDot and der(theta).
pub fn theta_dot(i: usize) -> &'static [&'static str] {
    [&THETA_DOT_1[..], &THETA_DOT_2, &THETA_DOT_3][i]
}

/// Element i of gravityCompensation; the third depends on none: the moment of gravity
/// about the vertical axis of {A} (E's third column is that axis) is 0 in every pose.
pub fn gravity_compensation(i: usize) -> &'static [&'static str] {
    if i == 2 { &[] } else { &GRAVITY_COMPENSATION }
}
