//! Nothing allocated by an instance survives fmi2FreeInstance (issue 12: the variable
//! table used to be built once per load into a static and never freed, so every
//! dlopen / instantiate / free / dlclose cycle leaked it).
//!
//! Truth: a counting global allocator; the live heap bytes of the test's thread (the
//! FMU runs entirely in the calling thread; the test harness's own threads are not
//! counted) after instantiate, a simulation step, an FMU state and free equal those
//! before. The first instantiation in a library builds the variable index its
//! instances share (`core/shared.rs`, released when the library is unloaded: the
//! hostile suite's dlopen / dlclose cycles and memcheck check that), so the count
//! starts after a first cycle.

use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::instantiate;
use robofmu_pss3_plant_fmu::Pss3Plant;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

struct Counting;

thread_local! {
    /// Live bytes allocated by this thread (const-initialized: no allocation itself).
    static LIVE: Cell<isize> = const { Cell::new(0) };
}

fn count(delta: isize) {
    LIVE.with(|live| live.set(live.get() + delta));
}

fn live() -> isize {
    LIVE.with(Cell::get)
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        count(layout.size() as isize);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        count(-(layout.size() as isize));
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        count(new_size as isize - layout.size() as isize);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static ALLOCATOR: Counting = Counting;

/// One instantiate / initialize / step / FMU state / free cycle; the FMU state is
/// freed by the host or, if `keep_state`, left to fmi2FreeInstance.
fn cycle(keep_state: bool) {
    let instance = instantiate::<Pss3Plant>(
        FMI2_CO_SIMULATION,
        "{66933d5c-c82b-4e7e-aaa5-b9c59a30f4c0}",
        false,
    )
    .unwrap_or_else(|env| panic!("{}", env.take_log()));
    let c = instance.c;
    unsafe {
        assert_eq!(
            api::setup_experiment::<Pss3Plant>(c, 0, 0.0, 0.0, 0, 0.0),
            Fmi2Status::Ok
        );
        assert_eq!(
            api::enter_initialization_mode::<Pss3Plant>(c),
            Fmi2Status::Ok
        );
        assert_eq!(
            api::exit_initialization_mode::<Pss3Plant>(c),
            Fmi2Status::Ok
        );
        assert_eq!(
            api::do_step::<Pss3Plant>(c, 0.0, 1e-3, FMI2_TRUE),
            Fmi2Status::Ok
        );
        let (vr, mut value) = (151u32, 0.0);
        assert_eq!(
            api::get_real::<Pss3Plant>(c, &vr, 1, &mut value),
            Fmi2Status::Ok
        );
        let mut state: Fmi2FmuState = std::ptr::null_mut();
        assert_eq!(
            api::get_fmu_state::<Pss3Plant>(c, &mut state),
            Fmi2Status::Ok
        );
        if !keep_state {
            assert_eq!(
                api::free_fmu_state::<Pss3Plant>(c, &mut state),
                Fmi2Status::Ok
            );
        }
    }
    drop(instance); // fmi2FreeInstance
}

#[test]
fn free_instance_releases_everything_the_instance_allocated() {
    cycle(false); // builds the library's shared index
    let before = live();
    cycle(false);
    let after_one = live();
    cycle(true);
    cycle(false);
    let after_three = live();
    assert_eq!(after_one - before, 0, "bytes still allocated after a free");
    assert_eq!(
        after_three - before,
        0,
        "bytes still allocated after three cycles (one left its FMU state to the free)"
    );
}
