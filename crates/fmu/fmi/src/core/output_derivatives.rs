//! Output derivatives of Co-Simulation (fmi2GetRealOutputDerivatives,
//! fmi3GetOutputDerivatives), independent of the FMI version: every request is checked
//! (a known Real output, an order from 1 to maxOutputDerivativeOrder) before the model
//! is asked, and nothing is returned unless every value is finite.

use super::instance::{Instance, variable};
use super::model::{Model, OutputDerivativeError};
use super::variables::{Causality, VariableType};

/// The derivative of order `order` of the table element `vr` (FMI 2.0 value reference),
/// or, with `element`, of that element of `vr`'s declaration (FMI 3.0: an array sized
/// by a structural parameter has elements past the FMI 2.0 table's).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Request {
    pub vr: u32,
    pub order: i32,
    pub element: Option<usize>,
}

/// The order once the requested variable is checked to be a Real output and the order
/// to be within 1 ..= maxOutputDerivativeOrder (names are formatted only for a refusal).
fn check<M: Model>(inst: &Instance<M>, r: Request) -> Result<u32, String> {
    let v = variable(inst.table(), r.vr)?;
    if v.causality != Causality::Output || v.variable_type() != VariableType::Real {
        return Err(format!(
            "\"{}\" (value reference {}) is not a Real output: only outputs have output \
             derivatives",
            v.name(),
            r.vr
        ));
    }
    let max = super::declare::max_output_derivative_order(M::VARIABLES);
    match u32::try_from(r.order) {
        Ok(order) if (1..=max).contains(&order) => Ok(order),
        _ if max == 0 => Err(format!(
            "{} provides no output derivatives (maxOutputDerivativeOrder=\"0\"); \
             asked for order {} of \"{}\"",
            M::INFO.model_name,
            r.order,
            v.name()
        )),
        _ => Err(format!(
            "order {} of \"{}\" is outside 1..{max} (maxOutputDerivativeOrder=\"{max}\")",
            r.order,
            v.name()
        )),
    }
}

/// Writes the derivatives of `requests` into `out` (same length) at the instance's
/// current time and state. Err: a request the FMU does not serve (the front-end
/// returns Error); Ok(Some(reason)): the model cannot be evaluated here (Discard, with
/// the time in the reason); Ok(None): done. Each message names the variable and the
/// order; `out` is written only when every value is finite.
pub fn output_derivatives<M: Model>(
    inst: &mut Instance<M>,
    requests: &[Request],
    out: &mut [f64],
) -> Result<Option<String>, String> {
    match evaluate(inst, requests) {
        Ok(values) => {
            out.copy_from_slice(&values);
            Ok(None)
        }
        Err(Refusal::Error(message)) => Err(message),
        Err(Refusal::Discard(reason)) => Ok(Some(format!("at t = {} s: {reason}", inst.time))),
    }
}

/// Why `evaluate` gave no values.
enum Refusal {
    Error(String),
    Discard(String),
}

/// The derivatives of `requests`, in order.
fn evaluate<M: Model>(inst: &mut Instance<M>, requests: &[Request]) -> Result<Vec<f64>, Refusal> {
    for &r in requests {
        check(inst, r).map_err(Refusal::Error)?;
    }
    if requests.is_empty() {
        return Ok(Vec::new());
    }
    inst.update_values()
        .map_err(|e| Refusal::Discard(format!("the outputs cannot be evaluated here: {e}")))?;
    let mut values = Vec::with_capacity(requests.len());
    for &r in requests {
        // Every request passed `check` above: its order is within 1..=max.
        let order = r.order as u32;
        let v = variable(inst.table(), r.vr).map_err(Refusal::Error)?;
        let index = r.element.unwrap_or(v.index);
        let name = super::variables::element_name(v.declaration, index);
        let what = || format!("derivative of order {order} of \"{name}\"");
        let value = match v.output_hook() {
            Some(f) => f(inst.model(), index, order),
            None => Err(OutputDerivativeError::NotProvided(format!(
                "{} declares no output derivatives for it",
                M::INFO.model_name
            ))),
        }
        .map_err(|e| match e {
            OutputDerivativeError::NotProvided(why) => {
                Refusal::Error(format!("{} is not provided: {why}", what()))
            }
            OutputDerivativeError::CannotEvaluate(why) => {
                Refusal::Discard(format!("{} cannot be evaluated here: {why}", what()))
            }
        })?;
        if !value.is_finite() {
            return Err(Refusal::Discard(format!("{} evaluates to {value}", what())));
        }
        values.push(value);
    }
    Ok(values)
}
