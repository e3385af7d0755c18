//! The plant driven hard: actuator forces of ±1e4 N (far beyond what the stops
//! hold back gently) with both end-stop modes, Co-Simulation steps from 1e-9 s to
//! 1 s and Model Exchange with an explicit Euler integrator. FMI 2.0 allows
//! fmi2Discard for a step or evaluation the model cannot complete (the master
//! retries smaller); everything else must be fmi2OK, and a getter that returns
//! fmi2OK never delivers NaN or inf.

use crate::Loaded;
use crate::binary::{DISCARD, EventInfo, OK, Status, status_name};
use crate::host::{Instance, Interface, State};

pub const FORCE: f64 = 1e4;
pub const STEP_SIZES: [f64; 10] = [1e-9, 1e-8, 1e-7, 1e-6, 1e-5, 1e-4, 1e-3, 1e-2, 1e-1, 1.0];
pub const STEPS_PER_SIZE: usize = 20;

/// Force patterns: all +F, all -F, alternating, one leg only.
pub const PATTERNS: [[f64; 3]; 4] = [
    [FORCE, FORCE, FORCE],
    [-FORCE, -FORCE, -FORCE],
    [FORCE, -FORCE, FORCE],
    [0.0, 0.0, -FORCE],
];

/// Calls made and Discards seen.
#[derive(Default, Debug)]
pub struct Tally {
    pub calls: usize,
    pub discards: usize,
}

fn accept(tally: &mut Tally, inst: &Instance, what: &str, s: Status) -> Result<Status, String> {
    tally.calls += 1;
    match s {
        OK => Ok(s),
        DISCARD => {
            tally.discards += 1;
            Ok(s)
        }
        _ => Err(format!(
            "{what} returned {} (log: {})",
            status_name(s),
            inst.take_log()
        )),
    }
}

fn check_outputs(tally: &mut Tally, inst: &Instance) -> Result<(), String> {
    let vrs = inst.description.real_vrs();
    let (s, x) = inst.get_reals(&vrs);
    if accept(tally, inst, "fmi2GetReal", s)? == OK && x.iter().any(|v| !v.is_finite()) {
        return Err("fmi2GetReal returned fmi2OK with a non-finite value".into());
    }
    Ok(())
}

/// A fresh plant with the end-stop mode and forces set, initialized.
fn plant<'a>(
    l: &'a Loaded,
    m: usize,
    interface: Interface,
    stop_mode: i32,
    forces: [f64; 3],
) -> Result<Instance<'a>, String> {
    let inst = Instance::new(&l.binaries[m], &l.fmus[m].description, interface);
    let d = inst.description;
    let mode_vr = d.by_name("endStopMode").vr;
    // SAFETY: one Integer parameter, set before initialization.
    let s = unsafe { (inst.binary.set_integer)(inst.c, &mode_vr, 1, &stop_mode) };
    if s != OK {
        return Err(format!(
            "endStopMode = {stop_mode} refused: {}",
            inst.take_log()
        ));
    }
    for (i, f) in forces.iter().enumerate() {
        inst.set_real(d.by_name(&format!("actuatorForce[{}]", i + 1)).vr, *f);
    }
    let state = match interface {
        Interface::CoSimulation => State::StepComplete,
        Interface::ModelExchange => State::ContinuousTimeMode,
    };
    inst.reach(state)?;
    Ok(inst)
}

/// Co-Simulation: `STEPS_PER_SIZE` steps of each size; a discarded step is retried
/// once with a tenth of the size, as a master would.
pub fn co_simulation(
    l: &Loaded,
    m: usize,
    stop_mode: i32,
    forces: [f64; 3],
    tally: &mut Tally,
) -> Result<(), String> {
    for h in STEP_SIZES {
        let inst = plant(l, m, Interface::CoSimulation, stop_mode, forces)?;
        let mut t = 0.0;
        for _ in 0..STEPS_PER_SIZE {
            let s = accept(
                tally,
                &inst,
                &format!("fmi2DoStep(t = {t}, h = {h})"),
                inst.do_step(t, h),
            )?;
            check_outputs(tally, &inst)?;
            if s == DISCARD {
                break;
            }
            t += h;
        }
    }
    Ok(())
}

