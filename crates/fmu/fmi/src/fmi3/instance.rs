//! One FMI 3.0 instance: the layer's one instance type ([`FmuInstance`]) for the FMI
//! 3.0 front-end, whose extra part ([`Fmi3Extra`]) is the FMI 3.0 view of the variable
//! table and the intermediate-update callback.
//! Values are read and written per FMI 3.0 variable (a scalar or an array) through the
//! table's elements.

use super::clocks::Clocks;
use super::declared::view;
use super::extra::Fmi3Extra;
use super::intermediate::IntermediateUpdate;
use super::logging::Logger;
use super::mode::{Fmi3, Interface, Mode};
use super::table::{Source, Table3, Variable3};
use crate::core::entry;
use crate::core::frontend::FmuInstance;
use crate::core::instance as core_instance;
use crate::core::model::Model;
use crate::core::structural::Sizes;
use crate::core::value_check::Value;
use crate::core::variables::{Causality, Initial, Variability};

use std::sync::Arc;

/// What a setter did besides writing: Some(line) when it accepted a fixed parameter
/// set again to the value it holds (the setter returns fmi3Warning with the line).
pub type Kept = Option<String>;

/// Everything an FMI 3.0 instance owns. Instances share no mutable state.
pub type Instance<M> = FmuInstance<Fmi3, M>;

impl<M: Model> FmuInstance<Fmi3, M> {
    /// An instance serving the array view, or the scalar-only one when `scalar`, once
    /// `check` accepts the view and the number of table variables (the instance is
    /// built in place only then: it is large, and each move of it is a copy).
    pub fn new(
        interface: Interface,
        log: Logger,
        intermediate_update: Option<IntermediateUpdate>,
        scalar: bool,
        check: impl FnOnce(&Table3, usize) -> Result<(), String>,
        index: Arc<core_instance::Index<M>>,
    ) -> Result<Self, String> {
        let core = core_instance::Instance::new(index)?;
        let table = views::<M>(core.index(), scalar)?;
        check(&table, core.index().len())?;
        let extra = Fmi3Extra {
            table,
            intermediate_update,
            clocks: Clocks::new::<M>(),
        };
        let mut inst = FmuInstance::with(interface, log, extra, core);
        inst.set_clock_periods_to_start();
        Ok(inst)
    }

    /// The period parameters of the model's clocks at their start values (at
    /// instantiation and reset; the model's `Default` need not know them).
    pub fn set_clock_periods_to_start(&mut self) {
        for c in M::CLOCKS {
            (c.period.set)(self.core.model_mut(), c.period.start);
        }
    }

