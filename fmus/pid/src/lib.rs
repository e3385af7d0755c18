//! Binding of the PID law (`robofmu_control::pid`) as the FMU "PID": three independent
//! channels; gains, filter time constant and limits per channel and tunable; the
//! integral and the derivative-filter state are the continuous states (Model
//! Exchange) and are stepped exactly under a zero-order hold of the inputs, or for
//! inputs following their first and second derivatives over the step when the master
//! gives them (Co-Simulation, fmi2SetRealInputDerivatives). Signals carry no unit: the
//! controller is generic.

use robofmu_control::pid::{self, PidGains, PidInputs, PidState};
use robofmu_control::pid_jacobian::{self, Known, Unknown};
use robofmu_control::pid_ramp::{PidInputRamp, step_with_ramp};
use robofmu_fmi::prelude::*;

pub const CHANNELS: usize = 3;

static INFO: ModelInfo = ModelInfo::new(
    "PID",
    "{9b7e2f14-3c6a-4e8d-b1f0-7a5d2c9e6b33}",
    "Three-channel PID controller with filtered derivative, measured-rate option, feedforward \
     and output limits with conditional-integration anti-windup",
    [0.0, 2.0, 1e-8, 0.01],
)
.logs(&[LOG]);
const LOG: LogCategory =
    LogCategory::new("logController", "Gains and options of each channel at initialization");

/// Parameters, inputs and states of the three channels.
#[derive(Clone, Default)]
pub struct Pid {
    gains: [PidGains; CHANNELS],
    /// Limits as set; they apply only when `limited` is true.
    limits: [(f64, f64); CHANNELS],
    limited: [bool; CHANNELS],
    inputs: [PidInputs; CHANNELS],
    /// Derivatives of the inputs at the start of a step (zero: held).
    ramps: [PidInputRamp; CHANNELS],
    states: [PidState; CHANNELS],
}

impl Pid {
    fn sync_limits(&mut self, c: usize) {
        self.gains[c].limits = self.limited[c].then_some(self.limits[c]);
    }

    fn output(&self, c: usize) -> pid::PidOutput {
        pid::output(&self.gains[c], &self.states[c], &self.inputs[c])
    }

    fn derivative(&self, c: usize) -> PidState {
        pid::derivatives(&self.gains[c], &self.states[c], &self.inputs[c])
    }

    /// The gains of channel c are usable, or why not.
    fn validate(&self, c: usize) -> Result<(), String> {
        (self.gains[c].validate()).map_err(|e| format!("channel {}: {e}", c + 1))
    }

    /// Applies a change of channel c (setting a limit updates the law's limits).
    fn change(&mut self, c: usize, f: impl FnOnce(&mut Self)) -> Result<(), String> {
        f(self);
        self.sync_limits(c);
        Ok(())
    }

    /// The input derivatives of `order` (1 or 2) of channel c.
    fn ramp(&mut self, c: usize, order: u32) -> Option<&mut PidInputs> {
        let ramp = self.ramps.get_mut(c)?;
        match order {
            1 => Some(&mut ramp.rate),
            2 => Some(&mut ramp.acceleration),
            _ => None,
        }
    }
}

type Decl = Declaration<Pid>;

/// The array of the three channels, element c at `vr + c - 1`, described as
/// "Channel c: ..." in FMI 2.0.
const fn channels(d: Decl, vr: u32) -> Decl {
    d.array(CHANNELS).at(vr).label("Channel")
}

/// A settable channel array of the field `m.$group[c]$(.$member)` (`$ty`: real or boolean).
macro_rules! settable {
    ($ty:ident, $set:ident, $name:literal, $vr:literal, $what:literal, $group:ident $(. $member:tt)?) => {
        channels(Decl::$ty($name, $what, |m, c| m.$group[c]$(.$member)?), $vr)
            .$set(|m, c, v| m.change(c, |m| m.$group[c]$(.$member)? = v))
    };
}

