//! Binding of the trajectory planner (`robofmu_control::trajectory`) as the FMU
//! "Planner": three axes, cubic or quintic, boundary conditions as parameters,
//! q / qdot / qddot per axis as outputs. Axis positions are angles (rad, shown in deg);
//! the planner itself is unit-agnostic. docs/fmi-layer.md walks through this file
//! ("Writing an FMU").

use robofmu_control::trajectory::{Boundary, Order, Plan};
use robofmu_fmi::prelude::*;

pub const AXES: usize = 3;

static INFO: ModelInfo = ModelInfo::new(
    "Planner",
    "{5d0c3a52-8f0e-4d6b-9a51-3c2b7e41a901}",
    "Cubic or quintic point-to-point trajectories of three axes from boundary conditions at t0 \
     and tf; at rest at q0 before t0 and at qf after tf",
    [0.0, 2.5, 1e-6, 0.01],
)
.logs(&[LOG]);
const LOG: LogCategory = LogCategory::new(
    "logTrajectory",
    "Polynomial coefficients computed at initialization",
);

/// Parameters and time of the planner (outputs are functions of them: no `do_step`).
#[derive(Clone, Default)]
pub struct Planner {
    degree: i32,
    t0: f64,
    tf: f64,
    boundary: [Boundary; AXES],
    time: f64,
    /// The trajectories of the parameters as set (None: they plan none, `why`).
    plan: Option<Plan<AXES>>,
}

impl Planner {
    /// Applies a change of the parameters and plans again.
    fn change(&mut self, f: impl FnOnce(&mut Self)) -> Result<(), String> {
        f(self);
        self.plan = self.planned().ok();
        Ok(())
    }

    fn planned(&self) -> Result<Plan<AXES>, String> {
        Plan::new(self.degree, self.t0, self.tf, &self.boundary)
    }

    /// Exact: order n of output k (0 q, 1 qdot, 2 qddot) of `axis` is the derivative of
    /// order k + n of its polynomial (one-sided at t0 and tf, zero while held).
    fn derivative(&self, axis: usize, k: usize, n: u32) -> Result<f64, OutputDerivativeError> {
        let why =
            || OutputDerivativeError::CannotEvaluate(self.planned().err().unwrap_or_default());
        let plan = self.plan.as_ref().ok_or_else(why)?;
        Ok(plan.axis(axis).derivative(self.time, k + n as usize))
    }
}

type Decl = Declaration<Planner>;

/// Unit and display unit of order k of a position: 0 q, 1 qdot, 2 qddot.
const UNITS: [(&str, &str); 3] = [("rad", "deg"), ("rad/s", "deg/s"), ("rad/s2", "deg/s2")];

/// The three axes of order k of a position: element a at `vr + 10 a`, "Axis a: ...".
const fn axes(d: Decl, vr: u32, k: usize) -> Decl {
    let d = d.array(AXES).at(vr).stride(10).label("Axis");
    d.unit(UNITS[k].0, Some(UNITS[k].1))
}

/// A boundary value of the three axes, order k of a position (writer given after it).
const fn boundary(d: Decl, vr: u32, k: usize, start: &'static [f64]) -> Decl {
    axes(d, vr, k)
        .parameter(Variability::Fixed)
        .start_real(start)
}

/// Planned output k (0 q, 1 qdot, 2 qddot) of the three axes (NaN until the parameters
/// are valid), with exact time derivatives.
const fn planned<const K: usize>(name: &'static str, vr: u32, what: &'static str) -> Decl {
    let q = |m: &Planner, a| m.derivative(a, K, 0).unwrap_or(f64::NAN);
    let d = axes(Decl::real(name, what, q), vr, K).output();
    d.output_derivative(2, |m, a, n| m.derivative(a, K, n))
        .initial_depends_on(&KNOWNS)
}

