//! Eight threads against a serial run, every packaged FMU, bit for bit: see
//! `robofmu_hostile::threads`. Runs in a forked child (a crash is reported).

use robofmu_hostile::threads::{STEPS, THREADS, compare};
use robofmu_hostile::{Loaded, isolate};

fn main() {
    let loaded = Loaded::all();
    let result = isolate::run_one(&|| match compare(&loaded) {
        Ok((differ, n)) => format!("{differ} {n}"),
        Err(e) => format!("error {e}"),
    });
    println!("threads ({THREADS} per model, {STEPS} steps each) vs serial: {result:?}");
    match result.as_deref().map(|r| r.split_once(' ')) {
        Ok(Some(("0", _))) => println!("identical bit for bit"),
        _ => std::process::exit(1),
    }
}
