//! FMU state: get, set, free, serialize, deserialize. Serialized states use the core's
//! checked format; the standard field records that FMI 3.0 wrote them.

use super::{input_slice, output_ref, output_slice, with_instance};
use crate::core::handles::{self, HandleKind};
use crate::core::instance::Snapshot;
use crate::core::model::Model;
use crate::core::serialize::{deserialize, serialize};
use crate::fmi3::mode::Call;
use crate::fmi3::types::*;

/// Checks that `state` is a live FMU state of this model (looked up, not
/// dereferenced). States are the core's snapshots, shared with FMI 2.0.
fn check_state<M: Model>(state: Fmi3FmuState) -> Result<(), String> {
    if state.is_null() {
        return Err("FMUState is a null pointer".to_string());
    }
    if !handles::is_live::<M>(state as usize, HandleKind::State) {
        return Err(format!(
            "FMUState {state:p} is not a live FMU state of {}: never issued, already \
             freed, or another FMU's",
            M::info().model_name
        ));
    }
    Ok(())
}

/// The snapshot behind an FMU state pointer.
unsafe fn snapshot<'a, M: Model>(state: Fmi3FmuState) -> Result<&'a Snapshot<M>, String> {
    check_state::<M>(state)?;
    // SAFETY: registered as a live state of M, created by `store` below.
    Ok(unsafe { &*(state as *const Snapshot<M>) })
}

/// Stores `s` in `*slot`, reusing the state already there (the standard lets the
/// host pass a previously obtained state to be overwritten). A new state belongs to
/// the instance `owner` and is freed with it at the latest.
unsafe fn store<M: Model>(
    slot: &mut Fmi3FmuState,
    s: Snapshot<M>,
    owner: Fmi3Instance,
) -> Result<(), String> {
    if slot.is_null() {
        let state = Box::into_raw(Box::new(s)) as Fmi3FmuState;
        handles::register::<M>(state as usize, HandleKind::State, owner as usize);
        *slot = state;
    } else {
        check_state::<M>(*slot)?;
        // SAFETY: registered as a live state of M.
        unsafe { *(*slot as *mut Snapshot<M>) = s };
    }
    Ok(())
}

pub unsafe fn get_fmu_state<M: Model>(c: Fmi3Instance, state: *mut Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetFMUState", Call::FmuState, |inst| {
            let slot = output_ref(state, "FMUState")?;
            store(slot, inst.snapshot(), c)?;
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn set_fmu_state<M: Model>(c: Fmi3Instance, state: Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetFMUState", Call::FmuState, |inst| {
            let s = snapshot::<M>(state)?;
            inst.restore(s);
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn free_fmu_state<M: Model>(c: Fmi3Instance, state: *mut Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3FreeFMUState", Call::FmuState, |_| {
            let slot = output_ref(state, "FMUState")?;
            if !slot.is_null() {
                check_state::<M>(*slot)?;
                handles::unregister::<M>(*slot as usize, HandleKind::State);
                // SAFETY: was a live state of M, now unregistered: freed exactly once.
                drop(Box::from_raw(*slot as *mut Snapshot<M>));
                *slot = std::ptr::null_mut();
            }
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn serialized_fmu_state_size<M: Model>(
    c: Fmi3Instance,
    state: Fmi3FmuState,
    size: *mut usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SerializedFMUStateSize", Call::FmuState, |inst| {
            let s = snapshot::<M>(state)?;
            *output_ref(size, "size")? = serialize(inst.core.table(), s).len();
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn serialize_fmu_state<M: Model>(
    c: Fmi3Instance,
    state: Fmi3FmuState,
    bytes: *mut Fmi3Byte,
    size: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SerializeFMUState", Call::FmuState, |inst| {
            let data = serialize(inst.core.table(), snapshot::<M>(state)?);
            if size != data.len() {
                return Err(format!(
                    "size {size} differs from fmi3SerializedFMUStateSize = {}",
                    data.len()
                ));
            }
            let out = output_slice(bytes, size, "serializedState[]")?;
            out.copy_from_slice(&data);
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn deserialize_fmu_state<M: Model>(
    c: Fmi3Instance,
    bytes: *const Fmi3Byte,
    size: usize,
    state: *mut Fmi3FmuState,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3DeserializeFMUState", Call::FmuState, |inst| {
            let data = input_slice(bytes, size, "serializedState[]")?;
            let slot = output_ref(state, "FMUState")?;
            store(slot, deserialize::<M>(inst.core.table(), data)?, c)?;
            Ok(Fmi3Status::Ok)
        })
    }
}
