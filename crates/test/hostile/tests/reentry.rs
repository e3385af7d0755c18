//! A host that calls back, reuses addresses, forges states and shares an instance
//! between threads (issue 20): every case of `robofmu_hostile::reentry::cases` for
//! every packaged FMU, both standards, each in a forked child (a crash is a failed
//! case with its signal). ROBOFMU_HOSTILE_DIST=<dir> runs them against other builds.

use robofmu_hostile::reentry::{Tally, apis, cases};
use robofmu_hostile::{Loaded, isolate};

fn main() {
    let loaded = Loaded::all();
    let mut tally = Tally::default();
    for api in apis(&loaded) {
        let cases = cases(api.as_ref());
        let results = isolate::run_cases(cases.len(), &|i| match (cases[i].run)(api.as_ref()) {
            Ok(seen) => format!("ok {seen}"),
            Err(why) => format!("FAIL {why}"),
        });
        for (case, result) in cases.iter().zip(results) {
            if matches!(&result, Ok(line) if line.starts_with("ok not applicable")) {
                continue; // e.g. intermediateUpdate of a model without intermediate points
            }
            let passed = matches!(&result, Ok(line) if line.starts_with("ok "));
            tally.add(case.class, passed);
            if !passed {
                println!("{} [{}] {}: {result:?}", api.name(), case.class, case.name);
            }
        }
    }
    println!("{}", tally.table());
    if tally.failed() > 0 {
        std::process::exit(1);
    }
}
