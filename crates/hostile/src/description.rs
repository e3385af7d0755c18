//! What an importer reads from modelDescription.xml: identity, counts and the
//! variable list (name, value reference, type, causality, variability, start).

use quick_xml::events::{BytesStart, Event};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VarType {
    Real,
    Integer,
    Boolean,
}

#[derive(Debug, Clone)]
pub struct Variable {
    pub name: String,
    pub vr: u32,
    pub var_type: VarType,
    pub causality: String,
    pub variability: String,
    /// Start value as written (None for calculated variables).
    pub start: Option<String>,
    /// For a state derivative: the 1-based index of its state variable.
    pub derivative_of: Option<usize>,
}

impl Variable {
    /// Parameters and inputs: what a host sets.
    pub fn is_settable(&self) -> bool {
        matches!(self.causality.as_str(), "parameter" | "input")
    }
    pub fn is_parameter(&self) -> bool {
        self.causality == "parameter"
    }
}

#[derive(Debug, Clone)]
pub struct Description {
    pub model_name: String,
    pub guid: String,
    pub model_identifier: String,
    pub number_of_event_indicators: usize,
    pub number_of_states: usize,
    pub provides_directional_derivative: bool,
    pub variables: Vec<Variable>,
}

impl Description {
    pub fn of_type(&self, t: VarType) -> impl Iterator<Item = &Variable> {
        self.variables.iter().filter(move |v| v.var_type == t)
    }
    pub fn by_name(&self, name: &str) -> &Variable {
        self.variables
            .iter()
            .find(|v| v.name == name)
            .unwrap_or_else(|| panic!("{} has no variable {name}", self.model_name))
    }
    /// (state, derivative) value references, in the order of the state vector.
    pub fn state_derivative_pairs(&self) -> Vec<(u32, u32)> {
        self.variables
            .iter()
            .filter_map(|d| {
                let state = self.variables.get(d.derivative_of? - 1)?;
                Some((state.vr, d.vr))
            })
            .collect()
    }

    /// Value references of every Real variable (what a master reads each step).
    pub fn real_vrs(&self) -> Vec<u32> {
        self.of_type(VarType::Real).map(|v| v.vr).collect()
    }
}

fn attribute(e: &BytesStart, name: &str) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == name)
        .and_then(|a| {
            a.normalized_value(quick_xml::XmlVersion::Explicit1_0)
                .ok()
                .map(|v| v.into_owned())
        })
}

/// Parses the text of a modelDescription.xml (FMI 2.0).
pub fn parse(xml: &str) -> Result<Description, String> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut d = Description {
        model_name: String::new(),
        guid: String::new(),
        model_identifier: String::new(),
        number_of_event_indicators: 0,
        number_of_states: 0,
        provides_directional_derivative: false,
        variables: Vec::new(),
    };
    let mut pending: Option<Variable> = None;
    let mut in_derivatives = false;
    loop {
        let event = reader.read_event().map_err(|e| e.to_string())?;
        match &event {
            Event::Start(e) | Event::Empty(e) => {
                read_element(e, &mut d, &mut pending, in_derivatives)?;
                if e.name().as_ref() == "Derivatives" && matches!(event, Event::Start(_)) {
                    in_derivatives = true;
                }
            }
            Event::End(e) => match e.name().as_ref() {
                "ScalarVariable" => d.variables.extend(pending.take()),
                "Derivatives" => in_derivatives = false,
                _ => {}
            },
            Event::Eof => break,
            _ => {}
        }
    }
    if d.guid.is_empty() || d.model_identifier.is_empty() {
        return Err("modelDescription has no guid or no ModelExchange element".into());
    }
    Ok(d)
}

fn read_element(
    e: &BytesStart,
    d: &mut Description,
    pending: &mut Option<Variable>,
    in_derivatives: bool,
) -> Result<(), String> {
    let get = |n: &str| attribute(e, n);
    match e.name().as_ref() {
        "fmiModelDescription" => {
            d.model_name = get("modelName").unwrap_or_default();
            d.guid = get("guid").unwrap_or_default();
            d.number_of_event_indicators = get("numberOfEventIndicators").map_or(Ok(0), |n| {
                n.parse().map_err(|_| "bad numberOfEventIndicators")
            })?;
        }
        "ModelExchange" => {
            d.model_identifier = get("modelIdentifier").unwrap_or_default();
            d.provides_directional_derivative =
                get("providesDirectionalDerivative").as_deref() == Some("true");
        }
        "ScalarVariable" => {
            *pending = Some(Variable {
                name: get("name").unwrap_or_default(),
                vr: get("valueReference")
                    .and_then(|v| v.parse().ok())
                    .ok_or("a ScalarVariable without a valid valueReference")?,
                var_type: VarType::Real,
                causality: get("causality").unwrap_or_else(|| "local".into()),
                variability: get("variability").unwrap_or_else(|| "continuous".into()),
                start: None,
                derivative_of: None,
            });
        }
        "Real" | "Integer" | "Boolean" => {
            if let Some(v) = pending.as_mut() {
                v.var_type = match e.name().as_ref() {
                    "Real" => VarType::Real,
                    "Integer" => VarType::Integer,
                    _ => VarType::Boolean,
                };
                v.start = get("start");
                v.derivative_of = get("derivative").and_then(|k| k.parse().ok());
            }
        }
        "Unknown" if in_derivatives => d.number_of_states += 1,
        _ => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_plant_description() {
        // Expected values: the checked-in modelDescription/Pss3Plant.xml (96
        // ScalarVariables, six <Unknown> under <Derivatives>, theta[2] has
        // valueReference 102, the state of variable 13 is theta[1] = vr 101).
        let xml = include_str!("../../../modelDescription/Pss3Plant.xml");
        let d = parse(xml).unwrap();
        assert_eq!(d.model_name, "Pss3Plant");
        assert_eq!(d.model_identifier, "Pss3Plant");
        assert_eq!(d.variables.len(), 96);
        assert_eq!(d.number_of_states, 6);
        assert_eq!(d.number_of_event_indicators, 6);
        assert!(d.provides_directional_derivative);
        assert_eq!(d.by_name("theta[2]").vr, 102);
        assert_eq!(d.state_derivative_pairs().len(), 6);
        assert_eq!(d.state_derivative_pairs()[0].0, 101);
        assert_eq!(d.by_name("endStopMode").var_type, VarType::Integer);
    }

    #[test]
    fn refuses_a_description_without_guid() {
        assert!(parse("<fmiModelDescription modelName=\"x\"/>").is_err());
    }
}
