//! Tests of the generic FMI 2.0 layer through its C-level entry points (the same
//! functions the exported symbols forward to): state machine, argument checks,
//! logging, FMU state serialization, Discard, directional derivatives, unwinds.

#[path = "support/panicky.rs"]
mod panicky;
mod support;

use panicky::Panicky;
use robofmu_fmi::core::Model;
use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::Host;
use robofmu_pid_fmu::Pid;
use std::ffi::c_char;

/// Instantiated with loggingOn = 0, so that only the categories a test enables log.
fn quiet<M: Model>(kind: i32) -> Host<M> {
    Host::with_logging(kind, false)
}

/// Instantiated quietly and initialized (every call OK).
fn initialized<M: Model>(kind: i32) -> Host<M> {
    let h = quiet(kind);
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    h
}

const CS: i32 = FMI2_CO_SIMULATION;
const ME: i32 = FMI2_MODEL_EXCHANGE;
// Value references of the PID binding (see fmus/pid/src/lib.rs).
const PID_KD1: u32 = 21;
const PID_TF1: u32 = 31;
const PID_SETPOINT1: u32 = 101;
const PID_U1: u32 = 201;
const PID_INTEGRAL1: u32 = 301;
const PID_FILTER1: u32 = 311;

#[test]
fn calls_out_of_sequence_return_error_and_move_to_error_mode() {
    let h = quiet::<Pid>(CS);
    // doStep before initialization: illegal in Instantiated.
    assert_eq!(h.step(0.0, 0.1), Fmi2Status::Error);
    assert!(
        h.last_message().contains("illegal call sequence"),
        "{}",
        h.last_message()
    );
    // The instance is now in the Error mode: only get/reset/free-like calls work.
    assert_eq!(
        unsafe { api::enter_initialization_mode::<Pid>(h.c) },
        Fmi2Status::Error
    );
    assert_eq!(unsafe { api::reset::<Pid>(h.c) }, Fmi2Status::Ok);
    assert_eq!(
        unsafe { api::enter_initialization_mode::<Pid>(h.c) },
        Fmi2Status::Ok
    );
    // Model Exchange functions are illegal for a Co-Simulation instance.
    assert_eq!(unsafe { api::set_time::<Pid>(h.c, 0.0) }, Fmi2Status::Error);
    // A null instance is rejected without a crash.
    assert_eq!(
        unsafe { api::do_step::<Pid>(std::ptr::null_mut(), 0.0, 0.1, 0) },
        Fmi2Status::Error
    );
}

#[test]
fn bad_arguments_are_rejected_with_a_reason() {
    let h = initialized::<Pid>(CS);
    type Case<'a> = (Box<dyn Fn() -> Fmi2Status + 'a>, &'static str);
    let cases: Vec<Case> = vec![
        (
            Box::new(|| unsafe { api::get_real::<Pid>(h.c, std::ptr::null(), 1, &mut 0.0) }),
            "null pointer",
        ),
        (
            Box::new(|| h.real_at(9999).0),
            "unknown value reference 9999",
        ),
        (
            Box::new(|| h.set_real_at(PID_SETPOINT1, f64::NAN)),
            "cannot be set to NaN",
        ),
        (Box::new(|| h.set_real_at(PID_U1, 1.0)), "cannot be set"),
        (
            Box::new(|| unsafe { api::get_integer::<Pid>(h.c, &PID_U1, 1, &mut 0) }),
            "not Integer",
        ),
        (Box::new(|| h.step(0.5, 0.1)), "differs from the FMU time"),
        (Box::new(|| h.step(0.0, -0.1)), "not positive"),
        (Box::new(|| h.step(0.0, f64::INFINITY)), "not finite"),
    ];
    for (call, reason) in cases {
        assert_eq!(call(), Fmi2Status::Error, "{reason}");
        assert!(
            h.last_message().contains(reason),
            "{} lacks {reason}",
            h.last_message()
        );
        assert_eq!(unsafe { api::reset::<Pid>(h.c) }, Fmi2Status::Ok);
        unsafe {
            api::enter_initialization_mode::<Pid>(h.c);
            api::exit_initialization_mode::<Pid>(h.c);
        }
    }
    // nvr = 0 with null arrays is a legal no-op.
    assert_eq!(
        unsafe { api::get_real::<Pid>(h.c, std::ptr::null(), 0, std::ptr::null_mut()) },
        Fmi2Status::Ok
    );
}

