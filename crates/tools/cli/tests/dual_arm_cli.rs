//! The `robofmu dual-arm` command end to end: the binary's output and its errors.

#[test]
fn cli_prints_pi_last_and_fails_with_a_message() {
    let run = |args: &[&str]| {
        std::process::Command::new(env!("CARGO_BIN_EXE_robofmu"))
            .args(args)
            .output()
            .unwrap()
    };
    let ok = run(&[
        "dual-arm",
        "solve",
        "--lock",
        "2",
        "--path",
        "B",
        "--intervals",
        "20",
    ]);
    assert!(ok.status.success());
    let stdout = String::from_utf8(ok.stdout).unwrap();
    let last = stdout.lines().last().unwrap();
    // The value is the lock-2 PI of the shooting test in crates/tools/analyses/tests/dual_arm.rs
    // (1.344570 rad^2/s).
    assert!(last.starts_with("PI = 1.34457"), "{last}");
    assert!(last.contains("iterations = ") && last.contains("residual = "));
    // The default method names its search and its local-minimum checks.
    assert!(
        stdout.contains("multi-start shooting: 10 starts"),
        "{stdout}"
    );
    assert!(
        stdout.contains("returned path is a local minimum")
            && stdout.contains("second-order check passed")
            && stdout.contains("neighbourhood check passed"),
        "{stdout}"
    );
    let bad = run(&[
        "dual-arm", "solve", "--lock", "1", "--path", "B", "--guess", "0.5",
    ]);
    // Truth: lock 1 has two redundant joints (theta_R2, theta_L2); a usage error is exit 2.
    assert_eq!(bad.status.code(), Some(2));
    assert!(
        String::from_utf8(bad.stderr)
            .unwrap()
            .contains("--guess needs 2 values")
    );
}
