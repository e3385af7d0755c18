//! The FMI 2.0 scalars of a model's declared table ([`declare`](super::declare)):
//! for every scalar its metadata (what modelDescription.xml says about it) and its
//! accessors (how the layer reads and writes it), each pointing back at its
//! declaration and element index ([`flatten`](super::flatten)).
//!
//! Nothing here is formatted or allocated per scalar: an element's name (`q[2]`),
//! labelled description and state are formatted from its declaration when asked
//! ([`Variable::name`]), for messages and the description writers.

pub use super::attributes::{Causality, Initial, Variability};
use super::declare::{Access, Declaration, Set, Value, write_element};
use super::hooks::{Element, InputDerivative, OutputDerivative};
use std::borrow::Cow;

/// Reads element `index` of a declaration (its accessor and the index: nothing boxed).
pub struct Getter<M, T> {
    pub f: Access<M, T>,
    pub index: usize,
}

/// Writes element `index` of a declaration: through the declaration's writer if it
/// gives one, else at its place (`access`).
pub struct Setter<M, T> {
    pub access: Access<M, T>,
    pub f: Option<Set<M, T>>,
    pub index: usize,
}

impl<M, T: Copy> Getter<M, T> {
    pub fn call(&self, model: &mut M) -> T {
        self.f.read(model, self.index)
    }
}

impl<M, T> Setter<M, T> {
    /// The write alone (`value_check::write` checks the value first and runs the
    /// declaration's `after_set` hook after it).
    pub fn call(&self, model: &mut M, value: T) -> Result<(), String> {
        write_element(self.access, self.f, model, self.index, value)
            .unwrap_or_else(|| Err("no writer and no place".to_string()))
    }
}

/// Type-specific part of a variable.
pub enum Kind<M> {
    Real {
        get: Getter<M, f64>,
        set: Option<Setter<M, f64>>,
        start: Option<f64>,
        min: Option<f64>,
        max: Option<f64>,
        unit: Option<&'static str>,
        display_unit: Option<&'static str>,
    },
    Integer {
        get: Getter<M, i32>,
        set: Option<Setter<M, i32>>,
        start: Option<i32>,
        min: Option<i32>,
        max: Option<i32>,
    },
    Boolean {
        get: Getter<M, bool>,
        set: Option<Setter<M, bool>>,
        start: Option<bool>,
    },
}

/// Which of the FMI types a variable has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum VariableType {
    Real,
    Integer,
    Boolean,
    /// An FMI 3.0 clock (no FMI 2.0 variable has this type).
    Clock,
    /// An FMI 3.0 UInt64: the structural parameters (`core::structural`).
    UInt64,
}

impl VariableType {
    pub fn as_str(self) -> &'static str {
        match self {
            VariableType::Real => "Real",
            VariableType::Integer => "Integer",
            VariableType::Boolean => "Boolean",
            VariableType::Clock => "Clock",
            VariableType::UInt64 => "UInt64",
        }
    }
}

/// One FMI 2.0 scalar: element `index` of its declaration.
pub struct Variable<M: 'static> {
    pub value_reference: u32,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub kind: Kind<M>,
    /// Names of the inputs and continuous states an output or state derivative
    /// depends on (ModelStructure `dependencies`); None: on all of them.
    pub dependencies: Option<Vec<String>>,
    /// Names of the knowns at initialization (inputs, variables with initial =
    /// "exact") an initial unknown depends on (InitialUnknowns `dependencies`); None:
    /// on all of them.
    pub initial_dependencies: Option<Vec<String>>,
    /// The declaration this scalar is an element of.
    pub declaration: &'static Declaration<M>,
    /// The element's index (0 for a scalar).
    pub index: usize,
}

