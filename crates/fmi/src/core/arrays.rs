//! One declaration for an array variable `base[1..n]` of the variable table: value
//! references `first + i * stride`, one getter and one setter taking the element
//! index, roles applied per element, and the [`ArrayElement`] metadata an FMI 3.0
//! array needs. [`Array::variables`] gives the scalars (FMI 2.0 names `base[1]` ...).

use super::variables::{Variable, find};
use std::borrow::Cow;
use std::sync::Arc;

/// Position of a scalar in an array variable `base[1..length]`: the FMI 2.0 name is
/// `base[index + 1]` (`der(base[index + 1])` for the derivative of an array state);
/// an FMI 3.0 front-end declares one array `base` (`der(base)`) with
/// `<Dimension start="length"/>` from its elements.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ArrayElement {
    pub base: &'static str,
    /// 0-based.
    pub index: usize,
    pub length: usize,
    /// Step of the value references from one element to the next.
    pub stride: u32,
    /// The element is the time derivative of `base[index + 1]`.
    pub derivative: bool,
}

impl ArrayElement {
    /// The FMI 2.0 name of element `index`.
    pub fn name(&self, index: usize) -> String {
        if self.derivative {
            format!("der({}[{}])", self.base, index + 1)
        } else {
            format!("{}[{}]", self.base, index + 1)
        }
    }

    /// Value reference of element `index` of the array whose element `self.index`
    /// has the value reference `vr`.
    pub fn value_reference(&self, vr: u32, index: usize) -> u32 {
        vr - self.index as u32 * self.stride + index as u32 * self.stride
    }
}

/// The FMI types an array element can have, with their variable constructors.
pub trait ElementType: Copy + Send + Sync + 'static {
    fn variable<M>(
        vr: u32,
        name: String,
        description: Cow<'static, str>,
        get: impl Fn(&M) -> Self + Send + Sync + 'static,
    ) -> Variable<M>;

    fn with_setter<M>(
        v: Variable<M>,
        set: impl Fn(&mut M, Self) -> Result<(), String> + Send + Sync + 'static,
    ) -> Variable<M>;
}

impl ElementType for f64 {
    fn variable<M>(
        vr: u32,
        name: String,
        description: Cow<'static, str>,
        get: impl Fn(&M) -> f64 + Send + Sync + 'static,
    ) -> Variable<M> {
        Variable::real(vr, name, description, get)
    }

    fn with_setter<M>(
        v: Variable<M>,
        set: impl Fn(&mut M, f64) -> Result<(), String> + Send + Sync + 'static,
    ) -> Variable<M> {
        v.set_real(set)
    }
}

impl ElementType for i32 {
    fn variable<M>(
        vr: u32,
        name: String,
        description: Cow<'static, str>,
        get: impl Fn(&M) -> i32 + Send + Sync + 'static,
    ) -> Variable<M> {
        Variable::integer(vr, name, description, get)
    }

    fn with_setter<M>(
        v: Variable<M>,
        set: impl Fn(&mut M, i32) -> Result<(), String> + Send + Sync + 'static,
    ) -> Variable<M> {
        v.set_integer(set)
    }
}

impl ElementType for bool {
    fn variable<M>(
        vr: u32,
        name: String,
        description: Cow<'static, str>,
        get: impl Fn(&M) -> bool + Send + Sync + 'static,
    ) -> Variable<M> {
        Variable::boolean(vr, name, description, get)
    }

    fn with_setter<M>(
        v: Variable<M>,
        set: impl Fn(&mut M, bool) -> Result<(), String> + Send + Sync + 'static,
    ) -> Variable<M> {
        v.set_boolean(set)
    }
}

type ElementGetter<M, T> = dyn Fn(&M, usize) -> T + Send + Sync;
type ElementSetter<M, T> = dyn Fn(&mut M, usize, T) -> Result<(), String> + Send + Sync;
/// A role applied to element i of an array (causality, unit, start value, ...).
type ElementRole<M> = Box<dyn Fn(Variable<M>, usize) -> Variable<M>>;

/// One declaration of an array `base[1..length]` of element type T (see the module
/// documentation).
pub struct Array<M, T: ElementType> {
    first_vr: u32,
    stride: u32,
    base: &'static str,
    length: usize,
    derivative: bool,
    get: Arc<ElementGetter<M, T>>,
    set: Option<Arc<ElementSetter<M, T>>>,
    roles: Vec<ElementRole<M>>,
    description: Cow<'static, str>,
    /// Element i is described as "`label` i: `description`".
    label: Option<&'static str>,
}

