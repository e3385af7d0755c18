//! Every tunable parameter and input set again after initialization, in each state
//! where its setter is legal (Event Mode, Continuous-Time Mode, Step Mode), to its
//! start value. FMI 3.0 (section 2.4.7.4, variability; 3.3 and 4.3, the state
//! tables) lets a tunable parameter change only in Event Mode (Model Exchange and
//! Co-Simulation with event mode) and in Step Mode (Co-Simulation), and an input in
//! every state where its setter is legal. Expected: fmi3OK where allowed, otherwise
//! fmi3Error naming the variable (and the instance recovers with fmi3Reset). Fixed
//! parameters, for both standards, are the class `fixed` (`matrix/fixed.rs`).

use crate::Loaded;
use crate::binary::Status;
use crate::description::{VarType, Variable};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::matrix::{Case, Expect, on_instance};

const WHY_ALLOWED: &str = "FMI 3.0 2.4.7.4: inputs in every state where their setter is legal, tunable parameters in Event and Step Mode: fmi3OK";
const WHY_REFUSED: &str = "FMI 3.0 2.4.7.4: a tunable parameter cannot change in Continuous-Time Mode: fmi3Error naming it";

/// Whether the standard lets `v` change in `state` (its setter being legal there).
fn may_change(v: &Variable, state: State3) -> bool {
    match (v.causality.as_str(), v.variability.as_str()) {
        ("input", _) => true,
        ("parameter", "tunable") => state != State3::ContinuousTimeMode,
        _ => false,
    }
}

/// States after initialization where the setter of type `t` is legal.
pub fn setter_states(t: VarType) -> &'static [State3] {
    match t {
        VarType::Real => &[
            State3::EventMode,
            State3::ContinuousTimeMode,
            State3::StepMode,
        ],
        _ => &[State3::EventMode, State3::StepMode],
    }
}

/// Sets `v` to its start values (zeros when it has none).
fn set_start(i: &Instance, v: &Variable) -> Status {
    let starts: Vec<&str> = v
        .start
        .as_deref()
        .unwrap_or("")
        .split_whitespace()
        .collect();
    let start = |k: usize| starts.get(k).copied().unwrap_or("0");
    let vr = v.vr;
    // SAFETY: one reference and all its elements.
    unsafe {
        match v.var_type {
            VarType::Real => {
                let x: Vec<f64> = (0..v.size)
                    .map(|k| start(k).parse().unwrap_or(0.0))
                    .collect();
                i.set_float64(&[vr], &x)
            }
            VarType::Integer => {
                let x: Vec<i32> = (0..v.size).map(|k| start(k).parse().unwrap_or(0)).collect();
                (i.binary.set_int32)(i.c, &vr, 1, x.as_ptr(), x.len())
            }
            VarType::Boolean => {
                let x: Vec<u8> = (0..v.size).map(|k| u8::from(start(k) == "true")).collect();
                (i.binary.set_boolean)(i.c, &vr, 1, x.as_ptr(), x.len())
            }
        }
    }
}

pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = &loaded.fmus3[m].description;
    let mut cases = Vec::new();
    for interface in Interface3::ALL {
        let settable = d.variables.iter().filter(|v| v.is_settable());
        for v in settable.filter(|v| !(v.is_parameter() && v.variability == "fixed")) {
            for state in State3::of(interface, setter_states(v.var_type)) {
                let allowed = may_change(v, state);
                let var = v.clone();
                cases.push(Case::new(
                    ("variability", m, interface),
                    format!("{} {} {} in {state:?}", v.variability, v.causality, v.name),
                    (
                        if allowed {
                            Expect::ok()
                        } else {
                            Expect::error(&format!("\"{}", v.name))
                        },
                        if allowed { WHY_ALLOWED } else { WHY_REFUSED },
                    ),
                    move |l| on_instance(l, m, interface, state, |i| set_start(i, &var)),
                ));
            }
        }
    }
    cases
}
