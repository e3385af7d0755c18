//! The computed-torque law sampled every Ts seconds: evaluated only at ticks on the
//! inputs sampled there, its output held until the next tick (zero-order hold), its
//! error integral the exact integral of the held error (I_k+1 = I_k + Ts e_k), frozen
//! at a tick where the output is limited and Ki e_k pushes it further out (the
//! continuous law's conditional integration, decided at the tick). The continuous law
//! ([`ComputedTorque::output`], [`ComputedTorque::integral_rate`]) is unchanged; the
//! tick times come from a clock on an integer counter (robofmu_control::sampled).

use super::law::{ComputedTorque, ControllerError, Inputs, Output};
use crate::pss3::dynamics::DynamicsError;
use nalgebra::Vector3;

/// A computed-torque controller sampled every `period` seconds.
#[derive(Debug, Clone, PartialEq)]
pub struct SampledComputedTorque {
    law: ComputedTorque,
    period: f64,
    integral: Vector3<f64>,
    held: Option<Output>,
}

impl SampledComputedTorque {
    /// The sampled form of `law`, with a zero error integral and no output before its
    /// first tick.
    pub fn new(law: ComputedTorque, period: f64) -> Result<Self, ControllerError> {
        if !(period.is_finite() && period > 0.0) {
            return Err(ControllerError::SamplePeriod(period));
        }
        Ok(Self {
            law,
            period,
            integral: Vector3::zeros(),
            held: None,
        })
    }

    /// The law at a tick: the output from the error integral and the sampled inputs
    /// (held until the next tick), then the integral advanced over one period. On an
    /// error (inputs the model cannot evaluate) nothing changes.
    pub fn tick(&mut self, inputs: &Inputs) -> Result<Output, DynamicsError> {
        let out = self.law.output(&self.integral, inputs)?;
        self.integral += self.law.integral_rate(&out) * self.period;
        self.held = Some(out);
        Ok(out)
    }

    /// The output held since the last tick (None before the first).
    pub fn held(&self) -> Option<&Output> {
        self.held.as_ref()
    }

    /// The error integral the next tick starts from, rad s.
    pub fn integral(&self) -> &Vector3<f64> {
        &self.integral
    }

    /// The continuous law evaluated at the ticks.
    pub fn law(&self) -> &ComputedTorque {
        &self.law
    }

    /// The sample period, s.
    pub fn period(&self) -> f64 {
        self.period
    }
}
