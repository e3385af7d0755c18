//! Sampled (discrete-time) controllers: a tick schedule from an integer counter and the
//! PID law updated only at ticks, its output held between them (zero-order hold).
//!
//! Clock: a period of `counter / resolution` seconds (two integers, as an FMI 3.0
//! clock's intervalCounter and resolution), tick k at
//!   t_k = start + (k counter) / resolution,
//! the integer product exact (as a double below 2^53) and the quotient one correctly
//! rounded division: the tick time after `start` is the double nearest the exact one,
//! for every k, and no error
//! accumulates over the ticks (summing the period does: 10^6 sums of 0.001 s miss
//! 1000 s by 1.7e-8 s).
//!
//! Sampled PID, per channel, at tick k (inputs sampled there, state s_k of `pid`):
//!   u_k = output(s_k, inputs_k), held on [t_k, t_k+1),
//!   s_k+1 = step(s_k, inputs_k, Ts).
//! `pid::step` is the exact solution of the continuous state equations for inputs held
//! over the step, so the discrete law is the zero-order-hold (step-invariant)
//! equivalent of the continuous PID: with a = exp(-Ts/Tf),
//!   I_k+1 = I_k + Ts e_k (frozen while the output is limited and Ki e_k pushes it
//!   further out: conditional integration decided at the tick, as the continuous law's
//!   co-simulation step decides it at the step start),
//!   x_k+1 = a x_k + (1 - a) w_k,
//! and for the error path without limits the transfer function from e to u - ff is
//!   Kp + Ki Ts / (z - 1) + (Kd / Tf) (z - 1) / (z - a).
//! The continuous law (`pid::output`, `pid::derivatives`, `pid::step`) is unchanged.

use crate::pid::{self, PidError, PidGains, PidInputs, PidOutput, PidState};
use std::fmt;

/// Largest resolution of a clock, ticks per second (10^18, within u64).
const MAX_RESOLUTION: u64 = 1_000_000_000_000_000_000;

/// Why a sampled law or its clock cannot be built.
#[derive(Debug, Clone, PartialEq)]
pub enum SampledError {
    /// The sample period is not a positive finite number of seconds.
    Period(f64),
    /// The period has more than 18 decimal places (its counter would not fit).
    PeriodTooFine(f64),
    /// The clock's counter or resolution is zero.
    ZeroInterval { counter: u64, resolution: u64 },
    /// The start time is not finite.
    Start(f64),
    /// The gains of a channel are unusable.
    Gains(PidError),
}

impl fmt::Display for SampledError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Period(p) => write!(
                f,
                "the sample period {p} s must be a positive finite number of seconds"
            ),
            Self::PeriodTooFine(p) => write!(
                f,
                "the sample period {p} s has more than 18 decimal places: round it"
            ),
            Self::ZeroInterval {
                counter,
                resolution,
            } => write!(
                f,
                "a clock interval of {counter}/{resolution} s: counter and resolution must \
                 be positive"
            ),
            Self::Start(t) => write!(f, "the clock's start time {t} s is not finite"),
            Self::Gains(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for SampledError {}

impl From<PidError> for SampledError {
    fn from(e: PidError) -> Self {
        Self::Gains(e)
    }
}

/// The tick schedule of a sampled law: tick k at start + k counter / resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SampleClock {
    start: f64,
    counter: u64,
    resolution: u64,
}

impl SampleClock {
    /// A clock ticking every `counter / resolution` seconds from `start` (s).
    pub fn new(start: f64, counter: u64, resolution: u64) -> Result<Self, SampledError> {
        if !start.is_finite() {
            return Err(SampledError::Start(start));
        }
        if counter == 0 || resolution == 0 {
            return Err(SampledError::ZeroInterval {
                counter,
                resolution,
            });
        }
        Ok(Self {
            start,
            counter,
            resolution,
        })
    }

    /// A clock ticking every `period` seconds from `start`, the period read as the
    /// decimal it prints as (0.001 -> 1/1000): the shortest decimal that rounds to the
    /// double, so a period written in a scenario is the one ticked.
    pub fn from_period(start: f64, period: f64) -> Result<Self, SampledError> {
        let (counter, resolution) = decimal_fraction(period)?;
        Self::new(start, counter, resolution)
    }

    /// Time of tick k, s.
    pub fn tick_time(&self, k: u64) -> f64 {
        let elapsed = (u128::from(k) * u128::from(self.counter)) as f64 / self.resolution as f64;
        self.start() + elapsed
    }

    /// The period as a double, s.
    pub fn period(&self) -> f64 {
        self.counter as f64 / self.resolution as f64
    }

    /// The time of tick 0, s.
    pub fn start(&self) -> f64 {
        self.start
    }

    /// The interval as (counter, resolution): counter / resolution seconds.
    pub fn interval(&self) -> (u64, u64) {
        (self.counter, self.resolution)
    }
}

/// `period` as counter / 10^d, read from its shortest round-trip decimal.
fn decimal_fraction(period: f64) -> Result<(u64, u64), SampledError> {
    if !(period.is_finite() && period > 0.0) {
        return Err(SampledError::Period(period));
    }
    // Display prints the shortest decimal that reads back as the same double, without
    // an exponent.
    let text = period.to_string();
    let (whole, fraction) = text.split_once('.').unwrap_or((&text, ""));
    let digits = format!("{whole}{fraction}");
    let too_fine = || SampledError::PeriodTooFine(period);
    let resolution = u32::try_from(fraction.len())
        .ok()
        .and_then(|d| 10u64.checked_pow(d))
        .filter(|&r| r <= MAX_RESOLUTION)
        .ok_or_else(too_fine)?;
    let counter = digits.parse::<u64>().map_err(|_| too_fine())?;
    Ok((counter, resolution))
}

/// The sampled law of one channel at a tick, period `ts` (see the module
/// documentation): the output from the state `s` and the sampled inputs (held until
/// the next tick), and the state the next tick starts from.
pub fn tick(g: &PidGains, s: &PidState, inputs: &PidInputs, ts: f64) -> (PidOutput, PidState) {
    (pid::output(g, s, inputs), pid::step(g, s, inputs, ts))
}

/// One PID channel sampled every `period` seconds (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct SampledPid {
    gains: PidGains,
    period: f64,
    state: PidState,
    held: Option<PidOutput>,
}

impl SampledPid {
    /// A channel with zero state and no output before its first tick.
    pub fn new(gains: PidGains, period: f64) -> Result<Self, SampledError> {
        gains.validate()?;
        if !(period.is_finite() && period > 0.0) {
            return Err(SampledError::Period(period));
        }
        Ok(Self {
            gains,
            period,
            state: PidState::default(),
            held: None,
        })
    }

    /// The law at a tick: the output from the state and the sampled inputs (held until
    /// the next tick), then the state advanced over one period.
    pub fn tick(&mut self, inputs: &PidInputs) -> PidOutput {
        let out;
        (out, self.state) = tick(&self.gains, &self.state, inputs, self.period);
        self.held = Some(out);
        out
    }

    /// The output held since the last tick (None before the first).
    pub fn held(&self) -> Option<PidOutput> {
        self.held
    }

    /// The state the next tick starts from.
    pub fn state(&self) -> PidState {
        self.state
    }

    pub fn gains(&self) -> &PidGains {
        &self.gains
    }

    /// The sample period, s.
    pub fn period(&self) -> f64 {
        self.period
    }
}
