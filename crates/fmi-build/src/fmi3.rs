//! modelDescription.xml of FMI 3.0, generated from a model's [`Description`]: its
//! `ModelInfo` and FMI 3.0 variables (Float64 / Int32 / Boolean, arrays with
//! `<Dimension>`, units with display units), and the ModelStructure (`<Output>`,
//! `<ContinuousStateDerivative>`, `<InitialUnknown>`, `<EventIndicator>` with their
//! dependencies as value references); the array view or the scalar-only one. The root
//! element and what both standards share: [`common`].

use crate::common::{self, ModelDescription, Parts, Standard, number};
use robofmu_fmi::core::variables::{Causality, Initial};
use robofmu_fmi::description::{Description, Scalar, Value, Variable3Description};
use robofmu_fmi::fmi3::table::Source;
use serde::Serialize;

/// Attributes of <ModelExchange> and <CoSimulation>; `None` ones are left out.
#[derive(Serialize)]
struct Interface {
    #[serde(rename = "@modelIdentifier")]
    model_identifier: &'static str,
    #[serde(rename = "@canGetAndSetFMUState")]
    get_set_state: bool,
    #[serde(rename = "@canSerializeFMUState")]
    serialize_state: bool,
    #[serde(rename = "@providesDirectionalDerivatives")]
    directional_derivatives: bool,
    #[serde(rename = "@providesAdjointDerivatives")]
    adjoint_derivatives: bool,
    #[serde(rename = "@providesPerElementDependencies")]
    per_element_dependencies: bool,
    #[serde(
        rename = "@needsCompletedIntegratorStep",
        skip_serializing_if = "Option::is_none"
    )]
    needs_completed_integrator_step: Option<bool>,
    #[serde(
        rename = "@canHandleVariableCommunicationStepSize",
        skip_serializing_if = "Option::is_none"
    )]
    variable_step: Option<bool>,
    #[serde(rename = "@hasEventMode", skip_serializing_if = "Option::is_none")]
    has_event_mode: Option<bool>,
    #[serde(
        rename = "@mightReturnEarlyFromDoStep",
        skip_serializing_if = "Option::is_none"
    )]
    might_return_early: Option<bool>,
    /// Co-Simulation only, and only when the model provides output derivatives.
    #[serde(
        rename = "@maxOutputDerivativeOrder",
        skip_serializing_if = "Option::is_none"
    )]
    max_output_derivative_order: Option<u32>,
    /// Co-Simulation only, and only when the model has intermediate points.
    #[serde(
        rename = "@providesIntermediateUpdate",
        skip_serializing_if = "Option::is_none"
    )]
    provides_intermediate_update: Option<bool>,
}

#[derive(Serialize)]
struct ModelVariables {
    #[serde(rename = "$value")]
    variables: Vec<TypedVariable>,
}

/// One element of <ModelVariables>: its tag is the type.
#[derive(Serialize)]
enum TypedVariable {
    Float64(ModelVariable),
    Int32(ModelVariable),
    Boolean(ModelVariable),
}

/// The attributes of a variable; those that do not apply to its type stay None.
#[derive(Serialize)]
struct ModelVariable {
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
    #[serde(
        rename = "@intermediateUpdate",
        skip_serializing_if = "Option::is_none"
    )]
    intermediate_update: Option<bool>,
    #[serde(rename = "@initial", skip_serializing_if = "Option::is_none")]
    initial: Option<&'static str>,
    #[serde(rename = "@unit", skip_serializing_if = "Option::is_none")]
    unit: Option<&'static str>,
    #[serde(rename = "@displayUnit", skip_serializing_if = "Option::is_none")]
    display_unit: Option<&'static str>,
    #[serde(rename = "@min", skip_serializing_if = "Option::is_none")]
    min: Option<String>,
    #[serde(rename = "@max", skip_serializing_if = "Option::is_none")]
    max: Option<String>,
    /// Space-separated start values of all elements.
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    start: Option<String>,
    #[serde(rename = "@derivative", skip_serializing_if = "Option::is_none")]
    derivative: Option<u32>,
    #[serde(rename = "Dimension", skip_serializing_if = "Option::is_none")]
    dimension: Option<Dimension>,
}

