//! The stepping loop of the co-simulation master (`robofmu/master.py`), the only one it
//! has, in native code. Python prepares every call of a step once (`robofmu/loop.py`):
//! an FMI 2.0 instance's own functions (function pointers from its library, instance
//! handles, value-reference arrays, shared buffers), or for any other instance (FMI
//! 3.0, a stand-in) a C callback into its Python adapter with the same signature; it
//! hands this library a [`Plan`] and [`cosim_kernel_run`] makes the steps with no
//! interpreter between native calls: per step every FMU's `fmi2DoStep` (sampled or
//! Gauss-Seidel coupling, a discarded step retried as two half steps from the saved
//! FMU states), the sampled propagation at the next communication point (values, then
//! input derivatives of orders 1..2) and the recorded row.
//!
//! A failing call stops the loop and is described by a [`Failure`]; Python raises the
//! error with the FMU's logged reason.

use std::ffi::c_void;
use std::os::raw::c_int;

mod plan;

pub use plan::{
    Discarded, DoStep, Exchange, Failure, Plan, Recorder, SlopeExchange, Slopes, StatePointer,
    StateValue, Stepper, Transfer,
};

/// `Failure::kind` values: which call failed.
pub mod kind {
    /// fmi2GetReal of a connected source.
    pub const GET: i32 = 0;
    /// fmi2SetReal of a connected target.
    pub const SET: i32 = 1;
    /// fmi2DoStep.
    pub const DO_STEP: i32 = 2;
    /// fmi2GetRealOutputDerivatives of a source.
    pub const GET_SLOPES: i32 = 3;
    /// fmi2SetRealInputDerivatives of a target.
    pub const SET_SLOPES: i32 = 4;
    /// fmi2GetReal of the recorded signals.
    pub const RECORD: i32 = 5;
    /// fmi2GetFMUstate before a step that may be retried.
    pub const GET_STATE: i32 = 6;
    /// fmi2SetFMUstate: the rollback of a discarded step.
    pub const SET_STATE: i32 = 7;
}

/// fmi2Warning: the highest status that lets the loop go on.
const WARNING: c_int = 1;
/// fmi2Discard: a step the FMU refused (retried when the plan allows halvings).
const DISCARD: c_int = 2;

/// Makes the steps `from..to` of the plan: per step k, every FMU steps from
/// t_k = start + k h by h (retried in halves after a discard, as the plan allows), then
/// with sampled coupling the inputs at t_{k+1} are propagated, and row k + 1 of `rows`
/// (`width` values per row) is recorded. With `propagate_first` (sampled coupling) the
/// inputs at t_from are propagated before the first step. Returns 0, or 1 with
/// `failure` filled.
///
/// # Safety
///
/// `plan` must point to a valid [`Plan`] whose arrays, handles and function pointers
/// are alive and match (as `robofmu/loop.py` builds them), `rows` must hold
/// `(to + 1) * width` values and `failure` must be writable.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn cosim_kernel_run(
    plan: *const Plan,
    from: u64,
    to: u64,
    propagate_first: c_int,
    rows: *mut f64,
    failure: *mut Failure,
) -> c_int {
    // SAFETY: the caller's contract above.
    let (plan, failure) = unsafe { (&*plan, &mut *failure) };
    let sampled = plan.gauss_seidel == 0;
    let result = (|| {
        for k in from..to {
            // SAFETY: as above.
            unsafe {
                plan.advance(k, 1, plan.halvings, k > from || propagate_first == 0)?;
                let t = plan.time(k + 1);
                if sampled {
                    plan.propagate(t)?;
                }
                plan.record(rows.add((k as usize + 1) * plan.width), t)?;
            }
        }
        Ok(())
    })();
    finish(result, failure)
}

/// The sampled propagation at time `t` alone (at the start).
///
/// # Safety
///
/// As [`cosim_kernel_run`].
#[unsafe(no_mangle)]
pub unsafe extern "C" fn cosim_kernel_propagate(
    plan: *const Plan,
    t: f64,
    failure: *mut Failure,
) -> c_int {
    // SAFETY: the caller's contract above.
    let (plan, failure) = unsafe { (&*plan, &mut *failure) };
    // SAFETY: as above.
    finish(unsafe { plan.propagate(t) }, failure)
}

/// The input values of FMU `stepper` from its sources (no derivatives): the
/// consistent inputs at the start, FMU by FMU in order, in initialization mode.
///
/// # Safety
///
/// As [`cosim_kernel_run`]; `stepper` < the plan's number of steppers.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn cosim_kernel_inputs(
    plan: *const Plan,
    stepper: usize,
    t: f64,
    failure: *mut Failure,
) -> c_int {
    // SAFETY: the caller's contract above.
    let (plan, failure) = unsafe { (&*plan, &mut *failure) };
    // SAFETY: as above.
    let s = unsafe { &*plan.steppers.add(stepper) };
    // SAFETY: as above.
    finish(
        unsafe { plan.exchange(s.first_exchange..s.first_exchange + s.n_exchanges, t) },
        failure,
    )
}

/// The recorded signals now into `row` (`width` values): row 0, at the start.
///
/// # Safety
///
/// As [`cosim_kernel_run`]; `row` holds `width` values.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn cosim_kernel_record(
    plan: *const Plan,
    row: *mut f64,
    t: f64,
    failure: *mut Failure,
) -> c_int {
    // SAFETY: the caller's contract above.
    let (plan, failure) = unsafe { (&*plan, &mut *failure) };
    // SAFETY: as above.
    finish(unsafe { plan.record(row, t) }, failure)
}

/// 0, or 1 with the failure written.
fn finish(result: Result<(), Failure>, failure: &mut Failure) -> c_int {
    match result {
        Ok(()) => 0,
        Err(f) => {
            *failure = f;
            1
        }
    }
}

/// An FMI call's status checked: above fmi2Warning it is the failure of `kind`.
fn check(status: c_int, kind: i32, index: usize, time: f64) -> Result<(), Failure> {
    if status > WARNING {
        Err(Failure {
            kind,
            index,
            status,
            time,
        })
    } else {
        Ok(())
    }
}

/// A null-free instance handle, as FMI functions take it.
type Handle = *mut c_void;
