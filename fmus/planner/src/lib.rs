//! Binding of the trajectory planner (`robofmu_control::trajectory`) as the FMU
//! "Planner": three axes, cubic or quintic, boundary conditions as parameters,
//! q / qdot / qddot per axis as outputs. Axis positions are angles (rad, shown in deg);
//! the planner itself is unit-agnostic.

use robofmu_control::trajectory::{Boundary, Order, Plan};
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
    /// The trajectories of the current parameters, or why there are none.
    plan: Result<Plan<AXES>, String>,
}

impl Planner {
    /// Applies a change of the parameters and plans again.
    fn change(&mut self, f: impl FnOnce(&mut Self)) -> Result<(), String> {
        f(self);
        self.plan = Plan::new(self.degree, self.t0, self.tf, &self.boundary);
        Ok(())
    }

    /// Exact: order n of output k (0 q, 1 qdot, 2 qddot) of `axis` is the derivative
    /// of order k + n of its polynomial (`Polynomial::derivative`: one-sided from inside
    /// the motion at t0 and tf, zero while held), so the first derivative of q equals
    /// the output qdot and that of qdot the output qddot at every time.
    fn derivative(&self, axis: usize, k: usize, n: u32) -> Result<f64, OutputDerivativeError> {
        let plan = self.plan.as_ref();
        let plan = plan.map_err(|e| OutputDerivativeError::CannotEvaluate(e.clone()))?;
        Ok(plan.axis(axis).derivative(self.time, k + n as usize))
    }

    /// Output k of `axis` (NaN until the parameters are valid).
    fn output(&self, axis: usize, k: usize) -> f64 {
        self.derivative(axis, k, 0).unwrap_or(f64::NAN)
    }
}

/// A boundary value of the three axes: parameter `$field` of `Boundary`, element a
/// at value reference `$vr + 10 (a - 1)` (the value references step by axis).
macro_rules! boundary {
    ($field:ident, $vr:literal, $unit:literal, $display:literal, $what:literal, $start:expr) => {
        axes(
            Decl::real(stringify!($field), $what, |m, a| m.boundary[a].$field),
            $vr,
        )
        .set_real(|m, a, v| m.change(|m| m.boundary[a].$field = v))
        .parameter(Variability::Fixed)
        .unit($unit, Some($display))
        .start_real($start)
    };
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

/// A planned output of the three axes (`k`: 0 q, 1 qdot, 2 qddot), element a at value
/// reference `$vr + 10 (a - 1)`, with its exact time derivatives and its knowns at
/// initialization.
macro_rules! planned {
    ($name:literal, $k:literal, $vr:literal, $unit:literal, $display:literal, $what:literal) => {
        axes(Decl::real($name, $what, |m, a| m.output(a, $k)), $vr)
            .output()
            .unit($unit, Some($display))
            .output_derivative(|m, a, n| m.derivative(a, $k, n))
            .initial_depends_on(|a| &AXIS_KNOWNS[a])
    };
}

/// The array of the three axes: element a at `vr + 10 (a - 1)`, "Axis a: ..." in FMI 2.0.
const fn axes(d: Decl, vr: u32) -> Decl {
    d.array(AXES).at(vr).stride(10).label("Axis")
}

type Decl = Declaration<Planner>;

static VARIABLES: &[Decl] = &[
    Decl::integer(
        "order",
        "Polynomial degree: 3 (cubic) or 5 (quintic)",
        |m, _| m.degree,
    )
    .set_integer(|m, _, v| match Order::from_degree(v) {
        None => Err("the order must be 3 or 5".to_string()),
        Some(_) => m.change(|m| m.degree = v),
    })
    .parameter(Variability::Fixed)
    .start_integer(&[5])
    .integer_range(3, 5)
    .at(1),
    Decl::real("t0", "Start time of the motion", |m, _| m.t0)
        .set_real(|m, _, v| m.change(|m| m.t0 = v))
        .parameter(Variability::Fixed)
        .unit("s", None)
        .start_real(&[0.0]),
    Decl::real("tf", "End time of the motion (after t0)", |m, _| m.tf)
        .set_real(|m, _, v| m.change(|m| m.tf = v))
        .parameter(Variability::Fixed)
        .unit("s", None)
        .start_real(&[2.0]),
    boundary!(q0, 10, "rad", "deg", "position at t0", &[0.0]),
    boundary!(qf, 11, "rad", "deg", "position at tf", &[0.5, -0.3, 0.8]),
    boundary!(qdot0, 12, "rad/s", "deg/s", "velocity at t0", &[0.0]),
    boundary!(qdotf, 13, "rad/s", "deg/s", "velocity at tf", &[0.0]),
    boundary!(
        qddot0,
        14,
        "rad/s2",
        "deg/s2",
        "acceleration at t0 (quintic only)",
        &[0.0]
    ),
    boundary!(
        qddotf,
        15,
        "rad/s2",
        "deg/s2",
        "acceleration at tf (quintic only)",
        &[0.0]
    ),
    planned!("q", 0, 100, "rad", "deg", "planned position"),
    planned!("qdot", 1, 101, "rad/s", "deg/s", "planned velocity"),
    planned!("qddot", 2, 102, "rad/s2", "deg/s2", "planned acceleration"),
];

impl Model for Planner {
    fn info() -> &'static ModelInfo {
        &INFO
    }

    fn declarations() -> &'static [Declaration<Self>] {
        VARIABLES
    }

    fn new() -> Self {
        Planner {
            degree: 5,
            t0: 0.0,
            tf: 1.0,
            boundary: [Boundary::default(); AXES],
            time: 0.0,
            plan: Err("not yet initialized".to_string()),
        }
    }

    fn set_time(&mut self, time: f64) {
        self.time = time;
    }

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        self.change(|_| ())?;
        let plan = self.plan.as_ref().map_err(String::clone)?;
        for a in 0..AXES {
            let c = plan.axis(a).shifted_coefficients();
            let message = format!(
                "axis {}: q(t) = sum c_k (t - {})^k, c = {c:?}",
                a + 1,
                self.t0
            );
            log.debug("logTrajectory", &message);
        }
        Ok(())
    }

    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        // Outputs are explicit functions of time: nothing to integrate.
        StepOutcome::Completed
    }

    fn next_time_event(&self, time: f64) -> Option<f64> {
        // The rates jump where the motion starts and ends.
        [self.t0, self.tf].into_iter().find(|&t| t > time)
    }
}

// The exported fmi2* symbols of this FMU.
export_fmu!(Planner);
