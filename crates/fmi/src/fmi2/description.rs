//! modelDescription.xml generated from a model's `ModelInfo` and variable table.

use super::instance::log_categories;
use crate::core::model::Model;
use crate::core::units::{UnitDefinition, unit};
use crate::core::variables::{
    Causality, Initial, Kind, Variable, check_table, derivative_variables,
};
use serde::Serialize;

/// Name and version of the generating tool, as written into generationTool.
pub const GENERATION_TOOL: &str = concat!("robofmu ", env!("CARGO_PKG_VERSION"));

#[derive(Serialize)]
#[serde(rename = "fmiModelDescription")]
struct ModelDescription {
    #[serde(rename = "@fmiVersion")]
    fmi_version: &'static str,
    #[serde(rename = "@modelName")]
    model_name: &'static str,
    #[serde(rename = "@guid")]
    guid: &'static str,
    #[serde(rename = "@description")]
    description: &'static str,
    #[serde(rename = "@generationTool")]
    generation_tool: &'static str,
    #[serde(rename = "@variableNamingConvention")]
    naming: &'static str,
    #[serde(rename = "@numberOfEventIndicators")]
    event_indicators: usize,
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
    #[serde(
        rename = "@canHandleVariableCommunicationStepSize",
        skip_serializing_if = "Option::is_none"
    )]
    variable_step: Option<bool>,
    #[serde(rename = "@canGetAndSetFMUstate")]
    get_set_state: bool,
    #[serde(rename = "@canSerializeFMUstate")]
    serialize_state: bool,
    #[serde(rename = "@providesDirectionalDerivative")]
    directional_derivative: bool,
}

#[derive(Serialize)]
struct UnitDefinitions {
    #[serde(rename = "Unit")]
    units: Vec<Unit>,
}

#[derive(Serialize)]
struct Unit {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "BaseUnit")]
    base: BaseUnit,
    #[serde(rename = "DisplayUnit")]
    display_units: Vec<DisplayUnit>,
}

#[derive(Serialize)]
struct BaseUnit {
    #[serde(rename = "@kg", skip_serializing_if = "is_zero")]
    kg: i32,
    #[serde(rename = "@m", skip_serializing_if = "is_zero")]
    m: i32,
    #[serde(rename = "@s", skip_serializing_if = "is_zero")]
    s: i32,
    #[serde(rename = "@rad", skip_serializing_if = "is_zero")]
    rad: i32,
}

fn is_zero(v: &i32) -> bool {
    *v == 0
}

#[derive(Serialize)]
struct DisplayUnit {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "@factor")]
    factor: String,
}

#[derive(Serialize)]
struct LogCategories {
    #[serde(rename = "Category")]
    categories: Vec<Category>,
}

#[derive(Serialize)]
struct Category {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "@description")]
    description: &'static str,
}

