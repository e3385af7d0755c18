//! modelDescription.xml of FMI 3.0, generated from a model's [`Description`]: its
//! `ModelInfo` and FMI 3.0 variables (Float64 / Int32 / Boolean, arrays with
//! `<Dimension>`, units with display units), and the ModelStructure (`<Output>`,
//! `<ContinuousStateDerivative>`, `<InitialUnknown>`, `<EventIndicator>` with their
//! dependencies as value references); the array view or the scalar-only one. The root
//! element and what both standards share: [`common`].

use crate::common::{self, Attributes, ModelDescription, Parts, Standard};
use crate::variable::{TypeAttributes, VariableHead};
use robofmu_fmi::core::variables::{Causality, Initial};
use robofmu_fmi::description::{ClockPart, Description, Scalar, Value, Variable3Description};
use robofmu_fmi::fmi3::table::Source;
use serde::Serialize;

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
    Clock(ModelVariable),
    UInt64(ModelVariable),
}

/// The attributes of a variable; those that do not apply to its type stay None.
#[derive(Serialize)]
struct ModelVariable {
    #[serde(flatten)]
    head: VariableHead,
    #[serde(
        rename = "@intermediateUpdate",
        skip_serializing_if = "Option::is_none"
    )]
    intermediate_update: Option<bool>,
    #[serde(rename = "@initial", skip_serializing_if = "Option::is_none")]
    initial: Option<&'static str>,
    /// The value reference of the clock a clocked variable belongs to.
    #[serde(rename = "@clocks", skip_serializing_if = "Option::is_none")]
    clocks: Option<u32>,
    #[serde(
        rename = "@intervalVariability",
        skip_serializing_if = "Option::is_none"
    )]
    interval_variability: Option<&'static str>,
    #[serde(rename = "@supportsFraction", skip_serializing_if = "Option::is_none")]
    supports_fraction: Option<bool>,
    #[serde(flatten)]
    attributes: TypeAttributes,
    #[serde(rename = "Dimension", skip_serializing_if = "Option::is_none")]
    dimension: Option<Dimension>,
}

/// `start` (a fixed size) or `valueReference` (the structural parameter holding it).
#[derive(Serialize)]
struct Dimension {
    #[serde(rename = "@start", skip_serializing_if = "Option::is_none")]
    start: Option<usize>,
    #[serde(rename = "@valueReference", skip_serializing_if = "Option::is_none")]
    value_reference: Option<u32>,
}

