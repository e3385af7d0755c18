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
use crate::core::variables::{Causality, Initial, Kind, Variability, Variable, VariableType, find};
use std::borrow::Cow;
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
    /// Elements of the model's table, by their (FMI 2.0) value references: element k
    /// at `first + k * stride` (k below the variable's size; nothing stored per element).
    Elements { first: u32, stride: u32 },
    /// The instance's time.
    Time,
    /// The model's event indicators (`Model::event_indicators`) from index `first` on
    /// (0 for the array of all; one index per scalar in the scalar-only view).
    EventIndicators { first: usize },
}

/// One variable of the FMI 3.0 description: a scalar or a one-dimensional array.
#[derive(Debug, Clone, PartialEq)]
pub struct Variable3 {
    pub value_reference: u32,
    /// Static for a scalar or an array declared by the core's `Array` (no allocation).
    pub name: Cow<'static, str>,
    pub variable_type: VariableType,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    /// `Some(n)`: an array of n elements (`<Dimension start="n"/>`).
    pub dimension: Option<usize>,
    pub source: Source,
    /// Value reference of the (FMI 3.0) state this variable is the derivative of.
    pub derivative_of: Option<u32>,
}

impl Variable3 {
    /// Number of scalar values (1 for a scalar).
    pub fn size(&self) -> usize {
        self.dimension.unwrap_or(1)
    }

    /// Whether the variable carries intermediateUpdate="true" for model M: the
    /// continuous Float64 inputs and outputs of a model with intermediate update
    /// (they can be set / read in Intermediate Update Mode).
    pub fn intermediate_update<M: Model>(&self) -> bool {
        M::INTERMEDIATE_UPDATE_POINTS > 0
            && self.variable_type == VariableType::Real
            && self.variability == Variability::Continuous
            && matches!(self.source, Source::Elements { .. })
            && matches!(self.causality, Causality::Input | Causality::Output)
    }

    /// The table's elements, in order (none for time and event indicators).
    pub fn elements(&self) -> Elements {
        match self.source {
            Source::Elements { first, stride } => Elements {
                next: first,
                stride,
                left: self.size(),
            },
            _ => Elements {
                next: 0,
                stride: 1,
                left: 0,
            },
        }
    }
}

/// The table elements (FMI 2.0 value references) of an FMI 3.0 variable, in order,
/// computed from the first one and the stride.
#[derive(Debug, Clone)]
pub struct Elements {
    next: u32,
    stride: u32,
    left: usize,
}

impl Elements {
    /// Whether there are none (time, event indicators).
    pub fn is_empty(&self) -> bool {
        self.left == 0
    }
}

impl Iterator for Elements {
    type Item = u32;

    fn next(&mut self) -> Option<u32> {
        self.left = self.left.checked_sub(1)?;
        let e = self.next;
        self.next = self.next.wrapping_add(self.stride);
        Some(e)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        (self.left, Some(self.left))
    }
}

impl ExactSizeIterator for Elements {}

/// The FMI 3.0 variables of a model, in description order, with a lookup by value
/// reference.
#[derive(Debug, Clone)]
pub struct Table3 {
    pub variables: Vec<Variable3>,
    /// (value reference, position) sorted, when the description order is not the
    /// value-reference order; empty otherwise (the lookup searches the variables).
    by_reference: Vec<(u32, usize)>,
}

impl Table3 {
    /// The table of `variables` (in description order).
    pub fn new(variables: Vec<Variable3>) -> Self {
        let mut by_reference = Vec::new();
        if !variables.is_sorted_by_key(|v| v.value_reference) {
            by_reference = (variables.iter().enumerate())
                .map(|(i, v)| (v.value_reference, i))
                .collect();
            by_reference.sort_unstable();
        }
        Table3 {
            variables,
            by_reference,
        }
    }

