//! fmi3Get*/fmi3Set* for the types the models use: Float64, Int32 and Boolean
//! (scalars and arrays; nValues counts the elements). Reading a calculated variable
//! where the model cannot be evaluated returns fmi3Discard with the model's reason.

use super::{input_slice, output_slice, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::structural::Sizes;
use crate::core::variables::VariableType;
use crate::ffi::check_array;
use crate::fmi3::instance::{Instance, Kept};
use crate::fmi3::mode::Call;
use crate::fmi3::table::Variable3;
use crate::fmi3::types::*;
use std::sync::Arc;

/// Reads the variables of `vrs` (of type `wanted`, `n_values` elements in all) into
/// `out` with `read`, after making the computed values current.
pub(super) fn read<M: Model, T: Default + Clone>(
    inst: &mut Instance<M>,
    function: &str,
    vrs: &[Fmi3ValueReference],
    wanted: VariableType,
    (values, n_values): (*mut T, usize),
    read: impl Fn(&mut Instance<M>, &Variable3, &mut [T]) -> Result<(), String>,
) -> Result<Fmi3Status, String> {
    check_array(values, n_values, "values[]")?;
    let table = Arc::clone(&inst.extra.table);
    // nValues is checked against the current sizes before a slice of that length
    // is formed over the host's buffer.
    let sizes = Sizes::of(inst.core.model(), M::STRUCTURAL);
    let variables = table.typed_all(vrs, wanted, n_values, &sizes)?;
    // SAFETY: the host's buffer holds nValues elements, which match the variables.
    let out = unsafe { output_slice(values, n_values, "values[]") }?;
    if let Some(reason) = inst.prepare_read(variables.clone())? {
        return Ok(entry::discard(inst, function, &reason));
    }
    let mut at = 0;
    for v in variables {
        let n = v.size_now(&sizes);
        read(inst, v, &mut out[at..at + n])?;
        at += n;
    }
    Ok(Fmi3Status::Ok)
}

/// Writes `values` to the variables of `vrs` (of type `wanted`) with `write`.
/// fmi3Warning, with a log line each, when `write` accepted a fixed parameter set
/// again to the values it holds (see `Instance::set`).
pub(super) fn write<M: Model, T>(
    inst: &mut Instance<M>,
    function: &str,
    vrs: &[Fmi3ValueReference],
    wanted: VariableType,
    (values, n_values): (*const T, usize),
    write: impl Fn(&mut Instance<M>, &Variable3, &[T]) -> Result<Kept, String>,
) -> Result<Fmi3Status, String> {
    check_array(values, n_values, "values[]")?;
    let table = Arc::clone(&inst.extra.table);
    // A write of these types changes no size (the sizes are UInt64 parameters).
    let sizes = Sizes::of(inst.core.model(), M::STRUCTURAL);
    let variables = table.typed_all(vrs, wanted, n_values, &sizes)?;
    // SAFETY: as in `read`, the length was checked against the variables first.
    let values = unsafe { input_slice(values, n_values, "values[]") }?;
    let mut at = 0;
    let mut status = Fmi3Status::Ok;
    for v in variables {
        let n = v.size_now(&sizes);
        if let Some(line) = write(inst, v, &values[at..at + n])? {
            status = Fmi3Status::Warning;
            inst.log.status(status, &format!("{function}: {line}"));
        }
        at += n;
    }
    Ok(status)
}

pub unsafe fn get_float64<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *mut Fmi3Float64,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetFloat64", Call::GetValues, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            read(
                inst,
                "fmi3GetFloat64",
                vrs,
                VariableType::Real,
                (values, n_values),
                |i, v, o| i.get_float64(v, o),
            )
        })
    }
}

pub unsafe fn get_int32<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *mut Fmi3Int32,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetInt32", Call::GetValues, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            read(
                inst,
                "fmi3GetInt32",
                vrs,
                VariableType::Integer,
                (values, n_values),
                |i, v, o| i.get_int32(v, o),
            )
        })
    }
}

pub unsafe fn get_boolean<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *mut Fmi3Boolean,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetBoolean", Call::GetValues, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            read(
                inst,
                "fmi3GetBoolean",
                vrs,
                VariableType::Boolean,
                (values, n_values),
                |i, v, o| {
                    let mut flags = vec![false; o.len()];
                    i.get_boolean(v, &mut flags)?;
                    for (byte, flag) in o.iter_mut().zip(flags) {
                        *byte = fmi3_bool(flag);
                    }
                    Ok(())
                },
            )
        })
    }
}

pub unsafe fn set_float64<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *const Fmi3Float64,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetFloat64", Call::SetFloat64, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            write(
                inst,
                "fmi3SetFloat64",
                vrs,
                VariableType::Real,
                (values, n_values),
                |i, v, x| i.set_float64(v, x),
            )
        })
    }
}

pub unsafe fn set_int32<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *const Fmi3Int32,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetInt32", Call::SetDiscrete, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            write(
                inst,
                "fmi3SetInt32",
                vrs,
                VariableType::Integer,
                (values, n_values),
                |i, v, x| i.set_int32(v, x),
            )
        })
    }
}

pub unsafe fn set_boolean<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *const Fmi3Boolean,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetBoolean", Call::SetDiscrete, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            write(
                inst,
                "fmi3SetBoolean",
                vrs,
                VariableType::Boolean,
                (values, n_values),
                |i, v, x| {
                    let flags: Vec<bool> = x.iter().map(|&b| b != FMI3_FALSE).collect();
                    i.set_boolean(v, &flags)
                },
            )
        })
    }
}
