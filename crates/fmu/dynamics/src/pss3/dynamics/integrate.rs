//! Co-simulation step: adaptive, error-controlled integration of the plant over one
//! communication step with the inputs held constant or following an [`InputRamp`],
//! landing exactly on its end.
//!
//! A trial stage that the model cannot evaluate (assembly lost, end stop in mode
//! `Error`, ...) returns NaN derivatives, which makes the solver reject the step and
//! retry with a smaller one; when it cannot get through, the step fails with the
//! solver's reason and the last model error. The caller's state is never modified.
//! The integrators ([`crate::ode`]) detect no stiffness: an engaged end stop is stiff,
//! and small explicit steps still integrate it correctly.

use super::error::DynamicsError;
use super::input_ramp::InputRamp;
use super::plant::{Plant, PlantInputs, PlantState};
use crate::ode;
use nalgebra::{SVector, Vector3};

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
    /// The integrator's settings: Hairer's defaults of the pair (safety 0.9; DOPRI5
    /// with the stabilised control, beta 0.04, step ratio 0.2 to 10; DOP853 with the
    /// classical one, 0.333 to 6), both tolerances `tolerance`.
    fn ode_settings(&self) -> ode::Settings {
        let base = match self.method {
            Method::Dopri5 => ode::Settings::dopri5(self.tolerance, self.max_step),
            Method::Dop853 => ode::Settings::dop853(self.tolerance, self.max_step),
        };
        ode::Settings {
            max_steps: self.max_internal_steps,
            ..base
        }
    }

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

/// The plant under its inputs, as an ODE right-hand side in the time since the step
/// start; remembers the last model error.
struct Flow<'a> {
    plant: &'a Plant,
    /// The inputs at the start of the step.
    inputs: PlantInputs,
    /// How they change over the step; None: held.
    ramp: Option<InputRamp>,
    last_error: Option<DynamicsError>,
}

impl Flow<'_> {
    /// The inputs `s` seconds into the step.
    fn inputs_at(&self, s: f64) -> PlantInputs {
        self.ramp
            .map_or(self.inputs, |ramp| ramp.inputs_at(&self.inputs, s))
    }

    /// Writes the state's derivative `s` seconds into the step into `dy`, NaN where the
    /// model cannot evaluate it.
    fn rates(&mut self, s: f64, y: &StateVector, dy: &mut StateVector) {
        if y.iter().any(|v| !v.is_finite()) {
            // A later stage of a step already spoiled by a model error: keep that error.
            dy.fill(f64::NAN);
            return;
        }
        match self
            .plant
            .derivative(&PlantState::from_vector(y), &self.inputs_at(s))
        {
            Ok(d) => {
                dy.fixed_rows_mut::<3>(0).copy_from(&d.euler_rates);
                dy.fixed_rows_mut::<3>(3).copy_from(&d.omega_dot);
            }
            Err(e) => {
                self.last_error = Some(e);
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
        let mut flow = Flow {
            plant: self,
            inputs: *inputs,
            ramp: (!ramp.is_held()).then_some(*ramp),
            last_error: None,
        };
        let end_inputs = flow.inputs_at(h);
        let ode_settings = settings.ode_settings();
        let rates = |s: f64, y: &StateVector, dy: &mut StateVector| flow.rates(s, y, dy);
        let end = match settings.method {
            Method::Dopri5 => ode::dopri5(rates, 0.0, h, state.to_vector(), &ode_settings),
            Method::Dop853 => ode::dop853(rates, 0.0, h, state.to_vector(), &ode_settings),
        };
        let end = match end {
            Ok(solution) if solution.y.iter().all(|v| v.is_finite()) => Ok(solution.y),
            Ok(_) => Err("the solver returned no finite end state".to_string()),
            Err(e) => Err(e.to_string()),
        };
        let end = end.map_err(|message| DynamicsError::Solver {
            message,
            cause: flow.last_error.map(Box::new),
        })?;
        // The last accepted point must itself be a valid state (Dop853 evaluates it
        // only after accepting the step).
        let end = PlantState::from_vector(&end);
        self.derivative(&end, &end_inputs)?;
        Ok(end)
    }
}
