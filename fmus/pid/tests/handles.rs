//! Hostile handles (issue 12): every instance and FMU-state handle is looked up in the
//! registry of live handles before use. A garbage pointer, an instance of another FMU,
//! a state never issued, an already freed state and another FMU's state return
//! fmi2Error (with a log line where an instance exists to log through), never a crash.
//! Also: fmi2Instantiate refuses null allocateMemory / freeMemory callbacks.

mod support;

use robofmu_fmi::core::{Declaration, Log, Model, ModelInfo, StepOutcome};
use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::{Callbacks, Environment, Fmi2Instance, Host, Keep, table};
use robofmu_pid_fmu::Pid;
use std::ffi::c_int;
use support::test_info;

const CS: i32 = FMI2_CO_SIMULATION;

/// A second model type in this binary, standing in for another FMU.
#[derive(Clone, Default)]
struct Other;

static OTHER: ModelInfo = test_info("Other", "{other}", "another FMU");

impl Model for Other {
    const INFO: &'static ModelInfo = &OTHER;
    const VARIABLES: &'static [Declaration<Self>] =
        &[Declaration::real("y", "output", |_, _| 1.0).output()];
    fn set_time(&mut self, _time: f64) {}
    fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
        Ok(())
    }
    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        StepOutcome::Completed
    }
}

fn initialized<M: Model>() -> Host<M> {
    let h = Host::<M>::new(CS);
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    h
}

fn get_state<M: Model>(h: &Host<M>) -> Fmi2FmuState {
    let mut state: Fmi2FmuState = std::ptr::null_mut();
    assert_eq!(
        unsafe { api::get_fmu_state::<M>(h.c, &mut state) },
        Fmi2Status::Ok
    );
    state
}

#[test]
fn garbage_and_foreign_instance_handles_are_errors() {
    // A buffer of 0xAA bytes: dereferenced as an instance it would have a garbage mode,
    // logger and model.
    let mut garbage = [0xAAu8; 512];
    let c = garbage.as_mut_ptr() as Fmi2Component;
    unsafe {
        assert_eq!(
            api::do_step::<Pid>(c, 0.0, 0.1, FMI2_TRUE),
            Fmi2Status::Error
        );
        assert_eq!(api::reset::<Pid>(c), Fmi2Status::Error);
        api::free_instance::<Pid>(c);
    }
    assert!(
        garbage.iter().all(|&b| b == 0xAA),
        "the garbage was written to"
    );
    // A live instance of another FMU is not an instance of this one.
    let other = initialized::<Other>();
    unsafe {
        assert_eq!(
            api::do_step::<Pid>(other.c, 0.0, 0.1, FMI2_TRUE),
            Fmi2Status::Error
        );
        api::free_instance::<Pid>(other.c);
    }
    // ... and it is still alive and usable afterwards.
    assert_eq!(other.step(0.0, 0.1), Fmi2Status::Ok);
}

#[test]
fn states_never_issued_freed_or_foreign_are_errors_with_a_log_line() {
    let h = initialized::<Pid>();
    let mut garbage = [0x55u8; 512];
    let never_issued = garbage.as_mut_ptr() as Fmi2FmuState;
    assert_eq!(
        unsafe { api::set_fmu_state::<Pid>(h.c, never_issued) },
        Fmi2Status::Error
    );
    assert!(
        h.last_message().contains("not a live FMU state"),
        "{}",
        h.last_message()
    );
    assert_eq!(unsafe { api::reset::<Pid>(h.c) }, Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok);

    // A freed state: set, serialize and a second free are refused (no double free).
    let mut state = get_state(&h);
    let dangling = state;
    assert_eq!(
        unsafe { api::free_fmu_state::<Pid>(h.c, &mut state) },
        Fmi2Status::Ok
    );
    assert!(state.is_null());
    assert_eq!(
        unsafe { api::set_fmu_state::<Pid>(h.c, dangling) },
        Fmi2Status::Error
    );
    assert!(
        h.last_message().contains("already freed"),
        "{}",
        h.last_message()
    );
    assert_eq!(unsafe { api::reset::<Pid>(h.c) }, Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let mut again = dangling;
    assert_eq!(
        unsafe { api::free_fmu_state::<Pid>(h.c, &mut again) },
        Fmi2Status::Error
    );
    assert_eq!(unsafe { api::reset::<Pid>(h.c) }, Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok);

    // Another FMU's live state.
    let other = initialized::<Other>();
    let foreign = get_state(&other);
    assert_eq!(
        unsafe { api::set_fmu_state::<Pid>(h.c, foreign) },
        Fmi2Status::Error
    );
    let mut size = 0;
    assert_eq!(unsafe { api::reset::<Pid>(h.c) }, Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    assert_eq!(
        unsafe { api::serialized_fmu_state_size::<Pid>(h.c, foreign, &mut size) },
        Fmi2Status::Error
    );
    // Overwriting a foreign state through fmi2GetFMUstate is refused too.
    assert_eq!(unsafe { api::reset::<Pid>(h.c) }, Fmi2Status::Ok);
    assert_eq!(h.initialize(), Fmi2Status::Ok);
    let mut slot = foreign;
    assert_eq!(
        unsafe { api::get_fmu_state::<Pid>(h.c, &mut slot) },
        Fmi2Status::Error
    );
    // The other FMU's state is intact and still its own.
    assert_eq!(
        unsafe { api::set_fmu_state::<Other>(other.c, foreign) },
        Fmi2Status::Ok
    );
}

#[test]
fn a_state_of_another_instance_of_the_same_fmu_is_accepted() {
    // Truth: the integrator and filter states carried over make the next step of b
    // equal to that of a bit for bit (same inputs, same state, same arithmetic), and
    // different from a fresh instance's.
    const SETPOINT1: u32 = 101;
    const U1: u32 = 201;
    let a = initialized::<Pid>();
    let b = initialized::<Pid>();
    let fresh = initialized::<Pid>();
    for h in [&a, &b, &fresh] {
        assert_eq!(h.set_real_at(SETPOINT1, 0.5), Fmi2Status::Ok);
    }
    assert_eq!(a.step(0.0, 0.1), Fmi2Status::Ok);
    assert_eq!(a.step(0.1, 0.1), Fmi2Status::Ok);
    let state = get_state(&a);
    assert_eq!(
        unsafe { api::set_fmu_state::<Pid>(b.c, state) },
        Fmi2Status::Ok
    );
    for (h, t) in [(&a, 0.2), (&b, 0.2), (&fresh, 0.0)] {
        assert_eq!(h.step(t, 0.1), Fmi2Status::Ok, "{}", h.last_message());
    }
    let u = |h: &Host<Pid>| h.real_at(U1).1;
    assert_eq!(u(&b), u(&a));
    assert_ne!(u(&fresh), u(&a));
}

#[test]
fn instantiate_refuses_null_memory_callbacks_with_a_log_line() {
    // The test host's callbacks with allocateMemory and freeMemory NULL; loggingOn off.
    let which = Callbacks {
        logger: true,
        allocate: false,
        free: false,
    };
    let env = Environment::keeping(which, Keep::Everything);
    let binary = table::binary::<Pid>();
    let refused = Fmi2Instance::instantiate(binary, "no-allocator", CS, Pid::INFO.guid, env, false);
    let env = refused.err().expect("refused without memory callbacks");
    // The line reached the log passed as componentEnvironment.
    let lines = env.log.lock().unwrap();
    assert_eq!(lines.len(), 1, "{lines:?}");
    assert_eq!(lines[0].status, Fmi2Status::Error as c_int);
    assert!(lines[0].message.contains("allocateMemory"), "{lines:?}");
}