#[test]
fn debug_logging_honours_categories_and_escapes_percent() {
    let h = quiet::<Pid>(CS);
    let cats = [c"logEvents".as_ptr()];
    assert_eq!(
        unsafe { api::set_debug_logging::<Pid>(h.c, 1, 1, cats.as_ptr()) },
        Fmi2Status::Ok
    );
    unsafe {
        api::enter_initialization_mode::<Pid>(h.c);
        api::exit_initialization_mode::<Pid>(h.c);
    }
    {
        let lines = h.env.log.lock().unwrap();
        assert!(
            lines
                .iter()
                .any(|l| l.category == "logEvents" && l.message.contains("initialized"))
        );
        // logController was not enabled.
        assert!(!lines.iter().any(|l| l.category == "logController"));
    }
    let bad = [c"log%sNothing".as_ptr()];
    assert_eq!(
        unsafe { api::set_debug_logging::<Pid>(h.c, 1, 1, bad.as_ptr()) },
        Fmi2Status::Error
    );
    assert!(
        h.last_message().contains("log%%sNothing"),
        "{}",
        h.last_message()
    );
}

#[test]
fn fmu_state_round_trip_reproduces_bit_for_bit() {
    let h = initialized::<Pid>(CS);
    for k in 0..5 {
        assert_eq!(h.step(k as f64 * 0.01, 0.01), Fmi2Status::Ok);
    }
    let mut state: Fmi2FmuState = std::ptr::null_mut();
    assert_eq!(
        unsafe { api::get_fmu_state::<Pid>(h.c, &mut state) },
        Fmi2Status::Ok
    );
    h.step(0.05, 0.01);
    let first = h.real_at(PID_U1).1;
    assert_eq!(
        unsafe { api::set_fmu_state::<Pid>(h.c, state) },
        Fmi2Status::Ok
    );
    h.step(0.05, 0.01);
    assert_eq!(h.real_at(PID_U1).1.to_bits(), first.to_bits());

    // Serialize, deserialize into a new state, restore, step: same bits again.
    let mut size = 0;
    unsafe { api::serialized_fmu_state_size::<Pid>(h.c, state, &mut size) };
    let mut bytes = vec![0 as c_char; size];
    assert_eq!(
        unsafe { api::serialize_fmu_state::<Pid>(h.c, state, bytes.as_mut_ptr(), size) },
        Fmi2Status::Ok
    );
    let mut copy: Fmi2FmuState = std::ptr::null_mut();
    assert_eq!(
        unsafe { api::de_serialize_fmu_state::<Pid>(h.c, bytes.as_ptr(), size, &mut copy) },
        Fmi2Status::Ok
    );
    assert_eq!(
        unsafe { api::set_fmu_state::<Pid>(h.c, copy) },
        Fmi2Status::Ok
    );
    h.step(0.05, 0.01);
    assert_eq!(h.real_at(PID_U1).1.to_bits(), first.to_bits());
    unsafe {
        assert_eq!(api::free_fmu_state::<Pid>(h.c, &mut state), Fmi2Status::Ok);
        assert_eq!(api::free_fmu_state::<Pid>(h.c, &mut copy), Fmi2Status::Ok);
    }
    assert!(state.is_null() && copy.is_null());
}