    pub fn find(&self, vr: u32) -> Option<&Variable3> {
        let i = if self.by_reference.is_empty() {
            (self.variables)
                .binary_search_by_key(&vr, |v| v.value_reference)
                .ok()?
        } else {
            let k = (self.by_reference)
                .binary_search_by_key(&vr, |&(r, _)| r)
                .ok()?;
            self.by_reference[k].1
        };
        Some(&self.variables[i])
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

    /// The event-indicator variables (one array, or one scalar per indicator).
    pub fn event_indicators(&self) -> impl Iterator<Item = &Variable3> {
        (self.variables)
            .iter()
            .filter(|v| matches!(v.source, Source::EventIndicators { .. }))
    }
}

/// The parts of a table name: `(false, "x", Some(2))` for `x[2]`, `(true, "x", Some(2))`
/// for `der(x[2])`, and `(derivative, name, None)` when it has no single trailing
/// index. Slices of `name`: nothing is allocated.
fn split_index(name: &str) -> (bool, &str, Option<usize>) {
    let (derivative, inner) = match name.strip_prefix("der(").and_then(|n| n.strip_suffix(')')) {
        Some(inner) => (true, inner),
        None => (false, name),
    };
    let parsed = inner.strip_suffix(']').and_then(|rest| {
        let open = rest.rfind('[')?;
        let index: usize = rest[open + 1..].parse().ok()?;
        let base = &rest[..open];
        (!base.is_empty() && !base.ends_with(']')).then_some((base, index))
    });
    match parsed {
        Some((base, index)) => (derivative, base, Some(index)),
        None => (derivative, inner, None),
    }
}

/// The FMI 3.0 name of the group `(derivative, base)`.
fn group_name(derivative: bool, base: &str) -> String {
    if derivative {
        format!("der({base})")
    } else {
        base.to_string()
    }
}

/// The description of an array: the elements' common text (capitalized) once a
/// leading "<Word> <i>: " naming element i is removed (e.g. "Axis 2: position at
/// t0"), else the first element's.
fn array_description(descriptions: &[&str]) -> String {
    let stripped: Vec<&str> = descriptions
        .iter()
        .enumerate()
        .map(|(i, d)| strip_element_label(d, i + 1))
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

/// `d` without a leading "<Word> <number>: " naming element `number`.
fn strip_element_label(d: &str, number: usize) -> &str {
    let labelled = d.split_once(": ").filter(|(label, _)| {
        label.split_once(' ').is_some_and(|(word, n)| {
            !word.is_empty() && word.chars().all(char::is_alphabetic) && n.parse() == Ok(number)
        })
    });
    labelled.map_or(d, |(_, rest)| rest)
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

/// [`split_index`] of a name borrowed from the table or formatted for it.
fn split_name(name: Cow<'_, str>) -> (bool, Cow<'_, str>, Option<usize>) {
    match name {
        Cow::Borrowed(name) => {
            let (derivative, base, index) = split_index(name);
            (derivative, Cow::Borrowed(base), index)
        }
        Cow::Owned(name) => {
            let (derivative, base, index) = split_index(&name);
            (derivative, Cow::Owned(base.to_string()), index)
        }
    }
}

/// The table positions of one FMI 3.0 variable: a scalar or the elements of an array
/// named `base` (`der(base)`).
struct Group<'a> {
    derivative: bool,
    base: Cow<'a, str>,
    is_array: bool,
    members: Vec<usize>,
}

/// Groups of table positions, one per FMI 3.0 variable, in order of first appearance.
fn groups<M>(table: &[Variable<M>]) -> Result<Vec<Group<'_>>, String> {
    let mut order: Vec<Group> = Vec::new();
    let mut position: HashMap<(bool, Cow<str>), usize> = HashMap::with_capacity(table.len());
    for (i, v) in table.iter().enumerate() {
        let (derivative, base, index) = split_name(v.name());
        let is_array = index.is_some();
        let slot = *position
            .entry((derivative, base.clone()))
            .or_insert_with(|| {
                order.push(Group {
                    derivative,
                    base: base.clone(),
                    is_array,
                    members: Vec::new(),
                });
                order.len() - 1
            });
        if order[slot].is_array != is_array {
            return Err(format!(
                "\"{}\" is declared both as a scalar and as an array",
                group_name(derivative, &base)
            ));
        }
        order[slot].members.push(i);
    }
    for group in &mut order {
        check_group(table, group)?;
    }
    Ok(order)
}

/// A scalar declared once; an array's elements numbered 1..n, agreeing with their
/// `ArrayElement` metadata, declared alike.
fn check_group<M>(table: &[Variable<M>], group: &mut Group) -> Result<(), String> {
    let name = || group_name(group.derivative, &group.base);
    if !group.is_array {
        if group.members.len() > 1 {
            return Err(format!("duplicate variable \"{}\"", name()));
        }
        return Ok(());
    }
    group
        .members
        .sort_by_key(|&i| split_index(&table[i].name()).2);
    let n = group.members.len();
    let first = &table[group.members[0]];
    for (k, &i) in group.members.iter().enumerate() {
        let v = &table[i];
        if split_index(&v.name()).2 != Some(k + 1) {
            return Err(format!(
                "the elements of \"{}\" are not numbered 1..n",
                name()
            ));
        }
        if let Some(a) = &v.array
            && (a.base != group.base.as_ref()
                || a.derivative != group.derivative
                || a.index != k
                || a.length != n)
        {
            return Err(format!(
                "\"{}\" is declared as element {} of {} of \"{}\", but the table has \
                 {n} elements named {}[..]",
                v.name(),
                a.index + 1,
                a.length,
                group_name(a.derivative, a.base),
                name()
            ));
        }
        if !same_declaration(first, v) {
            return Err(format!(
                "\"{}\" differs from \"{}\" in type, causality, variability, initial or unit",
                v.name(),
                first.name()
            ));
        }
    }
    Ok(())
}

/// The FMI 3.0 view of model M's table (see the module documentation), built from the
/// table an instance owns. Descriptions of arrays and dependencies, needed only in
/// modelDescription.xml, are derived there ([`description`], [`dependencies`]).
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
    let mut variables = Vec::with_capacity(groups.len() + 2);
    variables.push(time_variable());
    for group in &groups {
        variables.push(variable3(table, &groups, group)?);
    }
    let n_indicators = M::info().number_of_event_indicators;
    if n_indicators > 0 {
        let last = table.iter().map(|v| v.value_reference).max().unwrap_or(0);
        variables.push(event_indicator_variable(last + 1, n_indicators));
    }
    check_state_order(table, &variables)?;
    Ok(Table3::new(variables))
}

