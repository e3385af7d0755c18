//! The hostile importer's side of an FMI 3.0 instance: the test host's instance
//! (`robofmu_fmi_host::instance`: the keeping logger, fmi3InstantiateModelExchange /
//! fmi3InstantiateCoSimulation, the calls) with the model's description, and the
//! calls that bring an instance into each state of the FMI 3.0 state machines
//! (sections 3.3 and 4.3 of the standard).

use super::binary::{Binary3, FmuState, Instance3 as Handle, Vr};
use crate::binary::{DISCARD, ERROR, Status, status_name};
use crate::description::Description;
use crate::host::{Described, Log, Probed};
use robofmu_fmi_host::callbacks::logger3;
use robofmu_fmi_host::instance::instantiate3;
use std::ffi::c_void;

pub use robofmu_fmi_host::instance::{Fmi3Instance, Interface3, State3, StepOutcome};

/// The logger to pass to an instantiate function (as the binary table's pointer type).
pub fn logger() -> *const c_void {
    logger3()
}

/// A live FMI 3.0 instance of a loaded FMU.
pub type Instance<'a> = Described<'a, Fmi3Instance<'a>, Interface3>;

/// Instantiates `interface` with the logger on (environment: `log`); null when
/// refused.
pub fn instantiate(
    binary: &Binary3,
    description: &Description,
    interface: Interface3,
    log: &Log,
) -> Handle {
    let env = log as *const Log as *mut c_void;
    instantiate3(
        binary,
        interface,
        "hostile",
        &description.guid,
        env,
        logger(),
        std::ptr::null(),
    )
}

impl<'a> Instance<'a> {
    /// Instantiates with logging on; panics when refused.
    pub fn new(
        binary: &'a Binary3,
        description: &'a Description,
        interface: Interface3,
    ) -> Instance<'a> {
        let core = Fmi3Instance::new(binary, interface, "hostile", &description.guid)
            .unwrap_or_else(|e| panic!("{e}"));
        Instance {
            core,
            description,
            interface,
        }
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
            self.enter_initialization()?;
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
        let force = self.force_input("actuatorForce")?;
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

    /// fmi3GetFloat64 of `vrs`, every element.
    pub fn get_float64(&self, vrs: &[Vr]) -> (Status, Vec<f64>) {
        self.get_float64_elements(vrs, self.description.elements(vrs))
    }

    /// Every Float64 element of the model.
    pub fn get_all(&self) -> (Status, Vec<f64>) {
        self.get_float64(&self.description.real_vrs())
    }

    /// fmi3Reset then initialization: whether the instance is usable again after
    /// a refusal (FMI 3.0 section 2.3.1: from Error, fmi3Reset returns to
    /// Instantiated).
    pub fn recovers(&self) -> Result<(), String> {
        // SAFETY: a live instance.
        let s = unsafe { (self.binary.reset)(self.c) };
        self.expect_ok("fmi3Reset after the refusal", s)?;
        self.enter_initialization()?;
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
