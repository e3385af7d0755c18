//! Non-finite and extreme values for every variable a host can set, and for the
//! scalar arguments of the FMI 3.0 functions (times, step sizes, tolerances,
//! continuous states, seeds).
//!
//! NaN and infinities are refused with fmi3Error and a log line naming the
//! variable or the function (project choice: a model's Float64 values are
//! finite). Extreme finite values (±1e308, ±5e-324, the ends of the Int32 range,
//! Boolean bytes 2 and 255) follow the FMI 2.0 rule of issue 12: refused when set
//! or at fmi3ExitInitializationMode naming the variable, or a step/evaluation that
//! returns fmi3Discard; a getter is never the first to notice.

use super::{Case, Observed, on_instance};
use crate::Loaded;
use crate::binary::{DISCARD, ERROR, OK, Status, status_name};
use crate::description::{Description, VarType, Variable};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::matrix::Expect;
use crate::matrix::values::{discarded, me_evaluate, refused_naming};

const WHY_NON_FINITE: &str = "NaN/inf set: refused by fmi3SetFloat64 with fmi3Error naming the variable (project choice; Float64 values of a model are finite)";
const WHY_ARGUMENT: &str = "non-finite or out-of-range scalar argument (FMI 3.0: times finite, step size > 0, a step starts at the FMU's time (4.2.1), tolerance > 0, stopTime >= startTime): fmi3Error and a log line naming the function";
const WHY_EXTREME: &str = "extreme finite value: refused at set or fmi3ExitInitializationMode naming the variable, or a step/evaluation Discard; never first noticed by a getter (issue 12 item 3 for FMI 3.0)";

#[derive(Clone, Copy, Debug)]
enum Value {
    Float64(f64),
    Int32(i32),
    Boolean(u8),
}

fn extremes(t: VarType) -> Vec<Value> {
    match t {
        VarType::Real => [1e308, -1e308, 5e-324, -5e-324]
            .map(Value::Float64)
            .to_vec(),
        VarType::Integer => [i32::MIN, -1, 0, i32::MAX].map(Value::Int32).to_vec(),
        VarType::Boolean => [2, 255].map(Value::Boolean).to_vec(),
    }
}

/// Sets the first element of `v` to `value`, the others to their start values
/// (0 for a calculated start).
fn set(inst: &Instance, v: &Variable, value: Value) -> Status {
    let starts: Vec<&str> = v
        .start
        .as_deref()
        .map(|s| s.split_whitespace().collect())
        .unwrap_or_default();
    let start = |k: usize| starts.get(k).copied().unwrap_or("0");
    // SAFETY: one reference and all its elements.
    unsafe {
        match value {
            Value::Float64(x) => {
                let mut a: Vec<f64> = (0..v.size)
                    .map(|k| start(k).parse().unwrap_or(0.0))
                    .collect();
                a[0] = x;
                inst.set_float64(&[v.vr], &a)
            }
            Value::Int32(n) => {
                let mut a: Vec<i32> = (0..v.size).map(|k| start(k).parse().unwrap_or(0)).collect();
                a[0] = n;
                (inst.binary.set_int32)(inst.c, &v.vr, 1, a.as_ptr(), a.len())
            }
            Value::Boolean(b) => {
                let mut a: Vec<u8> = (0..v.size).map(|k| u8::from(start(k) == "true")).collect();
                a[0] = b;
                (inst.binary.set_boolean)(inst.c, &v.vr, 1, a.as_ptr(), a.len())
            }
        }
    }
}

