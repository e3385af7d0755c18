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
//! The numbers are this loaded copy's own: the counter goes through a bijection keyed
//! by a random number drawn when the copy issues its first handle (`number`), so
//! another FMU, or another copy of this very binary loaded from another path, issues
//! other numbers, and a handle given to the wrong library is not one of its live
//! handles (docs/reliability.md, "Handles of several loaded FMUs", argues the choice).
//!
//! An instance is busy while a call runs on it ([`enter`] .. [`leave`]): a second
//! call meanwhile, from a callback of the first (re-entrant) or from another thread,
//! is refused, and a FreeInstance is deferred until the running call leaves. The
//! registry is static data of the loaded library; it releases its heap memory when
//! the last handle is freed, so nothing of it survives unloading.
//!
//! `fork()` at any moment (Linux, glibc): the registry's lock is taken by a fork
//! handler before the process is copied and released in the parent and the child
//! after (`__register_atfork` under this library's `__dso_handle`, so glibc removes
//! the handlers when the library is unloaded: `__cxa_finalize` at dlclose), so the
//! child never finds it held by a thread that does not exist there.

use std::any::TypeId;
use std::collections::hash_map::RandomState;
use std::hash::{BuildHasher, Hasher};
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
    /// A call that could not touch the instance ([`fail`]) left it to the next call
    /// that enters to put it in the Error state.
    failed: bool,
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

/// The registry of this loaded copy: its live handles, sorted by handle (every lookup
/// is a binary search), how many handles it has issued and its key.
struct Registry {
    entries: Vec<Entry>,
    /// Handles issued so far; never reset, so never reused.
    issued: u64,
    /// The key of [`number`] (0: not drawn yet).
    key: u64,
}

static LIVE: Mutex<Registry> = Mutex::new(Registry {
    entries: Vec::new(),
    issued: 0,
    key: 0,
});

/// Bits of a handle that tell handles apart: 44 on 64-bit targets, 28 on 32-bit ones
/// (the other bits are [`HANDLE_BASE`] and four zero bits at the bottom).
const SPREAD_BITS: u32 = if usize::BITS == 64 { 44 } else { 28 };
const SPREAD: u64 = (1 << SPREAD_BITS) - 1;

/// High bits of every handle on 64-bit targets: outside the user address space of
/// x86-64 and AArch64 (even with a tagged top byte), so a handle is never also the
/// address of a live heap block of the importer.
const HANDLE_BASE: u64 = if usize::BITS == 64 {
    0xF0F0_0000_0000_0000
} else {
    0
};

/// A key no other loaded copy shares: 64 bits from the operating system's random
/// source (std's `RandomState`, seeded per copy of std, and every FMU links its own),
/// mixed with the address of this copy's registry. Never 0.
fn draw_key() -> u64 {
    let mut hasher = RandomState::new().build_hasher();
    hasher.write_usize(&LIVE as *const Mutex<Registry> as usize);
    hasher.finish() | 1
}

/// The `n`-th handle number of the copy with key `key`: a bijection of the
/// [`SPREAD_BITS`]-bit numbers (xor, multiplications by odd constants and xor-shifts
/// by half the width are each invertible there), so one copy never issues a number
/// twice, and two copies (two keys) issue unrelated numbers.
fn number(n: u64, key: u64) -> u64 {
    let half = SPREAD_BITS / 2;
    let mut x = (n ^ key) & SPREAD;
    x = x.wrapping_mul(0x9E37_79B9_7F4A_7C15) & SPREAD;
    x ^= x >> half;
    x = x.wrapping_add(key >> 32) & SPREAD;
    x = x.wrapping_mul(0xBF58_476D_1CE4_E5B9) & SPREAD;
    x ^ (x >> half)
}

/// The handle after `issued` handles of the copy with key `key`; None when every
/// number has been issued (2^44 registrations on a 64-bit target).
fn handle_after(issued: u64, key: u64) -> Option<usize> {
    (issued <= SPREAD).then(|| (HANDLE_BASE | (number(issued, key) << 4)) as usize)
}

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

