//! The whole life of FMI 3.0 instances through the loaded binary, for memcheck:
//! load, instantiate (ME, CS, CS with event mode), initialize, steps (CS, with the
//! event iteration when a step asks for it) or integration steps and an event
//! (ME), partial derivatives and variable dependencies, get/set/serialize/
//! deserialize/free FMU states, terminate, reset, free, unload.

use super::binary::{Binary3, FmuState};
use super::host::{Instance, Interface3, State3};
use crate::fmu::Fmu;
use crate::host::Probed;

/// fmi3UpdateDiscreteStates until no further update is needed (at most 10 rounds).
pub fn event_iteration(inst: &Instance) -> Result<(), String> {
    for _ in 0..10 {
        let mut flags = [0u8; 5];
        let mut next = 0.0;
        let [need, stop, nominals, values, defined] = &mut flags;
        // SAFETY: six outputs to fill.
        let s = unsafe {
            (inst.binary.update_discrete_states)(
                inst.c, need, stop, nominals, values, defined, &mut next,
            )
        };
        inst.expect_ok("fmi3UpdateDiscreteStates", s)?;
        if flags[0] == 0 {
            return Ok(());
        }
    }
    Err("discrete states still need an update after 10 rounds".into())
}

/// CS steps from `t` to `t + h`: a step that returns early (at an event, with
/// event mode) is followed by the event iteration and a step over the rest.
pub fn co_simulation_step(inst: &Instance, t: f64, h: f64) -> Result<(), String> {
    let end = t + h;
    let mut now = t;
    for _ in 0..10 {
        let step = inst.do_step(now, end - now);
        inst.expect_ok("fmi3DoStep", step.status)?;
        if inst.interface == Interface3::CoSimulationEvents && step.event_handling_needed {
            // SAFETY: legal calls in Step Mode and Event Mode.
            unsafe {
                let b = inst.binary;
                inst.expect_ok("fmi3EnterEventMode", (b.enter_event_mode)(inst.c))?;
                event_iteration(inst)?;
                inst.expect_ok("fmi3EnterStepMode", (b.enter_step_mode)(inst.c))?;
            }
        }
        if !step.early_return {
            return Ok(());
        }
        now = step.last_successful_time;
    }
    Err(format!(
        "fmi3DoStep returned early 10 times before t = {end}"
    ))
}

/// One explicit Euler step of `h` from `t` (ME, Continuous-Time Mode).
pub fn euler_step(inst: &Instance, t: f64, h: f64) -> Result<(), String> {
    let b = inst.binary;
    let n = inst.description.number_of_states;
    let (mut x, mut dx) = (vec![0.0; n], vec![0.0; n]);
    // SAFETY: arrays of the state count.
    unsafe {
        inst.expect_ok(
            "fmi3GetContinuousStates",
            (b.get_continuous_states)(inst.c, x.as_mut_ptr(), n),
        )?;
        inst.expect_ok(
            "fmi3GetContinuousStateDerivatives",
            (b.get_continuous_state_derivatives)(inst.c, dx.as_mut_ptr(), n),
        )?;
        inst.expect_ok("fmi3SetTime", (b.set_time)(inst.c, t + h))?;
        let next: Vec<f64> = x.iter().zip(&dx).map(|(a, d)| a + h * d).collect();
        inst.expect_ok(
            "fmi3SetContinuousStates",
            (b.set_continuous_states)(inst.c, next.as_ptr(), n),
        )?;
        let (mut enter, mut stop) = (0u8, 0u8);
        inst.expect_ok(
            "fmi3CompletedIntegratorStep",
            (b.completed_integrator_step)(inst.c, 1, &mut enter, &mut stop),
        )
    }
}

fn advance(inst: &Instance) -> Result<(), String> {
    for k in 0..20 {
        let t = k as f64 * 1e-3;
        if inst.interface.is_me() {
            euler_step(inst, t, 1e-3)?;
        } else {
            co_simulation_step(inst, t, 1e-3)?;
        }
        inst.expect_ok("fmi3GetFloat64", inst.get_all().0)?;
    }
    Ok(())
}

