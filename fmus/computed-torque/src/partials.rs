//! Directional derivatives (fmi2GetDirectionalDerivative, fmi3GetDirectionalDerivative,
//! fmi3GetAdjointDerivative) and the output's first time derivative, from the law's
//! Jacobian (`ComputedTorque::jacobian`: exact in the planned motion and the integral,
//! the measured rates exact up to rounding, the measured angles by Richardson-
//! extrapolated central differences, about 1e-9 relative), computed once per call.

use super::ComputedTorqueFmu;
use super::variables::{
    DER_INTEGRAL, INTEGRAL, MEASURED_RATE, MEASUREMENT, SETPOINT, SETPOINT_ACCELERATION,
    SETPOINT_RATE, U,
};
use robofmu_dynamics::computed_torque::{ComputedTorque, Known, LawJacobian};
use robofmu_fmi::prelude::*;

/// The unknowns: the output or the integral's rate.
#[derive(Clone, Copy)]
enum Unknown {
    Output,
    IntegralRate,
}

const UNKNOWNS: [(Declaration<ComputedTorqueFmu>, Unknown); 2] =
    [(U, Unknown::Output), (DER_INTEGRAL, Unknown::IntegralRate)];
const KNOWNS: [(Declaration<ComputedTorqueFmu>, Known); 6] = [
    (SETPOINT, Known::Setpoint),
    (SETPOINT_RATE, Known::SetpointRate),
    (SETPOINT_ACCELERATION, Known::SetpointAcceleration),
    (MEASUREMENT, Known::Measurement),
    (MEASURED_RATE, Known::MeasuredRate),
    (INTEGRAL, Known::Integral),
];

impl ComputedTorqueFmu {
    /// Runs `f` with the law for the current parameters (built when the layer has not
    /// built it yet), or says why there is none.
    fn with_law<T>(&self, f: impl FnOnce(&ComputedTorque) -> T) -> Result<T, String> {
        match &self.law {
            Some(law) => Ok(f(law)),
            None => Ok(f(&self.build_law()?)),
        }
    }

    /// The law's Jacobian at the current inputs and integral.
    fn jacobian(&self) -> Result<LawJacobian, String> {
        self.with_law(|law| law.jacobian(&self.integral, &self.inputs))?
            .map_err(|e| format!("the law cannot be differentiated here: {e}"))
    }
}

/// dvUnknown = J dvKnown for the unknowns and knowns given.
pub fn directional_derivative(
    m: &ComputedTorqueFmu,
    unknowns: &[Element],
    knowns: &[Element],
    seed: &[f64],
    out: &mut [f64],
) -> Result<(), String> {
    let roles = unknowns
        .iter()
        .map(|u| u.role_in(&UNKNOWNS, "an output or state derivative"))
        .collect::<Result<Vec<_>, _>>()?;
    let columns = knowns
        .iter()
        .map(|k| k.role_in(&KNOWNS, "an input or state"))
        .collect::<Result<Vec<_>, _>>()?;
    let jacobian = m.jacobian()?;
    for ((o, &unknown), role) in out.iter_mut().zip(unknowns).zip(roles) {
        *o = columns
            .iter()
            .zip(knowns)
            .zip(seed)
            .map(|((&known, element), &s)| {
                let block = match role {
                    Unknown::Output => jacobian.output(known),
                    Unknown::IntegralRate => jacobian.integral_rate(known),
                };
                block[(unknown.index, element.index)] * s
            })
            .sum();
    }
    Ok(())
}
