//! The FMI 3.0 view of a model's variable table: the scalars `x[1]`..`x[n]` of the
//! table become one array variable `x` with `<Dimension start="n"/>` (named like the
//! FMI 2.0 scalars, so one declaration serves both standards; elements declared by
//! the core's `RealArray` must agree with their `ArrayElement` metadata), plus the variables FMI
//! 3.0 requires that FMI 2.0 leaves implicit: the independent variable `time` and the
//! event indicators.
//!
//! Value references: an array takes the value reference of its element `[1]` (unique,
//! because the elements' are); `time` takes 0, which no table may use; the event
//! indicators take the value reference after the table's largest.

use crate::core::model::Model;
use crate::core::variables::{Causality, Initial, Kind, Variability, Variable, VariableType};
use std::collections::HashMap;

/// The type name of a table variable type in FMI 3.0.
pub fn type_name(t: VariableType) -> &'static str {
    match t {
        VariableType::Real => "Float64",
        VariableType::Integer => "Int32",
        VariableType::Boolean => "Boolean",
    }
}

/// Value reference of the independent variable `time`.
pub const TIME_VALUE_REFERENCE: u32 = 0;

/// What an FMI 3.0 variable reads and writes.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// Elements of the model's table, by their (FMI 2.0) value references.
    Elements(Vec<u32>),
    /// The instance's time.
    Time,
    /// The model's event indicators (`Model::event_indicators`).
    EventIndicators,
}

/// One variable of the FMI 3.0 description: a scalar or a one-dimensional array.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable3 {
    pub value_reference: u32,
    pub name: String,
    pub description: String,
    pub variable_type: VariableType,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    /// `Some(n)`: an array of n elements (`<Dimension start="n"/>`).
    pub dimension: Option<usize>,
    pub source: Source,
    /// Value reference of the (FMI 3.0) state this variable is the derivative of.
    pub derivative_of: Option<u32>,
    /// FMI 3.0 value references of the knowns this output or derivative depends on,
    /// ascending; None: on all of them.
    pub dependencies: Option<Vec<u32>>,
}

impl Variable3 {
    /// Number of scalar values (1 for a scalar).
    pub fn size(&self) -> usize {
        self.dimension.unwrap_or(1)
    }

    /// The table's elements, in order (empty for time and event indicators).
    pub fn elements(&self) -> &[u32] {
        match &self.source {
            Source::Elements(e) => e,
            _ => &[],
        }
    }
}

/// The FMI 3.0 variables of a model, in description order, with a lookup by value
/// reference.
#[derive(Debug, Clone)]
pub struct Table3 {
    pub variables: Vec<Variable3>,
    by_reference: HashMap<u32, usize>,
}

impl Table3 {
    pub fn find(&self, vr: u32) -> Option<&Variable3> {
        self.by_reference.get(&vr).map(|&i| &self.variables[i])
    }

    /// The variable with value reference `vr`, of type `wanted`.
    pub fn typed(&self, vr: u32, wanted: VariableType) -> Result<&Variable3, String> {
        let v = self
            .find(vr)
            .ok_or_else(|| format!("unknown value reference {vr}"))?;
        if v.variable_type != wanted {
            return Err(format!(
                "\"{}\" (value reference {vr}) is a {} variable, not {}",
                v.name,
                type_name(v.variable_type),
                type_name(wanted)
            ));
        }
        Ok(v)
    }

    /// The variables of `vrs`, checked against `wanted` and the total element count
    /// `n_values`.
    pub fn typed_all(
        &self,
        vrs: &[u32],
        wanted: VariableType,
        n_values: usize,
    ) -> Result<Vec<&Variable3>, String> {
        let variables = vrs
            .iter()
            .map(|&vr| self.typed(vr, wanted))
            .collect::<Result<Vec<_>, _>>()?;
        let total: usize = variables.iter().map(|v| v.size()).sum();
        if total != n_values {
            return Err(format!(
                "nValues = {n_values}, but the variables have {total} elements"
            ));
        }
        Ok(variables)
    }

    /// The continuous-state derivatives in state order.
    pub fn derivatives(&self) -> impl Iterator<Item = &Variable3> {
        self.variables.iter().filter(|v| v.derivative_of.is_some())
    }

    /// The knowns: inputs and continuous states, by FMI 3.0 value reference.
    pub fn knowns(&self) -> Vec<u32> {
        let mut knowns: Vec<u32> = self
            .variables
            .iter()
            .filter(|v| v.causality == Causality::Input)
            .map(|v| v.value_reference)
            .chain(self.derivatives().filter_map(|d| d.derivative_of))
            .collect();
        knowns.sort_unstable();
        knowns
    }

    /// The event-indicator variable, if the model has event indicators.
    pub fn event_indicators(&self) -> Option<&Variable3> {
        self.variables
            .iter()
            .find(|v| v.source == Source::EventIndicators)
    }
}

