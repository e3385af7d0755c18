//! Hand-written closed-loop scenarios (a `[motion]` table): waypoints in degrees with
//! base-frame angular velocities and accelerations, gains by the triple-pole rule or
//! explicit, every quantity with its unit (`"5 deg"`, `"-5, 3, 132 deg"`). The Python
//! harness (cosim/closed_loop.py) reads the same files with the same rules; this reader
//! resolves them into the loop the reference simulates, on the default plant. Several
//! waypoints make a multi-segment motion, one polynomial per segment.

use super::error::LoopError;
use super::gains::design_gains;
use super::scenario::LoopSpec;
use crate::control::pid::PidGains;
use crate::control::trajectory::{Boundary, Order, Polynomial};
use crate::pss3::dynamics::{DynamicsError, Plant, PlantParams};
use crate::pss3::rotation::{euler_accelerations, euler_rates};
use nalgebra::Vector3;
use toml::{Table, Value};

fn bad(message: String) -> LoopError {
    LoopError::Scenario(message)
}

/// (SI factor, dimension) of the units of the hand-written form.
fn unit(name: &str) -> Option<(f64, &'static str)> {
    let deg = std::f64::consts::PI / 180.0;
    Some(match name {
        "s" => (1.0, "time"),
        "ms" => (1e-3, "time"),
        "rad" => (1.0, "angle"),
        "deg" => (deg, "angle"),
        "rad/s" => (1.0, "angular velocity"),
        "deg/s" => (deg, "angular velocity"),
        "rad/s^2" => (1.0, "angular acceleration"),
        "deg/s^2" => (deg, "angular acceleration"),
        "N m/rad" => (1.0, "stiffness gain"),
        "N m/deg" => (1.0 / deg, "stiffness gain"),
        "N m/(rad s)" => (1.0, "integral gain"),
        "N m s/rad" => (1.0, "damping gain"),
        _ => return None,
    })
}

const UNITS: [&str; 12] = [
    "N m/(rad s)",
    "N m s/rad",
    "N m/rad",
    "N m/deg",
    "rad/s^2",
    "deg/s^2",
    "rad/s",
    "deg/s",
    "rad",
    "deg",
    "ms",
    "s",
];

/// SI values of the quantity `"x[, y, ...] unit"` at `field`, of dimension `dimension`.
fn quantities(value: Option<&Value>, dimension: &str, field: &str) -> Result<Vec<f64>, LoopError> {
    let text = value
        .ok_or_else(|| bad(format!("missing '{field}'")))?
        .as_str()
        .ok_or_else(|| bad(format!("'{field}' must be a string \"value unit\"")))?
        .trim();
    let name = UNITS
        .iter()
        .find(|u| {
            text.strip_suffix(*u)
                .is_some_and(|rest| rest.ends_with(' '))
        })
        .ok_or_else(|| bad(format!("'{field}': no known unit at the end of {text:?}")))?;
    let (factor, found) = unit(name).ok_or_else(|| bad(format!("'{field}': unit {name}")))?;
    if found != dimension {
        return Err(bad(format!(
            "'{field}' must be a {dimension}, got unit '{name}' ({found})"
        )));
    }
    text[..text.len() - name.len()]
        .split(',')
        .map(|x| match x.trim().parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v * factor),
            _ => Err(bad(format!("'{field}': cannot read numbers in {text:?}"))),
        })
        .collect()
}

fn scalar(value: Option<&Value>, dimension: &str, field: &str) -> Result<f64, LoopError> {
    match quantities(value, dimension, field)?.as_slice() {
        [v] => Ok(*v),
        _ => Err(bad(format!("'{field}' must be one value"))),
    }
}

fn triple(value: Option<&Value>, dimension: &str, field: &str) -> Result<Vector3<f64>, LoopError> {
    match quantities(value, dimension, field)?.as_slice() {
        [x, y, z] => Ok(Vector3::new(*x, *y, *z)),
        other => Err(bad(format!(
            "'{field}' must have 3 values, got {}",
            other.len()
        ))),
    }
}

/// A waypoint: time (s), Euler angles (rad), their rates and accelerations.
struct Waypoint {
    time: f64,
    q: Vector3<f64>,
    /// Angular velocity in the base frame, rad/s.
    omega: Vector3<f64>,
    qdot: Vector3<f64>,
    qddot: Vector3<f64>,
}

fn waypoint(p: &Value, k: usize) -> Result<Waypoint, LoopError> {
    let place = format!("motion.waypoints[{k}].");
    let get = |key: &str| p.get(key);
    let zero = Value::String("0, 0, 0 rad/s".into());
    let zero_acc = Value::String("0, 0, 0 rad/s^2".into());
    let q = triple(get("angles"), "angle", &format!("{place}angles"))?;
    let omega = triple(
        get("omega").or(Some(&zero)),
        "angular velocity",
        &format!("{place}omega"),
    )?;
    let omega_dot = triple(
        get("omega_dot").or(Some(&zero_acc)),
        "angular acceleration",
        &format!("{place}omega_dot"),
    )?;
    let singular = |e| LoopError::Dynamics(DynamicsError::from(e));
    let qdot = euler_rates(&q, &omega).map_err(singular)?;
    let qddot = euler_accelerations(&q, &qdot, &omega_dot).map_err(singular)?;
    let time = scalar(get("time"), "time", &format!("{place}time"))?;
    Ok(Waypoint {
        time,
        q,
        omega,
        qdot,
        qddot,
    })
}

fn table<'a>(doc: &'a Table, key: &str) -> Result<Option<&'a Table>, LoopError> {
    match doc.get(key) {
        None => Ok(None),
        Some(Value::Table(t)) => Ok(Some(t)),
        Some(_) => Err(bad(format!("'{key}' must be a table"))),
    }
}

