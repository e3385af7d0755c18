//! The handles this library issued and that are still live: instances and FMU states,
//! each tagged with its kind and its model type.
//!
//! A handle is an opaque number, not the address of what it names: every handle is
//! new (a counter that is never reset), so a freed handle stays refused even when the
//! allocator gives the same memory to a new instance or state. Every entry point looks
//! a handle up here before it reaches the object, so a garbage pointer, an instance of
//! another FMU, a state never issued, an already freed handle or a state of another
//! model is refused with an error instead of being used.
//!
//! An instance is busy while a call runs on it ([`enter`] .. [`leave`]): a second
//! call meanwhile, from a callback of the first (re-entrant) or from another thread,
//! is refused, and a FreeInstance is deferred until the running call leaves. The
//! registry is static data of the loaded library; it releases its heap memory when
//! the last handle is freed, so nothing of it survives unloading.

use std::any::TypeId;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex, MutexGuard};

/// What a handle points to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum HandleKind {
    Instance,
    State,
}

/// Logs an Error line through an instance's logger without touching the instance
/// (the refusal of a call that finds it busy).
pub type Reporter = Arc<dyn Fn(&str) + Send + Sync>;

struct Entry {
    /// The number the host holds.
    handle: usize,
    /// Where the object lives.
    address: usize,
    kind: HandleKind,
    model: TypeId,
    /// The handle of the instance a state belongs to (freed with it); for an
    /// instance, its own handle.
    owner: usize,
    /// The thread running a call on the instance.
    busy: Option<usize>,
    /// FreeInstance came while the instance was busy: the running call frees it.
    free_requested: bool,
    reporter: Option<Reporter>,
}

impl Entry {
    /// Whether this entry is the handle `handle` of `kind` for model `M`.
    fn is<M: 'static>(&self, handle: usize, kind: HandleKind) -> bool {
        self.handle == handle && self.kind == kind && self.model == TypeId::of::<M>()
    }
}

/// The live handles, sorted by handle (new handles are the largest, so a push keeps
/// the order; a removal shifts the rest): every lookup is a binary search.
static LIVE: Mutex<Vec<Entry>> = Mutex::new(Vec::new());

/// The next handle number; never reset, so never reused.
static NEXT: AtomicU64 = AtomicU64::new(1);

/// High bits of every handle: outside the user address space of x86-64 and AArch64,
/// so a handle is never also the address of a live heap block of the importer.
const HANDLE_BASE: u64 = 0xF0F0_0000_0000_0000;

thread_local! {
    /// A byte of every thread: its address tells the live threads apart. (A native
    /// thread-local without destructor: unlike `std::thread::current`, it takes no
    /// pthread key, which a library loaded and unloaded a thousand times would run
    /// out of.)
    static MARK: u8 = const { 0 };
}

/// A number that tells this thread from every other live thread.
fn this_thread() -> usize {
    MARK.with(|mark| mark as *const u8 as usize)
}

fn live() -> MutexGuard<'static, Vec<Entry>> {
    // A panic while holding the lock cannot leave the list inconsistent (every
    // change is a single push, remove or field store): recover from poisoning.
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The index of `handle` in the sorted list.
fn find(list: &[Entry], handle: usize) -> Option<usize> {
    list.binary_search_by_key(&handle, |e| e.handle).ok()
}

/// The index of `handle` if it is a live handle of `kind` for model `M`.
fn find_is<M: 'static>(list: &[Entry], handle: usize, kind: HandleKind) -> Option<usize> {
    find(list, handle).filter(|&i| list[i].is::<M>(handle, kind))
}

fn shrink(list: &mut Vec<Entry>) {
    if list.is_empty() {
        *list = Vec::new();
    }
}

/// Records the object at `address`, of model `M`, and returns its new handle.
pub fn register<M: 'static>(
    address: usize,
    kind: HandleKind,
    owner: Option<usize>,
    reporter: Option<Reporter>,
) -> usize {
    // Numbered under the lock, so that the list stays sorted.
    let mut list = live();
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let handle = (HANDLE_BASE | (n << 4)) as usize;
    list.push(Entry {
        handle,
        address,
        kind,
        model: TypeId::of::<M>(),
        owner: owner.unwrap_or(handle),
        busy: None,
        free_requested: false,
        reporter,
    });
    handle
}

