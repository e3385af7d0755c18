//! What the pid crate's layer tests share (each test file includes this module).

use robofmu_fmi::core::ModelInfo;

/// The `ModelInfo` of a test model: no event indicators or log categories; default
/// experiment 0..1 s by 0.1 s.
pub const fn test_info(
    name: &'static str,
    guid: &'static str,
    description: &'static str,
) -> ModelInfo {
    ModelInfo::new(name, guid, description, [0.0, 1.0, 1e-6, 0.1])
}
