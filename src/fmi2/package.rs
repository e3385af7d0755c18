//! Writes an FMU archive: modelDescription.xml, `binaries/linux64/<modelIdentifier>.so`
//! and documentation/index.html.

use std::fs::File;
use std::io::Write;
use std::path::Path;
use zip::ZipWriter;
use zip::write::SimpleFileOptions;

/// Contents of one FMU.
pub struct FmuContents<'a> {
    pub model_identifier: &'a str,
    pub model_description: &'a str,
    pub documentation: &'a str,
    /// The compiled cdylib of the model.
    pub library: &'a Path,
}

/// Writes the FMU archive to `out`.
pub fn write_fmu(out: &Path, c: &FmuContents) -> Result<(), String> {
    let binary = std::fs::read(c.library)
        .map_err(|e| format!("cannot read {}: {e} (build it first)", c.library.display()))?;
    let file = File::create(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    let library_entry = format!("binaries/linux64/{}.so", c.model_identifier);
    let entries: [(&str, &[u8]); 3] = [
        ("modelDescription.xml", c.model_description.as_bytes()),
        (&library_entry, &binary),
        ("documentation/index.html", c.documentation.as_bytes()),
    ];
    let zip_error = |e: &dyn std::fmt::Display| format!("writing {}: {e}", out.display());
    for (name, data) in entries {
        zip.start_file(name, options).map_err(|e| zip_error(&e))?;
        zip.write_all(data).map_err(|e| zip_error(&e))?;
    }
    zip.finish().map_err(|e| zip_error(&e))?;
    Ok(())
}
