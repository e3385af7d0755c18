//! Non-finite and extreme values for every variable a host can set, and for the
//! scalar arguments of functions (times, step sizes, tolerances, continuous
//! states, seeds) where the standard's tables list them.
//!
//! NaN and infinities are refused by the setter with an error naming the variable
//! (project choice: a model's Real/Float64 values are finite), a scalar argument
//! with an error naming the function. Extreme finite values (±1e308, ±5e-324, the
//! ends of the Integer/Int32 range, Booleans other than false/true) follow issue
//! 12: a value the model cannot work with is refused when it is set or at
//! fmiXExitInitializationMode with a message naming it; an input that overflows a
//! step makes that step (or evaluation) Discard; a getter is never the first to
//! notice (no error from a getter, no NaN from a getter that returned OK).

use super::seam::{Standard, Value};
use super::{Case, Expect, Observed, on_instance};
use crate::Loaded;
use crate::binary::{DISCARD, ERROR, OK, Status, status_name};
use crate::description::{VarType, Variable};
use crate::host::{Probed, take};
use crate::standard_interface::StandardInterface;

fn extremes<I: Standard>(t: VarType) -> Vec<Value> {
    match t {
        VarType::Real => [1e308, -1e308, 5e-324, -5e-324].map(Value::Real).to_vec(),
        VarType::Integer => [i32::MIN, -1, 0, i32::MAX].map(Value::Integer).to_vec(),
        VarType::Boolean => I::tables().values.booleans.map(Value::Boolean).to_vec(),
    }
}

/// Whether the log names the variable, or its array (\"theta0\" for \"theta0[2]\").
fn names(log: &str, variable: &str) -> bool {
    let array = variable.split('[').next().unwrap_or(variable);
    log.contains(variable) || log.contains(array)
}

/// After `what` returned `s` for a value of `variable`: a refusal whose log names
/// the variable is what the case expects; anything else is broken (both standards).
fn refused_naming<P: Probed>(inst: &P, variable: &str, what: &str, s: Status) -> Observed {
    let log = take(inst.log());
    if s == ERROR && names(&log, variable) {
        Observed::of(ERROR, log)
    } else {
        Observed::broken(format!("{what} returned {} (log: {log})", status_name(s)))
    }
}

/// Ok(false) when `s` is OK, Ok(true) when Discard, else Err with the log.
pub(crate) fn discarded<P: Probed>(inst: &P, what: &str, s: Status) -> Result<bool, String> {
    match s {
        OK => Ok(false),
        DISCARD => Ok(true),
        _ => Err(format!(
            "{what} returned {} (log: {})",
            status_name(s),
            take(inst.log())
        )),
    }
}

/// Model Exchange from Event Mode: enter Continuous-Time Mode, get the
/// derivatives and the event indicators; Ok(true) when one was discarded (both
/// standards).
pub(crate) fn me_evaluate<I: StandardInterface>(
    inst: &I::Instance<'_>,
    (nx, nz): (usize, usize),
) -> Result<bool, String> {
    let (binary, handle) = I::raw(inst);
    let (enter, derivatives, indicators) = I::me_evaluation(binary);
    let c = handle.into();
    let (mut dx, mut z) = (vec![0.0; nx], vec![0.0; nz]);
    let name = |what: &str| format!("{}{what}", I::PREFIX);
    // SAFETY: a live instance in Event Mode; arrays of the declared sizes.
    unsafe {
        discarded(inst, &name("EnterContinuousTimeMode"), enter(c))?;
        let a = discarded(inst, I::DERIVATIVES, derivatives(c, dx.as_mut_ptr(), nx))?;
        let e = discarded(
            inst,
            &name("GetEventIndicators"),
            indicators(c, z.as_mut_ptr(), nz),
        )?;
        Ok(a || e)
    }
}

/// Set, initialize, one step (CS) or derivatives and indicators (ME), read every
/// output.
fn scenario<I: Standard>(
    inst: &I::Instance<'_>,
    interface: I,
    v: &Variable,
    value: Value,
) -> Observed {
    let refused_naming = |what: &str, s: Status| refused_naming(inst, &v.name, what, s);
    let s = I::set_value(inst, v, value);
    if s != OK {
        return refused_naming("the set", s);
    }
    if let Err((what, s)) = I::initialize(inst) {
        return refused_naming(what, s);
    }
    let discarded = match I::evaluate(inst, interface) {
        Ok(d) => d,
        Err(e) => return Observed::broken(e),
    };
    let (s, x) = I::outputs(inst);
    let getter = I::tables().values.getter;
    match s {
        OK if x.iter().any(|v| !v.is_finite()) => {
            Observed::broken(format!("{getter} returned OK with a non-finite value"))
        }
        OK => Observed::of(if discarded { DISCARD } else { OK }, take(inst.log())),
        DISCARD if discarded && interface.is_me() => Observed::of(DISCARD, take(inst.log())),
        _ => Observed::broken(format!(
            "a getter was the first to notice: {getter} returned {} (log: {})",
            status_name(s),
            take(inst.log())
        )),
    }
}

/// NaN and infinities set into the first element of a Real variable.
fn non_finite_cases<I: Standard>(m: usize, interface: I, v: &Variable) -> Vec<Case> {
    let names = I::tables().values;
    [f64::NAN, f64::INFINITY, f64::NEG_INFINITY]
        .into_iter()
        .map(|x| {
            let var = v.clone();
            Case::new(
                ("non-finite value", m, interface),
                format!("{}({}{} = {x})", names.setter, v.name, names.element),
                (
                    Expect::error(&format!("\"{}{}", v.name, names.quote_end)),
                    I::tables().reasons.non_finite,
                ),
                move |l| {
                    on_instance(l, m, interface, I::INSTANTIATED, |i| {
                        I::set_value(i, &var, Value::Real(x))
                    })
                },
            )
        })
        .collect()
}

fn extreme_case<I: Standard>(m: usize, interface: I, v: &Variable, value: Value) -> Case {
    let names = I::tables().values;
    let var = v.clone();
    let expect = Expect {
        statuses: &[OK, DISCARD, ERROR],
        log: None,
    };
    Case::new(
        ("extreme value", m, interface),
        format!("{}{} = {}", v.name, names.element, value.label(names.types)),
        (expect, I::tables().reasons.extreme),
        move |l| scenario(&interface.instance(l, m), interface, &var, value),
    )
}

pub fn cases<I: Standard>(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = I::description(loaded, m);
    let tables = I::tables();
    let mut cases = Vec::new();
    for &interface in I::INTERFACES {
        for v in d.variables.iter().filter(|v| v.is_settable()) {
            if v.var_type == VarType::Real {
                cases.extend(non_finite_cases(m, interface, v));
            }
            for value in extremes::<I>(v.var_type) {
                cases.push(extreme_case(m, interface, v, value));
            }
        }
        for (function, label, state, applies, call) in (tables.scalar_arguments)() {
            if !applies(d, interface) {
                continue;
            }
            cases.push(Case::new(
                ("non-finite value", m, interface),
                format!("{function}({label})"),
                (Expect::error(function), tables.reasons.argument),
                move |l| on_instance(l, m, interface, state, call),
            ));
        }
    }
    cases
}
