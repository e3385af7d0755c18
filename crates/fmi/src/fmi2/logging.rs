//! Logging through the host's fmi2CallbackLogger (the policy is the core
//! [`Logger`](crate::core::logging::Logger)'s).
//!
//! Messages are formatted in Rust and passed as the format string with every '%'
//! doubled, so a printf-style logger prints them verbatim and FMPy (which cannot expand
//! format arguments) shows them as they are.

use super::types::{Fmi2CallbackLogger, Fmi2ComponentEnvironment, Fmi2Status};
use crate::core::logging::{self, LogCategory, LogSink};
use crate::ffi::c_string;
use std::ffi::CString;

/// Categories the layer itself logs under; models add their own after these.
pub const LAYER_CATEGORIES: [LogCategory; 6] =
    logging::layer_categories!("fmi2", "Mode changes, time events and steps");

/// The logger of one FMI 2.0 instance.
pub type Logger = logging::Logger<Callback>;

/// The host's fmi2CallbackLogger with its environment and the instance name.
#[derive(Clone)]
pub struct Callback {
    pub function: Fmi2CallbackLogger,
    pub environment: Fmi2ComponentEnvironment,
    pub instance_name: CString,
}

// The environment pointer is the host's opaque token; it is only handed back to the
// host's own callback, which the standard lets us call from the calling thread.
unsafe impl Send for Callback {}

impl LogSink for Callback {
    type Status = Fmi2Status;

    fn emit(&self, status: Fmi2Status, category: &str, message: &str) {
        let text = escape_message(message);
        let category = c_string(category);
        // SAFETY: the callback was checked non-null at instantiation; all strings are
        // NUL-terminated and live until the call returns; no variadic arguments follow
        // because the message contains no conversion specification.
        unsafe {
            (self.function)(
                self.environment,
                self.instance_name.as_ptr(),
                status,
                category.as_ptr(),
                text.as_ptr(),
            );
        }
    }
}

/// The message as a C string that printf prints verbatim: '%' doubled, NUL removed.
pub fn escape_message(message: &str) -> CString {
    c_string(&message.replace('%', "%%"))
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
