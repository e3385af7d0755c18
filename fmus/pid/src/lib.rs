//! The PID law (`robofmu_control::pid`) as the FMU "PID": independent channels (three;
//! FMI 3.0: `nChannels`, 1 to 64, set in Configuration Mode), their gains, filter time
//! constant and limits tunable; the integral and the filter state are the continuous
//! states (Model Exchange), stepped exactly for inputs held or following the derivatives
//! the master gives (Co-Simulation). Signals carry no unit.

use robofmu_control::pid;
use robofmu_control::pid_jacobian::{self, Known, Known::*, Unknown, Unknown::*};
use robofmu_control::pid_ramp::{output_slope, step_with_ramp};
use robofmu_fmi::prelude::{Variability::*, *};

mod channels;
mod clocked;
pub use channels::{CHANNELS, MAX_CHANNELS, Pid};
use channels::{STRUCTURAL, input};

static INFO: ModelInfo = ModelInfo::new(
    "PID",
    "{9b7e2f14-3c6a-4e8d-b1f0-7a5d2c9e6b33}",
    "Three-channel PID controller with filtered derivative, measured-rate option, feedforward \
     and output limits with conditional-integration anti-windup",
    [0.0, 2.0, 1e-8, 0.01],
)
.logs(&[LOG]);
const LOG: LogCategory = LogCategory::new(
    "logController",
    "Gains and options of each channel at initialization",
);

type Decl = Declaration<Pid>;

/// The channels' arrays, "Channel c: ..." in FMI 2.0; a parameter's write syncs the limits.
const CH: Family<Pid> = Family::new(CHANNELS, "Channel")
    .after_set(Pid::sync_limits)
    .sized_by(0);

/// Continuous input K of the channels (see [`input`]): one field selector names the
/// input's place and where its time derivatives are kept (the ramps).
const fn input_k<const K: usize>(name: &'static str, vr: u32, start: &'static [f64]) -> Decl {
    let d = CH.input(name, vr, start, |m, c| input::<K>(&mut m.inputs[c]));
    d.input_derivative(|m, c, n| Some(input::<K>(m.ramps.get_mut(c)?.order_mut(n)?)))
}

const KP: Decl = CH.tunable("Kp", 1, &[1.0], |m, c| &mut m.gains[c].kp);
const KI: Decl = CH.tunable("Ki", 11, &[0.5], |m, c| &mut m.gains[c].ki);
const KD: Decl = CH.tunable("Kd", 21, &[0.1], |m, c| &mut m.gains[c].kd);
const TF: Decl = CH.tunable("Tf", 31, &[0.05], |m, c| &mut m.gains[c].tf);
const LIMIT: Decl = CH.flag("limitOutput", 41, Tunable, |m, c| &mut m.limited[c]);
const U_MIN: Decl = CH.tunable("uMin", 51, &[-1.0], |m, c| &mut m.limits[c].0);
const U_MAX: Decl = CH.tunable("uMax", 61, &[1.0], |m, c| &mut m.limits[c].1);
const RATES: Decl = CH.flag("useRateInputs", 71, Fixed, |m, c| {
    &mut m.gains[c].use_rate_inputs
});
const SETPOINT: Decl = input_k::<0>("setpoint", 101, &[1.0, 0.5, -0.25]);
const MEASURED: Decl = input_k::<1>("measurement", 111, &[0.0]);
const R_RATE: Decl = input_k::<2>("setpointRate", 121, &[0.0]);
const Y_RATE: Decl = input_k::<3>("measuredRate", 131, &[0.0]);
const FEEDFWD: Decl = input_k::<4>("feedforward", 141, &[0.0]);
const U: Decl = CH
    .output("u", 201, |m, c| m.law(c, pid::output).u)
    .output_derivative(2, |m, c, n| {
        Ok(m.law(c, |g, s, i| output_slope(g, s, i, &m.ramps[c], n)))
    });
const INTEGRAL: Decl = CH.state("integral", 301, |m, c| &mut m.states[c].integral);
const FILTER: Decl = CH.state("filter", 311, |m, c| &mut m.states[c].filter);
const DER_INT: Decl = CH.derivative("der(integral)", 321, INTEGRAL, |m, c| m.rates(c).integral);
const DER_FILTER: Decl = CH.derivative("der(filter)", 331, FILTER, |m, c| m.rates(c).filter);

