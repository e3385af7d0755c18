//! The FMI 3.0 functions that take an FMU state (class `matrix::states`) and that
//! evaluate the model (class `matrix::pose`), and the importer's side of the
//! value classes (`matrix::values`): set, initialize, evaluate.

use crate::binary::{OK, Status};
use crate::description::{Description, Variable};
use crate::fmi3::host::{Instance, Interface3};
use crate::matrix::same_named::{fmu_state_use_rows, me_evaluation_rows};
use crate::matrix::seam::{Evaluate, Use, Value};
use crate::matrix::values::{discarded, me_evaluate};

pub fn state_uses() -> Vec<(&'static str, Use<Interface3>)> {
    fmu_state_use_rows!("fmi3", "FMUState", u8)
}

pub fn evaluations() -> Vec<(&'static str, Evaluate<Interface3>)> {
    let mut rows: Vec<(&'static str, Evaluate<Interface3>)> = me_evaluation_rows!(
        "fmi3",
        "GetContinuousStateDerivatives",
        get_continuous_state_derivatives
    );
    rows.extend::<[(&'static str, Evaluate<Interface3>); 3]>([
        ("fmi3GetFloat64(thetaDot)", |i| {
            i.get_float64(&[i.description.by_name("thetaDot").vr]).0
        }),
        ("fmi3GetDirectionalDerivative(der(theta) by theta)", |i| {
            partial(i, false)
        }),
        ("fmi3GetAdjointDerivative(der(theta) by theta)", |i| {
            partial(i, true)
        }),
    ]);
    rows
}

fn partial(i: &Instance, adjoint: bool) -> Status {
    let d = i.description;
    let (x, dx) = d.state_derivative_pairs()[0];
    let n = d.elements(&[x]);
    let seed = vec![1.0; n];
    let mut out = vec![0.0; n];
    let f = if adjoint {
        i.binary.get_adjoint_derivative
    } else {
        i.binary.get_directional_derivative
    };
    // SAFETY: arrays of the variables' element counts (both 3).
    unsafe { f(i.c, &dx, 1, &x, 1, seed.as_ptr(), n, out.as_mut_ptr(), n) }
}

/// Whether element 1 of the continuous state is `theta[2]` (theta is the first
/// state).
pub fn unassemblable(d: &Description) -> bool {
    let theta = d.variables.iter().find(|v| v.name == "theta").map(|v| v.vr);
    let pairs = d.state_derivative_pairs();
    !pairs.is_empty() && theta == Some(pairs[0].0)
}

/// Sets the first element of `v` to `value`, the others to their start values
/// (0 for a calculated start).
pub fn set_value(inst: &Instance, v: &Variable, value: Value) -> Status {
    let starts: Vec<&str> = v
        .start
        .as_deref()
        .map(|s| s.split_whitespace().collect())
        .unwrap_or_default();
    let start = |k: usize| starts.get(k).copied().unwrap_or("0");
    // SAFETY: one reference and all its elements.
    unsafe {
        match value {
            Value::Real(x) => {
                let mut a: Vec<f64> = (0..v.size)
                    .map(|k| start(k).parse().unwrap_or(0.0))
                    .collect();
                a[0] = x;
                inst.set_float64(&[v.vr], &a)
            }
            Value::Integer(n) => {
                let mut a: Vec<i32> = (0..v.size).map(|k| start(k).parse().unwrap_or(0)).collect();
                a[0] = n;
                (inst.binary.set_int32)(inst.c, &v.vr, 1, a.as_ptr(), a.len())
            }
            Value::Boolean(b) => {
                let mut a: Vec<u8> = (0..v.size).map(|k| u8::from(start(k) == "true")).collect();
                a[0] = b as u8;
                (inst.binary.set_boolean)(inst.c, &v.vr, 1, a.as_ptr(), a.len())
            }
        }
    }
}

pub fn initialize(inst: &Instance) -> Result<(), (&'static str, Status)> {
    let b = inst.binary;
    // SAFETY: a live instance, legal calls with well-formed arguments.
    unsafe {
        let s = (b.enter_initialization_mode)(inst.c, 0, 0.0, 0.0, 0, 0.0);
        if s != OK {
            return Err(("fmi3EnterInitializationMode", s));
        }
        let s = (b.exit_initialization_mode)(inst.c);
        if s != OK {
            return Err(("fmi3ExitInitializationMode", s));
        }
    }
    Ok(())
}

/// One step or one evaluation; Ok(true) when it was discarded.
pub fn evaluate(inst: &Instance, interface: Interface3) -> Result<bool, String> {
    let d = inst.description;
    let step = || discarded(inst, "fmi3DoStep", inst.do_step(0.0, 1e-3).status);
    match interface {
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
