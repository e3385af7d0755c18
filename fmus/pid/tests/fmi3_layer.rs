//! Tests of the FMI 3.0 front-end through its C-level entry points (the functions the
//! exported fmi3* symbols forward to): a panic in the model becomes fmi3Fatal with a
//! log line, after which only fmi3FreeInstance is possible; the FMU state written by
//! the FMI 3.0 front-end says so. The call sequences of the real FMUs are tested
//! through their shared libraries in tests/python/test_fmi3_calls.py.

#[path = "support/panicky.rs"]
mod panicky;
mod support;

use panicky::Panicky;
use robofmu_fmi::core::Model;
use robofmu_fmi::fmi3::api;
use robofmu_fmi::fmi3::mode::Interface;
use robofmu_fmi::fmi3::types::*;
use std::ffi::{CStr, c_void};
use std::sync::Mutex;

/// Log lines received: (status, message).
type Lines = Mutex<Vec<(Fmi3Status, String)>>;

unsafe extern "C-unwind" fn capture(
    env: Fmi3InstanceEnvironment,
    status: Fmi3Status,
    _category: Fmi3String,
    message: Fmi3String,
) {
    // SAFETY: env is the &Lines the test passed; the message comes from the layer.
    let lines = unsafe { &*(env as *const Lines) };
    let text = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .into_owned();
    lines.lock().unwrap().push((status, text));
}

/// A Co-Simulation instance of M with the capturing logger, initialized.
fn initialized<M: Model>(lines: &Lines) -> Fmi3Instance {
    let token = std::ffi::CString::new(M::INFO.guid).unwrap();
    let c = unsafe {
        api::instantiate::<M>(api::Instantiation {
            function: "fmi3InstantiateCoSimulation",
            instance_name: c"test".as_ptr(),
            token: token.as_ptr(),
            logging_on: FMI3_FALSE,
            environment: lines as *const Lines as *mut c_void,
            log_message: Some(capture),
            interface: Interface::CoSimulation {
                event_mode_used: false,
                early_return_allowed: false,
            },
            intermediate_update: None,
        })
    };
    assert!(!c.is_null());
    let start = unsafe { api::enter_initialization_mode::<M>(c, 0, 0.0, 0.0, 0, 0.0) };
    assert_eq!(start, Fmi3Status::Ok);
    assert_eq!(
        unsafe { api::exit_initialization_mode::<M>(c) },
        Fmi3Status::Ok
    );
    c
}

fn step<M: Model>(c: Fmi3Instance, t: f64, h: f64) -> Fmi3Status {
    let (mut event, mut terminate, mut early, mut last) = (0, 0, 0, 0.0);
    unsafe {
        api::do_step::<M>(
            c,
            t,
            h,
            FMI3_TRUE,
            api::StepResult {
                event_handling_needed: &mut event,
                terminate_simulation: &mut terminate,
                early_return: &mut early,
                last_successful_time: &mut last,
            },
        )
    }
}

#[test]
fn a_panic_in_the_model_becomes_fatal_with_a_log_line() {
    let lines = Lines::default();
    let c = initialized::<Panicky>(&lines);
    assert_eq!(step::<Panicky>(c, 0.0, 0.1), Fmi3Status::Fatal);
    let (status, message) = lines.lock().unwrap().last().cloned().unwrap();
    assert_eq!(status, Fmi3Status::Fatal);
    assert!(message.contains("fmi3DoStep") && message.contains("deliberate test panic"));
    // After fmi3Fatal only fmi3FreeInstance is possible.
    assert_eq!(unsafe { api::reset::<Panicky>(c) }, Fmi3Status::Error);
    unsafe { api::free_instance::<Panicky>(c) };
}

#[test]
fn serialized_states_record_the_fmi3_front_end() {
    // Expected: the standard field of the core's format (robofmu_fmi::core::serialize)
    // is 3 for a state taken through FMI 3.0 and survives the round trip.
    let lines = Lines::default();
    let c = initialized::<robofmu_pid_fmu::Pid>(&lines);
    assert_eq!(step::<robofmu_pid_fmu::Pid>(c, 0.0, 0.1), Fmi3Status::Ok);
    let mut state: Fmi3FmuState = std::ptr::null_mut();
    assert_eq!(
        unsafe { api::get_fmu_state::<robofmu_pid_fmu::Pid>(c, &mut state) },
        Fmi3Status::Ok
    );
    // The handle is opaque (core::handles): the registry gives the snapshot behind it.
    let snapshot =
        robofmu_fmi::core::fmu_states::snapshot::<robofmu_pid_fmu::Pid>(state, "FMUState").unwrap();
    assert_eq!(snapshot.standard, robofmu_fmi::core::Standard::Fmi3);
    let table = robofmu_fmi::core::instance::sorted_table::<robofmu_pid_fmu::Pid>().unwrap();
    let bytes = robofmu_fmi::core::serialize::serialize(&table, &snapshot);
    let back =
        robofmu_fmi::core::serialize::deserialize::<robofmu_pid_fmu::Pid>(&table, &bytes).unwrap();
    assert_eq!(back.standard, robofmu_fmi::core::Standard::Fmi3);
    assert_eq!(back.time, 0.1);
    assert_eq!(
        unsafe { api::free_fmu_state::<robofmu_pid_fmu::Pid>(c, &mut state) },
        Fmi3Status::Ok
    );
    unsafe { api::free_instance::<robofmu_pid_fmu::Pid>(c) };
}
