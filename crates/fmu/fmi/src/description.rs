//! What an FMU's cdylib tells a packager about itself: the symbol
//! `robofmu_fmu_description` that [`export_fmu!`](crate::export_fmu) exports, and the
//! [`Description`] behind it, everything the modelDescription writers of
//! `robofmu-fmi-build` need (the model's [`ModelInfo`], its FMI 2.0 scalars and both
//! FMI 3.0 views with names, units, starts, bounds, structure and dependencies), as
//! plain data that names no model type.
//!
//! The symbol returns a `#[repr(C)]` [`Header`]: a magic, the header's version, this
//! layer's version and a fingerprint of the Rust types below; only when all four
//! equal the packager's own ([`Header::check`]) does the packager call the Rust
//! function behind it. The description is built when a packager asks, never at
//! instantiation, and lent to the packager's closure: nothing allocated in the cdylib
//! is freed by the packager.

use crate::core::declare::{continuous_states, max_output_derivative_order};
use crate::core::frontend::log_categories;
use crate::core::instance::sorted_table;
use crate::core::log::LogCategory;
use crate::core::model::{Model, ModelInfo};
use crate::core::variables::check_table;
use crate::core::variables::{Causality, Initial, Kind, Variability, Variable};
use crate::fmi3::table::{self, Source, Variable3};
use crate::fmi3::{declared, scalar};
use std::any::TypeId;
use std::hash::{Hash, Hasher};

/// The name of the exported symbol.
pub const SYMBOL: &str = "robofmu_fmu_description";

const MAGIC: [u8; 8] = *b"robofmu\0";
/// Version of [`Header`]'s own layout.
const HEADER_VERSION: u32 = 1;
const LAYER_VERSION: &str = env!("CARGO_PKG_VERSION");

/// What the exported symbol points at: checked through its C layout before the Rust
/// function it carries is called.
#[repr(C)]
pub struct Header {
    /// `robofmu\0`.
    pub magic: [u8; 8],
    /// The version of this header's layout (1).
    pub header_version: u32,
    /// The FMI layer's crate version, NUL-padded.
    pub layer_version: [u8; 32],
    /// A hash of the `TypeId` of [`Description`] (crate name, version, compiler,
    /// features) and of this layer's sources (`build.rs`): equal only when the cdylib
    /// and the packager link the same build of the same sources of this crate.
    pub fingerprint: extern "C" fn() -> u64,
    /// Called (Rust ABI) only after the check.
    pub lend: Lend,
}

/// Builds the description and lends it (or the reason it cannot be built) to the
/// closure.
pub type Lend = fn(&mut dyn FnMut(Result<&Description, &str>));

impl Header {
    /// The header of model M (what `export_fmu!` exports).
    /// Evaluated in a `static`: a table whose value references collide does not compile
    /// ([`unique_value_references`](crate::core::declare::unique_value_references)).
    pub const fn of<M: Model>() -> Header {
        crate::core::declare::unique_value_references(M::VARIABLES);
        Header {
            magic: MAGIC,
            header_version: HEADER_VERSION,
            layer_version: padded(LAYER_VERSION),
            fingerprint,
            lend: lend::<M>,
        }
    }

    /// The header's lending function, once magic, versions and fingerprint are this
    /// build's; otherwise what differs, and the fix.
    pub fn check(&self) -> Result<Lend, String> {
        if self.magic != MAGIC || self.header_version != HEADER_VERSION {
            return Err(format!("{SYMBOL} is not a robofmu description header"));
        }
        if self.layer_version != padded(LAYER_VERSION) {
            let theirs = String::from_utf8_lossy(&self.layer_version);
            return Err(format!(
                "built with FMI layer {} but the packager has {LAYER_VERSION}: rebuild both \
                 with one `cargo build --release --workspace`",
                theirs.trim_end_matches('\0')
            ));
        }
        if (self.fingerprint)() != fingerprint() {
            return Err(
                "built from other sources or by another build of the FMI layer than the \
                 packager: rebuild both with one `cargo build --release --workspace`"
                    .to_string(),
            );
        }
        Ok(self.lend)
    }
}

const fn padded(text: &str) -> [u8; 32] {
    let mut out = [0u8; 32];
    let bytes = text.as_bytes();
    let mut i = 0;
    while i < bytes.len() && i < 31 {
        out[i] = bytes[i];
        i += 1;
    }
    out
}

