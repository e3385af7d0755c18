//! Clocked partitions through the FMI 3.0 functions (`fmi3::api`, as the exported
//! symbols call them) on a toy sampled model: an accumulator s_k+1 = s_k + Ts x_k
//! ticked by a periodic input clock. Expected values: the recursion itself (the
//! discrete integral of a held input is exact: s_n = n Ts x for a constant x), the
//! tick times k counter / resolution of FMI 3.0 section 2.2.9, and the state machine
//! and argument rules of the same section (fmi3SetClock only in Event Mode, only at a
//! tick; a fixed clock's interval read in Initialization Mode).

use robofmu_fmi::fmi3::api::{self, DiscreteStatesUpdate, StepResult};
use robofmu_fmi::fmi3::mode::Interface;
use robofmu_fmi::fmi3::types::*;
use robofmu_fmi::prelude::*;
mod support;

use support::{instantiate, last_message};

#[derive(Clone, Default)]
struct Accumulator {
    x: f64,
    sum: f64,
    ticks: f64,
    period: f64,
}

type Decl = Declaration<Accumulator>;

static VARIABLES: &[Decl] = &[Decl::real_in("x", |m, _| &mut m.x)
    .describe("input")
    .input()
    .start_real(&[2.0])
    .at(1)];
static OUTPUTS: &[ClockedOutput<Accumulator>] = &[
    ClockedOutput::new("sum", 12, "sum of Ts x", |m: &Accumulator, _| m.sum),
    ClockedOutput::new("ticks", 13, "ticks so far", |m: &Accumulator, _| m.ticks),
];
static CLOCKS: &[InputClock<Accumulator>] = &[InputClock::new(
    "sampleClock",
    10,
    "ticks the accumulator",
    PeriodParameter::new(
        "samplePeriod",
        11,
        "sample period, s",
        0.001,
        (
            |m: &Accumulator| m.period,
            |m: &mut Accumulator, p| m.period = p,
        ),
    ),
    OUTPUTS,
    |m, tick, _| {
        if !m.x.is_finite() || m.x.abs() > 1e6 {
            return Err(format!("x = {} is out of range", m.x));
        }
        m.sum += tick.period * m.x;
        m.ticks += 1.0;
        Ok(())
    },
)];
static INFO: ModelInfo = ModelInfo::new(
    "Accumulator",
    "{6c1d0d2e-8a44-4f5e-9d55-2b8f3c1a7e01}",
    "sampled accumulator",
    [0.0, 10.0, 1e-6, 0.001],
);

impl Model for Accumulator {
    const INFO: &'static ModelInfo = &INFO;
    const VARIABLES: &'static [Declaration<Self>] = VARIABLES;
    const CLOCKS: &'static [InputClock<Self>] = CLOCKS;
    fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> {
        Ok(())
    }
}

const CLOCK: u32 = 10;
const PERIOD: u32 = 11;
const SUM: u32 = 12;
const TICKS: u32 = 13;

struct Fmu(Fmi3Instance);

impl Fmu {
    fn new(interface: Interface) -> Fmu {
        Fmu(instantiate::<Accumulator>(
            interface,
            c"{6c1d0d2e-8a44-4f5e-9d55-2b8f3c1a7e01}",
        ))
    }

    fn co_simulation(early_return_allowed: bool) -> Fmu {
        Fmu::new(Interface::CoSimulation {
            event_mode_used: true,
            early_return_allowed,
        })
    }

    fn initialize(&self, start: f64) -> Fmi3Status {
        let s =
            unsafe { api::enter_initialization_mode::<Accumulator>(self.0, 0, 0.0, start, 0, 0.0) };
        assert_eq!(s, Fmi3Status::Ok);
        unsafe { api::exit_initialization_mode::<Accumulator>(self.0) }
    }

    fn real(&self, vr: u32) -> f64 {
        let mut v = f64::NAN;
        let s = unsafe { api::get_float64::<Accumulator>(self.0, &vr, 1, &mut v, 1) };
        assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
        v
    }

    fn set_real(&self, vr: u32, v: f64) -> Fmi3Status {
        unsafe { api::set_float64::<Accumulator>(self.0, &vr, 1, &v, 1) }
    }

