//! FMI 2.0 for the one matrix: `StandardInterface` (its two interfaces, eight
//! states, fmi2 instances and call arguments) and `seam::Standard` (its tables:
//! calls, rows, reasons, and the class only FMI 2.0 has, `references`).

pub mod calls;
pub mod instantiate;
pub mod pointers;
pub mod references;
pub mod uses;

use crate::Loaded;
use crate::binary::{Binary, Component, ERROR, OK, Status};
use crate::description::{Description, Variable};
use crate::fmu;
use crate::host::{Instance, Interface, State};
use crate::matrix::seam::{Handle, Reasons, ReferenceReasons, Standard, Tables, Value, ValueNames};
use crate::standard_interface::{GetArray, StandardInterface, Transition, same_named_methods};
use calls::Args;
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

    same_named_methods!();

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
    fn deserialize(inst: &Instance<'_>, bytes: &[u8]) -> (Status, *mut c_void) {
        let mut state = std::ptr::null_mut();
        // SAFETY: a buffer of the given length and a null slot for a new state.
        let s = unsafe {
            (inst.binary.deserialize)(inst.c, bytes.as_ptr().cast(), bytes.len(), &mut state)
        };
        (s, state)
    }
    fn me_evaluation(b: &Binary) -> (Transition, GetArray, GetArray) {
        (
            b.enter_continuous_time_mode,
            b.get_derivatives,
            b.get_event_indicators,
        )
    }
}

const REASONS: Reasons = Reasons {
    references: ReferenceReasons {
        unknown: "value reference not in the modelDescription (FMI 2.0 2.1.7): fmi2Error naming it",
        wrong_type: "value reference of another type than the function's (FMI 2.0 2.1.7): fmi2Error naming the variable",
        lacking: "the models have no String variables: every reference is refused",
        not_settable: "calculated output set with fmi2SetReal (FMI 2.0 2.2.7 allows setting only parameters, inputs and initial=exact/approx): fmi2Error naming it",
        count: "FMI 2.0 value functions take one value per reference: no count to probe",
    },
    illegal_order: "call not allowed in this state by the FMI 2.0 state tables (3.2.3 ME, 4.2.4 CS): fmi2Error and a log line",
    lacking: "function of a capability the model lacks: fmi2Error and a log line naming the function",
    null_pointer: "null argument with a non-zero length: undefined in FMI 2.0; refused with fmi2Error and a log line (project choice)",
    handle_null: "null instance: undefined in FMI 2.0; fmi2Error (fmi2FreeInstance: ignored)",
    handle_foreign: "handle not issued by this FMU: undefined in FMI 2.0; refused with fmi2Error after a tag check (issue 12 item 4)",
    bad_state: "FMU state not issued by this FMU instance or already freed: undefined in FMI 2.0; fmi2Error and a log line after a tag/registry check (issue 12 item 4)",
    cross_interface: "issue 12 item 6: the state of a ME instance restores a CS instance of the same FMU (and back); project choice: accepted, outputs bit for bit",
    damaged: "damaged serialized state: refused with fmi2Error and a log line (project format with magic, version, GUID, lengths and checksum)",
    control: "FMI 2.0 2.1.8: an FMU reads back its own serialized state; restored outputs are bit for bit those at serialization",
    unassemblable: "FMI 2.0 3.2.2: a model that cannot be evaluated at the current state returns fmi2Discard (integrator retries), not fmi2Error (issue 12 item 2)",
    non_finite: "NaN/inf set: refused by fmi2SetReal with fmi2Error naming the variable (project choice; FMI 2.0 Reals of a model are finite)",
    argument: "non-finite scalar argument: fmi2Error and a log line naming the function",
    extreme: "extreme finite value: refused at set or exitInitializationMode naming the variable, or a step Discard; never first noticed by a getter (issue 12 item 3)",
};

impl Standard for Interface {
    const STANDARD: fmu::Standard = fmu::Standard::Fmi2;

    fn tables() -> Tables<Interface> {
        Tables {
            calls: calls::calls,
            lacking: Vec::new,
            null_pointers: pointers::table,
            getters: references::getters,
            setters: references::setters,
            counted_values: false,
            reference_extras: references::extras,
            state_uses: uses::state_uses,
            state_seed: 0xbad,
            evaluations: uses::evaluations,
            unassemblable: uses::unassemblable,
            handles: &[
                Handle::Null,
                Handle::ZeroedBlock,
                Handle::RandomBlock,
                Handle::OtherFmuInstance,
            ],
            free_instance: "fmi2FreeInstance",
            other_standard: None,
            instantiation: instantiate::INSTANTIATION,
            scalar_arguments: Vec::new,
            values: ValueNames {
                setter: "fmi2SetReal",
                getter: "fmi2GetReal",
                element: "",
                quote_end: "\"",
                types: ["Real", "Integer", "Boolean"],
                booleans: [2, -1],
            },
            setter_states: uses::setter_states,
            own_classes: &[],
            reasons: REASONS,
        }
    }
    fn description(loaded: &Loaded, m: usize) -> &Description {
        &loaded.fmus[m].description
    }
    fn reference_state(self) -> State {
        match self {
            Interface::ModelExchange => State::EventMode,
            Interface::CoSimulation => State::StepComplete,
        }
    }
    fn do_step(inst: &Instance<'_>, t: f64, h: f64) -> Status {
        inst.do_step(t, h)
    }
    fn outputs(inst: &Instance<'_>) -> (Status, Vec<f64>) {
        uses::outputs(inst)
    }
    fn set_value(inst: &Instance<'_>, v: &Variable, value: Value) -> Status {
        uses::set_value(inst, v, value)
    }
    fn initialize(inst: &Instance<'_>) -> Result<(), (&'static str, Status)> {
        uses::initialize(inst)
    }
    fn evaluate(inst: &Instance<'_>, interface: Interface) -> Result<bool, String> {
        uses::evaluate(inst, interface)
    }
}
