//! Tables built once per loaded library and shared by its instances: the variable
//! index of a declared model and its FMI 3.0 views are the same for every instance, so
//! the first instantiation builds them and later ones take a reference (an atomic
//! increment instead of a table per instance).
//!
//! Nothing here outlives the library: the first table registers a release function with
//! `__cxa_atexit` under this library's `__dso_handle`, which the C runtime calls when
//! the library is unloaded (dlclose) or the process exits, so a dlopen / dlclose cycle
//! leaves nothing behind and valgrind finds nothing still reachable. An instance still
//! alive at that point keeps its own reference (its table is freed with it).

use std::any::{Any, TypeId};
use std::ffi::c_void;
use std::sync::{Arc, Mutex, PoisonError};

type Entry = (TypeId, Arc<dyn Any + Send + Sync>);

/// The tables of this library, by key type. A handful at most (one model per library:
/// its index and its two FMI 3.0 views), searched linearly.
static TABLES: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

unsafe extern "C" {
    /// This library's handle for `__cxa_atexit` (defined by the C runtime's crtbegin).
    static __dso_handle: c_void;
    fn __cxa_atexit(
        f: extern "C" fn(*mut c_void),
        arg: *mut c_void,
        dso: *const c_void,
    ) -> libc::c_int;
}

/// The table of key `K`, built by `build` the first time it is asked for in this
/// library (an error is returned, not kept: the next call builds again).
pub fn shared<K: 'static, T: Send + Sync + 'static>(
    build: impl FnOnce() -> Result<T, String>,
) -> Result<Arc<T>, String> {
    let key = TypeId::of::<K>();
    if let Some(table) = find(key) {
        return Ok(downcast(table));
    }
    let built: Arc<dyn Any + Send + Sync> = Arc::new(build()?);
    let mut tables = TABLES.lock().unwrap_or_else(PoisonError::into_inner);
    // Another thread may have built it meanwhile: keep the first one.
    if let Some((_, table)) = tables.iter().find(|(k, _)| *k == key) {
        return Ok(downcast(Arc::clone(table)));
    }
    if tables.is_empty() {
        // SAFETY: `release` is a function of this library, registered under this
        // library's handle, so the C runtime calls it before unmapping the library.
        unsafe { __cxa_atexit(release, std::ptr::null_mut(), &raw const __dso_handle) };
    }
    tables.push((key, Arc::clone(&built)));
    Ok(downcast(built))
}

fn find(key: TypeId) -> Option<Arc<dyn Any + Send + Sync>> {
    let tables = TABLES.lock().unwrap_or_else(PoisonError::into_inner);
    tables
        .iter()
        .find(|(k, _)| *k == key)
        .map(|(_, t)| Arc::clone(t))
}

/// The table as its type (one type per key: the key types are private to their
/// callers, each used with one table type).
pub(crate) fn downcast<T: Send + Sync + 'static>(table: Arc<dyn Any + Send + Sync>) -> Arc<T> {
    match table.downcast::<T>() {
        Ok(table) => table,
        Err(_) => unreachable!("a key type is used with one table type"),
    }
}

/// Drops this library's tables (at dlclose or exit).
extern "C" fn release(_: *mut c_void) {
    let tables = std::mem::take(&mut *TABLES.lock().unwrap_or_else(PoisonError::into_inner));
    drop(tables);
}