/// A tunable Real parameter of the three channels.
macro_rules! gain {
    ($name:literal, $vr:literal, $what:literal, $start:literal, $($field:tt)+) => {
        settable!(real, set_real, $name, $vr, $what, $($field)+)
            .parameter(Variability::Tunable)
            .start_real(&[$start])
    };
}

/// A Boolean parameter of the three channels (default false).
macro_rules! switch {
    ($name:literal, $vr:literal, $what:literal, $variability:ident, $($field:tt)+) => {
        settable!(boolean, set_boolean, $name, $vr, $what, $($field)+)
            .parameter(Variability::$variability)
            .start_boolean(&[false])
    };
}

/// A continuous Real input of the three channels, with its input derivatives.
macro_rules! input {
    ($name:literal, $vr:literal, $what:literal, $start:expr, $field:ident) => {
        settable!(real, set_real, $name, $vr, $what, inputs.$field)
            .input()
            .start_real($start)
            .input_derivative(|m, c, n| m.ramp(c, n).map(|r| &mut r.$field))
    };
}

/// A state of the three channels (start 0), and its time derivative.
macro_rules! state {
    ($name:literal, $vr:literal, $what:literal, $field:ident) => {
        settable!(real, set_real, $name, $vr, $what, states.$field).state().start_real(&[0.0])
    };
    ($name:literal, $state:ident, $vr:literal, $what:literal, $field:ident) => {
        Decl::real($name, $what, |m, c| m.derivative(c).$field)
            .array(CHANNELS)
            .at($vr)
            .derivative_of($state.name)
    };
}

const KP: Decl = gain!("Kp", 1, "Proportional gain", 1.0, gains.kp);
const KI: Decl = gain!("Ki", 11, "Integral gain (1/s)", 0.5, gains.ki);
const KD: Decl = gain!("Kd", 21, "Derivative gain (s)", 0.1, gains.kd);
const TF: Decl = gain!(
    "Tf",
    31,
    "Derivative filter time constant (0 allowed only with rate inputs)",
    0.05,
    gains.tf
)
.real_range(Some(0.0), None);
const LIMIT: Decl =
    switch!("limitOutput", 41, "clamp the output to [uMin, uMax]", Tunable, limited);
const U_MIN: Decl = gain!("uMin", 51, "Lower output limit (used when limitOutput)", -1.0, limits.0);
const U_MAX: Decl = gain!("uMax", 61, "Upper output limit (used when limitOutput)", 1.0, limits.1);
const RATES: Decl = switch!(
    "useRateInputs",
    71,
    "derivative from setpointRate - measuredRate instead of the filtered error",
    Fixed,
    gains.use_rate_inputs
);
const SETPOINT: Decl = input!("setpoint", 101, "Setpoint r", &[1.0, 0.5, -0.25], setpoint);
const MEASURED: Decl = input!("measurement", 111, "Measurement y (e = r - y)", &[0.0], measurement);
const R_RATE: Decl = input!(
    "setpointRate",
    121,
    "Setpoint rate dr/dt (used when useRateInputs)",
    &[0.0],
    setpoint_rate
);
const Y_RATE: Decl = input!(
    "measuredRate",
    131,
    "Measured rate dy/dt (used when useRateInputs)",
    &[0.0],
    measured_rate
);
const FEEDFWD: Decl =
    input!("feedforward", 141, "Added to the output before the limits", &[0.0], feedforward);
const U: Decl = channels(Decl::real("u", "control output", |m, c| m.output(c).u), 201)
    .output()
    .initial_depends_on(&OUTPUT_KNOWNS);
const INTEGRAL: Decl = state!("integral", 301, "integral of the error (state)", integral);
const FILTER: Decl = state!("filter", 311, "derivative filter state (state)", filter);
const DER_INT: Decl =
    state!("der(integral)", INTEGRAL, 321, "Time derivative of the error integral", integral)
        .initial_depends_on(&OUTPUT_KNOWNS);
const DER_FILTER: Decl =
    state!("der(filter)", FILTER, 331, "Time derivative of the derivative filter state", filter)
        .initial_depends_on(&FILTER_KNOWNS);

