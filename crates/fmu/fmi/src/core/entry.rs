//! The logic every C entry point of both front-ends shares: the handle check, the
//! mode check, the logCalls line and the conversion of errors and panics into the
//! standard's status ([`with_instance`]); creating and freeing an instance; and the
//! bodies of the functions that FMI 2.0 and FMI 3.0 define alike.

use super::callback;
use super::frontend::{FmuInstance, Frontend, LoggerOf, StatusCode};
use super::handles::{self, HandleKind};
use super::instance::Snapshot;
use super::log::Log;
use super::logging::{LogSink, status_category};
use super::model::Model;
use super::variables::{Causality, Variability};
use crate::ffi::{check_finite, input_slice, panic_message, text};
use std::cell::Cell;
use std::ffi::{c_char, c_void};
use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::Arc;

/// Runs `body` on the instance behind `handle` after checking that `call` is legal in
/// its mode; turns errors into the Error status (+ Error mode) and panics into Fatal
/// (+ Fatal mode), both with a log line naming `function`.
///
/// The instance is busy during the call: a call from one of its callbacks or from
/// another thread meanwhile is refused with Error and a log line; a FreeInstance meanwhile is
/// done when this call ends, and from the callback that asked for it on, this call
/// neither touches the instance nor logs through it.
///
/// # Safety
/// `handle` is looked up in the registry before use; a live handle of type
/// `FmuInstance<F, M>` names one that only this library reaches.
pub unsafe fn with_instance<F: Frontend, M: Model>(
    handle: *mut c_void,
    function: &str,
    call: F::Call,
    body: impl FnOnce(&mut FmuInstance<F, M>) -> Result<F::Status, String>,
) -> F::Status {
    let token = handle as usize;
    let entered = match handles::enter::<FmuInstance<F, M>>(token, callback::stack_mark()) {
        Ok(entered) => entered,
        Err(refused) => return refuse::<F>(function, refused),
    };
    let instance = entered.address as *mut FmuInstance<F, M>;
    if entered.failed || entered.abandoned {
        // SAFETY: as below; a call that could not touch it left the Error state, and
        // so does a call that never returned (its changes may be half done).
        let inst = unsafe { &mut *instance };
        if inst.mode != F::FATAL {
            inst.mode = F::ERROR;
        }
        if entered.abandoned {
            inst.log.status(
                F::Status::ERROR,
                &format!(
                    "{function}: the previous call on this instance never returned (a \
                     callback left it with longjmp): the instance is in the Error state; \
                     Reset or FreeInstance it"
                ),
            );
        }
    }
    // SAFETY: a live instance, busy with this call: nothing else reaches it.
    let start = unsafe { (*instance).log.emitted() };
    let outcome = catch_unwind(AssertUnwindSafe(|| {
        // SAFETY: as above.
        let inst = unsafe { &mut *instance };
        check_call(inst, call)?;
        inst.log.debug("logCalls", function);
        if inst.log.emitted() != start && handles::free_requested(token) {
            return Err(String::new()); // freed by the logger: the body does not run
        }
        body(inst)
    }));
    // SAFETY: as above (a requested free waits for `leave`); the closure's borrow ended.
    let inst = unsafe { &mut *instance };
    // Only a callback (a message to the host) can have freed it from this thread.
    let freed = inst.log.emitted() != start && handles::free_requested(token);
    let status = conclude(inst, freed, function, outcome);
    if let Some(freed) = handles::leave(token) {
        // SAFETY: registered by `instantiate` as boxes of these types; unregistered
        // by `leave`, so freed once.
        unsafe { free_boxes::<F, M>(freed) };
    }
    status
}

