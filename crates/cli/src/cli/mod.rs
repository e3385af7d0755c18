//! Subcommands of the `robofmu` binary: argument parsing and output only; the
//! computations live in the library.

pub mod args;
pub mod closed_loop;
pub mod dexterity;
pub mod dual_arm;
pub mod pss3;

/// Any failure of a subcommand, reported on stderr with a non-zero exit code.
pub type CliError = Box<dyn std::error::Error>;
