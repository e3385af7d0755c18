//! The hostile importer's side of an FMI 2.0 instance: the test host's instance
//! (`robofmu_fmi_host::instance`: callbacks, fmi2Instantiate, the calls) with the
//! model's description, and the calls that bring an instance into each state of the
//! FMI 2.0 state machines.

use crate::binary::{Binary, ERROR, OK, Status};
use crate::description::{Description, Variable};
use std::ffi::c_void;

pub use robofmu_fmi_host::callbacks::{Callbacks, Environment, Log, c_string, record, take};
pub use robofmu_fmi_host::instance::{Fmi2Instance, Interface, State};

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
    let lock = || inst.log().lock().unwrap_or_else(|e| e.into_inner());
    let kept = std::mem::take(&mut *lock());
    let result = f();
    *lock() = kept;
    result
}

/// An instance of the test host (`C`: [`Fmi2Instance`] or its FMI 3.0 counterpart)
/// with the model's description and the interface it was made for, which the probes
/// need; the instance's calls are reached through `Deref`, and it is freed on drop.
pub struct Described<'a, C, I> {
    pub core: C,
    pub description: &'a Description,
    pub interface: I,
}

impl<C, I> std::ops::Deref for Described<'_, C, I> {
    type Target = C;
    fn deref(&self) -> &C {
        &self.core
    }
}

impl<C, I> Described<'_, C, I> {
    /// The force input `name`, with which a step can be made to fail (1e100 N).
    pub fn force_input(&self, name: &str) -> Result<&Variable, String> {
        let variables = &self.description.variables;
        let force = variables.iter().find(|v| v.name == name);
        force.ok_or_else(|| "the model has no force input to fail a step with".to_string())
    }
}

/// A live FMI 2.0 instance of a loaded FMU.
pub type Instance<'a> = Described<'a, Fmi2Instance<'a>, Interface>;

impl<'a> Instance<'a> {
    /// fmi2Instantiate with all callbacks and logging on; panics when refused.
    pub fn new(
        binary: &'a Binary,
        description: &'a Description,
        interface: Interface,
    ) -> Instance<'a> {
        let core = Fmi2Instance::new(
            binary,
            "hostile",
            interface,
            &description.guid,
            Callbacks::ALL,
            true,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        Instance {
            core,
            description,
            interface,
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
            self.enter_initialization(0.0, None)?;
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
        let force = self.force_input("actuatorForce[1]")?;
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
