//! Logging as a model sees it: a sink for debug messages under declared categories
//! ([`Log`]; models never see a front-end type). The host side, policy and callbacks,
//! is the `logging` module.

/// A log category: name as declared in LogCategories, and its description.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LogCategory {
    pub name: &'static str,
    pub description: &'static str,
}

impl LogCategory {
    /// The category `name` (what the model passes to [`Log::debug`]: `LOG.name`).
    pub const fn new(name: &'static str, description: &'static str) -> Self {
        LogCategory { name, description }
    }
}

/// Where a model writes its debug messages.
pub trait Log {
    /// Logs `message` under `category` (a declared category name) if the host enabled it.
    fn debug(&self, category: &str, message: &str);
}
