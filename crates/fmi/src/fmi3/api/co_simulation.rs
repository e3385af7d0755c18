//! Functions of FMI 3.0 Co-Simulation.
//!
//! Events in a step: the layer compares the signs of the model's event indicators
//! before and after each step. The model handles a state event inside the step (the
//! plant updates its end-stop contacts at the end of every step, as in FMI 2.0);
//! with eventModeUsed the step also reports eventHandlingNeeded, so that the importer
//! passes through Event Mode where the contact changed. With earlyReturnAllowed the
//! step ends early, just after the first sign change: the layer locates it by
//! bisection of the step length (repeating the step from a snapshot of its start,
//! `BISECTIONS` halvings of h) and returns earlyReturn with lastSuccessfulTime there.
//! The core checks the step (communication point, positive size, stopTime) and
//! restores the state of a discarded step.

use super::intermediate_step::SplitStep;
use super::{input_slice, output_slice, with_instance};
use crate::core::entry;
use crate::core::instance::{Snapshot, Standard};
use crate::core::model::{Model, StepOutcome};
use crate::core::output_derivatives::{Request, output_derivatives};
use crate::core::variables::{Causality, VariableType};
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::{Call, Interface, Mode};
use crate::fmi3::types::*;

/// The outputs of fmi3DoStep.
pub struct StepResult {
    pub event_handling_needed: *mut Fmi3Boolean,
    pub terminate_simulation: *mut Fmi3Boolean,
    pub early_return: *mut Fmi3Boolean,
    pub last_successful_time: *mut Fmi3Float64,
}

/// The event indicators of the model now, if it has any and they can be evaluated.
fn indicators<M: Model>(model: &M) -> Option<Vec<f64>> {
    let mut z = vec![0.0; M::info().number_of_event_indicators];
    (!z.is_empty() && model.event_indicators(&mut z).is_ok()).then_some(z)
}

/// Halvings of the step that locate an event for an early return: 2^-30 h (1e-12 s for
/// a 1 ms step).
const BISECTIONS: usize = 30;

/// Whether an indicator changed sign between `before` and `after`.
fn sign_changed(before: &Option<Vec<f64>>, after: &Option<Vec<f64>>) -> bool {
    match (before, after) {
        (Some(b), Some(a)) => b.iter().zip(a).any(|(x, y)| (*x > 0.0) != (*y > 0.0)),
        _ => false,
    }
}

/// Restarts the step from `start` and advances it by `tau`; whether an event indicator
/// changed sign in (t, t + tau] (a step the model discards counts as one: it went too
/// far).
fn event_within<M: Model>(
    inst: &mut Instance<M>,
    start: &Snapshot<M>,
    z_start: &Option<Vec<f64>>,
    tau: f64,
) -> Result<bool, String> {
    inst.core.restore(start);
    Ok(match inst.core.do_step(start.time, tau, &inst.log)? {
        StepOutcome::Completed => sign_changed(z_start, &indicators(inst.core.model())),
        StepOutcome::Discarded { .. } => true,
    })
}

/// After a step of length h from `start` in which an event indicator changed sign:
/// the instance advanced to just after the first sign change instead (bisection);
/// whether that is before the end of the step.
fn return_early<M: Model>(
    inst: &mut Instance<M>,
    start: &Snapshot<M>,
    z_start: &Option<Vec<f64>>,
    h: f64,
) -> Result<bool, String> {
    let (mut before, mut after) = (0.0, h);
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (before + after);
        if event_within(inst, start, z_start, mid)? {
            after = mid;
        } else {
            before = mid;
        }
    }
    if !event_within(inst, start, z_start, after)? {
        return Err(format!(
            "the event located at t = {} s vanished when the step was repeated",
            start.time + after
        ));
    }
    Ok(after < h)
}

/// What a step (or a sub-step of a split one) reports through fmi3DoStep's outputs.
pub(super) struct StepReport {
    pub status: Fmi3Status,
    pub event_handling_needed: bool,
    pub terminate_simulation: bool,
    pub early_return: bool,
    pub last_successful_time: f64,
}

