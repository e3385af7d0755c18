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

use super::variables::{
    INTEGRAL, KD, KI, KP, LIMIT, MEASURED_RATE, MEASUREMENT, SETPOINT, SETPOINT_ACCELERATION,
    SETPOINT_RATE, U_MAX, U_MIN,
};
use robofmu_dynamics::computed_torque::MODEL_PARAMETERS;
use robofmu_fmi::prelude::Var;

/// The gains, inputs and integral of every axis.
const COUPLED: [Var; 9] = [
    KP.var(),
    KD.var(),
    KI.var(),
    SETPOINT.var(),
    SETPOINT_RATE.var(),
    SETPOINT_ACCELERATION.var(),
    MEASUREMENT.var(),
    MEASURED_RATE.var(),
    INTEGRAL.var(),
];

/// The output limits of the axis itself.
const LIMITS: [Var; 3] = [LIMIT.same(), U_MIN.same(), U_MAX.same()];

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

/// How many knowns u[k + 1] lists.
const fn count(k: usize) -> usize {
    COUPLED.len() + LIMITS.len() + MODEL_PARAMETERS.len() - UNSEEN[k].len()
}

/// Static tables (no allocation: a per-load allocation would leak on every dlclose).
static AXIS_1: [Var; count(0)] = knowns(0);
static AXIS_2: [Var; count(1)] = knowns(1);
static AXIS_3: [Var; count(2)] = knowns(2);

/// The knowns u[k + 1] and der(integral)[k + 1] depend on (k from 0).
pub fn of_axis(k: usize) -> &'static [Var] {
    [&AXIS_1[..], &AXIS_2, &AXIS_3][k]
}

/// COUPLED, the limits of axis k + 1 and the model parameters but UNSEEN[k] (a model
/// parameter by the name the library's table gives it, the table its declaration is
/// made from).
const fn knowns<const N: usize>(k: usize) -> [Var; N] {
    let mut out = [Var::Time; N];
    let mut n = 0;
    let mut i = 0;
    while i < COUPLED.len() {
        out[n] = COUPLED[i];
        (n, i) = (n + 1, i + 1);
    }
    i = 0;
    while i < LIMITS.len() {
        out[n] = LIMITS[i];
        (n, i) = (n + 1, i + 1);
    }
    i = 0;
    while i < MODEL_PARAMETERS.len() {
        let name = MODEL_PARAMETERS[i].name;
        if !contains(UNSEEN[k], name) {
            out[n] = Var::Named(name);
            n += 1;
        }
        i += 1;
    }
    assert!(n == N, "every UNSEEN name is a model parameter");
    out
}

const fn contains(names: &[&str], name: &str) -> bool {
    let mut i = 0;
    while i < names.len() {
        if same(names[i].as_bytes(), name.as_bytes()) {
            return true;
        }
        i += 1;
    }
    false
}

const fn same(a: &[u8], b: &[u8]) -> bool {
    if a.len() != b.len() {
        return false;
    }
    let mut i = 0;
    while i < a.len() {
        if a[i] != b[i] {
            return false;
        }
        i += 1;
    }
    true
}
