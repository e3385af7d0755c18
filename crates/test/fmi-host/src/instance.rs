//! A live instance of a loaded binary, FMI 2.0 ([`Fmi2Instance`]) and FMI 3.0
//! ([`Fmi3Instance`]): instantiated with the callbacks of [`crate::callbacks`], the
//! calls the tests make, freed when dropped. Statuses stay C ints (a corrupt one is
//! reported, not trusted); a refused call's log is the error text.

use crate::callbacks::{Callbacks, Environment, Log, c_string, logger3, take};
use crate::fmi2::{self, Binary, Component, OK, Status, status_name};
use crate::fmi3::{self, Binary3, Instance3};
use std::ffi::{c_char, c_int, c_void};
use std::sync::Mutex;

/// Err with the call, its status and `log` unless `s` is OK.
pub fn check(what: &str, s: Status, log: &Log) -> Result<(), String> {
    if s == OK {
        Ok(())
    } else {
        Err(format!("{what} returned {}: {}", status_name(s), take(log)))
    }
}

/// fmi2Type.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interface {
    ModelExchange = 0,
    CoSimulation = 1,
}

impl Interface {
    pub const BOTH: [Interface; 2] = [Interface::ModelExchange, Interface::CoSimulation];
    pub fn short(self) -> &'static str {
        match self {
            Interface::ModelExchange => "ME",
            Interface::CoSimulation => "CS",
        }
    }
}

/// States an FMI 2.0 instance can be brought into (FMI 2.0 sections 3.2.3 and 4.2.4).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State {
    Instantiated,
    InitializationMode,
    EventMode,
    ContinuousTimeMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
}

impl State {
    pub const ALL: [State; 8] = [
        State::Instantiated,
        State::InitializationMode,
        State::EventMode,
        State::ContinuousTimeMode,
        State::StepComplete,
        State::StepFailed,
        State::Terminated,
        State::Error,
    ];

    /// Whether the state belongs to the interface's state machine.
    pub fn exists_for(self, interface: Interface) -> bool {
        match self {
            State::EventMode | State::ContinuousTimeMode => interface == Interface::ModelExchange,
            State::StepComplete | State::StepFailed => interface == Interface::CoSimulation,
            _ => true,
        }
    }
}

/// An FMI 2.0 instance of a loaded binary; freed on drop.
pub struct Fmi2Instance<'a> {
    pub binary: &'a Binary,
    pub c: Component,
    pub env: Environment,
}

