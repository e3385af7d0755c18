//! One model instance, independent of the FMI version: the model, its time, the stop
//! time of the experiment, and typed, checked access to the variables. A front-end
//! adds its mode, logger and C entry points around it.

use super::declare::{self, Declaration, value_references, write_element};
use super::flatten::{flatten, start_of};
use super::log::Log;
use super::model::{Model, StepOutcome};
use super::shared::{Built, Shared};
use super::value_check::{self, Value, wrong_type};
use super::variables::{Initial, Variable, VariableType, element_name, find, value_type};
use super::view::Table3;
use std::sync::{Arc, Mutex, TryLockError};

/// Does not log: the model's checks on a copy are not the instance's.
pub struct Silent;

impl Log for Silent {
    fn debug(&self, _category: &str, _message: &str) {}
}

/// The FMI standard whose front-end wrote an FMU state.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Standard {
    Fmi2,
    Fmi3,
}

impl Standard {
    /// Byte stored in serialized states.
    pub fn code(self) -> u8 {
        match self {
            Standard::Fmi2 => 2,
            Standard::Fmi3 => 3,
        }
    }

    pub fn from_code(code: u8) -> Option<Standard> {
        match code {
            2 => Some(Standard::Fmi2),
            3 => Some(Standard::Fmi3),
            _ => None,
        }
    }
}

/// The version-neutral part of an instance. The model is private so that every change
/// goes through [`Instance::model_mut`], which marks the computed values stale.
pub struct Instance<M: Model> {
    /// The declarations with their value references and calculated flags: shared by
    /// every instance of the model in this library.
    index: Arc<Index<M>>,
    /// Boxed: an instance is moved several times while it is built (a model such as the
    /// plant's is kilobytes; a move of the box is a pointer).
    model: Box<M>,
    /// The model as it was before the current step (a discarded step swaps it back):
    /// kept between steps so that saving it is `clone_from`, which reuses what the
    /// model allocated (a model with vectors, such as the N-channel PID, then
    /// allocates nothing per step).
    before_step: Box<M>,
    /// Computed values are stale (`Model::calculate_values` not called since a change).
    dirty: bool,
    /// Why the model could not be evaluated at the last calculation, if it could not.
    evaluation_error: Option<String>,
    pub time: f64,
    /// Stop time of the experiment, if the host defined one: steps beyond it are refused.
    pub stop_time: Option<f64>,
    pub last_successful_time: f64,
    /// Set when a step was discarded because the model cannot go on at all.
    pub terminated_by_model: bool,
}

/// A copy of everything that setting an FMU state restores.
#[derive(Clone)]
pub struct Snapshot<M: Model> {
    pub model: M,
    pub time: f64,
    pub stop_time: Option<f64>,
    pub last_successful_time: f64,
    pub terminated_by_model: bool,
    /// The front-end that took (or serialized) the state.
    pub standard: Standard,
}

/// A new model with every start value of the table applied through its writer.
pub fn model_with_start_values<M: Model>(table: &[Variable<M>]) -> Result<M, String> {
    with_start_values(table.iter().map(|v| (v.declaration, v.index)))
}

/// A new model with the start value of every element of `elements` (a declaration and
/// an element index, in value-reference order) applied through its writer.
fn with_start_values<'a, M: Model>(
    elements: impl Iterator<Item = (&'a Declaration<M>, usize)>,
) -> Result<M, String> {
    let mut model = super::structural::at_start(M::default());
    for (d, i) in elements {
        let m = &mut model;
        let written = match d.value {
            declare::Value::Real {
                get, set, start, ..
            } => start_of(start, i).and_then(|s| write_element(get, set, m, i, s)),
            declare::Value::Integer {
                get, set, start, ..
            } => start_of(start, i).and_then(|s| write_element(get, set, m, i, s)),
            declare::Value::Boolean { get, set, start } => {
                start_of(start, i).and_then(|s| write_element(get, set, m, i, s))
            }
        };
        let name = element_name(d, i);
        match (written, d.after_set) {
            (Some(Err(e)), _) => return Err(format!("start value of \"{name}\" rejected: {e}")),
            (Some(Ok(())), Some(after)) => after(m, i),
            _ => {}
        }
    }
    // The clocks' periods (FMI 3.0 parameters) too, so that a model of either
    // standard carries valid periods in its FMU states.
    for c in M::CLOCKS {
        (c.period.set)(&mut model, c.period.start);
    }
    Ok(model)
}

