//! The attributes of a variable that FMI 2.0 and FMI 3.0 write alike: its head (name,
//! value reference, description, causality, variability) and its type attributes.

use crate::common::number;
use robofmu_fmi::core::variables::{Causality, Variability};
use robofmu_fmi::description::Value;
use serde::Serialize;

/// The attributes every variable of either standard starts with.
#[derive(Serialize)]
pub struct VariableHead {
    #[serde(rename = "@name")]
    name: String,
    #[serde(rename = "@valueReference")]
    value_reference: u32,
    #[serde(rename = "@description")]
    description: String,
    #[serde(rename = "@causality")]
    causality: &'static str,
    #[serde(rename = "@variability")]
    variability: &'static str,
}

impl VariableHead {
    pub fn new(
        name: String,
        value_reference: u32,
        description: String,
        (causality, variability): (Causality, Variability),
    ) -> VariableHead {
        VariableHead {
            name,
            value_reference,
            description,
            causality: causality.as_str(),
            variability: variability.as_str(),
        }
    }
}

/// The type-specific attributes of a variable of either standard, in the schemas'
/// order: `unit`, `displayUnit`, `min`, `max`, `start`, `derivative`; those that do
/// not apply stay None.
#[derive(Serialize, Default)]
pub struct TypeAttributes {
    #[serde(rename = "@unit", skip_serializing_if = "Option::is_none")]
    pub unit: Option<&'static str>,
    #[serde(rename = "@displayUnit", skip_serializing_if = "Option::is_none")]
    pub display_unit: Option<&'static str>,
    #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
    pub min: Option<String>,
    #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
    pub max: Option<String>,
    /// FMI 3.0: the space-separated start values of all elements.
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    pub start: Option<String>,
    /// FMI 2.0: the 1-based index of the state; FMI 3.0: its value reference.
    #[serde(rename = "@derivative", skip_serializing_if = "Option::is_none")]
    pub derivative: Option<u32>,
}

impl TypeAttributes {
    /// The unit, display unit and bounds of `value`, without start and derivative.
    pub fn of(value: &Value) -> TypeAttributes {
        match *value {
            Value::Real {
                unit,
                display_unit,
                min,
                max,
                ..
            } => TypeAttributes {
                unit,
                display_unit,
                min: min.map(number),
                max: max.map(number),
                ..TypeAttributes::default()
            },
            Value::Integer { min, max, .. } => TypeAttributes {
                min: min.map(|m| m.to_string()),
                max: max.map(|m| m.to_string()),
                ..TypeAttributes::default()
            },
            Value::Boolean { .. } => TypeAttributes::default(),
        }
    }
}

/// The start value of `value` as written in modelDescription.xml.
pub fn start(value: &Value) -> Option<String> {
    match *value {
        Value::Real { start, .. } => start.map(number),
        Value::Integer { start, .. } => start.map(|s| s.to_string()),
        Value::Boolean { start } => start.map(|s| s.to_string()),
    }
}
