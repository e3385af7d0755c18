//! Binding of the trajectory planner (`robofmu_control::trajectory`) as the FMU
//! "Planner": three axes, cubic or quintic, boundary conditions as parameters,
//! q / qdot / qddot per axis as outputs. Axis positions are angles (rad, shown in deg);
//! the planner itself is unit-agnostic.

use robofmu_control::trajectory::{Boundary, Order, Polynomial};
use robofmu_fmi::prelude::*;

pub const AXES: usize = 3;

static INFO: ModelInfo = ModelInfo {
    model_name: "Planner",
    model_identifier: "Planner",
    guid: "{5d0c3a52-8f0e-4d6b-9a51-3c2b7e41a901}",
    description: "Cubic or quintic point-to-point trajectories of three axes from boundary \
                  conditions at t0 and tf; at rest at q0 before t0 and at qf after tf",
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        stop_time: 2.5,
        tolerance: 1e-6,
        step_size: 0.01,
    },
    number_of_continuous_states: 0,
    number_of_event_indicators: 0,
    provides_directional_derivative: false,
    max_output_derivative_order: 2,
    log_categories: &[LogCategory {
        name: "logTrajectory",
        description: "Polynomial coefficients computed at initialization",
    }],
};

/// Parameters and time of the planner; the polynomials follow from them.
#[derive(Clone)]
pub struct Planner {
    degree: i32,
    t0: f64,
    tf: f64,
    boundary: [Boundary; AXES],
    time: f64,
    /// Polynomials of the current parameters, or why there are none.
    axes: Result<[Polynomial; AXES], String>,
}

impl Planner {
    fn rebuild(&mut self) {
        let order = Order::from_degree(self.degree);
        self.axes = match order {
            None => Err(format!("order {} is neither 3 nor 5", self.degree)),
            Some(order) => (0..AXES)
                .map(|a| Polynomial::new(order, self.t0, self.tf, &self.boundary[a]))
                .collect::<Result<Vec<_>, _>>()
                .map(|v| [v[0].clone(), v[1].clone(), v[2].clone()])
                .map_err(|e| e.to_string()),
        };
    }

    /// Every axis's coefficients and its samples at 21 equally spaced times of
    /// [t0, tf] finite: otherwise t0, tf and that axis's boundary values make the
    /// trajectory overflow (e.g. tf - t0 = 5e-324 s), named in the message.
    fn check_overflow(&self, axes: &[Polynomial; AXES]) -> Result<(), String> {
        for (a, p) in axes.iter().enumerate() {
            let times = (0..=20).map(|k| self.t0 + (self.tf - self.t0) * f64::from(k) / 20.0);
            let finite = p.shifted_coefficients().iter().all(|c| c.is_finite())
                && times
                    .map(|t| p.sample(t))
                    .all(|s| s.q.is_finite() && s.qdot.is_finite() && s.qddot.is_finite());
            if !finite {
                return Err(format!(
                    "t0 = {:e} s, tf = {:e} s and the boundary values of axis {} ({:?}) make \
                     the trajectory overflow (its coefficients or samples are not finite)",
                    self.t0,
                    self.tf,
                    a + 1,
                    self.boundary[a]
                ));
            }
        }
        Ok(())
    }

    fn sample(&self, axis: usize) -> Option<robofmu_control::trajectory::Sample> {
        self.axes.as_ref().ok().map(|p| p[axis].sample(self.time))
    }
}

/// Value references: order 1, t0 2, tf 3; boundary values 10 a + k (axis a = 1..3,
/// k = 0..5: q0, qf, qdot0, qdotf, qddot0, qddotf); outputs 100 + 10 (a - 1) + k
/// (k = 0..2: q, qdot, qddot).
fn boundary_vr(axis: usize, k: usize) -> u32 {
    AXIS_STRIDE * (axis as u32 + 1) + k as u32
}

fn output_vr(axis: usize, k: usize) -> u32 {
    100 + AXIS_STRIDE * axis as u32 + k as u32
}