impl<M: 'static> Variable<M> {
    /// The FMI 2.0 name: the declaration's, `q[2]` for element 2 of an array, and
    /// `der(x[2])` for element 2 of the derivative of an array state `x`.
    pub fn name(&self) -> Cow<'_, str> {
        match self.shown_name() {
            ShownName::Plain(name) => Cow::Borrowed(name),
            element => Cow::Owned(element.to_string()),
        }
    }

    /// The FMI 2.0 name as [`Display`](std::fmt::Display), written without an
    /// allocation (for messages formatted only on a refusal).
    pub fn shown_name(&self) -> ShownName<'static> {
        element_name(self.declaration, self.index)
    }

    /// The FMI 2.0 description; element i of a labelled array is described as
    /// "`label` i: description".
    pub fn description(&self) -> Cow<'static, str> {
        let d = self.declaration;
        match (d.label, d.length) {
            (Some(label), Some(_)) => {
                format!("{label} {}: {}", self.index + 1, d.description).into()
            }
            _ => d.description.into(),
        }
    }

    /// The scalar as (declaration name, element index; None for a scalar), compared
    /// with [`Variable::state_key`] without formatting a name.
    pub fn key(&self) -> (&'static str, Option<usize>) {
        let d = self.declaration;
        (d.name, d.length.map(|_| self.index))
    }

    /// The [`key`](Variable::key) of the state this scalar is the time derivative of.
    pub fn state_key(&self) -> Option<(&'static str, Option<usize>)> {
        let d = self.declaration;
        Some((d.derivative_of?, d.length.map(|_| self.index)))
    }

    /// The FMI 2.0 name of the state this scalar is the time derivative of.
    pub fn state_name(&self) -> Option<Cow<'static, str>> {
        Some(match self.state_key()? {
            (state, None) => Cow::Borrowed(state),
            (state, Some(i)) => Cow::Owned(ShownName::Element(state, i).to_string()),
        })
    }

    /// Whether this scalar is the time derivative of a state.
    pub fn is_derivative(&self) -> bool {
        self.declaration.derivative_of.is_some()
    }

    /// The declared element this scalar is.
    pub fn element(&self) -> Element {
        Element {
            name: self.declaration.name,
            index: self.index,
        }
    }

    /// The declaration's output-derivative hook, if any.
    pub fn output_hook(&self) -> Option<OutputDerivative<M>> {
        self.declaration.output_derivative
    }

    /// The declaration's input-derivative slot, if any.
    pub fn input_hook(&self) -> Option<InputDerivative<M>> {
        self.declaration.input_derivative
    }

    pub fn variable_type(&self) -> VariableType {
        match self.kind {
            Kind::Real { .. } => VariableType::Real,
            Kind::Integer { .. } => VariableType::Integer,
            Kind::Boolean { .. } => VariableType::Boolean,
        }
    }

    pub fn has_setter(&self) -> bool {
        match &self.kind {
            Kind::Real { set, .. } => set.is_some(),
            Kind::Integer { set, .. } => set.is_some(),
            Kind::Boolean { set, .. } => set.is_some(),
        }
    }

    pub fn has_start(&self) -> bool {
        match &self.kind {
            Kind::Real { start, .. } => start.is_some(),
            Kind::Integer { start, .. } => start.is_some(),
            Kind::Boolean { start, .. } => start.is_some(),
        }
    }
}

/// The FMI 2.0 name of element i of declaration `d` (see [`Variable::name`]), written
/// when displayed.
pub fn element_name<M>(d: &Declaration<M>, i: usize) -> ShownName<'static> {
    match (d.length, d.derivative_of) {
        (None, _) => ShownName::Plain(d.name),
        (Some(_), Some(state)) => ShownName::Derivative(state, i),
        (Some(_), None) => ShownName::Element(d.name, i),
    }
}

/// The FMI type of a declaration's value.
pub fn value_type<M>(value: &Value<M>) -> VariableType {
    match value {
        Value::Real { .. } => VariableType::Real,
        Value::Integer { .. } => VariableType::Integer,
        Value::Boolean { .. } => VariableType::Boolean,
    }
}

/// A variable's FMI 2.0 name, written when displayed ([`Variable::shown_name`]).
#[derive(Debug, Clone, Copy)]
pub enum ShownName<'a> {
    Plain(&'a str),
    /// Element i of an array: `base[i + 1]`.
    Element(&'a str, usize),
    /// Element i of the derivative of an array state: `der(state[i + 1])`.
    Derivative(&'a str, usize),
}

impl std::fmt::Display for ShownName<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            ShownName::Plain(name) => f.write_str(name),
            ShownName::Element(base, i) => write!(f, "{base}[{}]", i + 1),
            ShownName::Derivative(state, i) => write!(f, "der({state}[{}])", i + 1),
        }
    }
}

/// Position of the variable with value reference `vr` in a table sorted by value
/// reference (checked by `check_table`).
pub fn find<M>(table: &[Variable<M>], vr: u32) -> Option<&Variable<M>> {
    table
        .binary_search_by_key(&vr, |v| v.value_reference)
        .ok()
        .map(|i| &table[i])
}

