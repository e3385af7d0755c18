//! modelDescription.xml of FMI 3.0, generated from a model's `ModelInfo` and the FMI 3.0
//! view of its variable table (`table::Table3`): Float64 / Int32 / Boolean variables,
//! arrays with `<Dimension>`, units with display units, and the ModelStructure
//! (`<Output>`, `<ContinuousStateDerivative>`, `<InitialUnknown>`, `<EventIndicator>`
//! with their dependencies as value references).

use crate::common::{
    self, DefaultExperiment, GENERATION_TOOL, LogCategories, UnitDefinitions, number,
};
use robofmu_fmi::core::check::check_table;
use robofmu_fmi::core::frontend::log_categories;
use robofmu_fmi::core::instance::sorted_table;
use robofmu_fmi::core::model::Model;
use robofmu_fmi::core::variables::{Causality, Initial, Kind, Variable, find};
use robofmu_fmi::fmi3::declared::view;
use robofmu_fmi::fmi3::mode::Fmi3;
use robofmu_fmi::fmi3::scalar;
use robofmu_fmi::fmi3::table::{self, Table3, Variable3};
use serde::Serialize;

#[derive(Serialize)]
#[serde(rename = "fmiModelDescription")]
struct ModelDescription {
    #[serde(rename = "@fmiVersion")]
    fmi_version: &'static str,
    #[serde(rename = "@modelName")]
    model_name: &'static str,
    #[serde(rename = "@instantiationToken")]
    instantiation_token: String,
    #[serde(rename = "@description")]
    description: &'static str,
    #[serde(rename = "@generationTool")]
    generation_tool: &'static str,
    #[serde(rename = "@variableNamingConvention")]
    naming: &'static str,
    #[serde(rename = "ModelExchange")]
    model_exchange: Interface,
    #[serde(rename = "CoSimulation")]
    co_simulation: Interface,
    #[serde(rename = "UnitDefinitions", skip_serializing_if = "Option::is_none")]
    unit_definitions: Option<UnitDefinitions>,
    #[serde(rename = "LogCategories")]
    log_categories: LogCategories,
    #[serde(rename = "DefaultExperiment")]
    default_experiment: DefaultExperiment,
    #[serde(rename = "ModelVariables")]
    model_variables: ModelVariables,
    #[serde(rename = "ModelStructure")]
    model_structure: ModelStructure,
}

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

/// The type-specific attributes of `v`, read from its first element (shared by all)
/// and the start values of every element.
fn model_variable<M: Model>(table: &[Variable<M>], v: &Variable3) -> Result<TypedVariable, String> {
    let mut out = ModelVariable {
        name: v.name.to_string(),
        value_reference: v.value_reference,
        description: table::description(table, v),
        causality: v.causality.as_str(),
        variability: v.variability.as_str(),
        intermediate_update: v.intermediate_update::<M>().then_some(true),
        initial: v.initial.map(Initial::as_str),
        unit: None,
        display_unit: None,
        min: None,
        max: None,
        start: None,
        derivative: v.derivative_of,
        dimension: v.dimension.map(|start| Dimension { start }),
    };
    let elements: Vec<_> = v
        .elements()
        .map(|vr| find(table, vr).ok_or_else(|| format!("no element {vr}")))
        .collect::<Result<_, _>>()?;
    let Some(first) = elements.first() else {
        return Ok(TypedVariable::Float64(out));
    };
    let starts: Option<Vec<String>> = elements
        .iter()
        .map(|e| match &e.kind {
            Kind::Real { start, .. } => start.map(number),
            Kind::Integer { start, .. } => start.map(|s| s.to_string()),
            Kind::Boolean { start, .. } => start.map(|s| s.to_string()),
        })
        .collect();
    out.start = starts.map(joined);
    Ok(match &first.kind {
        Kind::Real {
            unit,
            display_unit,
            min,
            max,
            ..
        } => {
            out.unit = *unit;
            out.display_unit = *display_unit;
            out.min = min.map(number);
            out.max = max.map(number);
            TypedVariable::Float64(out)
        }
        Kind::Integer { min, max, .. } => {
            out.min = min.map(|m| m.to_string());
            out.max = max.map(|m| m.to_string());
            TypedVariable::Int32(out)
        }
        Kind::Boolean { .. } => TypedVariable::Boolean(out),
    })
}

/// The dependencies (ascending value references; None: all knowns) of an unknown, the
/// second argument choosing the initial ones; per view.
type DependencyOf<'a> = dyn Fn(&Variable3, bool) -> Result<Option<Vec<u32>>, String> + 'a;

fn dependencies(deps: &DependencyOf, v: &Variable3, initial: bool) -> Result<Dependencies, String> {
    Ok(Dependencies {
        value_reference: v.value_reference,
        dependencies: deps(v, initial)?.map(joined),
    })
}

/// The dependencies of `v` in the array view (by FMI 3.0 variable).
fn array_dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
    initial: bool,
) -> Result<Option<Vec<u32>>, String> {
    if initial {
        table::initial_dependencies(table, v)
    } else {
        table::dependencies(table, v)
    }
}

