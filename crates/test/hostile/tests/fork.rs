//! fork() at any moment (issue 42): while three threads instantiate, step and free
//! instances of every packaged FMU (FMI 2.0 and FMI 3.0) without pause, the main
//! thread forks 10,000 times (ROBOFMU_FORKS overrides the count); each child
//! instantiates an FMU (the models and standards in turn), initializes it, takes a
//! step, frees it and exits. Python's multiprocessing with the fork start method does
//! the same to an importer.
//!
//! First, once: an FMU loaded from a path of its own, used and unloaded, then a fork
//! (the handlers the FMU registered must leave with it).
//!
//! Expected: every child exits 0 within ROBOFMU_FORK_LIMIT_S seconds (default 5; a
//! child that takes longer is killed and counted deadlocked: before issue 42, 1 to 5 %
//! of the children inherited a lock of the handle registry or of the index cell held
//! by a thread that does not exist in the child). The child does not print (a lock of
//! stdout could be held by the parent's threads as well).

use robofmu_hostile::Loaded;
use robofmu_hostile::binary::OK;
use robofmu_hostile::fmi3::host::{Instance as Instance3, Interface3, State3};
use robofmu_hostile::fmu::{Fmu, Standard};
use robofmu_hostile::host::{Instance, Interface, State};
use std::sync::atomic::{AtomicBool, AtomicI32, AtomicU64, AtomicUsize, Ordering};
use std::time::{Duration, Instant};

/// Instantiates instance `k` (the models and both standards in turn), initializes it,
/// takes a step of 1 ms and frees it; true when every call returned OK.
fn cycle(l: &Loaded, k: usize) -> bool {
    let n = l.fmus.len();
    let m = (k / 2) % n;
    if k.is_multiple_of(2) {
        let inst = Instance::new(
            &l.binaries[m],
            &l.fmus[m].description,
            Interface::CoSimulation,
        );
        inst.reach(State::StepComplete).is_ok() && inst.do_step(0.0, 1e-3) == OK
    } else {
        let d = &l.fmus3[m].description;
        let inst = Instance3::new(&l.binaries3[m], d, Interface3::CoSimulation);
        inst.reach(State3::StepMode).is_ok() && inst.do_step(0.0, 1e-3).status == OK
    }
}

/// The fork handlers leave with their library: an FMU loaded from a path of its own,
/// instantiated (which registers them) and unloaded; then a fork. Err if the library
/// stayed mapped (nothing would be shown) or the child failed; a handler left behind
/// would crash this process in fork() (its code is unmapped).
fn handlers_leave_with_the_library() -> Result<(), String> {
    let model = &robofmu_hostile::fmu::models()[0];
    let fmu = Fmu::unpack(model, Standard::Fmi2)?.copy()?;
    let binary = fmu.open();
    let inst = Instance::new(&binary, &fmu.description, Interface::CoSimulation);
    inst.reach(State::StepComplete)?;
    drop(inst);
    drop(binary);
    let maps = std::fs::read_to_string("/proc/self/maps").map_err(|e| e.to_string())?;
    if maps.contains(&*fmu.library.to_string_lossy()) {
        return Err(format!(
            "{} is still mapped after dlclose",
            fmu.library.display()
        ));
    }
    // SAFETY: the child only exits.
    let pid = unsafe { libc::fork() };
    if pid == 0 {
        // SAFETY: ends the child at once.
        unsafe { libc::_exit(0) };
    }
    let mut status = 1;
    // SAFETY: waits for the child just forked.
    unsafe { libc::waitpid(pid, &mut status, 0) };
    if pid > 0 && status == 0 {
        Ok(())
    } else {
        Err(format!("fork after unloading: pid {pid}, status {status}"))
    }
}

fn env_number(name: &str, default: u64) -> u64 {
    std::env::var(name)
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(default)
}

fn main() {
    let forks = env_number("ROBOFMU_FORKS", 10_000) as usize;
    let limit = Duration::from_secs(env_number("ROBOFMU_FORK_LIMIT_S", 5));
    handlers_leave_with_the_library().unwrap_or_else(|e| panic!("{e}"));
    println!("fork after an FMU was used and unloaded: the child exited 0");
    let loaded = Loaded::all();
    let stop = AtomicBool::new(false);
    let cycles = AtomicUsize::new(0);
    let failed_cycles = AtomicUsize::new(0);
    // The child being waited for and since when (ms since `start`), for the watchdog.
    let child = AtomicI32::new(0);
    let since = AtomicU64::new(0);
    let start = Instant::now();
    let (mut deadlocked, mut failed, mut done) = (0, 0, 0);
    std::thread::scope(|scope| {
        for w in 0..3 {
            let (l, stop, cycles, failed_cycles) = (&loaded, &stop, &cycles, &failed_cycles);
            scope.spawn(move || {
                let mut k = w;
                while !stop.load(Ordering::Relaxed) {
                    if !cycle(l, k) {
                        failed_cycles.fetch_add(1, Ordering::Relaxed);
                    }
                    cycles.fetch_add(1, Ordering::Relaxed);
                    k += 1;
                }
            });
        }
        scope.spawn(|| {
            while !stop.load(Ordering::Relaxed) {
                std::thread::sleep(Duration::from_millis(50));
                let pid = child.load(Ordering::Acquire);
                let waited = start.elapsed().as_millis() as u64 - since.load(Ordering::Acquire);
                if pid > 0 && waited > limit.as_millis() as u64 {
                    // SAFETY: a child of this process that has not been reaped.
                    unsafe { libc::kill(pid, libc::SIGKILL) };
                }
            }
        });
        for i in 0..forks {
            // SAFETY: the child only calls into the loaded FMUs and exits with _exit.
            let pid = unsafe { libc::fork() };
            if pid == 0 {
                let ok = std::panic::catch_unwind(|| cycle(&loaded, i)).unwrap_or(false);
                // SAFETY: ends the child without running the parent's exit handlers.
                unsafe { libc::_exit(if ok { 0 } else { 1 }) };
            }
            assert!(pid > 0, "fork failed");
            since.store(start.elapsed().as_millis() as u64, Ordering::Release);
            child.store(pid, Ordering::Release);
            let mut status = 0;
            // SAFETY: waits for the child just forked.
            unsafe { libc::waitpid(pid, &mut status, 0) };
            child.store(0, Ordering::Release);
            done += 1;
            if libc::WIFSIGNALED(status) && libc::WTERMSIG(status) == libc::SIGKILL {
                deadlocked += 1;
            } else if !(libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0) {
                failed += 1;
            }
            if deadlocked + failed >= 3 {
                break;
            }
        }
        stop.store(true, Ordering::Relaxed);
    });
    println!(
        "{done} of {forks} forks in {:.1} s while 3 threads ran {} instantiate-step-free \
         cycles: {deadlocked} children deadlocked, {failed} failed (stops at 3); {} cycles \
         failed",
        start.elapsed().as_secs_f64(),
        cycles.load(Ordering::Relaxed),
        failed_cycles.load(Ordering::Relaxed)
    );
    assert_eq!((deadlocked, failed, done), (0, 0, forks));
    assert_eq!(failed_cycles.load(Ordering::Relaxed), 0);
    assert!(cycles.load(Ordering::Relaxed) > 0);
}
