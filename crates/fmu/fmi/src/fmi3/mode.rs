//! The state machine of FMI 3.0 (Model Exchange and Co-Simulation, sections 3.3 and
//! 4.3 of the standard): the states an instance can be in and which call is legal in
//! which state. Co-Simulation steps are never asynchronous; a model with
//! `INTERMEDIATE_UPDATE_POINTS` enters Intermediate Update Mode while fmi3DoStep calls
//! the importer's intermediateUpdate callback (section 4.2.4: only fmi3Get* of
//! variables and fmi3SetFloat64 of inputs declared intermediateUpdate are legal
//! there). Configuration Mode is entered from Instantiated to set structural
//! parameters (`core::structural`); the models' structural parameters are all fixed,
//! so Reconfiguration Mode (for tunable ones, from Event or Step Mode) is refused.

/// Interface an instance was created for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Interface {
    ModelExchange,
    /// `event_mode_used`: the importer passed eventModeUsed = true, so a step that
    /// needs event handling ends in Event Mode instead of being handled inside the FMU;
    /// `early_return_allowed`: a step may end early, at an event.
    CoSimulation {
        event_mode_used: bool,
        early_return_allowed: bool,
    },
}

/// State of an instance. `StepDiscarded` is the Step Mode after a step returned
/// fmi3Discard (only fmi3Terminate, state and output queries remain legal).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    Instantiated,
    /// Between fmi3EnterConfigurationMode and fmi3ExitConfigurationMode: only
    /// structural parameters are set (and read) there.
    ConfigurationMode,
    InitializationMode,
    EventMode,
    ContinuousTimeMode,
    StepMode,
    StepDiscarded,
    /// Inside fmi3DoStep, while the importer's intermediateUpdate callback runs.
    IntermediateUpdateMode,
    Terminated,
    Error,
    Fatal,
}

/// Every call that depends on the mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Call {
    SetDebugLogging,
    EnterInitializationMode,
    ExitInitializationMode,
    EnterEventMode,
    Terminate,
    Reset,
    GetValues,
    SetFloat64,
    SetDiscrete,
    VariableDependencies,
    FmuState,
    Derivative,
    /// A function of a capability the FMU lacks (structural parameters, Scheduled
    /// Execution, other variable types): answered with fmi3Error saying so.
    Unsupported,
    UpdateDiscreteStates,
    EnterContinuousTimeMode,
    CompletedIntegratorStep,
    SetTime,
    SetContinuousStates,
    ContinuousStateQuery,
    /// fmi3GetNumberOfContinuousStates and fmi3GetNumberOfEventIndicators.
    CountQuery,
    EnterStepMode,
    GetOutputDerivatives,
    DoStep,
    /// fmi3DoStep going on after the intermediateUpdate callback returned.
    ResumeStep,
    /// fmi3SetClock: Event Mode only (section 2.2.9 of FMI 3.0).
    SetClock,
    /// fmi3GetClock, fmi3GetInterval*, fmi3GetShift* and fmi3SetInterval* /
    /// fmi3SetShift*: Initialization and Event Mode.
    ClockQuery,
    /// fmi3EnterConfigurationMode: from Instantiated (Configuration Mode); from Event
    /// or Step Mode it would be Reconfiguration Mode, which the instance refuses with
    /// its reason (no structural parameter is tunable).
    EnterConfigurationMode,
    ExitConfigurationMode,
    /// fmi3SetUInt64 (the structural parameters): the instance says where it is legal
    /// (Configuration Mode), so a call elsewhere names the way there.
    SetStructural,
    /// fmi3GetUInt64: where values are readable, and in Configuration Mode.
    GetStructural,
}

use super::logging::{Callback, LAYER_CATEGORIES};
use super::types::Fmi3Status;
use crate::core::frontend::{Frontend, modes};
use crate::core::instance::Standard;
use crate::core::logging::LogCategory;
use Mode::*;

/// Every state but Fatal (declared last; after Fatal only FreeInstance is allowed) and
/// Intermediate Update Mode (only the calls of section 4.2.4 there).
const LIVE: u16 = (modes!(Fatal) - 1) & !modes!(IntermediateUpdateMode);
/// States in which variables can be read (section 2.3.3; also Error, for diagnosis):
/// all live ones after instantiation, and Intermediate Update Mode (the instance then
/// restricts reads to variables declared intermediateUpdate).
const READABLE: u16 =
    (LIVE & !modes!(Instantiated, ConfigurationMode)) | modes!(IntermediateUpdateMode);

