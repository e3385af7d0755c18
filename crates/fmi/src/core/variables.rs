//! The variable table of a model: for every variable its metadata (what
//! modelDescription.xml says about it) and its accessors (how the layer reads and writes
//! it). It is the single source of truth for both.

pub type Getter<M, T> = Box<dyn Fn(&M) -> T + Send + Sync>;
pub type Setter<M, T> = Box<dyn Fn(&mut M, T) -> Result<(), String> + Send + Sync>;

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
        /// Name of the state this variable is the time derivative of.
        derivative_of: Option<String>,
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

/// Position of a scalar in an array variable `base[1..length]`: the FMI 2.0 name is
/// `base[index + 1]`; an FMI 3.0 front-end declares one array `base` with
/// `<Dimension start="length"/>` from its elements.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ArrayElement {
    pub base: String,
    /// 0-based.
    pub index: usize,
    pub length: usize,
}

/// One scalar variable.
pub struct Variable<M> {
    pub value_reference: u32,
    pub name: String,
    pub description: String,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub kind: Kind<M>,
    /// Names of the inputs and continuous states an output or state derivative
    /// depends on (ModelStructure `dependencies`); None: on all of them.
    pub dependencies: Option<Vec<String>>,
    /// Set for the elements declared by [`RealArray`].
    pub array: Option<ArrayElement>,
}

impl<M> Variable<M> {
    fn with_kind(vr: u32, name: impl Into<String>, description: &str, kind: Kind<M>) -> Self {
        let variability = match kind {
            Kind::Real { .. } => Variability::Continuous,
            _ => Variability::Discrete,
        };
        Variable {
            value_reference: vr,
            name: name.into(),
            description: description.to_string(),
            causality: Causality::Local,
            variability,
            initial: None,
            kind,
            dependencies: None,
            array: None,
        }
    }

    /// Replaces the description (e.g. per element of an array).
    pub fn describe(mut self, description: impl Into<String>) -> Self {
        self.description = description.into();
        self
    }

    /// A Real variable read by `get` (a local until a role is given).
    pub fn real(
        vr: u32,
        name: impl Into<String>,
        description: &str,
        get: impl Fn(&M) -> f64 + Send + Sync + 'static,
    ) -> Self {
        let kind = Kind::Real {
            get: Box::new(get),
            set: None,
            start: None,
            min: None,
            max: None,
            unit: None,
            display_unit: None,
            derivative_of: None,
        };
        Self::with_kind(vr, name, description, kind)
    }

