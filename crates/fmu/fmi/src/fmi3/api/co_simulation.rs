//! Functions of FMI 3.0 Co-Simulation: fmi3DoStep (one step from `step`, or a step
//! split at the model's intermediate points from `intermediate_step`), Step Mode and
//! output derivatives.

use super::intermediate_step::SplitStep;
use super::step::{StepResult, step};
use super::{input_slice, output_slice, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::output_derivatives::{Request, output_derivatives};
use crate::core::variables::{Causality, VariableType};
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::{Call, Mode};
use crate::fmi3::types::*;

/// fmi3DoStep: one step of the model, or, when the importer passed an
/// intermediateUpdate callback and the model has intermediate points, a step split at
/// them (module `intermediate_step`).
pub unsafe fn do_step<M: Model>(
    c: Fmi3Instance,
    current_communication_point: Fmi3Float64,
    communication_step_size: Fmi3Float64,
    _no_set_fmu_state_prior_to_current_point: Fmi3Boolean,
    out: StepResult,
) -> Fmi3Status {
    let (t, h) = (current_communication_point, communication_step_size);
    let mut split = None;
    let status = unsafe {
        with_instance::<M>(c, "fmi3DoStep", Call::DoStep, |inst| {
            out.check()?;
            match SplitStep::new(inst, t, h)? {
                None => Ok(out.write(&step(inst, t, h)?)),
                Some(mut s) => {
                    let status = s.advance(inst, &out)?;
                    split = Some(s);
                    Ok(status)
                }
            }
        })
    };
    match split {
        // SAFETY: `c` and `out` as given to fmi3DoStep.
        Some(s) => unsafe { s.run::<M>(c, &out, status) },
        None => status,
    }
}

pub unsafe fn enter_step_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3EnterStepMode", Call::EnterStepMode, |inst| {
            entry::enter(inst, Mode::StepMode)
        })
    }
}

/// The core's requests for the FMI 3.0 pairs `(valueReferences[i], orders[i])`: every
/// element of an array variable with the order of its pair, in the order of the
/// values[] serialization; Err unless the elements number `n_values`.
fn element_requests<M: Model>(
    inst: &Instance<M>,
    vrs: &[u32],
    orders: &[i32],
    n_values: usize,
) -> Result<Vec<Request>, String> {
    let mut requests = Vec::with_capacity(n_values);
    for (&vr, &order) in vrs.iter().zip(orders) {
        let v = inst.extra.table.typed(vr, VariableType::Real)?;
        if v.causality != Causality::Output {
            return Err(format!(
                "\"{}\" (value reference {vr}) is not an output: only outputs have output \
                 derivatives",
                v.name
            ));
        }
        requests.extend(v.elements().map(|vr| Request { vr, order }));
    }
    if requests.len() != n_values {
        return Err(format!(
            "nValues = {n_values}, but the variables have {} elements",
            requests.len()
        ));
    }
    Ok(requests)
}

/// fmi3GetOutputDerivatives: for each pair `(valueReferences[i], orders[i])` the
/// `orders[i]`-th time derivative of every element of that output, at the current
/// communication point (`core::output_derivatives`).
pub unsafe fn get_output_derivatives<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    orders: *const Fmi3Int32,
    values: *mut Fmi3Float64,
    n_values: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3GetOutputDerivatives",
            Call::GetOutputDerivatives,
            |inst| {
                let vrs = input_slice(vr, nvr, "valueReferences[]")?;
                let orders = input_slice(orders, nvr, "orders[]")?;
                let out = output_slice(values, n_values, "values[]")?;
                let requests = element_requests(inst, vrs, orders, n_values)?;
                match output_derivatives(&mut inst.core, &requests, out)? {
                    None => Ok(Fmi3Status::Ok),
                    Some(reason) => Ok(entry::discard(inst, "fmi3GetOutputDerivatives", &reason)),
                }
            },
        )
    }
}
