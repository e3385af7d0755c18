//! Rigid-body dynamics of the 3-PSS robot and the state-space plant an FMU wraps.
//!
//! Main formulation (Kane's method, omega coordinates), see `model`:
//!   M(q) omega_dot + c(q, omega) + g(q) = J^T (f + f_stop - c_s l_dot) + tau - c_P omega,
//! and its Euler-angle form M_x x_ddot + C x_dot + G = F (`euler_form`), the thesis's.
//! Independent cross-check: Lagrange's equations with exact dual-number derivatives of
//! the body positions (`lagrange`). Derivation and conventions: docs/3pss-dynamics.md.

mod dual;
mod end_stops;
mod error;
mod euler_form;
mod inertia;
mod input_ramp;
mod integrate;
pub mod lagrange;
mod legs;
mod linearize;
mod local_motion;
mod model;
mod outputs;
mod plant;

pub use end_stops::{EndStopMode, EndStops, StopContact, StopForce};
pub use error::{DynamicsError, PlantParamError};
pub use euler_form::{EulerAngleForm, euler_generalized_force};
pub use inertia::Inertia;
pub use input_ramp::InputRamp;
pub use integrate::{Method, StateVector, StepSettings};
pub use linearize::Linearization;
pub use local_motion::LocalMotion;
pub use model::{DEFAULT_GRAVITY, Model, Terms};
pub use outputs::PlantOutputs;
pub use plant::{Friction, Plant, PlantInputs, PlantParams, PlantState, StateDerivative};
