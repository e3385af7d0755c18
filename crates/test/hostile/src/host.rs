//! The importer's side of an instance: callbacks (a capturing logger, calloc/free),
//! fmi2Instantiate through the loaded binary, and the calls that bring an instance
//! into each state of the FMI 2.0 state machines.

use crate::binary::{Binary, CallbackFunctions, Component, ERROR, OK, Status, Vr};
use crate::description::Description;
use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::sync::Mutex;

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

/// Log lines received, as "status category: message"; only messages of status
/// Warning and above are kept (debug lines such as logCalls are dropped).
pub type Log = Mutex<Vec<String>>;

/// The log received so far, one line per message, and clears it.
pub fn take(log: &Log) -> String {
    let mut lines = log.lock().unwrap_or_else(|e| e.into_inner());
    let text = lines.join(" | ");
    lines.clear();
    text
}

/// What the probes shared by both standards need of a live instance.
pub trait Probed {
    /// The instance's log.
    fn log(&self) -> &Log;
    /// A new FMU state of the instance: (status, state).
    fn new_state(&self) -> (Status, *mut c_void);
    /// Frees an FMU state through the instance.
    fn release_state(&self, state: *mut c_void) -> Status;

    /// Err with the status and the log unless `s` is OK.
    fn expect_ok(&self, what: &str, s: Status) -> Result<(), String> {
        if s == OK {
            Ok(())
        } else {
            Err(format!(
                "{what} returned {}: {}",
                crate::binary::status_name(s),
                take(self.log())
            ))
        }
    }
}

/// Runs `f` on `inst` without adding its log lines to what was logged before.
pub fn unlogged<P: Probed, T>(inst: &P, f: impl FnOnce() -> T) -> T {
    let kept = take(inst.log());
    let result = f();
    let mut lines = inst.log().lock().unwrap_or_else(|e| e.into_inner());
    lines.clear();
    if !kept.is_empty() {
        lines.push(kept);
    }
    result
}

/// Keeps a log message of status Warning and above as "status category: message"
/// in `env`, the &Log given to the FMU as its environment (shared by the FMI 2.0
/// and FMI 3.0 loggers).
pub(crate) fn record(
    env: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    let text = |p: *const c_char| {
        if p.is_null() {
            "(null)".to_string()
        } else {
            // SAFETY: the FMU passes NUL-terminated strings.
            unsafe { CStr::from_ptr(p) }
                .to_string_lossy()
                .replace("%%", "%")
        }
    };
    if status == 0 || env.is_null() {
        return;
    }
    // SAFETY: env is the &Log this crate passed as environment.
    let log = unsafe { &*(env as *const Log) };
    if let Ok(mut lines) = log.lock() {
        lines.push(format!("{status} {}: {}", text(category), text(message)));
    }
}

extern "C" fn capture(
    env: *mut c_void,
    _instance: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    record(env, status, category, message);
}

extern "C" fn allocate(n: usize, size: usize) -> *mut c_void {
    // SAFETY: calloc accepts any sizes and returns null on failure.
    unsafe { libc::calloc(n, size) }
}

extern "C" fn release(p: *mut c_void) {
    // SAFETY: p came from `allocate` (or is null).
    unsafe { libc::free(p) }
}

/// Which callbacks fmi2Instantiate receives.
#[derive(Debug, Clone, Copy)]
pub struct Callbacks {
    pub logger: bool,
    pub allocate: bool,
    pub free: bool,
}

impl Callbacks {
    pub const ALL: Callbacks = Callbacks {
        logger: true,
        allocate: true,
        free: true,
    };
}

/// The callback table and log of one instance; both must outlive it.
pub struct Environment {
    pub log: Box<Log>,
    pub functions: Box<CallbackFunctions>,
}

impl Environment {
    pub fn new(which: Callbacks) -> Environment {
        let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
        // The non-variadic `capture` stands in for the variadic C logger: on x86-64
        // System V both are called identically, and no variadic arguments are used
        // by FMUs that escape '%' (ours do; `capture` undoes the escaping).
        let functions = Box::new(CallbackFunctions {
            logger: if which.logger {
                capture as *const c_void
            } else {
                std::ptr::null()
            },
            allocate_memory: if which.allocate {
                allocate as *const c_void
            } else {
                std::ptr::null()
            },
            free_memory: if which.free {
                release as *const c_void
            } else {
                std::ptr::null()
            },
            step_finished: std::ptr::null(),
            component_environment: &*log as *const Log as *mut c_void,
        });
        Environment { log, functions }
    }

    /// The log received so far, one line per message, and clears it.
    pub fn take_log(&self) -> String {
        take(&self.log)
    }
}

/// States an instance can be brought into (FMI 2.0 sections 3.2.3 and 4.2.4).
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

/// A live instance of a loaded FMU; freed on drop.
pub struct Instance<'a> {
    pub binary: &'a Binary,
    pub description: &'a Description,
    pub interface: Interface,
    pub c: Component,
    pub env: Environment,
}

/// A C string that lives as long as the program (names and GUIDs of test instances).
pub fn c_string(s: &str) -> CString {
    CString::new(s).unwrap_or_default()
}

