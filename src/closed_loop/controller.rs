//! The loop's controller: the PID of the thesis or the computed-torque law, and the
//! scenario fields that choose and parameterise it.
//!
//! A scenario chooses with the top-level `controller = "pid" | "computed-torque"`
//! (default "pid"). The computed-torque controller is the FMU `ComputedTorque.fmu`
//! with inputs `setpoint`, `setpointRate`, `setpointAcceleration` (from the planner's
//! q, qdot, qddot), `measurement`, `measuredRate` (the plant's theta, thetaDot) and
//! output `u` (to the plant's generalizedForceCommand); its parameters are the gains
//! `Kp[i]`, `Kd[i]`, `Ki[i]`, the limits `limitOutput[i]`, `uMin[i]`, `uMax[i]`, and
//! its model of the robot under the plant FMU's parameter names (unset ones keep the
//! spec's values): the model-mismatch study sets these apart from the plant's.

use super::error::LoopError;
use super::form::FORM;
use super::scenario::{bad, number, output_limits, required};
use crate::computed_torque::{
    AxisGains, ComputedTorque, MODEL_PARAMETERS, controller_message, model_parameter,
};
use crate::control::pid::PidGains;
use crate::pss3::dynamics::PlantParams;
use toml::Table;

/// The controller of a loop.
#[derive(Debug, Clone, PartialEq)]
pub enum Controller {
    /// Three PID channels with the plant's gravity compensation as feedforward.
    Pid([PidGains; 3]),
    /// The computed-torque law on its own model of the robot (boxed: the model is
    /// larger than the PID gains).
    ComputedTorque(Box<ComputedTorque>),
}

/// The value of a scenario's `controller` field.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ControllerKind {
    Pid,
    ComputedTorque,
}

impl ControllerKind {
    /// Reads the top-level `controller` field (absent: the PID).
    pub fn of(doc: &Table) -> Result<Self, LoopError> {
        match doc.get("controller").map(|v| v.as_str()) {
            None | Some(Some("pid")) => Ok(Self::Pid),
            Some(Some("computed-torque")) => Ok(Self::ComputedTorque),
            Some(other) => Err(bad(format!(
                "'controller' must be \"pid\" or \"computed-torque\", got {}",
                other.unwrap_or("a non-string")
            ))),
        }
    }

    /// The file stem of the controller's FMU (robofmu/closed_loop.toml).
    pub fn fmu_stem(self) -> &'static str {
        &FORM.controller(self).fmu
    }

    /// The connections (source role, output, target role, input) that feed the
    /// controller and the plant (robofmu/closed_loop.toml).
    pub fn connections(self) -> &'static [(Role, String, Role, String)] {
        &FORM.controller(self).connections
    }
}

/// The three FMUs of a loop.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    Plan,
    Control,
    Robot,
}

/// The controller's model: the spec's robot with the model parameters (the plant
/// FMU's names, `computed_torque::MODEL_PARAMETERS`) the table sets.
fn model(p: &Table, place: &str) -> Result<PlantParams, LoopError> {
    let mut params = PlantParams::default();
    for parameter in &MODEL_PARAMETERS {
        if let Some(v) = number(p, parameter.name, place)? {
            (parameter.set)(&mut params, v);
        }
    }
    Ok(params)
}

fn is_known(key: &str) -> bool {
    let per_axis = ["Kp", "Kd", "Ki", "limitOutput", "uMin", "uMax"];
    let axis_key = |name: &str| (1..=3).any(|i| key == format!("{name}[{i}]"));
    per_axis.iter().any(|n| axis_key(n)) || model_parameter(key).is_some()
}

/// Reads the computed-torque controller's parameter table.
pub fn computed_torque(p: &Table, place: &str) -> Result<ComputedTorque, LoopError> {
    if let Some(key) = p.keys().find(|k| !is_known(k)) {
        return Err(bad(format!(
            "'{place}{key}' is not a computed-torque parameter (gains Kp, Kd, Ki, limits \
             limitOutput, uMin, uMax per axis, or a plant model parameter)"
        )));
    }
    let mut gains = Vec::with_capacity(3);
    for i in 1..=3 {
        let key = |name: &str| format!("{name}[{i}]");
        gains.push(AxisGains {
            kp: required(p, &key("Kp"), place)?,
            kd: required(p, &key("Kd"), place)?,
            ki: number(p, &key("Ki"), place)?.unwrap_or(0.0),
            limits: output_limits(p, i, place)?,
        });
    }
    let gains = [gains[0], gains[1], gains[2]];
    ComputedTorque::new(model(p, place)?, gains)
        .map_err(|e| bad(format!("'{place}': {}", controller_message(&e))))
}