#[derive(Serialize)]
struct Dimension {
    #[serde(rename = "@start")]
    start: usize,
}

#[derive(Serialize)]
struct ModelStructure {
    #[serde(rename = "$value")]
    unknowns: Vec<Unknown>,
}

/// The ModelStructure elements, in the order of the schema (the tags are the
/// standard's, hence the shared suffix).
#[derive(Serialize)]
#[allow(clippy::enum_variant_names)]
enum Unknown {
    Output(Dependencies),
    ContinuousStateDerivative(Dependencies),
    InitialUnknown(Dependencies),
    EventIndicator(Dependencies),
}

#[derive(Serialize)]
struct Dependencies {
    #[serde(rename = "@valueReference")]
    value_reference: u32,
    /// Space-separated value references of the knowns; absent: all knowns.
    #[serde(rename = "@dependencies", skip_serializing_if = "Option::is_none")]
    dependencies: Option<String>,
}

fn joined<T: ToString>(values: impl IntoIterator<Item = T>) -> String {
    values
        .into_iter()
        .map(|v| v.to_string())
        .collect::<Vec<_>>()
        .join(" ")
}

/// The scalar of `d` with value reference `vr`.
fn scalar(d: &Description, vr: u32) -> Result<&Scalar, String> {
    let i = (d.scalars)
        .binary_search_by_key(&vr, |s| s.value_reference)
        .map_err(|_| format!("no element {vr}"))?;
    Ok(&d.scalars[i])
}

/// The type-specific attributes of `v`, read from its first element (shared by all)
/// and the start values of every element.
fn model_variable(d: &Description, v3: &Variable3Description) -> Result<TypedVariable, String> {
    let v = &v3.variable;
    let mut out = ModelVariable {
        name: v.name.to_string(),
        value_reference: v.value_reference,
        description: v3.description.clone(),
        causality: v.causality.as_str(),
        variability: v.variability.as_str(),
        intermediate_update: v3.intermediate_update.then_some(true),
        initial: v.initial.map(Initial::as_str),
        unit: None,
        display_unit: None,
        min: None,
        max: None,
        start: None,
        derivative: v.derivative_of,
        dimension: v.dimension.map(|start| Dimension { start }),
    };
    let elements: Vec<&Scalar> = v
        .elements()
        .map(|vr| scalar(d, vr))
        .collect::<Result<_, _>>()?;
    let Some(first) = elements.first() else {
        return Ok(TypedVariable::Float64(out));
    };
    let starts: Option<Vec<String>> = elements
        .iter()
        .map(|e| match e.value {
            Value::Real { start, .. } => start.map(number),
            Value::Integer { start, .. } => start.map(|s| s.to_string()),
            Value::Boolean { start } => start.map(|s| s.to_string()),
        })
        .collect();
    out.start = starts.map(joined);
    Ok(match first.value {
        Value::Real {
            unit,
            display_unit,
            min,
            max,
            ..
        } => {
            out.unit = unit;
            out.display_unit = display_unit;
            out.min = min.map(number);
            out.max = max.map(number);
            TypedVariable::Float64(out)
        }
        Value::Integer { min, max, .. } => {
            out.min = min.map(|m| m.to_string());
            out.max = max.map(|m| m.to_string());
            TypedVariable::Int32(out)
        }
        Value::Boolean { .. } => TypedVariable::Boolean(out),
    })
}

fn dependencies(v: &Variable3Description, initial: bool) -> Dependencies {
    let list = if initial {
        &v.initial_dependencies
    } else {
        &v.dependencies
    };
    Dependencies {
        value_reference: v.variable.value_reference,
        dependencies: list.as_ref().map(joined),
    }
}

