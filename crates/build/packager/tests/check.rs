//! The checked-in descriptions (modelDescription/, modelDescription/fmi3/,
//! modelDescription/fmi3-scalar/) equal what every FMU's cdylib generates: the
//! packager's `--check`, run over the cdylibs cargo built for this test's profile
//! (`cargo test --workspace` builds them). The expected value is the checked-in file
//! itself, reviewed when it was regenerated with `--update`.

use std::process::Command;

fn packager(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_robofmu-packager"))
        .args(args)
        .current_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../../.."))
        .output()
        .expect("the packager runs")
}

#[test]
fn every_checked_in_description_matches_the_code() {
    let out = packager(&["--check"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{stderr}");
    let stdout = String::from_utf8_lossy(&out.stdout);
    let fmus = std::fs::read_dir(concat!(env!("CARGO_MANIFEST_DIR"), "/../../../fmus"))
        .unwrap()
        .filter(|e| e.as_ref().unwrap().path().join("Cargo.toml").is_file())
        .count();
    // Expected: one line for all FMU crates, as many as there are crates in fmus/.
    assert_eq!(
        stdout.trim(),
        format!("{fmus} FMUs: every checked-in description matches the code")
    );
}

#[test]
fn a_wrong_argument_is_refused_with_the_usage_and_exit_2() {
    // Expected: the user-error contract (one line, exit 2, no panic).
    let out = packager(&["--chek"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "robofmu-packager: usage: robofmu-packager [--out DIR] [--platforms TUPLE,...] \
         | --check | --update (from the repository root)\n"
    );
}

#[test]
fn an_unknown_platform_is_refused_with_the_known_ones_and_exit_2() {
    // Expected: the user-error contract, naming the flag and the five FMI 3.0 tuples.
    let out = packager(&["--platforms", "x86_64-linux,sparc-solaris"]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        String::from_utf8_lossy(&out.stderr),
        "robofmu-packager: --platforms: unknown platform \"sparc-solaris\"; use one of \
         x86_64-linux, aarch64-linux, x86_64-windows, x86_64-darwin, aarch64-darwin\n"
    );
}

#[test]
fn an_fmu_crate_without_its_built_cdylib_is_named_with_the_fix_and_exit_2() {
    // Expected: the packager run in a repository whose only FMU crate was never built
    // names the cdylib it looked for, the crate and the build command.
    let root = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("packager-unbuilt");
    std::fs::create_dir_all(root.join("fmus/ghost")).unwrap();
    std::fs::write(
        root.join("fmus/ghost/Cargo.toml"),
        "[package]\nname = \"robofmu-ghost-fmu\"\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_robofmu-packager"))
        .arg("--check")
        .current_dir(&root)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.contains("librobofmu_ghost_fmu.so: cannot load ("),
        "{stderr}"
    );
    assert!(
        stderr.ends_with(
            "build it with `cargo build --release --workspace` \
             (FMU crate ./fmus/ghost/Cargo.toml)\n"
        ),
        "{stderr}"
    );
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
}