impl Dimension {
    /// The dimension of `v3`, if it is an array.
    fn of(v3: &Variable3Description) -> Option<Dimension> {
        let start = v3.variable.dimension?;
        Some(match v3.dimension_reference {
            Some(vr) => Dimension {
                start: None,
                value_reference: Some(vr),
            },
            None => Dimension {
                start: Some(start),
                value_reference: None,
            },
        })
    }
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

/// The variable `v3`: its type-specific attributes read from its first element
/// (shared by all), with the start values of every element.
fn model_variable(d: &Description, v3: &Variable3Description) -> Result<TypedVariable, String> {
    let v = &v3.variable;
    let elements: Vec<&Scalar> = v
        .elements()
        .map(|vr| scalar(d, vr))
        .collect::<Result<_, _>>()?;
    let starts: Option<Vec<String>> = elements
        .iter()
        .map(|e| crate::variable::start(&e.value))
        .collect();
    let first = elements.first().map(|e| e.value);
    if let Some(part) = v3.clock_part {
        return Ok(clock_variable(v3, part));
    }
    if let Some([start, max]) = v3.structural {
        return Ok(structural_parameter(v3, start, max));
    }
    let attributes = TypeAttributes {
        start: starts.filter(|_| first.is_some()).map(joined),
        derivative: v.derivative_of,
        ..first.as_ref().map(TypeAttributes::of).unwrap_or_default()
    };
    let out = ModelVariable {
        intermediate_update: v3.intermediate_update.then_some(true),
        ..bare(v3, attributes, Dimension::of(v3))
    };
    Ok(match first {
        None | Some(Value::Real { .. }) => TypedVariable::Float64(out),
        Some(Value::Integer { .. }) => TypedVariable::Int32(out),
        Some(Value::Boolean { .. }) => TypedVariable::Boolean(out),
    })
}

/// A variable of a clocked partition: the clock (periodic, fixed interval from its
/// parameter, which the importer may read as a fraction), its period parameter or one
/// of its outputs (`clocks` naming the clock).
fn clock_variable(v3: &Variable3Description, part: ClockPart) -> TypedVariable {
    let mut out = bare(v3, TypeAttributes::default(), Dimension::of(v3));
    match part {
        ClockPart::Clock => {
            out.interval_variability = Some("fixed");
            out.supports_fraction = Some(true);
            TypedVariable::Clock(out)
        }
        ClockPart::Period { start } => {
            out.attributes.start = Some(common::number(start));
            TypedVariable::Float64(out)
        }
        ClockPart::Output { clock, unit } => {
            out.clocks = Some(clock);
            out.attributes.unit = unit;
            TypedVariable::Float64(out)
        }
    }
}

/// A structural parameter: UInt64 from 1 to `max`, start the default size.
fn structural_parameter(v3: &Variable3Description, start: u64, max: u64) -> TypedVariable {
    let attributes = TypeAttributes {
        min: Some("1".to_string()),
        max: Some(max.to_string()),
        start: Some(start.to_string()),
        ..TypeAttributes::default()
    };
    TypedVariable::UInt64(bare(v3, attributes, None))
}

/// The variable `v3` with `attributes` and `dimension`, nothing else (no clock, no
/// intermediate update).
fn bare(
    v3: &Variable3Description,
    attributes: TypeAttributes,
    dimension: Option<Dimension>,
) -> ModelVariable {
    let v = &v3.variable;
    ModelVariable {
        head: VariableHead::new(
            v.name.to_string(),
            v.value_reference,
            v3.description.clone(),
            (v.causality, v.variability),
        ),
        intermediate_update: None,
        initial: v.initial.map(Initial::as_str),
        clocks: None,
        interval_variability: None,
        supports_fraction: None,
        attributes,
        dimension,
    }
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
    if matches!(v.source, Source::Clocked { .. }) {
        // Clocked variables are computed at ticks, not at initialization.
        return false;
    }
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

/// `<ModelExchange>` and `<CoSimulation>` of the variables `view`.
fn interfaces(d: &Description, view: &[Variable3Description]) -> (Attributes, Attributes) {
    let ticked = view
        .iter()
        .any(|v| matches!(v.clock_part, Some(ClockPart::Clock)));
    let info = &d.info;
    let derivatives = d.provides_directional_derivative;
    let common = || {
        Attributes::default()
            .with("modelIdentifier", info.model_identifier)
            .with("canGetAndSetFMUState", true)
            .with("canSerializeFMUState", true)
            .with("providesDirectionalDerivatives", derivatives)
            .with("providesAdjointDerivatives", derivatives)
            .with("providesPerElementDependencies", true)
    };
    let model_exchange = common().with("needsCompletedIntegratorStep", false);
    let co_simulation = common()
        .with("canHandleVariableCommunicationStepSize", true)
        .with("hasEventMode", true)
        // Steps end early at events (sign changes of the event indicators) and, with
        // earlyReturnAllowed, at the ticks of an input clock.
        .with_some(
            "mightReturnEarlyFromDoStep",
            (info.number_of_event_indicators > 0 || ticked).then_some(true),
        )
        .with_some(
            "maxOutputDerivativeOrder",
            common::max_output_derivative_order(d),
        )
        .with_some(
            "providesIntermediateUpdate",
            (d.intermediate_update_points > 0).then_some(true),
        );
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
    if states != d.number_of_continuous_states {
        return Err(format!(
            "{states} state derivatives but {} continuous states",
            d.number_of_continuous_states
        ));
    }
    let variables = view
        .iter()
        .map(|v| model_variable(d, v))
        .collect::<Result<Vec<_>, _>>()?;
    let parts = Parts {
        interfaces: interfaces(d, view),
        variables: ModelVariables { variables },
        structure: model_structure(view),
    };
    ModelDescription::write(d, Standard::Fmi3 { token }, parts)
}
