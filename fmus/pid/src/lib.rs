//! Binding of the PID law (`robofmu_control::pid`) as the FMU "PID": three independent
//! channels; gains, filter time constant and limits per channel and tunable; the
//! integral and the derivative-filter state are the continuous states (Model
//! Exchange) and are stepped exactly under a zero-order hold of the inputs, or for
//! inputs following their first and second derivatives over the step when the master
//! gives them (Co-Simulation, fmi2SetRealInputDerivatives). Signals carry no unit: the
//! controller is generic.

use robofmu_control::pid::{self, PidGains, PidInputs, PidState};
use robofmu_control::pid_ramp::{PidInputRamp, step_with_ramp};
use robofmu_fmi::prelude::*;

pub const CHANNELS: usize = 3;

static INFO: ModelInfo = ModelInfo {
    model_name: "PID",
    model_identifier: "PID",
    guid: "{9b7e2f14-3c6a-4e8d-b1f0-7a5d2c9e6b33}",
    description: "Three-channel PID controller with filtered derivative, measured-rate \
                  option, feedforward and output limits with conditional-integration \
                  anti-windup",
    default_experiment: DefaultExperiment {
        start_time: 0.0,
        stop_time: 2.0,
        tolerance: 1e-8,
        step_size: 0.01,
    },
    number_of_continuous_states: 2 * CHANNELS,
    number_of_event_indicators: 0,
    provides_directional_derivative: true,
    max_output_derivative_order: 0,
    log_categories: &[LogCategory {
        name: "logController",
        description: "Gains and options of each channel at initialization",
    }],
};

/// Parameters, inputs and states of the three channels.
#[derive(Clone)]
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
}

impl Pid {
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
        settable!(real, set_real, $name, $vr, $what, states.$field)
            .state()
            .start_real(&[0.0])
    };
    ($name:literal, $state:literal, $vr:literal, $what:literal, $field:ident) => {
        Decl::real($name, $what, |m, c| m.derivative(c).$field)
            .array(CHANNELS)
            .at($vr)
            .derivative_of($state)
    };
}

/// The knowns at initialization of channel `c` that its output u reads (the law of
/// `control::pid`), also its dI/dt (conditional integration compares u with the limits).
macro_rules! output_knowns {
    ($c:literal) => {
        [
            concat!("Kp[", $c, "]"),
            concat!("Ki[", $c, "]"),
            concat!("Kd[", $c, "]"),
            concat!("Tf[", $c, "]"),
            concat!("limitOutput[", $c, "]"),
            concat!("uMin[", $c, "]"),
            concat!("uMax[", $c, "]"),
            concat!("useRateInputs[", $c, "]"),
            concat!("setpoint[", $c, "]"),
            concat!("measurement[", $c, "]"),
            concat!("setpointRate[", $c, "]"),
            concat!("measuredRate[", $c, "]"),
            concat!("feedforward[", $c, "]"),
            concat!("integral[", $c, "]"),
            concat!("filter[", $c, "]"),
        ]
    };
}

/// The knowns at initialization of channel `c` that the filter's dx/dt reads.
macro_rules! filter_knowns {
    ($c:literal) => {
        [
            concat!("Kd[", $c, "]"),
            concat!("Tf[", $c, "]"),
            concat!("useRateInputs[", $c, "]"),
            concat!("setpoint[", $c, "]"),
            concat!("measurement[", $c, "]"),
            concat!("setpointRate[", $c, "]"),
            concat!("measuredRate[", $c, "]"),
            concat!("filter[", $c, "]"),
        ]
    };
}

/// InitialUnknowns dependencies per channel: of u and dI/dt, of the filter's dx/dt.
static OUTPUT_KNOWNS: [[&str; 15]; CHANNELS] =
    [output_knowns!(1), output_knowns!(2), output_knowns!(3)];
static FILTER_KNOWNS: [[&str; 8]; CHANNELS] =
    [filter_knowns!(1), filter_knowns!(2), filter_knowns!(3)];

static VARIABLES: &[Decl] = &[
    gain!("Kp", 1, "Proportional gain", 1.0, gains.kp),
    gain!("Ki", 11, "Integral gain (1/s)", 0.5, gains.ki),
    gain!("Kd", 21, "Derivative gain (s)", 0.1, gains.kd),
    gain!(
        "Tf",
        31,
        "Derivative filter time constant (0 allowed only with rate inputs)",
        0.05,
        gains.tf
    )
    .real_range(Some(0.0), None),
    switch!(
        "limitOutput",
        41,
        "clamp the output to [uMin, uMax]",
        Tunable,
        limited
    ),
    gain!(
        "uMin",
        51,
        "Lower output limit (used when limitOutput)",
        -1.0,
        limits.0
    ),
    gain!(
        "uMax",
        61,
        "Upper output limit (used when limitOutput)",
        1.0,
        limits.1
    ),
    switch!(
        "useRateInputs",
        71,
        "derivative from setpointRate - measuredRate instead of the filtered error",
        Fixed,
        gains.use_rate_inputs
    ),
    input!("setpoint", 101, "Setpoint r", &[1.0, 0.5, -0.25], setpoint),
    input!(
        "measurement",
        111,
        "Measurement y (e = r - y)",
        &[0.0],
        measurement
    ),
    input!(
        "setpointRate",
        121,
        "Setpoint rate dr/dt (used when useRateInputs)",
        &[0.0],
        setpoint_rate
    ),
    input!(
        "measuredRate",
        131,
        "Measured rate dy/dt (used when useRateInputs)",
        &[0.0],
        measured_rate
    ),
    input!(
        "feedforward",
        141,
        "Added to the output before the limits",
        &[0.0],
        feedforward
    ),
    channels(Decl::real("u", "control output", |m, c| m.output(c).u), 201)
        .output()
        .initial_depends_on(|c| &OUTPUT_KNOWNS[c]),
    state!("integral", 301, "integral of the error (state)", integral),
    state!("filter", 311, "derivative filter state (state)", filter),
    state!(
        "der(integral)",
        "integral",
        321,
        "Time derivative of the error integral",
        integral
    )
    .initial_depends_on(|c| &OUTPUT_KNOWNS[c]),
    state!(
        "der(filter)",
        "filter",
        331,
        "Time derivative of the derivative filter state",
        filter
    )
    .initial_depends_on(|c| &FILTER_KNOWNS[c]),
];