    /// An Integer variable read by `get`.
    pub fn integer(
        vr: u32,
        name: impl Into<String>,
        description: &str,
        get: impl Fn(&M) -> i32 + Send + Sync + 'static,
    ) -> Self {
        let kind = Kind::Integer {
            get: Box::new(get),
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
        name: impl Into<String>,
        description: &str,
        get: impl Fn(&M) -> bool + Send + Sync + 'static,
    ) -> Self {
        let kind = Kind::Boolean {
            get: Box::new(get),
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
    pub fn derivative_of(mut self, state: &str) -> Self {
        self.causality = Causality::Local;
        self.initial = Some(Initial::Calculated);
        if let Kind::Real { derivative_of, .. } = &mut self.kind {
            *derivative_of = Some(state.to_string());
        }
        self
    }

    /// The inputs and continuous states (by name) this output or derivative depends on;
    /// declared so that importers see which outputs have no direct feedthrough.
    pub fn depends_on(mut self, names: impl IntoIterator<Item = String>) -> Self {
        self.dependencies = Some(names.into_iter().collect());
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
            *set = Some(Box::new(f));
        }
        self
    }

    /// Writer of an Integer variable.
    pub fn set_integer(
        mut self,
        f: impl Fn(&mut M, i32) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        if let Kind::Integer { set, .. } = &mut self.kind {
            *set = Some(Box::new(f));
        }
        self
    }

    /// Writer of a Boolean variable.
    pub fn set_boolean(
        mut self,
        f: impl Fn(&mut M, bool) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        if let Kind::Boolean { set, .. } = &mut self.kind {
            *set = Some(Box::new(f));
        }
        self
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

type ElementGetter<M> = dyn Fn(&M, usize) -> f64 + Send + Sync;
type ElementSetter<M> = dyn Fn(&mut M, usize, f64) -> Result<(), String> + Send + Sync;
/// A role applied to element i of an array (causality, unit, start value, ...).
type ElementRole<M> = Box<dyn Fn(Variable<M>, usize) -> Variable<M>>;

/// One declaration of a Real array `base[1..length]`: value references
/// `first_vr + i`, one getter and one setter taking the element index, and the
/// [`ArrayElement`] metadata an FMI 3.0 array needs. [`RealArray::variables`] gives
/// the scalars (FMI 2.0 names `base[1]` ...).
pub struct RealArray<M> {
    first_vr: u32,
    base: String,
    length: usize,
    get: std::sync::Arc<ElementGetter<M>>,
    set: Option<std::sync::Arc<ElementSetter<M>>>,
    roles: Vec<ElementRole<M>>,
    description: String,
}

impl<M: 'static> RealArray<M> {
    pub fn new(
        first_vr: u32,
        base: &str,
        length: usize,
        description: &str,
        get: impl Fn(&M, usize) -> f64 + Send + Sync + 'static,
    ) -> Self {
        RealArray {
            first_vr,
            base: base.to_string(),
            length,
            get: std::sync::Arc::new(get),
            set: None,
            roles: Vec::new(),
            description: description.to_string(),
        }
    }

    /// The writer of every element.
    pub fn set(
        mut self,
        set: impl Fn(&mut M, usize, f64) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        self.set = Some(std::sync::Arc::new(set));
        self
    }

    /// Applies `role` (causality, unit, start value, description, ...) to element `i`.
    pub fn each(mut self, role: impl Fn(Variable<M>, usize) -> Variable<M> + 'static) -> Self {
        self.roles.push(Box::new(role));
        self
    }

    /// The scalar variables, element 0 first.
    pub fn variables(self) -> Vec<Variable<M>> {
        (0..self.length)
            .map(|i| {
                let get = self.get.clone();
                let name = format!("{}[{}]", self.base, i + 1);
                let first = self.first_vr + i as u32;
                let mut v = Variable::real(first, name, &self.description, move |m: &M| get(m, i));
                if let Some(set) = &self.set {
                    let set = set.clone();
                    v = v.set_real(move |m, x| set(m, i, x));
                }
                v.array = Some(ArrayElement {
                    base: self.base.clone(),
                    index: i,
                    length: self.length,
                });
                self.roles.iter().fold(v, |v, role| role(v, i))
            })
            .collect()
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

/// Checks a table against the rules of the standard that importers enforce: unique
/// names, value references strictly increasing, legal (causality, variability,
/// initial) combinations, start values exactly where required, a writer for every
/// variable that may be set, derivatives that name an existing Real state.
pub fn check_table<M>(table: &[Variable<M>]) -> Result<(), String> {
    use Causality as C;
    use Variability as V;
    for pair in table.windows(2) {
        if pair[0].value_reference >= pair[1].value_reference {
            return Err(format!(
                "value references not strictly increasing at \"{}\"",
                pair[1].name
            ));
        }
    }
    let mut names: Vec<&str> = table.iter().map(|v| v.name.as_str()).collect();
    names.sort_unstable();
    if let Some(w) = names.windows(2).find(|w| w[0] == w[1]) {
        return Err(format!("duplicate variable name \"{}\"", w[0]));
    }
    for v in table {
        let name = &v.name;
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
        if let Kind::Real {
            derivative_of: Some(state),
            ..
        } = &v.kind
        {
            let found = table.iter().any(|s| {
                &s.name == state
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
    check_arrays(table)
}

/// Every array `base[1..n]`: all n elements present, named `base[i]`, with value
/// references increasing by one (what an FMI 3.0 array of one value reference needs).
fn check_arrays<M>(table: &[Variable<M>]) -> Result<(), String> {
    for v in table {
        let Some(element) = &v.array else { continue };
        if v.name != format!("{}[{}]", element.base, element.index + 1) {
            return Err(format!(
                "\"{}\": array element named unlike its position",
                v.name
            ));
        }
        let first = v.value_reference - element.index as u32;
        for i in 0..element.length {
            let found = find(table, first + i as u32).and_then(|e| e.array.as_ref());
            let same = found.is_some_and(|e| e.base == element.base && e.index == i);
            if !same {
                return Err(format!(
                    "array \"{}\": element {} is not at value reference {}",
                    element.base,
                    i + 1,
                    first + i as u32
                ));
            }
        }
    }
    Ok(())
}

/// Dependencies only on outputs and derivatives, and only on inputs and states.
fn check_dependencies<M>(v: &Variable<M>, table: &[Variable<M>]) -> Result<(), String> {
    let Some(names) = &v.dependencies else {
        return Ok(());
    };
    let is_derivative = |v: &Variable<M>| {
        matches!(
            v.kind,
            Kind::Real {
                derivative_of: Some(_),
                ..
            }
        )
    };
    if v.causality != Causality::Output && !is_derivative(v) {
        return Err(format!(
            "\"{}\": only outputs and derivatives declare dependencies",
            v.name
        ));
    }
    for name in names {
        let is_state = derivative_variables(table)
            .iter()
            .any(|d| matches!(&d.kind, Kind::Real { derivative_of: Some(s), .. } if s == name));
        let is_input = table
            .iter()
            .any(|k| &k.name == name && k.causality == Causality::Input);
        if !(is_state || is_input) {
            return Err(format!(
                "\"{}\": dependency \"{name}\" is neither an input nor a continuous state",
                v.name
            ));
        }
    }
    Ok(())
}

/// Value references of the derivative variables, in table order (= state order).
pub fn derivative_variables<M>(table: &[Variable<M>]) -> Vec<&Variable<M>> {
    table
        .iter()
        .filter(|v| {
            matches!(
                v.kind,
                Kind::Real {
                    derivative_of: Some(_),
                    ..
                }
            )
        })
        .collect()
}
