//! The native loop on two stand-in FMUs with closed-form results: a ramp y = t or a
//! parabola y = t^2 (no output derivatives) feeding an integrator x' = u that
//! interpolates its input (u + u' s + u'' s^2 / 2 over the step), the derivatives taken
//! through the source's last samples (order 1 or 2).

use std::ffi::c_void;
use std::os::raw::c_int;
use std::ptr;

use cosim_kernel::{
    Exchange, Failure, Plan, Recorder, SlopeExchange, Stepper, cosim_kernel_run, kind,
};

#[derive(Default, Clone)]
struct Fake {
    t: f64,
    x: f64,
    u: f64,
    slope: f64,
    curvature: f64,
    square: bool,
    fail_at_step: Option<u32>,
    steps: u32,
    /// Longest step taken; a longer one is discarded (fmi2Discard).
    h_max: Option<f64>,
}

fn fake<'a>(c: *mut c_void) -> &'a mut Fake {
    // SAFETY: the tests pass pointers to live Fakes.
    unsafe { &mut *(c as *mut Fake) }
}

unsafe extern "C" fn ramp_get(c: *mut c_void, _r: *const u32, _n: usize, v: *mut f64) -> c_int {
    let f = fake(c);
    // SAFETY: one value.
    unsafe { *v = if f.square { f.t * f.t } else { f.t } };
    0
}

unsafe extern "C" fn int_get(c: *mut c_void, _r: *const u32, _n: usize, v: *mut f64) -> c_int {
    // SAFETY: one value.
    unsafe { *v = fake(c).x };
    0
}

unsafe extern "C" fn int_set(c: *mut c_void, _r: *const u32, _n: usize, v: *mut f64) -> c_int {
    // SAFETY: one value.
    fake(c).u = unsafe { *v };
    0
}

unsafe extern "C" fn int_set_slope(
    c: *mut c_void,
    _r: *const u32,
    n: usize,
    o: *const i32,
    v: *mut f64,
) -> c_int {
    // SAFETY: n values and orders: one signal, orders 1..n.
    let (values, orders) = unsafe {
        (
            std::slice::from_raw_parts(v, n),
            std::slice::from_raw_parts(o, n),
        )
    };
    for (value, order) in values.iter().zip(orders) {
        match order {
            1 => fake(c).slope = *value,
            2 => fake(c).curvature = *value,
            _ => return 3,
        }
    }
    0
}

unsafe extern "C" fn step(c: *mut c_void, t: f64, h: f64, _no_set: c_int) -> c_int {
    let f = fake(c);
    if f.fail_at_step == Some(f.steps) {
        return 3;
    }
    if f.h_max.is_some_and(|m| h > m) {
        return 2;
    }
    assert!((f.t - t).abs() < 1e-12, "steps are contiguous");
    f.x += f.u * h + f.slope * h * h / 2.0 + f.curvature * h * h * h / 6.0;
    f.t = t + h;
    f.steps += 1;
    0
}

unsafe extern "C" fn get_state(c: *mut c_void, state: *mut *mut c_void) -> c_int {
    // SAFETY: a writable state pointer.
    unsafe { *state = Box::into_raw(Box::new(fake(c).clone())) as *mut c_void };
    0
}

unsafe extern "C" fn set_state(c: *mut c_void, state: *mut c_void) -> c_int {
    // SAFETY: a state get_state made.
    *fake(c) = unsafe { &*(state as *const Fake) }.clone();
    0
}

unsafe extern "C" fn free_state(_c: *mut c_void, state: *mut *mut c_void) -> c_int {
    // SAFETY: a state get_state made, freed once.
    drop(unsafe { Box::from_raw(*state as *mut Fake) });
    0
}

fn stepper(component: *mut c_void, exchanges: usize, slopes: usize) -> Stepper {
    Stepper {
        do_step: step,
        component,
        get_state: Some(get_state),
        set_state: Some(set_state),
        free_state: Some(free_state),
        first_exchange: 0,
        n_exchanges: exchanges,
        first_slope: 0,
        n_slopes: slopes,
    }
}

unsafe extern "C" fn count_discard(context: *mut c_void, _i: usize, _t: f64, _h: f64) {
    // SAFETY: the tests pass a counter.
    unsafe { *(context as *mut u32) += 1 };
}

/// Runs 10 steps of 0.1 s with derivatives of `order` through the source's samples;
/// the integrator's x per row, or the failure.
fn run(fail_at_step: Option<u32>, square: bool, order: usize) -> Result<Vec<f64>, Failure> {
    run_with(fail_at_step, square, order, None).map(|(rows, _)| rows.iter().map(|r| r[0]).collect())
}

