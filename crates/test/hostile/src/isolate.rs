//! Runs probes in forked children so that a crash of the FMU is reported as the
//! failure of one case (with its signal), not as the death of the test runner.

use std::io::{BufRead, BufReader, Write};
use std::os::fd::FromRawFd;
use std::panic::{AssertUnwindSafe, catch_unwind};

/// Seconds one case may run before SIGALRM ends its child (a hang counts as a
/// crash of that case); the clock restarts for every case.
const CASE_TIME_LIMIT: u32 = 120;

/// Result of one case: the text the probe returned, or how the child died.
pub type CaseResult = Result<String, String>;

/// Runs `probe(i)` for i in 0..n in forked children, in order. A child reports each
/// result on a pipe as it completes; when a child dies, the case it was running is
/// recorded as crashed and a new child continues with the next case.
pub fn run_cases(n: usize, probe: &dyn Fn(usize) -> String) -> Vec<CaseResult> {
    let mut results: Vec<CaseResult> = Vec::with_capacity(n);
    while results.len() < n {
        let start = results.len();
        let (lines, death) = run_child(start, n, probe);
        results.extend(lines.into_iter().map(Ok));
        if results.len() < n {
            results.push(Err(death.unwrap_or_else(|| "child ended early".into())));
        }
    }
    results
}

/// Runs `body` in a forked child and returns its text, or how it died.
pub fn run_one(body: &dyn Fn() -> String) -> CaseResult {
    run_cases(1, &|_| body()).remove(0)
}

fn run_child(
    start: usize,
    n: usize,
    probe: &dyn Fn(usize) -> String,
) -> (Vec<String>, Option<String>) {
    let mut fds = [0; 2];
    // SAFETY: a two-element array for pipe().
    assert_eq!(unsafe { libc::pipe(fds.as_mut_ptr()) }, 0, "pipe failed");
    // Flush so the child does not repeat the parent's buffered output.
    let _ = std::io::stdout().flush();
    // SAFETY: the test process is single-threaded (harness = false) when it forks.
    let pid = unsafe { libc::fork() };
    assert!(pid >= 0, "fork failed");
    if pid == 0 {
        // SAFETY: the child's ends of the pipe.
        unsafe { libc::close(fds[0]) };
        let mut out = unsafe { std::fs::File::from_raw_fd(fds[1]) };
        for i in start..n {
            // SAFETY: alarm has no preconditions.
            unsafe { libc::alarm(CASE_TIME_LIMIT) };
            let text = catch_unwind(AssertUnwindSafe(|| probe(i)));
            let Ok(text) = text else {
                // SAFETY: leave without running the parent's destructors.
                unsafe { libc::_exit(101) };
            };
            let line = text.replace(['\n', '\r'], " ");
            if writeln!(out, "{line}").is_err() {
                unsafe { libc::_exit(102) };
            }
        }
        let _ = out.flush();
        // SAFETY: as above.
        unsafe { libc::_exit(0) };
    }
    // SAFETY: the parent's ends of the pipe.
    unsafe { libc::close(fds[1]) };
    let input = unsafe { std::fs::File::from_raw_fd(fds[0]) };
    let lines: Vec<String> = BufReader::new(input)
        .lines()
        .map_while(Result::ok)
        .collect();
    let mut status = 0;
    // SAFETY: our own child.
    unsafe { libc::waitpid(pid, &mut status, 0) };
    (lines, describe_death(status))
}

fn describe_death(status: i32) -> Option<String> {
    if libc::WIFSIGNALED(status) {
        let signal = libc::WTERMSIG(status);
        let name = match signal {
            libc::SIGSEGV => "SIGSEGV",
            libc::SIGABRT => "SIGABRT",
            libc::SIGBUS => "SIGBUS",
            libc::SIGALRM => "SIGALRM (time limit)",
            libc::SIGILL => "SIGILL",
            libc::SIGFPE => "SIGFPE",
            _ => "signal",
        };
        Some(format!("crashed: {name} ({signal})"))
    } else if libc::WIFEXITED(status) && libc::WEXITSTATUS(status) != 0 {
        Some(format!(
            "child exited with code {} (panic in the probe)",
            libc::WEXITSTATUS(status)
        ))
    } else {
        None
    }
}
