//! Hostile command lines for every `robofmu` subcommand, written as a person trying to
//! break it would: sizes that exhaust memory or time, NaN and infinities, negative
//! counts, numbers past the integer types, missing and doubled options, unknown
//! values, bad and binary files, directories where files belong, unwritable outputs.
//!
//! Each case runs the binary in an empty working directory of its own and asserts:
//! the exit code (2 for an argument refused before anything runs, 1 for a computation
//! that ran and failed), exactly one line on stderr, `robofmu: ...` naming the argument
//! or file at fault, no panic text, no death by a signal, and no file written outside
//! the output directory (for exit code 2: nothing written at all). The truth for each
//! case is the documented range of the option (`robofmu ... --help`, cli/bounds.rs).

use std::collections::BTreeSet;
use std::fs;
use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::sync::atomic::{AtomicUsize, Ordering};

/// One hostile command line: its arguments, the expected exit code and a text the
/// one-line message must contain (the option or file named).
struct Case {
    args: &'static [&'static str],
    code: i32,
    names: &'static str,
}

const fn case(args: &'static [&'static str], code: i32, names: &'static str) -> Case {
    Case { args, code, names }
}

const PATH: [&str; 6] = [
    "pss3",
    "actuator-path",
    "--l0",
    "0.002,0.002,0.002",
    "--lf",
    "0.152,0.152,0.152",
];

