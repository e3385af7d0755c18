//! Functions of FMI 3.0 Co-Simulation.
//!
//! Events in a step: the layer compares the signs of the model's event indicators
//! before and after each step. The model handles a state event inside the step (the
//! plant updates its end-stop contacts at the end of every step, as in FMI 2.0);
//! with eventModeUsed the step also reports eventHandlingNeeded, so that the importer
//! passes through Event Mode at the communication point where the contact changed.
//! Steps never return early (mightReturnEarlyFromDoStep is not declared).

use super::{check_finite, input_slice, output_ref, with_instance};
use crate::core::model::{Model, StepOutcome};
use crate::fmi3::mode::{Call, Interface, Mode};
use crate::fmi3::types::*;

/// Largest accepted difference between the master's communication point and the
/// instance time, relative to max(1, |t|): absorbs round-off of t += h in the master.
const TIME_MATCH: f64 = 1e-9;

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

/// Whether an indicator changed sign between `before` and `after`.
fn sign_changed(before: &Option<Vec<f64>>, after: &Option<Vec<f64>>) -> bool {
    match (before, after) {
        (Some(b), Some(a)) => b.iter().zip(a).any(|(x, y)| (*x > 0.0) != (*y > 0.0)),
        _ => false,
    }
}

/// Checks the communication point and step against the instance time and stop time.
fn check_step(t: f64, h: f64, time: f64, stop_time: Option<f64>) -> Result<(), String> {
    if h <= 0.0 {
        return Err(format!("communicationStepSize = {h} is not positive"));
    }
    if (t - time).abs() > TIME_MATCH * t.abs().max(1.0) {
        return Err(format!(
            "currentCommunicationPoint {t} differs from the FMU time {time}"
        ));
    }
    if let Some(stop) = stop_time
        && t + h > stop + TIME_MATCH * stop.abs().max(1.0)
    {
        return Err(format!(
            "the step to t = {} s passes stopTime = {stop} s",
            t + h
        ));
    }
    Ok(())
}

pub unsafe fn do_step<M: Model>(
    c: Fmi3Instance,
    current_communication_point: Fmi3Float64,
    communication_step_size: Fmi3Float64,
    _no_set_fmu_state_prior_to_current_point: Fmi3Boolean,
    out: StepResult,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3DoStep", Call::DoStep, |inst| {
            let event = output_ref(out.event_handling_needed, "eventHandlingNeeded")?;
            let terminate = output_ref(out.terminate_simulation, "terminateSimulation")?;
            let early = output_ref(out.early_return, "earlyReturn")?;
            let last = output_ref(out.last_successful_time, "lastSuccessfulTime")?;
            let t = check_finite(current_communication_point, "currentCommunicationPoint")?;
            let h = check_finite(communication_step_size, "communicationStepSize")?;
            check_step(t, h, inst.core.time, inst.core.stop_time)?;
            let before = inst.core.model.clone();
            let z_before = indicators(&before);
            inst.core.set_time(t);
            *early = FMI3_FALSE;
            match inst.core.model.do_step(t, h, &inst.log) {
                StepOutcome::Completed => {
                    inst.core.set_time(t + h);
                    inst.core.last_successful_time = t + h;
                    let events_used = inst.interface
                        == Interface::CoSimulation {
                            event_mode_used: true,
                        };
                    let z_after = indicators(&inst.core.model);
                    *event = fmi3_bool(events_used && sign_changed(&z_before, &z_after));
                    *terminate = FMI3_FALSE;
                    *last = t + h;
                    Ok(Fmi3Status::Ok)
                }
                StepOutcome::Discarded {
                    reason,
                    terminate: cannot_go_on,
                } => {
                    inst.core.model = before;
                    inst.core.set_time(t);
                    inst.core.terminated_by_model = cannot_go_on;
                    inst.mode = Mode::StepDiscarded;
                    *event = FMI3_FALSE;
                    *terminate = fmi3_bool(cannot_go_on);
                    *last = t;
                    inst.log.status(
                        Fmi3Status::Discard,
                        &format!("fmi3DoStep: step from t = {t} s by {h} s rejected: {reason}"),
                    );
                    Ok(Fmi3Status::Discard)
                }
            }
        })
    }
}

pub unsafe fn enter_step_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3EnterStepMode", Call::EnterStepMode, |inst| {
            inst.mode = Mode::StepMode;
            Ok(Fmi3Status::Ok)
        })
    }
}

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
            |_| {
                input_slice(vr, nvr, "valueReferences[]")?;
                input_slice(orders, nvr, "orders[]")?;
                if n_values > 0 && values.is_null() {
                    return Err("values[] is a null pointer".to_string());
                }
                if nvr == 0 {
                    return Ok(Fmi3Status::Ok);
                }
                Err(
                    "output derivatives are not provided (maxOutputDerivativeOrder=\"0\")"
                        .to_string(),
                )
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

    #[test]
    fn steps_past_the_stop_time_are_refused() {
        assert!(check_step(0.0, 0.1, 0.0, Some(1.0)).is_ok());
        // The last step of a master that sums 0.1 ten times ends at 0.9999999999999999.
        assert!(check_step(0.9, 0.1 + 1e-15, 0.9, Some(1.0)).is_ok());
        assert!(check_step(0.95, 0.1, 0.95, Some(1.0)).is_err());
        assert!(check_step(0.0, 0.1, 0.5, None).is_err());
        assert!(check_step(0.0, 0.0, 0.0, None).is_err());
    }
}
