//! The FMI 3.0 rows of the null-pointer class (`matrix::pointers`): every pointer
//! argument of the functions the models support, with a length that makes the
//! pointer necessary.

use super::calls::Args;
use crate::binary::Status;
use crate::description::Description;
use crate::fmi3::binary::{Binary3, FmuState, Instance3, Vr};
use crate::fmi3::host::{Interface3, State3};
use crate::matrix::seam;
use std::ptr::{null, null_mut};

type Applies = seam::Applies<Interface3>;
type Invoke = crate::standard_interface::Invoke<Interface3>;
type Row = seam::Row<Interface3>;

fn init(_: &Description, _: Interface3) -> Option<State3> {
    Some(State3::InitializationMode)
}
fn instantiated(_: &Description, _: Interface3) -> Option<State3> {
    Some(State3::Instantiated)
}
fn event(_: &Description, i: Interface3) -> Option<State3> {
    (i != Interface3::CoSimulation).then_some(State3::EventMode)
}
fn me_instantiated(_: &Description, i: Interface3) -> Option<State3> {
    i.is_me().then_some(State3::Instantiated)
}
fn me_continuous(_: &Description, i: Interface3) -> Option<State3> {
    i.is_me().then_some(State3::ContinuousTimeMode)
}
fn me_with_states(d: &Description, i: Interface3) -> Option<State3> {
    (d.number_of_states > 0).then_some(me_continuous(d, i)?)
}
fn me_with_indicators(d: &Description, i: Interface3) -> Option<State3> {
    (d.number_of_event_indicators > 0).then_some(me_continuous(d, i)?)
}
fn cs_step(_: &Description, i: Interface3) -> Option<State3> {
    (!i.is_me()).then_some(State3::StepMode)
}
fn with_partials(d: &Description, _: Interface3) -> Option<State3> {
    d.provides_directional_derivative
        .then_some(State3::InitializationMode)
}

/// A variable with dependencies and their count (for fmi3GetVariableDependencies).
unsafe fn dependent(b: &Binary3, c: Instance3, a: &Args) -> (Vr, usize) {
    let mut n = 0usize;
    // SAFETY: a live instance and a count to fill.
    unsafe { (b.get_number_of_variable_dependencies)(c, a.dependent, &mut n) };
    (a.dependent, n)
}
fn with_dependencies(d: &Description, _: Interface3) -> Option<State3> {
    (!d.dependents.is_empty()).then_some(State3::InitializationMode)
}

fn values_table() -> Vec<Row> {
    vec![
        (
            "fmi3SetDebugLogging(categories=null, n=1)",
            instantiated,
            |b, c, _| unsafe { (b.set_debug_logging)(c, 1, 1, null()) },
        ),
        (
            "fmi3SetDebugLogging(categories[0]=null, n=1)",
            instantiated,
            |b, c, _| unsafe { (b.set_debug_logging)(c, 1, 1, &null()) },
        ),
        ("fmi3GetFloat64(vr=null)", init, |b, c, a| unsafe {
            let mut x = vec![0.0; a.float.size];
            (b.get_float64)(c, null(), 1, x.as_mut_ptr(), x.len())
        }),
        ("fmi3GetFloat64(values=null)", init, |b, c, a| unsafe {
            (b.get_float64)(c, &a.float.vr, 1, null_mut(), a.float.size)
        }),
        ("fmi3GetInt32(vr=null)", init, |b, c, a| unsafe {
            let mut x = vec![0; a.int.size];
            (b.get_int32)(c, null(), 1, x.as_mut_ptr(), x.len())
        }),
        ("fmi3GetInt32(values=null)", init, |b, c, a| unsafe {
            (b.get_int32)(c, &a.int.vr, 1, null_mut(), a.int.size)
        }),
        ("fmi3GetBoolean(vr=null)", init, |b, c, a| unsafe {
            let mut x = vec![0; a.boolean.size];
            (b.get_boolean)(c, null(), 1, x.as_mut_ptr(), x.len())
        }),
        ("fmi3GetBoolean(values=null)", init, |b, c, a| unsafe {
            (b.get_boolean)(c, &a.boolean.vr, 1, null_mut(), a.boolean.size)
        }),
        ("fmi3SetFloat64(vr=null)", instantiated, |b, c, a| unsafe {
            let x = vec![0.0; a.input.size];
            (b.set_float64)(c, null(), 1, x.as_ptr(), x.len())
        }),
        (
            "fmi3SetFloat64(values=null)",
            instantiated,
            |b, c, a| unsafe { (b.set_float64)(c, &a.input.vr, 1, null(), a.input.size) },
        ),
        ("fmi3SetInt32(vr=null)", instantiated, |b, c, a| unsafe {
            let x = vec![1; a.int.size];
            (b.set_int32)(c, null(), 1, x.as_ptr(), x.len())
        }),
        (
            "fmi3SetInt32(values=null)",
            instantiated,
            |b, c, a| unsafe { (b.set_int32)(c, &a.int.vr, 1, null(), a.int.size) },
        ),
        ("fmi3SetBoolean(vr=null)", instantiated, |b, c, a| unsafe {
            let x = vec![0; a.boolean.size];
            (b.set_boolean)(c, null(), 1, x.as_ptr(), x.len())
        }),
        (
            "fmi3SetBoolean(values=null)",
            instantiated,
            |b, c, a| unsafe { (b.set_boolean)(c, &a.boolean.vr, 1, null(), a.boolean.size) },
        ),
        (
            "fmi3GetNumberOfVariableDependencies(nDependencies=null)",
            init,
            |b, c, a| unsafe { (b.get_number_of_variable_dependencies)(c, a.float.vr, null_mut()) },
        ),
    ]
}

