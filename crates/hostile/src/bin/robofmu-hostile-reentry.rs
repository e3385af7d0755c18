//! The re-entrancy, reuse, thread, forged-state and time probes of
//! `robofmu_hostile::reentry` in one process, without forking: the program
//! scripts/memcheck.sh runs under valgrind (loggers that free, reset, set states and
//! re-enter; both standards, every packaged FMU). Exits 1 if a probe fails.

use robofmu_hostile::Loaded;
use robofmu_hostile::reentry::{Tally, apis, cases};

fn main() {
    let loaded = Loaded::all();
    let mut tally = Tally::default();
    for api in apis(&loaded) {
        for case in cases(api.as_ref()) {
            let result = (case.run)(api.as_ref());
            if matches!(&result, Ok(seen) if seen.starts_with("not applicable")) {
                continue;
            }
            if let Err(why) = &result {
                println!("{} [{}] {}: {why}", api.name(), case.class, case.name);
            }
            tally.add(case.class, result.is_ok());
        }
    }
    println!("{}", tally.table());
    if tally.failed() > 0 {
        std::process::exit(1);
    }
}
