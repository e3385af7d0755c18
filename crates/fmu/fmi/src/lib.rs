//! robofmu-fmi: the runtime FMI layer, with no robot code and nothing of packaging
//! (no zip, XML or serde: modelDescription.xml and the archive are written by
//! `robofmu-fmi-build`, the in-process test host lives in `robofmu-fmi-testing`).
//!
//! # Writing an FMU
//! Everything a model author needs is in the [`prelude`]:
//!
//! 1. describe the FMU once in a `static` [`ModelInfo`](prelude::ModelInfo) (names,
//!    instantiation token, default experiment, event-indicator count, log
//!    categories); the state count and the capabilities follow from what is declared;
//! 2. declare the variables once, in a `static` slice of
//!    [`Declaration`](prelude::Declaration)s: scalars and arrays (`.array(n)`), each
//!    with its getter and setter (`fn` pointers taking the element index), causality,
//!    [`Variability`](prelude::Variability), unit, start, bounds and hooks (output
//!    derivatives, input-derivative slots); value references are pinned with `.at(vr)`
//!    or assigned by the layer (see [`core::declare`]);
//! 3. implement [`Model`](prelude::Model) for the model type: `VARIABLES` is
//!    that slice; the step returns a [`StepOutcome`](prelude::StepOutcome), Model
//!    Exchange events an [`EventUpdate`](prelude::EventUpdate); a
//!    [`Jacobian`](prelude::Jacobian) names its variables as
//!    [`Element`](prelude::Element)s; messages go to the
//!    [`Log`](prelude::Log) in one of the model's [`LogCategory`](prelude::LogCategory)s;
//! 4. end the crate with [`export_fmu!`]`(Type);` it exports the FMI 2.0 and the
//!    FMI 3.0 C functions from the same cdylib.
//!
//! The modules below are the layer itself: [`core`] (the version-neutral core: model
//! trait, variable table, instance, FMU states, handles, the entry wrapper),
//! [`fmi2`] and [`fmi3`] (each standard's C types, state machine and C functions) and
//! [`ffi`] (checked reads of the host's pointers).

pub mod core;
pub mod description;
pub mod ffi;
pub mod fmi2;
pub mod fmi3;