/// d(output or state derivative)/d(input or state) of one channel, from the law in
/// `control::pid` (the limits make u flat, conditional integration makes dI/dt flat).
fn channel_partial(m: &Pid, c: usize, unknown: &str, known: &str) -> Result<f64, String> {
    let g = &m.gains[c];
    let out = m.output(c);
    // Coefficients of e (via setpoint/measurement), of the rate error and of the states
    // in the derivative term D.
    let (d_e, d_rate, d_filter) = if g.use_rate_inputs {
        if g.tf > 0.0 {
            (0.0, 0.0, g.kd)
        } else {
            (0.0, g.kd, 0.0)
        }
    } else if g.kd != 0.0 {
        (g.kd / g.tf, 0.0, -g.kd / g.tf)
    } else {
        (0.0, 0.0, 0.0)
    };
    let filter_active = g.tf > 0.0 && (g.use_rate_inputs || g.kd != 0.0);
    let saturated = g
        .limits
        .is_some_and(|(lo, hi)| out.u_raw > hi || out.u_raw < lo);
    let sign = |k: &str| match k {
        "setpoint" | "setpointRate" => 1.0,
        _ => -1.0,
    };
    Ok(match unknown {
        "u" if saturated => 0.0,
        "u" => match known {
            "setpoint" | "measurement" => sign(known) * (g.kp + d_e),
            "setpointRate" | "measuredRate" => sign(known) * d_rate,
            "feedforward" => 1.0,
            "integral" => g.ki,
            "filter" => d_filter,
            _ => {
                return Err(format!("\"{known}\" is not an input or state"));
            }
        },
        "der(integral)" if pid::integration_stopped(g, &out) => 0.0,
        "der(integral)" => match known {
            "setpoint" | "measurement" => sign(known),
            _ => 0.0,
        },
        "der(filter)" if !filter_active => 0.0,
        "der(filter)" => match (known, g.use_rate_inputs) {
            ("setpoint" | "measurement", false) | ("setpointRate" | "measuredRate", true) => {
                sign(known) / g.tf
            }
            ("filter", _) => -1.0 / g.tf,
            _ => 0.0,
        },
        _ => {
            return Err(format!("\"{unknown}\" is not an output or derivative"));
        }
    })
}

impl Model for Pid {
    fn info() -> &'static ModelInfo {
        &INFO
    }

    fn declarations() -> &'static [Declaration<Self>] {
        VARIABLES
    }

    fn new() -> Self {
        let gains = PidGains {
            kp: 0.0,
            ki: 0.0,
            kd: 0.0,
            tf: 0.0,
            limits: None,
            use_rate_inputs: false,
        };
        Pid {
            gains: [gains; CHANNELS],
            limits: [(-1.0, 1.0); CHANNELS],
            limited: [false; CHANNELS],
            inputs: [PidInputs::default(); CHANNELS],
            ramps: [PidInputRamp::default(); CHANNELS],
            states: [PidState::default(); CHANNELS],
        }
    }

    fn set_time(&mut self, _time: f64) {
        // The law is time invariant.
    }

    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        for c in 0..CHANNELS {
            self.gains[c]
                .validate()
                .map_err(|e| format!("channel {}: {e}", c + 1))?;
            log.debug(
                "logController",
                &format!("channel {}: {:?}", c + 1, self.gains[c]),
            );
        }
        Ok(())
    }

    fn do_step(&mut self, _time: f64, step: f64, _log: &dyn Log) -> StepOutcome {
        for c in 0..CHANNELS {
            if let Err(e) = self.gains[c].validate() {
                return StepOutcome::Discarded {
                    reason: format!("channel {}: {e}", c + 1),
                    terminate: true,
                };
            }
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

    fn continuous_states(&self, x: &mut [f64]) {
        for c in 0..CHANNELS {
            x[c] = self.states[c].integral;
            x[CHANNELS + c] = self.states[c].filter;
        }
    }

    fn set_continuous_states(&mut self, x: &[f64]) {
        for c in 0..CHANNELS {
            self.states[c].integral = x[c];
            self.states[c].filter = x[CHANNELS + c];
        }
    }

    fn derivatives(&self, dx: &mut [f64]) -> Result<(), String> {
        for c in 0..CHANNELS {
            let d = self.derivative(c);
            dx[c] = d.integral;
            dx[CHANNELS + c] = d.filter;
        }
        Ok(())
    }

    fn partial_derivative(&self, unknown: Element, known: Element) -> Result<f64, String> {
        if unknown.index != known.index {
            return Ok(0.0);
        }
        channel_partial(self, unknown.index, unknown.name, known.name)
    }
}

// The exported fmi2* symbols of this FMU.
export_fmu!(Pid);
