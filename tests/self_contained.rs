//! The repository stands on its own: no file in it points to the team's private
//! working material beside the repository (the folder `shared` next to it). What the
//! code and the docs need from there is restated in docs/ (3pss-model.md,
//! dexterity-data.md, dual-arm-data.md).

use std::path::{Path, PathBuf};
use std::process::Command;

/// References that would only resolve on a machine with the private folder. Built with
/// `concat!` so that this file does not contain them.
const FORBIDDEN: [&str; 2] = [concat!("..", "/shared"), concat!("shared", "/spec")];

/// Runs git in `dir` and returns its standard output; panics with git's message.
fn git(dir: &Path, args: &[&str]) -> Vec<u8> {
    let out = Command::new("git")
        .current_dir(dir)
        .args(args)
        .output()
        .expect("git must be installed to list the repository's files");
    assert!(
        out.status.success(),
        "git {args:?} failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out.stdout
}

/// Every file git tracks or would track (untracked but not ignored), as paths.
fn repository_files() -> Vec<PathBuf> {
    let here = Path::new(env!("CARGO_MANIFEST_DIR"));
    let top = String::from_utf8(git(here, &["rev-parse", "--show-toplevel"])).unwrap();
    let top = PathBuf::from(top.trim_end());
    let listing = git(
        &top,
        &[
            "ls-files",
            "-z",
            "--cached",
            "--others",
            "--exclude-standard",
        ],
    );
    listing
        .split(|&b| b == 0)
        .filter(|name| !name.is_empty())
        .map(|name| top.join(String::from_utf8_lossy(name).as_ref()))
        .collect()
}

#[test]
fn no_file_points_outside_the_repository_to_the_private_spec() {
    // Truth: the list of files from git and a plain substring search of each.
    let files = repository_files();
    assert!(
        files.iter().any(|f| f.ends_with("docs/3pss-model.md")),
        "the listing must include the docs (got {} files)",
        files.len()
    );
    let mut offenders = Vec::new();
    for file in &files {
        // A tracked file deleted in the work tree is not part of what is checked in next.
        let Ok(bytes) = std::fs::read(file) else {
            continue;
        };
        let text = String::from_utf8_lossy(&bytes);
        for (number, line) in text.lines().enumerate() {
            if FORBIDDEN.iter().any(|pattern| line.contains(pattern)) {
                offenders.push(format!("{}:{}: {line}", file.display(), number + 1));
            }
        }
    }
    assert!(
        offenders.is_empty(),
        "files point to the private spec outside the repository; restate what they need \
         in docs/ and point there instead:\n{}",
        offenders.join("\n")
    );
}
