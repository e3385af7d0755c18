//! Clocked partitions (FMI 3.0 only): what a model declares to run a sampled law on
//! an input clock. A model lists its clocks in [`Model::CLOCKS`](crate::core::model::Model::CLOCKS);
//! each [`InputClock`] is a periodic input clock (`intervalVariability="fixed"`, no
//! `intervalDecimal`: the importer reads the interval with fmi3GetIntervalDecimal or
//! fmi3GetIntervalFraction in Initialization Mode), its interval the FMI 3.0 parameter
//! [`PeriodParameter`] (fixed, read as the decimal it prints as, so 0.001 s is the
//! fraction 1/1000 and tick k falls at start + k counter / resolution exactly), the
//! outputs that belong to it ([`ClockedOutput`], `clocks="..."`: discrete, held
//! between ticks) and the hook the layer runs at a tick (in Event Mode, by
//! fmi3UpdateDiscreteStates after fmi3SetClock).
//!
//! None of these variables exists in FMI 2.0 (which has no clocks), nor in the
//! scalar-only FMI 3.0 view (for importers that refuse clocks): those descriptions and
//! their behaviour do not change when a model gains a clocked partition. The
//! model keeps the period and what its law holds between ticks (cloned with the model
//! into FMU states; serialized with
//! [`Model::write_extra_state`](crate::core::model::Model::write_extra_state)).
//!
//! A clocked partition in a binding (the model's own law at `tick`, its held output
//! read by `get`):
//!
//! ```
//! use robofmu_fmi::prelude::*;
//!
//! #[derive(Clone, Default)]
//! pub struct Counter { ticks: f64, period: f64 }
//!
//! static OUTPUTS: &[ClockedOutput<Counter>] = &[ClockedOutput::new(
//!     "ticks", 12, "ticks counted", |m, _| m.ticks,
//! )];
//! static CLOCKS: &[InputClock<Counter>] = &[InputClock::new(
//!     "sampleClock",
//!     10,
//!     "ticks the counter",
//!     PeriodParameter::new(
//!         "samplePeriod", 11, "sample period", 0.001,
//!         (|m: &Counter| m.period, |m: &mut Counter, p| m.period = p),
//!     ),
//!     OUTPUTS,
//!     |m, _tick, _log| { m.ticks += 1.0; Ok(()) },
//! )];
//! # static INFO: ModelInfo = ModelInfo::new("Counter", "{0}", "", [0.0, 1.0, 1e-6, 0.1]);
//! impl Model for Counter {
//!     const INFO: &'static ModelInfo = &INFO;
//!     const VARIABLES: &'static [Declaration<Self>] = &[];
//!     const CLOCKS: &'static [InputClock<Self>] = CLOCKS;
//!     fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> { Ok(()) }
//! }
//! ```

use super::log::Log;

/// What the layer tells the model at a tick.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Tick {
    /// The tick's time, s: start + index counter / resolution.
    pub time: f64,
    /// The tick's index k (0: the start time).
    pub index: u64,
    /// The clock's period, s (counter / resolution as a double).
    pub period: f64,
}

/// The hook run at a tick: the model's law on its inputs now; an error (the law cannot
/// be evaluated here) leaves the model as it was, and fmi3UpdateDiscreteStates returns
/// fmi3Discard with the reason.
pub type TickHook<M> = fn(&mut M, &Tick, &dyn Log) -> Result<(), String>;

/// Where a model keeps a clock's period: its reader and its writer.
pub type PeriodAccess<M> = (fn(&M) -> f64, fn(&mut M, f64));

/// How FMU states carry what a clock's law holds between ticks (its state, its held
/// outputs): a writer that appends it (with [`write_held`]) and a reader that reads it
/// back and checks it (with [`read_held`]).
pub type HeldAccess<M> = (
    fn(&M, &mut Vec<u8>),
    fn(&mut M, &[u8]) -> Result<(), String>,
);

/// The fixed Float64 parameter that sets a clock's period, s (FMI 3.0 only), kept by
/// the model (so that FMU states carry it: the model serializes it in
/// [`Model::write_extra_state`](crate::core::model::Model::write_extra_state) and checks it with
/// [`period_fraction`] when it reads it back); the layer checks a value before `set`.
pub struct PeriodParameter<M: 'static> {
    pub name: &'static str,
    pub value_reference: u32,
    pub description: &'static str,
    /// The start value, s (the layer sets it at instantiation and reset).
    pub start: f64,
    pub get: fn(&M) -> f64,
    pub set: fn(&mut M, f64),
}

