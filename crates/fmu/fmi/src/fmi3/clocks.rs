//! What an FMI 3.0 instance keeps of its model's input clocks
//! ([`crate::core::Model::CLOCKS`], declared with
//! [`core::clocks`](crate::core::clocks)): whether the importer activated each clock
//! in this Event Mode and whether it drives it, and the start time the ticks count
//! from; the periods are the model's (its period parameters). The ticks themselves are computed from the time
//! (tick k at start + k counter / resolution), so that an FMU state restored to an
//! earlier time ticks again from there.

use crate::core::clocks::{Tick, next_tick, period_fraction, tick_at, tick_time};
use crate::core::model::Model;

/// One clock's activation.
#[derive(Debug, Clone, PartialEq)]
pub struct ClockState {
    /// Set by fmi3SetClock in this Event Mode and not yet ticked by
    /// fmi3UpdateDiscreteStates.
    pub active: bool,
    /// The importer has set the clock since instantiation (or reset): it drives the
    /// clock, and Co-Simulation steps end at its ticks. An importer that never sets
    /// it (one that runs only the continuous law) steps across the ticks.
    pub driven: bool,
}

/// The clocks of one instance.
#[derive(Debug, Clone, PartialEq)]
pub struct Clocks {
    pub clocks: Vec<ClockState>,
    /// The start time of the experiment (tick 0), s.
    pub start: f64,
}

/// The interval of clock `k` of model M as counter / resolution, from the model's
/// period parameter.
pub fn interval<M: Model>(model: &M, k: usize) -> Result<(u64, u64), String> {
    let p = &M::CLOCKS[k].period;
    period_fraction((p.get)(model), p.name)
}

impl Clocks {
    /// The clocks of model M, none active.
    pub fn new<M: Model>() -> Self {
        let clock = || ClockState {
            active: false,
            driven: false,
        };
        Clocks {
            clocks: M::CLOCKS.iter().map(|_| clock()).collect(),
            start: M::INFO.default_experiment.start_time,
        }
    }

    /// The tick of clock `k` of `model` at time `t`, or why `t` is not one of its
    /// ticks.
    pub fn tick_at<M: Model>(&self, model: &M, k: usize, t: f64) -> Result<Tick, String> {
        let i = interval(model, k)?;
        let period = i.0 as f64 / i.1 as f64;
        match tick_at(self.start, i, t) {
            Some(index) => Ok(Tick {
                time: tick_time(self.start, i, index),
                index,
                period,
            }),
            None => {
                let next = next_tick(self.start, i, t).map_or(f64::NAN, |n| n.1);
                Err(format!(
                    "t = {t} s is not a tick of {} (every {period} s from t = {} s; the next \
                     is t = {next} s): a periodic input clock is set only at its ticks",
                    M::CLOCKS[k].name,
                    self.start
                ))
            }
        }
    }

    /// Where a step from `t` to `end` meets the clocks the importer drives: None when
    /// no tick lies in (t, end]; Some((tick, passes)) for the first tick after `t`,
    /// `passes` when the step goes beyond it (a step ending within the tolerance of
    /// [`tick_at`] ends at the tick).
    pub fn step_end<M: Model>(&self, model: &M, t: f64, end: f64) -> Option<(f64, bool)> {
        let (tick, period) = (self.clocks.iter().enumerate())
            .filter(|(_, c)| c.driven)
            .filter_map(|(k, _)| {
                let i = interval(model, k).ok()?;
                let period = i.0 as f64 / i.1 as f64;
                next_tick(self.start, i, t).map(|n| (n.1, period))
            })
            .min_by(|a, b| a.0.total_cmp(&b.0))?;
        if (end - tick).abs() <= 1e-9 * period {
            Some((tick, false))
        } else {
            (end > tick).then_some((tick, true))
        }
    }

    /// The name of the first clock set but not yet ticked, if any.
    pub fn pending<M: Model>(&self) -> Option<&'static str> {
        (self.clocks.iter().zip(M::CLOCKS))
            .find(|(c, _)| c.active)
            .map(|(_, spec)| spec.name)
    }
}
