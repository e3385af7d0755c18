//! The clocked partitions (FMI 3.0 section 2.2.9): for every FMU whose FMI 3.0
//! description declares an input clock, the clock functions in states where they are
//! illegal, with bad intervals (0, NaN, negative, 1e300) through the period parameter
//! and through fmi3SetIntervalDecimal, with a value reference that is no clock, a
//! null values array, Event Mode left with a clock set but not ticked, and a step
//! past a tick without earlyReturnAllowed. Expected: fmi3Error and a log line naming
//! the function or the argument; after it the instance recovers with fmi3Reset (the
//! matrix's `usable_after`). Controls: the legal calls return fmi3OK.
//!
//! The clock's value reference is read from the checked-in description
//! (`modelDescription/fmi3/<Model>.xml`, equal to the packaged one: the packager's
//! drift check); the matrix's description keeps no clocks.

use super::InstanceCases;
use crate::Loaded;
use crate::binary::Status;
use crate::fmi3::binary::{Binary3, Instance3 as Handle};
use crate::fmi3::host::{Instance, Interface3, State3, logger};
use crate::fmu::workspace_root;
use crate::host::{Log, c_string};
use crate::matrix::{Case, Expect};
use std::ffi::c_void;

const WHY_STATE: &str = "FMI 3.0 2.2.9: fmi3SetClock only in Event Mode, fmi3GetInterval* only in Initialization and Event Mode: fmi3Error naming the function";
const WHY_ARGUMENT: &str = "FMI 3.0 2.2.9: a clock interval is a positive finite time; a fixed clock without intervalDecimal is not set by the importer; only clocks are clock references: fmi3Error and a log line";
const WHY_PENDING: &str = "project choice: a clock set in Event Mode is ticked by fmi3UpdateDiscreteStates; leaving Event Mode before it is refused (the tick is not lost silently)";
const WHY_EARLY: &str = "FMI 3.0 4.2.1: without earlyReturnAllowed a step cannot end before its end; a step past a tick of a clock the importer drives is refused with fmi3Error";
const WHY_CONTROL: &str = "FMI 3.0 2.2.9: the legal clock calls succeed";

/// The value reference of the first input clock of `model`'s FMI 3.0 description.
fn clock_of(model: &str) -> Option<u32> {
    let path = workspace_root().join(format!("modelDescription/fmi3/{model}.xml"));
    let xml = std::fs::read_to_string(path).ok()?;
    let tag = &xml[xml.find("<Clock ")?..];
    let tag = &tag[..tag.find('>')?];
    let vr = &tag[tag.find("valueReference=\"")? + 16..];
    vr[..vr.find('"')?].parse().ok()
}

fn set_clock_on(b: &Binary3, c: Handle, vr: u32) -> Status {
    // SAFETY: a live instance, one reference, one value.
    unsafe { (b.set_clock)(c, &vr, 1, &1) }
}

fn set_clock(i: &Instance, vr: u32) -> Status {
    set_clock_on(i.binary, i.c, vr)
}

fn interval(i: &Instance, vr: u32) -> Status {
    let (mut x, mut q) = (0.0, 0);
    // SAFETY: one reference, one interval and one qualifier.
    unsafe { (i.binary.get_interval_decimal)(i.c, &vr, 1, &mut x, &mut q) }
}

fn set_interval(i: &Instance, vr: u32, x: f64) -> Status {
    // SAFETY: one reference, one value.
    unsafe { (i.binary.set_interval_decimal)(i.c, &vr, 1, &x) }
}

fn update_on(b: &Binary3, c: Handle) -> Status {
    let (mut a, mut e, mut n, mut v, mut d, mut t) = (0, 0, 0, 0, 0, 0.0);
    // SAFETY: a live instance, six outputs.
    unsafe { (b.update_discrete_states)(c, &mut a, &mut e, &mut n, &mut v, &mut d, &mut t) }
}