    fn set_clock(&self, vr: u32, on: bool) -> Fmi3Status {
        let value = fmi3_bool(on);
        unsafe { api::set_clock::<Accumulator>(self.0, &vr, 1, &value) }
    }

    fn update(&self) -> Fmi3Status {
        let (mut a, mut b, mut c, mut d, mut e, mut f) = (0, 0, 0, 0, 0, 0.0);
        unsafe {
            api::update_discrete_states::<Accumulator>(
                self.0,
                DiscreteStatesUpdate {
                    discrete_states_need_update: &mut a,
                    terminate_simulation: &mut b,
                    nominals_changed: &mut c,
                    values_changed: &mut d,
                    next_event_time_defined: &mut e,
                    next_event_time: &mut f,
                },
            )
        }
    }

    /// One tick in Event Mode: set the clock, update.
    fn tick(&self) {
        assert_eq!(
            self.set_clock(CLOCK, true),
            Fmi3Status::Ok,
            "{}",
            last_message()
        );
        assert_eq!(self.update(), Fmi3Status::Ok, "{}", last_message());
    }

    /// fmi3DoStep: (status, eventHandlingNeeded, earlyReturn, lastSuccessfulTime).
    fn step(&self, t: f64, h: f64) -> (Fmi3Status, bool, bool, f64) {
        let (mut event, mut terminate, mut early, mut last) = (0, 0, 0, f64::NAN);
        let s = unsafe {
            api::do_step::<Accumulator>(
                self.0,
                t,
                h,
                FMI3_TRUE,
                StepResult {
                    event_handling_needed: &mut event,
                    terminate_simulation: &mut terminate,
                    early_return: &mut early,
                    last_successful_time: &mut last,
                },
            )
        };
        (s, event != 0, early != 0, last)
    }

    fn interval_fraction(&self) -> (Fmi3Status, u64, u64, Fmi3IntervalQualifier) {
        let (mut n, mut r, mut q) = (0u64, 0u64, -1);
        let s = unsafe {
            api::get_interval_fraction::<Accumulator>(self.0, &CLOCK, 1, &mut n, &mut r, &mut q)
        };
        (s, n, r, q)
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        unsafe { api::free_instance::<Accumulator>(self.0) }
    }
}

#[test]
fn co_simulation_steps_end_at_the_ticks_and_return_early_there() {
    let fmu = Fmu::co_simulation(true);
    assert_eq!(fmu.set_real(PERIOD, 0.0025), Fmi3Status::Ok);
    unsafe { api::enter_initialization_mode::<Accumulator>(fmu.0, 0, 0.0, 0.0, 0, 0.0) };
    // A fixed clock's interval, read in Initialization Mode: changed, 25/10000 s.
    assert_eq!(
        fmu.interval_fraction(),
        (Fmi3Status::Ok, 25, 10000, FMI3_INTERVAL_CHANGED)
    );
    assert_eq!(
        unsafe { api::exit_initialization_mode::<Accumulator>(fmu.0) },
        Fmi3Status::Ok
    );
    assert_eq!(fmu.interval_fraction().3, FMI3_INTERVAL_UNCHANGED);
    fmu.tick(); // tick 0 at t = 0
    assert_eq!(
        unsafe { api::enter_step_mode::<Accumulator>(fmu.0) },
        Fmi3Status::Ok
    );
    // Steps of 1 ms: the third passes the tick at 2.5 ms and returns early there.
    let mut t = 0.0;
    let mut seen = Vec::new();
    for _ in 0..8 {
        let (s, event, early, last) = fmu.step(t, 0.001);
        assert_eq!(s, Fmi3Status::Ok, "{}", last_message());
        seen.push((event, early, last));
        t = last;
        if event {
            unsafe { api::enter_event_mode::<Accumulator>(fmu.0) };
            fmu.tick();
            unsafe { api::enter_step_mode::<Accumulator>(fmu.0) };
        }
    }
    // Expected: ticks at 2.5 ms and 5 ms (k 25 / 10000, exact), steps restart there
    // (their ends t + h as the importer's arithmetic gives them).
    let (a, b) = (0.0025, 0.005);
    assert_eq!(
        seen,
        vec![
            (false, false, 0.001),
            (false, false, 0.002),
            (true, true, a),
            (false, false, a + 0.001),
            (false, false, a + 0.001 + 0.001),
            (true, true, b),
            (false, false, b + 0.001),
            (false, false, b + 0.001 + 0.001),
        ]
    );
    // Three ticks (0, 2.5 ms, 5 ms) of x = 2: s = 3 Ts x.
    assert_eq!(fmu.real(TICKS), 3.0);
    assert_eq!(fmu.real(SUM), 3.0 * 0.0025 * 2.0);
}

