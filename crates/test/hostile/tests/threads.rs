//! Eight threads against a serial run, every packaged FMU, FMI 2.0 and FMI 3.0,
//! bit for bit: see
//! `robofmu_hostile::threads`. Runs in a forked child (a crash is reported).

use robofmu_hostile::threads::{STEPS, THREADS, compare, simulate, simulate3};
use robofmu_hostile::{Loaded, isolate};

fn main() {
    let loaded = Loaded::all();
    let mut failed = false;
    for (standard, simulation) in [("FMI 2.0", simulate as _), ("FMI 3.0", simulate3 as _)] {
        let result = isolate::run_one(&|| match compare(&loaded, simulation) {
            Ok((differ, n)) => format!("{differ} {n}"),
            Err(e) => format!("error {e}"),
        });
        println!(
            "{standard}: threads ({THREADS} per model, {STEPS} steps each) vs serial: {result:?}"
        );
        match result.as_deref().map(|r| r.split_once(' ')) {
            Ok(Some(("0", _))) => println!("{standard}: identical bit for bit"),
            _ => failed = true,
        }
    }
    if failed {
        std::process::exit(1);
    }
}
