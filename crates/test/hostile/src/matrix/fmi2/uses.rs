//! The FMI 2.0 functions that take an FMU state (class `matrix::states`) and that
//! evaluate the model (class `matrix::pose`), and the importer's side of the
//! value classes (`matrix::values`): set, initialize, evaluate.

use crate::binary::{OK, Status};
use crate::description::{Description, VarType, Variable};
use crate::host::{Instance, Interface, State};
use crate::matrix::same_named::{fmu_state_use_rows, me_evaluation_rows};
use crate::matrix::seam::{Evaluate, Use, Value};
use crate::matrix::values::{discarded, me_evaluate};
use std::ffi::c_char;

pub fn state_uses() -> Vec<(&'static str, Use<Interface>)> {
    fmu_state_use_rows!("fmi2", "FMUstate", c_char)
}

pub fn evaluations() -> Vec<(&'static str, Evaluate<Interface>)> {
    let mut rows: Vec<(&'static str, Evaluate<Interface>)> =
        me_evaluation_rows!("fmi2", "GetDerivatives", get_derivatives);
    rows.extend::<[(&'static str, Evaluate<Interface>); 2]>([
        ("fmi2GetReal(thetaDot[1])", |i| {
            i.get_reals(&[i.description.by_name("thetaDot[1]").vr]).0
        }),
        (
            "fmi2GetDirectionalDerivative(der(state 1) by state 2)",
            |i| unsafe {
                let pairs = i.description.state_derivative_pairs();
                let (unknown, known) = (pairs[0].1, pairs[1].0);
                (i.binary.get_directional_derivative)(i.c, &unknown, 1, &known, 1, &1.0, &mut 0.0)
            },
        ),
    ]);
    rows
}

/// Whether element 1 of the continuous state is `theta[2]`.
pub fn unassemblable(d: &Description) -> bool {
    let pairs = d.state_derivative_pairs();
    let theta2 = d
        .variables
        .iter()
        .find(|v| v.name == "theta[2]")
        .map(|v| v.vr);
    pairs.len() >= 2 && theta2 == Some(pairs[1].0)
}

pub fn set_value(inst: &Instance, v: &Variable, value: Value) -> Status {
    let vr = v.vr;
    // SAFETY: one reference and one value of the function's type.
    unsafe {
        match value {
            Value::Real(x) => inst.set_real(vr, x),
            Value::Integer(n) => (inst.binary.set_integer)(inst.c, &vr, 1, &n),
            Value::Boolean(b) => (inst.binary.set_boolean)(inst.c, &vr, 1, &b),
        }
    }
}

pub fn initialize(inst: &Instance) -> Result<(), (&'static str, Status)> {
    let b = inst.binary;
    // SAFETY: a live instance, legal calls with well-formed arguments.
    let s = unsafe {
        (b.setup_experiment)(inst.c, 0, 0.0, 0.0, 0, 0.0);
        (b.enter_initialization_mode)(inst.c);
        (b.exit_initialization_mode)(inst.c)
    };
    if s == OK {
        Ok(())
    } else {
        Err(("fmi2ExitInitializationMode", s))
    }
}

pub fn evaluate(inst: &Instance, interface: Interface) -> Result<bool, String> {
    let d = inst.description;
    match interface {
        Interface::CoSimulation => discarded(inst, "fmi2DoStep", inst.do_step(0.0, 1e-3)),
        Interface::ModelExchange => {
            me_evaluate::<Interface>(inst, (d.number_of_states, d.number_of_event_indicators))
        }
    }
}

/// The Real values of the instance.
pub fn outputs(inst: &Instance) -> (Status, Vec<f64>) {
    inst.get_reals(&inst.description.real_vrs())
}

/// The states after initialization where the setter of type `t` is legal (FMI 2.0
/// 3.2.3, 4.2.4: fmi2SetReal also in Continuous-Time Mode).
pub fn setter_states(t: VarType) -> &'static [State] {
    match t {
        VarType::Real => &[
            State::EventMode,
            State::ContinuousTimeMode,
            State::StepComplete,
        ],
        _ => &[State::EventMode, State::StepComplete],
    }
}
