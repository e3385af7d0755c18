//! The FMI 3.0 view of a declared model: one [`Variable3`] per
//! [`Declaration`], taken from the declaration as it
//! is (a scalar, or an array with its length), without parsing names or descriptions.
//! [`view`] falls back to the name-parsing [`build`] for a model still written with
//! `Model::variables`.

use super::table::{Source, Table3, Variable3, build, event_indicator_variable, time_variable};
use crate::core::declare::{Declaration, Value, value_references};
use crate::core::model::Model;
use crate::core::variables::{Variable, VariableType};
use std::borrow::Cow;

/// The FMI 3.0 view of model M, whose instance holds the flattened `table`.
pub fn view<M: Model>(table: &[Variable<M>]) -> Result<Table3, String> {
    let declarations = M::declarations();
    if declarations.is_empty() {
        return build(table);
    }
    let firsts = value_references(declarations);
    let mut variables = Vec::with_capacity(declarations.len() + 2);
    variables.push(time_variable());
    for (d, &first) in declarations.iter().zip(&firsts) {
        variables.push(variable3(declarations, &firsts, d, first)?);
    }
    let n_indicators = M::info().number_of_event_indicators;
    if n_indicators > 0 {
        let last = table.iter().map(|v| v.value_reference).max().unwrap_or(0);
        variables.push(event_indicator_variable(last + 1, n_indicators));
    }
    Ok(Table3::new(variables))
}

fn variable3<M>(
    declarations: &[Declaration<M>],
    firsts: &[u32],
    d: &Declaration<M>,
    first: u32,
) -> Result<Variable3, String> {
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
        },
        derivative_of,
    })
}
