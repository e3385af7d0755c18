//! The FMI 2.0 rows of the null-pointer class (`matrix::pointers`): every pointer
//! argument, with a length that makes the pointer necessary.

use crate::binary::FmuState;
use crate::description::Description;
use crate::host::{Interface, State};
use crate::matrix::seam::Row;
use std::ptr::{null, null_mut};

fn both_init(_: &Description, _: Interface) -> Option<State> {
    Some(State::InitializationMode)
}
fn both_instantiated(_: &Description, _: Interface) -> Option<State> {
    Some(State::Instantiated)
}
fn me_event(_: &Description, i: Interface) -> Option<State> {
    (i == Interface::ModelExchange).then_some(State::EventMode)
}
fn me_continuous(_: &Description, i: Interface) -> Option<State> {
    (i == Interface::ModelExchange).then_some(State::ContinuousTimeMode)
}
fn me_with_states(d: &Description, i: Interface) -> Option<State> {
    (d.number_of_states > 0).then_some(me_continuous(d, i)?)
}
fn me_with_indicators(d: &Description, i: Interface) -> Option<State> {
    (d.number_of_event_indicators > 0).then_some(me_continuous(d, i)?)
}
fn cs_step_complete(_: &Description, i: Interface) -> Option<State> {
    (i == Interface::CoSimulation).then_some(State::StepComplete)
}
fn with_partials(d: &Description, _: Interface) -> Option<State> {
    d.provides_directional_derivative
        .then_some(State::InitializationMode)
}

pub fn table() -> Vec<Row<Interface>> {
    let mut t: Vec<Row<Interface>> = vec![
        (
            "fmi2SetDebugLogging(categories=null, n=1)",
            both_instantiated,
            |b, c, _| unsafe { (b.set_debug_logging)(c, 1, 1, null()) },
        ),
        ("fmi2GetReal(vr=null)", both_init, |b, c, _| unsafe {
            (b.get_real)(c, null(), 1, &mut 0.0)
        }),
        ("fmi2GetReal(value=null)", both_init, |b, c, a| unsafe {
            (b.get_real)(c, &a.real_vr, 1, null_mut())
        }),
        ("fmi2GetInteger(vr=null)", both_init, |b, c, _| unsafe {
            (b.get_integer)(c, null(), 1, &mut 0)
        }),
        ("fmi2GetInteger(value=null)", both_init, |b, c, a| unsafe {
            (b.get_integer)(c, &a.int_vr, 1, null_mut())
        }),
        ("fmi2GetBoolean(vr=null)", both_init, |b, c, _| unsafe {
            (b.get_boolean)(c, null(), 1, &mut 0)
        }),
        ("fmi2GetBoolean(value=null)", both_init, |b, c, a| unsafe {
            (b.get_boolean)(c, &a.bool_vr, 1, null_mut())
        }),
        ("fmi2GetString(vr=null)", both_init, |b, c, _| unsafe {
            (b.get_string)(c, null(), 1, &mut null())
        }),
        ("fmi2GetString(value=null)", both_init, |b, c, a| unsafe {
            (b.get_string)(c, &a.real_vr, 1, null_mut())
        }),
        (
            "fmi2SetReal(vr=null)",
            both_instantiated,
            |b, c, _| unsafe { (b.set_real)(c, null(), 1, &0.0) },
        ),
        (
            "fmi2SetReal(value=null)",
            both_instantiated,
            |b, c, a| unsafe { (b.set_real)(c, &a.input_vr, 1, null()) },
        ),
        (
            "fmi2SetInteger(vr=null)",
            both_instantiated,
            |b, c, _| unsafe { (b.set_integer)(c, null(), 1, &1) },
        ),
        (
            "fmi2SetInteger(value=null)",
            both_instantiated,
            |b, c, a| unsafe { (b.set_integer)(c, &a.int_vr, 1, null()) },
        ),
        (
            "fmi2SetBoolean(vr=null)",
            both_instantiated,
            |b, c, _| unsafe { (b.set_boolean)(c, null(), 1, &0) },
        ),
        (
            "fmi2SetBoolean(value=null)",
            both_instantiated,
            |b, c, a| unsafe { (b.set_boolean)(c, &a.bool_vr, 1, null()) },
        ),
        (
            "fmi2SetString(vr=null)",
            both_instantiated,
            |b, c, _| unsafe { (b.set_string)(c, null(), 1, &c"x".as_ptr()) },
        ),
        (
            "fmi2SetString(value=null)",
            both_instantiated,
            |b, c, a| unsafe { (b.set_string)(c, &a.real_vr, 1, null()) },
        ),
    ];
    t.extend(state_table());
    t.extend(model_exchange_table());
    t.extend(co_simulation_table());
    t
}

