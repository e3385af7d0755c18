//! The one check of a value that comes from outside the model, before it is written
//! through the variable's writer: a setter's argument (fmi2Set*, fmi3Set*) and every
//! value read back from a serialized FMU state go through [`write()`], so a state can
//! hold nothing that the setters would refuse.

use super::declare::{Declaration, Value as Declared, write_element};
use super::variables::{ShownName, VariableType, element_name, value_type};

/// Largest magnitude the layer accepts for a Real value set by the host. No model
/// quantity in SI units comes near it, and the product of two such values is still
/// finite, so an extreme finite value (say 1e308) is refused where it is set, naming
/// the variable, instead of overflowing later in the model.
pub const MAX_MAGNITUDE: f64 = 1e150;

/// A value of one of the FMI types, to be written.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    Real(f64),
    Integer(i32),
    Boolean(bool),
}

impl Value {
    pub fn variable_type(self) -> VariableType {
        match self {
            Value::Real(_) => VariableType::Real,
            Value::Integer(_) => VariableType::Integer,
            Value::Boolean(_) => VariableType::Boolean,
        }
    }
}

/// The error for the variable `name` (value reference `vr`, of type `is`) used as a
/// variable of type `wanted`.
pub fn wrong_type(name: ShownName, vr: u32, is: VariableType, wanted: &str) -> String {
    format!(
        "\"{name}\" (value reference {vr}) is a {} variable, not {wanted}",
        is.as_str()
    )
}

/// Err unless the Real `value` is finite, within [`MAX_MAGNITUDE`] and within the
/// variable's [min, max].
fn check_real(
    name: ShownName,
    value: f64,
    min: Option<f64>,
    max: Option<f64>,
) -> Result<(), String> {
    if !value.is_finite() {
        return Err(format!("\"{name}\" cannot be set to {value}"));
    }
    if value.abs() > MAX_MAGNITUDE {
        return Err(format!(
            "\"{name}\" = {value:e} exceeds the magnitude {MAX_MAGNITUDE:e} the layer accepts \
             (such a value overflows the model's arithmetic)"
        ));
    }
    if min.is_some_and(|m| value < m) || max.is_some_and(|m| value > m) {
        return Err(format!(
            "\"{name}\" = {value} is outside [{}, {}]",
            min.unwrap_or(f64::NEG_INFINITY),
            max.unwrap_or(f64::INFINITY)
        ));
    }
    Ok(())
}

/// Checks `value` for element i of the declaration `d` (value reference `vr`) (type;
/// Real: finite, magnitude, min/max; Integer: min/max) and writes it through the
/// declaration's writer, whose own check may still refuse it. Whether the variable
/// may be set now is the front-end's rule.
pub fn write<M>(
    model: &mut M,
    d: &Declaration<M>,
    i: usize,
    vr: u32,
    value: Value,
) -> Result<(), String> {
    let name = element_name(d, i);
    let no_writer = || format!("\"{name}\" has no writer");
    let result = match (&d.value, value) {
        (
            Declared::Real {
                get, set, min, max, ..
            },
            Value::Real(x),
        ) => {
            check_real(name, x, *min, *max)?;
            write_element(*get, *set, model, i, x).ok_or_else(no_writer)?
        }
        (
            Declared::Integer {
                get, set, min, max, ..
            },
            Value::Integer(x),
        ) => {
            if min.is_some_and(|m| x < m) || max.is_some_and(|m| x > m) {
                return Err(format!("\"{name}\" = {x} is outside its range"));
            }
            write_element(*get, *set, model, i, x).ok_or_else(no_writer)?
        }
        (Declared::Boolean { get, set, .. }, Value::Boolean(x)) => {
            write_element(*get, *set, model, i, x).ok_or_else(no_writer)?
        }
        (is, Value::Real(_)) => return Err(wrong_type(name, vr, value_type(is), "Real")),
        (is, Value::Integer(_)) => return Err(wrong_type(name, vr, value_type(is), "Integer")),
        (is, Value::Boolean(_)) => return Err(wrong_type(name, vr, value_type(is), "Boolean")),
    };
    if let (Ok(()), Some(after)) = (&result, d.after_set) {
        after(model, i);
    }
    // Formatted only for a refusal (a float to text costs more than the write).
    result.map_err(|e| match value {
        Value::Real(x) => format!("\"{name}\" = {x}: {e}"),
        Value::Integer(x) => format!("\"{name}\" = {x}: {e}"),
        Value::Boolean(x) => format!("\"{name}\" = {x}: {e}"),
    })
}

/// Whether element i of the declaration `d` holds `value` already, bit for bit: a
/// Real compares its bits, so -0.0 and 0.0 differ and NaN never holds (the layer
/// refuses NaN, so no variable holds one). A value of another type never holds.
pub fn holds<M>(model: &mut M, d: &Declaration<M>, i: usize, value: Value) -> bool {
    match (&d.value, value) {
        (Declared::Real { get, .. }, Value::Real(x)) => {
            !x.is_nan() && get.read(model, i).to_bits() == x.to_bits()
        }
        (Declared::Integer { get, .. }, Value::Integer(x)) => get.read(model, i) == x,
        (Declared::Boolean { get, .. }, Value::Boolean(x)) => get.read(model, i) == x,
        _ => false,
    }
}