/// Checks a whole table against the rules of the standard that importers enforce (run
/// where modelDescription.xml is written; an instance relies only on unique value
/// references): unique names, value references strictly increasing, legal (causality,
/// variability, initial) combinations, start values exactly where required, a writer
/// for every variable that may be set, derivatives that name an existing Real state,
/// dependencies on inputs and states only.
pub fn check_table<M>(table: &[Variable<M>]) -> Result<(), String> {
    use Causality as C;
    use Variability as V;
    for pair in table.windows(2) {
        if pair[0].value_reference >= pair[1].value_reference {
            return Err(format!(
                "value references not strictly increasing at \"{}\"",
                pair[1].name()
            ));
        }
    }
    let mut names: Vec<Cow<str>> = table.iter().map(Variable::name).collect();
    names.sort_unstable();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!("duplicate variable name \"{}\"", w[0]));
    }
    for v in table {
        let name = v.name();
        let legal = matches!(
            (v.causality, v.variability, v.initial),
            (C::Parameter, V::Fixed | V::Tunable, Some(Initial::Exact))
                | (
                    C::CalculatedParameter,
                    V::Fixed | V::Tunable,
                    Some(Initial::Calculated | Initial::Approx)
                )
                | (C::Input, V::Discrete | V::Continuous, None)
                | (C::Output | C::Local, V::Constant, Some(Initial::Exact))
                | (C::Output | C::Local, V::Discrete | V::Continuous, Some(_))
                | (C::Independent, V::Continuous, None)
        );
        if !legal {
            return Err(format!(
                "\"{name}\": illegal combination causality={}, variability={}, initial={:?}",
                v.causality.as_str(),
                v.variability.as_str(),
                v.initial.map(Initial::as_str)
            ));
        }
        if v.variability == V::Continuous && v.variable_type() != VariableType::Real {
            return Err(format!("\"{name}\": only Real variables can be continuous"));
        }
        let needs_start =
            v.causality == C::Input || matches!(v.initial, Some(Initial::Exact | Initial::Approx));
        if needs_start != v.has_start() {
            return Err(format!(
                "\"{name}\": a start value is {} for this causality and initial",
                if needs_start {
                    "required"
                } else {
                    "not allowed"
                }
            ));
        }
        let settable = v.variability != V::Constant
            && (v.causality == C::Input
                || matches!(v.initial, Some(Initial::Exact | Initial::Approx)));
        if settable != v.has_setter() {
            return Err(format!(
                "\"{name}\": a writer is {} (it {} be set through fmi2Set*)",
                if settable { "missing" } else { "not allowed" },
                if settable { "may" } else { "may not" }
            ));
        }
        if let Some(state) = v.state_name() {
            let found = table.iter().any(|s| {
                s.name() == state
                    && s.variable_type() == VariableType::Real
                    && s.variability == V::Continuous
            });
            if !found {
                return Err(format!(
                    "\"{name}\": derivative of \"{state}\", which is not a continuous Real"
                ));
            }
        }
        check_dependencies(v, table)?;
    }
    Ok(())
}

/// Dependencies only on outputs and derivatives, and only on inputs and states.
fn check_dependencies<M>(v: &Variable<M>, table: &[Variable<M>]) -> Result<(), String> {
    let Some(names) = &v.dependencies else {
        return Ok(());
    };
    if v.causality != Causality::Output && !v.is_derivative() {
        return Err(format!(
            "\"{}\": only outputs and derivatives declare dependencies",
            v.name()
        ));
    }
    for name in names.iter() {
        let is_state = derivative_variables(table)
            .iter()
            .any(|d| d.state_name().is_some_and(|s| s == *name));
        let is_input = table
            .iter()
            .any(|k| k.name() == *name && k.causality == Causality::Input);
        if !(is_state || is_input) {
            return Err(format!(
                "\"{}\": dependency \"{name}\" is neither an input nor a continuous state",
                v.name()
            ));
        }
    }
    Ok(())
}

/// Value references of the derivative variables, in table order (= state order).
pub fn derivative_variables<M>(table: &[Variable<M>]) -> Vec<&Variable<M>> {
    table.iter().filter(|v| v.is_derivative()).collect()
}