const ORDER: Decl = Decl::integer(
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
.at(1);
const T0: Decl = Decl::real("t0", "Start time of the motion", |m, _| m.t0)
    .set_real(|m, _, v| m.change(|m| m.t0 = v))
    .parameter(Variability::Fixed)
    .unit("s", None)
    .start_real(&[0.0]);
const TF: Decl = Decl::real("tf", "End time of the motion (after t0)", |m, _| m.tf)
    .set_real(|m, _, v| m.change(|m| m.tf = v))
    .parameter(Variability::Fixed)
    .unit("s", None)
    .start_real(&[2.0]);
const Q0: Decl = boundary(
    Decl::real("q0", "position at t0", |m, a| m.boundary[a].q0),
    10,
    0,
    &[0.0],
)
.set_real(|m, a, v| m.change(|m| m.boundary[a].q0 = v));
const QF: Decl = boundary(
    Decl::real("qf", "position at tf", |m, a| m.boundary[a].qf),
    11,
    0,
    &[0.5, -0.3, 0.8],
)
.set_real(|m, a, v| m.change(|m| m.boundary[a].qf = v));
const QDOT0: Decl = boundary(
    Decl::real("qdot0", "velocity at t0", |m, a| m.boundary[a].qdot0),
    12,
    1,
    &[0.0],
)
.set_real(|m, a, v| m.change(|m| m.boundary[a].qdot0 = v));
const QDOTF: Decl = boundary(
    Decl::real("qdotf", "velocity at tf", |m, a| m.boundary[a].qdotf),
    13,
    1,
    &[0.0],
)
.set_real(|m, a, v| m.change(|m| m.boundary[a].qdotf = v));
const QDDOT0: Decl = boundary(
    Decl::real("qddot0", "acceleration at t0 (quintic only)", |m, a| {
        m.boundary[a].qddot0
    }),
    14,
    2,
    &[0.0],
)
.set_real(|m, a, v| m.change(|m| m.boundary[a].qddot0 = v));
const QDDOTF: Decl = boundary(
    Decl::real("qddotf", "acceleration at tf (quintic only)", |m, a| {
        m.boundary[a].qddotf
    }),
    15,
    2,
    &[0.0],
)
.set_real(|m, a, v| m.change(|m| m.boundary[a].qddotf = v));

/// What the outputs of axis a depend on at initialization: time, order, t0, tf and
/// that axis's boundary values.
static KNOWNS: [Var; 10] = concat(&[&[Var::Time], &AXIS_KNOWNS], Var::Time);
const AXIS_KNOWNS: [Var; 9] = same(&[ORDER, T0, TF, Q0, QF, QDOT0, QDOTF, QDDOT0, QDDOTF]);
const Q: Decl = planned::<0>("q", 100, "planned position");
const QDOT: Decl = planned::<1>("qdot", 101, "planned velocity");
const QDDOT: Decl = planned::<2>("qddot", 102, "planned acceleration");

static VARIABLES: &[Decl] = &[
    ORDER, T0, TF, Q0, QF, QDOT0, QDOTF, QDDOT0, QDDOTF, Q, QDOT, QDDOT,
];

impl Model for Planner {
    const INFO: &'static ModelInfo = &INFO;

    const VARIABLES: &'static [Declaration<Self>] = VARIABLES;

    fn set_time(&mut self, time: f64) {
        self.time = time;
    }

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        // Every writer planned again: the plan is the one of the parameters as set.
        let plan = self.planned()?;
        for a in 0..AXES {
            let (c, t0) = (plan.axis(a).shifted_coefficients(), self.t0);
            let message = format!("axis {}: q(t) = sum c_k (t - {t0})^k, c = {c:?}", a + 1);
            log.debug(LOG.name, &message);
        }
        Ok(())
    }

    fn next_time_event(&self, time: f64) -> Option<f64> {
        // The rates jump where the motion starts and ends.
        [self.t0, self.tf].into_iter().find(|&t| t > time)
    }
}

export_fmu!(Planner);
