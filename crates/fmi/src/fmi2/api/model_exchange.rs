//! Functions of FMI 2.0 Model Exchange.

use super::{check_finite, input_slice, output_ref, output_slice, with_instance};
use crate::core::logging::Log;
use crate::core::model::Model;
use crate::fmi2::instance::Instance;
use crate::fmi2::mode::{Call, Mode};
use crate::fmi2::types::*;

/// Checks an array length against the model's count.
fn check_len(n: usize, expected: usize, what: &str) -> Result<(), String> {
    if n == expected {
        Ok(())
    } else {
        Err(format!("{what} has length {n}, the model has {expected}"))
    }
}

fn fmi2_boolean(value: bool) -> Fmi2Boolean {
    if value { FMI2_TRUE } else { FMI2_FALSE }
}

fn states<M: Model>() -> usize {
    M::info().number_of_continuous_states
}

pub unsafe fn enter_event_mode<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2EnterEventMode", Call::EnterEventMode, |inst| {
            inst.mode = Mode::EventMode;
            inst.log.debug(
                "logEvents",
                &format!("event mode at t = {} s", inst.core.time),
            );
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn new_discrete_states<M: Model>(
    c: Fmi2Component,
    event_info: *mut Fmi2EventInfo,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2NewDiscreteStates",
            Call::NewDiscreteStates,
            |inst| {
                let info = output_ref(event_info, "fmi2EventInfo")?;
                let update = inst.core.model_mut().update_discrete_states();
                let next = inst.core.model().next_time_event(inst.core.time);
                *info = Fmi2EventInfo {
                    new_discrete_states_needed: fmi2_boolean(update.discrete_states_need_update),
                    terminate_simulation: fmi2_boolean(update.terminate_simulation),
                    nominals_of_continuous_states_changed: fmi2_boolean(
                        update.nominals_of_continuous_states_changed,
                    ),
                    values_of_continuous_states_changed: fmi2_boolean(
                        update.values_of_continuous_states_changed,
                    ),
                    next_event_time_defined: if next.is_some() {
                        FMI2_TRUE
                    } else {
                        FMI2_FALSE
                    },
                    next_event_time: next.unwrap_or(0.0),
                };
                if let Some(t) = next {
                    inst.log
                        .debug("logEvents", &format!("next time event at t = {t} s"));
                }
                Ok(Fmi2Status::Ok)
            },
        )
    }
}

pub unsafe fn enter_continuous_time_mode<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2EnterContinuousTimeMode",
            Call::EnterContinuousTimeMode,
            |inst| {
                inst.mode = Mode::ContinuousTimeMode;
                Ok(Fmi2Status::Ok)
            },
        )
    }
}

pub unsafe fn completed_integrator_step<M: Model>(
    c: Fmi2Component,
    _no_set_fmu_state_prior_to_current_point: Fmi2Boolean,
    enter_event_mode: *mut Fmi2Boolean,
    terminate_simulation: *mut Fmi2Boolean,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2CompletedIntegratorStep",
            Call::CompletedIntegratorStep,
            |_: &mut Instance<M>| {
                let enter = output_ref(enter_event_mode, "enterEventMode")?;
                let stop = output_ref(terminate_simulation, "terminateSimulation")?;
                // The models have no step events.
                *enter = FMI2_FALSE;
                *stop = FMI2_FALSE;
                Ok(Fmi2Status::Ok)
            },
        )
    }
}

pub unsafe fn set_time<M: Model>(c: Fmi2Component, time: Fmi2Real) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetTime", Call::SetTime, |inst| {
            inst.core.set_time(check_finite(time, "time")?);
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn set_continuous_states<M: Model>(
    c: Fmi2Component,
    x: *const Fmi2Real,
    nx: usize,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2SetContinuousStates",
            Call::SetContinuousStates,
            |inst| {
                check_len(nx, states::<M>(), "x[]")?;
                let x = input_slice(x, nx, "x[]")?;
                if let Some(bad) = x.iter().find(|v| !v.is_finite()) {
                    return Err(format!("x[] contains {bad}"));
                }
                inst.core.model_mut().set_continuous_states(x);
                Ok(Fmi2Status::Ok)
            },
        )
    }
}

/// Fills an output array of the model's state count with `f`, then checks finiteness.
unsafe fn fill_states<M: Model>(
    c: Fmi2Component,
    function: &str,
    call: Call,
    ptr: *mut Fmi2Real,
    n: usize,
    expected: fn() -> usize,
    f: fn(&M, &mut [f64]),
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, function, call, |inst| {
            check_len(n, expected(), "the array")?;
            let out = output_slice(ptr, n, "the array")?;
            f(inst.core.model(), out);
            if let Some(bad) = out.iter().find(|v| !v.is_finite()) {
                return Err(format!("the model computed {bad}"));
            }
            Ok(Fmi2Status::Ok)
        })
    }
}

/// Like `fill_states`, for a model function that may fail: its error is logged and
/// returned as fmi2Discard (the model cannot be evaluated here; the integrator may
/// retry with a smaller step), leaving the instance usable.
unsafe fn fill_fallible<M: Model>(
    c: Fmi2Component,
    function: &str,
    call: Call,
    ptr: *mut Fmi2Real,
    n: usize,
    expected: fn() -> usize,
    f: fn(&M, &mut [f64]) -> Result<(), String>,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, function, call, |inst| {
            check_len(n, expected(), "the array")?;
            let out = output_slice(ptr, n, "the array")?;
            if let Err(reason) = f(inst.core.model(), out) {
                inst.log.status(
                    Fmi2Status::Discard,
                    &format!("{function}: at t = {} s: {reason}", inst.core.time),
                );
                return Ok(Fmi2Status::Discard);
            }
            if let Some(bad) = out.iter().find(|v| !v.is_finite()) {
                return Err(format!("the model computed {bad}"));
            }
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn get_derivatives<M: Model>(
    c: Fmi2Component,
    dx: *mut Fmi2Real,
    nx: usize,
) -> Fmi2Status {
    unsafe {
        fill_fallible::<M>(
            c,
            "fmi2GetDerivatives",
            Call::GetDerivatives,
            dx,
            nx,
            states::<M>,
            M::derivatives,
        )
    }
}

pub unsafe fn get_event_indicators<M: Model>(
    c: Fmi2Component,
    z: *mut Fmi2Real,
    nz: usize,
) -> Fmi2Status {
    unsafe {
        fill_fallible::<M>(
            c,
            "fmi2GetEventIndicators",
            Call::GetEventIndicators,
            z,
            nz,
            || M::info().number_of_event_indicators,
            M::event_indicators,
        )
    }
}

pub unsafe fn get_continuous_states<M: Model>(
    c: Fmi2Component,
    x: *mut Fmi2Real,
    nx: usize,
) -> Fmi2Status {
    unsafe {
        fill_states::<M>(
            c,
            "fmi2GetContinuousStates",
            Call::GetContinuousStates,
            x,
            nx,
            states::<M>,
            M::continuous_states,
        )
    }
}

pub unsafe fn get_nominals_of_continuous_states<M: Model>(
    c: Fmi2Component,
    x_nominal: *mut Fmi2Real,
    nx: usize,
) -> Fmi2Status {
    unsafe {
        fill_states::<M>(
            c,
            "fmi2GetNominalsOfContinuousStates",
            Call::GetNominalsOfContinuousStates,
            x_nominal,
            nx,
            states::<M>,
            M::nominals_of_continuous_states,
        )
    }
}