fn state_table() -> Vec<Row<Interface>> {
    vec![
        (
            "fmi2GetFMUstate(FMUstate=null)",
            both_init,
            |b, c, _| unsafe { (b.get_fmu_state)(c, null_mut()) },
        ),
        (
            "fmi2FreeFMUstate(FMUstate=null)",
            both_init,
            |b, c, _| unsafe { (b.free_fmu_state)(c, null_mut()) },
        ),
        (
            "fmi2SetFMUstate(FMUstate=null)",
            both_init,
            |b, c, _| unsafe { (b.set_fmu_state)(c, null_mut()) },
        ),
        (
            "fmi2SerializedFMUstateSize(FMUstate=null)",
            both_init,
            |b, c, _| unsafe { (b.serialized_size)(c, null_mut(), &mut 0) },
        ),
        (
            "fmi2SerializedFMUstateSize(size=null)",
            both_init,
            |b, c, a| unsafe { (b.serialized_size)(c, a.state, null_mut()) },
        ),
        (
            "fmi2SerializeFMUstate(FMUstate=null)",
            both_init,
            |b, c, _| unsafe {
                let mut bytes = [0 as std::ffi::c_char; 16];
                (b.serialize)(c, null_mut(), bytes.as_mut_ptr(), 16)
            },
        ),
        (
            "fmi2SerializeFMUstate(serializedState=null)",
            both_init,
            |b, c, a| unsafe {
                let mut n = 0usize;
                (b.serialized_size)(c, a.state, &mut n);
                (b.serialize)(c, a.state, null_mut(), n)
            },
        ),
        (
            "fmi2DeSerializeFMUstate(serializedState=null, size=64)",
            both_init,
            |b, c, _| unsafe {
                let mut s: FmuState = null_mut();
                (b.deserialize)(c, null(), 64, &mut s)
            },
        ),
        (
            "fmi2DeSerializeFMUstate(FMUstate=null)",
            both_init,
            |b, c, a| unsafe {
                let mut n = 0usize;
                (b.serialized_size)(c, a.state, &mut n);
                let mut bytes = vec![0 as std::ffi::c_char; n];
                (b.serialize)(c, a.state, bytes.as_mut_ptr(), n);
                (b.deserialize)(c, bytes.as_ptr(), n, null_mut())
            },
        ),
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
    vec![
        (
            "fmi2NewDiscreteStates(eventInfo=null)",
            me_event,
            |b, c, _| unsafe { (b.new_discrete_states)(c, null_mut()) },
        ),
        (
            "fmi2CompletedIntegratorStep(enterEventMode=null)",
            me_continuous,
            |b, c, _| unsafe { (b.completed_integrator_step)(c, 1, null_mut(), &mut 0) },
        ),
        (
            "fmi2CompletedIntegratorStep(terminateSimulation=null)",
            me_continuous,
            |b, c, _| unsafe { (b.completed_integrator_step)(c, 1, &mut 0, null_mut()) },
        ),
        (
            "fmi2SetContinuousStates(x=null)",
            me_with_states,
            |b, c, a| unsafe { (b.set_continuous_states)(c, null(), a.nx) },
        ),
        (
            "fmi2GetContinuousStates(x=null)",
            me_with_states,
            |b, c, a| unsafe { (b.get_continuous_states)(c, null_mut(), a.nx) },
        ),
        (
            "fmi2GetDerivatives(derivatives=null)",
            me_with_states,
            |b, c, a| unsafe { (b.get_derivatives)(c, null_mut(), a.nx) },
        ),
        (
            "fmi2GetNominalsOfContinuousStates(x_nominal=null)",
            me_with_states,
            |b, c, a| unsafe { (b.get_nominals)(c, null_mut(), a.nx) },
        ),
        (
            "fmi2GetEventIndicators(eventIndicators=null)",
            me_with_indicators,
            |b, c, a| unsafe { (b.get_event_indicators)(c, null_mut(), a.nz) },
        ),
    ]
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