impl<M> PeriodParameter<M> {
    pub const fn new(
        name: &'static str,
        value_reference: u32,
        description: &'static str,
        start: f64,
        (get, set): PeriodAccess<M>,
    ) -> Self {
        PeriodParameter {
            name,
            value_reference,
            description,
            start,
            get,
            set,
        }
    }
}

/// A Float64 output (scalar or array) of a clock: discrete, computed at the ticks
/// and held between them (FMI 3.0 only).
pub struct ClockedOutput<M: 'static> {
    pub name: &'static str,
    pub value_reference: u32,
    pub description: &'static str,
    /// `Some(n)`: an array of n elements.
    pub length: Option<usize>,
    /// `Some(k)`: the array's size is the structural parameter `Model::STRUCTURAL[k]`
    /// (`length` its default), as a resizable family's arrays.
    pub sized_by: Option<usize>,
    pub unit: Option<&'static str>,
    /// Element i of the held value.
    pub get: fn(&M, usize) -> f64,
}

impl<M> ClockedOutput<M> {
    /// A scalar output without a unit.
    pub const fn new(
        name: &'static str,
        value_reference: u32,
        description: &'static str,
        get: fn(&M, usize) -> f64,
    ) -> Self {
        ClockedOutput {
            name,
            value_reference,
            description,
            length: None,
            sized_by: None,
            unit: None,
            get,
        }
    }

    /// An array of n elements.
    pub const fn array(mut self, n: usize) -> Self {
        self.length = Some(n);
        self
    }

    /// An array sized by the structural parameter `Model::STRUCTURAL[k]`, whose start
    /// is its length.
    pub const fn sized_by(mut self, k: usize) -> Self {
        assert!(
            self.length.is_some(),
            "only an array is sized by a structural parameter"
        );
        self.sized_by = Some(k);
        self
    }

    pub const fn unit(mut self, unit: &'static str) -> Self {
        self.unit = Some(unit);
        self
    }

    /// Number of scalar values (1 for a scalar).
    pub fn size(&self) -> usize {
        self.length.unwrap_or(1)
    }
}

/// A periodic input clock with its period parameter, its outputs and its tick hook
/// (see the module documentation).
pub struct InputClock<M: 'static> {
    pub name: &'static str,
    pub value_reference: u32,
    pub description: &'static str,
    pub period: PeriodParameter<M>,
    pub outputs: &'static [ClockedOutput<M>],
    pub tick: TickHook<M>,
    /// What the law holds between ticks, for FMU states ([`InputClock::holding`]).
    pub held: Option<HeldAccess<M>>,
}

impl<M> InputClock<M> {
    /// The clock `name` at `value_reference`, ticking `tick` every `period`, with its
    /// `outputs`.
    pub const fn new(
        name: &'static str,
        value_reference: u32,
        description: &'static str,
        period: PeriodParameter<M>,
        outputs: &'static [ClockedOutput<M>],
        tick: TickHook<M>,
    ) -> Self {
        InputClock {
            name,
            value_reference,
            description,
            period,
            outputs,
            tick,
            held: None,
        }
    }

    /// The clock of a sampled law, as both controllers declare it: `sampleClock` at
    /// `value_reference`, periodic every `samplePeriod` seconds (the fixed parameter at
    /// the next value reference, default 1 ms, kept where `period` says), ticking
    /// `tick`, with its `outputs`.
    pub const fn sample_clock(
        value_reference: u32,
        period: PeriodAccess<M>,
        outputs: &'static [ClockedOutput<M>],
        tick: TickHook<M>,
    ) -> Self {
        let description = "Sample period of the sampled law, s (a decimal of at most 18 places)";
        InputClock::new(
            "sampleClock",
            value_reference,
            "Ticks the sampled law: periodic, every samplePeriod seconds from the start time",
            PeriodParameter::new(
                "samplePeriod",
                value_reference + 1,
                description,
                1e-3,
                period,
            ),
            outputs,
            tick,
        )
    }

    /// The clock whose law holds what `held` writes and reads: a model that keeps the
    /// default extra FMU state ([`Model::write_extra_state`](crate::core::model::Model::write_extra_state))
    /// then needs no code of its own to carry its clocked partitions in FMU states
    /// ([`write_partitions`]).
    pub const fn holding(mut self, held: HeldAccess<M>) -> Self {
        self.held = Some(held);
        self
    }
}

