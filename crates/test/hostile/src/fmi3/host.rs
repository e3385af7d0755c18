//! The importer's side of an FMI 3.0 instance: the (non-variadic) log-message
//! callback, fmi3InstantiateModelExchange / fmi3InstantiateCoSimulation through the
//! loaded binary, and the calls that bring an instance into each state of the FMI
//! 3.0 state machines (sections 3.3 and 4.3 of the standard).

use super::binary::{Binary3, FmuState, Instance3 as Handle, Vr};
use crate::binary::{DISCARD, ERROR, Status, status_name};
use crate::description::Description;
use crate::host::{Log, Probed, c_string, record, take};
use std::ffi::{c_char, c_int, c_void};
use std::sync::Mutex;

/// The interfaces an instance can be created for. Co-Simulation comes twice:
/// without and with eventModeUsed (then a step that meets an event ends early and
/// the importer handles it in Event Mode).
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
/// here because this importer passes no intermediate-update callback (that mode is
/// tested through the ctypes host, tests/python/test_intermediate_update.py).
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
}

unsafe extern "C" fn capture(
    env: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    record(env, status, category, message);
}

/// The logger to pass to an instantiate function (as the binary table's pointer type).
pub fn logger() -> *const c_void {
    capture as *const c_void
}

/// A live FMI 3.0 instance of a loaded FMU; freed on drop. The log lives in a box
/// whose address is the instance environment.
pub struct Instance<'a> {
    pub binary: &'a Binary3,
    pub description: &'a Description,
    pub interface: Interface3,
    pub c: Handle,
    pub log: Box<Log>,
}

