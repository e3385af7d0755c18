//! N independent PID channels, the channel count a runtime parameter (one PID for a
//! six-joint arm as for the 3-PSS's three Euler angles). Each channel is the scalar law
//! of `pid` with its own gains and state; the arrays of gains and states are sized by the
//! count, the per-call arrays of inputs and outputs must match it. Nothing allocates
//! after construction or a resize: the callers own the input and output slices.

use crate::pid::{self, PidError, PidGains, PidInputs, PidOutput, PidState};
use std::fmt;

/// Largest channel count: far above any robot's joints, far below a size whose arrays
/// would exhaust memory (a count of 10^9 is a mistake to refuse, not to allocate).
pub const MAX_CHANNELS: usize = 1024;

/// Why a set of channels cannot be built or a call cannot be served.
#[derive(Debug, Clone, PartialEq)]
pub enum ChannelsError {
    /// The channel count is 0 or above [`MAX_CHANNELS`].
    Count(usize),
    /// The gains of a channel (1-based) are unusable.
    Gains { channel: usize, error: PidError },
    /// An array passed to a call has the wrong length.
    Length {
        what: &'static str,
        expected: usize,
        got: usize,
    },
    /// A channel (0-based) that does not exist.
    NoChannel { channel: usize, count: usize },
    /// The sample period of a tick is not a positive finite number, s.
    Period(f64),
}

impl fmt::Display for ChannelsError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::Count(n) => write!(
                f,
                "the channel count {n} must be between 1 and {MAX_CHANNELS}"
            ),
            Self::Gains { channel, error } => write!(f, "channel {channel}: {error}"),
            Self::Length {
                what,
                expected,
                got,
            } => write!(
                f,
                "{got} {what} given for {expected} channels: pass one per channel"
            ),
            Self::NoChannel { channel, count } => write!(
                f,
                "there is no channel {} of {count}: channels are 1 to {count}",
                channel + 1
            ),
            Self::Period(p) => write!(
                f,
                "the sample period {p} s must be a positive finite number of seconds"
            ),
        }
    }
}

impl std::error::Error for ChannelsError {}

fn check_count(n: usize) -> Result<(), ChannelsError> {
    if (1..=MAX_CHANNELS).contains(&n) {
        Ok(())
    } else {
        Err(ChannelsError::Count(n))
    }
}

fn check_length(what: &'static str, expected: usize, got: usize) -> Result<(), ChannelsError> {
    if expected == got {
        Ok(())
    } else {
        Err(ChannelsError::Length {
            what,
            expected,
            got,
        })
    }
}

/// N PID channels with their gains and states.
#[derive(Debug, Clone, PartialEq)]
pub struct PidChannels {
    gains: Vec<PidGains>,
    states: Vec<PidState>,
}

impl PidChannels {
    /// One channel per entry of `gains`, each with zero state.
    pub fn new(gains: &[PidGains]) -> Result<Self, ChannelsError> {
        check_count(gains.len())?;
        for (k, g) in gains.iter().enumerate() {
            g.validate().map_err(|error| ChannelsError::Gains {
                channel: k + 1,
                error,
            })?;
        }
        Ok(Self {
            gains: gains.to_vec(),
            states: vec![PidState::default(); gains.len()],
        })
    }

    /// The channel count.
    pub fn count(&self) -> usize {
        self.gains.len()
    }

    /// Changes the channel count to `n`: the first min(n, count) channels keep their
    /// gains and states, new ones take `gains` and a zero state. Refused (nothing
    /// changes) for a count out of range or unusable gains.
    pub fn resize(&mut self, n: usize, gains: PidGains) -> Result<(), ChannelsError> {
        check_count(n)?;
        if n > self.count() {
            gains.validate().map_err(|error| ChannelsError::Gains {
                channel: self.count() + 1,
                error,
            })?;
        }
        self.gains.resize(n, gains);
        self.states.resize(n, PidState::default());
        Ok(())
    }

    pub fn gains(&self) -> &[PidGains] {
        &self.gains
    }

    /// Sets the gains of channel `channel` (0-based); refused (nothing changes) when
    /// they are unusable or the channel does not exist.
    pub fn set_gains(&mut self, channel: usize, gains: PidGains) -> Result<(), ChannelsError> {
        let count = self.count();
        let slot = self
            .gains
            .get_mut(channel)
            .ok_or(ChannelsError::NoChannel { channel, count })?;
        gains.validate().map_err(|error| ChannelsError::Gains {
            channel: channel + 1,
            error,
        })?;
        *slot = gains;
        Ok(())
    }

    pub fn states(&self) -> &[PidState] {
        &self.states
    }

    /// Sets every channel's state; refused (nothing changes) for a wrong length.
    pub fn set_states(&mut self, states: &[PidState]) -> Result<(), ChannelsError> {
        check_length("states", self.count(), states.len())?;
        self.states.copy_from_slice(states);
        Ok(())
    }

    /// Each channel's output at its state for `inputs`, into `out`.
    pub fn outputs(
        &self,
        inputs: &[PidInputs],
        out: &mut [PidOutput],
    ) -> Result<(), ChannelsError> {
        check_length("inputs", self.count(), inputs.len())?;
        check_length("outputs", self.count(), out.len())?;
        for (k, o) in out.iter_mut().enumerate() {
            *o = pid::output(&self.gains[k], &self.states[k], &inputs[k]);
        }
        Ok(())
    }

    /// Each channel's state derivative for `inputs`, into `out`.
    pub fn derivatives(
        &self,
        inputs: &[PidInputs],
        out: &mut [PidState],
    ) -> Result<(), ChannelsError> {
        check_length("inputs", self.count(), inputs.len())?;
        check_length("derivatives", self.count(), out.len())?;
        for (k, d) in out.iter_mut().enumerate() {
            *d = pid::derivatives(&self.gains[k], &self.states[k], &inputs[k]);
        }
        Ok(())
    }

    /// Advances every channel over h with its inputs held (`pid::step`).
    pub fn step(&mut self, inputs: &[PidInputs], h: f64) -> Result<(), ChannelsError> {
        check_length("inputs", self.count(), inputs.len())?;
        for (k, s) in self.states.iter_mut().enumerate() {
            *s = pid::step(&self.gains[k], s, &inputs[k], h);
        }
        Ok(())
    }

    /// The sampled law at a tick (robofmu_control::sampled): every channel's output from
    /// its state and the sampled inputs into `out` (to be held until the next tick),
    /// then every state advanced over `period`.
    pub fn tick(
        &mut self,
        inputs: &[PidInputs],
        period: f64,
        out: &mut [PidOutput],
    ) -> Result<(), ChannelsError> {
        if !(period.is_finite() && period > 0.0) {
            return Err(ChannelsError::Period(period));
        }
        self.outputs(inputs, out)?;
        self.step(inputs, period)
    }
}
