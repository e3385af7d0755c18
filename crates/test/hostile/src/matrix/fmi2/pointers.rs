//! The FMI 2.0 rows of the null-pointer class (`matrix::pointers`): every pointer
//! argument, with a length that makes the pointer necessary.

use crate::binary::FmuState;
use crate::description::Description;
use crate::host::{Interface, State};
use crate::matrix::pointers::{
    init, instantiated, me_continuous, me_with_indicators, me_with_states, with_partials,
};
use crate::matrix::same_named::{fmu_state_null_rows, model_exchange_null_rows};
use crate::matrix::seam::Row;
use std::ffi::c_char;
use std::ptr::{null, null_mut};

fn me_event(_: &Description, i: Interface) -> Option<State> {
    (i == Interface::ModelExchange).then_some(State::EventMode)
}
fn cs_step_complete(_: &Description, i: Interface) -> Option<State> {
    (i == Interface::CoSimulation).then_some(State::StepComplete)
}

pub fn table() -> Vec<Row<Interface>> {
    let mut t: Vec<Row<Interface>> = vec![
        (
            "fmi2SetDebugLogging(categories=null, n=1)",
            instantiated,
            |b, c, _| unsafe { (b.set_debug_logging)(c, 1, 1, null()) },
        ),
        ("fmi2GetReal(vr=null)", init, |b, c, _| unsafe {
            (b.get_real)(c, null(), 1, &mut 0.0)
        }),
        ("fmi2GetReal(value=null)", init, |b, c, a| unsafe {
            (b.get_real)(c, &a.real_vr, 1, null_mut())
        }),
        ("fmi2GetInteger(vr=null)", init, |b, c, _| unsafe {
            (b.get_integer)(c, null(), 1, &mut 0)
        }),
        ("fmi2GetInteger(value=null)", init, |b, c, a| unsafe {
            (b.get_integer)(c, &a.int_vr, 1, null_mut())
        }),
        ("fmi2GetBoolean(vr=null)", init, |b, c, _| unsafe {
            (b.get_boolean)(c, null(), 1, &mut 0)
        }),
        ("fmi2GetBoolean(value=null)", init, |b, c, a| unsafe {
            (b.get_boolean)(c, &a.bool_vr, 1, null_mut())
        }),
        ("fmi2GetString(vr=null)", init, |b, c, _| unsafe {
            (b.get_string)(c, null(), 1, &mut null())
        }),
        ("fmi2GetString(value=null)", init, |b, c, a| unsafe {
            (b.get_string)(c, &a.real_vr, 1, null_mut())
        }),
        ("fmi2SetReal(vr=null)", instantiated, |b, c, _| unsafe {
            (b.set_real)(c, null(), 1, &0.0)
        }),
        ("fmi2SetReal(value=null)", instantiated, |b, c, a| unsafe {
            (b.set_real)(c, &a.input_vr, 1, null())
        }),
        ("fmi2SetInteger(vr=null)", instantiated, |b, c, _| unsafe {
            (b.set_integer)(c, null(), 1, &1)
        }),
        (
            "fmi2SetInteger(value=null)",
            instantiated,
            |b, c, a| unsafe { (b.set_integer)(c, &a.int_vr, 1, null()) },
        ),
        ("fmi2SetBoolean(vr=null)", instantiated, |b, c, _| unsafe {
            (b.set_boolean)(c, null(), 1, &0)
        }),
        (
            "fmi2SetBoolean(value=null)",
            instantiated,
            |b, c, a| unsafe { (b.set_boolean)(c, &a.bool_vr, 1, null()) },
        ),
        ("fmi2SetString(vr=null)", instantiated, |b, c, _| unsafe {
            (b.set_string)(c, null(), 1, &c"x".as_ptr())
        }),
        (
            "fmi2SetString(value=null)",
            instantiated,
            |b, c, a| unsafe { (b.set_string)(c, &a.real_vr, 1, null()) },
        ),
    ];
    t.extend(state_table());
    t.extend(model_exchange_table());
    t.extend(co_simulation_table());
    t
}

fn state_table() -> Vec<Row<Interface>> {
    let mut t: Vec<Row<Interface>> =
        fmu_state_null_rows!("fmi2", "FMUstate", "DeSerialize", c_char, init::<Interface>);
    t.extend(derivative_table());
    t
}

