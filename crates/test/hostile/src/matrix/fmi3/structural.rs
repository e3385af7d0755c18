//! Structural parameters (FMI 3.0 sections 2.2 and 3.2: Configuration Mode): for
//! every FMU whose FMI 3.0 description declares one (a UInt64 with
//! causality="structuralParameter" sizing arrays by `<Dimension valueReference>`),
//! sizes of 0, 10^9 and 2^64 - 1, the parameter set outside Configuration Mode,
//! Configuration Mode entered and left in wrong states (from Step or Event Mode it
//! would be Reconfiguration Mode, for tunable structural parameters only), nValues
//! wrong for the parameter, an array read and written with its old size after a
//! resize, and a serialized FMU state of a resized instance. Expected: fmi3Error and
//! a log line naming the rule; nothing lost (a refused size keeps the previous one, a
//! refused array write keeps the values; checked here, a failure of a check returns
//! fmi3Fatal, which no case expects); the instance recovers with fmi3Reset (the
//! matrix's `usable_after`). Controls: the legal sequence returns fmi3OK and the array
//! has the new size.

use super::InstanceCases;
use crate::Loaded;
use crate::binary::{ERROR, FATAL, OK, Status};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::matrix::{Case, Expect};

const WHY_RANGE: &str = "a size outside the structural parameter's min..max (here 0, 10^9, 2^64 - 1): fmi3Error naming the range, the previous size kept";
const WHY_MODE: &str = "FMI 3.0 3.2: a fixed structural parameter is set in Configuration Mode only: fmi3Error naming Configuration Mode";
const WHY_RECONFIGURATION: &str = "FMI 3.0 3.2: Reconfiguration Mode (from Event or Step Mode) is for tunable structural parameters; these are fixed: fmi3Error with the reason";
const WHY_ORDER: &str = "FMI 3.0 3.2: Configuration Mode is entered from Instantiated and left back to it: fmi3Error naming the function elsewhere";
const WHY_COUNT: &str = "FMI 3.0 2.2.6: nValues counts the elements at the current sizes; the old size after a resize is refused, nothing written";
const WHY_SERIALIZED: &str = "project choice: serialized FMU states hold the default sizes only; a resized state is kept by fmi3GetFMUState / fmi3SetFMUState, its serialization refused";
const WHY_CONTROL: &str = "FMI 3.0 3.2: the legal sequence (Configuration Mode, the size, back to Instantiated, initialization) succeeds, the arrays at the new size";

/// The size the cases resize to.
const RESIZED: usize = 6;

fn enter(i: &Instance) -> Status {
    // SAFETY: a live instance.
    unsafe { (i.binary.enter_configuration_mode)(i.c) }
}

fn exit(i: &Instance) -> Status {
    // SAFETY: a live instance.
    unsafe { (i.binary.exit_configuration_mode)(i.c) }
}

fn set_size(i: &Instance, vr: u32, n: u64) -> Status {
    // SAFETY: one reference, one value.
    unsafe { (i.binary.set_uint64)(i.c, &vr, 1, &n, 1) }
}

fn size(i: &Instance, vr: u32) -> Option<u64> {
    let mut n = 0;
    // SAFETY: one reference, one value.
    let s = unsafe { (i.binary.get_uint64)(i.c, &vr, 1, &mut n, 1) };
    (s == OK).then_some(n)
}

fn get(i: &Instance, vr: u32, n: usize) -> (Status, Vec<f64>) {
    let mut x = vec![f64::NAN; n];
    // SAFETY: one reference, n values.
    let s = unsafe { (i.binary.get_float64)(i.c, &vr, 1, x.as_mut_ptr(), n) };
    (s, x)
}

