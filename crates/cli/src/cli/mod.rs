//! Subcommands of the `robofmu` binary: argument parsing and output only; the
//! computations live in the library.

#[macro_use]
pub mod report;
pub mod args;
pub mod bounds;
pub mod closed_loop;
pub mod dexterity;
pub mod dual_arm;
pub mod pss3;

/// Any failure of a subcommand, reported on stderr with a non-zero exit code
/// ([`report::Usage`] for a refused argument: exit code 2).
pub type CliError = Box<dyn std::error::Error>;

/// The error of an I/O operation on `path`, naming the file.
pub fn io_at(path: &std::path::Path) -> impl Fn(std::io::Error) -> CliError + '_ {
    move |e| format!("cannot write {}: {e}", path.display()).into()
}