/// The default extra FMU state of a model: per clock of `clocks` (the model's
/// `CLOCKS`), its period (f64)
/// and, where the clock declares it ([`InputClock::holding`]), the length (u64) and
/// the bytes of what its law holds. Nothing for a model without clocks.
pub fn write_partitions<M>(clocks: &[InputClock<M>], model: &M, out: &mut Vec<u8>) {
    for clock in clocks {
        write_held(out, [(clock.period.get)(model)]);
        if let Some((write, _)) = clock.held {
            let mut bytes = Vec::new();
            write(model, &mut bytes);
            out.extend_from_slice(&(bytes.len() as u64).to_le_bytes());
            out.extend_from_slice(&bytes);
        }
    }
}

/// The first n bytes of `rest` (and `rest` after them), or why not (`what` names them).
fn take<'a>(rest: &mut &'a [u8], n: usize, what: &str) -> Result<&'a [u8], String> {
    if rest.len() < n {
        return Err(format!(
            "\"{what}\": the FMU state ends before its {n} bytes"
        ));
    }
    let (head, tail) = rest.split_at(n);
    *rest = tail;
    Ok(head)
}

/// Reads back what [`write_partitions`] wrote: each period checked as its setter
/// checks it, each law's bytes by its reader; Err names what is wrong (truncated,
/// longer than the clocks' state, a period or value refused).
pub fn read_partitions<M>(
    clocks: &[InputClock<M>],
    model: &mut M,
    bytes: &[u8],
) -> Result<(), String> {
    let mut rest = bytes;
    for clock in clocks {
        let what = clock.period.name;
        let period = f64::from_le_bytes(take(&mut rest, 8, what)?.try_into().expect("8 bytes"));
        period_fraction(period, what)?;
        (clock.period.set)(model, period);
        if let Some((_, read)) = clock.held {
            let length = take(&mut rest, 8, clock.name)?.try_into().expect("8 bytes");
            let length = usize::try_from(u64::from_le_bytes(length)).unwrap_or(usize::MAX);
            read(model, take(&mut rest, length, clock.name)?)?;
        }
    }
    match rest.len() {
        0 => Ok(()),
        n => Err(format!("{n} bytes beyond the state of the model's clocks")),
    }
}

/// Appends `values` to a model's extra FMU state
/// ([`Model::write_extra_state`](crate::core::model::Model::write_extra_state)) as little-endian
/// doubles: what a sampled law holds between ticks (its state, held outputs, period).
pub fn write_held(out: &mut Vec<u8>, values: impl IntoIterator<Item = f64>) {
    for x in values {
        out.extend_from_slice(&x.to_le_bytes());
    }
}

/// Reads back the N doubles [`write_held`] wrote, each finite; Err names them (`what`)
/// and says what is wrong (length, a value that is not finite).
pub fn read_held<const N: usize>(bytes: &[u8], what: &str) -> Result<[f64; N], String> {
    if bytes.len() != 8 * N {
        let n = bytes.len();
        return Err(format!(
            "{what}: {n} bytes, {} ({N} doubles) expected",
            8 * N
        ));
    }
    let mut values = [0.0; N];
    for (v, b) in values.iter_mut().zip(bytes.chunks_exact(8)) {
        *v = f64::from_le_bytes(b.try_into().expect("chunks of 8 bytes"));
    }
    match values.iter().find(|x| !x.is_finite()) {
        Some(bad) => Err(format!("{what}: a value is {bad}")),
        None => Ok(values),
    }
}

/// Largest resolution of a clock interval, ticks per second (10^18, within u64).
const MAX_RESOLUTION: u64 = 1_000_000_000_000_000_000;

/// `period` (s) as counter / resolution, read from the shortest decimal that reads back
/// as the same double (0.001 -> 1/1000), so that the period written is the one ticked;
/// Err with the reason (named `what`) for a period that is not a positive finite
/// number or whose decimal needs more than 18 places or a counter beyond 64 bits.
pub fn period_fraction(period: f64, what: &str) -> Result<(u64, u64), String> {
    if !(period.is_finite() && period > 0.0) {
        return Err(format!(
            "\"{what}\" = {period}: a clock period must be a positive finite number of seconds"
        ));
    }
    // Display prints the shortest round-trip decimal, without an exponent.
    let text = period.to_string();
    let (whole, fraction) = text.split_once('.').unwrap_or((&text, ""));
    let resolution = u32::try_from(fraction.len())
        .ok()
        .and_then(|d| 10u64.checked_pow(d))
        .filter(|&r| r <= MAX_RESOLUTION);
    let counter = format!("{whole}{fraction}").parse::<u64>().ok();
    match (counter, resolution) {
        (Some(c), Some(r)) if c > 0 => Ok((c, r)),
        _ => Err(format!(
            "\"{what}\" = {period} s cannot be a clock interval: it must be a whole number of \
             1e-18 s below 1.8e19 (64-bit counter / resolution)"
        )),
    }
}

