//! Handles given to the wrong library (issue 36): every case of
//! `robofmu_hostile::foreign::cases` (another model's and another copy's instance and
//! FMU state passed to every function that takes one, both standards, every
//! interface; FMI 2.0 functions given the FMI 3.0 instance of the same binary), each
//! in a forked child, where every library issues its first handles.

use robofmu_hostile::foreign::cases;
use robofmu_hostile::{Loaded, isolate};

fn main() {
    let loaded = Loaded::all();
    let copy = loaded.copy();
    let cases = cases();
    // One child per case: no library has issued a handle before the case starts.
    let results: Vec<_> = cases
        .iter()
        .map(|case| {
            isolate::run_one(&|| match (case.run)(&loaded, &copy) {
                Ok(seen) => format!("ok {seen}"),
                Err(why) => format!("FAIL {why}"),
            })
        })
        .collect();
    let mut failed = 0;
    for (case, result) in cases.iter().zip(&results) {
        if !matches!(result, Ok(line) if line.starts_with("ok ")) {
            failed += 1;
            println!("{}: {result:?}", case.name);
        }
    }
    println!(
        "foreign handles: {} cases, {} passed, {failed} failed",
        cases.len(),
        cases.len() - failed
    );
    if failed > 0 {
        std::process::exit(1);
    }
}
