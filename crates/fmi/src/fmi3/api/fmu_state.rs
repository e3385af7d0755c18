//! FMU state: get, set, free, serialize, deserialize. Serialized states use the core's
//! checked format; the standard field records that FMI 3.0 wrote them.

use super::{input_slice, output_ref, output_slice, with_instance};
use crate::core::instance::Snapshot;
use crate::core::model::Model;
use crate::core::serialize::{deserialize, serialize};
use crate::fmi3::mode::Call;
use crate::fmi3::types::*;

/// The snapshot behind an FMU state pointer.
unsafe fn snapshot<'a, M: Model>(state: Fmi3FmuState) -> Result<&'a Snapshot<M>, String> {
    if state.is_null() {
        return Err("FMUState is a null pointer".to_string());
    }
    // SAFETY: non-null FMU states were created by get_fmu_state/deserialize for M.
    Ok(unsafe { &*(state as *const Snapshot<M>) })
}

/// Stores `s` in `*slot`, reusing the state already there (the standard lets the
/// host pass a previously obtained state to be overwritten).
unsafe fn store<M: Model>(slot: &mut Fmi3FmuState, s: Snapshot<M>) {
    if slot.is_null() {
        *slot = Box::into_raw(Box::new(s)) as Fmi3FmuState;
    } else {
        // SAFETY: a non-null state was created by this module for M.
        unsafe { *(*slot as *mut Snapshot<M>) = s };
    }
}

pub unsafe fn get_fmu_state<M: Model>(c: Fmi3Instance, state: *mut Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetFMUState", Call::FmuState, |inst| {
            let slot = output_ref(state, "FMUState")?;
            store(slot, inst.snapshot());
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
                // SAFETY: created by this module for M, freed once, then nulled.
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
            store(slot, deserialize::<M>(inst.core.table(), data)?);
            Ok(Fmi3Status::Ok)
        })
    }
}
