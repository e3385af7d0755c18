//! Functions common to Model Exchange and Co-Simulation: creation, logging set-up,
//! initialization, termination.

use super::{check_finite, input_slice, panic_message, with_instance};
use crate::core::handles::{self, HandleKind};
use crate::core::instance::Snapshot;
use crate::core::model::Model;
use crate::fmi2::instance::{Instance, log_categories};
use crate::fmi2::logging::Logger;
use crate::fmi2::mode::{Call, Interface, Mode};
use crate::fmi2::types::*;
use std::ffi::{CStr, CString, c_char, c_int};
use std::panic::{AssertUnwindSafe, catch_unwind};

pub fn get_types_platform() -> *const c_char {
    c"default".as_ptr()
}

pub fn get_version() -> *const c_char {
    c"2.0".as_ptr()
}

/// A C string argument as UTF-8 text.
unsafe fn text<'a>(ptr: Fmi2String, what: &str) -> Result<&'a str, String> {
    if ptr.is_null() {
        return Err(format!("{what} is a null pointer"));
    }
    // SAFETY: non-null C strings from the host are NUL-terminated.
    let s = unsafe { CStr::from_ptr(ptr) };
    s.to_str().map_err(|_| format!("{what} is not UTF-8"))
}

pub unsafe fn instantiate<M: Model>(
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
    let created = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: the host passes NUL-terminated strings or null (checked).
        let name = unsafe { text(instance_name, "instanceName") };
        let name_for_log = match &name {
            Ok(n) if !n.is_empty() => CString::new(*n).unwrap_or_default(),
            _ => c"?".to_owned(),
        };
        let make_logger = || {
            Logger::new(
                callback,
                functions.component_environment,
                name_for_log.clone(),
                log_categories::<M>(),
                logging_on != FMI2_FALSE,
            )
        };
        let created = (|| -> Result<Instance<M>, String> {
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
            if given != M::info().guid {
                return Err(format!(
                    "fmuGUID {given} does not match this binary ({}, guid {})",
                    M::info().model_name,
                    M::info().guid
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
            Instance::<M>::new(interface, make_logger())
        })();
        match created {
            Ok(instance) => {
                instance.log.debug(
                    "logEvents",
                    &format!(
                        "instantiated {} for {:?}",
                        M::info().model_name,
                        instance.interface
                    ),
                );
                let c = Box::into_raw(Box::new(instance)) as Fmi2Component;
                handles::register::<M>(c as usize, HandleKind::Instance, c as usize);
                c
            }
            Err(message) => {
                make_logger().status(Fmi2Status::Error, &format!("fmi2Instantiate: {message}"));
                std::ptr::null_mut()
            }
        }
    }));
    created.unwrap_or_else(|payload| {
        let log = Logger::new(
            callback,
            functions.component_environment,
            c"?".to_owned(),
            log_categories::<M>(),
            true,
        );
        let message = panic_message(payload.as_ref());
        log.status(
            Fmi2Status::Fatal,
            &format!("fmi2Instantiate: internal error (panic): {message}"),
        );
        std::ptr::null_mut()
    })
}

/// Frees the instance and every FMU state it still owns. A handle that is not a live
/// instance of this FMU is ignored (fmi2FreeInstance returns nothing to report with).
pub unsafe fn free_instance<M: Model>(c: Fmi2Component) {
    // SAFETY: instantiate::<M> boxes an Instance<M> and registers it under M;
    // fmu_state boxes its states as Snapshot<M>.
    unsafe { handles::free_instance::<M, Instance<M>, Snapshot<M>>(c as usize) }
}

pub unsafe fn set_debug_logging<M: Model>(
    c: Fmi2Component,
    logging_on: Fmi2Boolean,
    n_categories: usize,
    categories: *const Fmi2String,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetDebugLogging", Call::SetDebugLogging, |inst| {
            let pointers = input_slice(categories, n_categories, "categories[]")?;
            let names = pointers
                .iter()
                .map(|&p| text(p, "a category name").map(str::to_string))
                .collect::<Result<Vec<_>, _>>()?;
            inst.log.configure(logging_on != FMI2_FALSE, &names)?;
            Ok(Fmi2Status::Ok)
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
            let start = check_finite(start_time, "startTime")?;
            if tolerance_defined != FMI2_FALSE && !(tolerance.is_finite() && tolerance > 0.0) {
                return Err(format!("tolerance = {tolerance} is not a positive number"));
            }
            let mut stop = None;
            if stop_time_defined != FMI2_FALSE {
                let defined = check_finite(stop_time, "stopTime")?;
                if defined < start {
                    return Err(format!("stopTime {defined} is before startTime {start}"));
                }
                stop = Some(defined);
            }
            inst.core.stop_time = stop;
            inst.core.set_time(start);
            inst.core.last_successful_time = start;
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
            |inst| {
                inst.mode = Mode::InitializationMode;
                Ok(Fmi2Status::Ok)
            },
        )
    }
}

pub unsafe fn exit_initialization_mode<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2ExitInitializationMode",
            Call::ExitInitializationMode,
            |inst| {
                inst.core
                    .exit_initialization(&inst.log)
                    .map_err(|e| format!("invalid parameters: {e}"))?;
                inst.mode = match inst.interface {
                    Interface::ModelExchange => Mode::EventMode,
                    Interface::CoSimulation => Mode::StepComplete,
                };
                inst.log.debug(
                    "logEvents",
                    &format!("initialized at t = {} s", inst.core.time),
                );
                Ok(Fmi2Status::Ok)
            },
        )
    }
}

pub unsafe fn terminate<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2Terminate", Call::Terminate, |inst| {
            inst.mode = Mode::Terminated;
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn reset<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2Reset", Call::Reset, |inst| {
            inst.reset()?;
            Ok(Fmi2Status::Ok)
        })
    }
}