#[rustfmt::skip]
/// Cases that need no prepared files (the working directory starts empty).
const CASES: &[Case] = &[
    // pss3 ik / jacobian / fk
    case(&["pss3", "ik", "--angles", "0,0"], 2, "--angles"),
    case(&["pss3", "ik", "--angles", "NaN,0,130"], 2, "--angles"),
    case(&["pss3", "ik", "--angles", "0,0,inf"], 2, "--angles"),
    case(&["pss3", "ik", "--angles", "0,0,1e999"], 2, "--angles"),
    case(&["pss3", "ik", "--angles", "0,0,13O"], 2, "--angles"),
    case(&["pss3", "ik", "--angles", "0,0,130", "--angles", "1,2,3"], 2, "--angles"),
    case(&["pss3", "ik"], 2, "--angles"),
    case(&["pss3", "ik", "--angles", "90,0,0"], 1, "cannot reach"),
    case(&["pss3", "jacobian", "--angles", ""], 2, "--angles"),
    case(&["pss3", "jacobian", "--angles", "-1e308,-1e308,-1e308"], 1, "leg"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--max-iter", "4294967295", "--tol", "0"], 2, "--max-iter"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--max-iter", "18446744073709551616"], 2, "--max-iter"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--max-iter", "0"], 2, "--max-iter"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--max-iter", "-5"], 2, "--max-iter"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--tol", "NaN"], 2, "--tol"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--tol", "-1"], 2, "--tol"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--tol", "1e400"], 2, "--tol"),
    case(&["pss3", "fk", "--l", "0.05,0.1"], 2, "--l"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--seed", "NaN,0,0"], 2, "--seed"),
    case(&["pss3", "fk", "--l", "5,5,5"], 2, "--l: actuator 1 at 5 m is outside the stroke"),
    case(&["pss3", "fk", "--l", "0.05,0.1,0.15", "--max-iter", "1", "--tol", "0"], 1, "converge"),
    // pss3 actuator-path / plant-reference / workspace
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "2", "--dt", "1e-300", "--out", "out/p.csv"], 2, "--dt"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "2", "--dt", "0", "--out", "out/p.csv"], 2, "--dt"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "2", "--dt", "3", "--out", "out/p.csv"], 2, "--dt"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "NaN", "--dt", "0.1", "--out", "out/p.csv"], 2, "--duration"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "-1", "--dt", "0.1", "--out", "out/p.csv"], 2, "--duration"),
    case(&[PATH[0], PATH[1], "--l0", "0.002,0.002", PATH[4], PATH[5], "--duration", "2", "--dt", "0.1", "--out", "out/p.csv"], 2, "--l0"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], "--lf", "inf,0.1,0.1", "--duration", "2", "--dt", "0.1", "--out", "out/p.csv"], 2, "--lf"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "2", "--dt", "0.1"], 2, "--out"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "2", "--dt", "0.1", "--out", "nodir/p.csv"], 2, "the folder nodir does not exist"),
    case(&[PATH[0], PATH[1], PATH[2], PATH[3], PATH[4], PATH[5], "--duration", "2", "--dt", "0.1", "--out", "."], 2, "that is a folder; give a file name"),
    case(&[PATH[0], PATH[1], "--l0", "0.5,0.5,0.5", PATH[4], PATH[5], "--duration", "2", "--dt", "0.1", "--out", "out/p.csv"], 2, "--l0: actuator 1 at 0.5 m is outside the stroke"),
    // Displacements in mm where m are expected: the likely fix is said.
    case(&[PATH[0], PATH[1], "--l0", "2,2,2", "--lf", "152,152,152", "--duration", "2", "--dt", "0.1", "--out", "out/p.csv"], 2, "--l0 is in m, not mm: did you mean --l0 0.002,0.002,0.002?"),
    case(&["pss3", "fk", "--l", "50,80,100"], 2, "--l is in m, not mm: did you mean --l 0.05,0.08,0.1?"),
    case(&["pss3", "plant-reference", "--dt", "1e-300", "--out-dir", "out"], 2, "--dt"),
    case(&["pss3", "plant-reference", "--dt", "-0.001", "--out-dir", "out"], 2, "--dt"),
    case(&["pss3", "workspace", "--out", "out", "--steps", "4294967295"], 2, "--steps"),
    case(&["pss3", "workspace", "--out", "out", "--steps", "1"], 2, "--steps"),
    case(&["pss3", "workspace", "--out", "out", "--angle-step", "0"], 2, "--angle-step"),
    case(&["pss3", "workspace", "--out", "out", "--angle-step", "NaN"], 2, "--angle-step"),
    case(&["pss3", "workspace", "--out", "out", "--angle-step", "1e-9"], 2, "--angle-step"),
    case(&["pss3", "workspace"], 2, "--out"),
    // dexterity
    case(&["dexterity", "max-lci", "--robot", "1rrr", "--phi", "10", "--grid", "4294967295"], 2, "--grid"),
    case(&["dexterity", "max-lci", "--robot", "1rrr", "--phi", "10", "--grid", "1"], 2, "--grid"),
    case(&["dexterity", "max-lci", "--robot", "1rrr", "--phi", "NaN"], 2, "--phi"),
    case(&["dexterity", "max-lci", "--robot", "4rrr", "--phi", "10"], 2, "--robot"),
    case(&["dexterity", "max-lci", "--robot", "3rrr", "--phi", "10", "--mode", "9"], 2, "--mode"),
    case(&["dexterity", "max-lci", "--robot", "3rrr", "--phi", "10", "--mode", "-1"], 2, "--mode"),
    case(&["dexterity", "gci", "--robot", "1rrr", "--cells", "0"], 2, "--cells"),
    case(&["dexterity", "gci", "--robot", "1rrr", "--phi-cells", "100000"], 2, "--phi-cells"),
    case(&["dexterity", "gci", "--robot", "1rrr", "--phi-min", "90", "--phi-max", "10"], 2, "--phi-max"),
    case(&["dexterity", "gci-convergence", "--robot", "1rrr", "--phi-min", "-inf"], 2, "--phi-min"),
    case(&["dexterity", "phi-sweep", "--step", "1e-300", "--out", "out"], 2, "--step"),
    case(&["dexterity", "phi-sweep", "--step", "0", "--out", "out"], 2, "--step"),
    case(&["dexterity", "phi-sweep", "--from", "180", "--to", "10", "--out", "out"], 2, "--to"),
    case(&["dexterity", "phi-sweep", "--grid", "1001", "--step", "0.5", "--out", "out"], 2, "--grid"),
    case(&["dexterity", "phi-sweep", "--mode-2rrr", "7", "--out", "out"], 2, "--mode-2rrr"),
    case(&["dexterity", "lci-map", "--robot", "2rrr", "--grid", "100000", "--out", "out"], 2, "--grid"),
    case(&["dexterity", "load-map", "--robot", "2rrr", "--phi", "inf", "--out", "out"], 2, "--phi"),
    case(&["dexterity", "workspace", "--grid", "-3", "--out", "out"], 2, "--grid"),
    case(&["dexterity", "readings", "--grid", "0"], 2, "--grid"),
    case(&["dexterity", "gci", "--robot", "1rrr", "--square", "round"], 2, "--square"),
    // dual-arm
    case(&["dual-arm", "solve", "--lock", "7", "--path", "B"], 2, "--lock"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--intervals", "0"], 2, "--intervals"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--intervals", "4294967295"], 2, "--intervals"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--guess", "NaN,0"], 2, "--guess"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--guess", "1,2,3"], 2, "--guess"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--guess", "1e7,1e7"], 2, "--guess"),
    case(&["dual-arm", "compare", "--lock", "none", "--path", "A", "--guess", "0,0,0,-1e300"], 2, "--guess"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--elbows", "negative"], 2, "--elbows"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--elbows", "up,down"], 2, "--elbows"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "missing.csv"], 2, "--path missing.csv"),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "."], 2, "--path ."),
    case(&["dual-arm", "solve", "--lock", "1", "--path", "B", "--method", "magic"], 2, "--method"),
    case(&["dual-arm", "compare", "--lock", "1"], 2, "--path"),
    case(&["dual-arm", "extremals", "--path", "C"], 2, "--path C"),
    // closed-loop
    case(&["closed-loop", "design-gains", "--bandwidth", "1e200", "--angles", "0,0,130"], 2, "--bandwidth"),
    case(&["closed-loop", "design-gains", "--bandwidth", "NaN", "--angles", "0,0,130"], 2, "--bandwidth"),
    case(&["closed-loop", "design-gains", "--bandwidth", "0", "--angles", "0,0,130"], 2, "--bandwidth"),
    case(&["closed-loop", "design-gains", "--bandwidth", "30", "--angles", "0,0"], 2, "--angles"),
    case(&["closed-loop", "boundary", "--angles", "0,90,0", "--omega", "1,1,1"], 1, "singular"),
    case(&["closed-loop", "boundary", "--angles", "0,89.9999999,0", "--omega", "1e308,1e308,1e308"], 2, "--omega"),
    case(&["closed-loop", "boundary", "--angles", "0,0,130", "--omega-dot", "1,x,1"], 2, "--omega-dot"),
    case(&["closed-loop", "reference", "--scenario", "missing.toml", "--out", "out/r.csv"], 2, "missing.toml"),
    case(&["closed-loop", "reference", "--scenario", ".", "--out", "out/r.csv"], 2, "cannot read the scenario"),
    case(&["closed-loop", "reference", "--scenario", "s.toml", "--out", "out/r.csv", "--tolerance", "0"], 2, "--tolerance"),
    case(&["closed-loop", "reference", "--scenario", "s.toml", "--out", "out/r.csv", "--every", "0"], 2, "--every"),
    case(&["closed-loop", "reference", "--scenario", "s.toml", "--out", "out/r.opt"], 2, "--out out/r.opt"),
    case(&["closed-loop", "reference", "--scenario", "s.toml", "--out", "missing/r.csv"], 2, "the folder missing does not exist"),
    case(&["closed-loop", "reference", "--scenario", "s.toml", "--out", "."], 2, "that is a folder"),
    // the command line itself
    case(&["pss4"], 2, "pss4"),
    case(&["pss3", "ik", "--angles", "0,0,130", "--bogus"], 2, "--bogus"),
    case(&["pss3", "ik", "--angles=0,0,130", "--angles=0,0,130", "extra"], 2, "extra"),
];

