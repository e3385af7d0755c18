//! modelDescription.xml of FMI 2.0, generated from a model's [`Description`]: its
//! `ModelInfo` and FMI 2.0 scalars (`<ScalarVariable>`), and the ModelStructure
//! (`<Outputs>`, `<Derivatives>`, `<InitialUnknowns>` with their dependencies as
//! 1-based indices). The root element and what both standards share: [`common`].

use crate::common::{self, ModelDescription, Parts, Standard, number};
use robofmu_fmi::core::variables::{Causality, Initial};
use robofmu_fmi::description::{Description, Scalar, Value};
use serde::Serialize;

/// Attributes of <ModelExchange> and <CoSimulation>; `None` ones are left out.
#[derive(Serialize)]
struct Interface {
    #[serde(rename = "@modelIdentifier")]
    model_identifier: &'static str,
    #[serde(
        rename = "@canHandleVariableCommunicationStepSize",
        skip_serializing_if = "Option::is_none"
    )]
    variable_step: Option<bool>,
    /// Co-Simulation only: the step uses the inputs' derivatives
    /// (`Model::MAX_INPUT_DERIVATIVE_ORDER` > 0).
    #[serde(
        rename = "@canInterpolateInputs",
        skip_serializing_if = "Option::is_none"
    )]
    interpolate_inputs: Option<bool>,
    #[serde(rename = "@canGetAndSetFMUstate")]
    get_set_state: bool,
    #[serde(rename = "@canSerializeFMUstate")]
    serialize_state: bool,
    #[serde(rename = "@providesDirectionalDerivative")]
    directional_derivative: bool,
    /// Co-Simulation only, and only when the model provides output derivatives.
    #[serde(
        rename = "@maxOutputDerivativeOrder",
        skip_serializing_if = "Option::is_none"
    )]
    max_output_derivative_order: Option<u32>,
}

#[derive(Serialize)]
struct ModelVariables {
    #[serde(rename = "ScalarVariable")]
    variables: Vec<ScalarVariable>,
}

#[derive(Serialize)]
struct ScalarVariable {
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
    #[serde(rename = "@initial", skip_serializing_if = "Option::is_none")]
    initial: Option<&'static str>,
    #[serde(rename = "$value")]
    kind: TypeElement,
}

#[derive(Serialize)]
enum TypeElement {
    Real(RealAttributes),
    Integer(IntegerAttributes),
    Boolean(BooleanAttributes),
}

#[derive(Serialize)]
struct RealAttributes {
    #[serde(rename = "@unit", skip_serializing_if = "Option::is_none")]
    unit: Option<&'static str>,
    #[serde(rename = "@displayUnit", skip_serializing_if = "Option::is_none")]
    display_unit: Option<&'static str>,
    #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
    min: Option<String>,
    #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
    max: Option<String>,
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    start: Option<String>,
    #[serde(rename = "@derivative", skip_serializing_if = "Option::is_none")]
    derivative: Option<usize>,
}

#[derive(Serialize)]
struct IntegerAttributes {
    #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
    min: Option<i32>,
    #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
    max: Option<i32>,
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    start: Option<i32>,
}

#[derive(Serialize)]
struct BooleanAttributes {
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    start: Option<bool>,
}

#[derive(Serialize)]
struct ModelStructure {
    #[serde(rename = "Outputs", skip_serializing_if = "Option::is_none")]
    outputs: Option<UnknownList>,
    #[serde(rename = "Derivatives", skip_serializing_if = "Option::is_none")]
    derivatives: Option<UnknownList>,
    #[serde(rename = "InitialUnknowns", skip_serializing_if = "Option::is_none")]
    initial_unknowns: Option<UnknownList>,
}

#[derive(Serialize)]
struct UnknownList {
    #[serde(rename = "Unknown")]
    unknowns: Vec<Unknown>,
}

#[derive(Serialize)]
struct Unknown {
    #[serde(rename = "@index")]
    index: usize,
    /// Space-separated indices of the knowns, ascending; absent: all knowns.
    #[serde(rename = "@dependencies", skip_serializing_if = "Option::is_none")]
    dependencies: Option<String>,
}

/// A list of unknowns, or None when empty (an empty list element is omitted).
fn unknown_list(unknowns: Vec<Unknown>) -> Option<UnknownList> {
    (!unknowns.is_empty()).then_some(UnknownList { unknowns })
}

