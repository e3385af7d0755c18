//! FMU state: get, set, free, serialize, deserialize.

use super::{input_slice, output_ref, output_slice, with_instance};
use crate::core::handles::{self, HandleKind};
use crate::core::instance::Snapshot;
use crate::core::model::Model;
use crate::core::serialize::{deserialize, serialize};
use crate::fmi2::mode::Call;
use crate::fmi2::types::*;

/// Checks that `state` is a live FMU state of this FMU (looked up, not dereferenced).
fn check_state<M: Model>(state: Fmi2FmuState) -> Result<(), String> {
    if state.is_null() {
        return Err("FMUstate is a null pointer".to_string());
    }
    if !handles::is_live::<M>(state as usize, HandleKind::State) {
        return Err(format!(
            "FMUstate {state:p} is not a live FMU state of {}: never issued, already \
             freed, or another FMU's",
            M::info().model_name
        ));
    }
    Ok(())
}

/// The snapshot behind an FMU state pointer.
unsafe fn snapshot<'a, M: Model>(state: Fmi2FmuState) -> Result<&'a Snapshot<M>, String> {
    check_state::<M>(state)?;
    // SAFETY: registered as a live state of M, created by `store` below.
    Ok(unsafe { &*(state as *const Snapshot<M>) })
}

/// Stores `s` in `*slot`, reusing the state already there (the standard lets the
/// host pass a previously obtained state to be overwritten). A new state belongs to
/// the instance `owner` and is freed with it at the latest.
unsafe fn store<M: Model>(
    slot: &mut Fmi2FmuState,
    s: Snapshot<M>,
    owner: Fmi2Component,
) -> Result<(), String> {
    if slot.is_null() {
        let state = Box::into_raw(Box::new(s)) as Fmi2FmuState;
        handles::register::<M>(state as usize, HandleKind::State, owner as usize);
        *slot = state;
    } else {
        check_state::<M>(*slot)?;
        // SAFETY: registered as a live state of M.
        unsafe { *(*slot as *mut Snapshot<M>) = s };
    }
    Ok(())
}

pub unsafe fn get_fmu_state<M: Model>(c: Fmi2Component, state: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetFMUstate", Call::FmuState, |inst| {
            let slot = output_ref(state, "FMUstate")?;
            store(slot, inst.snapshot(), c)?;
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn set_fmu_state<M: Model>(c: Fmi2Component, state: Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetFMUstate", Call::FmuState, |inst| {
            let s = snapshot::<M>(state)?;
            inst.restore(s);
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn free_fmu_state<M: Model>(c: Fmi2Component, state: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2FreeFMUstate", Call::FmuState, |_| {
            let slot = output_ref(state, "FMUstate")?;
            if !slot.is_null() {
                check_state::<M>(*slot)?;
                handles::unregister::<M>(*slot as usize, HandleKind::State);
                // SAFETY: was a live state of M, now unregistered: freed exactly once.
                drop(Box::from_raw(*slot as *mut Snapshot<M>));
                *slot = std::ptr::null_mut();
            }
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn serialized_fmu_state_size<M: Model>(
    c: Fmi2Component,
    state: Fmi2FmuState,
    size: *mut usize,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SerializedFMUstateSize", Call::FmuState, |inst| {
            let s = snapshot::<M>(state)?;
            *output_ref(size, "size")? = serialize(inst.core.table(), s).len();
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn serialize_fmu_state<M: Model>(
    c: Fmi2Component,
    state: Fmi2FmuState,
    bytes: *mut Fmi2Byte,
    size: usize,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SerializeFMUstate", Call::FmuState, |inst| {
            let data = serialize(inst.core.table(), snapshot::<M>(state)?);
            if size != data.len() {
                return Err(format!(
                    "size {size} differs from fmi2SerializedFMUstateSize = {}",
                    data.len()
                ));
            }
            let out = output_slice(bytes as *mut u8, size, "serializedState[]")?;
            out.copy_from_slice(&data);
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn de_serialize_fmu_state<M: Model>(
    c: Fmi2Component,
    bytes: *const Fmi2Byte,
    size: usize,
    state: *mut Fmi2FmuState,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2DeSerializeFMUstate", Call::FmuState, |inst| {
            let data = input_slice(bytes as *const u8, size, "serializedState[]")?;
            let slot = output_ref(state, "FMUstate")?;
            store(slot, deserialize::<M>(inst.core.table(), data)?, c)?;
            Ok(Fmi2Status::Ok)
        })
    }
}
