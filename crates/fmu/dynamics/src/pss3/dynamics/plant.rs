//! The state-space plant that an FMU wraps: parameters, state, inputs and the state
//! derivative.
//!
//! State: Euler angles x = (thx, thy, thz) (rad) and the angular velocity omega in {A}
//! (rad/s). Euler angles because they are the thesis's and the controller's
//! coordinates, are minimal (no norm constraint to keep, unlike a quaternion) and the
//! workspace (|thy| < 12 deg) is far from their singularity at thy = +-90 deg; omega
//! because the equations of motion are simplest and best conditioned in it.

use super::end_stops::{EndStops, StopContact};
use super::error::{DynamicsError, PlantParamError};
use super::euler_form::euler_generalized_force;
use super::inertia::Inertia;
use super::model::{DEFAULT_GRAVITY, Model, Terms};
use crate::pss3::rotation::{euler_rates, moment_from_generalized_force};
use crate::pss3::{Geometry, Params};
use nalgebra::Vector3;

/// Viscous friction (default none).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Friction {
    /// On each slider, force -c l_dot, N s/m.
    pub slider: f64,
    /// At the spherical joint P, moment -c omega, N m s/rad.
    pub pivot: f64,
}

/// Every parameter of the plant, with the spec's defaults.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlantParams {
    /// Geometry (lengths, angles, stroke).
    pub geometry: Params,
    /// Masses and inertias.
    pub inertia: Inertia,
    /// Gravitational acceleration in {A}, m/s^2.
    pub gravity: Vector3<f64>,
    /// Viscous friction.
    pub friction: Friction,
    /// End-stop constants.
    pub end_stops: EndStops,
}

impl Default for PlantParams {
    fn default() -> Self {
        Self {
            geometry: Params::default(),
            inertia: Inertia::default(),
            gravity: DEFAULT_GRAVITY,
            friction: Friction::default(),
            end_stops: EndStops::default(),
        }
    }
}

/// The plant's continuous state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlantState {
    /// Euler angles (thx, thy, thz), rad.
    pub euler: Vector3<f64>,
    /// Angular velocity of the platform in {A}, rad/s.
    pub omega: Vector3<f64>,
}

/// The plant's inputs, held constant over a communication step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PlantInputs {
    /// Actuator forces f along u_i, N.
    pub forces: Vector3<f64>,
    /// Disturbance moment on the platform about P, in {A}, N m.
    pub disturbance_torque: Vector3<f64>,
    /// Commanded platform moment about P in {A}, N m, realised by the actuators through
    /// the statics f = J^-T tau and added to `forces`.
    pub commanded_torque: Vector3<f64>,
    /// Commanded generalized force in Euler-angle coordinates (the thesis controller's
    /// F = E^T tau), N m, realised as tau = E^-T F at the current orientation and then
    /// like `commanded_torque`.
    pub generalized_force: Vector3<f64>,
}

/// Time derivative of the state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StateDerivative {
    /// Euler-angle rates, rad/s.
    pub euler_rates: Vector3<f64>,
    /// Angular acceleration in {A}, rad/s^2.
    pub omega_dot: Vector3<f64>,
}

/// Everything computed in one evaluation of the plant (stack values only).
pub(super) struct Evaluation {
    pub terms: Terms,
    pub derivative: StateDerivative,
    pub actuator_rates: Vector3<f64>,
    pub actuator_forces: Vector3<f64>,
    pub stop_forces: Vector3<f64>,
    pub contacts: [StopContact; 3],
    /// Generalized force of every applied load (moment about P in {A}).
    pub applied: Vector3<f64>,
}

/// A validated plant.
#[derive(Debug, Clone, PartialEq)]
pub struct Plant {
    model: Model,
    friction: Friction,
    end_stops: EndStops,
}

impl Plant {
    /// Validates every parameter; invalid values are refused with a typed error.
    pub fn new(params: PlantParams) -> Result<Self, PlantParamError> {
        let geometry = Geometry::new(params.geometry)?;
        let model = Model::new(geometry, params.inertia, params.gravity)?;
        let friction = params.friction;
        for (name, v) in [
            ("slider_friction", friction.slider),
            ("pivot_friction", friction.pivot),
        ] {
            if !v.is_finite() {
                return Err(PlantParamError::NotFinite(name));
            }
            if v < 0.0 {
                return Err(PlantParamError::Negative(name, v));
            }
        }
        params.end_stops.validate()?;
        Ok(Self {
            model,
            friction,
            end_stops: params.end_stops,
        })
    }

    /// The rigid-body model.
    pub fn model(&self) -> &Model {
        &self.model
    }

    /// The viscous friction constants.
    pub fn friction(&self) -> &Friction {
        &self.friction
    }