pub(super) fn time_variable() -> Variable3 {
    Variable3 {
        value_reference: TIME_VALUE_REFERENCE,
        name: Cow::Borrowed("time"),
        variable_type: VariableType::Real,
        causality: Causality::Independent,
        variability: Variability::Continuous,
        initial: None,
        dimension: None,
        source: Source::Time,
        derivative_of: None,
    }
}

pub(super) fn event_indicator_variable(value_reference: u32, n: usize) -> Variable3 {
    Variable3 {
        value_reference,
        name: Cow::Borrowed("eventIndicators"),
        variable_type: VariableType::Real,
        causality: Causality::Local,
        variability: Variability::Continuous,
        initial: Some(Initial::Calculated),
        dimension: Some(n),
        source: Source::EventIndicators { first: 0 },
        derivative_of: None,
    }
}

fn variable3<M>(
    table: &[Variable<M>],
    groups: &[Group],
    group: &Group,
) -> Result<Variable3, String> {
    let first = &table[group.members[0]];
    let derivative_of = match first.state_name() {
        Some(state) => Some(fmi3_reference(table, groups, &state).ok_or_else(|| {
            format!(
                "\"{}\" names the unknown variable \"{state}\"",
                first.name()
            )
        })?),
        None => None,
    };
    let name = match (&first.array, group.is_array) {
        (Some(a), true) if !a.derivative => Cow::Borrowed(a.base),
        (_, true) => Cow::Owned(group_name(group.derivative, &group.base)),
        (_, false) => first.stored_name.clone(),
    };
    Ok(Variable3 {
        value_reference: first.value_reference,
        name,
        variable_type: first.variable_type(),
        causality: first.causality,
        variability: first.variability,
        initial: first.initial,
        dimension: group.is_array.then_some(group.members.len()),
        source: evenly_spaced(table, group)?,
        derivative_of,
    })
}

