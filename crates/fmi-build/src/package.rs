//! Writes the three FMU archives of a [`Description`] (modelDescription.xml,
//! `binaries/<platform>/<modelIdentifier>` with the platform's library extension,
//! documentation/index.html): FMI 2.0, FMI 3.0 with arrays, FMI 3.0 scalar-only, each
//! a [`Variant`].

use crate::documentation::documentation;
use crate::platform::platform_tuple;
use crate::{fmi2, fmi3};
use robofmu_fmi::description::Description;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use zip::ZipWriter;
use zip::write::SimpleFileOptions;

/// Contents of one FMU.
pub struct FmuContents<'a> {
    pub model_identifier: &'a str,
    pub model_description: &'a str,
    pub documentation: &'a str,
    /// The compiled cdylib of the model.
    pub library: &'a Path,
    /// The folder under `binaries/`: [`platform_folder`] for FMI 2.0,
    /// [`platform_tuple`] for FMI 3.0.
    pub platform: &'a str,
}

/// The FMI 2.0 platform folder of the machine this packager was built for
/// (`binaries/<platform>/`): linux64, darwin64, win64 or their 32-bit forms.
pub fn platform_folder() -> &'static str {
    let bits64 = cfg!(target_pointer_width = "64");
    match (std::env::consts::OS, bits64) {
        ("macos", _) => "darwin64",
        ("windows", true) => "win64",
        ("windows", false) => "win32",
        (_, true) => "linux64",
        (_, false) => "linux32",
    }
}

/// The file name cargo gives the cdylib of the crate `crate_name` on this platform
/// (`librobofmu_pid_fmu.so` for `robofmu-pid-fmu` on Linux).
pub fn library_file_name(crate_name: &str) -> String {
    let stem = crate_name.replace('-', "_");
    format!(
        "{}{stem}{}",
        std::env::consts::DLL_PREFIX,
        std::env::consts::DLL_SUFFIX
    )
}

/// Writes the FMU archive to `out`.
pub fn write_fmu(out: &Path, c: &FmuContents) -> Result<(), String> {
    let binary = std::fs::read(c.library)
        .map_err(|e| format!("{}: cannot read: {e}; build it first", c.library.display()))?;
    let file = File::create(out).map_err(|e| format!("{}: cannot create: {e}", out.display()))?;
    let mut zip = ZipWriter::new(file);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    let library_entry = format!(
        "binaries/{}/{}{}",
        c.platform,
        c.model_identifier,
        std::env::consts::DLL_SUFFIX
    );
    let entries: [(&str, &[u8]); 3] = [
        ("modelDescription.xml", c.model_description.as_bytes()),
        (&library_entry, &binary),
        ("documentation/index.html", c.documentation.as_bytes()),
    ];
    let zip_error = |e: &dyn std::fmt::Display| format!("{}: cannot write: {e}", out.display());
    for (name, data) in entries {
        zip.start_file(name, options).map_err(|e| zip_error(&e))?;
        zip.write_all(data).map_err(|e| zip_error(&e))?;
    }
    zip.finish().map_err(|e| zip_error(&e))?;
    Ok(())
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

    /// The standard's name on the documentation page and its binaries folder.
    fn standard_and_platform(self) -> (&'static str, String) {
        match self {
            Variant::Fmi2 => ("FMI 2.0", platform_folder().to_string()),
            Variant::Fmi3 | Variant::Fmi3Scalar => ("FMI 3.0", platform_tuple()),
        }
    }
}

/// Creates the parent folder of `path`.
pub fn create_parent(path: &Path) -> Result<(), String> {
    let dir = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(dir).map_err(|e| format!("{}: cannot create: {e}", dir.display()))
}

/// Writes `<out>/<folder>/<modelName>.fmu` of every variant of `d` with the cdylib
/// `library`; the paths written.
pub fn package(d: &Description, library: &Path, out: &Path) -> Result<Vec<PathBuf>, String> {
    let mut written = Vec::new();
    for variant in Variant::ALL {
        let path = out
            .join(variant.folder())
            .join(format!("{}.fmu", d.info.model_name));
        create_parent(&path)?;
        let (standard, platform) = variant.standard_and_platform();
        let contents = FmuContents {
            model_identifier: d.info.model_identifier,
            model_description: &variant.model_description(d)?,
            documentation: &documentation(d, standard),
            library,
            platform: &platform,
        };
        write_fmu(&path, &contents)?;
        written.push(path);
    }
    Ok(written)
}
