//! fmi3GetDirectionalDerivative and fmi3GetAdjointDerivative: the Jacobian J of the
//! unknowns (outputs, state derivatives) with respect to the knowns (inputs, states),
//! element by element, times a seed: J s (directional) or s^T J (adjoint).

use super::{input_slice, output_slice, with_instance};
use crate::core::model::Model;
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::Call;
use crate::fmi3::types::*;

/// The table elements (FMI 2.0 value references) of FMI 3.0 variables, in order.
fn elements<M: Model>(inst: &Instance<M>, vrs: &[u32], what: &str) -> Result<Vec<u32>, String> {
    let mut out = Vec::new();
    for &vr in vrs {
        let v = inst
            .table
            .find(vr)
            .ok_or_else(|| format!("{what}: unknown value reference {vr}"))?;
        if v.elements().is_empty() {
            return Err(format!("{what}: \"{}\" has no partial derivatives", v.name));
        }
        out.extend_from_slice(v.elements());
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

/// J (rows: unknown elements, columns: known elements) at the current point.
fn jacobian<M: Model>(
    inst: &Instance<M>,
    rows: &[u32],
    columns: &[u32],
) -> Result<Vec<Vec<f64>>, String> {
    rows.iter()
        .map(|&u| {
            columns
                .iter()
                .map(|&k| inst.core.model.partial_derivative(u, k))
                .collect()
        })
        .collect()
}

unsafe fn derivative<M: Model>(
    c: Fmi3Instance,
    function: &str,
    adjoint: bool,
    r: DerivativeRequest,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, function, Call::Derivative, |inst| {
            if !M::info().provides_directional_derivative {
                return Err(format!(
                    "{} provides no partial derivatives",
                    M::info().model_name
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
            let j = jacobian(inst, &rows, &columns)?;
            for (i, o) in out.iter_mut().enumerate() {
                *o = if adjoint {
                    j.iter().zip(seed).map(|(row, s)| row[i] * s).sum()
                } else {
                    j[i].iter().zip(seed).map(|(d, s)| d * s).sum()
                };
            }
            Ok(Fmi3Status::Ok)
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