fn motion(doc: &Table) -> Result<(Order, Vec<Waypoint>), LoopError> {
    let motion = table(doc, "motion")?.ok_or_else(|| bad("missing 'motion'".into()))?;
    let order = match motion.get("profile").and_then(Value::as_str) {
        Some("cubic") => Order::Cubic,
        Some("quintic") => Order::Quintic,
        _ => {
            return Err(bad(
                "'motion.profile' must be \"cubic\" or \"quintic\"".into()
            ));
        }
    };
    let points = motion.get("waypoints").and_then(Value::as_array);
    match points {
        Some(list) if list.len() >= 2 => Ok((
            order,
            list.iter()
                .enumerate()
                .map(|(k, p)| waypoint(p, k))
                .collect::<Result<_, _>>()?,
        )),
        _ => Err(bad(
            "'motion.waypoints' must list at least two waypoints".into()
        )),
    }
}

/// The polynomials of the segment from `a` to `b`.
fn segment(order: Order, a: &Waypoint, b: &Waypoint) -> Result<[Polynomial; 3], LoopError> {
    let boundary = |i: usize| Boundary {
        q0: a.q[i],
        qf: b.q[i],
        qdot0: a.qdot[i],
        qdotf: b.qdot[i],
        qddot0: a.qddot[i],
        qddotf: b.qddot[i],
    };
    let axis = |i| Polynomial::new(order, a.time, b.time, &boundary(i));
    Ok([axis(0)?, axis(1)?, axis(2)?])
}

/// The design poses of the Python harness: the start, and 0, 1/4, ..., 1 of every
/// segment.
fn default_poses(start: &Vector3<f64>, points: &[Waypoint]) -> Vec<Vector3<f64>> {
    let mut poses = vec![*start];
    for pair in points.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        poses.extend([0.0, 0.25, 0.5, 0.75, 1.0].map(|s| a.q + (b.q - a.q) * s));
    }
    poses
}

fn gains(doc: &Table, poses: Vec<Vector3<f64>>) -> Result<[PidGains; 3], LoopError> {
    let g = table(doc, "gains")?.ok_or_else(|| bad("missing 'gains'".into()))?;
    if g.contains_key("omega") {
        let bandwidth = scalar(g.get("omega"), "angular velocity", "gains.omega")?;
        let poses = match g.get("design_poses").and_then(Value::as_array) {
            Some(list) => list
                .iter()
                .enumerate()
                .map(|(k, p)| triple(Some(p), "angle", &format!("gains.design_poses[{k}]")))
                .collect::<Result<Vec<_>, _>>()?,
            None => poses,
        };
        let plant = Plant::new(PlantParams::default())?;
        return Ok(design_gains(&plant, &poses, bandwidth)?.gains);
    }
    let kp = triple(g.get("Kp"), "stiffness gain", "gains.Kp")?;
    let ki = triple(g.get("Ki"), "integral gain", "gains.Ki")?;
    let kd = triple(g.get("Kd"), "damping gain", "gains.Kd")?;
    let gains = [0, 1, 2].map(|i| PidGains {
        kp: kp[i],
        ki: ki[i],
        kd: kd[i],
        tf: 0.0,
        limits: None,
        use_rate_inputs: true,
    });
    for g in &gains {
        g.validate()?;
    }
    Ok(gains)
}

/// The top-level fields of the hand-written form (as cosim/closed_loop.py reads it).
const KNOWN: [&str; 13] = [
    "name",
    "description",
    "start_time",
    "stop_time",
    "step_size",
    "fmus",
    "motion",
    "start",
    "gains",
    "plant",
    "record",
    "coupling",
    "max_step_halvings",
];

/// The loop of a hand-written scenario (`aliases` from the FMU file names).
pub fn parse_human_scenario(
    doc: &Table,
    name: String,
    aliases: [String; 3],
) -> Result<LoopSpec, LoopError> {
    if let Some(key) = doc.keys().find(|k| !KNOWN.contains(&k.as_str())) {
        return Err(bad(format!("unknown field '{key}'")));
    }
    if let Some(key) = table(doc, "plant")?.and_then(|p| p.keys().next()) {
        return Err(bad(format!(
            "plant parameter 'plant.{key}' is not modelled by the reference (it uses the \
             default plant)"
        )));
    }
    let (order, points) = motion(doc)?;
    let first = &points[0];
    let start = table(doc, "start")?;
    let theta0 = match start.and_then(|s| s.get("angles")) {
        Some(v) => triple(Some(v), "angle", "start.angles")?,
        None => first.q,
    };
    let omega0 = match start.and_then(|s| s.get("omega")) {
        Some(v) => triple(Some(v), "angular velocity", "start.omega")?,
        None => first.omega,
    };
    let mut segments = points
        .windows(2)
        .map(|pair| Ok((pair[0].time, segment(order, &pair[0], &pair[1])?)))
        .collect::<Result<Vec<_>, LoopError>>()?;
    let (_, trajectories) = segments.remove(0);
    let start_time = match doc.get("start_time") {
        Some(v) => scalar(Some(v), "time", "start_time")?,
        None => 0.0,
    };
    let step_size = match doc.get("step_size") {
        Some(v) => scalar(Some(v), "time", "step_size")?,
        None => 1e-3,
    };
    Ok(LoopSpec {
        name,
        aliases,
        start_time,
        stop_time: scalar(doc.get("stop_time"), "time", "stop_time")?,
        step_size,
        trajectories,
        later_segments: segments,
        gains: gains(doc, default_poses(&theta0, &points))?,
        plant: PlantParams::default(),
        theta0,
        omega0,
    })
}
