//! Behaviour of the pairs against closed-form solutions.

use super::*;
use nalgebra::{Vector1, Vector2};
use std::f64::consts::TAU;

/// Settings that take `steps` equal steps over `span`: the first step is `span/steps`,
/// the step ratio is pinned to 1 and the tolerance is so loose that every step passes.
fn fixed(span: f64, steps: u32) -> Settings {
    let h = span / f64::from(steps);
    Settings {
        rtol: 1e6,
        atol: 1e6,
        safety: 1.0,
        beta: 0.0,
        fac_min: 1.0,
        fac_max: 1.0,
        h_max: h,
        h_initial: h,
        max_steps: 10 * steps,
    }
}

/// x'' = -(2 pi)^2 x from x = 1, x' = 0: x(t) = cos(2 pi t), x'(t) = -2 pi sin(2 pi t).
fn oscillator(_t: f64, y: &Vector2<f64>, dy: &mut Vector2<f64>) {
    dy[0] = y[1];
    dy[1] = -TAU * TAU * y[0];
}

fn oscillator_error(t: f64, y: &Vector2<f64>) -> f64 {
    (y[0] - (TAU * t).cos())
        .abs()
        .max((y[1] + TAU * (TAU * t).sin()).abs() / TAU)
}

type Integrator = fn(
    fn(f64, &Vector2<f64>, &mut Vector2<f64>),
    f64,
    f64,
    Vector2<f64>,
    &Settings,
) -> Result<Solution<nalgebra::U2>, OdeError>;

/// Global errors at t = 1 (one period) with `steps`, 2 `steps`, 4 `steps` fixed steps.
fn halving_errors(integrate: Integrator, steps: u32) -> [f64; 3] {
    [1, 2, 4].map(|m| {
        let s = integrate(
            oscillator,
            0.0,
            1.0,
            Vector2::new(1.0, 0.0),
            &fixed(1.0, steps * m),
        )
        .unwrap();
        assert_eq!(s.stats.accepted, steps * m);
        assert_eq!(s.stats.rejected, 0);
        oscillator_error(1.0, &s.y)
    })
}

#[test]
fn dopri5_converges_with_order_five() {
    // Truth: the closed-form oscillator; a fifth-order method's global error falls by
    // 2^5 = 32 per halving of the step once h is small.
    let e = halving_errors(|f, a, b, y, s| dopri5(f, a, b, y, s), 40);
    let ratios = [e[0] / e[1], e[1] / e[2]];
    println!("errors {e:?}, ratios {ratios:?}");
    for r in ratios {
        assert!((r / 32.0 - 1.0).abs() < 0.1, "ratio {r}");
    }
}

#[test]
fn dop853_converges_with_order_eight() {
    // Truth: as above with 2^8 = 256 per halving for the eighth-order method.
    let e = halving_errors(|f, a, b, y, s| dop853(f, a, b, y, s), 10);
    let ratios = [e[0] / e[1], e[1] / e[2]];
    println!("errors {e:?}, ratios {ratios:?}");
    for r in ratios {
        assert!((r / 256.0 - 1.0).abs() < 0.15, "ratio {r}");
    }
}

#[test]
fn adaptive_steps_meet_the_tolerance() {
    // Truth: the closed-form oscillator over ten periods. The local error per step is
    // kept below the tolerance, so the global error after ~100-1000 steps stays within
    // a small multiple of it, and falls as the tolerance does.
    for (name, integrate) in [
        (
            "dopri5",
            (|f, a, b, y, s| dopri5(f, a, b, y, s)) as Integrator,
        ),
        (
            "dop853",
            (|f, a, b, y, s| dop853(f, a, b, y, s)) as Integrator,
        ),
    ] {
        let mut previous = f64::INFINITY;
        for tol in [1e-5, 1e-8, 1e-11] {
            let settings = if name == "dopri5" {
                Settings::dopri5(tol, 1.0)
            } else {
                Settings::dop853(tol, 1.0)
            };
            let s = integrate(oscillator, 0.0, 10.0, Vector2::new(1.0, 0.0), &settings).unwrap();
            let error = oscillator_error(10.0, &s.y);
            println!("{name} tol {tol:.0e}: error {error:.2e}, {:?}", s.stats);
            assert_eq!(s.x, 10.0);
            assert!(error < 20.0 * tol, "{name} tol {tol}: error {error}");
            assert!(error < previous);
            previous = error;
        }
    }
}

