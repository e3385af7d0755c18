//! fmi2SetRealInputDerivatives on the PID binding: each input's derivatives reach its
//! channel and field (setpoint, measurement, rates, feedforward), checked against the
//! closed-form step of `control::pid_ramp`'s documentation; derivatives survive a
//! serialized FMU state.

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pid_fmu::Pid;

fn initialized() -> Host<Pid> {
    let h = Host::<Pid>::with_logging(FMI2_CO_SIMULATION, false);
    // Channel 3 takes its derivative from the rate inputs.
    assert_eq!(h.set_boolean("useRateInputs[3]", true), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    h
}

fn set(h: &Host<Pid>, name: &str, order: i32, value: f64) {
    let s = h.set_input_derivative(name, order, value);
    assert_eq!(s, Fmi2Status::Ok, "{name}: {}", h.last_message());
}

#[test]
fn each_derivative_moves_its_own_channel_and_field() {
    // Expected (defaults: setpoint 1, 0.5, -0.25, measurement 0, Tf 0.05 s, zero
    // states): channel 2 error e(s) = 0.5 + 1.2 s + 3 s^2/2 (measurement slope -1.2,
    // setpoint curvature 3): integral(h) = 0.5 h + 1.2 h^2/2 + 3 h^3/6; channel 3 rate
    // error -2 s from measuredRate slope 2: filter(h) = -2 Tf (z - 1 + exp(-z)), z = h/Tf;
    // channel 1 only gets a feedforward slope, which no state sees: the held step.
    let h = initialized();
    set(&h, "measurement[2]", 1, -1.2);
    set(&h, "setpoint[2]", 2, 3.0);
    set(&h, "measuredRate[3]", 1, 2.0);
    set(&h, "feedforward[1]", 1, 7.0);
    let step = 0.1;
    assert_eq!(h.step(0.0, step), Fmi2Status::Ok);
    let integral = 0.5 * step + 1.2 * step * step / 2.0 + 3.0 * step.powi(3) / 6.0;
    assert!((h.real("integral[2]") - integral).abs() < 1e-15);
    let z: f64 = step / 0.05;
    let filter = -2.0 * 0.05 * (z - 1.0 + (-z).exp());
    assert!((h.real("filter[3]") - filter).abs() < 1e-15);
    // Channel 1 (e = 1 held): integral h, filter 1 - exp(-z).
    assert_eq!(h.real("integral[1]"), 1.0 * step);
    assert!((h.real("filter[1]") - (1.0 - (-z).exp())).abs() < 1e-15);
}

#[test]
fn derivatives_survive_a_serialized_state_and_a_reset_clears_them() {
    // Truth: the run of the instance that serialized the state; after fmi2Reset the run
    // of a fresh instance (held inputs).
    let h = initialized();
    set(&h, "setpoint[1]", 1, 0.8);
    set(&h, "measurement[3]", 2, -4.0);
    let saved = h.serialize();
    assert_eq!(h.step(0.0, 0.05), Fmi2Status::Ok);
    let original = [h.vector("integral"), h.vector("filter")];
    let other = initialized();
    assert_eq!(other.restore(&saved), Fmi2Status::Ok);
    assert_eq!(other.step(0.0, 0.05), Fmi2Status::Ok);
    assert_eq!([other.vector("integral"), other.vector("filter")], original);

    assert_eq!(
        unsafe { robofmu_fmi::fmi2::api::reset::<Pid>(h.c) },
        Fmi2Status::Ok
    );
    assert_eq!(h.set_boolean("useRateInputs[3]", true), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let fresh = initialized();
    for one in [&h, &fresh] {
        assert_eq!(one.step(0.0, 0.05), Fmi2Status::Ok);
    }
    assert_eq!(h.vector("integral"), fresh.vector("integral"));
    assert_ne!(h.vector("integral"), original[0]);
}
