//! The declarative, array-native variable table: a model declares its variables once,
//! as a `static` slice of [`Declaration`]s, plain data and `fn` pointers, so the
//! declaration allocates nothing and nothing of it has to be freed when the library
//! is unloaded.
//!
//! A variable the model keeps (parameter, input, state) is declared with its place,
//! `|m, i| &mut m.field[i]`: the layer reads and writes through that one accessor
//! ([`Access::Place`]); a variable the model computes (output, derivative) with a
//! getter ([`Access::Get`]). A writer of the model's own ([`Declaration::set_real`]
//! ...) checks a value before it is stored, and [`Declaration::after_set`] runs after
//! every accepted write (a law rebuilt from its parameters).
//!
//! One declaration is a scalar or a one-dimensional array (FMI 3.0 shape: `q` with
//! `<Dimension start="3"/>`); FMI 2.0 sees the array flattened into the scalars
//! `q[1]`..`q[3]` ([`flatten`](super::flatten)). Accessors take the element index (0 for a scalar),
//! hooks take the element index too, so a model never decodes a value reference.
//!
//! The builder methods are `const fn`: a declaration that contradicts itself (a unit on
//! an Integer, a start list of the wrong length, a stride of 0) is a compile error in
//! the `static`. What needs the whole table (unique names, legal causality and
//! variability combinations, derivatives of existing states) is checked by
//! [`check_table`](super::variables::check_table) on the flattened table, in each FMU's
//! drift test.
//!
//! Value references: a declaration pinned with [`Declaration::at`] has its element i
//! at `vr + i * stride`; an unpinned declaration takes the value reference after the
//! largest one of the declarations before it in the slice (the first one takes 1: 0
//! is FMI 3.0's `time`), elements consecutive. Appending a declaration therefore never
//! moves an existing value reference.

use super::attributes::{Causality, Initial, Variability};
pub use super::hooks::{
    Dependencies, Element, ElementDependencies, InputDerivative, OutputDerivative, Var,
};
use super::sizes::Sizes;

/// Reads element i (0 for a scalar) of a value the model computes.
pub type Get<M, T> = fn(&M, usize) -> T;
/// Where the model keeps element i (0 for a scalar): one accessor through which the
/// layer both reads and writes the value.
pub type Place<M, T> = fn(&mut M, usize) -> &mut T;
/// Writes element i (0 for a scalar) with a check of the model's own; Err: the value
/// is refused, with the reason.
pub type Set<M, T> = fn(&mut M, usize, T) -> Result<(), String>;
/// Runs after every accepted write of element i (the model brings what depends on the
/// value up to date).
pub type AfterSet<M> = fn(&mut M, usize);

/// How the layer reads a variable: computed by a getter, or kept at a place (then
/// also written there, unless the declaration gives a writer of its own).
pub enum Access<M, T> {
    Get(Get<M, T>),
    Place(Place<M, T>),
}

impl<M, T: Copy> Access<M, T> {
    /// Element i of `model` (a place is reached through `&mut`, not changed).
    #[inline(always)]
    pub fn read(self, model: &mut M, i: usize) -> T {
        match self {
            Access::Get(get) => get(model, i),
            Access::Place(place) => *place(model, i),
        }
    }

    /// Whether the variable is kept at a place.
    pub fn is_place(self) -> bool {
        matches!(self, Access::Place(_))
    }

    /// Element i of `model` when it is computed (None: it is kept at a place, which
    /// only `&mut` reaches).
    pub fn computed(self, model: &M, i: usize) -> Option<T> {
        match self {
            Access::Get(get) => Some(get(model, i)),
            Access::Place(_) => None,
        }
    }
}

/// The typed part of a declaration. `start` holds no value (none), one value (every
/// element's) or one per element.
pub enum Value<M: 'static> {
    Real {
        get: Access<M, f64>,
        set: Option<Set<M, f64>>,
        start: &'static [f64],
        min: Option<f64>,
        max: Option<f64>,
        unit: Option<&'static str>,
        display_unit: Option<&'static str>,
    },
    Integer {
        get: Access<M, i32>,
        set: Option<Set<M, i32>>,
        start: &'static [i32],
        min: Option<i32>,
        max: Option<i32>,
    },
    Boolean {
        get: Access<M, bool>,
        set: Option<Set<M, bool>>,
        start: &'static [bool],
    },
}

