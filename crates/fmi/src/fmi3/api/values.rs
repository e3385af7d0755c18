//! fmi3Get*/fmi3Set* for the types the models use: Float64, Int32 and Boolean
//! (scalars and arrays; nValues counts the elements).

use super::{input_slice, output_slice, with_instance};
use crate::core::model::Model;
use crate::core::variables::VariableType;
use crate::fmi3::mode::Call;
use crate::fmi3::types::*;

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
            let out = output_slice(values, n_values, "values[]")?;
            let mut at = 0;
            for v in inst.variables(vrs, VariableType::Real, n_values)? {
                inst.get_float64(v, &mut out[at..at + v.size()])?;
                at += v.size();
            }
            Ok(Fmi3Status::Ok)
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
            let out = output_slice(values, n_values, "values[]")?;
            let mut at = 0;
            for v in inst.variables(vrs, VariableType::Integer, n_values)? {
                inst.get_int32(v, &mut out[at..at + v.size()])?;
                at += v.size();
            }
            Ok(Fmi3Status::Ok)
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
            let out = output_slice(values, n_values, "values[]")?;
            let mut at = 0;
            for v in inst.variables(vrs, VariableType::Boolean, n_values)? {
                let mut flags = vec![false; v.size()];
                inst.get_boolean(v, &mut flags)?;
                for (o, f) in out[at..at + v.size()].iter_mut().zip(flags) {
                    *o = fmi3_bool(f);
                }
                at += v.size();
            }
            Ok(Fmi3Status::Ok)
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
            let given = input_slice(values, n_values, "values[]")?;
            let mut at = 0;
            for v in inst.variables(vrs, VariableType::Real, n_values)? {
                inst.set_float64(v, &given[at..at + v.size()])?;
                at += v.size();
            }
            Ok(Fmi3Status::Ok)
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
            let given = input_slice(values, n_values, "values[]")?;
            let mut at = 0;
            for v in inst.variables(vrs, VariableType::Integer, n_values)? {
                inst.set_int32(v, &given[at..at + v.size()])?;
                at += v.size();
            }
            Ok(Fmi3Status::Ok)
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
            let given = input_slice(values, n_values, "values[]")?;
            let mut at = 0;
            for v in inst.variables(vrs, VariableType::Boolean, n_values)? {
                let flags: Vec<bool> = given[at..at + v.size()]
                    .iter()
                    .map(|&b| b != FMI3_FALSE)
                    .collect();
                inst.set_boolean(v, &flags)?;
                at += v.size();
            }
            Ok(Fmi3Status::Ok)
        })
    }
}