impl<'a> Fmi2Instance<'a> {
    /// fmi2Instantiate (no resource location, not visible) with the callbacks in
    /// `which`; the log when refused.
    pub fn new(
        binary: &'a Binary,
        name: &str,
        interface: Interface,
        guid: &str,
        which: Callbacks,
        logging_on: bool,
    ) -> Result<Fmi2Instance<'a>, String> {
        let env = Environment::new(which);
        Fmi2Instance::instantiate(binary, name, interface as c_int, guid, env, logging_on)
            .map_err(|env| format!("fmi2Instantiate refused: {}", env.take_log()))
    }

    /// fmi2Instantiate (no resource location, not visible) of fmi2Type `kind`, any
    /// C int, with the callbacks of `env`; `env` back when refused, with its log.
    pub fn instantiate(
        binary: &'a Binary,
        name: &str,
        kind: c_int,
        guid: &str,
        env: Environment,
        logging_on: bool,
    ) -> Result<Fmi2Instance<'a>, Environment> {
        let (name, guid) = (c_string(name), c_string(guid));
        // SAFETY: valid strings and a callback table that outlive the instance.
        let c = unsafe {
            (binary.instantiate)(
                name.as_ptr(),
                kind,
                guid.as_ptr(),
                std::ptr::null(),
                &*env.functions,
                0,
                c_int::from(logging_on),
            )
        };
        if c.is_null() {
            return Err(env);
        }
        Ok(Fmi2Instance { binary, c, env })
    }

    /// Err with the call, its status and the log unless `s` is OK.
    pub fn ok(&self, what: &str, s: Status) -> Result<(), String> {
        check(what, s, &self.env.log)
    }

    /// fmi2SetupExperiment: no tolerance, the start time and the stop time if any.
    pub fn setup_experiment(&self, start: f64, stop: Option<f64>) -> Result<(), String> {
        let defined = c_int::from(stop.is_some());
        let stop = stop.unwrap_or(0.0);
        // SAFETY: a live component, plain values.
        let s = unsafe { (self.binary.setup_experiment)(self.c, 0, 0.0, start, defined, stop) };
        self.ok("fmi2SetupExperiment", s)
    }

    /// fmi2SetupExperiment then fmi2EnterInitializationMode.
    pub fn enter_initialization(&self, start: f64, stop: Option<f64>) -> Result<(), String> {
        self.setup_experiment(start, stop)?;
        // SAFETY: a live component.
        let s = unsafe { (self.binary.enter_initialization_mode)(self.c) };
        self.ok("fmi2EnterInitializationMode", s)
    }

    pub fn set_real(&self, vr: fmi2::Vr, value: f64) -> Status {
        // SAFETY: one value reference and one value.
        unsafe { (self.binary.set_real)(self.c, &vr, 1, &value) }
    }

    pub fn set_reals(&self, vrs: &[fmi2::Vr], values: &[f64]) -> Status {
        assert_eq!(vrs.len(), values.len(), "one value per reference");
        // SAFETY: arrays of equal length.
        unsafe { (self.binary.set_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_ptr()) }
    }

    pub fn get_reals(&self, vrs: &[fmi2::Vr]) -> (Status, Vec<f64>) {
        let mut values = vec![f64::NAN; vrs.len()];
        // SAFETY: arrays of equal length.
        let s =
            unsafe { (self.binary.get_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        (s, values)
    }

    pub fn set_integer(&self, vr: fmi2::Vr, value: c_int) -> Status {
        // SAFETY: one value reference and one value.
        unsafe { (self.binary.set_integer)(self.c, &vr, 1, &value) }
    }

    pub fn set_boolean(&self, vr: fmi2::Vr, value: bool) -> Status {
        let value = c_int::from(value);
        // SAFETY: one value reference and one value.
        unsafe { (self.binary.set_boolean)(self.c, &vr, 1, &value) }
    }

    /// fmi2DoStep from `t` by `h` (noSetFMUStatePriorToCurrentPoint).
    pub fn do_step(&self, t: f64, h: f64) -> Status {
        // SAFETY: plain values.
        unsafe { (self.binary.do_step)(self.c, t, h, 1) }
    }

    /// fmi2GetFMUstate into a new state.
    pub fn get_state(&self) -> (Status, fmi2::FmuState) {
        let mut state = std::ptr::null_mut();
        // SAFETY: a null slot asks for a new state.
        let s = unsafe { (self.binary.get_fmu_state)(self.c, &mut state) };
        (s, state)
    }

    /// Serialized bytes of a state of this instance. The state pointer is only
    /// handed to the FMU (never dereferenced here): checking it is the FMU's job.
    #[allow(clippy::not_unsafe_ptr_arg_deref)]
    pub fn serialize(&self, state: fmi2::FmuState) -> Result<Vec<u8>, String> {
        let mut size = 0usize;
        // SAFETY: a state issued by this instance, a buffer of the announced size.
        unsafe {
            let s = (self.binary.serialized_size)(self.c, state, &mut size);
            self.ok("fmi2SerializedFMUstateSize", s)?;
            let mut bytes = vec![0u8; size];
            let s = (self.binary.serialize)(self.c, state, bytes.as_mut_ptr() as *mut c_char, size);
            self.ok("fmi2SerializeFMUstate", s)?;
            Ok(bytes)
        }
    }

    pub fn free_state(&self, mut state: fmi2::FmuState) -> Status {
        // SAFETY: a state issued by this binary (or a probe's pointer).
        unsafe { (self.binary.free_fmu_state)(self.c, &mut state) }
    }

    /// The log received so far, one line per message, and clears it.
    pub fn take_log(&self) -> String {
        self.env.take_log()
    }
}

impl Drop for Fmi2Instance<'_> {
    fn drop(&mut self) {
        // SAFETY: the component came from this binary's fmi2Instantiate.
        unsafe { (self.binary.free_instance)(self.c) }
    }
}

/// The interfaces of an FMI 3.0 instance. Co-Simulation comes twice: without and
/// with eventModeUsed (then a step that meets an event ends early and the importer
/// handles it in Event Mode).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interface3 {
    ModelExchange,
    CoSimulation,
    CoSimulationEvents,
}