/// The 1-based index of the scalar `name` in `table`.
fn index_of(table: &[Scalar], name: &str) -> Option<usize> {
    table.iter().position(|s| s.name == name).map(|i| i + 1)
}

/// The unknown `v` with its declared dependencies as ascending 1-based indices.
fn with_dependencies(v: &Scalar, table: &[Scalar]) -> Unknown {
    unknown(v, v.dependencies, table)
}

/// The unknown `v` with the knowns `names` as ascending 1-based indices (None: all).
fn unknown(v: &Scalar, names: Option<&'static [&'static str]>, table: &[Scalar]) -> Unknown {
    let dependencies = names.map(|names| {
        let mut indices: Vec<usize> = names.iter().filter_map(|n| index_of(table, n)).collect();
        indices.sort_unstable();
        indices.dedup();
        indices
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(" ")
    });
    Unknown {
        index: index_of(table, &v.name).unwrap_or(0),
        dependencies,
    }
}

fn scalar_variable(v: &Scalar, table: &[Scalar]) -> ScalarVariable {
    let kind = match v.value {
        Value::Real {
            start,
            min,
            max,
            unit,
            display_unit,
        } => TypeElement::Real(RealAttributes {
            unit,
            display_unit,
            min: min.map(number),
            max: max.map(number),
            start: start.map(number),
            derivative: v.state.as_deref().and_then(|s| index_of(table, s)),
        }),
        Value::Integer { start, min, max } => {
            TypeElement::Integer(IntegerAttributes { min, max, start })
        }
        Value::Boolean { start } => TypeElement::Boolean(BooleanAttributes { start }),
    };
    ScalarVariable {
        name: v.name.clone(),
        value_reference: v.value_reference,
        description: v.description.clone(),
        causality: v.causality.as_str(),
        variability: v.variability.as_str(),
        initial: v.initial.map(Initial::as_str),
        kind,
    }
}

/// The text of the FMI 2.0 modelDescription.xml of `d`.
pub fn model_description(d: &Description) -> Result<String, String> {
    let info = &d.info;
    let table = &d.scalars[..];
    let derivatives: Vec<&Scalar> = table.iter().filter(|v| v.state.is_some()).collect();
    if derivatives.len() != info.number_of_continuous_states {
        return Err(format!(
            "{} derivative variables but {} continuous states",
            derivatives.len(),
            info.number_of_continuous_states
        ));
    }
    let outputs = table
        .iter()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| with_dependencies(v, table))
        .collect();
    let initial_unknowns = table
        .iter()
        .filter(|v| {
            let calculated = matches!(v.initial, Some(Initial::Calculated | Initial::Approx));
            (v.causality == Causality::Output && calculated)
                || v.causality == Causality::CalculatedParameter
                || (calculated
                    && derivatives
                        .iter()
                        .any(|d| d.value_reference == v.value_reference))
        })
        .map(|v| unknown(v, v.initial_dependencies, table))
        .collect();
    let interface = |variable_step: Option<bool>| Interface {
        model_identifier: info.model_identifier,
        variable_step,
        interpolate_inputs: None,
        get_set_state: true,
        serialize_state: true,
        directional_derivative: info.provides_directional_derivative,
        max_output_derivative_order: None,
    };
    let co_simulation = Interface {
        interpolate_inputs: (d.max_input_derivative_order > 0).then_some(true),
        max_output_derivative_order: common::max_output_derivative_order(info),
        ..interface(Some(true))
    };
    let parts = Parts {
        interfaces: (interface(None), co_simulation),
        variables: ModelVariables {
            variables: table.iter().map(|v| scalar_variable(v, table)).collect(),
        },
        structure: ModelStructure {
            outputs: unknown_list(outputs),
            derivatives: unknown_list(
                derivatives
                    .iter()
                    .map(|d| with_dependencies(d, table))
                    .collect(),
            ),
            initial_unknowns: unknown_list(initial_unknowns),
        },
    };
    ModelDescription::write(d, Standard::Fmi2, parts)
}

/// Number of `<Unknown>` entries in one ModelStructure section (`Outputs`,
/// `Derivatives`, `InitialUnknowns`) of an FMI 2.0 modelDescription; 0 when the
/// section is absent. For the bindings' structure tests.
pub fn unknowns_in_section(xml: &str, section: &str) -> usize {
    match (
        xml.find(&format!("<{section}>")),
        xml.find(&format!("</{section}>")),
    ) {
        (Some(start), Some(end)) => xml[start..end].matches("<Unknown ").count(),
        _ => 0,
    }
}