/// Model Exchange: explicit Euler with step `dt`, event iteration at sign changes
/// of the event indicators; a discarded evaluation returns to the last accepted
/// state and halves the step, as an integrator would.
pub fn model_exchange(
    l: &Loaded,
    m: usize,
    stop_mode: i32,
    forces: [f64; 3],
    dt: f64,
    tally: &mut Tally,
) -> Result<(), String> {
    let inst = plant(l, m, Interface::ModelExchange, stop_mode, forces)?;
    let b = inst.binary;
    let n = inst.description.number_of_states;
    let nz = inst.description.number_of_event_indicators;
    let (mut x, mut dx, mut z, mut z_before) =
        (vec![0.0; n], vec![0.0; n], vec![0.0; nz], vec![0.0; nz]);
    let mut t = 0.0;
    let mut h = dt;
    // SAFETY: arrays of the declared sizes, a live instance in the legal modes.
    unsafe {
        accept(
            tally,
            &inst,
            "fmi2GetEventIndicators",
            (b.get_event_indicators)(inst.c, z_before.as_mut_ptr(), nz),
        )?;
        accept(
            tally,
            &inst,
            "fmi2GetContinuousStates",
            (b.get_continuous_states)(inst.c, x.as_mut_ptr(), n),
        )?;
        let mut good = x.clone();
        for _ in 0..200 {
            accept(
                tally,
                &inst,
                "fmi2GetContinuousStates",
                (b.get_continuous_states)(inst.c, x.as_mut_ptr(), n),
            )?;
            if accept(
                tally,
                &inst,
                "fmi2GetDerivatives",
                (b.get_derivatives)(inst.c, dx.as_mut_ptr(), n),
            )? == DISCARD
            {
                accept(
                    tally,
                    &inst,
                    "fmi2SetContinuousStates",
                    (b.set_continuous_states)(inst.c, good.as_ptr(), n),
                )?;
                h /= 2.0;
                continue;
            }
            good.copy_from_slice(&x);
            if dx.iter().any(|v| !v.is_finite()) {
                return Err("fmi2GetDerivatives returned fmi2OK with a non-finite value".into());
            }
            t += h;
            accept(tally, &inst, "fmi2SetTime", (b.set_time)(inst.c, t))?;
            let next: Vec<f64> = x.iter().zip(&dx).map(|(xi, di)| xi + h * di).collect();
            accept(
                tally,
                &inst,
                "fmi2SetContinuousStates",
                (b.set_continuous_states)(inst.c, next.as_ptr(), n),
            )?;
            let (mut enter, mut stop) = (0, 0);
            accept(
                tally,
                &inst,
                "fmi2CompletedIntegratorStep",
                (b.completed_integrator_step)(inst.c, 1, &mut enter, &mut stop),
            )?;
            if accept(
                tally,
                &inst,
                "fmi2GetEventIndicators",
                (b.get_event_indicators)(inst.c, z.as_mut_ptr(), nz),
            )? == DISCARD
            {
                accept(
                    tally,
                    &inst,
                    "fmi2SetContinuousStates",
                    (b.set_continuous_states)(inst.c, good.as_ptr(), n),
                )?;
                h /= 2.0;
                continue;
            }
            check_outputs(tally, &inst)?;
            if enter != 0
                || z.iter()
                    .zip(&z_before)
                    .any(|(a, b)| (a > &0.0) != (b > &0.0))
            {
                accept(
                    tally,
                    &inst,
                    "fmi2EnterEventMode",
                    (b.enter_event_mode)(inst.c),
                )?;
                let mut info = EventInfo::default();
                accept(
                    tally,
                    &inst,
                    "fmi2NewDiscreteStates",
                    (b.new_discrete_states)(inst.c, &mut info),
                )?;
                accept(
                    tally,
                    &inst,
                    "fmi2EnterContinuousTimeMode",
                    (b.enter_continuous_time_mode)(inst.c),
                )?;
            }
            z_before.copy_from_slice(&z);
        }
    }
    Ok(())
}

/// Every combination: the tally and every failure (one per combination at most).
pub fn drive(l: &Loaded, m: usize) -> (Tally, Vec<String>) {
    let mut tally = Tally::default();
    let mut failures = Vec::new();
    for stop_mode in [1, 2] {
        for forces in PATTERNS {
            let label = format!("endStopMode {stop_mode}, forces {forces:?}");
            if let Err(e) = co_simulation(l, m, stop_mode, forces, &mut tally) {
                failures.push(format!("{label}, CS: {e}"));
            }
            for dt in [1e-6, 1e-4, 1e-3] {
                if let Err(e) = model_exchange(l, m, stop_mode, forces, dt, &mut tally) {
                    failures.push(format!("{label}, ME dt {dt}: {e}"));
                }
            }
        }
    }
    (tally, failures)
}
