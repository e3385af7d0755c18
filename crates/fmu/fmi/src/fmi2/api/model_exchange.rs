//! Functions of FMI 2.0 Model Exchange.

use super::{output_ref, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::model_exchange_calls::{self as calls, state_array_getters};
use crate::fmi2::instance::Instance;
use crate::fmi2::mode::{Call, Fmi2, Mode};
use crate::fmi2::types::*;

fn fmi2_boolean(value: bool) -> Fmi2Boolean {
    if value { FMI2_TRUE } else { FMI2_FALSE }
}

pub unsafe fn enter_event_mode<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2EnterEventMode", Call::EnterEventMode, |inst| {
            calls::enter_event_mode(inst, Mode::EventMode)
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
                let (update, next) = calls::update_discrete_states(inst);
                *info = Fmi2EventInfo {
                    new_discrete_states_needed: fmi2_boolean(update.discrete_states_need_update),
                    terminate_simulation: fmi2_boolean(update.terminate_simulation),
                    nominals_of_continuous_states_changed: fmi2_boolean(
                        update.nominals_of_continuous_states_changed,
                    ),
                    values_of_continuous_states_changed: fmi2_boolean(
                        update.values_of_continuous_states_changed,
                    ),
                    next_event_time_defined: fmi2_boolean(next.is_some()),
                    next_event_time: next.unwrap_or(0.0),
                };
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
            |inst| entry::enter(inst, Mode::ContinuousTimeMode),
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
            |inst: &mut Instance<M>| {
                calls::completed_integrator_step(inst, enter_event_mode, terminate_simulation)
            },
        )
    }
}

pub unsafe fn set_time<M: Model>(c: Fmi2Component, time: Fmi2Real) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2SetTime", Call::SetTime, |inst| {
            entry::set_time(&mut inst.core, time)?;
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
            |inst| calls::set_continuous_states(inst, x, nx, "x[]"),
        )
    }
}

state_array_getters! {
    Fmi2, Fmi2Component, Fmi2Status;
    get_derivatives: "fmi2GetDerivatives", Call::GetDerivatives, Derivatives;
    get_event_indicators: "fmi2GetEventIndicators", Call::GetEventIndicators, EventIndicators;
    get_continuous_states: "fmi2GetContinuousStates", Call::GetContinuousStates, ContinuousStates;
    get_nominals_of_continuous_states: "fmi2GetNominalsOfContinuousStates",
        Call::GetNominalsOfContinuousStates, Nominals;
}
