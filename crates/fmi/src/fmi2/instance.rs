//! One FMU instance in safe Rust: mode, time, logger and the model, with typed and
//! checked access to the variables. The C entry points in `api` only translate
//! pointers into calls on this type.

use super::logging::{LAYER_CATEGORIES, Logger};
use super::mode::{Interface, Mode};
use super::model::Model;
use super::variables::{Causality, Initial, Kind, Variability, Variable, find};

/// Everything an instance owns. Instances share no mutable state.
pub struct Instance<M: Model> {
    pub mode: Mode,
    pub interface: Interface,
    pub log: Logger,
    pub model: M,
    pub time: f64,
    pub last_successful_time: f64,
    /// Set when a step was discarded because the model cannot go on at all.
    pub terminated_by_model: bool,
}

/// A copy of everything that fmi2SetFMUstate restores.
#[derive(Clone)]
pub struct Snapshot<M: Model> {
    pub model: M,
    pub time: f64,
    pub last_successful_time: f64,
    pub terminated_by_model: bool,
}

/// All log categories of a model: the layer's, then the model's own.
pub fn log_categories<M: Model>() -> Vec<super::logging::LogCategory> {
    let mut all = LAYER_CATEGORIES.to_vec();
    all.extend_from_slice(M::info().log_categories);
    all
}

/// A new model with every start value of the table applied through its writer.
pub fn model_with_start_values<M: Model>() -> Result<M, String> {
    let mut model = M::new();
    for v in M::variables() {
        let result = match &v.kind {
            Kind::Real {
                set: Some(set),
                start: Some(s),
                ..
            } => set(&mut model, *s),
            Kind::Integer {
                set: Some(set),
                start: Some(s),
                ..
            } => set(&mut model, *s),
            Kind::Boolean {
                set: Some(set),
                start: Some(s),
                ..
            } => set(&mut model, *s),
            _ => Ok(()),
        };
        result.map_err(|e| format!("start value of \"{}\" rejected: {e}", v.name))?;
    }
    Ok(model)
}

fn variable<M: Model>(vr: u32) -> Result<&'static Variable<M>, String> {
    find(M::variables(), vr).ok_or_else(|| format!("unknown value reference {vr}"))
}

fn wrong_type<M>(v: &Variable<M>, wanted: &str) -> String {
    format!(
        "\"{}\" (value reference {}) is a {} variable, not {wanted}",
        v.name,
        v.value_reference,
        v.variable_type().as_str()
    )
}

impl<M: Model> Instance<M> {
    pub fn new(interface: Interface, log: Logger) -> Result<Self, String> {
        let mut model = model_with_start_values::<M>()?;
        let time = M::info().default_experiment.start_time;
        model.set_time(time);
        Ok(Instance {
            mode: Mode::Instantiated,
            interface,
            log,
            model,
            time,
            last_successful_time: time,
            terminated_by_model: false,
        })
    }

    /// fmi2Reset: back to the state right after fmi2Instantiate.
    pub fn reset(&mut self) -> Result<(), String> {
        self.model = model_with_start_values::<M>()?;
        self.time = M::info().default_experiment.start_time;
        self.model.set_time(self.time);
        self.last_successful_time = self.time;
        self.terminated_by_model = false;
        self.mode = Mode::Instantiated;
        Ok(())
    }

    pub fn set_time(&mut self, time: f64) {
        self.time = time;
        self.model.set_time(time);
    }

    pub fn snapshot(&self) -> Snapshot<M> {
        Snapshot {
            model: self.model.clone(),
            time: self.time,
            last_successful_time: self.last_successful_time,
            terminated_by_model: self.terminated_by_model,
        }
    }

    pub fn restore(&mut self, s: &Snapshot<M>) {
        self.model = s.model.clone();
        self.time = s.time;
        self.last_successful_time = s.last_successful_time;
        self.terminated_by_model = s.terminated_by_model;
        if self.mode == Mode::StepFailed {
            self.mode = Mode::StepComplete;
        }
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
        if ok {
            Ok(())
        } else {
            Err(format!(
                "\"{}\" (causality {}, variability {}) cannot be set in {:?}",
                v.name,
                v.causality.as_str(),
                v.variability.as_str(),
                mode
            ))
        }
    }

    pub fn get_real(&self, vr: u32) -> Result<f64, String> {
        let v = variable::<M>(vr)?;
        match &v.kind {
            Kind::Real { get, .. } => {
                let value = get(&self.model);
                if value.is_finite() {
                    Ok(value)
                } else {
                    Err(format!("\"{}\" evaluated to {value}", v.name))
                }
            }
            _ => Err(wrong_type(v, "Real")),
        }
    }

    pub fn get_integer(&self, vr: u32) -> Result<i32, String> {
        let v = variable::<M>(vr)?;
        match &v.kind {
            Kind::Integer { get, .. } => Ok(get(&self.model)),
            _ => Err(wrong_type(v, "Integer")),
        }
    }

    pub fn get_boolean(&self, vr: u32) -> Result<bool, String> {
        let v = variable::<M>(vr)?;
        match &v.kind {
            Kind::Boolean { get, .. } => Ok(get(&self.model)),
            _ => Err(wrong_type(v, "Boolean")),
        }
    }

    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<(), String> {
        let v = variable::<M>(vr)?;
        let Kind::Real { set, min, max, .. } = &v.kind else {
            return Err(wrong_type(v, "Real"));
        };
        self.check_settable(v)?;
        if !value.is_finite() {
            return Err(format!("\"{}\" cannot be set to {value}", v.name));
        }
        if min.is_some_and(|m| value < m) || max.is_some_and(|m| value > m) {
            return Err(format!(
                "\"{}\" = {value} is outside [{}, {}]",
                v.name,
                min.unwrap_or(f64::NEG_INFINITY),
                max.unwrap_or(f64::INFINITY)
            ));
        }
        let set = set
            .as_ref()
            .ok_or_else(|| format!("\"{}\" has no writer", v.name))?;
        set(&mut self.model, value).map_err(|e| format!("\"{}\" = {value}: {e}", v.name))
    }

    pub fn set_integer(&mut self, vr: u32, value: i32) -> Result<(), String> {
        let v = variable::<M>(vr)?;
        let Kind::Integer { set, min, max, .. } = &v.kind else {
            return Err(wrong_type(v, "Integer"));
        };
        self.check_settable(v)?;
        if min.is_some_and(|m| value < m) || max.is_some_and(|m| value > m) {
            return Err(format!("\"{}\" = {value} is outside its range", v.name));
        }
        let set = set
            .as_ref()
            .ok_or_else(|| format!("\"{}\" has no writer", v.name))?;
        set(&mut self.model, value).map_err(|e| format!("\"{}\" = {value}: {e}", v.name))
    }

    pub fn set_boolean(&mut self, vr: u32, value: bool) -> Result<(), String> {
        let v = variable::<M>(vr)?;
        let Kind::Boolean { set, .. } = &v.kind else {
            return Err(wrong_type(v, "Boolean"));
        };
        self.check_settable(v)?;
        let set = set
            .as_ref()
            .ok_or_else(|| format!("\"{}\" has no writer", v.name))?;
        set(&mut self.model, value).map_err(|e| format!("\"{}\" = {value}: {e}", v.name))
    }
}
