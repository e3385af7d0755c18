//! Every FMI 2.0 function that takes an instance, with well-formed arguments, and
//! the states in which the standard allows it (FMI 2.0.4, the tables of sections
//! 3.2.3 "State Machine of Calling Sequence" for Model Exchange and 4.2.4 for
//! Co-Simulation). The probes call them with a bad handle or in a state where they
//! are not allowed.

use crate::binary::{EventInfo, FmuState, Vr};
use crate::description::{Description, VarType};
use crate::host::{Interface, State};
use crate::matrix::same_named::fmu_state_call_rows;
use std::ffi::c_int;

/// Well-formed arguments for the calls on one model.
pub struct Args {
    pub real_vr: Vr,
    pub input_vr: Vr,
    pub int_vr: Vr,
    pub bool_vr: Vr,
    pub nx: usize,
    pub nz: usize,
    /// (unknown, known) for fmi2GetDirectionalDerivative.
    pub partial: (Vr, Vr),
    /// A valid FMU state of the instance (or null when none was taken).
    pub state: FmuState,
}

impl Args {
    pub fn new(d: &Description, state: FmuState) -> Args {
        let first = |t: VarType, settable: bool| {
            d.of_type(t)
                .find(|v| !settable || v.is_settable())
                .map(|v| v.vr)
        };
        let real_vr = first(VarType::Real, false).unwrap_or(0);
        let pairs = d.state_derivative_pairs();
        let input_vr = d
            .variables
            .iter()
            .find(|v| v.causality == "input" && v.var_type == VarType::Real)
            .map(|v| v.vr)
            .or(first(VarType::Real, true))
            .unwrap_or(real_vr);
        Args {
            real_vr,
            input_vr,
            int_vr: first(VarType::Integer, true).unwrap_or(real_vr),
            bool_vr: first(VarType::Boolean, true).unwrap_or(real_vr),
            nx: d.number_of_states,
            nz: d.number_of_event_indicators,
            partial: pairs
                .first()
                .map(|&(x, dx)| (dx, x))
                .unwrap_or((real_vr, input_vr)),
            state,
        }
    }
}

type Legal = crate::standard_interface::Legal<Interface>;
type Invoke = crate::standard_interface::Invoke<Interface>;
pub type Call = crate::standard_interface::Call<Interface>;

use Interface::{CoSimulation as Cs, ModelExchange as Me};
use State::*;

fn everywhere(_: Interface, _: State) -> bool {
    true
}
fn readable(_: Interface, s: State) -> bool {
    !matches!(s, Instantiated)
}
fn only_instantiated(_: Interface, s: State) -> bool {
    s == Instantiated
}

/// The calls with their legal states; FMU-state functions and fmi2SetDebugLogging
/// are legal in every live state and fmi2FreeInstance everywhere.
pub fn calls() -> Vec<Call> {
    let mut v: Vec<Call> = Vec::new();
    let mut add = |name, legal: Legal, invoke: Invoke| {
        v.push(Call {
            name,
            legal,
            invoke,
        })
    };
    add("fmi2SetDebugLogging", everywhere, |b, c, _| unsafe {
        (b.set_debug_logging)(c, 1, 0, std::ptr::null())
    });
    add("fmi2SetupExperiment", only_instantiated, |b, c, _| unsafe {
        (b.setup_experiment)(c, 0, 0.0, 0.0, 0, 0.0)
    });
    add(
        "fmi2EnterInitializationMode",
        only_instantiated,
        |b, c, _| unsafe { (b.enter_initialization_mode)(c) },
    );
    add(
        "fmi2ExitInitializationMode",
        |_, s| s == InitializationMode,
        |b, c, _| unsafe { (b.exit_initialization_mode)(c) },
    );
    add(
        "fmi2Terminate",
        |_, s| {
            matches!(
                s,
                EventMode | ContinuousTimeMode | StepComplete | StepFailed
            )
        },
        |b, c, _| unsafe { (b.terminate)(c) },
    );
    add("fmi2Reset", everywhere, |b, c, _| unsafe { (b.reset)(c) });
    add("fmi2GetReal", readable, |b, c, a| unsafe {
        let mut x = 0.0;
        (b.get_real)(c, &a.real_vr, 1, &mut x)
    });
    add("fmi2GetInteger", readable, |b, c, a| unsafe {
        let mut x: c_int = 0;
        (b.get_integer)(c, &a.int_vr, 1, &mut x)
    });
    add("fmi2GetBoolean", readable, |b, c, a| unsafe {
        let mut x: c_int = 0;
        (b.get_boolean)(c, &a.bool_vr, 1, &mut x)
    });
    add(
        "fmi2SetReal",
        |i, s| match i {
            Me => matches!(
                s,
                Instantiated | InitializationMode | EventMode | ContinuousTimeMode
            ),
            Cs => matches!(s, Instantiated | InitializationMode | StepComplete),
        },
        |b, c, a| unsafe { (b.set_real)(c, &a.input_vr, 1, &0.0) },
    );
    let discrete: Legal = |i, s| match i {
        Me => matches!(s, Instantiated | InitializationMode | EventMode),
        Cs => matches!(s, Instantiated | InitializationMode | StepComplete),
    };
    add("fmi2SetInteger", discrete, |b, c, a| unsafe {
        (b.set_integer)(c, &a.int_vr, 1, &1)
    });
    add("fmi2SetBoolean", discrete, |b, c, a| unsafe {
        (b.set_boolean)(c, &a.bool_vr, 1, &0)
    });
    fmu_state_call_rows!(add, everywhere, "fmi2", "FMUstate");
    add("fmi2GetDirectionalDerivative", readable, |b, c, a| unsafe {
        let mut out = 0.0;
        (b.get_directional_derivative)(c, &a.partial.0, 1, &a.partial.1, 1, &1.0, &mut out)
    });
    add_model_exchange(&mut add);
    add_co_simulation(&mut add);
    v
}

