//! The variable table of a model: for every variable its metadata (what
//! modelDescription.xml says about it) and its accessors (how the layer reads and writes
//! it). It is the single source of truth for both.
//!
//! Every instance builds its own table (nothing of it may outlive the instance: a
//! table kept by the loaded library would leak at dlclose), so building one is kept
//! cheap: names, descriptions and dependency lists are static strings wherever the
//! declaration allows (`Cow<'static, str>`); an element of a declared array is named
//! and described from its declaration only when asked ([`Variable::name`]).

use super::declare::Declaration;
use super::element::{ArrayElement, numbered};
use super::hooks::{Element, InputDerivative, OutputDerivative};
use std::borrow::Cow;

/// Reads a variable: a declared element (`fn` and element index: nothing allocated per
/// instance) or a closure (a `Variable` built per instance).
pub enum Getter<M, T> {
    Element(fn(&M, usize) -> T, usize),
    Closure(Box<dyn Fn(&M) -> T + Send + Sync>),
}

/// A writer closure of a variable built per instance.
pub type SetClosure<M, T> = Box<dyn Fn(&mut M, T) -> Result<(), String> + Send + Sync>;

/// Writes a variable, like [`Getter`]; Err: the value is refused, with the reason.
pub enum Setter<M, T> {
    Element(fn(&mut M, usize, T) -> Result<(), String>, usize),
    Closure(SetClosure<M, T>),
}

impl<M, T> Getter<M, T> {
    pub fn call(&self, model: &M) -> T {
        match self {
            Getter::Element(f, i) => f(model, *i),
            Getter::Closure(f) => f(model),
        }
    }
}

impl<M, T> Setter<M, T> {
    pub fn call(&self, model: &mut M, value: T) -> Result<(), String> {
        match self {
            Setter::Element(f, i) => f(model, *i, value),
            Setter::Closure(f) => f(model, value),
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Causality {
    Parameter,
    CalculatedParameter,
    Input,
    Output,
    Local,
    Independent,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variability {
    Constant,
    Fixed,
    Tunable,
    Discrete,
    Continuous,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Initial {
    Exact,
    Approx,
    Calculated,
}

impl Causality {
    pub fn as_str(self) -> &'static str {
        match self {
            Causality::Parameter => "parameter",
            Causality::CalculatedParameter => "calculatedParameter",
            Causality::Input => "input",
            Causality::Output => "output",
            Causality::Local => "local",
            Causality::Independent => "independent",
        }
    }
}

impl Variability {
    pub fn as_str(self) -> &'static str {
        match self {
            Variability::Constant => "constant",
            Variability::Fixed => "fixed",
            Variability::Tunable => "tunable",
            Variability::Discrete => "discrete",
            Variability::Continuous => "continuous",
        }
    }
}

impl Initial {
    pub fn as_str(self) -> &'static str {
        match self {
            Initial::Exact => "exact",
            Initial::Approx => "approx",
            Initial::Calculated => "calculated",
        }
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
        /// Name of the state this variable (built per instance, not declared) is the
        /// time derivative of; a declared one says it in its declaration.
        derivative_of_built: Option<Cow<'static, str>>,
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
}

impl VariableType {
    pub fn as_str(self) -> &'static str {
        match self {
            VariableType::Real => "Real",
            VariableType::Integer => "Integer",
            VariableType::Boolean => "Boolean",
        }
    }
}

/// One scalar variable.
pub struct Variable<M: 'static> {
    pub value_reference: u32,
    /// The name ([`Variable::name`]; of a declared array: the declaration's).
    pub(crate) stored_name: Cow<'static, str>,
    /// The description ([`Variable::description`]; of a declared array: the
    /// declaration's).
    pub(crate) stored_description: Cow<'static, str>,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub kind: Kind<M>,
    /// Names of the inputs and continuous states an output or state derivative
    /// depends on (ModelStructure `dependencies`); None: on all of them.
    pub dependencies: Option<&'static [&'static str]>,
    /// Names of the knowns at initialization (inputs, variables with initial =
    /// "exact") an initial unknown depends on (InitialUnknowns `dependencies`); None:
    /// on all of them.
    pub initial_dependencies: Option<&'static [&'static str]>,
    /// Set for the elements declared by [`RealArray`](super::arrays::RealArray).
    pub array: Option<ArrayElement>,
    /// The declaration this scalar is element i of, if it was declared
    /// ([`declare`](super::declare)).
    pub declared: Option<(&'static Declaration<M>, usize)>,
}

