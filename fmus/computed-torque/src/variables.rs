//! The variable table of the ComputedTorque FMU: gains and limits per axis (tunable),
//! the controller's model (fixed, the plant FMU's names), the inputs, the output and
//! the error integral (state).

use super::{AXES, ComputedTorqueFmu};
use nalgebra::Vector3;
use robofmu::computed_torque::{MODEL_PARAMETERS, ModelParameter};
use robofmu::pss3::dynamics::PlantParams;
use robofmu::pss3::start_pose;
use robofmu_fmi::core::arrays::ElementType;
use robofmu_fmi::prelude::*;

/// Value references: group (below) plus axis 1..3; the model parameters from MODEL on.
const KP: u32 = 0;
const KD: u32 = 10;
const KI: u32 = 20;
const LIMITED: u32 = 30;
const U_MIN: u32 = 40;
const U_MAX: u32 = 50;
const INPUTS: u32 = 100;
const U: u32 = 200;
const INTEGRAL: u32 = 300;
const DER_INTEGRAL: u32 = 310;
const MODEL: u32 = 1000;

/// Read and write access to element k of a per-axis field.
type Field<T> = (
    fn(&ComputedTorqueFmu, usize) -> T,
    fn(&mut ComputedTorqueFmu, usize) -> &mut T,
);

/// `field!(m, k => m.gains[k].kp)`: the `Field` of that place.
macro_rules! field {
    ($m:ident, $k:ident => $($place:tt)+) => {
        (
            |$m: &ComputedTorqueFmu, $k: usize| $($place)+,
            |$m: &mut ComputedTorqueFmu, $k: usize| &mut $($place)+,
        )
    };
}

/// The array `base[1..3]` read and written through `field`; writing rebuilds the law
/// before its next use.
fn axes<T: ElementType>(
    group: u32,
    base: &'static str,
    description: &'static str,
    (read, write): Field<T>,
) -> Array<ComputedTorqueFmu, T, impl Role<ComputedTorqueFmu>> {
    Array::new(group + 1, base, AXES, description, read)
        .label("Axis")
        .set(move |m, k, v| {
            *write(m, k) = v;
            m.changed();
            Ok(())
        })
}

fn tunable(v: Variable<ComputedTorqueFmu>) -> Variable<ComputedTorqueFmu> {
    v.parameter(Variability::Tunable)
}

/// Gains and output limits.
fn gains(defaults: &ComputedTorqueFmu) -> Vec<Variable<ComputedTorqueFmu>> {
    type Parameter = (
        u32,
        &'static str,
        &'static str,
        Option<&'static str>,
        Field<f64>,
        [f64; AXES],
    );
    let real: [Parameter; 5] = [
        (
            KP,
            "Kp",
            "acceleration per angle error, 1/s2",
            None,
            field!(m, k => m.gains[k].kp),
            defaults.gains.map(|g| g.kp),
        ),
        (
            KD,
            "Kd",
            "acceleration per rate error",
            Some("1/s"),
            field!(m, k => m.gains[k].kd),
            defaults.gains.map(|g| g.kd),
        ),
        (
            KI,
            "Ki",
            "acceleration per integrated error, 1/s3",
            None,
            field!(m, k => m.gains[k].ki),
            defaults.gains.map(|g| g.ki),
        ),
        (
            U_MIN,
            "uMin",
            "lower output limit (used when limitOutput)",
            Some("N.m"),
            field!(m, k => m.limits[k].0),
            defaults.limits.map(|l| l.0),
        ),
        (
            U_MAX,
            "uMax",
            "upper output limit (used when limitOutput)",
            Some("N.m"),
            field!(m, k => m.limits[k].1),
            defaults.limits.map(|l| l.1),
        ),
    ];
    let mut table = Vec::new();
    for (group, name, description, unit, field, start) in real {
        let array = axes(group, name, description, field).each(move |v, k| {
            let v = tunable(v).start_real(start[k]);
            if let Some(unit) = unit {
                v.unit(unit, None)
            } else {
                v
            }
        });
        table.extend(array.variables());
    }
    let limited = axes(
        LIMITED,
        "limitOutput",
        "clamp the output to [uMin, uMax]",
        field!(m, k => m.limited[k]),
    )
    .each(|v, _| tunable(v).start_boolean(false));
    table.extend(limited.variables());
    table
}