/// The status of a call from its outcome, with the log line and mode of an error or a
/// panic. When a callback freed the instance during the call (`freed`): Error (Fatal
/// for a panic) without a log line, since the instance is gone for the host.
fn conclude<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    freed: bool,
    function: &str,
    outcome: std::thread::Result<Result<F::Status, String>>,
) -> F::Status {
    if freed {
        return match outcome {
            Ok(_) => F::Status::ERROR,
            Err(_) => F::Status::FATAL,
        };
    }
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

thread_local! {
    /// This thread is reporting a refusal: a call from that logger is refused
    /// silently (no endless recursion through a logger that calls again).
    static REPORTING: Cell<bool> = const { Cell::new(false) };
}

/// The Error status for a call that [`handles::enter`] refused, with a log line
/// through the instance's logger when it is busy (the instance is not touched).
fn refuse<F: Frontend>(function: &str, refused: handles::Refused) -> F::Status {
    let handles::Refused::Busy {
        reentrant,
        reporter: Some(report),
    } = refused
    else {
        // Not a live instance of this front-end and FMU (null, garbage, freed,
        // another FMU's, the other standard's): no logger to report through.
        return F::Status::ERROR;
    };
    if REPORTING.replace(true) {
        return F::Status::ERROR;
    }
    report(&if reentrant {
        format!(
            "{function}: refused: called from a callback of a call still running on this \
             instance (the instance is unchanged; FreeInstance from a callback is done when \
             that call returns)"
        )
    } else {
        format!(
            "{function}: refused: another thread is inside a call on this instance (the \
             standard allows one thread per instance at a time; the instance is unchanged)"
        )
    });
    REPORTING.set(false);
    F::Status::ERROR
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

/// The host's logger, shared with the registry to report refused calls from any
/// thread without touching the instance.
struct SharedSink<S>(S);

// SAFETY: the sink is the host's callback and its environment; the standards let a
// logger be called for an instance from the thread calling it, and a refusal is a
// call on that instance (its Error line) from the refused thread.
unsafe impl<S> Sync for SharedSink<S> {}
unsafe impl<S> Send for SharedSink<S> {}

impl<S: LogSink> SharedSink<S> {
    fn error(&self, message: &str) {
        let error = S::Status::ERROR;
        self.0.emit(error, status_category(error), message);
    }
}

fn reporter<F: Frontend>(logger: &LoggerOf<F>) -> handles::Reporter {
    let sink = SharedSink(logger.sink().clone());
    Arc::new(move |message: &str| sink.error(message))
}

/// Instantiation: `create` checks the standard's arguments and builds the instance,
/// which is then logged, boxed and registered under a new handle; on an error or a
/// panic, null with a log line through a logger from `logger`.
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
                    M::INFO.model_name,
                    instance.interface
                );
                instance.log.debug("logEvents", &message);
            }
            let report = reporter::<F>(&instance.log);
            let address = Box::into_raw(Box::new(instance));
            let kind = HandleKind::Instance;
            let registered =
                handles::register::<FmuInstance<F, M>>(address as usize, kind, None, Some(report));
            // SAFETY: just boxed; the host does not know the handle yet (or never
            // will: then it is dropped here, once).
            let Some(handle) = registered else {
                let instance = unsafe { Box::from_raw(address) };
                instance.log.status(
                    F::Status::ERROR,
                    &format!("{function}: this FMU has issued every handle it can"),
                );
                return std::ptr::null_mut();
            };
            unsafe { (*address).handle = handle };
            handle as *mut c_void
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
/// `FmuInstance<F, M>` is ignored (FreeInstance has no status to report with); an
/// instance busy with a call (FreeInstance from its logger, or from another thread)
/// is freed when that call returns.
///
/// # Safety
/// Every live handle of type `FmuInstance<F, M>` must come from [`instantiate`].
pub unsafe fn free_instance<F: Frontend, M: Model>(handle: *mut c_void) {
    let mark = callback::stack_mark();
    if let Some(freed) = handles::free_instance::<FmuInstance<F, M>>(handle as usize, mark) {
        // SAFETY: by the contract above; unregistered, so freed once.
        unsafe { free_boxes::<F, M>(freed) }
    }
}

/// Drops an unregistered instance and its states. A panic while dropping is caught:
/// the C boundary holds regardless.
///
/// # Safety
/// `freed` must come from the registry: an instance boxed by [`instantiate`] and
/// states boxed by `fmu_states`, all unregistered.
unsafe fn free_boxes<F: Frontend, M: Model>(freed: handles::Freed) {
    let _ = catch_unwind(AssertUnwindSafe(|| {
        for state in freed.states {
            // SAFETY: by the contract above.
            drop(unsafe { Box::from_raw(state as *mut Snapshot<M>) });
        }
        // SAFETY: by the contract above.
        drop(unsafe { Box::from_raw(freed.instance as *mut FmuInstance<F, M>) });
    }));
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
        return Err(format!(
            "tolerance = {tolerance} is not a positive number (toleranceDefined = true): pass \
             a positive relative tolerance or toleranceDefined = false (these FMUs use none)"
        ));
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

/// SetTime (Model Exchange): a finite time. A time past the stop time is accepted:
/// variable-step integrators (CVode in FMPy) evaluate the derivatives there.
pub fn set_time<M: Model>(
    core: &mut super::instance::Instance<M>,
    time: f64,
) -> Result<(), String> {
    core.set_time(check_finite(time, "time")?);
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
/// and returns Discard: the instance stays usable. Before initialization ends, the
/// reason is the parameters' when ExitInitializationMode would refuse them (a value
/// that cannot be evaluated is then their consequence).
pub fn discard<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    function: &str,
    reason: &str,
) -> F::Status {
    let discard = StatusCode::DISCARD;
    let initializing = inst.mode == F::INSTANTIATED || inst.mode == F::INITIALIZATION;
    let refused = initializing
        .then(|| inst.core.parameters_refused())
        .flatten();
    let reason = match refused {
        Some(why) => format!("invalid parameters (ExitInitializationMode refuses them): {why}"),
        None => reason.to_string(),
    };
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

/// A set of the fixed parameter `name` after initialization, which [`settable`]
/// refuses (`refusal`): accepted without effect when every value is the one the
/// parameter holds, bit for bit (`unchanged`; then Ok with the text of the Warning
/// line the setter logs), otherwise the refusal, unchanged. Importers that set every
/// parameter of a study again in step mode (gemseo-fmu) need it; a different value
/// still cannot change what initialization computed from the parameter.
pub fn refuse_unless_unchanged(
    refusal: String,
    name: &dyn std::fmt::Display,
    mode: impl std::fmt::Debug,
    unchanged: bool,
) -> Result<Option<String>, String> {
    if !unchanged {
        return Err(refusal);
    }
    Ok(Some(format!(
        "\"{name}\" (causality parameter, variability fixed) set in {mode:?} to the value it \
         holds: accepted without effect (a fixed parameter cannot change after \
         initialization; a different value is refused with an Error)"
    )))
}

/// Enters `mode` (a call whose only effect is the change of mode).
pub fn enter<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    mode: F::Mode,
) -> Result<F::Status, String> {
    inst.mode = mode;
    Ok(StatusCode::OK)
}
