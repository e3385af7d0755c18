#!/usr/bin/env bash
# Builds the workspace in release mode, cross-builds every FMU crate under fmus/ for the
# five platforms the FMUs carry, and packages them into dist/<Model>.fmu (FMI 2.0),
# dist/fmi3/<Model>.fmu (FMI 3.0) and dist/fmi3-scalar/<Model>.fmu (FMI 3.0, scalars
# only), all from the same cdylib of each platform (modelDescription.xml,
# binaries/<platform>/<modelIdentifier>.<ext>, documentation/).
#
# Platforms (docs/interoperability.md): x86_64-linux and aarch64-linux (glibc 2.17 and
# newer), x86_64-windows, x86_64-darwin and aarch64-darwin (macOS 10.12 / 11 and newer).
# One cargo call per platform and library, `--profile fmu` (release, whole-program LTO,
# symbols stripped). Linux and macOS are linked by zig (`cargo-zigbuild`; ziglang and
# cargo-zigbuild come from PyPI, pinned in scripts/toolchain-requirements.txt, into
# target/toolchain/venv); Windows by MinGW-w64's gcc (Debian's gcc-mingw-w64-x86-64,
# installed with apt-get when this runs as root), which honours the export list rustc
# gives it (zig's linker exported every symbol) and links libgcc and winpthread
# statically. Each platform's standard library comes from `rustup target add`. A platform whose toolchain cannot be
# had is left out of every FMU and named, with the reason, at the end of the output and
# in target/toolchain/platforms.txt (the platform tests report it as skipped); nothing
# is left out silently. The workspace packager target/release/robofmu-packager
# (crates/build/packager) finds the FMU crates and reads each cdylib's description of itself,
# so adding an FMU needs no change here.
#
# Usage: bash scripts/build-fmus.sh
# A development build may name the platforms to build, comma-separated
# (ROBOFMU_PLATFORMS=x86_64-linux bash scripts/build-fmus.sh); the others are recorded
# as missing with that reason, as a platform whose toolchain is missing is.
set -euo pipefail
cd "$(dirname "$0")/.."

cargo build --release --workspace

tools=target/toolchain
record="$tools/platforms.txt"
mkdir -p "$tools"
: >"$record.new"

# platform tuple, Rust target (with zig's glibc version for Linux).
platforms=(
    "x86_64-linux x86_64-unknown-linux-gnu.2.17"
    "aarch64-linux aarch64-unknown-linux-gnu.2.17"
    "x86_64-windows x86_64-pc-windows-gnu"
    "x86_64-darwin x86_64-apple-darwin"
    "aarch64-darwin aarch64-apple-darwin"
)

missing() { # tuple, reason
    echo "$1 missing $2" >>"$record.new"
    echo "build-fmus: $1 is MISSING from every FMU: $2" >&2
}

# zig and cargo-zigbuild.
requirements=scripts/toolchain-requirements.txt
stamp="$tools/venv/.requirements-installed"
zig_error=""
if ! { [[ -f "$stamp" ]] && cmp -s "$requirements" "$stamp"; }; then
    if python3 -m venv "$tools/venv" >"$tools/venv.log" 2>&1 &&
        "$tools/venv/bin/python" -m pip install --quiet --disable-pip-version-check \
            -r "$requirements" >>"$tools/venv.log" 2>&1; then
        cp "$requirements" "$stamp"
    else
        zig_error="ziglang/cargo-zigbuild could not be installed from PyPI ($(tail -n 1 "$tools/venv.log"))"
    fi
fi
export PATH="$PWD/$tools/venv/bin:$PATH"