pub type RealArray<M> = Array<M, f64>;
pub type IntegerArray<M> = Array<M, i32>;
pub type BooleanArray<M> = Array<M, bool>;

impl<M: 'static, T: ElementType> Array<M, T> {
    /// The array `base[1..length]`, value references `first_vr + i` (see
    /// [`Array::stride`]), element i read by `get(model, i)`.
    pub fn new(
        first_vr: u32,
        base: &'static str,
        length: usize,
        description: impl Into<Cow<'static, str>>,
        get: impl Fn(&M, usize) -> T + Send + Sync + 'static,
    ) -> Self {
        Array {
            first_vr,
            stride: 1,
            base,
            length,
            derivative: false,
            get: Arc::new(get),
            set: None,
            roles: Vec::new(),
            description: description.into(),
            label: None,
        }
    }

    /// Value references `first_vr + i * stride` instead of consecutive ones (arrays
    /// whose elements interleave with other arrays' by index).
    pub fn stride(mut self, stride: u32) -> Self {
        self.stride = stride;
        self
    }

    /// Describes element i as "`label` i: description" (e.g. "Axis 2: position").
    pub fn label(mut self, label: &'static str) -> Self {
        self.label = Some(label);
        self
    }

    /// The writer of every element.
    pub fn set(
        mut self,
        set: impl Fn(&mut M, usize, T) -> Result<(), String> + Send + Sync + 'static,
    ) -> Self {
        self.set = Some(Arc::new(set));
        self
    }

    /// Applies `role` (causality, unit, start value, description, ...) to element `i`.
    pub fn each(mut self, role: impl Fn(Variable<M>, usize) -> Variable<M> + 'static) -> Self {
        self.roles.push(Box::new(role));
        self
    }

    fn element(&self) -> ArrayElement {
        ArrayElement {
            base: self.base,
            index: 0,
            length: self.length,
            stride: self.stride,
            derivative: self.derivative,
        }
    }

    fn description(&self, i: usize) -> Cow<'static, str> {
        match self.label {
            Some(label) => format!("{label} {}: {}", i + 1, self.description).into(),
            None => self.description.clone(),
        }
    }

    /// The scalar variables, element 0 first.
    pub fn variables(self) -> Vec<Variable<M>> {
        (0..self.length)
            .map(|i| {
                let element = ArrayElement {
                    index: i,
                    ..self.element()
                };
                let get = self.get.clone();
                let vr = self.first_vr + i as u32 * self.stride;
                let mut v =
                    T::variable(vr, element.name(i), self.description(i), move |m| get(m, i));
                if let Some(set) = &self.set {
                    let set = set.clone();
                    v = T::with_setter(v, move |m, x| set(m, i, x));
                }
                if self.derivative {
                    v = v.derivative_of(format!("{}[{}]", self.base, i + 1));
                }
                v.array = Some(element);
                self.roles.iter().fold(v, |v, role| role(v, i))
            })
            .collect()
    }
}

impl<M: 'static> RealArray<M> {
    /// The time derivatives `der(state[1..length])` of the array state `state`, value
    /// references `first_vr + i` (see [`Array::stride`]), element i read by
    /// `get(model, i)`.
    pub fn derivatives(
        first_vr: u32,
        state: &'static str,
        length: usize,
        description: impl Into<Cow<'static, str>>,
        get: impl Fn(&M, usize) -> f64 + Send + Sync + 'static,
    ) -> Self {
        Array {
            derivative: true,
            ..Array::new(first_vr, state, length, description, get)
        }
    }
}

/// Every array: all elements present, named `base[i]` (`der(base[i])`), at the value
/// references its stride gives (what an FMI 3.0 array of one value reference needs).
pub(super) fn check_arrays<M>(table: &[Variable<M>]) -> Result<(), String> {
    for v in table {
        let Some(element) = &v.array else { continue };
        if v.name != element.name(element.index) {
            return Err(format!(
                "\"{}\": array element named unlike its position",
                v.name
            ));
        }
        if element.stride == 0 {
            return Err(format!(
                "array \"{}\": value reference stride 0",
                element.base
            ));
        }
        for i in 0..element.length {
            let vr = element.value_reference(v.value_reference, i);
            let found = find(table, vr).and_then(|e| e.array.as_ref());
            let same = found.is_some_and(|e| {
                e.base == element.base && e.derivative == element.derivative && e.index == i
            });
            if !same {
                return Err(format!(
                    "array \"{}\": element {} is not at value reference {vr}",
                    element.name(i),
                    i + 1,
                ));
            }
        }
    }
    Ok(())
}
