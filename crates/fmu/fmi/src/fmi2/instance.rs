//! One FMI 2.0 instance: the layer's one instance type
//! ([`FmuInstance`]) for the FMI 2.0 front-end, with the 2.0 rules for setting values.
//! The C entry points in `api` only translate pointers into calls on this type.

use super::logging::Logger;
use super::mode::{Fmi2, Interface, Mode};
use crate::core::declare::Declaration;
use crate::core::entry;
use crate::core::frontend::FmuInstance;
use crate::core::instance as core_instance;
use crate::core::model::Model;
use crate::core::value_check::Value;
use crate::core::variables::{Causality, Initial, Variability, element_name, value_type};
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

    /// Whether element i of `v` may be written in the current mode (FMI 2.0 rules for
    /// fmi2Set*).
    fn check_settable(&self, v: &Declaration<M>, i: usize) -> Result<(), String> {
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
        if ok {
            return Ok(());
        }
        let name = element_name(v, i).to_string();
        entry::settable(ok, &name, v.causality, v.variability, mode)
    }

    /// Writes `value` to `vr` after the mode check (a wrong type is reported by the
    /// core's writer). Ok(Some(line)): a fixed parameter set after initialization to
    /// the value it holds, bit for bit, is accepted without effect and the setter
    /// returns fmi2Warning with that line; a different value is refused.
    fn set(&mut self, vr: u32, value: Value) -> Result<Option<String>, String> {
        let (v, i) = self.core.element(vr)?;
        if value_type(&v.value) == value.variable_type()
            && let Err(refusal) = self.check_settable(v, i)
        {
            // The rule refuses a fixed parameter only after initialization.
            if (v.causality, v.variability) != (Causality::Parameter, Variability::Fixed) {
                return Err(refusal);
            }
            let unchanged = self.core.holds(vr, value)?;
            return entry::refuse_unless_unchanged(
                refusal,
                &element_name(v, i),
                self.mode,
                unchanged,
            );
        }
        self.core.write(vr, value)?;
        Ok(None)
    }

    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<Option<String>, String> {
        self.set(vr, Value::Real(value))
    }

    pub fn set_integer(&mut self, vr: u32, value: i32) -> Result<Option<String>, String> {
        self.set(vr, Value::Integer(value))
    }

    pub fn set_boolean(&mut self, vr: u32, value: bool) -> Result<Option<String>, String> {
        self.set(vr, Value::Boolean(value))
    }
}
