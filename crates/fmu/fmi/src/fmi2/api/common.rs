//! Functions common to Model Exchange and Co-Simulation: creation, logging set-up,
//! initialization, termination.

use super::with_instance;
use crate::core::entry;
use crate::core::frontend::log_categories;
use crate::core::instance::{Index, IndexOf};
use crate::core::model::Model;
use crate::ffi::text;
use crate::fmi2::instance::Instance;
use crate::fmi2::logging::{Callback, Logger};
use crate::fmi2::mode::{Call, Fmi2, Interface, Mode};
use crate::fmi2::types::*;
use std::ffi::{CString, c_char, c_int};

pub fn get_types_platform() -> *const c_char {
    c"default".as_ptr()
}

pub fn get_version() -> *const c_char {
    c"2.0".as_ptr()
}

/// fmi2Instantiate for an in-process host: the instance gets an index of its own
/// ([`instantiate_with`] and [`Index::own`]).
///
/// # Safety
/// As [`instantiate_with`].
pub unsafe fn instantiate<M: Model>(
    instance_name: Fmi2String,
    fmu_type: c_int,
    guid: Fmi2String,
    resource_location: Fmi2String,
    functions: *const Fmi2CallbackFunctions,
    visible: Fmi2Boolean,
    logging_on: Fmi2Boolean,
) -> Fmi2Component {
    // SAFETY: by the contract above.
    unsafe {
        instantiate_with::<M>(
            Index::own,
            instance_name,
            fmu_type,
            guid,
            resource_location,
            functions,
            visible,
            logging_on,
        )
    }
}

/// fmi2Instantiate with the model's index taken from `index` (the exported symbol
/// passes [`Index::shared`]).
///
/// # Safety
/// The host passes NUL-terminated strings or null and a valid callback table or null.
#[allow(clippy::too_many_arguments)]
pub unsafe fn instantiate_with<M: Model>(
    index: IndexOf<M>,
    instance_name: Fmi2String,
    fmu_type: c_int,
    guid: Fmi2String,
    _resource_location: Fmi2String,
    functions: *const Fmi2CallbackFunctions,
    _visible: Fmi2Boolean,
    logging_on: Fmi2Boolean,
) -> Fmi2Component {
    // Without callbacks there is no way to report anything: refuse silently.
    if functions.is_null() {
        return std::ptr::null_mut();
    }
    // SAFETY: non-null, points to the host's callback table.
    let functions = unsafe { &*functions };
    let Some(callback) = functions.logger else {
        return std::ptr::null_mut();
    };
    // SAFETY: the host passes NUL-terminated strings or null (checked).
    let name = unsafe { text(instance_name, "instanceName") };
    let name_for_log = match &name {
        Ok(n) if !n.is_empty() => CString::new(*n).unwrap_or_default(),
        _ => c"?".to_owned(),
    };
    let logger = || {
        let sink = Callback {
            function: callback,
            environment: functions.component_environment,
            instance_name: name_for_log.clone(),
        };
        Logger::new(sink, log_categories::<Fmi2, M>(), logging_on != FMI2_FALSE)
    };
    entry::instantiate(
        "fmi2Instantiate",
        logger,
        |log| -> Result<Instance<M>, String> {
            if functions.allocate_memory.is_none() || functions.free_memory.is_none() {
                return Err(
                    "the callback functions allocateMemory and freeMemory must not be null"
                        .to_string(),
                );
            }
            if name?.is_empty() {
                return Err("instanceName is empty".to_string());
            }
            // SAFETY: as above.
            let given = unsafe { text(guid, "fmuGUID") }?;
            if given != M::INFO.guid {
                return Err(format!(
                    "fmuGUID {given} does not match this binary ({}, guid {})",
                    M::INFO.model_name,
                    M::INFO.guid
                ));
            }
            let interface = match fmu_type {
                FMI2_MODEL_EXCHANGE => Interface::ModelExchange,
                FMI2_CO_SIMULATION => Interface::CoSimulation,
                other => {
                    return Err(format!(
                        "fmuType {other} is neither fmi2ModelExchange (0) nor fmi2CoSimulation (1)"
                    ));
                }
            };
            Instance::<M>::new(interface, log, index()?)
        },
    )
}

/// Frees the instance and every FMU state it still owns. A handle that is not a live
/// instance of this FMU is ignored (fmi2FreeInstance returns nothing to report with).
pub unsafe fn free_instance<M: Model>(c: Fmi2Component) {
    unsafe { entry::free_instance::<Fmi2, M>(c) }
}

pub unsafe fn set_debug_logging<M: Model>(
    c: Fmi2Component,
    logging_on: Fmi2Boolean,
    n_categories: usize,
    categories: *const Fmi2String,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetDebugLogging", Call::SetDebugLogging, |inst| {
            entry::set_debug_logging(inst, logging_on != FMI2_FALSE, n_categories, categories)
        })
    }
}

pub unsafe fn setup_experiment<M: Model>(
    c: Fmi2Component,
    tolerance_defined: Fmi2Boolean,
    tolerance: Fmi2Real,
    start_time: Fmi2Real,
    stop_time_defined: Fmi2Boolean,
    stop_time: Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetupExperiment", Call::SetupExperiment, |inst| {
            let tolerance = (tolerance_defined != FMI2_FALSE).then_some(tolerance);
            let stop = (stop_time_defined != FMI2_FALSE).then_some(stop_time);
            entry::setup_experiment(&mut inst.core, tolerance, start_time, stop)?;
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn enter_initialization_mode<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2EnterInitializationMode",
            Call::EnterInitializationMode,
            |inst| entry::enter(inst, Mode::InitializationMode),
        )
    }
}

pub unsafe fn exit_initialization_mode<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2ExitInitializationMode",
            Call::ExitInitializationMode,
            entry::exit_initialization_mode,
        )
    }
}

pub unsafe fn terminate<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2Terminate", Call::Terminate, |inst| {
            entry::enter(inst, Mode::Terminated)
        })
    }
}

pub unsafe fn reset<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2Reset", Call::Reset, |inst| {
            inst.reset();
            Ok(Fmi2Status::Ok)
        })
    }
}
