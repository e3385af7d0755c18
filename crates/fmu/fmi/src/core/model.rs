//! The contract between a model and the FMI layer. A model implements `Model` in safe
//! Rust with core types only; a front-end does all pointer handling, argument checking, state-machine
//! enforcement, logging and unwind catching.

use super::clocks::InputClock;
use super::declare::Declaration;
use super::hooks::Element;
pub use super::hooks::OutputDerivativeError;
use super::log::{Log, LogCategory};
use super::sizes::{Sizes, StructuralParameter};

/// DefaultExperiment of modelDescription.xml.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DefaultExperiment {
    pub start_time: f64,
    pub stop_time: f64,
    pub tolerance: f64,
    pub step_size: f64,
}

/// What a model's author states about it: names, instantiation token, description,
/// default experiment, event indicators and log categories. The rest of the
/// description's facts are derived, so that they cannot disagree with what they describe:
/// the continuous states are counted from the declarations
/// ([`continuous_states`](super::declare::continuous_states)), directional derivatives
/// are provided exactly when [`Model::JACOBIAN`] is given, and maxOutputDerivativeOrder
/// is the highest order the declarations' output-derivative hooks answer
/// ([`max_output_derivative_order`](super::declare::max_output_derivative_order)).
#[derive(Debug, Clone, Copy)]
pub struct ModelInfo {
    /// modelName (also the FMU's file name).
    pub model_name: &'static str,
    /// modelIdentifier: a C identifier naming the binary.
    pub model_identifier: &'static str,
    /// The instantiation token (FMI 2.0 guid, FMI 3.0 instantiationToken).
    pub guid: &'static str,
    pub description: &'static str,
    pub default_experiment: DefaultExperiment,
    pub number_of_event_indicators: usize,
    /// Model-specific log categories (the layer's own come first).
    pub log_categories: &'static [LogCategory],
}

impl ModelInfo {
    /// The facts of a model named `name` (modelName and modelIdentifier) without event
    /// indicators or log categories of its own; the methods below add them.
    pub const fn new(
        name: &'static str,
        guid: &'static str,
        description: &'static str,
        [start_time, stop_time, tolerance, step_size]: [f64; 4],
    ) -> Self {
        ModelInfo {
            model_name: name,
            model_identifier: name,
            guid,
            description,
            default_experiment: DefaultExperiment {
                start_time,
                stop_time,
                tolerance,
                step_size,
            },
            number_of_event_indicators: 0,
            log_categories: &[],
        }
    }

    /// The model's own log categories.
    pub const fn logs(mut self, categories: &'static [LogCategory]) -> Self {
        self.log_categories = categories;
        self
    }
}

/// d(unknown)/d(known) of one pair of declared elements (see [`Jacobian`]).
pub type PartialDerivative<M> = fn(&M, Element, Element) -> Result<f64, String>;

/// dvUnknown = J dvKnown into `out` for (`model`, `unknowns`, `knowns`, `seed`, `out`)
/// (see [`Jacobian`]).
pub type DirectionalDerivative<M> =
    fn(&M, &[Element], &[Element], &[f64], &mut [f64]) -> Result<(), String>;

/// How a model answers directional derivatives (fmi2GetDirectionalDerivative,
/// fmi3GetDirectionalDerivative and fmi3GetAdjointDerivative), the variables given as
/// declared [`Element`]s at the current point (computed values are current). An error
/// (the model cannot be evaluated here) makes the call return Discard.
pub enum Jacobian<M> {
    /// d(unknown)/d(known) one pair at a time; the layer sums the pairs over the seed.
    Partial(PartialDerivative<M>),
    /// As `Partial`, for a model whose array elements are independent (channels,
    /// axes): d(unknown element i)/d(known element j) is 0 for i != j without a call
    /// (a scalar is element 0), and the model answers the pairs i == j.
    Diagonal(PartialDerivative<M>),
    /// dvUnknown = J dvKnown for all unknowns at once (`unknowns`, `knowns`, `seed`,
    /// `out`), for a model that linearizes once per call instead of once per pair.
    Directional(DirectionalDerivative<M>),
}