impl StepResult {
    /// Err unless every output pointer is non-null.
    pub(super) fn check(&self) -> Result<(), String> {
        for (null, what) in [
            (self.event_handling_needed.is_null(), "eventHandlingNeeded"),
            (self.terminate_simulation.is_null(), "terminateSimulation"),
            (self.early_return.is_null(), "earlyReturn"),
            (self.last_successful_time.is_null(), "lastSuccessfulTime"),
        ] {
            if null {
                return Err(format!("{what} is a null pointer"));
            }
        }
        Ok(())
    }

    /// Writes `report` to the host's outputs (checked by [`StepResult::check`]).
    pub(super) unsafe fn write(&self, report: &StepReport) -> Fmi3Status {
        // SAFETY: non-null (checked) and, by fmi3DoStep's contract, valid.
        unsafe {
            *self.event_handling_needed = fmi3_bool(report.event_handling_needed);
            *self.terminate_simulation = fmi3_bool(report.terminate_simulation);
            *self.early_return = fmi3_bool(report.early_return);
            *self.last_successful_time = report.last_successful_time;
        }
        report.status
    }
}

/// One step of the model from `t` by `h`, with the event handling of the module
/// documentation; the instance moves to StepDiscarded when the model discards it.
pub(super) fn step<M: Model>(inst: &mut Instance<M>, t: f64, h: f64) -> Result<StepReport, String> {
    let (events_used, early_allowed) = match inst.interface {
        Interface::CoSimulation {
            event_mode_used,
            early_return_allowed,
        } => (event_mode_used, early_return_allowed),
        Interface::ModelExchange => (false, false),
    };
    // The indicators matter only to an importer that handles events or returns
    // early; for any other the step evaluates none (no sign change without them).
    let watch_events = events_used || early_allowed;
    let z_before = watch_events
        .then(|| indicators(inst.core.model()))
        .flatten();
    let start = (early_allowed && z_before.is_some()).then(|| inst.core.snapshot(Standard::Fmi3));
    match inst.core.do_step(t, h, &inst.log)? {
        StepOutcome::Completed => {
            let z_after = watch_events
                .then(|| indicators(inst.core.model()))
                .flatten();
            let changed = sign_changed(&z_before, &z_after);
            let early = match (changed, &start) {
                (true, Some(start)) => return_early(inst, start, &z_before, h)?,
                _ => false,
            };
            Ok(StepReport {
                status: Fmi3Status::Ok,
                event_handling_needed: events_used && changed,
                terminate_simulation: false,
                early_return: early,
                last_successful_time: inst.core.last_successful_time,
            })
        }
        StepOutcome::Discarded {
            reason,
            terminate: cannot_go_on,
        } => {
            inst.mode = Mode::StepDiscarded;
            inst.log.status(
                Fmi3Status::Discard,
                &format!("fmi3DoStep: step from t = {t} s by {h} s rejected: {reason}"),
            );
            Ok(StepReport {
                status: Fmi3Status::Discard,
                event_handling_needed: false,
                terminate_simulation: cannot_go_on,
                early_return: false,
                last_successful_time: inst.core.time,
            })
        }
    }
}

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
        let v = inst.table.typed(vr, VariableType::Real)?;
        if v.causality != Causality::Output {
            return Err(format!(
                "\"{}\" (value reference {vr}) is not an output: only outputs have output \
                 derivatives",
                v.name
            ));
        }
        requests.extend(v.elements().iter().map(|&vr| Request { vr, order }));
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sign_change_of_any_indicator_is_an_event() {
        let before = Some(vec![0.5, -1.0]);
        assert!(!sign_changed(&before, &Some(vec![0.1, -2.0])));
        assert!(sign_changed(&before, &Some(vec![-0.1, -2.0])));
        assert!(sign_changed(&before, &Some(vec![0.1, 2.0])));
        assert!(!sign_changed(&None, &Some(vec![-0.1, 2.0])));
    }
}
