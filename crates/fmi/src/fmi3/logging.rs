//! Logging through the host's fmi3LogMessageCallback.
//!
//! FMI 3.0 passes the message as plain text (no format string), so messages go out
//! verbatim with only NUL bytes replaced. Policy as in FMI 2.0: fmi3Error and
//! fmi3Fatal messages always reach the host; warnings, discards and debug messages
//! only when logging is on and their category is enabled (an empty category list in
//! fmi3SetDebugLogging enables all categories).

use super::types::{Fmi3InstanceEnvironment, Fmi3LogMessageCallback, Fmi3Status};
use crate::core::logging::{CategoryFilter, Log, LogCategory};
use crate::core::model::Model;
use std::ffi::CString;

/// Categories the layer itself logs under; models add their own after these.
pub const LAYER_CATEGORIES: [LogCategory; 6] = [
    LogCategory {
        name: "logStatusWarning",
        description: "Calls that return fmi3Warning",
    },
    LogCategory {
        name: "logStatusDiscard",
        description: "Calls that return fmi3Discard (rejected steps)",
    },
    LogCategory {
        name: "logStatusError",
        description: "Calls that return fmi3Error (always logged)",
    },
    LogCategory {
        name: "logStatusFatal",
        description: "Calls that return fmi3Fatal (always logged)",
    },
    LogCategory {
        name: "logEvents",
        description: "Mode changes, events and steps",
    },
    LogCategory {
        name: "logCalls",
        description: "The name of every FMI function called",
    },
];

/// All log categories of a model: the layer's, then the model's own.
pub fn log_categories<M: Model>() -> Vec<LogCategory> {
    let mut all = LAYER_CATEGORIES.to_vec();
    all.extend_from_slice(M::info().log_categories);
    all
}

/// The category a status is logged under.
fn status_category(status: Fmi3Status) -> &'static str {
    match status {
        Fmi3Status::Warning => "logStatusWarning",
        Fmi3Status::Discard => "logStatusDiscard",
        Fmi3Status::Fatal => "logStatusFatal",
        _ => "logStatusError",
    }
}

/// The logger of one instance. A host may pass no callback (logMessage = NULL): then
/// nothing is logged.
pub struct Logger {
    callback: Option<Fmi3LogMessageCallback>,
    environment: Fmi3InstanceEnvironment,
    filter: CategoryFilter,
}

// The environment pointer is the host's opaque token; it is only handed back to the
// host's own callback, from the calling thread.
unsafe impl Send for Logger {}

impl Logger {
    pub fn new(
        callback: Option<Fmi3LogMessageCallback>,
        environment: Fmi3InstanceEnvironment,
        categories: Vec<LogCategory>,
        logging_on: bool,
    ) -> Logger {
        Logger {
            callback,
            environment,
            filter: CategoryFilter::new(categories, logging_on),
        }
    }

    /// fmi3SetDebugLogging: see [`CategoryFilter::configure`].
    pub fn configure(&mut self, logging_on: bool, names: &[String]) -> Result<(), String> {
        self.filter.configure(logging_on, names)
    }

    fn is_enabled(&self, category: &str) -> bool {
        self.filter.is_enabled(category)
    }

    /// Logs a message about a call that ends with `status`.
    pub fn status(&self, status: Fmi3Status, message: &str) {
        let category = status_category(status);
        if status >= Fmi3Status::Error || self.is_enabled(category) {
            self.emit(status, category, message);
        }
    }

    fn emit(&self, status: Fmi3Status, category: &str, message: &str) {
        let Some(callback) = self.callback else {
            return;
        };
        let text = plain_text(message);
        let category = plain_text(category);
        // SAFETY: the callback is the host's fmi3LogMessageCallback; both strings are
        // NUL-terminated and live until the call returns.
        unsafe { callback(self.environment, status, category.as_ptr(), text.as_ptr()) };
    }
}

impl Log for Logger {
    fn debug(&self, category: &str, message: &str) {
        if self.is_enabled(category) {
            self.emit(Fmi3Status::Ok, category, message);
        }
    }
}

/// The message as a C string: NUL bytes (which would cut it short) replaced.
fn plain_text(message: &str) -> CString {
    CString::new(message.replace('\0', " ")).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn messages_keep_percent_signs_and_lose_nul_bytes() {
        // FMI 3.0 messages are not format strings (fmi3LogMessageCallback, section
        // 2.3.1), so '%' stays single, unlike the FMI 2.0 logger.
        assert_eq!(plain_text("50% of %s\0x").to_str().unwrap(), "50% of %s x");
    }
}
