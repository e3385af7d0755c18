//! Functions of FMI 3.0 Co-Simulation: fmi3DoStep (one step from `step`, or a step
//! split at the model's intermediate points from `intermediate_step`), Step Mode and
//! output derivatives.

use super::intermediate_step::SplitStep;
use super::step::{StepReport, StepResult, step};
use super::{input_slice, output_slice, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::output_derivatives::{Request, output_derivatives};
use crate::core::structural::Sizes;
use crate::core::variables::{Causality, VariableType};
use crate::core::view::Source;
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::{Call, Interface, Mode};
use crate::fmi3::types::*;

/// fmi3DoStep: one step of the model, or, when the importer passed an
/// intermediateUpdate callback and the model has intermediate points, a step split at
/// them (module `intermediate_step`). With event mode and input clocks, a step ends at
/// the next tick (`ClockCut`; such a step is not split).
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
            if let Some(cut) = ClockCut::of(inst, t, h)? {
                let report = step(inst, t, cut.tick - t)?;
                return Ok(out.write(&cut.finish(inst, report)));
            }
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

/// A step of Co-Simulation with event mode that meets a tick of an input clock the
/// importer drives (it has set the clock; an importer that never does runs the
/// continuous law and steps across the ticks): it
/// ends exactly at the tick (the time set to the tick's, not t + h rounded), with
/// eventHandlingNeeded, so that the importer enters Event Mode, sets the clock and
/// updates the discrete states there; a step that would go beyond the tick returns
/// early at it when the importer allowed early return (the next step starts there),
/// and is refused otherwise (nothing changes).
struct ClockCut {
    tick: f64,
    early: bool,
}

impl ClockCut {
    /// The cut of the step from `t` by `h`, if it meets a tick; Err for a step past a
    /// tick without early return. None for arguments the core refuses (it says why).
    fn of<M: Model>(inst: &Instance<M>, t: f64, h: f64) -> Result<Option<Self>, String> {
        let Interface::CoSimulation {
            event_mode_used: true,
            early_return_allowed,
        } = inst.interface
        else {
            return Ok(None);
        };
        if M::CLOCKS.is_empty() || !(t.is_finite() && h.is_finite() && h > 0.0) {
            return Ok(None);
        }
        inst.core.check_step(t, h)?;
        match inst.extra.clocks.step_end(inst.core.model(), t, t + h) {
            None => Ok(None),
            Some((tick, false)) => Ok(Some(ClockCut { tick, early: false })),
            Some((tick, true)) if early_return_allowed => Ok(Some(ClockCut { tick, early: true })),
            Some((tick, true)) => Err(format!(
                "the step from t = {t} s by {h} s passes the clock tick at t = {tick} s: end \
                 the step at the tick (the interval from fmi3GetIntervalFraction), or \
                 instantiate with earlyReturnAllowed to have the step return there"
            )),
        }
    }

    /// The report of the step cut at the tick: the time exactly the tick's, and
    /// eventHandlingNeeded (a discarded step, or one that returned early at a state
    /// event before the tick, is reported as it is).
    fn finish<M: Model>(&self, inst: &mut Instance<M>, mut report: StepReport) -> StepReport {
        if report.status == Fmi3Status::Discard || report.early_return {
            return report;
        }
        inst.core.set_time(self.tick);
        inst.core.last_successful_time = self.tick;
        report.event_handling_needed = true;
        report.early_return = self.early;
        report.last_successful_time = self.tick;
        report
    }
}

pub unsafe fn enter_step_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3EnterStepMode", Call::EnterStepMode, |inst| {
            super::clocks::check_none_pending(inst)?;
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
        if let Source::Clocked { clock, .. } = v.source {
            return Err(format!(
                "\"{}\" (value reference {vr}) is clocked by {}: it changes only at ticks \
                 (held between them), and output derivatives are of continuous outputs",
                v.name,
                M::CLOCKS[clock].name
            ));
        }
        // Each element of the declaration, as many as the variable has now.
        if let Source::Elements { first, element, .. } = v.source {
            let n = v.size_now(&Sizes::of(inst.core.model(), M::STRUCTURAL));
            requests.extend((element..element + n).map(|k| Request {
                vr: first,
                order,
                element: Some(k),
            }));
        }
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