/// Whether `v` is an initial unknown (section 2.4.8 of FMI 3.0): outputs and state
/// derivatives computed at initialization, and calculated parameters.
fn is_initial_unknown(v: &Variable3Description) -> bool {
    let v = &v.variable;
    let calculated = matches!(v.initial, Some(Initial::Calculated | Initial::Approx));
    (calculated && (v.causality == Causality::Output || v.derivative_of.is_some()))
        || v.causality == Causality::CalculatedParameter
}

fn model_structure(variables: &[Variable3Description]) -> ModelStructure {
    let all = || variables.iter();
    let outputs = all()
        .filter(|v| v.variable.causality == Causality::Output)
        .map(|v| Unknown::Output(dependencies(v, false)));
    let derivatives = all()
        .filter(|v| v.variable.derivative_of.is_some())
        .map(|v| Unknown::ContinuousStateDerivative(dependencies(v, false)));
    let initial = all()
        .filter(|v| is_initial_unknown(v))
        .map(|v| Unknown::InitialUnknown(dependencies(v, true)));
    let indicators = all()
        .filter(|v| matches!(v.variable.source, Source::EventIndicators { .. }))
        .map(|v| Unknown::EventIndicator(dependencies(v, false)));
    ModelStructure {
        unknowns: outputs
            .chain(derivatives)
            .chain(initial)
            .chain(indicators)
            .collect(),
    }
}

fn interfaces(d: &Description) -> (Interface, Interface) {
    let info = &d.info;
    let common = || Interface {
        model_identifier: info.model_identifier,
        get_set_state: true,
        serialize_state: true,
        directional_derivatives: info.provides_directional_derivative,
        adjoint_derivatives: info.provides_directional_derivative,
        per_element_dependencies: true,
        needs_completed_integrator_step: None,
        variable_step: None,
        has_event_mode: None,
        might_return_early: None,
        max_output_derivative_order: None,
        provides_intermediate_update: None,
    };
    let model_exchange = Interface {
        needs_completed_integrator_step: Some(false),
        ..common()
    };
    let co_simulation = Interface {
        variable_step: Some(true),
        has_event_mode: Some(true),
        // Steps end early at events (sign changes of the event indicators).
        might_return_early: (info.number_of_event_indicators > 0).then_some(true),
        max_output_derivative_order: common::max_output_derivative_order(info),
        provides_intermediate_update: (d.intermediate_update_points > 0).then_some(true),
        ..common()
    };
    (model_exchange, co_simulation)
}

/// The text of the FMI 3.0 modelDescription.xml of `d`.
pub fn model_description(d: &Description) -> Result<String, String> {
    description(d, &d.arrays, d.info.guid.to_string())
}

/// The text of the scalar-only FMI 3.0 modelDescription.xml of `d` (every FMI 2.0
/// scalar an FMI 3.0 scalar, instantiationToken `d.scalar_token`).
pub fn scalar_model_description(d: &Description) -> Result<String, String> {
    description(d, &d.scalar_view, d.scalar_token.clone())
}

fn description(
    d: &Description,
    view: &[Variable3Description],
    token: String,
) -> Result<String, String> {
    let states: usize = view
        .iter()
        .filter(|v| v.variable.derivative_of.is_some())
        .map(|v| v.variable.size())
        .sum();
    if states != d.info.number_of_continuous_states {
        return Err(format!(
            "{states} state derivatives but {} continuous states",
            d.info.number_of_continuous_states
        ));
    }
    let variables = view
        .iter()
        .map(|v| model_variable(d, v))
        .collect::<Result<Vec<_>, _>>()?;
    let parts = Parts {
        interfaces: interfaces(d),
        variables: ModelVariables { variables },
        structure: model_structure(view),
    };
    ModelDescription::write(d, Standard::Fmi3 { token }, parts)
}
