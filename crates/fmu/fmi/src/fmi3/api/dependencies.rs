//! fmi3GetNumberOfVariableDependencies and fmi3GetVariableDependencies: per element,
//! which knowns (inputs and continuous states) an output, state derivative or event
//! indicator depends on, from the dependencies the model declares for its scalars
//! (all knowns where it declares none). Every dependency is reported as
//! fmi3Dependent (the layer does not know which are linear). Element indices start at
//! 1 for arrays and are 0 for scalars. An array sized by a structural parameter
//! answers at its current size: an element past the default size has the dependencies
//! of the last default element, each on that element's own index of an array of the
//! same size moved to its own (a channel's output on the same channel's inputs); an
//! element of a known past its size is left out.

use super::{output_ref, output_slice, with_instance};
use crate::core::model::Model;
use crate::core::sizes::Sizes;
use crate::core::variables::{Causality, Variable, find};
use crate::fmi3::mode::Call;
use crate::fmi3::table::{Source, Table3, Variable3};
use crate::fmi3::types::*;

/// One dependency: (element of the dependent, independent, element of it).
type Dependency = (usize, u32, usize);

/// Element index of position `i` in `v` (0 for a scalar).
fn element_index(v: &Variable3, i: usize) -> usize {
    if v.dimension.is_some() { i + 1 } else { 0 }
}

/// Every element of every known at the sizes `sizes`, as (variable, element index).
fn all_knowns(t: &Table3, sizes: &Sizes) -> Vec<(u32, usize)> {
    t.knowns()
        .iter()
        .filter_map(|&vr| t.find(vr))
        .flat_map(|k| (0..k.size_now(sizes)).map(move |i| (k.value_reference, element_index(k, i))))
        .collect()
}

/// The (variable, element index) of the scalar named `name` in the FMI 3.0 table.
fn locate(t: &Table3, table_vr: u32) -> Option<(u32, usize)> {
    t.variables.iter().find_map(|v| {
        let i = v.elements().position(|e| e == table_vr)?;
        Some((v.value_reference, element_index(v, i)))
    })
}

fn is_unknown(v: &Variable3) -> bool {
    v.causality == Causality::Output
        || v.derivative_of.is_some()
        || matches!(v.source, Source::EventIndicators { .. })
}

/// The dependencies of the variable `v` of model M (whose table is `table`).
fn dependencies<M: Model>(
    table: &[Variable<M>],
    t: &Table3,
    v: &Variable3,
    sizes: &Sizes,
) -> Result<Vec<Dependency>, String> {
    if !is_unknown(v) {
        return Ok(Vec::new());
    }
    let mut out = Vec::new();
    let elements = v.elements();
    if elements.is_empty() {
        for (known, k) in all_knowns(t, sizes) {
            out.push((0, known, k));
        }
        return Ok(out);
    }
    // Past the default size d, element i takes the last default element's list, a
    // dependency on that element's own index of an array sized alike moved to its own.
    let elements: Vec<u32> = elements.collect();
    let d = elements.len();
    let sized_alike = |known: u32| {
        v.sized_by.is_some() && t.find(known).is_some_and(|k| k.sized_by == v.sized_by)
    };
    let fits = |known: u32, k: usize| {
        (t.find(known)).is_none_or(|kv| kv.sized_by.is_none() || k <= kv.size_now(sizes))
    };
    for i in 0..v.size_now(sizes) {
        let e = elements[i.min(d - 1)];
        let scalar = find(table, e).ok_or_else(|| format!("no element {e}"))?;
        let knowns = match &scalar.dependencies {
            None => all_knowns(t, sizes),
            Some(names) => names
                .iter()
                .map(|name| {
                    table
                        .iter()
                        .find(|s| s.name() == *name)
                        .and_then(|s| locate(t, s.value_reference))
                        .ok_or_else(|| {
                            format!("\"{}\" depends on unknown \"{name}\"", scalar.name())
                        })
                })
                .collect::<Result<Vec<_>, _>>()?
                .into_iter()
                .map(|(known, k)| {
                    let own = i >= d && k == d && sized_alike(known);
                    (known, if own { i + 1 } else { k })
                })
                .collect(),
        };
        out.extend(
            (knowns.into_iter())
                .filter(|&(known, k)| fits(known, k))
                .map(|(known, k)| (element_index(v, i), known, k)),
        );
    }
    Ok(out)
}

pub unsafe fn get_number_of_variable_dependencies<M: Model>(
    c: Fmi3Instance,
    vr: Fmi3ValueReference,
    n: *mut usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3GetNumberOfVariableDependencies",
            Call::VariableDependencies,
            |inst| {
                let out = output_ref(n, "nDependencies")?;
                let v = inst
                    .extra
                    .table
                    .find(vr)
                    .ok_or_else(|| format!("unknown value reference {vr}"))?;
                let sizes = Sizes::of(inst.core.model(), M::STRUCTURAL);
                *out = dependencies(inst.core.table(), &inst.extra.table, v, &sizes)?.len();
                Ok(Fmi3Status::Ok)
            },
        )
    }
}

/// The output arrays of fmi3GetVariableDependencies.
pub struct DependencyArrays {
    pub element_indices_of_dependent: *mut usize,
    pub independents: *mut Fmi3ValueReference,
    pub element_indices_of_independents: *mut usize,
    pub dependency_kinds: *mut Fmi3DependencyKind,
    pub n_dependencies: usize,
}

pub unsafe fn get_variable_dependencies<M: Model>(
    c: Fmi3Instance,
    dependent: Fmi3ValueReference,
    out: DependencyArrays,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3GetVariableDependencies",
            Call::VariableDependencies,
            |inst| {
                let v = inst
                    .extra
                    .table
                    .find(dependent)
                    .ok_or_else(|| format!("unknown value reference {dependent}"))?;
                let sizes = Sizes::of(inst.core.model(), M::STRUCTURAL);
                let list = dependencies(inst.core.table(), &inst.extra.table, v, &sizes)?;
                let n = out.n_dependencies;
                if n != list.len() {
                    return Err(format!(
                        "nDependencies = {n}, but \"{}\" has {} dependencies",
                        v.name,
                        list.len()
                    ));
                }
                let of_dependent = output_slice(
                    out.element_indices_of_dependent,
                    n,
                    "elementIndicesOfDependent[]",
                )?;
                let independents = output_slice(out.independents, n, "independents[]")?;
                let of_independents = output_slice(
                    out.element_indices_of_independents,
                    n,
                    "elementIndicesOfIndependents[]",
                )?;
                let kinds = output_slice(out.dependency_kinds, n, "dependencyKinds[]")?;
                for (i, (d, known, k)) in list.into_iter().enumerate() {
                    of_dependent[i] = d;
                    independents[i] = known;
                    of_independents[i] = k;
                    kinds[i] = Fmi3DependencyKind::Dependent;
                }
                Ok(Fmi3Status::Ok)
            },
        )
    }
}
