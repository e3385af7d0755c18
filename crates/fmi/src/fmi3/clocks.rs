//! What an FMI 3.0 instance keeps of its model's input clocks
//! ([`crate::core::Model::CLOCKS`], declared with
//! [`core::clocks`](crate::core::clocks)): each clock's period as set through its
//! parameter, whether the importer activated it in this Event Mode, and the start
//! time the ticks count from. The ticks themselves are computed from the time
//! (tick k at start + k counter / resolution), so that an FMU state restored to an
//! earlier time ticks again from there.

use crate::core::clocks::{Tick, next_tick, period_fraction, tick_at, tick_time};
use crate::core::model::Model;

/// One clock's period and activation.
#[derive(Debug, Clone, PartialEq)]
pub struct ClockState {
    /// The period as set, s.
    pub period: f64,
    /// The period as counter / resolution.
    pub interval: (u64, u64),
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

impl Clocks {
    /// The clocks of model M with their start periods.
    pub fn new<M: Model>() -> Result<Self, String> {
        let clocks = M::CLOCKS
            .iter()
            .map(|c| {
                Ok(ClockState {
                    period: c.period.start,
                    interval: period_fraction(c.period.start, c.period.name)?,
                    active: false,
                    driven: false,
                })
            })
            .collect::<Result<_, String>>()?;
        Ok(Clocks {
            clocks,
            start: M::INFO.default_experiment.start_time,
        })
    }

    /// Sets the period of clock `k` (checked: a positive finite decimal of at most 18
    /// places; `name` in the message).
    pub fn set_period(&mut self, k: usize, period: f64, name: &str) -> Result<(), String> {
        let interval = period_fraction(period, name)?;
        self.clocks[k] = ClockState {
            period,
            interval,
            active: false,
            driven: false,
        };
        Ok(())
    }

    /// The tick of clock `k` at time `t`, or why `t` is not one of its ticks.
    pub fn tick_at(&self, k: usize, t: f64, name: &str) -> Result<Tick, String> {
        let c = &self.clocks[k];
        match tick_at(self.start, c.interval, t) {
            Some(index) => Ok(Tick {
                time: tick_time(self.start, c.interval, index),
                index,
                period: c.interval.0 as f64 / c.interval.1 as f64,
            }),
            None => {
                let next = next_tick(self.start, c.interval, t).map_or(f64::NAN, |n| n.1);
                Err(format!(
                    "t = {t} s is not a tick of {name} (every {} s from t = {} s; the next \
                     is t = {next} s): a periodic input clock is set only at its ticks",
                    c.period, self.start
                ))
            }
        }
    }

    /// Where a step from `t` to `end` meets the clocks the importer drives: None when
    /// no tick lies in (t, end]; Some((tick, passes)) for the first tick after `t`,
    /// `passes` when the step goes beyond it (a step ending within the tolerance of
    /// [`tick_at`] ends at the tick).
    pub fn step_end(&self, t: f64, end: f64) -> Option<(f64, bool)> {
        let (tick, period) = (self.clocks.iter())
            .filter(|c| c.driven)
            .filter_map(|c| {
                let period = c.interval.0 as f64 / c.interval.1 as f64;
                next_tick(self.start, c.interval, t).map(|n| (n.1, period))
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
