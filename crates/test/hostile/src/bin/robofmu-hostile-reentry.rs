//! The re-entrancy, reuse, thread, forged-state and time probes of
//! `robofmu_hostile::reentry`, and the foreign handles of `robofmu_hostile::foreign`
//! (class "foreign": another model's and another copy's instances and states), in
//! one process, without forking: the program scripts/memcheck.sh runs under valgrind
//! (loggers that free, reset, set states and re-enter; both standards, every
//! packaged FMU). Arguments name the classes to run (all without arguments). Exits 1
//! if a probe fails.

use robofmu_hostile::Loaded;
use robofmu_hostile::reentry::{Tally, apis, cases};

fn main() {
    let classes: Vec<String> = std::env::args().skip(1).collect();
    let loaded = Loaded::all();
    let mut tally = Tally::default();
    for api in apis(&loaded) {
        let chosen = cases(api.as_ref())
            .into_iter()
            .filter(|c| classes.is_empty() || classes.iter().any(|k| k == c.class));
        for case in chosen {
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
    if classes.is_empty() || classes.iter().any(|k| k == "foreign") {
        let copy = loaded.copy();
        for case in robofmu_hostile::foreign::cases() {
            let result = (case.run)(&loaded, &copy);
            if let Err(why) = &result {
                println!("[foreign] {}: {why}", case.name);
            }
            tally.add("foreign", result.is_ok());
        }
    }
    println!("{}", tally.table());
    if tally.failed() > 0 {
        std::process::exit(1);
    }
}
