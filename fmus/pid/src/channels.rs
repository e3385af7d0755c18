//! The PID's channels (`Pid`): the parameters, inputs and states of each channel, as
//! many as the structural parameter `nChannels` says (FMI 3.0; three in FMI 2.0 and
//! the scalar-only view), and the law's values of a channel.

use robofmu_control::pid::{self, PidGains, PidInputs, PidState};
use robofmu_control::pid_ramp::PidInputRamp;
use robofmu_fmi::prelude::StructuralParameter;

/// The default channel count (FMI 2.0's, and the scalar-only view's).
pub const CHANNELS: usize = 3;
/// The most channels: more than any arm's joints, and every array call's buffers and
/// every FMU state stay small (docs/fmus.md).
pub const MAX_CHANNELS: usize = 64;

/// Parameters, inputs and states of the channels (empty by default: the layer sizes
/// them to `nChannels`).
#[derive(Default)]
pub struct Pid {
    pub(crate) gains: Vec<PidGains>,
    /// Limits as set; they apply only when `limited` is true.
    pub(crate) limits: Vec<(f64, f64)>,
    pub(crate) limited: Vec<bool>,
    pub(crate) inputs: Vec<PidInputs>,
    /// Derivatives of the inputs at the start of a step (zero: held).
    pub(crate) ramps: Vec<PidInputRamp>,
    pub(crate) states: Vec<PidState>,
    /// The sampled law's state and held outputs (`clocked`).
    pub(crate) sampled: super::clocked::Sampled,
}

/// Field by field, so that `clone_from` (the layer's copy before each step) reuses
/// the vectors: no allocation per step.
impl Clone for Pid {
    fn clone(&self) -> Self {
        let mut copy = Pid::default();
        copy.clone_from(self);
        copy
    }

    fn clone_from(&mut self, from: &Self) {
        self.gains.clone_from(&from.gains);
        self.limits.clone_from(&from.limits);
        self.limited.clone_from(&from.limited);
        self.inputs.clone_from(&from.inputs);
        self.ramps.clone_from(&from.ramps);
        self.states.clone_from(&from.states);
        self.sampled.clone_from(&from.sampled);
    }
}

impl Pid {
    /// n channels (the new ones get their start values from the layer).
    fn resize(&mut self, n: usize) {
        self.gains.resize(n, PidGains::default());
        self.limits.resize(n, (0.0, 0.0));
        self.limited.resize(n, false);
        self.inputs.resize(n, PidInputs::default());
        self.ramps.resize(n, PidInputRamp::default());
        self.states.resize(n, PidState::default());
        self.sampled.resize(n);
    }

    /// Brings the law's limits of channel c up to date (after a parameter is set).
    pub(crate) fn sync_limits(&mut self, c: usize) {
        self.gains[c].limits = self.limited[c].then_some(self.limits[c]);
    }

    /// The gains of every channel are usable, or why not.
    pub(crate) fn validate(&self) -> Result<(), String> {
        (self.gains.iter().enumerate())
            .try_for_each(|(c, g)| g.validate().map_err(|e| format!("channel {}: {e}", c + 1)))
    }

    /// `law` (`pid::output`, `pid::derivatives`, ...) on the gains, state and inputs of
    /// channel c.
    pub(crate) fn law<T>(
        &self,
        c: usize,
        law: impl Fn(&PidGains, &PidState, &PidInputs) -> T,
    ) -> T {
        law(&self.gains[c], &self.states[c], &self.inputs[c])
    }
    pub(crate) fn rates(&self, c: usize) -> PidState {
        self.law(c, pid::derivatives)
    }
}

/// Input K of the law, in the order of the declarations: setpoint, measurement,
/// setpointRate, measuredRate, feedforward.
pub(crate) fn input<const K: usize>(inputs: &mut PidInputs) -> &mut f64 {
    match K {
        0 => &mut inputs.setpoint,
        1 => &mut inputs.measurement,
        2 => &mut inputs.setpoint_rate,
        3 => &mut inputs.measured_rate,
        _ => &mut inputs.feedforward,
    }
}

/// `nChannels`: the length of every per-channel array (FMI 3.0).
pub(crate) static STRUCTURAL: &[StructuralParameter<Pid>] = &[StructuralParameter::new(
    "nChannels",
    90,
    "Number of channels: the length of every per-channel array",
    [CHANNELS, MAX_CHANNELS],
    |m| m.gains.len(),
    Pid::resize,
)];
