//! The trajectory planner (`robofmu_control::trajectory`) as the FMU "Planner": three
//! axes, cubic or quintic, boundary conditions as parameters, q / qdot / qddot per axis
//! as outputs (angles: rad, shown in deg). docs/fmi-layer.md walks through this file.

use robofmu_control::trajectory::{Boundary, Order, Plan};
use robofmu_fmi::prelude::{OutputDerivativeError::CannotEvaluate, Variability::Fixed, *};
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
/// The parameters and the time; the outputs are functions of them (no `do_step`).
#[derive(Clone, Default)]
pub struct Planner {
    degree: i32,
    times: [f64; 2],            // t0, tf
    boundary: [[f64; 6]; AXES], // per axis: q0, qf, qdot0, qdotf, qddot0, qddotf
    time: f64,
    plan: Option<Plan<AXES>>, // None: the parameters plan none (`planned` says why)
}
impl Planner {
    fn planned(&self) -> Result<Plan<AXES>, String> {
        let [t0, tf] = self.times;
        Plan::new(self.degree, t0, tf, &self.boundary.map(Boundary::from))
    }
    fn derivative(&self, axis: usize, k: usize, n: u32) -> Result<f64, OutputDerivativeError> {
        let why = || CannotEvaluate(self.planned().err().unwrap_or_default());
        let plan = self.plan.as_ref().ok_or_else(why)?;
        Ok(plan.axis(axis).derivative(self.time, k + n as usize)) // exact: order k + n of q
    }
}
type Decl = Declaration<Planner>;
/// Order k of a position (0 q, 1 qdot, 2 qddot) for the axes, element a at `vr + 10 a`.
const fn axes(d: Decl, vr: u32, k: usize) -> Decl {
    let (unit, shown) = [("rad", "deg"), ("rad/s", "deg/s"), ("rad/s2", "deg/s2")][k];
    let d = d.array(AXES).at(vr).stride(10).label("Axis");
    d.unit(unit, Some(shown))
}
const fn fixed(d: Decl, what: &'static str) -> Decl {
    let d = d.parameter(Fixed).describe(what);
    d.after_set(|m, _| m.plan = m.planned().ok()) // planned again after every set
}
const fn time<const I: usize>(name: &'static str, what: &'static str) -> Decl {
    let place: Place<Planner, f64> = |m, _| &mut m.times[I]; // 0 t0, 1 tf
    fixed(Decl::real_in(name, place), what).unit("s", None)
}
/// Boundary value I of the axes (order I / 2 of a position) at 10 + I, start 0 or given.
const fn boundary<const I: usize>(name: &'static str, what: &'static str) -> Decl {
    let place: Place<Planner, f64> = |m, a| &mut m.boundary[a][I];
    fixed(axes(Decl::real_in(name, place), 10 + I as u32, I / 2), what).start_real(&[0.0])
}
/// Planned output K of the axes at 100 + K (NaN until planned), exact derivatives.
const fn planned<const K: usize>(name: &'static str, what: &'static str) -> Decl {
    let q = |m: &Planner, a| m.derivative(a, K, 0).unwrap_or(f64::NAN);
    let d = axes(Decl::real(name, what, q), 100 + K as u32, K).output();
    d.output_derivative(2, |m, a, n| m.derivative(a, K, n))
        .initial_depends_on(&KNOWNS)
}
const DEGREE: &str = "Polynomial degree: 3 (cubic) or 5 (quintic)";
const ORDER: Decl = fixed(Decl::integer_in("order", |m, _| &mut m.degree), DEGREE)
    .set_integer(|m, _, v| {
        let order = Order::from_degree(v).map(|_| m.degree = v);
        order.ok_or_else(|| "the order must be 3 or 5".to_string())
    })
    .start_integer(&[5])
    .integer_range(3, 5)
    .at(1);
const T0: Decl = time::<0>("t0", "Start time of the motion").start_real(&[0.0]);
const TF: Decl = time::<1>("tf", "End time of the motion (after t0)").start_real(&[2.0]);
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
static KNOWNS: [Var; 10] = concat(&[&[Var::Time], &same(&PARAMETERS)], Var::Time);
static VARIABLES: [Decl; 12] = concat(&[&PARAMETERS, &[Q, QDOT, QDDOT]], ORDER);

impl Model for Planner {
    const INFO: &'static ModelInfo = &INFO;
    const VARIABLES: &'static [Declaration<Self>] = &VARIABLES;
    fn set_time(&mut self, time: f64) {
        self.time = time;
    }
    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        let (plan, t0) = (self.planned()?, self.times[0]);
        for a in 0..AXES {
            let c = plan.axis(a).shifted_coefficients();
            let message = format!("axis {}: q(t) = sum c_k (t - {t0})^k, c = {c:?}", a + 1);
            log.debug(LOG.name, &message);
        }
        Ok(())
    }
    fn next_time_event(&self, time: f64) -> Option<f64> {
        self.times.into_iter().find(|&t| t > time) // the rates jump there
    }
}
export_fmu!(Planner);
