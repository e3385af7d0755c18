//! The parts of modelDescription.xml that FMI 2.0 and FMI 3.0 write alike: the root
//! element [`ModelDescription`] with its attributes, the generating tool, numbers,
//! `<UnitDefinitions>` (units and display units the scalars use), `<LogCategories>`
//! and `<DefaultExperiment>`. Each standard's writer fills in its interfaces,
//! variables and structure.

use crate::units::{UNITS, UnitDefinition, unit};
use robofmu_fmi::core::logging::LogCategory;
use robofmu_fmi::core::model::{DefaultExperiment as Experiment, ModelInfo};
use robofmu_fmi::core::variables::{Causality, Variability};
use robofmu_fmi::description::{Description, Scalar, Value};
use serde::Serialize;
use serde::ser::{SerializeMap, Serializer};

/// `<fmiModelDescription>` of either standard, with the standard's variables `V` and
/// structure `S`.
#[derive(Serialize)]
#[serde(rename = "fmiModelDescription")]
pub struct ModelDescription<V, S> {
    #[serde(rename = "@fmiVersion")]
    fmi_version: &'static str,
    #[serde(rename = "@modelName")]
    model_name: &'static str,
    /// FMI 2.0.
    #[serde(rename = "@guid", skip_serializing_if = "Option::is_none")]
    guid: Option<String>,
    /// FMI 3.0.
    #[serde(
        rename = "@instantiationToken",
        skip_serializing_if = "Option::is_none"
    )]
    instantiation_token: Option<String>,
    #[serde(rename = "@description")]
    description: &'static str,
    #[serde(rename = "@generationTool")]
    generation_tool: &'static str,
    #[serde(rename = "@variableNamingConvention")]
    naming: &'static str,
    /// FMI 2.0.
    #[serde(
        rename = "@numberOfEventIndicators",
        skip_serializing_if = "Option::is_none"
    )]
    event_indicators: Option<usize>,
    #[serde(rename = "ModelExchange")]
    model_exchange: Attributes,
    #[serde(rename = "CoSimulation")]
    co_simulation: Attributes,
    #[serde(rename = "UnitDefinitions", skip_serializing_if = "Option::is_none")]
    unit_definitions: Option<UnitDefinitions>,
    #[serde(rename = "LogCategories")]
    log_categories: LogCategories,
    #[serde(rename = "DefaultExperiment")]
    default_experiment: DefaultExperiment,
    #[serde(rename = "ModelVariables")]
    model_variables: V,
    #[serde(rename = "ModelStructure")]
    model_structure: S,
}

/// The standard a description is written for, with its instantiation token.
pub enum Standard {
    Fmi2,
    Fmi3 { token: String },
}

/// What a standard's writer contributes: its two interfaces (Model Exchange,
/// Co-Simulation), variables and structure.
pub struct Parts<V, S> {
    pub interfaces: (Attributes, Attributes),
    pub variables: V,
    pub structure: S,
}

/// An element that has attributes only, written in the order they were added
/// (`<ModelExchange>`, `<CoSimulation>`: each standard names its own).
#[derive(Default)]
pub struct Attributes(Vec<(&'static str, String)>);

impl Attributes {
    /// The attribute `name` = `value` added.
    pub fn with(mut self, name: &'static str, value: impl ToString) -> Self {
        self.0.push((name, value.to_string()));
        self
    }

    /// The attribute `name` added when `value` is Some (left out otherwise).
    pub fn with_some(self, name: &'static str, value: Option<impl ToString>) -> Self {
        match value {
            Some(v) => self.with(name, v),
            None => self,
        }
    }
}

impl Serialize for Attributes {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(&format!("@{name}"), value)?;
        }
        map.end()
    }
}

