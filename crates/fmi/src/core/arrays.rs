//! One declaration for an array variable `base[1..n]` of the variable table: value
//! references `first + i * stride`, one getter and one setter taking the element
//! index, roles applied per element, and the [`ArrayElement`] metadata an FMI 3.0
//! array needs. [`Array::variables`] gives the scalars (FMI 2.0 names `base[1]` ...).

pub use super::element::ArrayElement;
use super::element::numbered;
use super::variables::{Variable, find};
use std::borrow::Cow;
use std::marker::PhantomData;

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

/// `ElementType` for `$t` through the `Variable` constructor `$new` and writer `$set`.
macro_rules! element_type {
    ($t:ty, $new:ident, $set:ident) => {
        impl ElementType for $t {
            fn variable<M>(
                vr: u32,
                name: String,
                description: Cow<'static, str>,
                get: impl Fn(&M) -> $t + Send + Sync + 'static,
            ) -> Variable<M> {
                Variable::$new(vr, name, description, get)
            }

            fn with_setter<M>(
                v: Variable<M>,
                set: impl Fn(&mut M, $t) -> Result<(), String> + Send + Sync + 'static,
            ) -> Variable<M> {
                v.$set(set)
            }
        }
    };
}

element_type!(f64, real, set_real);
element_type!(i32, integer, set_integer);
element_type!(bool, boolean, set_boolean);

/// What a declaration does to element i (causality, unit, start value, writer, ...).
pub trait Role<M: 'static>: Fn(Variable<M>, usize) -> Variable<M> {}

impl<M: 'static, F: Fn(Variable<M>, usize) -> Variable<M>> Role<M> for F {}

/// One declaration of an array `base[1..length]` of element type T (see the module
/// documentation). The elements are built at once; the roles given by
/// [`Array::each`], [`Array::set`] and [`Array::label`] are composed (no boxing) and
/// applied in one pass by [`Array::variables`], so a declaration allocates nothing
/// beyond its scalars.
pub struct Array<M: 'static, T: ElementType, R = fn(Variable<M>, usize) -> Variable<M>> {
    elements: Vec<Variable<M>>,
    first_vr: u32,
    role: R,
    marker: PhantomData<T>,
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
        get: impl Fn(&M, usize) -> T + Clone + Send + Sync + 'static,
    ) -> Self {
        Self::declare(first_vr, base, length, description.into(), false, get)
    }

    fn declare(
        first_vr: u32,
        base: &'static str,
        length: usize,
        description: Cow<'static, str>,
        derivative: bool,
        get: impl Fn(&M, usize) -> T + Clone + Send + Sync + 'static,
    ) -> Self {
        let elements = (0..length)
            .map(|i| {
                let element = ArrayElement {
                    base,
                    index: i,
                    length,
                    stride: 1,
                    derivative,
                };
                let get = get.clone();
                let vr = first_vr + i as u32;
                let mut v =
                    T::variable(vr, element.name(i), description.clone(), move |m| get(m, i));
                if derivative {
                    v = v.derivative_of(numbered(&[base, "["], i + 1, "]"));
                }
                v.array = Some(element);
                v
            })
            .collect();
        Array {
            elements,
            first_vr,
            role: |v, _| v,
            marker: PhantomData,
        }
    }
}

impl<M: 'static, T: ElementType, R: Role<M>> Array<M, T, R> {
    /// Value references `first_vr + i * stride` instead of consecutive ones (arrays
    /// whose elements interleave with other arrays' by index).
    pub fn stride(mut self, stride: u32) -> Self {
        for (i, v) in self.elements.iter_mut().enumerate() {
            v.value_reference = self.first_vr + i as u32 * stride;
            if let Some(element) = &mut v.array {
                element.stride = stride;
            }
        }
        self
    }

    /// Describes element i as "`label` i: description" (e.g. "Axis 2: position").
    pub fn label(self, label: &'static str) -> Array<M, T, impl Role<M>> {
        self.each(move |v, i| {
            let description = numbered(&[label, " "], i + 1, ": ") + &v.stored_description;
            v.describe(description)
        })
    }

    /// The writer of every element.
    pub fn set(
        self,
        set: impl Fn(&mut M, usize, T) -> Result<(), String> + Clone + Send + Sync + 'static,
    ) -> Array<M, T, impl Role<M>> {
        self.each(move |v, i| {
            let set = set.clone();
            T::with_setter(v, move |m, x| set(m, i, x))
        })
    }

    /// Applies `role` (causality, unit, start value, description, ...) to element `i`
    /// after the roles given before.
    pub fn each(self, role: impl Role<M>) -> Array<M, T, impl Role<M>> {
        let previous = self.role;
        Array {
            elements: self.elements,
            first_vr: self.first_vr,
            role: move |v, i| role(previous(v, i), i),
            marker: PhantomData,
        }
    }

    /// The scalar variables, element 0 first.
    pub fn variables(self) -> Vec<Variable<M>> {
        let role = self.role;
        self.elements
            .into_iter()
            .enumerate()
            .map(|(i, v)| role(v, i))
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
        get: impl Fn(&M, usize) -> f64 + Clone + Send + Sync + 'static,
    ) -> Self {
        Self::declare(first_vr, state, length, description.into(), true, get)
    }
}

/// Every array: all elements present, named `base[i]` (`der(base[i])`), at the value
/// references its stride gives (what an FMI 3.0 array of one value reference needs).
pub(super) fn check_arrays<M>(table: &[Variable<M>]) -> Result<(), String> {
    for v in table {
        let Some(element) = &v.array else { continue };
        if v.name() != element.name(element.index) {
            return Err(format!(
                "\"{}\": array element named unlike its position",
                v.name()
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

#[cfg(test)]
mod tests {
    use super::numbered;

    #[test]
    fn numbers_are_written_in_decimal() {
        assert_eq!(numbered(&["x", "["], 1, "]"), "x[1]");
        assert_eq!(numbered(&["der(", "x", "["], 10, "])"), "der(x[10])");
        assert_eq!(numbered(&["Axis "], 1234, ": "), "Axis 1234: ");
        assert_eq!(numbered(&[], 0, ""), "0");
    }
}
