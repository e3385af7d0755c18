//! Model Exchange at a point where the model cannot be evaluated: the plant's
//! continuous state with `theta[2]` (element 1 of the state vector) = 0.351832
//! rad, a pose that cannot assemble (found by the probes of issue 12). Both
//! standards (FMI 2.0 3.2.2, FMI 3.0 3.2.1) let every function that evaluates the
//! model return Discard there so that the integrator can retry with a smaller
//! step; Error would end the instance (issue 12 item 2). The evaluations are the
//! rows of `seam::Tables::evaluations`.

use super::seam::Standard;
use super::{Case, Expect, on_instance};
use crate::Loaded;
use crate::binary::{OK, Status};

pub const UNASSEMBLABLE_THETA2: f64 = 0.351832;

/// Moves the instance's state to the unassemblable pose (element 1 of the
/// continuous state is `theta[2]`); the status of the set.
fn break_pose<I: Standard>(i: &I::Instance<'_>, n: usize) -> Status {
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

/// One case per evaluation of a Model Exchange instance of model `m` moved to
/// the unassemblable pose: fmiXDiscard. None for a model without that pose.
pub fn cases<I: Standard>(l: &Loaded, m: usize) -> Vec<Case> {
    let d = I::description(l, m);
    let tables = I::tables();
    if !(tables.unassemblable)(d) {
        return Vec::new();
    }
    let (n, why) = (d.number_of_states, tables.reasons.unassemblable);
    (tables.evaluations)()
        .into_iter()
        .map(|(name, evaluate)| {
            Case::new(
                ("unassemblable pose", m, I::MODEL_EXCHANGE),
                format!("{name} at theta[2] = {UNASSEMBLABLE_THETA2}"),
                (Expect::discard(), why),
                move |l| {
                    on_instance(l, m, I::MODEL_EXCHANGE, I::CONTINUOUS_TIME_MODE, |i| {
                        let s = break_pose::<I>(i, n);
                        if s != OK {
                            return s;
                        }
                        crate::host::take(crate::host::Probed::log(i));
                        evaluate(i)
                    })
                },
            )
        })
        .collect()
}