fn update(i: &Instance) -> Status {
    update_on(i.binary, i.c)
}

/// fmi3SetClock at t = 0 in Event Mode, its tick, and Step Mode: the instance then
/// drives the clock.
fn tick_and_step_mode(b: &Binary3, c: Handle, vr: u32) -> Status {
    let s = set_clock_on(b, c, vr).max(update_on(b, c));
    // SAFETY: a live instance in Event Mode.
    s.max(unsafe { (b.enter_step_mode)(c) })
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = &loaded.fmus3[m].description;
    let Some(clock) = clock_of(&d.model_name) else {
        return Vec::new();
    };
    let period = d
        .variables
        .iter()
        .find(|v| v.is_parameter() && v.variability == "fixed" && v.name.ends_with("Period"))
        .map(|v| (v.vr, v.name.clone()));
    let mut cases = InstanceCases::new("clocks", m);
    for interface in [Interface3::ModelExchange, Interface3::CoSimulationEvents] {
        for state in State3::of(
            interface,
            &[
                State3::Instantiated,
                State3::InitializationMode,
                State3::ContinuousTimeMode,
                State3::StepMode,
                State3::Terminated,
            ],
        ) {
            cases.add(
                interface,
                format!("fmi3SetClock in {state:?}"),
                (Expect::error("fmi3SetClock"), WHY_STATE),
                state,
                Box::new(move |i| set_clock(i, clock)),
            );
        }
        for state in State3::of(
            interface,
            &[
                State3::Instantiated,
                State3::ContinuousTimeMode,
                State3::StepMode,
            ],
        ) {
            cases.add(
                interface,
                format!("fmi3GetIntervalDecimal in {state:?}"),
                (Expect::error("fmi3GetIntervalDecimal"), WHY_STATE),
                state,
                Box::new(move |i| interval(i, clock)),
            );
        }
        cases.add(
            interface,
            "fmi3SetClock at a tick in Event Mode".into(),
            (Expect::ok(), WHY_CONTROL),
            State3::EventMode,
            Box::new(move |i| set_clock(i, clock).max(update(i))),
        );
        cases.add(
            interface,
            "fmi3GetIntervalDecimal in InitializationMode".into(),
            (Expect::ok(), WHY_CONTROL),
            State3::InitializationMode,
            Box::new(move |i| interval(i, clock)),
        );
        for bad in [0.0, f64::NAN, -1e-3] {
            cases.add(
                interface,
                format!("fmi3SetIntervalDecimal({bad})"),
                (Expect::error("not a valid clock interval"), WHY_ARGUMENT),
                State3::InitializationMode,
                Box::new(move |i| set_interval(i, clock, bad)),
            );
        }
        cases.add(
            interface,
            "fmi3SetIntervalDecimal(1e300) of a fixed clock".into(),
            (Expect::error("intervalVariability"), WHY_ARGUMENT),
            State3::InitializationMode,
            Box::new(move |i| set_interval(i, clock, 1e300)),
        );
        if let Some((vr, name)) = period.clone() {
            for bad in [0.0, f64::NAN, -1e-3, 1e300] {
                cases.add(
                    interface,
                    format!("{name} = {bad}"),
                    (Expect::error(&name), WHY_ARGUMENT),
                    State3::Instantiated,
                    Box::new(move |i| i.set_float64(&[vr], &[bad])),
                );
            }
        }
        let unknown = 999_999;
        cases.add(
            interface,
            "fmi3SetClock of an unknown value reference".into(),
            (
                Expect::error("unknown value reference 999999"),
                WHY_ARGUMENT,
            ),
            State3::EventMode,
            Box::new(move |i| set_clock(i, unknown)),
        );
        cases.add(
            interface,
            "fmi3GetIntervalDecimal of an unknown value reference".into(),
            (
                Expect::error("unknown value reference 999999"),
                WHY_ARGUMENT,
            ),
            State3::EventMode,
            Box::new(move |i| interval(i, unknown)),
        );
        let float = d
            .variables
            .iter()
            .find(|v| {
                v.var_type == crate::description::VarType::Real && v.causality != "independent"
            })
            .map_or(1, |v| v.vr);
        cases.add(
            interface,
            "fmi3SetClock of a Float64 variable".into(),
            (Expect::error("not a Clock"), WHY_ARGUMENT),
            State3::EventMode,
            Box::new(move |i| set_clock(i, float)),
        );
        cases.add(
            interface,
            "fmi3SetClock with values = NULL".into(),
            (Expect::error("values[] is a null pointer"), WHY_ARGUMENT),
            State3::EventMode,
            Box::new(move |i| unsafe { (i.binary.set_clock)(i.c, &clock, 1, std::ptr::null()) }),
        );
    }
    cases.add(
        Interface3::CoSimulationEvents,
        "fmi3EnterStepMode with a clock set, not ticked".into(),
        (Expect::error("fmi3UpdateDiscreteStates"), WHY_PENDING),
        State3::EventMode,
        Box::new(move |i| set_clock(i, clock).max(unsafe { (i.binary.enter_step_mode)(i.c) })),
    );
    cases.add(
        Interface3::ModelExchange,
        "fmi3EnterContinuousTimeMode with a clock set, not ticked".into(),
        (Expect::error("fmi3UpdateDiscreteStates"), WHY_PENDING),
        State3::EventMode,
        Box::new(move |i| {
            set_clock(i, clock).max(unsafe { (i.binary.enter_continuous_time_mode)(i.c) })
        }),
    );
    cases.add(
        Interface3::CoSimulationEvents,
        "a step to the next tick".into(),
        (Expect::ok(), WHY_CONTROL),
        State3::EventMode,
        Box::new(move |i| {
            tick_and_step_mode(i.binary, i.c, clock).max(i.do_step(0.0, 1e-3).status)
        }),
    );
    cases.add(
        Interface3::CoSimulationEvents,
        "a step past a tick without earlyReturnAllowed".into(),
        (Expect::error("passes the clock tick"), WHY_EARLY),
        State3::Instantiated,
        Box::new(move |i| past_tick_without_early_return(i, clock)),
    );
    cases.cases
}

