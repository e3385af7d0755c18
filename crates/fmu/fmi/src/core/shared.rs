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
//! No lock: the cell is an atomic pointer, so a `fork()` while another thread
//! instantiates leaves the child nothing to wait for (two first instantiations at
//! once may both build the table; one is kept, the other dropped).
//!
//! Nothing here outlives the library: a cell that is filled registers its release with
//! `__cxa_atexit` under this library's `__dso_handle`, which the C runtime calls when
//! the library is unloaded (dlclose) or the process exits, so a dlopen / dlclose cycle
//! leaves nothing behind and valgrind finds nothing still reachable. An instance still
//! alive at that point keeps its own reference (its table is freed with it).

use std::ffi::c_void;
use std::sync::Arc;
use std::sync::atomic::{AtomicPtr, Ordering};

/// One table of this library, built the first time it is asked for and dropped when
/// the library is unloaded: null, or a pointer from `Arc::into_raw` that holds one
/// reference.
pub struct Shared<T>(AtomicPtr<T>);

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
        Shared(AtomicPtr::new(std::ptr::null_mut()))
    }

    /// The table, built by `build` the first time it is asked for in this library (an
    /// error is returned, not kept: the next call builds again).
    pub fn get(&'static self, build: impl FnOnce() -> Result<T, String>) -> Result<Arc<T>, String> {
        let kept = self.0.load(Ordering::Acquire);
        if !kept.is_null() {
            // SAFETY: a pointer from Arc::into_raw whose reference the cell holds until
            // the library is unloaded (no call runs then).
            return Ok(unsafe { clone_raw(kept) });
        }
        let built = Arc::new(build()?);
        let raw = Arc::into_raw(Arc::clone(&built)) as *mut T;
        let null = std::ptr::null_mut();
        match self
            .0
            .compare_exchange(null, raw, Ordering::AcqRel, Ordering::Acquire)
        {
            Ok(_) => {
                let arg = self as *const Self as *mut c_void;
                // SAFETY: `release::<T>` is a function of this library, registered under
                // this library's handle, so the C runtime calls it before unmapping the
                // library; `arg` is this `static` cell, alive as long as the library is.
                unsafe { __cxa_atexit(release::<T>, arg, &raw const __dso_handle) };
                Ok(built)
            }
            Err(other) => {
                // Another thread kept its table first: use that one, drop this one.
                // SAFETY: `raw` came from Arc::into_raw above and was not published;
                // `other` is the kept pointer, as above.
                unsafe {
                    drop(Arc::from_raw(raw));
                    Ok(clone_raw(other))
                }
            }
        }
    }
}

/// A new reference to the table behind `raw`.
///
/// # Safety
/// `raw` must come from `Arc::into_raw` and its reference must still be held.
unsafe fn clone_raw<T>(raw: *mut T) -> Arc<T> {
    // SAFETY: by the contract above.
    unsafe {
        Arc::increment_strong_count(raw);
        Arc::from_raw(raw)
    }
}

/// Drops the table of the cell `cell` (a `&'static Shared<T>`; at dlclose or exit).
extern "C" fn release<T>(cell: *mut c_void) {
    // SAFETY: registered by `Shared::get` with its own `'static` address.
    let cell = unsafe { &*(cell as *const Shared<T>) };
    let raw = cell.0.swap(std::ptr::null_mut(), Ordering::AcqRel);
    if !raw.is_null() {
        // SAFETY: the reference the cell held, from Arc::into_raw.
        drop(unsafe { Arc::from_raw(raw) });
    }
}

/// A value built the first time it is asked for, without a lock (an atomic pointer to
/// a box): a `fork()` while another thread builds it leaves the child nothing to wait
/// for, unlike `OnceLock`. Two threads that ask first at once may both build it; one
/// value is kept, the other dropped.
pub struct Built<T>(AtomicPtr<T>, std::marker::PhantomData<Box<T>>);

impl<T> Default for Built<T> {
    fn default() -> Self {
        Self::new()
    }
}

impl<T> Built<T> {
    pub const fn new() -> Self {
        Built(
            AtomicPtr::new(std::ptr::null_mut()),
            std::marker::PhantomData,
        )
    }

    /// The value, if built.
    pub fn get(&self) -> Option<&T> {
        let kept = self.0.load(Ordering::Acquire);
        // SAFETY: null or a box published once and freed only with `self`.
        (!kept.is_null()).then(|| unsafe { &*kept })
    }

    /// The value, built by `build` if it is not yet.
    pub fn get_or_init(&self, build: impl FnOnce() -> T) -> &T {
        if let Some(value) = self.get() {
            return value;
        }
        let raw = Box::into_raw(Box::new(build()));
        let null = std::ptr::null_mut();
        match (self.0).compare_exchange(null, raw, Ordering::AcqRel, Ordering::Acquire) {
            // SAFETY: published now; freed only with `self`.
            Ok(_) => unsafe { &*raw },
            Err(kept) => {
                // SAFETY: `raw` was not published; `kept` is, as in `get`.
                unsafe {
                    drop(Box::from_raw(raw));
                    &*kept
                }
            }
        }
    }
}

impl<T> Drop for Built<T> {
    fn drop(&mut self) {
        let kept = *self.0.get_mut();
        if !kept.is_null() {
            // SAFETY: the box published by `get_or_init`, freed once.
            drop(unsafe { Box::from_raw(kept) });
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Built;

    #[test]
    fn a_built_value_is_built_once_and_kept() {
        // Expected: the first get_or_init builds, later ones return the same value
        // without building; eight threads at once agree on one value.
        let cell: Built<Vec<u32>> = Built::new();
        assert!(cell.get().is_none());
        assert_eq!(cell.get_or_init(|| vec![1, 2]), &[1, 2]);
        assert_eq!(cell.get_or_init(|| unreachable!()), &[1, 2]);
        let shared: Built<usize> = Built::new();
        let seen: Vec<usize> = std::thread::scope(|s| {
            let handles: Vec<_> = (0..8)
                .map(|k| {
                    let shared = &shared;
                    s.spawn(move || *shared.get_or_init(|| k))
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        assert!(seen.iter().all(|&v| v == seen[0]));
        assert_eq!(shared.get(), Some(&seen[0]));
    }
}
