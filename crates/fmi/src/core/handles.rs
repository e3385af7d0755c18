//! The handles this library issued and that are still live: instances and FMU states,
//! each tagged with its kind and its model type.
//!
//! Every entry point looks a handle up here before dereferencing it, so a garbage
//! pointer, an instance of another FMU, a state never issued, an already freed state
//! or a state of another model is refused with an error instead of being used. The
//! registry is static data of the loaded library; it releases its heap memory when
//! the last handle is freed, so nothing of it survives unloading.

use std::any::TypeId;
use std::sync::{Mutex, MutexGuard};

/// What a handle points to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HandleKind {
    Instance,
    State,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Entry {
    address: usize,
    kind: HandleKind,
    model: TypeId,
    /// The instance a state belongs to (freed with it); for an instance, itself.
    owner: usize,
}

impl Entry {
    /// Whether this entry is the handle `address` of `kind` for model `M`.
    fn is<M: 'static>(&self, address: usize, kind: HandleKind) -> bool {
        self.address == address && self.kind == kind && self.model == TypeId::of::<M>()
    }
}

static LIVE: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

fn live() -> MutexGuard<'static, Vec<Entry>> {
    // A panic while holding the lock cannot leave the list inconsistent (every
    // change is a single push or remove): recover from poisoning.
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Records a new handle of model `M`.
pub fn register<M: 'static>(address: usize, kind: HandleKind, owner: usize) {
    live().push(Entry {
        address,
        kind,
        model: TypeId::of::<M>(),
        owner,
    });
}

/// Whether `address` is a live handle of `kind` for model `M`.
pub fn is_live<M: 'static>(address: usize, kind: HandleKind) -> bool {
    live().iter().any(|e| e.is::<M>(address, kind))
}

/// Runs `f` if `address` is a live handle of `kind` for model `M` (None if not), with
/// the registry locked throughout: no other thread can unregister and free the handle
/// while `f` reads or writes what it points to.
pub fn while_live<M: 'static, R>(
    address: usize,
    kind: HandleKind,
    f: impl FnOnce() -> R,
) -> Option<R> {
    let list = live();
    let found = list.iter().any(|e| e.is::<M>(address, kind));
    let result = found.then(f);
    drop(list);
    result
}

/// Forgets a handle of model `M`; false if it was not live. The list gives its memory
/// back when it becomes empty.
pub fn unregister<M: 'static>(address: usize, kind: HandleKind) -> bool {
    let mut list = live();
    let found = list.iter().position(|e| e.is::<M>(address, kind));
    if let Some(i) = found {
        list.swap_remove(i);
    }
    if list.is_empty() {
        *list = Vec::new();
    }
    found.is_some()
}

/// Forgets every state owned by the instance at `owner` and returns their addresses.
pub fn take_states_of(owner: usize) -> Vec<usize> {
    let mut list = live();
    let mut taken = Vec::new();
    list.retain(|e| {
        let owned = e.kind == HandleKind::State && e.owner == owner;
        if owned {
            taken.push(e.address);
        }
        !owned
    });
    if list.is_empty() {
        *list = Vec::new();
    }
    taken
}

/// Frees the instance at `address`, registered under key `K` and boxed as an `I`, and
/// every state it still owns (each boxed as an `S`). A handle that is not a live
/// instance under `K` is ignored. A panic while dropping is caught: the C boundary
/// holds regardless.
///
/// # Safety
/// Every handle registered under `K` must come from `Box::<I>::into_raw`, and every
/// state owned by such a handle from `Box::<S>::into_raw`.
pub unsafe fn free_instance<K: 'static, I, S>(address: usize) {
    if !unregister::<K>(address, HandleKind::Instance) {
        return;
    }
    let _ = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        for state in take_states_of(address) {
            // SAFETY: boxed as an S when registered, and just unregistered, so freed
            // exactly once.
            drop(unsafe { Box::from_raw(state as *mut S) });
        }
        // SAFETY: boxed as an I when registered and just unregistered: freed once.
        drop(unsafe { Box::from_raw(address as *mut I) });
    }));
}

#[cfg(test)]
mod tests {
    use super::*;

    struct A;
    struct B;

    #[test]
    fn handles_are_told_apart_by_address_kind_and_model() {
        register::<A>(0x1000, HandleKind::Instance, 0x1000);
        register::<A>(0x2000, HandleKind::State, 0x1000);
        assert!(is_live::<A>(0x1000, HandleKind::Instance));
        assert!(!is_live::<B>(0x1000, HandleKind::Instance));
        assert!(!is_live::<A>(0x1000, HandleKind::State));
        assert!(!is_live::<A>(0x3000, HandleKind::State));
        assert_eq!(take_states_of(0x1000), vec![0x2000]);
        assert!(!is_live::<A>(0x2000, HandleKind::State));
        assert!(unregister::<A>(0x1000, HandleKind::Instance));
        assert!(!unregister::<A>(0x1000, HandleKind::Instance));
    }

    #[test]
    fn a_handle_cannot_be_unregistered_while_another_thread_uses_it() {
        // Expected order: the reader holds the registry while it uses the handle, so
        // the other thread's unregister (the first step of freeing) comes after it.
        struct C;
        use std::sync::mpsc;
        register::<C>(0x5000, HandleKind::State, 0x4000);
        let order = Mutex::new(Vec::new());
        let (inside, entered) = mpsc::channel();
        std::thread::scope(|scope| {
            scope.spawn(|| {
                while_live::<C, _>(0x5000, HandleKind::State, || {
                    inside.send(()).unwrap();
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    order.lock().unwrap().push("read");
                })
                .expect("live");
            });
            entered.recv().unwrap();
            assert!(unregister::<C>(0x5000, HandleKind::State));
            order.lock().unwrap().push("unregistered");
        });
        assert_eq!(*order.lock().unwrap(), ["read", "unregistered"]);
        assert_eq!(while_live::<C, _>(0x5000, HandleKind::State, || ()), None);
    }
}
