//! Functions of FMI 3.0 Model Exchange, and fmi3UpdateDiscreteStates (Event Mode of
//! both interfaces).

use super::{output_ref, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::model_exchange_calls::{self as calls, indicators, state_array_getters, states};
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::{Call, Fmi3, Mode};
use crate::fmi3::types::*;

/// The outputs of fmi3UpdateDiscreteStates.
pub struct DiscreteStatesUpdate {
    pub discrete_states_need_update: *mut Fmi3Boolean,
    pub terminate_simulation: *mut Fmi3Boolean,
    pub nominals_changed: *mut Fmi3Boolean,
    pub values_changed: *mut Fmi3Boolean,
    pub next_event_time_defined: *mut Fmi3Boolean,
    pub next_event_time: *mut Fmi3Float64,
}

pub unsafe fn update_discrete_states<M: Model>(
    c: Fmi3Instance,
    out: DiscreteStatesUpdate,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3UpdateDiscreteStates",
            Call::UpdateDiscreteStates,
            |inst| {
                let need = output_ref(out.discrete_states_need_update, "discreteStatesNeedUpdate")?;
                let terminate = output_ref(out.terminate_simulation, "terminateSimulation")?;
                let nominals =
                    output_ref(out.nominals_changed, "nominalsOfContinuousStatesChanged")?;
                let values = output_ref(out.values_changed, "valuesOfContinuousStatesChanged")?;
                let defined = output_ref(out.next_event_time_defined, "nextEventTimeDefined")?;
                let next_time = output_ref(out.next_event_time, "nextEventTime")?;
                if let Some(reason) = super::clocks::run_ticks(inst)? {
                    return Ok(entry::discard(inst, "fmi3UpdateDiscreteStates", &reason));
                }
                let (update, next) = calls::update_discrete_states(inst);
                *need = fmi3_bool(update.discrete_states_need_update);
                *terminate = fmi3_bool(update.terminate_simulation);
                *nominals = fmi3_bool(update.nominals_of_continuous_states_changed);
                *values = fmi3_bool(update.values_of_continuous_states_changed);
                *defined = fmi3_bool(next.is_some());
                *next_time = next.unwrap_or(0.0);
                Ok(Fmi3Status::Ok)
            },
        )
    }
}

pub unsafe fn enter_continuous_time_mode<M: Model>(c: Fmi3Instance) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3EnterContinuousTimeMode",
            Call::EnterContinuousTimeMode,
            |inst| {
                super::clocks::check_none_pending(inst)?;
                entry::enter(inst, Mode::ContinuousTimeMode)
            },
        )
    }
}

pub unsafe fn completed_integrator_step<M: Model>(
    c: Fmi3Instance,
    _no_set_fmu_state_prior_to_current_point: Fmi3Boolean,
    enter_event_mode: *mut Fmi3Boolean,
    terminate_simulation: *mut Fmi3Boolean,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3CompletedIntegratorStep",
            Call::CompletedIntegratorStep,
            |inst: &mut Instance<M>| {
                calls::completed_integrator_step(inst, enter_event_mode, terminate_simulation)
            },
        )
    }
}

pub unsafe fn set_time<M: Model>(c: Fmi3Instance, time: Fmi3Float64) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetTime", Call::SetTime, |inst| {
            entry::set_time(&mut inst.core, time)?;
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn set_continuous_states<M: Model>(
    c: Fmi3Instance,
    x: *const Fmi3Float64,
    nx: usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi3SetContinuousStates",
            Call::SetContinuousStates,
            |inst| calls::set_continuous_states(inst, x, nx, "continuousStates[]"),
        )
    }
}

state_array_getters! {
    Fmi3, Fmi3Instance, Fmi3Status;
    get_continuous_state_derivatives: "fmi3GetContinuousStateDerivatives",
        Call::ContinuousStateQuery, Derivatives;
    get_event_indicators: "fmi3GetEventIndicators", Call::ContinuousStateQuery, EventIndicators;
    get_continuous_states: "fmi3GetContinuousStates", Call::ContinuousStateQuery, ContinuousStates;
    get_nominals_of_continuous_states: "fmi3GetNominalsOfContinuousStates",
        Call::ContinuousStateQuery, Nominals;
}

unsafe fn get_count<M: Model>(
    c: Fmi3Instance,
    function: &str,
    out: *mut usize,
    count: fn(&M) -> usize,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, function, Call::CountQuery, |inst| {
            *output_ref(out, "the count")? = count(inst.core.model());
            Ok(Fmi3Status::Ok)
        })
    }
}

pub unsafe fn get_number_of_event_indicators<M: Model>(
    c: Fmi3Instance,
    n: *mut usize,
) -> Fmi3Status {
    unsafe {
        get_count::<M>(c, "fmi3GetNumberOfEventIndicators", n, |_| {
            indicators::<M>()
        })
    }
}

pub unsafe fn get_number_of_continuous_states<M: Model>(
    c: Fmi3Instance,
    n: *mut usize,
) -> Fmi3Status {
    unsafe { get_count::<M>(c, "fmi3GetNumberOfContinuousStates", n, states::<M>) }
}
