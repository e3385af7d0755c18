//! The FMI 3.0 rows of the value-reference class (`matrix::references`): the
//! typed getters and setters with nValues, and the cases of functions only FMI 3.0
//! has (`extras`): nSeed and nSensitivity of the directional and adjoint
//! derivatives and an unknown reference given to them, the serialized size,
//! nDependencies, and output-derivative orders. Also the class only FMI 3.0 has,
//! "element count" of the Model Exchange arrays (nx, nz; `cases`). FMI 3.0
//! (section 2.2.6.2) defines nValues as the total of the variables' elements; the
//! project refuses anything else with fmi3Error and a log line naming the
//! reference, the variable or the counts, and the instance recovers with
//! fmi3Reset.

use super::calls::Target;
use crate::Loaded;
use crate::binary::Status;
use crate::description::{Description, VarType};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::host::unlogged;
use crate::matrix::references::{unused, wrong_counts};
use crate::matrix::seam::Access;
use crate::matrix::{Case, Expect, on_instance};

const WHY_UNKNOWN: &str =
    "value reference not in the modelDescription (FMI 3.0 2.2.6): fmi3Error naming it";
const WHY_ORDER: &str = "FMI 3.0 4.2.1 fmi3GetOutputDerivatives: order from 1 to maxOutputDerivativeOrder; 0, -1 and 2^31-1 are refused with fmi3Error naming the order";
pub const WHY_COUNT: &str = "count that does not match the arrays (FMI 3.0 2.2.6.2 nValues = total elements; 3.2 nx, nz; 2.2.11 nSeed, nSensitivity; 2.2.9 serialized size): fmi3Error naming the counts";

pub fn getters() -> Vec<Access<Interface3>> {
    vec![
        ("fmi3GetFloat64", Some(VarType::Real), |i, vr, n| unsafe {
            let mut x = vec![0.0; n.min(64)];
            (i.binary.get_float64)(i.c, &vr, 1, x.as_mut_ptr(), n)
        }),
        ("fmi3GetInt32", Some(VarType::Integer), |i, vr, n| unsafe {
            let mut x = vec![0; n.min(64)];
            (i.binary.get_int32)(i.c, &vr, 1, x.as_mut_ptr(), n)
        }),
        (
            "fmi3GetBoolean",
            Some(VarType::Boolean),
            |i, vr, n| unsafe {
                let mut x = vec![0; n.min(64)];
                (i.binary.get_boolean)(i.c, &vr, 1, x.as_mut_ptr(), n)
            },
        ),
    ]
}

pub fn setters() -> Vec<Access<Interface3>> {
    vec![
        ("fmi3SetFloat64", Some(VarType::Real), |i, vr, n| unsafe {
            let x = vec![0.0; n.min(64)];
            (i.binary.set_float64)(i.c, &vr, 1, x.as_ptr(), n)
        }),
        ("fmi3SetInt32", Some(VarType::Integer), |i, vr, n| unsafe {
            let x = vec![1; n.min(64)];
            (i.binary.set_int32)(i.c, &vr, 1, x.as_ptr(), n)
        }),
        (
            "fmi3SetBoolean",
            Some(VarType::Boolean),
            |i, vr, n| unsafe {
                let x = vec![0; n.min(64)];
                (i.binary.set_boolean)(i.c, &vr, 1, x.as_ptr(), n)
            },
        ),
    ]
}

