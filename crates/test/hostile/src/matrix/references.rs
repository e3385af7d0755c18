//! Value references the model does not have, of the wrong type, or of variables
//! that cannot be set, passed to the typed getters and setters of the standard's
//! tables; where the functions take a count of values (FMI 3.0 nValues), counts
//! that do not match the arrays: one element too few, one too many, none, and a
//! huge count with a real array of the right size (the FMU must compare counts
//! before touching the array). The standards only define calls with references of
//! the modelDescription and the function's type (FMI 2.0 2.1.7, FMI 3.0 2.2.6,
//! nValues the total of the elements in 2.2.6.2); the project refuses anything
//! else with an error and a log line naming the reference, the variable or the
//! counts, and the instance stays usable as its standard requires. Cases only
//! one standard has (its derivative, dependency and order functions) are the
//! tables' `reference_extras`.

use super::seam::{Access, Standard};
use super::{Case, Expect, on_instance};
use crate::Loaded;
use crate::description::{Description, VarType};

type Vr = u32;

/// An unused value reference: above every one the model declares.
pub fn unused(d: &Description) -> Vr {
    d.variables.iter().map(|v| v.vr).max().unwrap_or(0) + 1
}

/// The value references no variable has (one above the largest, and the largest
/// representable), as (label, value reference, expected log text).
fn unknown_references(d: &Description) -> [(String, Vr, String); 2] {
    [
        (
            format!("unused vr {}", unused(d)),
            unused(d),
            unused(d).to_string(),
        ),
        ("vr 4294967295".into(), Vr::MAX, "4294967295".into()),
    ]
}

/// Counts that do not match `size` elements: one less, one more, none, huge. A huge
/// count is given with an array of at most 64 elements (the FMU must not use it).
pub fn wrong_counts(size: usize) -> Vec<usize> {
    let mut n = vec![size + 1, 0, usize::MAX / 16];
    if size > 1 {
        n.insert(0, size - 1);
    }
    n
}

/// One probe: label, value reference, count, expected log text, why.
type Probe = (String, Vr, usize, String, &'static str);

/// The probes of a function of `own` type (None: a type the models lack).
fn probes<I: Standard>(d: &Description, own: Option<VarType>, settable: bool) -> Vec<Probe> {
    let tables = I::tables();
    let why = &tables.reasons.references;
    let mut probes: Vec<Probe> = unknown_references(d)
        .into_iter()
        .map(|(label, vr, log)| (label, vr, 1, log, why.unknown))
        .collect();
    for t in [VarType::Real, VarType::Integer, VarType::Boolean] {
        let first = d
            .of_type(t)
            .find(|v| Some(t) != own && v.causality != "independent");
        if let Some(v) = first {
            let why = if own.is_none() {
                why.lacking
            } else {
                why.wrong_type
            };
            let label = format!("{t:?} variable {}", v.name);
            probes.push((label, v.vr, v.size, v.name.clone(), why));
        }
    }
    let Some(own) = own.filter(|_| tables.counted_values) else {
        return probes;
    };
    let own_var = d
        .of_type(own)
        .find(|v| v.causality != "independent" && (!settable || v.is_settable()));
    if let Some(v) = own_var {
        for n in wrong_counts(v.size) {
            let label = format!("{} with nValues = {n}", v.name);
            probes.push((label, v.vr, n, "nValues".into(), why.count));
        }
    }
    probes
}

/// Every probe passed to every getter (Initialization Mode) and setter
/// (Instantiated), and a calculated output set.
fn interface_cases<I: Standard>(d: &Description, m: usize, interface: I) -> Vec<Case> {
    let tables = I::tables();
    let mut cases = Vec::new();
    let groups = [
        ((tables.getters)(), I::INITIALIZATION_MODE, false),
        ((tables.setters)(), I::INSTANTIATED, true),
    ];
    for (functions, state, settable) in groups {
        for (function, own, call) in functions {
            for (label, vr, n, log, why) in probes::<I>(d, own, settable) {
                cases.push(Case::new(
                    ("value reference", m, interface),
                    format!("{function}({label})"),
                    (Expect::error(&log), why),
                    move |l| on_instance(l, m, interface, state, |i| call(i, vr, n)),
                ));
            }
        }
    }
    if let Some(output) = d
        .variables
        .iter()
        .find(|v| v.causality == "output" && v.var_type == VarType::Real)
    {
        let (vr, n) = (output.vr, output.size);
        let set: Access<I> = (tables.setters)()[0];
        cases.push(Case::new(
            ("value reference", m, interface),
            format!("{}(output {})", set.0, output.name),
            (
                Expect::error(&output.name),
                tables.reasons.references.not_settable,
            ),
            move |l| on_instance(l, m, interface, I::INSTANTIATED, |i| (set.2)(i, vr, n)),
        ));
    }
    cases
}

pub fn cases<I: Standard>(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = I::description(loaded, m);
    let extras = I::tables().reference_extras;
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        cases.extend(interface_cases(d, m, interface));
        cases.extend(extras(d, m, interface));
    }
    cases
}
