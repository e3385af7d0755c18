//! A hostile FMI 2.0 importer for the project's FMUs.
//!
//! It unpacks the packaged `dist/<Model>.fmu` files, opens their binaries with
//! dlopen and calls them through dlsym'd function pointers exactly as a C importer
//! would (no call goes through the Rust library). On top of that it probes them:
//! a matrix of bad inputs and illegal call orders whose every case records the
//! status and log text it expects and why (`matrix`), random sequences of legal
//! calls (`sequences`), load/unload cycles with an RSS bound (`rss`), threads
//! against a serial run (`threads`) and the plant driven into its stops
//! (`plant_hard`). Every probe runs in a forked child (`isolate`), so a crash of an
//! FMU is reported as a failed case with its signal.

pub mod binary;
pub mod cycles;
pub mod description;
pub mod fmu;
pub mod host;
pub mod isolate;
pub mod lifecycle;
pub mod matrix;
pub mod plant_hard;
pub mod rng;
pub mod sequences;
pub mod threads;

use binary::Binary;
use fmu::Fmu;

/// Every FMU unpacked and loaded (in the parent, before forking).
pub struct Loaded {
    pub fmus: Vec<Fmu>,
    pub binaries: Vec<Binary>,
}

impl Loaded {
    /// Unpacks and opens every FMU of `fmu::MODELS`; panics with the reason.
    pub fn all() -> Loaded {
        let fmus: Vec<Fmu> = fmu::MODELS
            .iter()
            .map(|m| Fmu::unpack(m).unwrap_or_else(|e| panic!("{e}")))
            .collect();
        let binaries = fmus.iter().map(Fmu::open).collect();
        Loaded { fmus, binaries }
    }
}
