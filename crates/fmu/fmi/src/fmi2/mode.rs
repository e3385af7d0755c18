//! The state machine of FMI 2.0 (Model Exchange and Co-Simulation): the modes an
//! instance can be in and which call is legal in which mode.

/// Interface an instance was created for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interface {
    ModelExchange,
    CoSimulation,
}

/// Mode of an instance. Co-Simulation never pends (no asynchronous steps), so the
/// standard's stepInProgress and stepCanceled are never entered.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Instantiated,
    InitializationMode,
    EventMode,
    ContinuousTimeMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
    Fatal,
}

/// Every call that depends on the mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Call {
    SetDebugLogging,
    SetupExperiment,
    EnterInitializationMode,
    ExitInitializationMode,
    Terminate,
    Reset,
    GetValues,
    SetReal,
    SetDiscrete,
    FmuState,
    GetDirectionalDerivative,
    EnterEventMode,
    NewDiscreteStates,
    EnterContinuousTimeMode,
    CompletedIntegratorStep,
    SetTime,
    SetContinuousStates,
    GetEventIndicators,
    GetContinuousStates,
    GetDerivatives,
    GetNominalsOfContinuousStates,
    SetRealInputDerivatives,
    GetRealOutputDerivatives,
    DoStep,
    CancelStep,
    GetStatus,
}

use super::logging::{Callback, LAYER_CATEGORIES};
use super::types::Fmi2Status;
use crate::core::frontend::{Frontend, modes};
use crate::core::instance::Standard;
use crate::core::logging::LogCategory;
use Mode::*;

/// Every mode but Fatal (declared last): after Fatal only FreeInstance is allowed.
const LIVE: u16 = modes!(Fatal) - 1;
/// Modes in which variables can be read: all live ones after instantiation.
const READABLE: u16 = LIVE & !modes!(Instantiated);

impl Call {
    /// Modes in which the call is legal, for the given interface.
    fn allowed(self, interface: Interface) -> u16 {
        let me = interface == Interface::ModelExchange;
        let only_me = |m: u16| if me { m } else { 0 };
        let only_cs = |m: u16| if me { 0 } else { m };
        match self {
            Call::SetDebugLogging | Call::Reset | Call::FmuState => LIVE,
            Call::SetupExperiment | Call::EnterInitializationMode => modes!(Instantiated),
            Call::ExitInitializationMode => modes!(InitializationMode),
            Call::Terminate => modes!(EventMode, ContinuousTimeMode, StepComplete, StepFailed),
            Call::GetValues | Call::GetDirectionalDerivative => READABLE,
            Call::SetReal => modes!(
                Instantiated,
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                StepComplete,
            ),
            Call::SetDiscrete => modes!(Instantiated, InitializationMode, EventMode, StepComplete),
            Call::EnterEventMode => only_me(modes!(EventMode, ContinuousTimeMode)),
            Call::NewDiscreteStates | Call::EnterContinuousTimeMode => only_me(modes!(EventMode)),
            Call::CompletedIntegratorStep | Call::SetContinuousStates => {
                only_me(modes!(ContinuousTimeMode))
            }
            Call::SetTime => only_me(modes!(EventMode, ContinuousTimeMode)),
            Call::GetEventIndicators | Call::GetContinuousStates => only_me(modes!(
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                Terminated,
                Error,
            )),
            Call::GetDerivatives => {
                only_me(modes!(EventMode, ContinuousTimeMode, Terminated, Error))
            }
            Call::GetNominalsOfContinuousStates => only_me(modes!(
                Instantiated,
                EventMode,
                ContinuousTimeMode,
                Terminated,
                Error,
            )),
            Call::SetRealInputDerivatives => {
                only_cs(modes!(Instantiated, InitializationMode, StepComplete))
            }
            Call::GetRealOutputDerivatives => {
                only_cs(modes!(StepComplete, StepFailed, Terminated, Error))
            }
            Call::DoStep => only_cs(modes!(StepComplete)),
            // No step is ever in progress: cancelling is never legal.
            Call::CancelStep => 0,
            Call::GetStatus => only_cs(modes!(StepComplete, StepFailed, Terminated)),
        }
    }

    /// Whether the call is legal in `mode` for an instance of `interface`.
    pub fn is_legal(self, mode: Mode, interface: Interface) -> bool {
        self.allowed(interface) & modes!(mode) != 0
    }
}

/// The FMI 2.0 front-end: its status, state machine and logger callback.
pub struct Fmi2;

impl Frontend for Fmi2 {
    type Status = Fmi2Status;
    type Mode = Mode;
    type Interface = Interface;
    type Call = Call;
    type Sink = Callback;
    type Extra = ();
    const STANDARD: Standard = Standard::Fmi2;
    const FMU_STATE: &'static str = "FMUstate";
    const MODE_WORD: &'static str = "mode";
    const INSTANTIATED: Mode = Instantiated;
    const INITIALIZATION: Mode = InitializationMode;
    const ERROR: Mode = Error;
    const FATAL: Mode = Fatal;
    const LAYER_CATEGORIES: [LogCategory; 6] = LAYER_CATEGORIES;

    fn is_legal(call: Call, mode: Mode, interface: Interface) -> bool {
        call.is_legal(mode, interface)
    }

    /// Event Mode for Model Exchange, stepComplete for Co-Simulation.
    fn after_initialization(interface: Interface) -> Mode {
        match interface {
            Interface::ModelExchange => EventMode,
            Interface::CoSimulation => StepComplete,
        }
    }

    /// A failed step is undone: back to stepComplete.
    fn after_restore(mode: Mode) -> Mode {
        if mode == StepFailed {
            StepComplete
        } else {
            mode
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn co_simulation_calls_are_illegal_for_model_exchange_and_back() {
        // Expected values: the state tables of the FMI 2.0 standard (sections 3.2.3, 4.2.4).
        assert!(!Call::DoStep.is_legal(StepComplete, Interface::ModelExchange));
        assert!(Call::DoStep.is_legal(StepComplete, Interface::CoSimulation));
        assert!(!Call::SetTime.is_legal(EventMode, Interface::CoSimulation));
        assert!(Call::SetTime.is_legal(ContinuousTimeMode, Interface::ModelExchange));
    }

    #[test]
    fn only_free_instance_is_possible_after_fatal() {
        for call in [
            Call::Reset,
            Call::GetValues,
            Call::FmuState,
            Call::SetDebugLogging,
        ] {
            for interface in [Interface::ModelExchange, Interface::CoSimulation] {
                assert!(!call.is_legal(Fatal, interface), "{call:?}");
            }
        }
    }

    #[test]
    fn values_are_not_readable_before_initialization() {
        assert!(!Call::GetValues.is_legal(Instantiated, Interface::CoSimulation));
        assert!(Call::GetValues.is_legal(InitializationMode, Interface::CoSimulation));
        assert!(!Call::SetDiscrete.is_legal(ContinuousTimeMode, Interface::ModelExchange));
        assert!(Call::SetReal.is_legal(ContinuousTimeMode, Interface::ModelExchange));
    }
}
