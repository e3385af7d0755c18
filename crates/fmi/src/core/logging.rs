//! Logging as a model sees it: a sink for debug messages under declared categories.
//! Each front-end implements [`Log`] on its own logger (the FMI 2.0 one forwards to
//! fmi2CallbackLogger); models never see a front-end type.

/// A log category: name as declared in LogCategories, and its description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LogCategory {
    pub name: &'static str,
    pub description: &'static str,
}

/// Where a model writes its debug messages.
pub trait Log {
    /// Logs `message` under `category` (a declared category name) if the host enabled it.
    fn debug(&self, category: &str, message: &str);
}