/// One variable of the table, scalar or array (see the module documentation).
///
/// ```
/// use robofmu_fmi::prelude::*;
/// struct Arm { q: [f64; 3] }
/// static VARIABLES: &[Declaration<Arm>] = &[
///     Declaration::real_in("q", |m: &mut Arm, i| &mut m.q[i])
///         .describe("joint angle")
///         .array(3)
///         .parameter(Variability::Fixed)
///         .unit("rad", Some("deg"))
///         .start_real(&[0.0, 0.5, 1.0]),
/// ];
/// ```
///
/// A declaration that contradicts itself does not compile, e.g. two start values for
/// three elements:
///
/// ```compile_fail
/// use robofmu_fmi::prelude::*;
/// struct Arm { q: [f64; 3] }
/// static VARIABLES: &[Declaration<Arm>] = &[
///     Declaration::real("q", "joint angle", |m: &Arm, i| m.q[i]).array(3).start_real(&[0.0, 0.5]),
/// ];
/// ```
pub struct Declaration<M: 'static> {
    pub name: &'static str,
    pub description: &'static str,
    /// FMI 2.0 element descriptions "`label` i: description" (e.g. "Axis 2: ...").
    pub label: Option<&'static str>,
    /// `Some(n)`: an array of n elements.
    pub length: Option<usize>,
    /// Pinned value reference of element 1, if any.
    pub value_reference: Option<u32>,
    /// Step of the value references from one element to the next.
    pub stride: u32,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub value: Value<M>,
    /// The state (scalar or array) this declaration is the time derivative of.
    pub derivative_of: Option<&'static str>,
    /// The inputs and continuous states an output or derivative depends on.
    pub dependencies: Option<Dependencies>,
    /// Hook: the knowns at initialization an initial unknown depends on, by element.
    pub initial_dependencies: Option<Dependencies>,
    /// Hook: time derivatives of an output.
    pub output_derivative: Option<OutputDerivative<M>>,
    /// The highest order `output_derivative` answers (0: no hook).
    pub output_derivative_order: u32,
    /// Hook: where the model keeps the time derivatives of a continuous input.
    pub input_derivative: Option<InputDerivative<M>>,
    /// Hook: runs after every accepted write of an element.
    pub after_set: Option<AfterSet<M>>,
    /// `Some(k)`: the array's length is the structural parameter `Model::STRUCTURAL[k]`
    /// (FMI 3.0 array view; `length` is its default, the size FMI 2.0 and the
    /// scalar-only view keep).
    pub sized_by: Option<usize>,
}

impl<M, T> Clone for Access<M, T> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M, T> Copy for Access<M, T> {}

/// Writes `value` to element i through `set` if given, else at the place of `get`;
/// None: neither (a computed variable without a writer).
pub fn write_element<M, T>(
    get: Access<M, T>,
    set: Option<Set<M, T>>,
    model: &mut M,
    i: usize,
    value: T,
) -> Option<Result<(), String>> {
    match (set, get) {
        (Some(set), _) => Some(set(model, i, value)),
        (None, Access::Place(place)) => {
            *place(model, i) = value;
            Some(Ok(()))
        }
        (None, Access::Get(_)) => None,
    }
}

impl<M> Clone for Value<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Value<M> {}
impl<M> Clone for Declaration<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Declaration<M> {}