/// Step of the value references from one axis to the next.
const AXIS_STRIDE: u32 = 10;

/// (axis, k) of the output value reference `output_vr(axis, k)`.
fn output_of(vr: u32) -> Option<(usize, usize)> {
    let offset = vr.checked_sub(100)?;
    let (axis, k) = (
        (offset / AXIS_STRIDE) as usize,
        (offset % AXIS_STRIDE) as usize,
    );
    (axis < AXES && k < OUTPUTS.len()).then_some((axis, k))
}

/// Name, unit, description and default per axis of the boundary values, in the order
/// of `boundary_field`.
const BOUNDARY_FIELDS: [(&str, &str, &str, [f64; AXES]); 6] = [
    ("q0", "rad", "position at t0", [0.0, 0.0, 0.0]),
    ("qf", "rad", "position at tf", [0.5, -0.3, 0.8]),
    ("qdot0", "rad/s", "velocity at t0", [0.0; AXES]),
    ("qdotf", "rad/s", "velocity at tf", [0.0; AXES]),
    (
        "qddot0",
        "rad/s2",
        "acceleration at t0 (quintic only)",
        [0.0; AXES],
    ),
    (
        "qddotf",
        "rad/s2",
        "acceleration at tf (quintic only)",
        [0.0; AXES],
    ),
];

fn boundary_field(b: &mut Boundary, k: usize) -> &mut f64 {
    match k {
        0 => &mut b.q0,
        1 => &mut b.qf,
        2 => &mut b.qdot0,
        3 => &mut b.qdotf,
        4 => &mut b.qddot0,
        _ => &mut b.qddotf,
    }
}

const OUTPUTS: [(&str, &str, &str); 3] = [
    ("q", "rad", "planned position"),
    ("qdot", "rad/s", "planned velocity"),
    ("qddot", "rad/s2", "planned acceleration"),
];

/// The array `base[1..3]` of the axes, element a at `first_vr + 10 (a - 1)` (the
/// value references step by axis), described as "Axis a: `what`".
fn axes(
    first_vr: u32,
    base: &'static str,
    what: &'static str,
    get: impl Fn(&Planner, usize) -> f64 + Clone + Send + Sync + 'static,
) -> Array<Planner, f64, impl Role<Planner>> {
    Array::new(first_vr, base, AXES, what, get)
        .stride(AXIS_STRIDE)
        .label("Axis")
}

fn display_unit(unit: &str) -> Option<&'static str> {
    match unit {
        "rad" => Some("deg"),
        "rad/s" => Some("deg/s"),
        "rad/s2" => Some("deg/s2"),
        _ => None,
    }
}

/// The knowns at initialization of axis `a`: the start time (FMI 3.0 only: FMI 2.0
/// has no time variable to name), the polynomial's order, times and that axis's
/// boundary values (InitialUnknowns dependencies of q, qdot, qddot).
macro_rules! axis_knowns {
    ($a:literal) => {
        [
            "time",
            "order",
            "t0",
            "tf",
            concat!("q0[", $a, "]"),
            concat!("qf[", $a, "]"),
            concat!("qdot0[", $a, "]"),
            concat!("qdotf[", $a, "]"),
            concat!("qddot0[", $a, "]"),
            concat!("qddotf[", $a, "]"),
        ]
    };
}

static AXIS_KNOWNS: [[&str; 10]; AXES] = [axis_knowns!(1), axis_knowns!(2), axis_knowns!(3)];

