//! `robofmu fmi ...`: modelDescription files and FMU packaging.

use super::CliError;
use clap::{Args, Subcommand};
use robofmu::fmi2::package::{FmuContents, write_fmu};
use robofmu::fmus;
use std::path::PathBuf;

#[derive(Args)]
pub struct FmiArgs {
    #[command(subcommand)]
    command: FmiCommand,
}

#[derive(Subcommand)]
enum FmiCommand {
    /// Regenerate modelDescription/MODEL.xml from the code (the checked-in copies).
    WriteModelDescriptions {
        /// Directory to write into.
        #[arg(long, default_value = "modelDescription")]
        dir: PathBuf,
    },
    /// Package every FMU as OUT/MODEL.fmu from the release cdylibs.
    Package {
        /// Directory holding the built cdylibs (lib*.so).
        #[arg(long, default_value = "target/release")]
        libraries: PathBuf,
        /// Output directory.
        #[arg(long, default_value = "dist")]
        out: PathBuf,
    },
}

pub fn run(args: FmiArgs) -> Result<(), CliError> {
    match args.command {
        FmiCommand::WriteModelDescriptions { dir } => {
            std::fs::create_dir_all(&dir)?;
            for fmu in fmus::all() {
                let path = dir.join(format!("{}.xml", fmu.model_name));
                std::fs::write(&path, (fmu.model_description)()?)?;
                println!("wrote {}", path.display());
            }
        }
        FmiCommand::Package { libraries, out } => {
            std::fs::create_dir_all(&out)?;
            for fmu in fmus::all() {
                let path = out.join(format!("{}.fmu", fmu.model_name));
                let model_description = (fmu.model_description)()?;
                let documentation = (fmu.documentation)()?;
                let library = libraries.join(fmu.library_file);
                let contents = FmuContents {
                    model_identifier: fmu.model_identifier,
                    model_description: &model_description,
                    documentation: &documentation,
                    library: &library,
                };
                write_fmu(&path, &contents)?;
                println!("wrote {}", path.display());
            }
        }
    }
    Ok(())
}
