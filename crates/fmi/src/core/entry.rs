//! The logic every C entry point of both front-ends shares: the handle check, the
//! mode check, the logCalls line and the conversion of errors and panics into the
//! standard's status ([`with_instance`]); creating and freeing an instance; and the
//! bodies of the functions that FMI 2.0 and FMI 3.0 define alike.

use super::frontend::{Frontend, FrontendInstance, LoggerOf, StatusCode, StatusOf};
use super::handles::{self, HandleKind};
use super::instance::Snapshot;
use super::log::Log;
use super::model::Model;
use super::variables::{Causality, Variability};
use crate::ffi::{check_finite, input_slice, panic_message, text};
use std::ffi::{c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};

type FrontendOf<I> = <I as FrontendInstance>::Frontend;
type CallOf<I> = <FrontendOf<I> as Frontend>::Call;

/// Runs `body` on the instance behind `handle` after checking that `call` is legal in
/// its mode; turns errors into the Error status (+ Error mode) and panics into Fatal
/// (+ Fatal mode), both with a log line naming `function`.
///
/// # Safety
/// `handle` is looked up in the registry before use; a live handle of type `I` must
/// point to an `I` that nothing else borrows during the call.
pub unsafe fn with_instance<I: FrontendInstance>(
    handle: *mut c_void,
    function: &str,
    call: CallOf<I>,
    body: impl FnOnce(&mut I) -> Result<StatusOf<FrontendOf<I>>, String>,
) -> StatusOf<FrontendOf<I>> {
    type S<I> = StatusOf<FrontendOf<I>>;
    // Not a live instance of this front-end and FMU (null, garbage, freed, another
    // FMU's, the other standard's): there is no logger to report through.
    if !handles::is_live::<I>(handle as usize, HandleKind::Instance) {
        return S::<I>::ERROR;
    }
    let instance = handle as *mut I;
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: by the contract above, `handle` points to a live I.
        let inst = unsafe { &mut *instance };
        check_call(inst, call)?;
        inst.parts().log.debug("logCalls", function);
        body(inst)
    }));
    // SAFETY: as above; the closure's borrow has ended.
    let parts = unsafe { &mut *instance }.parts();
    match outcome {
        Ok(Ok(status)) => status,
        Ok(Err(message)) => {
            parts
                .log
                .status(S::<I>::ERROR, &format!("{function}: {message}"));
            if *parts.mode != FrontendOf::<I>::FATAL {
                *parts.mode = FrontendOf::<I>::ERROR;
            }
            S::<I>::ERROR
        }
        Err(payload) => {
            let message = panic_message(payload.as_ref());
            *parts.mode = FrontendOf::<I>::FATAL;
            parts.log.status(
                S::<I>::FATAL,
                &format!("{function}: internal error (panic): {message}"),
            );
            S::<I>::FATAL
        }
    }
}

/// Err when `call` is not legal in the instance's mode.
fn check_call<I: FrontendInstance>(inst: &mut I, call: CallOf<I>) -> Result<(), String> {
    let parts = inst.parts();
    if FrontendOf::<I>::is_legal(call, *parts.mode, parts.interface) {
        Ok(())
    } else {
        Err(format!(
            "illegal call sequence: not allowed in {} {:?} ({:?})",
            FrontendOf::<I>::MODE_WORD,
            parts.mode,
            parts.interface
        ))
    }
}

/// Instantiation: `create` checks the standard's arguments and builds the instance,
/// which is then logged, boxed and registered; on an error or a panic, null with a log
/// line through a logger from `logger`.
pub fn instantiate<I: FrontendInstance>(
    function: &str,
    logger: impl Fn() -> LoggerOf<FrontendOf<I>>,
    create: impl FnOnce(LoggerOf<FrontendOf<I>>) -> Result<I, String>,
) -> *mut c_void {
    type S<I> = StatusOf<FrontendOf<I>>;
    let created = catch_unwind(AssertUnwindSafe(|| match create(logger()) {
        Ok(mut instance) => {
            let parts = instance.parts();
            parts.log.debug(
                "logEvents",
                &format!(
                    "instantiated {} for {:?}",
                    I::Model::info().model_name,
                    parts.interface
                ),
            );
            let c = Box::into_raw(Box::new(instance)) as *mut c_void;
            handles::register::<I>(c as usize, HandleKind::Instance, c as usize);
            c
        }
        Err(message) => {
            logger().status(S::<I>::ERROR, &format!("{function}: {message}"));
            std::ptr::null_mut()
        }
    }));
    created.unwrap_or_else(|payload| {
        let message = panic_message(payload.as_ref());
        logger().status(
            S::<I>::FATAL,
            &format!("{function}: internal error (panic): {message}"),
        );
        std::ptr::null_mut()
    })
}

/// Frees the instance and every FMU state it still owns. A handle that is not a live
/// `I` is ignored (FreeInstance has no status to report with).
///
/// # Safety
/// Every live handle of type `I` must come from [`instantiate`].
pub unsafe fn free_instance<I: FrontendInstance>(handle: *mut c_void) {
    // SAFETY: instantiate boxes an I and registers it under I; `fmu_states` boxes the
    // states as Snapshot<I::Model>.
    unsafe { handles::free_instance::<I, I, Snapshot<I::Model>>(handle as usize) }
}

/// SetDebugLogging: logging on or off and the enabled categories (all for an empty
/// list).
///
/// # Safety
/// `categories` must be null or valid for `n_categories` C strings.
pub unsafe fn set_debug_logging<I: FrontendInstance>(
    inst: &mut I,
    logging_on: bool,
    n_categories: usize,
    categories: *const *const c_char,
) -> Result<StatusOf<FrontendOf<I>>, String> {
    // SAFETY: by the contract above.
    let pointers = unsafe { input_slice(categories, n_categories, "categories[]") }?;
    let names = pointers
        .iter()
        // SAFETY: the host's category names are NUL-terminated strings or null.
        .map(|&p| unsafe { text(p, "a category name") }.map(str::to_string))
        .collect::<Result<Vec<_>, _>>()?;
    inst.log_mut().configure(logging_on, &names)?;
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
pub fn exit_initialization_mode<I: FrontendInstance>(
    inst: &mut I,
) -> Result<StatusOf<FrontendOf<I>>, String> {
    let parts = inst.parts();
    parts
        .core
        .exit_initialization(parts.log)
        .map_err(|e| format!("invalid parameters: {e}"))?;
    *parts.mode = FrontendOf::<I>::after_initialization(parts.interface);
    parts.log.debug(
        "logEvents",
        &format!("initialized at t = {} s", parts.core.time),
    );
    Ok(StatusCode::OK)
}

/// Logs that `function` cannot evaluate the model at the instance's time (`reason`)
/// and returns Discard: the instance stays usable.
pub fn discard<I: FrontendInstance>(
    inst: &mut I,
    function: &str,
    reason: &str,
) -> StatusOf<FrontendOf<I>> {
    let parts = inst.parts();
    let discard = StatusCode::DISCARD;
    parts.log.status(
        discard,
        &format!("{function}: at t = {} s: {reason}", parts.core.time),
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
pub fn enter<I: FrontendInstance>(
    inst: &mut I,
    mode: <FrontendOf<I> as Frontend>::Mode,
) -> Result<StatusOf<FrontendOf<I>>, String> {
    *inst.parts().mode = mode;
    Ok(StatusCode::OK)
}