/// The model's variable table sorted by value reference, with unique value
/// references (all the runtime relies on; the full `check_table` runs where the
/// modelDescription is written, in every FMU crate's drift test).
pub fn sorted_table<M: Model>() -> Result<Vec<Variable<M>>, String> {
    let table = by_value_reference(flatten(M::VARIABLES));
    if let Some(pair) = table
        .windows(2)
        .find(|p| p[0].value_reference == p[1].value_reference)
    {
        return Err(format!(
            "\"{}\" and \"{}\" share the value reference {}",
            pair[0].name(),
            pair[1].name(),
            pair[0].value_reference
        ));
    }
    Ok(table)
}

/// `table` sorted by value reference, each variable moved once (a variable is a few
/// hundred bytes: an in-place sort of a table declared array by array, whose value
/// references interleave, would move each several times).
fn by_value_reference<M>(table: Vec<Variable<M>>) -> Vec<Variable<M>> {
    if table.is_sorted_by_key(|v| v.value_reference) {
        return table;
    }
    let mut order: Vec<(u32, usize)> = table
        .iter()
        .enumerate()
        .map(|(i, v)| (v.value_reference, i))
        .collect();
    order.sort_unstable();
    let mut slots: Vec<Option<Variable<M>>> = table.into_iter().map(Some).collect();
    order.iter().filter_map(|&(_, i)| slots[i].take()).collect()
}

/// The variable with value reference `vr` in a sorted table.
#[inline]
pub fn variable<M>(table: &[Variable<M>], vr: u32) -> Result<&Variable<M>, String> {
    find(table, vr).ok_or_else(|| format!("unknown value reference {vr}"))
}

/// Whether reading the declaration `d` of `all` needs the computed values (an output,
/// derivative or other calculated variable, as opposed to a parameter, an input or a
/// continuous state, even one declared as an output).
fn calculated<M>(all: &[Declaration<M>], d: &Declaration<M>) -> bool {
    let is_state = || all.iter().any(|s| s.derivative_of == Some(d.name));
    let computed = matches!(d.initial, Some(Initial::Calculated | Initial::Approx));
    d.derivative_of.is_some() || (computed && !is_state())
}

/// A model whose index has a cell of its own in this library: implemented by
/// [`share_index!`](crate::share_index) for the type [`export_fmu!`](crate::export_fmu)
/// exports (or a test names).
pub trait Library: Model {
    /// The model's index cell (a `static` of the FMU crate).
    fn index() -> &'static Shared<Index<Self>>;
}

/// Defines the [`Library`] cell of a model type (called by
/// [`export_fmu!`](crate::export_fmu); a test that instantiates a model in process
/// calls it once per model type).
#[macro_export]
macro_rules! share_index {
    ($model:ty) => {
        impl $crate::core::instance::Library for $model {
            fn index()
            -> &'static $crate::core::shared::Shared<$crate::core::instance::Index<$model>> {
                static INDEX: $crate::core::shared::Shared<$crate::core::instance::Index<$model>> =
                    $crate::core::shared::Shared::new();
                &INDEX
            }
        }
    };
}

/// One declaration as the index holds it: the value reference of its element 0
/// (element i at `first + i * stride`) and whether reading it needs the computed
/// values.
pub struct Declared<M: 'static> {
    pub declaration: &'static Declaration<M>,
    pub first: u32,
    /// Reading it needs the computed values (see [`Index`]).
    pub calculated: bool,
}

/// One element in the index's map from value reference to declaration.
struct Slot<M: 'static> {
    value_reference: u32,
    /// Element index within the declaration (0 for a scalar).
    element: u32,
    /// The declaration's [`Declared::calculated`].
    calculated: bool,
    declaration: &'static Declaration<M>,
}

impl<M> Clone for Slot<M> {
    fn clone(&self) -> Self {
        *self
    }
}
impl<M> Copy for Slot<M> {}

/// A calculated Real element, checked to be finite after each calculation.
struct CalculatedReal<M: 'static> {
    get: declare::Access<M, f64>,
    element: usize,
    declaration: &'static Declaration<M>,
}

