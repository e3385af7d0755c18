//! One model instance, independent of the FMI version: the model, its time, the stop
//! time of the experiment, and typed, checked access to the variables. A front-end
//! adds its mode, logger and C entry points around it.

use super::model::Model;
use super::variables::{Kind, Variable, find};

/// The FMI standard whose front-end wrote an FMU state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Standard {
    Fmi2,
    Fmi3,
}

impl Standard {
    /// Byte stored in serialized states.
    pub fn code(self) -> u8 {
        match self {
            Standard::Fmi2 => 2,
            Standard::Fmi3 => 3,
        }
    }

    pub fn from_code(code: u8) -> Option<Standard> {
        match code {
            2 => Some(Standard::Fmi2),
            3 => Some(Standard::Fmi3),
            _ => None,
        }
    }
}

/// The version-neutral part of an instance.
pub struct Instance<M: Model> {
    pub model: M,
    pub time: f64,
    /// Stop time of the experiment, if the host defined one.
    pub stop_time: Option<f64>,
    pub last_successful_time: f64,
    /// Set when a step was discarded because the model cannot go on at all.
    pub terminated_by_model: bool,
}

/// A copy of everything that setting an FMU state restores.
#[derive(Clone)]
pub struct Snapshot<M: Model> {
    pub model: M,
    pub time: f64,
    pub stop_time: Option<f64>,
    pub last_successful_time: f64,
    pub terminated_by_model: bool,
    /// The front-end that took (or serialized) the state.
    pub standard: Standard,
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

/// The variable with value reference `vr`.
pub fn variable<M: Model>(vr: u32) -> Result<&'static Variable<M>, String> {
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
    /// The model with its start values, at the default experiment's start time.
    pub fn new() -> Result<Self, String> {
        let mut model = model_with_start_values::<M>()?;
        let time = M::info().default_experiment.start_time;
        model.set_time(time);
        Ok(Instance {
            model,
            time,
            stop_time: None,
            last_successful_time: time,
            terminated_by_model: false,
        })
    }

    pub fn set_time(&mut self, time: f64) {
        self.time = time;
        self.model.set_time(time);
    }

    pub fn snapshot(&self, standard: Standard) -> Snapshot<M> {
        Snapshot {
            model: self.model.clone(),
            time: self.time,
            stop_time: self.stop_time,
            last_successful_time: self.last_successful_time,
            terminated_by_model: self.terminated_by_model,
            standard,
        }
    }

    pub fn restore(&mut self, s: &Snapshot<M>) {
        self.model = s.model.clone();
        self.time = s.time;
        self.stop_time = s.stop_time;
        self.last_successful_time = s.last_successful_time;
        self.terminated_by_model = s.terminated_by_model;
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

    /// Writes a Real through its writer after the type, finiteness and range checks
    /// (whether the variable may be set now is the front-end's rule).
    pub fn set_real(&mut self, vr: u32, value: f64) -> Result<(), String> {
        let v = variable::<M>(vr)?;
        let Kind::Real { set, min, max, .. } = &v.kind else {
            return Err(wrong_type(v, "Real"));
        };
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
        let set = set
            .as_ref()
            .ok_or_else(|| format!("\"{}\" has no writer", v.name))?;
        set(&mut self.model, value).map_err(|e| format!("\"{}\" = {value}: {e}", v.name))
    }
}