#[test]
fn foreign_truncated_and_corrupted_state_bytes_are_rejected() {
    let good = serialized_pid_state();
    let size = good.len();
    let pid = initialized::<Pid>(CS);
    let attempt = |data: &[c_char]| {
        let mut s: Fmi2FmuState = std::ptr::null_mut();
        let status =
            unsafe { api::de_serialize_fmu_state::<Pid>(pid.c, data.as_ptr(), data.len(), &mut s) };
        assert!(s.is_null());
        unsafe { api::reset::<Pid>(pid.c) };
        (status, pid.last_message())
    };
    let (status, why) = attempt(&foreign_copy(&good));
    assert_eq!(status, Fmi2Status::Error);
    assert!(why.contains("belongs to model"), "{why}");
    let (status, why) = attempt(&good[..size - 3]);
    assert_eq!(status, Fmi2Status::Error);
    assert!(
        why.contains("truncated") || why.contains("belongs"),
        "{why}"
    );
    let (status, why) = attempt(&[0; 5]);
    assert_eq!(status, Fmi2Status::Error);
    assert!(why.contains("truncated"), "{why}");

    // Corrupt one payload byte of a genuine PID state: the checksum catches it.
    let mut corrupted = good.clone();
    corrupted[size / 2] ^= 0x10;
    let (status, why) = attempt(&corrupted);
    assert_eq!(status, Fmi2Status::Error);
    assert!(why.contains("checksum"), "{why}");
}

/// The serialized FMU state of an initialized PID.
fn serialized_pid_state() -> Vec<c_char> {
    let own = initialized::<Pid>(CS);
    let mut s: Fmi2FmuState = std::ptr::null_mut();
    let mut n = 0;
    unsafe {
        api::get_fmu_state::<Pid>(own.c, &mut s);
        api::serialized_fmu_state_size::<Pid>(own.c, s, &mut n);
    }
    let mut bytes = vec![0 as c_char; n];
    unsafe {
        api::serialize_fmu_state::<Pid>(own.c, s, bytes.as_mut_ptr(), n);
        api::free_fmu_state::<Pid>(own.c, &mut s);
    }
    bytes
}

/// A well-formed state of another model: the PID state with one character of its
/// GUID changed and the checksum redone. Layout from the layer's documented format:
/// magic (8) | version u32 | guid length u32 | guid | ... | FNV-1a 64 of all before it.
fn foreign_copy(state: &[c_char]) -> Vec<c_char> {
    let mut bytes: Vec<u8> = state.iter().map(|&b| b as u8).collect();
    bytes[16] ^= 0x01;
    let body = bytes.len() - 8;
    let checksum = bytes[..body]
        .iter()
        .fold(0xcbf2_9ce4_8422_2325u64, |h, &b| {
            (h ^ b as u64).wrapping_mul(0x0100_0000_01b3)
        });
    bytes[body..].copy_from_slice(&checksum.to_le_bytes());
    bytes.into_iter().map(|b| b as c_char).collect()
}

#[test]
fn discarded_step_leaves_state_unchanged_and_reports_status() {
    let h = initialized::<Pid>(CS);
    h.step(0.0, 0.1);
    let states_before = (h.real_at(PID_INTEGRAL1).1, h.real_at(PID_FILTER1).1);
    // Kd != 0 with Tf = 0 (both tunable) makes the next step impossible.
    assert_eq!(h.set_real_at(PID_TF1, 0.0), Fmi2Status::Ok);
    assert_eq!(h.set_real_at(PID_KD1, 0.2), Fmi2Status::Ok);
    assert_eq!(h.step(0.1, 0.1), Fmi2Status::Discard);
    let mut terminated = FMI2_FALSE;
    let mut last = 0.0;
    unsafe {
        assert_eq!(
            api::get_boolean_status::<Pid>(h.c, FMI2_TERMINATED, &mut terminated),
            Fmi2Status::Ok
        );
        assert_eq!(
            api::get_real_status::<Pid>(h.c, FMI2_LAST_SUCCESSFUL_TIME, &mut last),
            Fmi2Status::Ok
        );
    }
    assert_eq!(terminated, FMI2_TRUE);
    assert_eq!(last, 0.1);
    // The states are those of t = 0.1 s, untouched by the rejected step.
    assert_eq!(
        (h.real_at(PID_INTEGRAL1).1, h.real_at(PID_FILTER1).1),
        states_before
    );
    assert!(states_before.0 > 0.0);
    // doStep is illegal after a discard until the state is restored.
    assert_eq!(h.step(0.1, 0.1), Fmi2Status::Error);
}