/// The model's index, built once from its declarations: one record per declaration
/// and a compact map, sorted by value reference, from every element's value reference
/// to (declaration, element); the getters and setters call the declaration's accessor
/// with the element index. FMI 2.0's scalars ([`Variable`]) and FMI 3.0's variables
/// are views of it, each built the first time it is asked for. It also holds the
/// model as instantiation makes it, which every instance and reset clones.
pub struct Index<M: 'static> {
    /// The model's declarations (`Model::declarations`).
    all: &'static [Declaration<M>],
    /// One record per declaration, in declaration order.
    pub declarations: Vec<Declared<M>>,
    /// Every element, sorted by value reference (unique: checked when built).
    slots: Vec<Slot<M>>,
    /// The calculated Real elements, in value-reference order.
    calculated_reals: Vec<CalculatedReal<M>>,
    /// The FMI 2.0 scalars sorted by value reference (descriptions, FMU states,
    /// directional derivatives, messages), built the first time they are asked for.
    table: Built<Vec<Variable<M>>>,
    /// The model with every start value applied, built once (a clone costs a copy; the
    /// setters of every start value cost about 1,700 instructions for the PID). In a
    /// Mutex because a model need not be `Sync` (the plant keeps a `RefCell` cache).
    fresh: Mutex<M>,
    /// FMI 3.0's two views (the array view and the scalar-only view), each built the
    /// first time an FMI 3.0 instance asks for it. No `OnceLock` here: the cells take
    /// no lock, so a child forked while a view is built finds nothing held.
    arrays: Built<Arc<Table3>>,
    scalars: Built<Arc<Table3>>,
}

/// Where an instantiation takes the model's index from: [`Index::shared`] (the exported
/// C functions) or [`Index::own`] (an in-process host calling the generic functions).
pub type IndexOf<M> = fn() -> Result<Arc<Index<M>>, String>;

impl<M: Library> Index<M> {
    /// The index of model M: built once per loaded library (its declarations are
    /// static, so every instance has the same), in M's own cell.
    pub fn shared() -> Result<Arc<Self>, String> {
        M::index().get(Self::build)
    }
}

impl<M: Model> Index<M> {
    /// An index of its own: what an in-process host gets, which calls the generic
    /// instantiate functions with a model type that has no library cell.
    pub fn own() -> Result<Arc<Self>, String> {
        Self::build().map(Arc::new)
    }

    /// The index of M's declarations; Err when two elements share a value reference
    /// (all the runtime relies on; the full `check_table` runs where the
    /// modelDescription is written, in every FMU crate's drift test).
    fn build() -> Result<Self, String> {
        let all = M::VARIABLES;
        let declarations: Vec<Declared<M>> = (all.iter().zip(value_references(all)))
            .map(|(declaration, first)| Declared {
                declaration,
                first,
                calculated: calculated(all, declaration),
            })
            .collect();
        let mut slots = Vec::with_capacity(all.iter().map(Declaration::size).sum());
        for d in &declarations {
            let stride = d.declaration.stride;
            slots.extend((0..d.declaration.size() as u32).map(|i| Slot {
                value_reference: d.first + i * stride,
                element: i,
                calculated: d.calculated,
                declaration: d.declaration,
            }));
        }
        slots.sort_unstable_by_key(|s| s.value_reference);
        let element = |s: &Slot<M>| (s.declaration, s.element as usize);
        if let Some(pair) = slots
            .windows(2)
            .find(|p| p[0].value_reference == p[1].value_reference)
        {
            let ((a, i), (b, j)) = (element(&pair[0]), element(&pair[1]));
            return Err(format!(
                "\"{}\" and \"{}\" share the value reference {}",
                element_name(a, i),
                element_name(b, j),
                pair[0].value_reference
            ));
        }
        let fresh = with_start_values(slots.iter().map(element))?;
        let calculated_reals = (slots.iter())
            .filter(|s| s.calculated)
            .filter_map(|s| match s.declaration.value {
                declare::Value::Real { get, .. } => Some(CalculatedReal {
                    get,
                    element: s.element as usize,
                    declaration: s.declaration,
                }),
                _ => None,
            })
            .collect();
        Ok(Index {
            all,
            declarations,
            slots,
            calculated_reals,
            table: Built::new(),
            fresh: Mutex::new(fresh),
            arrays: Built::new(),
            scalars: Built::new(),
        })
    }