/// A builder method `$method(x)` that sets the field `$field` of a `Value::$variant`
/// to `x` (or `$wrap(x)`); on a declaration of another type it panics, which in the
/// `static` of a model is a compile error.
macro_rules! typed {
    ($(#[$doc:meta])* $method:ident, $variant:ident, $field:ident: $t:ty $(, $wrap:ident)?) => {
        $(#[$doc])*
        pub const fn $method(mut self, x: $t) -> Self {
            match &mut self.value {
                Value::$variant { $field, .. } => *$field = $($wrap)?(x),
                _ => panic!(concat!(stringify!($method), " on a declaration of another type")),
            }
            assert!(self.start_fits(), "give one start value or one per element");
            self
        }
    };
}

impl<M> Declaration<M> {
    const fn with_value(name: &'static str, description: &'static str, value: Value<M>) -> Self {
        let variability = match value {
            Value::Real { .. } => Variability::Continuous,
            _ => Variability::Discrete,
        };
        Declaration {
            name,
            description,
            label: None,
            length: None,
            value_reference: None,
            stride: 1,
            causality: Causality::Local,
            variability,
            initial: None,
            value,
            derivative_of: None,
            dependencies: None,
            initial_dependencies: None,
            output_derivative: None,
            output_derivative_order: 0,
            input_derivative: None,
            after_set: None,
            sized_by: None,
        }
    }

    /// The number of elements now: its structural parameter's value in `sizes`, or
    /// its length.
    pub fn size_now(&self, sizes: &Sizes) -> usize {
        match self.sized_by {
            Some(k) => sizes.get(k),
            None => self.size(),
        }
    }

    /// An array whose length is the structural parameter `Model::STRUCTURAL[k]` (its
    /// default is the declared length).
    pub const fn sized_by(mut self, k: usize) -> Self {
        assert!(
            self.length.is_some(),
            "only an array is sized by a structural parameter"
        );
        self.sized_by = Some(k);
        self
    }

    /// A Real variable the model computes, read by `get` (a local until a role is
    /// given).
    pub const fn real(name: &'static str, description: &'static str, get: Get<M, f64>) -> Self {
        Self::real_access(name, description, Access::Get(get))
    }

    /// A Real variable kept at `place`, read and written there (its description given
    /// by [`describe`](Self::describe)): `Declaration::real_in("kp", |m, i| &mut m.kp[i])`.
    pub const fn real_in(name: &'static str, place: Place<M, f64>) -> Self {
        Self::real_access(name, "", Access::Place(place))
    }

    /// An Integer variable kept at `place`, read and written there.
    pub const fn integer_in(name: &'static str, place: Place<M, i32>) -> Self {
        Self::integer_access(name, "", Access::Place(place))
    }

    /// A Boolean variable kept at `place`, read and written there.
    pub const fn boolean_in(name: &'static str, place: Place<M, bool>) -> Self {
        Self::boolean_access(name, "", Access::Place(place))
    }

    const fn real_access(
        name: &'static str,
        description: &'static str,
        get: Access<M, f64>,
    ) -> Self {
        let value = Value::Real {
            get,
            set: None,
            start: &[],
            min: None,
            max: None,
            unit: None,
            display_unit: None,
        };
        Self::with_value(name, description, value)
    }

    /// An Integer variable the model computes, read by `get`.
    pub const fn integer(name: &'static str, description: &'static str, get: Get<M, i32>) -> Self {
        Self::integer_access(name, description, Access::Get(get))
    }

    const fn integer_access(
        name: &'static str,
        description: &'static str,
        get: Access<M, i32>,
    ) -> Self {
        let value = Value::Integer {
            get,
            set: None,
            start: &[],
            min: None,
            max: None,
        };
        Self::with_value(name, description, value)
    }

    /// A Boolean variable the model computes, read by `get`.
    pub const fn boolean(name: &'static str, description: &'static str, get: Get<M, bool>) -> Self {
        Self::boolean_access(name, description, Access::Get(get))
    }

    const fn boolean_access(
        name: &'static str,
        description: &'static str,
        get: Access<M, bool>,
    ) -> Self {
        let value = Value::Boolean {
            get,
            set: None,
            start: &[],
        };
        Self::with_value(name, description, value)
    }

    /// The description (FMI 2.0 prefixes each element's with its label).
    pub const fn describe(mut self, description: &'static str) -> Self {
        self.description = description;
        self
    }

    /// Hook: `f(model, i)` after every accepted write of element i (e.g. a law
    /// rebuilt from its parameters).
    pub const fn after_set(mut self, f: AfterSet<M>) -> Self {
        self.after_set = Some(f);
        self
    }

    /// An array of `length` elements instead of a scalar.
    pub const fn array(mut self, length: usize) -> Self {
        assert!(length > 0, "an array has at least one element");
        self.length = Some(length);
        assert!(self.start_fits(), "give one start value or one per element");
        self
    }

    /// Pins the value reference of element 1 (see the module documentation).
    pub const fn at(mut self, value_reference: u32) -> Self {
        self.value_reference = Some(value_reference);
        self
    }

    /// Value references `vr + i * stride` (arrays interleaved with others by index).
    pub const fn stride(mut self, stride: u32) -> Self {
        assert!(stride > 0, "a value reference stride is at least 1");
        self.stride = stride;
        self
    }

    /// Describes element i in FMI 2.0 as "`label` i: description".
    pub const fn label(mut self, label: &'static str) -> Self {
        self.label = Some(label);
        self
    }

    /// Role: parameter (initial exact), fixed after initialization or tunable.
    pub const fn parameter(mut self, variability: Variability) -> Self {
        self.causality = Causality::Parameter;
        self.variability = variability;
        self.initial = Some(Initial::Exact);
        self
    }

    /// Role: input (no initial attribute; a start value is required).
    pub const fn input(mut self) -> Self {
        self.causality = Causality::Input;
        self
    }

    /// Role: output computed by the model (initial calculated, no start value).
    pub const fn output(mut self) -> Self {
        self.causality = Causality::Output;
        self.initial = Some(Initial::Calculated);
        self
    }

    /// Role: continuous state (local, initial exact with a start value).
    pub const fn state(mut self) -> Self {
        self.causality = Causality::Local;
        self.initial = Some(Initial::Exact);
        self
    }

    /// Role: time derivative of the state `state` (local, calculated); for an array,
    /// element i is the derivative of element i of the array `state`.
    pub const fn derivative_of(mut self, state: &'static str) -> Self {
        assert!(
            matches!(
                self.value,
                Value::Real {
                    get: Access::Get(_),
                    ..
                }
            ),
            "a derivative is a Real the model computes"
        );
        self.causality = Causality::Local;
        self.initial = Some(Initial::Calculated);
        self.derivative_of = Some(state);
        self
    }

    /// The inputs and continuous states this output or derivative depends on; without
    /// it, on all of them.
    pub const fn depends_on(mut self, vars: &'static [Var]) -> Self {
        self.dependencies = Some(Dependencies::All(vars));
        self
    }

    /// Hook: the inputs and continuous states element i of this output or derivative
    /// depends on, when the elements differ (`theta[i]` on `theta[i]` alone).
    pub const fn depends_on_each(mut self, f: ElementDependencies) -> Self {
        self.dependencies = Some(Dependencies::Each(f));
        self
    }

    /// The knowns at initialization this output or derivative depends on (the same
    /// for every element; [`Var::Same`] names the element's own index); without it, on
    /// all of them.
    pub const fn initial_depends_on(mut self, vars: &'static [Var]) -> Self {
        self.initial_dependencies = Some(Dependencies::All(vars));
        self
    }

    /// Hook: the knowns at initialization element i of this output or derivative
    /// depends on, when the elements differ otherwise than by [`Var::Same`].
    pub const fn initial_depends_on_each(mut self, f: ElementDependencies) -> Self {
        self.initial_dependencies = Some(Dependencies::Each(f));
        self
    }

    /// Unit (and display unit) of a Real.
    pub const fn unit(mut self, name: &'static str, display: Option<&'static str>) -> Self {
        match &mut self.value {
            Value::Real {
                unit, display_unit, ..
            } => {
                *unit = Some(name);
                *display_unit = display;
            }
            _ => panic!("only a Real has a unit"),
        }
        self
    }

    /// Bounds of a Real, enforced on every set.
    pub const fn real_range(mut self, lower: Option<f64>, upper: Option<f64>) -> Self {
        match &mut self.value {
            Value::Real { min, max, .. } => {
                *min = lower;
                *max = upper;
            }
            _ => panic!("real_range on a declaration that is no Real"),
        }
        self
    }

    /// Bounds of an Integer, enforced on every set.
    pub const fn integer_range(mut self, lower: i32, upper: i32) -> Self {
        match &mut self.value {
            Value::Integer { min, max, .. } => {
                *min = Some(lower);
                *max = Some(upper);
            }
            _ => panic!("integer_range on a declaration that is no Integer"),
        }
        self
    }

    typed! {
        /// Start value(s) of a Real: one for every element or one per element.
        start_real, Real, start: &'static [f64]
    }
    typed! {
        /// Start value(s) of an Integer: one for every element or one per element.
        start_integer, Integer, start: &'static [i32]
    }
    typed! {
        /// Start value(s) of a Boolean: one for every element or one per element.
        start_boolean, Boolean, start: &'static [bool]
    }
    typed! {
        /// Writer of a Real.
        set_real, Real, set: Set<M, f64>, Some
    }
    typed! {
        /// Writer of an Integer.
        set_integer, Integer, set: Set<M, i32>, Some
    }
    typed! {
        /// Writer of a Boolean.
        set_boolean, Boolean, set: Set<M, bool>, Some
    }

    /// Hook: the time derivatives of this Real output of orders 1 ..= `order`, element
    /// by element. maxOutputDerivativeOrder is the highest `order` of the table's hooks
    /// ([`max_output_derivative_order`]), so the capability and the hook are one fact.
    ///
    /// A hook that answers no order does not compile:
    ///
    /// ```compile_fail
    /// use robofmu_fmi::prelude::*;
    /// struct Arm { q: f64 }
    /// static VARIABLES: &[Declaration<Arm>] = &[
    ///     Declaration::real("q", "joint angle", |m: &Arm, _| m.q).output().output_derivative(0, |_, _, _| Ok(0.0)),
    /// ];
    /// ```
    pub const fn output_derivative(mut self, order: u32, f: OutputDerivative<M>) -> Self {
        assert!(
            matches!(self.value, Value::Real { .. }),
            "only a Real output has output derivatives"
        );
        assert!(
            order > 0,
            "an output-derivative hook answers order 1 at least"
        );
        self.output_derivative = Some(f);
        self.output_derivative_order = order;
        self
    }

    /// Hook: where the model keeps the time derivatives of this continuous Real input,
    /// element by element (the layer checks the order and the value before writing).
    pub const fn input_derivative(mut self, f: InputDerivative<M>) -> Self {
        assert!(
            matches!(self.value, Value::Real { .. }),
            "only a Real input has input derivatives"
        );
        self.input_derivative = Some(f);
        self
    }

    /// This declaration as a dependency: the scalar, or every element of the array.
    pub const fn var(&self) -> Var {
        Var::Whole(self.name)
    }

    /// Element i (from 0) of this array as a dependency; out of range: a compile error
    /// in a `static`.
    pub const fn item(&self, i: usize) -> Var {
        assert!(
            self.length.is_some() && i < self.size(),
            "item of an array, within its length"
        );
        Var::Item(self.name, i)
    }

    /// The element of this array with the dependent element's own index, as a
    /// dependency.
    pub const fn same(&self) -> Var {
        assert!(self.length.is_some(), "same of an array");
        Var::Same(self.name)
    }

    /// Whether `e` is an element of this declaration (a partial derivative's unknown or
    /// known, compared by the compiler-checked declaration instead of its name).
    pub fn is(&self, e: Element) -> bool {
        e.name == self.name
    }

    /// Number of elements (1 for a scalar).
    pub const fn size(&self) -> usize {
        match self.length {
            Some(n) => n,
            None => 1,
        }
    }

    const fn start_count(&self) -> usize {
        match self.value {
            Value::Real { start, .. } => start.len(),
            Value::Integer { start, .. } => start.len(),
            Value::Boolean { start, .. } => start.len(),
        }
    }

    const fn start_fits(&self) -> bool {
        let n = self.start_count();
        n <= 1 || n == self.size()
    }
}

/// Number of continuous states of a table: the elements of its derivative declarations
/// (numberOfContinuousStates and the length of every state vector the layer passes,
/// counted from the table so that no second count can disagree).
pub const fn continuous_states<M>(declarations: &[Declaration<M>]) -> usize {
    let mut n = 0;
    let mut k = 0;
    while k < declarations.len() {
        if declarations[k].derivative_of.is_some() {
            n += declarations[k].size();
        }
        k += 1;
    }
    n
}

/// maxOutputDerivativeOrder of a table: the highest order its output-derivative hooks
/// answer (0: none), taken from the hooks' declarations so that the two cannot disagree.
pub const fn max_output_derivative_order<M>(declarations: &[Declaration<M>]) -> u32 {
    let (mut max, mut k) = (0, 0);
    while k < declarations.len() {
        if declarations[k].output_derivative_order > max {
            max = declarations[k].output_derivative_order;
        }
        k += 1;
    }
    max
}

/// Calls `f(k, state, derivative, i)` for continuous state k: element i of the state
/// declaration `state` whose time derivative is element i of `derivative`, in the
/// order of the derivative declarations (the state order: the FMI 3.0 view checks at
/// packaging that the derivatives list the states in that order).
fn each_state<M>(
    declarations: &[Declaration<M>],
    sizes: &Sizes,
    mut f: impl FnMut(usize, &Declaration<M>, &Declaration<M>, usize),
) {
    let mut k = 0;
    for d in declarations {
        let Some(name) = d.derivative_of else {
            continue;
        };
        let Some(state) = declarations.iter().find(|s| s.name == name) else {
            continue;
        };
        for i in 0..d.size_now(sizes) {
            f(k, state, d, i);
            k += 1;
        }
    }
}

/// The continuous states as the table declares them: `x[k]` = state k.
pub fn read_states<M>(
    declarations: &[Declaration<M>],
    sizes: &Sizes,
    model: &mut M,
    x: &mut [f64],
) {
    each_state(declarations, sizes, |k, state, _, i| {
        if let (Value::Real { get, .. }, Some(slot)) = (&state.value, x.get_mut(k)) {
            *slot = get.read(model, i);
        }
    });
}

/// Writes the continuous states through the state declarations' writers or places
/// (the layer has checked the values).
pub fn write_states<M>(declarations: &[Declaration<M>], sizes: &Sizes, model: &mut M, x: &[f64]) {
    each_state(declarations, sizes, |k, state, _, i| {
        if let (Value::Real { get, set, .. }, Some(&v)) = (&state.value, x.get(k)) {
            // A state's writer refuses nothing the layer's value check lets through.
            if let Some(Ok(())) = write_element(*get, *set, model, i, v)
                && let Some(after) = state.after_set
            {
                after(model, i);
            }
        }
    });
}

/// The state derivatives as the table declares them: `dx[k]` = the getter of the
/// derivative of state k.
pub fn read_derivatives<M>(
    declarations: &[Declaration<M>],
    sizes: &Sizes,
    model: &M,
    dx: &mut [f64],
) {
    each_state(declarations, sizes, |k, _, derivative, i| {
        // A derivative is computed (`derivative_of` refuses a place).
        if let (Value::Real { get, .. }, Some(slot)) = (&derivative.value, dx.get_mut(k)) {
            *slot = get.computed(model, i).unwrap_or(f64::NAN);
        }
    });
}

/// Where declaration `d` lies when the next unpinned value reference is `next`: the
/// value reference of its element 1, and the next unpinned one after it (the scheme of
/// the module documentation, once for [`value_references`] and, at compile time,
/// [`unique_value_references`]).
const fn placed<M>(d: &Declaration<M>, next: u32) -> (u32, u32) {
    let first = match d.value_reference {
        Some(vr) => vr,
        None => next,
    };
    let last = first + (d.size() as u32 - 1) * d.stride;
    (first, if last + 1 > next { last + 1 } else { next })
}

/// Whether an element of `a` (element 1 at `fa`) and one of `b` (element 1 at `fb`)
/// share a value reference.
const fn overlaps<M>(a: &Declaration<M>, fa: u32, b: &Declaration<M>, fb: u32) -> bool {
    let mut i = 0;
    while i < a.size() {
        let mut j = 0;
        while j < b.size() {
            if fa + i as u32 * a.stride == fb + j as u32 * b.stride {
                return true;
            }
            j += 1;
        }
        i += 1;
    }
    false
}

/// Panics, naming the later declaration, when two elements of the table share a value
/// reference. `export_fmu!` evaluates it on the model's table in a `static`
/// ([`Header::of`](crate::description::Header::of)), so a duplicate value reference is a
/// compile error of the FMU crate:
///
/// ```compile_fail
/// use robofmu_fmi::prelude::*;
/// struct Arm { q: f64, p: f64 }
/// const TABLE: &[Declaration<Arm>] = &[
///     Declaration::real("q", "joint angle", |m: &Arm, _| m.q).at(7),
///     Declaration::real("p", "joint rate", |m: &Arm, _| m.p).at(7),
/// ];
/// const _: () = robofmu_fmi::core::declare::unique_value_references(TABLE);
/// ```
pub const fn unique_value_references<M>(declarations: &[Declaration<M>]) {
    let (mut b, mut next_b) = (0, 1);
    while b < declarations.len() {
        let (fb, after_b) = placed(&declarations[b], next_b);
        let (mut a, mut next_a) = (0, 1);
        while a < b {
            let (fa, after_a) = placed(&declarations[a], next_a);
            if overlaps(&declarations[a], fa, &declarations[b], fb) {
                panic!("{}", declarations[b].name); // takes a value reference taken before
            }
            (a, next_a) = (a + 1, after_a);
        }
        (b, next_b) = (b + 1, after_b);
    }
}

/// The value references of every declaration's element 1 by the scheme of the module
/// documentation.
pub fn value_references<M>(declarations: &[Declaration<M>]) -> Vec<u32> {
    let mut next = 1;
    declarations
        .iter()
        .map(|d| {
            let first;
            (first, next) = placed(d, next);
            first
        })
        .collect()
}
