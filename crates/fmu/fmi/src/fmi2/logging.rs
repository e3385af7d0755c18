//! Logging through the host's fmi2CallbackLogger (the policy is the core
//! [`Logger`](crate::core::logging::Logger)'s).
//!
//! Messages are formatted in Rust and passed as the format string with every '%'
//! doubled, so a printf-style logger prints them verbatim and FMPy (which cannot expand
//! format arguments) shows them as they are.

use super::types::{Fmi2CallbackLogger, Fmi2ComponentEnvironment, Fmi2Status};
use crate::core::callback;
use crate::core::logging::{self, LogCategory, LogSink};
use crate::ffi::with_c_text;
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
        with_c_text(message, true, |text| {
            with_c_text(category, false, |category| {
                // SAFETY: the callback was checked non-null at instantiation; all
                // strings are NUL-terminated and live until the call returns; no
                // variadic arguments follow because the message contains no
                // conversion specification.
                callback::host("logger", || unsafe {
                    (self.function)(
                        self.environment,
                        self.instance_name.as_ptr(),
                        status,
                        category,
                        text,
                    );
                })
            })
        });
    }
}

#[cfg(test)]
mod tests {
    use crate::ffi::with_c_text;
    use std::ffi::CStr;

    #[test]
    fn percent_signs_are_doubled_and_nul_bytes_removed() {
        // Expected: the message as a printf format that prints it verbatim.
        let text = with_c_text("50% of %s\0x", true, |p| {
            unsafe { CStr::from_ptr(p) }.to_str().unwrap().to_string()
        });
        assert_eq!(text, "50%% of %%s x");
    }
}
