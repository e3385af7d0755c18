//! The sampled computed-torque law against closed forms of its error integral and
//! acceleration command on a known input sequence, and its anti-windup at ticks.

use nalgebra::Vector3;
use robofmu_dynamics::computed_torque::{
    AxisGains, ComputedTorque, ControllerError, Inputs, SampledComputedTorque,
};
use robofmu_dynamics::pss3::dynamics::PlantParams;

fn gains(limits: Option<(f64, f64)>) -> [AxisGains; 3] {
    [0, 1, 2].map(|k| AxisGains {
        kp: 2700.0 + 100.0 * k as f64,
        kd: 90.0 - k as f64,
        ki: 27000.0,
        limits,
    })
}

/// Tick k of a motion whose angle error grows as a ramp, e_k = slope k Ts, at the
/// flat pose with constant rates and planned accelerations.
fn ramp_inputs(k: u32, ts: f64, slope: &Vector3<f64>) -> Inputs {
    let theta = Vector3::new(0.02, -0.01, 138f64.to_radians());
    Inputs {
        setpoint: theta + slope * (k as f64 * ts),
        setpoint_rate: Vector3::new(0.1, -0.2, 0.05),
        setpoint_acceleration: Vector3::new(1.5, -0.5, 2.0),
        measurement: theta,
        measured_rate: Vector3::new(0.08, -0.15, 0.0),
    }
}

#[test]
fn ticks_give_the_law_on_the_closed_form_integral_and_hold_it() {
    // Truth: e_k = c k Ts from a zero integral gives I_k = c Ts^2 k (k - 1) / 2 (the sum
    // of the held errors), so the commanded acceleration at tick k is
    //   a_k = q_ddot + Kd e_dot + Kp e_k + Ki c Ts^2 k (k - 1) / 2
    // and the output is the continuous law's at that integral.
    let slope = Vector3::new(0.01, -0.02, 0.005);
    let g = gains(None);
    let law = ComputedTorque::new(PlantParams::default(), g).unwrap();
    for ts in [1e-3, 4e-3] {
        let mut sampled = SampledComputedTorque::new(law.clone(), ts).unwrap();
        assert!(sampled.held().is_none());
        for k in 0..1000 {
            let inputs = ramp_inputs(k, ts, &slope);
            let out = sampled.tick(&inputs).unwrap();
            let kf = k as f64;
            let integral = slope * (ts * ts * kf * (kf - 1.0) / 2.0);
            for axis in 0..3 {
                let e = slope[axis] * kf * ts;
                let rate_error = inputs.setpoint_rate[axis] - inputs.measured_rate[axis];
                let a = inputs.setpoint_acceleration[axis]
                    + g[axis].kd * rate_error
                    + g[axis].kp * e
                    + g[axis].ki * integral[axis];
                assert!(
                    (out.acceleration[axis] - a).abs() < 1e-12 * a.abs().max(1.0),
                    "Ts {ts} tick {k} axis {axis}: {} vs {a}",
                    out.acceleration[axis]
                );
            }
            let want = law.output(&integral, &inputs).unwrap().u;
            assert!(
                (out.u - want).amax() < 1e-12 * want.amax().max(1.0),
                "Ts {ts} tick {k}: {} vs {want}",
                out.u
            );
            assert_eq!(sampled.held().unwrap().u, out.u);
        }
    }
}

#[test]
fn the_integral_freezes_at_the_tick_the_output_reaches_its_limit() {
    // Rule of the continuous law, decided at ticks: while u_raw_k is beyond a limit and
    // Ki e_k pushes further out, I_k+1 = I_k; otherwise I_k+1 = I_k + Ts e_k exactly.
    let limits = Some((-30.0, 30.0));
    let law = ComputedTorque::new(PlantParams::default(), gains(limits)).unwrap();
    let ts = 2e-3;
    let slope = Vector3::new(0.5, -0.4, 0.3);
    let mut sampled = SampledComputedTorque::new(law, ts).unwrap();
    let mut frozen_ticks = 0;
    for k in 0..400 {
        let inputs = ramp_inputs(k, ts, &slope);
        let before = *sampled.integral();
        let out = sampled.tick(&inputs).unwrap();
        for axis in 0..3 {
            let (raw, e) = (out.u_raw[axis], out.error[axis]);
            let stopped = (raw >= 30.0 && e > 0.0) || (raw <= -30.0 && e < 0.0);
            let want = if stopped {
                frozen_ticks += 1;
                before[axis]
            } else {
                before[axis] + ts * e
            };
            assert_eq!(sampled.integral()[axis], want, "tick {k} axis {axis}");
            assert!(out.u[axis].abs() <= 30.0);
        }
    }
    assert!(
        frozen_ticks > 100,
        "the limits were reached {frozen_ticks} times"
    );
}

#[test]
fn bad_periods_and_inputs_are_refused_without_a_change() {
    let law = ComputedTorque::new(PlantParams::default(), gains(None)).unwrap();
    for p in [0.0, -1e-3, f64::NAN, f64::INFINITY] {
        let e = SampledComputedTorque::new(law.clone(), p).unwrap_err();
        assert_eq!(e.to_string(), ControllerError::SamplePeriod(p).to_string());
        assert!(e.to_string().contains("sample period"), "{e}");
    }
    let mut sampled = SampledComputedTorque::new(law, 1e-3).unwrap();
    let slope = Vector3::new(0.01, 0.0, 0.0);
    sampled.tick(&ramp_inputs(5, 1e-3, &slope)).unwrap();
    let (integral, held) = (*sampled.integral(), sampled.held().unwrap().u);
    let mut bad = ramp_inputs(6, 1e-3, &slope);
    bad.setpoint_acceleration[1] = f64::NAN;
    assert!(sampled.tick(&bad).is_err());
    assert_eq!(*sampled.integral(), integral);
    assert_eq!(sampled.held().unwrap().u, held);
}
