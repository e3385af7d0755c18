//! Extreme finite values (issue 12) are refused where they are set, naming them.

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pid_fmu::Pid;

#[test]
fn gains_and_setpoints_of_1e308_are_refused_where_they_are_set() {
    // Truth: 1e308 exceeds the layer's limit 1e150; Kd e / Tf or Kp e would overflow.
    for name in ["Kd[1]", "setpoint[1]"] {
        let h: Host<Pid> = Host::with_logging(FMI2_CO_SIMULATION, false);
        assert_eq!(h.set_real(name, 1e308), Fmi2Status::Error, "{name}");
        let message = h.last_message();
        assert!(
            message.contains(&format!("\"{name}\" = 1e308")),
            "{message}"
        );
    }
}

#[test]
fn large_but_accepted_values_run() {
    // 1e6 (rad) setpoint with the default gains: finite output, step OK.
    let h: Host<Pid> = Host::with_logging(FMI2_CO_SIMULATION, false);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(h.set_real("setpoint[1]", 1e6), Fmi2Status::Ok);
    assert_eq!(h.step(0.0, 0.01), Fmi2Status::Ok, "{}", h.last_message());
    assert!(h.real("u[1]").is_finite());
}
