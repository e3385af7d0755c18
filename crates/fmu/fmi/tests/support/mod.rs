//! What the FMI layer's FMI 3.0 tests on toy models share: an instance made through the
//! layer's C-level entry point, with a logger that keeps the messages of this thread.

use robofmu_fmi::core::Model;
use robofmu_fmi::fmi3::api::{self, Instantiation};
use robofmu_fmi::fmi3::mode::Interface;
use robofmu_fmi::fmi3::types::*;
use std::cell::RefCell;
use std::ffi::{CStr, c_void};

thread_local! {
    static MESSAGES: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

unsafe extern "C-unwind" fn log(
    _env: Fmi3InstanceEnvironment,
    _status: Fmi3Status,
    _category: Fmi3String,
    message: Fmi3String,
) {
    // SAFETY: the layer passes a NUL-terminated message.
    let text = unsafe { CStr::from_ptr(message) }
        .to_string_lossy()
        .into_owned();
    MESSAGES.with(|m| m.borrow_mut().push(text));
}

/// The last message the layer logged on this thread (empty when none).
pub fn last_message() -> String {
    MESSAGES.with(|m| m.borrow().last().cloned().unwrap_or_default())
}

/// An instance of `M` for `interface` with the instantiation token `token`, logging
/// into [`last_message`]; it must not be refused.
pub fn instantiate<M: Model>(interface: Interface, token: &CStr) -> Fmi3Instance {
    let c = unsafe {
        api::instantiate::<M>(Instantiation {
            function: "fmi3Instantiate",
            instance_name: c"test".as_ptr(),
            token: token.as_ptr(),
            logging_on: FMI3_FALSE,
            environment: std::ptr::null_mut::<c_void>(),
            log_message: Some(log),
            interface,
            intermediate_update: None,
        })
    };
    assert!(!c.is_null(), "{}", last_message());
    c
}
