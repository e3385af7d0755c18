//! How the binary ends: one line on stderr and the exit code for every failure, and
//! the quiet end when the reader of standard output has gone (`robofmu ... | head`).
//!
//! Exit codes: 0 success; 1 the computation ran and failed (no convergence, a pose
//! outside the workspace, a disk that is full); 2 a usage error (an argument refused
//! before anything ran, with the argument named and what is allowed, or an output path
//! that cannot be written where it points: a missing folder, a file in the way, no
//! permission).

use clap::error::ErrorKind;
use std::io::Write;
use std::process::ExitCode;

/// An argument refused before any computation: exit code 2.
#[derive(Debug)]
pub struct Usage(pub String);

impl std::fmt::Display for Usage {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for Usage {}

/// A usage error with this message.
pub fn usage(message: impl Into<String>) -> super::CliError {
    Box::new(Usage(message.into()))
}

/// Exit code 2 for a usage error, 1 for any other; the message on one line.
pub fn failure(error: &(dyn std::error::Error + 'static)) -> ExitCode {
    let code = if error.is::<Usage>() { 2 } else { 1 };
    say_error(&error.to_string());
    ExitCode::from(code)
}

/// clap's verdict on the command line: help and version as clap prints them, every
/// other error as one line (its first paragraph, the argument named) and exit code 2.
pub fn parse_error(error: &clap::Error) -> ExitCode {
    match error.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            let text = error.render().to_string();
            print_quietly(&text);
            ExitCode::SUCCESS
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // `robofmu` or `robofmu pss3` alone: the help of that level, a usage error.
            let _ = write!(std::io::stderr(), "{}", error.render());
            ExitCode::from(2)
        }
        _ => {
            let text = error.render().to_string();
            let first = text.split("\n\n").next().unwrap_or("");
            let line = first.trim_start_matches("error: ");
            say_error(&format!("{line}; see --help"));
            ExitCode::from(2)
        }
    }
}

/// `robofmu: MESSAGE` on stderr, the message's lines joined into one.
fn say_error(message: &str) {
    let line = message.split_whitespace().collect::<Vec<_>>().join(" ");
    // Nothing more can be done when stderr itself is closed.
    let _ = writeln!(std::io::stderr(), "robofmu: {line}");
}

/// Writes to stdout; a closed stdout ends the process quietly (see [`stdout_failed`]).
pub fn print_quietly(text: &str) {
    let mut out = std::io::stdout().lock();
    if let Err(e) = out.write_all(text.as_bytes()).and_then(|()| out.flush()) {
        stdout_failed(&e);
    }
}

/// The end of the process when stdout cannot be written: quietly with exit code 0 when
/// its reader has gone (a broken pipe: the reader took what it wanted), else one line
/// and exit code 1.
pub fn stdout_failed(error: &std::io::Error) -> ! {
    if error.kind() == std::io::ErrorKind::BrokenPipe {
        std::process::exit(0);
    }
    say_error(&format!("cannot write to standard output: {error}"));
    std::process::exit(1);
}

/// `outln!` that ends the process quietly when stdout's reader has gone, where
/// `outln!` panics.
macro_rules! outln {
    () => {
        $crate::cli::report::print_quietly("\n")
    };
    ($($arg:tt)*) => {
        $crate::cli::report::print_quietly(&format!("{}\n", format_args!($($arg)*)))
    };
}