/// What the filter's dx/dt reads at initialization, in the same channel.
static FILTER_KNOWNS: [Var; 8] = same(&[KD, TF, RATES, SETPOINT, MEASURED, R_RATE, Y_RATE, FILTER]);
/// What u reads at initialization (the law of `control::pid`), in the same channel;
/// also dI/dt (conditional integration compares u with the limits).
static OUTPUT_KNOWNS: [Var; 15] = same(&[
    KP, KI, KD, TF, LIMIT, U_MIN, U_MAX, RATES, SETPOINT, MEASURED, R_RATE, Y_RATE, FEEDFWD,
    INTEGRAL, FILTER,
]);

static VARIABLES: &[Decl] = &[
    KP.describe("Proportional gain"),
    KI.describe("Integral gain (1/s)"),
    KD.describe("Derivative gain (s)"),
    (TF.describe("Derivative filter time constant (0 allowed only with rate inputs)"))
        .real_range(Some(0.0), None),
    LIMIT.describe("clamp the output to [uMin, uMax]"),
    U_MIN.describe("Lower output limit (used when limitOutput)"),
    U_MAX.describe("Upper output limit (used when limitOutput)"),
    RATES.describe("derivative from setpointRate - measuredRate instead of the filtered error"),
    SETPOINT.describe("Setpoint r"),
    MEASURED.describe("Measurement y (e = r - y)"),
    R_RATE.describe("Setpoint rate dr/dt (used when useRateInputs)"),
    Y_RATE.describe("Measured rate dy/dt (used when useRateInputs)"),
    FEEDFWD.describe("Added to the output before the limits"),
    (U.describe("control output")).initial_depends_on(&OUTPUT_KNOWNS),
    INTEGRAL.describe("integral of the error (state)"),
    FILTER.describe("derivative filter state (state)"),
    (DER_INT.describe("Time derivative of the error integral")).initial_depends_on(&OUTPUT_KNOWNS),
    (DER_FILTER.describe("Time derivative of the derivative filter state"))
        .initial_depends_on(&FILTER_KNOWNS),
];

/// The law's unknowns and knowns (`control::pid_jacobian`) by declaration.
const UNKNOWNS: [(Decl, Unknown); 3] = [
    (U, Output),
    (DER_INT, IntegralRate),
    (DER_FILTER, FilterRate),
];
const KNOWNS: [(Decl, Known); 7] = [
    (SETPOINT, Setpoint),
    (MEASURED, Measurement),
    (R_RATE, SetpointRate),
    (Y_RATE, MeasuredRate),
    (FEEDFWD, Feedforward),
    (INTEGRAL, Integral),
    (FILTER, Filter),
];

/// d(output or state derivative)/d(input or state) of the law in one channel (the
/// channels are independent: `Jacobian::Diagonal`).
fn partial(m: &Pid, unknown: Element, known: Element) -> Result<f64, String> {
    let of = unknown.role_in(&UNKNOWNS, "an output or derivative")?;
    let c = unknown.index;
    let (g, s, i) = (&m.gains[c], &m.states[c], &m.inputs[c]);
    let d = pid_jacobian::partial(g, s, i, of, known.role(&KNOWNS));
    d.ok_or_else(|| format!("\"{}\" is not an input or state", known.name))
}

impl Model for Pid {
    const INFO: &'static ModelInfo = &INFO;
    const VARIABLES: &'static [Declaration<Self>] = VARIABLES;
    const STRUCTURAL: &'static [StructuralParameter<Self>] = STRUCTURAL;

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        self.validate()?;
        for (c, gains) in self.gains.iter().enumerate() {
            log.debug(LOG.name, &format!("channel {}: {gains:?}", c + 1));
        }
        Ok(())
    }

    fn do_step(&mut self, _time: f64, step: f64, _log: &dyn Log) -> StepOutcome {
        if let Err(reason) = self.validate() {
            return StepOutcome::terminate(reason);
        }
        for c in 0..self.gains.len() {
            self.states[c] = self.law(c, |g, s, i| step_with_ramp(g, s, i, &self.ramps[c], step));
        }
        StepOutcome::Completed
    }

    const MAX_INPUT_DERIVATIVE_ORDER: u32 = 2;
    /// FMI 3.0 intermediate update: each communication step split into 10 equal parts,
    /// the continuous inputs settable at the 9 inner points (held over the next part).
    const INTERMEDIATE_UPDATE_POINTS: u32 = 10;
    const JACOBIAN: Option<Jacobian<Self>> = Some(Jacobian::Diagonal(partial));
    const CLOCKS: &'static [InputClock<Self>] = clocked::CLOCKS;
}

export_fmu!(Pid);
