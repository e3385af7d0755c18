//! What the matrix machinery shared by FMI 2.0 and FMI 3.0 needs of a standard,
//! as a trait on the standard's interface type (`host::Interface`,
//! `fmi3::host::Interface3`): its states, a live instance of a loaded model, the
//! legal calls that reach a state, the check after a refusal and the well-formed
//! arguments of its call table. The generic probes (`matrix::on_instance`,
//! `matrix::with_args`, `sequence_run`) are written once on it; the matrix's
//! classes on its extension `matrix::seam::Standard`.

use crate::Loaded;
use crate::binary::Status;
use crate::host::Probed;
use std::ffi::c_void;
use std::fmt::Debug;

/// One standard's interfaces (Model Exchange, Co-Simulation, ...) and what differs
/// per standard for the probes written on them.
pub trait StandardInterface: Copy + PartialEq + Send + Sync + 'static {
    /// The states an instance can be brought into.
    type State: Copy + Debug + PartialEq + Send + Sync + 'static;
    /// A live instance, freed on drop.
    type Instance<'a>: Probed;
    /// The loaded function table.
    type Binary;
    /// The C handle of an instance.
    type Handle: Copy + Into<*mut c_void> + From<*mut c_void>;
    /// Well-formed arguments of the call table.
    type Args;

    /// Every interface of the standard.
    const INTERFACES: &'static [Self];
    /// Every state of the standard's state machines.
    const STATES: &'static [Self::State];
    /// The prefix of the standard's function names ("fmi2", "fmi3").
    const PREFIX: &'static str;
    /// How the standard spells "FMU state" in function names ("FMUstate",
    /// "FMUState").
    const FMU_STATE: &'static str;
    /// The name of the function that deserializes an FMU state.
    const DESERIALIZE: &'static str;
    /// The name of the getter of the state derivatives.
    const DERIVATIVES: &'static str;
    /// The state of a fresh instance.
    const INSTANTIATED: Self::State;
    /// Initialization Mode, where FMU states can be taken and set.
    const INITIALIZATION_MODE: Self::State;
    /// Model Exchange.
    const MODEL_EXCHANGE: Self;
    /// Continuous-Time Mode of Model Exchange.
    const CONTINUOUS_TIME_MODE: Self::State;

    /// The interface's short name in case names ("ME", "CS", ...).
    fn short(self) -> &'static str;
    /// A fresh instance of model `m` of `loaded` for this interface.
    fn instance(self, loaded: &Loaded, m: usize) -> Self::Instance<'_>;
    /// Whether `state` can be reached on model `m` with this interface.
    fn reachable(self, loaded: &Loaded, m: usize, state: Self::State) -> bool;
    /// Brings a fresh instance into `state` with legal calls.
    fn reach(inst: &Self::Instance<'_>, state: Self::State) -> Result<(), String>;
    /// After a call returned `status`: whether the instance is still usable as
    /// the standard requires (FMI 3.0 recovers from Error with fmi3Reset; an FMI
    /// 2.0 instance in Error can only be freed).
    fn usable_after(inst: &Self::Instance<'_>, status: Status) -> Result<(), String>;
    /// The loaded function table and the C handle of an instance.
    fn raw<'i>(inst: &'i Self::Instance<'_>) -> (&'i Self::Binary, Self::Handle);
    /// fmiXGetContinuousStates and fmiXSetContinuousStates of the loaded binary.
    fn continuous_states(binary: &Self::Binary) -> (GetArray, SetStates);
    /// The serialized bytes of an FMU state of the instance.
    fn serialize(inst: &Self::Instance<'_>, state: *mut c_void) -> Result<Vec<u8>, String>;
    /// Deserializes `bytes` into a new FMU state: (status, state).
    fn deserialize(inst: &Self::Instance<'_>, bytes: &[u8]) -> (Status, *mut c_void);
    /// Sets an FMU state into the instance.
    ///
    /// # Safety
    /// `state` is a state the FMU issued (or what a probe means to test).
    unsafe fn set_state(inst: &Self::Instance<'_>, state: *mut c_void) -> Status;
    /// The Model Exchange evaluation: fmiXEnterContinuousTimeMode, the getters of
    /// the derivatives and of the event indicators.
    fn me_evaluation(binary: &Self::Binary) -> (Transition, GetArray, GetArray);
    /// fmiXFreeInstance of the loaded binary.
    fn free_instance(binary: &Self::Binary) -> FreeInstance;
    /// fmiXSetTime of the loaded binary.
    fn set_time(binary: &Self::Binary) -> SetTime;
    /// Well-formed arguments for the calls on the instance's model, with `state`
    /// a valid FMU state of the instance.
    fn args(inst: &Self::Instance<'_>, state: *mut c_void) -> Self::Args;
}

/// A getter of a Float64 array: fmiXGetContinuousStates, the derivatives, the
/// event indicators (the same C signature in both standards).
pub type GetArray = unsafe extern "C" fn(*mut c_void, *mut f64, usize) -> Status;
/// fmi2SetContinuousStates / fmi3SetContinuousStates (the same C signature).
pub type SetStates = unsafe extern "C" fn(*mut c_void, *const f64, usize) -> Status;

/// fmi2FreeInstance / fmi3FreeInstance (the same C signature).
pub type FreeInstance = unsafe extern "C" fn(*mut c_void);
/// fmi2SetTime / fmi3SetTime (the same C signature).
pub type SetTime = unsafe extern "C" fn(*mut c_void, f64) -> Status;
/// A function that takes only the instance (fmiXTerminate, fmiXReset, the mode
/// transitions; the same C signature in both standards).
pub type Transition = unsafe extern "C" fn(*mut c_void) -> Status;

/// Whether the standard allows a call in a state of an interface.
pub type Legal<I> = fn(I, <I as StandardInterface>::State) -> bool;
/// A call through the loaded function table on an instance, with well-formed
/// arguments.
pub type Invoke<I> = unsafe fn(
    &<I as StandardInterface>::Binary,
    <I as StandardInterface>::Handle,
    &<I as StandardInterface>::Args,
) -> Status;

/// One entry of a standard's call table: a function, the states in which the
/// standard allows it, and how to call it.
pub struct Call<I: StandardInterface> {
    pub name: &'static str,
    pub legal: Legal<I>,
    pub invoke: Invoke<I>,
}

/// The methods of `StandardInterface` whose bodies read the same for both
/// standards, because the two instance types and the two function tables share
/// their field and method names (`binary`, `c`, `description`, `reach`,
/// `serialize`, `set_fmu_state`, ...). Expanded inside each standard's impl.
macro_rules! same_named_methods {
    () => {
        fn reach(inst: &Self::Instance<'_>, state: Self::State) -> Result<(), String> {
            inst.reach(state)
        }
        fn raw<'i>(inst: &'i Self::Instance<'_>) -> (&'i Self::Binary, Self::Handle) {
            (inst.binary, inst.c)
        }
        fn continuous_states(
            b: &Self::Binary,
        ) -> (
            $crate::standard_interface::GetArray,
            $crate::standard_interface::SetStates,
        ) {
            (b.get_continuous_states, b.set_continuous_states)
        }
        fn serialize(inst: &Self::Instance<'_>, state: *mut c_void) -> Result<Vec<u8>, String> {
            inst.serialize(state)
        }
        unsafe fn set_state(inst: &Self::Instance<'_>, state: *mut c_void) -> Status {
            // SAFETY: a live instance; the caller vouches for the state.
            unsafe { (inst.binary.set_fmu_state)(inst.c, state) }
        }
        fn free_instance(b: &Self::Binary) -> $crate::standard_interface::FreeInstance {
            b.free_instance
        }
        fn set_time(b: &Self::Binary) -> $crate::standard_interface::SetTime {
            b.set_time
        }
        fn args(inst: &Self::Instance<'_>, state: *mut c_void) -> Self::Args {
            <Self::Args>::new(inst.description, state)
        }
    };
}
pub(crate) use same_named_methods;
