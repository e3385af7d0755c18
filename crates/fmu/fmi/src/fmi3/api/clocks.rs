//! The clock functions of FMI 3.0 (section 2.2.9) for a model's periodic input clocks
//! ([`Model::CLOCKS`](crate::core::Model::CLOCKS)): fmi3SetClock (Event Mode; only at
//! a tick of the clock), fmi3GetIntervalDecimal / fmi3GetIntervalFraction and
//! fmi3GetShiftDecimal / fmi3GetShiftFraction (Initialization and Event Mode; the
//! interval from the clock's period parameter, the shift 0), and the refusals of what
//! a fixed clock without intervalDecimal does not allow: fmi3GetClock (input clocks
//! are set, not read), fmi3SetInterval* and fmi3SetShift* (the interval comes from the
//! parameter). Every function checks the handle, the state and its arguments first; a
//! refusal is fmi3Error with a log line and changes nothing (the arguments of a
//! whole call are checked before any clock changes).
//!
//! The ticks run in fmi3UpdateDiscreteStates (module `model_exchange`); a step of
//! Co-Simulation with event mode ends at the next tick (module `co_simulation`).

use super::{input_slice, output_slice, with_instance};
use crate::core::log::Log;
use crate::core::model::Model;
use crate::fmi3::clocks::interval;
use crate::fmi3::instance::Instance;
use crate::fmi3::mode::{Call, Mode};
use crate::fmi3::table::{Source, type_name};
use crate::fmi3::types::*;

/// The clock indices (in `Model::CLOCKS`) of the value references `vrs`; Err names the
/// first that is not a clock.
fn clocks_of<M: Model>(inst: &Instance<M>, vrs: &[u32]) -> Result<Vec<usize>, String> {
    vrs.iter()
        .map(|&vr| match inst.extra.table.find(vr) {
            Some(v) => match v.source {
                Source::Clock { clock } => Ok(clock),
                _ => Err(format!(
                    "\"{}\" (value reference {vr}) is a {} variable, not a Clock",
                    v.name,
                    type_name(v.variable_type)
                )),
            },
            None => Err(format!(
                "unknown value reference {vr}: not a clock of {}",
                M::INFO.model_name
            )),
        })
        .collect()
}

/// fmi3SetClock: activates (or deactivates) the input clocks `vr` at the current
/// time, which must be one of their ticks; the tick runs in the next
/// fmi3UpdateDiscreteStates. From the first activation on, the importer drives the
/// clock: Co-Simulation steps end at its ticks.
pub unsafe fn set_clock<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *const Fmi3Clock,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3SetClock", Call::SetClock, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            let values = input_slice(values, nvr, "values[]")?;
            let clocks = clocks_of(inst, vrs)?;
            let t = inst.core.time;
            for (&k, &on) in clocks.iter().zip(values) {
                if on != FMI3_FALSE {
                    inst.extra.clocks.tick_at(inst.core.model(), k, t)?;
                }
            }
            for (&k, &on) in clocks.iter().zip(values) {
                let clock = &mut inst.extra.clocks.clocks[k];
                clock.active = on != FMI3_FALSE;
                clock.driven |= clock.active;
            }
            Ok(Fmi3Status::Ok)
        })
    }
}

/// fmi3GetClock: refused for input clocks (the importer sets them; this layer has no
/// output clocks).
pub unsafe fn get_clock<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    values: *mut Fmi3Clock,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetClock", Call::ClockQuery, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            output_slice(values, nvr, "values[]")?;
            match clocks_of(inst, vrs)?.first() {
                Some(&k) => Err(format!(
                    "\"{}\" is an input clock: the importer sets it with fmi3SetClock; only \
                     output clocks are read",
                    M::CLOCKS[k].name
                )),
                None => Ok(Fmi3Status::Ok),
            }
        })
    }
}

/// The qualifier of a fixed clock's interval (section 2.2.9, table of qualifiers):
/// changed in Initialization Mode (where the importer learns it), unchanged after.
fn qualifier<M: Model>(inst: &Instance<M>) -> Fmi3IntervalQualifier {
    if inst.mode == Mode::InitializationMode {
        FMI3_INTERVAL_CHANGED
    } else {
        FMI3_INTERVAL_UNCHANGED
    }
}

/// fmi3GetIntervalDecimal: the period of each clock, s.
pub unsafe fn get_interval_decimal<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    intervals: *mut Fmi3Float64,
    qualifiers: *mut Fmi3IntervalQualifier,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetIntervalDecimal", Call::ClockQuery, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            let clocks = clocks_of(inst, vrs)?;
            let intervals = output_slice(intervals, nvr, "intervals[]")?;
            let qualifiers = output_slice(qualifiers, nvr, "qualifiers[]")?;
            let q = qualifier(inst);
            for (i, k) in clocks.into_iter().enumerate() {
                let (counter, resolution) = interval(inst.core.model(), k)?;
                intervals[i] = counter as f64 / resolution as f64;
                qualifiers[i] = q;
            }
            Ok(Fmi3Status::Ok)
        })
    }
}

