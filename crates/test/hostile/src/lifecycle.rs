//! The whole life of an instance through the loaded binary, for memcheck: load,
//! instantiate, initialize, steps (CS) or integration steps and an event (ME),
//! get/set/serialize/deserialize/free FMU states, reset, terminate, free, unload.

use crate::binary::{Binary, EventInfo, FmuState};
use crate::fmu::Fmu;
use crate::host::Probed;
use crate::host::{Instance, Interface, State};
use std::ffi::c_char;

fn advance(inst: &Instance) -> Result<(), String> {
    let b = inst.binary;
    let n = inst.description.number_of_states;
    let (mut x, mut dx) = (vec![0.0; n], vec![0.0; n]);
    for k in 0..20 {
        let t = k as f64 * 1e-3;
        // SAFETY: arrays of the state count, legal calls in the reached states.
        unsafe {
            match inst.interface {
                Interface::CoSimulation => inst.expect_ok("fmi2DoStep", inst.do_step(t, 1e-3))?,
                Interface::ModelExchange => {
                    inst.expect_ok(
                        "fmi2GetContinuousStates",
                        (b.get_continuous_states)(inst.c, x.as_mut_ptr(), n),
                    )?;
                    inst.expect_ok(
                        "fmi2GetDerivatives",
                        (b.get_derivatives)(inst.c, dx.as_mut_ptr(), n),
                    )?;
                    inst.expect_ok("fmi2SetTime", (b.set_time)(inst.c, t + 1e-3))?;
                    let next: Vec<f64> = x.iter().zip(&dx).map(|(a, d)| a + 1e-3 * d).collect();
                    inst.expect_ok(
                        "fmi2SetContinuousStates",
                        (b.set_continuous_states)(inst.c, next.as_ptr(), n),
                    )?;
                    let (mut enter, mut stop) = (0, 0);
                    inst.expect_ok(
                        "fmi2CompletedIntegratorStep",
                        (b.completed_integrator_step)(inst.c, 1, &mut enter, &mut stop),
                    )?;
                }
            }
        }
        let (s, _) = inst.get_reals(&inst.description.real_vrs());
        inst.expect_ok("fmi2GetReal", s)?;
    }
    Ok(())
}

fn states(inst: &Instance) -> Result<(), String> {
    let (s, state) = inst.get_state();
    inst.expect_ok("fmi2GetFMUstate", s)?;
    let bytes = inst.serialize(state)?;
    let mut copy: FmuState = std::ptr::null_mut();
    // SAFETY: the instance's own bytes and states.
    unsafe {
        inst.expect_ok(
            "fmi2DeSerializeFMUstate",
            (inst.binary.deserialize)(
                inst.c,
                bytes.as_ptr() as *const c_char,
                bytes.len(),
                &mut copy,
            ),
        )?;
        inst.expect_ok("fmi2SetFMUstate", (inst.binary.set_fmu_state)(inst.c, copy))?;
        // Overwrite an existing state, as the standard allows.
        let mut again = state;
        inst.expect_ok(
            "fmi2GetFMUstate(overwrite)",
            (inst.binary.get_fmu_state)(inst.c, &mut again),
        )?;
        inst.expect_ok("fmi2FreeFMUstate", inst.free_state(copy))?;
        inst.expect_ok("fmi2FreeFMUstate", inst.free_state(again))?;
    }
    Ok(())
}

/// The life of one instance of each interface, then unload.
pub fn run(fmu: &Fmu) -> Result<(), String> {
    let binary = Binary::open(&fmu.library)?;
    for interface in Interface::BOTH {
        let inst = Instance::new(&binary, &fmu.description, interface);
        let running = match interface {
            Interface::CoSimulation => State::StepComplete,
            Interface::ModelExchange => State::ContinuousTimeMode,
        };
        inst.reach(running)?;
        advance(&inst)?;
        states(&inst)?;
        let b = inst.binary;
        // SAFETY: legal calls on a live instance.
        unsafe {
            if interface == Interface::ModelExchange {
                inst.expect_ok("fmi2EnterEventMode", (b.enter_event_mode)(inst.c))?;
                let mut info = EventInfo::default();
                inst.expect_ok(
                    "fmi2NewDiscreteStates",
                    (b.new_discrete_states)(inst.c, &mut info),
                )?;
            }
            inst.expect_ok("fmi2Terminate", (b.terminate)(inst.c))?;
            inst.expect_ok("fmi2Reset", (b.reset)(inst.c))?;
        }
        inst.reach(running)?;
        advance(&inst)?;
    }
    drop(binary);
    Ok(())
}
