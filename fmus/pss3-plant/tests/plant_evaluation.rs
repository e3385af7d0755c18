//! The plant through the core's computed values: reads and directional derivatives
//! where the pose cannot assemble (Discard, not Error), and directional derivatives
//! for a whole seed vector in one call.

use robofmu_fmi::fmi2::api;
use robofmu_fmi::fmi2::types::*;
use robofmu_fmi_testing::{Host, vr};
use robofmu_pss3_plant_fmu::Pss3Plant;

type H = Host<Pss3Plant>;

/// A tilted, moving state inside the stroke (l about 47, 73, 95 mm).
const THETA: [f64; 3] = [0.05, -0.04, 2.35];
const OMEGA: [f64; 3] = [0.3, -0.5, 0.8];

/// Model Exchange, initialized (at the tilted state if `tilt`), in continuous-time mode.
fn continuous(tilt: bool) -> H {
    let h = H::new(FMI2_MODEL_EXCHANGE);
    if tilt {
        h.set_vector("theta0", THETA);
        h.set_vector("omega0", OMEGA);
    }
    assert_eq!(h.initialize(), Fmi2Status::Ok, "{}", h.last_message());
    h.enter_continuous_time_mode();
    h
}

fn vrs(names: &[&str]) -> Vec<u32> {
    names.iter().map(|n| vr::<Pss3Plant>(n)).collect()
}

/// fmi2GetDirectionalDerivative of `unknowns` along `seed` over `knowns`.
fn directional(h: &H, unknowns: &[u32], knowns: &[u32], seed: &[f64]) -> (Fmi2Status, Vec<f64>) {
    let mut out = vec![0.0; unknowns.len()];
    let status = unsafe {
        api::get_directional_derivative::<Pss3Plant>(
            h.c,
            unknowns.as_ptr(),
            unknowns.len(),
            knowns.as_ptr(),
            knowns.len(),
            seed.as_ptr(),
            out.as_mut_ptr(),
        )
    };
    (status, out)
}

#[test]
fn reads_and_directional_derivatives_discard_where_the_pose_cannot_assemble() {
    // Truth (issue 12): at thy = 0.351832 rad (20.2 deg) the legs cannot reach the
    // platform from the default start pose's roll, and fmi2GetDerivatives already
    // returns fmi2Discard there; a dependent output and a directional derivative must
    // say the same, not fmi2Error.
    let h = continuous(false);
    let mut x = h.states();
    x[1] = 0.351832;
    assert_eq!(h.set_states(&x), Fmi2Status::Ok);
    assert_eq!(h.derivatives().0, Fmi2Status::Discard);
    for name in ["l[1]", "detJ", "thetaDot[2]", "gravityCompensation[3]"] {
        let (status, _) = h.real_at(vr::<Pss3Plant>(name));
        assert_eq!(status, Fmi2Status::Discard, "{name}: {}", h.last_message());
        assert!(
            h.last_message().contains("fmi2GetReal"),
            "{}",
            h.last_message()
        );
    }
    let (status, _) = directional(&h, &vrs(&["der(omega[1])"]), &vrs(&["theta[1]"]), &[1.0]);
    assert_eq!(status, Fmi2Status::Discard, "{}", h.last_message());
    // The state itself is readable (it is not computed), and the instance is usable.
    assert_eq!(h.real("theta[2]"), 0.351832);
    x[1] = 0.0;
    assert_eq!(h.set_states(&x), Fmi2Status::Ok);
    assert_eq!(h.real("theta[2]"), 0.0);
    assert!(h.real("l[1]") > 0.0);
}

#[test]
fn one_call_with_a_seed_vector_equals_the_sum_of_single_columns() {
    // Truth: the directional derivative is linear in the seed, J v = sum_j v_j J e_j
    // (second formulation: one call per column), for linearized rows, exact rows and
    // finite-difference rows alike.
    let h = continuous(true);
    assert_eq!(h.set_real("actuatorForce[2]", 15.0), Fmi2Status::Ok);
    let unknowns = vrs(&[
        "der(theta[1])",
        "der(omega[3])",
        "omegaDot[2]",
        "theta[2]",
        "pitch",
        "l[1]",
        "lDot[3]",
        "force[2]",
        "condJ",
        "kineticEnergy",
    ]);
    let knowns = vrs(&[
        "theta[1]",
        "theta[2]",
        "omega[3]",
        "actuatorForce[1]",
        "torqueCommand[2]",
        "generalizedForceCommand[3]",
    ]);
    let seed = [0.7, -1.3, 0.4, 2.0, -0.5, 1.1];
    let (status, together) = directional(&h, &unknowns, &knowns, &seed);
    assert_eq!(status, Fmi2Status::Ok, "{}", h.last_message());
    let mut summed = vec![0.0; unknowns.len()];
    for (k, s) in knowns.iter().zip(seed) {
        let (status, column) = directional(&h, &unknowns, &[*k], &[1.0]);
        assert_eq!(status, Fmi2Status::Ok);
        for (sum, c) in summed.iter_mut().zip(column) {
            *sum += s * c;
        }
    }
    for ((u, a), b) in unknowns.iter().zip(&together).zip(&summed) {
        assert!(
            (a - b).abs() <= 1e-12 * (1.0 + b.abs()),
            "value reference {u}: {a} in one call, {b} column by column"
        );
    }
    // Not trivially zero: der(theta[1]) along theta/omega and the lever arms move.
    assert!(
        together.iter().filter(|v| v.abs() > 1e-6).count() >= 8,
        "{together:?}"
    );
}

#[test]
fn a_co_simulation_instance_continues_from_a_model_exchange_state() {
    // Decision (issue 12): accepted. An FMU state holds the parameters, inputs,
    // continuous states, contact flags and time, which mean the same in both
    // interfaces; the interface itself is the instance's, not the state's.
    // Truth (second formulation): the CS instance restored from an ME state moved
    // off the initial pose steps exactly as a CS instance initialized at that pose.
    let me = continuous(true);
    let moved_theta = [0.06, -0.03, 2.36];
    let mut x = me.states();
    x[..3].copy_from_slice(&moved_theta);
    assert_eq!(me.set_states(&x), Fmi2Status::Ok);
    me.handle_event();
    let bytes = me.serialize();

    let restored = H::new(FMI2_CO_SIMULATION);
    assert_eq!(restored.initialize(), Fmi2Status::Ok);
    assert_eq!(
        restored.restore(&bytes),
        Fmi2Status::Ok,
        "{}",
        restored.last_message()
    );
    let direct = H::new(FMI2_CO_SIMULATION);
    direct.set_vector("theta0", moved_theta);
    direct.set_vector("omega0", OMEGA);
    assert_eq!(direct.initialize(), Fmi2Status::Ok);
    for h in [&restored, &direct] {
        assert_eq!(h.step(0.0, 1e-3), Fmi2Status::Ok, "{}", h.last_message());
    }
    for name in ["theta", "omega", "l", "force"] {
        assert_eq!(restored.vector(name), direct.vector(name), "{name}");
    }
    assert!(
        restored.vector("theta") != moved_theta,
        "the step moved nothing"
    );
}