    /// The end-stop constants.
    pub fn end_stops(&self) -> &EndStops {
        &self.end_stops
    }

    /// Stroke [min, max], m.
    pub(super) fn stroke(&self) -> (f64, f64) {
        let p = &self.model.geometry.params;
        (p.stroke_min, p.stroke_max)
    }

    /// A checked initial state: finite, assembled and (in mode `Error`) within the stroke.
    pub fn initial_state(
        &self,
        euler: Vector3<f64>,
        omega: Vector3<f64>,
    ) -> Result<PlantState, DynamicsError> {
        let state = PlantState { euler, omega };
        self.derivative(&state, &PlantInputs::default())?;
        Ok(state)
    }

    /// State derivative (x_dot, omega_dot). Allocation-free.
    pub fn derivative(
        &self,
        state: &PlantState,
        inputs: &PlantInputs,
    ) -> Result<StateDerivative, DynamicsError> {
        Ok(self.evaluate(state, inputs)?.derivative)
    }

    /// G_x = E^T g(theta): the generalized force in Euler-angle coordinates that holds
    /// the pose `euler` at rest against gravity (a controller's gravity feedforward).
    pub fn gravity_compensation(
        &self,
        euler: &Vector3<f64>,
    ) -> Result<Vector3<f64>, DynamicsError> {
        let terms = self.model.terms(euler, &Vector3::zeros())?;
        Ok(euler_generalized_force(euler, &terms.gravity))
    }

    /// Actuator forces that give the angular acceleration `omega_dot` at `state` under
    /// the disturbance moment `disturbance_torque` (inverse dynamics). Friction and end
    /// stops act as in `derivative`, so feeding the result back as `forces` returns
    /// `omega_dot`.
    pub fn inverse_dynamics(
        &self,
        state: &PlantState,
        omega_dot: &Vector3<f64>,
        disturbance_torque: &Vector3<f64>,
    ) -> Result<Vector3<f64>, DynamicsError> {
        if omega_dot.iter().any(|v| !v.is_finite()) {
            return Err(DynamicsError::NotFinite("angular acceleration"));
        }
        let inputs = PlantInputs {
            disturbance_torque: *disturbance_torque,
            ..PlantInputs::default()
        };
        let passive = self.evaluate(state, &inputs)?;
        let missing = passive.terms.required_force(omega_dot) - passive.applied;
        Ok(passive.terms.jacobian.forces(&missing)?)
    }

    pub(super) fn evaluate(
        &self,
        state: &PlantState,
        inputs: &PlantInputs,
    ) -> Result<Evaluation, DynamicsError> {
        check_finite(&state.euler, "orientation")?;
        check_finite(&state.omega, "angular velocity")?;
        check_finite(&inputs.forces, "actuator forces")?;
        check_finite(&inputs.disturbance_torque, "disturbance torque")?;
        check_finite(&inputs.commanded_torque, "commanded torque")?;
        check_finite(&inputs.generalized_force, "commanded generalized force")?;

        let terms = self.model.terms(&state.euler, &state.omega)?;
        let euler_rates = euler_rates(&state.euler, &state.omega)?;
        let actuator_rates = terms.jacobian.actuator_rates(&state.omega);
        let commanded_torque = if inputs.generalized_force == Vector3::zeros() {
            inputs.commanded_torque
        } else {
            inputs.commanded_torque
                + moment_from_generalized_force(&state.euler, &inputs.generalized_force)?
        };
        let actuator_forces = if commanded_torque == Vector3::zeros() {
            inputs.forces
        } else {
            inputs.forces + terms.jacobian.forces(&commanded_torque)?
        };

        let mut stop_forces = Vector3::zeros();
        let mut contacts = [StopContact::Free; 3];
        for i in 0..3 {
            let stop =
                self.end_stops
                    .force(i, terms.assembly.l[i], actuator_rates[i], self.stroke())?;
            stop_forces[i] = stop.force;
            contacts[i] = stop.contact;
        }
        let slider_forces = actuator_forces + stop_forces - self.friction.slider * actuator_rates;
        let applied = terms.jacobian.torque(&slider_forces) + inputs.disturbance_torque
            - self.friction.pivot * state.omega;
        let omega_dot = terms.angular_acceleration(&applied)?;
        Ok(Evaluation {
            terms,
            derivative: StateDerivative {
                euler_rates,
                omega_dot,
            },
            actuator_rates,
            actuator_forces,
            stop_forces,
            contacts,
            applied,
        })
    }
}

fn check_finite(v: &Vector3<f64>, what: &'static str) -> Result<(), DynamicsError> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(DynamicsError::NotFinite(what))
    }
}
