//! What each initial unknown of ComputedTorque depends on at initialization
//! (ModelStructure InitialUnknowns `dependencies`); the knowns there are the inputs,
//! the parameters and the error integral's start value (all initial = "exact").
//!
//! u = clamp(M_x(theta) a + C theta_dot + G(theta) + F, uMin, uMax) with
//! a = q_ddot + Kd (q_dot - theta_dot) + Kp e + Ki I: the model's inertia M_x couples
//! the axes, so u[k] reads the gains, inputs and integral of every axis, and the limits
//! of its own axis only. Of the model parameters it reads all (geometry, masses,
//! inertias, friction, gravity) except where the gravity moment m g (R c) x (-z) has
//! no component along the axis of the Euler angle: u[3] (rate about the fixed z axis)
//! never sees gravity (g, platformMass, platformCom), and u[1] (rate about the
//! platform's own x axis R e_x) not the centre of mass's offset along that axis,
//! platformCom[1]. The integral's rate is e_k, or 0 across the anti-windup switch,
//! which reads everything u[k] reads: it lists the same. Checked against finite
//! differences at initialization in tests/python/test_initial_dependencies.py.

use robofmu::computed_torque::MODEL_PARAMETERS;
use std::sync::OnceLock;

/// The gains, inputs and integral of every axis.
const COUPLED: [&str; 27] = [
    "Kp[1]",
    "Kp[2]",
    "Kp[3]",
    "Kd[1]",
    "Kd[2]",
    "Kd[3]",
    "Ki[1]",
    "Ki[2]",
    "Ki[3]",
    "setpoint[1]",
    "setpoint[2]",
    "setpoint[3]",
    "setpointRate[1]",
    "setpointRate[2]",
    "setpointRate[3]",
    "setpointAcceleration[1]",
    "setpointAcceleration[2]",
    "setpointAcceleration[3]",
    "measurement[1]",
    "measurement[2]",
    "measurement[3]",
    "measuredRate[1]",
    "measuredRate[2]",
    "measuredRate[3]",
    "integral[1]",
    "integral[2]",
    "integral[3]",
];

/// The output limits of each axis.
const LIMITS: [[&str; 3]; 3] = [
    ["limitOutput[1]", "uMin[1]", "uMax[1]"],
    ["limitOutput[2]", "uMin[2]", "uMax[2]"],
    ["limitOutput[3]", "uMin[3]", "uMax[3]"],
];

/// The model parameters that do not move the output of each axis (see above).
const UNSEEN: [&[&str]; 3] = [
    &["platformCom[1]"],
    &[],
    &[
        "g",
        "platformMass",
        "platformCom[1]",
        "platformCom[2]",
        "platformCom[3]",
    ],
];

/// The knowns u[k + 1] and der(integral)[k + 1] depend on (k from 0).
pub fn of_axis(k: usize) -> &'static [&'static str] {
    static KNOWNS: OnceLock<[Vec<&'static str>; 3]> = OnceLock::new();
    &KNOWNS.get_or_init(|| std::array::from_fn(knowns))[k]
}

fn knowns(k: usize) -> Vec<&'static str> {
    let model = MODEL_PARAMETERS
        .iter()
        .map(|p| p.name)
        .filter(|name| !UNSEEN[k].contains(name));
    COUPLED
        .iter()
        .chain(&LIMITS[k])
        .copied()
        .chain(model)
        .collect()
}
