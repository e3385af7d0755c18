//! FMU state: get, set, free, serialize, deserialize (the bodies are the core's
//! [`fmu_state_calls`](crate::core::fmu_state_calls), shared with FMI 2.0). Serialized
//! states use the core's checked format; the standard field records that FMI 3.0
//! wrote them.

use super::with_instance;
use crate::core::fmu_state_calls as calls;
use crate::core::model::Model;
use crate::fmi3::mode::Call;
use crate::fmi3::types::*;

pub unsafe fn get_fmu_state<M: Model>(c: Fmi3Instance, state: *mut Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetFMUState", Call::FmuState, |inst| {
            calls::get(inst, state)
        })
    }
}

pub unsafe fn set_fmu_state<M: Model>(c: Fmi3Instance, state: Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetFMUState", Call::FmuState, |inst| {
            calls::set(inst, state)
        })
    }
}

pub unsafe fn free_fmu_state<M: Model>(c: Fmi3Instance, state: *mut Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3FreeFMUState", Call::FmuState, |inst| {
            calls::free(inst, state)
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
            calls::serialized_size(inst, state, size)
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
            calls::serialize_into(inst, state, bytes, size)
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
            calls::deserialize_from(inst, bytes, size, state)
        })
    }
}