fn variables() -> Vec<Variable<Planner>> {
    let mut table = vec![
        Variable::integer(
            1,
            "order",
            "Polynomial degree: 3 (cubic) or 5 (quintic)",
            |m: &Planner| m.degree,
        )
        .parameter(Variability::Fixed)
        .start_integer(5)
        .integer_range(3, 5)
        .set_integer(|m, v| {
            if Order::from_degree(v).is_none() {
                return Err("the order must be 3 or 5".to_string());
            }
            m.degree = v;
            m.rebuild();
            Ok(())
        }),
        Variable::real(2, "t0", "Start time of the motion", |m: &Planner| m.t0)
            .parameter(Variability::Fixed)
            .unit("s", None)
            .start_real(0.0)
            .set_real(|m, v| {
                m.t0 = v;
                m.rebuild();
                Ok(())
            }),
        Variable::real(
            3,
            "tf",
            "End time of the motion (after t0)",
            |m: &Planner| m.tf,
        )
        .parameter(Variability::Fixed)
        .unit("s", None)
        .start_real(2.0)
        .set_real(|m, v| {
            m.tf = v;
            m.rebuild();
            Ok(())
        }),
    ];
    for (k, &(name, unit, what, defaults)) in BOUNDARY_FIELDS.iter().enumerate() {
        let get = move |m: &Planner, axis: usize| {
            let mut b = m.boundary[axis];
            *boundary_field(&mut b, k)
        };
        let array = axes(boundary_vr(0, k), name, what, get)
            .set(move |m, axis, v| {
                *boundary_field(&mut m.boundary[axis], k) = v;
                m.rebuild();
                Ok(())
            })
            .each(move |v, axis| {
                v.parameter(Variability::Fixed)
                    .unit(unit, display_unit(unit))
                    .start_real(defaults[axis])
            });
        table.extend(array.variables());
    }
    for (k, &(name, unit, what)) in OUTPUTS.iter().enumerate() {
        let get = move |m: &Planner, axis: usize| match m.sample(axis) {
            Some(s) => [s.q, s.qdot, s.qddot][k],
            None => f64::NAN,
        };
        let array = axes(output_vr(0, k), name, what, get).each(move |v, axis| {
            v.output()
                .unit(unit, display_unit(unit))
                .initial_depends_on(&AXIS_KNOWNS[axis])
        });
        table.extend(array.variables());
    }
    table
}

impl Model for Planner {
    fn info() -> &'static ModelInfo {
        &INFO
    }

    fn variables() -> Vec<Variable<Self>> {
        variables()
    }

    fn new() -> Self {
        Planner {
            degree: 5,
            t0: 0.0,
            tf: 1.0,
            boundary: [Boundary::default(); AXES],
            time: 0.0,
            axes: Err("not yet initialized".to_string()),
        }
    }

    fn set_time(&mut self, time: f64) {
        self.time = time;
    }

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        self.rebuild();
        let axes = self.axes.as_ref().map_err(String::clone)?;
        self.check_overflow(axes)?;
        for (a, p) in axes.iter().enumerate() {
            log.debug(
                "logTrajectory",
                &format!(
                    "axis {}: q(t) = sum c_k (t - {})^k, c = {:?}",
                    a + 1,
                    self.t0,
                    p.shifted_coefficients()
                ),
            );
        }
        Ok(())
    }

    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        // Outputs are explicit functions of time: nothing to integrate.
        StepOutcome::Completed
    }

    /// Exact: order n of q, qdot, qddot is the derivative of order n, n + 1, n + 2 of
    /// the axis's polynomial (`Polynomial::derivative`: one-sided from inside the
    /// motion at t0 and tf, zero while held), so the first derivative of q equals the
    /// output qdot and that of qdot the output qddot at every time.
    fn output_derivative(&self, vr: u32, order: u32) -> Result<f64, OutputDerivativeError> {
        let (axis, k) = output_of(vr).ok_or_else(|| {
            OutputDerivativeError::NotProvided(format!("value reference {vr} is no planner output"))
        })?;
        let axes = self
            .axes
            .as_ref()
            .map_err(|e| OutputDerivativeError::CannotEvaluate(e.clone()))?;
        Ok(axes[axis].derivative(self.time, k + order as usize))
    }

    fn next_time_event(&self, time: f64) -> Option<f64> {
        // The rates jump where the motion starts and ends.
        [self.t0, self.tf].into_iter().find(|&t| t > time)
    }
}

// The exported fmi2* symbols of this FMU.
export_fmu!(Planner);