fn add_model_exchange(add: &mut impl FnMut(&'static str, Legal, Invoke)) {
    let evaluable: Legal = |i, s| {
        i == Me
            && matches!(
                s,
                InitializationMode | EventMode | ContinuousTimeMode | Terminated | State::Error
            )
    };
    add(
        "fmi2EnterEventMode",
        |i, s| i == Me && matches!(s, EventMode | ContinuousTimeMode),
        |b, c, _| unsafe { (b.enter_event_mode)(c) },
    );
    add(
        "fmi2NewDiscreteStates",
        |i, s| i == Me && s == EventMode,
        |b, c, _| unsafe {
            let mut info = EventInfo::default();
            (b.new_discrete_states)(c, &mut info)
        },
    );
    add(
        "fmi2EnterContinuousTimeMode",
        |i, s| i == Me && s == EventMode,
        |b, c, _| unsafe { (b.enter_continuous_time_mode)(c) },
    );
    add(
        "fmi2CompletedIntegratorStep",
        |i, s| i == Me && s == ContinuousTimeMode,
        |b, c, _| unsafe {
            let (mut enter, mut stop) = (0, 0);
            (b.completed_integrator_step)(c, 1, &mut enter, &mut stop)
        },
    );
    add(
        "fmi2SetTime",
        |i, s| i == Me && matches!(s, EventMode | ContinuousTimeMode),
        |b, c, _| unsafe { (b.set_time)(c, 0.0) },
    );
    add(
        "fmi2SetContinuousStates",
        |i, s| i == Me && s == ContinuousTimeMode,
        |b, c, a| unsafe {
            let mut x = vec![0.0; a.nx];
            (b.get_continuous_states)(c, x.as_mut_ptr(), a.nx);
            (b.set_continuous_states)(c, x.as_ptr(), a.nx)
        },
    );
    add("fmi2GetEventIndicators", evaluable, |b, c, a| unsafe {
        let mut z = vec![0.0; a.nz];
        (b.get_event_indicators)(c, z.as_mut_ptr(), a.nz)
    });
    add("fmi2GetContinuousStates", evaluable, |b, c, a| unsafe {
        let mut x = vec![0.0; a.nx];
        (b.get_continuous_states)(c, x.as_mut_ptr(), a.nx)
    });
    add(
        "fmi2GetDerivatives",
        |i, s| {
            i == Me
                && matches!(
                    s,
                    EventMode | ContinuousTimeMode | Terminated | State::Error
                )
        },
        |b, c, a| unsafe {
            let mut dx = vec![0.0; a.nx];
            (b.get_derivatives)(c, dx.as_mut_ptr(), a.nx)
        },
    );
    add(
        "fmi2GetNominalsOfContinuousStates",
        |i, s| {
            i == Me
                && matches!(
                    s,
                    Instantiated | EventMode | ContinuousTimeMode | Terminated | State::Error
                )
        },
        |b, c, a| unsafe {
            let mut x = vec![0.0; a.nx];
            (b.get_nominals)(c, x.as_mut_ptr(), a.nx)
        },
    );
}

fn add_co_simulation(add: &mut impl FnMut(&'static str, Legal, Invoke)) {
    let status_readable: Legal =
        |i, s| i == Cs && matches!(s, StepComplete | StepFailed | Terminated);
    add(
        "fmi2SetRealInputDerivatives",
        |i, s| i == Cs && matches!(s, Instantiated | InitializationMode | StepComplete),
        |b, c, a| unsafe { (b.set_real_input_derivatives)(c, &a.input_vr, 0, &1, &0.0) },
    );
    add(
        "fmi2GetRealOutputDerivatives",
        |i, s| i == Cs && matches!(s, StepComplete | StepFailed | Terminated | State::Error),
        |b, c, a| unsafe {
            let mut out = 0.0;
            (b.get_real_output_derivatives)(c, &a.real_vr, 0, &1, &mut out)
        },
    );
    add(
        "fmi2DoStep",
        |i, s| i == Cs && s == StepComplete,
        |b, c, _| unsafe { (b.do_step)(c, 0.0, 1e-3, 1) },
    );
    // Legal only while an asynchronous step is pending, which these FMUs never start.
    add(
        "fmi2CancelStep",
        |_, _| false,
        |b, c, _| unsafe { (b.cancel_step)(c) },
    );
    add("fmi2GetStatus", status_readable, |b, c, _| unsafe {
        let mut s: c_int = 0;
        (b.get_status)(c, 0, &mut s)
    });
    add("fmi2GetRealStatus", status_readable, |b, c, _| unsafe {
        let mut t = 0.0;
        (b.get_real_status)(c, 2, &mut t)
    });
    add("fmi2GetIntegerStatus", status_readable, |b, c, _| unsafe {
        let mut n: c_int = 0;
        (b.get_integer_status)(c, 0, &mut n)
    });
    add("fmi2GetBooleanStatus", status_readable, |b, c, _| unsafe {
        let mut f: c_int = 0;
        (b.get_boolean_status)(c, 3, &mut f)
    });
    add("fmi2GetStringStatus", status_readable, |b, c, _| unsafe {
        let mut s = std::ptr::null();
        (b.get_string_status)(c, 0, &mut s)
    });
}
