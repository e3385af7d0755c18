//! The clocked partition of the ComputedTorque FMU (FMI 3.0 only): the computed-torque
//! law sampled on the input clock `sampleClock`, every `samplePeriod` seconds
//! (default 1 ms). At tick k the law is evaluated on the inputs set there and the
//! sampled error integral I_k, its output held as `uSampled` until the next tick, and
//! the integral advanced over one period with the rate at the tick (I_k+1 = I_k + Ts
//! e_k, frozen where the limited output is pushed further out): the zero-order-hold
//! law of `robofmu_dynamics::computed_torque::SampledComputedTorque`, with the gains
//! and limits the FMU holds at the tick (they are tunable). The continuous output
//! `u`, its state `integral` and FMI 2.0 are unchanged.

use super::{AXES, ComputedTorqueFmu};
use robofmu_fmi::prelude::*;

/// The value references of the clock (its period at the next one) and its output
/// (FMI 3.0 array view only: the scalar-only view has no clocks).
const CLOCK_VR: u32 = 401;
const OUTPUT_VR: u32 = 411;

static OUTPUTS: &[ClockedOutput<ComputedTorqueFmu>] = &[ClockedOutput::new(
    "uSampled",
    OUTPUT_VR,
    "Euler-angle generalized force of the sampled law, held between the ticks of \
     sampleClock (zero before the first)",
    |m: &ComputedTorqueFmu, k| m.held[k],
)
.array(AXES)
.unit("N.m")];

pub static CLOCKS: &[InputClock<ComputedTorqueFmu>] = &[InputClock::sample_clock(
    CLOCK_VR,
    (
        |m: &ComputedTorqueFmu| m.sample_period,
        |m: &mut ComputedTorqueFmu, p| m.sample_period = p,
    ),
    OUTPUTS,
    ComputedTorqueFmu::tick,
)];

impl ComputedTorqueFmu {
    /// The sampled law at a tick: output from the sampled integral and the inputs now
    /// (held), then the integral advanced over the period. On an error nothing
    /// changes (the layer reports it).
    fn tick(&mut self, tick: &Tick, _log: &dyn Log) -> Result<(), String> {
        let law = match self.law.take() {
            Some(law) => law,
            None => self.build_law()?,
        };
        let result = self.evaluate_at(&law, &self.sampled_integral);
        self.law = Some(law);
        let evaluation = result?;
        self.held = evaluation.u;
        self.sampled_integral += evaluation.integral_rate * tick.period;
        Ok(())
    }
}
