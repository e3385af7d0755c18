//! The logic every C entry point of both front-ends shares: the handle check, the
//! mode check, the logCalls line and the conversion of errors and panics into the
//! standard's status ([`with_instance`]); creating and freeing an instance; and the
//! bodies of the functions that FMI 2.0 and FMI 3.0 define alike.

use super::frontend::{FmuInstance, Frontend, LoggerOf, StatusCode};
use super::handles::{self, HandleKind};
use super::instance::Snapshot;
use super::log::Log;
use super::model::Model;
use super::variables::{Causality, Variability};
use crate::ffi::{check_finite, input_slice, panic_message, text};
use std::ffi::{c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Runs `body` on the instance behind `handle` after checking that `call` is legal in
/// its mode; turns errors into the Error status (+ Error mode) and panics into Fatal
/// (+ Fatal mode), both with a log line naming `function`.
///
/// # Safety
/// `handle` is looked up in the registry before use; a live handle of type
/// `FmuInstance<F, M>` must point to one that nothing else borrows during the call.
pub unsafe fn with_instance<F: Frontend, M: Model>(
    handle: *mut c_void,
    function: &str,
    call: F::Call,
    body: impl FnOnce(&mut FmuInstance<F, M>) -> Result<F::Status, String>,
) -> F::Status {
    // Not a live instance of this front-end and FMU (null, garbage, freed, another
    // FMU's, the other standard's): there is no logger to report through.
    if !handles::is_live::<FmuInstance<F, M>>(handle as usize, HandleKind::Instance) {
        return F::Status::ERROR;
    }
    let instance = handle as *mut FmuInstance<F, M>;
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: by the contract above, `handle` points to a live instance.
        let inst = unsafe { &mut *instance };
        check_call(inst, call)?;
        inst.log.debug("logCalls", function);
        body(inst)
    }));
    // SAFETY: as above; the closure's borrow has ended.
    let inst = unsafe { &mut *instance };
    match outcome {
        Ok(Ok(status)) => status,
        Ok(Err(message)) => {
            inst.log
                .status(F::Status::ERROR, &format!("{function}: {message}"));
            if inst.mode != F::FATAL {
                inst.mode = F::ERROR;
            }
            F::Status::ERROR
        }
        Err(payload) => {
            let message = panic_message(payload.as_ref());
            inst.mode = F::FATAL;
            inst.log.status(
                F::Status::FATAL,
                &format!("{function}: internal error (panic): {message}"),
            );
            F::Status::FATAL
        }
    }
}

/// Err when `call` is not legal in the instance's mode.
fn check_call<F: Frontend, M: Model>(
    inst: &FmuInstance<F, M>,
    call: F::Call,
) -> Result<(), String> {
    if F::is_legal(call, inst.mode, inst.interface) {
        Ok(())
    } else {
        Err(format!(
            "illegal call sequence: not allowed in {} {:?} ({:?})",
            F::MODE_WORD,
            inst.mode,
            inst.interface
        ))
    }
}

/// Instantiation: `create` checks the standard's arguments and builds the instance,
/// which is then logged, boxed and registered; on an error or a panic, null with a log
/// line through a logger from `logger`.
pub fn instantiate<F: Frontend, M: Model>(
    function: &str,
    logger: impl Fn() -> LoggerOf<F>,
    create: impl FnOnce(LoggerOf<F>) -> Result<FmuInstance<F, M>, String>,
) -> *mut c_void {
    let created = catch_unwind(AssertUnwindSafe(|| match create(logger()) {
        Ok(instance) => {
            if instance.log.enabled("logEvents") {
                let message = format!(
                    "instantiated {} for {:?}",
                    M::info().model_name,
                    instance.interface
                );
                instance.log.debug("logEvents", &message);
            }
            let c = Box::into_raw(Box::new(instance)) as *mut c_void;
            handles::register::<FmuInstance<F, M>>(c as usize, HandleKind::Instance, c as usize);
            c
        }
        Err(message) => {
            logger().status(F::Status::ERROR, &format!("{function}: {message}"));
            std::ptr::null_mut()
        }
    }));
    created.unwrap_or_else(|payload| {
        let message = panic_message(payload.as_ref());
        logger().status(
            F::Status::FATAL,
            &format!("{function}: internal error (panic): {message}"),
        );
        std::ptr::null_mut()
    })
}

