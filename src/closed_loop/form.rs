//! The closed loop's one description, shared with the Python harness:
//! `robofmu/closed_loop.toml` (read by `robofmu/controllers.py` at import), compiled in
//! here. It holds each controller's FMU and connections and the gain rules, so that the
//! reference and the co-simulation cannot describe different loops or design different
//! gains.

use super::controller::{ControllerKind, Role};
use std::collections::BTreeMap;
use std::sync::LazyLock;
use toml::{Table, Value};

/// The file's text (the Python package's copy, the one source).
const TEXT: &str = include_str!("../../robofmu/closed_loop.toml");

/// One controller of the file: its FMU's file stem and the connections of each axis
/// (source role, output, target role, input).
#[derive(Debug)]
pub(super) struct ControllerForm {
    pub fmu: String,
    pub connections: Vec<(Role, String, Role, String)>,
}

/// A gain rule: (factor, power) of Kp, Ki and Kd, each gain factor * m * w * ... * w.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GainRule {
    terms: [(f64, u32); 3],
}

impl GainRule {
    /// (Kp, Ki, Kd) for inertia `m` and bandwidth `w`, evaluated in the file's order.
    pub fn gains(&self, m: f64, w: f64) -> (f64, f64, f64) {
        let [kp, ki, kd] = self.terms.map(|(factor, power)| {
            let mut gain = factor * m;
            for _ in 0..power {
                gain *= w;
            }
            gain
        });
        (kp, ki, kd)
    }
}

#[derive(Debug)]
pub(super) struct Form {
    pub pid: ControllerForm,
    pub computed_torque: ControllerForm,
    pub rules: BTreeMap<String, GainRule>,
    pid_rule: GainRule,
}

impl Form {
    pub fn controller(&self, kind: ControllerKind) -> &ControllerForm {
        match kind {
            ControllerKind::Pid => &self.pid,
            ControllerKind::ComputedTorque => &self.computed_torque,
        }
    }

    /// The PID's rule ("pid"), which the gain design uses.
    pub fn pid_rule(&self) -> GainRule {
        self.pid_rule
    }
}

/// The file, read once. It is part of the source tree (a test reads it), so a
/// malformed one is a build defect, not a user's input.
pub(super) static FORM: LazyLock<Form> = LazyLock::new(|| match parse(TEXT) {
    Ok(form) => form,
    Err(e) => panic!("robofmu/closed_loop.toml: {e}"),
});

/// The gain rule `name` of the file ("pid", "computed-torque", ...).
pub fn gain_rule(name: &str) -> Option<GainRule> {
    FORM.rules.get(name).copied()
}

fn role(name: &str) -> Result<Role, String> {
    match name {
        "planner" => Ok(Role::Plan),
        "controller" => Ok(Role::Control),
        "plant" => Ok(Role::Robot),
        other => Err(format!("unknown role '{other}'")),
    }
}

fn text(value: Option<&Value>, what: &str) -> Result<String, String> {
    value
        .and_then(Value::as_str)
        .map(str::to_string)
        .ok_or_else(|| format!("{what} must be a string"))
}

fn controller(doc: &Table, kind: &str) -> Result<ControllerForm, String> {
    let entry = doc
        .get("controllers")
        .and_then(|c| c.get(kind))
        .ok_or_else(|| format!("no controllers.{kind}"))?;
    let list = entry
        .get("connections")
        .and_then(Value::as_array)
        .ok_or_else(|| format!("controllers.{kind}.connections must be an array"))?;
    let connections = list
        .iter()
        .map(|c| {
            let items: Vec<String> = c
                .as_array()
                .map(|a| {
                    a.iter()
                        .filter_map(Value::as_str)
                        .map(str::to_string)
                        .collect()
                })
                .unwrap_or_default();
            match items.as_slice() {
                [a, x, b, y] => Ok((role(a)?, x.clone(), role(b)?, y.clone())),
                _ => Err(format!("controllers.{kind}.connections: four strings each")),
            }
        })
        .collect::<Result<_, String>>()?;
    Ok(ControllerForm {
        fmu: text(entry.get("fmu"), &format!("controllers.{kind}.fmu"))?,
        connections,
    })
}

fn rule(value: &Value, name: &str) -> Result<GainRule, String> {
    let term = |gain: &str| {
        let t = value.get(gain);
        let factor = t.and_then(|t| t.get("factor")).and_then(Value::as_float);
        let power = t.and_then(|t| t.get("power")).and_then(Value::as_integer);
        match (factor, power.map(u32::try_from)) {
            (Some(factor), Some(Ok(power))) => Ok((factor, power)),
            _ => Err(format!(
                "rules.{name}.{gain} needs a float factor and a power >= 0"
            )),
        }
    };
    Ok(GainRule {
        terms: [term("Kp")?, term("Ki")?, term("Kd")?],
    })
}

fn parse(text: &str) -> Result<Form, String> {
    let doc: Table = text.parse().map_err(|e| format!("not valid TOML: {e}"))?;
    let rules = doc
        .get("rules")
        .and_then(Value::as_table)
        .ok_or("no [rules]")?
        .iter()
        .map(|(name, value)| Ok((name.clone(), rule(value, name)?)))
        .collect::<Result<BTreeMap<_, _>, String>>()?;
    let pid_rule = *rules.get("pid").ok_or("no rules.pid")?;
    Ok(Form {
        pid: controller(&doc, "pid")?,
        computed_torque: controller(&doc, "computed-torque")?,
        rules,
        pid_rule,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::computed_torque::pole_placement;

    #[test]
    fn the_shared_file_reads() {
        let form = parse(TEXT).unwrap();
        assert_eq!(form.pid.fmu, "PID");
        assert_eq!(form.computed_torque.fmu, "ComputedTorque");
        assert_eq!(form.pid.connections.len(), 6);
        assert!(form.rules.contains_key("pid"));
    }

    #[test]
    fn the_computed_torque_rules_are_the_laws_pole_placement() {
        // crates/fmu/dynamics keeps its own const pole_placement (no TOML reader in the
        // FMUs' crate): it must agree bit for bit with the file's rules, which the
        // Python harness designs with.
        for w in [1.0, 17.3, 30.0, 12.345678, 1e3] {
            for (integral, name) in [
                (true, "computed-torque"),
                (false, "computed-torque-without-integral"),
            ] {
                let (kp, ki, kd) = gain_rule(name).unwrap().gains(1.0, w);
                let law = pole_placement(w, integral).unwrap();
                assert_eq!((law.kp, law.ki, law.kd), (kp, ki, kd), "w = {w}, {name}");
            }
        }
    }
}
