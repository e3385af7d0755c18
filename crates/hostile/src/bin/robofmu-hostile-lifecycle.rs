//! The lifecycle of every packaged FMU (or of the models named as arguments)
//! through dlopen, without forking: the program scripts/test.sh runs under
//! valgrind memcheck. Exits 1 if a call fails.

use robofmu_hostile::fmu::{Fmu, MODELS};
use robofmu_hostile::lifecycle;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let models: Vec<&str> = if args.is_empty() {
        MODELS.to_vec()
    } else {
        args.iter().map(String::as_str).collect()
    };
    let mut failed = false;
    for model in models {
        let result = Fmu::unpack(model).and_then(|fmu| lifecycle::run(&fmu));
        match result {
            Ok(()) => println!("{model}: lifecycle ok"),
            Err(e) => {
                println!("{model}: {e}");
                failed = true;
            }
        }
    }
    if failed {
        std::process::exit(1);
    }
}
