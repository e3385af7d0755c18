//! The plant driven into its stops with forces of 1e4 N, steps from 1e-9 s to 1 s:
//! see `robofmu_hostile::plant_hard`. Runs in a forked child.

use robofmu_hostile::plant_hard::drive;
use robofmu_hostile::{Loaded, fmu, isolate};

fn main() {
    let loaded = Loaded::all();
    let m = fmu::models()
        .iter()
        .position(|n| n == "Pss3Plant")
        .expect("Pss3Plant is shipped");
    let result = isolate::run_one(&|| {
        let (tally, failures) = drive(&loaded, m);
        let mut text = format!(
            "{} calls, {} discards, {} failures",
            tally.calls,
            tally.discards,
            failures.len()
        );
        for f in failures {
            text += &format!("\u{1f}{f}");
        }
        text
    });
    let text =
        result.unwrap_or_else(|death| format!("0 calls, 0 discards, 1 failures\u{1f}{death}"));
    let mut parts = text.split('\u{1f}');
    let summary = parts.next().unwrap_or("");
    let failures: Vec<&str> = parts.collect();
    for f in &failures {
        println!("FAIL {f}");
    }
    println!("plant driven hard: {summary}");
    if !failures.is_empty() {
        std::process::exit(1);
    }
}