/// What the filter's dx/dt reads at initialization, in the same channel.
static FILTER_KNOWNS: [Var; 8] = same(&[KD, TF, RATES, SETPOINT, MEASURED, R_RATE, Y_RATE, FILTER]);
/// What u reads at initialization (the law of `control::pid`), in the same channel;
/// also dI/dt (conditional integration compares u with the limits).
static OUTPUT_KNOWNS: [Var; 15] = same(&[
    KP, KI, KD, TF, LIMIT, U_MIN, U_MAX, RATES, SETPOINT, MEASURED, R_RATE, Y_RATE, FEEDFWD,
    INTEGRAL, FILTER,
]);

static VARIABLES: &[Decl] = &[
    KP, KI, KD, TF, LIMIT, U_MIN, U_MAX, RATES, SETPOINT, MEASURED, R_RATE, Y_RATE, FEEDFWD, U,
    INTEGRAL, FILTER, DER_INT, DER_FILTER,
];

/// The law's unknowns and knowns (`control::pid_jacobian`) by declaration.
const UNKNOWNS: [(Decl, Unknown); 3] =
    [(U, Unknown::Output), (DER_INT, Unknown::IntegralRate), (DER_FILTER, Unknown::FilterRate)];
const KNOWNS: [(Decl, Known); 7] = [
    (SETPOINT, Known::Setpoint),
    (MEASURED, Known::Measurement),
    (R_RATE, Known::SetpointRate),
    (Y_RATE, Known::MeasuredRate),
    (FEEDFWD, Known::Feedforward),
    (INTEGRAL, Known::Integral),
    (FILTER, Known::Filter),
];

/// The entry of `table` whose declaration is element e's.
fn role<T: Copy>(table: &[(Decl, T)], e: Element) -> Option<T> {
    table.iter().find(|(d, _)| d.is(e)).map(|&(_, t)| t)
}

/// d(output or state derivative)/d(input or state) of the law; the channels are
/// independent.
fn partial(m: &Pid, unknown: Element, known: Element) -> Result<f64, String> {
    let c = unknown.index;
    let not = |e: Element, what| format!("\"{}\" is not an {what}", e.name);
    if known.index != c {
        return Ok(0.0);
    }
    let of = role(&UNKNOWNS, unknown).ok_or_else(|| not(unknown, "output or derivative"))?;
    let (g, s, i) = (&m.gains[c], &m.states[c], &m.inputs[c]);
    pid_jacobian::partial(g, s, i, of, role(&KNOWNS, known))
        .ok_or_else(|| not(known, "input or state"))
}

impl Model for Pid {
    const INFO: &'static ModelInfo = &INFO;

    const VARIABLES: &'static [Declaration<Self>] = VARIABLES;

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        for c in 0..CHANNELS {
            self.validate(c)?;
            let message = format!("channel {}: {:?}", c + 1, self.gains[c]);
            log.debug(LOG.name, &message);
        }
        Ok(())
    }

    fn do_step(&mut self, _time: f64, step: f64, _log: &dyn Log) -> StepOutcome {
        if let Err(reason) = (0..CHANNELS).try_for_each(|c| self.validate(c)) {
            return StepOutcome::Discarded { reason, terminate: true };
        }
        for c in 0..CHANNELS {
            let (g, s, i) = (&self.gains[c], &self.states[c], &self.inputs[c]);
            self.states[c] = step_with_ramp(g, s, i, &self.ramps[c], step);
        }
        StepOutcome::Completed
    }

    const MAX_INPUT_DERIVATIVE_ORDER: u32 = 2;

    /// FMI 3.0 intermediate update: with a callback, each communication step is split
    /// into 10 equal sub-intervals, and the importer may set the continuous inputs at
    /// the 9 inner points (held over the next sub-interval).
    const INTERMEDIATE_UPDATE_POINTS: u32 = 10;

    // The continuous states and their derivatives: the layer's defaults, through the
    // declarations of integral, filter and their derivatives.

    const JACOBIAN: Option<Jacobian<Self>> = Some(Jacobian::Partial(partial));
}

// The exported fmi2* symbols of this FMU.
export_fmu!(Pid);