/// Whether `handle` is a live handle of `kind` for model `M`.
pub fn is_live<M: 'static>(handle: usize, kind: HandleKind) -> bool {
    find_is::<M>(&live(), handle, kind).is_some()
}

/// Runs `f` on the address behind `handle` if it is a live handle of `kind` for model
/// `M` (None if not), with the registry locked throughout: no other thread can
/// unregister and free the object while `f` reads or writes it.
pub fn while_live<M: 'static, R>(
    handle: usize,
    kind: HandleKind,
    f: impl FnOnce(usize) -> R,
) -> Option<R> {
    let list = live();
    let address = list
        .iter()
        .find(|e| e.is::<M>(handle, kind))
        .map(|e| e.address);
    let result = address.map(f);
    drop(list);
    result
}

/// Forgets a handle of model `M` and returns its address; None if it was not live.
pub fn unregister<M: 'static>(handle: usize, kind: HandleKind) -> Option<usize> {
    let mut list = live();
    let found = find_is::<M>(&list, handle, kind);
    let address = found.map(|i| list.remove(i).address);
    shrink(&mut list);
    address
}

/// Forgets every state owned by the instance `owner` and returns their addresses.
fn take_states_of(list: &mut Vec<Entry>, owner: usize) -> Vec<usize> {
    let mut taken = Vec::new();
    list.retain(|e| {
        let owned = e.kind == HandleKind::State && e.owner == owner;
        if owned {
            taken.push(e.address);
        }
        !owned
    });
    taken
}

/// Why [`enter`] refused a call.
pub enum Refused {
    /// Not a live instance of this model (no logger to report through).
    Unknown,
    /// Busy with another call: from this thread (`reentrant`, a callback of that
    /// call) or from another one.
    Busy {
        reentrant: bool,
        reporter: Option<Reporter>,
    },
}

/// Marks the instance `handle` of model `M` busy with a call of this thread and
/// returns its address.
pub fn enter<M: 'static>(handle: usize) -> Result<usize, Refused> {
    let mut list = live();
    let i = find_is::<M>(&list, handle, HandleKind::Instance).ok_or(Refused::Unknown)?;
    let entry = &mut list[i];
    if entry.free_requested {
        return Err(Refused::Unknown);
    }
    let me = this_thread();
    match entry.busy {
        None => {
            entry.busy = Some(me);
            Ok(entry.address)
        }
        Some(thread) => Err(Refused::Busy {
            reentrant: thread == me,
            reporter: entry.reporter.clone(),
        }),
    }
}

/// Whether FreeInstance was called on the busy instance `handle` (by a callback of
/// the running call or by another thread).
pub fn free_requested(handle: usize) -> bool {
    let list = live();
    find(&list, handle).is_some_and(|i| list[i].free_requested)
}

/// What freeing an instance takes: its address and those of the states it owns.
pub struct Freed {
    pub instance: usize,
    pub states: Vec<usize>,
}

/// The end of a call on the instance `handle`: not busy any more. Some when a
/// FreeInstance came during the call: the instance is unregistered with its states,
/// and the caller frees them.
pub fn leave(handle: usize) -> Option<Freed> {
    let mut list = live();
    let i = find(&list, handle).filter(|&i| list[i].kind == HandleKind::Instance)?;
    list[i].busy = None;
    if !list[i].free_requested {
        return None;
    }
    let instance = list.remove(i).address;
    let states = take_states_of(&mut list, handle);
    shrink(&mut list);
    Some(Freed { instance, states })
}

