//! Speed of the 3-PSS kinematics at a mid-workspace pose: closed-form IK, the
//! Jacobian, and Newton forward kinematics from a seed 1 mm of actuator travel away.

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Vector3;
use robofmu::pss3::{
    FkOptions, Geometry, forward_kinematics as fk, inverse_kinematics, jacobian, start_pose,
};
use std::hint::black_box;

fn kinematics(c: &mut Criterion) {
    let g = Geometry::default();
    let options = FkOptions::default();
    let l = Vector3::new(0.06, 0.09, 0.12);
    let pose = fk(&g, &l, &start_pose(), &options).unwrap().assembly;
    // The near seed: the pose of actuators 1 mm away, as in a path or a neighbour scan.
    let near = Vector3::new(0.061, 0.089, 0.121);
    let seed = fk(&g, &near, &start_pose(), &options)
        .unwrap()
        .assembly
        .euler;

    c.bench_function("pss3 ik", |b| {
        b.iter(|| inverse_kinematics(&g, black_box(&pose.euler)))
    });
    c.bench_function("pss3 jacobian", |b| {
        b.iter(|| jacobian(&g, black_box(&pose)))
    });
    c.bench_function("pss3 fk near seed", |b| {
        b.iter(|| fk(&g, black_box(&l), black_box(&seed), &options))
    });
    c.bench_function("pss3 fk from start pose", |b| {
        b.iter(|| fk(&g, black_box(&l), &start_pose(), &options))
    });
}

criterion_group!(benches, kinematics);
criterion_main!(benches);
