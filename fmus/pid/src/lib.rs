//! Binding of the PID law (`robofmu_control::pid`) as the FMU "PID": three independent
//! channels; gains, filter time constant and limits per channel and tunable; the
//! integral and the derivative-filter state are the continuous states (Model
//! Exchange) and are stepped exactly under a zero-order hold of the inputs, or for
//! inputs following their first and second derivatives over the step when the master
//! gives them (Co-Simulation, fmi2SetRealInputDerivatives). Signals carry no unit: the
//! controller is generic.

use robofmu_control::pid::{self, PidGains, PidInputs, PidState};
use robofmu_control::pid_ramp::{PidInputRamp, step_with_ramp};
use robofmu_fmi::core::arrays::ElementType;
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

/// Value references: group g (below) times 10, plus channel 1..3.
const KP: u32 = 0;
const KI: u32 = 10;
const KD: u32 = 20;
const TF: u32 = 30;
const LIMITED: u32 = 40;
const U_MIN: u32 = 50;
const U_MAX: u32 = 60;
const USE_RATES: u32 = 70;
const SETPOINT: u32 = 100;
const MEASUREMENT: u32 = 110;
const SETPOINT_RATE: u32 = 120;
const MEASURED_RATE: u32 = 130;
const FEEDFORWARD: u32 = 140;
const U: u32 = 200;
const INTEGRAL: u32 = 300;
const FILTER: u32 = 310;
const DER_INTEGRAL: u32 = 320;
const DER_FILTER: u32 = 330;

fn vr(group: u32, c: usize) -> u32 {
    group + c as u32 + 1
}

/// (group, channel) of a value reference.
fn split(vr: u32) -> (u32, usize) {
    (vr - (vr - 1) % 10 - 1, ((vr - 1) % 10) as usize)
}

/// The field of `inputs` that the input group `group` sets.
fn input_field(inputs: &mut PidInputs, group: u32) -> Option<&mut f64> {
    match group {
        SETPOINT => Some(&mut inputs.setpoint),
        MEASUREMENT => Some(&mut inputs.measurement),
        SETPOINT_RATE => Some(&mut inputs.setpoint_rate),
        MEASURED_RATE => Some(&mut inputs.measured_rate),
        FEEDFORWARD => Some(&mut inputs.feedforward),
        _ => None,
    }
}

/// Read and write access to one field of channel c (reading needs no copy of the
/// model).
struct Field<T> {
    read: fn(&Pid, usize) -> T,
    write: fn(&mut Pid, usize) -> &mut T,
}

// Copy without requiring T: Copy (the fields are function pointers).
impl<T> Clone for Field<T> {
    fn clone(&self) -> Self {
        *self
    }
}

impl<T> Copy for Field<T> {}

type RealField = Field<f64>;

/// `field!(gains.kp)`: the `Field` of `m.gains[c].kp`; `field!(limited)`: of
/// `m.limited[c]`.
macro_rules! field {
    ($group:ident . $member:tt) => {
        Field {
            read: |m, c| m.$group[c].$member,
            write: |m, c| &mut m.$group[c].$member,
        }
    };
    ($group:ident) => {
        Field {
            read: |m, c| m.$group[c],
            write: |m, c| &mut m.$group[c],
        }
    };
}

/// Tunable Real parameters: group, name, description, default, field.
const REAL_PARAMETERS: [(u32, &str, &str, f64, RealField); 6] = [
    (KP, "Kp", "Proportional gain", 1.0, field!(gains.kp)),
    (KI, "Ki", "Integral gain (1/s)", 0.5, field!(gains.ki)),
    (KD, "Kd", "Derivative gain (s)", 0.1, field!(gains.kd)),
    (
        TF,
        "Tf",
        "Derivative filter time constant (0 allowed only with rate inputs)",
        0.05,
        field!(gains.tf),
    ),
    (
        U_MIN,
        "uMin",
        "Lower output limit (used when limitOutput)",
        -1.0,
        field!(limits.0),
    ),
    (
        U_MAX,
        "uMax",
        "Upper output limit (used when limitOutput)",
        1.0,
        field!(limits.1),
    ),
];

