//! FMI 3.0 for the one matrix: `StandardInterface` (its three interfaces,
//! Co-Simulation with and without event mode, eight states, fmi3 instances and
//! call arguments) and `seam::Standard` (its tables: calls, rows, reasons, and
//! the classes only FMI 3.0 has: `arrays`, `variability`, `cross_standard`).
//! Besides the status and the log line, every case in which a live instance
//! refuses a call (fmi3Error: the instance is in the Error state, FMI 3.0 section
//! 2.3.1) checks that it is usable afterwards: fmi3Reset, initialization and a
//! read of every Float64 succeed with finite values.

pub mod arrays;
pub mod calls;
pub mod clocks;
pub mod cross_standard;
pub mod instantiate;
pub mod pointers;
pub mod structural;
pub mod uses;
pub mod values;
pub mod variability;

use crate::Loaded;
use crate::binary::{ERROR, Status};
use crate::description::{Description, Variable};
use crate::fmi3::binary::{Binary3, Instance3};
use crate::fmi3::host::{Instance, Interface3, State3};
use crate::fmu;
use crate::matrix::seam::{Handle, Reasons, ReferenceReasons, Standard, Tables, Value, ValueNames};
use crate::matrix::{Case, Expect, on_instance};
use crate::standard_interface::{GetArray, StandardInterface, Transition, same_named_methods};
use calls::Args;
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

    same_named_methods!();

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
    fn deserialize(inst: &Instance<'_>, bytes: &[u8]) -> (Status, *mut c_void) {
        inst.deserialize(bytes)
    }
    fn me_evaluation(b: &Binary3) -> (Transition, GetArray, GetArray) {
        (
            b.enter_continuous_time_mode,
            b.get_continuous_state_derivatives,
            b.get_event_indicators,
        )
    }
}

const REASONS: Reasons = Reasons {
    references: ReferenceReasons {
        unknown: "value reference not in the modelDescription (FMI 3.0 2.2.6): fmi3Error naming it",
        wrong_type: "value reference of another type than the function's (FMI 3.0 2.2.6): fmi3Error naming the variable",
        lacking: "a type the models lack: every reference is refused",
        not_settable: "calculated output set with fmi3SetFloat64 (FMI 3.0 2.2.6 allows setting only parameters, inputs and initial=exact/approx): fmi3Error naming it",
        count: arrays::WHY_COUNT,
    },
    illegal_order: "call not allowed in this state by the FMI 3.0 state machines (3.3 ME, 4.3 CS): fmi3Error and a log line; fmi3Reset recovers (2.3.1)",
    lacking: "function of a capability the model lacks (variable type, clocks, structural parameters, Scheduled Execution): fmi3Error and a log line naming the function in every state",
    null_pointer: "null argument with a non-zero length: undefined in FMI 3.0; refused with fmi3Error and a log line (project choice); fmi3Reset recovers",
    handle_null: "null instance: undefined in FMI 3.0; fmi3Error (fmi3FreeInstance: ignored)",
    handle_foreign: "handle not issued by this FMU's FMI 3.0 interface, or freed: undefined in FMI 3.0; refused with fmi3Error after a registry check (fmi3FreeInstance: ignored)",
    bad_state: "FMU state not issued by this FMU or already freed: undefined in FMI 3.0; fmi3Error and a log line after a registry check; fmi3Reset recovers",
    cross_interface: "the serialized state of one interface restores an instance of another interface of the same FMU (project choice: the model state is the same); outputs bit for bit",
    damaged: "damaged serialized state: refused with fmi3Error and a log line (project format with magic, version, token, lengths and checksum); fmi3Reset recovers",
    control: "FMI 3.0 2.2.9: an FMU reads back its own serialized state; restored outputs are bit for bit those at serialization",
    unassemblable: "FMI 3.0 3.2.1: a model that cannot be evaluated at the current state returns fmi3Discard (integrator retries), not fmi3Error",
    non_finite: "NaN/inf set: refused by fmi3SetFloat64 with fmi3Error naming the variable (project choice; Float64 values of a model are finite)",
    argument: "non-finite or out-of-range scalar argument (FMI 3.0: times finite, step size > 0, a step starts at the FMU's time (4.2.1), tolerance > 0, stopTime >= startTime): fmi3Error and a log line naming the function",
    extreme: "extreme finite value: refused at set or fmi3ExitInitializationMode naming the variable, or a step/evaluation Discard; never first noticed by a getter (issue 12 item 3 for FMI 3.0)",
};