/// fmi3GetVariableDependencies with array `k` (0..4) null and the right count.
fn dependencies_row(k: usize) -> Row {
    const NAMES: [&str; 4] = [
        "fmi3GetVariableDependencies(elementIndicesOfDependent=null)",
        "fmi3GetVariableDependencies(independents=null)",
        "fmi3GetVariableDependencies(elementIndicesOfIndependents=null)",
        "fmi3GetVariableDependencies(dependencyKinds=null)",
    ];
    let invoke: [Invoke; 4] = [
        |b, c, a| unsafe { dependencies_with_null(b, c, a, 0) },
        |b, c, a| unsafe { dependencies_with_null(b, c, a, 1) },
        |b, c, a| unsafe { dependencies_with_null(b, c, a, 2) },
        |b, c, a| unsafe { dependencies_with_null(b, c, a, 3) },
    ];
    (NAMES[k], with_dependencies, invoke[k])
}

unsafe fn dependencies_with_null(b: &Binary3, c: Instance3, a: &Args, k: usize) -> Status {
    // SAFETY: arrays of the announced count, one of them replaced by null.
    unsafe {
        let (vr, n) = dependent(b, c, a);
        let (mut e, mut v, mut ei) = (vec![0usize; n], vec![0u32; n], vec![0usize; n]);
        let mut kinds = vec![0i32; n];
        let e = if k == 0 { null_mut() } else { e.as_mut_ptr() };
        let v = if k == 1 { null_mut() } else { v.as_mut_ptr() };
        let ei = if k == 2 { null_mut() } else { ei.as_mut_ptr() };
        let kinds = if k == 3 {
            null_mut()
        } else {
            kinds.as_mut_ptr()
        };
        (b.get_variable_dependencies)(c, vr, e, v, ei, kinds, n)
    }
}

fn state_table() -> Vec<Row> {
    vec![
        ("fmi3GetFMUState(FMUState=null)", init, |b, c, _| unsafe {
            (b.get_fmu_state)(c, null_mut())
        }),
        ("fmi3FreeFMUState(FMUState=null)", init, |b, c, _| unsafe {
            (b.free_fmu_state)(c, null_mut())
        }),
        ("fmi3SetFMUState(FMUState=null)", init, |b, c, _| unsafe {
            (b.set_fmu_state)(c, null_mut())
        }),
        (
            "fmi3SerializedFMUStateSize(FMUState=null)",
            init,
            |b, c, _| unsafe { (b.serialized_size)(c, null_mut(), &mut 0) },
        ),
        (
            "fmi3SerializedFMUStateSize(size=null)",
            init,
            |b, c, a| unsafe { (b.serialized_size)(c, a.state, null_mut()) },
        ),
        (
            "fmi3SerializeFMUState(FMUState=null)",
            init,
            |b, c, _| unsafe {
                let mut bytes = [0u8; 16];
                (b.serialize)(c, null_mut(), bytes.as_mut_ptr(), 16)
            },
        ),
        (
            "fmi3SerializeFMUState(serializedState=null)",
            init,
            |b, c, a| unsafe {
                let mut n = 0usize;
                (b.serialized_size)(c, a.state, &mut n);
                (b.serialize)(c, a.state, null_mut(), n)
            },
        ),
        (
            "fmi3DeserializeFMUState(serializedState=null, size=64)",
            init,
            |b, c, _| unsafe {
                let mut s: FmuState = null_mut();
                (b.deserialize)(c, null(), 64, &mut s)
            },
        ),
        (
            "fmi3DeserializeFMUState(FMUState=null)",
            init,
            |b, c, a| unsafe {
                let mut n = 0usize;
                (b.serialized_size)(c, a.state, &mut n);
                let mut bytes = vec![0u8; n];
                (b.serialize)(c, a.state, bytes.as_mut_ptr(), n);
                (b.deserialize)(c, bytes.as_ptr(), n, null_mut())
            },
        ),
    ]
}

