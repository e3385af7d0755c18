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

/// A tunable Real parameter of the three channels (its writer given after it).
const fn gain(d: Decl, vr: u32, start: &'static [f64]) -> Decl {
    channels(d, vr)
        .parameter(Variability::Tunable)
        .start_real(start)
}

/// A continuous Real input of the three channels, its derivatives kept by `ramp`.
const fn input(d: Decl, vr: u32, start: &'static [f64], ramp: InputDerivative<Pid>) -> Decl {
    channels(d, vr)
        .input()
        .start_real(start)
        .input_derivative(ramp)
}

/// A continuous state of the three channels (start 0).
const fn state(d: Decl, vr: u32) -> Decl {
    channels(d, vr).state().start_real(&[0.0])
}

const KP: Decl = gain(
    Decl::real("Kp", "Proportional gain", |m, c| m.gains[c].kp),
    1,
    &[1.0],
)
.set_real(|m, c, v| m.change(c, |m| m.gains[c].kp = v));
const KI: Decl = gain(
    Decl::real("Ki", "Integral gain (1/s)", |m, c| m.gains[c].ki),
    11,
    &[0.5],
)
.set_real(|m, c, v| m.change(c, |m| m.gains[c].ki = v));
const KD: Decl = gain(
    Decl::real("Kd", "Derivative gain (s)", |m, c| m.gains[c].kd),
    21,
    &[0.1],
)
.set_real(|m, c, v| m.change(c, |m| m.gains[c].kd = v));
const TF: Decl = gain(
    Decl::real(
        "Tf",
        "Derivative filter time constant (0 allowed only with rate inputs)",
        |m, c| m.gains[c].tf,
    ),
    31,
    &[0.05],
)
.set_real(|m, c, v| m.change(c, |m| m.gains[c].tf = v))
.real_range(Some(0.0), None);
const LIMIT: Decl = channels(
    Decl::boolean("limitOutput", "clamp the output to [uMin, uMax]", |m, c| {
        m.limited[c]
    }),
    41,
)
.set_boolean(|m, c, v| m.change(c, |m| m.limited[c] = v))
.parameter(Variability::Tunable)
.start_boolean(&[false]);
const U_MIN: Decl = gain(
    Decl::real(
        "uMin",
        "Lower output limit (used when limitOutput)",
        |m, c| m.limits[c].0,
    ),
    51,
    &[-1.0],
)
.set_real(|m, c, v| m.change(c, |m| m.limits[c].0 = v));
const U_MAX: Decl = gain(
    Decl::real(
        "uMax",
        "Upper output limit (used when limitOutput)",
        |m, c| m.limits[c].1,
    ),
    61,
    &[1.0],
)
.set_real(|m, c, v| m.change(c, |m| m.limits[c].1 = v));
const RATES: Decl = channels(
    Decl::boolean(
        "useRateInputs",
        "derivative from setpointRate - measuredRate instead of the filtered error",
        |m, c| m.gains[c].use_rate_inputs,
    ),
    71,
)
.set_boolean(|m, c, v| m.change(c, |m| m.gains[c].use_rate_inputs = v))
.parameter(Variability::Fixed)
.start_boolean(&[false]);
const SETPOINT: Decl = input(
    Decl::real("setpoint", "Setpoint r", |m, c| m.inputs[c].setpoint),
    101,
    &[1.0, 0.5, -0.25],
    |m, c, n| m.ramp(c, n).map(|r| &mut r.setpoint),
)
.set_real(|m, c, v| m.change(c, |m| m.inputs[c].setpoint = v));
const MEASURED: Decl = input(
    Decl::real("measurement", "Measurement y (e = r - y)", |m, c| {
        m.inputs[c].measurement
    }),
    111,
    &[0.0],
    |m, c, n| m.ramp(c, n).map(|r| &mut r.measurement),
)
.set_real(|m, c, v| m.change(c, |m| m.inputs[c].measurement = v));
const R_RATE: Decl = input(
    Decl::real(
        "setpointRate",
        "Setpoint rate dr/dt (used when useRateInputs)",
        |m, c| m.inputs[c].setpoint_rate,
    ),
    121,
    &[0.0],
    |m, c, n| m.ramp(c, n).map(|r| &mut r.setpoint_rate),
)
.set_real(|m, c, v| m.change(c, |m| m.inputs[c].setpoint_rate = v));
const Y_RATE: Decl = input(
    Decl::real(
        "measuredRate",
        "Measured rate dy/dt (used when useRateInputs)",
        |m, c| m.inputs[c].measured_rate,
    ),
    131,
    &[0.0],
    |m, c, n| m.ramp(c, n).map(|r| &mut r.measured_rate),
)
.set_real(|m, c, v| m.change(c, |m| m.inputs[c].measured_rate = v));
const FEEDFWD: Decl = input(
    Decl::real(
        "feedforward",
        "Added to the output before the limits",
        |m, c| m.inputs[c].feedforward,
    ),
    141,
    &[0.0],
    |m, c, n| m.ramp(c, n).map(|r| &mut r.feedforward),
)
.set_real(|m, c, v| m.change(c, |m| m.inputs[c].feedforward = v));
const U: Decl = channels(Decl::real("u", "control output", |m, c| m.output(c).u), 201)
    .output()
    .initial_depends_on(&OUTPUT_KNOWNS);
const INTEGRAL: Decl = state(
    Decl::real("integral", "integral of the error (state)", |m, c| {
        m.states[c].integral
    }),
    301,
)
.set_real(|m, c, v| m.change(c, |m| m.states[c].integral = v));
const FILTER: Decl = state(
    Decl::real("filter", "derivative filter state (state)", |m, c| {
        m.states[c].filter
    }),
    311,
)
.set_real(|m, c, v| m.change(c, |m| m.states[c].filter = v));
const DER_INT: Decl = Decl::real(
    "der(integral)",
    "Time derivative of the error integral",
    |m, c| m.derivative(c).integral,
)
.array(CHANNELS)
.at(321)
.derivative_of(INTEGRAL.name)
.initial_depends_on(&OUTPUT_KNOWNS);
const DER_FILTER: Decl = Decl::real(
    "der(filter)",
    "Time derivative of the derivative filter state",
    |m, c| m.derivative(c).filter,
)
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
