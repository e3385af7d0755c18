//! FMU states behind the host's opaque pointers, for both front-ends: a state is a
//! boxed [`Snapshot`] registered in [`handles`] under its model and owned by the
//! instance that made it. `noun` is the standard's spelling of the handle in messages
//! ("FMUstate" in FMI 2.0, "FMUState" in FMI 3.0).

use super::handles::{self, HandleKind};
use super::instance::Snapshot;
use super::model::Model;
use std::ffi::c_void;

/// Checks that `state` is a live FMU state of model M (looked up, not dereferenced).
fn check<M: Model>(state: *mut c_void, noun: &str) -> Result<(), String> {
    if state.is_null() {
        return Err(format!("{noun} is a null pointer"));
    }
    if !handles::is_live::<M>(state as usize, HandleKind::State) {
        return Err(format!(
            "{noun} {state:p} is not a live FMU state of {}: never issued, already \
             freed, or another FMU's",
            M::info().model_name
        ));
    }
    Ok(())
}

/// The snapshot behind an FMU state pointer.
///
/// # Safety
/// A live state of M must not be freed while the returned reference is used.
pub unsafe fn snapshot<'a, M: Model>(
    state: *mut c_void,
    noun: &str,
) -> Result<&'a Snapshot<M>, String> {
    check::<M>(state, noun)?;
    // SAFETY: registered as a live state of M, created by `store` below.
    Ok(unsafe { &*(state as *const Snapshot<M>) })
}

/// Stores `s` in `*slot`, reusing the state already there (the standard lets the
/// host pass a previously obtained state to be overwritten). A new state belongs to
/// the instance `owner` and is freed with it at the latest.
///
/// # Safety
/// No reference to the snapshot in a non-null `*slot` may be alive.
pub unsafe fn store<M: Model>(
    slot: &mut *mut c_void,
    s: Snapshot<M>,
    owner: *mut c_void,
    noun: &str,
) -> Result<(), String> {
    if slot.is_null() {
        let state = Box::into_raw(Box::new(s)) as *mut c_void;
        handles::register::<M>(state as usize, HandleKind::State, owner as usize);
        *slot = state;
    } else {
        check::<M>(*slot, noun)?;
        // SAFETY: registered as a live state of M.
        unsafe { *(*slot as *mut Snapshot<M>) = s };
    }
    Ok(())
}

/// Frees the state in `*slot` (nothing if null) and sets `*slot` to null.
///
/// # Safety
/// No reference to the snapshot in `*slot` may be alive.
pub unsafe fn free<M: Model>(slot: &mut *mut c_void, noun: &str) -> Result<(), String> {
    if !slot.is_null() {
        check::<M>(*slot, noun)?;
        handles::unregister::<M>(*slot as usize, HandleKind::State);
        // SAFETY: was a live state of M, now unregistered: freed exactly once.
        drop(unsafe { Box::from_raw(*slot as *mut Snapshot<M>) });
        *slot = std::ptr::null_mut();
    }
    Ok(())
}
