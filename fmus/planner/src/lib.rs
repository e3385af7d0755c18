//! The trajectory planner (`robofmu_control::trajectory`) as the FMU "Planner": three
//! axes, cubic or quintic, boundary conditions as parameters, q / qdot / qddot per axis
//! as outputs (angles: rad, shown in deg). docs/fmi-layer.md walks through this file.

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
    /// Per axis: q0, qf, qdot0, qdotf, qddot0, qddotf (`Boundary::from`).
    boundary: [[f64; 6]; AXES],
    time: f64,
    /// The trajectories of the parameters as set (None: they plan none, `why`).
    plan: Option<Plan<AXES>>,
}

impl Planner {
    fn planned(&self) -> Result<Plan<AXES>, String> {
        let boundary = self.boundary.map(Boundary::from);
        Plan::new(self.degree, self.t0, self.tf, &boundary)
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

/// A fixed parameter, `what`: planned again after every set.
const fn fixed(d: Decl, what: &'static str) -> Decl {
    let d = d.parameter(Variability::Fixed).describe(what);
    d.after_set(|m, _| m.plan = m.planned().ok())
}

/// Boundary value I of the axes (order I / 2 of a position) at 10 + I, start 0 or given.
const fn boundary<const I: usize>(name: &'static str, what: &'static str) -> Decl {
    let place: Place<Planner, f64> = |m, a| &mut m.boundary[a][I];
    fixed(axes(Decl::real_in(name, place), 10 + I as u32, I / 2), what).start_real(&[0.0])
}

/// Planned output K (0 q, 1 qdot, 2 qddot) of the axes at 100 + K (NaN until the
/// parameters are valid), with exact time derivatives.
const fn planned<const K: usize>(name: &'static str, what: &'static str) -> Decl {
    let q = |m: &Planner, a| m.derivative(a, K, 0).unwrap_or(f64::NAN);
    let d = axes(Decl::real(name, what, q), 100 + K as u32, K).output();
    d.output_derivative(2, |m, a, n| m.derivative(a, K, n))
        .initial_depends_on(&KNOWNS)
}

const ORDER: Decl = fixed(
    Decl::integer_in("order", |m, _| &mut m.degree),
    "Polynomial degree: 3 (cubic) or 5 (quintic)",
)
.set_integer(|m, _, v| {
    let order = Order::from_degree(v).map(|_| m.degree = v);
    order.ok_or_else(|| "the order must be 3 or 5".to_string())
})
.start_integer(&[5])
.integer_range(3, 5)
.at(1);
const T0: Decl = fixed(
    Decl::real_in("t0", |m, _| &mut m.t0),
    "Start time of the motion",
)
.unit("s", None)
.start_real(&[0.0]);
const TF: Decl = fixed(
    Decl::real_in("tf", |m, _| &mut m.tf),
    "End time of the motion (after t0)",
)
.unit("s", None)
.start_real(&[2.0]);
const Q0: Decl = boundary::<0>("q0", "position at t0");
const QF: Decl = boundary::<1>("qf", "position at tf").start_real(&[0.5, -0.3, 0.8]);
const QDOT0: Decl = boundary::<2>("qdot0", "velocity at t0");
const QDOTF: Decl = boundary::<3>("qdotf", "velocity at tf");
const QDDOT0: Decl = boundary::<4>("qddot0", "acceleration at t0 (quintic only)");
const QDDOTF: Decl = boundary::<5>("qddotf", "acceleration at tf (quintic only)");
const Q: Decl = planned::<0>("q", "planned position");
const QDOT: Decl = planned::<1>("qdot", "planned velocity");
const QDDOT: Decl = planned::<2>("qddot", "planned acceleration");

const PARAMETERS: [Decl; 9] = [ORDER, T0, TF, Q0, QF, QDOT0, QDOTF, QDDOT0, QDDOTF];
/// What the outputs of axis a depend on at initialization: time and the parameters.
static KNOWNS: [Var; 10] = concat(&[&[Var::Time], &same(&PARAMETERS)], Var::Time);
static VARIABLES: [Decl; 12] = concat(&[&PARAMETERS, &[Q, QDOT, QDDOT]], ORDER);

impl Model for Planner {
    const INFO: &'static ModelInfo = &INFO;
    const VARIABLES: &'static [Declaration<Self>] = &VARIABLES;

    fn set_time(&mut self, time: f64) {
        self.time = time;
    }

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        let plan = self.planned()?;
        for a in 0..AXES {
            let (c, t0) = (plan.axis(a).shifted_coefficients(), self.t0);
            let message = format!("axis {}: q(t) = sum c_k (t - {t0})^k, c = {c:?}", a + 1);
            log.debug(LOG.name, &message);
        }
        Ok(())
    }

    fn next_time_event(&self, time: f64) -> Option<f64> {
        [self.t0, self.tf].into_iter().find(|&t| t > time) // the rates jump there
    }
}

export_fmu!(Planner);
