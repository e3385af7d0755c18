//! Reads a co-simulation scenario in its plain (expanded, SI) form, the TOML file that
//! `cosim run` runs, into the loop it describes. Only the planner -> controller ->
//! plant topology of this module (controller: the PID or the computed-torque law, see
//! `controller`) is accepted; any other connection or an unmodelled plant
//! parameter is refused by name, so the reference can never silently describe a
//! different loop than the FMUs run: the topology (each controller's FMU and
//! connections) is read from robofmu/closed_loop.toml, the file the Python harness
//! builds its scenarios from (`form`). The scenario rules of the hand-written form
//! (units, base-frame rates, gain design, workspace) live in one place, the Python
//! harness: `cosim check SCENARIO --expanded FILE.toml` writes the form read here, with
//! the `[[plan_switches]]` of a multi-segment motion.

use super::controller::{self, Controller, ControllerKind, Role};
use super::error::LoopError;
use crate::control::pid::PidGains;
use crate::control::trajectory::{Boundary, Order, Polynomial};
use crate::pss3::dynamics::PlantParams;
use nalgebra::Vector3;
use std::collections::BTreeSet;
use toml::{Table, Value};

/// The closed loop of one scenario.
#[derive(Debug, Clone)]
pub struct LoopSpec {
    pub name: String,
    /// Scenario aliases of the planner, controller (PID or computed torque) and plant
    /// FMUs.
    pub aliases: [String; 3],
    pub start_time: f64,
    pub stop_time: f64,
    /// Communication step of the co-simulation, s: the reference samples at it.
    pub step_size: f64,
    /// Planned motion of each Euler angle (the first segment of a multi-segment one).
    pub trajectories: [Polynomial; 3],
    /// Further segments of a multi-segment motion, each with its start time (s), in
    /// order; each takes over from its start time on.
    pub later_segments: Vec<(f64, [Polynomial; 3])>,
    pub controller: Controller,
    pub plant: PlantParams,
    /// Initial Euler angles, rad.
    pub theta0: Vector3<f64>,
    /// Initial angular velocity in the base frame, rad/s.
    pub omega0: Vector3<f64>,
}

impl LoopSpec {
    /// The planner polynomials in force at time `t` (s).
    pub fn trajectories_at(&self, t: f64) -> &[Polynomial; 3] {
        self.later_segments
            .iter()
            .rev()
            .find(|(start, _)| *start <= t)
            .map_or(&self.trajectories, |(_, segment)| segment)
    }
}

/// The FMU roles, recognised by the FMU file names of the scenario (the controller's
/// by its kind).
const PLANNER: &str = "Planner";
const PLANT: &str = "Pss3Plant";

pub(super) fn bad(message: String) -> LoopError {
    LoopError::Scenario(message)
}

pub(super) fn number(table: &Table, key: &str, place: &str) -> Result<Option<f64>, LoopError> {
    match table.get(key) {
        None => Ok(None),
        Some(Value::Float(v)) if v.is_finite() => Ok(Some(*v)),
        Some(Value::Integer(v)) => Ok(Some(*v as f64)),
        Some(other) => Err(bad(format!(
            "'{place}{key}' must be a finite number, got {other}"
        ))),
    }
}

pub(super) fn required(table: &Table, key: &str, place: &str) -> Result<f64, LoopError> {
    number(table, key, place)?.ok_or_else(|| bad(format!("missing '{place}{key}'")))
}

pub(super) fn boolean(table: &Table, key: &str, place: &str) -> Result<bool, LoopError> {
    match table.get(key) {
        None => Ok(false),
        Some(Value::Boolean(b)) => Ok(*b),
        Some(other) => Err(bad(format!(
            "'{place}{key}' must be true or false, got {other}"
        ))),
    }
}

/// The aliases of the planner, controller and plant, from the FMU file names.
fn roles(fmus: &Table, kind: ControllerKind) -> Result<[String; 3], LoopError> {
    let find = |stem: &str| {
        let matching: Vec<&String> = fmus
            .iter()
            .filter(|(_, path)| {
                path.as_str()
                    .and_then(|p| std::path::Path::new(p).file_stem())
                    .is_some_and(|s| s == stem)
            })
            .map(|(alias, _)| alias)
            .collect();
        match matching.as_slice() {
            [alias] => Ok((*alias).clone()),
            _ => Err(bad(format!("'fmus' must name exactly one {stem}.fmu"))),
        }
    };
    if fmus.len() != 3 {
        return Err(bad(
            "'fmus' must name exactly the planner, controller and plant FMUs".into(),
        ));
    }
    Ok([find(PLANNER)?, find(kind.fmu_stem())?, find(PLANT)?])
}

