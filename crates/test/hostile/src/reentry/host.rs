//! An importer whose callbacks call back into the FMU: the log callback (FMI 2.0 and
//! FMI 3.0) and the FMI 3.0 intermediateUpdate callback run a hook, once, when the
//! host's trigger fires; the hook may free the instance, reset it, set a state,
//! call a getter or block until another thread acted. Everything the FMU logged is
//! kept as "status category: message" lines. The memory callbacks and the
//! reading of the FMU's strings are the test host's (`robofmu_fmi_host::callbacks`).

use super::api::Handle;
use crate::binary::{CallbackFunctions, ERROR, Status};
use robofmu_fmi_host::callbacks::{allocate, release, text};
use std::cell::{Cell, RefCell};
use std::ffi::{c_char, c_int, c_void};

/// When the hook runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Trigger {
    Never,
    /// At the first message of status Error or above.
    Error,
    /// At the logCalls line of this function.
    Call(&'static str),
    /// At the first intermediateUpdate callback (FMI 3.0).
    Intermediate,
}

/// What the hook does with the instance handle; Some(status) of the call it made.
pub type Hook<'a> = Box<dyn FnOnce(Handle) -> Option<Status> + 'a>;

/// The importer's side of one instance: its callbacks' state.
pub struct Host<'a> {
    pub handle: Cell<Handle>,
    pub trigger: Cell<Trigger>,
    hook: Cell<Option<Hook<'a>>>,
    /// The status of the call the hook made (None before it ran, or if it made none).
    pub nested: Cell<Option<Status>>,
    pub fired: Cell<bool>,
    pub lines: RefCell<Vec<String>>,
    /// The FMI 2.0 callback table (environment: this host).
    pub callbacks: CallbackFunctions,
}

impl<'a> Host<'a> {
    /// A host with no hook; boxed, so that its address (the environment) is stable.
    pub fn new() -> Box<Host<'a>> {
        let mut host = Box::new(Host {
            handle: Cell::new(std::ptr::null_mut()),
            trigger: Cell::new(Trigger::Never),
            hook: Cell::new(None),
            nested: Cell::new(None),
            fired: Cell::new(false),
            lines: RefCell::new(Vec::new()),
            callbacks: CallbackFunctions {
                logger: log2 as *const c_void,
                allocate_memory: allocate as *const c_void,
                free_memory: release as *const c_void,
                step_finished: std::ptr::null(),
                component_environment: std::ptr::null_mut(),
            },
        });
        host.callbacks.component_environment = host.environment();
        host
    }

    /// The instance environment the FMU hands back to the callbacks.
    pub fn environment(&self) -> *mut c_void {
        self as *const Host as *mut c_void
    }

    /// Runs `hook` once, at the first `trigger`.
    pub fn arm(&self, trigger: Trigger, hook: Hook<'a>) {
        self.trigger.set(trigger);
        self.hook.set(Some(hook));
    }

    /// Whether a line logged so far contains `text`.
    pub fn logged(&self, text: &str) -> bool {
        self.lines.borrow().iter().any(|l| l.contains(text))
    }

    /// The lines logged so far, for a failure message.
    pub fn log_text(&self) -> String {
        self.lines.borrow().join(" | ")
    }

    fn fire(&self, now: Trigger) {
        if now != self.trigger.get() {
            return;
        }
        if let Some(hook) = self.hook.take() {
            self.fired.set(true);
            self.nested.set(hook(self.handle.get()));
        }
    }

    fn message(&self, status: c_int, category: &str, message: &str) {
        self.lines
            .borrow_mut()
            .push(format!("{status} {category}: {message}"));
        if status >= ERROR {
            self.fire(Trigger::Error);
        }
        if category == "logCalls"
            && let Trigger::Call(function) = self.trigger.get()
            && message == function
        {
            self.fire(Trigger::Call(function));
        }
    }
}

/// # Safety
/// `env` is a live `Host` (this module's environment).
unsafe fn host<'a>(env: *mut c_void) -> &'a Host<'a> {
    // SAFETY: by the contract above.
    unsafe { &*(env as *const Host) }
}

extern "C" fn log2(
    env: *mut c_void,
    _instance: *const c_char,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: the environment given with this logger is a Host.
    unsafe { host(env) }.message(status, &text(category), &text(message));
}

extern "C" fn log3(
    env: *mut c_void,
    status: c_int,
    category: *const c_char,
    message: *const c_char,
) {
    // SAFETY: as above.
    unsafe { host(env) }.message(status, &text(category), &text(message));
}

/// The FMI 3.0 log callback of a [`Host`].
pub fn logger3() -> *const c_void {
    log3 as *const c_void
}

#[allow(clippy::too_many_arguments)]
extern "C" fn update(
    env: *mut c_void,
    _time: f64,
    _set_requested: u8,
    _get_allowed: u8,
    _finished: u8,
    _can_return_early: u8,
    requested: *mut u8,
    _at: *mut f64,
) {
    // SAFETY: the FMU passes a live output.
    unsafe { *requested = 0 };
    // SAFETY: as above.
    unsafe { host(env) }.fire(Trigger::Intermediate);
}

/// The FMI 3.0 intermediateUpdate callback of a [`Host`].
pub fn intermediate_update() -> *const c_void {
    update as *const c_void
}
