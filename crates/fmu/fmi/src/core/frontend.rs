//! What a front-end (FMI 2.0, FMI 3.0) is to the shared code: its status codes, its
//! state machine and its logger ([`Frontend`]), and an instance of it
//! ([`FmuInstance`]: a core instance with that front-end's mode, interface and
//! logger). `entry` runs every C entry point of both standards through
//! these types; each front-end keeps only its C types, its state table, its
//! exported symbols and its modelDescription schema.

use super::instance::{Instance, Snapshot, Standard};
use super::log::LogCategory;
use super::logging::{LogSink, Logger};
use super::model::Model;
pub use super::status::StatusCode;
use std::fmt::Debug;

/// One FMI standard's front-end: the types and rules in which FMI 2.0 and FMI 3.0
/// differ.
pub trait Frontend: 'static {
    type Status: StatusCode;
    /// Mode (FMI 2.0) or state (FMI 3.0) of an instance.
    type Mode: Copy + Eq + Debug;
    /// Model Exchange or Co-Simulation (with its options).
    type Interface: Copy + Debug;
    /// A call whose legality depends on the mode.
    type Call: Copy;
    /// The host's logger callback of the standard.
    type Sink: LogSink<Status = Self::Status> + Clone;
    /// What an instance of this standard keeps beyond mode, interface, logger and core.
    type Extra: 'static;
    /// The standard that writes this front-end's FMU states.
    const STANDARD: Standard;
    /// The standard's word for a mode in messages: "mode" or "state".
    const MODE_WORD: &'static str;
    /// The standard's spelling of an FMU state in messages and function names.
    const FMU_STATE: &'static str;
    const INSTANTIATED: Self::Mode;
    /// Initialization Mode: with Instantiated, where parameters may still be refused.
    const INITIALIZATION: Self::Mode;
    const ERROR: Self::Mode;
    const FATAL: Self::Mode;
    /// The categories the layer itself logs under (models add theirs after these).
    const LAYER_CATEGORIES: [LogCategory; 6];

    /// Whether `call` is legal in `mode` for an instance of `interface`.
    fn is_legal(call: Self::Call, mode: Self::Mode, interface: Self::Interface) -> bool;
    /// The mode after ExitInitializationMode.
    fn after_initialization(interface: Self::Interface) -> Self::Mode;
    /// The mode after an FMU state was restored in `mode` (a failed step is undone).
    fn after_restore(mode: Self::Mode) -> Self::Mode;
}

/// The set of the given modes as the bits of a `u16` (for a state table; the modes'
/// discriminants are below 16).
macro_rules! modes {
    ($($mode:expr),* $(,)?) => {
        0u16 $(| (1u16 << ($mode as u16)))*
    };
}
pub(crate) use modes;

/// A standard's return status enum (`#[repr(C)]`, `Ok` = 0 .. `Fatal` = 4, then the
/// standard's own codes such as FMI 2.0's `Pending = 5`), its [`StatusCode`] and its
/// `name()` as the standard spells it (`$prefix` "fmi2": "fmi2OK", "fmi2Warning", ..).
macro_rules! status_code {
    ($(#[$doc:meta])* $status:ident, $prefix:literal $(, $extra:ident = $code:literal)*) => {
        $(#[$doc])*
        #[repr(C)]
        #[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
        pub enum $status {
            Ok = 0,
            Warning = 1,
            Discard = 2,
            Error = 3,
            Fatal = 4,
            $($extra = $code,)*
        }

        impl $crate::core::frontend::StatusCode for $status {
            const OK: Self = $status::Ok;
            const WARNING: Self = $status::Warning;
            const DISCARD: Self = $status::Discard;
            const ERROR: Self = $status::Error;
            const FATAL: Self = $status::Fatal;
        }

        impl $status {
            /// The name the standard uses, for log lines.
            pub fn name(self) -> &'static str {
                match self {
                    $status::Ok => concat!($prefix, "OK"),
                    $status::Warning => concat!($prefix, "Warning"),
                    $status::Discard => concat!($prefix, "Discard"),
                    $status::Error => concat!($prefix, "Error"),
                    $status::Fatal => concat!($prefix, "Fatal"),
                    $($status::$extra => concat!($prefix, stringify!($extra)),)*
                }
            }
        }
    };
}
pub(crate) use status_code;

/// The status type of front-end `F`.
pub type StatusOf<F> = <F as Frontend>::Status;

/// The logger of an instance of front-end `F`.
pub type LoggerOf<F> = Logger<<F as Frontend>::Sink>;

/// All log categories of model M under front-end F: the layer's, then the model's.
pub fn log_categories<F: Frontend, M: Model>() -> Vec<LogCategory> {
    let model = M::INFO.log_categories;
    // Sized once: a grown Vec costs a realloc per instantiation.
    let mut all = Vec::with_capacity(F::LAYER_CATEGORIES.len() + model.len());
    all.extend_from_slice(&F::LAYER_CATEGORIES[..]);
    all.extend_from_slice(model);
    all
}

/// One instance of model M under the standard of front-end F: the version-neutral
/// core instance with the standard's mode, interface and logger, and what only that
/// standard keeps ([`Frontend::Extra`]). FMI 2.0's and FMI 3.0's instance types are
/// this type (`fmi2::instance::Instance<M>`, `fmi3::instance::Instance<M>`); the
/// shared code in [`entry`](super::entry) and the `*_calls` modules takes it for
/// either. Its handle is registered in [`handles`](super::handles) under its own
/// type, so that an instance of another FMU or of the other standard is refused.
pub struct FmuInstance<F: Frontend, M: Model> {
    /// The handle the host holds (set when the instance is registered).
    pub handle: usize,
    pub mode: F::Mode,
    pub interface: F::Interface,
    pub log: LoggerOf<F>,
    /// Model, table, time, stop time.
    pub core: Instance<M>,
    pub extra: F::Extra,
}

impl<F: Frontend, M: Model> FmuInstance<F, M> {
    /// A new instance in the Instantiated mode.
    pub fn with(
        interface: F::Interface,
        log: LoggerOf<F>,
        extra: F::Extra,
        core: Instance<M>,
    ) -> Self {
        FmuInstance {
            handle: 0,
            mode: F::INSTANTIATED,
            interface,
            log,
            core,
            extra,
        }
    }

    /// Reset: back to the state right after instantiation.
    pub fn reset(&mut self) {
        self.core.reset();
        self.mode = F::INSTANTIATED;
    }

    /// The FMU state of the instance now.
    pub fn snapshot(&mut self) -> Snapshot<M> {
        self.core.snapshot(F::STANDARD)
    }

    /// Sets the FMU state `s`.
    pub fn restore(&mut self, s: &Snapshot<M>) {
        self.core.restore(s);
        self.mode = F::after_restore(self.mode);
    }
}
