//! FMI 3.0 packaging: the platform tuple that names the binaries folder
//! (`binaries/x86_64-linux/`, section 2.5.1.1 of FMI 3.0) and the texts of an FMI 3.0
//! FMU; the zip is written by the shared packager.

/// The FMI 3.0 platform tuple `<arch>-<sys>` of the machine this code was built for.
pub fn platform_tuple() -> String {
    let arch = match std::env::consts::ARCH {
        "arm" => "aarch32",
        "powerpc" => "ppc32",
        "powerpc64" => "ppc64",
        other => other,
    };
    let system = match std::env::consts::OS {
        "macos" => "darwin",
        other => other,
    };
    format!("{arch}-{system}")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_platform_tuple_names_architecture_and_system() {
        // Expected: the tuples of FMI 3.0 section 2.5.1.1 for the machines we build on.
        let tuple = platform_tuple();
        #[cfg(all(target_arch = "x86_64", target_os = "linux"))]
        assert_eq!(tuple, "x86_64-linux");
        #[cfg(all(target_arch = "aarch64", target_os = "macos"))]
        assert_eq!(tuple, "aarch64-darwin");
        assert!(tuple.contains('-'));
    }
}
