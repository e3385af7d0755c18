//! The step path of a real-time host: per FMU, standard and interface, one live
//! instance after initialization and the calls a fixed-step controller makes every
//! period, with every buffer allocated beforehand, so that the host itself allocates
//! nothing while it steps.
//!
//! - Co-Simulation: set every Real input, DoStep of 1 ms, get every Real output;
//! - Model Exchange: set every Real input, SetTime, SetContinuousStates (the initial
//!   states moved by a small sinusoid), GetDerivatives, the event indicators, every
//!   Real output and CompletedIntegratorStep (FMI 2.0; FMI 3.0 ME the same calls).
//!
//! `tests/allocations.rs` counts the heap allocations of these calls (zero after
//! initialization) and `robofmu-hostile-steps` times them (median and 99.9th
//! percentile per FMU).

use crate::Loaded;
use crate::binary::{OK, Status, Vr, status_name};
use crate::description::{Description, VarType, Variable};
use crate::fmi3::host::{Instance as Instance3, Interface3, State3};
use crate::host::{Instance, Interface, State};
use crate::sequences::{POSE_REACH, pose_centre};

/// The step size of every Co-Simulation step, s (a 1 kHz controller).
pub const STEP: f64 = 1e-3;

/// The live instance of one case.
enum Live<'a> {
    Fmi2(Instance<'a>),
    Fmi3(Instance3<'a>),
}

/// One case: a live instance in Step Mode (CS) or Continuous-Time Mode (ME) with the
/// buffers of its step path.
pub struct Stepper<'a> {
    /// `<Model> FMI 2.0 CS`, ...
    pub name: String,
    live: Live<'a>,
    me: bool,
    /// Input value references, one per call (FMI 3.0: one per array).
    inputs: Vec<(Vr, Vec<Option<f64>>)>,
    input_values: Vec<f64>,
    outputs: Vec<Vr>,
    output_values: Vec<f64>,
    start_states: Vec<f64>,
    states: Vec<f64>,
    derivatives: Vec<f64>,
    indicators: Vec<f64>,
    time: f64,
}

/// Real variables of `d` with causality `causality`.
fn reals<'d>(d: &'d Description, causality: &'d str) -> impl Iterator<Item = &'d Variable> {
    d.variables
        .iter()
        .filter(move |v| v.causality == causality && v.var_type == VarType::Real)
}

/// Every case of the loaded FMUs: FMI 2.0 and FMI 3.0, Co-Simulation and Model
/// Exchange, each instantiated (logging off, as a real-time host runs) and
/// initialized.
pub fn steppers(l: &Loaded) -> Result<Vec<Stepper<'_>>, String> {
    let mut cases = Vec::new();
    for (fmu, binary) in l.fmus.iter().zip(&l.binaries) {
        for interface in [Interface::CoSimulation, Interface::ModelExchange] {
            let inst = Instance::new(binary, &fmu.description, interface);
            // SAFETY: a live instance; logging off, every category.
            let s = unsafe { (binary.set_debug_logging)(inst.c, 0, 0, std::ptr::null()) };
            check("fmi2SetDebugLogging", s, &|| inst.take_log())?;
            let me = interface == Interface::ModelExchange;
            inst.reach(if me {
                State::ContinuousTimeMode
            } else {
                State::StepComplete
            })?;
            let name = format!("{} FMI 2.0 {}", fmu.name(), interface.short());
            cases.push(Stepper::new(name, Live::Fmi2(inst), &fmu.description, me)?);
        }
    }
    for (fmu, binary) in l.fmus3.iter().zip(&l.binaries3) {
        for interface in [Interface3::CoSimulation, Interface3::ModelExchange] {
            let inst = Instance3::new(binary, &fmu.description, interface);
            // SAFETY: a live instance; logging off, every category.
            let s = unsafe { (binary.set_debug_logging)(inst.c, 0, 0, std::ptr::null()) };
            check("fmi3SetDebugLogging", s, &|| inst.take_log())?;
            let me = interface.is_me();
            inst.reach(if me {
                State3::ContinuousTimeMode
            } else {
                State3::StepMode
            })?;
            let name = format!("{} FMI 3.0 {}", fmu.name(), interface.short());
            cases.push(Stepper::new(name, Live::Fmi3(inst), &fmu.description, me)?);
        }
    }
    Ok(cases)
}

/// Err naming `what`, its status and the instance's log unless `s` is OK.
fn check(what: &str, s: Status, log: &dyn Fn() -> String) -> Result<(), String> {
    if s == OK {
        Ok(())
    } else {
        Err(format!("{what} returned {}: {}", status_name(s), log()))
    }
}

impl<'a> Stepper<'a> {
    fn new(name: String, live: Live<'a>, d: &Description, me: bool) -> Result<Self, String> {
        let fmi3 = matches!(live, Live::Fmi3(_));
        // FMI 2.0 names every element of an array input ("measurement[3]"); FMI 3.0
        // sets an array by one value reference.
        let inputs: Vec<(Vr, Vec<Option<f64>>)> = reals(d, "input")
            .map(|v| {
                let n = if fmi3 { v.size } else { 1 };
                let centres = (0..n).map(|i| pose_centre(&d.model_name, v, i)).collect();
                (v.vr, centres)
            })
            .collect();
        let widest = inputs.iter().map(|(_, c)| c.len()).max().unwrap_or(0);
        let outputs: Vec<Vr> = reals(d, "output").map(|v| v.vr).collect();
        let n_out = if fmi3 {
            d.elements(&outputs)
        } else {
            outputs.len()
        };
        let n = d.number_of_states;
        let mut stepper = Stepper {
            name,
            live,
            me,
            inputs,
            input_values: vec![0.0; widest],
            outputs,
            output_values: vec![0.0; n_out],
            start_states: vec![0.0; n],
            states: vec![0.0; n],
            derivatives: vec![0.0; n],
            indicators: vec![0.0; d.number_of_event_indicators],
            time: 0.0,
        };
        if me {
            let mut x = vec![0.0; n];
            // SAFETY: a live instance in Continuous-Time Mode, a buffer of n states.
            let s = match &stepper.live {
                Live::Fmi2(i) => unsafe {
                    (i.binary.get_continuous_states)(i.c, x.as_mut_ptr(), n)
                },
                Live::Fmi3(i) => unsafe {
                    (i.binary.get_continuous_states)(i.c, x.as_mut_ptr(), n)
                },
            };
            check("GetContinuousStates", s, &|| stepper.log())?;
            stepper.start_states = x;
        }
        Ok(stepper)
    }

