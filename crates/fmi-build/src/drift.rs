//! The drift check: the three checked-in descriptions of an FMU,
//! `<dir>/<modelName>.xml` (FMI 2.0), `<dir>/fmi3/<modelName>.xml` (FMI 3.0) and
//! `<dir>/fmi3-scalar/<modelName>.xml` (FMI 3.0, scalars only), must equal what its
//! [`Description`] generates; the workspace packager runs it (`--check`) and rewrites
//! them (`--update`).

use crate::package::Variant;
use robofmu_fmi::description::Description;
use std::path::{Path, PathBuf};

/// The checked-in description files of `d` under `dir` that differ from the generated
/// ones (a missing file differs).
pub fn drifted(d: &Description, dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut drifted = Vec::new();
    for variant in Variant::ALL {
        let path = variant.description_path(dir, d);
        if std::fs::read_to_string(&path).ok() != Some(variant.model_description(d)?) {
            drifted.push(path);
        }
    }
    Ok(drifted)
}

/// Writes the three descriptions of `d` under `dir`; the paths written.
pub fn update(d: &Description, dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut written = Vec::new();
    for variant in Variant::ALL {
        let path = variant.description_path(dir, d);
        crate::package::create_parent(&path)?;
        std::fs::write(&path, variant.model_description(d)?)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}