/// (function, state, call(instance, count)) for the counted arrays of ME.
type Counted = (&'static str, fn(&Instance, usize) -> Status);

fn counted() -> [Counted; 5] {
    [
        ("fmi3GetContinuousStates", |i, n| unsafe {
            let mut x = vec![0.0; n.min(64)];
            (i.binary.get_continuous_states)(i.c, x.as_mut_ptr(), n)
        }),
        ("fmi3SetContinuousStates", |i, n| unsafe {
            let x = vec![0.0; n.min(64)];
            (i.binary.set_continuous_states)(i.c, x.as_ptr(), n)
        }),
        ("fmi3GetContinuousStateDerivatives", |i, n| unsafe {
            let mut x = vec![0.0; n.min(64)];
            (i.binary.get_continuous_state_derivatives)(i.c, x.as_mut_ptr(), n)
        }),
        ("fmi3GetNominalsOfContinuousStates", |i, n| unsafe {
            let mut x = vec![0.0; n.min(64)];
            (i.binary.get_nominals)(i.c, x.as_mut_ptr(), n)
        }),
        ("fmi3GetEventIndicators", |i, n| unsafe {
            let mut x = vec![0.0; n.min(64)];
            (i.binary.get_event_indicators)(i.c, x.as_mut_ptr(), n)
        }),
    ]
}

fn count_cases(d: &Description, m: usize) -> Vec<Case> {
    let mut cases = Vec::new();
    for (function, call) in counted() {
        let right = if function == "fmi3GetEventIndicators" {
            d.number_of_event_indicators
        } else {
            d.number_of_states
        };
        let mut wrong = wrong_counts(right);
        wrong.retain(|&n| n != right);
        for n in wrong {
            cases.push(Case::new(
                ("element count", m, Interface3::ModelExchange),
                format!("{function}(n = {n}, the model has {right})"),
                (Expect::error("length"), WHY_COUNT),
                move |l| {
                    on_instance(
                        l,
                        m,
                        Interface3::ModelExchange,
                        State3::ContinuousTimeMode,
                        |i| call(i, n),
                    )
                },
            ));
        }
    }
    cases
}

/// Directional (adjoint = false) or adjoint derivative with nSeed or nSensitivity off.
fn derivative(
    i: &Instance,
    partial: &(Target, Target),
    adjoint: bool,
    n_seed: usize,
    n_out: usize,
) -> Status {
    let (u, x) = partial;
    let seed = vec![1.0; n_seed.min(64)];
    let mut out = vec![0.0; n_out.min(64)];
    let f = if adjoint {
        i.binary.get_adjoint_derivative
    } else {
        i.binary.get_directional_derivative
    };
    // SAFETY: arrays of at most the announced sizes (the point of the probe).
    unsafe {
        f(
            i.c,
            &u.vr,
            1,
            &x.vr,
            1,
            seed.as_ptr(),
            n_seed,
            out.as_mut_ptr(),
            n_out,
        )
    }
}

fn derivative_cases(d: &Description, m: usize, interface: Interface3) -> Vec<Case> {
    let mut cases = Vec::new();
    if !d.provides_directional_derivative {
        return cases;
    }
    let Some(&(x, dx)) = d.state_derivative_pairs().first() else {
        return cases;
    };
    let partial = (
        Target {
            vr: dx,
            size: d.elements(&[dx]),
        },
        Target {
            vr: x,
            size: d.elements(&[x]),
        },
    );
    for adjoint in [false, true] {
        let function = if adjoint {
            "fmi3GetAdjointDerivative"
        } else {
            "fmi3GetDirectionalDerivative"
        };
        let (seed, out) = if adjoint {
            (partial.0.size, partial.1.size)
        } else {
            (partial.1.size, partial.0.size)
        };
        let mut wrong: Vec<(usize, usize)> =
            wrong_counts(seed).into_iter().map(|n| (n, out)).collect();
        wrong.extend(wrong_counts(out).into_iter().map(|n| (seed, n)));
        for (n_seed, n_out) in wrong {
            let p = partial.clone();
            cases.push(Case::new(
                ("element count", m, interface),
                format!(
                    "{function}(nSeed = {n_seed}, nSensitivity = {n_out}; needs {seed}, {out})"
                ),
                (Expect::error("nSeed"), WHY_COUNT),
                move |l| {
                    on_instance(l, m, interface, State3::InitializationMode, |i| {
                        derivative(i, &p, adjoint, n_seed, n_out)
                    })
                },
            ));
        }
        let bad = unused(d);
        let p = partial.clone();
        cases.push(Case::new(
            ("value reference", m, interface),
            format!("{function}(unknown vr {bad})"),
            (Expect::error(&bad.to_string()), WHY_UNKNOWN),
            move |l| {
                on_instance(l, m, interface, State3::InitializationMode, |i| {
                    let q = (Target { vr: bad, size: 1 }, p.1.clone());
                    derivative(
                        i,
                        &q,
                        adjoint,
                        if adjoint { 1 } else { q.1.size },
                        if adjoint { q.1.size } else { 1 },
                    )
                })
            },
        ));
    }
    cases
}

fn serialized_size_cases(m: usize, interface: Interface3) -> Vec<Case> {
    [-1isize, 1]
        .into_iter()
        .map(|delta| {
            Case::new(
                ("element count", m, interface),
                format!("fmi3SerializeFMUState(size = serialized size {delta:+})"),
                (Expect::error("size"), WHY_COUNT),
                move |l| {
                    on_instance(l, m, interface, State3::InitializationMode, |i| {
                        let (_, state) = i.get_state();
                        let mut n = 0usize;
                        // SAFETY: a state of this instance; a buffer one byte larger than asked.
                        let s = unsafe {
                            (i.binary.serialized_size)(i.c, state, &mut n);
                            let size = n.saturating_add_signed(delta);
                            let mut bytes = vec![0u8; n + 1];
                            (i.binary.serialize)(i.c, state, bytes.as_mut_ptr(), size)
                        };
                        unlogged(i, || i.free_state(state));
                        s
                    })
                },
            )
        })
        .collect()
}

/// fmi3GetVariableDependencies of the first dependent with a wrong nDependencies.
fn dependency_cases(d: &Description, m: usize, interface: Interface3) -> Vec<Case> {
    let Some(&dependent) = d.dependents.first() else {
        return Vec::new();
    };
    [1isize, -1, isize::MAX / 32]
        .into_iter()
        .map(|delta| {
            Case::new(
                ("element count", m, interface),
                format!(
                    "fmi3GetVariableDependencies(vr {dependent}, nDependencies = count {delta:+})"
                ),
                (Expect::error("nDependencies"), WHY_COUNT),
                move |l| {
                    on_instance(l, m, interface, State3::InitializationMode, |i| unsafe {
                        let mut n = 0usize;
                        (i.binary.get_number_of_variable_dependencies)(i.c, dependent, &mut n);
                        let claimed = n.saturating_add_signed(delta);
                        let room = (n + 1).min(claimed.max(1));
                        let (mut e, mut v, mut ei, mut k) =
                            (vec![0; room], vec![0; room], vec![0; room], vec![0; room]);
                        (i.binary.get_variable_dependencies)(
                            i.c,
                            dependent,
                            e.as_mut_ptr(),
                            v.as_mut_ptr(),
                            ei.as_mut_ptr(),
                            k.as_mut_ptr(),
                            claimed,
                        )
                    })
                },
            )
        })
        .collect()
}

/// fmi3GetOutputDerivatives of the first Float64 output with an order that no
/// FMU can provide (orders start at 1; i32::MAX exceeds any maxOutputDerivativeOrder).
fn order_cases(d: &Description, m: usize, interface: Interface3) -> Vec<Case> {
    let Some(output) = d
        .variables
        .iter()
        .find(|v| v.causality == "output" && v.var_type == VarType::Real)
    else {
        return Vec::new();
    };
    let (vr, size, name) = (output.vr, output.size, output.name.clone());
    [0, -1, i32::MAX]
        .into_iter()
        .map(|order| {
            Case::new(
                ("value reference", m, interface),
                format!("fmi3GetOutputDerivatives({name}, order {order})"),
                (Expect::error("order"), WHY_ORDER),
                move |l| {
                    on_instance(l, m, interface, State3::StepMode, |i| unsafe {
                        let mut out = vec![0.0; size];
                        (i.binary.get_output_derivatives)(
                            i.c,
                            &vr,
                            1,
                            &order,
                            out.as_mut_ptr(),
                            size,
                        )
                    })
                },
            )
        })
        .collect()
}

/// The cases of the functions only FMI 3.0 has, for one interface.
pub fn extras(d: &Description, m: usize, interface: Interface3) -> Vec<Case> {
    let mut cases = derivative_cases(d, m, interface);
    cases.extend(serialized_size_cases(m, interface));
    cases.extend(dependency_cases(d, m, interface));
    if !interface.is_me() {
        cases.extend(order_cases(d, m, interface));
    }
    cases
}

/// The class only FMI 3.0 has: wrong nx and nz given to the Model Exchange arrays.
pub fn cases(loaded: &Loaded, m: usize) -> Vec<Case> {
    let d = &loaded.fmus3[m].description;
    if d.number_of_states > 0 {
        count_cases(d, m)
    } else {
        Vec::new()
    }
}