#[derive(Serialize)]
struct DefaultExperiment {
    #[serde(rename = "@startTime")]
    start_time: String,
    #[serde(rename = "@stopTime")]
    stop_time: String,
    #[serde(rename = "@tolerance")]
    tolerance: String,
    #[serde(rename = "@stepSize")]
    step_size: String,
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

/// Shortest decimal text that reads back to the same f64.
fn number(v: f64) -> String {
    format!("{v:?}")
}

/// A list of unknowns, or None when empty (an empty list element is omitted).
fn unknown_list(unknowns: Vec<Unknown>) -> Option<UnknownList> {
    (!unknowns.is_empty()).then_some(UnknownList { unknowns })
}

/// An unknown without dependencies (it depends on all knowns).
fn plain(index: usize) -> Unknown {
    Unknown {
        index,
        dependencies: None,
    }
}

/// The unknown `v` with its declared dependencies as ascending 1-based indices.
fn with_dependencies<M>(v: &Variable<M>, table: &[Variable<M>]) -> Unknown {
    let index_of = |name: &str| table.iter().position(|s| s.name == name).map(|i| i + 1);
    let dependencies = v.dependencies.as_ref().map(|names| {
        let mut indices: Vec<usize> = names.iter().filter_map(|n| index_of(n)).collect();
        indices.sort_unstable();
        indices.dedup();
        indices
            .iter()
            .map(usize::to_string)
            .collect::<Vec<_>>()
            .join(" ")
    });
    Unknown {
        index: index_of(&v.name).unwrap_or(0),
        dependencies,
    }
}

fn scalar_variable<M>(v: &Variable<M>, table: &[Variable<M>]) -> ScalarVariable {
    let index_of = |name: &str| table.iter().position(|s| s.name == name).map(|i| i + 1);
    let kind = match &v.kind {
        Kind::Real {
            start,
            min,
            max,
            unit,
            display_unit,
            derivative_of,
            ..
        } => TypeElement::Real(RealAttributes {
            unit: *unit,
            display_unit: *display_unit,
            min: min.map(number),
            max: max.map(number),
            start: start.map(number),
            derivative: derivative_of.as_deref().and_then(index_of),
        }),
        Kind::Integer {
            start, min, max, ..
        } => TypeElement::Integer(IntegerAttributes {
            min: *min,
            max: *max,
            start: *start,
        }),
        Kind::Boolean { start, .. } => TypeElement::Boolean(BooleanAttributes { start: *start }),
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

/// The units the table uses, in the order of the layer's unit list, after checking
/// that every unit and display unit is defined.
fn used_units<M>(table: &[Variable<M>]) -> Result<Vec<&'static UnitDefinition>, String> {
    let mut used: Vec<&'static UnitDefinition> = Vec::new();
    for v in table {
        if let Kind::Real {
            unit: Some(name),
            display_unit,
            ..
        } = &v.kind
        {
            let def = unit(name).ok_or_else(|| format!("\"{}\": unknown unit {name}", v.name))?;
            if let Some(d) = display_unit
                && !def.display_units.iter().any(|du| du.name == *d)
            {
                return Err(format!(
                    "\"{}\": {d} is not a display unit of {name}",
                    v.name
                ));
            }
            if !used.iter().any(|u| u.name == def.name) {
                used.push(def);
            }
        }
    }
    used.sort_by_key(|u| {
        crate::core::units::UNITS
            .iter()
            .position(|k| k.name == u.name)
    });
    Ok(used)
}

/// The text of modelDescription.xml for model M.
pub fn model_description<M: Model>() -> Result<String, String> {
    let info = M::info();
    let sorted = crate::core::instance::sorted_table::<M>()?;
    let table = &sorted[..];
    check_table(table)?;
    let derivatives = derivative_variables(table);
    if derivatives.len() != info.number_of_continuous_states {
        return Err(format!(
            "{} derivative variables but {} continuous states",
            derivatives.len(),
            info.number_of_continuous_states
        ));
    }
    let index_of = |v: &Variable<M>| {
        table
            .iter()
            .position(|s| s.value_reference == v.value_reference)
            .map_or(0, |i| i + 1)
    };
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
        .map(|v| plain(index_of(v)))
        .collect();
    let units = used_units(table)?;
    let interface = |variable_step: Option<bool>| Interface {
        model_identifier: info.model_identifier,
        variable_step,
        get_set_state: true,
        serialize_state: true,
        directional_derivative: info.provides_directional_derivative,
    };
    let experiment = info.default_experiment;
    let description = ModelDescription {
        fmi_version: "2.0",
        model_name: info.model_name,
        guid: info.guid,
        description: info.description,
        generation_tool: GENERATION_TOOL,
        naming: "structured",
        event_indicators: info.number_of_event_indicators,
        model_exchange: interface(None),
        co_simulation: interface(Some(true)),
        unit_definitions: (!units.is_empty()).then(|| UnitDefinitions {
            units: units
                .iter()
                .map(|u| Unit {
                    name: u.name,
                    base: BaseUnit {
                        kg: u.base.kg,
                        m: u.base.m,
                        s: u.base.s,
                        rad: u.base.rad,
                    },
                    display_units: u
                        .display_units
                        .iter()
                        .map(|d| DisplayUnit {
                            name: d.name,
                            factor: number(d.factor),
                        })
                        .collect(),
                })
                .collect(),
        }),
        log_categories: LogCategories {
            categories: log_categories::<M>()
                .iter()
                .map(|c| Category {
                    name: c.name,
                    description: c.description,
                })
                .collect(),
        },
        default_experiment: DefaultExperiment {
            start_time: number(experiment.start_time),
            stop_time: number(experiment.stop_time),
            tolerance: number(experiment.tolerance),
            step_size: number(experiment.step_size),
        },
        model_variables: ModelVariables {
            variables: table.iter().map(|v| scalar_variable(v, table)).collect(),
        },
        model_structure: ModelStructure {
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
    let mut xml = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let mut serializer = quick_xml::se::Serializer::new(&mut xml);
    serializer.indent(' ', 2);
    description
        .serialize(serializer)
        .map_err(|e| format!("XML serialization failed: {e}"))?;
    xml.push('\n');
    Ok(xml)
}

/// The drift check of an FMU crate: the checked-in `<dir>/<modelName>.xml` must equal
/// what the code generates. With the environment variable UPDATE_MODEL_DESCRIPTION
/// set, the file is rewritten first.
pub fn check_checked_in<M: Model>(dir: &std::path::Path) -> Result<(), String> {
    let generated = model_description::<M>()?;
    let path = dir.join(format!("{}.xml", M::info().model_name));
    if std::env::var_os("UPDATE_MODEL_DESCRIPTION").is_some() {
        std::fs::write(&path, &generated).map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let on_disk = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    if on_disk != generated {
        return Err(format!(
            "{} drifted from the code: rerun this test with UPDATE_MODEL_DESCRIPTION=1",
            path.display()
        ));
    }
    Ok(())
}
