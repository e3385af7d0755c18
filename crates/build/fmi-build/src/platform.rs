//! The platforms every FMU carries and the folders that name them under `binaries/`:
//! FMI 3.0's platform tuples (`x86_64-linux`, section 2.5.1.1 of FMI 3.0) and FMI
//! 2.0's folders (`linux64`, `win64`, `darwin64`, section 2.4 of FMI 2.0), with the
//! Rust target each binary is built for (scripts/build-fmus.sh).
//!
//! FMI 2.0 names no folder for aarch64. The importers decide (docs/interoperability.md
//! has the evidence): FMPy and FMI Library look for `darwin64` on both Mac
//! architectures, so `darwin64` holds one universal (fat) Mach-O file with the x86_64
//! and the arm64 library ([`fat_mach_o`]); on aarch64 Linux they look for `linux64`,
//! which the x86_64 library holds, so the aarch64 Linux library goes to the FMI 3.0
//! tuple `aarch64-linux` (the FMI 3.0 FMUs are what an aarch64 Linux user imports).

/// One platform the FMUs carry.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Platform {
    /// The FMI 3.0 platform tuple: the folder under `binaries/` of FMI 3.0 FMUs.
    pub tuple: &'static str,
    /// The Rust target triple of its binary.
    pub target: &'static str,
    /// The folder under `binaries/` of FMI 2.0 FMUs.
    pub fmi2_folder: &'static str,
    /// The library file prefix cargo gives a cdylib on this platform.
    pub prefix: &'static str,
    /// The extension of a shared library on this platform, with its dot.
    pub extension: &'static str,
}

/// The five platforms, in the order the packager writes them.
pub const PLATFORMS: [Platform; 5] = [
    Platform {
        tuple: "x86_64-linux",
        target: "x86_64-unknown-linux-gnu",
        fmi2_folder: "linux64",
        prefix: "lib",
        extension: ".so",
    },
    Platform {
        tuple: "aarch64-linux",
        target: "aarch64-unknown-linux-gnu",
        fmi2_folder: "aarch64-linux",
        prefix: "lib",
        extension: ".so",
    },
    Platform {
        tuple: "x86_64-windows",
        target: "x86_64-pc-windows-gnu",
        fmi2_folder: "win64",
        prefix: "",
        extension: ".dll",
    },
    Platform {
        tuple: "x86_64-darwin",
        target: "x86_64-apple-darwin",
        fmi2_folder: "darwin64",
        prefix: "lib",
        extension: ".dylib",
    },
    Platform {
        tuple: "aarch64-darwin",
        target: "aarch64-apple-darwin",
        fmi2_folder: "darwin64",
        prefix: "lib",
        extension: ".dylib",
    },
];

impl Platform {
    /// The platform of an FMI 3.0 tuple, or an error listing the known ones.
    pub fn from_tuple(tuple: &str) -> Result<Platform, String> {
        PLATFORMS
            .iter()
            .find(|p| p.tuple == tuple)
            .copied()
            .ok_or_else(|| {
                let known: Vec<&str> = PLATFORMS.iter().map(|p| p.tuple).collect();
                format!(
                    "unknown platform {tuple:?}; use one of {}",
                    known.join(", ")
                )
            })
    }

    /// The file name cargo gives the cdylib of the crate `crate_name` on this
    /// platform (`robofmu_pid_fmu.dll` for `robofmu-pid-fmu` on Windows).
    pub fn library_file_name(&self, crate_name: &str) -> String {
        format!(
            "{}{}{}",
            self.prefix,
            crate_name.replace('-', "_"),
            self.extension
        )
    }
}

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

/// The CPU type of a thin 64-bit little-endian Mach-O file (`MH_MAGIC_64`), with
/// its subtype.
fn mach_o_cpu(bytes: &[u8]) -> Option<(u32, u32)> {
    let word = |at: usize| Some(u32::from_le_bytes(bytes.get(at..at + 4)?.try_into().ok()?));
    (word(0)? == 0xfeed_facf).then_some((word(4)?, word(8)?))
}

/// A universal ("fat") Mach-O file holding the thin 64-bit libraries `slices`, each
/// at an offset aligned to 2^14 bytes (the arm64 page size), as `lipo -create`
/// writes it: the big-endian `fat_header` (magic 0xcafebabe, count) and one
/// `fat_arch` (cputype, cpusubtype, offset, size, align) per slice. Each slice keeps
/// its own code signature.
pub fn fat_mach_o(slices: &[&[u8]]) -> Result<Vec<u8>, String> {
    const ALIGN: u32 = 14;
    let align = 1usize << ALIGN;
    let mut header = Vec::new();
    header.extend(0xcafe_babe_u32.to_be_bytes());
    header.extend((slices.len() as u32).to_be_bytes());
    let mut offset = align;
    let mut body = Vec::new();
    for slice in slices {
        let (cpu, subtype) =
            mach_o_cpu(slice).ok_or("a slice of a universal binary is no 64-bit Mach-O file")?;
        let (Ok(at), Ok(size)) = (u32::try_from(offset), u32::try_from(slice.len())) else {
            return Err("a universal binary over 4 GiB".to_string());
        };
        for field in [cpu, subtype, at, size, ALIGN] {
            header.extend(field.to_be_bytes());
        }
        body.resize(offset - align, 0);
        body.extend_from_slice(slice);
        offset = (align + body.len()).next_multiple_of(align);
    }
    header.resize(align, 0);
    header.extend(body);
    Ok(header)
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

    #[test]
    fn the_host_platform_is_one_of_the_five() {
        // Expected: this machine's tuple (when it is one we ship) names the library
        // the way cargo does here (std::env::consts), an independent source.
        if let Ok(p) = Platform::from_tuple(&platform_tuple()) {
            assert_eq!(
                p.library_file_name("robofmu-pid-fmu"),
                format!(
                    "{}robofmu_pid_fmu{}",
                    std::env::consts::DLL_PREFIX,
                    std::env::consts::DLL_SUFFIX
                )
            );
        }
        let e = Platform::from_tuple("x86_64-solaris").unwrap_err();
        assert!(e.starts_with("unknown platform \"x86_64-solaris\"; use one of x86_64-linux, "));
    }

    #[test]
    fn a_fat_file_lists_each_slice_at_an_aligned_offset() {
        // Expected: the fat_header/fat_arch layout of <mach-o/fat.h> (big-endian), by
        // hand: two slices of 40 and 36 bytes at 16384 and 32768.
        let thin = |cpu: u32, len: usize| {
            let mut b = vec![0u8; len];
            b[..4].copy_from_slice(&0xfeed_facf_u32.to_le_bytes());
            b[4..8].copy_from_slice(&cpu.to_le_bytes());
            b[len - 1] = 7;
            b
        };
        let (x86, arm) = (thin(0x0100_0007, 40), thin(0x0100_000c, 36));
        let fat = fat_mach_o(&[&x86, &arm]).unwrap();
        let be = |at: usize| u32::from_be_bytes(fat[at..at + 4].try_into().unwrap());
        assert_eq!((be(0), be(4)), (0xcafe_babe, 2));
        assert_eq!(
            [be(8), be(16), be(20), be(24)],
            [0x0100_0007, 16384, 40, 14]
        );
        assert_eq!(
            [be(28), be(36), be(40), be(44)],
            [0x0100_000c, 32768, 36, 14]
        );
        assert_eq!(&fat[16384..16424], &x86[..]);
        assert_eq!(&fat[32768..], &arm[..]);
        assert!(fat_mach_o(&[b"not mach-o"]).is_err());
    }
}
