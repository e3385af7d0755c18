//! FMU state: get, set, free, serialize, deserialize (the bodies are the core's
//! [`fmu_state_calls`](crate::core::fmu_state_calls), shared with FMI 3.0).

use super::with_instance;
use crate::core::fmu_state_calls as calls;
use crate::core::model::Model;
use crate::fmi2::mode::Call;
use crate::fmi2::types::*;

pub unsafe fn get_fmu_state<M: Model>(c: Fmi2Component, state: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetFMUstate", Call::FmuState, |inst| {
            calls::get(inst, state)
        })
    }
}

pub unsafe fn set_fmu_state<M: Model>(c: Fmi2Component, state: Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetFMUstate", Call::FmuState, |inst| {
            calls::set(inst, state)
        })
    }
}

pub unsafe fn free_fmu_state<M: Model>(c: Fmi2Component, state: *mut Fmi2FmuState) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2FreeFMUstate", Call::FmuState, |inst| {
            calls::free(inst, state)
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
            calls::serialized_size(inst, state, size)
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
            calls::serialize_into(inst, state, bytes as *mut u8, size)
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
            calls::deserialize_from(inst, bytes as *const u8, size, state)
        })
    }
}
