//! Cost of one best-mode LCI evaluation per manipulator, and of a phi sweep of the
//! largest LCI over the own workspaces (all three manipulators).

use criterion::{Criterion, criterion_group, criterion_main};
use robofmu_analyses::dexterity::sweep::{Region, phi_sweep};
use robofmu_analyses::dexterity::workspace::ModeChoice;
use robofmu_analyses::dexterity::{Manipulator, Pose, Robot, RobotKind};
use std::hint::black_box;

fn lci_evaluation(c: &mut Criterion) {
    let pose = Pose::new(0.10, 0.05, 10f64.to_radians());
    for kind in RobotKind::ALL {
        let robot = Robot::paper(kind);
        c.bench_function(&format!("best_lci_{kind}"), |b| {
            b.iter(|| robot.best_lci(black_box(pose)))
        });
    }
}

fn sweep(c: &mut Criterion) {
    let robots: Vec<Robot> = RobotKind::ALL.iter().map(|&k| Robot::paper(k)).collect();
    // 18 orientations every 10 deg from 10 to 180 deg, 81 x 81 grid per workspace.
    let phis: Vec<f64> = (1..=18).map(|i| (10.0 * i as f64).to_radians()).collect();
    let best = [ModeChoice::Best; 3];
    let mut group = c.benchmark_group("phi_sweep");
    group.sample_size(10);
    group.bench_function("own_18x81x81", |b| {
        b.iter(|| phi_sweep(&robots, &best, black_box(&phis), Region::Own, 81))
    });
    group.finish();
}

criterion_group!(benches, lci_evaluation, sweep);
criterion_main!(benches);
