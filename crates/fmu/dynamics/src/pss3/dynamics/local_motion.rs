//! The plant's motion near one instant, inputs held, to second order in time, and the
//! first two time derivatives of any smooth function of the state along it (what an
//! FMU's output derivatives need).
//!
//! For y(t) = h(x(t)) with x' = f(x, u), u held: y' = Dh[x'] and
//! y'' = D^2h[x', x'] + Dh[x'']. Both involve x only up to second order, so they are the
//! derivatives at s = 0 of h along the curve x + x' s + x'' s^2 / 2 (`LocalMotion::at`):
//! exact up to the accuracy of x'' and of the differences taken along that curve.
//! - x' = f(x, u): the dynamics, exact.
//! - x'': of the Euler angles exact (`euler_accelerations`, E^-1 (omega' - E' theta'));
//!   of omega, Df[x'] by central differences of the dynamics along x'.
//! - The derivatives of h along the curve: central differences with one Richardson
//!   extrapolation, D = (4 D(s/2) - D(s)) / 3 (truncation O(s^4)), five evaluations of
//!   h. The step s is `STEP` over the motion's rate scale 1 + |x'| + sqrt(|x''|) (max
//!   norms), so that the state moves by about `STEP` (rad, rad/s) whatever the speed.
//!
//! Accuracy: about 1e-9 relative for smooth h (measured against differences along the
//! integrated trajectory in fmus/pss3-plant/tests/output_derivatives.rs). In contact
//! with an end stop the stiff spring (1e6 N/m by default) amplifies the rounding of l
//! in the stop force and hence in omega' : the second derivatives of the
//! accelerations and stop forces are good to about 1e-2 relative there (measured: they
//! vary by 5e-3 with the step).
//! Where the motion is not smooth (an end stop's edge within s of the state: its spring
//! and damper start there) the result is the average slope across the edge.

use super::error::DynamicsError;
use super::plant::{Plant, PlantInputs, PlantState, StateDerivative};
use crate::pss3::rotation::euler_accelerations;
use nalgebra::Vector3;
use std::ops::{Add, Mul, Sub};

/// Step of the differences in units of the motion's time scale. Rounding grows as
/// eps / STEP^2 (second derivative, 1e-11 here), truncation as STEP^4 (3e-10; 3e-6
/// where the rate scale underestimates the motion's 10-fold, as in a stiff stop).
const STEP: f64 = 4e-3;

/// The state, its rate and its acceleration at one instant, inputs held.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LocalMotion {
    pub state: PlantState,
    /// x' (Euler-angle rates, angular acceleration).
    pub rate: StateDerivative,
    /// x'' (Euler-angle accelerations, derivative of the angular acceleration).
    pub acceleration: StateDerivative,
}

impl Plant {
    /// The local motion at `state` under held `inputs` (see the module doc).
    pub fn local_motion(
        &self,
        state: &PlantState,
        inputs: &PlantInputs,
    ) -> Result<LocalMotion, DynamicsError> {
        let rate = self.derivative(state, inputs)?;
        let theta_ddot = euler_accelerations(&state.euler, &rate.euler_rates, &rate.omega_dot)?;
        let first_order = LocalMotion {
            state: *state,
            rate,
            acceleration: StateDerivative {
                euler_rates: theta_ddot,
                omega_dot: Vector3::zeros(),
            },
        };
        // Along x + x' s the omega part of the curvature does not matter to first order.
        let [omega_ddot, _] =
            first_order.derivatives(|x| self.derivative(x, inputs).map(|d| d.omega_dot))?;
        Ok(LocalMotion {
            acceleration: StateDerivative {
                omega_dot: omega_ddot,
                ..first_order.acceleration
            },
            ..first_order
        })
    }
}

/// The largest absolute component of `d`.
fn largest(d: &StateDerivative) -> f64 {
    d.euler_rates.amax().max(d.omega_dot.amax())
}

impl LocalMotion {
    /// The state at time s from now along the second-order curve.
    pub fn at(&self, s: f64) -> PlantState {
        let (r, a) = (&self.rate, &self.acceleration);
        PlantState {
            euler: self.state.euler + r.euler_rates * s + a.euler_rates * (0.5 * s * s),
            omega: self.state.omega + r.omega_dot * s + a.omega_dot * (0.5 * s * s),
        }
    }

    /// The time step of the differences, s.
    pub fn step(&self) -> f64 {
        STEP / (1.0 + largest(&self.rate) + largest(&self.acceleration).sqrt())
    }

    /// The first and second time derivatives of `h` along the motion (see the module
    /// doc). `h` may be vector valued.
    pub fn derivatives<V, E>(
        &self,
        mut h: impl FnMut(&PlantState) -> Result<V, E>,
    ) -> Result<[V; 2], E>
    where
        V: Copy + Add<Output = V> + Sub<Output = V> + Mul<f64, Output = V>,
    {
        let s = self.step();
        let mut g = |s: f64| h(&self.at(s));
        let (centre, near, far) = (g(0.0)?, [g(-0.5 * s)?, g(0.5 * s)?], [g(-s)?, g(s)?]);
        let first = |[minus, plus]: [V; 2], s: f64| (plus - minus) * (0.5 / s);
        let second =
            |[minus, plus]: [V; 2], s: f64| (plus + minus - centre * 2.0) * (1.0 / (s * s));
        let richardson = |fine: V, coarse: V| (fine * 4.0 - coarse) * (1.0 / 3.0);
        Ok([
            richardson(first(near, 0.5 * s), first(far, s)),
            richardson(second(near, 0.5 * s), second(far, s)),
        ])
    }
}