#[test]
fn directional_derivatives_match_finite_differences() {
    // Expected values: central differences of the outputs/derivatives under
    // perturbations of inputs and states set through fmi2SetReal.
    let h = initialized::<Pid>(ME);
    assert_eq!(
        unsafe { api::enter_continuous_time_mode::<Pid>(h.c) },
        Fmi2Status::Ok
    );
    // Move away from the zero state so that every term contributes.
    let x = [0.3, 0.0, 0.0, -0.2, 0.0, 0.0];
    assert_eq!(
        unsafe { api::set_continuous_states::<Pid>(h.c, x.as_ptr(), 6) },
        Fmi2Status::Ok
    );
    let vr = |group: u32, channel: u32| group + channel;
    // Knowns: inputs (set with fmi2SetReal) and states (index into x).
    let knowns: [(u32, Option<usize>); 5] = [
        (vr(100, 1), None),
        (vr(110, 1), None),
        (vr(140, 1), None),
        (PID_INTEGRAL1, Some(0)),
        (PID_FILTER1, Some(3)),
    ];
    for (seed_vr, state_index) in knowns {
        for unknown in [vr(200, 1), vr(320, 1), vr(330, 1), vr(200, 2)] {
            let mut analytic = 0.0;
            let one = 1.0;
            let status = unsafe {
                api::get_directional_derivative::<Pid>(
                    h.c,
                    &unknown,
                    1,
                    &seed_vr,
                    1,
                    &one,
                    &mut analytic,
                )
            };
            assert_eq!(status, Fmi2Status::Ok);
            let eps = 1e-6;
            let value_at = |delta: f64| {
                let status = match state_index {
                    Some(i) => {
                        let mut xp = x;
                        xp[i] += delta;
                        unsafe { api::set_continuous_states::<Pid>(h.c, xp.as_ptr(), 6) }
                    }
                    None => {
                        let x0 = h.real_at(seed_vr).1;
                        h.set_real_at(seed_vr, x0 + delta)
                    }
                };
                assert_eq!(status, Fmi2Status::Ok, "{}", h.last_message());
                let v = h.real_at(unknown).1;
                match state_index {
                    Some(_) => unsafe { api::set_continuous_states::<Pid>(h.c, x.as_ptr(), 6) },
                    None => h.set_real_at(seed_vr, h.real_at(seed_vr).1 - delta),
                };
                v
            };
            let fd = (value_at(eps) - value_at(-eps)) / (2.0 * eps);
            assert!(
                (analytic - fd).abs() < 1e-6,
                "d{unknown}/d{seed_vr}: {analytic} vs {fd}"
            );
        }
    }
}

#[test]
fn instances_on_different_threads_do_not_interfere() {
    // Expected values: the same run on the main thread, alone.
    let run = |setpoint: f64| {
        let h = quiet::<Pid>(CS);
        h.set_real_at(PID_SETPOINT1, setpoint);
        unsafe {
            api::enter_initialization_mode::<Pid>(h.c);
            api::exit_initialization_mode::<Pid>(h.c);
        }
        for k in 0..1000 {
            h.step(k as f64 * 1e-3, 1e-3);
        }
        h.real_at(PID_U1).1
    };
    let alone: Vec<f64> = (0..4).map(|i| run(i as f64)).collect();
    let threads: Vec<_> = (0..4)
        .map(|i| std::thread::spawn(move || run(i as f64)))
        .collect();
    let parallel: Vec<f64> = threads.into_iter().map(|t| t.join().unwrap()).collect();
    assert_eq!(alone, parallel);
}

#[test]
fn a_panic_in_the_model_becomes_fatal_with_a_log_line() {
    let h = initialized::<Panicky>(CS);
    assert_eq!(h.step(0.0, 0.1), Fmi2Status::Fatal);
    assert!(h.last_message().contains("deliberate test panic"));
    // After fatal only fmi2FreeInstance is possible.
    assert_eq!(unsafe { api::reset::<Panicky>(h.c) }, Fmi2Status::Error);
}
