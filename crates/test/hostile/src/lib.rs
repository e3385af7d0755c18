//! A hostile FMI 2.0 and FMI 3.0 importer for the project's FMUs.
//!
//! It unpacks the packaged `dist/<Model>.fmu` files, opens their binaries with
//! dlopen and calls them through dlsym'd function pointers exactly as a C importer
//! would (no call goes through the Rust library). On top of that it probes them:
//! a matrix of bad inputs and illegal call orders whose every case records the
//! status and log text it expects and why (`matrix`), random sequences of legal
//! calls (`sequences`), load/unload cycles with an RSS bound (`rss`), threads
//! against a serial run (`threads`) and the plant driven into its stops
//! (`plant_hard`). Every probe runs in a forked child (`isolate`), so a crash of an
//! FMU is reported as a failed case with its signal. The machinery (isolation,
//! generator, description reader, judge) serves both standards. The matrix is one
//! for both: each case class is written once over the seam `matrix::seam` and run
//! for FMI 2.0 and FMI 3.0, whose tables (calls, rows, reasons) are in
//! `matrix::fmi2` and `matrix::fmi3`. The sequence bookkeeping (`sequence_run`)
//! is written once on the `standard_interface::StandardInterface` trait; what is
//! per standard (C signatures, instances, state machines) lives in the FMI 2.0
//! modules (`binary`, `host`, `sequences`, `lifecycle`) and in `fmi3`.

/// The FMI 2.0 function table and types (shared with the platform-test host).
pub use robofmu_fmi_host::fmi2 as binary;
pub mod cycles;
pub mod description;
pub mod fmi3;
pub mod fmu;
pub mod foreign;
pub mod forged;
pub mod host;
pub mod isolate;
pub mod lifecycle;
pub mod matrix;
pub mod plant_hard;
pub mod realtime;
pub mod reentry;
pub mod rng;
pub mod sequence_run;
pub mod sequences;
pub mod standard_interface;
pub mod threads;

use binary::Binary;
use fmi3::binary::Binary3;
use fmu::{Fmu, Standard};

/// Every FMU unpacked and loaded (in the parent, before forking): the FMI 2.0
/// archives with their fmi2 functions, the FMI 3.0 archives with their fmi3 ones,
/// both in the order of `fmu::models()`.
pub struct Loaded {
    pub fmus: Vec<Fmu>,
    pub binaries: Vec<Binary>,
    pub fmus3: Vec<Fmu>,
    pub binaries3: Vec<Binary3>,
}

fn unpack_all(standard: Standard) -> Vec<Fmu> {
    fmu::models()
        .iter()
        .map(|m| Fmu::unpack(m, standard).unwrap_or_else(|e| panic!("{e}")))
        .collect()
}

impl Loaded {
    /// Unpacks and opens every FMU of `fmu::models()`, both standards; panics with
    /// the reason.
    pub fn all() -> Loaded {
        Loaded::open(unpack_all(Standard::Fmi2), unpack_all(Standard::Fmi3))
    }

    /// Every binary copied to another path and loaded from there: a second copy of
    /// each library in the process (`Fmu::copy`); panics with the reason.
    pub fn copy(&self) -> Loaded {
        let copy = |fmus: &[Fmu]| -> Vec<Fmu> {
            fmus.iter()
                .map(|f| f.copy().unwrap_or_else(|e| panic!("{e}")))
                .collect()
        };
        Loaded::open(copy(&self.fmus), copy(&self.fmus3))
    }

    /// Opens the binaries of unpacked FMI 2.0 and FMI 3.0 FMUs.
    fn open(fmus: Vec<Fmu>, fmus3: Vec<Fmu>) -> Loaded {
        let binaries = fmus.iter().map(Fmu::open).collect();
        let binaries3 = fmus3.iter().map(Fmu::open3).collect();
        Loaded {
            fmus,
            binaries,
            fmus3,
            binaries3,
        }
    }
}
