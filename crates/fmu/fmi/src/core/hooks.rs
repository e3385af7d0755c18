//! The hooks a declaration can carry ([`declare`](super::declare)): functions of the
//! model that the layer calls with an element index, never with a value reference.

/// A variable as a model's callbacks see it: the name of its declaration (the FMI 3.0
/// name: `u`, `der(integral)`) and the element's index (0 for a scalar).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Element {
    pub name: &'static str,
    pub index: usize,
}

/// Why `Model::output_derivative` gives no value.
#[derive(Debug, Clone, PartialEq)]
pub enum OutputDerivativeError {
    /// The model does not provide this derivative (this output, or this order of it):
    /// the importer asked for something the FMU does not offer (fmi2Error/fmi3Error).
    NotProvided(String),
    /// The model provides it but cannot evaluate it at this point (Discard).
    CannotEvaluate(String),
}

/// The `order`-th time derivative of output element i (0 for a scalar), at the
/// current time and state with the inputs held; the layer has checked the variable (a
/// Real output) and the order (1 ..= maxOutputDerivativeOrder), and the computed values
/// are current.
pub type OutputDerivative<M> = fn(&M, usize, u32) -> Result<f64, OutputDerivativeError>;

/// Where the model keeps the `order`-th time derivative (1 ..=
/// `MAX_INPUT_DERIVATIVE_ORDER`) of continuous Real input element i, relative to the
/// start of the next step; None: it keeps none. The layer checks the order and the
/// value (finite) before writing, and reads it to serialize FMU states. A derivative
/// holds for every later step until it is set again (a field of the model: clones and
/// FMU states carry it, a reset clears it); it changes neither the input's value nor
/// any output read before the step (see [`input_derivatives`](super::input_derivatives)).
pub type InputDerivative<M> = for<'a> fn(&'a mut M, usize, u32) -> Option<&'a mut f64>;

/// A variable named by a compiler-checked handle in a dependency list: a declaration
/// (`T0.var()`: the scalar, or every element of an array) or one element of an array
/// declaration (`Q0.item(a)`), or the independent variable. The layer turns it into
/// FMI 2.0 names (`q0[2]`) when it flattens the table; no model writes such a name.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Var {
    /// The independent variable, a known at initialization (FMI 3.0's `time`; FMI 2.0
    /// has no variable to name).
    Time,
    /// The declaration of this name: a scalar, or every element of an array.
    Whole(&'static str),
    /// Element i (from 0) of the array declaration of this name.
    Item(&'static str, usize),
    /// The element of the array declaration of this name with the index of the
    /// dependent element itself (`setpoint[c]` for `u[c]`).
    Same(&'static str),
}

/// The variables element i of a declaration depends on: the inputs and states
/// (ModelStructure `dependencies`), or the knowns at initialization (inputs, variables
/// with initial = "exact", [`Var::Time`]) of an initial unknown (InitialUnknowns).
pub type ElementDependencies = fn(usize) -> &'static [Var];

/// The dependencies of a declaration's elements: the same for all, or element by element.
#[derive(Debug, Clone, Copy)]
pub enum Dependencies {
    All(&'static [Var]),
    Each(ElementDependencies),
}

impl Dependencies {
    /// The variables element i depends on.
    pub fn of(self, i: usize) -> &'static [Var] {
        match self {
            Dependencies::All(vars) => vars,
            Dependencies::Each(f) => f(i),
        }
    }
}