/// `("x", Some(2))` for `x[2]`, `("der(x)", Some(2))` for `der(x[2])`, and the name
/// itself with None when it has no single trailing index.
fn split_index(name: &str) -> (String, Option<usize>) {
    let (prefix, inner, suffix) = match name.strip_prefix("der(").and_then(|n| n.strip_suffix(')'))
    {
        Some(inner) => ("der(", inner, ")"),
        None => ("", name, ""),
    };
    let parsed = inner.strip_suffix(']').and_then(|rest| {
        let open = rest.rfind('[')?;
        let index: usize = rest[open + 1..].parse().ok()?;
        let base = &rest[..open];
        (!base.is_empty() && !base.ends_with(']')).then(|| (base.to_string(), index))
    });
    match parsed {
        Some((base, index)) => (format!("{prefix}{base}{suffix}"), Some(index)),
        None => (name.to_string(), None),
    }
}

/// The description of an array: the elements' common text (capitalized) once a
/// leading "<Word> <i>: " naming element i is removed (e.g. "Axis 2: position at
/// t0"), else the first element's.
fn array_description(descriptions: &[&str]) -> String {
    let stripped: Vec<&str> = descriptions
        .iter()
        .enumerate()
        .map(|(i, d)| {
            d.split_once(&format!(" {}: ", i + 1))
                .filter(|(word, _)| word.chars().all(char::is_alphabetic))
                .map_or(*d, |(_, rest)| rest)
        })
        .collect();
    if stripped.iter().all(|d| *d == stripped[0]) {
        let mut chars = stripped[0].chars();
        chars
            .next()
            .map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
    } else {
        descriptions[0].to_string()
    }
}

/// Metadata the elements of one array must share.
fn same_declaration<M>(a: &Variable<M>, b: &Variable<M>) -> bool {
    let unit = |v: &Variable<M>| match &v.kind {
        Kind::Real {
            unit, display_unit, ..
        } => (*unit, *display_unit),
        _ => (None, None),
    };
    a.variable_type() == b.variable_type()
        && a.causality == b.causality
        && a.variability == b.variability
        && a.initial == b.initial
        && unit(a) == unit(b)
}

/// Groups of table positions, one per FMI 3.0 variable, in order of first appearance.
fn groups<M>(table: &[Variable<M>]) -> Result<Vec<(String, Vec<usize>, bool)>, String> {
    let mut order: Vec<(String, Vec<usize>, bool)> = Vec::new();
    let mut position: HashMap<String, usize> = HashMap::new();
    for (i, v) in table.iter().enumerate() {
        let (base, index) = split_index(&v.name);
        let is_array = index.is_some();
        let slot = *position.entry(base.clone()).or_insert_with(|| {
            order.push((base.clone(), Vec::new(), is_array));
            order.len() - 1
        });
        if order[slot].2 != is_array {
            return Err(format!(
                "\"{base}\" is declared both as a scalar and as an array"
            ));
        }
        order[slot].1.push(i);
    }
    for (base, members, is_array) in &mut order {
        if !*is_array {
            if members.len() > 1 {
                return Err(format!("duplicate variable \"{base}\""));
            }
            continue;
        }
        members.sort_by_key(|&i| split_index(&table[i].name).1);
        for (k, &i) in members.iter().enumerate() {
            if split_index(&table[i].name).1 != Some(k + 1) {
                return Err(format!("the elements of \"{base}\" are not numbered 1..n"));
            }
            if let Some(a) = &table[i].array
                && (a.base != *base || a.index != k || a.length != members.len())
            {
                return Err(format!(
                    "\"{}\" is declared as element {} of {} of \"{}\", but the table has \
                     {} elements named {base}[..]",
                    table[i].name,
                    a.index + 1,
                    a.length,
                    a.base,
                    members.len()
                ));
            }
            if !same_declaration(&table[members[0]], &table[i]) {
                return Err(format!(
                    "\"{}\" differs from \"{}\" in type, causality, variability, initial or unit",
                    table[i].name, table[members[0]].name
                ));
            }
        }
    }
    Ok(order)
}