fn derivative_table() -> Vec<Row<Interface>> {
    vec![
        (
            "fmi2GetDirectionalDerivative(vUnknown_ref=null)",
            with_partials,
            |b, c, a| unsafe {
                (b.get_directional_derivative)(c, null(), 1, &a.partial.1, 1, &1.0, &mut 0.0)
            },
        ),
        (
            "fmi2GetDirectionalDerivative(vKnown_ref=null)",
            with_partials,
            |b, c, a| unsafe {
                (b.get_directional_derivative)(c, &a.partial.0, 1, null(), 1, &1.0, &mut 0.0)
            },
        ),
        (
            "fmi2GetDirectionalDerivative(dvKnown=null)",
            with_partials,
            |b, c, a| unsafe {
                (b.get_directional_derivative)(
                    c,
                    &a.partial.0,
                    1,
                    &a.partial.1,
                    1,
                    null(),
                    &mut 0.0,
                )
            },
        ),
        (
            "fmi2GetDirectionalDerivative(dvUnknown=null)",
            with_partials,
            |b, c, a| unsafe {
                (b.get_directional_derivative)(
                    c,
                    &a.partial.0,
                    1,
                    &a.partial.1,
                    1,
                    &1.0,
                    null_mut(),
                )
            },
        ),
    ]
}

fn model_exchange_table() -> Vec<Row<Interface>> {
    let mut t: Vec<Row<Interface>> = vec![(
        "fmi2NewDiscreteStates(eventInfo=null)",
        me_event,
        |b, c, _| unsafe { (b.new_discrete_states)(c, null_mut()) },
    )];
    t.extend::<Vec<Row<Interface>>>(model_exchange_null_rows!(
        "fmi2",
        "GetDerivatives(derivatives",
        "x_nominal",
        get_derivatives
    ));
    t
}

fn co_simulation_table() -> Vec<Row<Interface>> {
    vec![
        (
            "fmi2SetRealInputDerivatives(vr=null)",
            cs_step_complete,
            |b, c, _| unsafe { (b.set_real_input_derivatives)(c, null(), 1, &1, &0.0) },
        ),
        (
            "fmi2SetRealInputDerivatives(order=null)",
            cs_step_complete,
            |b, c, a| unsafe { (b.set_real_input_derivatives)(c, &a.input_vr, 1, null(), &0.0) },
        ),
        (
            "fmi2SetRealInputDerivatives(value=null)",
            cs_step_complete,
            |b, c, a| unsafe { (b.set_real_input_derivatives)(c, &a.input_vr, 1, &1, null()) },
        ),
        (
            "fmi2GetRealOutputDerivatives(vr=null)",
            cs_step_complete,
            |b, c, _| unsafe { (b.get_real_output_derivatives)(c, null(), 1, &1, &mut 0.0) },
        ),
        (
            "fmi2GetRealOutputDerivatives(order=null)",
            cs_step_complete,
            |b, c, a| unsafe {
                (b.get_real_output_derivatives)(c, &a.real_vr, 1, null(), &mut 0.0)
            },
        ),
        (
            "fmi2GetRealOutputDerivatives(value=null)",
            cs_step_complete,
            |b, c, a| unsafe { (b.get_real_output_derivatives)(c, &a.real_vr, 1, &1, null_mut()) },
        ),
        (
            "fmi2GetStatus(value=null)",
            cs_step_complete,
            |b, c, _| unsafe { (b.get_status)(c, 0, null_mut()) },
        ),
        (
            "fmi2GetRealStatus(value=null)",
            cs_step_complete,
            |b, c, _| unsafe { (b.get_real_status)(c, 2, null_mut()) },
        ),
        (
            "fmi2GetIntegerStatus(value=null)",
            cs_step_complete,
            |b, c, _| unsafe { (b.get_integer_status)(c, 0, null_mut()) },
        ),
        (
            "fmi2GetBooleanStatus(value=null)",
            cs_step_complete,
            |b, c, _| unsafe { (b.get_boolean_status)(c, 3, null_mut()) },
        ),
        (
            "fmi2GetStringStatus(value=null)",
            cs_step_complete,
            |b, c, _| unsafe { (b.get_string_status)(c, 0, null_mut()) },
        ),
    ]
}