packages=()
for manifest in fmus/*/Cargo.toml; do
    packages+=(-p "$(sed -n 's/^name = "\(.*\)"$/\1/p' "$manifest" | head -n 1)")
done

# Builds the FMU crates (and the test hosts) for $tuple/$target with "${build[@]}" (a
# cargo that takes `rustc`'s arguments), $flags (the platform's RUSTFLAGS) and, on macOS,
# $minimum. One cargo call per library, each as a cdylib only: the crates are also rlibs
# (for their tests), and cargo applies the profile's link-time optimisation only to a
# build whose crate types allow it. Whole-program LTO is what makes the binaries small
# (docs/release.md): the standard library is optimised with the FMU, its unused code
# dropped (Windows' prebuilt standard library has no per-function sections, so the
# linker cannot drop it), and every Rust symbol not exported becomes internal (zig's
# Mach-O linker ignores rustc's export list, so on macOS only LTO hides them).
build_library() { # package, library file name (without prefix/extension)
    local extra=() environment=("$variable=$flags")
    # macOS: the install name @rpath/<file> instead of the build folder's path.
    if [[ "$tuple" == *-darwin ]]; then
        extra=(-C "link-arg=-Wl,-install_name,@rpath/lib$2.dylib")
        environment+=(MACOSX_DEPLOYMENT_TARGET="$minimum")
    fi
    env "${environment[@]}" \
        "${build[@]}" --profile fmu --target "$target" -p "$1" --lib --crate-type cdylib -- \
        "${extra[@]}"
}

build_platform() {
    variable="CARGO_TARGET_$(echo "$triple" | tr 'a-z-' 'A-Z_')_RUSTFLAGS"
    flags="" minimum=""
    if [[ "$tuple" == *-linux ]]; then
        # scripts/toolchain/finalize.c: the unload-time __cxa_finalize that gcc's C
        # runtime objects give a shared library and zig's link does not. The stub
        # libgcc_s (scripts/toolchain/libgcc_s.c, built here by zig for the target):
        # the binaries use the process's unwinder, libgcc_s.so.1, instead of a copy
        # of LLVM's libunwind that zig would link in (the stub is linked first, so
        # nothing of that copy is needed).
        local stub="$PWD/$tools/libgcc_s/$triple"
        mkdir -p "$stub"
        "$tools/venv/bin/python" -m ziglang cc -target "${target/unknown-linux-gnu/linux-gnu}" \
            -shared -nostdlib -o "$stub/libgcc_s_stub.so" scripts/toolchain/libgcc_s.c \
            -Wl,--version-script=scripts/toolchain/libgcc_s.map -Wl,-soname,libgcc_s.so.1 ||
            return 1
        flags="-C link-arg=$PWD/scripts/toolchain/finalize.c -L native=$stub -l dylib=gcc_s_stub"
    elif [[ "$tuple" == *-darwin ]]; then
        # macOS: the minimum version (Rust's default for the target, stated in
        # docs/interoperability.md); -dead_strip_dylibs drops libiconv, which the libc
        # crate names but nothing calls, so that only libSystem is linked. zig signs
        # the arm64 library ad hoc as it links it; nothing strips it afterwards (that
        # would void the signature): LTO leaves only the exported symbols global.
        minimum=10.12
        [[ "$tuple" == aarch64-* ]] && minimum=11.0
        flags="-C link-arg=-Wl,-dead_strip_dylibs"
    fi
    local i
    for ((i = 1; i < ${#packages[@]}; i += 2)); do
        build_library "${packages[i]}" "${packages[i]//-/_}" || return 1
    done
    build_library robofmu-cosim-kernel cosim_kernel || return 1
    # The platform-test host (not on macOS: nothing runs it there).
    if [[ "$tuple" != *-darwin ]]; then
        env "$variable=$flags" "${build[@]}" --profile fmu --target "$target" \
            -p robofmu-fmi-host --bin robofmu-platform-host
    fi
}

# Two platforms build at once, each in a target folder of its own
# (target/platforms/<tuple>: cargo locks a target folder for a whole build), so that
# their link-time optimisations, one core each, overlap; what a platform built is then
# copied to target/<triple>/fmu/, where the packager, the tests and the wheel read it.
at_once=2
launch() { # builds $tuple in the background; "built" in $tools/outcome-$tuple if it did
    rm -f "$tools/outcome-$tuple"
    (
        export CARGO_TARGET_DIR="$PWD/target/platforms/$tuple"
        if build_platform >"$tools/build-$tuple.log" 2>&1; then
            mkdir -p "target/$triple/fmu"
            find "$CARGO_TARGET_DIR/$triple/fmu" -maxdepth 1 -type f ! -name '*.d' \
                -exec cp -p {} "target/$triple/fmu/" \; &&
                echo built >"$tools/outcome-$tuple"
        fi
    ) &
}

launched=()
for entry in "${platforms[@]}"; do
    read -r tuple target <<<"$entry"
    triple="${target%.2.17}"
    if [[ -n "${ROBOFMU_PLATFORMS:-}" && ",$ROBOFMU_PLATFORMS," != *",$tuple,"* ]]; then
        missing "$tuple" "left out by ROBOFMU_PLATFORMS=$ROBOFMU_PLATFORMS (a development build)"
        continue
    fi
    if [[ -n "$zig_error" ]]; then
        missing "$tuple" "$zig_error"
        continue
    fi
    if ! rustc --print target-libdir --target "$triple" >/dev/null 2>&1 ||
        [[ ! -d "$(rustc --print target-libdir --target "$triple")" ]]; then
        if ! command -v rustup >/dev/null 2>&1; then
            missing "$tuple" "Rust's standard library for $triple is not installed and there is no rustup to add it"
            continue
        fi
        if ! rustup target add "$triple" >"$tools/rustup-$triple.log" 2>&1; then
            missing "$tuple" "rustup target add $triple failed: $(tail -n 1 "$tools/rustup-$triple.log")"
            continue
        fi
    fi
    # The platform-test host runs where the tests can run it: Linux (native, qemu)
    # and Windows (Wine); it never goes into an FMU.
    # The master's stepping kernel (crates/tools/cosim-kernel) goes into the wheel for every
    # platform built (hatch_build.py), beside the FMUs.
    build=(cargo-zigbuild rustc)
    if [[ "$tuple" == *-windows ]]; then
        if ! command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 &&
            [[ "$(id -u)" -eq 0 ]] && command -v apt-get >/dev/null 2>&1; then
            { apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq \
                --no-install-recommends gcc-mingw-w64-x86-64; } >"$tools/apt-mingw.log" 2>&1 || true
        fi
        if ! command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1; then
            missing "$tuple" "the MinGW-w64 linker x86_64-w64-mingw32-gcc is missing (Debian: apt-get install gcc-mingw-w64-x86-64)"
            continue
        fi
        build=(env CARGO_TARGET_X86_64_PC_WINDOWS_GNU_LINKER=x86_64-w64-mingw32-gcc cargo rustc)
    fi
    while (($(jobs -rp | wc -l) >= at_once)); do wait -n || true; done
    launch
    launched+=("$tuple $triple $target")
done
wait
built=()
for entry in "${launched[@]}"; do
    read -r tuple triple target <<<"$entry"
    if [[ -f "$tools/outcome-$tuple" ]]; then
        built+=("$tuple")
        echo "$tuple built" >>"$record.new"
        echo "build-fmus: $tuple built (target/$triple/fmu/)"
    else
        tail -n 20 "$tools/build-$tuple.log" >&2
        missing "$tuple" "the build for $target failed (log: $tools/build-$tuple.log)"
    fi
done
mv "$record.new" "$record"

if [[ ${#built[@]} -eq 0 ]]; then
    echo "build-fmus: no platform could be built; see the messages above" >&2
    exit 1
fi
list="$(IFS=,; echo "${built[*]}")"
target/release/robofmu-packager --out dist --platforms "$list"
if [[ ${#built[@]} -lt ${#platforms[@]} ]]; then
    echo "build-fmus: the FMUs carry ${#built[@]} of ${#platforms[@]} platforms ($list); missing:" >&2
    grep ' missing ' "$record" | sed 's/^/  /' >&2
fi