impl<M> Jacobian<M> {
    /// dvUnknown = J dvKnown into `out` (one value per unknown).
    pub fn apply(
        &self,
        model: &M,
        unknowns: &[Element],
        knowns: &[Element],
        seed: &[f64],
        out: &mut [f64],
    ) -> Result<(), String> {
        match self {
            Jacobian::Directional(f) => f(model, unknowns, knowns, seed, out),
            Jacobian::Partial(partial) | Jacobian::Diagonal(partial) => {
                let diagonal = matches!(self, Jacobian::Diagonal(_));
                for (o, &u) in out.iter_mut().zip(unknowns) {
                    let mut sum = 0.0;
                    for (&k, &s) in knowns.iter().zip(seed) {
                        if !diagonal || k.index == u.index {
                            sum += partial(model, u, k)? * s;
                        }
                    }
                    *o = sum;
                }
                Ok(())
            }
        }
    }
}

/// Result of a co-simulation step.
#[derive(Debug, Clone, PartialEq)]
pub enum StepOutcome {
    Completed,
    /// The step was rejected (the layer restores the state as it was before the step).
    /// `terminate` says the model cannot continue at all (fmi2Terminated = true)
    /// rather than asking for a smaller step.
    Discarded {
        reason: String,
        terminate: bool,
    },
}

impl StepOutcome {
    /// A step the model refuses for good, with the reason: it cannot go on
    /// (`Discarded` with `terminate`).
    pub fn terminate(reason: String) -> Self {
        StepOutcome::Discarded {
            reason,
            terminate: true,
        }
    }
}

/// What an event update (fmi2NewDiscreteStates, fmi3UpdateDiscreteStates) changed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct EventUpdate {
    /// Another event iteration is needed at the same time instant.
    pub discrete_states_need_update: bool,
    /// The model cannot go on: the host should terminate the simulation.
    pub terminate_simulation: bool,
    /// The continuous states were changed (re-initialized) by the event.
    pub values_of_continuous_states_changed: bool,
    /// The nominal values of the continuous states changed.
    pub nominals_of_continuous_states_changed: bool,
}