/// The dependencies of `v` in the scalar view (by table scalar); time and the event
/// indicators (no table element) depend on all knowns.
fn scalar_dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
    initial: bool,
) -> Result<Option<Vec<u32>>, String> {
    let Some(vr) = v.elements().next() else {
        return array_dependencies(table, v, initial);
    };
    let s = find(table, vr).ok_or_else(|| format!("no element {vr}"))?;
    let names = if initial {
        s.initial_dependencies
    } else {
        s.dependencies
    };
    names.map(|n| scalar::references(table, n)).transpose()
}

/// Whether `v` is an initial unknown (section 2.4.8 of FMI 3.0): outputs and state
/// derivatives computed at initialization, and calculated parameters.
fn is_initial_unknown(v: &Variable3) -> bool {
    let calculated = matches!(v.initial, Some(Initial::Calculated | Initial::Approx));
    (calculated && (v.causality == Causality::Output || v.derivative_of.is_some()))
        || v.causality == Causality::CalculatedParameter
}

fn model_structure(deps: &DependencyOf, t: &Table3) -> Result<ModelStructure, String> {
    let all = || t.variables.iter();
    let mut unknowns: Vec<Unknown> = all()
        .filter(|v| v.causality == Causality::Output)
        .map(|v| dependencies(deps, v, false).map(Unknown::Output))
        .collect::<Result<_, _>>()?;
    for v in t.derivatives() {
        unknowns.push(Unknown::ContinuousStateDerivative(dependencies(
            deps, v, false,
        )?));
    }
    for v in all().filter(|v| is_initial_unknown(v)) {
        unknowns.push(Unknown::InitialUnknown(dependencies(deps, v, true)?));
    }
    for v in t.event_indicators() {
        unknowns.push(Unknown::EventIndicator(dependencies(deps, v, false)?));
    }
    Ok(ModelStructure { unknowns })
}

fn interfaces<M: Model>() -> (Interface, Interface) {
    let info = M::info();
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
        provides_intermediate_update: (M::INTERMEDIATE_UPDATE_POINTS > 0).then_some(true),
        ..common()
    };
    (model_exchange, co_simulation)
}

/// The text of the FMI 3.0 modelDescription.xml for model M.
pub fn model_description<M: Model>() -> Result<String, String> {
    description::<M>(false)
}

/// The text of the scalar-only FMI 3.0 modelDescription.xml for model M (every FMI 2.0
/// scalar an FMI 3.0 scalar, instantiationToken `scalar::token`).
pub fn scalar_model_description<M: Model>() -> Result<String, String> {
    description::<M>(true)
}

fn description<M: Model>(scalar_view: bool) -> Result<String, String> {
    let info = M::info();
    let table = sorted_table::<M>()?;
    check_table(&table)?;
    let t = view::<M>(&table)?;
    let t = if scalar_view {
        scalar::view(&table, &t)?
    } else {
        t
    };
    let array_deps = |v: &Variable3, i| array_dependencies(&table, v, i);
    let scalar_deps = |v: &Variable3, i| scalar_dependencies(&table, v, i);
    let deps: &DependencyOf = if scalar_view {
        &scalar_deps
    } else {
        &array_deps
    };
    let token = if scalar_view {
        scalar::token::<M>()
    } else {
        info.guid.to_string()
    };
    let states: usize = t.derivatives().map(Variable3::size).sum();
    if states != info.number_of_continuous_states {
        return Err(format!(
            "{states} state derivatives but {} continuous states",
            info.number_of_continuous_states
        ));
    }
    let variables = t
        .variables
        .iter()
        .map(|v| model_variable(&table, v))
        .collect::<Result<Vec<_>, _>>()?;
    let (model_exchange, co_simulation) = interfaces::<M>();
    let description = ModelDescription {
        fmi_version: "3.0",
        model_name: info.model_name,
        instantiation_token: token,
        description: info.description,
        generation_tool: GENERATION_TOOL,
        naming: "structured",
        model_exchange,
        co_simulation,
        unit_definitions: UnitDefinitions::of(&table)?,
        log_categories: LogCategories::of(&log_categories::<Fmi3, M>()),
        default_experiment: DefaultExperiment::of(&info.default_experiment),
        model_variables: ModelVariables { variables },
        model_structure: model_structure(deps, &t)?,
    };
    common::xml_document(&description)
}

/// The drift check of an FMU crate: the checked-in `<dir>/<modelName>.xml` (dir:
/// `modelDescription/fmi3`) must equal what the code generates. With the environment
/// variable UPDATE_MODEL_DESCRIPTION set, the file is rewritten first.
pub fn check_checked_in<M: Model>(dir: &std::path::Path) -> Result<(), String> {
    common::check_checked_in::<M>(dir, &model_description::<M>()?)
}

/// The drift check of the scalar-only description (dir: `modelDescription/fmi3-scalar`).
pub fn check_scalar_checked_in<M: Model>(dir: &std::path::Path) -> Result<(), String> {
    common::check_checked_in::<M>(dir, &scalar_model_description::<M>()?)
}