    /// FMI 3.0's scalar-only view when `scalar`, else its array view, built from the
    /// FMI 2.0 view by `build` the first time it is asked for (an error is returned,
    /// not kept).
    pub fn view3(
        &self,
        scalar: bool,
        build: impl FnOnce(&[Variable<M>]) -> Result<Table3, String>,
    ) -> Result<Arc<Table3>, String> {
        let cell = if scalar { &self.scalars } else { &self.arrays };
        if let Some(view) = cell.get() {
            return Ok(Arc::clone(view));
        }
        let built = Arc::new(build(self.table())?);
        Ok(Arc::clone(cell.get_or_init(|| built)))
    }

    /// The model with every start value applied: a clone of the one built once, or,
    /// when another thread holds it (or, in a child forked meanwhile, a thread that
    /// does not exist there), the same model built again from the start values (no
    /// wait: a fork at any moment cannot leave the child blocked here).
    pub fn fresh_model(&self) -> M {
        match self.fresh.try_lock() {
            Ok(model) => model.clone(),
            Err(TryLockError::Poisoned(poisoned)) => poisoned.into_inner().clone(),
            Err(TryLockError::WouldBlock) => with_start_values(
                self.slots
                    .iter()
                    .map(|s| (s.declaration, s.element as usize)),
            )
            .expect("the start values were applied when the index was built"),
        }
    }
}

impl<M: 'static> Index<M> {
    /// The FMI 2.0 view: every element as a scalar [`Variable`], sorted by value
    /// reference (built the first time it is asked for).
    pub fn table(&self) -> &[Variable<M>] {
        (self.table).get_or_init(|| by_value_reference(flatten(self.all)))
    }

    /// Number of elements (FMI 2.0 scalars).
    pub fn len(&self) -> usize {
        self.slots.len()
    }

    /// Whether the model declares no variable.
    pub fn is_empty(&self) -> bool {
        self.slots.is_empty()
    }

    /// The declaration, element index and calculated flag of value reference `vr`.
    #[inline(always)]
    pub fn element(&self, vr: u32) -> Option<(&'static Declaration<M>, usize, bool)> {
        let k = (self.slots)
            .binary_search_by_key(&vr, |s| s.value_reference)
            .ok()?;
        let s = self.slots[k];
        Some((s.declaration, s.element as usize, s.calculated))
    }
}

pub use super::value_check::MAX_MAGNITUDE;

/// Largest accepted difference between the master's communication point and the
/// instance time (and overshoot of the stop time), relative to max(1, |t|): absorbs
/// round-off of t += h in the master.
pub const TIME_MATCH: f64 = 1e-9;

impl<M: Model> Instance<M> {
    /// The model with its start values (those of `index`), at the default experiment's
    /// start time.
    pub fn new(index: Arc<Index<M>>) -> Result<Self, String> {
        let mut model = index.fresh_model();
        let time = M::INFO.default_experiment.start_time;
        model.set_time(time);
        Ok(Instance {
            index,
            before_step: Box::new(model.clone()),
            model: Box::new(model),
            dirty: true,
            evaluation_error: None,
            time,
            stop_time: None,
            last_successful_time: time,
            terminated_by_model: false,
        })
    }

    /// Back to the state right after instantiation (the table is kept).
    pub fn reset(&mut self) {
        *self.model = self.index.fresh_model();
        self.dirty = true;
        self.stop_time = None;
        self.terminated_by_model = false;
        self.set_time(M::INFO.default_experiment.start_time);
        self.last_successful_time = self.time;
    }

    /// The FMI 2.0 view of the index ([`Index::table`]).
    pub fn table(&self) -> &[Variable<M>] {
        self.index.table()
    }

    /// The declaration and element index of value reference `vr`.
    #[inline(always)]
    pub fn element(&self, vr: u32) -> Result<(&'static Declaration<M>, usize), String> {
        match self.index.element(vr) {
            Some((d, i, _)) => Ok((d, i)),
            None => Err(format!("unknown value reference {vr}")),
        }
    }

    /// The index (shared with the other instances of a declared model).
    pub fn index(&self) -> &Arc<Index<M>> {
        &self.index
    }

    pub fn model(&self) -> &M {
        &self.model
    }

    /// The model for reading variables kept at places (reached through `&mut`, not
    /// changed: the computed values stay current).
    pub fn model_to_read(&mut self) -> &mut M {
        &mut self.model
    }

