//! One fmi3DoStep without intermediate updates: the step of the model with the event
//! logic of Co-Simulation, and the outputs it writes ([`StepResult`]). Used by
//! `co_simulation` (a whole step) and `intermediate_step` (each piece of a split step).
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

use crate::core::instance::{Snapshot, Standard};
use crate::core::model::{Model, StepOutcome};
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::{Interface, Mode};
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
    let mut z = vec![0.0; M::INFO.number_of_event_indicators];
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