impl Call {
    /// States in which the call is legal, for the given interface.
    fn allowed(self, interface: Interface) -> u16 {
        let me = interface == Interface::ModelExchange;
        let cs_events = matches!(
            interface,
            Interface::CoSimulation {
                event_mode_used: true,
                ..
            }
        );
        let only_me = |m: u16| if me { m } else { 0 };
        let only_cs = |m: u16| if me { 0 } else { m };
        match self {
            Call::SetDebugLogging | Call::Reset => LIVE,
            Call::FmuState => LIVE & !modes!(ConfigurationMode),
            Call::VariableDependencies | Call::Unsupported => LIVE,
            Call::EnterInitializationMode => modes!(Instantiated),
            Call::ExitInitializationMode => modes!(InitializationMode),
            Call::EnterEventMode if me => modes!(ContinuousTimeMode),
            Call::EnterEventMode if cs_events => modes!(StepMode),
            Call::EnterEventMode => 0,
            Call::Terminate => modes!(EventMode, ContinuousTimeMode, StepMode, StepDiscarded),
            Call::GetValues => READABLE,
            Call::SetFloat64 => modes!(
                Instantiated,
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                StepMode,
                IntermediateUpdateMode,
            ),
            Call::SetDiscrete => modes!(Instantiated, InitializationMode, EventMode, StepMode),
            Call::Derivative => modes!(
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                StepMode,
                Terminated,
            ),
            Call::UpdateDiscreteStates => modes!(EventMode),
            Call::EnterContinuousTimeMode => only_me(modes!(EventMode)),
            Call::CompletedIntegratorStep | Call::SetContinuousStates => {
                only_me(modes!(ContinuousTimeMode))
            }
            Call::SetTime => only_me(modes!(EventMode, ContinuousTimeMode)),
            Call::ContinuousStateQuery => only_me(modes!(
                InitializationMode,
                EventMode,
                ContinuousTimeMode,
                Terminated,
            )),
            Call::CountQuery => only_me(LIVE),
            Call::EnterStepMode => only_cs(modes!(EventMode)),
            Call::GetOutputDerivatives => only_cs(modes!(StepMode, StepDiscarded, Terminated)),
            Call::DoStep => only_cs(modes!(StepMode)),
            Call::ResumeStep => only_cs(modes!(IntermediateUpdateMode)),
            Call::SetClock => modes!(EventMode),
            Call::ClockQuery => modes!(InitializationMode, EventMode),
            Call::EnterConfigurationMode => modes!(Instantiated, EventMode, StepMode),
            Call::ExitConfigurationMode => modes!(ConfigurationMode),
            Call::SetStructural => LIVE,
            Call::GetStructural => READABLE | modes!(ConfigurationMode),
        }
    }

    /// Whether the call is legal in `mode` for an instance of `interface`.
    pub fn is_legal(self, mode: Mode, interface: Interface) -> bool {
        self.allowed(interface) & modes!(mode) != 0
    }
}

/// The FMI 3.0 front-end: its status, state machine and logger callback.
pub struct Fmi3;

impl Frontend for Fmi3 {
    type Status = Fmi3Status;
    type Mode = Mode;
    type Interface = Interface;
    type Call = Call;
    type Sink = Callback;
    type Extra = super::extra::Fmi3Extra;
    const STANDARD: Standard = Standard::Fmi3;
    const FMU_STATE: &'static str = "FMUState";
    const MODE_WORD: &'static str = "state";
    const INSTANTIATED: Mode = Instantiated;
    const INITIALIZATION: Mode = InitializationMode;
    const ERROR: Mode = Error;
    const FATAL: Mode = Fatal;
    const LAYER_CATEGORIES: [LogCategory; 6] = LAYER_CATEGORIES;

    fn is_legal(call: Call, mode: Mode, interface: Interface) -> bool {
        call.is_legal(mode, interface)
    }

    /// Event Mode for Model Exchange and for Co-Simulation with event mode, Step Mode
    /// otherwise.
    fn after_initialization(interface: Interface) -> Mode {
        match interface {
            Interface::CoSimulation {
                event_mode_used: false,
                ..
            } => StepMode,
            _ => EventMode,
        }
    }

