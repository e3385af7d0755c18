//! Random legal call sequences (fixed seeds) against the packaged FMUs: see
//! `robofmu_hostile::sequences`. ROBOFMU_HOSTILE_SEQUENCES sets the count
//! (default `DEFAULT_SEQUENCES`; the issue-12 probe ran 240000).

use robofmu_hostile::sequences::{BASE_SEED, count_from_env, run_sequence};
use robofmu_hostile::{Loaded, isolate};

fn main() {
    let loaded = Loaded::all();
    let n = count_from_env();
    let results = isolate::run_cases(n, &|i| match run_sequence(&loaded, BASE_SEED + i as u64) {
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
        "random sequences: {n}, calls: {calls}, failed: {}",
        failures.len()
    );
    if !failures.is_empty() {
        std::process::exit(1);
    }
}
