//! Logging through the host's fmi3LogMessageCallback (the policy is the core
//! [`Logger`](crate::core::logging::Logger)'s, as in FMI 2.0).
//!
//! FMI 3.0 passes the message as plain text (no format string), so messages go out
//! verbatim with only NUL bytes replaced.

use super::types::{Fmi3InstanceEnvironment, Fmi3LogMessageCallback, Fmi3Status};
use crate::core::callback;
use crate::core::logging::{self, LogCategory, LogSink};
use crate::ffi::with_c_text;

/// Categories the layer itself logs under; models add their own after these.
pub const LAYER_CATEGORIES: [LogCategory; 6] =
    logging::layer_categories!("fmi3", "Mode changes, events and steps");

/// The logger of one FMI 3.0 instance.
pub type Logger = logging::Logger<Callback>;

/// The host's fmi3LogMessageCallback with its environment. A host may pass no
/// callback (logMessage = NULL): then nothing is logged.
#[derive(Clone)]
pub struct Callback {
    pub function: Option<Fmi3LogMessageCallback>,
    pub environment: Fmi3InstanceEnvironment,
}

// The environment pointer is the host's opaque token; it is only handed back to the
// host's own callback, from the calling thread.
unsafe impl Send for Callback {}

impl LogSink for Callback {
    type Status = Fmi3Status;

    fn emit(&self, status: Fmi3Status, category: &str, message: &str) {
        let Some(function) = self.function else {
            return;
        };
        with_c_text(message, false, |text| {
            with_c_text(category, false, |category| {
                // SAFETY: the callback is the host's fmi3LogMessageCallback; both
                // strings are NUL-terminated and live until the call returns.
                callback::host("logMessage", || unsafe {
                    function(self.environment, status, category, text)
                })
            })
        });
    }
}

#[cfg(test)]
mod tests {
    use crate::ffi::c_string;

    #[test]
    fn messages_keep_percent_signs_and_lose_nul_bytes() {
        // FMI 3.0 messages are not format strings (fmi3LogMessageCallback, section
        // 2.3.1), so '%' stays single, unlike the FMI 2.0 logger.
        assert_eq!(c_string("50% of %s\0x").to_str().unwrap(), "50% of %s x");
    }
}