    /// A discarded step is undone: back to Step Mode.
    fn after_restore(mode: Mode) -> Mode {
        if mode == StepDiscarded {
            StepMode
        } else {
            mode
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const ME: Interface = Interface::ModelExchange;
    const CS: Interface = Interface::CoSimulation {
        event_mode_used: false,
        early_return_allowed: false,
    };
    const CS_EVENTS: Interface = Interface::CoSimulation {
        event_mode_used: true,
        early_return_allowed: true,
    };

    #[test]
    fn co_simulation_event_mode_exists_only_when_the_importer_uses_it() {
        // Expected values: the Co-Simulation state machine of FMI 3.0 (section 4.3):
        // fmi3EnterEventMode leaves Step Mode only with eventModeUsed = true, and
        // fmi3EnterStepMode leaves Event Mode.
        assert!(!Call::EnterEventMode.is_legal(StepMode, CS));
        assert!(Call::EnterEventMode.is_legal(StepMode, CS_EVENTS));
        assert!(Call::EnterStepMode.is_legal(EventMode, CS_EVENTS));
        assert!(!Call::EnterStepMode.is_legal(EventMode, ME));
        assert_eq!(Fmi3::after_initialization(CS), StepMode);
        assert_eq!(Fmi3::after_initialization(CS_EVENTS), EventMode);
        assert_eq!(Fmi3::after_initialization(ME), EventMode);
    }

    #[test]
    fn interface_specific_calls_are_illegal_for_the_other_interface() {
        // Expected values: fmi3DoStep exists only in Co-Simulation (section 4.2.1),
        // fmi3SetTime and the continuous-state functions only in Model Exchange (3.2).
        assert!(!Call::DoStep.is_legal(StepMode, ME));
        assert!(Call::DoStep.is_legal(StepMode, CS));
        assert!(!Call::SetTime.is_legal(EventMode, CS_EVENTS));
        assert!(Call::SetTime.is_legal(ContinuousTimeMode, ME));
        assert!(!Call::ContinuousStateQuery.is_legal(StepMode, CS));
    }

    #[test]
    fn only_free_instance_is_possible_after_fatal() {
        for call in [
            Call::Reset,
            Call::GetValues,
            Call::FmuState,
            Call::SetDebugLogging,
            Call::VariableDependencies,
        ] {
            for interface in [ME, CS, CS_EVENTS] {
                assert!(!call.is_legal(Fatal, interface), "{call:?}");
            }
        }
    }

    #[test]
    fn discarded_step_allows_termination_but_no_further_step() {
        // Section 4.2.1: after fmi3Discard from fmi3DoStep the importer may only
        // terminate, restore a state or read values.
        assert!(!Call::DoStep.is_legal(StepDiscarded, CS));
        assert!(Call::Terminate.is_legal(StepDiscarded, CS));
        assert!(Call::GetValues.is_legal(StepDiscarded, CS));
        assert!(Call::FmuState.is_legal(StepDiscarded, CS));
    }

    #[test]
    fn intermediate_update_mode_allows_only_get_and_set_of_values() {
        // Expected values: section 4.2.4 of FMI 3.0 (Intermediate Update Mode): the
        // importer's callback may get variables and set inputs; the step itself, the
        // FMU state, reset, termination and events wait until fmi3DoStep returned.
        let m = IntermediateUpdateMode;
        assert!(Call::GetValues.is_legal(m, CS));
        assert!(Call::SetFloat64.is_legal(m, CS));
        assert!(Call::ResumeStep.is_legal(m, CS));
        for call in [
            Call::DoStep,
            Call::SetDiscrete,
            Call::FmuState,
            Call::Reset,
            Call::Terminate,
            Call::EnterEventMode,
            Call::SetDebugLogging,
            Call::GetOutputDerivatives,
            Call::Derivative,
        ] {
            assert!(!call.is_legal(m, CS_EVENTS), "{call:?}");
        }
        assert!(!Call::ResumeStep.is_legal(StepMode, CS));
    }

    #[test]
    fn clocks_are_set_in_event_mode_only() {
        // Expected values: FMI 3.0 section 2.2.9 (fmi3SetClock in Event Mode; the
        // interval of a fixed clock read in Initialization Mode, and in Event Mode).
        for interface in [ME, CS_EVENTS] {
            assert!(Call::SetClock.is_legal(EventMode, interface));
            assert!(!Call::SetClock.is_legal(InitializationMode, interface));
            assert!(Call::ClockQuery.is_legal(InitializationMode, interface));
        }
        assert!(!Call::SetClock.is_legal(ContinuousTimeMode, ME));
        assert!(!Call::SetClock.is_legal(StepMode, CS));
        assert!(!Call::ClockQuery.is_legal(StepMode, CS_EVENTS));
    }

    #[test]
    fn configuration_mode_is_entered_from_instantiated_and_serves_structural_calls() {
        // Expected values: FMI 3.0 section 3.2 (state machine): Configuration Mode is
        // entered from Instantiated and left back to it; in it only structural
        // parameters are set and read (no other values, no FMU state, no
        // initialization).
        for interface in [ME, CS, CS_EVENTS] {
            assert!(Call::EnterConfigurationMode.is_legal(Instantiated, interface));
            assert!(!Call::EnterConfigurationMode.is_legal(InitializationMode, interface));
            assert!(Call::ExitConfigurationMode.is_legal(ConfigurationMode, interface));
            assert!(!Call::ExitConfigurationMode.is_legal(Instantiated, interface));
            assert!(Call::GetStructural.is_legal(ConfigurationMode, interface));
            for call in [
                Call::GetValues,
                Call::SetFloat64,
                Call::SetDiscrete,
                Call::FmuState,
                Call::EnterInitializationMode,
            ] {
                assert!(!call.is_legal(ConfigurationMode, interface), "{call:?}");
            }
        }
    }

    #[test]
    fn values_are_not_readable_before_initialization() {
        assert!(!Call::GetValues.is_legal(Instantiated, CS));
        assert!(Call::GetValues.is_legal(InitializationMode, CS));
        assert!(!Call::SetDiscrete.is_legal(ContinuousTimeMode, ME));
        assert!(Call::SetFloat64.is_legal(ContinuousTimeMode, ME));
        assert!(!Call::SetFloat64.is_legal(Terminated, ME));
    }
}
