//! Hosts that leave a callback without returning (issue 42), on every packaged FMU, FMI
//! 2.0 and FMI 3.0: `native/leave.c` compiled as C (pthread_exit, pthread_cancel while
//! the thread waits in the callback, longjmp) and as C++ (the same and a thrown
//! exception), each case in a process of its own. The callback left is the logger
//! (logMessage in FMI 3.0) and, for the FMI 3.0 models with intermediate points, also
//! intermediateUpdate (every way but longjmp).
//!
//! Expected (docs/reliability.md, "Leaving a callback"): an unwind out of the callback
//! (C++ exception, pthread_exit, cancellation) ends the process with SIGABRT and the
//! FMU's message naming the callback, every time, never another signal; a longjmp
//! leaves the instance to the next call of that thread, which finds it in the Error
//! state (status 3); Reset makes it usable again (the later calls return OK, 0) and
//! FreeInstance frees it. With ROBOFMU_LEAVE_VALGRIND=1 (scripts/memcheck.sh) the
//! longjmp cases run under valgrind: no memory error, no definite leak.

use robofmu_hostile::fmu::{Fmu, Standard, models, workspace_root};
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Compiles native/leave.c with `compiler` as `language` ("c" or "c++").
fn compile(compiler: &str, language: &str, out: &Path) -> Result<(), String> {
    let source = workspace_root().join("crates/test/hostile/native/leave.c");
    let status = Command::new(compiler)
        .args(["-O1", "-g", "-Wall", "-Werror", "-x", language])
        .arg(&source)
        .arg("-o")
        .arg(out)
        .args(["-lpthread", "-ldl"])
        .status()
        .map_err(|e| format!("{compiler} cannot be run ({e}): install gcc and g++"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "{compiler} -x {language} {}: {status}",
            source.display()
        ))
    }
}

/// What the host printed after the longjmp (FMI 2.0 has EnterInitializationMode).
fn after_longjmp(standard: Standard) -> String {
    let enter = if standard == Standard::Fmi2 {
        "enter 0\n"
    } else {
        ""
    };
    format!("left\nagain 3\nreset 0\nstart 0\n{enter}exit 0\nstep 0\nfreed\njoined\n")
}

/// Runs one case, leaving `callback` ("logger" or "update", leave.c's argument); Err
/// says what differed from the expected outcome.
fn case(
    host: &Path,
    fmu: &Fmu,
    standard: Standard,
    (way, callback): (&str, &str),
    valgrind: bool,
) -> Result<(), String> {
    let number = if standard == Standard::Fmi2 { "2" } else { "3" };
    let mut command = if valgrind {
        let mut c = Command::new("valgrind");
        c.args([
            "-q",
            "--error-exitcode=1",
            "--leak-check=full",
            "--errors-for-leak-kinds=definite",
            "--show-leak-kinds=definite",
        ])
        .arg(host);
        c
    } else {
        Command::new(host)
    };
    let output = command
        .arg(&fmu.library)
        .args([number, &fmu.description.guid, way, callback])
        .output()
        .map_err(|e| format!("cannot run {}: {e}", host.display()))?;
    let stdout = String::from_utf8_lossy(&output.stdout);
    let stderr = String::from_utf8_lossy(&output.stderr);
    let seen = format!("{} (stdout {stdout:?}, stderr {stderr:?})", output.status);
    if way == "longjmp" {
        if output.status.success() && stdout == after_longjmp(standard) {
            return Ok(());
        }
        return Err(seen);
    }
    let callback = match (callback, standard) {
        ("update", _) => "intermediateUpdate",
        (_, Standard::Fmi2) => "logger",
        _ => "logMessage",
    };
    let message = format!("robofmu FMU: fatal: the host's {callback} callback did not return");
    if output.status.signal() == Some(libc::SIGABRT)
        && stdout == "left\n"
        && stderr.contains(&message)
    {
        Ok(())
    } else {
        Err(seen)
    }
}

fn main() {
    let valgrind = std::env::var_os("ROBOFMU_LEAVE_VALGRIND").is_some_and(|v| v == "1");
    let dir: PathBuf = workspace_root()
        .join("target/hostile")
        .join(format!("{}-leave", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{}: {e}", dir.display()));
    let hosts = [
        ("C", dir.join("leave-c"), vec!["exit", "cancel", "longjmp"]),
        (
            "C++",
            dir.join("leave-cpp"),
            vec!["throw", "exit", "cancel", "longjmp"],
        ),
    ];
    compile("cc", "c", &hosts[0].1).unwrap_or_else(|e| panic!("{e}"));
    compile("c++", "c++", &hosts[1].1).unwrap_or_else(|e| panic!("{e}"));
    let (mut passed, mut failed) = (0, Vec::new());
    for model in models() {
        for standard in Standard::BOTH {
            let fmu = Fmu::unpack(model, standard).unwrap_or_else(|e| panic!("{e}"));
            let points = fmu
                .description
                .variables
                .iter()
                .any(|v| v.intermediate_update);
            let callbacks: &[&str] = if points {
                &["logger", "update"]
            } else {
                &["logger"]
            };
            for (language, host, ways) in &hosts {
                for (way, callback) in ways
                    .iter()
                    .flat_map(|w| callbacks.iter().map(move |c| (*w, *c)))
                {
                    let longjmp = way == "longjmp";
                    if (valgrind && !longjmp) || (longjmp && callback == "update") {
                        continue;
                    }
                    match case(host, &fmu, standard, (way, callback), valgrind) {
                        Ok(()) => passed += 1,
                        Err(e) => failed.push(format!(
                            "{model} {} {language} host, {way} out of {callback}: {e}",
                            standard.name()
                        )),
                    }
                }
            }
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let under = if valgrind { " under valgrind" } else { "" };
    println!("leaving a callback{under}: {passed} cases as documented");
    for f in &failed {
        println!("FAILED: {f}");
    }
    assert!(
        passed > 0 && failed.is_empty(),
        "{} cases failed",
        failed.len()
    );
}