/// As [`run`], with the integrator's longest step (two halvings allowed, no slopes
/// with a limit); per row the integrator's x and the source's value copied from the
/// exchange's buffer (a recorder without a get call), and the number of discards the
/// plan was told of.
fn run_with(
    fail_at_step: Option<u32>,
    square: bool,
    order: usize,
    h_max: Option<f64>,
) -> Result<(Vec<[f64; 2]>, u32), Failure> {
    let mut ramp = Fake {
        square,
        ..Fake::default()
    };
    let mut int = Fake {
        fail_at_step,
        h_max,
        ..Fake::default()
    };
    let mut discards = 0u32;
    let (r, i) = (
        &mut ramp as *mut Fake as *mut c_void,
        &mut int as *mut Fake as *mut c_void,
    );
    let refs = [0u32; 2];
    let orders = [1i32, 2];
    let (mut buffer, mut slopes, mut past, mut state) = ([0.0], [0.0; 2], [0.0; 2], [0.0; 3]);
    let exchange = Exchange {
        get: ramp_get,
        source: r,
        source_refs: refs.as_ptr(),
        set: int_set,
        target: i,
        target_refs: refs.as_ptr(),
        n: 1,
        buffer: buffer.as_mut_ptr(),
    };
    let slope = SlopeExchange {
        get: None,
        source: ptr::null_mut(),
        source_refs: ptr::null(),
        set: int_set_slope,
        target: i,
        target_refs: refs.as_ptr(),
        n: order,
        orders: orders.as_ptr(),
        slopes: slopes.as_mut_ptr(),
        order,
        values: buffer.as_ptr(),
        past: past.as_mut_ptr(),
        state: state.as_mut_ptr(),
    };
    let slopes_used = usize::from(h_max.is_none());
    let steppers = [stepper(r, 0, 0), stepper(i, 1, slopes_used)];
    let recorders = [
        Recorder {
            get: Some(int_get),
            component: i,
            refs: refs.as_ptr(),
            n: 1,
            column: 0,
            buffer: ptr::null(),
        },
        Recorder {
            get: None,
            component: ptr::null_mut(),
            refs: ptr::null(),
            n: 1,
            column: 1,
            buffer: buffer.as_ptr(),
        },
    ];
    let plan = Plan {
        exchanges: &exchange,
        n_exchanges: 1,
        slopes: &slope,
        n_slopes: slopes_used,
        steppers: steppers.as_ptr(),
        n_steppers: 2,
        recorders: recorders.as_ptr(),
        n_recorders: 2,
        width: 2,
        start: 0.0,
        h: 0.1,
        gauss_seidel: 0,
        halvings: 2,
        discarded: Some(count_discard),
        context: &mut discards as *mut u32 as *mut c_void,
    };
    let mut rows = vec![0.0; 22];
    let mut failure = Failure::default();
    // SAFETY: every pointer above lives until the call returns.
    let status = unsafe { cosim_kernel_run(&plan, 0, 10, 1, rows.as_mut_ptr(), &mut failure) };
    if status == 0 {
        Ok((rows.chunks(2).map(|r| [r[0], r[1]]).collect(), discards))
    } else {
        Err(failure)
    }
}

#[test]
fn history_slopes_integrate_a_ramp_exactly_after_the_first_step() {
    // Closed form: the input over step k is k h + s_k (t - t_k) with s_0 = 0 (no
    // history) and s_k = 1 after: x_k = h^2 k (k - 1) / 2 + (k - 1) h^2 / 2 for k >= 1.
    let rows = run(None, false, 1).unwrap();
    for (k, x) in rows.iter().enumerate().skip(1) {
        let k = k as f64;
        let expected = 0.01 * k * (k - 1.0) / 2.0 + (k - 1.0) * 0.01 / 2.0;
        assert!((x - expected).abs() < 1e-14, "row {k}: {x} vs {expected}");
    }
    assert!((rows[10] - 0.495).abs() < 1e-14);
}

#[test]
fn second_order_history_integrates_a_parabola_exactly_after_the_second_step() {
    // Closed form for y = t^2: step 0 holds 0 (no history; the exact integral is
    // h^3 / 3), step 1 takes the slope (h^2 - 0) / h = h and no curvature
    // (integral 3 h^3 / 2 against 7 h^3 / 3), then the parabola through the last
    // three samples is y itself: x_k = t_k^3 / 3 - (1/3 + 5/6) h^3 for k >= 2.
    let rows = run(None, true, 2).unwrap();
    for (k, x) in rows.iter().enumerate().skip(2) {
        let t = 0.1 * k as f64;
        let expected = t * t * t / 3.0 - 7.0 / 6.0 * 0.001;
        assert!((x - expected).abs() < 1e-14, "row {k}: {x} vs {expected}");
    }
}

#[test]
fn a_discarded_step_is_retried_in_halves_from_the_saved_states() {
    // Closed form: with h_max = 0.03 every 0.1 s step is discarded, then its halves;
    // the quarters (0.025 s) are taken. Sampled coupling, held input: over quarter j
    // the integrator holds u = t_j = j h / 4, so x_M = (h/4)^2 M (M - 1) / 2 after M
    // quarters: 0.4875 at M = 40. Per step one discard of the whole and two of halves.
    let (rows, discards) = run_with(None, false, 1, Some(0.03)).unwrap();
    assert!((rows[10][0] - 0.4875).abs() < 1e-14, "{}", rows[10][0]);
    assert_eq!(discards, 10 * 3);
}

#[test]
fn a_recorder_without_get_copies_the_value_exchanged_at_the_same_point() {
    // The ramp y = t (or t^2) read at t_k by the propagation after step k - 1: row k
    // holds the ramp's y, exactly what an fmi2GetReal of y would return (the ramp's
    // clock after step k - 1 is t_(k-1) + h, the plan's t_(k-1) = 0.1 (k - 1)).
    for square in [false, true] {
        let (rows, _) = run_with(None, square, 1, None).unwrap();
        for (k, row) in rows.iter().enumerate().skip(1) {
            let t = 0.1 * (k - 1) as f64 + 0.1;
            assert_eq!(row[1], if square { t * t } else { t }, "row {k}");
        }
    }
}

#[test]
fn a_failing_step_is_reported_with_its_call_fmu_status_and_step() {
    let failure = run(Some(4), false, 1).unwrap_err();
    assert!((failure.time - 0.4).abs() < 1e-15);
    let expected = Failure {
        kind: kind::DO_STEP,
        index: 1,
        status: 3,
        time: failure.time,
    };
    assert_eq!(failure, expected);
}