/// The FMI 3.0 view of model M's table (see the module documentation), built from the
/// table an instance owns.
pub fn build<M: Model>(table: &[Variable<M>]) -> Result<Table3, String> {
    if table
        .iter()
        .any(|v| v.value_reference == TIME_VALUE_REFERENCE)
    {
        return Err(format!(
            "value reference {TIME_VALUE_REFERENCE} is reserved for time in FMI 3.0"
        ));
    }
    let groups = groups(table)?;
    // FMI 2.0 name of every element -> (FMI 3.0 value reference of its variable).
    let mut owner: HashMap<&str, u32> = HashMap::new();
    for (_, members, _) in &groups {
        for &i in members {
            owner.insert(&table[i].name, table[members[0]].value_reference);
        }
    }
    let mut variables = vec![time_variable()];
    for (base, members, is_array) in &groups {
        variables.push(variable3(table, base, members, *is_array, &owner)?);
    }
    let n_indicators = M::info().number_of_event_indicators;
    if n_indicators > 0 {
        let last = table.iter().map(|v| v.value_reference).max().unwrap_or(0);
        variables.push(event_indicator_variable(last + 1, n_indicators));
    }
    check_state_order(table, &variables)?;
    let by_reference = variables
        .iter()
        .enumerate()
        .map(|(i, v)| (v.value_reference, i))
        .collect();
    Ok(Table3 {
        variables,
        by_reference,
    })
}

fn time_variable() -> Variable3 {
    Variable3 {
        value_reference: TIME_VALUE_REFERENCE,
        name: "time".to_string(),
        description: "Simulation time".to_string(),
        variable_type: VariableType::Real,
        causality: Causality::Independent,
        variability: Variability::Continuous,
        initial: None,
        dimension: None,
        source: Source::Time,
        derivative_of: None,
        dependencies: None,
    }
}

fn event_indicator_variable(value_reference: u32, n: usize) -> Variable3 {
    Variable3 {
        value_reference,
        name: "eventIndicators".to_string(),
        description: "Event indicators: an event occurs where one changes sign".to_string(),
        variable_type: VariableType::Real,
        causality: Causality::Local,
        variability: Variability::Continuous,
        initial: Some(Initial::Calculated),
        dimension: Some(n),
        source: Source::EventIndicators,
        derivative_of: None,
        dependencies: None,
    }
}

fn variable3<M>(
    table: &[Variable<M>],
    base: &str,
    members: &[usize],
    is_array: bool,
    owner: &HashMap<&str, u32>,
) -> Result<Variable3, String> {
    let first = &table[members[0]];
    let lookup = |name: &str| {
        owner
            .get(name)
            .copied()
            .ok_or_else(|| format!("\"{}\" names the unknown variable \"{name}\"", first.name))
    };
    let derivative_of = match &first.kind {
        Kind::Real {
            derivative_of: Some(state),
            ..
        } => Some(lookup(state)?),
        _ => None,
    };
    let mut dependencies: Option<Vec<u32>> = Some(Vec::new());
    for &i in members {
        match (&table[i].dependencies, &mut dependencies) {
            (Some(names), Some(list)) => {
                for name in names {
                    list.push(lookup(name)?);
                }
            }
            _ => dependencies = None,
        }
    }
    if let Some(list) = &mut dependencies {
        list.sort_unstable();
        list.dedup();
    }
    let descriptions: Vec<&str> = members
        .iter()
        .map(|&i| table[i].description.as_str())
        .collect();
    Ok(Variable3 {
        value_reference: first.value_reference,
        name: base.to_string(),
        description: array_description(&descriptions),
        variable_type: first.variable_type(),
        causality: first.causality,
        variability: first.variability,
        initial: first.initial,
        dimension: is_array.then_some(members.len()),
        source: Source::Elements(members.iter().map(|&i| table[i].value_reference).collect()),
        derivative_of,
        dependencies,
    })
}

/// The FMI 3.0 state vector (the derivative arrays' elements in description order)
/// must be the model's state vector (the FMI 2.0 derivatives in table order).
fn check_state_order<M>(table: &[Variable<M>], variables: &[Variable3]) -> Result<(), String> {
    let fmi2: Vec<u32> = crate::core::variables::derivative_variables(table)
        .iter()
        .map(|v| v.value_reference)
        .collect();
    let fmi3: Vec<u32> = variables
        .iter()
        .filter(|v| v.derivative_of.is_some())
        .flat_map(|v| v.elements().iter().copied())
        .collect();
    if fmi2 == fmi3 {
        Ok(())
    } else {
        Err("the derivative arrays do not list the states in the model's order".to_string())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn indices_split_off_plain_and_derivative_names() {
        assert_eq!(split_index("theta[2]"), ("theta".to_string(), Some(2)));
        assert_eq!(
            split_index("der(omega[3])"),
            ("der(omega)".to_string(), Some(3))
        );
        assert_eq!(split_index("order"), ("order".to_string(), None));
        assert_eq!(split_index("der(x)"), ("der(x)".to_string(), None));
        assert_eq!(split_index("a[1][2]"), ("a[1][2]".to_string(), None));
    }

    #[test]
    fn element_prefixes_are_removed_from_array_descriptions() {
        assert_eq!(
            array_description(&["Axis 1: position", "Axis 2: position", "Axis 3: position"]),
            "Position"
        );
        assert_eq!(
            array_description(&["Euler rate", "Euler rate"]),
            "Euler rate"
        );
        assert_eq!(array_description(&["a", "b"]), "a");
    }
}
