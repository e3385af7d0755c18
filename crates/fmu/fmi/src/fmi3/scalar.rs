//! The scalar-only FMI 3.0 view (dist/fmi3-scalar): every FMI 2.0 scalar of the table
//! (`theta[1]`, ...) is an FMI 3.0 scalar with the same name and value reference, for
//! importers that cannot use FMI 3.0 arrays; the event indicators (no FMI 2.0 variable)
//! are the scalars `eventIndicators[k]` after the table's last value reference; the
//! clocked partitions (`core::clocks`) are left out. The
//! binary serves this view to an instance created with [`token`] instead of the
//! model's GUID.

use super::table::{Source, Table3, Variable3};
use crate::core::model::Model;
use crate::core::variables::{Variable, find};
use std::borrow::Cow;

/// The instantiationToken of the scalar-only description of model M.
pub fn token<M: Model>() -> String {
    format!("{}{SUFFIX}", M::INFO.guid)
}

/// What [`token`] appends to the model's GUID.
const SUFFIX: &str = "-scalar";

/// Whether `given` is [`token`] of model M (compared without formatting the token).
pub fn is_token<M: Model>(given: &str) -> bool {
    given.strip_suffix(SUFFIX) == Some(M::INFO.guid)
}

/// The scalar view of `arrays` (the array view of the flattened `table`): each array
/// of table elements becomes one scalar per element, and so does the event indicators'
/// array; time stays.
pub fn view<M>(table: &[Variable<M>], arrays: &Table3) -> Result<Table3, String> {
    let mut variables = Vec::with_capacity(table.len() + 2);
    for v in &arrays.variables {
        if let Source::EventIndicators { .. } = v.source {
            variables.extend((0..v.size()).map(|k| Variable3 {
                value_reference: v.value_reference + k as u32,
                name: Cow::Owned(format!("{}[{}]", v.name, k + 1)),
                dimension: None,
                sized_by: None,
                source: Source::EventIndicators { first: k },
                ..v.clone()
            }));
            continue;
        }
        if matches!(
            v.source,
            Source::Clock { .. }
                | Source::ClockPeriod { .. }
                | Source::Clocked { .. }
                | Source::Structural { .. }
        ) {
            // The clocked partitions and the structural parameters are served by the
            // array view only: the importers this view is for (ecos) refuse a
            // description with clocks; its arrays keep their default sizes.
            continue;
        }
        let Source::Elements {
            stride,
            declaration,
            element,
            ..
        } = v.source
        else {
            variables.push(v.clone());
            continue;
        };
        let states: Vec<u32> = match v.derivative_of {
            Some(state) => arrays
                .find(state)
                .ok_or_else(|| format!("\"{}\" names an unknown state", v.name))?
                .elements()
                .collect(),
            None => Vec::new(),
        };
        for (k, vr) in v.elements().enumerate() {
            let scalar = find(table, vr).ok_or_else(|| format!("no element {vr}"))?;
            variables.push(Variable3 {
                value_reference: vr,
                name: Cow::Owned(scalar.name().into_owned()),
                dimension: None,
                sized_by: None,
                source: Source::Elements {
                    first: vr,
                    stride,
                    declaration,
                    element: element + k,
                },
                derivative_of: states.get(k).copied(),
                ..v.clone()
            });
        }
    }
    Ok(Table3::new(variables))
}

/// The table value references of the knowns named by `names` (table names, or "time"
/// for value reference 0), ascending; the scalar view's dependencies.
pub fn references<M>(table: &[Variable<M>], names: &[String]) -> Result<Vec<u32>, String> {
    let mut list = names
        .iter()
        .map(|name| match name.as_str() {
            "time" => Ok(super::table::TIME_VALUE_REFERENCE),
            _ => table
                .iter()
                .find(|s| s.name() == *name)
                .map(|s| s.value_reference)
                .ok_or_else(|| format!("unknown variable \"{name}\"")),
        })
        .collect::<Result<Vec<_>, _>>()?;
    list.sort_unstable();
    list.dedup();
    Ok(list)
}
