//! The native loop on two stand-in FMUs with closed-form results: a ramp y = t (no
//! output derivatives) feeding an integrator x' = u that interpolates its input
//! (u + u' s over the step), the slope taken through the ramp's last two samples.

use std::ffi::c_void;
use std::os::raw::c_int;
use std::ptr;

use cosim_kernel::{
    Exchange, Failure, Plan, Recorder, SlopeExchange, Stepper, cosim_kernel_run, kind,
};

#[derive(Default)]
struct Fake {
    t: f64,
    x: f64,
    u: f64,
    slope: f64,
    fail_at_step: Option<u32>,
    steps: u32,
}

fn fake<'a>(c: *mut c_void) -> &'a mut Fake {
    // SAFETY: the tests pass pointers to live Fakes.
    unsafe { &mut *(c as *mut Fake) }
}

unsafe extern "C" fn ramp_get(c: *mut c_void, _r: *const u32, _n: usize, v: *mut f64) -> c_int {
    // SAFETY: one value.
    unsafe { *v = fake(c).t };
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
    _n: usize,
    _o: *const i32,
    v: *mut f64,
) -> c_int {
    // SAFETY: one value.
    fake(c).slope = unsafe { *v };
    0
}

unsafe extern "C" fn step(c: *mut c_void, t: f64, h: f64, _no_set: c_int) -> c_int {
    let f = fake(c);
    if f.fail_at_step == Some(f.steps) {
        return 3;
    }
    assert!((f.t - t).abs() < 1e-12, "steps are contiguous");
    f.x += f.u * h + f.slope * h * h / 2.0;
    f.t = t + h;
    f.steps += 1;
    0
}

/// Runs 10 steps of 0.1 s; the integrator's x per row, or the failure.
fn run(fail_at_step: Option<u32>) -> Result<Vec<f64>, Failure> {
    let mut ramp = Fake::default();
    let mut int = Fake {
        fail_at_step,
        ..Fake::default()
    };
    let (r, i) = (
        &mut ramp as *mut Fake as *mut c_void,
        &mut int as *mut Fake as *mut c_void,
    );
    let refs = [0u32];
    let orders = [1i32];
    let (mut buffer, mut slopes, mut previous, mut state) = ([0.0], [0.0], [0.0], [0.0; 2]);
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
        n: 1,
        orders: orders.as_ptr(),
        slopes: slopes.as_mut_ptr(),
        values: buffer.as_ptr(),
        previous: previous.as_mut_ptr(),
        state: state.as_mut_ptr(),
    };
    let steppers = [
        Stepper {
            do_step: step,
            component: r,
        },
        Stepper {
            do_step: step,
            component: i,
        },
    ];
    let recorder = Recorder {
        get: int_get,
        component: i,
        refs: refs.as_ptr(),
        n: 1,
        column: 0,
    };
    let plan = Plan {
        exchanges: &exchange,
        n_exchanges: 1,
        slopes: &slope,
        n_slopes: 1,
        steppers: steppers.as_ptr(),
        n_steppers: 2,
        recorders: &recorder,
        n_recorders: 1,
        width: 1,
        start: 0.0,
        h: 0.1,
    };
    let mut rows = vec![0.0; 11];
    let mut failure = Failure::default();
    // SAFETY: every pointer above lives until the call returns.
    let status = unsafe { cosim_kernel_run(&plan, 0, 10, 1, rows.as_mut_ptr(), &mut failure) };
    if status == 0 { Ok(rows) } else { Err(failure) }
}

#[test]
fn history_slopes_integrate_a_ramp_exactly_after_the_first_step() {
    // Closed form: the input over step k is k h + s_k (t - t_k) with s_0 = 0 (no
    // history) and s_k = 1 after: x_k = h^2 k (k - 1) / 2 + (k - 1) h^2 / 2 for k >= 1.
    let rows = run(None).unwrap();
    for (k, x) in rows.iter().enumerate().skip(1) {
        let k = k as f64;
        let expected = 0.01 * k * (k - 1.0) / 2.0 + (k - 1.0) * 0.01 / 2.0;
        assert!((x - expected).abs() < 1e-14, "row {k}: {x} vs {expected}");
    }
    assert!((rows[10] - 0.495).abs() < 1e-14);
}

#[test]
fn a_failing_step_is_reported_with_its_call_fmu_status_and_step() {
    let failure = run(Some(4)).unwrap_err();
    let expected = Failure {
        kind: kind::DO_STEP,
        index: 1,
        status: 3,
        step: 4,
    };
    assert_eq!(failure, expected);
}
