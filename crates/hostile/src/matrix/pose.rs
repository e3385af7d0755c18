//! Model Exchange at a point where the model cannot be evaluated: the plant's
//! continuous state set to a pose that cannot assemble (`theta[2]` = 0.351832 rad,
//! found by the probes of issue 12). FMI 2.0 section 3.2.2 lets every function that
//! evaluates the model return fmi2Discard there so that the integrator can retry
//! with a smaller step; fmi2Error would end the instance (issue 12 item 2). The
//! case construction serves both standards (`unassemblable_cases`); the
//! evaluations are per standard.

use super::{Case, Expect, on_instance};
use crate::Loaded;
use crate::binary::{OK, Status};
use crate::host::{Instance, Interface};
use crate::standard_interface::StandardInterface;

const WHY: &str = "FMI 2.0 3.2.2: a model that cannot be evaluated at the current state returns fmi2Discard (integrator retries), not fmi2Error (issue 12 item 2)";
pub const UNASSEMBLABLE_THETA2: f64 = 0.351832;

/// A call that evaluates the model, on an instance.
pub type Evaluate<I> = fn(&<I as StandardInterface>::Instance<'_>) -> Status;

fn evaluations() -> Vec<(&'static str, Evaluate<Interface>)> {
    vec![
        ("fmi2GetDerivatives", |i: &Instance| unsafe {
            let mut dx = vec![0.0; i.description.number_of_states];
            (i.binary.get_derivatives)(i.c, dx.as_mut_ptr(), dx.len())
        }),
        ("fmi2GetEventIndicators", |i| unsafe {
            let mut z = vec![0.0; i.description.number_of_event_indicators];
            (i.binary.get_event_indicators)(i.c, z.as_mut_ptr(), z.len())
        }),
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
    ]
}

/// Moves the instance's state to the unassemblable pose (element 1 of the
/// continuous state is `theta[2]`); the status of the set.
fn break_pose<I: StandardInterface>(i: &I::Instance<'_>, n: usize) -> Status {
    let (binary, handle) = I::raw(i);
    let (get, set) = I::continuous_states(binary);
    let mut x = vec![0.0; n];
    // SAFETY: arrays of the model's state count.
    unsafe {
        get(handle.into(), x.as_mut_ptr(), n);
        x[1] = UNASSEMBLABLE_THETA2;
        set(handle.into(), x.as_ptr(), n)
    }
}

/// One case per evaluation of a Model Exchange instance of model `m` (with `n`
/// continuous states) moved to the unassemblable pose: fmiXDiscard.
pub fn unassemblable_cases<I: StandardInterface>(
    (m, n): (usize, usize),
    (class, why): (&'static str, &'static str),
    evaluations: Vec<(&'static str, Evaluate<I>)>,
) -> Vec<Case> {
    evaluations
        .into_iter()
        .map(|(name, evaluate)| Case {
            class,
            model: m,
            interface: Some(I::MODEL_EXCHANGE.short()),
            name: format!("{name} at theta[2] = {UNASSEMBLABLE_THETA2}"),
            expect: Expect::discard(),
            why,
            probe: Box::new(move |l| {
                on_instance(l, m, I::MODEL_EXCHANGE, I::CONTINUOUS_TIME_MODE, |i| {
                    let s = break_pose::<I>(i, n);
                    if s != OK {
                        return s;
                    }
                    crate::host::take(crate::host::Probed::log(i));
                    evaluate(i)
                })
            }),
        })
        .collect()
}

pub fn cases(l: &Loaded, m: usize) -> Vec<Case> {
    let d = &l.fmus[m].description;
    let pairs = d.state_derivative_pairs();
    let theta2 = d
        .variables
        .iter()
        .find(|v| v.name == "theta[2]")
        .map(|v| v.vr);
    if pairs.len() < 2 || theta2 != Some(pairs[1].0) {
        return Vec::new();
    }
    unassemblable_cases::<Interface>(
        (m, d.number_of_states),
        ("unassemblable pose", WHY),
        evaluations(),
    )
}
