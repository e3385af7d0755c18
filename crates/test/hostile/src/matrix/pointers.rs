//! Null pointers for every pointer argument of the functions the models support,
//! with a length that makes the pointer necessary, in a state where the call is
//! legal (the rows of `seam::Tables::null_pointers`). Expected: an error and a log
//! line saying which argument is null (the standards leave null arguments
//! undefined; the project refuses them, see docs/reliability.md), and the instance
//! usable as its standard requires.

use super::orders::invoke_probe;
use super::seam::{Row, Standard};
use super::{Case, Expect};
use crate::Loaded;
use crate::description::Description;
use crate::standard_interface::StandardInterface;

/// The states in which the rows of both standards apply (`seam::Applies`).
pub fn init<I: StandardInterface>(_: &Description, _: I) -> Option<I::State> {
    Some(I::INITIALIZATION_MODE)
}
pub fn instantiated<I: StandardInterface>(_: &Description, _: I) -> Option<I::State> {
    Some(I::INSTANTIATED)
}
pub fn me_continuous<I: StandardInterface>(_: &Description, i: I) -> Option<I::State> {
    (i == I::MODEL_EXCHANGE).then_some(I::CONTINUOUS_TIME_MODE)
}
pub fn me_with_states<I: StandardInterface>(d: &Description, i: I) -> Option<I::State> {
    (d.number_of_states > 0).then_some(me_continuous(d, i)?)
}
pub fn me_with_indicators<I: StandardInterface>(d: &Description, i: I) -> Option<I::State> {
    (d.number_of_event_indicators > 0).then_some(me_continuous(d, i)?)
}
pub fn with_partials<I: StandardInterface>(d: &Description, _: I) -> Option<I::State> {
    d.provides_directional_derivative
        .then_some(I::INITIALIZATION_MODE)
}

/// One case per row of `table` that applies to the model and interface: the call
/// with a null pointer in the state the row names, refused with an error and a
/// log line saying "null" (both standards).
fn null_pointer_cases<I: Standard>(
    (d, m): (&Description, usize),
    (class, why): (&'static str, &'static str),
    table: impl Fn() -> Vec<Row<I>>,
) -> Vec<Case> {
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        for (name, applies, invoke) in table() {
            let Some(state) = applies(d, interface) else {
                continue;
            };
            cases.push(Case::new(
                (class, m, interface),
                name.to_string(),
                (Expect::error("null"), why),
                invoke_probe(m, interface, state, invoke),
            ));
        }
    }
    cases
}

pub fn cases<I: Standard>(loaded: &Loaded, m: usize) -> Vec<Case> {
    let tables = I::tables();
    null_pointer_cases::<I>(
        (I::description(loaded, m), m),
        ("null pointer", tables.reasons.null_pointer),
        tables.null_pointers,
    )
}
