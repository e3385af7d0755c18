//! modelDescription.xml of FMI 2.0, generated from a model's [`Description`]: its
//! `ModelInfo` and FMI 2.0 scalars (`<ScalarVariable>`), and the ModelStructure
//! (`<Outputs>`, `<Derivatives>`, `<InitialUnknowns>` with their dependencies as
//! 1-based indices). The root element and what both standards share: [`common`].

use crate::common::{self, Attributes, ModelDescription, Parts, Standard};
use crate::variable::{TypeAttributes, VariableHead};
use robofmu_fmi::core::variables::{Causality, Initial};
use robofmu_fmi::description::{Description, Scalar, Value};
use serde::Serialize;

#[derive(Serialize)]
struct ModelVariables {
    #[serde(rename = "ScalarVariable")]
    variables: Vec<ScalarVariable>,
}

#[derive(Serialize)]
struct ScalarVariable {
    #[serde(flatten)]
    head: VariableHead,
    #[serde(rename = "@initial", skip_serializing_if = "Option::is_none")]
    initial: Option<&'static str>,
    #[serde(rename = "$value")]
    kind: TypeElement,
}

/// The type element, named after the type.
#[derive(Serialize)]
enum TypeElement {
    Real(TypeAttributes),
    Integer(TypeAttributes),
    Boolean(TypeAttributes),
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
    unknown(v, v.dependencies.as_deref(), table)
}

/// The unknown `v` with the knowns `names` as ascending 1-based indices (None: all).
fn unknown(v: &Scalar, names: Option<&[String]>, table: &[Scalar]) -> Unknown {
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
    let attributes = TypeAttributes {
        start: crate::variable::start(&v.value),
        derivative: (v.state.as_deref())
            .and_then(|s| index_of(table, s))
            .map(|i| i as u32),
        ..TypeAttributes::of(&v.value)
    };
    let kind = match v.value {
        Value::Real { .. } => TypeElement::Real(attributes),
        Value::Integer { .. } => TypeElement::Integer(attributes),
        Value::Boolean { .. } => TypeElement::Boolean(attributes),
    };
    ScalarVariable {
        head: VariableHead::new(
            v.name.clone(),
            v.value_reference,
            v.description.clone(),
            (v.causality, v.variability),
        ),
        initial: v.initial.map(Initial::as_str),
        kind,
    }
}

/// `<ModelExchange>` and `<CoSimulation>`.
fn interfaces(d: &Description) -> (Attributes, Attributes) {
    let info = &d.info;
    let identified = || Attributes::default().with("modelIdentifier", info.model_identifier);
    let capabilities = |a: Attributes| {
        a.with("canGetAndSetFMUstate", true)
            .with("canSerializeFMUstate", true)
            .with(
                "providesDirectionalDerivative",
                d.provides_directional_derivative,
            )
    };
    let co_simulation = identified()
        .with("canHandleVariableCommunicationStepSize", true)
        // The step uses the inputs' derivatives.
        .with_some(
            "canInterpolateInputs",
            (d.max_input_derivative_order > 0).then_some(true),
        );
    let co_simulation = capabilities(co_simulation).with_some(
        "maxOutputDerivativeOrder",
        common::max_output_derivative_order(d),
    );
    (capabilities(identified()), co_simulation)
}

/// The text of the FMI 2.0 modelDescription.xml of `d`.
pub fn model_description(d: &Description) -> Result<String, String> {
    let table = &d.scalars[..];
    let derivatives: Vec<&Scalar> = table.iter().filter(|v| v.state.is_some()).collect();
    if derivatives.len() != d.number_of_continuous_states {
        return Err(format!(
            "{} derivative variables but {} continuous states",
            derivatives.len(),
            d.number_of_continuous_states
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
        .map(|v| unknown(v, v.initial_dependencies.as_deref(), table))
        .collect();
    let parts = Parts {
        interfaces: interfaces(d),
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