impl<V: Serialize, S: Serialize> ModelDescription<V, S> {
    /// The text of the description of `d` for `standard` from that standard's parts.
    pub fn write(
        d: &Description,
        standard: Standard,
        parts: Parts<V, S>,
    ) -> Result<String, String> {
        let info = &d.info;
        let (fmi_version, guid, instantiation_token, event_indicators, categories) = match standard
        {
            Standard::Fmi2 => (
                "2.0",
                Some(info.guid.to_string()),
                None,
                Some(info.number_of_event_indicators),
                &d.log_categories[0],
            ),
            Standard::Fmi3 { token } => ("3.0", None, Some(token), None, &d.log_categories[1]),
        };
        let (model_exchange, co_simulation) = parts.interfaces;
        xml_document(&ModelDescription {
            fmi_version,
            model_name: info.model_name,
            guid,
            instantiation_token,
            description: info.description,
            generation_tool: GENERATION_TOOL,
            naming: "structured",
            event_indicators,
            model_exchange,
            co_simulation,
            unit_definitions: UnitDefinitions::of(&d.scalars)?,
            log_categories: LogCategories::of(categories),
            default_experiment: DefaultExperiment::of(&info.default_experiment),
            model_variables: parts.variables,
            model_structure: parts.structure,
        })
    }
}

/// Name and version of the generating tool, as written into generationTool.
pub const GENERATION_TOOL: &str = concat!("robofmu ", env!("CARGO_PKG_VERSION"));

/// Shortest decimal text that reads back to the same f64.
pub fn number(v: f64) -> String {
    format!("{v:?}")
}

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

/// `<UnitDefinitions>`.
#[derive(Serialize)]
pub struct UnitDefinitions {
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

impl UnitDefinitions {
    /// The units `table` uses (None: no unit), in the order of the layer's unit list,
    /// after checking that every unit and display unit is defined.
    pub fn of(table: &[Scalar]) -> Result<Option<UnitDefinitions>, String> {
        let units = used_units(table)?;
        Ok((!units.is_empty()).then(|| UnitDefinitions {
            units: units.iter().map(|u| Unit::of(u)).collect(),
        }))
    }
}

impl Unit {
    fn of(u: &UnitDefinition) -> Unit {
        Unit {
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
        }
    }
}

fn used_units(table: &[Scalar]) -> Result<Vec<&'static UnitDefinition>, String> {
    let mut used: Vec<&'static UnitDefinition> = Vec::new();
    for v in table {
        if let Value::Real {
            unit: Some(name),
            display_unit,
            ..
        } = &v.value
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
    used.sort_by_key(|u| UNITS.iter().position(|k| k.name == u.name));
    Ok(used)
}

/// `<LogCategories>`.
#[derive(Serialize)]
pub struct LogCategories {
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

impl LogCategories {
    pub fn of(categories: &[LogCategory]) -> LogCategories {
        LogCategories {
            categories: categories
                .iter()
                .map(|c| Category {
                    name: c.name,
                    description: c.description,
                })
                .collect(),
        }
    }
}

/// `<DefaultExperiment>`.
#[derive(Serialize)]
pub struct DefaultExperiment {
    #[serde(rename = "@startTime")]
    start_time: String,
    #[serde(rename = "@stopTime")]
    stop_time: String,
    #[serde(rename = "@tolerance")]
    tolerance: String,
    #[serde(rename = "@stepSize")]
    step_size: String,
}

impl DefaultExperiment {
    pub fn of(e: &Experiment) -> DefaultExperiment {
        DefaultExperiment {
            start_time: number(e.start_time),
            stop_time: number(e.stop_time),
            tolerance: number(e.tolerance),
            step_size: number(e.step_size),
        }
    }
}

/// The XML document of `root`: the XML declaration, `root` indented by two spaces, and
/// a final newline.
fn xml_document<T: Serialize>(root: &T) -> Result<String, String> {
    let mut xml = String::from("<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    let mut serializer = quick_xml::se::Serializer::new(&mut xml);
    serializer.indent(' ', 2);
    root.serialize(serializer)
        .map_err(|e| format!("XML serialization failed: {e}"))?;
    xml.push('\n');
    Ok(xml)
}

/// The maxOutputDerivativeOrder attribute of `<CoSimulation>`: left out (default 0) when
/// the model provides no output derivatives.
pub fn max_output_derivative_order(info: &ModelInfo) -> Option<u32> {
    (info.max_output_derivative_order > 0).then_some(info.max_output_derivative_order)
}