impl Interface3 {
    pub const ALL: [Interface3; 3] = [
        Interface3::ModelExchange,
        Interface3::CoSimulation,
        Interface3::CoSimulationEvents,
    ];
    pub fn short(self) -> &'static str {
        match self {
            Interface3::ModelExchange => "ME",
            Interface3::CoSimulation => "CS",
            Interface3::CoSimulationEvents => "CS+events",
        }
    }
    pub fn is_me(self) -> bool {
        self == Interface3::ModelExchange
    }
    /// The state after fmi3ExitInitializationMode (sections 3.3 and 4.3).
    pub fn after_initialization(self) -> State3 {
        match self {
            Interface3::CoSimulation => State3::StepMode,
            _ => State3::EventMode,
        }
    }
}

/// States an instance can be brought into. `StepDiscarded` is Step Mode after a
/// step returned fmi3Discard (section 4.2.1: then only terminate, FMU-state and
/// get calls remain). Configuration and Reconfiguration Mode do not occur (the
/// models have no structural parameters); Intermediate Update Mode does not occur
/// in the hostile matrix's states (its instances get no intermediate-update callback;
/// the re-entry host passes one, and tests/python/test_intermediate_update.py
/// drives that mode through FMPy).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum State3 {
    Instantiated,
    InitializationMode,
    EventMode,
    ContinuousTimeMode,
    StepMode,
    StepDiscarded,
    Terminated,
    Error,
}

impl State3 {
    pub const ALL: [State3; 8] = [
        State3::Instantiated,
        State3::InitializationMode,
        State3::EventMode,
        State3::ContinuousTimeMode,
        State3::StepMode,
        State3::StepDiscarded,
        State3::Terminated,
        State3::Error,
    ];

    /// Whether the state belongs to the interface's state machine.
    pub fn exists_for(self, interface: Interface3) -> bool {
        match self {
            State3::EventMode => interface != Interface3::CoSimulation,
            State3::ContinuousTimeMode => interface.is_me(),
            State3::StepMode | State3::StepDiscarded => !interface.is_me(),
            _ => true,
        }
    }

    /// The states of `states` that belong to the interface's state machine.
    pub fn of(interface: Interface3, states: &[State3]) -> impl Iterator<Item = State3> + '_ {
        states
            .iter()
            .copied()
            .filter(move |s| s.exists_for(interface))
    }
}

/// fmi3InstantiateModelExchange or fmi3InstantiateCoSimulation (no resource
/// location, not visible, logging on; Co-Simulation with early return exactly when
/// with events, no required intermediate variables) with the environment `env` and
/// the logMessage and intermediateUpdate callbacks given (each may be NULL); null
/// when refused. The pointers are only handed to the FMU.
#[allow(clippy::not_unsafe_ptr_arg_deref)]
pub fn instantiate3(
    binary: &Binary3,
    interface: Interface3,
    name: &str,
    token: &str,
    env: *mut c_void,
    logger: *const c_void,
    intermediate_update: *const c_void,
) -> Instance3 {
    let (name, token) = (c_string(name), c_string(token));
    let null = std::ptr::null();
    let events = u8::from(interface == Interface3::CoSimulationEvents);
    // SAFETY: valid strings; callbacks and environment that outlive the instance.
    unsafe {
        match interface {
            Interface3::ModelExchange => {
                (binary.instantiate_me)(name.as_ptr(), token.as_ptr(), null, 0, 1, env, logger)
            }
            _ => (binary.instantiate_cs)(
                name.as_ptr(),
                token.as_ptr(),
                null,
                0,
                1,
                events,
                events,
                std::ptr::null(),
                0,
                env,
                logger,
                intermediate_update,
            ),
        }
    }
}

/// The outputs of fmi3DoStep.
#[derive(Debug, Default, Clone, Copy)]
pub struct StepOutcome {
    pub status: Status,
    pub event_handling_needed: bool,
    pub terminate: bool,
    pub early_return: bool,
    pub last_successful_time: f64,
}

/// An FMI 3.0 instance of a loaded binary with the keeping logger; freed on drop.
/// The log lives in a box whose address is the instance environment.
pub struct Fmi3Instance<'a> {
    pub binary: &'a Binary3,
    pub c: Instance3,
    pub log: Box<Log>,
}

