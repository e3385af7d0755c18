//! FMU states behind the host's opaque pointers, for both front-ends: a state is a
//! boxed [`Snapshot`] registered in [`handles`] under its model and owned by the
//! instance that made it. `noun` is the standard's spelling of the handle in messages
//! ("FMUstate" in FMI 2.0, "FMUState" in FMI 3.0).

use super::handles::{self, HandleKind};
use super::instance::Snapshot;
use super::model::Model;
use std::ffi::c_void;

/// The refusal of a pointer that is not a live FMU state of model M.
fn not_live<M: Model>(state: *mut c_void, noun: &str) -> String {
    format!(
        "{noun} {state:p} is not a live FMU state of {}: never issued, already \
         freed, or another FMU's",
        M::INFO.model_name
    )
}

fn null(state: *mut c_void, noun: &str) -> Result<(), String> {
    if state.is_null() {
        return Err(format!("{noun} is a null pointer"));
    }
    Ok(())
}

/// A copy of the snapshot behind an FMU state pointer, taken with the registry locked
/// so that no other thread (another instance the state was passed to) can free it
/// during the copy.
pub fn snapshot<M: Model>(state: *mut c_void, noun: &str) -> Result<Snapshot<M>, String> {
    null(state, noun)?;
    handles::while_live::<M, _>(state as usize, HandleKind::State, |address| {
        // SAFETY: registered as a live state of M (created by `store` below) and
        // not freeable while the registry is locked.
        unsafe { (*(address as *const Snapshot<M>)).clone() }
    })
    .ok_or_else(|| not_live::<M>(state, noun))
}

/// Stores `s` in `*slot`, reusing the state already there (the standard lets the
/// host pass a previously obtained state to be overwritten). A new state belongs to
/// the instance with the handle `owner` and is freed with it at the latest. The
/// host's handle of a state is new (never an address: see [`handles`]).
pub fn store<M: Model>(
    slot: &mut *mut c_void,
    s: Snapshot<M>,
    owner: usize,
    noun: &str,
) -> Result<(), String> {
    if slot.is_null() {
        let address = Box::into_raw(Box::new(s)) as usize;
        let Some(state) = handles::register::<M>(address, HandleKind::State, Some(owner), None)
        else {
            // SAFETY: boxed just above and never registered: dropped once.
            drop(unsafe { Box::from_raw(address as *mut Snapshot<M>) });
            return Err(format!("this FMU has issued every {noun} handle it can"));
        };
        *slot = state as *mut c_void;
        return Ok(());
    }
    let state = *slot;
    handles::while_live::<M, _>(state as usize, HandleKind::State, |address| {
        // SAFETY: a live state of M, not freeable while the registry is locked.
        unsafe { *(address as *mut Snapshot<M>) = s };
    })
    .ok_or_else(|| not_live::<M>(state, noun))
}

/// Frees the state in `*slot` (nothing if null) and sets `*slot` to null. Only the
/// call that unregisters the state frees it, so two threads freeing the same state
/// cannot both drop it.
pub fn free<M: Model>(slot: &mut *mut c_void, noun: &str) -> Result<(), String> {
    let state = *slot;
    if state.is_null() {
        return Ok(());
    }
    let Some(address) = handles::unregister::<M>(state as usize, HandleKind::State) else {
        return Err(not_live::<M>(state, noun));
    };
    // SAFETY: was a live state of M, and this call unregistered it: freed once.
    drop(unsafe { Box::from_raw(address as *mut Snapshot<M>) });
    *slot = std::ptr::null_mut();
    Ok(())
}
