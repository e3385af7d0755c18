//! The lifecycle of every packaged FMU (or of the models named as arguments)
//! through dlopen, without forking, FMI 2.0, FMI 3.0 and the FMI 3.0 scalar-only view
//! (dist/fmi3-scalar: the same binary, instantiated with the scalar token): the program
//! scripts/memcheck.sh runs under valgrind memcheck. Exits 1 if a call fails.

use robofmu_hostile::fmu::{Fmu, Standard, models};
use robofmu_hostile::{fmi3, lifecycle};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let models: Vec<&str> = if args.is_empty() {
        models().iter().map(String::as_str).collect()
    } else {
        args.iter().map(String::as_str).collect()
    };
    let mut failed = false;
    let mut report = |model: &str, view: &str, result: Result<(), String>| match result {
        Ok(()) => println!("{model} ({view}): lifecycle ok"),
        Err(e) => {
            println!("{model} ({view}): {e}");
            failed = true;
        }
    };
    for standard in Standard::BOTH {
        for &model in &models {
            let result = Fmu::unpack(model, standard).and_then(|fmu| match standard {
                Standard::Fmi2 => lifecycle::run(&fmu),
                Standard::Fmi3 => {
                    fmi3::lifecycle::run(&fmu).and_then(|()| fmi3::resized::run(&fmu))
                }
            });
            report(model, standard.name(), result);
        }
    }
    for &model in &models {
        let result = Fmu::unpack_scalar(model).and_then(|fmu| fmi3::lifecycle::run(&fmu));
        report(model, "FMI 3.0 scalar", result);
    }
    if failed {
        std::process::exit(1);
    }
}