#[rustfmt::skip]
/// Cases that read a file the test writes first (name, content).
const FILE_CASES: &[(Case, &str, &[u8])] = &[
    (case(&["dual-arm", "solve", "--lock", "1", "--path", "one.csv"], 2, "--path one.csv"), "one.csv", b"t,x,y\n0,0.1,0.2\n"),
    (case(&["dual-arm", "solve", "--lock", "1", "--path", "bin.csv"], 2, "--path bin.csv"), "bin.csv", b"\xff\xfe\x00t,x\x00"),
    (case(&["dual-arm", "solve", "--lock", "1", "--path", "nan.csv"], 2, "--path nan.csv"), "nan.csv", b"t,x,y\n0,NaN,0\n0.3,0,0\n0.6,0,0\n1,0,0\n"),
    (case(&["closed-loop", "reference", "--scenario", "bin.toml", "--out", "out/r.csv"], 2, "bin.toml"), "bin.toml", b"name = \"\xff\xfe\"\n"), (case(&["closed-loop", "reference", "--scenario", "junk.toml", "--out", "out/r.csv"], 2, "junk.toml"), "junk.toml", b"[[[[not toml"),
    (case(&["closed-loop", "reference", "--scenario", "deep.toml", "--out", "out/r.csv"], 2, "deep.toml"), "deep.toml", DEEP),
    // An output folder where a file is: refused with the fix (formerly exit code 1).
    (case(&["pss3", "workspace", "--out", "taken", "--steps", "2"], 2, "a file is in the way where a folder belongs"), "taken", b"x"),
    (case(&["dexterity", "workspace", "--out", "taken"], 2, "a file is in the way"), "taken", b"x"),
];

