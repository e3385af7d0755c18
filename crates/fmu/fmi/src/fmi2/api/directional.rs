//! fmi2GetDirectionalDerivative.

use super::{input_slice, output_slice, with_instance};
use crate::core::entry;
use crate::core::model::Model;
use crate::core::variables::find;
use crate::fmi2::mode::Call;
use crate::fmi2::types::*;

#[allow(clippy::too_many_arguments)]
pub unsafe fn get_directional_derivative<M: Model>(
    c: Fmi2Component,
    unknown_refs: *const Fmi2ValueReference,
    n_unknown: usize,
    known_refs: *const Fmi2ValueReference,
    n_known: usize,
    dv_known: *const Fmi2Real,
    dv_unknown: *mut Fmi2Real,
) -> Fmi2Status {
    unsafe {
        with_instance::<M>(
            c,
            "fmi2GetDirectionalDerivative",
            Call::GetDirectionalDerivative,
            |inst| {
                if M::JACOBIAN.is_none() {
                    return Err(format!(
                        "{} does not provide directional derivatives \
                     (providesDirectionalDerivative=\"false\")",
                        M::INFO.model_name
                    ));
                }
                let unknowns = input_slice(unknown_refs, n_unknown, "vUnknown_ref[]")?;
                let knowns = input_slice(known_refs, n_known, "vKnown_ref[]")?;
                let seeds = input_slice(dv_known, n_known, "dvKnown[]")?;
                let out = output_slice(dv_unknown, n_unknown, "dvUnknown[]")?;
                for &vr in unknowns.iter().chain(knowns) {
                    if find(inst.core.table(), vr).is_none() {
                        return Err(format!("unknown value reference {vr}"));
                    }
                }
                if let Some(bad) = seeds.iter().find(|s| !s.is_finite()) {
                    return Err(format!("dvKnown contains {bad}"));
                }
                let evaluated = inst.core.update_values().and_then(|()| {
                    (inst.core).directional_derivative(unknowns, knowns, seeds, out)
                });
                let reason = match evaluated {
                    Ok(()) => match out.iter().find(|v| !v.is_finite()) {
                        None => return Ok(Fmi2Status::Ok),
                        Some(bad) => format!("the derivative evaluates to {bad}"),
                    },
                    Err(reason) => reason,
                };
                Ok(entry::discard(
                    inst,
                    "fmi2GetDirectionalDerivative",
                    &reason,
                ))
            },
        )
    }
}
