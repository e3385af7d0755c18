//! The prepared calls of one master ([`Plan`]) and what one step does with them.

use std::os::raw::c_int;

use crate::{Handle, check, kind};

/// fmi2GetReal / fmi2SetReal.
pub type Transfer = unsafe extern "C" fn(Handle, *const u32, usize, *mut f64) -> c_int;
/// fmi2GetRealOutputDerivatives / fmi2SetRealInputDerivatives.
pub type Slopes = unsafe extern "C" fn(Handle, *const u32, usize, *const i32, *mut f64) -> c_int;
/// fmi2DoStep.
pub type DoStep = unsafe extern "C" fn(Handle, f64, f64, c_int) -> c_int;

/// One connected pair: the source's values read into `buffer`, written to the target.
#[repr(C)]
pub struct Exchange {
    /// fmi2GetReal of the source.
    pub get: Transfer,
    /// The source instance.
    pub source: Handle,
    /// The source's value references.
    pub source_refs: *const u32,
    /// fmi2SetReal of the target.
    pub set: Transfer,
    /// The target instance.
    pub target: Handle,
    /// The target's value references.
    pub target_refs: *const u32,
    /// Number of values.
    pub n: usize,
    /// The values (shared by the two calls).
    pub buffer: *mut f64,
}

/// The input derivatives of one connected pair (orders 1..k, all of order 1 first):
/// the source's output derivatives (`get` set) or, when the source gives none, the
/// derivatives through the pair's values at the last communication points
/// (`cosim.slopes.History`; `values`: the value [`Exchange`]'s buffer).
#[repr(C)]
pub struct SlopeExchange {
    /// fmi2GetRealOutputDerivatives of the source, or None for the history.
    pub get: Option<Slopes>,
    /// The source instance.
    pub source: Handle,
    /// The source's value references (repeated for each order).
    pub source_refs: *const u32,
    /// fmi2SetRealInputDerivatives of the target.
    pub set: Slopes,
    /// The target instance.
    pub target: Handle,
    /// The target's value references (repeated for each order).
    pub target_refs: *const u32,
    /// Number of values passed: signals times orders.
    pub n: usize,
    /// Derivative order of each value passed.
    pub orders: *const i32,
    /// The derivatives passed (order rows of n / order values).
    pub slopes: *mut f64,
    /// History: its order k (1 or 2; 0 for served derivatives).
    pub order: usize,
    /// History: the values just propagated (n / k).
    pub values: *const f64,
    /// History: the values at the last k points, newest first (n values).
    pub past: *mut f64,
    /// History: [points known (at most k), their times newest first] (k + 1 values).
    pub state: *mut f64,
}

/// One FMU's fmi2DoStep.
#[repr(C)]
pub struct Stepper {
    /// fmi2DoStep.
    pub do_step: DoStep,
    /// The instance.
    pub component: Handle,
}

/// The recorded signals of one FMU: read into columns `column..column + n` of a row.
#[repr(C)]
pub struct Recorder {
    /// fmi2GetReal.
    pub get: Transfer,
    /// The instance.
    pub component: Handle,
    /// The value references.
    pub refs: *const u32,
    /// Number of values.
    pub n: usize,
    /// First column in the row.
    pub column: usize,
}

/// What failed: the call ([`kind`]), the index of the exchange, stepper or recorder
/// in its array, the FMI status and the step.
#[repr(C)]
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct Failure {
    /// One of the [`kind`] constants.
    pub kind: i32,
    /// Index in the array of that kind.
    pub index: usize,
    /// The FMI status returned.
    pub status: c_int,
    /// The step k.
    pub step: u64,
}

/// The prepared calls of one master, in the scenario's order.
#[repr(C)]
pub struct Plan {
    /// Value exchanges, in order of their targets.
    pub exchanges: *const Exchange,
    /// Their number.
    pub n_exchanges: usize,
    /// Slope exchanges, in order of their targets.
    pub slopes: *const SlopeExchange,
    /// Their number.
    pub n_slopes: usize,
    /// The FMUs' steps, in order.
    pub steppers: *const Stepper,
    /// Their number.
    pub n_steppers: usize,
    /// The recorders.
    pub recorders: *const Recorder,
    /// Their number.
    pub n_recorders: usize,
    /// Values per recorded row.
    pub width: usize,
    /// Start time (s).
    pub start: f64,
    /// Communication step (s).
    pub h: f64,
}

/// A slice from a pointer and a length (empty for a null pointer).
///
/// # Safety
///
/// A non-null `p` must point to `n` valid values.
unsafe fn items<'a, T>(p: *const T, n: usize) -> &'a [T] {
    if p.is_null() || n == 0 {
        &[]
    } else {
        // SAFETY: the caller's contract.
        unsafe { std::slice::from_raw_parts(p, n) }
    }
}

impl Plan {
    /// t_k = start + k h, as the Python master computes it.
    pub fn time(&self, k: u64) -> f64 {
        self.start + k as f64 * self.h
    }

