//! The prepared calls of one master ([`Plan`]) and what one step does with them.

use std::ffi::c_void;
use std::os::raw::c_int;
use std::ptr;

use crate::{DISCARD, Handle, check, kind};

/// fmi2GetReal / fmi2SetReal.
pub type Transfer = unsafe extern "C" fn(Handle, *const u32, usize, *mut f64) -> c_int;
/// fmi2GetRealOutputDerivatives / fmi2SetRealInputDerivatives.
pub type Slopes = unsafe extern "C" fn(Handle, *const u32, usize, *const i32, *mut f64) -> c_int;
/// fmi2DoStep.
pub type DoStep = unsafe extern "C" fn(Handle, f64, f64, c_int) -> c_int;
/// fmi2GetFMUstate / fmi2FreeFMUstate (the state through a pointer).
pub type StatePointer = unsafe extern "C" fn(Handle, *mut *mut c_void) -> c_int;
/// fmi2SetFMUstate.
pub type StateValue = unsafe extern "C" fn(Handle, *mut c_void) -> c_int;
/// Told of a discarded step before it is retried: (context, stepper index, t, h).
pub type Discarded = unsafe extern "C" fn(*mut c_void, usize, f64, f64);

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
/// (`robofmu.slopes.History`; `values`: the value [`Exchange`]'s buffer).
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

/// One FMU's step: fmi2DoStep, its state calls (for steps retried after a discard)
/// and, for Gauss-Seidel coupling, the ranges of its inputs' exchanges.
#[repr(C)]
pub struct Stepper {
    /// fmi2DoStep.
    pub do_step: DoStep,
    /// The instance.
    pub component: Handle,
    /// fmi2GetFMUstate (needed when the plan allows step halvings).
    pub get_state: Option<StatePointer>,
    /// fmi2SetFMUstate.
    pub set_state: Option<StateValue>,
    /// fmi2FreeFMUstate.
    pub free_state: Option<StatePointer>,
    /// First value exchange into this FMU.
    pub first_exchange: usize,
    /// Number of value exchanges into this FMU.
    pub n_exchanges: usize,
    /// First slope exchange into this FMU.
    pub first_slope: usize,
    /// Number of slope exchanges into this FMU.
    pub n_slopes: usize,
}

/// Recorded signals: read by `get` from one FMU, or (`get` None) copied from the
/// buffer of a value [`Exchange`] that read them at the same point, into columns
/// `column..column + n` of a row.
#[repr(C)]
pub struct Recorder {
    /// fmi2GetReal, or None to copy from `buffer`.
    pub get: Option<Transfer>,
    /// The instance.
    pub component: Handle,
    /// The value references.
    pub refs: *const u32,
    /// Number of values.
    pub n: usize,
    /// First column in the row.
    pub column: usize,
    /// Without `get`: the exchange buffer holding the `n` values.
    pub buffer: *const f64,
}

