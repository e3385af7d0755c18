//! The structural parameters (`core::structural`): fmi3EnterConfigurationMode and
//! fmi3ExitConfigurationMode, fmi3GetUInt64 and fmi3SetUInt64 (the structural
//! parameters are the only UInt64 variables). Configuration Mode is entered from
//! Instantiated only: every structural parameter is fixed, so Reconfiguration Mode
//! (from Event or Step Mode, for tunable ones) is refused with a log line, as is
//! Configuration Mode of an instance whose view has none (FMI 2.0 has no such call;
//! the scalar-only view keeps the default sizes).

use super::values::{read, write};
use super::{input_slice, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::variables::VariableType;
use crate::fmi3::mode::{Call, Mode};
use crate::fmi3::table::Source;
use crate::fmi3::types::*;

pub unsafe fn enter_configuration_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3EnterConfigurationMode",
            Call::EnterConfigurationMode,
            |inst| {
                let structural = (inst.extra.table.variables.iter())
                    .any(|v| matches!(v.source, Source::Structural { .. }));
                if !structural {
                    return Err(format!(
                        "{} has no structural parameters in this view: its arrays keep \
                         their sizes",
                        M::INFO.model_name
                    ));
                }
                if inst.mode != Mode::Instantiated {
                    return Err(format!(
                        "Reconfiguration Mode (from {:?}) is for tunable structural \
                         parameters; those of {} are fixed: set them in Configuration Mode, \
                         after instantiation or fmi3Reset",
                        inst.mode,
                        M::INFO.model_name
                    ));
                }
                entry::enter(inst, Mode::ConfigurationMode)
            },
        )
    }
}

pub unsafe fn exit_configuration_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3ExitConfigurationMode",
            Call::ExitConfigurationMode,
            |inst| entry::enter(inst, Mode::Instantiated),
        )
    }
}

pub unsafe fn get_uint64<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *mut Fmi3UInt64,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetUInt64", Call::GetStructural, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            read(
                inst,
                "fmi3GetUInt64",
                vrs,
                VariableType::UInt64,
                (values, n_values),
                |i, v, o| i.get_uint64(v, o),
            )
        })
    }
}

pub unsafe fn set_uint64<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *const Fmi3UInt64,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetUInt64", Call::SetStructural, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            write(
                inst,
                "fmi3SetUInt64",
                vrs,
                VariableType::UInt64,
                (values, n_values),
                |i, v, x| i.set_uint64(v, x),
            )
        })
    }
}
