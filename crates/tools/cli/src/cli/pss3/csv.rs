//! Minimal CSV output: a header line of quoted column names, then rows of SI numbers.

use crate::cli::CliError;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// Writes `rows` under the quoted column `names` to `path`.
pub fn write_csv(
    path: &Path,
    names: &[&str],
    rows: impl Iterator<Item = Vec<f64>>,
) -> Result<(), CliError> {
    let fail = |e| crate::cli::io_at(path)(e);
    let mut out = BufWriter::new(File::create(path).map_err(fail)?);
    let header: Vec<String> = names.iter().map(|n| format!("\"{n}\"")).collect();
    writeln!(out, "{}", header.join(",")).map_err(fail)?;
    for row in rows {
        let cells: Vec<String> = row.iter().map(|v| format!("{v:e}")).collect();
        writeln!(out, "{}", cells.join(",")).map_err(fail)?;
    }
    out.flush().map_err(fail)?;
    Ok(())
}