/// Directional (adjoint = false) or adjoint derivative with argument `k` null.
unsafe fn derivative_with_null(
    b: &Binary3,
    c: Instance3,
    a: &Args,
    adjoint: bool,
    k: usize,
) -> Status {
    let (u, x) = &a.partial;
    let (n_seed, n_out) = if adjoint {
        (u.size, x.size)
    } else {
        (x.size, u.size)
    };
    let seed = vec![1.0; n_seed];
    let mut out = vec![0.0; n_out];
    let f = if adjoint {
        b.get_adjoint_derivative
    } else {
        b.get_directional_derivative
    };
    let pick = |i: usize, p: *const Vr| if i == k { null() } else { p };
    // SAFETY: arrays of the announced sizes, one replaced by null.
    unsafe {
        f(
            c,
            pick(0, &u.vr),
            1,
            pick(1, &x.vr),
            1,
            if k == 2 { null() } else { seed.as_ptr() },
            n_seed,
            if k == 3 { null_mut() } else { out.as_mut_ptr() },
            n_out,
        )
    }
}

fn derivative_table() -> Vec<Row> {
    vec![
        (
            "fmi3GetDirectionalDerivative(unknowns=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, false, 0) },
        ),
        (
            "fmi3GetDirectionalDerivative(knowns=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, false, 1) },
        ),
        (
            "fmi3GetDirectionalDerivative(seed=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, false, 2) },
        ),
        (
            "fmi3GetDirectionalDerivative(sensitivity=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, false, 3) },
        ),
        (
            "fmi3GetAdjointDerivative(unknowns=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, true, 0) },
        ),
        (
            "fmi3GetAdjointDerivative(knowns=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, true, 1) },
        ),
        (
            "fmi3GetAdjointDerivative(seed=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, true, 2) },
        ),
        (
            "fmi3GetAdjointDerivative(sensitivity=null)",
            with_partials,
            |b, c, a| unsafe { derivative_with_null(b, c, a, true, 3) },
        ),
    ]
}

/// fmi3UpdateDiscreteStates with output `k` (0..6) null.
unsafe fn update_with_null(b: &Binary3, c: Instance3, k: usize) -> Status {
    let mut flags = [0u8; 5];
    let mut time = 0.0;
    let p: Vec<*mut u8> = (0..5)
        .map(|i| {
            if i == k {
                null_mut()
            } else {
                &mut flags[i] as *mut u8
            }
        })
        .collect();
    let t = if k == 5 {
        null_mut()
    } else {
        &mut time as *mut f64
    };
    // SAFETY: valid outputs except the one replaced by null.
    unsafe { (b.update_discrete_states)(c, p[0], p[1], p[2], p[3], p[4], t) }
}

fn event_table() -> Vec<Row> {
    let names = [
        "fmi3UpdateDiscreteStates(discreteStatesNeedUpdate=null)",
        "fmi3UpdateDiscreteStates(terminateSimulation=null)",
        "fmi3UpdateDiscreteStates(nominalsOfContinuousStatesChanged=null)",
        "fmi3UpdateDiscreteStates(valuesOfContinuousStatesChanged=null)",
        "fmi3UpdateDiscreteStates(nextEventTimeDefined=null)",
        "fmi3UpdateDiscreteStates(nextEventTime=null)",
    ];
    let invoke: [Invoke; 6] = [
        |b, c, _| unsafe { update_with_null(b, c, 0) },
        |b, c, _| unsafe { update_with_null(b, c, 1) },
        |b, c, _| unsafe { update_with_null(b, c, 2) },
        |b, c, _| unsafe { update_with_null(b, c, 3) },
        |b, c, _| unsafe { update_with_null(b, c, 4) },
        |b, c, _| unsafe { update_with_null(b, c, 5) },
    ];
    names
        .into_iter()
        .zip(invoke)
        .map(|(n, f)| (n, event as Applies, f))
        .collect()
}

