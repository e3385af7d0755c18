//! The FMI 3.0 view of a model's variables: one [`Variable3`] per declaration (an
//! array `x` with `<Dimension start="n"/>` whose elements are the FMI 2.0 scalars
//! `x[1]`..`x[n]`, built in [`declared`](super::declared)), plus the variables FMI 3.0
//! requires that FMI 2.0 leaves implicit: the independent variable `time` and the
//! event indicators; and what modelDescription.xml says about each (description,
//! dependencies), taken from the declarations.
//!
//! Value references: an array takes the value reference of its element `[1]` (unique,
//! because the elements' are); `time` takes 0, which no table may use; the event
//! indicators take the value reference after the table's largest.

use crate::core::model::Model;
use crate::core::variables::{Causality, Initial, Variability, Variable, VariableType, find};
use std::borrow::Cow;

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
    /// Elements of a declaration: element k of the variable is element `element + k`
    /// of the declaration at position `declaration` in `Model::declarations` (read and
    /// written through its accessors), whose (FMI 2.0) value reference is
    /// `first + k * stride` (k below the variable's size; nothing stored per element).
    Elements {
        first: u32,
        stride: u32,
        declaration: usize,
        element: usize,
    },
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
    /// The declaration's name (static: no allocation).
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
            Source::Elements { first, stride, .. } => Elements {
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

/// The FMI 3.0 value reference of the variable holding the table scalar named `name`
/// (an FMI 2.0 name): its declaration's element 1.
fn fmi3_reference<M>(table: &[Variable<M>], name: &str) -> Option<u32> {
    let s = table.iter().find(|s| s.name() == name)?;
    Some(s.value_reference - s.index as u32 * s.declaration.stride)
}

/// The description of the FMI 3.0 variable `v` (for modelDescription.xml): of an
/// array its declaration's, capitalized (its FMI 2.0 elements may carry a label,
/// "Axis 2: position"); of a scalar the FMI 2.0 one.
pub fn description<M>(table: &[Variable<M>], v: &Variable3) -> String {
    match &v.source {
        Source::Time => "Simulation time".to_string(),
        Source::EventIndicators { .. } => {
            "Event indicators: an event occurs where one changes sign".to_string()
        }
        Source::Elements { first, .. } => {
            let Some(scalar) = find(table, *first) else {
                return String::new();
            };
            if v.dimension.is_none() {
                // A scalar, or an element of the scalar-only view: the FMI 2.0 text.
                return scalar.description().into_owned();
            }
            let mut chars = scalar.declaration.description.chars();
            chars
                .next()
                .map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
        }
    }
}

/// FMI 3.0 value references of the knowns the output or derivative `v` depends on,
/// ascending (for modelDescription.xml); None: on all of them.
pub fn dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
) -> Result<Option<Vec<u32>>, String> {
    references(table, v, |scalar| scalar.dependencies.as_deref())
}

/// As [`dependencies`], for the initial unknown `v` and the knowns at initialization
/// (among them "time", the start time, which FMI 2.0 tables have no variable for).
pub fn initial_dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
) -> Result<Option<Vec<u32>>, String> {
    references(table, v, |scalar| scalar.initial_dependencies.as_deref())
}

/// The value references of the names `names` gives for every element of `v`, merged.
fn references<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
    names: impl Fn(&Variable<M>) -> Option<&[String]>,
) -> Result<Option<Vec<u32>>, String> {
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
            list.push(fmi3_reference(table, name).ok_or_else(|| {
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
