//! Functions of FMI 2.0 Co-Simulation.

use super::{input_slice, output_ref, output_slice, with_instance};
use crate::core::entry;
use crate::core::model::{Model, StepOutcome};
use crate::core::output_derivatives::{Request, output_derivatives};
use crate::fmi2::mode::{Call, Mode};
use crate::fmi2::types::*;
use std::ffi::c_int;

pub unsafe fn do_step<M: Model>(
    c: Fmi2Component,
    current_communication_point: Fmi2Real,
    communication_step_size: Fmi2Real,
    _no_set_fmu_state_prior_to_current_point: Fmi2Boolean,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2DoStep", Call::DoStep, |inst| {
            let t = current_communication_point;
            let h = communication_step_size;
            match inst.core.do_step(t, h, &inst.log)? {
                StepOutcome::Completed => Ok(Fmi2Status::Ok),
                StepOutcome::Discarded { reason, .. } => {
                    inst.mode = Mode::StepFailed;
                    inst.log.status(
                        Fmi2Status::Discard,
                        &format!("fmi2DoStep: step from t = {t} s by {h} s rejected: {reason}"),
                    );
                    Ok(Fmi2Status::Discard)
                }
            }
        })
    }
}

pub unsafe fn cancel_step<M: Model>(c: Fmi2Component) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2CancelStep", Call::CancelStep, |_| {
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn set_real_input_derivatives<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    order: *const Fmi2Integer,
    value: *const Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2SetRealInputDerivatives",
            Call::SetRealInputDerivatives,
            |inst| {
                let vrs = input_slice(vr, nvr, "vr[]")?;
                let orders = input_slice(order, nvr, "order[]")?;
                let values = input_slice(value, nvr, "value[]")?;
                for ((&vr, &order), &value) in vrs.iter().zip(orders).zip(values) {
                    inst.core.set_input_derivative(vr, order, value)?;
                }
                Ok(Fmi2Status::Ok)
            },
        )
    }
}

/// fmi2GetRealOutputDerivatives: `value[i]` is the `order[i]`-th time derivative of the
/// output `vr[i]` at the current communication point (`core::output_derivatives`).
pub unsafe fn get_real_output_derivatives<M: Model>(
    c: Fmi2Component,
    vr: *const Fmi2ValueReference,
    nvr: usize,
    order: *const Fmi2Integer,
    value: *mut Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2GetRealOutputDerivatives",
            Call::GetRealOutputDerivatives,
            |inst| {
                let vrs = input_slice(vr, nvr, "vr[]")?;
                let orders = input_slice(order, nvr, "order[]")?;
                let out = output_slice(value, nvr, "value[]")?;
                let requests: Vec<Request> = vrs
                    .iter()
                    .zip(orders)
                    .map(|(&vr, &order)| Request {
                        vr,
                        order,
                        element: None,
                    })
                    .collect();
                match output_derivatives(&mut inst.core, &requests, out)? {
                    None => Ok(Fmi2Status::Ok),
                    Some(reason) => Ok(entry::discard(
                        inst,
                        "fmi2GetRealOutputDerivatives",
                        &reason,
                    )),
                }
            },
        )
    }
}

fn no_such_status(kind: c_int, function: &str) -> String {
    match kind {
        FMI2_DO_STEP_STATUS | FMI2_PENDING_STATUS => format!(
            "{function}: status kind {kind} concerns asynchronous steps, which this FMU never runs"
        ),
        FMI2_LAST_SUCCESSFUL_TIME | FMI2_TERMINATED => {
            format!("{function}: status kind {kind} is not of this type")
        }
        other => format!("{function}: {other} is not an fmi2StatusKind"),
    }
}

pub unsafe fn get_status<M: Model>(
    c: Fmi2Component,
    kind: c_int,
    value: *mut Fmi2Status,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetStatus", Call::GetStatus, |_| {
            output_ref(value, "value")?;
            Err(no_such_status(kind, "fmi2GetStatus"))
        })
    }
}

pub unsafe fn get_real_status<M: Model>(
    c: Fmi2Component,
    kind: c_int,
    value: *mut Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetRealStatus", Call::GetStatus, |inst| {
            let out = output_ref(value, "value")?;
            if kind != FMI2_LAST_SUCCESSFUL_TIME {
                return Err(no_such_status(kind, "fmi2GetRealStatus"));
            }
            *out = inst.core.last_successful_time;
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn get_integer_status<M: Model>(
    c: Fmi2Component,
    kind: c_int,
    value: *mut Fmi2Integer,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetIntegerStatus", Call::GetStatus, |_| {
            output_ref(value, "value")?;
            Err(no_such_status(kind, "fmi2GetIntegerStatus"))
        })
    }
}

pub unsafe fn get_boolean_status<M: Model>(
    c: Fmi2Component,
    kind: c_int,
    value: *mut Fmi2Boolean,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetBooleanStatus", Call::GetStatus, |inst| {
            let out = output_ref(value, "value")?;
            if kind != FMI2_TERMINATED {
                return Err(no_such_status(kind, "fmi2GetBooleanStatus"));
            }
            *out = if inst.core.terminated_by_model {
                FMI2_TRUE
            } else {
                FMI2_FALSE
            };
            Ok(Fmi2Status::Ok)
        })
    }
}

pub unsafe fn get_string_status<M: Model>(
    c: Fmi2Component,
    kind: c_int,
    value: *mut Fmi2String,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(c, "fmi2GetStringStatus", Call::GetStatus, |_| {
            output_ref(value, "value")?;
            Err(no_such_status(kind, "fmi2GetStringStatus"))
        })
    }
}
