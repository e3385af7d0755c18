//! Cost of one state-derivative evaluation of the 3-PSS plant (the Model Exchange and
//! integrator inner loop), and of the Co-Simulation step and linearisation around it.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Vector3;
use robofmu::pss3::dynamics::{Plant, PlantInputs, PlantParams, PlantState, StepSettings};
use std::hint::black_box;

fn plant_benchmarks(c: &mut Criterion) {
    let plant = Plant::new(PlantParams::default()).expect("default parameters are valid");
    let state = PlantState {
        euler: Vector3::new(0.06, -0.04, 2.35),
        omega: Vector3::new(0.4, -0.9, 1.3),
    };
    let inputs = PlantInputs {
        forces: Vector3::new(25.0, -8.0, 14.0),
        disturbance_torque: Vector3::new(0.3, -0.2, 0.5),
        commanded_torque: Vector3::zeros(),
        generalized_force: Vector3::zeros(),
    };
    c.bench_function("pss3 derivative", |b| {
        b.iter(|| plant.derivative(black_box(&state), black_box(&inputs)))
    });
    c.bench_function("pss3 linearize", |b| {
        b.iter(|| plant.linearize(black_box(&state), black_box(&inputs)))
    });
    let settings = StepSettings::default();
    c.bench_function("pss3 advance 10 ms (Dopri5, 1e-8)", |b| {
        b.iter(|| plant.advance(black_box(&state), black_box(&inputs), 0.01, &settings))
    });
}

criterion_group!(benches, plant_benchmarks);
criterion_main!(benches);
