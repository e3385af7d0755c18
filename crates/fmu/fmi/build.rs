//! Hashes the layer's sources into ROBOFMU_FMI_SOURCE_HASH: part of the fingerprint
//! of `description::Header`, so that a packager refuses a cdylib built from other
//! sources of this layer (whose Rust types may differ).

use std::hash::{Hash, Hasher};
use std::path::Path;

fn hash_dir(dir: &Path, hasher: &mut impl Hasher) {
    let mut entries: Vec<_> = std::fs::read_dir(dir)
        .expect("src/ is readable")
        .flatten()
        .map(|e| e.path())
        .collect();
    entries.sort();
    for path in entries {
        if path.is_dir() {
            hash_dir(&path, hasher);
        } else {
            path.strip_prefix("src").unwrap_or(&path).hash(hasher);
            std::fs::read(&path)
                .expect("a source is readable")
                .hash(hasher);
        }
    }
}

fn main() {
    println!("cargo:rerun-if-changed=src");
    let mut hasher = std::collections::hash_map::DefaultHasher::new();
    hash_dir(Path::new("src"), &mut hasher);
    println!(
        "cargo:rustc-env=ROBOFMU_FMI_SOURCE_HASH={:016x}",
        hasher.finish()
    );
}
