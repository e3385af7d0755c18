//! The step path allocates nothing after initialization: every packaged FMU, FMI 2.0
//! and FMI 3.0, Co-Simulation (inputs, DoStep, outputs) and Model Exchange (inputs,
//! SetTime, SetContinuousStates, GetDerivatives, event indicators, outputs,
//! CompletedIntegratorStep), see `robofmu_hostile::realtime`.
//!
//! The count is the C library's: this program defines `malloc`, `calloc`, `realloc`,
//! `free` and the aligned allocators (forwarded to glibc's `__libc_*` functions), and
//! the dynamic linker binds the FMU's calls to them, the executable coming first in
//! the lookup order (glibc's documented way of replacing malloc). The FMU's Rust
//! standard library allocates through these functions, as any C code in it would. A
//! probe allocation of the FMU itself (`fmi2Instantiate`) shows that the count sees
//! the library's allocations at all: a count of zero cannot come from a counter that
//! counts nothing. One thread, no test harness: nothing else allocates while it counts.

use robofmu_hostile::Loaded;
use robofmu_hostile::realtime::steppers;
use std::ffi::c_void;
use std::sync::atomic::{AtomicUsize, Ordering};

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe extern "C" {
    fn __libc_malloc(size: usize) -> *mut c_void;
    fn __libc_calloc(n: usize, size: usize) -> *mut c_void;
    fn __libc_realloc(p: *mut c_void, size: usize) -> *mut c_void;
    fn __libc_free(p: *mut c_void);
    fn __libc_memalign(align: usize, size: usize) -> *mut c_void;
}

fn counted() {
    ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
}

#[unsafe(no_mangle)]
pub extern "C" fn malloc(size: usize) -> *mut c_void {
    counted();
    // SAFETY: glibc's allocator, called as malloc would be.
    unsafe { __libc_malloc(size) }
}

#[unsafe(no_mangle)]
pub extern "C" fn calloc(n: usize, size: usize) -> *mut c_void {
    counted();
    // SAFETY: as above.
    unsafe { __libc_calloc(n, size) }
}

/// # Safety
/// `p` is null or a block of this allocator.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn realloc(p: *mut c_void, size: usize) -> *mut c_void {
    counted();
    // SAFETY: by the contract above.
    unsafe { __libc_realloc(p, size) }
}

/// # Safety
/// `p` is null or a block of this allocator.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn free(p: *mut c_void) {
    // SAFETY: by the contract above.
    unsafe { __libc_free(p) }
}

#[unsafe(no_mangle)]
pub extern "C" fn memalign(align: usize, size: usize) -> *mut c_void {
    counted();
    // SAFETY: as above.
    unsafe { __libc_memalign(align, size) }
}

#[unsafe(no_mangle)]
pub extern "C" fn aligned_alloc(align: usize, size: usize) -> *mut c_void {
    memalign(align, size)
}

/// # Safety
/// `out` is valid for one pointer.
#[unsafe(no_mangle)]
pub unsafe extern "C" fn posix_memalign(out: *mut *mut c_void, align: usize, size: usize) -> i32 {
    let p = memalign(align, size);
    if p.is_null() {
        return libc::ENOMEM;
    }
    // SAFETY: by the contract above.
    unsafe { *out = p };
    0
}

fn count() -> usize {
    ALLOCATIONS.load(Ordering::Relaxed)
}

/// Steps counted per case, after as many uncounted ones (first-call effects).
const STEPS: usize = 1000;

fn main() {
    let loaded = Loaded::all();
    let before = count();
    let mut cases = steppers(&loaded).unwrap_or_else(|e| panic!("{e}"));
    let setup = count() - before;
    println!(
        "{} cases instantiated and initialized: {setup} allocations (FMUs and host)",
        cases.len()
    );
    // Truth for the counter: instantiating and initializing twelve-odd instances of
    // Rust code allocates (boxes, tables, names); a counter that saw none of it would
    // prove nothing below.
    assert!(setup > cases.len(), "the counter sees no allocation at all");
    let mut failed = Vec::new();
    for case in &mut cases {
        for k in 0..STEPS {
            case.step(k)
                .unwrap_or_else(|e| panic!("{}: {e}", case.name));
        }
        let before = count();
        for k in STEPS..2 * STEPS {
            if let Err(e) = case.step(k) {
                panic!("{}: {e}", case.name);
            }
        }
        let n = count() - before;
        println!("{}: {n} allocations in {STEPS} steps", case.name);
        if n != 0 {
            failed.push(case.name.clone());
        }
    }
    assert!(failed.is_empty(), "the step path allocates: {failed:?}");
    println!("every step path: 0 allocations");
}
