//! Functions common to Model Exchange and Co-Simulation: creation, logging set-up,
//! initialization, event mode, termination, reset.

use super::{check_finite, input_slice, panic_message, with_instance};
use crate::core::handles::{self, HandleKind};
use crate::core::instance::Snapshot;
use crate::core::logging::Log;
use crate::core::model::Model;
use crate::fmi3::instance::Instance;
use crate::fmi3::logging::{Logger, log_categories};
use crate::fmi3::mode::{Call, Interface, Mode, after_initialization};
use crate::fmi3::types::*;
use std::ffi::{CStr, c_char};
use std::panic::{AssertUnwindSafe, catch_unwind};

pub fn get_version() -> *const c_char {
    c"3.0".as_ptr()
}

/// A C string argument as UTF-8 text.
unsafe fn text<'a>(ptr: Fmi3String, what: &str) -> Result<&'a str, String> {
    if ptr.is_null() {
        return Err(format!("{what} is a null pointer"));
    }
    // SAFETY: non-null C strings from the host are NUL-terminated.
    let s = unsafe { CStr::from_ptr(ptr) };
    s.to_str().map_err(|_| format!("{what} is not UTF-8"))
}

/// What an instantiate function was given.
pub struct Instantiation {
    pub function: &'static str,
    pub instance_name: Fmi3String,
    pub token: Fmi3String,
    pub logging_on: Fmi3Boolean,
    pub environment: Fmi3InstanceEnvironment,
    pub log_message: Option<Fmi3LogMessageCallback>,
    pub interface: Interface,
}

/// Creates an instance (fmi3InstantiateModelExchange and -CoSimulation): checks the
/// instance name and the instantiation token; null on failure, with a log line.
pub unsafe fn instantiate<M: Model>(args: Instantiation) -> Fmi3Instance {
    let logger = || {
        Logger::new(
            args.log_message,
            args.environment,
            log_categories::<M>(),
            args.logging_on != FMI3_FALSE,
        )
    };
    let created = catch_unwind(AssertUnwindSafe(|| {
        let created = (|| -> Result<Instance<M>, String> {
            // SAFETY: the host passes NUL-terminated strings or null (checked).
            let name = unsafe { text(args.instance_name, "instanceName") }?;
            if name.is_empty() {
                return Err("instanceName is empty".to_string());
            }
            // SAFETY: as above.
            let given = unsafe { text(args.token, "instantiationToken") }?;
            if given != M::info().guid {
                return Err(format!(
                    "instantiationToken {given} does not match this binary ({}, {})",
                    M::info().model_name,
                    M::info().guid
                ));
            }
            Instance::<M>::new(args.interface, logger())
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
                let c = Box::into_raw(Box::new(instance)) as Fmi3Instance;
                handles::register::<Instance<M>>(c as usize, HandleKind::Instance, c as usize);
                c
            }
            Err(message) => {
                logger().status(Fmi3Status::Error, &format!("{}: {message}", args.function));
                std::ptr::null_mut()
            }
        }
    }));
    created.unwrap_or_else(|payload| {
        let message = panic_message(payload.as_ref());
        logger().status(
            Fmi3Status::Fatal,
            &format!("{}: internal error (panic): {message}", args.function),
        );
        std::ptr::null_mut()
    })
}

/// fmi3InstantiateScheduledExecution: not supported (no clocks); null with a log line.
pub unsafe fn refuse_scheduled_execution<M: Model>(
    logging_on: Fmi3Boolean,
    environment: Fmi3InstanceEnvironment,
    log_message: Option<Fmi3LogMessageCallback>,
) -> Fmi3Instance {
    let log = Logger::new(
        log_message,
        environment,
        log_categories::<M>(),
        logging_on != FMI3_FALSE,
    );
    log.status(
        Fmi3Status::Error,
        &format!(
            "fmi3InstantiateScheduledExecution: {} supports Model Exchange and \
             Co-Simulation only",
            M::info().model_name
        ),
    );
    std::ptr::null_mut()
}

/// Frees the instance and every FMU state it still owns. A handle that is not a live
/// FMI 3.0 instance of this FMU is ignored (fmi3FreeInstance reports nothing).
pub unsafe fn free_instance<M: Model>(c: Fmi3Instance) {
    // SAFETY: instantiate::<M> boxes an Instance<M> and registers it under Instance<M>;
    // fmu_state boxes its states as Snapshot<M>.
    unsafe { handles::free_instance::<Instance<M>, Instance<M>, Snapshot<M>>(c as usize) }
}

pub unsafe fn set_debug_logging<M: Model>(
    c: Fmi3Instance,
    logging_on: Fmi3Boolean,
    n_categories: usize,
    categories: *const Fmi3String,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetDebugLogging", Call::SetDebugLogging, |inst| {
            let pointers = input_slice(categories, n_categories, "categories[]")?;
            let names = pointers
                .iter()
                .map(|&p| text(p, "a category name").map(str::to_string))
                .collect::<Result<Vec<_>, _>>()?;
            inst.log.configure(logging_on != FMI3_FALSE, &names)?;
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn enter_initialization_mode<M: Model>(
    c: Fmi3Instance,
    tolerance_defined: Fmi3Boolean,
    tolerance: Fmi3Float64,
    start_time: Fmi3Float64,
    stop_time_defined: Fmi3Boolean,
    stop_time: Fmi3Float64,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3EnterInitializationMode",
            Call::EnterInitializationMode,
            |inst| {
                let start = check_finite(start_time, "startTime")?;
                if tolerance_defined != FMI3_FALSE && !(tolerance.is_finite() && tolerance > 0.0) {
                    return Err(format!("tolerance = {tolerance} is not a positive number"));
                }
                let stop = if stop_time_defined != FMI3_FALSE {
                    let stop = check_finite(stop_time, "stopTime")?;
                    if stop < start {
                        return Err(format!("stopTime {stop} is before startTime {start}"));
                    }
                    Some(stop)
                } else {
                    None
                };
                inst.core.set_time(start);
                inst.core.last_successful_time = start;
                inst.core.stop_time = stop;
                inst.mode = Mode::InitializationMode;
                Ok(Fmi3Status::Ok)
            },
        )
    }
}

pub unsafe fn exit_initialization_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3ExitInitializationMode",
            Call::ExitInitializationMode,
            |inst| {
                inst.core
                    .exit_initialization(&inst.log)
                    .map_err(|e| format!("invalid parameters: {e}"))?;
                inst.mode = after_initialization(inst.interface);
                inst.log.debug(
                    "logEvents",
                    &format!("initialized at t = {} s", inst.core.time),
                );
                Ok(Fmi3Status::Ok)
            },
        )
    }
}

pub unsafe fn enter_event_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3EnterEventMode", Call::EnterEventMode, |inst| {
            inst.mode = Mode::EventMode;
            inst.log.debug(
                "logEvents",
                &format!("event mode at t = {} s", inst.core.time),
            );
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn terminate<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3Terminate", Call::Terminate, |inst| {
            inst.mode = Mode::Terminated;
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn reset<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3Reset", Call::Reset, |inst| {
            inst.reset()?;
            Ok(Fmi3Status::Ok)
        })
    }
}
