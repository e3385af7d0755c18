//! Random sequences of legal calls with legal arguments, from a fixed seed. The
//! importer tracks the FMI 2.0 state machine itself and picks, at each step, one of
//! the calls the standard allows in the current state. A legal sequence must never
//! produce fmi2Error or fmi2Fatal; fmi2Discard is accepted where the model may be
//! unable to evaluate (a step, or a Model Exchange evaluation at a state the
//! integrator chose); a getter that returns fmi2OK never delivers NaN or inf.

use crate::Loaded;
use crate::binary::{EventInfo, OK};
use crate::description::Variable;
use crate::host::{Interface, State};
use crate::sequence_run::{self, random_input};

/// FMI 2.0 sequences run by default; ROBOFMU_HOSTILE_SEQUENCES overrides.
pub const DEFAULT_SEQUENCES: usize = 30_000;
/// The seed of sequence i is BASE_SEED + i.
pub const BASE_SEED: u64 = 0x5EED_F0F0;

/// ROBOFMU_HOSTILE_SEQUENCES when set (for both standards), else `default`.
pub fn count_from_env(default: usize) -> usize {
    std::env::var("ROBOFMU_HOSTILE_SEQUENCES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

/// Plausible magnitude of an input.
pub(crate) fn input_scale(v: &Variable) -> f64 {
    match v.name.split('[').next().unwrap_or("") {
        "actuatorForce" => 100.0,
        "torqueCommand" | "generalizedForceCommand" | "disturbanceTorque" => 10.0,
        _ => 2.0,
    }
}

/// The start pose of the robot, rad: (0, 0, 139.79 deg).
const START_POSE: [f64; 3] = [0.0, 0.0, 2.439_788];
/// How far a plausible measured pose lies from the start pose, per angle, rad (3 deg).
pub(crate) const POSE_REACH: f64 = 0.05;

/// The centre of element `i` of input `v` of `model` when the input is a measured pose:
/// the ComputedTorque's `measurement` (Euler angles). Its model cannot be evaluated
/// where the legs cannot reach (Discard from every getter, issue 20), so a plausible
/// one lies within POSE_REACH of the start pose; None for every other input.
pub(crate) fn pose_centre(model: &str, v: &Variable, i: usize) -> Option<f64> {
    let (base, index) = v.name.split_once('[').unwrap_or((&v.name, ""));
    if model != "ComputedTorque" || base != "measurement" {
        return None;
    }
    // FMI 2.0 names the element ("measurement[3]"); FMI 3.0 passes its index.
    let element = index
        .trim_end_matches(']')
        .parse::<usize>()
        .map_or(i, |k| k - 1);
    START_POSE.get(element).copied()
}

type Run<'a> = sequence_run::Run<'a, Interface>;

impl Run<'_> {
    fn set_input(&mut self) -> Result<(), String> {
        let Some(v) = random_input(self.inst.description, &mut self.rng) else {
            return Ok(());
        };
        let scale = input_scale(v);
        let x = match pose_centre(&self.inst.description.model_name, v, 0) {
            Some(c) => c + self.rng.uniform(-POSE_REACH, POSE_REACH),
            None => self.rng.uniform(-scale, scale),
        };
        let s = self.inst.set_real(v.vr, x);
        self.check(&format!("fmi2SetReal({} = {x})", v.name), s, false)?;
        Ok(())
    }

    fn get_all(&mut self) -> Result<(), String> {
        let vrs = self.inst.description.real_vrs();
        let (s, x) = self.inst.get_reals(&vrs);
        let s = self.check("fmi2GetReal(all)", s, self.me())?;
        if s == OK
            && let Some(i) = x.iter().position(|v| !v.is_finite())
        {
            return Err(format!(
                "fmi2GetReal returned fmi2OK with {} = {}",
                self.inst
                    .description
                    .variables
                    .iter()
                    .find(|v| v.vr == vrs[i])
                    .map_or("?", |v| &v.name),
                x[i]
            ));
        }
        Ok(())
    }

    fn evaluate(&mut self) -> Result<(), String> {
        let d = self.inst.description;
        let b = self.inst.binary;
        self.derivatives_and_indicators(d)?;
        if d.provides_directional_derivative && !d.state_derivative_pairs().is_empty() {
            let (x, der) = d.state_derivative_pairs()[self.rng.below(d.number_of_states)];
            let mut out = 0.0;
            // SAFETY: one reference each, one seed and one output.
            let s = unsafe {
                (b.get_directional_derivative)(self.inst.c, &der, 1, &x, 1, &1.0, &mut out)
            };
            if self.check("fmi2GetDirectionalDerivative", s, true)? == OK && !out.is_finite() {
                return Err(
                    "fmi2GetDirectionalDerivative returned fmi2OK with a non-finite value".into(),
                );
            }
        }
        Ok(())
    }

    fn reset(&mut self) -> Result<(), String> {
        self.transition("fmi2Reset", self.inst.binary.reset, State::Instantiated)?;
        self.time = 0.0;
        Ok(())
    }

    /// One random call that is legal in the current state.
    fn step(&mut self) -> Result<(), String> {
        let b = self.inst.binary;
        let choice = self.rng.below(8);
        match (self.state, choice) {
            (State::Instantiated, 0..=2) => self.set_input(),
            (State::Instantiated, 3) => self.state_round_trip(),
            (State::Instantiated, _) => {
                // SAFETY: a live instance.
                let s = unsafe { (b.setup_experiment)(self.inst.c, 0, 0.0, 0.0, 0, 0.0) };
                self.check("fmi2SetupExperiment", s, false)?;
                self.transition(
                    "fmi2EnterInitializationMode",
                    b.enter_initialization_mode,
                    State::InitializationMode,
                )
            }
            (State::InitializationMode, 0..=1) => self.set_input(),
            (State::InitializationMode, 2) => self.get_all(),
            (State::InitializationMode, 3) => self.state_round_trip(),
            (State::InitializationMode, _) => {
                let to = if self.me() {
                    State::EventMode
                } else {
                    State::StepComplete
                };
                self.transition("fmi2ExitInitializationMode", b.exit_initialization_mode, to)
            }
            (State::EventMode, 0) => self.set_input(),
            (State::EventMode, 1) => self.get_all(),
            (State::EventMode, 2) => {
                let mut info = EventInfo::default();
                // SAFETY: a live instance and an event info to fill.
                let s = unsafe { (b.new_discrete_states)(self.inst.c, &mut info) };
                self.check("fmi2NewDiscreteStates", s, false).map(|_| ())
            }
            (State::EventMode, 3) => self.evaluate(),
            (State::EventMode, 4) => self.state_round_trip(),
            (State::EventMode, 5) if self.rng.below(8) == 0 => {
                self.transition("fmi2Terminate", b.terminate, State::Terminated)
            }
            (State::EventMode, _) => self.transition(
                "fmi2EnterContinuousTimeMode",
                b.enter_continuous_time_mode,
                State::ContinuousTimeMode,
            ),
            (State::ContinuousTimeMode, 0) => self.set_input(),
            (State::ContinuousTimeMode, 1) => self.get_all(),
            (State::ContinuousTimeMode, 2) => self.advance_time(),
            (State::ContinuousTimeMode, 3) => {
                self.perturb_states(self.inst.description.number_of_states)
            }
            (State::ContinuousTimeMode, 4) => self.evaluate(),
            (State::ContinuousTimeMode, 5) => self.state_round_trip(),
            (State::ContinuousTimeMode, 6) => {
                let (mut enter, mut stop) = (0, 0);
                // SAFETY: two flags to fill.
                let s =
                    unsafe { (b.completed_integrator_step)(self.inst.c, 1, &mut enter, &mut stop) };
                self.check("fmi2CompletedIntegratorStep", s, false)
                    .map(|_| ())
            }
            (State::ContinuousTimeMode, _) => {
                self.transition("fmi2EnterEventMode", b.enter_event_mode, State::EventMode)
            }
            (State::StepComplete, 0..=1) => self.set_input(),
            (State::StepComplete, 2) => self.get_all(),
            (State::StepComplete, 3) => self.state_round_trip(),
            (State::StepComplete, 4) if self.rng.below(8) == 0 => {
                self.transition("fmi2Terminate", b.terminate, State::Terminated)
            }
            (State::StepComplete, _) => {
                let h = self.rng.uniform(1e-4, 1e-2);
                let s = self.inst.do_step(self.time, h);
                if self.check(&format!("fmi2DoStep(t = {}, h = {h})", self.time), s, true)? == OK {
                    self.time += h;
                } else {
                    self.state = State::StepFailed;
                }
                Ok(())
            }
            (State::StepFailed, 0..=3) => self.get_all(),
            (State::StepFailed, _) => self.reset(),
            (State::Terminated, 0..=3) => self.get_all(),
            (State::Terminated, _) => self.reset(),
            (State::Error, _) => Err("reached the Error state".into()),
        }
    }
}

/// Runs sequence `seed`: the number of calls, or what went wrong.
pub fn run_sequence(l: &Loaded, seed: u64) -> Result<usize, String> {
    sequence_run::run_sequence::<Interface>(l, (seed, ""), |run| run.step())
}
