//! Model Exchange at a point where the model cannot be evaluated: the plant's
//! continuous state with `theta[2]` (element 1 of theta) = 0.351832 rad, a pose
//! that cannot assemble (issue 12). FMI 3.0 section 3.2.1 lets every function that
//! evaluates the model return fmi3Discard there so that the integrator can retry
//! with a smaller step; fmi3Error would end the instance.

use super::Case;
use crate::Loaded;
use crate::binary::Status;
use crate::fmi3::host::{Instance, Interface3};
use crate::matrix::pose::{Evaluate, unassemblable_cases};

const WHY: &str = "FMI 3.0 3.2.1: a model that cannot be evaluated at the current state returns fmi3Discard (integrator retries), not fmi3Error";

fn evaluations() -> Vec<(&'static str, Evaluate<Interface3>)> {
    vec![
        ("fmi3GetContinuousStateDerivatives", |i: &Instance| unsafe {
            let mut dx = vec![0.0; i.description.number_of_states];
            (i.binary.get_continuous_state_derivatives)(i.c, dx.as_mut_ptr(), dx.len())
        }),
        ("fmi3GetEventIndicators", |i| unsafe {
            let mut z = vec![0.0; i.description.number_of_event_indicators];
            (i.binary.get_event_indicators)(i.c, z.as_mut_ptr(), z.len())
        }),
        ("fmi3GetFloat64(thetaDot)", |i| {
            i.get_float64(&[i.description.by_name("thetaDot").vr]).0
        }),
        ("fmi3GetDirectionalDerivative(der(theta) by theta)", |i| {
            partial(i, false)
        }),
        ("fmi3GetAdjointDerivative(der(theta) by theta)", |i| {
            partial(i, true)
        }),
    ]
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

pub fn cases(l: &Loaded, m: usize) -> Vec<Case> {
    let d = &l.fmus3[m].description;
    let theta = d.variables.iter().find(|v| v.name == "theta").map(|v| v.vr);
    let pairs = d.state_derivative_pairs();
    if pairs.is_empty() || theta != Some(pairs[0].0) {
        return Vec::new();
    }
    unassemblable_cases::<Interface3>(
        (m, d.number_of_states),
        ("fmi3 unassemblable pose", WHY),
        evaluations(),
    )
}