/// Hundreds of nested arrays: a parser that recurses without a limit overflows its stack.
const DEEP: &[u8] = b"x = [[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[[";

/// The expanded form of scenarios/regulation.toml, the form the Rust reference reads.
const EXPANDED: &str = include_str!("../../../../tests/scenarios/expanded/regulation.toml");

static NEXT: AtomicUsize = AtomicUsize::new(0);

/// A fresh empty working directory for one case.
fn workdir() -> PathBuf {
    let n = NEXT.fetch_add(1, Ordering::Relaxed);
    let dir = std::env::temp_dir().join(format!("robofmu-hostile-{}-{n}", std::process::id()));
    let _ = fs::remove_dir_all(&dir);
    fs::create_dir_all(&dir).unwrap();
    dir
}

/// Every file and directory below `dir`, relative to it.
fn listing(dir: &Path) -> BTreeSet<PathBuf> {
    let mut found = BTreeSet::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            found.insert(path.strip_prefix(dir).unwrap().to_path_buf());
            if path.is_dir() {
                stack.push(path);
            }
        }
    }
    found
}

fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_robofmu"))
        .args(args)
        .current_dir(dir)
        .env_remove("RUST_BACKTRACE")
        .output()
        .expect("the robofmu binary runs")
}

/// Runs one case in `dir` and returns what is wrong with the outcome, if anything.
fn check(dir: &Path, c: &Case) -> Option<String> {
    let before = listing(dir);
    let o = run_in(dir, c.args);
    let stderr = String::from_utf8_lossy(&o.stderr).into_owned();
    let after = listing(dir);
    let written: Vec<&PathBuf> = after.difference(&before).collect();
    let mut problems = Vec::new();
    match o.status.code() {
        None => problems.push(format!("killed by a signal: {:?}", o.status)),
        Some(code) if code != c.code => problems.push(format!("exit code {code}, want {}", c.code)),
        Some(_) => {}
    }
    if stderr.lines().count() != 1 || !stderr.starts_with("robofmu: ") {
        problems.push("not one `robofmu: ...` line on stderr".into());
    }
    if !stderr.contains(c.names) {
        problems.push(format!("the message does not name {:?}", c.names));
    }
    if ["panicked", "RUST_BACKTRACE", "Backtrace"]
        .iter()
        .any(|p| stderr.contains(p))
    {
        problems.push("panic text".into());
    }
    let outside = |p: &&&PathBuf| !p.starts_with("out");
    if c.code == 2 && !written.is_empty() || written.iter().any(|p| outside(&p)) {
        problems.push(format!("wrote {written:?}"));
    }
    (!problems.is_empty())
        .then(|| format!("{:?}: {} (stderr: {stderr:?})", c.args, problems.join("; ")))
}