#[test]
fn a_nan_stage_rejects_the_step() {
    // Truth: y' = -y, y(0) = 1 has y(1) = e^-1. The right-hand side fails (NaN) on its
    // first three calls past x = 0.3, as a model losing its assembly in a trial stage
    // would; each such step is rejected and retried with a smaller one, and the
    // result still meets the tolerance.
    for pair in ["dopri5", "dop853"] {
        let mut failures = 0;
        let f = |x: f64, y: &Vector1<f64>, dy: &mut Vector1<f64>| {
            if x > 0.3 && failures < 3 {
                failures += 1;
                dy[0] = f64::NAN;
            } else {
                dy[0] = -y[0];
            }
        };
        let tol = 1e-9;
        let s = if pair == "dopri5" {
            let settings = Settings::dopri5(tol, 0.1);
            dopri5(f, 0.0, 1.0, Vector1::new(1.0), &settings)
        } else {
            let settings = Settings::dop853(tol, 0.1);
            dop853(f, 0.0, 1.0, Vector1::new(1.0), &settings)
        };
        let s = s.unwrap();
        let error = (s.y[0] - (-1.0f64).exp()).abs();
        println!("{pair}: {:?}, error {error:.1e}", s.stats);
        assert!(s.stats.rejected >= 1, "{pair}");
        assert!(
            s.y[0].is_finite() && error < 10.0 * tol,
            "{pair}: error {error}"
        );
    }
}

#[test]
fn a_rejection_shrinks_the_step_by_fac_min() {
    // Truth: Hairer's control after a NaN error (err^alpha is NaN, the clamp gives
    // its bound): h_new = h * fac_min; the next accepted step may not grow past it.
    let settings = Settings::dopri5(1e-6, 1.0);
    let mut control = Control::new(&settings, 0.17, 1.0);
    let verdict = control.judge(f64::NAN, 0.5);
    assert!(!verdict.accepted);
    assert_eq!(verdict.h_new, 0.5 / (1.0 / 0.2));
    let verdict = control.judge(1e-12, 0.1);
    assert!(verdict.accepted);
    assert_eq!(verdict.h_new, 0.1, "no growth right after a rejection");
    let verdict = control.judge(1e-12, 0.1);
    assert_eq!(verdict.h_new, 0.1 * 10.0, "then growth up to fac_max");
}

#[test]
fn a_right_hand_side_that_keeps_failing_stops_with_an_error() {
    // Truth: no step can pass x = 0.5 when every evaluation there is NaN: the step
    // shrinks until it underflows or the attempts run out; no NaN state comes back.
    let f = |x: f64, y: &Vector1<f64>, dy: &mut Vector1<f64>| {
        dy[0] = if x > 0.5 { f64::NAN } else { -y[0] };
    };
    let settings = Settings {
        max_steps: 2000,
        ..Settings::dopri5(1e-8, 0.1)
    };
    let e = dopri5(f, 0.0, 1.0, Vector1::new(1.0), &settings).unwrap_err();
    println!("{e}");
    match e {
        OdeError::StepSizeUnderflow { x } | OdeError::TooManySteps { x, .. } => {
            assert!(x <= 0.5 && x > 0.49, "stopped at {x}");
        }
    }
    let e = dop853(f, 0.0, 1.0, Vector1::new(1.0), &Settings::dop853(1e-8, 0.1)).unwrap_err();
    assert!(matches!(
        e,
        OdeError::StepSizeUnderflow { .. } | OdeError::TooManySteps { .. }
    ));
}

#[test]
fn backward_integration_and_an_empty_interval() {
    // Truth: y' = y from y(1) = e back to x = 0 gives y(0) = 1; an empty interval
    // returns the start unchanged without evaluating f.
    let f = |_x: f64, y: &Vector1<f64>, dy: &mut Vector1<f64>| dy[0] = y[0];
    let e = std::f64::consts::E;
    let s = dop853(f, 1.0, 0.0, Vector1::new(e), &Settings::dop853(1e-12, 1.0)).unwrap();
    assert_eq!(s.x, 0.0);
    assert!((s.y[0] - 1.0).abs() < 1e-11, "{}", s.y[0]);
    let s = dopri5(f, 2.0, 2.0, Vector1::new(3.0), &Settings::dopri5(1e-8, 1.0)).unwrap();
    assert_eq!((s.y[0], s.stats.evaluations), (3.0, 0));
}