    /// The instance's log lines received so far.
    fn log(&self) -> String {
        match &self.live {
            Live::Fmi2(i) => i.take_log(),
            Live::Fmi3(i) => i.take_log(),
        }
    }

    /// One period: inputs, the step (CS) or the derivatives (ME), outputs. The host
    /// side allocates nothing unless a call fails (then the error message does).
    pub fn step(&mut self, k: usize) -> Result<(), String> {
        let t = self.time;
        for j in 0..self.inputs.len() {
            let (vr, ref centres) = self.inputs[j];
            for (i, centre) in centres.iter().enumerate() {
                let x = (t * 3.0 + (j + i) as f64).sin();
                self.input_values[i] = centre.map_or(x, |c| c + POSE_REACH * x);
            }
            let n = centres.len();
            let values = self.input_values.as_ptr();
            // SAFETY: a live instance; one value reference, n values.
            let s = match &self.live {
                Live::Fmi2(i) => unsafe { (i.binary.set_real)(i.c, &vr, 1, values) },
                Live::Fmi3(i) => unsafe { (i.binary.set_float64)(i.c, &vr, 1, values, n) },
            };
            check("set an input", s, &|| self.log())?;
        }
        if self.me {
            self.derivatives_at(t, k)?;
        } else {
            self.do_step(t)?;
        }
        let (vrs, out) = (self.outputs.as_ptr(), self.output_values.as_mut_ptr());
        let (n_vr, n_out) = (self.outputs.len(), self.output_values.len());
        // SAFETY: arrays of the lengths given.
        let s = match &self.live {
            Live::Fmi2(i) => unsafe { (i.binary.get_real)(i.c, vrs, n_vr, out) },
            Live::Fmi3(i) => unsafe { (i.binary.get_float64)(i.c, vrs, n_vr, out, n_out) },
        };
        check("get the outputs", s, &|| self.log())?;
        self.time += STEP;
        Ok(())
    }

    fn do_step(&mut self, t: f64) -> Result<(), String> {
        let s = match &self.live {
            // SAFETY: a live instance in Step Mode.
            Live::Fmi2(i) => unsafe { (i.binary.do_step)(i.c, t, STEP, 1) },
            Live::Fmi3(i) => {
                let (mut event, mut stop, mut early, mut last) = (0u8, 0u8, 0u8, 0.0);
                // SAFETY: four outputs to fill.
                unsafe {
                    (i.binary.do_step)(
                        i.c, t, STEP, 1, &mut event, &mut stop, &mut early, &mut last,
                    )
                }
            }
        };
        check("DoStep", s, &|| self.log())
    }

    fn derivatives_at(&mut self, t: f64, k: usize) -> Result<(), String> {
        for (i, (x, x0)) in self.states.iter_mut().zip(&self.start_states).enumerate() {
            *x = x0 + 1e-3 * ((k + i) as f64 * 0.01).sin();
        }
        let (n, n_ei) = (self.states.len(), self.indicators.len());
        let (x, dx) = (self.states.as_ptr(), self.derivatives.as_mut_ptr());
        let z = self.indicators.as_mut_ptr();
        let (mut enter_event, mut terminate) = (0, 0);
        let (mut event3, mut terminate3) = (0u8, 0u8);
        // SAFETY: a live instance in Continuous-Time Mode; buffers of n states and
        // n_ei indicators.
        let statuses = match &self.live {
            Live::Fmi2(i) => unsafe {
                let b = i.binary;
                [
                    (b.set_time)(i.c, t),
                    (b.set_continuous_states)(i.c, x, n),
                    (b.get_derivatives)(i.c, dx, n),
                    (b.get_event_indicators)(i.c, z, n_ei),
                    (b.completed_integrator_step)(i.c, 1, &mut enter_event, &mut terminate),
                ]
            },
            Live::Fmi3(i) => unsafe {
                let b = i.binary;
                [
                    (b.set_time)(i.c, t),
                    (b.set_continuous_states)(i.c, x, n),
                    (b.get_continuous_state_derivatives)(i.c, dx, n),
                    (b.get_event_indicators)(i.c, z, n_ei),
                    (b.completed_integrator_step)(i.c, 1, &mut event3, &mut terminate3),
                ]
            },
        };
        const CALLS: [&str; 5] = [
            "SetTime",
            "SetContinuousStates",
            "GetDerivatives",
            "GetEventIndicators",
            "CompletedIntegratorStep",
        ];
        for (call, s) in CALLS.iter().zip(statuses) {
            check(call, s, &|| self.log())?;
        }
        if enter_event != 0 || event3 != 0 {
            return Err(format!("{}: an event at t = {t} s", self.name));
        }
        Ok(())
    }
}
