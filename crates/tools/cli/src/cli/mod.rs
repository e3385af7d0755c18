//! Subcommands of the `robofmu` binary: argument parsing and output only; the
//! computations live in the library.

#[macro_use]
pub mod report;
pub mod args;
pub mod bounds;
pub mod closed_loop;
pub mod dexterity;
pub mod dual_arm;
pub mod pss3;

/// Any failure of a subcommand, reported on stderr with a non-zero exit code
/// ([`report::Usage`] for a refused argument: exit code 2).
pub type CliError = Box<dyn std::error::Error>;

/// The error of writing `path`, naming the file: a path the user gave wrongly (a
/// missing folder, a file where a folder belongs or the reverse, no permission) is a
/// usage error (exit code 2) that says the fix; any other failure (a full disk) exit 1.
pub fn io_at(path: &std::path::Path) -> impl Fn(std::io::Error) -> CliError + '_ {
    use std::io::ErrorKind as K;
    move |e| {
        let shown = path.display();
        let fix = match e.kind() {
            K::NotFound => "its folder does not exist; create it first or give another path",
            K::AlreadyExists | K::NotADirectory => {
                "a file is in the way where a folder belongs; give a folder (it is created)"
            }
            K::IsADirectory => "that is a folder; give a file name",
            K::PermissionDenied | K::ReadOnlyFilesystem => {
                "no permission to write there; give a writable place"
            }
            _ => return format!("cannot write {shown}: {e}").into(),
        };
        report::usage(format!("cannot write {shown}: {e}; {fix}"))
    }
}

/// Refuses an output file `path` whose folder does not exist or that is a folder,
/// before anything is computed (usage errors, exit code 2).
pub fn check_output_file(path: &std::path::Path) -> Result<(), CliError> {
    let folder = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => std::path::Path::new("."),
    };
    if path.is_dir() {
        return Err(report::usage(format!(
            "cannot write {}: that is a folder; give a file name",
            path.display()
        )));
    }
    if !folder.is_dir() {
        return Err(report::usage(format!(
            "cannot write {}: the folder {} does not exist; create it first or give \
             another path",
            path.display(),
            folder.display()
        )));
    }
    Ok(())
}
