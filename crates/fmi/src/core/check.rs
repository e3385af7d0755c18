//! The check of a whole variable table: each variable ([`variables`](super::variables))
//! and each array's elements ([`arrays`](super::arrays)).

use super::arrays::check_arrays;
use super::variables::{Variable, check_variables};

/// Checks a table against the rules of the standard that importers enforce: the rules
/// of every variable ([`check_variables`]) and the arrays' elements (consecutive
/// indices from 1, one type, causality and unit per array).
pub fn check_table<M>(table: &[Variable<M>]) -> Result<(), String> {
    check_variables(table)?;
    check_arrays(table)
}
