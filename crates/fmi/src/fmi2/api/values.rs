//! fmi2Get*/fmi2Set* for Real, Integer, Boolean and String variables.

use super::{input_slice, output_slice, with_instance};
use crate::core::model::Model;
use crate::core::variables::find;
use crate::fmi2::instance::Instance;
use crate::fmi2::mode::Call;
use crate::fmi2::types::*;

/// Brings the computed values up to date for reading `vrs`; Some(Discard) (logged)
/// when a calculated one is requested and the model cannot be evaluated here.
fn prepare<M: Model>(
    inst: &mut Instance<M>,
    function: &str,
    vrs: &[Fmi2ValueReference],
) -> Result<Option<Fmi2Status>, String> {
    let Some(reason) = inst.core.prepare_read(vrs)? else {
        return Ok(None);
    };
    inst.log.status(
        Fmi2Status::Discard,
        &format!("{function}: at t = {} s: {reason}", inst.core.time),
    );
    Ok(Some(Fmi2Status::Discard))
}

/// Applies `f` to each (value reference, value) pair; stops at the first error.
fn each<T>(
    vrs: &[Fmi2ValueReference],
    values: &mut [T],
    mut f: impl FnMut(u32, &mut T) -> Result<(), String>,
) -> Result<Fmi2Status, String> {
    for (vr, value) in vrs.iter().zip(values.iter_mut()) {
        f(*vr, value)?;
    }
    Ok(Fmi2Status::Ok)
}

pub unsafe fn get_real<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    value: *mut Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetReal", Call::GetValues, |inst| {
            let vrs = input_slice(vr, nvr, "vr[]")?;
            let out = output_slice(value, nvr, "value[]")?;
            if let Some(status) = prepare(inst, "fmi2GetReal", vrs)? {
                return Ok(status);
            }
            each(vrs, out, |r, v| {
                *v = inst.core.get_real(r)?;
                Ok(())
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
            let vrs = input_slice(vr, nvr, "vr[]")?;
            let out = output_slice(value, nvr, "value[]")?;
            if let Some(status) = prepare(inst, "fmi2GetInteger", vrs)? {
                return Ok(status);
            }
            each(vrs, out, |r, v| {
                *v = inst.core.get_integer(r)?;
                Ok(())
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
            let vrs = input_slice(vr, nvr, "vr[]")?;
            let out = output_slice(value, nvr, "value[]")?;
            if let Some(status) = prepare(inst, "fmi2GetBoolean", vrs)? {
                return Ok(status);
            }
            each(vrs, out, |r, v| {
                *v = if inst.core.get_boolean(r)? {
                    FMI2_TRUE
                } else {
                    FMI2_FALSE
                };
                Ok(())
            })
        })
    }
}

/// No model has String variables: any value reference is unknown or of another type.
fn no_string_variable<M: Model>(inst: &Instance<M>, vr: u32) -> String {
    match find(inst.core.table(), vr) {
        Some(v) => format!(
            "\"{}\" (value reference {vr}) is a {} variable, not String",
            v.name,
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
            let vrs = input_slice(vr, nvr, "vr[]")?;
            let values = input_slice(value, nvr, "value[]")?;
            for (&r, &v) in vrs.iter().zip(values) {
                inst.set_real(r, v)?;
            }
            Ok(Fmi2Status::Ok)
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
            let vrs = input_slice(vr, nvr, "vr[]")?;
            let values = input_slice(value, nvr, "value[]")?;
            for (&r, &v) in vrs.iter().zip(values) {
                inst.set_integer(r, v)?;
            }
            Ok(Fmi2Status::Ok)
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
            let vrs = input_slice(vr, nvr, "vr[]")?;
            let values = input_slice(value, nvr, "value[]")?;
            for (&r, &v) in vrs.iter().zip(values) {
                inst.set_boolean(r, v != FMI2_FALSE)?;
            }
            Ok(Fmi2Status::Ok)
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
