//! The FMUs link what they run and nothing of the robot library's scenario reader or
//! analyses (issue 34): `cargo tree -e normal` of every FMU crate names none of toml,
//! serde, rayon or ode_solvers (which needs serde; it is a dev-dependency of this crate
//! only, so it never reaches an FMU). Truth: the crate graph as cargo resolves it.

use std::path::Path;
use std::process::Command;

const FMUS: [&str; 4] = [
    "robofmu-pss3-plant-fmu",
    "robofmu-computed-torque-fmu",
    "robofmu-pid-fmu",
    "robofmu-planner-fmu",
];

const FORBIDDEN: [&str; 5] = ["toml", "serde", "serde_core", "rayon", "ode_solvers"];

#[test]
fn no_fmu_links_toml_serde_or_rayon() {
    let workspace = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../Cargo.toml");
    for fmu in FMUS {
        let out = Command::new(env!("CARGO"))
            .args(["tree", "-q", "-e", "normal", "--prefix", "none", "-p", fmu])
            .arg("--manifest-path")
            .arg(&workspace)
            .output()
            .expect("cargo runs");
        assert!(
            out.status.success(),
            "cargo tree -p {fmu}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
        let tree = String::from_utf8(out.stdout).unwrap();
        let crates: Vec<&str> = tree.lines().filter_map(|l| l.split(' ').next()).collect();
        println!("{fmu}: {} lines", crates.len());
        assert!(
            crates.contains(&fmu),
            "{fmu} missing from its own tree:\n{tree}"
        );
        for name in FORBIDDEN {
            assert!(!crates.contains(&name), "{fmu} links {name}:\n{tree}");
        }
    }
}
