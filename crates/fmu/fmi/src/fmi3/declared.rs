//! The FMI 3.0 view of a declared model: one [`Variable3`] per [`Declaration`], taken
//! from the declaration as it is (a scalar, or an array with its length), without
//! parsing names or descriptions.

use super::table::{
    Source, TIME_VALUE_REFERENCE, Table3, Variable3, event_indicator_variable, time_variable,
};
use crate::core::declare::{Declaration, Value, value_references};
use crate::core::model::Model;
use crate::core::variables::{
    Causality, Initial, Variability, Variable, VariableType, derivative_variables,
};
use std::borrow::Cow;

/// The FMI 3.0 view of model M, whose instance holds the flattened `table`.
pub fn view<M: Model>(table: &[Variable<M>]) -> Result<Table3, String> {
    if table
        .iter()
        .any(|v| v.value_reference == TIME_VALUE_REFERENCE)
    {
        return Err(format!(
            "value reference {TIME_VALUE_REFERENCE} is reserved for time in FMI 3.0"
        ));
    }
    let declarations = M::VARIABLES;
    let firsts = value_references(declarations);
    crate::core::structural::check::<M>()?;
    let mut variables = Vec::with_capacity(declarations.len() + 2);
    variables.push(time_variable());
    variables.extend(structural_variables::<M>());
    for (position, &first) in firsts.iter().enumerate() {
        variables.push(variable3(declarations, &firsts, position, first)?);
    }
    let n_indicators = M::INFO.number_of_event_indicators;
    if n_indicators > 0 {
        let last = table.iter().map(|v| v.value_reference).max().unwrap_or(0);
        variables.push(event_indicator_variable(last + 1, n_indicators));
    }
    variables.extend(clock_variables::<M>());
    check_state_order(table, &variables)?;
    let mut references: Vec<u32> = variables.iter().map(|v| v.value_reference).collect();
    references.sort_unstable();
    if let Some(w) = references.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!(
            "value reference {} is used twice (a clock's or structural parameter's variable and another)",
            w[0]
        ));
    }
    Ok(Table3::new(variables))
}

/// The variables of the model's clocked partitions (FMI 3.0 only): per input clock,
/// the clock, its period parameter and its outputs.
fn clock_variables<M: Model>() -> impl Iterator<Item = Variable3> {
    M::CLOCKS.iter().enumerate().flat_map(|(k, c)| {
        let clock = Variable3 {
            value_reference: c.value_reference,
            name: Cow::Borrowed(c.name),
            variable_type: VariableType::Clock,
            causality: Causality::Input,
            variability: Variability::Discrete,
            initial: None,
            dimension: None,
            source: Source::Clock { clock: k },
            derivative_of: None,
            sized_by: None,
        };
        let period = Variable3 {
            value_reference: c.period.value_reference,
            name: Cow::Borrowed(c.period.name),
            variable_type: VariableType::Real,
            causality: Causality::Parameter,
            variability: Variability::Fixed,
            initial: Some(Initial::Exact),
            dimension: None,
            source: Source::ClockPeriod { clock: k },
            derivative_of: None,
            sized_by: None,
        };
        let outputs = c.outputs.iter().enumerate().map(move |(i, o)| Variable3 {
            value_reference: o.value_reference,
            name: Cow::Borrowed(o.name),
            variable_type: VariableType::Real,
            causality: Causality::Output,
            variability: Variability::Discrete,
            initial: Some(Initial::Calculated),
            dimension: o.length,
            source: Source::Clocked {
                clock: k,
                output: i,
            },
            derivative_of: None,
            sized_by: o.sized_by,
        });
        [clock, period].into_iter().chain(outputs)
    })
}

/// The model's structural parameters (FMI 3.0 only): UInt64, fixed, start the
/// default size.
fn structural_variables<M: Model>() -> impl Iterator<Item = Variable3> {
    M::STRUCTURAL.iter().enumerate().map(|(k, p)| Variable3 {
        value_reference: p.value_reference,
        name: Cow::Borrowed(p.name),
        variable_type: VariableType::UInt64,
        causality: Causality::StructuralParameter,
        variability: Variability::Fixed,
        initial: Some(Initial::Exact),
        dimension: None,
        source: Source::Structural { parameter: k },
        derivative_of: None,
        sized_by: None,
    })
}

/// The FMI 3.0 state vector (the derivative arrays' elements in description order)
/// must be the model's state vector (the FMI 2.0 derivatives in value-reference order).
fn check_state_order<M>(table: &[Variable<M>], variables: &[Variable3]) -> Result<(), String> {
    let derivatives = derivative_variables(table);
    let fmi2 = derivatives.iter().map(|v| v.value_reference);
    let fmi3 = variables
        .iter()
        .filter(|v| v.derivative_of.is_some())
        .flat_map(Variable3::elements);
    if fmi2.eq(fmi3) {
        Ok(())
    } else {
        Err(
            "the derivative declarations do not list the states in value-reference order"
                .to_string(),
        )
    }
}

fn variable3<M>(
    declarations: &[Declaration<M>],
    firsts: &[u32],
    position: usize,
    first: u32,
) -> Result<Variable3, String> {
    let d = &declarations[position];
    let derivative_of = match d.derivative_of {
        None => None,
        Some(state) => {
            let i = declarations.iter().position(|s| s.name == state);
            Some(
                firsts[i.ok_or_else(|| {
                    format!("\"{}\" names the unknown variable \"{state}\"", d.name)
                })?],
            )
        }
    };
    let variable_type = match d.value {
        Value::Real { .. } => VariableType::Real,
        Value::Integer { .. } => VariableType::Integer,
        Value::Boolean { .. } => VariableType::Boolean,
    };
    Ok(Variable3 {
        value_reference: first,
        name: Cow::Borrowed(d.name),
        variable_type,
        causality: d.causality,
        variability: d.variability,
        initial: d.initial,
        dimension: d.length,
        source: Source::Elements {
            first,
            stride: d.stride,
            declaration: position,
            element: 0,
        },
        derivative_of,
        sized_by: d.sized_by,
    })
}
