//! The array view of a model's variables: one [`Variable3`] per declaration (a scalar
//! or a one-dimensional array) with what it reads and writes ([`Source`]: the
//! declaration and its first element, the time or the event indicators), and the
//! [`Table3`] of them with a lookup by value reference. FMI 3.0 describes and serves
//! this view (`fmi3::declared`, `fmi3::scalar`, `fmi3::table`); the index
//! ([`Index`](super::instance::Index)) keeps the two views built from it.

use super::model::Model;
use super::sizes::Sizes;
use super::variables::{Causality, Initial, Variability, VariableType};
use std::borrow::Cow;

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
    /// The input clock `Model::CLOCKS[clock]` (FMI 3.0 only, as the next two).
    Clock { clock: usize },
    /// The period parameter of clock `clock`, held by the instance's clocks.
    ClockPeriod { clock: usize },
    /// Output `output` of clock `clock` (array view only: the scalar-only view has no
    /// clocks).
    Clocked { clock: usize, output: usize },
    /// The structural parameter `Model::STRUCTURAL[parameter]` (array view only).
    Structural { parameter: usize },
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
    /// `Some(n)`: an array of n elements (`<Dimension start="n"/>`; n is the default
    /// size of an array sized by a structural parameter).
    pub dimension: Option<usize>,
    /// `Some(k)`: the array's size is the structural parameter `Model::STRUCTURAL[k]`
    /// (`<Dimension valueReference=".."/>`); read it with [`size_now`](Self::size_now).
    pub sized_by: Option<usize>,
    pub source: Source,
    /// Value reference of the (FMI 3.0) state this variable is the derivative of.
    pub derivative_of: Option<u32>,
}

impl Variable3 {
    /// Number of scalar values (1 for a scalar) at the default sizes.
    pub fn size(&self) -> usize {
        self.dimension.unwrap_or(1)
    }

    /// Number of scalar values with the structural parameters at `sizes`.
    pub fn size_now(&self, sizes: &Sizes) -> usize {
        match self.sized_by {
            Some(k) => sizes.get(k),
            None => self.size(),
        }
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

    /// The continuous-state derivatives in state order.
    pub fn derivatives(&self) -> impl Iterator<Item = &Variable3> {
        self.variables.iter().filter(|v| v.derivative_of.is_some())
    }

    /// The knowns: inputs (not input clocks: they activate, they carry no value) and
    /// continuous states, by FMI 3.0 value reference.
    pub fn knowns(&self) -> Vec<u32> {
        let mut knowns: Vec<u32> = self
            .variables
            .iter()
            .filter(|v| v.causality == Causality::Input && v.variable_type != VariableType::Clock)
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
