//! One FMI 2.0 instance: the layer's one instance type
//! ([`FmuInstance`]) for the FMI 2.0 front-end, with the 2.0 rules for setting values.
//! The C entry points in `api` only translate pointers into calls on this type.

use super::logging::Logger;
use super::mode::{Fmi2, Interface, Mode};
use crate::core::entry;
use crate::core::frontend::FmuInstance;
use crate::core::instance as core_instance;
use crate::core::model::Model;
use crate::core::variables::{Causality, Initial, Variability, Variable, VariableType};
use std::sync::Arc;

/// Everything an FMI 2.0 instance owns (nothing beyond the shared fields). Instances
/// share no mutable state.
pub type Instance<M> = FmuInstance<Fmi2, M>;

impl<M: Model> FmuInstance<Fmi2, M> {
    pub fn new(
        interface: Interface,
        log: Logger,
        index: Arc<core_instance::Index<M>>,
    ) -> Result<Self, String> {
        let core = core_instance::Instance::new(index)?;
        Ok(FmuInstance::with(interface, log, (), core))
    }

    /// Whether `v` may be written in the current mode (FMI 2.0 rules for fmi2Set*).
    fn check_settable(&self, v: &Variable<M>) -> Result<(), String> {
        use Mode::*;
        let mode = self.mode;
        let ok = match (v.causality, v.variability) {
            (_, Variability::Constant) => false,
            (Causality::Parameter, Variability::Fixed) => {
                matches!(mode, Instantiated | InitializationMode)
            }
            (Causality::Parameter, Variability::Tunable) => {
                matches!(
                    mode,
                    Instantiated | InitializationMode | EventMode | StepComplete
                )
            }
            (Causality::Input, variability) => {
                matches!(
                    mode,
                    Instantiated | InitializationMode | EventMode | StepComplete
                ) || (mode == ContinuousTimeMode && variability == Variability::Continuous)
            }
            _ => match v.initial {
                Some(Initial::Exact) => matches!(mode, Instantiated | InitializationMode),
                Some(Initial::Approx) => mode == Instantiated,
                _ => false,
            },
        };
        entry::settable(ok, &v.name(), v.causality, v.variability, mode)
    }

    /// The mode check for writing `vr` as a `wanted` variable (a wrong type is
    /// reported by the core's writer instead).
    fn check_write(&self, vr: u32, wanted: VariableType) -> Result<(), String> {
        let v = core_instance::variable(self.core.table(), vr)?;
        if v.variable_type() == wanted {
            self.check_settable(v)?;
        }
        Ok(())
    }

    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<(), String> {
        self.check_write(vr, VariableType::Real)?;
        self.core.set_real(vr, value)
    }

    pub fn set_integer(&mut self, vr: u32, value: i32) -> Result<(), String> {
        self.check_write(vr, VariableType::Integer)?;
        self.core.set_integer(vr, value)
    }

    pub fn set_boolean(&mut self, vr: u32, value: bool) -> Result<(), String> {
        self.check_write(vr, VariableType::Boolean)?;
        self.core.set_boolean(vr, value)
    }
}