/// The connections of the loop of controller `kind` between the FMUs `aliases`
/// (planner, controller, plant).
fn expected_connections(kind: ControllerKind, aliases: &[String; 3]) -> BTreeSet<(String, String)> {
    let alias = |role: Role| match role {
        Role::Plan => &aliases[0],
        Role::Control => &aliases[1],
        Role::Robot => &aliases[2],
    };
    (1..=3)
        .flat_map(|i| {
            kind.connections().iter().map(move |(a, x, b, y)| {
                (
                    format!("{}.{x}[{i}]", alias(*a)),
                    format!("{}.{y}[{i}]", alias(*b)),
                )
            })
        })
        .collect()
}

fn connections(doc: &Table) -> Result<BTreeSet<(String, String)>, LoopError> {
    let list = doc.get("connections").and_then(Value::as_array);
    let list = list.ok_or_else(|| bad("missing 'connections'".into()))?;
    list.iter()
        .enumerate()
        .map(|(k, c)| {
            let end = |key: &str| c.get(key).and_then(Value::as_str).map(str::to_string);
            match (end("from"), end("to")) {
                (Some(from), Some(to)) => Ok((from, to)),
                _ => Err(bad(format!(
                    "'connections[{k}]' needs string 'from' and 'to'"
                ))),
            }
        })
        .collect()
}

fn trajectories(p: &Table, place: &str) -> Result<[Polynomial; 3], LoopError> {
    let degree = required(p, "order", place)?;
    let order = Order::from_degree(degree as i32)
        .filter(|_| degree.fract() == 0.0)
        .ok_or_else(|| bad(format!("'{place}order' must be 3 or 5, got {degree}")))?;
    let (t0, tf) = (required(p, "t0", place)?, required(p, "tf", place)?);
    let mut out = Vec::with_capacity(3);
    for i in 1..=3 {
        let opt = |name: &str| number(p, &format!("{name}[{i}]"), place);
        let b = Boundary {
            q0: required(p, &format!("q0[{i}]"), place)?,
            qf: required(p, &format!("qf[{i}]"), place)?,
            qdot0: opt("qdot0")?.unwrap_or(0.0),
            qdotf: opt("qdotf")?.unwrap_or(0.0),
            qddot0: opt("qddot0")?.unwrap_or(0.0),
            qddotf: opt("qddotf")?.unwrap_or(0.0),
        };
        out.push(Polynomial::new(order, t0, tf, &b)?);
    }
    out.try_into()
        .map_err(|_| bad("three planner axes expected".into()))
}

/// The output limits (uMin[i], uMax[i]) of a controller's axis `i` (1-based) when its
/// `limitOutput[i]` is true, else None (the PID and the computed-torque law alike).
pub(super) fn output_limits(
    p: &Table,
    i: usize,
    place: &str,
) -> Result<Option<(f64, f64)>, LoopError> {
    if !boolean(p, &format!("limitOutput[{i}]"), place)? {
        return Ok(None);
    }
    Ok(Some((
        required(p, &format!("uMin[{i}]"), place)?,
        required(p, &format!("uMax[{i}]"), place)?,
    )))
}

fn gains(p: &Table, place: &str) -> Result<[PidGains; 3], LoopError> {
    let mut out = Vec::with_capacity(3);
    for i in 1..=3 {
        let key = |name: &str| format!("{name}[{i}]");
        let g = PidGains {
            kp: required(p, &key("Kp"), place)?,
            ki: required(p, &key("Ki"), place)?,
            kd: required(p, &key("Kd"), place)?,
            tf: required(p, &key("Tf"), place)?,
            limits: output_limits(p, i, place)?,
            use_rate_inputs: boolean(p, &key("useRateInputs"), place)?,
        };
        g.validate()
            .map_err(|e| bad(format!("'{place}' axis {i}: PID {e}")))?;
        out.push(g);
    }
    Ok([out[0], out[1], out[2]])
}

fn initial(p: &Table, name: &str, place: &str) -> Result<Vector3<f64>, LoopError> {
    let mut v = Vector3::zeros();
    for i in 0..3 {
        v[i] = required(p, &format!("{name}[{}]", i + 1), place)?;
    }
    Ok(v)
}

fn parameters<'a>(doc: &'a Table, alias: &str) -> Result<&'a Table, LoopError> {
    doc.get("parameters")
        .and_then(|p| p.get(alias))
        .and_then(Value::as_table)
        .ok_or_else(|| bad(format!("missing table 'parameters.{alias}'")))
}

