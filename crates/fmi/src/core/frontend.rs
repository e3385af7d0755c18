//! What a front-end (FMI 2.0, FMI 3.0) is to the shared code: its status codes, its
//! state machine and its logger ([`Frontend`]), and an instance of it
//! ([`FrontendInstance`]: a core instance with that front-end's mode, interface and
//! logger). [`entry`](super::entry) runs every C entry point of both standards through
//! these traits; each front-end keeps only its C types, its state table, its
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
    type Sink: LogSink<Status = Self::Status>;
    /// The standard that writes this front-end's FMU states.
    const STANDARD: Standard;
    /// The standard's word for a mode in messages: "mode" or "state".
    const MODE_WORD: &'static str;
    /// The standard's spelling of an FMU state in messages and function names.
    const FMU_STATE: &'static str;
    const INSTANTIATED: Self::Mode;
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

/// Implements [`StatusCode`] for a standard's status enum (variants `Ok`, `Warning`,
/// `Discard`, `Error`, `Fatal`).
macro_rules! status_code {
    ($status:ident) => {
        impl $crate::core::frontend::StatusCode for $status {
            const OK: Self = $status::Ok;
            const WARNING: Self = $status::Warning;
            const DISCARD: Self = $status::Discard;
            const ERROR: Self = $status::Error;
            const FATAL: Self = $status::Fatal;
        }
    };
}
pub(crate) use status_code;

/// Implements [`FrontendInstance`] for a front-end's `Instance<M>` (fields `mode`,
/// `interface`, `log`, `core`) of front-end `$frontend`.
macro_rules! frontend_instance {
    ($instance:ident, $frontend:ty) => {
        impl<M: $crate::core::model::Model> $crate::core::frontend::FrontendInstance
            for $instance<M>
        {
            type Frontend = $frontend;
            type Model = M;

            fn parts(&mut self) -> $crate::core::frontend::Parts<'_, $frontend, M> {
                $crate::core::frontend::Parts {
                    mode: &mut self.mode,
                    interface: self.interface,
                    log: &self.log,
                    core: &mut self.core,
                }
            }

            fn log_mut(&mut self) -> &mut $crate::core::frontend::LoggerOf<$frontend> {
                &mut self.log
            }
        }
    };
}
pub(crate) use frontend_instance;

/// The status type of front-end `F`.
pub type StatusOf<F> = <F as Frontend>::Status;

/// The logger of an instance of front-end `F`.
pub type LoggerOf<F> = Logger<<F as Frontend>::Sink>;

/// All log categories of model M under front-end F: the layer's, then the model's.
pub fn log_categories<F: Frontend, M: Model>() -> Vec<LogCategory> {
    let mut all = F::LAYER_CATEGORIES.to_vec();
    all.extend_from_slice(M::info().log_categories);
    all
}

/// The parts of a front-end instance the shared code works on, borrowed apart.
pub struct Parts<'a, F: Frontend, M: Model> {
    pub mode: &'a mut F::Mode,
    pub interface: F::Interface,
    pub log: &'a LoggerOf<F>,
    pub core: &'a mut Instance<M>,
}

/// An instance of a front-end. Its handle is registered in
/// [`handles`](super::handles) under its own type, so that an instance of another FMU
/// or of the other standard is refused.
pub trait FrontendInstance: Sized + 'static {
    type Frontend: Frontend;
    type Model: Model;

    fn parts(&mut self) -> Parts<'_, Self::Frontend, Self::Model>;

    /// The logger, to change which categories reach the host.
    fn log_mut(&mut self) -> &mut LoggerOf<Self::Frontend>;

    /// Reset: back to the state right after instantiation.
    fn reset(&mut self) -> Result<(), String> {
        let parts = self.parts();
        parts.core.reset()?;
        *parts.mode = Self::Frontend::INSTANTIATED;
        Ok(())
    }

    /// The FMU state of the instance now.
    fn snapshot(&mut self) -> Snapshot<Self::Model> {
        self.parts().core.snapshot(Self::Frontend::STANDARD)
    }

    /// Sets the FMU state `s`.
    fn restore(&mut self, s: &Snapshot<Self::Model>) {
        let parts = self.parts();
        parts.core.restore(s);
        *parts.mode = Self::Frontend::after_restore(*parts.mode);
    }
}