/// Time of tick k of a clock of interval counter / resolution from `start`: the exact
/// product k counter (128 bits) over the resolution, one rounding; no drift over
/// the ticks.
pub fn tick_time(start: f64, (counter, resolution): (u64, u64), k: u64) -> f64 {
    start + (u128::from(k) * u128::from(counter)) as f64 / resolution as f64
}

/// The tick of `interval` from `start` that `t` falls on (within 1e-9 of a period,
/// rounding of the importer's time arithmetic), if any.
pub fn tick_at(start: f64, interval: (u64, u64), t: f64) -> Option<u64> {
    let period = interval.0 as f64 / interval.1 as f64;
    let k = ((t - start) / period).round();
    if !(k.is_finite() && k >= 0.0 && k < u64::MAX as f64) {
        return None;
    }
    let k = k as u64;
    ((tick_time(start, interval, k) - t).abs() <= 1e-9 * period).then_some(k)
}

/// The first tick strictly after `t` (a tick within the tolerance of [`tick_at`]
/// counts as at `t`, not after it): (k, its time).
pub fn next_tick(start: f64, interval: (u64, u64), t: f64) -> Option<(u64, f64)> {
    let period = interval.0 as f64 / interval.1 as f64;
    let guess = ((t - start) / period).floor().max(0.0);
    if !(guess.is_finite() && guess < (u64::MAX - 2) as f64) {
        return None;
    }
    let mut k = guess as u64;
    if let Some(at) = tick_at(start, interval, t) {
        k = at + 1;
    }
    while tick_time(start, interval, k) <= t {
        k += 1;
    }
    Some((k, tick_time(start, interval, k)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_periods_are_exact_fractions() {
        // Expected values: the decimals as written (0.001 = 1/1000, 0.0025 = 25/10000).
        assert_eq!(period_fraction(0.001, "p"), Ok((1, 1000)));
        assert_eq!(period_fraction(0.0025, "p"), Ok((25, 10000)));
        assert_eq!(period_fraction(2.0, "p"), Ok((2, 1)));
        for bad in [0.0, -0.001, f64::NAN, f64::INFINITY, 1e300, 1e-19] {
            let e = period_fraction(bad, "samplePeriod").unwrap_err();
            assert!(e.contains("samplePeriod"), "{e}");
        }
    }

    #[test]
    fn a_million_ticks_at_1_ms_land_on_the_decimal_times() {
        // Expected value: tick k of 1/1000 s is the double nearest k / 1000 (the
        // integer k over 1000, correctly rounded); summing 0.001 a million times
        // misses 1000 s by 1.7e-8 s, the counter does not.
        let i = (1, 1000);
        for k in [1u64, 3, 999_999, 1_000_000] {
            assert_eq!(tick_time(0.0, i, k), k as f64 / 1000.0);
        }
        assert_eq!(tick_time(0.0, i, 1_000_000), 1000.0);
        let summed = (0..1_000_000).fold(0.0f64, |t, _| t + 0.001);
        assert!((summed - 1000.0).abs() > 1e-9);
        // The summed time is within the tolerance of tick 10^6: the tick is found.
        assert_eq!(tick_at(0.0, i, 1000.0), Some(1_000_000));
        assert_eq!(tick_at(0.0, i, 0.0015), None);
        assert_eq!(next_tick(0.0, i, 0.0), Some((1, 0.001)));
        assert_eq!(next_tick(0.0, i, 0.0015), Some((2, 0.002)));
        assert_eq!(next_tick(0.0, i, 999.9995), Some((1_000_000, 1000.0)));
        // A time a rounding away from a tick is at that tick: the next one follows.
        assert_eq!(next_tick(0.0, i, 0.30000000000000004), Some((301, 0.301)));
    }

    #[test]
    fn held_values_round_trip_and_bad_bytes_are_refused() {
        // Expected values: the doubles written, bit for bit; 8 bytes per double.
        let mut out = Vec::new();
        write_held(&mut out, [1.5, -0.0, 1e-300]);
        assert_eq!(out.len(), 24);
        let back: [f64; 3] = read_held(&out, "held").unwrap();
        assert_eq!(
            back.map(f64::to_bits),
            [1.5, -0.0, 1e-300].map(f64::to_bits)
        );
        let short = read_held::<3>(&out[..16], "the law's state").unwrap_err();
        assert!(short.contains("the law's state: 16 bytes, 24"), "{short}");
        write_held(&mut out, [f64::NAN]);
        let nan = read_held::<4>(&out, "held").unwrap_err();
        assert!(nan.contains("NaN"), "{nan}");
    }
}
