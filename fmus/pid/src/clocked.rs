//! The clocked partition of the PID FMU (FMI 3.0 only): the sampled PID law on the
//! input clock `sampleClock`, every `samplePeriod` seconds (default 1 ms). At tick k
//! each channel's output is computed from the inputs set there and the channel's
//! sampled state s_k (error integral and derivative filter), held as `uSampled` until
//! the next tick, and the state advanced over one period with the inputs held
//! (`robofmu_control::sampled::tick`: the zero-order-hold equivalent of the
//! continuous law, I_k+1 = I_k + Ts e_k, x_k+1 = a x_k + (1 - a) w_k, a =
//! exp(-Ts/Tf), conditional integration decided at the tick), with the gains and
//! limits the FMU holds at the tick (they are tunable). The continuous output `u`, its
//! states and FMI 2.0 are unchanged.

use super::{CHANNELS, Pid};
use robofmu_control::pid::PidState;
use robofmu_control::sampled;
use robofmu_fmi::core::clocks::{read_held, write_held};
use robofmu_fmi::prelude::*;

/// The value references of the clock (its period at the next one) and its output
/// (FMI 3.0 array view only: the scalar-only view has no clocks), as ComputedTorque's.
const CLOCK_VR: u32 = 401;
const OUTPUT_VR: u32 = 411;

/// What the sampled law holds between ticks, per channel (as many as `nChannels`).
#[derive(Default)]
pub struct Sampled {
    /// Each channel's state the next tick starts from.
    states: Vec<PidState>,
    /// Each channel's output since the last tick (zero before the first).
    held: Vec<f64>,
    /// The sample period, s (the FMI 3.0 parameter samplePeriod).
    period: f64,
}

/// Field by field, as the PID's channels (`clone_from` reuses the vectors).
impl Clone for Sampled {
    fn clone(&self) -> Self {
        let mut copy = Sampled::default();
        copy.clone_from(self);
        copy
    }

    fn clone_from(&mut self, from: &Self) {
        self.states.clone_from(&from.states);
        self.held.clone_from(&from.held);
        self.period = from.period;
    }
}

/// Doubles in the FMU state of the sampled law: integral, filter and output per
/// channel (the layer carries the period; a serialized state has the default
/// channel count).
const HELD: usize = 3 * CHANNELS;

impl Sampled {
    /// n channels, the new ones at rest (state and output zero).
    pub(crate) fn resize(&mut self, n: usize) {
        self.states.resize(n, PidState::default());
        self.held.resize(n, 0.0);
    }

    /// Appends the sampled law's state to an FMU state's bytes.
    fn write(&self, out: &mut Vec<u8>) {
        let channels = self.states.iter().zip(self.held.iter().copied());
        write_held(out, channels.flat_map(|(s, u)| [s.integral, s.filter, u]));
    }

    /// Reads back what [`Sampled::write`] wrote (every value finite).
    fn read(&mut self, bytes: &[u8]) -> Result<(), String> {
        let v: [f64; HELD] = read_held(bytes, "the sampled PID's state")?;
        for (c, x) in v.chunks_exact(3).enumerate() {
            self.states[c] = PidState {
                integral: x[0],
                filter: x[1],
            };
            self.held[c] = x[2];
        }
        Ok(())
    }
}

static OUTPUTS: &[ClockedOutput<Pid>] = &[ClockedOutput::new(
    "uSampled",
    OUTPUT_VR,
    "control output of the sampled law, held between the ticks of sampleClock (zero \
     before the first)",
    |m: &Pid, c| m.sampled.held[c],
)
.array(CHANNELS)
.sized_by(0)];

pub static CLOCKS: &[InputClock<Pid>] = &[InputClock::sample_clock(
    CLOCK_VR,
    (
        |m: &Pid| m.sampled.period,
        |m: &mut Pid, p| m.sampled.period = p,
    ),
    OUTPUTS,
    Pid::tick,
)
.holding((
    |m: &Pid, out| m.sampled.write(out),
    |m: &mut Pid, bytes| m.sampled.read(bytes),
))];

impl Pid {
    /// The sampled law at a tick, every channel on its inputs now. With unusable gains
    /// nothing changes (the layer reports the reason).
    fn tick(&mut self, tick: &Tick, _log: &dyn Log) -> Result<(), String> {
        self.validate()?;
        let law = &mut self.sampled;
        for c in 0..self.gains.len() {
            let (g, i) = (&self.gains[c], &self.inputs[c]);
            let (out, next) = sampled::tick(g, &law.states[c], i, tick.period);
            (law.held[c], law.states[c]) = (out.u, next);
        }
        Ok(())
    }
}
