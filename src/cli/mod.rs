//! Subcommands of the `robofmu` binary: argument parsing and output only; the
//! computations live in the library.

pub mod dexterity;

/// Any failure of a subcommand, reported on stderr with a non-zero exit code.
pub type CliError = Box<dyn std::error::Error>;
