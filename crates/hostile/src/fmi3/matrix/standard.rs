//! FMI 3.0 as a `StandardInterface`: its three interfaces (Co-Simulation with and
//! without event mode), eight states, fmi3 instances and call arguments.

use super::calls::Args;
use crate::Loaded;
use crate::binary::{ERROR, Status};
use crate::fmi3::binary::{Binary3, Instance3};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::standard_interface::{
    FreeInstance, GetArray, SetStates, SetTime, StandardInterface, Transition,
};
use std::ffi::c_void;

impl StandardInterface for Interface3 {
    type State = State3;
    type Instance<'a> = Instance<'a>;
    type Binary = Binary3;
    type Handle = Instance3;
    type Args = Args;

    const INTERFACES: &'static [Interface3] = &Interface3::ALL;
    const STATES: &'static [State3] = &State3::ALL;
    const PREFIX: &'static str = "fmi3";
    const FMU_STATE: &'static str = "FMUState";
    const DESERIALIZE: &'static str = "fmi3DeserializeFMUState";
    const DERIVATIVES: &'static str = "fmi3GetContinuousStateDerivatives";
    const INSTANTIATED: State3 = State3::Instantiated;
    const INITIALIZATION_MODE: State3 = State3::InitializationMode;
    const MODEL_EXCHANGE: Interface3 = Interface3::ModelExchange;
    const CONTINUOUS_TIME_MODE: State3 = State3::ContinuousTimeMode;

    fn short(self) -> &'static str {
        Interface3::short(self)
    }
    fn instance(self, loaded: &Loaded, m: usize) -> Instance<'_> {
        Instance::new(&loaded.binaries3[m], &loaded.fmus3[m].description, self)
    }
    /// StepDiscarded is reached with a discarded step, which needs a force input.
    fn reachable(self, loaded: &Loaded, m: usize, state: State3) -> bool {
        state.exists_for(self)
            && (state != State3::StepDiscarded
                || loaded.fmus3[m]
                    .description
                    .variables
                    .iter()
                    .any(|v| v.name == "actuatorForce"))
    }
    fn reach(inst: &Instance<'_>, state: State3) -> Result<(), String> {
        inst.reach(state)
    }
    /// After fmi3Error the instance is in Error and must recover with fmi3Reset
    /// (FMI 3.0 section 2.3.1).
    fn usable_after(inst: &Instance<'_>, status: Status) -> Result<(), String> {
        if status == ERROR {
            inst.recovers()
                .map_err(|e| format!("not usable after the refusal: {e}"))
        } else {
            Ok(())
        }
    }
    fn raw<'i>(inst: &'i Instance<'_>) -> (&'i Binary3, Instance3) {
        (inst.binary, inst.c)
    }
    fn continuous_states(b: &Binary3) -> (GetArray, SetStates) {
        (b.get_continuous_states, b.set_continuous_states)
    }
    fn serialize(inst: &Instance<'_>, state: *mut c_void) -> Result<Vec<u8>, String> {
        inst.serialize(state)
    }
    fn deserialize(inst: &Instance<'_>, bytes: &[u8]) -> (Status, *mut c_void) {
        inst.deserialize(bytes)
    }
    unsafe fn set_state(inst: &Instance<'_>, state: *mut c_void) -> Status {
        // SAFETY: a live instance; the caller vouches for the state.
        unsafe { (inst.binary.set_fmu_state)(inst.c, state) }
    }
    fn me_evaluation(b: &Binary3) -> (Transition, GetArray, GetArray) {
        (
            b.enter_continuous_time_mode,
            b.get_continuous_state_derivatives,
            b.get_event_indicators,
        )
    }
    fn free_instance(b: &Binary3) -> FreeInstance {
        b.free_instance
    }
    fn set_time(b: &Binary3) -> SetTime {
        b.set_time
    }
    fn args(inst: &Instance<'_>, state: *mut c_void) -> Args {
        Args::new(inst.description, state)
    }
}
