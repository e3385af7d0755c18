//! The one check of a value that comes from outside the model, before it is written
//! through the variable's writer: a setter's argument (fmi2Set*, fmi3Set*) and every
//! value read back from a serialized FMU state go through [`write()`], so a state can
//! hold nothing that the setters would refuse.

use super::variables::{Kind, ShownName, Variable};

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

/// The error for `v` used as a variable of type `wanted`.
pub fn wrong_type<M>(v: &Variable<M>, wanted: &str) -> String {
    format!(
        "\"{}\" (value reference {}) is a {} variable, not {wanted}",
        v.shown_name(),
        v.value_reference,
        v.variable_type().as_str()
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

/// Checks `value` for the variable `v` (type; Real: finite, magnitude, min/max;
/// Integer: min/max) and writes it through the variable's writer, whose own check
/// may still refuse it. Whether the variable may be set now is the front-end's rule.
pub fn write<M>(model: &mut M, v: &Variable<M>, value: Value) -> Result<(), String> {
    let name = v.shown_name();
    let result = match (&v.kind, value) {
        (Kind::Real { set, min, max, .. }, Value::Real(x)) => {
            check_real(name, x, *min, *max)?;
            let set = set
                .as_ref()
                .ok_or_else(|| format!("\"{name}\" has no writer"))?;
            set.call(model, x)
        }
        (Kind::Integer { set, min, max, .. }, Value::Integer(x)) => {
            if min.is_some_and(|m| x < m) || max.is_some_and(|m| x > m) {
                return Err(format!("\"{name}\" = {x} is outside its range"));
            }
            let set = set
                .as_ref()
                .ok_or_else(|| format!("\"{name}\" has no writer"))?;
            set.call(model, x)
        }
        (Kind::Boolean { set, .. }, Value::Boolean(x)) => {
            let set = set
                .as_ref()
                .ok_or_else(|| format!("\"{name}\" has no writer"))?;
            set.call(model, x)
        }
        (_, Value::Real(_)) => return Err(wrong_type(v, "Real")),
        (_, Value::Integer(_)) => return Err(wrong_type(v, "Integer")),
        (_, Value::Boolean(_)) => return Err(wrong_type(v, "Boolean")),
    };
    // Formatted only for a refusal (a float to text costs more than the write).
    result.map_err(|e| match value {
        Value::Real(x) => format!("\"{name}\" = {x}: {e}"),
        Value::Integer(x) => format!("\"{name}\" = {x}: {e}"),
        Value::Boolean(x) => format!("\"{name}\" = {x}: {e}"),
    })
}
