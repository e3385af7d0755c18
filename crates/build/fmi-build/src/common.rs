//! What FMI 2.0 and FMI 3.0 write alike: the root element [`ModelDescription`] with
//! its attributes and the sections of [`sections`](crate::sections), interfaces as
//! [`Attributes`], the generating tool and numbers. Each standard's writer fills in
//! its interfaces, variables (with [`variable`](crate::variable)) and structure.

use crate::sections::{DefaultExperiment, LogCategories, UnitDefinitions};
use robofmu_fmi::description::Description;
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
    /// The model's version: the workspace's ([`VERSION`]).
    #[serde(rename = "@version")]
    version: &'static str,
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
            version: VERSION,
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

/// The version of every FMU, written into the `version` attribute: the workspace's
/// (`[workspace.package]` of the root Cargo.toml), the version of the wheel and of
/// `cosim --version` and `robofmu --version` too.
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Name and version of the generating tool, as written into generationTool.
pub const GENERATION_TOOL: &str = concat!("robofmu ", env!("CARGO_PKG_VERSION"));

/// Shortest decimal text that reads back to the same f64.
pub fn number(v: f64) -> String {
    format!("{v:?}")
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
pub fn max_output_derivative_order(d: &Description) -> Option<u32> {
    (d.max_output_derivative_order > 0).then_some(d.max_output_derivative_order)
}
