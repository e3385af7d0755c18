//! Logging as a model sees it: a sink for debug messages under declared categories.
//! Each front-end implements [`Log`] on its own logger (the FMI 2.0 one forwards to
//! fmi2CallbackLogger); models never see a front-end type. [`CategoryFilter`] is the
//! category bookkeeping both front-ends' loggers share.

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
