//! The bad-input matrix against the packaged FMUs (dist/*.fmu, loaded with dlopen):
//! see `robofmu_hostile::matrix` and docs/reliability.md. Fails on any case whose
//! outcome differs from its expectation, including crashes (reported with the
//! signal) and listed known failures that pass.

use robofmu_hostile::{Loaded, matrix};

fn main() {
    let loaded = Loaded::all();
    let cases = matrix::all_cases(&loaded);
    let verdicts = matrix::run(&loaded, &cases);
    let (report, failed) = matrix::report(&cases, &verdicts);
    println!("{report}");
    if failed {
        eprintln!("hostile matrix: failures above");
        std::process::exit(1);
    }
}
