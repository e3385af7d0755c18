//! Extreme finite parameters (issue 12) are refused where they are set or at
//! fmi2ExitInitializationMode, naming them; no getter is the first to notice.

use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_planner_fmu::Planner;

fn planner() -> Host<Planner> {
    Host::with_logging(FMI2_CO_SIMULATION, false)
}

#[test]
fn an_interval_so_short_that_the_coefficients_overflow_is_refused_at_initialization() {
    // Truth: tf - t0 = 5e-324 s (the smallest subnormal) makes the quintic's
    // coefficients (qf - q0) / T^3 ... infinite.
    let h = planner();
    assert_eq!(h.set_real("tf", 5e-324), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Error);
    let message = h.last_message();
    assert!(message.contains("tf = 5e-324"), "{message}");
    assert!(message.contains("overflow"), "{message}");
}

#[test]
fn a_boundary_value_of_1e308_is_refused_where_it_is_set() {
    // Truth: 1e308 exceeds the layer's limit 1e150 (10 (qf - q0) alone would overflow).
    let h = planner();
    assert_eq!(h.set_real("q0[1]", 1e308), Fmi2Status::Error);
    assert!(
        h.last_message().contains("\"q0[1]\" = 1e308"),
        "{}",
        h.last_message()
    );
}

#[test]
fn a_short_but_representable_interval_still_initializes() {
    // tf - t0 = 1e-3 s: coefficients up to about 1e16, all finite.
    let h = planner();
    assert_eq!(h.set_real("tf", 1e-3), Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
}
