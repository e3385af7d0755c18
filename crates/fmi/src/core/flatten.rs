//! The FMI 2.0 scalars of a declared table ([`declare`](super::declare)): what an
//! instance holds, element by element, pointing back at its declaration. Nothing is
//! formatted here: an element's name, description and state are formatted from its
//! declaration when asked ([`Variable::name`]).

use super::declare::{Declaration, Value, value_references};
use super::element::ArrayElement;
use super::variables::{Getter, Kind, Setter, Variable};
use std::borrow::Cow;

/// The FMI 2.0 scalars of the declarations, in declaration order (the layer sorts them
/// by value reference).
pub fn flatten<M>(declarations: &'static [Declaration<M>]) -> Vec<Variable<M>> {
    let firsts = value_references(declarations);
    let total = declarations.iter().map(Declaration::size).sum();
    let mut table = Vec::with_capacity(total);
    for (d, first) in declarations.iter().zip(firsts) {
        table.extend((0..d.size()).map(|i| element(d, first, i)));
    }
    table
}

/// Element i of declaration `d` as an FMI 2.0 scalar.
fn element<M>(d: &'static Declaration<M>, first: u32, i: usize) -> Variable<M> {
    let vr = first + i as u32 * d.stride;
    let array = d.length.map(|length| ArrayElement {
        base: d.derivative_of.unwrap_or(d.name),
        index: i,
        length,
        stride: d.stride,
        derivative: d.derivative_of.is_some(),
    });
    Variable {
        value_reference: vr,
        stored_name: Cow::Borrowed(d.name),
        stored_description: Cow::Borrowed(d.description),
        causality: d.causality,
        variability: d.variability,
        initial: d.initial,
        kind: kind(&d.value, i),
        dependencies: d.dependencies.map(|x| x.of(i)),
        initial_dependencies: d.initial_dependencies.map(|f| f(i)),
        array,
        declared: Some((d, i)),
    }
}

/// The scalar accessors of element i.
fn kind<M>(value: &Value<M>, i: usize) -> Kind<M> {
    match *value {
        Value::Real {
            get,
            set,
            start,
            min,
            max,
            unit,
            display_unit,
        } => Kind::Real {
            get: Getter::Element(get, i),
            set: set.map(|s| Setter::Element(s, i)),
            start: start_of(start, i),
            min,
            max,
            unit,
            display_unit,
            derivative_of_built: None,
        },
        Value::Integer {
            get,
            set,
            start,
            min,
            max,
        } => Kind::Integer {
            get: Getter::Element(get, i),
            set: set.map(|s| Setter::Element(s, i)),
            start: start_of(start, i),
            min,
            max,
        },
        Value::Boolean { get, set, start } => Kind::Boolean {
            get: Getter::Element(get, i),
            set: set.map(|s| Setter::Element(s, i)),
            start: start_of(start, i),
        },
    }
}

/// Start value of element i: none, the one for all, or element i's.
fn start_of<T: Copy>(start: &[T], i: usize) -> Option<T> {
    match start {
        [] => None,
        [all] => Some(*all),
        each => Some(each[i]),
    }
}
