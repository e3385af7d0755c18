//! CSV files and output directories of the `dexterity` subcommands.

use crate::cli::CliError;
use std::fs::{self, File};
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

/// Creates `dir` if needed and returns the path of `name` inside it.
pub fn file_in(dir: &Path, name: &str) -> Result<PathBuf, CliError> {
    fs::create_dir_all(dir).map_err(crate::cli::io_at(dir))?;
    Ok(dir.join(name))
}

/// Writes a CSV file: one header line, then one line per row.
pub fn write_csv(path: &Path, header: &[&str], rows: &[Vec<String>]) -> Result<(), CliError> {
    let fail = crate::cli::io_at(path);
    let mut w = BufWriter::new(File::create(path).map_err(&fail)?);
    writeln!(w, "{}", header.join(",")).map_err(&fail)?;
    for row in rows {
        writeln!(w, "{}", row.join(",")).map_err(&fail)?;
    }
    w.flush().map_err(&fail)?;
    Ok(())
}

/// A value for a CSV cell: empty when absent.
pub fn cell(v: Option<f64>) -> String {
    v.map(|v| format!("{v:.6}")).unwrap_or_default()
}

/// Metres to centimetres for labelled output.
pub fn cm(metres: f64) -> f64 {
    100.0 * metres
}