fn live() -> MutexGuard<'static, Registry> {
    // A panic while holding the lock cannot leave the list inconsistent (every
    // change is a single push, remove or field store): recover from poisoning.
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// The fork handlers of the registry (glibc).
#[cfg(all(target_os = "linux", target_env = "gnu"))]
mod fork {
    use super::{Registry, live};
    use std::cell::UnsafeCell;
    use std::ffi::c_void;
    use std::sync::MutexGuard;
    use std::sync::atomic::{AtomicBool, Ordering};

    unsafe extern "C" {
        /// This library's handle (crtbegin), under which glibc keeps the handlers
        /// and removes them when the library is unloaded.
        static __dso_handle: c_void;
        /// glibc's registration behind pthread_atfork (which passes the caller's
        /// `__dso_handle` the same way), exported since glibc 2.3.2.
        fn __register_atfork(
            prepare: Option<extern "C" fn()>,
            parent: Option<extern "C" fn()>,
            child: Option<extern "C" fn()>,
            dso: *const c_void,
        ) -> libc::c_int;
    }

    /// The registry's lock, held by the forking thread from `prepare` to `release`.
    struct Held(UnsafeCell<Option<MutexGuard<'static, Registry>>>);
    // SAFETY: only touched by the thread that holds the registry's lock.
    unsafe impl Sync for Held {}
    static HELD: Held = Held(UnsafeCell::new(None));

    extern "C" fn prepare() {
        let guard = live();
        // SAFETY: this thread holds the lock, so no other thread touches HELD.
        unsafe { *HELD.0.get() = Some(guard) };
    }

    /// After fork, in the parent and in the child (whose only thread is the copy of
    /// the forking one): the lock released.
    extern "C" fn release() {
        // SAFETY: as in `prepare`: the forking thread still holds the lock.
        drop(unsafe { (*HELD.0.get()).take() });
    }

    /// Registers the handlers once per loaded copy of the library.
    pub fn guard_once() {
        static DONE: AtomicBool = AtomicBool::new(false);
        if !DONE.swap(true, Ordering::AcqRel) {
            // SAFETY: functions of this library under its own handle (removed at its
            // unload); glibc calls them around every fork.
            unsafe {
                __register_atfork(
                    Some(prepare),
                    Some(release),
                    Some(release),
                    &raw const __dso_handle,
                )
            };
        }
    }
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

/// Records the object at `address`, of model `M`, and returns its new handle; None
/// when this copy has issued every number it has.
pub fn register<M: 'static>(
    address: usize,
    kind: HandleKind,
    owner: Option<usize>,
    reporter: Option<Reporter>,
) -> Option<usize> {
    // Before the lock: glibc runs the fork handlers under a lock of its own.
    #[cfg(all(target_os = "linux", target_env = "gnu"))]
    fork::guard_once();
    let mut registry = live();
    if registry.key == 0 {
        registry.key = draw_key();
    }
    let handle = handle_after(registry.issued, registry.key)?;
    registry.issued += 1;
    let list = &mut registry.entries;
    let at = list.partition_point(|e| e.handle < handle);
    list.insert(
        at,
        Entry {
            handle,
            address,
            kind,
            model: TypeId::of::<M>(),
            owner: owner.unwrap_or(handle),
            busy: None,
            failed: false,
            free_requested: false,
            reporter,
        },
    );
    Some(handle)
}

/// Whether `handle` is a live handle of `kind` for model `M`.
pub fn is_live<M: 'static>(handle: usize, kind: HandleKind) -> bool {
    find_is::<M>(&live().entries, handle, kind).is_some()
}

/// Runs `f` on the address behind `handle` if it is a live handle of `kind` for model
/// `M` (None if not), with the registry locked throughout: no other thread can
/// unregister and free the object while `f` reads or writes it.
pub fn while_live<M: 'static, R>(
    handle: usize,
    kind: HandleKind,
    f: impl FnOnce(usize) -> R,
) -> Option<R> {
    let registry = live();
    let list = &registry.entries;
    let address = find_is::<M>(list, handle, kind).map(|i| list[i].address);
    let result = address.map(f);
    drop(registry);
    result
}

