//! Pss3Plant's output derivatives (fmi2GetRealOutputDerivatives) in Co-Simulation:
//! the exact ones against central differences of the outputs along a fine CS
//! trajectory (the integrator's, an independent path), and the refusal of the others.

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pss3_plant_fmu::Pss3Plant;

type H = Host<Pss3Plant>;

/// (output, order) pairs the plant provides, each an exact expression of the state.
fn provided() -> Vec<(String, i32)> {
    let mut pairs = Vec::new();
    for i in 1..=3 {
        for order in [1, 2] {
            pairs.push((format!("theta[{i}]"), order));
            pairs.push((format!("l[{i}]"), order));
        }
        for name in ["thetaDot", "lDot", "omega"] {
            pairs.push((format!("{name}[{i}]"), 1));
        }
    }
    for name in ["yaw", "pitch", "roll"] {
        pairs.push((name.to_string(), 1));
        pairs.push((name.to_string(), 2));
    }
    pairs
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

/// Largest error of each provided derivative against central differences (step
/// `delta`) of its output along the CS trajectory, relative to 1 + |difference|.
fn largest_difference_errors(delta: f64) -> Vec<((String, i32), f64)> {
    let h = moving_plant();
    let pairs = provided();
    let names: Vec<&str> = pairs.iter().map(|(n, _)| n.as_str()).collect();
    let orders: Vec<i32> = pairs.iter().map(|(_, o)| *o).collect();
    let values = |h: &H| -> Vec<f64> { names.iter().map(|n| h.real(n)).collect() };
    let mut worst = vec![0.0f64; pairs.len()];
    let mut t = 0.0;
    for point in [0.02, 0.05, 0.1, 0.15] {
        assert_eq!(h.step(t, point - delta - t), Fmi2Status::Ok);
        let before = values(&h);
        assert_eq!(h.step(point - delta, delta), Fmi2Status::Ok);
        let at = values(&h);
        let (s, d) = h.output_derivatives(&names, &orders);
        assert_eq!(s, Fmi2Status::Ok, "{}", h.last_message());
        assert_eq!(h.step(point, delta), Fmi2Status::Ok);
        let after = values(&h);
        t = point + delta;
        for (i, w) in worst.iter_mut().enumerate() {
            let difference = if orders[i] == 1 {
                (after[i] - before[i]) / (2.0 * delta)
            } else {
                (after[i] - 2.0 * at[i] + before[i]) / (delta * delta)
            };
            *w = w.max((d[i] - difference).abs() / (1.0 + difference.abs()));
        }
    }
    pairs.into_iter().zip(worst).collect()
}

#[test]
fn exact_derivatives_match_central_differences_along_the_trajectory() {
    // Expected: central differences over CS steps of delta, order 1 with delta = 1e-5 s,
    // order 2 with delta = 1e-4 s (a smaller delta makes the second difference
    // round-off bound: 4 eps |y| / delta^2). Their truncation errors delta^2/6 |y'''|
    // and delta^2/12 |y''''| dominate: the errors fall 100-fold per 10-fold smaller
    // delta (measured from 1e-2 to 1e-5 s), the integrator's (tolerance 1e-12) is far
    // below. The plant moves fast (|y'''| up to about 3e3 here), hence tolerances of
    // 3e-7 (order 1) and 1e-5 (order 2), relative to 1 + |difference|.
    for (delta, order, tolerance) in [(1e-5, 1, 3e-7), (1e-4, 2, 1e-5)] {
        for ((name, o), error) in largest_difference_errors(delta) {
            if o != order {
                continue;
            }
            println!("{name} order {order}, delta {delta:e}: largest relative error {error:.1e}");
            assert!(
                error < tolerance,
                "order {order} of {name} is off by {error:e}"
            );
        }
    }
}

#[test]
fn derivatives_that_are_not_exact_are_refused_naming_them() {
    // omegaDot would need the derivative of the dynamics, force that of J^-T; the
    // second derivatives of omega, lDot and thetaDot likewise.
    for (name, order) in [
        ("omegaDot[1]", 1),
        ("force[2]", 1),
        ("kineticEnergy", 1),
        ("omega[3]", 2),
        ("lDot[1]", 2),
        ("thetaDot[2]", 2),
    ] {
        let h = moving_plant();
        assert_eq!(h.step(0.0, 0.01), Fmi2Status::Ok);
        let (s, v) = h.output_derivatives(&[name], &[order]);
        assert_eq!(s, Fmi2Status::Error, "{name} {order}");
        assert!(v[0].is_nan(), "written despite the error");
        let message = h.last_message();
        let expected = format!("order {order} of \"{name}\" is not provided");
        assert!(message.contains(&expected), "{message}");
        assert!(
            message.contains("exact output derivatives only of theta"),
            "{message}"
        );
    }
}
