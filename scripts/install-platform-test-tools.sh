#!/usr/bin/env bash
# What tests/python/test_platforms.py needs beyond the build: Wine (runs the Windows
# test host and DLLs), qemu-user with Debian's aarch64 glibc (runs the aarch64 Linux
# ones), MinGW-w64's gcc (builds the test-only stand-in DLL) and g++ (the Windows host
# that throws out of the FMUs' callbacks, crates/test/hostile/native/leave.c) and LLVM's
# llvm-readobj, llvm-objdump and llvm-nm (read ELF, PE and Mach-O alike: rustup's llvm-tools, or
# Debian's llvm when rustup's download is refused). Installs them with apt-get and
# rustup when they are missing and this runs as root (CI); otherwise names what to
# install and fails, so that the platform tests never run without them.
set -euo pipefail
packages=()
[[ -x /usr/lib/wine/wine64 ]] || command -v wine64 >/dev/null 2>&1 || packages+=(wine64)
command -v qemu-aarch64 >/dev/null 2>&1 || packages+=(qemu-user)
[[ -e /usr/aarch64-linux-gnu/lib/ld-linux-aarch64.so.1 ]] || packages+=(libc6-arm64-cross)
# The aarch64 FMUs need libgcc_s.so.1, the unwinder of the process (issue 42).
[[ -e /usr/aarch64-linux-gnu/lib/libgcc_s.so.1 ]] || packages+=(libgcc-s1-arm64-cross)
command -v x86_64-w64-mingw32-gcc >/dev/null 2>&1 || packages+=(gcc-mingw-w64-x86-64)
command -v x86_64-w64-mingw32-g++-posix >/dev/null 2>&1 || packages+=(g++-mingw-w64-x86-64)
tools="$(rustc --print sysroot)/lib/rustlib/$(rustc -vV | sed -n 's/^host: //p')/bin"
if [[ ! -x "$tools/llvm-objdump" ]] && ! command -v llvm-objdump >/dev/null 2>&1 &&
    ! rustup component add llvm-tools >/dev/null 2>&1; then
    packages+=(llvm)
fi
if [[ ${#packages[@]} -gt 0 ]]; then
    if [ "$(id -u)" -eq 0 ] && command -v apt-get >/dev/null 2>&1; then
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
            "${packages[@]}" >/dev/null
    else
        echo "missing: ${packages[*]} (Debian: apt-get install ${packages[*]})" >&2
        exit 1
    fi
fi
