//! robofmu-packager: the one packager of the workspace. It finds every FMU crate
//! under `fmus/` and the cdylib `cargo build --release --workspace` wrote for it
//! beside this binary, reads the description the cdylib gives of itself (the symbol
//! `robofmu_fmu_description` of `export_fmu!`), and
//!
//! - writes `<out>/<Model>.fmu` (FMI 2.0), `<out>/fmi3/<Model>.fmu` and
//!   `<out>/fmi3-scalar/<Model>.fmu` (default out: `dist`) with the binaries of the
//!   platforms `--platforms` names (default: all five), each taken from
//!   `target/<triple>/fmu/` where scripts/build-fmus.sh built it, and the test cases of
//!   `tests/references/<Model>/` as the experiments the FMU carries (FMI-LS-REF:
//!   robofmu_fmi_build::lsref); an archive is
//!   replaced atomically, and left as it is when its bytes would not change;
//! - with `--check`, compares every generated modelDescription and the layout of
//!   every FMU's `binaries/` folders with the checked-in ones under
//!   `modelDescription/` (exit 1 when one drifted);
//! - with `--update`, rewrites the checked-in descriptions and layouts.
//!
//! Run it from the repository root. Errors: one line naming the file and the fix,
//! exit 2.

mod fmus;
mod load;

use robofmu_fmi_build::lsref;
use robofmu_fmi_build::package::Library;
use robofmu_fmi_build::platform::{PLATFORMS, Platform};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

const USAGE: &str = "usage: robofmu-packager [--out DIR] [--platforms TUPLE,...] | --check \
                     | --update (from the repository root)";
const DESCRIPTIONS: &str = "modelDescription";
/// The test cases each FMU carries as its experiments (FMI-LS-REF).
const REFERENCES: &str = "tests/references";

enum Command {
    Package {
        out: PathBuf,
        platforms: Vec<Platform>,
    },
    Check,
    Update,
}

fn parse(args: &[String]) -> Result<Command, String> {
    match args {
        [flag] if flag == "--check" => return Ok(Command::Check),
        [flag] if flag == "--update" => return Ok(Command::Update),
        _ => {}
    }
    let mut out = PathBuf::from("dist");
    let mut platforms = PLATFORMS.to_vec();
    let mut rest = args;
    while let [flag, value, tail @ ..] = rest {
        match flag.as_str() {
            "--out" => out = PathBuf::from(value),
            "--platforms" => {
                platforms = value
                    .split(',')
                    .map(Platform::from_tuple)
                    .collect::<Result<_, _>>()
                    .map_err(|e| format!("--platforms: {e}"))?;
            }
            _ => return Err(USAGE.to_string()),
        }
        rest = tail;
    }
    if !rest.is_empty() {
        return Err(USAGE.to_string());
    }
    Ok(Command::Package { out, platforms })
}

/// What went wrong: a user error (exit 2) or drifted descriptions (exit 1).
enum Failure {
    User(String),
    Drift(Vec<PathBuf>),
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(Failure::User(e)) => {
            eprintln!("robofmu-packager: {e}");
            ExitCode::from(2)
        }
        Err(Failure::Drift(paths)) => {
            for path in paths {
                eprintln!(
                    "robofmu-packager: {}: drifted from the code; regenerate it with \
                     `target/release/robofmu-packager --update` after \
                     `cargo build --release --workspace`",
                    path.display()
                );
            }
            ExitCode::from(1)
        }
    }
}

fn run(args: &[String]) -> Result<(), Failure> {
    let command = parse(args).map_err(Failure::User)?;
    let exe = std::env::current_exe()
        .map_err(|e| Failure::User(format!("cannot locate this packager: {e}")))?;
    let target_dir = exe.parent().unwrap_or(Path::new("."));
    let target_root = target_dir.parent().unwrap_or(Path::new("."));
    let crates = fmus::fmu_crates(Path::new("."), target_dir).map_err(Failure::User)?;
    let mut drifted = Vec::new();
    for fmu in &crates {
        let descriptions = Path::new(DESCRIPTIONS);
        let done = load::with_description(&fmu.library, |d| match &command {
            Command::Package { out, platforms } => {
                let paths: Vec<PathBuf> = platforms
                    .iter()
                    .map(|p| fmu.platform_library(target_root, p))
                    .collect();
                let libraries: Vec<Library> = platforms
                    .iter()
                    .zip(&paths)
                    .map(|(p, path)| Library { platform: *p, path })
                    .collect();
                let cases = lsref::read_cases(Path::new(REFERENCES), d.info.model_name)?;
                robofmu_fmi_build::package::package(d, &libraries, &cases, out)
            }
            Command::Check => robofmu_fmi_build::drift::drifted(d, descriptions).map(|paths| {
                drifted.extend(paths);
                Vec::new()
            }),
            Command::Update => robofmu_fmi_build::drift::update(d, descriptions)
                .map(|paths| paths.into_iter().map(|p| (p, true)).collect()),
        })
        .map_err(|e| Failure::User(format!("{e} (FMU crate {})", fmu.manifest.display())))?;
        for (path, written) in done {
            let verb = if written { "wrote" } else { "unchanged" };
            println!("{verb} {}", path.display());
        }
    }
    if !drifted.is_empty() {
        return Err(Failure::Drift(drifted));
    }
    if let Command::Check = command {
        println!(
            "{} FMUs: every checked-in description matches the code",
            crates.len()
        );
    }
    Ok(())
}
