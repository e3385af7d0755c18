//! Random sequences of legal FMI 3.0 calls with legal arguments, from a fixed seed
//! (the FMI 2.0 rules of `crate::sequences`, on the FMI 3.0 state machines). The
//! importer tracks the state itself and picks one of the calls the standard allows
//! there, for Model Exchange, Co-Simulation and Co-Simulation with event mode
//! (where a step that meets an event, such as the plant reaching an end stop,
//! returns early and the importer iterates the event in Event Mode). It follows the
//! FMU's requests: enter Event Mode when fmi3CompletedIntegratorStep or fmi3DoStep
//! asks for it, update discrete states until no update is needed, terminate when
//! asked to. A legal sequence never produces fmi3Error or fmi3Fatal; fmi3Discard
//! is accepted for a step and for Model Exchange evaluations at states the
//! integrator chose; a call that returns fmi3OK never delivers NaN or inf.

use super::host::{Interface3, State3};
use crate::Loaded;
use crate::binary::DISCARD;
use crate::description::{VarType, Variable};
use crate::sequence_run::{self, random_input};
use crate::sequences::{POSE_REACH, input_scale, pose_centre};

/// FMI 3.0 sequences run by default: a third of the FMI 2.0 count, because one
/// costs about 4 times the CPU time of an FMI 2.0 sequence (measured: 20,000 took
/// 28 s, 30,000 FMI 2.0 ones 10.5 s); 10,000 add about 14 s to CI.
/// ROBOFMU_HOSTILE_SEQUENCES overrides.
pub const DEFAULT_SEQUENCES: usize = 10_000;

/// The legal values of the Int32 parameters the sequences set (their min and max
/// in the modelDescription).
fn legal_integers(v: &Variable) -> &'static [i32] {
    match v.name.as_str() {
        "endStopMode" => &[1, 2],
        "order" => &[3, 5],
        _ => &[],
    }
}

type Run<'a> = sequence_run::Run<'a, Interface3>;