/// The controller's model: scalars, and the arrays `name[1..3]` of consecutive entries.
fn model(defaults: &PlantParams) -> Vec<Variable<ComputedTorqueFmu>> {
    let mut table = Vec::new();
    let mut k = 0;
    while k < MODEL_PARAMETERS.len() {
        let p = &MODEL_PARAMETERS[k];
        let vr = MODEL + k as u32 + 1;
        if let Some(base) = p.name.strip_suffix("[1]") {
            let entries: [&'static ModelParameter; 3] =
                std::array::from_fn(|i| &MODEL_PARAMETERS[k + i]);
            let start = entries.map(|e| (e.get)(defaults));
            let base: &'static str = base;
            let description = p.description.trim_end_matches(", x");
            let array =
                RealArray::new(vr, base, 3, description, move |m: &ComputedTorqueFmu, i| {
                    (entries[i].get)(&m.model)
                })
                .set(move |m, i, v| {
                    (entries[i].set)(&mut m.model, v);
                    m.changed();
                    Ok(())
                })
                .each(move |v, i| fixed(v, entries[i], start[i]));
            table.extend(array.variables());
            k += 3;
            continue;
        }
        let (get, set) = (p.get, p.set);
        let v = Variable::real(vr, p.name, p.description, move |m: &ComputedTorqueFmu| {
            get(&m.model)
        })
        .set_real(move |m, v| {
            set(&mut m.model, v);
            m.changed();
            Ok(())
        });
        table.push(fixed(v, p, (p.get)(defaults)));
        k += 1;
    }
    table
}

fn fixed(
    v: Variable<ComputedTorqueFmu>,
    p: &ModelParameter,
    start: f64,
) -> Variable<ComputedTorqueFmu> {
    let v = v.parameter(Variability::Fixed).start_real(start);
    match p.unit {
        Some(unit) => v.unit(unit, p.display_unit),
        None => v,
    }
}

/// The inputs: measured at rest in the start pose (path 1's start), planned at rest
/// 0.5, -0.5 and 1 deg away, so that the default run's output moves (the error's
/// integral grows).
fn inputs() -> Vec<Variable<ComputedTorqueFmu>> {
    let pose = start_pose();
    let planned = pose + Vector3::new(0.5, -0.5, 1.0).map(f64::to_radians);
    /// Name, description, unit, display unit, field, start value.
    type Input = (
        &'static str,
        &'static str,
        &'static str,
        Option<&'static str>,
        Field<f64>,
        Vector3<f64>,
    );
    let list: [Input; 5] = [
        (
            "setpoint",
            "planned Euler angle q",
            "rad",
            Some("deg"),
            field!(m, k => m.inputs.setpoint[k]),
            planned,
        ),
        (
            "setpointRate",
            "planned Euler-angle rate qdot",
            "rad/s",
            Some("deg/s"),
            field!(m, k => m.inputs.setpoint_rate[k]),
            Vector3::zeros(),
        ),
        (
            "setpointAcceleration",
            "planned Euler-angle acceleration qddot",
            "rad/s2",
            Some("deg/s2"),
            field!(m, k => m.inputs.setpoint_acceleration[k]),
            Vector3::zeros(),
        ),
        (
            "measurement",
            "measured Euler angle theta",
            "rad",
            Some("deg"),
            field!(m, k => m.inputs.measurement[k]),
            pose,
        ),
        (
            "measuredRate",
            "measured Euler-angle rate thetaDot",
            "rad/s",
            Some("deg/s"),
            field!(m, k => m.inputs.measured_rate[k]),
            Vector3::zeros(),
        ),
    ];
    let mut table = Vec::new();
    for (n, (name, description, unit, display, (read, write), start)) in
        list.into_iter().enumerate()
    {
        let array = RealArray::new(INPUTS + 10 * n as u32 + 1, name, AXES, description, read)
            .label("Axis")
            .set(move |m, k, v| {
                *write(m, k) = v;
                Ok(())
            })
            .each(move |v, k| v.input().unit(unit, display).start_real(start[k]));
        table.extend(array.variables());
    }
    table
}

/// The whole table.
pub fn table() -> Vec<Variable<ComputedTorqueFmu>> {
    let defaults = <ComputedTorqueFmu as Model>::new();
    let mut table = gains(&defaults);
    table.extend(model(&defaults.model));
    table.extend(inputs());
    let u = RealArray::new(
        U + 1,
        "u",
        AXES,
        "Euler-angle generalized force (plant generalizedForceCommand)",
        |m: &ComputedTorqueFmu, k| m.u(k),
    )
    .label("Axis")
    .each(|v, _| v.output().unit("N.m", None));
    table.extend(u.variables());
    let integral = axes(
        INTEGRAL,
        "integral",
        "integral of the angle error (state)",
        field!(m, k => m.integral[k]),
    )
    .each(|v, _| v.state().start_real(0.0));
    table.extend(integral.variables());
    let derivative = RealArray::derivatives(
        DER_INTEGRAL + 1,
        "integral",
        AXES,
        "Time derivative of the error integral",
        |m: &ComputedTorqueFmu, k| m.integral_rate(k),
    );
    table.extend(derivative.variables());
    table
}
