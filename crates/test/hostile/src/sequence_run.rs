//! The bookkeeping of a random legal call sequence, shared by the FMI 2.0 driver
//! (`sequences`) and the FMI 3.0 one (`fmi3::sequences`): the instance, the random
//! generator, the state the importer tracks, the time and the count of calls; the
//! status check of every call, and the calls whose logic is the same in both
//! standards (set the time, perturb the continuous states, a mode transition).
//! Which call is legal in which state stays with each standard's driver.

use crate::Loaded;
use crate::binary::{DISCARD, OK, Status, status_name};
use crate::description::{Description, VarType, Variable};
use crate::host::{Probed, take};
use crate::rng::SplitMix64;
use crate::standard_interface::{StandardInterface, Transition};

/// One sequence on one instance.
pub struct Run<'a, I: StandardInterface> {
    pub inst: I::Instance<'a>,
    pub interface: I,
    pub rng: SplitMix64,
    pub state: I::State,
    pub time: f64,
    pub calls: usize,
    /// fmi3UpdateDiscreteStates asked to be called again (FMI 3.0 only).
    pub update_needed: bool,
}

/// One random call legal in the run's current state.
pub type Step<I> = fn(&mut Run<'_, I>) -> Result<(), String>;

impl<I: StandardInterface> Run<'_, I> {
    /// Records a call; Err when its status is not acceptable.
    pub fn check(&mut self, what: &str, s: Status, may_discard: bool) -> Result<Status, String> {
        self.calls += 1;
        if s == OK || (s == DISCARD && may_discard) {
            Ok(s)
        } else {
            Err(format!(
                "call {} {what} in {:?} returned {} (log: {})",
                self.calls,
                self.state,
                status_name(s),
                take(self.inst.log())
            ))
        }
    }

    /// Model Exchange.
    pub fn me(&self) -> bool {
        self.interface == I::MODEL_EXCHANGE
    }

    /// A mode transition (or fmiXTerminate, fmiXReset) into `to`.
    pub fn transition(&mut self, what: &str, f: Transition, to: I::State) -> Result<(), String> {
        let (_, handle) = I::raw(&self.inst);
        // SAFETY: a live instance.
        let s = unsafe { f(handle.into()) };
        self.check(what, s, false)?;
        self.state = to;
        Ok(())
    }

    /// Moves the continuous states by a random trial step.
    pub fn perturb_states(&mut self, n: usize) -> Result<(), String> {
        let mut x = vec![0.0; n];
        let (binary, handle) = I::raw(&self.inst);
        let (get, set) = I::continuous_states(binary);
        // SAFETY: arrays of the state count.
        let s = unsafe { get(handle.into(), x.as_mut_ptr(), n) };
        self.check(&format!("{}GetContinuousStates", I::PREFIX), s, false)?;
        // Small trial steps mostly, sometimes a large one (an integrator's
        // rejected trial): both may leave the region where the model evaluates.
        let reach = if self.rng.below(4) == 0 { 0.5 } else { 0.05 };
        for xi in &mut x {
            *xi += self.rng.uniform(-reach, reach);
        }
        let s = unsafe { set(handle.into(), x.as_ptr(), n) };
        self.check(&format!("{}SetContinuousStates", I::PREFIX), s, false)?;
        Ok(())
    }

    /// Get, serialize, deserialize and set back the state: nothing changes.
    pub fn state_round_trip(&mut self) -> Result<(), String> {
        let name = |verb: &str| format!("{}{verb}{}", I::PREFIX, I::FMU_STATE);
        let (s, state) = self.inst.new_state();
        self.check(&name("Get"), s, false)?;
        let bytes = I::serialize(&self.inst, state)?;
        self.calls += 2;
        let (s, copy) = I::deserialize(&self.inst, &bytes);
        self.check(I::DESERIALIZE, s, false)?;
        // SAFETY: a state this instance just deserialized.
        let s = unsafe { I::set_state(&self.inst, copy) };
        self.check(&name("Set"), s, false)?;
        let s = self.inst.release_state(copy);
        self.check(&name("Free"), s, false)?;
        let s = self.inst.release_state(state);
        self.check(&name("Free"), s, false)?;
        Ok(())
    }

    /// Err when a call that returned OK delivered a value that is not finite.
    pub fn finite(&self, what: &str, s: Status, x: &[f64]) -> Result<(), String> {
        match x.iter().position(|v| !v.is_finite()) {
            Some(i) if s == OK => Err(format!("{what} returned OK with element {i} = {}", x[i])),
            _ => Ok(()),
        }
    }

    /// The state derivatives and the event indicators of model `d` (Model
    /// Exchange): Discard accepted, finite when OK.
    pub fn derivatives_and_indicators(&mut self, d: &Description) -> Result<(), String> {
        let mut dx = vec![0.0; d.number_of_states];
        let mut z = vec![0.0; d.number_of_event_indicators];
        let (binary, handle) = I::raw(&self.inst);
        let (_, derivatives, indicators) = I::me_evaluation(binary);
        // SAFETY: arrays of the declared sizes.
        let s = unsafe { derivatives(handle.into(), dx.as_mut_ptr(), dx.len()) };
        let s = self.check(I::DERIVATIVES, s, true)?;
        self.finite(I::DERIVATIVES, s, &dx)?;
        let s = unsafe { indicators(handle.into(), z.as_mut_ptr(), z.len()) };
        let what = format!("{}GetEventIndicators", I::PREFIX);
        let s = self.check(&what, s, true)?;
        self.finite(&what, s, &z)
    }

    /// Advances the time of Model Exchange by a random step.
    pub fn advance_time(&mut self) -> Result<(), String> {
        self.time += self.rng.uniform(1e-4, 1e-2);
        let (binary, handle) = I::raw(&self.inst);
        // SAFETY: a live instance and a finite time.
        let s = unsafe { I::set_time(binary)(handle.into(), self.time) };
        self.check(&format!("{}SetTime", I::PREFIX), s, false)?;
        Ok(())
    }
}

/// A Real input of model `d` drawn with `rng` (None, and nothing drawn, when it
/// has none).
pub fn random_input<'d>(d: &'d Description, rng: &mut SplitMix64) -> Option<&'d Variable> {
    let inputs: Vec<&Variable> = d
        .variables
        .iter()
        .filter(|v| v.causality == "input" && v.var_type == VarType::Real)
        .collect();
    (!inputs.is_empty()).then(|| inputs[rng.below(inputs.len())])
}

/// Runs sequence `seed` of a standard, `label` naming it in failures: a model, an
/// interface and a length drawn from the seed, then `step` that many times. The
/// number of calls, or what went wrong.
pub fn run_sequence<I: StandardInterface>(
    l: &Loaded,
    (seed, label): (u64, &str),
    step: Step<I>,
) -> Result<usize, String> {
    let mut rng = SplitMix64::new(seed);
    let m = rng.below(crate::fmu::models().len());
    let interface = I::INTERFACES[rng.below(I::INTERFACES.len())];
    let length = 10 + rng.below(30);
    let mut run = Run {
        inst: interface.instance(l, m),
        interface,
        rng,
        state: I::INSTANTIATED,
        time: 0.0,
        calls: 1,
        update_needed: false,
    };
    for _ in 0..length {
        step(&mut run).map_err(|e| {
            format!(
                "{label}seed {seed:#x} ({} {}): {e}",
                l.fmus[m].name(),
                interface.short()
            )
        })?;
    }
    Ok(run.calls + 1)
}
