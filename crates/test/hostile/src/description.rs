//! What an importer reads from modelDescription.xml, FMI 2.0 or FMI 3.0: identity,
//! counts and the variable list (name, value reference, type, causality,
//! variability, start, array size). FMI 3.0 Float64/Int32 map to Real/Integer.

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
    /// Number of elements (FMI 3.0 arrays; 1 for scalars and in FMI 2.0).
    pub size: usize,
    /// FMI 3.0 intermediateUpdate="true": readable in Intermediate Update Mode.
    pub intermediate_update: bool,
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
    /// "2.0" or "3.0".
    pub fmi_version: String,
    pub model_name: String,
    pub guid: String,
    pub model_identifier: String,
    pub number_of_event_indicators: usize,
    pub number_of_states: usize,
    pub provides_directional_derivative: bool,
    pub variables: Vec<Variable>,
    /// FMI 3.0: unknowns of the ModelStructure with a non-empty dependency list.
    pub dependents: Vec<u32>,
    /// FMI 3.0: the structural parameters (UInt64, causality="structuralParameter"),
    /// (value reference, start): the default size of the arrays they size.
    pub structural: Vec<(u32, usize)>,
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

    /// Elements behind value references `vrs` (nValues of an FMI 3.0 call).
    pub fn elements(&self, vrs: &[u32]) -> usize {
        vrs.iter()
            .map(|vr| {
                self.variables
                    .iter()
                    .find(|v| v.vr == *vr)
                    .map_or(1, |v| v.size)
            })
            .sum()
    }

    pub fn is_fmi3(&self) -> bool {
        self.fmi_version.starts_with('3')
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

/// Parses the text of a modelDescription.xml (FMI 2.0 or 3.0).
pub fn parse(xml: &str) -> Result<Description, String> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut d = Description {
        fmi_version: String::new(),
        model_name: String::new(),
        guid: String::new(),
        model_identifier: String::new(),
        number_of_event_indicators: 0,
        number_of_states: 0,
        provides_directional_derivative: false,
        variables: Vec::new(),
        dependents: Vec::new(),
        structural: Vec::new(),
    };
    let mut pending: Option<Variable> = None;
    let mut in_derivatives = false;
    loop {
        let event = reader.read_event().map_err(|e| e.to_string())?;
        match &event {
            Event::Start(e) | Event::Empty(e) => {
                read_element(e, &mut d, &mut pending, in_derivatives)?;
                if d.is_fmi3()
                    && matches!(event, Event::Empty(_))
                    && is_fmi3_variable(e.name().as_ref())
                {
                    d.variables.extend(pending.take());
                }
                if e.name().as_ref() == "Derivatives" && matches!(event, Event::Start(_)) {
                    in_derivatives = true;
                }
            }
            Event::End(e) => match e.name().as_ref() {
                "ScalarVariable" => d.variables.extend(pending.take()),
                name if d.is_fmi3() && is_fmi3_variable(name) => d.variables.extend(pending.take()),
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
    if d.is_fmi3() {
        index_fmi3_derivatives(&mut d);
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
            d.fmi_version = get("fmiVersion").unwrap_or_default();
            d.model_name = get("modelName").unwrap_or_default();
            d.guid = get("guid")
                .or_else(|| get("instantiationToken"))
                .unwrap_or_default();
            d.number_of_event_indicators = get("numberOfEventIndicators").map_or(Ok(0), |n| {
                n.parse().map_err(|_| "bad numberOfEventIndicators")
            })?;
        }
        "ModelExchange" => {
            d.model_identifier = get("modelIdentifier").unwrap_or_default();
            d.provides_directional_derivative = get("providesDirectionalDerivative")
                .or_else(|| get("providesDirectionalDerivatives"))
                .as_deref()
                == Some("true");
        }
        _ if d.is_fmi3() => read_fmi3_element(e, d, pending)?,
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
                size: 1,
                intermediate_update: false,
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

fn is_fmi3_variable(element: &str) -> bool {
    matches!(element, "Float64" | "Int32" | "Boolean")
}

/// FMI 3.0: variables are the type elements themselves (with a Dimension child for
/// arrays); states and event indicators are counted in elements.
fn read_fmi3_element(
    e: &BytesStart,
    d: &mut Description,
    pending: &mut Option<Variable>,
) -> Result<(), String> {
    let get = |n: &str| attribute(e, n);
    let var_type = match e.name().as_ref() {
        "Float64" => Some(VarType::Real),
        "Int32" => Some(VarType::Integer),
        "Boolean" => Some(VarType::Boolean),
        _ => None,
    };
    let size_of = |d: &Description, vr: Option<u32>| {
        vr.and_then(|vr| d.variables.iter().find(|v| v.vr == vr))
            .map_or(1, |v| v.size)
    };
    let vr = get("valueReference").and_then(|v| v.parse::<u32>().ok());
    match (e.name().as_ref(), var_type) {
        (_, Some(var_type)) => {
            *pending = Some(Variable {
                name: get("name").unwrap_or_default(),
                vr: vr.ok_or("a variable without a valid valueReference")?,
                var_type,
                causality: get("causality").unwrap_or_else(|| "local".into()),
                variability: get("variability").unwrap_or_else(|| "continuous".into()),
                start: get("start"),
                // The state's value reference for now; an index after parsing.
                derivative_of: get("derivative").and_then(|k| k.parse().ok()),
                size: 1,
                intermediate_update: get("intermediateUpdate").as_deref() == Some("true"),
            })
        }
        ("UInt64", _) if get("causality").as_deref() == Some("structuralParameter") => {
            let start = get("start").and_then(|n| n.parse().ok());
            if let (Some(vr), Some(start)) = (vr, start) {
                d.structural.push((vr, start));
            }
        }
        ("Dimension", _) => {
            // A fixed size, or the default of the structural parameter that sizes it.
            let by_parameter = || {
                let vr = get("valueReference")?.parse::<u32>().ok()?;
                d.structural.iter().find(|s| s.0 == vr).map(|s| s.1)
            };
            let size = get("start")
                .and_then(|n| n.parse().ok())
                .or_else(by_parameter);
            if let Some(v) = pending.as_mut() {
                v.size *= size.unwrap_or(1);
            }
        }
        ("ContinuousStateDerivative", _) => d.number_of_states += size_of(d, vr),
        ("EventIndicator", _) => d.number_of_event_indicators += size_of(d, vr),
        _ => {}
    }
    // fmi3GetVariableDependencies answers the continuous-time structure (outputs,
    // state derivatives, event indicators), not an <InitialUnknown>'s list.
    let structural = matches!(
        e.name().as_ref(),
        "Output" | "ContinuousStateDerivative" | "EventIndicator"
    );
    let listed = structural && get("dependencies").is_some_and(|l| !l.trim().is_empty());
    if let Some(vr) = vr.filter(|vr| listed && !d.dependents.contains(vr)) {
        d.dependents.push(vr);
    }
    Ok(())
}

/// FMI 3.0 names a derivative's state by value reference; FMI 2.0 by 1-based index.
fn index_fmi3_derivatives(d: &mut Description) {
    let vrs: Vec<u32> = d.variables.iter().map(|v| v.vr).collect();
    for v in &mut d.variables {
        v.derivative_of = v
            .derivative_of
            .and_then(|vr| vrs.iter().position(|&x| x as usize == vr))
            .map(|i| i + 1);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_plant_description() {
        // Expected values: the checked-in modelDescription/Pss3Plant.xml (96
        // ScalarVariables, six <Unknown> under <Derivatives>, theta[2] has
        // valueReference 102, the state of variable 13 is theta[1] = vr 101).
        let xml = include_str!("../../../../modelDescription/Pss3Plant.xml");
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
    fn reads_the_fmi3_plant_description() {
        // Expected values: the checked-in modelDescription/fmi3/Pss3Plant.xml
        // (theta is the Float64 array of 3 at valueReference 101, der(theta) at 301
        // names it as its state; two ContinuousStateDerivative arrays of 3 = 6
        // states; one EventIndicator array of 6; endStopMode is an Int32).
        let xml = include_str!("../../../../modelDescription/fmi3/Pss3Plant.xml");
        let d = parse(xml).unwrap();
        assert!(d.is_fmi3());
        assert_eq!(d.guid, "{66933d5c-c82b-4e7e-aaa5-b9c59a30f4c0}");
        assert_eq!(d.by_name("theta").vr, 101);
        assert_eq!(d.by_name("theta").size, 3);
        assert_eq!(d.state_derivative_pairs()[0], (101, 301));
        assert_eq!(d.number_of_states, 6);
        assert_eq!(d.number_of_event_indicators, 6);
        assert_eq!(d.elements(&[1, 11, 1041]), 7);
        assert_eq!(d.by_name("endStopMode").var_type, VarType::Integer);
        assert!(d.provides_directional_derivative);
        // <Output valueReference="121" dependencies="101 111"/>
        assert!(d.dependents.contains(&121));
    }

    #[test]
    fn refuses_a_description_without_guid() {
        assert!(parse("<fmiModelDescription modelName=\"x\"/>").is_err());
    }
}
