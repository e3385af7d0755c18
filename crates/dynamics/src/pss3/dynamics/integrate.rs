//! Co-simulation step: adaptive, error-controlled integration of the plant over one
//! communication step with the inputs held constant or following an [`InputRamp`],
//! landing exactly on its end.
//!
//! A trial stage that the model cannot evaluate (assembly lost, end stop in mode
//! `Error`, ...) returns NaN derivatives, which makes the solver reject the step and
//! retry with a smaller one; when it cannot get through, the step fails with the
//! solver's reason and the last model error. The caller's state is never modified.
//! The solver's stiffness detection is off: an engaged end stop is stiff, and small
//! explicit steps still integrate it correctly.

use super::error::DynamicsError;
use super::input_ramp::InputRamp;
use super::plant::{Plant, PlantInputs, PlantState};
use nalgebra::{SVector, Vector3};
use ode_solvers::{Dop853, Dopri5, OutputType, System};
use std::cell::RefCell;

/// The state as one vector: (thx, thy, thz, omega_x, omega_y, omega_z).
pub type StateVector = SVector<f64, 6>;

/// Which Runge-Kutta pair integrates the step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Dormand-Prince 5(4).
    Dopri5,
    /// Dormand-Prince 8(5,3), for tight tolerances.
    Dop853,
}

/// Integration settings of a communication step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepSettings {
    /// The Runge-Kutta pair.
    pub method: Method,
    /// Relative and absolute tolerance of the error control (rad, rad/s).
    pub tolerance: f64,
    /// Largest internal step, s.
    pub max_step: f64,
    /// Largest number of internal steps (accepted or rejected) per communication step.
    pub max_internal_steps: u32,
}

impl Default for StepSettings {
    fn default() -> Self {
        Self {
            method: Method::Dopri5,
            tolerance: 1e-8,
            max_step: 1e-2,
            max_internal_steps: 100_000,
        }
    }
}

impl StepSettings {
    fn validate(&self) -> Result<(), DynamicsError> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(DynamicsError::InvalidSetting("tolerance", self.tolerance));
        }
        if !(self.max_step.is_finite() && self.max_step > 0.0) {
            return Err(DynamicsError::InvalidSetting("max_step", self.max_step));
        }
        if self.max_internal_steps == 0 {
            return Err(DynamicsError::InvalidSetting("max_internal_steps", 0.0));
        }
        Ok(())
    }
}

impl PlantState {
    /// The state as one vector.
    pub fn to_vector(&self) -> StateVector {
        StateVector::new(
            self.euler.x,
            self.euler.y,
            self.euler.z,
            self.omega.x,
            self.omega.y,
            self.omega.z,
        )
    }

    /// The state from one vector.
    pub fn from_vector(v: &StateVector) -> Self {
        Self {
            euler: Vector3::new(v[0], v[1], v[2]),
            omega: Vector3::new(v[3], v[4], v[5]),
        }
    }
}

/// The plant under its inputs, as an ODE system in the time since the step start;
/// remembers the last model error.
struct Flow<'a> {
    plant: &'a Plant,
    /// The inputs at the start of the step.
    inputs: PlantInputs,
    /// How they change over the step; None: held.
    ramp: Option<InputRamp>,
    last_error: &'a RefCell<Option<DynamicsError>>,
}

impl Flow<'_> {
    /// The inputs `s` seconds into the step.
    fn inputs_at(&self, s: f64) -> PlantInputs {
        self.ramp
            .map_or(self.inputs, |ramp| ramp.inputs_at(&self.inputs, s))
    }
}

impl System<f64, StateVector> for Flow<'_> {
    fn system(&self, t: f64, y: &StateVector, dy: &mut StateVector) {
        if y.iter().any(|v| !v.is_finite()) {
            // A later stage of a step already spoiled by a model error: keep that error.
            dy.fill(f64::NAN);
            return;
        }
        match self
            .plant
            .derivative(&PlantState::from_vector(y), &self.inputs_at(t))
        {
            Ok(d) => {
                dy.fixed_rows_mut::<3>(0).copy_from(&d.euler_rates);
                dy.fixed_rows_mut::<3>(3).copy_from(&d.omega_dot);
            }
            Err(e) => {
                *self.last_error.borrow_mut() = Some(e);
                dy.fill(f64::NAN);
            }
        }
    }
}

impl Plant {
    /// The state after a communication step of `h` seconds from `state` with `inputs`
    /// held constant. On failure the reason is returned and `state` stays valid.
    pub fn advance(
        &self,
        state: &PlantState,
        inputs: &PlantInputs,
        h: f64,
        settings: &StepSettings,
    ) -> Result<PlantState, DynamicsError> {
        self.advance_with_ramp(state, inputs, &InputRamp::default(), h, settings)
    }

    /// As [`Plant::advance`], with the inputs starting at `inputs` and following
    /// `ramp` over the step (a held ramp integrates exactly as `advance`).
    pub fn advance_with_ramp(
        &self,
        state: &PlantState,
        inputs: &PlantInputs,
        ramp: &InputRamp,
        h: f64,
        settings: &StepSettings,
    ) -> Result<PlantState, DynamicsError> {
        settings.validate()?;
        if !(h.is_finite() && h >= 0.0) {
            return Err(DynamicsError::InvalidSetting("communication step", h));
        }
        self.derivative(state, inputs)?;
        if h == 0.0 {
            return Ok(*state);
        }
        let last_error = RefCell::new(None);
        let flow = Flow {
            plant: self,
            inputs: *inputs,
            ramp: (!ramp.is_held()).then_some(*ramp),
            last_error: &last_error,
        };
        let end_inputs = flow.inputs_at(h);
        let end = match settings.method {
            Method::Dopri5 => {
                let mut solver = Dopri5::from_param(
                    flow,
                    0.0,
                    h,
                    h,
                    state.to_vector(),
                    settings.tolerance,
                    settings.tolerance,
                    0.9,
                    0.04,
                    0.2,
                    10.0,
                    settings.max_step,
                    0.0,
                    settings.max_internal_steps,
                    u32::MAX,
                    OutputType::Sparse,
                );
                let outcome = solver.integrate();
                finish(outcome, solver.x_out(), solver.y_out())
            }
            Method::Dop853 => {
                let mut solver = Dop853::from_param(
                    flow,
                    0.0,
                    h,
                    h,
                    state.to_vector(),
                    settings.tolerance,
                    settings.tolerance,
                    0.9,
                    0.0,
                    0.333,
                    6.0,
                    settings.max_step,
                    0.0,
                    settings.max_internal_steps,
                    u32::MAX,
                    OutputType::Sparse,
                );
                let outcome = solver.integrate();
                finish(outcome, solver.x_out(), solver.y_out())
            }
        };
        let end = end.map_err(|message| DynamicsError::Solver {
            message,
            cause: last_error.into_inner().map(Box::new),
        })?;
        // The last accepted point must itself be a valid state (Dop853 evaluates it
        // only after accepting the step).
        let end = PlantState::from_vector(&end);
        self.derivative(&end, &end_inputs)?;
        Ok(end)
    }
}

/// The end state of a finished run, or why there is none.
fn finish<E: std::fmt::Display>(
    outcome: Result<ode_solvers::dop_shared::Stats, E>,
    times: &[f64],
    states: &[StateVector],
) -> Result<StateVector, String> {
    match outcome {
        Err(e) => Err(e.to_string()),
        Ok(_) => match (times.last(), states.last()) {
            (Some(_), Some(y)) if y.iter().all(|v| v.is_finite()) => Ok(*y),
            _ => Err("the solver returned no finite end state".to_string()),
        },
    }
}
