//! The bodies of the FMU-state functions, alike in FMI 2.0 and FMI 3.0 (Get, Set,
//! Free, SerializedSize, Serialize, Deserialize): each front-end runs them inside its
//! `with_instance`. Messages spell the handle as the standard does
//! ([`Frontend::FMU_STATE`]).

use super::fmu_states;
use super::frontend::{FmuInstance, Frontend, StatusCode};
use super::model::Model;
use super::serialize::{deserialize, serialize};
use super::structural::at_default_sizes;
use crate::ffi::{input_slice, output_ref, output_slice};
use std::ffi::c_void;

type Result<F> = std::result::Result<<F as Frontend>::Status, String>;

fn noun<F: Frontend>() -> &'static str {
    F::FMU_STATE
}

/// GetFMUState: a new state in `*state`, or the state already there overwritten.
///
/// # Safety
/// `state` must be null or valid; a non-null `*state` must not be borrowed.
pub unsafe fn get<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    state: *mut *mut c_void,
) -> Result<F> {
    let owner = inst.handle;
    let slot = unsafe { output_ref(state, noun::<F>()) }?;
    let snapshot = inst.snapshot();
    fmu_states::store(slot, snapshot, owner, noun::<F>())?;
    Ok(StatusCode::OK)
}

/// SetFMUState.
///
pub fn set<F: Frontend, M: Model>(inst: &mut FmuInstance<F, M>, state: *mut c_void) -> Result<F> {
    let s = fmu_states::snapshot::<M>(state, noun::<F>())?;
    inst.restore(&s);
    Ok(StatusCode::OK)
}

/// FreeFMUState (the instance only names the model and standard).
///
/// # Safety
/// `state` must be null or valid; a non-null `*state` must not be borrowed.
pub unsafe fn free<F: Frontend, M: Model>(
    _inst: &mut FmuInstance<F, M>,
    state: *mut *mut c_void,
) -> Result<F> {
    let slot = unsafe { output_ref(state, noun::<F>()) }?;
    fmu_states::free::<M>(slot, noun::<F>())?;
    Ok(StatusCode::OK)
}

/// SerializedFMUStateSize.
///
/// # Safety
/// `size` must be null or valid.
pub unsafe fn serialized_size<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    state: *mut c_void,
    size: *mut usize,
) -> Result<F> {
    let s = fmu_states::snapshot::<M>(state, noun::<F>())?;
    at_default_sizes(&s.model)?;
    *unsafe { output_ref(size, "size") }? = serialize(inst.core.table(), &s).len();
    Ok(StatusCode::OK)
}

/// SerializeFMUState into `bytes` of the length SerializedFMUStateSize gave.
///
/// # Safety
/// `bytes` must be null or valid for `size` bytes.
pub unsafe fn serialize_into<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> Result<F> {
    let s = fmu_states::snapshot::<M>(state, noun::<F>())?;
    at_default_sizes(&s.model)?;
    let data = serialize(inst.core.table(), &s);
    if size != data.len() {
        return Err(format!(
            "size {size} differs from fmi{}Serialized{}Size = {}",
            F::STANDARD.code(),
            noun::<F>(),
            data.len()
        ));
    }
    let out = unsafe { output_slice(bytes, size, "serializedState[]") }?;
    out.copy_from_slice(&data);
    Ok(StatusCode::OK)
}

/// DeserializeFMUState: the state in `bytes` checked and stored in `*state`.
///
/// # Safety
/// `bytes` must be null or valid for `size` bytes, `state` null or valid; a non-null
/// `*state` must not be borrowed.
pub unsafe fn deserialize_from<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Result<F> {
    let owner = inst.handle;
    let data = unsafe { input_slice(bytes, size, "serializedState[]") }?;
    let slot = unsafe { output_ref(state, noun::<F>()) }?;
    let s = deserialize::<M>(inst.core.table(), data)?;
    fmu_states::store(slot, s, owner, noun::<F>())?;
    Ok(StatusCode::OK)
}