/// A model that can be exported as an FMU by a front-end (`export_fmu!`).
///
/// Slices passed to the continuous-state methods have exactly one element per
/// continuous state (element of a derivative declaration), or per event indicator
/// (`INFO.number_of_event_indicators`).
/// The model never sees a value reference: variables reach it as the accessors and
/// hooks of its declarations, called with an element index, or as [`Element`]s.
///
/// The layer builds a model as `Default::default()` and then applies every start value
/// of the table through its writers, so start values live in the declarations only.
pub trait Model: Clone + Default + Send + Sized + 'static {
    const INFO: &'static ModelInfo;

    /// The variable table, declared once: a `static` slice of [`Declaration`]s
    /// (scalars and arrays, accessors and hooks as `fn` pointers; see
    /// [`declare`](super::declare)).
    const VARIABLES: &'static [Declaration<Self>];

    /// The layer's simulation time changed (setup, fmi2SetTime, a completed step); a
    /// time-invariant model ignores it (the default).
    fn set_time(&mut self, _time: f64) {}

    /// End of initialization: check the parameters together (a message says which
    /// one is wrong and why) and prepare for simulation.
    fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String>;

    /// Co-simulation step from `time` to `time + step`: each continuous Real input
    /// follows u(s) = u + u' s + u'' s^2/2 + ... (s the time since `time`) with the
    /// derivatives last written to its declaration's
    /// [`input_derivative`](Declaration::input_derivative) slot, i.e. it is held when
    /// none were given. Without it, a step completes and changes nothing: a model
    /// whose outputs are functions of time and parameters has nothing to integrate.
    fn do_step(&mut self, _time: f64, _step: f64, _log: &dyn Log) -> StepOutcome {
        StepOutcome::Completed
    }

    /// Highest order of input time derivative that `do_step` uses (FMI 2.0
    /// canInterpolateInputs when above 0); 0: the inputs are held over a step.
    const MAX_INPUT_DERIVATIVE_ORDER: u32 = 0;

    /// FMI 3.0 Co-Simulation intermediate update: the number of equal sub-intervals a
    /// communication step is split into when the importer passed an intermediateUpdate
    /// callback (each sub-interval one `do_step`; the callback is called at the inner
    /// points, where the importer may read outputs and set continuous inputs, which
    /// then hold until the next point). 0: no intermediate update (the default).
    const INTERMEDIATE_UPDATE_POINTS: u32 = 0;

    /// Computes every calculated value (outputs, derivatives, ...) after a change of
    /// parameters, inputs, states or time, for the getters to read. The layer calls it
    /// once before the first read after a change (not once per read). An error means
    /// the model cannot be evaluated at this point: reads of calculated variables then
    /// return Discard with this reason.
    fn calculate_values(&mut self) -> Result<(), String> {
        Ok(())
    }

    /// The continuous states, by default read through the accessors of the declared
    /// states (element i of the state of each derivative declaration, in their order;
    /// `&mut` because a state kept at a place is reached through it, not changed).
    fn continuous_states(&mut self, x: &mut [f64]) {
        let sizes = Sizes::of(self, Self::STRUCTURAL);
        super::declare::read_states(Self::VARIABLES, &sizes, self, x);
    }

    /// Sets the continuous states, by default through the declared states' writers or
    /// places.
    fn set_continuous_states(&mut self, x: &[f64]) {
        let sizes = Sizes::of(self, Self::STRUCTURAL);
        super::declare::write_states(Self::VARIABLES, &sizes, self, x);
    }

    /// State derivatives, by default read through the getters of the derivative
    /// declarations; an error (the model cannot be evaluated at this point, e.g. a
    /// function outside its domain) makes fmi2GetDerivatives return fmi2Discard.
    fn derivatives(&self, dx: &mut [f64]) -> Result<(), String> {
        let sizes = Sizes::of(self, Self::STRUCTURAL);
        super::declare::read_derivatives(Self::VARIABLES, &sizes, self, dx);
        Ok(())
    }

    fn nominals_of_continuous_states(&self, nominals: &mut [f64]) {
        nominals.fill(1.0);
    }

    /// Event indicators; an error makes fmi2GetEventIndicators return fmi2Discard.
    fn event_indicators(&self, _z: &mut [f64]) -> Result<(), String> {
        Ok(())
    }

    /// Event mode, fmi2NewDiscreteStates: update the discrete variables (Model Exchange)
    /// and say what else the event changed or needs.
    fn update_discrete_states(&mut self) -> EventUpdate {
        EventUpdate::default()
    }

    /// Next time event strictly after `time`, if any (Model Exchange).
    fn next_time_event(&self, _time: f64) -> Option<f64> {
        None
    }

    /// FMI 3.0 clocked partitions: the model's input clocks, each with its period
    /// parameter, outputs and tick hook ([`clocks`](super::clocks)); none by default.
    /// FMI 2.0 serves none of it.
    const CLOCKS: &'static [InputClock<Self>] = &[];

    /// FMI 3.0 structural parameters: UInt64 sizes of the arrays declared
    /// [`sized_by`](Declaration::sized_by) them, set in Configuration Mode
    /// ([`structural`](super::structural)); none by default. FMI 2.0 and the
    /// scalar-only FMI 3.0 view keep the default sizes.
    const STRUCTURAL: &'static [StructuralParameter<Self>] = &[];

    /// Directional derivatives: provided (providesDirectionalDerivative) exactly when
    /// given.
    const JACOBIAN: Option<Jacobian<Self>> = None;

    /// Internal state that is neither a settable variable nor a continuous state,
    /// appended to serialized FMU states; by default the clocks' periods and what their
    /// laws hold ([`write_partitions`](super::clocks::write_partitions); nothing for a
    /// model without clocks).
    fn write_extra_state(&self, out: &mut Vec<u8>) {
        super::clocks::write_partitions(Self::CLOCKS, self, out);
    }

    /// Reads back what `write_extra_state` wrote.
    fn read_extra_state(&mut self, bytes: &[u8]) -> Result<(), String> {
        super::clocks::read_partitions(Self::CLOCKS, self, bytes)
    }
}
