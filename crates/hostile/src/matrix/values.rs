//! Non-finite and extreme values for every variable a host can set.
//!
//! NaN and infinities are refused by fmi2SetReal with fmi2Error naming the
//! variable (FMI 2.0 has no non-finite Real values in a model; project choice to
//! refuse). Extreme finite values (±1e308, ±5e-324, the ends of the Integer range,
//! Booleans other than 0/1) follow issue 12: a value the model cannot work with is
//! refused when it is set or at fmi2ExitInitializationMode with a message naming
//! it; an input that overflows a step makes that step Discard; a getter is never
//! the first to notice (no fmi2Error from a getter, no NaN from a getter that
//! returned fmi2OK).

use super::{Case, Expect, Observed};
use crate::Loaded;
use crate::binary::{DISCARD, ERROR, OK, Status, status_name};
use crate::description::{VarType, Variable};
use crate::host::{Instance, Interface, Probed, State, take};
use crate::standard_interface::StandardInterface;

const WHY_NON_FINITE: &str = "NaN/inf set: refused by fmi2SetReal with fmi2Error naming the variable (project choice; FMI 2.0 Reals of a model are finite)";
const WHY_EXTREME: &str = "extreme finite value: refused at set or exitInitializationMode naming the variable, or a step Discard; never first noticed by a getter (issue 12 item 3)";

#[derive(Clone, Copy, Debug)]
enum Value {
    Real(f64),
    Integer(i32),
    Boolean(i32),
}

fn extremes(t: VarType) -> Vec<Value> {
    match t {
        VarType::Real => [1e308, -1e308, 5e-324, -5e-324].map(Value::Real).to_vec(),
        VarType::Integer => [i32::MIN, -1, 0, i32::MAX].map(Value::Integer).to_vec(),
        VarType::Boolean => [2, -1].map(Value::Boolean).to_vec(),
    }
}

fn set(inst: &Instance, vr: u32, value: Value) -> Status {
    // SAFETY: one reference and one value of the function's type.
    unsafe {
        match value {
            Value::Real(x) => inst.set_real(vr, x),
            Value::Integer(n) => (inst.binary.set_integer)(inst.c, &vr, 1, &n),
            Value::Boolean(b) => (inst.binary.set_boolean)(inst.c, &vr, 1, &b),
        }
    }
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = &loaded.fmus[m].description;
    let mut cases = Vec::new();
    for interface in Interface::BOTH {
        for v in d.variables.iter().filter(|v| v.is_settable()) {
            let vr = v.vr;
            if v.var_type == VarType::Real {
                for x in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
                    cases.push(Case {
                        class: "non-finite value",
                        model: m,
                        interface: Some(interface.short()),
                        name: format!("fmi2SetReal({} = {x})", v.name),
                        expect: Expect::error(&format!("\"{}\"", v.name)),
                        why: WHY_NON_FINITE,
                        probe: Box::new(move |l| {
                            super::on_instance(l, m, interface, State::Instantiated, |i| {
                                i.set_real(vr, x)
                            })
                        }),
                    });
                }
            }
            for value in extremes(v.var_type) {
                let var = v.clone();
                cases.push(Case {
                    class: "extreme value",
                    model: m,
                    interface: Some(interface.short()),
                    name: format!("{} = {value:?}", v.name),
                    expect: Expect {
                        statuses: &[OK, DISCARD, ERROR],
                        log: None,
                    },
                    why: WHY_EXTREME,
                    probe: Box::new(move |l| {
                        let inst = Instance::new(&l.binaries[m], &l.fmus[m].description, interface);
                        scenario(&inst, &var, value)
                    }),
                });
            }
        }
    }
    cases
}

/// Whether the log names the variable, or its array (\"theta0\" for \"theta0[2]\").
pub(crate) fn names(log: &str, variable: &str) -> bool {
    let array = variable.split('[').next().unwrap_or(variable);
    log.contains(variable) || log.contains(array)
}

/// After `what` returned `s` for a value of `variable`: a refusal whose log names
/// the variable is what the case expects; anything else is broken (both standards).
pub(crate) fn refused_naming<P: Probed>(
    inst: &P,
    variable: &str,
    what: &str,
    s: Status,
) -> Observed {
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

/// Set, initialize, one step (CS) or derivatives (ME), read every Real.
fn scenario(inst: &Instance, v: &Variable, value: Value) -> Observed {
    let refused_naming = |what: &str, s: Status| refused_naming(inst, &v.name, what, s);
    let s = set(inst, v.vr, value);
    if s != OK {
        return refused_naming("the set", s);
    }
    let b = inst.binary;
    // SAFETY: a live instance, legal calls with well-formed arguments.
    unsafe {
        (b.setup_experiment)(inst.c, 0, 0.0, 0.0, 0, 0.0);
        (b.enter_initialization_mode)(inst.c);
        let s = (b.exit_initialization_mode)(inst.c);
        if s != OK {
            return refused_naming("fmi2ExitInitializationMode", s);
        }
    }
    let discarded = match evaluate(inst) {
        Ok(d) => d,
        Err(e) => return Observed::broken(e),
    };
    read_outputs(inst, discarded)
}

/// One step or one evaluation; Ok(true) when it was discarded.
fn evaluate(inst: &Instance) -> Result<bool, String> {
    let d = inst.description;
    match inst.interface {
        Interface::CoSimulation => discarded(inst, "fmi2DoStep", inst.do_step(0.0, 1e-3)),
        Interface::ModelExchange => {
            me_evaluate::<Interface>(inst, (d.number_of_states, d.number_of_event_indicators))
        }
    }
}

fn read_outputs(inst: &Instance, discarded: bool) -> Observed {
    let d = inst.description;
    let may_discard = discarded && inst.interface == Interface::ModelExchange;
    for v in d.of_type(VarType::Real) {
        let (s, x) = inst.get_reals(&[v.vr]);
        match s {
            OK if !x[0].is_finite() => {
                return Observed::broken(format!(
                    "fmi2GetReal({}) returned fmi2OK with {}",
                    v.name, x[0]
                ));
            }
            OK => {}
            DISCARD if may_discard => {}
            _ => {
                return Observed::broken(format!(
                    "a getter was the first to notice: fmi2GetReal({}) returned {} (log: {})",
                    v.name,
                    status_name(s),
                    inst.take_log()
                ));
            }
        }
    }
    let status = if discarded { DISCARD } else { OK };
    Observed::of(status, inst.take_log())
}
