//! The FMI 3.0 rows of the null-pointer class (`matrix::pointers`): every pointer
//! argument of the functions the models support, with a length that makes the
//! pointer necessary.

use super::calls::Args;
use crate::binary::Status;
use crate::description::Description;
use crate::fmi3::binary::{Binary3, FmuState, Instance3, Vr};
use crate::fmi3::host::{Interface3, State3};
use crate::matrix::pointers::{
    init, instantiated, me_continuous, me_with_indicators, me_with_states, with_partials,
};
use crate::matrix::same_named::{fmu_state_null_rows, model_exchange_null_rows};
use crate::matrix::seam;
use std::ptr::{null, null_mut};

type Applies = seam::Applies<Interface3>;
type Invoke = crate::standard_interface::Invoke<Interface3>;
type Row = seam::Row<Interface3>;

fn event(_: &Description, i: Interface3) -> Option<State3> {
    (i != Interface3::CoSimulation).then_some(State3::EventMode)
}
fn me_instantiated(_: &Description, i: Interface3) -> Option<State3> {
    i.is_me().then_some(State3::Instantiated)
}
fn cs_step(_: &Description, i: Interface3) -> Option<State3> {
    (!i.is_me()).then_some(State3::StepMode)
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

/// The rows of fmi3GetVariableDependencies with one of its four arrays null.
fn dependencies_table() -> Vec<Row> {
    let names = [
        "fmi3GetVariableDependencies(elementIndicesOfDependent=null)",
        "fmi3GetVariableDependencies(independents=null)",
        "fmi3GetVariableDependencies(elementIndicesOfIndependents=null)",
        "fmi3GetVariableDependencies(dependencyKinds=null)",
    ];
    let invoke: [Invoke; 4] = [
        dependencies_with_null::<0>,
        dependencies_with_null::<1>,
        dependencies_with_null::<2>,
        dependencies_with_null::<3>,
    ];
    rows(&names, with_dependencies, &invoke)
}

/// A row per name, all applying where `applies` says.
fn rows(names: &[&'static str], applies: Applies, invoke: &[Invoke]) -> Vec<Row> {
    names
        .iter()
        .zip(invoke)
        .map(|(&n, &f)| (n, applies, f))
        .collect()
}

/// fmi3GetVariableDependencies with array `K` (0..4) null and the right count.
unsafe fn dependencies_with_null<const K: usize>(b: &Binary3, c: Instance3, a: &Args) -> Status {
    // SAFETY: arrays of the announced count, one of them replaced by null.
    unsafe {
        let (vr, n) = dependent(b, c, a);
        let (mut e, mut v, mut ei) = (vec![0usize; n], vec![0u32; n], vec![0usize; n]);
        let mut kinds = vec![0i32; n];
        let e = if K == 0 { null_mut() } else { e.as_mut_ptr() };
        let v = if K == 1 { null_mut() } else { v.as_mut_ptr() };
        let ei = if K == 2 { null_mut() } else { ei.as_mut_ptr() };
        let kinds = if K == 3 {
            null_mut()
        } else {
            kinds.as_mut_ptr()
        };
        (b.get_variable_dependencies)(c, vr, e, v, ei, kinds, n)
    }
}

fn state_table() -> Vec<Row> {
    fmu_state_null_rows!("fmi3", "FMUState", "Deserialize", u8, init::<Interface3>)
}

/// Directional (ADJOINT = false) or adjoint derivative with argument `K` null.
unsafe fn derivative_with_null<const ADJOINT: bool, const K: usize>(
    b: &Binary3,
    c: Instance3,
    a: &Args,
) -> Status {
    let (adjoint, k) = (ADJOINT, K);
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
    let names = [
        "fmi3GetDirectionalDerivative(unknowns=null)",
        "fmi3GetDirectionalDerivative(knowns=null)",
        "fmi3GetDirectionalDerivative(seed=null)",
        "fmi3GetDirectionalDerivative(sensitivity=null)",
        "fmi3GetAdjointDerivative(unknowns=null)",
        "fmi3GetAdjointDerivative(knowns=null)",
        "fmi3GetAdjointDerivative(seed=null)",
        "fmi3GetAdjointDerivative(sensitivity=null)",
    ];
    let invoke: [Invoke; 8] = [
        derivative_with_null::<false, 0>,
        derivative_with_null::<false, 1>,
        derivative_with_null::<false, 2>,
        derivative_with_null::<false, 3>,
        derivative_with_null::<true, 0>,
        derivative_with_null::<true, 1>,
        derivative_with_null::<true, 2>,
        derivative_with_null::<true, 3>,
    ];
    rows(&names, with_partials::<Interface3>, &invoke)
}

/// `N` flags and a time to fill, output `k` null (k = N: the time), passed to
/// `call`.
fn outputs_with_null<const N: usize>(
    k: usize,
    call: impl FnOnce([*mut u8; N], *mut f64) -> Status,
) -> Status {
    let mut flags = [0u8; N];
    let mut time = 0.0;
    let base = flags.as_mut_ptr();
    let p: [*mut u8; N] = std::array::from_fn(|i| {
        if i == k {
            null_mut()
        } else {
            base.wrapping_add(i)
        }
    });
    let t = if k == N {
        null_mut()
    } else {
        &mut time as *mut f64
    };
    call(p, t)
}

/// fmi3UpdateDiscreteStates with output `K` (0..6) null.
unsafe fn update_with_null<const K: usize>(b: &Binary3, c: Instance3, _: &Args) -> Status {
    outputs_with_null::<5>(K, |p, t| unsafe {
        // SAFETY: valid outputs except the one replaced by null.
        (b.update_discrete_states)(c, p[0], p[1], p[2], p[3], p[4], t)
    })
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
        update_with_null::<0>,
        update_with_null::<1>,
        update_with_null::<2>,
        update_with_null::<3>,
        update_with_null::<4>,
        update_with_null::<5>,
    ];
    rows(&names, event, &invoke)
}

fn model_exchange_table() -> Vec<Row> {
    let mut t: Vec<Row> = model_exchange_null_rows!(
        "fmi3",
        "GetContinuousStateDerivatives(derivatives",
        "nominals",
        get_continuous_state_derivatives
    );
    t.extend::<[Row; 2]>([
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
    ]);
    t
}

/// fmi3DoStep with output `K` (0..4) null.
unsafe fn step_with_null<const K: usize>(b: &Binary3, c: Instance3, _: &Args) -> Status {
    outputs_with_null::<3>(K, |p, t| unsafe {
        // SAFETY: valid outputs except the one replaced by null.
        (b.do_step)(c, 0.0, 1e-3, 1, p[0], p[1], p[2], t)
    })
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
    ]
}

fn step_table() -> Vec<Row> {
    let names = [
        "fmi3DoStep(eventHandlingNeeded=null)",
        "fmi3DoStep(terminateSimulation=null)",
        "fmi3DoStep(earlyReturn=null)",
        "fmi3DoStep(lastSuccessfulTime=null)",
    ];
    let invoke: [Invoke; 4] = [
        step_with_null::<0>,
        step_with_null::<1>,
        step_with_null::<2>,
        step_with_null::<3>,
    ];
    rows(&names, cs_step, &invoke)
}

pub fn table() -> Vec<Row> {
    let mut t = values_table();
    t.extend(dependencies_table());
    t.extend(state_table());
    t.extend(derivative_table());
    t.extend(event_table());
    t.extend(model_exchange_table());
    t.extend(co_simulation_table());
    t.extend(step_table());
    t
}
