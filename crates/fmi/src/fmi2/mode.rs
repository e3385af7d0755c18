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

impl Mode {
    fn bit(self) -> u16 {
        1 << (self as u16)
    }
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

const fn mask(modes: &[Mode]) -> u16 {
    let mut m = 0;
    let mut i = 0;
    while i < modes.len() {
        m |= 1 << (modes[i] as u16);
        i += 1;
    }
    m
}

use Mode::*;

const LIVE: u16 = mask(&[
    Instantiated,
    InitializationMode,
    EventMode,
    ContinuousTimeMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
]);
const READABLE: u16 = mask(&[
    InitializationMode,
    EventMode,
    ContinuousTimeMode,
    StepComplete,
    StepFailed,
    Terminated,
    Error,
]);

impl Call {
    /// Modes in which the call is legal, for the given interface.
    fn allowed(self, interface: Interface) -> u16 {
        let me = interface == Interface::ModelExchange;
        let only_me = |m: u16| if me { m } else { 0 };
        let only_cs = |m: u16| if me { 0 } else { m };
        match self {
            Call::SetDebugLogging | Call::Reset | Call::FmuState => LIVE,
            Call::SetupExperiment | Call::EnterInitializationMode => mask(&[Instantiated]),
            Call::ExitInitializationMode => mask(&[InitializationMode]),
            Call::Terminate => mask(&[EventMode, ContinuousTimeMode, StepComplete, StepFailed]),
            Call::GetValues | Call::GetDirectionalDerivative => READABLE,
            Call::SetReal => mask(&[
                Instantiated,
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                StepComplete,
            ]),
            Call::SetDiscrete => mask(&[Instantiated, InitializationMode, EventMode, StepComplete]),
            Call::EnterEventMode => only_me(mask(&[EventMode, ContinuousTimeMode])),
            Call::NewDiscreteStates | Call::EnterContinuousTimeMode => only_me(mask(&[EventMode])),
            Call::CompletedIntegratorStep | Call::SetContinuousStates => {
                only_me(mask(&[ContinuousTimeMode]))
            }
            Call::SetTime => only_me(mask(&[EventMode, ContinuousTimeMode])),
            Call::GetEventIndicators | Call::GetContinuousStates => only_me(mask(&[
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                Terminated,
                Error,
            ])),
            Call::GetDerivatives => {
                only_me(mask(&[EventMode, ContinuousTimeMode, Terminated, Error]))
            }
            Call::GetNominalsOfContinuousStates => only_me(mask(&[
                Instantiated,
                EventMode,
                ContinuousTimeMode,
                Terminated,
                Error,
            ])),
            Call::SetRealInputDerivatives => {
                only_cs(mask(&[Instantiated, InitializationMode, StepComplete]))
            }
            Call::GetRealOutputDerivatives => {
                only_cs(mask(&[StepComplete, StepFailed, Terminated, Error]))
            }
            Call::DoStep => only_cs(mask(&[StepComplete])),
            // No step is ever in progress: cancelling is never legal.
            Call::CancelStep => 0,
            Call::GetStatus => only_cs(mask(&[StepComplete, StepFailed, Terminated])),
        }
    }

    /// Whether the call is legal in `mode` for an instance of `interface`.
    pub fn is_legal(self, mode: Mode, interface: Interface) -> bool {
        self.allowed(interface) & mode.bit() != 0
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