/// Forgets a handle of model `M` and returns its address; None if it was not live.
pub fn unregister<M: 'static>(handle: usize, kind: HandleKind) -> Option<usize> {
    let mut registry = live();
    let list = &mut registry.entries;
    let found = find_is::<M>(list, handle, kind);
    let address = found.map(|i| list.remove(i).address);
    shrink(list);
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

/// A call [`enter`] let in.
pub struct Entered {
    /// Where the instance lives.
    pub address: usize,
    /// The instance is to be put in the Error state before the call runs ([`fail`]).
    pub failed: bool,
    /// The earlier call of this thread on the instance never returned: a callback
    /// left it with longjmp (see `abandoned`). The instance is to be put in the Error
    /// state, with a log line.
    pub abandoned: bool,
}

/// Whether the call of this thread that holds an instance busy was abandoned: this
/// thread calls again (`mark`: a [`stack_mark`](super::callback::stack_mark) of the
/// new call) from outside every host callback it runs, so the earlier call is no
/// longer on its stack (a callback left it with longjmp). A call from inside a
/// callback is re-entrant instead.
fn abandoned(busy: Option<usize>, me: usize, mark: usize) -> bool {
    busy == Some(me) && !super::callback::inside_callback(mark)
}

/// Marks the instance `handle` of model `M` busy with a call of this thread (`mark`:
/// a stack address of that call) and returns its address.
pub fn enter<M: 'static>(handle: usize, mark: usize) -> Result<Entered, Refused> {
    let mut registry = live();
    let list = &mut registry.entries;
    let i = find_is::<M>(list, handle, HandleKind::Instance).ok_or(Refused::Unknown)?;
    let entry = &mut list[i];
    if entry.free_requested {
        return Err(Refused::Unknown);
    }
    let me = this_thread();
    let abandoned = abandoned(entry.busy, me, mark);
    if abandoned {
        entry.busy = None;
    }
    match entry.busy {
        None => {
            entry.busy = Some(me);
            Ok(Entered {
                address: entry.address,
                failed: std::mem::take(&mut entry.failed),
                abandoned,
            })
        }
        Some(thread) => Err(Refused::Busy {
            reentrant: thread == me,
            reporter: entry.reporter.clone(),
        }),
    }
}

/// A call on the live instance `handle` of model `M` failed without touching it (it
/// was refused because another thread was inside a call): the next call that enters
/// puts the instance in the Error state, as the failed call's Error status told the
/// host. Nothing if it is not a live instance.
pub fn fail<M: 'static>(handle: usize) {
    let mut registry = live();
    let list = &mut registry.entries;
    if let Some(i) = find_is::<M>(list, handle, HandleKind::Instance) {
        list[i].failed = true;
    }
}

/// Whether FreeInstance was called on the busy instance `handle` (by a callback of
/// the running call or by another thread).
pub fn free_requested(handle: usize) -> bool {
    let list = &live().entries;
    find(list, handle).is_some_and(|i| list[i].free_requested)
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
    let mut registry = live();
    let list = &mut registry.entries;
    let i = find(list, handle).filter(|&i| list[i].kind == HandleKind::Instance)?;
    list[i].busy = None;
    if !list[i].free_requested {
        return None;
    }
    let instance = list.remove(i).address;
    let states = take_states_of(list, handle);
    shrink(list);
    Some(Freed { instance, states })
}

