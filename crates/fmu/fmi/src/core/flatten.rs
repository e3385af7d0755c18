//! The FMI 2.0 scalars of a declared table ([`declare`](super::declare)): what an
//! instance holds, element by element, pointing back at its declaration. Nothing is
//! formatted here: an element's name, description and state are formatted from its
//! declaration when asked ([`Variable::name`]).

use super::declare::{Access, Declaration, Set, Value, value_references};
use super::hooks::Var;
use super::variables::{Getter, Kind, Setter, Variable};

/// The FMI 2.0 scalars of the declarations, in declaration order (the layer sorts them
/// by value reference).
pub fn flatten<M>(declarations: &'static [Declaration<M>]) -> Vec<Variable<M>> {
    let firsts = value_references(declarations);
    let total = declarations.iter().map(Declaration::size).sum();
    let mut table = Vec::with_capacity(total);
    for (d, first) in declarations.iter().zip(firsts) {
        table.extend((0..d.size()).map(|i| element(declarations, d, first, i)));
    }
    table
}

/// Element i of declaration `d` as an FMI 2.0 scalar.
fn element<M>(
    all: &[Declaration<M>],
    d: &'static Declaration<M>,
    first: u32,
    i: usize,
) -> Variable<M> {
    Variable {
        value_reference: first + i as u32 * d.stride,
        causality: d.causality,
        variability: d.variability,
        initial: d.initial,
        kind: kind(&d.value, i),
        dependencies: d.dependencies.map(|x| names(x.of(i), all, i)),
        initial_dependencies: d.initial_dependencies.map(|x| names(x.of(i), all, i)),
        declaration: d,
        index: i,
    }
}

/// The FMI 2.0 names of the variables `vars` of element i stands for ("time" for the
/// independent variable); a name that no declaration has is kept as it is, for
/// `check_table` to refuse.
fn names<M>(vars: &[Var], all: &[Declaration<M>], i: usize) -> Vec<String> {
    let length = |name: &str| all.iter().find(|d| d.name == name).and_then(|d| d.length);
    let mut out = Vec::with_capacity(vars.len());
    for var in vars {
        match *var {
            Var::Time => out.push("time".to_string()),
            Var::Whole(name) => match length(name) {
                Some(n) => out.extend((1..=n).map(|k| format!("{name}[{k}]"))),
                None => out.push(name.to_string()),
            },
            Var::Item(name, k) => out.push(format!("{name}[{}]", k + 1)),
            Var::Same(name) => out.push(format!("{name}[{}]", i + 1)),
        }
    }
    out
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
            get: Getter { f: get, index: i },
            set: setter(get, set, i),
            start: start_of(start, i),
            min,
            max,
            unit,
            display_unit,
        },
        Value::Integer {
            get,
            set,
            start,
            min,
            max,
        } => Kind::Integer {
            get: Getter { f: get, index: i },
            set: setter(get, set, i),
            start: start_of(start, i),
            min,
            max,
        },
        Value::Boolean { get, set, start } => Kind::Boolean {
            get: Getter { f: get, index: i },
            set: setter(get, set, i),
            start: start_of(start, i),
        },
    }
}

/// The writer of element i, if the element is writable (a writer or a place).
fn setter<M, T: Copy>(get: Access<M, T>, set: Option<Set<M, T>>, i: usize) -> Option<Setter<M, T>> {
    let setter = Setter {
        access: get,
        f: set,
        index: i,
    };
    (set.is_some() || get.is_place()).then_some(setter)
}

/// Start value of element i: none, the one for all, or element i's.
pub(super) fn start_of<T: Copy>(start: &[T], i: usize) -> Option<T> {
    match start {
        [] => None,
        [all] => Some(*all),
        each => Some(each[i]),
    }
}