impl Standard for Interface3 {
    const STANDARD: fmu::Standard = fmu::Standard::Fmi3;

    fn tables() -> Tables<Interface3> {
        Tables {
            calls: calls::calls,
            lacking: calls::unsupported,
            null_pointers: pointers::table,
            getters: arrays::getters,
            setters: arrays::setters,
            counted_values: true,
            reference_extras: arrays::extras,
            state_uses: uses::state_uses,
            state_seed: 0xbad3,
            evaluations: uses::evaluations,
            unassemblable: uses::unassemblable,
            handles: &[
                Handle::Null,
                Handle::ZeroedBlock,
                Handle::RandomBlock,
                Handle::OtherFmuInstance,
                Handle::FreedInstance,
                Handle::Fmi2InstanceOfThisFmu,
            ],
            free_instance: "fmi3FreeInstance",
            other_standard: Some(cross_standard::with_fmi2_instance),
            instantiation: instantiate::INSTANTIATION,
            scalar_arguments: values::scalar_arguments,
            values: ValueNames {
                setter: "fmi3SetFloat64",
                getter: "fmi3GetFloat64",
                element: "[0]",
                quote_end: "",
                types: ["Float64", "Int32", "Boolean"],
                booleans: [2, 255],
            },
            setter_states: variability::setter_states,
            own_classes: &[
                arrays::cases,
                variability::cases,
                cross_standard::cases,
                clocks::cases,
                structural::cases,
            ],
            reasons: REASONS,
        }
    }
    fn description(loaded: &Loaded, m: usize) -> &Description {
        &loaded.fmus3[m].description
    }
    fn reference_state(self) -> State3 {
        match self {
            Interface3::ModelExchange => State3::EventMode,
            _ => State3::StepMode,
        }
    }
    fn do_step(inst: &Instance<'_>, t: f64, h: f64) -> Status {
        inst.do_step(t, h).status
    }
    fn outputs(inst: &Instance<'_>) -> (Status, Vec<f64>) {
        inst.get_all()
    }
    fn set_value(inst: &Instance<'_>, v: &Variable, value: Value) -> Status {
        uses::set_value(inst, v, value)
    }
    fn initialize(inst: &Instance<'_>) -> Result<(), (&'static str, Status)> {
        uses::initialize(inst)
    }
    fn evaluate(inst: &Instance<'_>, interface: Interface3) -> Result<bool, String> {
        uses::evaluate(inst, interface)
    }
}

/// The cases of one class on one model that each call something on a fresh instance
/// (the clock and structural-parameter classes): [`InstanceCases::add`].
pub struct InstanceCases {
    class: &'static str,
    model: usize,
    pub cases: Vec<Case>,
}

impl InstanceCases {
    pub fn new(class: &'static str, model: usize) -> Self {
        InstanceCases {
            class,
            model,
            cases: Vec::new(),
        }
    }

    /// A case `name`: an instance of `interface` brought into `state`, then `call`.
    pub fn add(
        &mut self,
        interface: Interface3,
        name: String,
        expect: (Expect, &'static str),
        state: State3,
        call: Box<dyn Fn(&Instance) -> Status>,
    ) {
        let m = self.model;
        self.cases.push(Case::new(
            (self.class, m, interface),
            name,
            expect,
            move |l| on_instance(l, m, interface, state, |i| call(i)),
        ));
    }
}