/// Partial derivatives and the dependencies of every Float64 variable.
fn structure(inst: &Instance) -> Result<(), String> {
    let b = inst.binary;
    let d = inst.description;
    if let Some(&(x, dx)) = d.state_derivative_pairs().first()
        && d.provides_directional_derivative
    {
        let n = d.elements(&[x]);
        let seed = vec![1.0; n];
        let mut out = vec![0.0; n];
        for f in [b.get_directional_derivative, b.get_adjoint_derivative] {
            // SAFETY: arrays of the variables' element counts.
            let s = unsafe { f(inst.c, &dx, 1, &x, 1, seed.as_ptr(), n, out.as_mut_ptr(), n) };
            inst.expect_ok("partial derivative", s)?;
        }
    }
    for vr in d.real_vrs() {
        let mut n = 0usize;
        // SAFETY: a count, then arrays of that count.
        unsafe {
            inst.expect_ok(
                "fmi3GetNumberOfVariableDependencies",
                (b.get_number_of_variable_dependencies)(inst.c, vr, &mut n),
            )?;
            let (mut e, mut v, mut ei, mut k) = (vec![0; n], vec![0; n], vec![0; n], vec![0; n]);
            let s = (b.get_variable_dependencies)(
                inst.c,
                vr,
                e.as_mut_ptr(),
                v.as_mut_ptr(),
                ei.as_mut_ptr(),
                k.as_mut_ptr(),
                n,
            );
            inst.expect_ok("fmi3GetVariableDependencies", s)?;
        }
    }
    Ok(())
}

fn states(inst: &Instance) -> Result<(), String> {
    let (s, state) = inst.get_state();
    inst.expect_ok("fmi3GetFMUState", s)?;
    let bytes = inst.serialize(state)?;
    let (s, copy) = inst.deserialize(&bytes);
    inst.expect_ok("fmi3DeserializeFMUState", s)?;
    // SAFETY: the instance's own states.
    unsafe {
        inst.expect_ok("fmi3SetFMUState", (inst.binary.set_fmu_state)(inst.c, copy))?;
        // Overwrite an existing state, as the standard allows.
        let mut again: FmuState = state;
        inst.expect_ok(
            "fmi3GetFMUState(overwrite)",
            (inst.binary.get_fmu_state)(inst.c, &mut again),
        )?;
        inst.expect_ok("fmi3FreeFMUState", inst.free_state(copy))?;
        inst.expect_ok("fmi3FreeFMUState", inst.free_state(again))?;
    }
    Ok(())
}

/// The running state of an interface: Continuous-Time Mode or Step Mode.
pub fn running(interface: Interface3) -> State3 {
    if interface.is_me() {
        State3::ContinuousTimeMode
    } else {
        State3::StepMode
    }
}

/// The life of one instance of each interface, then unload.
pub fn run(fmu: &Fmu) -> Result<(), String> {
    let binary = Binary3::open(&fmu.library)?;
    for interface in Interface3::ALL {
        let inst = Instance::new(&binary, &fmu.description, interface);
        inst.reach(running(interface))?;
        advance(&inst)?;
        structure(&inst)?;
        states(&inst)?;
        let b = inst.binary;
        // SAFETY: legal calls on a live instance.
        unsafe {
            if interface.is_me() {
                inst.expect_ok("fmi3EnterEventMode", (b.enter_event_mode)(inst.c))?;
                event_iteration(&inst)?;
            }
            inst.expect_ok("fmi3Terminate", (b.terminate)(inst.c))?;
            inst.expect_ok("fmi3Reset", (b.reset)(inst.c))?;
        }
        inst.reach(running(interface))?;
        advance(&inst)?;
    }
    drop(binary);
    Ok(())
}
