//! The derivative evaluation allocates nothing (the Model Exchange inner loop and the
//! FMU's real-time path): counted with a wrapping global allocator. This file holds a
//! single test so that no other test allocates concurrently.

use nalgebra::Vector3;
use robofmu::pss3::dynamics::{Plant, PlantInputs, PlantParams, PlantState};
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::SeqCst);
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: forwarded unchanged to the system allocator.
        unsafe { System.dealloc(ptr, layout) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

#[test]
fn derivative_does_not_allocate() {
    // Truth: zero heap allocations over 1000 evaluations, end stops engaged or not,
    // with a commanded torque (the statics solve) and with an error result.
    let plant = Plant::new(PlantParams::default()).unwrap();
    let states = [
        PlantState {
            euler: Vector3::new(0.06, -0.04, 2.35),
            omega: Vector3::new(0.4, -0.9, 1.3),
        },
        PlantState {
            euler: Vector3::new(0.0, 0.0, 110f64.to_radians()),
            omega: Vector3::new(0.0, 0.0, -1.0),
        },
        PlantState {
            euler: Vector3::new(1.05, 0.0, 2.3),
            omega: Vector3::zeros(),
        },
    ];
    let inputs = PlantInputs {
        forces: Vector3::new(25.0, -8.0, 14.0),
        disturbance_torque: Vector3::new(0.3, -0.2, 0.5),
        commanded_torque: Vector3::new(-1.0, 0.5, 2.0),
        generalized_force: Vector3::zeros(),
    };
    let before = ALLOCATIONS.load(Ordering::SeqCst);
    let mut ok = 0;
    for k in 0..1000 {
        ok += usize::from(plant.derivative(&states[k % 3], &inputs).is_ok());
    }
    let allocations = ALLOCATIONS.load(Ordering::SeqCst) - before;
    assert_eq!(ok, 667);
    assert_eq!(allocations, 0);
}