impl Run<'_> {
    fn set_input(&mut self) -> Result<(), String> {
        let Some(v) = random_input(self.inst.description, &mut self.rng) else {
            return Ok(());
        };
        // Now and then a force far beyond what the plant's stops hold back.
        let scale = input_scale(v) * if self.rng.below(8) == 0 { 100.0 } else { 1.0 };
        let model = &self.inst.description.model_name;
        let x: Vec<f64> = (0..v.size)
            .map(|i| match pose_centre(model, v, i) {
                Some(c) => c + self.rng.uniform(-POSE_REACH, POSE_REACH),
                None => self.rng.uniform(-scale, scale),
            })
            .collect();
        let s = self.inst.set_float64(&[v.vr], &x);
        self.check(&format!("fmi3SetFloat64({} = {x:?})", v.name), s, false)?;
        Ok(())
    }

    fn set_parameter(&mut self) -> Result<(), String> {
        let d = self.inst.description;
        let Some(v) = d
            .of_type(VarType::Integer)
            .find(|v| !legal_integers(v).is_empty())
        else {
            return self.set_input();
        };
        let values = legal_integers(v);
        let n = values[self.rng.below(values.len())];
        // SAFETY: one scalar Int32 and its value.
        let s = unsafe { (self.inst.binary.set_int32)(self.inst.c, &v.vr, 1, &n, 1) };
        self.check(&format!("fmi3SetInt32({} = {n})", v.name), s, false)?;
        Ok(())
    }

    fn get_all(&mut self) -> Result<(), String> {
        let (s, x) = self.inst.get_all();
        let may_discard = self.me() || self.state == State3::StepDiscarded;
        let s = self.check("fmi3GetFloat64(all)", s, may_discard)?;
        self.finite("fmi3GetFloat64(all)", s, &x)
    }

    /// Derivatives, event indicators and a random partial derivative (ME).
    fn evaluate(&mut self) -> Result<(), String> {
        let d = self.inst.description;
        let b = self.inst.binary;
        self.derivatives_and_indicators(d)?;
        let pairs = d.state_derivative_pairs();
        if d.provides_directional_derivative && !pairs.is_empty() {
            let (x, der) = pairs[self.rng.below(pairs.len())];
            let n = d.elements(&[x]);
            let seed: Vec<f64> = (0..n).map(|_| self.rng.uniform(-1.0, 1.0)).collect();
            let mut out = vec![0.0; n];
            let adjoint = self.rng.below(2) == 0;
            let (f, name) = if adjoint {
                (b.get_adjoint_derivative, "fmi3GetAdjointDerivative")
            } else {
                (b.get_directional_derivative, "fmi3GetDirectionalDerivative")
            };
            // SAFETY: arrays of the variables' element counts.
            let s = unsafe {
                f(
                    self.inst.c,
                    &der,
                    1,
                    &x,
                    1,
                    seed.as_ptr(),
                    n,
                    out.as_mut_ptr(),
                    n,
                )
            };
            let s = self.check(name, s, true)?;
            self.finite(name, s, &out)?;
        }
        Ok(())
    }

    fn terminate(&mut self) -> Result<(), String> {
        let b = self.inst.binary;
        self.transition("fmi3Terminate", b.terminate, State3::Terminated)
    }

    fn reset(&mut self) -> Result<(), String> {
        self.transition("fmi3Reset", self.inst.binary.reset, State3::Instantiated)?;
        self.time = 0.0;
        self.update_needed = false;
        Ok(())
    }

    fn update_discrete_states(&mut self) -> Result<(), String> {
        let mut flags = [0u8; 5];
        let mut next = 0.0;
        let [need, stop, nominals, values, defined] = &mut flags;
        // SAFETY: six outputs to fill.
        let s = unsafe {
            (self.inst.binary.update_discrete_states)(
                self.inst.c,
                need,
                stop,
                nominals,
                values,
                defined,
                &mut next,
            )
        };
        self.check("fmi3UpdateDiscreteStates", s, false)?;
        self.update_needed = flags[0] != 0;
        if flags[1] != 0 {
            return self.terminate();
        }
        Ok(())
    }

    fn completed_integrator_step(&mut self) -> Result<(), String> {
        let (mut enter, mut stop) = (0u8, 0u8);
        let b = self.inst.binary;
        // SAFETY: two flags to fill.
        let s = unsafe { (b.completed_integrator_step)(self.inst.c, 1, &mut enter, &mut stop) };
        self.check("fmi3CompletedIntegratorStep", s, false)?;
        if stop != 0 {
            self.terminate()
        } else if enter != 0 {
            self.transition("fmi3EnterEventMode", b.enter_event_mode, State3::EventMode)
        } else {
            Ok(())
        }
    }

    fn do_step(&mut self) -> Result<(), String> {
        let h = self.rng.uniform(1e-4, 1e-2);
        let step = self.inst.do_step(self.time, h);
        let what = format!("fmi3DoStep(t = {}, h = {h})", self.time);
        if self.check(&what, step.status, true)? == DISCARD {
            self.state = State3::StepDiscarded;
            return Ok(());
        }
        if step.early_return && !step.last_successful_time.is_finite() {
            return Err(format!(
                "{what}: early return at t = {}",
                step.last_successful_time
            ));
        }
        self.time = if step.early_return {
            step.last_successful_time
        } else {
            self.time + h
        };
        if step.terminate {
            self.terminate()
        } else if step.event_handling_needed
            && self.inst.interface == Interface3::CoSimulationEvents
        {
            let b = self.inst.binary;
            self.transition("fmi3EnterEventMode", b.enter_event_mode, State3::EventMode)
        } else {
            Ok(())
        }
    }

    fn leave_event_mode(&mut self) -> Result<(), String> {
        let b = self.inst.binary;
        match self.inst.interface {
            Interface3::ModelExchange => self.transition(
                "fmi3EnterContinuousTimeMode",
                b.enter_continuous_time_mode,
                State3::ContinuousTimeMode,
            ),
            _ => self.transition("fmi3EnterStepMode", b.enter_step_mode, State3::StepMode),
        }
    }

    /// One random call that is legal in the current state.
    fn step(&mut self) -> Result<(), String> {
        let b = self.inst.binary;
        let choice = self.rng.below(8);
        match (self.state, choice) {
            (State3::Instantiated, 0..=1) => self.set_input(),
            (State3::Instantiated, 2) => self.set_parameter(),
            (State3::Instantiated, 3) => self.state_round_trip(),
            (State3::Instantiated, _) => {
                // SAFETY: a live instance; no tolerance, start 0, no stop time.
                let s = unsafe { (b.enter_initialization_mode)(self.inst.c, 0, 0.0, 0.0, 0, 0.0) };
                self.check("fmi3EnterInitializationMode", s, false)?;
                self.state = State3::InitializationMode;
                Ok(())
            }
            (State3::InitializationMode, 0..=1) => self.set_input(),
            (State3::InitializationMode, 2) => self.get_all(),
            (State3::InitializationMode, 3) => self.state_round_trip(),
            (State3::InitializationMode, _) => {
                let to = self.inst.interface.after_initialization();
                self.transition("fmi3ExitInitializationMode", b.exit_initialization_mode, to)
            }
            (State3::EventMode, _) if self.update_needed => self.update_discrete_states(),
            (State3::EventMode, 0) => self.set_input(),
            (State3::EventMode, 1) => self.get_all(),
            (State3::EventMode, 2) => self.update_discrete_states(),
            (State3::EventMode, 3) if self.me() => self.evaluate(),
            (State3::EventMode, 4) => self.state_round_trip(),
            (State3::EventMode, 5) if self.rng.below(8) == 0 => self.terminate(),
            (State3::EventMode, _) => self.leave_event_mode(),
            (State3::ContinuousTimeMode, 0) => self.set_input(),
            (State3::ContinuousTimeMode, 1) => self.get_all(),
            (State3::ContinuousTimeMode, 2) => self.advance_time(),
            (State3::ContinuousTimeMode, 3) => {
                self.perturb_states(self.inst.description.number_of_states)
            }
            (State3::ContinuousTimeMode, 4) => self.evaluate(),
            (State3::ContinuousTimeMode, 5) => self.state_round_trip(),
            (State3::ContinuousTimeMode, 6) => self.completed_integrator_step(),
            (State3::ContinuousTimeMode, _) => {
                self.transition("fmi3EnterEventMode", b.enter_event_mode, State3::EventMode)
            }
            (State3::StepMode, 0..=1) => self.set_input(),
            (State3::StepMode, 2) => self.get_all(),
            (State3::StepMode, 3) => self.state_round_trip(),
            (State3::StepMode, 4) if self.rng.below(8) == 0 => self.terminate(),
            (State3::StepMode, _) => self.do_step(),
            (State3::StepDiscarded, 0..=2) => self.get_all(),
            (State3::StepDiscarded, 3) => self.terminate(),
            (State3::StepDiscarded, _) => self.reset(),
            (State3::Terminated, 0..=3) => self.get_all(),
            (State3::Terminated, _) => self.reset(),
            (State3::Error, _) => Err("reached the Error state".into()),
        }
    }
}

/// Runs FMI 3.0 sequence `seed`: the number of calls, or what went wrong.
pub fn run_sequence(l: &Loaded, seed: u64) -> Result<usize, String> {
    sequence_run::run_sequence::<Interface3>(l, (seed, "FMI 3.0 "), |run| run.step())
}