impl<'a> Fmi3Instance<'a> {
    /// Instantiates `interface` with the keeping logger; the log when refused.
    pub fn new(
        binary: &'a Binary3,
        interface: Interface3,
        name: &str,
        token: &str,
    ) -> Result<Fmi3Instance<'a>, String> {
        let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
        let env = &*log as *const Log as *mut c_void;
        let c = instantiate3(
            binary,
            interface,
            name,
            token,
            env,
            logger3(),
            std::ptr::null(),
        );
        if c.is_null() {
            return Err(format!("fmi3 instantiate refused: {}", take(&log)));
        }
        Ok(Fmi3Instance { binary, c, log })
    }

    /// Err with the call, its status and the log unless `s` is OK.
    pub fn ok(&self, what: &str, s: Status) -> Result<(), String> {
        check(what, s, &self.log)
    }

    /// fmi3EnterInitializationMode: no tolerance, start time 0, no stop time.
    pub fn enter_initialization(&self) -> Result<(), String> {
        // SAFETY: a live instance, plain values.
        let s = unsafe { (self.binary.enter_initialization_mode)(self.c, 0, 0.0, 0.0, 0, 0.0) };
        self.ok("fmi3EnterInitializationMode", s)
    }

    pub fn set_float64(&self, vrs: &[fmi3::Vr], values: &[f64]) -> Status {
        // SAFETY: slices of the given lengths.
        unsafe {
            (self.binary.set_float64)(
                self.c,
                vrs.as_ptr(),
                vrs.len(),
                values.as_ptr(),
                values.len(),
            )
        }
    }

    /// fmi3GetFloat64 of `vrs`, `elements` values in all (arrays count each element).
    pub fn get_float64_elements(&self, vrs: &[fmi3::Vr], elements: usize) -> (Status, Vec<f64>) {
        let mut values = vec![f64::NAN; elements];
        // SAFETY: slices of the given lengths.
        let s = unsafe {
            (self.binary.get_float64)(
                self.c,
                vrs.as_ptr(),
                vrs.len(),
                values.as_mut_ptr(),
                values.len(),
            )
        };
        (s, values)
    }

    /// fmi3DoStep from `t` by `h` (noSetFMUStatePriorToCurrentPoint).
    pub fn do_step(&self, t: f64, h: f64) -> StepOutcome {
        let (mut event, mut stop, mut early) = (0u8, 0u8, 0u8);
        let mut last = f64::NAN;
        // SAFETY: four outputs to fill.
        let status = unsafe {
            (self.binary.do_step)(
                self.c, t, h, 1, &mut event, &mut stop, &mut early, &mut last,
            )
        };
        StepOutcome {
            status,
            event_handling_needed: event != 0,
            terminate: stop != 0,
            early_return: early != 0,
            last_successful_time: last,
        }
    }

    /// fmi3GetFMUState into a new state.
    pub fn get_state(&self) -> (Status, fmi3::FmuState) {
        let mut state = std::ptr::null_mut();
        // SAFETY: a null slot asks for a new state.
        let s = unsafe { (self.binary.get_fmu_state)(self.c, &mut state) };
        (s, state)
    }

    /// Serialized bytes of a state of this instance. The state pointer is only
    /// handed to the FMU (never dereferenced here).
    #[allow(clippy::not_unsafe_ptr_arg_deref)]
    pub fn serialize(&self, state: fmi3::FmuState) -> Result<Vec<u8>, String> {
        let mut size = 0usize;
        // SAFETY: a state issued by this instance, a buffer of the announced size.
        unsafe {
            let s = (self.binary.serialized_size)(self.c, state, &mut size);
            self.ok("fmi3SerializedFMUStateSize", s)?;
            let mut bytes = vec![0u8; size];
            let s = (self.binary.serialize)(self.c, state, bytes.as_mut_ptr(), size);
            self.ok("fmi3SerializeFMUState", s)?;
            Ok(bytes)
        }
    }

    /// fmi3DeserializeFMUState of `bytes` into a new state.
    pub fn deserialize(&self, bytes: &[u8]) -> (Status, fmi3::FmuState) {
        let mut state: fmi3::FmuState = std::ptr::null_mut();
        // SAFETY: a buffer of the given length and a null slot for a new state.
        let s =
            unsafe { (self.binary.deserialize)(self.c, bytes.as_ptr(), bytes.len(), &mut state) };
        (s, state)
    }

    pub fn free_state(&self, mut state: fmi3::FmuState) -> Status {
        // SAFETY: a state issued by this binary (or a probe's pointer).
        unsafe { (self.binary.free_fmu_state)(self.c, &mut state) }
    }

    /// The log received so far, one line per message, and clears it.
    pub fn take_log(&self) -> String {
        take(&self.log)
    }
}

impl Drop for Fmi3Instance<'_> {
    fn drop(&mut self) {
        // SAFETY: the instance came from this binary.
        unsafe { (self.binary.free_instance)(self.c) }
    }
}
