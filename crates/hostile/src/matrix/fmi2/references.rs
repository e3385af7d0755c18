//! Value references the model does not have, of the wrong type, or of variables
//! that cannot be set. The standard (FMI 2.0 section 2.1.7) only defines calls
//! with value references of the modelDescription and the function's type; the
//! project refuses anything else with fmi2Error and a log line naming the
//! reference or the variable.

use crate::Loaded;
use crate::binary::{Status, Vr};
use crate::description::{Description, VarType};
use crate::fmu::Standard;
use crate::host::{Instance, Interface, State};
use crate::matrix::{Case, Expect, on_instance};

const WHY_UNKNOWN: &str =
    "value reference not in the modelDescription (FMI 2.0 2.1.7): fmi2Error naming it";
const WHY_TYPE: &str = "value reference of another type than the function's (FMI 2.0 2.1.7): fmi2Error naming the variable";
const WHY_NOT_SETTABLE: &str = "calculated output set with fmi2SetReal (FMI 2.0 2.2.7 allows setting only parameters, inputs and initial=exact/approx): fmi2Error naming it";
const WHY_STRING: &str = "the models have no String variables: every reference is refused";

type Getter = fn(&Instance, Vr) -> Status;

fn getters() -> [(&'static str, Option<VarType>, Getter); 4] {
    [
        ("fmi2GetReal", Some(VarType::Real), |i, vr| {
            i.get_reals(&[vr]).0
        }),
        ("fmi2GetInteger", Some(VarType::Integer), |i, vr| unsafe {
            (i.binary.get_integer)(i.c, &vr, 1, &mut 0)
        }),
        ("fmi2GetBoolean", Some(VarType::Boolean), |i, vr| unsafe {
            (i.binary.get_boolean)(i.c, &vr, 1, &mut 0)
        }),
        ("fmi2GetString", None, |i, vr| unsafe {
            (i.binary.get_string)(i.c, &vr, 1, &mut std::ptr::null())
        }),
    ]
}

fn setters() -> [(&'static str, Option<VarType>, Getter); 4] {
    [
        ("fmi2SetReal", Some(VarType::Real), |i, vr| {
            i.set_real(vr, 0.0)
        }),
        ("fmi2SetInteger", Some(VarType::Integer), |i, vr| unsafe {
            (i.binary.set_integer)(i.c, &vr, 1, &1)
        }),
        ("fmi2SetBoolean", Some(VarType::Boolean), |i, vr| unsafe {
            (i.binary.set_boolean)(i.c, &vr, 1, &0)
        }),
        ("fmi2SetString", None, |i, vr| unsafe {
            (i.binary.set_string)(i.c, &vr, 1, &c"x".as_ptr())
        }),
    ]
}

/// An unused value reference: above every one the model declares.
pub(crate) fn unused(d: &Description) -> Vr {
    d.variables.iter().map(|v| v.vr).max().unwrap_or(0) + 1
}

/// The value references no variable has (one above the largest, and the largest
/// representable), as (label, value reference, expected log text); shared with
/// the FMI 3.0 matrix.
pub(crate) fn unknown_references(d: &Description) -> [(String, Vr, String); 2] {
    [
        (
            format!("unused vr {}", unused(d)),
            unused(d),
            unused(d).to_string(),
        ),
        ("vr 4294967295".into(), Vr::MAX, "4294967295".into()),
    ]
}

/// (label, value reference, expected log text, why) for a function of `own` type.
fn probes(d: &Description, own: Option<VarType>) -> Vec<(String, Vr, String, &'static str)> {
    let mut p: Vec<_> = unknown_references(d)
        .into_iter()
        .map(|(label, vr, log)| (label, vr, log, WHY_UNKNOWN))
        .collect();
    for t in [VarType::Real, VarType::Integer, VarType::Boolean] {
        if Some(t) == own {
            continue;
        }
        if let Some(v) = d.of_type(t).next() {
            let why = if own.is_none() { WHY_STRING } else { WHY_TYPE };
            p.push((
                format!("{:?} variable {}", t, v.name),
                v.vr,
                v.name.clone(),
                why,
            ));
        }
    }
    p
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = &loaded.fmus[m].description;
    let mut cases = Vec::new();
    for interface in Interface::BOTH {
        let groups = [
            (getters(), State::InitializationMode),
            (setters(), State::Instantiated),
        ];
        for (functions, state) in groups {
            for (function, own, call) in functions {
                for (label, vr, log, why) in probes(d, own) {
                    cases.push(Case {
                        standard: Standard::Fmi2,
                        class: "value reference",
                        model: m,
                        interface: Some(interface.short()),
                        name: format!("{function}({label})"),
                        expect: Expect::error(&log),
                        why,
                        probe: Box::new(move |l| {
                            on_instance(l, m, interface, state, |i| call(i, vr))
                        }),
                    });
                }
            }
        }
        if let Some(output) = d
            .variables
            .iter()
            .find(|v| v.causality == "output" && v.var_type == VarType::Real)
        {
            let vr = output.vr;
            cases.push(Case {
                standard: Standard::Fmi2,
                class: "value reference",
                model: m,
                interface: Some(interface.short()),
                name: format!("fmi2SetReal(output {})", output.name),
                expect: Expect::error(&output.name),
                why: WHY_NOT_SETTABLE,
                probe: Box::new(move |l| {
                    on_instance(l, m, interface, State::Instantiated, |i| {
                        i.set_real(vr, 0.0)
                    })
                }),
            });
        }
        if d.provides_directional_derivative {
            let bad = unused(d);
            cases.push(Case {
                standard: Standard::Fmi2,
                class: "value reference",
                model: m,
                interface: Some(interface.short()),
                name: format!("fmi2GetDirectionalDerivative(unknown vr {bad})"),
                expect: Expect::error(&bad.to_string()),
                why: WHY_UNKNOWN,
                probe: Box::new(move |l| {
                    on_instance(l, m, interface, State::InitializationMode, |i| unsafe {
                        let known = i.description.real_vrs()[0];
                        (i.binary.get_directional_derivative)(
                            i.c, &bad, 1, &known, 1, &1.0, &mut 0.0,
                        )
                    })
                }),
            });
        }
    }
    cases
}
