//! Random legal call sequences (fixed seeds) against the packaged FMUs, FMI 2.0
//! then FMI 3.0: see `robofmu_hostile::sequences` and
//! `robofmu_hostile::fmi3::sequences`. ROBOFMU_HOSTILE_SEQUENCES sets the count of
//! each (default: `DEFAULT_SEQUENCES` of each module; the issue-12 probe ran
//! 240000).

use robofmu_hostile::sequences::{BASE_SEED, count_from_env};
use robofmu_hostile::{Loaded, fmi3, isolate, sequences};

type Sequence = fn(&Loaded, u64) -> Result<usize, String>;

/// Runs `n` sequences; prints the first failures and a summary; whether all passed.
fn run(loaded: &Loaded, standard: &str, n: usize, sequence: Sequence) -> bool {
    let results = isolate::run_cases(n, &|i| match sequence(loaded, BASE_SEED + i as u64) {
        Ok(calls) => format!("ok {calls}"),
        Err(e) => format!("fail {e}"),
    });
    let mut calls = 0usize;
    let mut failures = Vec::new();
    for (i, r) in results.iter().enumerate() {
        match r {
            Ok(line) if line.starts_with("ok ") => calls += line[3..].parse::<usize>().unwrap_or(0),
            Ok(line) => failures.push(line.clone()),
            Err(death) => failures.push(format!("seed {:#x}: {death}", BASE_SEED + i as u64)),
        }
    }
    for f in failures.iter().take(30) {
        println!("{f}");
    }
    println!(
        "random sequences ({standard}): {n}, calls: {calls}, failed: {}",
        failures.len()
    );
    failures.is_empty()
}

fn main() {
    let loaded = Loaded::all();
    let n2 = count_from_env(sequences::DEFAULT_SEQUENCES);
    let n3 = count_from_env(fmi3::sequences::DEFAULT_SEQUENCES);
    let fmi2 = run(&loaded, "FMI 2.0", n2, sequences::run_sequence);
    let fmi3 = run(&loaded, "FMI 3.0", n3, fmi3::sequences::run_sequence);
    if !(fmi2 && fmi3) {
        std::process::exit(1);
    }
}
