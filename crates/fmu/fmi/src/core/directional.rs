//! Directional derivatives (fmi2GetDirectionalDerivative, fmi3GetDirectionalDerivative,
//! fmi3GetAdjointDerivative), independent of the standard: the value references become
//! declared [`Element`]s before the model is asked, so the model decodes none.

use super::hooks::Element;
use super::instance::{Instance, variable};
use super::model::Model;
use super::variables::Variable;

impl<M: Model> Instance<M> {
    /// dvUnknown = J dvKnown at the current point for the table scalars `unknowns` and
    /// `knowns` ([`Model::JACOBIAN`], which the caller has checked is given); the
    /// computed values must be current.
    pub fn directional_derivative(
        &self,
        unknowns: &[u32],
        knowns: &[u32],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<(), String> {
        let (unknowns, knowns) = (self.elements(unknowns)?, self.elements(knowns)?);
        self.directional_derivative_of(&unknowns, &knowns, seed, out)
    }

    /// [`directional_derivative`](Self::directional_derivative) for declared elements
    /// (FMI 3.0: an array sized by a structural parameter has elements past the FMI
    /// 2.0 table's).
    pub fn directional_derivative_of(
        &self,
        unknowns: &[Element],
        knowns: &[Element],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<(), String> {
        let jacobian = M::JACOBIAN.ok_or("the model provides no directional derivatives")?;
        jacobian.apply(self.model(), unknowns, knowns, seed, out)
    }

    fn elements(&self, vrs: &[u32]) -> Result<Vec<Element>, String> {
        vrs.iter()
            .map(|&vr| variable(self.table(), vr).map(Variable::element))
            .collect()
    }
}
