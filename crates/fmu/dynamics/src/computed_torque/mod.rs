//! Computed-torque control of the 3-PSS robot: inverse dynamics of a reference
//! acceleration plus PD (optionally PID) feedback on the tracking error, evaluated with
//! the controller's own model of the robot (a [`PlantParams`] that may differ from the
//! plant's, for model-mismatch studies).
//!
//! Law, per Euler angle k (e = q - theta, e_dot = q_dot - theta_dot, I = int e dt):
//!   a_k = q_ddot_k + Kd_k e_dot_k + Kp_k e_k + Ki_k I_k,
//!   u_raw = M_x(theta) a + C(theta, theta_dot) theta_dot + G(theta) + F_fric(theta, theta_dot),
//!   u = clamp(u_raw, u_min, u_max) per axis,
//! with M_x, C theta_dot and G the Euler-angle form of the robot library's rigid-body
//! model (`pss3::dynamics`, the plant's own equations) and F_fric the Euler-angle
//! generalized force that cancels the model's viscous friction. With a perfect model
//! and no saturation the plant's Euler angles obey exactly
//!   e_ddot + Kd e_dot + Kp e + Ki I = 0 on every axis, independently of the motion.
//!
//! Output: the generalized force in Euler-angle coordinates, N m, the plant's
//! `generalizedForceCommand` input. The PID drives the same input, so the two
//! controllers are interchangeable in a scenario without touching the plant, and the
//! law is written in the coordinates its error dynamics are placed in (the plant
//! realises u through tau = E^-T u and f = J^-T tau). Actuator forces would need the
//! controller to invert J itself for nothing in return.
//!
//! Force limits and anti-windup follow the PID: each axis's output is clamped to
//! [u_min, u_max], and its integral stops (conditional integration) while the output is
//! at a limit and Ki e would push it further out. End stops are not modelled by the
//! controller: they are the plant's protection, not a force a controller plans for.
//! Derivation and numbers: docs/computed-torque.md. The sampled (discrete-time) form,
//! evaluated at ticks with its output held between them: [`SampledComputedTorque`].
//!
//! [`PlantParams`]: crate::pss3::dynamics::PlantParams

mod gains;
mod jacobian;
mod law;
mod model_parameters;
mod sampled;

pub use gains::pole_placement;
pub use jacobian::{Known, LawJacobian};
pub use law::{AxisGains, ComputedTorque, ControllerError, Inputs, Output};
pub use model_parameters::{
    GEOMETRY, MODEL_PARAMETER_SPECS, MODEL_PARAMETERS, ModelParameter, controller_message,
    model_parameter, with_fmu_names,
};
pub use sampled::SampledComputedTorque;