    /// The model for a change: the computed values become stale.
    pub fn model_mut(&mut self) -> &mut M {
        self.dirty = true;
        &mut self.model
    }

    pub fn set_time(&mut self, time: f64) {
        self.time = time;
        self.model_mut().set_time(time);
    }

    /// Brings the computed values up to date (once per change) and checks that every
    /// calculated Real is finite; Err: why the model cannot be evaluated here.
    pub fn update_values(&mut self) -> Result<(), String> {
        if self.dirty {
            self.dirty = false;
            self.evaluation_error = self
                .model
                .calculate_values()
                .and_then(|()| self.check_calculated_finite())
                .err();
        }
        self.evaluation_error.clone().map_or(Ok(()), Err)
    }

    /// Every calculated Real element, in value-reference order, is finite.
    fn check_calculated_finite(&mut self) -> Result<(), String> {
        for c in &self.index.calculated_reals {
            let value = c.get.read(&mut self.model, c.element);
            if !value.is_finite() {
                let name = element_name(c.declaration, c.element);
                return Err(format!("\"{name}\" evaluates to {value}"));
            }
        }
        Ok(())
    }

    /// Prepares reading `vrs`: Err for an unknown value reference; Ok(Some(reason))
    /// when one of them cannot be evaluated here (a calculated one where the model
    /// cannot be evaluated, or any Real that is not finite: the front-end returns
    /// Discard); Ok(None) when all can be read.
    /// The value references come as an iterator (FMI 3.0: the elements of its arrays,
    /// not collected).
    pub fn prepare_read(
        &mut self,
        vrs: impl IntoIterator<Item = u32>,
    ) -> Result<Option<String>, String> {
        let mut needs_values = false;
        for vr in vrs {
            let Some((d, i, calculated)) = self.index.element(vr) else {
                return Err(format!("unknown value reference {vr}"));
            };
            if calculated {
                needs_values = true;
            } else if let Some(reason) = self.not_finite(d, i) {
                return Ok(Some(reason));
            }
        }
        self.prepared(needs_values)
    }

    /// [`prepare_read`](Instance::prepare_read) for FMI 3.0's variables, given as
    /// (declaration position, first element, count) (a [`Declared`] of the index and
    /// the elements an FMI 3.0 variable reads).
    pub fn prepare_read_declared(
        &mut self,
        parts: impl IntoIterator<Item = (usize, usize, usize)>,
    ) -> Result<Option<String>, String> {
        let mut needs_values = false;
        for (position, from, n) in parts {
            let d = self.declared(position)?;
            if d.calculated {
                needs_values = true;
                continue;
            }
            let d = d.declaration;
            if let Some(reason) = (from..from + n).find_map(|i| self.not_finite(d, i)) {
                return Ok(Some(reason));
            }
        }
        self.prepared(needs_values)
    }

    /// Why element i of `d` cannot be read now, if it is a Real that is not finite.
    #[inline(always)]
    fn not_finite(&mut self, d: &Declaration<M>, i: usize) -> Option<String> {
        let declare::Value::Real { get, .. } = d.value else {
            return None;
        };
        let value = get.read(&mut self.model, i);
        (!value.is_finite()).then(|| format!("\"{}\" evaluates to {value}", element_name(d, i)))
    }

    /// The end of a `prepare_read`: the computed values made current if needed.
    fn prepared(&mut self, needs_values: bool) -> Result<Option<String>, String> {
        if needs_values {
            return Ok(self.update_values().err());
        }
        Ok(None)
    }

    /// The index's declaration at `position` (of an FMI 3.0 variable's source).
    #[inline(always)]
    fn declared(&self, position: usize) -> Result<&Declared<M>, String> {
        (self.index.declarations)
            .get(position)
            .ok_or_else(|| format!("no declaration at position {position}"))
    }

    /// Reads elements `from..from + out.len()` of the Real declaration at `position`
    /// (FMI 3.0's array view, after `prepare_read_declared`).
    #[inline(always)]
    pub fn get_reals(
        &mut self,
        position: usize,
        from: usize,
        out: &mut [f64],
    ) -> Result<(), String> {
        let d = self.declared(position)?.declaration;
        let declare::Value::Real { get, .. } = d.value else {
            return Err(format!("\"{}\" is not a Real", d.name));
        };
        for (o, i) in out.iter_mut().zip(from..) {
            let value = get.read(&mut self.model, i);
            if !value.is_finite() {
                return Err(format!("\"{}\" evaluated to {value}", element_name(d, i)));
            }
            *o = value;
        }
        Ok(())
    }

