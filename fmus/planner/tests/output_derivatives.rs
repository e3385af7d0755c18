//! The planner's output derivatives (fmi2GetRealOutputDerivatives, orders 1 and 2 of
//! q, qdot, qddot) through the FMI 2.0 layer in Co-Simulation, against the textbook
//! rest-to-rest polynomials and against finite differences of the outputs themselves
//! over small communication steps.

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_planner_fmu::Planner;

type H = Host<Planner>;

const AXES: usize = 3;
const OUTPUTS: [&str; 3] = ["q", "qdot", "qddot"];

/// A Co-Simulation planner of polynomial degree `order` from t0 = 0.5 s to tf = 2 s
/// with the boundary values `boundary` (name, value per axis), initialized at t = 0.
fn planner(order: i32, boundary: &[(&str, [f64; AXES])]) -> H {
    let h = H::with_logging(FMI2_CO_SIMULATION, false);
    assert_eq!(h.set_integer("order", order), Fmi2Status::Ok);
    assert_eq!(h.set_real("t0", 0.5), Fmi2Status::Ok);
    assert_eq!(h.set_real("tf", 2.0), Fmi2Status::Ok);
    for (name, values) in boundary {
        h.set_vector(name, *values);
    }
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    h
}

/// Every output name `q[1]` .. `qddot[3]`, axis by axis.
fn output_names() -> Vec<String> {
    (1..=AXES)
        .flat_map(|a| OUTPUTS.iter().map(move |o| format!("{o}[{a}]")))
        .collect()
}

/// Orders 1 and 2 of every output at the current time: d[name index][order - 1].
fn derivatives(h: &H) -> Vec<[f64; 2]> {
    let names = output_names();
    let mut requests: Vec<&str> = Vec::new();
    let mut orders = Vec::new();
    for name in &names {
        requests.extend([name.as_str(), name.as_str()]);
        orders.extend([1, 2]);
    }
    let (s, v) = h.output_derivatives(&requests, &orders);
    assert_eq!(s, Fmi2Status::Ok, "{}", h.last_message());
    v.chunks(2).map(|c| [c[0], c[1]]).collect()
}

/// q and its derivatives 1..4 of the textbook rest-to-rest polynomial in s = tau / T
/// (cubic q0 + dq (3 s^2 - 2 s^3), quintic q0 + dq (10 s^3 - 15 s^4 + 6 s^5)), held
/// outside [0, T] (zero rates).
fn textbook(degree: i32, dq: f64, duration: f64, tau: f64) -> [f64; 5] {
    let s = tau.clamp(0.0, duration) / duration;
    let mut d = if degree == 3 {
        [
            dq * (3.0 * s * s - 2.0 * s * s * s),
            dq * (6.0 * s - 6.0 * s * s),
            dq * (6.0 - 12.0 * s),
            -12.0 * dq,
            0.0,
        ]
    } else {
        [
            dq * (10.0 * s.powi(3) - 15.0 * s.powi(4) + 6.0 * s.powi(5)),
            dq * (30.0 * s * s - 60.0 * s.powi(3) + 30.0 * s.powi(4)),
            dq * (60.0 * s - 180.0 * s * s + 120.0 * s.powi(3)),
            dq * (60.0 - 360.0 * s + 360.0 * s * s),
            dq * (-360.0 + 720.0 * s),
        ]
    };
    for (n, dn) in d.iter_mut().enumerate().skip(1) {
        *dn /= duration.powi(n as i32);
        if !(0.0..=duration).contains(&tau) {
            *dn = 0.0;
        }
    }
    d
}

#[test]
fn rest_to_rest_derivatives_match_the_textbook_polynomials() {
    // Expected: `textbook` with the default qf = (0.5, -0.3, 0.8), q0 = 0, T = 1.5 s.
    // At t0 the right-sided and at tf the left-sided derivative (inside the motion):
    // the quintic's jerk at tf is 60 dq / T^3, not 0. Times are dyadic, so the
    // communication points hit t0 and tf exactly.
    let qf = [0.5, -0.3, 0.8];
    for degree in [3, 5] {
        let h = planner(degree, &[]);
        let mut t = 0.0;
        for next in [0.25, 0.5, 0.75, 1.25, 1.875, 2.0, 2.25] {
            assert_eq!(h.step(t, next - t), Fmi2Status::Ok);
            t = next;
            let d = derivatives(&h);
            for (a, dq) in qf.iter().enumerate() {
                let want = textbook(degree, *dq, 1.5, t - 0.5);
                for (k, output) in OUTPUTS.iter().enumerate() {
                    for order in 1..=2 {
                        let got = d[3 * a + k][order - 1];
                        let expected = want[k + order];
                        assert!(
                            (got - expected).abs() < 1e-12 * (1.0 + expected.abs()),
                            "degree {degree}, t = {t}: order {order} of {output}[{}] is \
                             {got}, textbook {expected}",
                            a + 1
                        );
                    }
                }
            }
        }
    }
}

/// Largest error of orders 1 and 2 against central differences of the outputs, over
/// points inside the motion (each a step delta before, at and after the point).
fn largest_difference_error(degree: i32, delta: f64) -> [f64; 2] {
    let boundary = [
        ("q0", [0.3, -0.2, 1.0]),
        ("qf", [-1.1, 0.4, 0.2]),
        ("qdot0", [0.7, 0.0, -0.5]),
        ("qdotf", [-0.2, 0.3, 0.0]),
        ("qddot0", [1.5, -1.0, 0.0]),
        ("qddotf", [-0.4, 0.0, 2.0]),
    ];
    let h = planner(degree, &boundary);
    let names = output_names();
    let values = |h: &H| -> Vec<f64> { names.iter().map(|n| h.real(n)).collect() };
    let mut worst = [0.0f64; 2];
    let mut t = 0.0;
    for point in [0.6, 0.9, 1.2, 1.5, 1.9] {
        assert_eq!(h.step(t, point - delta - t), Fmi2Status::Ok);
        let before = values(&h);
        assert_eq!(h.step(point - delta, delta), Fmi2Status::Ok);
        let (at, d) = (values(&h), derivatives(&h));
        assert_eq!(h.step(point, delta), Fmi2Status::Ok);
        let after = values(&h);
        t = point + delta;
        for i in 0..names.len() {
            let first = (after[i] - before[i]) / (2.0 * delta);
            let second = (after[i] - 2.0 * at[i] + before[i]) / (delta * delta);
            worst[0] = worst[0].max((d[i][0] - first).abs() / (1.0 + first.abs()));
            worst[1] = worst[1].max((d[i][1] - second).abs() / (1.0 + second.abs()));
        }
    }
    worst
}

#[test]
fn derivatives_match_central_differences_of_the_outputs() {
    // Expected: central differences over steps of delta = 1e-4 s. Their errors:
    // truncation delta^2/6 |y'''| (first) and delta^2/12 |y''''| (second), with
    // |y'''|, |y''''| below about 1e3 here, plus round-off 4 eps |y| / delta^2 (about
    // 1e-7) for the second difference. Tolerances 1e-6 and 1e-5 (relative to 1 + |y|).
    for degree in [3, 5] {
        let [first, second] = largest_difference_error(degree, 1e-4);
        println!(
            "degree {degree}: largest relative error order 1 {first:.1e}, order 2 {second:.1e}"
        );
        assert!(first < 1e-6, "degree {degree}: order 1 off by {first:e}");
        assert!(second < 1e-5, "degree {degree}: order 2 off by {second:e}");
    }
}