    /// Makes the computed values current for reading `variables`; Ok(Some(reason))
    /// when one of them cannot be evaluated here (the read returns Discard). In
    /// Intermediate Update Mode only variables declared intermediateUpdate are read.
    pub fn prepare_read<'a>(
        &mut self,
        variables: impl Iterator<Item = &'a Variable3> + Clone,
    ) -> Result<Option<String>, String> {
        if self.mode == Mode::IntermediateUpdateMode
            && let Some(v) = variables.clone().find(|v| !v.intermediate_update::<M>())
        {
            return Err(format!(
                "\"{}\" is not declared intermediateUpdate: it cannot be read in \
                 IntermediateUpdateMode",
                v.name
            ));
        }
        let sizes = Sizes::of(self.core.model(), M::STRUCTURAL);
        let parts = variables.clone().filter_map(move |v| match v.source {
            Source::Elements {
                declaration,
                element,
                ..
            } => Some((declaration, element, v.size_now(&sizes))),
            _ => None,
        });
        if let Some(reason) = self.core.prepare_read_declared(parts)? {
            return Ok(Some(reason));
        }
        let indicators = {
            let mut variables = variables;
            variables.any(|v| matches!(v.source, Source::EventIndicators { .. }))
        };
        Ok(indicators.then(|| self.indicators_unevaluable()).flatten())
    }

    /// Why the event indicators cannot be evaluated here, if they cannot (the same
    /// answer as fmi3GetEventIndicators: the model's reason, or a non-finite value).
    fn indicators_unevaluable(&self) -> Option<String> {
        let mut z = vec![0.0; M::INFO.number_of_event_indicators];
        match self.core.model().event_indicators(&mut z) {
            Err(reason) => Some(reason),
            Ok(()) => z
                .iter()
                .find(|x| !x.is_finite())
                .map(|bad| format!("the model computed the event indicator {bad}")),
        }
    }

    /// Reads the Float64 variable `v` into `out` (its size).
    #[inline]
    pub fn get_float64(&mut self, v: &Variable3, out: &mut [f64]) -> Result<(), String> {
        match &v.source {
            Source::Time => out[0] = self.core.time,
            Source::EventIndicators { first } => {
                let mut z = vec![0.0; M::INFO.number_of_event_indicators];
                self.core.model().event_indicators(&mut z)?;
                if let Some(bad) = z.iter().find(|z| !z.is_finite()) {
                    return Err(format!("the model computed the event indicator {bad}"));
                }
                out.copy_from_slice(&z[*first..*first + out.len()]);
            }
            Source::Elements {
                declaration,
                element,
                ..
            } => self.core.get_reals(*declaration, *element, out)?,
            Source::ClockPeriod { clock } => {
                out[0] = (M::CLOCKS[*clock].period.get)(self.core.model());
            }
            Source::Clocked { clock, output } => {
                let get = M::CLOCKS[*clock].outputs[*output].get;
                let model = self.core.model();
                for (i, o) in out.iter_mut().enumerate() {
                    *o = get(model, i);
                }
            }
            Source::Clock { .. } => return Err(format!("\"{}\" is a Clock", v.name)),
            Source::Structural { .. } => return Err(format!("\"{}\" is a UInt64", v.name)),
        }
        Ok(())
    }

    #[inline]
    pub fn get_int32(&mut self, v: &Variable3, out: &mut [i32]) -> Result<(), String> {
        match v.source {
            Source::Elements {
                declaration,
                element,
                ..
            } => self.core.get_integers(declaration, element, out),
            _ => Ok(()),
        }
    }

    #[inline]
    pub fn get_boolean(&mut self, v: &Variable3, out: &mut [bool]) -> Result<(), String> {
        match v.source {
            Source::Elements {
                declaration,
                element,
                ..
            } => self.core.get_booleans(declaration, element, out),
            _ => Ok(()),
        }
    }

    /// Reads the structural parameter `v` (the size the model holds).
    pub fn get_uint64(&mut self, v: &Variable3, out: &mut [u64]) -> Result<(), String> {
        let Source::Structural { parameter } = v.source else {
            return Err(format!("\"{}\" is not a UInt64", v.name));
        };
        out[0] = (M::STRUCTURAL[parameter].get)(self.core.model()) as u64;
        Ok(())
    }

    /// Sets the structural parameter `v` (Configuration Mode only): the model resized
    /// to the checked size, the new elements at their start values
    /// (`core::structural::resize`); a refused size leaves the model as it was.
    pub fn set_uint64(&mut self, v: &Variable3, values: &[u64]) -> Result<Kept, String> {
        let Source::Structural { parameter } = v.source else {
            return Err(format!("\"{}\" is not a UInt64", v.name));
        };
        self.check_settable(v)?;
        let n = M::STRUCTURAL[parameter].checked(values[0])?;
        let mut model = self.core.model().clone();
        crate::core::structural::resize(&mut model, parameter, n)?;
        *self.core.model_mut() = model;
        Ok(None)
    }

    pub fn set_float64(&mut self, v: &Variable3, values: &[f64]) -> Result<Kept, String> {
        self.set(v, values.iter().map(|&x| Value::Real(x)))
    }

    pub fn set_int32(&mut self, v: &Variable3, values: &[i32]) -> Result<Kept, String> {
        self.set(v, values.iter().map(|&x| Value::Integer(x)))
    }

    pub fn set_boolean(&mut self, v: &Variable3, values: &[bool]) -> Result<Kept, String> {
        self.set(v, values.iter().map(|&x| Value::Boolean(x)))
    }

    /// Writes `values` to the elements of `v` through the core's checks, after the
    /// mode check (nothing for time and the event indicators, which are not
    /// settable). Ok(Some(line)): a fixed parameter set after initialization to the
    /// values it holds, every element bit for bit, is accepted without effect and the
    /// setter returns fmi3Warning with that line; one different element refuses all.
    fn set(&mut self, v: &Variable3, values: impl Iterator<Item = Value>) -> Result<Kept, String> {
        let Source::Elements {
            first,
            stride,
            declaration,
            element,
        } = v.source
        else {
            if let Source::ClockPeriod { clock } = v.source {
                return self.set_period(v, clock, values);
            }
            return self.check_settable(v).map(|()| None);
        };
        if let Err(refusal) = self.check_settable(v) {
            // The rule refuses a fixed parameter only after initialization.
            if (v.causality, v.variability) != (Causality::Parameter, Variability::Fixed) {
                return Err(refusal);
            }
            let unchanged = self.core.holds_declared(declaration, element, values)?;
            return entry::refuse_unless_unchanged(refusal, &v.name, self.mode, unchanged);
        }
        (self.core).set_declared(declaration, element, (first, stride), values)?;
        Ok(None)
    }

    /// Sets the period parameter `v` of clock `clock` (a fixed parameter: before the
    /// end of initialization; afterwards only to the value it holds, with a warning).
    fn set_period(
        &mut self,
        v: &Variable3,
        clock: usize,
        mut values: impl Iterator<Item = Value>,
    ) -> Result<Kept, String> {
        let Some(Value::Real(period)) = values.next() else {
            return Err(format!("\"{}\" takes one Float64", v.name));
        };
        if let Err(refusal) = self.check_settable(v) {
            let held = (M::CLOCKS[clock].period.get)(self.core.model());
            let unchanged = held.to_bits() == period.to_bits();
            return entry::refuse_unless_unchanged(refusal, &v.name, self.mode, unchanged);
        }
        crate::core::clocks::period_fraction(period, &v.name)?;
        (M::CLOCKS[clock].period.set)(self.core.model_mut(), period);
        Ok(None)
    }

    /// Whether `v` may be written in the current mode (FMI 3.0 rules for fmi3Set*,
    /// section 2.3.4).
    fn check_settable(&self, v: &Variable3) -> Result<(), String> {
        use Mode::*;
        let mode = self.mode;
        let exact = v.initial == Some(Initial::Exact);
        if v.causality == Causality::StructuralParameter && mode != ConfigurationMode {
            return Err(format!(
                "\"{}\" is a structural parameter: it is set in Configuration Mode \
                 (fmi3EnterConfigurationMode after instantiation), not in {mode:?}",
                v.name
            ));
        }
        let ok = v.variability != Variability::Constant
            && v.source != Source::Time
            && match mode {
                ConfigurationMode => v.causality == Causality::StructuralParameter,
                Instantiated => {
                    v.causality == Causality::Input
                        || matches!(v.initial, Some(Initial::Exact | Initial::Approx))
                }
                InitializationMode => v.causality == Causality::Input || exact,
                EventMode | StepMode => {
                    v.causality == Causality::Input
                        || (v.causality == Causality::Parameter
                            && v.variability == Variability::Tunable)
                }
                ContinuousTimeMode => {
                    v.causality == Causality::Input && v.variability == Variability::Continuous
                }
                IntermediateUpdateMode => {
                    v.causality == Causality::Input && v.intermediate_update::<M>()
                }
                _ => false,
            };
        entry::settable(ok, &v.name, v.causality, v.variability, mode)
    }
}

/// The FMI 3.0 view (array or scalar-only) of model M's table: derived once from the
/// index shared by the instances of the model in this library (`Index::view3`).
fn views<M: Model>(index: &core_instance::Index<M>, scalar: bool) -> Result<Arc<Table3>, String> {
    if scalar {
        let arrays = views(index, false)?;
        index.view3(true, |table| super::scalar::view(table, &arrays))
    } else {
        index.view3(false, view::<M>)
    }
}
