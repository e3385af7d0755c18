//! The packaged FMUs under dist/: found, checked to be newer than the sources,
//! unpacked (modelDescription.xml and `binaries/<platform>/<id>.so`) into
//! `target/hostile/<pid>-<model>` (removed when the `Fmu` is dropped) and opened
//! with dlopen.

use crate::binary::Binary;
use crate::description::{self, Description};
use crate::fmi3::binary::Binary3;
use std::io::Read;
use std::path::{Path, PathBuf};
use std::sync::OnceLock;
use std::time::SystemTime;

/// The FMUs the project ships (each as FMI 2.0 and as FMI 3.0), sorted by name: one per
/// checked-in `modelDescription/<Model>.xml`, which the packager writes for every FMU
/// crate, so that adding an FMU changes no list here.
pub fn models() -> &'static [String] {
    static MODELS: OnceLock<Vec<String>> = OnceLock::new();
    MODELS.get_or_init(|| {
        let dir = workspace_root().join("modelDescription");
        let entries = std::fs::read_dir(&dir)
            .unwrap_or_else(|e| panic!("cannot list {}: {e}", dir.display()));
        let mut names: Vec<String> = entries
            .flatten()
            .map(|e| e.path())
            .filter(|p| p.extension().is_some_and(|x| x == "xml"))
            .filter_map(|p| Some(p.file_stem()?.to_str()?.to_string()))
            .collect();
        names.sort();
        names
    })
}

/// The standard of a packaged FMU: `dist/<Model>.fmu` or `dist/fmi3/<Model>.fmu`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Standard {
    Fmi2,
    Fmi3,
}

impl Standard {
    pub const BOTH: [Standard; 2] = [Standard::Fmi2, Standard::Fmi3];

    /// The folder of its archives under dist/.
    fn folder(self) -> &'static str {
        match self {
            Standard::Fmi2 => "",
            Standard::Fmi3 => "fmi3",
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Standard::Fmi2 => "FMI 2.0",
            Standard::Fmi3 => "FMI 3.0",
        }
    }

    /// The platform folder of the Linux x86-64 binary (FMI 2.0 section 2.4, FMI
    /// 3.0 section 2.5.1.1).
    fn platform(self) -> &'static str {
        match self {
            Standard::Fmi2 => "linux64",
            Standard::Fmi3 => "x86_64-linux",
        }
    }
}

/// The workspace root (two levels above this crate).
pub fn workspace_root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../..")
}

/// dist/ of the workspace, or ROBOFMU_HOSTILE_DIST when set.
pub fn dist_dir() -> PathBuf {
    std::env::var_os("ROBOFMU_HOSTILE_DIST")
        .map(PathBuf::from)
        .unwrap_or_else(|| workspace_root().join("dist"))
}

/// An FMU unpacked into a folder of its own.
#[derive(Debug)]
pub struct Fmu {
    pub description: Description,
    pub library: PathBuf,
}

impl Fmu {
    /// Unpacks `dist/<model>.fmu` (FMI 2.0) or `dist/fmi3/<model>.fmu` (FMI 3.0);
    /// an error says how to build it.
    pub fn unpack(model: &str, standard: Standard) -> Result<Fmu, String> {
        Fmu::unpack_from(model, standard, standard.folder())
    }

    /// Unpacks `dist/fmi3-scalar/<model>.fmu`: the FMI 3.0 binary's scalar-only view
    /// (instantiationToken `<guid>-scalar`, read from its description like any token).
    pub fn unpack_scalar(model: &str) -> Result<Fmu, String> {
        Fmu::unpack_from(model, Standard::Fmi3, "fmi3-scalar")
    }

