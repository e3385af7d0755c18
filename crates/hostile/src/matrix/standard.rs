//! FMI 2.0 as a `StandardInterface`: its two interfaces, eight states, fmi2
//! instances and call arguments.

use super::calls::Args;
use crate::Loaded;
use crate::binary::{Binary, Component, ERROR, OK, Status};
use crate::host::{Instance, Interface, State};
use crate::standard_interface::{
    FreeInstance, GetArray, SetStates, SetTime, StandardInterface, Transition,
};
use std::ffi::c_void;

impl StandardInterface for Interface {
    type State = State;
    type Instance<'a> = Instance<'a>;
    type Binary = Binary;
    type Handle = Component;
    type Args = Args;

    const INTERFACES: &'static [Interface] = &Interface::BOTH;
    const STATES: &'static [State] = &State::ALL;
    const PREFIX: &'static str = "fmi2";
    const FMU_STATE: &'static str = "FMUstate";
    const DESERIALIZE: &'static str = "fmi2DeSerializeFMUstate";
    const DERIVATIVES: &'static str = "fmi2GetDerivatives";
    const INSTANTIATED: State = State::Instantiated;
    const INITIALIZATION_MODE: State = State::InitializationMode;
    const MODEL_EXCHANGE: Interface = Interface::ModelExchange;
    const CONTINUOUS_TIME_MODE: State = State::ContinuousTimeMode;

    fn short(self) -> &'static str {
        Interface::short(self)
    }
    fn instance(self, loaded: &Loaded, m: usize) -> Instance<'_> {
        Instance::new(&loaded.binaries[m], &loaded.fmus[m].description, self)
    }
    /// StepFailed is reached with a discarded step, which needs a force input.
    fn reachable(self, loaded: &Loaded, m: usize, state: State) -> bool {
        state.exists_for(self)
            && (state != State::StepFailed
                || loaded.fmus[m]
                    .description
                    .variables
                    .iter()
                    .any(|v| v.name == "actuatorForce[1]"))
    }
    fn reach(inst: &Instance<'_>, state: State) -> Result<(), String> {
        inst.reach(state)
    }
    /// An FMI 2.0 instance in Error can only be freed; what it still reports
    /// must not be a silent NaN: after fmi2Error, outputs read with fmi2OK are
    /// finite.
    fn usable_after(inst: &Instance<'_>, status: Status) -> Result<(), String> {
        if status != ERROR {
            return Ok(());
        }
        let (s, x) = inst.get_reals(&inst.description.real_vrs());
        if s == OK && x.iter().any(|v| !v.is_finite()) {
            return Err("outputs not finite after the refusal".into());
        }
        Ok(())
    }
    fn raw<'i>(inst: &'i Instance<'_>) -> (&'i Binary, Component) {
        (inst.binary, inst.c)
    }
    fn continuous_states(b: &Binary) -> (GetArray, SetStates) {
        (b.get_continuous_states, b.set_continuous_states)
    }
    fn serialize(inst: &Instance<'_>, state: *mut c_void) -> Result<Vec<u8>, String> {
        inst.serialize(state)
    }
    fn deserialize(inst: &Instance<'_>, bytes: &[u8]) -> (Status, *mut c_void) {
        super::serialized::deserialize(inst, bytes)
    }
    unsafe fn set_state(inst: &Instance<'_>, state: *mut c_void) -> Status {
        // SAFETY: a live instance; the caller vouches for the state.
        unsafe { (inst.binary.set_fmu_state)(inst.c, state) }
    }
    fn me_evaluation(b: &Binary) -> (Transition, GetArray, GetArray) {
        (
            b.enter_continuous_time_mode,
            b.get_derivatives,
            b.get_event_indicators,
        )
    }
    fn free_instance(b: &Binary) -> FreeInstance {
        b.free_instance
    }
    fn set_time(b: &Binary) -> SetTime {
        b.set_time
    }
    fn args(inst: &Instance<'_>, state: *mut c_void) -> Args {
        Args::new(inst.description, state)
    }
}
