//! The FMI 2.0 rows of the value-reference class (`matrix::references`): the
//! typed getters and setters, and an unknown reference given to
//! fmi2GetDirectionalDerivative.

use crate::description::{Description, VarType};
use crate::host::{Interface, State};
use crate::matrix::references::unused;
use crate::matrix::seam::Access;
use crate::matrix::{Case, Expect, on_instance};

const WHY_UNKNOWN: &str =
    "value reference not in the modelDescription (FMI 2.0 2.1.7): fmi2Error naming it";

pub fn getters() -> Vec<Access<Interface>> {
    vec![
        ("fmi2GetReal", Some(VarType::Real), |i, vr, _| {
            i.get_reals(&[vr]).0
        }),
        (
            "fmi2GetInteger",
            Some(VarType::Integer),
            |i, vr, _| unsafe { (i.binary.get_integer)(i.c, &vr, 1, &mut 0) },
        ),
        (
            "fmi2GetBoolean",
            Some(VarType::Boolean),
            |i, vr, _| unsafe { (i.binary.get_boolean)(i.c, &vr, 1, &mut 0) },
        ),
        ("fmi2GetString", None, |i, vr, _| unsafe {
            (i.binary.get_string)(i.c, &vr, 1, &mut std::ptr::null())
        }),
    ]
}

pub fn setters() -> Vec<Access<Interface>> {
    vec![
        ("fmi2SetReal", Some(VarType::Real), |i, vr, _| {
            i.set_real(vr, 0.0)
        }),
        (
            "fmi2SetInteger",
            Some(VarType::Integer),
            |i, vr, _| unsafe { (i.binary.set_integer)(i.c, &vr, 1, &1) },
        ),
        (
            "fmi2SetBoolean",
            Some(VarType::Boolean),
            |i, vr, _| unsafe { (i.binary.set_boolean)(i.c, &vr, 1, &0) },
        ),
        ("fmi2SetString", None, |i, vr, _| unsafe {
            (i.binary.set_string)(i.c, &vr, 1, &c"x".as_ptr())
        }),
    ]
}

/// fmi2GetDirectionalDerivative with an unknown reference.
pub fn extras(d: &Description, m: usize, interface: Interface) -> Vec<Case> {
    let mut cases = Vec::new();
    if d.provides_directional_derivative {
        let bad = unused(d);
        cases.push(Case::new(
            ("value reference", m, interface),
            format!("fmi2GetDirectionalDerivative(unknown vr {bad})"),
            (Expect::error(&bad.to_string()), WHY_UNKNOWN),
            move |l| {
                on_instance(l, m, interface, State::InitializationMode, |i| unsafe {
                    let known = i.description.real_vrs()[0];
                    (i.binary.get_directional_derivative)(i.c, &bad, 1, &known, 1, &1.0, &mut 0.0)
                })
            },
        ));
    }
    cases
}
