//! The importer's callbacks, shared by every host of the tests: a logger that keeps
//! what the FMU reports (FMI 2.0 and FMI 3.0 signatures), calloc/free for FMI 2.0's
//! memory callbacks, and the FMI 2.0 callback table with each member present or NULL
//! as a hostile case asks.

use crate::fmi2::CallbackFunctions;
use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::sync::Mutex;

/// Log lines received, as "status category: message"; only messages of status
/// Warning and above are kept (debug lines such as logCalls are dropped).
pub type Log = Mutex<Vec<String>>;

/// The log received so far, one line per message, and clears it.
pub fn take(log: &Log) -> String {
    let mut lines = log.lock().unwrap_or_else(|e| e.into_inner());
    let text = lines.join(" | ");
    lines.clear();
    text
}

/// A string the FMU passed ("(null)" for NULL), with its '%' escaping undone.
/// Called by callbacks with the FMU's pointers only.
#[allow(clippy::not_unsafe_ptr_arg_deref)]
pub fn text(p: *const c_char) -> String {
    if p.is_null() {
        return "(null)".to_string();
    }
    // SAFETY: the FMU passes NUL-terminated strings, alive during the callback.
    unsafe { CStr::from_ptr(p) }
        .to_string_lossy()
        .replace("%%", "%")
}

/// A C string of a test's name, GUID or token (empty when `s` holds a NUL).
pub fn c_string(s: &str) -> CString {
    CString::new(s).unwrap_or_default()
}

/// Keeps a log message of status Warning and above as "status category: message"
/// in `env`, the &Log given to the FMU as its environment (shared by the FMI 2.0
/// and FMI 3.0 loggers).
pub fn record(env: *mut c_void, status: c_int, category: *const c_char, message: *const c_char) {
    if status == 0 || env.is_null() {
        return;
    }
    // SAFETY: env is the &Log this crate passed as environment.
    let log = unsafe { &*(env as *const Log) };
    if let Ok(mut lines) = log.lock() {
        lines.push(format!("{status} {}: {}", text(category), text(message)));
    }
}

extern "C" fn capture2(
    env: *mut c_void,
    _instance: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    record(env, status, category, message);
}

extern "C" fn capture3(
    env: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    record(env, status, category, message);
}

/// The FMI 3.0 logMessage callback that keeps lines in the &Log passed as the
/// instance environment (as the instantiate functions' pointer type).
pub fn logger3() -> *const c_void {
    capture3 as *const c_void
}

/// fmi2CallbackAllocateMemory: zeroed memory of the C heap.
pub extern "C" fn allocate(n: usize, size: usize) -> *mut c_void {
    // SAFETY: calloc accepts any sizes and returns null on failure.
    unsafe { libc::calloc(n, size) }
}

/// fmi2CallbackFreeMemory.
///
/// # Safety
/// `p` is null or came from [`allocate`] and was not freed yet.
pub unsafe extern "C" fn release(p: *mut c_void) {
    // SAFETY: by the contract above.
    unsafe { libc::free(p) }
}

/// Which callbacks fmi2Instantiate receives (a missing one is NULL).
#[derive(Debug, Clone, Copy)]
pub struct Callbacks {
    pub logger: bool,
    pub allocate: bool,
    pub free: bool,
}

impl Callbacks {
    pub const ALL: Callbacks = Callbacks {
        logger: true,
        allocate: true,
        free: true,
    };
}

/// The FMI 2.0 callback table and log of one instance; both must outlive it.
pub struct Environment {
    pub log: Box<Log>,
    pub functions: Box<CallbackFunctions>,
}

impl Environment {
    pub fn new(which: Callbacks) -> Environment {
        let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
        let or_null = |on: bool, f: *const c_void| if on { f } else { std::ptr::null() };
        // The non-variadic `capture2` stands in for the variadic C logger: the five
        // fixed arguments are passed the same way on x86_64 (System V and Windows) and
        // aarch64 Linux, and FMUs that escape '%' pass no variadic arguments (ours
        // do; `text` undoes the escaping).
        let functions = Box::new(CallbackFunctions {
            logger: or_null(which.logger, capture2 as *const c_void),
            allocate_memory: or_null(which.allocate, allocate as *const c_void),
            free_memory: or_null(which.free, release as *const c_void),
            step_finished: std::ptr::null(),
            component_environment: &*log as *const Log as *mut c_void,
        });
        Environment { log, functions }
    }

    /// The log received so far, one line per message, and clears it.
    pub fn take_log(&self) -> String {
        take(&self.log)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_logger_keeps_warnings_and_above_unescaped() {
        // Expected: an OK line dropped (debug output), a Warning (1) and an Error (3)
        // kept as "status category: message" with "%%" read as "%".
        let env = Environment::new(Callbacks::ALL);
        let e = env.functions.component_environment;
        record(e, 0, c"logCalls".as_ptr(), c"fmi2DoStep".as_ptr());
        record(e, 1, c"logStatusWarning".as_ptr(), c"at 5%%".as_ptr());
        record(e, 3, c"logStatusError".as_ptr(), std::ptr::null());
        assert_eq!(
            env.take_log(),
            "1 logStatusWarning: at 5% | 3 logStatusError: (null)"
        );
        assert_eq!(env.take_log(), "");
    }

    #[test]
    fn a_missing_callback_is_null() {
        // Expected: the members asked to be missing are NULL, the others set.
        let env = Environment::new(Callbacks {
            logger: true,
            allocate: false,
            free: true,
        });
        assert!(!env.functions.logger.is_null());
        assert!(env.functions.allocate_memory.is_null());
        assert!(!env.functions.free_memory.is_null());
    }
}
