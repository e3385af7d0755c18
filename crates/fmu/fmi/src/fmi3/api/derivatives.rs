//! fmi3GetDirectionalDerivative and fmi3GetAdjointDerivative: the Jacobian J of the
//! unknowns (outputs, state derivatives) with respect to the knowns (inputs, states),
//! element by element, times a seed: J s (directional, one call of the model's
//! `directional_derivative`) or s^T J (adjoint, one such call per known element, each
//! giving a column of J). Where the model cannot be evaluated the call returns
//! fmi3Discard with its reason.

use super::{input_slice, output_slice, with_instance};
use crate::core::hooks::Element;
use crate::core::model::Model;
use crate::core::structural::Sizes;
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::Call;
use crate::fmi3::table::Source;
use crate::fmi3::types::*;

/// The declared elements of FMI 3.0 variables, in order (an array sized by a
/// structural parameter: as many as it has now).
fn elements<M: Model>(inst: &Instance<M>, vrs: &[u32], what: &str) -> Result<Vec<Element>, String> {
    let sizes = Sizes::of(inst.core.model(), M::STRUCTURAL);
    let mut out = Vec::new();
    for &vr in vrs {
        let v = inst
            .extra
            .table
            .find(vr)
            .ok_or_else(|| format!("{what}: unknown value reference {vr}"))?;
        let Source::Elements {
            declaration,
            element,
            ..
        } = v.source
        else {
            return Err(format!("{what}: \"{}\" has no partial derivatives", v.name));
        };
        let name = M::VARIABLES[declaration].name;
        out.extend((0..v.size_now(&sizes)).map(|k| Element {
            name,
            index: element + k,
        }));
    }
    Ok(out)
}

/// The arguments of both functions.
pub struct DerivativeRequest {
    pub unknowns: *const Fmi3ValueReference,
    pub n_unknowns: usize,
    pub knowns: *const Fmi3ValueReference,
    pub n_knowns: usize,
    pub seed: *const Fmi3Float64,
    pub n_seed: usize,
    pub sensitivity: *mut Fmi3Float64,
    pub n_sensitivity: usize,
}

/// J s (`adjoint` false) or s^T J (true) at the current point.
fn evaluate<M: Model>(
    inst: &mut Instance<M>,
    adjoint: bool,
    rows: &[Element],
    columns: &[Element],
    seed: &[f64],
    out: &mut [f64],
) -> Result<(), String> {
    inst.core.update_values()?;
    let core = &inst.core;
    if !adjoint {
        return core.directional_derivative_of(rows, columns, seed, out);
    }
    let mut unit = vec![0.0; columns.len()];
    let mut column = vec![0.0; rows.len()];
    for (k, o) in out.iter_mut().enumerate() {
        unit[k] = 1.0;
        core.directional_derivative_of(rows, columns, &unit, &mut column)?;
        unit[k] = 0.0;
        *o = column.iter().zip(seed).map(|(j, s)| j * s).sum();
    }
    Ok(())
}

unsafe fn derivative<M: Model>(
    c: Fmi3Instance,
    function: &str,
    adjoint: bool,
    r: DerivativeRequest,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, function, Call::Derivative, |inst| {
            if M::JACOBIAN.is_none() {
                return Err(format!(
                    "{} provides no partial derivatives",
                    M::INFO.model_name
                ));
            }
            let unknowns = input_slice(r.unknowns, r.n_unknowns, "unknowns[]")?;
            let knowns = input_slice(r.knowns, r.n_knowns, "knowns[]")?;
            let rows = elements(inst, unknowns, "unknowns[]")?;
            let columns = elements(inst, knowns, "knowns[]")?;
            let (n_seed, n_out) = if adjoint {
                (rows.len(), columns.len())
            } else {
                (columns.len(), rows.len())
            };
            if r.n_seed != n_seed || r.n_sensitivity != n_out {
                return Err(format!(
                    "nSeed = {}, nSensitivity = {}; the variables need {n_seed} and {n_out}",
                    r.n_seed, r.n_sensitivity
                ));
            }
            let seed = input_slice(r.seed, n_seed, "seed[]")?;
            let out = output_slice(r.sensitivity, n_out, "sensitivity[]")?;
            if let Some(bad) = seed.iter().find(|s| !s.is_finite()) {
                return Err(format!("seed[] contains {bad}"));
            }
            let reason = match evaluate(inst, adjoint, &rows, &columns, seed, out) {
                Ok(()) => match out.iter().find(|v| !v.is_finite()) {
                    None => return Ok(Fmi3Status::Ok),
                    Some(bad) => format!("the derivative evaluates to {bad}"),
                },
                Err(reason) => reason,
            };
            inst.log.status(
                Fmi3Status::Discard,
                &format!("{function}: at t = {} s: {reason}", inst.core.time),
            );
            Ok(Fmi3Status::Discard)
        })
    }
}

pub unsafe fn get_directional_derivative<M: Model>(
    c: Fmi3Instance,
    request: DerivativeRequest,
) -> Fmi3Status {
    unsafe { derivative::<M>(c, "fmi3GetDirectionalDerivative", false, request) }
}

pub unsafe fn get_adjoint_derivative<M: Model>(
    c: Fmi3Instance,
    request: DerivativeRequest,
) -> Fmi3Status {
    unsafe { derivative::<M>(c, "fmi3GetAdjointDerivative", true, request) }
}
