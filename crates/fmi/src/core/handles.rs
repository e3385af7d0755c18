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
    live()
        .iter()
        .any(|e| e.address == address && e.kind == kind && e.model == TypeId::of::<M>())
}

/// Forgets a handle of model `M`; false if it was not live. The list gives its memory
/// back when it becomes empty.
pub fn unregister<M: 'static>(address: usize, kind: HandleKind) -> bool {
    let mut list = live();
    let found = list
        .iter()
        .position(|e| e.address == address && e.kind == kind && e.model == TypeId::of::<M>());
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
}