extern "C" fn fingerprint() -> u64 {
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    TypeId::of::<Description>().hash(&mut hasher);
    env!("ROBOFMU_FMI_SOURCE_HASH").hash(&mut hasher);
    hasher.finish()
}

fn lend<M: Model>(to: &mut dyn FnMut(Result<&Description, &str>)) {
    match describe::<M>() {
        Ok(d) => to(Ok(&d)),
        Err(e) => to(Err(&e)),
    }
}

/// Everything the writers need about one FMU, naming no model type.
pub struct Description {
    pub info: ModelInfo,
    /// numberOfContinuousStates, counted from the declarations.
    pub number_of_continuous_states: usize,
    /// providesDirectionalDerivative: `Model::JACOBIAN` is given.
    pub provides_directional_derivative: bool,
    /// maxOutputDerivativeOrder: the highest order of the output-derivative hooks.
    pub max_output_derivative_order: u32,
    /// `Model::MAX_INPUT_DERIVATIVE_ORDER`.
    pub max_input_derivative_order: u32,
    /// `Model::INTERMEDIATE_UPDATE_POINTS`.
    pub intermediate_update_points: u32,
    /// The LogCategories of FMI 2.0 and of FMI 3.0 (the layer's, then the model's).
    pub log_categories: [Vec<LogCategory>; 2],
    /// The FMI 2.0 scalars, by value reference, checked (`check_table`).
    pub scalars: Vec<Scalar>,
    /// The FMI 3.0 variables (arrays), in description order.
    pub arrays: Vec<Variable3Description>,
    /// The scalar-only FMI 3.0 variables, in description order.
    pub scalar_view: Vec<Variable3Description>,
    /// The instantiationToken of the scalar-only FMI 3.0 description.
    pub scalar_token: String,
}

/// One FMI 2.0 scalar.
pub struct Scalar {
    pub value_reference: u32,
    pub name: String,
    pub description: String,
    pub causality: Causality,
    pub variability: Variability,
    pub initial: Option<Initial>,
    pub value: Value,
    /// The name of the state this scalar is the time derivative of.
    pub state: Option<String>,
    /// Knowns this output or derivative depends on (names); None: all.
    pub dependencies: Option<Vec<String>>,
    /// Knowns at initialization this initial unknown depends on; None: all.
    pub initial_dependencies: Option<Vec<String>>,
}

/// A scalar's type and its type-specific attributes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    Real {
        start: Option<f64>,
        min: Option<f64>,
        max: Option<f64>,
        unit: Option<&'static str>,
        display_unit: Option<&'static str>,
    },
    Integer {
        start: Option<i32>,
        min: Option<i32>,
        max: Option<i32>,
    },
    Boolean {
        start: Option<bool>,
    },
}

/// One FMI 3.0 variable with what its description says beyond [`Variable3`].
pub struct Variable3Description {
    pub variable: Variable3,
    pub description: String,
    pub intermediate_update: bool,
    /// Value references of the knowns it depends on, ascending; None: all.
    pub dependencies: Option<Vec<u32>>,
    /// The same at initialization.
    pub initial_dependencies: Option<Vec<u32>>,
    /// What a variable of a clocked partition (FMI 3.0 only) adds; None for the others.
    pub clock_part: Option<ClockPart>,
    /// A structural parameter (FMI 3.0 only): its start and largest value (the
    /// smallest is 1).
    pub structural: Option<[u64; 2]>,
    /// An array sized by a structural parameter: that parameter's value reference
    /// (`<Dimension valueReference=".."/>` instead of `start`).
    pub dimension_reference: Option<u32>,
}

/// The attributes of a clocked partition's variables (`core::clocks`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ClockPart {
    /// A periodic input clock, intervalVariability="fixed" without intervalDecimal
    /// (the interval from its period parameter, as a decimal or a fraction).
    Clock,
    /// The clock's period parameter, s.
    Period { start: f64 },
    /// An output of the clock with value reference `clock`.
    Output {
        clock: u32,
        unit: Option<&'static str>,
    },
}

/// The clocked-partition attributes of `v` for model M.
fn clock_part<M: Model>(v: &Variable3) -> Option<ClockPart> {
    match v.source {
        Source::Clock { .. } => Some(ClockPart::Clock),
        Source::ClockPeriod { clock } => Some(ClockPart::Period {
            start: M::CLOCKS[clock].period.start,
        }),
        Source::Clocked { clock, output, .. } => Some(ClockPart::Output {
            clock: M::CLOCKS[clock].value_reference,
            unit: M::CLOCKS[clock].outputs[output].unit,
        }),
        _ => None,
    }
}

