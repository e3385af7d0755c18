//! The scripting interface: `robofmu dexterity max-lci` and `gci` print one line on
//! stdout, the number first and then the manipulator and working mode it refers to;
//! errors go to stderr with a non-zero exit code.

use std::process::Command;

fn robofmu(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_robofmu"))
        .args(args)
        .output()
        .expect("run robofmu")
}

fn number(out: &std::process::Output) -> f64 {
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout.clone()).unwrap();
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(text.contains("mode"), "the mode is not named: {text}");
    text.split_whitespace()
        .next()
        .and_then(|t| t.parse().ok())
        .unwrap_or_else(|| panic!("not a number first: {text:?}"))
}

#[test]
fn max_lci_prints_the_paper_figure_for_the_serial_arm() {
    // Paper: 0.2595 at phi = 10 deg over x, y in [-20, 20] cm; within 1 %.
    let v = number(&robofmu(&[
        "dexterity",
        "max-lci",
        "--robot",
        "1rrr",
        "--phi",
        "10",
    ]));
    assert!((v / 0.2595 - 1.0).abs() < 0.01, "{v}");
}

#[test]
fn max_lci_prints_the_paper_figure_for_the_3rrr_on_a_2_cm_grid_in_mode_4() {
    // Paper: 0.5038; see crates/tools/analyses/tests/dexterity_reproduction.rs for the reading.
    let args = [
        "dexterity",
        "max-lci",
        "--robot",
        "3rrr",
        "--phi",
        "10",
        "--grid",
        "21",
        "--mode",
        "4",
    ];
    assert_eq!(number(&robofmu(&args)), 0.5038);
}

#[test]
fn serial_max_lci_over_own_workspace_does_not_depend_on_phi() {
    // Rotation invariance about the base: the own-workspace maximum is the same at every
    // phi, up to the grid (here 0.28 cm over the 90 cm square; in one fixed mode the
    // 161-point grid's 0.56 cm leaves 2e-4).
    let at = |phi: &str| {
        number(&robofmu(&[
            "dexterity",
            "max-lci",
            "--robot",
            "1rrr",
            "--phi",
            phi,
            "--workspace",
            "own",
            "--grid",
            "321",
        ]))
    };
    assert!((at("10") - at("135")).abs() < 2e-4);
}

#[test]
fn gci_prints_a_number_in_the_unit_interval() {
    let out = robofmu(&[
        "dexterity",
        "gci",
        "--robot",
        "2rrr",
        "--cells",
        "30",
        "--phi-cells",
        "17",
    ]);
    let v = number(&out);
    assert!(v > 0.0 && v < 1.0, "{v}");
}

#[test]
fn unknown_robot_is_an_error_on_stderr() {
    let out = robofmu(&["dexterity", "max-lci", "--robot", "4rrr", "--phi", "10"]);
    assert!(!out.status.success());
    assert!(out.stdout.is_empty());
    assert!(String::from_utf8_lossy(&out.stderr).contains("unknown robot"));
}

#[test]
fn missing_working_mode_is_an_error_on_stderr() {
    // The 2-RRR has four working modes (0 to 3).
    let out = robofmu(&[
        "dexterity",
        "max-lci",
        "--robot",
        "2rrr",
        "--phi",
        "10",
        "--mode",
        "4",
    ]);
    assert!(!out.status.success());
    assert!(out.stdout.is_empty());
    assert!(String::from_utf8_lossy(&out.stderr).contains("working modes 0 to 3"));
}

#[test]
fn workspace_command_prints_the_serial_disc_area_and_writes_files() {
    // With l1 = l2 = 15 cm the 1-RRR reaches a disc of radius 30 cm at every phi:
    // pi 30^2 = 2827 cm^2; a 181 x 181 grid (0.5 cm cells) counts it within 1 %.
    let dir = std::env::temp_dir().join(format!("robofmu-dex-ws-{}", std::process::id()));
    let out = robofmu(&[
        "dexterity",
        "workspace",
        "--phi",
        "30",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = String::from_utf8(out.stdout).unwrap();
    let line = text.lines().find(|l| l.starts_with("1rrr")).unwrap();
    let area: f64 = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!(
        (area / (std::f64::consts::PI * 900.0) - 1.0).abs() < 0.01,
        "{area}"
    );
    let csv = std::fs::read_to_string(dir.join("workspace-phi30.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1 + 181 * 181);
    let png = std::fs::read(dir.join("workspace-phi30.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    std::fs::remove_dir_all(&dir).unwrap();
}
