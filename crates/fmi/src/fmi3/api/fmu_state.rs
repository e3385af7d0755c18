//! FMU state: get, set, free, serialize, deserialize. Serialized states use the core's
//! checked format; the standard field records that FMI 3.0 wrote them.

use super::{input_slice, output_ref, output_slice, with_instance};
use crate::core::fmu_states;
use crate::core::frontend::FrontendInstance;
use crate::core::model::Model;
use crate::core::serialize::{deserialize, serialize};
use crate::fmi3::mode::Call;
use crate::fmi3::types::*;

/// The standard's name of an FMU state in messages.
const NOUN: &str = "FMUState";

pub unsafe fn get_fmu_state<M: Model>(c: Fmi3Instance, state: *mut Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetFMUState", Call::FmuState, |inst| {
            let slot = output_ref(state, NOUN)?;
            fmu_states::store(slot, inst.snapshot(), c, NOUN)?;
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn set_fmu_state<M: Model>(c: Fmi3Instance, state: Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetFMUState", Call::FmuState, |inst| {
            let s = fmu_states::snapshot::<M>(state, NOUN)?;
            inst.restore(s);
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn free_fmu_state<M: Model>(c: Fmi3Instance, state: *mut Fmi3FmuState) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3FreeFMUState", Call::FmuState, |_| {
            let slot = output_ref(state, NOUN)?;
            fmu_states::free::<M>(slot, NOUN)?;
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
            let s = fmu_states::snapshot::<M>(state, NOUN)?;
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
            let data = serialize(inst.core.table(), fmu_states::snapshot::<M>(state, NOUN)?);
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
            let slot = output_ref(state, NOUN)?;
            fmu_states::store(slot, deserialize::<M>(inst.core.table(), data)?, c, NOUN)?;
            Ok(Fmi3Status::Ok)
        })
    }
}