/// FreeInstance of `handle` (model `M`; `mark`: a stack address of the call): Some
/// when it can be freed now (it is unregistered with its states), also when the call
/// of this thread that held it busy was abandoned (see `abandoned`); None when it is
/// not a live instance, or busy, in which case the running call frees it when it
/// leaves ([`leave`]).
pub fn free_instance<M: 'static>(handle: usize, mark: usize) -> Option<Freed> {
    let mut registry = live();
    let list = &mut registry.entries;
    let i = find_is::<M>(list, handle, HandleKind::Instance)?;
    if abandoned(list[i].busy, this_thread(), mark) {
        list[i].busy = None;
        list[i].free_requested = false;
    }
    if list[i].free_requested {
        return None;
    }
    if list[i].busy.is_some() {
        list[i].free_requested = true;
        return None;
    }
    let instance = list.remove(i).address;
    let states = take_states_of(list, handle);
    shrink(list);
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
        let a = register::<A>(0x1000, HandleKind::Instance, None, None).unwrap();
        let s = register::<A>(0x2000, HandleKind::State, Some(a), None).unwrap();
        assert!(is_live::<A>(a, HandleKind::Instance));
        assert!(!is_live::<B>(a, HandleKind::Instance));
        assert!(!is_live::<A>(a, HandleKind::State));
        assert!(!is_live::<A>(0x1000, HandleKind::Instance));
        let freed = free_instance::<A>(a, 0).expect("not busy: freed now");
        assert_eq!((freed.instance, freed.states), (0x1000, vec![0x2000]));
        assert!(!is_live::<A>(s, HandleKind::State));
        let again = register::<A>(0x1000, HandleKind::Instance, None, None).unwrap();
        assert_ne!(again, a);
        assert!(!is_live::<A>(a, HandleKind::Instance));
        assert_eq!(unregister::<A>(again, HandleKind::Instance), Some(0x1000));
        assert_eq!(unregister::<A>(again, HandleKind::Instance), None);
    }

    /// The inverse of [`number`], step by step: xor-shift by half the width undone by
    /// the same shift (its square is the identity when twice the shift covers the
    /// width), a multiplication by an odd c undone by c^-1 mod 2^bits (Newton's
    /// iteration x <- x (2 - c x) doubles the correct low bits from x = c).
    fn inverse(y: u64, key: u64) -> u64 {
        fn odd_inverse(c: u64) -> u64 {
            let mut x = c;
            for _ in 0..6 {
                x = x.wrapping_mul(2u64.wrapping_sub(c.wrapping_mul(x)));
            }
            x
        }
        let half = SPREAD_BITS / 2;
        let mut x = y ^ (y >> half);
        x = x.wrapping_mul(odd_inverse(0xBF58_476D_1CE4_E5B9)) & SPREAD;
        x = x.wrapping_sub(key >> 32) & SPREAD;
        x ^= x >> half;
        x = x.wrapping_mul(odd_inverse(0x9E37_79B9_7F4A_7C15)) & SPREAD;
        (x ^ key) & SPREAD
    }

    #[test]
    fn numbers_are_a_bijection_and_differ_between_copies() {
        // Expected: the explicit inverse above recovers every n (so one copy never
        // issues a number twice); the first 4096 handles of two keys share none (a
        // shared one would be a handle both copies accept); after 2^SPREAD_BITS
        // handles none is left.
        let (k1, k2) = (0x0123_4567_89AB_CDEF, 0xFEDC_BA98_7654_3211);
        for n in (0..4096).chain([SPREAD - 1, SPREAD, 1 << 40, 0x0AAA_AAAA_AAAA]) {
            let n = n & SPREAD;
            assert_eq!(inverse(number(n, k1), k1), n);
            assert_eq!(inverse(number(n, k2), k2), n);
        }
        let first = |k| (0..4096).map(move |n| handle_after(n, k).unwrap());
        let one: std::collections::HashSet<usize> = first(k1).collect();
        assert_eq!(one.len(), 4096);
        assert!(first(k2).all(|h| !one.contains(&h)));
        for h in first(k1) {
            assert_eq!(h as u64 >> 48, HANDLE_BASE >> 48);
            assert_eq!(h & 0xF, 0);
        }
        assert!(handle_after(SPREAD, k1).is_some());
        assert_eq!(handle_after(SPREAD + 1, k1), None);
        assert_ne!(draw_key(), draw_key(), "two draws (RandomState) alike");
    }

    #[test]
    fn a_failed_call_leaves_the_error_state_to_the_next_call() {
        // Expected: fail() on an instance marks it for exactly the next enter.
        struct E;
        let e = register::<E>(0x6000, HandleKind::Instance, None, None).unwrap();
        fail::<E>(e);
        fail::<A>(e); // another model's type: not this instance
        assert!(enter::<E>(e, 0).ok().unwrap().failed);
        assert!(leave(e).is_none());
        assert!(!enter::<E>(e, 0).ok().unwrap().failed);
        assert!(leave(e).is_none());
        assert!(free_instance::<E>(e, 0).is_some());
    }

    #[test]
    fn a_busy_instance_refuses_a_second_call_and_defers_its_free() {
        // Expected: enter marks the instance busy; a second enter from a callback of
        // this thread is re-entrant, from another thread not; a free while busy
        // happens at leave.
        use crate::core::callback::{host, stack_mark};
        struct C;
        let c = register::<C>(0x3000, HandleKind::Instance, None, None).unwrap();
        assert_eq!(
            enter::<C>(c, stack_mark()).ok().map(|e| e.address),
            Some(0x3000)
        );
        // A callback is a call through the host's function pointer: a frame below
        // `host`'s (black_box keeps the call from being inlined into it).
        fn in_callback<R>(f: fn(usize) -> R, c: usize) -> R {
            host("logger", || std::hint::black_box(f)(c))
        }
        assert!(matches!(
            in_callback(|c| enter::<C>(c, stack_mark()), c),
            Err(Refused::Busy {
                reentrant: true,
                ..
            })
        ));
        std::thread::scope(|scope| {
            let other = scope.spawn(|| enter::<C>(c, 0)).join().unwrap();
            assert!(matches!(
                other,
                Err(Refused::Busy {
                    reentrant: false,
                    ..
                })
            ));
        });
        assert!(in_callback(|c| free_instance::<C>(c, stack_mark()), c).is_none());
        assert!(free_requested(c));
        assert!(matches!(enter::<C>(c, 0), Err(Refused::Unknown)));
        let freed = leave(c).expect("freed at leave");
        assert_eq!(freed.instance, 0x3000);
        assert!(!is_live::<C>(c, HandleKind::Instance));
    }

    #[test]
    fn a_call_abandoned_by_its_thread_lets_the_next_call_of_that_thread_in() {
        // Expected: an instance busy with a call of this thread that no callback of
        // this thread is running any more (a longjmp out of the callback) is let in
        // by the next call of the thread, marked abandoned (the Error state follows),
        // and freed at once by its FreeInstance; another thread is still refused.
        use crate::core::callback::stack_mark;
        struct F;
        let f = register::<F>(0x7000, HandleKind::Instance, None, None).unwrap();
        assert!(!enter::<F>(f, stack_mark()).ok().unwrap().abandoned);
        std::thread::scope(|scope| {
            let other = scope.spawn(|| enter::<F>(f, stack_mark())).join().unwrap();
            assert!(matches!(
                other,
                Err(Refused::Busy {
                    reentrant: false,
                    ..
                })
            ));
        });
        let again = enter::<F>(f, stack_mark()).ok().expect("let in");
        assert!(again.abandoned && !again.failed);
        assert_eq!(again.address, 0x7000);
        let freed = free_instance::<F>(f, stack_mark()).expect("freed now");
        assert_eq!(freed.instance, 0x7000);
        assert!(leave(f).is_none());
        assert!(!is_live::<F>(f, HandleKind::Instance));
    }

    #[test]
    fn a_handle_cannot_be_unregistered_while_another_thread_uses_it() {
        // Expected order: the reader holds the registry while it uses the handle, so
        // the other thread's unregister (the first step of freeing) comes after it.
        struct D;
        use std::sync::mpsc;
        let s = register::<D>(0x5000, HandleKind::State, Some(0x4000), None).unwrap();
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