/// Real inputs: group, name, description, default per channel, field.
const INPUTS: [(u32, &str, &str, [f64; CHANNELS], RealField); 5] = [
    (
        SETPOINT,
        "setpoint",
        "Setpoint r",
        [1.0, 0.5, -0.25],
        field!(inputs.setpoint),
    ),
    (
        MEASUREMENT,
        "measurement",
        "Measurement y (e = r - y)",
        [0.0; CHANNELS],
        field!(inputs.measurement),
    ),
    (
        SETPOINT_RATE,
        "setpointRate",
        "Setpoint rate dr/dt (used when useRateInputs)",
        [0.0; CHANNELS],
        field!(inputs.setpoint_rate),
    ),
    (
        MEASURED_RATE,
        "measuredRate",
        "Measured rate dy/dt (used when useRateInputs)",
        [0.0; CHANNELS],
        field!(inputs.measured_rate),
    ),
    (
        FEEDFORWARD,
        "feedforward",
        "Added to the output before the limits",
        [0.0; CHANNELS],
        field!(inputs.feedforward),
    ),
];

/// `base[1..3]` read by `get`, each element described as "Channel c: `description`".
fn channels<T: ElementType>(
    group: u32,
    base: &'static str,
    description: &'static str,
    get: impl Fn(&Pid, usize) -> T + Clone + Send + Sync + 'static,
) -> Array<Pid, T, impl Role<Pid>> {
    Array::new(vr(group, 0), base, CHANNELS, description, get).label("Channel")
}

/// The settable channel array of `field` (setting a limit updates the law's limits).
fn settable<T: ElementType>(
    group: u32,
    base: &'static str,
    description: &'static str,
    field: Field<T>,
) -> Array<Pid, T, impl Role<Pid>> {
    channels(group, base, description, field.read).set(move |m, c, v| {
        *(field.write)(m, c) = v;
        m.sync_limits(c);
        Ok(())
    })
}

/// The Boolean parameter `base[1..3]` (default false) of `field`.
fn switches(
    group: u32,
    base: &'static str,
    description: &'static str,
    variability: Variability,
    field: Field<bool>,
) -> Array<Pid, bool, impl Role<Pid>> {
    settable(group, base, description, field)
        .each(move |v, _| v.parameter(variability).start_boolean(false))
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

fn variables() -> Vec<Variable<Pid>> {
    let mut table = Vec::new();
    let parameter = |(group, name, description, default, field): &(
        u32,
        &'static str,
        &'static str,
        f64,
        RealField,
    )| {
        let default = *default;
        settable(*group, name, description, *field)
            .each(move |v, _| v.parameter(Variability::Tunable).start_real(default))
            .variables()
    };
    table.extend(REAL_PARAMETERS.iter().flat_map(parameter));
    let limited = switches(
        LIMITED,
        "limitOutput",
        "clamp the output to [uMin, uMax]",
        Variability::Tunable,
        field!(limited),
    );
    let use_rates = switches(
        USE_RATES,
        "useRateInputs",
        "derivative from setpointRate - measuredRate instead of the filtered error",
        Variability::Fixed,
        field!(gains.use_rate_inputs),
    );
    table.extend(limited.variables().into_iter().chain(use_rates.variables()));
    for (group, name, description, defaults, field) in INPUTS {
        let array = settable(group, name, description, field)
            .each(move |v, c| v.input().start_real(defaults[c]));
        table.extend(array.variables());
    }
    let u = channels(U, "u", "control output", |m, c| m.output(c).u)
        .each(|v, c| v.output().initial_depends_on(&OUTPUT_KNOWNS[c]));
    table.extend(u.variables());
    /// Group, name, description, field of a state; group, description, value of its
    /// derivative.
    type Derivative = fn(&Pid, usize) -> f64;
    let states: [(u32, &str, &str, RealField, u32, &str, Derivative); 2] = [
        (
            INTEGRAL,
            "integral",
            "integral of the error (state)",
            field!(states.integral),
            DER_INTEGRAL,
            "Time derivative of the error integral",
            |m, c| m.derivative(c).integral,
        ),
        (
            FILTER,
            "filter",
            "derivative filter state (state)",
            field!(states.filter),
            DER_FILTER,
            "Time derivative of the derivative filter state",
            |m, c| m.derivative(c).filter,
        ),
    ];
    for (group, name, description, field, der_group, der_description, der) in states {
        let state =
            settable(group, name, description, field).each(|v, _| v.state().start_real(0.0));
        let knowns: fn(usize) -> &'static [&'static str] = if group == INTEGRAL {
            |c| &OUTPUT_KNOWNS[c]
        } else {
            |c| &FILTER_KNOWNS[c]
        };
        let derivative =
            RealArray::derivatives(vr(der_group, 0), name, CHANNELS, der_description, der)
                .each(move |v, c| v.initial_depends_on(knowns(c)));
        table.extend(state.variables().into_iter().chain(derivative.variables()));
    }
    table
}

