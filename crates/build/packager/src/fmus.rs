//! The FMU crates of the workspace: every `fmus/<folder>/Cargo.toml`, by package
//! name, with the cdylib cargo built for it beside this packager (whose description
//! the packager reads) and those scripts/build-fmus.sh built for each platform.

use robofmu_fmi_build::platform::Platform;
use std::path::{Path, PathBuf};

/// One FMU crate and its built cdylibs.
pub struct FmuCrate {
    pub manifest: PathBuf,
    /// The cdylib built for this machine with this packager (`target/release/`).
    pub library: PathBuf,
    /// The package name (`robofmu-pid-fmu`).
    pub name: String,
}

impl FmuCrate {
    /// The cdylib scripts/build-fmus.sh built for `platform`:
    /// `<target>/<triple>/fmu/<file>` beside the `target_dir` of [`fmu_crates`].
    pub fn platform_library(&self, target_root: &Path, platform: &Platform) -> PathBuf {
        target_root
            .join(platform.target)
            .join("fmu")
            .join(platform.library_file_name(&self.name))
    }
}

/// The FMU crates under `<root>/fmus`, sorted by folder, with their cdylibs in
/// `target_dir`.
pub fn fmu_crates(root: &Path, target_dir: &Path) -> Result<Vec<FmuCrate>, String> {
    let fmus = root.join("fmus");
    let entries = std::fs::read_dir(&fmus).map_err(|e| {
        format!(
            "{}: cannot list: {e}; run the packager from the repository root",
            fmus.display()
        )
    })?;
    let mut manifests: Vec<PathBuf> = entries
        .flatten()
        .map(|e| e.path().join("Cargo.toml"))
        .filter(|p| p.is_file())
        .collect();
    manifests.sort();
    if manifests.is_empty() {
        return Err(format!(
            "{}: no FMU crate (fmus/<name>/Cargo.toml)",
            fmus.display()
        ));
    }
    manifests
        .into_iter()
        .map(|manifest| {
            let name = package_name(&manifest)?;
            let library = target_dir.join(format!(
                "{}{}{}",
                std::env::consts::DLL_PREFIX,
                name.replace('-', "_"),
                std::env::consts::DLL_SUFFIX
            ));
            Ok(FmuCrate {
                manifest,
                library,
                name,
            })
        })
        .collect()
}

/// The `name` of the `[package]` table of a Cargo.toml.
fn package_name(manifest: &Path) -> Result<String, String> {
    let text = std::fs::read_to_string(manifest)
        .map_err(|e| format!("{}: cannot read: {e}", manifest.display()))?;
    let mut in_package = false;
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            in_package = line == "[package]";
        } else if in_package && let Some(value) = line.strip_prefix("name") {
            let value = value.trim_start().strip_prefix('=').map(str::trim);
            if let Some(name) = value.and_then(|v| v.strip_prefix('"')?.strip_suffix('"')) {
                return Ok(name.to_string());
            }
        }
    }
    Err(format!(
        "{}: [package]: no name = \"...\"; give the FMU crate a package name",
        manifest.display()
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_package_name_is_read_from_the_package_table_only() {
        // Expected: the name under [package], not the [lib] name before or after it.
        let dir = std::env::temp_dir().join(format!("robofmu-packager-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let manifest = dir.join("Cargo.toml");
        std::fs::write(
            &manifest,
            "[lib]\nname = \"x_lib\"\n[package]\nversion = \"1\"\nname = \"robofmu-x-fmu\"\n",
        )
        .unwrap();
        assert_eq!(package_name(&manifest).unwrap(), "robofmu-x-fmu");
        std::fs::write(&manifest, "[lib]\nname = \"x_lib\"\n").unwrap();
        let e = package_name(&manifest).unwrap_err();
        assert!(
            e.ends_with("[package]: no name = \"...\"; give the FMU crate a package name"),
            "{e}"
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
