//! The FMI 3.0 view of a model's variables: one [`Variable3`] per declaration (an
//! array `x` with `<Dimension start="n"/>` whose elements are the FMI 2.0 scalars
//! `x[1]`..`x[n]`, built in [`declared`](super::declared)), plus the variables FMI 3.0
//! requires that FMI 2.0 leaves implicit: the independent variable `time` and the
//! event indicators; and what modelDescription.xml says about each (description,
//! dependencies), taken from the declarations. The view's types ([`Variable3`],
//! [`Source`], [`Table3`]) are the core's ([`crate::core::view`], which the index
//! keeps), re-exported here; FMI 3.0's type names and checks are added here.
//!
//! Value references: an array takes the value reference of its element `[1]` (unique,
//! because the elements' are); `time` takes 0, which no table may use; the event
//! indicators take the value reference after the table's largest.

use crate::core::model::Model;
use crate::core::structural::Sizes;
use crate::core::variables::{Causality, Initial, Variability, Variable, VariableType, find};
use std::borrow::Cow;

/// The type name of a table variable type in FMI 3.0.
pub fn type_name(t: VariableType) -> &'static str {
    match t {
        VariableType::Real => "Float64",
        VariableType::Integer => "Int32",
        VariableType::Boolean => "Boolean",
        VariableType::Clock => "Clock",
        VariableType::UInt64 => "UInt64",
    }
}

/// Value reference of the independent variable `time`.
pub const TIME_VALUE_REFERENCE: u32 = 0;

pub use crate::core::view::{Elements, Source, Table3, Variable3};

impl Table3 {
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
    /// `n_values`, as an iterator (not collected: a get or set allocates nothing).
    /// An array sized by a structural parameter counts its elements at `sizes` (the
    /// instance's current sizes).
    pub fn typed_all<'a>(
        &'a self,
        vrs: &'a [u32],
        wanted: VariableType,
        n_values: usize,
        sizes: &Sizes,
    ) -> Result<impl Iterator<Item = &'a Variable3> + Clone + 'a, String> {
        let mut total = 0;
        for &vr in vrs {
            total += self.typed(vr, wanted)?.size_now(sizes);
        }
        if total != n_values {
            return Err(format!(
                "nValues = {n_values}, but the variables have {total} elements"
            ));
        }
        // Every value reference was found above: no lookup below fails.
        Ok(vrs.iter().filter_map(|&vr| self.find(vr)))
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
        sized_by: None,
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
        sized_by: None,
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
pub fn description<M: Model>(table: &[Variable<M>], v: &Variable3) -> String {
    match &v.source {
        Source::Time => "Simulation time".to_string(),
        Source::EventIndicators { .. } => {
            "Event indicators: an event occurs where one changes sign".to_string()
        }
        Source::Clock { clock } => M::CLOCKS[*clock].description.to_string(),
        Source::ClockPeriod { clock } => M::CLOCKS[*clock].period.description.to_string(),
        Source::Clocked { clock, output, .. } => {
            M::CLOCKS[*clock].outputs[*output].description.to_string()
        }
        Source::Structural { parameter } => M::STRUCTURAL[*parameter].description.to_string(),
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