/// FreeInstance of `handle` (model `M`): Some when it can be freed now (it is
/// unregistered with its states); None when it is not a live instance, or busy, in
/// which case the running call frees it when it leaves ([`leave`]).
pub fn free_instance<M: 'static>(handle: usize) -> Option<Freed> {
    let mut list = live();
    let i = find_is::<M>(&list, handle, HandleKind::Instance)?;
    if list[i].free_requested {
        return None;
    }
    if list[i].busy.is_some() {
        list[i].free_requested = true;
        return None;
    }
    let instance = list.remove(i).address;
    let states = take_states_of(&mut list, handle);
    shrink(&mut list);
    Some(Freed { instance, states })
}

#[cfg(test)]
mod tests {
    use super::*;

    struct A;
    struct B;

    #[test]
    fn handles_are_told_apart_by_number_kind_and_model_and_never_reused() {
        // Expected: a handle names one registration only; the same address registered
        // again after a free gets a new handle, and the old one stays refused.
        let a = register::<A>(0x1000, HandleKind::Instance, None, None);
        let s = register::<A>(0x2000, HandleKind::State, Some(a), None);
        assert!(is_live::<A>(a, HandleKind::Instance));
        assert!(!is_live::<B>(a, HandleKind::Instance));
        assert!(!is_live::<A>(a, HandleKind::State));
        assert!(!is_live::<A>(0x1000, HandleKind::Instance));
        let freed = free_instance::<A>(a).expect("not busy: freed now");
        assert_eq!((freed.instance, freed.states), (0x1000, vec![0x2000]));
        assert!(!is_live::<A>(s, HandleKind::State));
        let again = register::<A>(0x1000, HandleKind::Instance, None, None);
        assert_ne!(again, a);
        assert!(!is_live::<A>(a, HandleKind::Instance));
        assert_eq!(unregister::<A>(again, HandleKind::Instance), Some(0x1000));
        assert_eq!(unregister::<A>(again, HandleKind::Instance), None);
    }

    #[test]
    fn a_busy_instance_refuses_a_second_call_and_defers_its_free() {
        // Expected: enter marks the instance busy; a second enter from this thread is
        // re-entrant, from another thread not; a free while busy happens at leave.
        struct C;
        let c = register::<C>(0x3000, HandleKind::Instance, None, None);
        assert_eq!(enter::<C>(c).ok(), Some(0x3000));
        assert!(matches!(
            enter::<C>(c),
            Err(Refused::Busy {
                reentrant: true,
                ..
            })
        ));
        std::thread::scope(|scope| {
            let other = scope.spawn(|| enter::<C>(c)).join().unwrap();
            assert!(matches!(
                other,
                Err(Refused::Busy {
                    reentrant: false,
                    ..
                })
            ));
        });
        assert!(free_instance::<C>(c).is_none());
        assert!(free_requested(c));
        assert!(matches!(enter::<C>(c), Err(Refused::Unknown)));
        let freed = leave(c).expect("freed at leave");
        assert_eq!(freed.instance, 0x3000);
        assert!(!is_live::<C>(c, HandleKind::Instance));
    }

    #[test]
    fn a_handle_cannot_be_unregistered_while_another_thread_uses_it() {
        // Expected order: the reader holds the registry while it uses the handle, so
        // the other thread's unregister (the first step of freeing) comes after it.
        struct D;
        use std::sync::mpsc;
        let s = register::<D>(0x5000, HandleKind::State, Some(0x4000), None);
        let order = Mutex::new(Vec::new());
        let (inside, entered) = mpsc::channel();
        std::thread::scope(|scope| {
            scope.spawn(|| {
                while_live::<D, _>(s, HandleKind::State, |_| {
                    inside.send(()).unwrap();
                    std::thread::sleep(std::time::Duration::from_millis(50));
                    order.lock().unwrap().push("read");
                })
                .expect("live");
            });
            entered.recv().unwrap();
            assert!(unregister::<D>(s, HandleKind::State).is_some());
            order.lock().unwrap().push("unregistered");
        });
        assert_eq!(*order.lock().unwrap(), ["read", "unregistered"]);
        assert_eq!(while_live::<D, _>(s, HandleKind::State, |_| ()), None);
    }
}
