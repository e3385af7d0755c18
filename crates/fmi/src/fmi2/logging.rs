//! Logging through the host's fmi2CallbackLogger.
//!
//! Messages are formatted in Rust and passed as the format string with every '%'
//! doubled, so a printf-style logger prints them verbatim and FMPy (which cannot expand
//! format arguments) shows them as they are.
//!
//! Policy: messages of status fmi2Error and fmi2Fatal are always passed to the logger
//! (the host needs to know why a call failed); warnings, discards and debug messages
//! only when logging is on and their category is enabled (fmi2Instantiate's loggingOn
//! and fmi2SetDebugLogging; an empty category list enables all categories).

use super::types::{Fmi2CallbackLogger, Fmi2ComponentEnvironment, Fmi2Status};
use crate::core::logging::{CategoryFilter, Log, LogCategory};
use std::ffi::CString;

/// Categories the layer itself logs under; models add their own after these.
pub const LAYER_CATEGORIES: [LogCategory; 6] = [
    LogCategory {
        name: "logStatusWarning",
        description: "Calls that return fmi2Warning",
    },
    LogCategory {
        name: "logStatusDiscard",
        description: "Calls that return fmi2Discard (rejected steps)",
    },
    LogCategory {
        name: "logStatusError",
        description: "Calls that return fmi2Error (always logged)",
    },
    LogCategory {
        name: "logStatusFatal",
        description: "Calls that return fmi2Fatal (always logged)",
    },
    LogCategory {
        name: "logEvents",
        description: "Mode changes, time events and steps",
    },
    LogCategory {
        name: "logCalls",
        description: "The name of every FMI function called",
    },
];

/// The category a status is logged under.
pub fn status_category(status: Fmi2Status) -> &'static str {
    match status {
        Fmi2Status::Warning => "logStatusWarning",
        Fmi2Status::Discard => "logStatusDiscard",
        Fmi2Status::Fatal => "logStatusFatal",
        _ => "logStatusError",
    }
}

/// The logger of one instance.
pub struct Logger {
    callback: Fmi2CallbackLogger,
    environment: Fmi2ComponentEnvironment,
    instance_name: CString,
    filter: CategoryFilter,
}

// The environment pointer is the host's opaque token; it is only handed back to the
// host's own callback, which the standard lets us call from the calling thread.
unsafe impl Send for Logger {}

impl Logger {
    pub fn new(
        callback: Fmi2CallbackLogger,
        environment: Fmi2ComponentEnvironment,
        instance_name: CString,
        categories: Vec<LogCategory>,
        logging_on: bool,
    ) -> Logger {
        Logger {
            callback,
            environment,
            instance_name,
            filter: CategoryFilter::new(categories, logging_on),
        }
    }

    pub fn instance_name(&self) -> &str {
        self.instance_name.to_str().unwrap_or("?")
    }

    /// fmi2SetDebugLogging: see [`CategoryFilter::configure`].
    pub fn configure(&mut self, logging_on: bool, names: &[String]) -> Result<(), String> {
        self.filter.configure(logging_on, names)
    }

    /// Whether a debug message of this category would reach the host.
    pub fn is_enabled(&self, category: &str) -> bool {
        self.filter.is_enabled(category)
    }

    /// Logs a message about a call that ends with `status`.
    pub fn status(&self, status: Fmi2Status, message: &str) {
        let category = status_category(status);
        if status >= Fmi2Status::Error || self.is_enabled(category) {
            self.emit(status, category, message);
        }
    }

    /// Logs a debug message under `category` (a declared category name).
    pub fn debug(&self, category: &str, message: &str) {
        if self.is_enabled(category) {
            self.emit(Fmi2Status::Ok, category, message);
        }
    }

    fn emit(&self, status: Fmi2Status, category: &str, message: &str) {
        let text = escape_message(message);
        let category = CString::new(category.replace('\0', " ")).unwrap_or_default();
        // SAFETY: the callback was checked non-null at instantiation; all strings are
        // NUL-terminated and live until the call returns; no variadic arguments follow
        // because the message contains no conversion specification.
        unsafe {
            (self.callback)(
                self.environment,
                self.instance_name.as_ptr(),
                status,
                category.as_ptr(),
                text.as_ptr(),
            );
        }
    }
}

impl Log for Logger {
    fn debug(&self, category: &str, message: &str) {
        Logger::debug(self, category, message);
    }
}

/// The message as a C string that printf prints verbatim: '%' doubled, NUL removed.
pub fn escape_message(message: &str) -> CString {
    let escaped = message.replace('%', "%%").replace('\0', " ");
    CString::new(escaped).unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percent_signs_are_doubled_and_nul_bytes_removed() {
        assert_eq!(
            escape_message("50% of %s\0x").to_str().unwrap(),
            "50%% of %%s x"
        );
    }
}
