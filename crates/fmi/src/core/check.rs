//! The check of a whole variable table against the rules of the standard that
//! importers enforce (run where modelDescription.xml is written; an instance relies
//! only on unique value references).

use super::variables::{Variable, check_variables};

/// Checks a table: unique names, value references strictly increasing, legal
/// (causality, variability, initial) combinations, start values and writers exactly
/// where required, derivatives of existing continuous states, dependencies on inputs
/// and states only ([`check_variables`]).
pub fn check_table<M>(table: &[Variable<M>]) -> Result<(), String> {
    check_variables(table)
}