impl<'a> Instance<'a> {
    /// fmi2Instantiate with all callbacks and logging on; panics when refused.
    pub fn new(
        binary: &'a Binary,
        description: &'a Description,
        interface: Interface,
    ) -> Instance<'a> {
        let env = Environment::new(Callbacks::ALL);
        let name = c_string("hostile");
        let guid = c_string(&description.guid);
        // SAFETY: valid strings and callback table that outlive the instance.
        let c = unsafe {
            (binary.instantiate)(
                name.as_ptr(),
                interface as c_int,
                guid.as_ptr(),
                std::ptr::null(),
                &*env.functions,
                0,
                1,
            )
        };
        assert!(!c.is_null(), "fmi2Instantiate refused: {}", env.take_log());
        Instance {
            binary,
            description,
            interface,
            c,
            env,
        }
    }

    /// Brings a fresh instance into `state` with legal calls.
    pub fn reach(&self, state: State) -> Result<(), String> {
        let b = self.binary;
        let ok = |what: &str, s: Status| self.expect_ok(what, s);
        // SAFETY: a live component; every call below has well-formed arguments.
        unsafe {
            match state {
                State::Instantiated => return Ok(()),
                State::Error => {
                    let s = (b.exit_initialization_mode)(self.c);
                    self.env.take_log();
                    return if s == ERROR {
                        Ok(())
                    } else {
                        Err(format!("an illegal call returned {s}"))
                    };
                }
                _ => {}
            }
            ok(
                "fmi2SetupExperiment",
                (b.setup_experiment)(self.c, 0, 0.0, 0.0, 0, 0.0),
            )?;
            ok(
                "fmi2EnterInitializationMode",
                (b.enter_initialization_mode)(self.c),
            )?;
            if state == State::InitializationMode {
                return Ok(());
            }
            ok(
                "fmi2ExitInitializationMode",
                (b.exit_initialization_mode)(self.c),
            )?;
            match state {
                State::ContinuousTimeMode => ok(
                    "fmi2EnterContinuousTimeMode",
                    (b.enter_continuous_time_mode)(self.c),
                ),
                State::Terminated => ok("fmi2Terminate", (b.terminate)(self.c)),
                State::StepFailed => self.fail_a_step(),
                _ => Ok(()),
            }
        }
    }

    /// A Co-Simulation step the model must refuse: a force input of 1e100 N (finite
    /// and accepted when set, but no step can be integrated with it). Only models
    /// with such an input can reach StepFailed.
    fn fail_a_step(&self) -> Result<(), String> {
        let force = self
            .description
            .variables
            .iter()
            .find(|v| v.name == "actuatorForce[1]")
            .ok_or("the model has no force input to fail a step with")?;
        let s = self.set_real(force.vr, 1e100);
        if s != OK {
            return Err(format!(
                "a force of 1e100 N was refused: {}",
                self.env.take_log()
            ));
        }
        let s = self.do_step(0.0, 1e-3);
        self.env.take_log();
        if s == crate::binary::DISCARD {
            Ok(())
        } else {
            Err(format!("a step with a force of 1e100 N returned {s}"))
        }
    }

    pub fn set_real(&self, vr: Vr, value: f64) -> Status {
        // SAFETY: one value reference and one value.
        unsafe { (self.binary.set_real)(self.c, &vr, 1, &value) }
    }

    pub fn get_reals(&self, vrs: &[Vr]) -> (Status, Vec<f64>) {
        let mut values = vec![f64::NAN; vrs.len()];
        // SAFETY: arrays of equal length.
        let s =
            unsafe { (self.binary.get_real)(self.c, vrs.as_ptr(), vrs.len(), values.as_mut_ptr()) };
        (s, values)
    }

    pub fn do_step(&self, t: f64, h: f64) -> Status {
        // SAFETY: plain values.
        unsafe { (self.binary.do_step)(self.c, t, h, 1) }
    }

    /// fmi2GetFMUstate into a new state.
    pub fn get_state(&self) -> (Status, crate::binary::FmuState) {
        let mut state = std::ptr::null_mut();
        // SAFETY: a null slot asks for a new state.
        let s = unsafe { (self.binary.get_fmu_state)(self.c, &mut state) };
        (s, state)
    }

    /// Serialized bytes of a state of this instance. The state pointer is only
    /// handed to the FMU (never dereferenced here): checking it is the FMU's job.
    #[allow(clippy::not_unsafe_ptr_arg_deref)]
    pub fn serialize(&self, state: crate::binary::FmuState) -> Result<Vec<u8>, String> {
        let mut size = 0usize;
        // SAFETY: a state issued by this instance, buffers of the announced size.
        unsafe {
            if (self.binary.serialized_size)(self.c, state, &mut size) != OK {
                return Err(format!(
                    "fmi2SerializedFMUstateSize: {}",
                    self.env.take_log()
                ));
            }
            let mut bytes = vec![0u8; size];
            if (self.binary.serialize)(self.c, state, bytes.as_mut_ptr() as *mut c_char, size) != OK
            {
                return Err(format!("fmi2SerializeFMUstate: {}", self.env.take_log()));
            }
            Ok(bytes)
        }
    }

    pub fn free_state(&self, mut state: crate::binary::FmuState) -> Status {
        // SAFETY: a state issued by this binary.
        unsafe { (self.binary.free_fmu_state)(self.c, &mut state) }
    }

    pub fn take_log(&self) -> String {
        self.env.take_log()
    }
}

impl Probed for Instance<'_> {
    fn log(&self) -> &Log {
        &self.env.log
    }
    fn new_state(&self) -> (Status, *mut c_void) {
        self.get_state()
    }
    fn release_state(&self, state: *mut c_void) -> Status {
        self.free_state(state)
    }
}

impl Drop for Instance<'_> {
    fn drop(&mut self) {
        // SAFETY: the component came from this binary's fmi2Instantiate.
        unsafe { (self.binary.free_instance)(self.c) }
    }
}
