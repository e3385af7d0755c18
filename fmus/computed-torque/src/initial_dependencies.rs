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
    FRICTION, G, GEOMETRY, INTEGRAL, KD, KI, KP, LEGS_AND_SLIDERS, LIMIT, MEASURED_RATE,
    MEASUREMENT, PLATFORM_COM, PLATFORM_INERTIA, PLATFORM_MASS, SETPOINT, SETPOINT_ACCELERATION,
    SETPOINT_RATE, U_MAX, U_MIN,
};
use robofmu_fmi::prelude::{Var, concat, every};

/// The gains, inputs and integral of every axis, and the output limits of the axis
/// itself.
const LAW: [Var; 12] = [
    KP.var(),
    KD.var(),
    KI.var(),
    SETPOINT.var(),
    SETPOINT_RATE.var(),
    SETPOINT_ACCELERATION.var(),
    MEASUREMENT.var(),
    MEASURED_RATE.var(),
    INTEGRAL.var(),
    LIMIT.same(),
    U_MIN.same(),
    U_MAX.same(),
];

/// The model parameters every axis reads: all but the gravity moment's (g,
/// platformMass, platformCom).
const MODEL: [Var; 19] = concat(
    &[
        &every(&GEOMETRY),
        &every(&PLATFORM_INERTIA),
        &every(&LEGS_AND_SLIDERS),
        &every(&FRICTION),
    ],
    Var::Time,
);

/// Static tables (no allocation: a per-load allocation would leak on every dlclose).
/// u[1]: the gravity moment but platformCom[1].
static AXIS_1: [Var; 35] = concat(
    &[
        &LAW,
        &MODEL,
        &[
            G.var(),
            PLATFORM_MASS.var(),
            PLATFORM_COM.item(1),
            PLATFORM_COM.item(2),
        ],
    ],
    Var::Time,
);
/// u[2]: every model parameter.
static AXIS_2: [Var; 34] = concat(
    &[
        &LAW,
        &MODEL,
        &[G.var(), PLATFORM_MASS.var(), PLATFORM_COM.var()],
    ],
    Var::Time,
);
/// u[3]: no gravity.
static AXIS_3: [Var; 31] = concat(&[&LAW, &MODEL], Var::Time);

/// The knowns u[k + 1] and der(integral)[k + 1] depend on (k from 0).
pub fn of_axis(k: usize) -> &'static [Var] {
    [&AXIS_1[..], &AXIS_2, &AXIS_3][k]
}
