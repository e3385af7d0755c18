//! Writes the three FMU archives of a [`Description`] (modelDescription.xml,
//! `binaries/<platform>/<modelIdentifier>` with each platform's library extension,
//! documentation/index.html, the FMI-LS-REF files of [`lsref`]): FMI 2.0, FMI 3.0 with arrays, FMI 3.0 scalar-only, each
//! a [`Variant`], with the libraries of every [`Platform`] given.
//!
//! An archive is built in memory and written beside its target, then renamed into
//! place (atomic on one file system: a reader sees the old archive or the new one,
//! never a part); an archive whose bytes would not change is not rewritten (only its
//! modification time is set to now: it is as new as the sources it was compared with).

use crate::documentation::documentation;
use crate::lsref::{self, Case};
use crate::platform::{Platform, fat_mach_o};
use crate::{fmi2, fmi3};
use robofmu_fmi::description::Description;
use std::io::{Cursor, Write};
use std::path::{Path, PathBuf};
use zip::ZipWriter;
use zip::write::SimpleFileOptions;

/// The built library of one platform.
pub struct Library<'a> {
    pub platform: Platform,
    pub path: &'a Path,
}

/// The `binaries/` entries of an FMU of `variant` for `libraries`: each entry's name
/// and the platforms whose library it holds (two for FMI 2.0's universal `darwin64`
/// file), in [`PLATFORMS`](crate::platform::PLATFORMS) order.
pub fn binaries_layout(
    variant: Variant,
    model_identifier: &str,
    platforms: &[Platform],
) -> Vec<(String, Vec<Platform>)> {
    let mut entries: Vec<(String, Vec<Platform>)> = Vec::new();
    for p in platforms {
        let folder = match variant {
            Variant::Fmi2 => p.fmi2_folder,
            Variant::Fmi3 | Variant::Fmi3Scalar => p.tuple,
        };
        let name = format!("binaries/{folder}/{model_identifier}{}", p.extension);
        match entries.iter_mut().find(|(n, _)| *n == name) {
            Some((_, holders)) => holders.push(*p),
            None => entries.push((name, vec![*p])),
        }
    }
    entries
}

/// The bytes of a `binaries/` entry holding the libraries of `holders`: the library
/// itself, or a universal Mach-O file of several.
fn entry_bytes(holders: &[Platform], libraries: &[Library]) -> Result<Vec<u8>, String> {
    let mut slices = Vec::new();
    for holder in holders {
        let library = libraries
            .iter()
            .find(|l| l.platform == *holder)
            .ok_or_else(|| format!("no library of {}", holder.tuple))?;
        slices.push(std::fs::read(library.path).map_err(|e| {
            format!(
                "{}: cannot read: {e}; build it with `bash scripts/build-fmus.sh`",
                library.path.display()
            )
        })?);
    }
    match slices.as_slice() {
        [one] => Ok(one.clone()),
        _ => fat_mach_o(&slices.iter().map(Vec::as_slice).collect::<Vec<_>>()),
    }
}

/// The bytes of a zip archive of `entries` (name, contents), deflated at zlib's best
/// level (9: about 0.5 % smaller binaries than the default 6 at no measurable cost; the
/// zopfli levels above 9 would give 3 % more at seconds per binary), every time stamp
/// 1980-01-01 so that the same entries give the same bytes.
pub fn zip_bytes(entries: &[(String, Vec<u8>)]) -> Result<Vec<u8>, String> {
    let mut zip = ZipWriter::new(Cursor::new(Vec::new()));
    let options = SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .compression_level(Some(9))
        .last_modified_time(zip::DateTime::default());
    for (name, data) in entries {
        zip.start_file(name.as_str(), options)
            .map_err(|e| e.to_string())?;
        zip.write_all(data).map_err(|e| e.to_string())?;
    }
    Ok(zip.finish().map_err(|e| e.to_string())?.into_inner())
}