impl<M: 'static> Variable<M> {
    fn with_kind(
        vr: u32,
        name: impl Into<Cow<'static, str>>,
        description: impl Into<Cow<'static, str>>,
        kind: Kind<M>,
    ) -> Self {
        let variability = match kind {
            Kind::Real { .. } => Variability::Continuous,
            _ => Variability::Discrete,
        };
        Variable {
            value_reference: vr,
            stored_name: name.into(),
            stored_description: description.into(),
            causality: Causality::Local,
            variability,
            initial: None,
            kind,
            dependencies: None,
            initial_dependencies: None,
            array: None,
            declared: None,
        }
    }

    /// Replaces the description (e.g. per element of an array).
    pub fn describe(mut self, description: impl Into<Cow<'static, str>>) -> Self {
        self.stored_description = description.into();
        self
    }

    /// A Real variable read by `get` (a local until a role is given).
    pub fn real(
        vr: u32,
        name: impl Into<Cow<'static, str>>,
        description: impl Into<Cow<'static, str>>,
        get: impl Fn(&M) -> f64 + Send + Sync + 'static,
    ) -> Self {
        let kind = Kind::Real {
            get: Getter::Closure(Box::new(get)),
            set: None,
            start: None,
            min: None,
            max: None,
            unit: None,
            display_unit: None,
            derivative_of_built: None,
        };
        Self::with_kind(vr, name, description, kind)
    }

    /// An Integer variable read by `get`.
    pub fn integer(
        vr: u32,
        name: impl Into<Cow<'static, str>>,
        description: impl Into<Cow<'static, str>>,
        get: impl Fn(&M) -> i32 + Send + Sync + 'static,
    ) -> Self {
        let kind = Kind::Integer {
            get: Getter::Closure(Box::new(get)),
            set: None,
            start: None,
            min: None,
            max: None,
        };
        Self::with_kind(vr, name, description, kind)
    }

    /// A Boolean variable read by `get`.
    pub fn boolean(
        vr: u32,
        name: impl Into<Cow<'static, str>>,
        description: impl Into<Cow<'static, str>>,
        get: impl Fn(&M) -> bool + Send + Sync + 'static,
    ) -> Self {
        let kind = Kind::Boolean {
            get: Getter::Closure(Box::new(get)),
            set: None,
            start: None,
        };
        Self::with_kind(vr, name, description, kind)
    }

    /// Role: parameter (initial exact), fixed after initialization or tunable.
    pub fn parameter(mut self, variability: Variability) -> Self {
        self.causality = Causality::Parameter;
        self.variability = variability;
        self.initial = Some(Initial::Exact);
        self
    }

    /// Role: input (no initial attribute; a start value is required).
    pub fn input(mut self) -> Self {
        self.causality = Causality::Input;
        self
    }

    /// Role: output computed by the model (initial calculated, no start value).
    pub fn output(mut self) -> Self {
        self.causality = Causality::Output;
        self.initial = Some(Initial::Calculated);
        self
    }

    /// Role: continuous state (local, initial exact with a start value).
    pub fn state(mut self) -> Self {
        self.causality = Causality::Local;
        self.initial = Some(Initial::Exact);
        self
    }

    /// Role: time derivative of the state named `state` (local, calculated).
    pub fn derivative_of(mut self, state: impl Into<Cow<'static, str>>) -> Self {
        self.causality = Causality::Local;
        self.initial = Some(Initial::Calculated);
        if let Kind::Real {
            derivative_of_built,
            ..
        } = &mut self.kind
        {
            *derivative_of_built = Some(state.into());
        }
        self
    }

    /// The inputs and continuous states (by name) this output or derivative depends on;
    /// declared so that importers see which outputs have no direct feedthrough.
    /// A static list: building it costs nothing at instantiation.
    pub fn depends_on(mut self, names: &'static [&'static str]) -> Self {
        self.dependencies = Some(names);
        self
    }

    /// Start value of a Real variable.
    pub fn start_real(mut self, value: f64) -> Self {
        if let Kind::Real { start, .. } = &mut self.kind {
            *start = Some(value);
        }
        self
    }

    /// Start value of an Integer variable.
    pub fn start_integer(mut self, value: i32) -> Self {
        if let Kind::Integer { start, .. } = &mut self.kind {
            *start = Some(value);
        }
        self
    }

    /// Start value of a Boolean variable.
    pub fn start_boolean(mut self, value: bool) -> Self {
        if let Kind::Boolean { start, .. } = &mut self.kind {
            *start = Some(value);
        }
        self
    }

    /// Unit (and optionally display unit) of a Real variable.
    pub fn unit(mut self, name: &'static str, display: Option<&'static str>) -> Self {
        if let Kind::Real {
            unit, display_unit, ..
        } = &mut self.kind
        {
            *unit = Some(name);
            *display_unit = display;
        }
        self
    }

    /// Bounds of a Real variable, enforced on every set.
    pub fn real_range(mut self, lower: Option<f64>, upper: Option<f64>) -> Self {
        if let Kind::Real { min, max, .. } = &mut self.kind {
            *min = lower;
            *max = upper;
        }
        self
    }

    /// Bounds of an Integer variable, enforced on every set.
    pub fn integer_range(mut self, lower: i32, upper: i32) -> Self {
        if let Kind::Integer { min, max, .. } = &mut self.kind {
            *min = Some(lower);
            *max = Some(upper);
        }
        self
    }

    /// Writer of a Real variable.
    pub fn set_real(
        mut self,
        f: impl Fn(&mut M, f64) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        if let Kind::Real { set, .. } = &mut self.kind {
            *set = Some(Setter::Closure(Box::new(f)));
        }
        self
    }

    /// Writer of an Integer variable.
    pub fn set_integer(
        mut self,
        f: impl Fn(&mut M, i32) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        if let Kind::Integer { set, .. } = &mut self.kind {
            *set = Some(Setter::Closure(Box::new(f)));
        }
        self
    }

    /// Writer of a Boolean variable.
    pub fn set_boolean(
        mut self,
        f: impl Fn(&mut M, bool) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        if let Kind::Boolean { set, .. } = &mut self.kind {
            *set = Some(Setter::Closure(Box::new(f)));
        }
        self
    }

    /// The FMI 2.0 name; an element of a declared array is named when asked (`q[2]`),
    /// so that nothing is formatted at instantiation.
    pub fn name(&self) -> Cow<'_, str> {
        match (&self.array, self.declared) {
            (Some(array), Some((_, i))) => array.name(i).into(),
            _ => Cow::Borrowed(&self.stored_name),
        }
    }

    /// The FMI 2.0 name as [`Display`](std::fmt::Display), written without an
    /// allocation (for messages formatted only on a refusal).
    pub fn shown_name(&self) -> ShownName<'_> {
        match (self.array, self.declared) {
            (Some(array), Some((_, i))) => ShownName::Element(array, i),
            _ => ShownName::Plain(&self.stored_name),
        }
    }

    /// The FMI 2.0 description; element i of a labelled declared array is described
    /// when asked ("`label` i: description").
    pub fn description(&self) -> Cow<'_, str> {
        match self.declared {
            Some((d, i)) => match (d.label, d.length) {
                (Some(label), Some(_)) => format!("{label} {}: {}", i + 1, d.description).into(),
                _ => d.description.into(),
            },
            None => Cow::Borrowed(&self.stored_description),
        }
    }

    /// The scalar as (name, element index): a declared element by its declaration's
    /// name and index (None for a scalar), any other by its name. Compared with
    /// [`Variable::state_key`] without formatting a name.
    pub fn key(&self) -> (&str, Option<usize>) {
        match self.declared {
            Some((d, i)) => (d.name, d.length.map(|_| i)),
            None => (&self.stored_name, None),
        }
    }

    /// The [`key`](Variable::key) of the state this scalar is the time derivative of.
    pub fn state_key(&self) -> Option<(&str, Option<usize>)> {
        match (self.declared, &self.kind) {
            (Some((d, i)), _) => Some((d.derivative_of?, d.length.map(|_| i))),
            (
                None,
                Kind::Real {
                    derivative_of_built: Some(state),
                    ..
                },
            ) => Some((state, None)),
            _ => None,
        }
    }

    /// The name of the state this scalar is the time derivative of (formatted when
    /// asked for an element of a declared array).
    pub fn state_name(&self) -> Option<Cow<'_, str>> {
        Some(match self.state_key()? {
            (state, None) => Cow::Borrowed(state),
            (state, Some(i)) => numbered(&[state, "["], i + 1, "]").into(),
        })
    }

    /// Whether this scalar is the time derivative of a state.
    pub fn is_derivative(&self) -> bool {
        self.state_key().is_some()
    }

    /// The declared element this scalar is, if it was declared.
    pub fn element(&self) -> Option<Element> {
        let (d, index) = self.declared?;
        Some(Element {
            name: d.name,
            index,
        })
    }

    /// The declaration's output-derivative hook and the element index, if any.
    pub fn output_hook(&self) -> Option<(OutputDerivative<M>, usize)> {
        let (d, index) = self.declared?;
        Some((d.output_derivative?, index))
    }

    /// The declaration's input-derivative slot and the element index, if any.
    pub fn input_hook(&self) -> Option<(InputDerivative<M>, usize)> {
        let (d, index) = self.declared?;
        Some((d.input_derivative?, index))
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

/// A variable's FMI 2.0 name, written when displayed ([`Variable::shown_name`]).
#[derive(Debug, Clone, Copy)]
pub enum ShownName<'a> {
    Plain(&'a str),
    /// Element i of a declared array.
    Element(ArrayElement, usize),
}

impl std::fmt::Display for ShownName<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            ShownName::Plain(name) => f.write_str(name),
            ShownName::Element(a, i) if a.derivative => write!(f, "der({}[{}])", a.base, i + 1),
            ShownName::Element(a, i) => write!(f, "{}[{}]", a.base, i + 1),
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

/// Checks every variable of a table against the rules of the standard that importers
/// enforce: unique names, value references strictly increasing, legal (causality,
/// variability, initial) combinations, start values exactly where required, a writer
/// for every variable that may be set, derivatives that name an existing Real state.
/// The whole check, arrays included, is [`check_table`](super::check::check_table).
pub fn check_variables<M>(table: &[Variable<M>]) -> Result<(), String> {
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