/// fmi3GetIntervalFraction: the period of each clock as counter / resolution, exact.
pub unsafe fn get_interval_fraction<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    counters: *mut Fmi3UInt64,
    resolutions: *mut Fmi3UInt64,
    qualifiers: *mut Fmi3IntervalQualifier,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetIntervalFraction", Call::ClockQuery, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            let clocks = clocks_of(inst, vrs)?;
            let counters = output_slice(counters, nvr, "counters[]")?;
            let resolutions = output_slice(resolutions, nvr, "resolutions[]")?;
            let qualifiers = output_slice(qualifiers, nvr, "qualifiers[]")?;
            let q = qualifier(inst);
            for (i, k) in clocks.into_iter().enumerate() {
                (counters[i], resolutions[i]) = interval(inst.core.model(), k)?;
                qualifiers[i] = q;
            }
            Ok(Fmi3Status::Ok)
        })
    }
}

/// fmi3GetShiftDecimal: 0 s for every clock (tick 0 at the start time).
pub unsafe fn get_shift_decimal<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    shifts: *mut Fmi3Float64,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetShiftDecimal", Call::ClockQuery, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            clocks_of(inst, vrs)?;
            output_slice(shifts, nvr, "shifts[]")?.fill(0.0);
            Ok(Fmi3Status::Ok)
        })
    }
}

/// fmi3GetShiftFraction: 0 / 1 for every clock.
pub unsafe fn get_shift_fraction<M: Model>(
    c: Fmi3Instance,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    counters: *mut Fmi3UInt64,
    resolutions: *mut Fmi3UInt64,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, "fmi3GetShiftFraction", Call::ClockQuery, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            clocks_of(inst, vrs)?;
            output_slice(counters, nvr, "counters[]")?.fill(0);
            output_slice(resolutions, nvr, "resolutions[]")?.fill(1);
            Ok(Fmi3Status::Ok)
        })
    }
}

/// What fmi3SetInterval* / fmi3SetShift* would set, for the message.
pub enum Setting<'a> {
    Decimal(&'a [f64]),
    Fraction(&'a [u64], &'a [u64]),
}

/// fmi3SetIntervalDecimal, fmi3SetIntervalFraction, fmi3SetShiftDecimal and
/// fmi3SetShiftFraction (`what`: "interval" or "shift"): the arguments are checked
/// (a value that could never be an interval is named), then the call is refused: a
/// fixed clock without intervalDecimal takes its interval from its period parameter.
pub unsafe fn set_interval_or_shift<'a, M: Model>(
    c: Fmi3Instance,
    function: &str,
    what: &str,
    vr: *const Fmi3ValueReference,
    nvr: usize,
    setting: impl FnOnce(usize) -> Result<Setting<'a>, String>,
) -> Fmi3Status {
    unsafe {
        with_instance::<M>(c, function, Call::ClockQuery, |inst| {
            let vrs = input_slice(vr, nvr, "valueReferences[]")?;
            let clocks = clocks_of(inst, vrs)?;
            let bad = match setting(nvr)? {
                Setting::Decimal(v) => v
                    .iter()
                    .find(|x| !(x.is_finite() && (**x > 0.0 || (what == "shift" && **x == 0.0))))
                    .map(|x| format!("{x} s")),
                Setting::Fraction(counters, resolutions) => counters
                    .iter()
                    .zip(resolutions)
                    .find(|(n, r)| **r == 0 || (what == "interval" && **n == 0))
                    .map(|(n, r)| format!("{n}/{r} s")),
            };
            if let Some(bad) = bad {
                return Err(format!("the {what} {bad} is not a valid clock {what}"));
            }
            match clocks.first() {
                Some(&k) => {
                    let spec = &M::CLOCKS[k];
                    Err(format!(
                        "\"{}\" is a periodic clock with intervalVariability=\"fixed\": its \
                         {what} is not set by the importer; its interval is the parameter \
                         \"{}\" (set it before fmi3ExitInitializationMode), its shift 0",
                        spec.name, spec.period.name
                    ))
                }
                None => Ok(Fmi3Status::Ok),
            }
        })
    }
}

/// Runs the tick of every clock set in this Event Mode (in the order of
/// `Model::CLOCKS`), then deactivates it. A tick the model cannot evaluate leaves the
/// model as it was and the clock active: Ok(Some(reason)) for fmi3Discard.
pub(super) fn run_ticks<M: Model>(inst: &mut Instance<M>) -> Result<Option<String>, String> {
    for (k, spec) in M::CLOCKS.iter().enumerate() {
        if !inst.extra.clocks.clocks[k].active {
            continue;
        }
        let tick = inst
            .extra
            .clocks
            .tick_at(inst.core.model(), k, inst.core.time)?;
        let before = inst.core.model().clone();
        if let Err(reason) = (spec.tick)(inst.core.model_mut(), &tick, &inst.log) {
            *inst.core.model_mut() = before;
            return Ok(Some(format!(
                "the tick of {} at t = {} s: {reason}",
                spec.name, tick.time
            )));
        }
        inst.extra.clocks.clocks[k].active = false;
        inst.log.debug(
            "logEvents",
            &format!(
                "{} ticked at t = {} s (tick {})",
                spec.name, tick.time, tick.index
            ),
        );
    }
    Ok(None)
}

/// Err when a clock was set but not ticked: Event Mode must not be left before
/// fmi3UpdateDiscreteStates ran its tick (nothing is lost silently).
pub(super) fn check_none_pending<M: Model>(inst: &Instance<M>) -> Result<(), String> {
    match inst.extra.clocks.pending::<M>() {
        Some(name) => Err(format!(
            "{name} was set but fmi3UpdateDiscreteStates has not run its tick: call it \
             before leaving Event Mode"
        )),
        None => Ok(()),
    }
}