/// Frees the instance and every FMU state it still owns. A handle that is not a live
/// `FmuInstance<F, M>` is ignored (FreeInstance has no status to report with).
///
/// # Safety
/// Every live handle of type `FmuInstance<F, M>` must come from [`instantiate`].
pub unsafe fn free_instance<F: Frontend, M: Model>(handle: *mut c_void) {
    type I<F, M> = FmuInstance<F, M>;
    // SAFETY: instantiate boxes an instance and registers it under its type;
    // `fmu_states` boxes the states as Snapshot<M>.
    unsafe { handles::free_instance::<I<F, M>, I<F, M>, Snapshot<M>>(handle as usize) }
}

/// SetDebugLogging: logging on or off and the enabled categories (all for an empty
/// list).
///
/// # Safety
/// `categories` must be null or valid for `n_categories` C strings.
pub unsafe fn set_debug_logging<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    logging_on: bool,
    n_categories: usize,
    categories: *const *const c_char,
) -> Result<F::Status, String> {
    // SAFETY: by the contract above.
    let pointers = unsafe { input_slice(categories, n_categories, "categories[]") }?;
    let names = pointers
        .iter()
        // SAFETY: the host's category names are NUL-terminated strings or null.
        .map(|&p| unsafe { text(p, "a category name") }.map(str::to_string))
        .collect::<Result<Vec<_>, _>>()?;
    inst.log.configure(logging_on, &names)?;
    Ok(StatusCode::OK)
}

/// The experiment (fmi2SetupExperiment, the arguments of fmi3EnterInitializationMode):
/// tolerance, start time and stop time, checked, then the time set to the start.
pub fn setup_experiment<M: Model>(
    core: &mut super::instance::Instance<M>,
    tolerance: Option<f64>,
    start_time: f64,
    stop_time: Option<f64>,
) -> Result<(), String> {
    let start = check_finite(start_time, "startTime")?;
    if let Some(tolerance) = tolerance
        && !(tolerance.is_finite() && tolerance > 0.0)
    {
        return Err(format!("tolerance = {tolerance} is not a positive number"));
    }
    if let Some(stop) = stop_time {
        let stop = check_finite(stop, "stopTime")?;
        if stop < start {
            return Err(format!("stopTime {stop} is before startTime {start}"));
        }
    }
    core.stop_time = stop_time;
    core.set_time(start);
    core.last_successful_time = start;
    Ok(())
}

/// ExitInitializationMode: the model's checks, then the mode after initialization.
pub fn exit_initialization_mode<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
) -> Result<F::Status, String> {
    inst.core
        .exit_initialization(&inst.log)
        .map_err(|e| format!("invalid parameters: {e}"))?;
    inst.mode = F::after_initialization(inst.interface);
    inst.log.debug(
        "logEvents",
        &format!("initialized at t = {} s", inst.core.time),
    );
    Ok(StatusCode::OK)
}

/// Logs that `function` cannot evaluate the model at the instance's time (`reason`)
/// and returns Discard: the instance stays usable.
pub fn discard<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    function: &str,
    reason: &str,
) -> F::Status {
    let discard = StatusCode::DISCARD;
    inst.log.status(
        discard,
        &format!("{function}: at t = {} s: {reason}", inst.core.time),
    );
    discard
}

/// Ok when the standard's rule allows setting the variable `name` in `mode`
/// (`allowed`), else the error that says why not.
pub fn settable(
    allowed: bool,
    name: &str,
    causality: Causality,
    variability: Variability,
    mode: impl std::fmt::Debug,
) -> Result<(), String> {
    if allowed {
        return Ok(());
    }
    Err(format!(
        "\"{name}\" (causality {}, variability {}) cannot be set in {mode:?}",
        causality.as_str(),
        variability.as_str()
    ))
}

/// Enters `mode` (a call whose only effect is the change of mode).
pub fn enter<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    mode: F::Mode,
) -> Result<F::Status, String> {
    inst.mode = mode;
    Ok(StatusCode::OK)
}