/// Instantiates `interface` with the logger on; null when refused.
pub fn instantiate(
    binary: &Binary3,
    description: &Description,
    interface: Interface3,
    log: &Log,
) -> Handle {
    let name = c_string("hostile");
    let token = c_string(&description.guid);
    let env = log as *const Log as *mut c_void;
    let null = std::ptr::null();
    // SAFETY: valid strings, a logger and an environment that outlive the instance.
    unsafe {
        match interface {
            Interface3::ModelExchange => {
                (binary.instantiate_me)(name.as_ptr(), token.as_ptr(), null, 0, 1, env, logger())
            }
            _ => (binary.instantiate_cs)(
                name.as_ptr(),
                token.as_ptr(),
                null,
                0,
                1,
                u8::from(interface == Interface3::CoSimulationEvents),
                u8::from(interface == Interface3::CoSimulationEvents),
                std::ptr::null(),
                0,
                env,
                logger(),
                std::ptr::null(),
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

impl<'a> Instance<'a> {
    /// Instantiates with logging on; panics when refused.
    pub fn new(
        binary: &'a Binary3,
        description: &'a Description,
        interface: Interface3,
    ) -> Instance<'a> {
        let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
        let c = instantiate(binary, description, interface, &log);
        assert!(!c.is_null(), "fmi3 instantiate refused: {}", take(&log));
        Instance {
            binary,
            description,
            interface,
            c,
            log,
        }
    }

    pub fn take_log(&self) -> String {
        take(&self.log)
    }

    /// Brings a fresh instance into `state` with legal calls.
    pub fn reach(&self, state: State3) -> Result<(), String> {
        let b = self.binary;
        // SAFETY: a live instance; every call below has well-formed arguments.
        unsafe {
            match state {
                State3::Instantiated => return Ok(()),
                State3::Error => {
                    let s = (b.exit_initialization_mode)(self.c);
                    self.take_log();
                    return if s == ERROR {
                        Ok(())
                    } else {
                        Err(format!("an illegal call returned {}", status_name(s)))
                    };
                }
                _ => {}
            }
            self.initialize()?;
            if state == State3::InitializationMode {
                return Ok(());
            }
            self.expect_ok(
                "fmi3ExitInitializationMode",
                (b.exit_initialization_mode)(self.c),
            )?;
            let first = self.interface.after_initialization();
            match state {
                State3::ContinuousTimeMode => self.expect_ok(
                    "fmi3EnterContinuousTimeMode",
                    (b.enter_continuous_time_mode)(self.c),
                ),
                State3::StepMode | State3::StepDiscarded if first == State3::EventMode => {
                    self.expect_ok("fmi3EnterStepMode", (b.enter_step_mode)(self.c))?;
                    self.discard_if(state)
                }
                State3::Terminated => self.expect_ok("fmi3Terminate", (b.terminate)(self.c)),
                _ => self.discard_if(state),
            }
        }
    }

    fn initialize(&self) -> Result<(), String> {
        // SAFETY: a live instance, no tolerance, start time 0, no stop time.
        let s = unsafe { (self.binary.enter_initialization_mode)(self.c, 0, 0.0, 0.0, 0, 0.0) };
        self.expect_ok("fmi3EnterInitializationMode", s)
    }

    fn discard_if(&self, state: State3) -> Result<(), String> {
        if state == State3::StepDiscarded {
            self.fail_a_step()
        } else {
            Ok(())
        }
    }

    /// A step the model must refuse: a force input of 1e100 N on the first leg
    /// (finite and accepted when set, but no step can be integrated with it).
    fn fail_a_step(&self) -> Result<(), String> {
        let force = self
            .description
            .variables
            .iter()
            .find(|v| v.name == "actuatorForce")
            .ok_or("the model has no force input to fail a step with")?;
        let mut values = vec![0.0; force.size];
        values[0] = 1e100;
        self.expect_ok(
            "fmi3SetFloat64(actuatorForce)",
            self.set_float64(&[force.vr], &values),
        )?;
        let step = self.do_step(0.0, 1e-3);
        self.take_log();
        if step.status == DISCARD {
            Ok(())
        } else {
            Err(format!(
                "a step with a force of 1e100 N returned {}",
                status_name(step.status)
            ))
        }
    }

    pub fn set_float64(&self, vrs: &[Vr], values: &[f64]) -> Status {
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

    /// fmi3GetFloat64 of `vrs`, every element.
    pub fn get_float64(&self, vrs: &[Vr]) -> (Status, Vec<f64>) {
        let mut values = vec![f64::NAN; self.description.elements(vrs)];
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

    /// Every Float64 element of the model.
    pub fn get_all(&self) -> (Status, Vec<f64>) {
        self.get_float64(&self.description.real_vrs())
    }

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
    pub fn get_state(&self) -> (Status, FmuState) {
        let mut state = std::ptr::null_mut();
        // SAFETY: a null slot asks for a new state.
        let s = unsafe { (self.binary.get_fmu_state)(self.c, &mut state) };
        (s, state)
    }

    /// Serialized bytes of a state of this instance. The state pointer is only
    /// handed to the FMU (never dereferenced here).
    #[allow(clippy::not_unsafe_ptr_arg_deref)]
    pub fn serialize(&self, state: FmuState) -> Result<Vec<u8>, String> {
        let mut size = 0usize;
        // SAFETY: a state issued by this instance, a buffer of the announced size.
        unsafe {
            let s = (self.binary.serialized_size)(self.c, state, &mut size);
            self.expect_ok("fmi3SerializedFMUStateSize", s)?;
            let mut bytes = vec![0u8; size];
            let s = (self.binary.serialize)(self.c, state, bytes.as_mut_ptr(), size);
            self.expect_ok("fmi3SerializeFMUState", s)?;
            Ok(bytes)
        }
    }

    /// fmi3DeserializeFMUState of `bytes` into a new state.
    pub fn deserialize(&self, bytes: &[u8]) -> (Status, FmuState) {
        let mut state: FmuState = std::ptr::null_mut();
        // SAFETY: a buffer of the given length and a null slot for a new state.
        let s =
            unsafe { (self.binary.deserialize)(self.c, bytes.as_ptr(), bytes.len(), &mut state) };
        (s, state)
    }

    pub fn free_state(&self, mut state: FmuState) -> Status {
        // SAFETY: a state issued by this binary (or the probe's point).
        unsafe { (self.binary.free_fmu_state)(self.c, &mut state) }
    }

    /// fmi3Reset then initialization: whether the instance is usable again after
    /// a refusal (FMI 3.0 section 2.3.1: from Error, fmi3Reset returns to
    /// Instantiated).
    pub fn recovers(&self) -> Result<(), String> {
        // SAFETY: a live instance.
        let s = unsafe { (self.binary.reset)(self.c) };
        self.expect_ok("fmi3Reset after the refusal", s)?;
        self.initialize()?;
        // SAFETY: as above.
        let s = unsafe { (self.binary.exit_initialization_mode)(self.c) };
        self.expect_ok("fmi3ExitInitializationMode after fmi3Reset", s)?;
        let (s, x) = self.get_all();
        self.expect_ok("fmi3GetFloat64 after fmi3Reset", s)?;
        match x.iter().position(|v| !v.is_finite()) {
            Some(i) => Err(format!("element {i} is {} after fmi3Reset", x[i])),
            None => Ok(()),
        }
    }
}

impl Probed for Instance<'_> {
    fn log(&self) -> &Log {
        &self.log
    }
    fn new_state(&self) -> (Status, FmuState) {
        self.get_state()
    }
    fn release_state(&self, state: FmuState) -> Status {
        self.free_state(state)
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        // SAFETY: the instance came from this binary.
        unsafe { (self.binary.free_instance)(self.c) }
    }
}
