//! fmi3DoStep split at intermediate points (FMI 3.0 intermediate update, section
//! 4.2.4), for a model with `Model::INTERMEDIATE_UPDATE_POINTS` = n > 0 and an
//! importer that passed an intermediateUpdate callback.
//!
//! The communication step [t, t + h] is split into n equal sub-intervals; each is one
//! step of the model (with the event handling of a whole step: an early return at an
//! event ends the communication step there). After each inner point the instance is
//! in Intermediate Update Mode and the callback runs with no Rust reference into the
//! instance alive: the importer reads outputs (current at that point) and sets the
//! continuous inputs, which hold over the next sub-interval. An early return the
//! callback requests (only with earlyReturnAllowed) ends the step at the first point
//! at or after the requested time. A sub-interval the model discards ends the step
//! with fmi3Discard, the instance at the start of that sub-interval (lastSuccessfulTime).
//! Any illegal call from the callback puts the instance in the Error state, and the
//! step then ends with fmi3Error.

use super::step::{StepReport, StepResult, step};
use super::with_instance;
use crate::core::handles;
use crate::core::model::Model;
use crate::fmi3::instance::Instance;
use crate::fmi3::intermediate::IntermediateUpdate;
use crate::fmi3::mode::{Call, Interface, Mode};
use crate::fmi3::types::{Fmi3Instance, Fmi3Status};

/// A communication step being split: where it is and what it will report.
pub(super) struct SplitStep {
    t: f64,
    h: f64,
    points: u32,
    /// Sub-intervals done.
    done: u32,
    /// An event was met in a sub-interval (eventHandlingNeeded).
    event: bool,
    /// The importer asked to return early, at the first point from then on.
    return_at: Option<f64>,
    /// The importer's callback.
    callback: IntermediateUpdate,
    /// The time of the intermediate point waiting for the callback.
    pending: Option<f64>,
    can_return_early: bool,
}

impl SplitStep {
    /// Some when the step is to be split (a callback and intermediate points), after
    /// the checks of the whole step.
    pub(super) fn new<M: Model>(
        inst: &Instance<M>,
        t: f64,
        h: f64,
    ) -> Result<Option<Self>, String> {
        let Some(callback) = inst.extra.intermediate_update else {
            return Ok(None);
        };
        if M::INTERMEDIATE_UPDATE_POINTS == 0 {
            return Ok(None);
        }
        inst.core.check_step(t, h)?;
        let can_return_early = matches!(
            inst.interface,
            Interface::CoSimulation {
                early_return_allowed: true,
                ..
            }
        );
        Ok(Some(SplitStep {
            t,
            h,
            points: M::INTERMEDIATE_UPDATE_POINTS,
            done: 0,
            event: false,
            return_at: None,
            callback,
            pending: None,
            can_return_early,
        }))
    }

    /// The end of sub-interval `k` (1 ..= points); the last one ends at t + h exactly.
    fn end_of(&self, k: u32) -> f64 {
        if k == self.points {
            self.t + self.h
        } else {
            self.t + self.h * f64::from(k) / f64::from(self.points)
        }
    }

    /// Steps over the next sub-interval. At the end of the communication step (or an
    /// early return, or a discarded step) the outputs are written and its status
    /// returned; otherwise the instance enters Intermediate Update Mode and the point
    /// waits for the callback.
    pub(super) fn advance<M: Model>(
        &mut self,
        inst: &mut Instance<M>,
        out: &StepResult,
    ) -> Result<Fmi3Status, String> {
        inst.mode = Mode::StepMode;
        let from = inst.core.time;
        if self.return_at.is_some_and(|at| from >= at) {
            // The importer asked to return at this point (or before).
            let report = StepReport {
                status: Fmi3Status::Ok,
                event_handling_needed: self.event,
                terminate_simulation: false,
                early_return: true,
                last_successful_time: from,
            };
            // SAFETY: the outputs were checked at the start of fmi3DoStep.
            return Ok(unsafe { out.write(&report) });
        }
        self.done += 1;
        let mut report = step(inst, from, self.end_of(self.done) - from)?;
        self.event |= report.event_handling_needed;
        report.event_handling_needed = self.event;
        let now = inst.core.time;
        let requested = self.return_at.is_some_and(|at| now >= at);
        let last = self.done == self.points;
        if report.status != Fmi3Status::Ok || report.early_return || requested || last {
            report.early_return |= requested && !last;
            // SAFETY: the outputs were checked at the start of fmi3DoStep.
            return Ok(unsafe { out.write(&report) });
        }
        inst.mode = Mode::IntermediateUpdateMode;
        self.pending = Some(now);
        Ok(Fmi3Status::Ok)
    }

    /// Calls the importer at each pending point and resumes the step after it, until
    /// the step ends (or the instance refuses to go on: an illegal call from the
    /// callback, a freed instance); the status of fmi3DoStep.
    ///
    /// # Safety
    /// `c` and `out` as given to fmi3DoStep; no reference into the instance is live.
    pub(super) unsafe fn run<M: Model>(
        mut self,
        c: Fmi3Instance,
        out: &StepResult,
        mut status: Fmi3Status,
    ) -> Fmi3Status {
        while let Some(time) = self.pending.take() {
            // SAFETY: no reference into the instance is live here.
            if let Some(at) = unsafe { self.callback.call(time, self.can_return_early) } {
                self.return_at = Some(at);
            }
            // SAFETY: the instance is looked up again (the callback may have freed it).
            status = unsafe {
                with_instance::<M>(c, "fmi3DoStep", Call::ResumeStep, |inst| {
                    self.advance(inst, out)
                })
            };
            if status == Fmi3Status::Error {
                // Refused (another thread was inside a call when the callback
                // returned), the instance is still in Intermediate Update Mode: it is
                // put in the Error state that fmi3DoStep reports as soon as it is free
                // (after any other Error it is there already).
                handles::fail::<Instance<M>>(c as usize);
            }
        }
        status
    }
}