#[test]
fn hostile_command_lines_get_one_line_a_code_and_no_writes() {
    let mut failures = Vec::new();
    let mut count = 0;
    for c in CASES {
        let dir = workdir();
        fs::write(dir.join("s.toml"), EXPANDED).unwrap();
        failures.extend(check(&dir, c));
        fs::remove_dir_all(&dir).unwrap();
        count += 1;
    }
    for (c, name, content) in FILE_CASES {
        let dir = workdir();
        fs::write(dir.join(name), content).unwrap();
        failures.extend(check(&dir, c));
        fs::remove_dir_all(&dir).unwrap();
        count += 1;
    }
    assert!(count >= 40, "{count} cases");
    assert!(
        failures.is_empty(),
        "{} of {count} cases:\n{}",
        failures.len(),
        failures.join("\n")
    );
}

#[test]
fn expanded_scenarios_with_a_bad_step_or_length_are_refused() {
    // Truth: a step must be > 0 and a run at most 1e6 steps (cli/bounds.rs); the
    // regulation's expanded form with its step made negative, or its run 1e9 s long.
    let step = "\"step_size\" = 0.001";
    let stop = "\"stop_time\" = 1.0";
    assert!(EXPANDED.contains(step) && EXPANDED.contains(stop));
    let variants = [
        EXPANDED.replace(step, "\"step_size\" = -0.001"),
        EXPANDED.replace(step, "\"step_size\" = 0.0"),
        EXPANDED.replace(stop, "\"stop_time\" = 1e9"),
    ];
    let c = case(
        &[
            "closed-loop",
            "reference",
            "--scenario",
            "x.toml",
            "--out",
            "out/r.csv",
        ],
        2,
        "step_size",
    );
    for text in variants {
        let dir = workdir();
        fs::write(dir.join("x.toml"), text).unwrap();
        assert_eq!(check(&dir, &c), None);
        fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn a_subcommand_missing_shows_the_help_with_exit_code_2() {
    // Truth: clap's convention, a usage error; the help lists the subcommands.
    for args in [&[][..], &["pss3"][..], &["dexterity"][..]] {
        let dir = workdir();
        let o = run_in(&dir, args);
        let stderr = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}");
        assert!(
            stderr.contains("Usage:") && !stderr.contains("panicked"),
            "{stderr}"
        );
        assert!(listing(&dir).is_empty());
        fs::remove_dir_all(&dir).unwrap();
    }
}

#[test]
fn a_closed_stdout_ends_quietly() {
    // `robofmu ... | head` where head has gone: every write to stdout fails with a
    // broken pipe (the read end is closed before the process starts, so this is
    // deterministic); the process ends with exit code 0 and says nothing.
    for args in [
        &["pss3", "jacobian", "--angles", "0,0,130"][..],
        &["closed-loop", "boundary", "--angles", "1,2,130"][..],
        &[
            "dexterity",
            "max-lci",
            "--robot",
            "1rrr",
            "--phi",
            "10",
            "--grid",
            "21",
        ][..],
        &["--help"][..],
    ] {
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let o = Command::new(env!("CARGO_BIN_EXE_robofmu"))
            .args(args)
            .stdout(Stdio::from(writer))
            .stderr(Stdio::piped())
            .output()
            .unwrap();
        assert_eq!(o.status.code(), Some(0), "{args:?}: {:?}", o.status);
        assert!(
            o.stderr.is_empty(),
            "{args:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
    }
}

#[test]
fn non_utf8_arguments_are_refused_by_name() {
    // A number that is not text at all: clap refuses it, naming the option.
    use std::os::unix::ffi::OsStrExt;
    let dir = workdir();
    let bad = std::ffi::OsStr::from_bytes(b"0,0,\xff");
    let o = Command::new(env!("CARGO_BIN_EXE_robofmu"))
        .args(["pss3", "ik", "--angles"])
        .arg(bad)
        .current_dir(&dir)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{stderr}");
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(
        stderr.starts_with("robofmu: ") && !stderr.contains("panicked"),
        "{stderr}"
    );
    assert!(listing(&dir).is_empty());
    fs::remove_dir_all(&dir).unwrap();
}
