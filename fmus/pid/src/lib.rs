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
const LOG: LogCategory = LogCategory::new(
    "logController",
    "Gains and options of each channel at initialization",
);

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
    /// Brings the law's limits of channel c up to date (after a parameter is set).
    fn sync_limits(&mut self, c: usize) {
        self.gains[c].limits = self.limited[c].then_some(self.limits[c]);
    }

    /// The gains of channel c are usable, or why not.
    fn validate(&self, c: usize) -> Result<(), String> {
        (self.gains[c].validate()).map_err(|e| format!("channel {}: {e}", c + 1))
    }

    fn output(&self, c: usize) -> pid::PidOutput {
        pid::output(&self.gains[c], &self.states[c], &self.inputs[c])
    }

    fn derivative(&self, c: usize) -> PidState {
        pid::derivatives(&self.gains[c], &self.states[c], &self.inputs[c])
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

/// Input K of `inputs`, in the order of the declarations: setpoint, measurement,
/// setpointRate, measuredRate, feedforward.
fn input<const K: usize>(inputs: &mut PidInputs) -> &mut f64 {
    match K {
        0 => &mut inputs.setpoint,
        1 => &mut inputs.measurement,
        2 => &mut inputs.setpoint_rate,
        3 => &mut inputs.measured_rate,
        _ => &mut inputs.feedforward,
    }
}

type Decl = Declaration<Pid>;

/// The array of the three channels, element c at `vr + c - 1`, described as
/// "Channel c: ..." in FMI 2.0.
const fn channels(d: Decl, vr: u32) -> Decl {
    d.array(CHANNELS).at(vr).label("Channel")
}

/// A tunable Real parameter of the three channels.
const fn gain(name: &'static str, vr: u32, start: &'static [f64], place: Place<Pid, f64>) -> Decl {
    let d = channels(Decl::real_in(name, place), vr).parameter(Variability::Tunable);
    d.start_real(start).after_set(Pid::sync_limits)
}

/// A Boolean parameter of the three channels (start false).
const fn flag(name: &'static str, vr: u32, v: Variability, place: Place<Pid, bool>) -> Decl {
    let d = channels(Decl::boolean_in(name, place), vr).parameter(v);
    d.start_boolean(&[false]).after_set(Pid::sync_limits)
}

/// Continuous Real input K of the three channels (see [`input`]), its time derivatives
/// kept in the ramps.
const fn input_k<const K: usize>(name: &'static str, vr: u32, start: &'static [f64]) -> Decl {
    let d = Decl::real_in(name, |m, c| input::<K>(&mut m.inputs[c]));
    let d = channels(d, vr).input().start_real(start);
    d.input_derivative(|m, c, n| Some(input::<K>(m.ramp(c, n)?)))
}

/// A continuous state of the three channels (start 0).
const fn state(name: &'static str, vr: u32, place: Place<Pid, f64>) -> Decl {
    channels(Decl::real_in(name, place), vr)
        .state()
        .start_real(&[0.0])
}

const KP: Decl = gain("Kp", 1, &[1.0], |m, c| &mut m.gains[c].kp).describe("Proportional gain");
const KI: Decl = gain("Ki", 11, &[0.5], |m, c| &mut m.gains[c].ki).describe("Integral gain (1/s)");
const KD: Decl = gain("Kd", 21, &[0.1], |m, c| &mut m.gains[c].kd).describe("Derivative gain (s)");
const TF: Decl = gain("Tf", 31, &[0.05], |m, c| &mut m.gains[c].tf)
    .describe("Derivative filter time constant (0 allowed only with rate inputs)")
    .real_range(Some(0.0), None);
const LIMIT: Decl = flag("limitOutput", 41, Variability::Tunable, |m, c| {
    &mut m.limited[c]
})
.describe("clamp the output to [uMin, uMax]");
const U_MIN: Decl = gain("uMin", 51, &[-1.0], |m, c| &mut m.limits[c].0)
    .describe("Lower output limit (used when limitOutput)");
const U_MAX: Decl = gain("uMax", 61, &[1.0], |m, c| &mut m.limits[c].1)
    .describe("Upper output limit (used when limitOutput)");
const RATES: Decl = flag("useRateInputs", 71, Variability::Fixed, |m, c| {
    &mut m.gains[c].use_rate_inputs
})
.describe("derivative from setpointRate - measuredRate instead of the filtered error");
const SETPOINT: Decl = input_k::<0>("setpoint", 101, &[1.0, 0.5, -0.25]).describe("Setpoint r");
const MEASURED: Decl =
    input_k::<1>("measurement", 111, &[0.0]).describe("Measurement y (e = r - y)");
const R_RATE: Decl = input_k::<2>("setpointRate", 121, &[0.0])
    .describe("Setpoint rate dr/dt (used when useRateInputs)");
const Y_RATE: Decl = input_k::<3>("measuredRate", 131, &[0.0])
    .describe("Measured rate dy/dt (used when useRateInputs)");
const FEEDFWD: Decl =
    input_k::<4>("feedforward", 141, &[0.0]).describe("Added to the output before the limits");
const U: Decl = channels(Decl::real("u", "control output", |m, c| m.output(c).u), 201)
    .output()
    .initial_depends_on(&OUTPUT_KNOWNS);
const INTEGRAL: Decl = state("integral", 301, |m, c| &mut m.states[c].integral)
    .describe("integral of the error (state)");
const FILTER: Decl = state("filter", 311, |m, c| &mut m.states[c].filter)
    .describe("derivative filter state (state)");
const DER_INT: Decl = Decl::real("der(integral)", "", |m, c| m.derivative(c).integral)
    .describe("Time derivative of the error integral")
    .array(CHANNELS)
    .at(321)
    .derivative_of(INTEGRAL.name)
    .initial_depends_on(&OUTPUT_KNOWNS);
const DER_FILTER: Decl = Decl::real("der(filter)", "", |m, c| m.derivative(c).filter)
    .describe("Time derivative of the derivative filter state")
    .array(CHANNELS)
    .at(331)
    .derivative_of(FILTER.name)
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
const UNKNOWNS: [(Decl, Unknown); 3] = [
    (U, Unknown::Output),
    (DER_INT, Unknown::IntegralRate),
    (DER_FILTER, Unknown::FilterRate),
];
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
            return StepOutcome::Discarded {
                reason,
                terminate: true,
            };
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