fn model_exchange_table() -> Vec<Row> {
    vec![
        (
            "fmi3CompletedIntegratorStep(enterEventMode=null)",
            me_continuous,
            |b, c, _| unsafe { (b.completed_integrator_step)(c, 1, null_mut(), &mut 0) },
        ),
        (
            "fmi3CompletedIntegratorStep(terminateSimulation=null)",
            me_continuous,
            |b, c, _| unsafe { (b.completed_integrator_step)(c, 1, &mut 0, null_mut()) },
        ),
        (
            "fmi3SetContinuousStates(x=null)",
            me_with_states,
            |b, c, a| unsafe { (b.set_continuous_states)(c, null(), a.nx) },
        ),
        (
            "fmi3GetContinuousStates(x=null)",
            me_with_states,
            |b, c, a| unsafe { (b.get_continuous_states)(c, null_mut(), a.nx) },
        ),
        (
            "fmi3GetContinuousStateDerivatives(derivatives=null)",
            me_with_states,
            |b, c, a| unsafe { (b.get_continuous_state_derivatives)(c, null_mut(), a.nx) },
        ),
        (
            "fmi3GetNominalsOfContinuousStates(nominals=null)",
            me_with_states,
            |b, c, a| unsafe { (b.get_nominals)(c, null_mut(), a.nx) },
        ),
        (
            "fmi3GetEventIndicators(eventIndicators=null)",
            me_with_indicators,
            |b, c, a| unsafe { (b.get_event_indicators)(c, null_mut(), a.nz) },
        ),
        (
            "fmi3GetNumberOfEventIndicators(nEventIndicators=null)",
            me_instantiated,
            |b, c, _| unsafe { (b.get_number_of_event_indicators)(c, null_mut()) },
        ),
        (
            "fmi3GetNumberOfContinuousStates(nContinuousStates=null)",
            me_instantiated,
            |b, c, _| unsafe { (b.get_number_of_continuous_states)(c, null_mut()) },
        ),
    ]
}

/// fmi3DoStep with output `k` (0..4) null.
unsafe fn step_with_null(b: &Binary3, c: Instance3, k: usize) -> Status {
    let mut flags = [0u8; 3];
    let mut last = 0.0;
    let p: Vec<*mut u8> = (0..3)
        .map(|i| {
            if i == k {
                null_mut()
            } else {
                &mut flags[i] as *mut u8
            }
        })
        .collect();
    let t = if k == 3 {
        null_mut()
    } else {
        &mut last as *mut f64
    };
    // SAFETY: valid outputs except the one replaced by null.
    unsafe { (b.do_step)(c, 0.0, 1e-3, 1, p[0], p[1], p[2], t) }
}

fn co_simulation_table() -> Vec<Row> {
    vec![
        (
            "fmi3GetOutputDerivatives(vr=null)",
            cs_step,
            |b, c, a| unsafe {
                let mut out = vec![0.0; a.float.size];
                (b.get_output_derivatives)(c, null(), 1, &1, out.as_mut_ptr(), out.len())
            },
        ),
        (
            "fmi3GetOutputDerivatives(order=null)",
            cs_step,
            |b, c, a| unsafe {
                let mut out = vec![0.0; a.float.size];
                (b.get_output_derivatives)(c, &a.float.vr, 1, null(), out.as_mut_ptr(), out.len())
            },
        ),
        (
            "fmi3GetOutputDerivatives(values=null)",
            cs_step,
            |b, c, a| unsafe {
                (b.get_output_derivatives)(c, &a.float.vr, 1, &1, null_mut(), a.float.size)
            },
        ),
        (
            "fmi3DoStep(eventHandlingNeeded=null)",
            cs_step,
            |b, c, _| unsafe { step_with_null(b, c, 0) },
        ),
        (
            "fmi3DoStep(terminateSimulation=null)",
            cs_step,
            |b, c, _| unsafe { step_with_null(b, c, 1) },
        ),
        ("fmi3DoStep(earlyReturn=null)", cs_step, |b, c, _| unsafe {
            step_with_null(b, c, 2)
        }),
        (
            "fmi3DoStep(lastSuccessfulTime=null)",
            cs_step,
            |b, c, _| unsafe { step_with_null(b, c, 3) },
        ),
    ]
}

pub fn table() -> Vec<Row> {
    let mut t = values_table();
    t.extend((0..4).map(dependencies_row));
    t.extend(state_table());
    t.extend(derivative_table());
    t.extend(event_table());
    t.extend(model_exchange_table());
    t.extend(co_simulation_table());
    t
}