/// Set, initialize, one step (CS) or derivatives and indicators (ME), read every
/// Float64.
fn scenario(inst: &Instance, v: &Variable, value: Value) -> Observed {
    let refused_naming = |what: &str, s: Status| refused_naming(inst, &v.name, what, s);
    let s = set(inst, v, value);
    if s != OK {
        return refused_naming("the set", s);
    }
    let b = inst.binary;
    // SAFETY: a live instance, legal calls with well-formed arguments.
    unsafe {
        let s = (b.enter_initialization_mode)(inst.c, 0, 0.0, 0.0, 0, 0.0);
        if s != OK {
            return refused_naming("fmi3EnterInitializationMode", s);
        }
        let s = (b.exit_initialization_mode)(inst.c);
        if s != OK {
            return refused_naming("fmi3ExitInitializationMode", s);
        }
    }
    let discarded = match evaluate(inst) {
        Ok(d) => d,
        Err(e) => return Observed::broken(e),
    };
    let (s, x) = inst.get_all();
    match s {
        OK if x.iter().any(|v| !v.is_finite()) => {
            Observed::broken("fmi3GetFloat64 returned OK with a non-finite value".into())
        }
        OK => Observed::of(if discarded { DISCARD } else { OK }, inst.take_log()),
        DISCARD if discarded && inst.interface.is_me() => Observed::of(DISCARD, inst.take_log()),
        _ => Observed::broken(format!(
            "a getter was the first to notice: fmi3GetFloat64 returned {} (log: {})",
            status_name(s),
            inst.take_log()
        )),
    }
}

/// One step or one evaluation; Ok(true) when it was discarded.
fn evaluate(inst: &Instance) -> Result<bool, String> {
    let d = inst.description;
    let step = || discarded(inst, "fmi3DoStep", inst.do_step(0.0, 1e-3).status);
    match inst.interface {
        Interface3::ModelExchange => {
            me_evaluate::<Interface3>(inst, (d.number_of_states, d.number_of_event_indicators))
        }
        Interface3::CoSimulationEvents => {
            // SAFETY: a live instance in Event Mode.
            let s = unsafe { (inst.binary.enter_step_mode)(inst.c) };
            discarded(inst, "fmi3EnterStepMode", s)?;
            step()
        }
        Interface3::CoSimulation => step(),
    }
}

type Applies = fn(&Description, Interface3) -> bool;
type Scalar = (
    &'static str,
    &'static str,
    State3,
    Applies,
    fn(&Instance) -> Status,
);

