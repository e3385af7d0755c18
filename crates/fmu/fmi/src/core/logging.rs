//! The host side of logging: the [`Logger`] of an instance of either front-end, the
//! category bookkeeping ([`CategoryFilter`]) and the policy around a [`LogSink`], the
//! host's callback of one standard. What a model sees ([`Log`], [`LogCategory`]) is in
//! [`log`](super::log).
//!
//! Policy: messages of status Error and Fatal always reach the host (it needs to know
//! why a call failed); warnings, discards and debug messages only when logging is on
//! and their category is enabled (loggingOn at instantiation and SetDebugLogging; an
//! empty category list enables all categories).

pub use super::log::{Log, LogCategory};
use super::status::StatusCode;
use std::cell::Cell;

/// The log categories of one instance and which of them the host enabled: the state
/// that fmi2SetDebugLogging and fmi3SetDebugLogging change.
pub struct CategoryFilter {
    categories: Vec<LogCategory>,
    enabled: Vec<bool>,
    logging_on: bool,
}

impl CategoryFilter {
    /// All `categories` enabled; debug logging on or off as `logging_on` says.
    pub fn new(categories: Vec<LogCategory>, logging_on: bool) -> CategoryFilter {
        let enabled = vec![true; categories.len()];
        CategoryFilter {
            categories,
            enabled,
            logging_on,
        }
    }

    /// SetDebugLogging: an empty list enables every category. Unknown names are
    /// rejected (and nothing changes).
    pub fn configure(&mut self, logging_on: bool, names: &[String]) -> Result<(), String> {
        let mut enabled = vec![names.is_empty(); self.categories.len()];
        for name in names {
            match self.categories.iter().position(|c| c.name == name) {
                Some(i) => enabled[i] = true,
                None => {
                    let known: Vec<&str> = self.categories.iter().map(|c| c.name).collect();
                    return Err(format!(
                        "unknown log category \"{name}\" (declared: {})",
                        known.join(", ")
                    ));
                }
            }
        }
        self.enabled = enabled;
        self.logging_on = logging_on;
        Ok(())
    }

    /// Whether a message of this category would reach the host.
    pub fn is_enabled(&self, category: &str) -> bool {
        self.logging_on
            && self
                .categories
                .iter()
                .position(|c| c.name == category)
                .is_some_and(|i| self.enabled[i])
    }
}

/// The host's logger callback of one standard.
pub trait LogSink {
    type Status: StatusCode;
    /// Passes one message to the host.
    fn emit(&self, status: Self::Status, category: &str, message: &str);
}

/// The category a status is logged under.
pub fn status_category<S: StatusCode>(status: S) -> &'static str {
    if status == S::WARNING {
        "logStatusWarning"
    } else if status == S::DISCARD {
        "logStatusDiscard"
    } else if status == S::FATAL {
        "logStatusFatal"
    } else {
        "logStatusError"
    }
}

/// The logger of one instance: which categories the host enabled, and its callback.
pub struct Logger<S> {
    sink: S,
    filter: CategoryFilter,
    /// Messages passed to the host so far: a call whose count changed has called back.
    emitted: Cell<u64>,
}

impl<S: LogSink> Logger<S> {
    pub fn new(sink: S, categories: Vec<LogCategory>, logging_on: bool) -> Logger<S> {
        Logger {
            sink,
            filter: CategoryFilter::new(categories, logging_on),
            emitted: Cell::new(0),
        }
    }

    /// The host's callback.
    pub fn sink(&self) -> &S {
        &self.sink
    }

    /// How many messages went to the host so far (each a call into the host, which
    /// may have called back into the FMU).
    pub fn emitted(&self) -> u64 {
        self.emitted.get()
    }

    fn emit(&self, status: S::Status, category: &str, message: &str) {
        self.emitted.set(self.emitted.get().wrapping_add(1));
        self.sink.emit(status, category, message);
    }

    /// SetDebugLogging: see [`CategoryFilter::configure`].
    pub fn configure(&mut self, logging_on: bool, names: &[String]) -> Result<(), String> {
        self.filter.configure(logging_on, names)
    }

    /// Whether messages under `category` reach the host (to skip formatting them).
    pub fn enabled(&self, category: &str) -> bool {
        self.filter.is_enabled(category)
    }

    /// Logs a message about a call that ends with `status`.
    pub fn status(&self, status: S::Status, message: &str) {
        let category = status_category(status);
        if status >= S::Status::ERROR || self.filter.is_enabled(category) {
            self.emit(status, category, message);
        }
    }
}

impl<S: LogSink> Log for Logger<S> {
    fn debug(&self, category: &str, message: &str) {
        if self.filter.is_enabled(category) {
            self.emit(S::Status::OK, category, message);
        }
    }
}

/// The categories the layer itself logs under, as a `[LogCategory; 6]`; `$standard`
/// ("fmi2" or "fmi3") names the status codes, `$events` describes logEvents.
macro_rules! layer_categories {
    ($standard:literal, $events:literal) => {
        [
            $crate::core::logging::LogCategory {
                name: "logStatusWarning",
                description: concat!("Calls that return ", $standard, "Warning"),
            },
            $crate::core::logging::LogCategory {
                name: "logStatusDiscard",
                description: concat!("Calls that return ", $standard, "Discard (rejected steps)"),
            },
            $crate::core::logging::LogCategory {
                name: "logStatusError",
                description: concat!("Calls that return ", $standard, "Error (always logged)"),
            },
            $crate::core::logging::LogCategory {
                name: "logStatusFatal",
                description: concat!("Calls that return ", $standard, "Fatal (always logged)"),
            },
            $crate::core::logging::LogCategory {
                name: "logEvents",
                description: $events,
            },
            $crate::core::logging::LogCategory {
                name: "logCalls",
                description: "The name of every FMI function called",
            },
        ]
    };
}
pub(crate) use layer_categories;

#[cfg(test)]
mod tests {
    use super::*;

    const A: LogCategory = LogCategory {
        name: "a",
        description: "",
    };
    const B: LogCategory = LogCategory {
        name: "b",
        description: "",
    };

    #[test]
    fn set_debug_logging_enables_the_named_categories_or_all_for_an_empty_list() {
        // Expected behaviour from fmi2SetDebugLogging / fmi3SetDebugLogging: the
        // listed categories only; an empty list means all; logging off means none.
        let mut filter = CategoryFilter::new(vec![A, B], false);
        assert!(!filter.is_enabled("a"));
        filter.configure(true, &["b".to_string()]).unwrap();
        assert!(!filter.is_enabled("a") && filter.is_enabled("b"));
        filter.configure(true, &[]).unwrap();
        assert!(filter.is_enabled("a") && filter.is_enabled("b"));
        assert!(!filter.is_enabled("undeclared"));
    }

    #[test]
    fn an_unknown_category_is_rejected_and_changes_nothing() {
        let mut filter = CategoryFilter::new(vec![A, B], true);
        let error = filter.configure(false, &["c".to_string()]).unwrap_err();
        assert_eq!(error, "unknown log category \"c\" (declared: a, b)");
        assert!(filter.is_enabled("a"));
    }
}