pub mod prelude {
    //! The names a model author uses: `use robofmu_fmi::prelude::*;`.
    //!
    //! A whole FMU in one file: a cooling body, T' = -(T - ambient) / tau, with the time
    //! constant as a parameter, the ambient temperature as an input, the temperature as a
    //! state and an output with its first time derivative:
    //!
    //! ```
    //! use robofmu_fmi::prelude::*;
    //!
    //! #[derive(Clone, Default)]
    //! pub struct Cooling { t: f64, tau: f64, ambient: f64 }
    //!
    //! impl Cooling {
    //!     fn rate(&self) -> f64 { -(self.t - self.ambient) / self.tau }
    //! }
    //!
    //! // 1. What the FMU is (name, instantiation token, default experiment: start, stop,
    //! //    tolerance, step); the count of states and the capabilities come from the
    //! //    declarations and hooks below.
    //! static INFO: ModelInfo = ModelInfo::new(
    //!     "Cooling", "{5b1f6c36-0a5e-4d43-9d1e-3f1f0c2d9a11}", "Newton's law of cooling",
    //!     [0.0, 10.0, 1e-6, 0.1],
    //! );
    //!
    //! // 2. Every variable once: where it is kept (one accessor the layer reads and
    //! //    writes through) or how it is computed, role, unit, start, hooks (value
    //! //    references 1, 2, ... in this order; `.at(vr)` pins one). A declaration
    //! //    another one names (a state, a dependency) is a `const`: the compiler checks
    //! //    the name.
    //! type Decl = Declaration<Cooling>;
    //! const T: Decl = Decl::real_in("T", |m, _| &mut m.t)
    //!     .describe("temperature")
    //!     .state()
    //!     .unit("K", None)
    //!     .start_real(&[350.0]);
    //! static VARIABLES: &[Decl] = &[
    //!     // A writer of its own checks the value (the place still serves reading).
    //!     Decl::real_in("tau", |m, _| &mut m.tau)
    //!         .describe("time constant")
    //!         .set_real(|m, _, v| if v > 0.0 { m.tau = v; Ok(()) } else { Err("tau > 0".into()) })
    //!         .parameter(Variability::Fixed)
    //!         .unit("s", None)
    //!         .start_real(&[2.0]),
    //!     Decl::real_in("ambient", |m, _| &mut m.ambient)
    //!         .describe("ambient temperature")
    //!         .input()
    //!         .unit("K", None)
    //!         .start_real(&[293.15]),
    //!     T,
    //!     Decl::real("der(T)", "cooling rate", |m, _| m.rate())
    //!         .derivative_of(T.name)
    //!         .unit("K/s", None),
    //!     Decl::real("y", "temperature seen outside", |m, _| m.t)
    //!         .output()
    //!         .depends_on(&[T.var()])
    //!         .output_derivative(1, |m, _, _order| Ok(m.rate()))
    //!         .unit("K", None),
    //! ];
    //!
    //! // 3. The model's behaviour; the layer does the rest (a model from `Default`
    //! //    and the start values, arguments, state machine, FMU states, logging, both
    //! //    standards' C functions).
    //! impl Model for Cooling {
    //!     const INFO: &'static ModelInfo = &INFO;
    //!     const VARIABLES: &'static [Declaration<Self>] = VARIABLES;
    //!     fn set_time(&mut self, _time: f64) {}
    //!     fn exit_initialization(&mut self, _log: &dyn Log) -> Result<(), String> { Ok(()) }
    //!     fn do_step(&mut self, _time: f64, step: f64, _log: &dyn Log) -> StepOutcome {
    //!         // Exact over a step with the input held.
    //!         self.t = self.ambient + (self.t - self.ambient) * (-step / self.tau).exp();
    //!         StepOutcome::Completed
    //!     }
    //!     // Model Exchange reads and writes the state T and reads der(T) through
    //!     // their declarations (the defaults of continuous_states, derivatives, ...).
    //! }
    //!
    //! // 4. Both standards' C functions from this cdylib.
    //! export_fmu!(Cooling);
    //! # fn main() {}
    //! ```
    //!
    //! Where each name is explained: [`ModelInfo`] and [`Model`] (the contract and its
    //! optional methods: events, time events, extra FMU state), [`Jacobian`] (partial or
    //! directional derivatives by [`Element`]), [`Declaration`] (roles, units, bounds, arrays, value references and the
    //! hooks), [`StepOutcome`] and [`EventUpdate`] (what a step or an event did), [`Log`]
    //! and [`LogCategory`] (messages), [`Family`] (arrays of one length declared per channel or
    //! axis, with [`Element::role`] for a law's Jacobian tables), [`OutputDerivativeError`] (why a hook gives no
    //! output derivative), [`Var`] (a variable in a dependency list, named by its
    //! declaration), [`concat()`], [`every`] and [`same`] (static tables from named parts),
    //! [`Place`] (where a model keeps a variable: one accessor to read and write it),
    //! [`InputDerivative`] and [`OutputDerivative`] (the hooks' types, for a model's own
    //! declaring functions).

    pub use crate::core::clocks::{ClockedOutput, InputClock, PeriodParameter, Tick};
    pub use crate::core::declare::{InputDerivative, OutputDerivative, Place};
    pub use crate::core::structural::StructuralParameter;
    pub use crate::core::tables::{concat, every, same};
    pub use crate::core::{
        Declaration, DefaultExperiment, Element, EventUpdate, Family, Jacobian, Log, LogCategory,
        Model, ModelInfo, OutputDerivativeError, StepOutcome, Var, Variability,
    };
    pub use crate::export_fmu;
}

/// Exports one model as an FMU of both standards: the model's index cell
/// ([`share_index!`]: built once per loaded library, shared by the instances), the FMI
/// 2.0 functions ([`export_fmi2!`]) and the FMI 3.0 functions ([`export_fmi3!`]) from
/// one cdylib,
/// and the symbol `robofmu_fmu_description` through which the workspace packager
/// reads the model's [`Description`](description::Description) (see [`description`]).
/// Call it once per FMU crate, at the crate root: `robofmu_fmi::export_fmu!(Planner);`.
#[macro_export]
macro_rules! export_fmu {
    ($model:ty) => {
        $crate::share_index!($model);
        $crate::export_fmi2!($model);
        $crate::export_fmi3!($model);

        /// The FMU's description header, for the workspace packager (not an FMI function).
        #[unsafe(no_mangle)]
        pub extern "C" fn robofmu_fmu_description() -> *const $crate::description::Header {
            static HEADER: $crate::description::Header =
                $crate::description::Header::of::<$model>();
            &HEADER
        }
    };
}