#[test]
fn without_early_return_a_step_past_a_tick_is_refused_and_steps_to_it_are_exact() {
    let fmu = Fmu::co_simulation(false);
    assert_eq!(fmu.initialize(0.0), Fmi3Status::Ok);
    fmu.tick();
    unsafe { api::enter_step_mode::<Accumulator>(fmu.0) };
    let (s, ..) = fmu.step(0.0, 0.0015);
    assert_eq!(s, Fmi3Status::Error);
    assert!(
        last_message().contains("passes the clock tick at t = 0.001 s"),
        "{}",
        last_message()
    );
    // The importer's time summed in steps of 1 ms drifts from the ticks (3 sums of
    // 0.001 are 0.0030000000000000005); each step still ends exactly at its tick.
    let fmu = Fmu::co_simulation(false);
    fmu.initialize(0.0);
    fmu.tick();
    unsafe { api::enter_step_mode::<Accumulator>(fmu.0) };
    let mut t = 0.0f64;
    for k in 1..=2000u32 {
        let (s, event, early, last) = fmu.step(t, 0.001);
        assert_eq!(
            (s, event, early),
            (Fmi3Status::Ok, true, false),
            "{}",
            last_message()
        );
        assert_eq!(last, f64::from(k) / 1000.0);
        t += 0.001; // the importer's own sum
        unsafe { api::enter_event_mode::<Accumulator>(fmu.0) };
        fmu.tick();
        unsafe { api::enter_step_mode::<Accumulator>(fmu.0) };
    }
    assert_ne!(t, 2.0);
    assert_eq!(fmu.real(TICKS), 2001.0);
    // s = sum of 2001 ticks of 0.001 * 2 (exact recursion, summed in order).
    let expected = (0..2001).fold(0.0, |s: f64, _| s + 0.001 * 2.0);
    assert_eq!(fmu.real(SUM), expected);
}

#[test]
fn model_exchange_ticks_where_the_importer_sets_the_clock_and_only_at_ticks() {
    let fmu = Fmu::new(Interface::ModelExchange);
    assert_eq!(fmu.initialize(0.0), Fmi3Status::Ok);
    fmu.tick();
    let enter_ct = || unsafe { api::enter_continuous_time_mode::<Accumulator>(fmu.0) };
    assert_eq!(enter_ct(), Fmi3Status::Ok);
    // Tick 10^6 at 1 ms is t = 1000 s exactly (10^6 / 1000); the importer that summed
    // 0.001 10^6 times is 1.7e-8 s off and is refused, as is a time 1e-12 s away.
    let summed = (0..1_000_000).fold(0.0f64, |t, _| t + 0.001);
    for (t, ok) in [(summed, false), (1000.0 - 1e-9, false), (1000.0, true)] {
        let fmu = Fmu::new(Interface::ModelExchange);
        fmu.initialize(0.0);
        fmu.tick();
        unsafe { api::enter_continuous_time_mode::<Accumulator>(fmu.0) };
        unsafe { api::set_time::<Accumulator>(fmu.0, t) };
        unsafe { api::enter_event_mode::<Accumulator>(fmu.0) };
        let s = fmu.set_clock(CLOCK, true);
        assert_eq!(s == Fmi3Status::Ok, ok, "t = {t}: {}", last_message());
        if !ok {
            assert!(
                last_message().contains("is not a tick of sampleClock"),
                "{}",
                last_message()
            );
        }
    }
    // The clock set outside Event Mode is refused (Continuous-Time Mode).
    assert_eq!(fmu.set_clock(CLOCK, true), Fmi3Status::Error);
    assert!(
        last_message().contains("fmi3SetClock"),
        "{}",
        last_message()
    );
}