    fn unpack_from(model: &str, standard: Standard, folder: &str) -> Result<Fmu, String> {
        let archive = dist_dir().join(folder).join(format!("{model}.fmu"));
        if !archive.is_file() {
            return Err(format!(
                "{} is missing: run `bash scripts/build-fmus.sh` first",
                archive.display()
            ));
        }
        check_not_stale(&archive)?;
        let file = std::fs::File::open(&archive).map_err(|e| e.to_string())?;
        let mut zip = zip::ZipArchive::new(file).map_err(|e| e.to_string())?;
        let xml = String::from_utf8(entry(&mut zip, "modelDescription.xml")?)
            .map_err(|_| "modelDescription.xml is not UTF-8")?;
        let description = description::parse(&xml)?;
        let binary = format!(
            "binaries/{}/{}.so",
            standard.platform(),
            description.model_identifier
        );
        let unpacked = workspace_root()
            .join("target/hostile")
            .join(format!("{}-{model}{folder}", std::process::id()));
        std::fs::create_dir_all(&unpacked).map_err(|e| e.to_string())?;
        let library = unpacked.join(format!("{}.so", description.model_identifier));
        std::fs::write(&library, entry(&mut zip, &binary)?).map_err(|e| e.to_string())?;
        Ok(Fmu {
            description,
            library,
        })
    }

    /// dlopen of the unpacked binary, its FMI 2.0 functions.
    pub fn open(&self) -> Binary {
        Binary::open(&self.library).unwrap_or_else(|e| panic!("{e}"))
    }

    /// dlopen of the unpacked binary, its FMI 3.0 functions.
    pub fn open3(&self) -> Binary3 {
        Binary3::open(&self.library).unwrap_or_else(|e| panic!("{e}"))
    }

    pub fn name(&self) -> &str {
        &self.description.model_name
    }

    /// The unpacked binary copied to another folder (`<folder>-copy`): loaded from
    /// there, it is a second copy of the library in the process, with its own
    /// statics.
    pub fn copy(&self) -> Result<Fmu, String> {
        let (folder, file) = match (self.library.parent(), self.library.file_name()) {
            (Some(folder), Some(file)) => (folder, file),
            _ => return Err(format!("{} has no folder", self.library.display())),
        };
        let mut name = folder.as_os_str().to_owned();
        name.push("-copy");
        let copied = PathBuf::from(name);
        std::fs::create_dir_all(&copied).map_err(|e| e.to_string())?;
        let library = copied.join(file);
        std::fs::copy(&self.library, &library).map_err(|e| e.to_string())?;
        Ok(Fmu {
            description: self.description.clone(),
            library,
        })
    }
}

impl Drop for Fmu {
    fn drop(&mut self) {
        if let Some(folder) = self.library.parent() {
            let _ = std::fs::remove_dir_all(folder);
        }
    }
}

fn entry(zip: &mut zip::ZipArchive<std::fs::File>, name: &str) -> Result<Vec<u8>, String> {
    let mut f = zip
        .by_name(name)
        .map_err(|e| format!("{name} in the FMU: {e}"))?;
    let mut bytes = Vec::new();
    f.read_to_end(&mut bytes).map_err(|e| e.to_string())?;
    Ok(bytes)
}

/// Refuses an FMU older than the FMI layer (runtime and packager) or FMU sources: it
/// would test old code.
fn check_not_stale(archive: &Path) -> Result<(), String> {
    let built = modified(archive).unwrap_or(SystemTime::UNIX_EPOCH);
    let root = workspace_root();
    let mut folders = vec![
        root.join("crates/fmu/fmi/src"),
        root.join("crates/build/fmi-build/src"),
    ];
    if let Ok(fmus) = std::fs::read_dir(root.join("fmus")) {
        folders.extend(fmus.flatten().map(|e| e.path().join("src")));
    }
    for folder in folders {
        if let Some(newest) = newest_file(&folder)
            && newest > built
        {
            return Err(format!(
                "{} is older than {}: run `bash scripts/build-fmus.sh` to rebuild it",
                archive.display(),
                folder.display()
            ));
        }
    }
    Ok(())
}

fn modified(path: &Path) -> Option<SystemTime> {
    std::fs::metadata(path).and_then(|m| m.modified()).ok()
}

fn newest_file(folder: &Path) -> Option<SystemTime> {
    let mut newest = None;
    for entry in std::fs::read_dir(folder).ok()?.flatten() {
        let path = entry.path();
        let t = if path.is_dir() {
            newest_file(&path)
        } else {
            modified(&path)
        };
        newest = newest.max(t);
    }
    newest
}