    /// Every FMU's step k.
    ///
    /// # Safety
    ///
    /// The plan's pointers are valid (see `cosim_kernel_run`).
    pub unsafe fn step_all(&self, k: u64) -> Result<(), Failure> {
        let t = self.time(k);
        // SAFETY: the caller's contract.
        for (i, s) in unsafe { items(self.steppers, self.n_steppers) }
            .iter()
            .enumerate()
        {
            // SAFETY: a valid fmi2DoStep and its instance.
            check(
                unsafe { (s.do_step)(s.component, t, self.h, 1) },
                kind::DO_STEP,
                i,
                k,
            )?;
        }
        Ok(())
    }

    /// The sampled propagation at `t`: every value exchange, then every slope exchange.
    ///
    /// # Safety
    ///
    /// As [`Plan::step_all`].
    pub unsafe fn propagate(&self, t: f64, k: u64) -> Result<(), Failure> {
        // SAFETY: the caller's contract.
        for (i, e) in unsafe { items(self.exchanges, self.n_exchanges) }
            .iter()
            .enumerate()
        {
            // SAFETY: valid functions, instances and arrays of n values.
            unsafe {
                check(
                    (e.get)(e.source, e.source_refs, e.n, e.buffer),
                    kind::GET,
                    i,
                    k,
                )?;
                check(
                    (e.set)(e.target, e.target_refs, e.n, e.buffer),
                    kind::SET,
                    i,
                    k,
                )?;
            }
        }
        // SAFETY: the caller's contract.
        for (i, s) in unsafe { items(self.slopes, self.n_slopes) }
            .iter()
            .enumerate()
        {
            // SAFETY: as above.
            unsafe { s.pass(t, i, k) }?;
        }
        Ok(())
    }

    /// Row `row` of the recorded signals.
    ///
    /// # Safety
    ///
    /// As [`Plan::step_all`]; `row` holds `width` values.
    pub unsafe fn record(&self, row: *mut f64, k: u64) -> Result<(), Failure> {
        // SAFETY: the caller's contract.
        for (i, r) in unsafe { items(self.recorders, self.n_recorders) }
            .iter()
            .enumerate()
        {
            // SAFETY: the recorder's columns lie within the row.
            let status = unsafe { (r.get)(r.component, r.refs, r.n, row.add(r.column)) };
            check(status, kind::RECORD, i, k)?;
        }
        Ok(())
    }
}

impl SlopeExchange {
    /// The slopes at `t` passed to the target.
    ///
    /// # Safety
    ///
    /// Valid functions, instances and arrays of `n` values (`state`: 2 values).
    unsafe fn pass(&self, t: f64, i: usize, k: u64) -> Result<(), Failure> {
        match self.get {
            // SAFETY: the caller's contract.
            Some(get) => unsafe {
                let status = get(
                    self.source,
                    self.source_refs,
                    self.n,
                    self.orders,
                    self.slopes,
                );
                check(status, kind::GET_SLOPES, i, k)?;
            },
            // SAFETY: the caller's contract.
            None => unsafe { self.history(t) },
        }
        // SAFETY: the caller's contract.
        let status = unsafe {
            (self.set)(
                self.target,
                self.target_refs,
                self.n,
                self.orders,
                self.slopes,
            )
        };
        check(status, kind::SET_SLOPES, i, k)
    }

    /// The derivatives at `t` of the polynomial through the last points (Newton's
    /// divided differences; as `cosim.slopes.History.derivatives`, operation for
    /// operation): zero at the first point, the last derivatives at a time already seen.
    ///
    /// # Safety
    ///
    /// As [`SlopeExchange::pass`].
    unsafe fn history(&self, t: f64) {
        let order = self.order;
        let m = self.n / order;
        // SAFETY: the caller's contract.
        let (values, past, out, state) = unsafe {
            (
                std::slice::from_raw_parts(self.values, m),
                std::slice::from_raw_parts_mut(self.past, self.n),
                std::slice::from_raw_parts_mut(self.slopes, self.n),
                std::slice::from_raw_parts_mut(self.state, order + 1),
            )
        };
        let count = state[0] as usize;
        if count > 0 && t <= state[1] {
            return;
        }
        out.fill(0.0);
        if count >= 1 {
            let (d, second) = out.split_at_mut(m);
            for i in 0..m {
                let d1 = (values[i] - past[i]) / (t - state[1]);
                d[i] = d1;
                if order >= 2 && count >= 2 {
                    let back = (past[i] - past[m + i]) / (state[1] - state[2]);
                    let d2 = (d1 - back) / (t - state[2]);
                    d[i] = d1 + d2 * (t - state[1]);
                    second[i] = 2.0 * d2;
                }
            }
        }
        past.copy_within(0..self.n - m, m);
        state.copy_within(1..order, 2);
        past[..m].copy_from_slice(values);
        state[1] = t;
        state[0] = (count + 1).min(order) as f64;
    }
}