/// The elements of a group as a first value reference and a stride (an FMI 3.0 array
/// reads its elements by index arithmetic).
fn evenly_spaced<M>(table: &[Variable<M>], group: &Group) -> Result<Source, String> {
    let vr = |k: usize| table[group.members[k]].value_reference;
    let first = vr(0);
    let stride = if group.members.len() > 1 {
        vr(1).wrapping_sub(first)
    } else {
        1
    };
    let even = (0..group.members.len()).all(|k| vr(k) == first.wrapping_add(k as u32 * stride));
    if !even || stride == 0 {
        return Err(format!(
            "the elements of \"{}\" do not have evenly spaced value references",
            group_name(group.derivative, &group.base)
        ));
    }
    Ok(Source::Elements { first, stride })
}

/// The FMI 3.0 value reference of the variable owning the table scalar `name`.
fn fmi3_reference<M>(table: &[Variable<M>], groups: &[Group], name: &str) -> Option<u32> {
    let (derivative, base, index) = split_index(name);
    groups
        .iter()
        .find(|g| g.derivative == derivative && g.base == base && g.is_array == index.is_some())
        .filter(|g| g.members.iter().any(|&i| table[i].name() == name))
        .map(|g| table[g.members[0]].value_reference)
}

/// The description of the FMI 3.0 variable `v` (for modelDescription.xml): an array's
/// elements' common text without the "Axis i: " labels naming each element.
pub fn description<M>(table: &[Variable<M>], v: &Variable3) -> String {
    match &v.source {
        Source::Time => "Simulation time".to_string(),
        Source::EventIndicators { .. } => {
            "Event indicators: an event occurs where one changes sign".to_string()
        }
        Source::Elements { .. } => {
            let owned: Vec<Cow<str>> = v
                .elements()
                .filter_map(|e| find(table, e))
                .map(Variable::description)
                .collect();
            let descriptions: Vec<&str> = owned.iter().map(AsRef::as_ref).collect();
            if v.dimension.is_some() {
                array_description(&descriptions)
            } else {
                descriptions
                    .first()
                    .map_or_else(String::new, |d| d.to_string())
            }
        }
    }
}

/// FMI 3.0 value references of the knowns the output or derivative `v` depends on,
/// ascending (for modelDescription.xml); None: on all of them.
pub fn dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
) -> Result<Option<Vec<u32>>, String> {
    references(table, v, |scalar| scalar.dependencies)
}

/// As [`dependencies`], for the initial unknown `v` and the knowns at initialization
/// (among them "time", the start time, which FMI 2.0 tables have no variable for).
pub fn initial_dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
) -> Result<Option<Vec<u32>>, String> {
    references(table, v, |scalar| scalar.initial_dependencies)
}

/// The value references of the names `names` gives for every element of `v`, merged.
fn references<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
    names: impl Fn(&Variable<M>) -> Option<&'static [&'static str]>,
) -> Result<Option<Vec<u32>>, String> {
    let groups = groups(table)?;
    let mut list = Vec::new();
    for e in v.elements() {
        let scalar = find(table, e).ok_or_else(|| format!("no element {e}"))?;
        let Some(names) = names(scalar) else {
            return Ok(None);
        };
        for name in names {
            if *name == "time" {
                // The independent variable, a known of the initial unknowns.
                list.push(TIME_VALUE_REFERENCE);
                continue;
            }
            list.push(fmi3_reference(table, &groups, name).ok_or_else(|| {
                format!(
                    "\"{}\" names the unknown variable \"{name}\"",
                    scalar.name()
                )
            })?);
        }
    }
    if v.elements().is_empty() {
        return Ok(None);
    }
    list.sort_unstable();
    list.dedup();
    Ok(Some(list))
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
        .flat_map(Variable3::elements)
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
        assert_eq!(split_index("theta[2]"), (false, "theta", Some(2)));
        assert_eq!(split_index("der(omega[3])"), (true, "omega", Some(3)));
        assert_eq!(split_index("order"), (false, "order", None));
        assert_eq!(split_index("der(x)"), (true, "x", None));
        assert_eq!(split_index("a[1][2]"), (false, "a[1][2]", None));
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
