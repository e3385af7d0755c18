//! The bodies of the FMU-state functions, alike in FMI 2.0 and FMI 3.0 (Get, Set,
//! Free, SerializedSize, Serialize, Deserialize): each front-end runs them inside its
//! `with_instance`. Messages spell the handle as the standard does
//! ([`Frontend::FMU_STATE`]).

use super::fmu_states;
use super::frontend::{Frontend, FrontendInstance, StatusCode, StatusOf};
use super::serialize::{deserialize, serialize};
use crate::ffi::{input_slice, output_ref, output_slice};
use std::ffi::c_void;

type Result<I> = std::result::Result<StatusOf<<I as FrontendInstance>::Frontend>, String>;

fn noun<I: FrontendInstance>() -> &'static str {
    I::Frontend::FMU_STATE
}

/// GetFMUState: a new state in `*state`, or the state already there overwritten.
///
/// # Safety
/// `state` must be null or valid; a non-null `*state` must not be borrowed.
pub unsafe fn get<I: FrontendInstance>(inst: &mut I, state: *mut *mut c_void) -> Result<I> {
    let owner = inst as *mut I as *mut c_void;
    let slot = unsafe { output_ref(state, noun::<I>()) }?;
    let snapshot = inst.snapshot();
    fmu_states::store(slot, snapshot, owner, noun::<I>())?;
    Ok(StatusCode::OK)
}

/// SetFMUState.
///
pub fn set<I: FrontendInstance>(inst: &mut I, state: *mut c_void) -> Result<I> {
    let s = fmu_states::snapshot::<I::Model>(state, noun::<I>())?;
    inst.restore(&s);
    Ok(StatusCode::OK)
}

/// FreeFMUState (the instance only names the model and standard).
///
/// # Safety
/// `state` must be null or valid; a non-null `*state` must not be borrowed.
pub unsafe fn free<I: FrontendInstance>(_inst: &mut I, state: *mut *mut c_void) -> Result<I> {
    let slot = unsafe { output_ref(state, noun::<I>()) }?;
    fmu_states::free::<I::Model>(slot, noun::<I>())?;
    Ok(StatusCode::OK)
}

/// SerializedFMUStateSize.
///
/// # Safety
/// `size` must be null or valid.
pub unsafe fn serialized_size<I: FrontendInstance>(
    inst: &mut I,
    state: *mut c_void,
    size: *mut usize,
) -> Result<I> {
    let s = fmu_states::snapshot::<I::Model>(state, noun::<I>())?;
    *unsafe { output_ref(size, "size") }? = serialize(inst.parts().core.table(), &s).len();
    Ok(StatusCode::OK)
}

/// SerializeFMUState into `bytes` of the length SerializedFMUStateSize gave.
///
/// # Safety
/// `bytes` must be null or valid for `size` bytes.
pub unsafe fn serialize_into<I: FrontendInstance>(
    inst: &mut I,
    state: *mut c_void,
    bytes: *mut u8,
    size: usize,
) -> Result<I> {
    let s = fmu_states::snapshot::<I::Model>(state, noun::<I>())?;
    let data = serialize(inst.parts().core.table(), &s);
    if size != data.len() {
        return Err(format!(
            "size {size} differs from fmi{}Serialized{}Size = {}",
            I::Frontend::STANDARD.code(),
            noun::<I>(),
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
pub unsafe fn deserialize_from<I: FrontendInstance>(
    inst: &mut I,
    bytes: *const u8,
    size: usize,
    state: *mut *mut c_void,
) -> Result<I> {
    let owner = inst as *mut I as *mut c_void;
    let data = unsafe { input_slice(bytes, size, "serializedState[]") }?;
    let slot = unsafe { output_ref(state, noun::<I>()) }?;
    let s = deserialize::<I::Model>(inst.parts().core.table(), data)?;
    fmu_states::store(slot, s, owner, noun::<I>())?;
    Ok(StatusCode::OK)
}