/// d(output or state derivative)/d(input or state) of one channel, from the law in
/// `control::pid` (the limits make u flat, conditional integration makes dI/dt flat).
fn channel_partial(m: &Pid, c: usize, unknown: u32, known: u32) -> Result<f64, String> {
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
    let sign = |k: u32| match k {
        SETPOINT | SETPOINT_RATE => 1.0,
        _ => -1.0,
    };
    Ok(match unknown {
        U if saturated => 0.0,
        U => match known {
            SETPOINT | MEASUREMENT => sign(known) * (g.kp + d_e),
            SETPOINT_RATE | MEASURED_RATE => sign(known) * d_rate,
            FEEDFORWARD => 1.0,
            INTEGRAL => g.ki,
            FILTER => d_filter,
            _ => {
                return Err(format!(
                    "value reference group {known} is not an input or state"
                ));
            }
        },
        DER_INTEGRAL if pid::integration_stopped(g, &out) => 0.0,
        DER_INTEGRAL => match known {
            SETPOINT | MEASUREMENT => sign(known),
            _ => 0.0,
        },
        DER_FILTER if !filter_active => 0.0,
        DER_FILTER => match (known, g.use_rate_inputs) {
            (SETPOINT | MEASUREMENT, false) | (SETPOINT_RATE | MEASURED_RATE, true) => {
                sign(known) / g.tf
            }
            (FILTER, _) => -1.0 / g.tf,
            _ => 0.0,
        },
        _ => {
            return Err(format!(
                "value reference group {unknown} is not an output or derivative"
            ));
        }
    })
}

impl Model for Pid {
    fn info() -> &'static ModelInfo {
        &INFO
    }

    fn variables() -> Vec<Variable<Self>> {
        variables()
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

    fn input_derivative_mut(&mut self, vr: u32, order: u32) -> Option<&mut f64> {
        let (group, c) = split(vr);
        let ramp = self.ramps.get_mut(c)?;
        let part = match order {
            1 => &mut ramp.rate,
            2 => &mut ramp.acceleration,
            _ => return None,
        };
        input_field(part, group)
    }

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

    fn partial_derivative(&self, unknown: u32, known: u32) -> Result<f64, String> {
        let ((ug, uc), (kg, kc)) = (split(unknown), split(known));
        if uc >= CHANNELS || kc >= CHANNELS {
            return Err(format!("value reference {unknown} or {known} out of range"));
        }
        if uc != kc {
            return Ok(0.0);
        }
        channel_partial(self, uc, ug, kg)
    }
}

// The exported fmi2* symbols of this FMU.
export_fmu!(Pid);
