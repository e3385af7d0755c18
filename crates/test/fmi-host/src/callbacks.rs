//! The importer's callbacks, shared by every host of the tests: a logger that keeps
//! what the FMU reports (FMI 2.0 and FMI 3.0 signatures), calloc/free for FMI 2.0's
//! memory callbacks, and the FMI 2.0 callback table with each member present or NULL
//! as a hostile case asks.

use crate::fmi2::CallbackFunctions;
use std::ffi::{CStr, CString, c_char, c_int, c_void};
use std::fmt;
use std::sync::Mutex;

/// One message of the FMU, its strings as the FMU passed them ("(null)" for NULL).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Line {
    pub status: c_int,
    pub category: String,
    pub message: String,
}

/// "status category: message", with the FMU's '%' escaping undone.
impl fmt::Display for Line {
    fn fmt(&self, f: &mut fmt::Formatter) -> fmt::Result {
        let unescape = |s: &str| s.replace("%%", "%");
        let (category, message) = (unescape(&self.category), unescape(&self.message));
        write!(f, "{} {category}: {message}", self.status)
    }
}

/// Log lines received. The hostile importer's logger keeps messages of status
/// Warning and above (debug lines such as logCalls are dropped, [`Keep::Problems`]);
/// the in-process host's keeps every line ([`Keep::Everything`]).
pub type Log = Mutex<Vec<Line>>;

/// Which messages a logger keeps.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Keep {
    /// Status Warning and above.
    Problems,
    /// Every message, OK (debug) lines included.
    Everything,
}

/// The log received so far, one line per message, and clears it.
pub fn take(log: &Log) -> String {
    let mut lines = log.lock().unwrap_or_else(|e| e.into_inner());
    let text: Vec<String> = lines.iter().map(Line::to_string).collect();
    lines.clear();
    text.join(" | ")
}

/// A string the FMU passed ("(null)" for NULL), as it passed it.
fn verbatim(p: *const c_char) -> String {
    if p.is_null() {
        return "(null)".to_string();
    }
    // SAFETY: the FMU passes NUL-terminated strings, alive during the callback.
    unsafe { CStr::from_ptr(p) }.to_string_lossy().into_owned()
}

/// A string the FMU passed ("(null)" for NULL), with its '%' escaping undone.
/// Called by callbacks with the FMU's pointers only.
#[allow(clippy::not_unsafe_ptr_arg_deref)]
pub fn text(p: *const c_char) -> String {
    verbatim(p).replace("%%", "%")
}

/// A C string of a test's name, GUID or token (empty when `s` holds a NUL).
pub fn c_string(s: &str) -> CString {
    CString::new(s).unwrap_or_default()
}

/// Keeps a log message of status Warning and above in `env`, the &Log given to the
/// FMU as its environment (shared by the FMI 2.0 and FMI 3.0 loggers).
pub fn record(env: *mut c_void, status: c_int, category: *const c_char, message: *const c_char) {
    if status != 0 {
        record_all(env, status, category, message);
    }
}

/// Keeps any log message in `env`, the &Log given to the FMU as its environment.
pub fn record_all(
    env: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    if env.is_null() {
        return;
    }
    // SAFETY: env is the &Log this crate passed as environment.
    let log = unsafe { &*(env as *const Log) };
    if let Ok(mut lines) = log.lock() {
        lines.push(Line {
            status,
            category: verbatim(category),
            message: verbatim(message),
        });
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

extern "C" fn capture2_all(
    env: *mut c_void,
    _instance: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    record_all(env, status, category, message);
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
    /// The callbacks in `which`, the logger keeping Warning and above.
    pub fn new(which: Callbacks) -> Environment {
        Environment::keeping(which, Keep::Problems)
    }

    /// The callbacks in `which`, the logger keeping the messages `keep` names.
    pub fn keeping(which: Callbacks, keep: Keep) -> Environment {
        let log: Box<Log> = Box::new(Mutex::new(Vec::new()));
        let or_null = |on: bool, f: *const c_void| if on { f } else { std::ptr::null() };
        let logger = match keep {
            Keep::Problems => capture2 as *const c_void,
            Keep::Everything => capture2_all as *const c_void,
        };
        // The non-variadic loggers stand in for the variadic C logger: the five
        // fixed arguments are passed the same way on x86_64 (System V and Windows) and
        // aarch64 Linux, and FMUs that escape '%' pass no variadic arguments (ours
        // do; `text` undoes the escaping).
        let functions = Box::new(CallbackFunctions {
            logger: or_null(which.logger, logger),
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
    fn the_keeping_all_logger_keeps_debug_lines_as_passed() {
        // Expected: the OK line kept too, its strings as passed ("%%" unchanged); the
        // text form undoes the escaping as for the hostile logger.
        let env = Environment::keeping(Callbacks::ALL, Keep::Everything);
        type Logger =
            extern "C" fn(*mut c_void, *const c_char, c_int, *const c_char, *const c_char);
        // SAFETY: the table's logger is `capture2_all`, of this signature.
        let logger: Logger = unsafe { std::mem::transmute(env.functions.logger) };
        let e = env.functions.component_environment;
        logger(
            e,
            c"x".as_ptr(),
            0,
            c"logEvents".as_ptr(),
            c"at 5%%".as_ptr(),
        );
        let line = Line {
            status: 0,
            category: "logEvents".into(),
            message: "at 5%%".into(),
        };
        assert_eq!(env.log.lock().unwrap().clone(), vec![line]);
        assert_eq!(env.take_log(), "0 logEvents: at 5%");
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
