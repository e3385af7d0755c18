//! Functions common to Model Exchange and Co-Simulation: creation, logging set-up,
//! initialization, event mode, termination, reset.

use super::with_instance;
use crate::core::entry;
use crate::core::frontend::log_categories;
use crate::core::instance::{Index, IndexOf};
use crate::core::model::Model;
use crate::core::model_exchange_calls;
use crate::ffi::{input_slice, text};
use crate::fmi3::instance::Instance;
use crate::fmi3::intermediate::IntermediateUpdate;
use crate::fmi3::logging::{Callback, Logger};
use crate::fmi3::mode::{Call, Fmi3, Interface, Mode};
use crate::fmi3::table::Table3;
use crate::fmi3::types::*;
use std::ffi::c_char;

pub fn get_version() -> *const c_char {
    c"3.0".as_ptr()
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
    /// The intermediateUpdate callback (Co-Simulation; None for Model Exchange).
    pub intermediate_update: Option<IntermediateUpdate>,
}

/// Err unless requiredIntermediateVariables names at most as many variables as the
/// model has, each a variable the importer may set or get in Intermediate Update Mode
/// (declared intermediateUpdate; FMI 3.0 section 4.2.4). The count is checked before
/// the array is read, so a wrong count never reads beyond the importer's array.
///
/// # Safety
/// A non-null `vrs` must be valid for `n` value references.
unsafe fn check_required<M: Model>(
    table: &Table3,
    declared: usize,
    (vrs, n): (*const Fmi3ValueReference, usize),
) -> Result<(), String> {
    if n > declared {
        return Err(format!(
            "nRequiredIntermediateVariables = {n}, but the model has {declared} variables"
        ));
    }
    // SAFETY: by the contract above.
    let vrs = unsafe { input_slice(vrs, n, "requiredIntermediateVariables[]") }?;
    for &vr in vrs {
        let v = table.find(vr).ok_or_else(|| {
            format!("requiredIntermediateVariables: unknown value reference {vr}")
        })?;
        if !v.intermediate_update::<M>() {
            return Err(format!(
                "requiredIntermediateVariables: \"{}\" (value reference {vr}) is not declared \
                 intermediateUpdate",
                v.name
            ));
        }
    }
    Ok(())
}

/// The logger of an instance of M.
fn logger<M: Model>(
    function: Option<Fmi3LogMessageCallback>,
    environment: Fmi3InstanceEnvironment,
    logging_on: Fmi3Boolean,
) -> Logger {
    let sink = Callback {
        function,
        environment,
    };
    Logger::new(sink, log_categories::<Fmi3, M>(), logging_on != FMI3_FALSE)
}

/// Creates an instance (fmi3InstantiateModelExchange and -CoSimulation): checks the
/// instance name and the instantiation token; null on failure, with a log line.
pub unsafe fn instantiate<M: Model>(args: Instantiation) -> Fmi3Instance {
    // SAFETY: an empty list.
    unsafe { instantiate_requiring::<M>(args, (std::ptr::null(), 0)) }
}

/// [`instantiate_with`] for an in-process host: the instance gets an index of its own
/// ([`Index::own`]).
///
/// # Safety
/// A non-null `required.0` must be valid for `required.1` value references.
pub unsafe fn instantiate_requiring<M: Model>(
    args: Instantiation,
    required: (*const Fmi3ValueReference, usize),
) -> Fmi3Instance {
    // SAFETY: by the contract above.
    unsafe { instantiate_with::<M>(Index::own, args, required) }
}

/// [`instantiate`] with the model's index taken from `index` (the exported symbols
/// pass [`Index::shared`]), which also checks requiredIntermediateVariables
/// (`required`: the array and its length; empty for Model Exchange).
///
/// # Safety
/// A non-null `required.0` must be valid for `required.1` value references.
pub unsafe fn instantiate_with<M: Model>(
    index: IndexOf<M>,
    args: Instantiation,
    required: (*const Fmi3ValueReference, usize),
) -> Fmi3Instance {
    let logger = || logger::<M>(args.log_message, args.environment, args.logging_on);
    entry::instantiate(
        args.function,
        logger,
        |log| -> Result<Instance<M>, String> {
            // SAFETY: the host passes NUL-terminated strings or null (checked).
            let name = unsafe { text(args.instance_name, "instanceName") }?;
            if name.is_empty() {
                return Err("instanceName is empty".to_string());
            }
            // SAFETY: as above.
            let given = unsafe { text(args.token, "instantiationToken") }?;
            let scalar = crate::fmi3::scalar::is_token::<M>(given);
            if given != M::INFO.guid && !scalar {
                return Err(format!(
                    "instantiationToken {given} does not match this binary ({}, {})",
                    M::INFO.model_name,
                    M::INFO.guid
                ));
            }
            // SAFETY: the host passes an array of the given length or null.
            let check = |table: &Table3, declared| unsafe {
                check_required::<M>(table, declared, required)
            };
            let (interface, update) = (args.interface, args.intermediate_update);
            Instance::<M>::new(interface, log, update, scalar, check, index()?)
        },
    )
}

/// fmi3InstantiateScheduledExecution: not supported (no clocks); null with a log line.
pub unsafe fn refuse_scheduled_execution<M: Model>(
    logging_on: Fmi3Boolean,
    environment: Fmi3InstanceEnvironment,
    log_message: Option<Fmi3LogMessageCallback>,
) -> Fmi3Instance {
    logger::<M>(log_message, environment, logging_on).status(
        Fmi3Status::Error,
        &format!(
            "fmi3InstantiateScheduledExecution: {} supports Model Exchange and \
             Co-Simulation only",
            M::INFO.model_name
        ),
    );
    std::ptr::null_mut()
}

/// Frees the instance and every FMU state it still owns. A handle that is not a live
/// FMI 3.0 instance of this FMU is ignored (fmi3FreeInstance reports nothing).
pub unsafe fn free_instance<M: Model>(c: Fmi3Instance) {
    unsafe { entry::free_instance::<Fmi3, M>(c) }
}

pub unsafe fn set_debug_logging<M: Model>(
    c: Fmi3Instance,
    logging_on: Fmi3Boolean,
    n_categories: usize,
    categories: *const Fmi3String,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetDebugLogging", Call::SetDebugLogging, |inst| {
            entry::set_debug_logging(inst, logging_on != FMI3_FALSE, n_categories, categories)
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
                let tolerance = (tolerance_defined != FMI3_FALSE).then_some(tolerance);
                let stop = (stop_time_defined != FMI3_FALSE).then_some(stop_time);
                entry::setup_experiment(&mut inst.core, tolerance, start_time, stop)?;
                // Tick 0 of every clock at the start time.
                inst.extra.clocks.start = inst.core.time;
                entry::enter(inst, Mode::InitializationMode)
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
            entry::exit_initialization_mode,
        )
    }
}

pub unsafe fn enter_event_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3EnterEventMode", Call::EnterEventMode, |inst| {
            model_exchange_calls::enter_event_mode(inst, Mode::EventMode)
        })
    }
}

pub unsafe fn terminate<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3Terminate", Call::Terminate, |inst| {
            entry::enter(inst, Mode::Terminated)
        })
    }
}

pub unsafe fn reset<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3Reset", Call::Reset, |inst| {
            inst.reset();
            inst.extra.clocks = crate::fmi3::clocks::Clocks::new::<M>();
            inst.set_clock_periods_to_start();
            Ok(Fmi3Status::Ok)
        })
    }
}