    /// Reads elements `from..from + out.len()` of the Integer declaration at `position`.
    #[inline(always)]
    pub fn get_integers(
        &mut self,
        position: usize,
        from: usize,
        out: &mut [i32],
    ) -> Result<(), String> {
        let d = self.declared(position)?.declaration;
        let declare::Value::Integer { get, .. } = d.value else {
            return Err(format!("\"{}\" is not an Integer", d.name));
        };
        for (o, i) in out.iter_mut().zip(from..) {
            *o = get.read(&mut self.model, i);
        }
        Ok(())
    }

    /// Reads elements `from..from + out.len()` of the Boolean declaration at `position`.
    #[inline(always)]
    pub fn get_booleans(
        &mut self,
        position: usize,
        from: usize,
        out: &mut [bool],
    ) -> Result<(), String> {
        let d = self.declared(position)?.declaration;
        let declare::Value::Boolean { get, .. } = d.value else {
            return Err(format!("\"{}\" is not a Boolean", d.name));
        };
        for (o, i) in out.iter_mut().zip(from..) {
            *o = get.read(&mut self.model, i);
        }
        Ok(())
    }

    /// Writes `values` to elements `from..` of the declaration at `position`, whose
    /// value references are `first + k * stride`, each through the checks of
    /// [`value_check::write`], in order (the first refusal stops).
    pub fn set_declared(
        &mut self,
        position: usize,
        from: usize,
        (first, stride): (u32, u32),
        values: impl IntoIterator<Item = Value>,
    ) -> Result<(), String> {
        let d = self.declared(position)?.declaration;
        for (k, value) in values.into_iter().enumerate() {
            let vr = first.wrapping_add(k as u32 * stride);
            self.dirty = true;
            value_check::write(&mut *self.model, d, from + k, vr, value)?;
        }
        Ok(())
    }

    /// Whether elements `from..` of the declaration at `position` hold `values`
    /// already, each bit for bit ([`value_check::holds`]).
    pub fn holds_declared(
        &mut self,
        position: usize,
        from: usize,
        values: impl IntoIterator<Item = Value>,
    ) -> Result<bool, String> {
        let d = self.declared(position)?.declaration;
        let model = &mut *self.model;
        Ok((from..)
            .zip(values)
            .all(|(i, x)| value_check::holds(model, d, i, x)))
    }

    /// Why ExitInitializationMode would refuse the parameters now, if it would (the
    /// model's check on a copy).
    pub fn parameters_refused(&self) -> Option<String> {
        (*self.model).clone().exit_initialization(&Silent).err()
    }

    pub fn snapshot(&self, standard: Standard) -> Snapshot<M> {
        Snapshot {
            model: (*self.model).clone(),
            time: self.time,
            stop_time: self.stop_time,
            last_successful_time: self.last_successful_time,
            terminated_by_model: self.terminated_by_model,
            standard,
        }
    }

    pub fn restore(&mut self, s: &Snapshot<M>) {
        *self.model = s.model.clone();
        self.dirty = true;
        self.time = s.time;
        self.stop_time = s.stop_time;
        self.last_successful_time = s.last_successful_time;
        self.terminated_by_model = s.terminated_by_model;
    }

    /// End of initialization: the model's own checks, then the computed values at the
    /// start must exist and be finite (a parameter that overflows is refused here,
    /// not noticed by a getter later).
    pub fn exit_initialization(&mut self, log: &dyn Log) -> Result<(), String> {
        self.model_mut().exit_initialization(log)?;
        self.update_values()
            .map_err(|e| format!("the model cannot be evaluated at the start: {e}"))
    }

