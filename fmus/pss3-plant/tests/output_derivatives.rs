//! Pss3Plant's output derivatives (fmi2GetRealOutputDerivatives) in Co-Simulation: of
//! every Real output, orders 1 and 2 (maxOutputDerivativeOrder = 2), against central
//! differences of the outputs along a fine CS trajectory (the integrator's, an
//! independent path to the same numbers).

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pss3_plant_fmu::Pss3Plant;

type H = Host<Pss3Plant>;

/// Every Real output of the plant, from its variable table.
fn real_outputs() -> Vec<String> {
    robofmu_fmi_testing::real_outputs::<Pss3Plant>()
}

/// A tilted, moving plant driven by constant actuator forces, with a tight integrator
/// tolerance. By t = 0.15 s actuator 1 has run 0.02 mm into its upper end stop (the
/// stop spring acts; the derivatives hold there as well).
fn moving_plant() -> H {
    let h = H::with_logging(FMI2_CO_SIMULATION, false);
    h.set_vector("theta0", [0.05, -0.04, 2.35]);
    h.set_vector("omega0", [0.3, -0.5, 0.8]);
    h.set_vector("actuatorForce", [20.0, -5.0, 12.0]);
    assert_eq!(h.set_real("tolerance", 1e-12), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    h
}

/// One output's derivative of one order at one point of the trajectory, with its
/// central differences of steps delta (fine) and 2 delta (coarse).
struct Sample {
    name: String,
    order: i32,
    derivative: f64,
    fine: f64,
    coarse: f64,
    /// 1 + |value at the point|.
    scale: f64,
}

impl Sample {
    /// The error of the derivative against the difference of step delta.
    fn error(&self) -> f64 {
        (self.derivative - self.fine).abs()
    }

    /// What the difference of step delta may be off by: its truncation error, about
    /// |fine - coarse| / 3 (both are O(delta^2)), with a safety factor of 3, plus the
    /// error of the values (the integrator's, tolerance 1e-12, taken as 1e-11
    /// relative) amplified by the difference (1 / delta, 4 / delta^2).
    fn tolerance(&self, delta: f64) -> f64 {
        let amplification = if self.order == 1 {
            1.0 / delta
        } else {
            4.0 / (delta * delta)
        };
        (self.fine - self.coarse).abs() + 1e-11 * self.scale * amplification
    }
}

/// Central difference of order 1 or 2 from the values at t - step, t, t + step.
fn difference(order: i32, minus: f64, at: f64, plus: f64, step: f64) -> f64 {
    if order == 1 {
        (plus - minus) / (2.0 * step)
    } else {
        (plus - 2.0 * at + minus) / (step * step)
    }
}

/// For every (output, order) and each of four points t of the CS trajectory, the
/// derivative at t and the differences of the values at t - 2 delta ..= t + 2 delta.
fn samples(delta: f64) -> Vec<Sample> {
    let h = moving_plant();
    let names = real_outputs();
    let refs: Vec<&str> = names.iter().map(String::as_str).collect();
    let values = |h: &H| -> Vec<f64> { refs.iter().map(|n| h.real(n)).collect() };
    let mut out = Vec::new();
    let mut t = 0.0;
    for point in [0.02, 0.05, 0.1, 0.15] {
        assert_eq!(h.step(t, point - 2.0 * delta - t), Fmi2Status::Ok);
        let mut y = Vec::new();
        let mut derivatives = Vec::new();
        for k in -2..=2 {
            y.push(values(&h));
            if k == 0 {
                for order in [1, 2] {
                    let (s, d) = h.output_derivatives(&refs, &vec![order; refs.len()]);
                    assert_eq!(s, Fmi2Status::Ok, "{}", h.last_message());
                    derivatives.push((order, d));
                }
            }
            if k < 2 {
                assert_eq!(h.step(point + k as f64 * delta, delta), Fmi2Status::Ok);
            }
        }
        t = point + 2.0 * delta;
        for (order, d) in &derivatives {
            for (i, name) in names.iter().enumerate() {
                let at = |k: usize| y[k][i];
                out.push(Sample {
                    name: format!("{name} at t = {point} s"),
                    order: *order,
                    derivative: d[i],
                    fine: difference(*order, at(1), at(2), at(3), delta),
                    coarse: difference(*order, at(0), at(2), at(4), 2.0 * delta),
                    scale: 1.0 + at(2).abs(),
                });
            }
        }
    }
    out
}

#[test]
fn every_output_derivative_matches_central_differences_along_the_trajectory() {
    // Expected: central differences over CS steps of delta (order 1 with delta = 1e-5 s,
    // order 2 with delta = 1e-4 s: a smaller delta makes the second difference
    // round-off bound). Their truncation errors delta^2/6 |y'''| and delta^2/12
    // |y''''| dominate and are estimated from the difference of step 2 delta (see
    // `Sample::tolerance`).
    let mut checked = 0;
    for (delta, order) in [(1e-5, 1), (1e-4, 2)] {
        for s in samples(delta).into_iter().filter(|s| s.order == order) {
            let (error, tolerance) = (s.error(), s.tolerance(delta));
            println!(
                "{} order {order}: {:.6e}, error {error:.1e}, tolerance {tolerance:.1e}",
                s.name, s.derivative
            );
            assert!(
                error <= tolerance,
                "order {order} of {} is off by {error:e} > {tolerance:e}",
                s.name
            );
            checked += 1;
        }
    }
    // 9 vector outputs and 7 scalar ones, 4 points, 2 orders.
    assert_eq!(checked, (9 * 3 + 7) * 4 * 2);
}