/// What failed: the call ([`kind`]), the index of the exchange, stepper or recorder
/// in its array, the FMI status and the (communication or retried) time.
#[repr(C)]
#[derive(Debug, Default, Clone, Copy, PartialEq)]
pub struct Failure {
    /// One of the [`kind`] constants.
    pub kind: i32,
    /// Index in the array of that kind.
    pub index: usize,
    /// The FMI status returned.
    pub status: c_int,
    /// The time of the step or propagation (s).
    pub time: f64,
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
    /// Non-zero: Gauss-Seidel coupling (each FMU's inputs set just before it steps);
    /// zero: sampled (every input set at the communication point, then every step).
    pub gauss_seidel: c_int,
    /// How many times a discarded step may be halved.
    pub halvings: u32,
    /// Told of each discarded step before it is retried (may be None).
    pub discarded: Option<Discarded>,
    /// Passed to `discarded`.
    pub context: *mut c_void,
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
        self.at(k, 1)
    }

    /// start + numerator h / denominator (a point of a halved step).
    fn at(&self, numerator: u64, denominator: u64) -> f64 {
        self.start + numerator as f64 * self.h / denominator as f64
    }

    /// The steppers.
    ///
    /// # Safety
    ///
    /// The plan's pointers are valid (see `cosim_kernel_run`).
    unsafe fn steppers(&self) -> &[Stepper] {
        // SAFETY: the caller's contract.
        unsafe { items(self.steppers, self.n_steppers) }
    }

    /// Every FMU's step from t(numerator / denominator) by h / denominator; with
    /// `inputs_set` the sampled propagation there is done already. A discarded step
    /// with halvings left is retried as two half steps from the states saved before
    /// it (every FMU rolled back), as `robofmu.master` did in Python.
    ///
    /// # Safety
    ///
    /// The plan's pointers are valid (see `cosim_kernel_run`).
    pub unsafe fn advance(
        &self,
        numerator: u64,
        denominator: u64,
        halvings_left: u32,
        inputs_set: bool,
    ) -> Result<(), Failure> {
        let t = self.at(numerator, denominator);
        let h = self.h / denominator as f64;
        // SAFETY: the caller's contract.
        let steppers = unsafe { self.steppers() };
        let mut saved = Vec::new();
        let mut result = Ok(());
        if halvings_left > 0 {
            for (i, s) in steppers.iter().enumerate() {
                let mut state = ptr::null_mut();
                let status = match s.get_state {
                    // SAFETY: a valid fmi2GetFMUstate and its instance.
                    Some(get) => unsafe { get(s.component, &mut state) },
                    None => 3,
                };
                result = check(status, kind::GET_STATE, i, t);
                if result.is_err() {
                    break;
                }
                saved.push(state);
            }
        }
        if result.is_ok() {
            let sampled = self.gauss_seidel == 0;
            // SAFETY: the caller's contract.
            result = unsafe { self.step_all(t, h, sampled && !inputs_set, halvings_left == 0) };
        }
        if let Err(f) = result
            && f.kind == kind::DO_STEP
            && f.status == DISCARD
            && saved.len() == steppers.len()
        {
            // SAFETY: the caller's contract (the callback's own).
            result = unsafe { self.retry(f, &saved, numerator, denominator, halvings_left) };
        }
        for (s, state) in steppers.iter().zip(saved.iter_mut()) {
            if let Some(free) = s.free_state {
                // SAFETY: a state this instance gave; a failure to free it loses nothing
                // the run needs (the FMU logs it).
                unsafe { free(s.component, state) };
            }
        }
        result
    }

    /// The retry of a discarded step: told, every FMU rolled back, two half steps.
    ///
    /// # Safety
    ///
    /// As [`Plan::advance`]; `saved` holds a state of every stepper.
    unsafe fn retry(
        &self,
        f: Failure,
        saved: &[*mut c_void],
        numerator: u64,
        denominator: u64,
        halvings_left: u32,
    ) -> Result<(), Failure> {
        let h = self.h / denominator as f64;
        if let Some(told) = self.discarded {
            // SAFETY: the caller's callback and context.
            unsafe { told(self.context, f.index, f.time, h) };
        }
        // SAFETY: the caller's contract.
        for (i, (s, state)) in unsafe { self.steppers() }.iter().zip(saved).enumerate() {
            let status = match s.set_state {
                // SAFETY: a valid fmi2SetFMUstate, its instance and a state it gave.
                Some(set) => unsafe { set(s.component, *state) },
                None => 3,
            };
            check(status, kind::SET_STATE, i, f.time)?;
        }
        let (n, d) = (2 * numerator, 2 * denominator);
        // SAFETY: as above.
        unsafe {
            self.advance(n, d, halvings_left - 1, false)?;
            self.advance(n + 1, d, halvings_left - 1, false)
        }
    }

    /// Every FMU's step from t by h, in order: the sampled propagation first when
    /// `propagate`, with Gauss-Seidel coupling each FMU's inputs just before its step.
    /// `final_step`: no state from before t will be set again (fmi2DoStep's
    /// noSetFMUStatePriorToCurrentPoint; false while the step may be retried).
    ///
    /// # Safety
    ///
    /// As [`Plan::advance`].
    unsafe fn step_all(
        &self,
        t: f64,
        h: f64,
        propagate: bool,
        final_step: bool,
    ) -> Result<(), Failure> {
        if propagate {
            // SAFETY: the caller's contract.
            unsafe { self.propagate(t) }?;
        }
        // SAFETY: the caller's contract.
        for (i, s) in unsafe { self.steppers() }.iter().enumerate() {
            if self.gauss_seidel != 0 {
                // SAFETY: as above.
                unsafe { self.inputs_of(s, t) }?;
            }
            // SAFETY: a valid fmi2DoStep and its instance.
            check(
                unsafe { (s.do_step)(s.component, t, h, c_int::from(final_step)) },
                kind::DO_STEP,
                i,
                t,
            )?;
        }
        Ok(())
    }

    /// The value exchanges, then the slope exchanges, into one FMU (at time `t`).
    ///
    /// # Safety
    ///
    /// As [`Plan::advance`]; the stepper's ranges lie within the plan's arrays.
    unsafe fn inputs_of(&self, s: &Stepper, t: f64) -> Result<(), Failure> {
        // SAFETY: the caller's contract.
        unsafe {
            self.exchange(s.first_exchange..s.first_exchange + s.n_exchanges, t)?;
            self.pass_slopes(s.first_slope..s.first_slope + s.n_slopes, t)
        }
    }

    /// The value exchanges `range`.
    ///
    /// # Safety
    ///
    /// As [`Plan::inputs_of`].
    pub(crate) unsafe fn exchange(
        &self,
        range: std::ops::Range<usize>,
        t: f64,
    ) -> Result<(), Failure> {
        // SAFETY: the caller's contract.
        let all = unsafe { items(self.exchanges, self.n_exchanges) };
        for i in range {
            let e = &all[i];
            // SAFETY: valid functions, instances and arrays of n values.
            unsafe {
                check(
                    (e.get)(e.source, e.source_refs, e.n, e.buffer),
                    kind::GET,
                    i,
                    t,
                )?;
                check(
                    (e.set)(e.target, e.target_refs, e.n, e.buffer),
                    kind::SET,
                    i,
                    t,
                )?;
            }
        }
        Ok(())
    }

    /// The slope exchanges `range` at `t`.
    ///
    /// # Safety
    ///
    /// As [`Plan::inputs_of`].
    unsafe fn pass_slopes(&self, range: std::ops::Range<usize>, t: f64) -> Result<(), Failure> {
        // SAFETY: the caller's contract.
        let all = unsafe { items(self.slopes, self.n_slopes) };
        for i in range {
            // SAFETY: as above.
            unsafe { all[i].pass(t, i) }?;
        }
        Ok(())
    }

    /// The sampled propagation at `t`: every value exchange, then every slope exchange.
    ///
    /// # Safety
    ///
    /// As [`Plan::advance`].
    pub unsafe fn propagate(&self, t: f64) -> Result<(), Failure> {
        // SAFETY: the caller's contract.
        unsafe {
            self.exchange(0..self.n_exchanges, t)?;
            self.pass_slopes(0..self.n_slopes, t)
        }
    }

    /// Row `row` of the recorded signals.
    ///
    /// # Safety
    ///
    /// As [`Plan::advance`]; `row` holds `width` values.
    pub unsafe fn record(&self, row: *mut f64, t: f64) -> Result<(), Failure> {
        // SAFETY: the caller's contract.
        for (i, r) in unsafe { items(self.recorders, self.n_recorders) }
            .iter()
            .enumerate()
        {
            match r.get {
                // SAFETY: the recorder's columns lie within the row.
                Some(get) => {
                    let status = unsafe { get(r.component, r.refs, r.n, row.add(r.column)) };
                    check(status, kind::RECORD, i, t)?;
                }
                // SAFETY: the buffer holds n values; the columns lie within the row.
                None => unsafe { ptr::copy_nonoverlapping(r.buffer, row.add(r.column), r.n) },
            }
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
    unsafe fn pass(&self, t: f64, i: usize) -> Result<(), Failure> {
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
                check(status, kind::GET_SLOPES, i, t)?;
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
        check(status, kind::SET_SLOPES, i, t)
    }

    /// The derivatives at `t` of the polynomial through the last points (Newton's
    /// divided differences; as `robofmu.slopes.History.derivatives`, operation for
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
