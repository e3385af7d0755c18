//! Eight threads, each simulating its own instance (FMI 2.0 and FMI 3.0 let
//! instances of one binary run in parallel on different threads), against the same
//! eight simulations run one after the other: the outputs must be identical bit for
//! bit (no shared mutable state between instances). The FMI 3.0 simulations run in
//! Co-Simulation with event mode, so that events are handled in Event Mode.

use crate::Loaded;
use crate::binary::OK;
use crate::description::Variable;
use crate::fmi3::host::{Instance as Instance3, Interface3};
use crate::fmi3::lifecycle::{co_simulation_step, running};
use crate::host::{Instance, Interface, State};
use crate::sequences::{POSE_REACH, pose_centre};

/// Simulation k of model m: every output of every step, as bits.
pub type Simulation = fn(&Loaded, usize, usize) -> Result<Vec<u64>, String>;

/// Input j of simulation k at time t: a sinusoid of a k-dependent frequency (element i
/// of a measured pose: that sinusoid times POSE_REACH about the pose's centre).
fn input(k: usize, j: usize, t: f64, pose: Option<f64>) -> f64 {
    let x = (t * (1.0 + k as f64) + j as f64).sin();
    pose.map_or(x, |c| c + POSE_REACH * x)
}

/// The FMI 3.0 version of `simulate`: Co-Simulation with event mode, the inputs
/// element by element.
pub fn simulate3(l: &Loaded, m: usize, k: usize) -> Result<Vec<u64>, String> {
    let d = &l.fmus3[m].description;
    let interface = Interface3::CoSimulationEvents;
    let inst = Instance3::new(&l.binaries3[m], d, interface);
    inst.reach(running(interface))?;
    let inputs: Vec<&Variable> = d
        .variables
        .iter()
        .filter(|v| v.causality == "input" && v.var_type == crate::description::VarType::Real)
        .collect();
    let mut bits = Vec::new();
    let h = 1e-3;
    for step in 0..STEPS {
        let t = step as f64 * h;
        let mut j = 0;
        for v in &inputs {
            let values: Vec<f64> = (0..v.size)
                .map(|i| input(k, j + i, t, pose_centre(&d.model_name, v, i)))
                .collect();
            j += v.size;
            inst.set_float64(&[v.vr], &values);
        }
        co_simulation_step(&inst, t, h)?;
        let (g, values) = inst.get_all();
        if g != OK {
            return Err(format!("fmi3GetFloat64 returned {g}: {}", inst.take_log()));
        }
        bits.extend(values.iter().map(|x| x.to_bits()));
    }
    Ok(bits)
}

pub const THREADS: usize = 8;
pub const STEPS: usize = 300;

/// Simulation `k` of model `m`: Co-Simulation steps of 1 ms with inputs that are
/// sinusoids of a k-dependent frequency; every Real output of every step, as bits.
pub fn simulate(l: &Loaded, m: usize, k: usize) -> Result<Vec<u64>, String> {
    let d = &l.fmus[m].description;
    let inst = Instance::new(&l.binaries[m], d, Interface::CoSimulation);
    inst.reach(State::StepComplete)?;
    let inputs: Vec<&Variable> = d
        .variables
        .iter()
        .filter(|v| v.causality == "input")
        .filter(|v| v.var_type == crate::description::VarType::Real)
        .collect();
    let outputs = d.real_vrs();
    let mut bits = Vec::with_capacity(STEPS * outputs.len());
    let h = 1e-3;
    for step in 0..STEPS {
        let t = step as f64 * h;
        for (j, v) in inputs.iter().enumerate() {
            let value = input(k, j, t, pose_centre(&d.model_name, v, 0));
            inst.set_real(v.vr, value);
        }
        let s = inst.do_step(t, h);
        let (g, values) = inst.get_reals(&outputs);
        if g != OK {
            return Err(format!("fmi2GetReal returned {g}: {}", inst.take_log()));
        }
        bits.push(s as u64);
        bits.extend(values.iter().map(|x| x.to_bits()));
    }
    Ok(bits)
}

/// (simulations that differ between the serial and the threaded run, simulations)
/// for the simulations of one standard (`simulate` or `simulate3`).
pub fn compare(l: &Loaded, simulate: Simulation) -> Result<(usize, usize), String> {
    let mut jobs = Vec::new();
    for m in 0..l.fmus.len() {
        for k in 0..THREADS {
            jobs.push((m, k));
        }
    }
    let serial: Vec<Result<Vec<u64>, String>> =
        jobs.iter().map(|&(m, k)| simulate(l, m, k)).collect();
    let mut threaded = Vec::new();
    for m in 0..l.fmus.len() {
        let per_model: Vec<Result<Vec<u64>, String>> = std::thread::scope(|scope| {
            let handles: Vec<_> = (0..THREADS)
                .map(|k| scope.spawn(move || simulate(l, m, k)))
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().unwrap_or_else(|_| Err("thread panicked".into())))
                .collect()
        });
        threaded.extend(per_model);
    }
    let mut differ = 0;
    for (s, t) in serial.iter().zip(&threaded) {
        let (s, t) = (s.as_ref()?, t.as_ref()?);
        if s != t {
            differ += 1;
        }
    }
    Ok((differ, jobs.len()))
}