#[test]
fn bad_clock_arguments_are_refused_with_a_message_and_change_nothing() {
    for bad in [0.0, -0.001, f64::NAN, 1e300] {
        let fmu = Fmu::co_simulation(true);
        assert_eq!(fmu.set_real(PERIOD, bad), Fmi3Status::Error, "{bad}");
        assert!(
            last_message().contains("samplePeriod"),
            "{}",
            last_message()
        );
    }
    let fmu = Fmu::co_simulation(true);
    assert_eq!(fmu.initialize(0.0), Fmi3Status::Ok);
    assert_eq!(fmu.real(PERIOD), 0.001);
    // An unknown value reference, a variable that is no clock.
    assert_eq!(fmu.set_clock(99, true), Fmi3Status::Error);
    assert!(
        last_message().contains("unknown value reference 99"),
        "{}",
        last_message()
    );
    let fmu = Fmu::co_simulation(true);
    fmu.initialize(0.0);
    assert_eq!(fmu.set_clock(SUM, true), Fmi3Status::Error);
    assert!(last_message().contains("not a Clock"), "{}", last_message());
    // Setting the interval of a fixed clock: refused, naming the parameter; an
    // interval of 0 or NaN named as such.
    for (value, says) in [
        (0.002, "samplePeriod"),
        (0.0, "not a valid"),
        (f64::NAN, "not a valid"),
    ] {
        let fmu = Fmu::co_simulation(true);
        unsafe { api::enter_initialization_mode::<Accumulator>(fmu.0, 0, 0.0, 0.0, 0, 0.0) };
        let values = [value];
        let s = unsafe {
            api::set_interval_or_shift::<Accumulator>(
                fmu.0,
                "fmi3SetIntervalDecimal",
                "interval",
                &CLOCK,
                1,
                |_| Ok(api::Setting::Decimal(&values)),
            )
        };
        assert_eq!(s, Fmi3Status::Error);
        assert!(last_message().contains(says), "{}", last_message());
    }
    // Leaving Event Mode with a clock set but not ticked is refused: the tick is not
    // lost silently.
    let fmu = Fmu::co_simulation(true);
    fmu.initialize(0.0);
    assert_eq!(fmu.set_clock(CLOCK, true), Fmi3Status::Ok);
    assert_eq!(
        unsafe { api::enter_step_mode::<Accumulator>(fmu.0) },
        Fmi3Status::Error
    );
    assert!(
        last_message().contains("fmi3UpdateDiscreteStates"),
        "{}",
        last_message()
    );
    // A tick the model cannot evaluate: fmi3Discard, the model unchanged.
    let fmu = Fmu::co_simulation(true);
    let on =
        unsafe { api::set_debug_logging::<Accumulator>(fmu.0, FMI3_TRUE, 0, std::ptr::null()) };
    assert_eq!(on, Fmi3Status::Ok);
    fmu.initialize(0.0);
    assert_eq!(fmu.set_real(1, 1e9), Fmi3Status::Ok);
    assert_eq!(fmu.set_clock(CLOCK, true), Fmi3Status::Ok);
    assert_eq!(fmu.update(), Fmi3Status::Discard);
    assert!(
        last_message().contains("out of range"),
        "{}",
        last_message()
    );
    assert_eq!((fmu.real(SUM), fmu.real(TICKS)), (0.0, 0.0));
}

#[test]
fn an_importer_that_never_sets_the_clock_steps_across_the_ticks() {
    // With event mode but without ever setting the clock (an importer that runs the
    // continuous form only), steps are not cut at ticks and nothing ticks.
    let fmu = Fmu::co_simulation(false);
    assert_eq!(fmu.initialize(0.0), Fmi3Status::Ok);
    unsafe { api::enter_step_mode::<Accumulator>(fmu.0) };
    assert_eq!(
        fmu.step(0.0, 0.0155),
        (Fmi3Status::Ok, false, false, 0.0155)
    );
    assert_eq!((fmu.real(SUM), fmu.real(TICKS)), (0.0, 0.0));
}
