//! Writes an FMU archive (modelDescription.xml, `binaries/<platform>/<modelIdentifier>`
//! with the platform's library extension, documentation/index.html), and the small
//! command-line packager that every FMU crate's `examples/package.rs` runs.

use crate::documentation::documentation;
use crate::fmi2::model_description;
use crate::fmi3::{model_description as fmi3_description, scalar_model_description};
use crate::platform::platform_tuple;
use robofmu_fmi::core::model::Model;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use zip::ZipWriter;
use zip::write::SimpleFileOptions;

/// Contents of one FMU.
pub struct FmuContents<'a> {
    pub model_identifier: &'a str,
    pub model_description: &'a str,
    pub documentation: &'a str,
    /// The compiled cdylib of the model.
    pub library: &'a Path,
    /// The folder under `binaries/`: `platform_folder()` for FMI 2.0,
    /// `fmi3::package::platform_tuple()` for FMI 3.0.
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
        .map_err(|e| format!("cannot read {}: {e} (build it first)", c.library.display()))?;
    let file = File::create(out).map_err(|e| format!("cannot create {}: {e}", out.display()))?;
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
    let zip_error = |e: &dyn std::fmt::Display| format!("writing {}: {e}", out.display());
    for (name, data) in entries {
        zip.start_file(name, options).map_err(|e| zip_error(&e))?;
        zip.write_all(data).map_err(|e| zip_error(&e))?;
    }
    zip.finish().map_err(|e| zip_error(&e))?;
    Ok(())
}

const USAGE: &str = "usage: <packager> package [--out DIR] | model-description [--out DIR]";

/// Entry point of an FMU crate's packager (`examples/package.rs` calls it with
/// `env!("CARGO_PKG_NAME")`): `package` writes the FMI 2.0 FMU `<DIR>/<modelName>.fmu`
/// and the FMI 3.0 FMU `<DIR>/fmi3/<modelName>.fmu` (default `dist`) from the cdylib
/// built beside the binary, which exports both; `model-description` writes
/// `<DIR>/<modelName>.xml` and `<DIR>/fmi3/<modelName>.xml` (default
/// `modelDescription`).
pub fn packager_main<M: Model>(crate_name: &str) -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run_packager::<M>(crate_name, &args) {
        Ok(paths) => {
            for path in paths {
                println!("wrote {}", path.display());
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("{crate_name}: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run_packager<M: Model>(crate_name: &str, args: &[String]) -> Result<Vec<PathBuf>, String> {
    let (command, out) = match args {
        [command] => (command.as_str(), None),
        [command, flag, dir] if flag == "--out" => (command.as_str(), Some(PathBuf::from(dir))),
        _ => return Err(USAGE.to_string()),
    };
    let name = M::info().model_name;
    match command {
        "package" => {
            let dir = out.unwrap_or_else(|| PathBuf::from("dist"));
            let mut paths = Vec::new();
            for variant in VARIANTS {
                create_dir(&dir.join(variant.folder()))?;
                let path = dir.join(variant.folder()).join(format!("{name}.fmu"));
                package::<M>(crate_name, &path, variant)?;
                paths.push(path);
            }
            Ok(paths)
        }
        "model-description" => {
            let dir = out.unwrap_or_else(|| PathBuf::from("modelDescription"));
            let mut paths = Vec::new();
            for variant in VARIANTS {
                create_dir(&dir.join(variant.folder()))?;
                let path = dir.join(variant.folder()).join(format!("{name}.xml"));
                std::fs::write(&path, variant.model_description::<M>()?)
                    .map_err(|e| format!("cannot write {}: {e}", path.display()))?;
                paths.push(path);
            }
            Ok(paths)
        }
        _ => Err(USAGE.to_string()),
    }
}

/// The three FMUs of a model: FMI 2.0, FMI 3.0 (arrays) and FMI 3.0 scalar-only.
#[derive(Clone, Copy)]
enum Variant {
    Fmi2,
    Fmi3,
    Fmi3Scalar,
}

const VARIANTS: [Variant; 3] = [Variant::Fmi2, Variant::Fmi3, Variant::Fmi3Scalar];

impl Variant {
    /// The folder under the output directory ("" for FMI 2.0).
    fn folder(self) -> &'static str {
        match self {
            Variant::Fmi2 => "",
            Variant::Fmi3 => "fmi3",
            Variant::Fmi3Scalar => "fmi3-scalar",
        }
    }

    fn model_description<M: Model>(self) -> Result<String, String> {
        match self {
            Variant::Fmi2 => model_description::<M>(),
            Variant::Fmi3 => fmi3_description::<M>(),
            Variant::Fmi3Scalar => scalar_model_description::<M>(),
        }
    }
}

fn create_dir(dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))
}

/// The cdylib of `crate_name` that cargo built for the running packager: the packager
/// is an example (`target/<profile>/examples/`), the cdylib is in `target/<profile>/`.
fn built_library(crate_name: &str) -> Result<PathBuf, String> {
    let exe = std::env::current_exe().map_err(|e| format!("cannot locate the packager: {e}"))?;
    let examples = exe.parent().ok_or("the packager has no parent directory")?;
    let profile = examples.parent().unwrap_or(examples);
    Ok(profile.join(library_file_name(crate_name)))
}

/// Packages M as `variant` from the cdylib that cargo built for the running packager.
fn package<M: Model>(crate_name: &str, out: &Path, variant: Variant) -> Result<(), String> {
    let library = built_library(crate_name)?;
    let (documentation, platform) = match variant {
        Variant::Fmi2 => (
            documentation::<M>("FMI 2.0")?,
            platform_folder().to_string(),
        ),
        Variant::Fmi3 | Variant::Fmi3Scalar => (documentation::<M>("FMI 3.0")?, platform_tuple()),
    };
    let model_description = variant.model_description::<M>()?;
    let contents = FmuContents {
        model_identifier: M::info().model_identifier,
        model_description: &model_description,
        documentation: &documentation,
        library: &library,
        platform: &platform,
    };
    write_fmu(out, &contents)
}
