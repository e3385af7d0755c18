//! fmi2Get*/fmi2Set* for Real, Integer, Boolean and String variables.

use super::{input_slice, output_slice, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::variables::find;
use crate::fmi2::instance::Instance;
use crate::fmi2::mode::Call;
use crate::fmi2::types::*;

/// Reads the variables `vr[0..nvr]` into `value` with `get`, after making the
/// computed values current; Discard (logged) when a calculated one is requested and
/// the model cannot be evaluated here.
unsafe fn read<M: Model, T>(
    inst: &mut Instance<M>,
    function: &str,
    (vr, nvr): (*const Fmi2ValueReference, usize),
    value: *mut T,
    get: impl Fn(&mut Instance<M>, u32) -> Result<T, String>,
) -> Result<Fmi2Status, String> {
    let vrs = unsafe { input_slice(vr, nvr, "vr[]") }?;
    let out = unsafe { output_slice(value, nvr, "value[]") }?;
    if let Some(reason) = inst.core.prepare_read(vrs.iter().copied())? {
        return Ok(entry::discard(inst, function, &reason));
    }
    for (&r, v) in vrs.iter().zip(out) {
        *v = get(inst, r)?;
    }
    Ok(Fmi2Status::Ok)
}

/// Writes `value[0..nvr]` to the variables `vr[0..nvr]` with `set`; stops at the
/// first error. fmi2Warning, with a log line each, when `set` accepted a fixed
/// parameter set again to the value it holds (see `Instance::set`).
unsafe fn write<M: Model, T: Copy>(
    inst: &mut Instance<M>,
    function: &str,
    (vr, nvr): (*const Fmi2ValueReference, usize),
    value: *const T,
    set: impl Fn(&mut Instance<M>, u32, T) -> Result<Option<String>, String>,
) -> Result<Fmi2Status, String> {
    let vrs = unsafe { input_slice(vr, nvr, "vr[]") }?;
    let values = unsafe { input_slice(value, nvr, "value[]") }?;
    let mut status = Fmi2Status::Ok;
    for (&r, &v) in vrs.iter().zip(values) {
        if let Some(line) = set(inst, r, v)? {
            status = Fmi2Status::Warning;
            inst.log.status(status, &format!("{function}: {line}"));
        }
    }
    Ok(status)
}

pub unsafe fn get_real<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetReal", Call::GetValues, |inst| {
            read(inst, "fmi2GetReal", (vr, nvr), value, |i, r| {
                i.core.get_real(r)
            })
        })
    }
}

pub unsafe fn get_integer<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut Fmi2Integer,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetInteger", Call::GetValues, |inst| {
            read(inst, "fmi2GetInteger", (vr, nvr), value, |i, r| {
                i.core.get_integer(r)
            })
        })
    }
}

pub unsafe fn get_boolean<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut Fmi2Boolean,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetBoolean", Call::GetValues, |inst| {
            read(inst, "fmi2GetBoolean", (vr, nvr), value, |i, r| {
                Ok(if i.core.get_boolean(r)? {
                    FMI2_TRUE
                } else {
                    FMI2_FALSE
                })
            })
        })
    }
}

/// No model has String variables: any value reference is unknown or of another type.
fn no_string_variable<M: Model>(inst: &Instance<M>, vr: u32) -> String {
    match find(inst.core.table(), vr) {
        Some(v) => format!(
            "\"{}\" (value reference {vr}) is a {} variable, not String",
            v.name(),
            v.variable_type().as_str()
        ),
        None => format!("unknown value reference {vr}"),
    }
}

pub unsafe fn get_string<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut Fmi2String,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2GetString",
            Call::GetValues,
            |inst: &mut Instance<M>| {
                let vrs = input_slice(vr, nvr, "vr[]")?;
                output_slice(value, nvr, "value[]")?;
                match vrs.first() {
                    Some(&r) => Err(no_string_variable(inst, r)),
                    None => Ok(Fmi2Status::Ok),
                }
            },
        )
    }
}

pub unsafe fn set_real<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetReal", Call::SetReal, |inst| {
            write(inst, "fmi2SetReal", (vr, nvr), value, |i, r, v| {
                i.set_real(r, v)
            })
        })
    }
}

pub unsafe fn set_integer<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const Fmi2Integer,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetInteger", Call::SetDiscrete, |inst| {
            write(inst, "fmi2SetInteger", (vr, nvr), value, |i, r, v| {
                i.set_integer(r, v)
            })
        })
    }
}

pub unsafe fn set_boolean<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const Fmi2Boolean,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetBoolean", Call::SetDiscrete, |inst| {
            write(inst, "fmi2SetBoolean", (vr, nvr), value, |i, r, v| {
                i.set_boolean(r, v != FMI2_FALSE)
            })
        })
    }
}

pub unsafe fn set_string<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *const Fmi2String,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2SetString",
            Call::SetDiscrete,
            |inst: &mut Instance<M>| {
                let vrs = input_slice(vr, nvr, "vr[]")?;
                input_slice(value, nvr, "value[]")?;
                match vrs.first() {
                    Some(&r) => Err(no_string_variable(inst, r)),
                    None => Ok(Fmi2Status::Ok),
                }
            },
        )
    }
}
