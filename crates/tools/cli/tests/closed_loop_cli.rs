//! `robofmu closed-loop reference`: the cross-check CSV and options file it writes for an
//! expanded scenario (the multi-segment three_axis_waypoints, 3 s at 1 ms).

use std::path::{Path, PathBuf};
use std::process::Command;

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../..")
}

fn table(text: &str) -> (Vec<String>, Vec<Vec<f64>>) {
    let mut lines = text.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(str::to_string)
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    (header, rows)
}

#[test]
fn reference_writes_every_nth_sample_and_the_options_of_the_scenario() {
    let dir = std::env::temp_dir().join(format!("robofmu-cl-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("w_ref.csv");
    let scenario = root().join("tests/scenarios/expanded/three_axis_waypoints.toml");
    let o = Command::new(env!("CARGO_BIN_EXE_robofmu"))
        .args([
            "closed-loop",
            "reference",
            "--every",
            "10",
            "--tolerance",
            "1e-11",
        ])
        .arg("--scenario")
        .arg(&scenario)
        .arg("--out")
        .arg(&out)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // Truth: 3 s / 1 ms = 3000 steps, 3001 samples; every 10th from 0 is 301 rows at
    // t = 0.01 k; 33 signals (11 vectors of 3) after the time.
    assert!(
        stdout.contains("3001 samples") && stdout.contains("301 written"),
        "{stdout}"
    );
    let (header, rows) = table(&std::fs::read_to_string(&out).unwrap());
    assert_eq!(header.len(), 34);
    assert_eq!(
        (header[0].as_str(), header[1].as_str()),
        ("\"time\"", "\"planner.q[1]\"")
    );
    assert_eq!(rows.len(), 301);
    for (k, r) in rows.iter().enumerate() {
        assert!(
            (r[0] - 0.01 * k as f64).abs() < 1e-12,
            "row {k}: t = {}",
            r[0]
        );
    }
    // Truth: the scenario's first waypoint, -5, 3, 132 deg, is the plan at t = 0.
    for (i, deg) in [-5.0f64, 3.0, 132.0].iter().enumerate() {
        assert!((rows[0][1 + i] - deg.to_radians()).abs() < 1e-15);
    }
    let options = std::fs::read_to_string(dir.join("w_ref.opt")).unwrap();
    assert_eq!(
        options,
        "StartTime, 0\nStopTime, 3\nStepSize, 0.001\nRelTol, 1e-11\n"
    );
    // Truth: the committed reference the co-simulation is checked against in CI
    // (tests/python, FMPy): the command still writes it (angles to 1e-12 rad).
    let stored = root()
        .join("tests/closed_loop_references/three_axis_waypoints/three_axis_waypoints_ref.csv");
    let (stored_header, stored_rows) = table(&std::fs::read_to_string(stored).unwrap());
    assert_eq!(stored_header, header);
    let worst = rows
        .iter()
        .zip(&stored_rows)
        .flat_map(|(a, b)| (10..13).map(move |c| (a[c] - b[c]).abs()))
        .fold(0.0, f64::max);
    assert!(
        worst < 1e-12,
        "plant.theta off the stored reference by {worst:e} rad"
    );
    std::fs::remove_dir_all(&dir).unwrap();
}
