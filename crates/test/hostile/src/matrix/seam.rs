//! The seam between the one matrix and a standard: what every case class needs
//! of FMI 2.0 or FMI 3.0 beyond `StandardInterface`, as a trait (`Standard`) and a
//! table of the standard's calls, rows and reasons (`Tables`). The classes in
//! `matrix/*.rs` are written once on it; `matrix/fmi2` and `matrix/fmi3` fill it.

use super::{Case, Cases, Expect, Observed, Probe};
use crate::Loaded;
use crate::binary::Status;
use crate::description::{Description, VarType, Variable};
use crate::fmu;
use crate::standard_interface::{Call, Invoke, StandardInterface};
use std::ffi::c_void;

/// The state in which a null-pointer row's call applies to a model and
/// interface, if any.
pub type Applies<I> = fn(&Description, I) -> Option<<I as StandardInterface>::State>;
/// A call with a null pointer: its name, where it applies, how to make it.
pub type Row<I> = (&'static str, Applies<I>, Invoke<I>);
/// A function that takes an FMU state, called on an instance.
pub type Use<I> = fn(&<I as StandardInterface>::Instance<'_>, *mut c_void) -> Status;
/// A call that evaluates the model, on an instance.
pub type Evaluate<I> = fn(&<I as StandardInterface>::Instance<'_>) -> Status;
/// Runs `call` with a live instance of the FMU's other standard in the same
/// loaded binary, and checks that instance afterwards (Err: it no longer answers).
pub type OtherStandard<I> =
    fn(&Loaded, usize, I, &mut dyn FnMut(*mut c_void) -> Status) -> Result<Status, String>;

/// A typed getter or setter: its name, its type (None: a type the models lack)
/// and the call (instance, value reference, count of values).
pub type Access<I> = (
    &'static str,
    Option<VarType>,
    fn(&<I as StandardInterface>::Instance<'_>, u32, usize) -> Status,
);
/// Cases of a class only one standard has for model `m` and an interface.
pub type Extras<I> = fn(&Description, usize, I) -> Vec<Case>;

/// Instance handles the FMU never issued (or no longer owns).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Handle {
    Null,
    ZeroedBlock,
    RandomBlock,
    OtherFmuInstance,
    FreedInstance,
    /// A live instance of the FMU's other standard in the same binary.
    Fmi2InstanceOfThisFmu,
}

/// A value set into a variable (the first element of an array).
#[derive(Clone, Copy, Debug)]
pub enum Value {
    Real(f64),
    Integer(i32),
    Boolean(i32),
}

impl Value {
    /// "Float64(1e308)" with the standard's type names (Real, Integer, Boolean).
    pub fn label(self, types: [&str; 3]) -> String {
        match self {
            Value::Real(x) => format!("{}({x:?})", types[0]),
            Value::Integer(n) => format!("{}({n})", types[1]),
            Value::Boolean(b) => format!("{}({b})", types[2]),
        }
    }
}

/// How the standard names what the value classes set and read.
#[derive(Clone, Copy)]
pub struct ValueNames {
    /// The setter of Real values ("fmi2SetReal") and the getter.
    pub setter: &'static str,
    pub getter: &'static str,
    /// After the variable's name in a case name: "" or "\[0\]" (first element).
    pub element: &'static str,
    /// After the variable's name in the expected log: "\"" (the whole name) or ""
    /// (FMI 3.0 logs an element: "theta0\[1\]").
    pub quote_end: &'static str,
    /// The names of Real, Integer and Boolean in the standard.
    pub types: [&'static str; 3],
    /// Boolean values other than false and true.
    pub booleans: [i32; 2],
}

/// A scalar argument of a function set to a value it refuses: function, label,
/// the state it is called in, where it applies, the call.
pub type ScalarRow<I> = (
    &'static str,
    &'static str,
    <I as StandardInterface>::State,
    fn(&Description, I) -> bool,
    Evaluate<I>,
);

/// The two arguments both standards' instantiation functions take and the
/// instantiation class varies: the instance name and the GUID (FMI 3.0:
/// instantiation token).
#[derive(Clone)]
pub struct Names {
    pub name: Option<&'static str>,
    pub token: Option<String>,
}

/// A standard's instantiation functions for the instantiation class.
pub struct Instantiation<I: 'static> {
    /// The interfaces instantiated with a function each (None: one function).
    pub kinds: &'static [Option<I>],
    /// The name of the token argument, and the text its refusal logs.
    pub token: (&'static str, &'static str),
    pub why: &'static str,
    /// Instantiates model `m` (interface `kind`) with `names`, then frees it:
    /// OK for an instance, Error for NULL, and the log.
    pub attempt: fn(&Loaded, usize, Option<I>, &Names) -> Observed,
    /// The rows only this standard has.
    pub own: fn(&Loaded, usize) -> Vec<Attempt>,
}

/// One attempt to instantiate with the arguments of a row of the standard's
/// instantiation table.
pub struct Attempt {
    pub interface: Option<&'static str>,
    pub name: String,
    pub expect: Expect,
    pub why: &'static str,
    pub probe: Probe,
}

/// Why the value-reference class expects an error.
pub struct ReferenceReasons {
    pub unknown: &'static str,
    pub wrong_type: &'static str,
    /// A function of a type the models lack: every reference is refused.
    pub lacking: &'static str,
    pub not_settable: &'static str,
    pub count: &'static str,
}

/// Why each class expects what it expects, in the words of the standard.
pub struct Reasons {
    pub references: ReferenceReasons,
    pub illegal_order: &'static str,
    pub lacking: &'static str,
    pub null_pointer: &'static str,
    pub handle_null: &'static str,
    pub handle_foreign: &'static str,
    pub bad_state: &'static str,
    pub cross_interface: &'static str,
    pub damaged: &'static str,
    pub control: &'static str,
    pub unassemblable: &'static str,
    pub non_finite: &'static str,
    pub argument: &'static str,
    pub extreme: &'static str,
}

/// A standard's rows of every class.
pub struct Tables<I: StandardInterface> {
    /// Every function that takes an instance and the states that allow it.
    pub calls: fn() -> Vec<Call<I>>,
    /// Functions of capabilities the models lack: refused in every state.
    pub lacking: fn() -> Vec<(&'static str, Invoke<I>)>,
    pub null_pointers: fn() -> Vec<Row<I>>,
    /// The typed getters and setters, Real first.
    pub getters: fn() -> Vec<Access<I>>,
    pub setters: fn() -> Vec<Access<I>>,
    /// Whether they take a count of values (FMI 3.0 nValues): wrong counts probed.
    pub counted_values: bool,
    /// Value-reference and count cases of functions only this standard has.
    pub reference_extras: Extras<I>,
    /// The functions that take an FMU state.
    pub state_uses: fn() -> Vec<(&'static str, Use<I>)>,
    /// The seed of the random "FMU state" block.
    pub state_seed: u64,
    /// The calls that evaluate the model (Model Exchange).
    pub evaluations: fn() -> Vec<(&'static str, Evaluate<I>)>,
    /// Whether the model's continuous state holds `theta[2]` at element 1.
    pub unassemblable: fn(&Description) -> bool,
    /// The bad handles, and fmiXFreeInstance's name.
    pub handles: &'static [Handle],
    pub free_instance: &'static str,
    pub other_standard: Option<OtherStandard<I>>,
    pub instantiation: Instantiation<I>,
    /// Scalar arguments of functions (times, steps, tolerances) set to values
    /// they refuse.
    pub scalar_arguments: fn() -> Vec<ScalarRow<I>>,
    pub values: ValueNames,
    /// The states after initialization where the setter of a type is legal.
    pub setter_states: fn(VarType) -> &'static [<I as StandardInterface>::State],
    /// Classes only this standard has.
    pub own_classes: &'static [Cases],
    pub reasons: Reasons,
}

/// What the matrix needs of a standard beyond `StandardInterface`.
pub trait Standard: StandardInterface {
    const STANDARD: fmu::Standard;
    fn tables() -> Tables<Self>;
    fn description(loaded: &Loaded, m: usize) -> &Description;
    /// The state a reference instance is in when its state is serialized (after
    /// one step in Co-Simulation).
    fn reference_state(self) -> Self::State;
    /// One step of a Co-Simulation instance.
    fn do_step(inst: &Self::Instance<'_>, t: f64, h: f64) -> Status;
    /// Every Real/Float64 value of the instance (not the independent variable).
    fn outputs(inst: &Self::Instance<'_>) -> (Status, Vec<f64>);
    /// Sets `value` into the first element of `v` (the others to their starts).
    fn set_value(inst: &Self::Instance<'_>, v: &Variable, value: Value) -> Status;
    /// Enters and exits Initialization Mode (start time 0); Err names the call
    /// that failed and its status.
    fn initialize(inst: &Self::Instance<'_>) -> Result<(), (&'static str, Status)>;
    /// One step (CS) or the derivatives and event indicators (ME) after
    /// initialization; Ok(true) when it was discarded.
    fn evaluate(inst: &Self::Instance<'_>, interface: Self) -> Result<bool, String>;
    /// Whether this interface is Model Exchange.
    fn is_me(self) -> bool {
        self == Self::MODEL_EXCHANGE
    }
}
