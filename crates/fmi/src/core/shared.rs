//! Tables built once per loaded library and shared by its instances: the variable
//! index of a declared model and its FMI 3.0 views are the same for every instance, so
//! the first instantiation builds them and later ones take a reference (an atomic
//! increment instead of a table per instance).
//!
//! Each model type has its own typed `static` [`Shared`] cell, defined for it by
//! [`share_index!`](crate::share_index) (which [`export_fmu!`](crate::export_fmu)
//! calls) as its `Library` implementation (`core/instance.rs`): no type-erased
//! table, no lookup by type.
//!
//! Nothing here outlives the library: a cell that is filled registers its release with
//! `__cxa_atexit` under this library's `__dso_handle`, which the C runtime calls when
//! the library is unloaded (dlclose) or the process exits, so a dlopen / dlclose cycle
//! leaves nothing behind and valgrind finds nothing still reachable. An instance still
//! alive at that point keeps its own reference (its table is freed with it).

use std::ffi::c_void;
use std::sync::{Arc, Mutex, PoisonError};

/// One table of this library, built the first time it is asked for and dropped when
/// the library is unloaded.
pub struct Shared<T>(Mutex<Option<Arc<T>>>);

impl<T> Default for Shared<T> {
    fn default() -> Self {
        Self::new()
    }
}

unsafe extern "C" {
    /// This library's handle for `__cxa_atexit` (defined by the C runtime's crtbegin).
    static __dso_handle: c_void;
    fn __cxa_atexit(
        f: extern "C" fn(*mut c_void),
        arg: *mut c_void,
        dso: *const c_void,
    ) -> libc::c_int;
}

impl<T> Shared<T> {
    pub const fn new() -> Self {
        Shared(Mutex::new(None))
    }

    /// The table, built by `build` the first time it is asked for in this library (an
    /// error is returned, not kept: the next call builds again). Built under the lock,
    /// so concurrent first instantiations build it once.
    pub fn get(&'static self, build: impl FnOnce() -> Result<T, String>) -> Result<Arc<T>, String> {
        let mut slot = self.0.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(table) = &*slot {
            return Ok(Arc::clone(table));
        }
        let built = Arc::new(build()?);
        *slot = Some(Arc::clone(&built));
        let arg = self as *const Self as *mut c_void;
        // SAFETY: `release::<T>` is a function of this library, registered under this
        // library's handle, so the C runtime calls it before unmapping the library;
        // `arg` is this `static` cell, alive as long as the library is.
        unsafe { __cxa_atexit(release::<T>, arg, &raw const __dso_handle) };
        Ok(built)
    }
}

/// Drops the table of the cell `cell` (a `&'static Shared<T>`; at dlclose or exit).
extern "C" fn release<T>(cell: *mut c_void) {
    // SAFETY: registered by `Shared::get` with its own `'static` address.
    let cell = unsafe { &*(cell as *const Shared<T>) };
    let table = cell.0.lock().unwrap_or_else(PoisonError::into_inner).take();
    drop(table);
}