    /// Err unless a co-simulation step from `t` by `h` is legal: finite, positive
    /// size, from the FMU's time, not past the stop time.
    pub fn check_step(&self, t: f64, h: f64) -> Result<(), String> {
        for (value, what) in [
            (t, "currentCommunicationPoint"),
            (h, "communicationStepSize"),
        ] {
            if !value.is_finite() {
                return Err(format!("{what} = {value} is not finite"));
            }
        }
        if h <= 0.0 {
            return Err(format!("communicationStepSize = {h} is not positive"));
        }
        let end = t + h;
        if !end.is_finite() {
            return Err(format!(
                "the step from t = {t} s by {h} s ends at t = {end} s"
            ));
        }
        if end <= t {
            return Err(format!(
                "the step from t = {t} s by {h} s does not advance the time (t + h = t in \
                 double precision): use a larger step or an earlier start time"
            ));
        }
        if (t - self.time).abs() > TIME_MATCH * t.abs().max(1.0) {
            return Err(format!(
                "currentCommunicationPoint {t} differs from the FMU time {}",
                self.time
            ));
        }
        if let Some(stop) = self.stop_time
            && t + h > stop + TIME_MATCH * stop.abs().max(1.0)
        {
            return Err(format!(
                "the step from t = {t} s by {h} s ends after stopTime = {stop} s"
            ));
        }
        Ok(())
    }

    /// A co-simulation step from `t` by `h` with the inputs held. Err: an illegal
    /// call ([`Instance::check_step`]).
    /// A discarded step leaves the instance as it was before the step.
    pub fn do_step(&mut self, t: f64, h: f64, log: &dyn Log) -> Result<StepOutcome, String> {
        self.check_step(t, h)?;
        self.before_step.clone_from(&self.model);
        self.set_time(t);
        let mut outcome = self.model_mut().do_step(t, h, log);
        if outcome == StepOutcome::Completed {
            self.set_time(t + h);
            if let Err(reason) = self.update_values() {
                outcome = StepOutcome::Discarded {
                    reason: format!("after the step: {reason}"),
                    terminate: false,
                };
            }
        }
        match &outcome {
            StepOutcome::Completed => self.last_successful_time = t + h,
            StepOutcome::Discarded { terminate, .. } => {
                std::mem::swap(&mut self.model, &mut self.before_step);
                self.dirty = true;
                self.set_time(t);
                self.terminated_by_model = *terminate;
            }
        }
        Ok(outcome)
    }

    /// The value of declaration `d` as a `wanted` one: Err for another type.
    #[cold]
    fn wrong_type(d: &Declaration<M>, i: usize, vr: u32, wanted: VariableType) -> String {
        wrong_type(
            element_name(d, i),
            vr,
            value_type(&d.value),
            wanted.as_str(),
        )
    }

    /// Reads a Real (after `prepare_read`, so computed values are current).
    #[inline(always)]
    pub fn get_real(&mut self, vr: u32) -> Result<f64, String> {
        let (d, i) = self.element(vr)?;
        let declare::Value::Real { get, .. } = d.value else {
            return Err(Self::wrong_type(d, i, vr, VariableType::Real));
        };
        let value = get.read(&mut self.model, i);
        if value.is_finite() {
            Ok(value)
        } else {
            Err(format!("\"{}\" evaluated to {value}", element_name(d, i)))
        }
    }

    #[inline(always)]
    pub fn get_integer(&mut self, vr: u32) -> Result<i32, String> {
        let (d, i) = self.element(vr)?;
        match d.value {
            declare::Value::Integer { get, .. } => Ok(get.read(&mut self.model, i)),
            _ => Err(Self::wrong_type(d, i, vr, VariableType::Integer)),
        }
    }

    #[inline(always)]
    pub fn get_boolean(&mut self, vr: u32) -> Result<bool, String> {
        let (d, i) = self.element(vr)?;
        match d.value {
            declare::Value::Boolean { get, .. } => Ok(get.read(&mut self.model, i)),
            _ => Err(Self::wrong_type(d, i, vr, VariableType::Boolean)),
        }
    }

    /// Whether the variable `vr` holds `value` already, bit for bit
    /// ([`value_check::holds`]).
    pub fn holds(&mut self, vr: u32, value: Value) -> Result<bool, String> {
        let (d, i) = self.element(vr)?;
        Ok(value_check::holds(&mut *self.model, d, i, value))
    }

    /// Writes a value through its writer after the checks of [`value_check::write`]
    /// (whether the variable may be set now is the front-end's rule).
    pub fn write(&mut self, vr: u32, value: Value) -> Result<(), String> {
        let (d, i) = self.element(vr)?;
        self.dirty = true;
        value_check::write(&mut *self.model, d, i, vr, value)
    }
}
