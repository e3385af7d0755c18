//! PID vs computed torque at equal bandwidth on the thesis's path 1 and the three-axis
//! motions, and computed torque with its model off by +-20 % in leg mass and in
//! platform inertia: the table of docs/computed-torque.md.
//!
//! Run: `cargo run --release --example computed_torque_table`. Every run is the Rust
//! reference loop (one ODE, Dop853 at tolerance 1e-10) of a scenario in
//! tests/scenarios/expanded/; the computed-torque runs replace its PID by the law with
//! poles at the PID design's -30 rad/s.

use robofmu::closed_loop::{
    Controller, LoopError, LoopSpec, Tracking, parse_loop_scenario, simulate, tracking,
};
use robofmu::computed_torque::{ComputedTorque, pole_placement};
use robofmu::pss3::dynamics::PlantParams;
use std::path::Path;

/// The bandwidth the PID scenarios were designed at (their [gains] omega), rad/s.
const BANDWIDTH: f64 = 30.0;
const TOLERANCE: f64 = 1e-10;
const SCENARIOS: [&str; 6] = [
    "regulation",
    "path1_cubic",
    "path1_quintic",
    "three_axis_cubic",
    "three_axis_quintic",
    "three_axis_waypoints",
];

/// The controller's model: the nominal robot with the leg mass and the platform inertia
/// (about its centre of mass, so the tensor stays physical) scaled.
fn model(leg_mass: f64, platform_inertia: f64) -> PlantParams {
    let mut p = PlantParams::default();
    p.inertia.leg_mass *= leg_mass;
    let about_com = p.inertia.platform_inertia_about_com();
    p.inertia.platform_inertia += (platform_inertia - 1.0) * about_com;
    p
}

fn run(spec: &LoopSpec) -> Result<Tracking, LoopError> {
    Ok(tracking(&simulate(spec, TOLERANCE)?))
}

fn computed_torque(
    spec: &LoopSpec,
    model: PlantParams,
    integral: bool,
) -> Result<Tracking, Box<dyn std::error::Error>> {
    let gains = [pole_placement(BANDWIDTH, integral)?; 3];
    let law = ComputedTorque::new(model, gains)?;
    let spec = LoopSpec {
        controller: Controller::ComputedTorque(Box::new(law)),
        ..spec.clone()
    };
    Ok(run(&spec)?)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mismatches = [(0.8, 1.0), (1.2, 1.0), (1.0, 0.8), (1.0, 1.2)];
    println!(
        "| scenario | controller | RMS error, deg | max error, deg | peak force, N | \
         RMS error, deg, model: leg mass x0.8 / x1.2, platform inertia x0.8 / x1.2 |"
    );
    println!("|---|---|---|---|---|---|");
    for name in SCENARIOS {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/scenarios/expanded")
            .join(format!("{name}.toml"));
        let spec = parse_loop_scenario(&std::fs::read_to_string(path)?)?;
        let pid = run(&spec)?;
        print_row(name, "PID (plant's G_x feedforward)", &pid, "model-free");
        for (label, integral) in [
            ("computed torque, PD", false),
            ("computed torque, PID", true),
        ] {
            let nominal = computed_torque(&spec, model(1.0, 1.0), integral)?;
            let mut off = Vec::new();
            for (legs, platform) in mismatches {
                let t = computed_torque(&spec, model(legs, platform), integral)?;
                off.push(format!("{:.2e}", t.rms_error.to_degrees()));
            }
            print_row(name, label, &nominal, &off.join(" / "));
        }
    }
    Ok(())
}

fn print_row(name: &str, controller: &str, t: &Tracking, mismatch: &str) {
    println!(
        "| {name} | {controller} | {:.2e} | {:.2e} | {:.3} | {mismatch} |",
        t.rms_error.to_degrees(),
        t.max_error.to_degrees(),
        t.peak_force
    );
}
