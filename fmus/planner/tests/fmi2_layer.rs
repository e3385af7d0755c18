//! FMI 2.0 layer tests that need the planner: instantiation checks, parameters
//! refused at exitInitializationMode, and a model without directional derivatives.

use robofmu_fmi::core::Model;
use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::{self as fmu_host, Host};
use robofmu_planner_fmu::Planner;
use std::ffi::CString;

const CS: i32 = FMI2_CO_SIMULATION;
const ME: i32 = FMI2_MODEL_EXCHANGE;

/// Instantiated with loggingOn = 0.
fn quiet(kind: i32) -> Host<Planner> {
    Host::with_logging(kind, false)
}

#[test]
fn instantiate_rejects_wrong_guid_type_and_missing_callbacks() {
    let refused = fmu_host::instantiate::<Planner>(CS, "{not-the-guid}", false).err();
    let env = refused.expect("a wrong GUID refused");
    assert!(
        env.log.lock().unwrap()[0]
            .message
            .contains("does not match")
    );
    let refused = fmu_host::instantiate::<Planner>(7, Planner::INFO.guid, false).err();
    assert!(refused.is_some(), "fmi2Type 7 refused");
    let name = CString::new("x").unwrap();
    let c = unsafe {
        api::instantiate::<Planner>(
            name.as_ptr(),
            CS,
            name.as_ptr(),
            std::ptr::null(),
            std::ptr::null(),
            0,
            0,
        )
    };
    assert!(c.is_null());
}

#[test]
fn invalid_parameters_fail_at_exit_initialization_with_a_message() {
    let h = quiet(CS);
    // tf (vr 3) before t0 (vr 2).
    assert_eq!(h.set_real_at(2, 3.0), Fmi2Status::Ok);
    unsafe { api::enter_initialization_mode::<Planner>(h.c) };
    assert_eq!(
        unsafe { api::exit_initialization_mode::<Planner>(h.c) },
        Fmi2Status::Error
    );
    assert!(
        h.last_message().contains("must be after the start time"),
        "{}",
        h.last_message()
    );
    // order 4 is refused at once (range 3..5, then the writer's own check).
    let h = quiet(CS);
    assert_eq!(
        unsafe { api::set_integer::<Planner>(h.c, &1, 1, &4) },
        Fmi2Status::Error
    );
    assert!(h.last_message().contains("3 or 5"));
}

#[test]
fn a_model_without_partial_derivatives_refuses_directional_derivatives() {
    let p = quiet(ME);
    assert_eq!(p.initialize(), Fmi2Status::Ok, "{}", p.last_message());
    let (u, k, seed) = (100u32, 2u32, 1.0);
    let mut out = 0.0;
    let status =
        unsafe { api::get_directional_derivative::<Planner>(p.c, &u, 1, &k, 1, &seed, &mut out) };
    assert_eq!(status, Fmi2Status::Error);
    assert!(p.last_message().contains("does not provide"));
}
