//! Model Exchange at a point where the model cannot be evaluated: the plant's
//! continuous state set to a pose that cannot assemble (`theta[2]` = 0.351832 rad,
//! found by the probes of issue 12). FMI 2.0 section 3.2.2 lets every function that
//! evaluates the model return fmi2Discard there so that the integrator can retry
//! with a smaller step; fmi2Error would end the instance (issue 12 item 2).

use super::{Case, Expect, on_instance};
use crate::Loaded;
use crate::binary::Status;
use crate::host::{Instance, Interface, State};

const WHY: &str = "FMI 2.0 3.2.2: a model that cannot be evaluated at the current state returns fmi2Discard (integrator retries), not fmi2Error (issue 12 item 2)";
const UNASSEMBLABLE_THETA2: f64 = 0.351832;

type Evaluate = fn(&Instance) -> Status;

fn evaluations() -> [(&'static str, Evaluate); 4] {
    [
        ("fmi2GetDerivatives", |i| unsafe {
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

/// Moves the instance's state to the unassemblable pose; the status of the set.
fn break_pose(i: &Instance) -> Status {
    let n = i.description.number_of_states;
    let mut x = vec![0.0; n];
    // SAFETY: arrays of the model's state count.
    unsafe {
        (i.binary.get_continuous_states)(i.c, x.as_mut_ptr(), n);
        x[1] = UNASSEMBLABLE_THETA2;
        (i.binary.set_continuous_states)(i.c, x.as_ptr(), n)
    }
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
    evaluations()
        .into_iter()
        .map(|(name, evaluate)| Case {
            class: "unassemblable pose",
            model: m,
            interface: Some(Interface::ModelExchange.short()),
            name: format!("{name} at theta[2] = {UNASSEMBLABLE_THETA2}"),
            expect: Expect::discard(),
            why: WHY,
            probe: Box::new(move |l| {
                on_instance(
                    l,
                    m,
                    Interface::ModelExchange,
                    State::ContinuousTimeMode,
                    |i| {
                        let s = break_pose(i);
                        if s != crate::binary::OK {
                            return s;
                        }
                        i.take_log();
                        evaluate(i)
                    },
                )
            }),
        })
        .collect()
}
