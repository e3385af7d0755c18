//! FMU state: get, set, free, serialize, deserialize.

use super::{input_slice, output_ref, output_slice, with_instance};
use crate::core::fmu_states;
use crate::core::frontend::FrontendInstance;
use crate::core::model::Model;
use crate::core::serialize::{deserialize, serialize};
use crate::fmi2::mode::Call;
use crate::fmi2::types::*;

/// The standard's name of an FMU state in messages.
const NOUN: &str = "FMUstate";

pub unsafe fn get_fmu_state<M: Model>(c: Fmi2Component, state: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetFMUstate", Call::FmuState, |inst| {
            let slot = output_ref(state, NOUN)?;
            fmu_states::store(slot, inst.snapshot(), c, NOUN)?;
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn set_fmu_state<M: Model>(c: Fmi2Component, state: Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetFMUstate", Call::FmuState, |inst| {
            let s = fmu_states::snapshot::<M>(state, NOUN)?;
            inst.restore(s);
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn free_fmu_state<M: Model>(c: Fmi2Component, state: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2FreeFMUstate", Call::FmuState, |_| {
            let slot = output_ref(state, NOUN)?;
            fmu_states::free::<M>(slot, NOUN)?;
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
            let s = fmu_states::snapshot::<M>(state, NOUN)?;
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
            let data = serialize(inst.core.table(), fmu_states::snapshot::<M>(state, NOUN)?);
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
            let slot = output_ref(state, NOUN)?;
            fmu_states::store(slot, deserialize::<M>(inst.core.table(), data)?, c, NOUN)?;
            Ok(Fmi2Status::Ok)
        })
    }
}
