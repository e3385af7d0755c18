//! The bodies of the Model Exchange functions that FMI 2.0 and FMI 3.0 define alike
//! (entering Event Mode, updating discrete states, setting and reading the continuous
//! state arrays): each front-end runs them inside its `with_instance` and writes the
//! results into its own C types. The getters of the four state arrays are whole entry
//! points here ([`get_array`]): a front-end only names the function and its call.

use super::entry::{self, discard};
use super::frontend::{FmuInstance, Frontend, StatusCode};
use super::logging::Log;
use super::model::{EventUpdate, Model};
use crate::ffi::{input_slice, output_ref, output_slice};
use std::ffi::c_void;

type Result<F> = std::result::Result<<F as Frontend>::Status, String>;

/// Checks an array length against the model's count.
pub fn check_len(n: usize, expected: usize, what: &str) -> std::result::Result<(), String> {
    if n == expected {
        Ok(())
    } else {
        Err(format!("{what} has length {n}, the model has {expected}"))
    }
}

/// The number of continuous states of `model`, counted from its declarations at
/// its current sizes (`core::structural`).
pub fn states<M: Model>(model: &M) -> usize {
    super::structural::continuous_states_now(model)
}

/// The number of event indicators of M.
pub fn indicators<M: Model>() -> usize {
    M::INFO.number_of_event_indicators
}

/// EnterEventMode: `event_mode` (the front-end's Event Mode) with a log line.
pub fn enter_event_mode<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    event_mode: F::Mode,
) -> Result<F> {
    inst.mode = event_mode;
    inst.log.debug(
        "logEvents",
        &format!("event mode at t = {} s", inst.core.time),
    );
    Ok(StatusCode::OK)
}

/// NewDiscreteStates / UpdateDiscreteStates: the model's update and its next time
/// event (logged), for the front-end to write out.
pub fn update_discrete_states<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
) -> (EventUpdate, Option<f64>) {
    let update = inst.core.model_mut().update_discrete_states();
    let next = inst.core.model().next_time_event(inst.core.time);
    if let Some(t) = next {
        inst.log
            .debug("logEvents", &format!("next time event at t = {t} s"));
    }
    (update, next)
}

/// CompletedIntegratorStep: the models have no step events, so neither
/// enterEventMode nor terminateSimulation.
///
/// # Safety
/// Both pointers must be null or valid.
pub unsafe fn completed_integrator_step<F: Frontend, M: Model, B: From<bool>>(
    _inst: &mut FmuInstance<F, M>,
    enter_event_mode: *mut B,
    terminate_simulation: *mut B,
) -> Result<F> {
    // SAFETY: by the contract above.
    let enter = unsafe { output_ref(enter_event_mode, "enterEventMode") }?;
    let stop = unsafe { output_ref(terminate_simulation, "terminateSimulation") }?;
    *enter = B::from(false);
    *stop = B::from(false);
    Ok(StatusCode::OK)
}

/// SetContinuousStates from the array `x` (named `what` in messages) of `nx` values.
///
/// # Safety
/// `x` must be null or valid for `nx` values.
pub unsafe fn set_continuous_states<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    x: *const f64,
    nx: usize,
    what: &str,
) -> Result<F> {
    check_len(nx, states(inst.core.model()), what)?;
    // SAFETY: by the contract above.
    let x = unsafe { input_slice(x, nx, what) }?;
    if let Some(bad) = x.iter().find(|v| !v.is_finite()) {
        return Err(format!("{what} contains {bad}"));
    }
    inst.core.model_mut().set_continuous_states(x);
    Ok(StatusCode::OK)
}

/// The arrays of Model Exchange that both standards read alike.
#[derive(Clone, Copy, Debug)]
pub enum StateArray {
    Derivatives,
    EventIndicators,
    ContinuousStates,
    Nominals,
}

impl StateArray {
    /// The model's length of the array.
    fn expected<M: Model>(self, model: &M) -> usize {
        match self {
            StateArray::EventIndicators => indicators::<M>(),
            _ => states(model),
        }
    }

    /// The array of model `m` into `out`.
    fn compute<M: Model>(self, m: &mut M, out: &mut [f64]) -> std::result::Result<(), String> {
        match self {
            StateArray::Derivatives => m.derivatives(out),
            StateArray::EventIndicators => m.event_indicators(out),
            StateArray::ContinuousStates => {
                m.continuous_states(out);
                Ok(())
            }
            StateArray::Nominals => {
                m.nominals_of_continuous_states(out);
                Ok(())
            }
        }
    }
}

/// GetDerivatives (FMI 3.0: GetContinuousStateDerivatives), GetEventIndicators,
/// GetContinuousStates and GetNominalsOfContinuousStates of front-end F: `array` of
/// the instance behind `c` into `ptr` (a model error or a non-finite value:
/// Discard), as `function`, legal where `call` is.
///
/// # Safety
/// `c` is a handle the FMU issued (or anything the registry refuses); `ptr` must be
/// null or valid for `n` values.
pub unsafe fn get_array<F: Frontend, M: Model>(
    c: *mut c_void,
    (function, call): (&str, F::Call),
    array: StateArray,
    ptr: *mut f64,
    n: usize,
) -> F::Status {
    // SAFETY: by the contract above.
    unsafe {
        entry::with_instance::<F, M>(c, function, call, |inst| {
            let expected = array.expected(inst.core.model());
            fill(inst, function, ptr, n, expected, |m, out| {
                array.compute(m, out)
            })
        })
    }
}

/// Fills the output array `ptr` of the model's count `expected` with `f`. An error of
/// the model (it cannot be evaluated here; an integrator may retry with a smaller
/// step) is logged and returned as Discard, leaving the instance usable, and so is a
/// non-finite value (the same rule as for every getter).
///
/// # Safety
/// `ptr` must be null or valid for `n` values.
unsafe fn fill<F: Frontend, M: Model>(
    inst: &mut FmuInstance<F, M>,
    function: &str,
    ptr: *mut f64,
    n: usize,
    expected: usize,
    f: impl FnOnce(&mut M, &mut [f64]) -> std::result::Result<(), String>,
) -> Result<F> {
    check_len(n, expected, "the array")?;
    // SAFETY: by the contract above.
    let out = unsafe { output_slice(ptr, n, "the array") }?;
    if let Err(reason) = f(inst.core.model_to_read(), out) {
        return Ok(discard(inst, function, &reason));
    }
    if let Some(bad) = out.iter().find(|v| !v.is_finite()) {
        let reason = format!("the model computed {bad}");
        return Ok(discard(inst, function, &reason));
    }
    Ok(StatusCode::OK)
}

/// Defines a front-end's getters of the state arrays, each an entry point of
/// [`get_array`]: `fn_name: "fmiXFunctionName", the front-end's call, StateArray
/// variant;` for front-end `$frontend` with its handle and status types.
macro_rules! state_array_getters {
    ($frontend:ty, $handle:ty, $status:ty; $($name:ident: $function:literal, $call:expr, $array:ident;)*) => {
        $(
            #[doc = concat!("`", $function, "`: [`get_array`](crate::core::model_exchange_calls::get_array).")]
            pub unsafe fn $name<M: Model>(c: $handle, values: *mut f64, n: usize) -> $status {
                use $crate::core::model_exchange_calls::{StateArray, get_array};
                unsafe { get_array::<$frontend, M>(c, ($function, $call), StateArray::$array, values, n) }
            }
        )*
    };
}
pub(crate) use state_array_getters;