/// The description of model M (what the exported symbol lends).
pub fn describe<M: Model>() -> Result<Description, String> {
    let table = sorted_table::<M>()?;
    check_table(&table)?;
    let arrays = declared::view::<M>(&table)?;
    let scalars3 = scalar::view(&table, &arrays)?;
    Ok(Description {
        info: *M::INFO,
        number_of_continuous_states: continuous_states(M::VARIABLES),
        provides_directional_derivative: M::JACOBIAN.is_some(),
        max_output_derivative_order: max_output_derivative_order(M::VARIABLES),
        max_input_derivative_order: M::MAX_INPUT_DERIVATIVE_ORDER,
        intermediate_update_points: M::INTERMEDIATE_UPDATE_POINTS,
        log_categories: [
            log_categories::<crate::fmi2::mode::Fmi2, M>(),
            log_categories::<crate::fmi3::mode::Fmi3, M>(),
        ],
        scalars: table.iter().map(scalar_of).collect(),
        arrays: (arrays.variables.iter())
            .map(|v| variable3(&table, v, array_dependencies::<M>))
            .collect::<Result<_, _>>()?,
        scalar_view: (scalars3.variables.iter())
            .map(|v| variable3(&table, v, scalar_dependencies::<M>))
            .collect::<Result<_, _>>()?,
        scalar_token: scalar::token::<M>(),
    })
}

fn scalar_of<M>(v: &Variable<M>) -> Scalar {
    let value = match &v.kind {
        Kind::Real {
            start,
            min,
            max,
            unit,
            display_unit,
            ..
        } => Value::Real {
            start: *start,
            min: *min,
            max: *max,
            unit: *unit,
            display_unit: *display_unit,
        },
        Kind::Integer {
            start, min, max, ..
        } => Value::Integer {
            start: *start,
            min: *min,
            max: *max,
        },
        Kind::Boolean { start, .. } => Value::Boolean { start: *start },
    };
    Scalar {
        value_reference: v.value_reference,
        name: v.name().into_owned(),
        description: v.description().into_owned(),
        causality: v.causality,
        variability: v.variability,
        initial: v.initial,
        value,
        state: v.state_name().map(|s| s.into_owned()),
        dependencies: v.dependencies.clone(),
        initial_dependencies: v.initial_dependencies.clone(),
    }
}

/// The dependencies (ascending value references; None: all knowns) of an FMI 3.0
/// variable, the last argument choosing the initial ones; one function per view.
type Dependencies<M> = fn(&[Variable<M>], &Variable3, bool) -> Result<Option<Vec<u32>>, String>;

fn variable3<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
    dependencies: Dependencies<M>,
) -> Result<Variable3Description, String> {
    Ok(Variable3Description {
        variable: v.clone(),
        description: table::description(table, v),
        intermediate_update: v.intermediate_update::<M>(),
        dependencies: dependencies(table, v, false)?,
        initial_dependencies: dependencies(table, v, true)?,
        clock_part: clock_part::<M>(v),
        structural: match v.source {
            Source::Structural { parameter } => {
                let p = &M::STRUCTURAL[parameter];
                Some([p.start as u64, p.max as u64])
            }
            _ => None,
        },
        dimension_reference: v.sized_by.map(|k| M::STRUCTURAL[k].value_reference),
    })
}

/// The dependencies of `v` in the array view (by FMI 3.0 variable).
fn array_dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
    initial: bool,
) -> Result<Option<Vec<u32>>, String> {
    if initial {
        table::initial_dependencies(table, v)
    } else {
        table::dependencies(table, v)
    }
}

/// The dependencies of `v` in the scalar view (by table scalar); time and the event
/// indicators (no table element) depend on all knowns.
fn scalar_dependencies<M: Model>(
    table: &[Variable<M>],
    v: &Variable3,
    initial: bool,
) -> Result<Option<Vec<u32>>, String> {
    let Some(vr) = v.elements().next() else {
        return array_dependencies(table, v, initial);
    };
    let s = crate::core::variables::find(table, vr).ok_or_else(|| format!("no element {vr}"))?;
    let names = if initial {
        &s.initial_dependencies
    } else {
        &s.dependencies
    };
    names
        .as_deref()
        .map(|n| scalar::references(table, n))
        .transpose()
}