/// `then(i)` after Configuration Mode set the size to RESIZED and initialization;
/// fmi3Fatal (expected by no case) when the legal sequence fails.
fn resized(i: &Instance, vr: u32, then: impl Fn(&Instance) -> Status) -> Status {
    let s = enter(i).max(set_size(i, vr, RESIZED as u64)).max(exit(i));
    if s != OK || i.enter_initialization().is_err() {
        return FATAL;
    }
    // SAFETY: a live instance in Initialization Mode.
    if unsafe { (i.binary.exit_initialization_mode)(i.c) } != OK {
        return FATAL;
    }
    then(i)
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = &loaded.fmus3[m].description;
    let Some(&(n, start)) = d.structural.first() else {
        return Vec::new();
    };
    // An array sized by it: a Float64 parameter of the default size.
    let Some(array) = (d.variables.iter())
        .find(|v| v.is_parameter() && v.size == start && v.size > 1)
        .map(|v| (v.vr, v.name.clone()))
    else {
        return Vec::new();
    };
    let mut cases = InstanceCases::new("structural", m);
    for interface in [Interface3::ModelExchange, Interface3::CoSimulation] {
        for bad in [0, 1_000_000_000, u64::MAX] {
            cases.add(
                interface,
                format!("size {bad} in ConfigurationMode"),
                (Expect::error("outside 1..="), WHY_RANGE),
                State3::Instantiated,
                Box::new(move |i| {
                    if enter(i) != OK {
                        return FATAL;
                    }
                    let s = set_size(i, n, bad);
                    // Nothing lost: the previous size is kept.
                    if size(i, n) == Some(start as u64) {
                        s
                    } else {
                        FATAL
                    }
                }),
            );
        }
        for state in State3::of(
            interface,
            &[
                State3::Instantiated,
                State3::InitializationMode,
                State3::EventMode,
                State3::ContinuousTimeMode,
                State3::StepMode,
                State3::Terminated,
            ],
        ) {
            cases.add(
                interface,
                format!("size {RESIZED} in {state:?}"),
                (Expect::error("Configuration Mode"), WHY_MODE),
                state,
                Box::new(move |i| set_size(i, n, RESIZED as u64)),
            );
        }
        let running = match interface {
            Interface3::ModelExchange => State3::EventMode,
            _ => State3::StepMode,
        };
        cases.add(
            interface,
            format!("fmi3EnterConfigurationMode in {running:?}"),
            (Expect::error("Reconfiguration Mode"), WHY_RECONFIGURATION),
            running,
            Box::new(enter),
        );
        for state in [State3::InitializationMode, State3::Terminated] {
            cases.add(
                interface,
                format!("fmi3EnterConfigurationMode in {state:?}"),
                (Expect::error("fmi3EnterConfigurationMode"), WHY_ORDER),
                state,
                Box::new(enter),
            );
        }
        cases.add(
            interface,
            "fmi3ExitConfigurationMode in Instantiated".into(),
            (Expect::error("fmi3ExitConfigurationMode"), WHY_ORDER),
            State3::Instantiated,
            Box::new(exit),
        );
        cases.add(
            interface,
            "fmi3EnterConfigurationMode twice".into(),
            (Expect::error("fmi3EnterConfigurationMode"), WHY_ORDER),
            State3::Instantiated,
            Box::new(|i| if enter(i) == OK { enter(i) } else { FATAL }),
        );
        cases.add(
            interface,
            "fmi3SetUInt64 with nValues = 2".into(),
            (Expect::error("nValues = 2"), WHY_COUNT),
            State3::Instantiated,
            Box::new(move |i| {
                if enter(i) != OK {
                    return FATAL;
                }
                let values = [RESIZED as u64; 2];
                // SAFETY: one reference, two values.
                unsafe { (i.binary.set_uint64)(i.c, &n, 1, values.as_ptr(), 2) }
            }),
        );
        let (vr, name) = (array.0, array.1.clone());
        cases.add(
            interface,
            format!("fmi3GetFloat64({name}) with the old size {start} after a resize"),
            (Expect::error(&format!("nValues = {start}")), WHY_COUNT),
            State3::Instantiated,
            Box::new(move |i| resized(i, n, |i| get(i, vr, start).0)),
        );
        cases.add(
            interface,
            format!("fmi3SetFloat64({name}) with the old size {start} after a resize"),
            (Expect::error(&format!("nValues = {start}")), WHY_COUNT),
            State3::Instantiated,
            Box::new(move |i| {
                resized(i, n, |i| {
                    let before = get(i, vr, RESIZED);
                    let values = vec![0.125; start];
                    // SAFETY: one reference, `start` values.
                    let s = unsafe { (i.binary.set_float64)(i.c, &vr, 1, values.as_ptr(), start) };
                    // Nothing written: the values read in Error are those before.
                    let kept = before.0 == OK && get(i, vr, RESIZED) == before;
                    if kept { s } else { FATAL }
                })
            }),
        );
        cases.add(
            interface,
            format!("fmi3SerializedFMUStateSize at size {RESIZED}"),
            (Expect::error("default sizes only"), WHY_SERIALIZED),
            State3::Instantiated,
            Box::new(move |i| {
                resized(i, n, |i| {
                    let (s, state) = i.get_state();
                    if s != OK {
                        return FATAL;
                    }
                    let mut bytes = 0;
                    // SAFETY: a live instance and its own FMU state.
                    unsafe { (i.binary.serialized_size)(i.c, state, &mut bytes) }
                })
            }),
        );
        cases.add(
            interface,
            format!("size {RESIZED}, then {name} read with {RESIZED} values"),
            (Expect::ok(), WHY_CONTROL),
            State3::Instantiated,
            Box::new(move |i| {
                resized(i, n, |i| match get(i, vr, RESIZED) {
                    (OK, x) if x.iter().all(|v| v.is_finite()) => OK,
                    (OK, _) => FATAL,
                    (s, _) => s.max(ERROR),
                })
            }),
        );
    }
    cases.cases
}
