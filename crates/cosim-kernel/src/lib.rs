//! The stepping loop of the Python co-simulation master (`cosim/master.py`) in native
//! code. Python prepares every FMI 2.0 call of a step once (function pointers from the
//! FMUs' libraries, instance handles, value-reference arrays, shared buffers; see
//! `cosim/native.py`) and hands this library a [`Plan`]; [`cosim_kernel_run`] then makes
//! the steps with no interpreter between the calls: per step every FMU's `fmi2DoStep`,
//! the sampled propagation at the next communication point (values, then input slopes)
//! and the recorded row. The calls and their order are those of `cosim/fastpath.py`, so
//! the results are the same bit for bit.
//!
//! A failing call stops the loop and is described by a [`Failure`]; Python raises the
//! error with the FMU's logged reason.

use std::ffi::c_void;
use std::os::raw::c_int;

mod plan;

pub use plan::{Exchange, Failure, Plan, Recorder, SlopeExchange, Stepper};

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
}

/// fmi2Warning: the highest status that lets the loop go on.
const WARNING: c_int = 1;

/// Makes the steps `from..to` of the plan: per step k, every FMU steps from
/// t_k = start + k h by h, then the inputs at t_{k+1} are propagated and row k + 1 of
/// `rows` (`width` values per row) is recorded. With `propagate_first` the inputs at
/// t_from are propagated before the first step. Returns 0, or 1 with `failure` filled.
///
/// # Safety
///
/// `plan` must point to a valid [`Plan`] whose arrays, handles and function pointers
/// are alive and match (as `cosim/native.py` builds them), `rows` must hold
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
    let result = (|| {
        if propagate_first != 0 {
            // SAFETY: as above.
            unsafe { plan.propagate(plan.time(from), from) }?;
        }
        for k in from..to {
            // SAFETY: as above.
            unsafe {
                plan.step_all(k)?;
                plan.propagate(plan.time(k + 1), k)?;
                plan.record(rows.add((k as usize + 1) * plan.width), k)?;
            }
        }
        Ok(())
    })();
    match result {
        Ok(()) => 0,
        Err(f) => {
            *failure = f;
            1
        }
    }
}

/// The sampled propagation at time `t` alone (after a plan switch or at the start).
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
    match unsafe { plan.propagate(t, 0) } {
        Ok(()) => 0,
        Err(f) => {
            *failure = f;
            1
        }
    }
}

/// An FMI call's status checked: above fmi2Warning it is the failure of `kind`.
fn check(status: c_int, kind: i32, index: usize, step: u64) -> Result<(), Failure> {
    if status > WARNING {
        Err(Failure {
            kind,
            index,
            status,
            step,
        })
    } else {
        Ok(())
    }
}

/// A null-free instance handle, as FMI functions take it.
type Handle = *mut c_void;
