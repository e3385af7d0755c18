//! The drift check: the three checked-in descriptions of an FMU,
//! `<dir>/<modelName>.xml` (FMI 2.0), `<dir>/fmi3/<modelName>.xml` (FMI 3.0) and
//! `<dir>/fmi3-scalar/<modelName>.xml` (FMI 3.0, scalars only), and the layout of
//! its three FMUs' `binaries/` folders, `<dir>/binaries/<modelName>.txt`, must equal
//! what its [`Description`] and the packager's platform table generate; the
//! workspace packager runs it (`--check`) and rewrites them (`--update`).

use crate::package::{Variant, binaries_layout};
use crate::platform::PLATFORMS;
use robofmu_fmi::description::Description;
use std::path::{Path, PathBuf};

/// `<dir>/binaries/<modelName>.txt`: where the binaries layout of `d` is checked in.
pub fn layout_path(dir: &Path, d: &Description) -> PathBuf {
    dir.join("binaries")
        .join(format!("{}.txt", d.info.model_name))
}

/// The binaries layout of the three FMUs of `d` with all five platforms: one line per
/// `binaries/` entry, the FMU under dist/, the entry, the platforms it holds.
pub fn layout(d: &Description) -> String {
    let mut text = String::from(
        "# The binaries/ entries of this model's FMUs and the platforms each holds \
         (written by robofmu-packager --update; docs/interoperability.md)\n",
    );
    for variant in Variant::ALL {
        let fmu = Path::new(variant.folder()).join(format!("{}.fmu", d.info.model_name));
        for (name, holders) in binaries_layout(variant, d.info.model_identifier, &PLATFORMS) {
            let tuples: Vec<&str> = holders.iter().map(|p| p.tuple).collect();
            text.push_str(&format!("{} {name} {}\n", fmu.display(), tuples.join(" ")));
        }
    }
    text
}

/// The checked-in files of `d` under `dir` (descriptions, binaries layout) that
/// differ from the generated ones (a missing file differs).
pub fn drifted(d: &Description, dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut drifted = Vec::new();
    for (path, text) in generated(d, dir)? {
        if std::fs::read_to_string(&path).ok() != Some(text) {
            drifted.push(path);
        }
    }
    Ok(drifted)
}

/// Writes the three descriptions and the binaries layout of `d` under `dir`; the
/// paths written.
pub fn update(d: &Description, dir: &Path) -> Result<Vec<PathBuf>, String> {
    let mut written = Vec::new();
    for (path, text) in generated(d, dir)? {
        crate::package::create_parent(&path)?;
        std::fs::write(&path, text)
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?;
        written.push(path);
    }
    Ok(written)
}

/// Each checked-in file of `d` under `dir` with the text it must hold.
fn generated(d: &Description, dir: &Path) -> Result<Vec<(PathBuf, String)>, String> {
    let mut files = Vec::new();
    for variant in Variant::ALL {
        files.push((
            variant.description_path(dir, d),
            variant.model_description(d)?,
        ));
    }
    files.push((layout_path(dir, d), layout(d)));
    Ok(files)
}