/// A Co-Simulation instance of its own, with event mode but without early return,
/// that drives the clock, then a step of 1.5 intervals (read with
/// fmi3GetIntervalDecimal); the status of that step. Its log goes to `i`'s.
fn past_tick_without_early_return(i: &Instance, clock: u32) -> Status {
    let b = i.binary;
    let name = c_string("early");
    let token = c_string(&i.description.guid);
    let env = &*i.log as *const Log as *mut c_void;
    let null = std::ptr::null();
    // SAFETY: valid strings, the logger and the environment of `i` (which outlives
    // this instance); well-formed arguments; the instance is freed before returning.
    unsafe {
        let c = (b.instantiate_cs)(
            name.as_ptr(),
            token.as_ptr(),
            null,
            0,
            1,
            1,
            0,
            std::ptr::null(),
            0,
            env,
            logger(),
            std::ptr::null(),
        );
        if c.is_null() {
            return -1;
        }
        let mut status = (b.enter_initialization_mode)(c, 0, 0.0, 0.0, 0, 0.0);
        let (mut x, mut q) = (0.0, 0);
        status = status.max((b.get_interval_decimal)(c, &clock, 1, &mut x, &mut q));
        status = status.max((b.exit_initialization_mode)(c));
        status = status.max(tick_and_step_mode(b, c, clock));
        let step = if status == 0 {
            let (mut event, mut stop, mut early, mut last) = (0, 0, 0, 0.0);
            (b.do_step)(
                c,
                0.0,
                1.5 * x,
                1,
                &mut event,
                &mut stop,
                &mut early,
                &mut last,
            )
        } else {
            -1
        };
        (b.free_instance)(c);
        step
    }
}