/// Puts `bytes` at `out`: nothing when the file already holds them (its
/// modification time is set to now), else a write to a file beside it and a rename
/// over it. True when the file was (re)written.
pub fn replace_file(out: &Path, bytes: &[u8]) -> Result<bool, String> {
    let shown = out.display();
    if std::fs::read(out).is_ok_and(|old| old == bytes) {
        std::fs::File::options()
            .append(true)
            .open(out)
            .and_then(|f| f.set_modified(std::time::SystemTime::now()))
            .map_err(|e| format!("{shown}: cannot touch: {e}"))?;
        return Ok(false);
    }
    let name = out
        .file_name()
        .ok_or_else(|| format!("{shown}: not a file name"))?;
    let mut partial = name.to_os_string();
    partial.push(format!(".partial-{}", std::process::id()));
    let partial = out.with_file_name(partial);
    let written = std::fs::write(&partial, bytes)
        .and_then(|()| std::fs::rename(&partial, out))
        .map_err(|e| format!("{shown}: cannot write: {e}"));
    if written.is_err() {
        let _ = std::fs::remove_file(&partial);
    }
    written.map(|()| true)
}

/// The three FMUs of a model: FMI 2.0, FMI 3.0 (arrays) and FMI 3.0 scalar-only.
#[derive(Clone, Copy)]
pub enum Variant {
    Fmi2,
    Fmi3,
    Fmi3Scalar,
}

impl Variant {
    pub const ALL: [Variant; 3] = [Variant::Fmi2, Variant::Fmi3, Variant::Fmi3Scalar];

    /// The folder under the output or descriptions directory ("" for FMI 2.0).
    pub fn folder(self) -> &'static str {
        match self {
            Variant::Fmi2 => "",
            Variant::Fmi3 => "fmi3",
            Variant::Fmi3Scalar => "fmi3-scalar",
        }
    }

    /// The text of this variant's modelDescription.xml.
    pub fn model_description(self, d: &Description) -> Result<String, String> {
        match self {
            Variant::Fmi2 => fmi2::model_description(d),
            Variant::Fmi3 => fmi3::model_description(d),
            Variant::Fmi3Scalar => fmi3::scalar_model_description(d),
        }
    }

    /// `<dir>/<folder>/<modelName>.xml`: where the description is checked in.
    pub fn description_path(self, dir: &Path, d: &Description) -> PathBuf {
        dir.join(self.folder())
            .join(format!("{}.xml", d.info.model_name))
    }

    /// The standard's name on the documentation page.
    fn standard(self) -> &'static str {
        match self {
            Variant::Fmi2 => "FMI 2.0",
            Variant::Fmi3 | Variant::Fmi3Scalar => "FMI 3.0",
        }
    }
}

/// Creates the parent folder of `path`.
pub fn create_parent(path: &Path) -> Result<(), String> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))
}

/// Writes `<out>/<folder>/<modelName>.fmu` of every variant of `d` with the
/// `libraries` of its platforms and the experiments of `cases` (FMI-LS-REF); each path
/// with whether it was (re)written.
pub fn package(
    d: &Description,
    libraries: &[Library],
    cases: &[Case],
    out: &Path,
) -> Result<Vec<(PathBuf, bool)>, String> {
    let platforms: Vec<Platform> = libraries.iter().map(|l| l.platform).collect();
    let mut done = Vec::new();
    for variant in Variant::ALL {
        let path = out
            .join(variant.folder())
            .join(format!("{}.fmu", d.info.model_name));
        create_parent(&path)?;
        let mut entries = vec![(
            "modelDescription.xml".to_string(),
            variant.model_description(d)?.into_bytes(),
        )];
        for (name, holders) in binaries_layout(variant, d.info.model_identifier, &platforms) {
            entries.push((name, entry_bytes(&holders, libraries)?));
        }
        entries.push((
            "documentation/index.html".to_string(),
            documentation(d, variant.standard(), !cases.is_empty()).into_bytes(),
        ));
        entries.extend(lsref::entries(d, cases, variant.standard())?);
        let bytes = zip_bytes(&entries).map_err(|e| format!("{}: {e}", path.display()))?;
        let written = replace_file(&path, &bytes)?;
        done.push((path, written));
    }
    Ok(done)
}
