//! Time derivatives of continuous inputs for the co-simulation step (FMI 2.0
//! fmi2SetRealInputDerivatives), checked here for every front-end and stored by the
//! model where the input's declaration says
//! ([`Declaration::input_derivative`](super::declare::Declaration::input_derivative)).
//!
//! Semantics (FMI 2.0, section 4.2.1: inputs and their derivatives are set with
//! respect to the beginning of a communication step): over a step from t, an input u
//! with derivatives u', u'' is u(t + s) = u + u' s + u'' s^2/2. A derivative holds
//! until it is set again (a master that passes slopes passes them before every step,
//! as FMPy does after each fmi2SetReal), is cleared by a reset, and is part of the FMU
//! state (restored by setting or deserializing a state). It changes neither the
//! input's value nor any output: outputs read after a step use the inputs as set.

use super::hooks::InputDerivative;
use super::instance::{Instance, MAX_MAGNITUDE, variable};
use super::model::Model;
use super::variables::{Causality, Kind, Variability, Variable};

/// Whether the variable can take input derivatives: a continuous Real input.
pub fn interpolated_input<M>(v: &Variable<M>) -> bool {
    v.causality == Causality::Input
        && v.variability == Variability::Continuous
        && matches!(v.kind, Kind::Real { .. })
}

/// Why `order` is not an input derivative order model M takes, if it is not (`name`
/// formats the input's name, for a refusal only).
fn check_order<M: Model>(name: impl Fn() -> String, order: i32) -> Result<u32, String> {
    let max = M::MAX_INPUT_DERIVATIVE_ORDER;
    if max == 0 {
        return Err(format!(
            "{} takes no input derivatives (its inputs are held over a step)",
            M::INFO.model_name
        ));
    }
    match u32::try_from(order) {
        Ok(o) if (1..=max).contains(&o) => Ok(o),
        _ if order < 1 => Err(format!(
            "order {order} for \"{}\" is not a derivative order (orders start at 1)",
            name()
        )),
        _ => Err(format!(
            "order {order} for \"{}\" is above {max}, the highest input derivative \
             order {} uses",
            name(),
            M::INFO.model_name
        )),
    }
}

impl<M: Model> Instance<M> {
    /// Sets the `order`-th time derivative of the continuous Real input `vr` after
    /// checking the value reference, the variable's kind, the order and the value
    /// (finite, within `MAX_MAGNITUDE`). Whether the call is legal now is the
    /// front-end's rule.
    pub fn set_input_derivative(&mut self, vr: u32, order: i32, value: f64) -> Result<(), String> {
        let v = variable(self.table(), vr)?;
        if !interpolated_input(v) {
            return Err(format!(
                "\"{}\" (value reference {vr}) is a {} {} {}, not a continuous Real input",
                v.name(),
                v.variability.as_str(),
                v.variable_type().as_str(),
                v.causality.as_str()
            ));
        }
        // The name is formatted for a refusal only (an array element's is built on
        // request): a master sets every input's derivatives every step.
        let name = || v.name().into_owned();
        let order = check_order::<M>(name, order)?;
        if !value.is_finite() || value.abs() > MAX_MAGNITUDE {
            return Err(format!(
                "derivative of order {order} of \"{}\" = {value:e} is not a finite number \
                 of magnitude at most {MAX_MAGNITUDE:e}",
                name()
            ));
        }
        let (hook, index) = (v.input_hook(), v.index);
        match slot(self.model_mut(), hook, index, order) {
            Some(slot) => *slot = value,
            None => {
                let name = variable(self.table(), vr)?.name().into_owned();
                return Err(no_slot::<M>(&name, order));
            }
        }
        Ok(())
    }
}

/// The slot of the `order`-th derivative of element `index` of an input: its
/// declaration's hook, if it has one.
pub fn slot<M: Model>(
    model: &mut M,
    hook: Option<InputDerivative<M>>,
    index: usize,
    order: u32,
) -> Option<&mut f64> {
    hook.and_then(|f| f(model, index, order))
}

/// The message for a model that declares an order but keeps no derivative for `name`.
fn no_slot<M: Model>(name: &str, order: u32) -> String {
    format!(
        "{} keeps no derivative of order {order} for \"{name}\"",
        M::INFO.model_name
    )
}
