#!/usr/bin/env bash
# Writes the release folder of the workspace version (Cargo.toml [workspace.package]):
#   robofmu-VERSION-py3-none-any.whl, robofmu-VERSION.tar.gz   (python -m build)
#   fmus/<Model>.fmu, fmus/fmi3/<Model>.fmu, fmus/fmi3-scalar/<Model>.fmu   (dist/)
#   ssp/<scenario>.ssp   the example scenarios as SSP archives (cosim ssp; multi-segment
#                        motions have no SSP form and are left out, said on stdout)
#   compatibility/       the compatibility information the FMI tools list asks for (every
#                        FMU with its reference and Readme.txt, imported by running it:
#                        results/, junit.xml, the results page index.html, README.md)
#   CHANGELOG-VERSION.md the version's section of CHANGELOG.md
#   SHA256SUMS           of every other file (sha256sum -c SHA256SUMS checks them)
# and lists the files with their sizes (docs/release.md).
# usage: bash scripts/release.sh [--out DIR]   (default: release/VERSION)
# It builds first (scripts/build-fmus.sh, scripts/setup-venv.sh). A folder that is not
# empty is refused unless an earlier run of this script wrote it (it has SHA256SUMS).
set -euo pipefail
cd "$(dirname "$0")/.."
version=$(sed -n '/^\[workspace\.package\]/,/^\[/s/^version = "\(.*\)"$/\1/p' Cargo.toml)
usage="usage: bash scripts/release.sh [--out DIR]"
case $# in
    0) out=release/$version ;;
    2) [[ "$1" == --out && -n "$2" ]] || { echo "release.sh: $usage" >&2; exit 2; }; out=$2 ;;
    *) echo "release.sh: $usage" >&2; exit 2 ;;
esac
if [[ -e "$out" && ! -d "$out" ]]; then
    echo "release.sh: --out: $out is not a folder; name a new or empty folder" >&2; exit 2
fi
if [[ -d "$out" && -n "$(ls -A "$out")" ]]; then
    if [[ ! -f "$out/SHA256SUMS" ]]; then
        echo "release.sh: --out: $out is not empty and not a release folder; name a new" \
            "or empty folder" >&2
        exit 2
    fi
    rm -rf "$out"
fi
# From '## VERSION' to the next version's heading ('## X.Y.Z'; dated sections belong to
# the version above them).
changelog=$(awk -v v="$version" '
    /^## [0-9]+\.[0-9]+\.[0-9]+/ { if (inside) exit; if ($2 == v) inside = 1 }
    inside' CHANGELOG.md)
if [[ -z "$changelog" ]]; then
    echo "release.sh: CHANGELOG.md: no section '## $version'; add one (the version is" \
        "Cargo.toml's [workspace.package] version)" >&2
    exit 2
fi

bash scripts/build-fmus.sh
bash scripts/setup-venv.sh
mkdir -p "$out/fmus" "$out/ssp"
.venv/bin/python -m build --no-isolation --outdir "$out" . >"$out/build.log" 2>&1 ||
    { cat "$out/build.log" >&2; exit 1; }
rm "$out/build.log"
for folder in "" fmi3 fmi3-scalar; do
    mkdir -p "$out/fmus/$folder"
    cp dist/$folder/*.fmu "$out/fmus/$folder/"
done
for scenario in scenarios/*.toml; do
    name=$(basename "$scenario" .toml)
    if ! said=$(.venv/bin/cosim ssp "$scenario" --out "$out/ssp/$name.ssp" 2>&1); then
        if [[ "$said" == *"has no SSP form"* ]]; then
            echo "ssp/$name.ssp: left out: ${said#cosim: }"
            continue
        fi
        echo "$said" >&2
        exit 1
    fi
done
# The compatibility information of the FMI tools list, every FMU imported by running it
# (FMPy, libcosim, ecos: ecospy needs libtbb12), with the results page
# (scripts/compatibility.py).
bash scripts/install-importer-libs.sh
.venv/bin/python scripts/compatibility.py "$out/compatibility" >/dev/null
printf '%s\n' "$changelog" >"$out/CHANGELOG-$version.md"
(cd "$out" && find . -type f ! -name SHA256SUMS | sed 's#^\./##' | LC_ALL=C sort |
    xargs sha256sum >SHA256SUMS &&
    sha256sum --check --quiet SHA256SUMS)
echo "release $version in $out:"
(cd "$out" && find . -type f | sed 's#^\./##' | LC_ALL=C sort | xargs du -b |
    awk '{ printf "%10d  %s\n", $1, $2 }')
