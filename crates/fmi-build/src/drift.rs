//! The drift check of an FMU crate: the three checked-in descriptions of model M,
//! `modelDescription/<modelName>.xml` (FMI 2.0),
//! `modelDescription/fmi3/<modelName>.xml` (FMI 3.0) and
//! `modelDescription/fmi3-scalar/<modelName>.xml` (FMI 3.0, scalars only), must equal
//! what the code generates. With the environment variable UPDATE_MODEL_DESCRIPTION set,
//! the files are rewritten first.

use robofmu_fmi::core::model::Model;
use std::path::Path;

/// Checks the three descriptions of M for the FMU crate at `manifest_dir` (its
/// `CARGO_MANIFEST_DIR`, two levels below the workspace root); the error names every
/// file that drifted.
pub fn check_checked_in<M: Model>(manifest_dir: &str) -> Result<(), String> {
    let dir = Path::new(manifest_dir).join("../../modelDescription");
    let errors: Vec<String> = [
        crate::fmi2::check_checked_in::<M>(&dir),
        crate::fmi3::check_checked_in::<M>(&dir.join("fmi3")),
        crate::fmi3::check_scalar_checked_in::<M>(&dir.join("fmi3-scalar")),
    ]
    .into_iter()
    .filter_map(Result::err)
    .collect();
    if errors.is_empty() {
        Ok(())
    } else {
        Err(errors.join("; "))
    }
}