fn scalar_arguments() -> Vec<Scalar> {
    let any: Applies = |_, _| true;
    let me: Applies = |_, i| i.is_me();
    let me_states: Applies = |d, i| i.is_me() && d.number_of_states > 0;
    let cs: Applies = |_, i| i == Interface3::CoSimulation;
    let partials: Applies = |d, _| !d.state_derivative_pairs().is_empty();
    vec![
        (
            "fmi3EnterInitializationMode",
            "startTime = NaN",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, f64::NAN, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "startTime = inf",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, f64::INFINITY, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "tolerance = -1",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 1, -1.0, 0.0, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "tolerance = NaN",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 1, f64::NAN, 0.0, 0, 0.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "stopTime = -1 < startTime",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, 0.0, 1, -1.0) },
        ),
        (
            "fmi3EnterInitializationMode",
            "stopTime = NaN",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.enter_initialization_mode)(i.c, 0, 0.0, 0.0, 1, f64::NAN) },
        ),
        (
            "fmi3SetDebugLogging",
            "categories = [\"noSuchCategory\"]",
            State3::Instantiated,
            any,
            |i| unsafe { (i.binary.set_debug_logging)(i.c, 1, 1, &c"noSuchCategory".as_ptr()) },
        ),
        (
            "fmi3SetTime",
            "time = NaN",
            State3::ContinuousTimeMode,
            me,
            |i| unsafe { (i.binary.set_time)(i.c, f64::NAN) },
        ),
        (
            "fmi3SetTime",
            "time = inf",
            State3::ContinuousTimeMode,
            me,
            |i| unsafe { (i.binary.set_time)(i.c, f64::INFINITY) },
        ),
        (
            "fmi3SetContinuousStates",
            "x[0] = NaN",
            State3::ContinuousTimeMode,
            me_states,
            |i| unsafe {
                let n = i.description.number_of_states;
                let mut x = vec![0.0; n];
                (i.binary.get_continuous_states)(i.c, x.as_mut_ptr(), n);
                if let Some(first) = x.first_mut() {
                    *first = f64::NAN;
                }
                (i.binary.set_continuous_states)(i.c, x.as_ptr(), n)
            },
        ),
        (
            "fmi3DoStep",
            "communicationStepSize = NaN",
            State3::StepMode,
            cs,
            |i| i.do_step(0.0, f64::NAN).status,
        ),
        (
            "fmi3DoStep",
            "communicationStepSize = inf",
            State3::StepMode,
            cs,
            |i| i.do_step(0.0, f64::INFINITY).status,
        ),
        (
            "fmi3DoStep",
            "communicationStepSize = -1 ms",
            State3::StepMode,
            cs,
            |i| i.do_step(0.0, -1e-3).status,
        ),
        (
            "fmi3DoStep",
            "currentCommunicationPoint = NaN",
            State3::StepMode,
            cs,
            |i| i.do_step(f64::NAN, 1e-3).status,
        ),
        (
            "fmi3DoStep",
            "currentCommunicationPoint = 1 s, the FMU is at 0 s",
            State3::StepMode,
            cs,
            |i| i.do_step(1.0, 1e-3).status,
        ),
        (
            "fmi3GetDirectionalDerivative",
            "seed = NaN",
            State3::InitializationMode,
            partials,
            |i| unsafe {
                let d = i.description;
                let Some(&(x, dx)) = d.state_derivative_pairs().first() else {
                    return ERROR;
                };
                let seed = vec![f64::NAN; d.elements(&[x])];
                let mut out = vec![0.0; d.elements(&[dx])];
                (i.binary.get_directional_derivative)(
                    i.c,
                    &dx,
                    1,
                    &x,
                    1,
                    seed.as_ptr(),
                    seed.len(),
                    out.as_mut_ptr(),
                    out.len(),
                )
            },
        ),
    ]
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = &loaded.fmus3[m].description;
    let mut cases = Vec::new();
    for interface in Interface3::ALL {
        for v in d.variables.iter().filter(|v| v.is_settable()) {
            if v.var_type == VarType::Real {
                for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    let var = v.clone();
                    cases.push(Case {
                        class: "fmi3 non-finite value",
                        model: m,
                        interface: Some(interface.short()),
                        name: format!("fmi3SetFloat64({}[0] = {x})", v.name),
                        // The log names the element: "theta0[1]" for theta0[0].
                        expect: Expect::error(&format!("\"{}", v.name)),
                        why: WHY_NON_FINITE,
                        probe: Box::new(move |l| {
                            on_instance(l, m, interface, State3::Instantiated, |i| {
                                set(i, &var, Value::Float64(x))
                            })
                        }),
                    });
                }
            }
            for value in extremes(v.var_type) {
                let var = v.clone();
                cases.push(Case {
                    class: "fmi3 extreme value",
                    model: m,
                    interface: Some(interface.short()),
                    name: format!("{}[0] = {value:?}", v.name),
                    expect: Expect {
                        statuses: &[OK, DISCARD, ERROR],
                        log: None,
                    },
                    why: WHY_EXTREME,
                    probe: Box::new(move |l| {
                        let inst =
                            Instance::new(&l.binaries3[m], &l.fmus3[m].description, interface);
                        scenario(&inst, &var, value)
                    }),
                });
            }
        }
        for (function, label, state, applies, call) in scalar_arguments() {
            if !applies(d, interface) {
                continue;
            }
            cases.push(Case {
                class: "fmi3 non-finite value",
                model: m,
                interface: Some(interface.short()),
                name: format!("{function}({label})"),
                expect: Expect::error(function),
                why: WHY_ARGUMENT,
                probe: Box::new(move |l| on_instance(l, m, interface, state, call)),
            });
        }
    }
    cases
}
