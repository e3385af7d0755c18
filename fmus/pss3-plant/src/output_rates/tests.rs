//! The derivatives along the motion, all outputs at once and stored per point, are those
//! of one output at a time (the way they were computed before the cache) to the last
//! bit: the vector differences do per component the same floating-point operations in
//! the same order as the scalar ones.

use super::*;
use crate::motion_cache::ALONG;

/// A started plant away from rest, tilted, driven by every kind of input.
fn moving() -> Pss3Plant {
    let state = robofmu_dynamics::pss3::dynamics::PlantState {
        euler: Vector3::new(0.05, -0.04, 2.35),
        omega: Vector3::new(0.3, -0.5, 0.8),
    };
    let mut m = Pss3Plant {
        state,
        ..Default::default()
    };
    m.inputs.forces = Vector3::new(20.0, -5.0, 12.0);
    m.inputs.commanded_torque = Vector3::new(0.1, 0.2, -0.3);
    m.inputs.generalized_force = Vector3::new(-0.2, 0.1, 0.05);
    m.inputs.disturbance_torque = Vector3::new(0.01, -0.02, 0.03);
    m.started = true;
    m.computed = m.compute();
    m
}

/// Every output element differentiated along the motion.
fn along_outputs() -> Vec<(Output, usize)> {
    let vectors = VECTORS.iter().flat_map(|&v| [(v, 0), (v, 1), (v, 2)]);
    SCALARS.map(|s| (s, 0)).into_iter().chain(vectors).collect()
}

/// Element `i` of `output` alone along the motion, order 1 and 2 (one local motion per
/// output).
fn one_at_a_time(m: &Pss3Plant, (output, i): (Output, usize)) -> [f64; 2] {
    let k = slot(output, i).unwrap();
    let motion = m.plant.as_ref().unwrap().local_motion(&m.state, &m.inputs);
    motion
        .unwrap()
        .derivatives(|x| m.compute_at(x).map(|c| samples(&c)[k]))
        .unwrap()
}

#[test]
fn all_at_once_equals_one_at_a_time_bit_for_bit() {
    let m = moving();
    let outputs = along_outputs();
    assert_eq!(outputs.len(), ALONG);
    for (output, i) in outputs {
        let expected = one_at_a_time(&m, (output, i));
        for order in [1, 2] {
            let got = along_motion(&m, output, i, order).unwrap();
            let want = expected[order as usize - 1];
            let what = format!("{output:?} element {i} order {order}");
            assert_eq!(got.to_bits(), want.to_bits(), "{what}");
        }
    }
}

/// Order 1 and 2 of every output differentiated along the motion, as bit patterns.
fn along_bits(m: &Pss3Plant) -> Vec<u64> {
    let orders = along_outputs()
        .into_iter()
        .flat_map(|(output, i)| [(output, i, 1), (output, i, 2)]);
    orders
        .map(|(output, i, order)| along_motion(m, output, i, order).unwrap().to_bits())
        .collect()
}

#[test]
fn a_parameter_alone_changes_the_point() {
    // Expected: a plant built with the other slider mass from the start (nothing
    // stored); the state and inputs stay bit for bit the same, so only the
    // parameters tell the two points apart.
    let mut m = moving();
    let first = along_bits(&m);
    m.params.inertia.slider_mass *= 1.5;
    m.rebuild();
    m.computed = m.compute();
    let mut fresh = moving();
    fresh.params = m.params;
    fresh.rebuild();
    fresh.computed = fresh.compute();
    let expected = along_bits(&fresh);
    assert_ne!(expected, first);
    assert_eq!(along_bits(&m), expected);
}
