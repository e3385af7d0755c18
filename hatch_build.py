"""The build hook of the `robofmu` distribution (pyproject.toml): the package data that
.gitignore hides from hatchling or that lives outside robofmu/.

- sdist: the built FMUs (dist/*.fmu, dist/fmi3/*.fmu, dist/fmi3-scalar/*.fmu) and the
  native stepping kernels (target/<target>/fmu/, target/release/) at their own paths, so that the
  wheel builds from the sdist without Rust;
- wheel: the FMUs as robofmu/data/fmus/ (same layout as dist/), tests/references/ as
  robofmu/data/references/, scenarios/ as robofmu/data/scenarios/, the kernel as
  robofmu/_native/<platform>/ (robofmu.loop.PLATFORM), one per platform build-fmus.sh
  built; the wheel is py3-none-any: where no kernel is bundled for the platform, robofmu
  refuses to run with one line naming the platform (the master has one loop, the native one);
- editable installs: nothing (robofmu.bundle finds dist/, tests/references/ and
  scenarios/ in the checkout).

A build without the FMUs (the same models in each folder) stops with one line naming
the command that builds them.
"""

from __future__ import annotations

import platform
import sys
from pathlib import Path

from hatchling.builders.hooks.plugin.interface import BuildHookInterface

FMU_FOLDERS = ("", "fmi3", "fmi3-scalar")
KERNEL = {"linux": "libcosim_kernel.so", "darwin": "libcosim_kernel.dylib",
          "win32": "cosim_kernel.dll"}
# The kernels scripts/build-fmus.sh cross-builds beside the FMUs: (cargo target, the
# folder robofmu.loop.PLATFORM names on that platform, the library's file name).
CROSS_KERNELS = (
    ("x86_64-unknown-linux-gnu", "linux-x86_64", KERNEL["linux"]),
    ("aarch64-unknown-linux-gnu", "linux-aarch64", KERNEL["linux"]),
    ("x86_64-pc-windows-gnu", "win32-amd64", KERNEL["win32"]),
    ("x86_64-apple-darwin", "darwin-x86_64", KERNEL["darwin"]),
    ("aarch64-apple-darwin", "darwin-arm64", KERNEL["darwin"]),
)


def kernel_platform() -> str:
    """The folder name of this machine's kernel: robofmu.loop.PLATFORM's rule."""
    return f"{sys.platform}-{platform.machine().lower()}"


def kernels(root: Path) -> dict[str, Path]:
    """The stepping kernels to bundle, by platform folder: every cross-built one (the
    Linux ones for glibc 2.17), else this machine's release build for its own platform."""
    found = {folder: root / "target" / target / "fmu" / name
             for target, folder, name in CROSS_KERNELS}
    found = {folder: path for folder, path in found.items() if path.is_file()}
    native = root / "target" / "release" / KERNEL.get(sys.platform, "")
    if kernel_platform() not in found and native.is_file():
        found[kernel_platform()] = native
    return found


class BundleHook(BuildHookInterface):
    PLUGIN_NAME = "custom"

    def initialize(self, version: str, build_data: dict) -> None:
        if self.target_name == "wheel" and version == "editable":
            return
        root = Path(self.root)
        models = [sorted(p.stem for p in (root / "dist" / folder).glob("*.fmu"))
                  for folder in FMU_FOLDERS]
        if not models[0] or any(m != models[0] for m in models):
            raise SystemExit("hatch_build.py: dist/, dist/fmi3/, dist/fmi3-scalar/ must hold "
                             f"the same FMUs (found {', '.join(map(str, map(len, models)))}); "
                             "run 'bash scripts/build-fmus.sh' first")
        fmus = [root / "dist" / folder / f"{m}.fmu" for folder in FMU_FOLDERS for m in models[0]]
        bundled = kernels(root)
        include = build_data["force_include"]
        if self.target_name == "sdist":
            for path in [*fmus, *bundled.values()]:
                include[str(path)] = str(path.relative_to(root))
            return
        for path in fmus:
            include[str(path)] = f"robofmu/data/fmus/{path.relative_to(root / 'dist').as_posix()}"
        include[str(root / "tests" / "references")] = "robofmu/data/references"
        include[str(root / "scenarios")] = "robofmu/data/scenarios"
        for folder, path in bundled.items():
            include[str(path)] = f"robofmu/_native/{folder}/{path.name}"
