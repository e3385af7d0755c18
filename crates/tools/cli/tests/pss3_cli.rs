//! The `robofmu pss3` command line: printouts in labelled degrees, CSV in SI, errors on
//! stderr with a non-zero exit code.

use std::process::{Command, Output};

fn robofmu(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_robofmu"))
        .args(args)
        .output()
        .expect("the robofmu binary runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

#[test]
fn ik_then_fk_round_trip_through_the_printout() {
    // Truth: FK of the printed IK displacements returns the orientation given to IK.
    let ik = robofmu(&["pss3", "ik", "--angles", "-5,3,135"]);
    assert!(ik.status.success());
    let text = stdout(&ik);
    let line = text.lines().find(|l| l.starts_with("actuators:")).unwrap();
    let l: Vec<&str> = line
        .split(['=', ','])
        .filter_map(|s| s.trim().strip_suffix(" m"))
        .collect();
    assert_eq!(l.len(), 3, "{line}");
    let fk = robofmu(&["pss3", "fk", "--l", &l.join(",")]);
    assert!(fk.status.success());
    // 6 decimals in metres (1 um) pin the angles to about 1e-3 deg.
    let expected = "thx = -5.000";
    assert!(stdout(&fk).contains(expected), "{}", stdout(&fk));
    assert!(stdout(&fk).contains("thz (roll) = 135.00"));
}

#[test]
fn bad_input_is_an_error_on_stderr() {
    for args in [
        vec!["pss3", "ik", "--angles", "0,0,90"],
        vec!["pss3", "fk", "--l", "0.2,0.1,0.1"],
        vec!["pss3", "ik", "--angles", "1,2"],
    ] {
        let o = robofmu(&args);
        assert!(!o.status.success(), "{args:?}");
        assert!(o.stdout.is_empty());
        assert!(String::from_utf8_lossy(&o.stderr).starts_with("robofmu: "));
    }
}

#[test]
fn actuator_path_writes_si_csv() {
    // Truth: the linear drive's own numbers: 26 samples over 1 s at 0.04 s, first row
    // at t = 0 with l = 2 mm and l_dot = 0.15 m / 1 s.
    let file = std::env::temp_dir().join(format!("robofmu-path-{}.csv", std::process::id()));
    let path = file.to_str().unwrap();
    let o = robofmu(&[
        "pss3",
        "actuator-path",
        "--l0",
        "0.002,0.002,0.002",
        "--lf",
        "0.152,0.152,0.152",
        "--duration",
        "1",
        "--dt",
        "0.04",
        "--out",
        path,
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&file).unwrap();
    std::fs::remove_file(&file).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header.len(), 16);
    assert_eq!(header[0], "\"time_s\"");
    assert_eq!(header[15], "\"omega_dot_z_rad_per_s2\"");
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.len(), 26);
    assert_eq!(rows[0][0], 0.0);
    assert!((rows[0][1] - 0.002).abs() < 1e-12 && (rows[0][4] - 0.15).abs() < 1e-12);
    assert_eq!(rows[25][0], 1.0);
}

/// Runs `robofmu pss3 plant-reference [extra] --out-dir <tmp>` and checks that every file
/// equals the checked-in case `tests/references/Pss3Plant/<case>` byte for byte; returns
/// the output directory (removed by the caller).
fn regenerate_plant_case(case: &str, extra: &[&str]) -> std::path::PathBuf {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../..");
    let out = std::env::temp_dir().join(format!("robofmu-{case}-{}", std::process::id()));
    let mut args = vec!["pss3", "plant-reference"];
    args.extend_from_slice(extra);
    args.extend_from_slice(&["--out-dir", out.to_str().unwrap()]);
    let run = robofmu(&args);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let checked_in = root.join("tests/references/Pss3Plant").join(case);
    for file in [
        "Pss3Plant_ref.csv",
        "Pss3Plant_input.csv",
        "Pss3Plant_ref.opt",
        "case.json",
    ] {
        let fresh = std::fs::read(out.join(file)).unwrap();
        let kept = std::fs::read(checked_in.join(file)).unwrap();
        assert!(
            fresh == kept,
            "{file} differs: regenerate with robofmu pss3 plant-reference {}",
            extra.join(" ")
        );
    }
    out
}

#[test]
fn plant_reference_regenerates_the_checked_in_path1_case() {
    // Truth: the checked-in tests/references/Pss3Plant/path1 files were written by this
    // command (kinematics + inverse dynamics); regenerating must give the same bytes.
    let out = regenerate_plant_case("path1", &[]);
    // The spec's path-1 end roll: 154.36 deg at 2 s.
    let reference = std::fs::read_to_string(out.join("Pss3Plant_ref.csv")).unwrap();
    let last = reference.lines().last().unwrap();
    let roll: f64 = last.split(',').nth(3).unwrap().parse().unwrap();
    assert!((roll.to_degrees() - 154.36).abs() < 0.005, "{roll}");
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn plant_reference_regenerates_the_checked_in_default_pose_case() {
    // Truth: tests/references/Pss3Plant/from_default_pose was written by this command;
    // the case has no start values, so it must start where the FMU's defaults put the
    // plant (roll 2.439784063985299 rad = forward kinematics at 77 mm, at rest) and end
    // at rest (the quintic move has zero rate at both ends).
    let out = regenerate_plant_case("from_default_pose", &["--from-default-pose"]);
    let reference = std::fs::read_to_string(out.join("Pss3Plant_ref.csv")).unwrap();
    let row = |line: &str| -> Vec<f64> { line.split(',').map(|v| v.parse().unwrap()).collect() };
    let first = row(reference.lines().nth(1).unwrap());
    let last = row(reference.lines().last().unwrap());
    assert!((first[3] - 2.439784063985299).abs() < 1e-12, "{first:?}");
    assert!(first[4..].iter().chain(&last[4..]).all(|w| w.abs() < 1e-12));
    std::fs::remove_dir_all(&out).unwrap();
}

#[test]
fn ct_reference_regenerates_the_checked_in_defaults_case() {
    // Truth: tests/references/ComputedTorque/defaults was written by this command
    // (Lagrange's equations at the FMU's defaults); regenerating gives the same bytes.
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../..");
    let out = std::env::temp_dir().join(format!("robofmu-ct-{}", std::process::id()));
    let run = robofmu(&["pss3", "ct-reference", "--out-dir", out.to_str().unwrap()]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let checked_in = root.join("tests/references/ComputedTorque/defaults");
    for file in [
        "ComputedTorque_ref.csv",
        "ComputedTorque_input.csv",
        "ComputedTorque_ref.opt",
        "case.json",
    ] {
        let fresh = std::fs::read(out.join(file)).unwrap();
        let kept = std::fs::read(checked_in.join(file)).unwrap();
        assert!(
            fresh == kept,
            "{file} differs: regenerate with robofmu pss3 ct-reference"
        );
    }
    std::fs::remove_dir_all(out).unwrap();
}