/// The later segments of a multi-segment motion: each `[[plan_switches]]` entry resets
/// the planner at communication step `step` with its `parameters`. As the harness
/// (`robofmu/scenario.py`), the steps must increase and lie inside the run: a switch at
/// step 0 or out of order would make [`LoopSpec::trajectories_at`] pick a segment the
/// co-simulation never runs.
fn plan_switches(
    doc: &Table,
    planner: &str,
    start_time: f64,
    step_size: f64,
    steps: f64,
) -> Result<Vec<(f64, [Polynomial; 3])>, LoopError> {
    let Some(list) = doc.get("plan_switches") else {
        return Ok(Vec::new());
    };
    let list = list
        .as_array()
        .ok_or_else(|| bad("'plan_switches' must be an array of tables".into()))?;
    let mut out = Vec::with_capacity(list.len());
    let mut after = 0;
    for (k, item) in list.iter().enumerate() {
        let place = format!("plan_switches[{k}].");
        let step = item.get("step").and_then(Value::as_integer);
        let alias = item.get("alias").and_then(Value::as_str);
        let params = item.get("parameters").and_then(Value::as_table);
        let (Some(step), Some(alias), Some(params)) = (step, alias, params) else {
            return Err(bad(format!(
                "'{place}' needs an integer 'step', an 'alias' and a 'parameters' table"
            )));
        };
        if !(step > after && (step as f64) < steps) {
            return Err(bad(format!(
                "'{place}step' is {step}: it must be after the previous switch's ({after}) \
                 and before the last step ({steps})"
            )));
        }
        after = step;
        if alias != planner {
            return Err(bad(format!(
                "'{place}alias' is '{alias}': the reference switches only the planner"
            )));
        }
        let time = start_time + step as f64 * step_size;
        out.push((time, trajectories(params, &format!("{place}parameters."))?));
    }
    Ok(out)
}

fn controller_of(kind: ControllerKind, p: &Table, alias: &str) -> Result<Controller, LoopError> {
    let place = format!("parameters.{alias}.");
    Ok(match kind {
        ControllerKind::Pid => Controller::Pid(gains(p, &place)?),
        ControllerKind::ComputedTorque => {
            Controller::ComputedTorque(Box::new(controller::computed_torque(p, &place)?))
        }
    })
}

/// Reads the loop of a scenario file's text.
pub fn parse_loop_scenario(text: &str) -> Result<LoopSpec, LoopError> {
    let doc: Table = text
        .parse()
        .map_err(|e| bad(format!("not valid TOML: {e}")))?;
    let name = doc.get("name").and_then(Value::as_str);
    let name = name
        .ok_or_else(|| bad("missing 'name'".into()))?
        .to_string();
    let fmus = doc.get("fmus").and_then(Value::as_table);
    let kind = ControllerKind::of(&doc)?;
    let fmus = fmus.ok_or_else(|| bad("missing 'fmus'".into()))?;
    let aliases = roles(fmus, kind)?;
    let [planner, control, plant] = aliases.clone();
    if doc.contains_key("motion") {
        return Err(bad(
            "a hand-written scenario (a [motion] table): the reference reads its expanded \
             form; write it with `cosim check SCENARIO --expanded FILE.toml`"
                .into(),
        ));
    }
    let found = connections(&doc)?;
    let expected = expected_connections(kind, &aliases);
    if let Some((from, to)) = found.symmetric_difference(&expected).next() {
        let what = if found.contains(&(from.clone(), to.clone())) {
            "unexpected"
        } else {
            "missing"
        };
        return Err(bad(format!(
            "{what} connection {from} -> {to}: the reference models only the \
             planner -> {} -> plant loop",
            kind.fmu_stem()
        )));
    }
    let plant_params = parameters(&doc, &plant)?;
    let modelled = [
        "theta0[1]",
        "theta0[2]",
        "theta0[3]",
        "omega0[1]",
        "omega0[2]",
        "omega0[3]",
    ];
    if let Some(key) = plant_params
        .keys()
        .find(|k| !modelled.contains(&k.as_str()))
    {
        return Err(bad(format!(
            "plant parameter '{plant}.{key}' is not modelled by the reference (it uses the \
             default plant)"
        )));
    }
    let start_time = number(&doc, "start_time", "")?.unwrap_or(0.0);
    let stop_time = required(&doc, "stop_time", "")?;
    let step_size = required(&doc, "step_size", "")?;
    if !(step_size > 0.0 && stop_time > start_time) {
        return Err(bad("need step_size > 0 and stop_time > start_time".into()));
    }
    Ok(LoopSpec {
        name,
        aliases,
        start_time,
        stop_time,
        step_size,
        trajectories: trajectories(
            parameters(&doc, &planner)?,
            &format!("parameters.{planner}."),
        )?,
        later_segments: plan_switches(
            &doc,
            &planner,
            start_time,
            step_size,
            ((stop_time - start_time) / step_size).round(),
        )?,
        controller: controller_of(kind, parameters(&doc, &control)?, &control)?,
        plant: PlantParams::default(),
        theta0: initial(plant_params, "theta0", &format!("parameters.{plant}."))?,
        omega0: initial(plant_params, "omega0", &format!("parameters.{plant}."))?,
    })
}
