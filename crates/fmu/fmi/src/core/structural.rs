//! Structural parameters (FMI 3.0 only): a UInt64 parameter that sizes arrays, set in
//! Configuration Mode. A model lists them in [`Model::STRUCTURAL`]; an array declares
//! its size with [`Declaration::sized_by`](super::Declaration::sized_by) (a [`Family`](super::Family) sized by one
//! says it once for all its arrays). The model keeps the size itself (the length of its
//! per-channel vectors): `get` reads it, `resize` changes it; the layer then writes the
//! start value of each new element of every array the parameter sizes (the declared
//! start of that element when the declaration lists one per element and the element is
//! among them, the one start value when it gives one for all, else zero / false), so
//! elements kept keep their values. The model's `Default` may hold empty vectors: the
//! layer resizes it to the starts before it writes the start values. FMI 2.0 and the
//! scalar-only FMI 3.0 view serve the default size only.

use super::declare::{self, write_element};
use super::model::Model;
pub use super::sizes::{MAX_STRUCTURAL, Sizes, StructuralParameter};
use super::variables::element_name;

/// The start value of element i of a declaration whose start values are `start`.
fn start_at<T: Copy + Default>(start: &[T], i: usize) -> Option<T> {
    match start {
        [] => None,
        [all] => Some(*all),
        each => Some(each.get(i).copied().unwrap_or_default()),
    }
}

/// Sets structural parameter k of `model` to `n` (checked by the caller): the model
/// resizes, then every new element of the arrays it sizes takes its start value
/// (through the declaration's writer or place, then its `after_set` hook).
pub fn resize<M: Model>(model: &mut M, k: usize, n: usize) -> Result<(), String> {
    let p = M::STRUCTURAL
        .get(k)
        .ok_or_else(|| format!("no structural parameter {k}"))?;
    let old = (p.get)(model);
    (p.resize)(model, n);
    for d in M::VARIABLES.iter().filter(|d| d.sized_by == Some(k)) {
        for i in old..n {
            let written = match d.value {
                declare::Value::Real {
                    get, set, start, ..
                } => start_at(start, i).and_then(|s| write_element(get, set, model, i, s)),
                declare::Value::Integer {
                    get, set, start, ..
                } => start_at(start, i).and_then(|s| write_element(get, set, model, i, s)),
                declare::Value::Boolean { get, set, start } => {
                    start_at(start, i).and_then(|s| write_element(get, set, model, i, s))
                }
            };
            match (written, d.after_set) {
                (Some(Err(e)), _) => {
                    let name = element_name(d, i);
                    return Err(format!("start value of \"{name}\" rejected: {e}"));
                }
                (Some(Ok(())), Some(after)) => after(model, i),
                _ => {}
            }
        }
    }
    Ok(())
}

/// `model` (a model's `Default`, whose vectors may be empty) resized to every
/// structural parameter's start, before the start values are written.
pub fn at_start<M: Model>(mut model: M) -> M {
    for p in M::STRUCTURAL {
        if (p.get)(&model) != p.start {
            (p.resize)(&mut model, p.start);
        }
    }
    model
}

/// The model's structural parameters agree with its declarations: each sized
/// declaration names an existing parameter whose default is its length, at most
/// [`MAX_STRUCTURAL`] of them, and the model's `get` answers the start once resized
/// to it (checked where the FMI 3.0 view is built).
pub fn check<M: Model>() -> Result<(), String> {
    let fresh = at_start(M::default());
    if M::STRUCTURAL.len() > MAX_STRUCTURAL {
        return Err(format!("more than {MAX_STRUCTURAL} structural parameters"));
    }
    for d in M::VARIABLES {
        let Some(k) = d.sized_by else { continue };
        let Some(p) = M::STRUCTURAL.get(k) else {
            return Err(format!(
                "\"{}\" is sized by structural parameter {k}, which the model lacks",
                d.name
            ));
        };
        if d.size() != p.start {
            return Err(format!(
                "\"{}\" has {} elements, its structural parameter \"{}\" starts at {}",
                d.name,
                d.size(),
                p.name,
                p.start
            ));
        }
    }
    let clocked = M::CLOCKS.iter().flat_map(|c| c.outputs);
    for o in clocked.filter(|o| o.sized_by.is_some()) {
        let p = o.sized_by.and_then(|k| M::STRUCTURAL.get(k));
        if p.is_none_or(|p| o.length != Some(p.start)) {
            return Err(format!(
                "\"{}\" is sized by a structural parameter the model lacks or whose start \
                 is not its length",
                o.name
            ));
        }
    }
    for p in M::STRUCTURAL {
        if (p.get)(&fresh) != p.start {
            return Err(format!(
                "the model holds \"{}\" = {} after resizing it to its start {}",
                p.name,
                (p.get)(&fresh),
                p.start
            ));
        }
    }
    Ok(())
}

/// Err unless every structural parameter of `model` is at its default: the byte form
/// of FMU states (`core::serialize`) holds the default sizes only, so a state of
/// other sizes is kept (fmi3GetFMUState / fmi3SetFMUState copy the model, sizes
/// included) but not serialized.
pub fn at_default_sizes<M: Model>(model: &M) -> Result<(), String> {
    match M::STRUCTURAL.iter().find(|p| (p.get)(model) != p.start) {
        None => Ok(()),
        Some(p) => Err(format!(
            "\"{}\" = {} (default {}): serialized FMU states hold the default sizes only; \
             fmi3GetFMUState / fmi3SetFMUState keep this state",
            p.name,
            (p.get)(model),
            p.start
        )),
    }
}

/// The number of continuous states of `model` at its current sizes (FMI 3.0: an
/// array of states sized by a structural parameter has as many as it holds now).
pub fn continuous_states_now<M: Model>(model: &M) -> usize {
    let sizes = Sizes::of(model, M::STRUCTURAL);
    (M::VARIABLES.iter())
        .filter(|d| d.derivative_of.is_some())
        .map(|d| d.size_now(&sizes))
        .sum()
}
