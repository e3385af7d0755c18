#!/usr/bin/env bash
# The wheel as a user gets it: builds the sdist and the wheel (python -m build, after
# scripts/build-fmus.sh and scripts/setup-venv.sh), installs the wheel into a fresh venv
# in an empty temporary folder (no checkout there or on sys.path, no Rust on PATH; the
# dependencies from PyPI, pinned by scripts/python-requirements.txt as constraints) and
# runs from that folder:
#   cosim --version                = the workspace version (Cargo.toml) = every bundled
#                                    FMU's modelDescription version (read by FMPy)
#   fmpy info <bundled FMU>
#   cosim run <a bundled example scenario, copied here: it names bundled FMUs>
#   cosim verify <bundled Pss3Plant> <bundled reference case> --junit  (0 failures)
# Run by scripts/test.sh (CI); about a minute, most of it pip.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
version=$(sed -n '/^\[workspace\.package\]/,/^\[/s/^version = "\(.*\)"$/\1/p' Cargo.toml)
[[ -n "$version" ]] || { echo "test-wheel: Cargo.toml: no [workspace.package] version" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

.venv/bin/python -m build --no-isolation --outdir "$work/packages" . >/dev/null
wheel="$work/packages/robofmu-$version-py3-none-any.whl"
[[ -f "$wheel" ]] || { echo "test-wheel: no $wheel" >&2; ls "$work/packages" >&2; exit 1; }
# pip refuses extras in constraints: dask[distributed]==X constrains dask==X.
sed 's/\[[^]]*\]//' scripts/python-requirements.txt >"$work/constraints.txt"

user="$work/user"
mkdir "$user"
base=$(.venv/bin/python -c 'import sys; print(sys._base_executable)')
"$base" -m venv "$user/venv"
# The user's environment: nothing of this shell's (no cargo, no PYTHONPATH, no checkout).
as_user() {
    (cd "$user" && env -i HOME="$user" LANG=C.UTF-8 MPLBACKEND=Agg \
        PATH="$user/venv/bin:/usr/bin:/bin" "$@")
}
as_user python -m pip install --quiet --disable-pip-version-check \
    --constraint "$work/constraints.txt" "$wheel"

as_user bash -euo pipefail -s "$version" <<'EOF'
version=$1
fail() { echo "test-wheel: $*" >&2; exit 1; }
if command -v cargo >/dev/null || command -v rustc >/dev/null; then
    fail "Rust is on the user's PATH ($PATH)"
fi
[[ -z "$(ls -A | grep -v '^venv$')" ]] || fail "the user's folder is not empty"
where=$(python -c 'import cosim; print(cosim.__file__)')
[[ "$where" == "$PWD/venv/"* ]] || fail "cosim imported from $where, not the venv"

said=$(cosim --version)
[[ "$said" == "cosim $version" ]] || fail "cosim --version says '$said', Cargo.toml $version"
names=$(cosim fmus | awk '{print $1}')
[[ $(wc -l <<<"$names") == 12 ]] || fail "cosim fmus lists $(wc -l <<<"$names") FMUs, not 12"
for name in $names; do
    python - "$(cosim fmus --path "$name")" "$version" <<'PY'
import sys
from fmpy import read_model_description
path, version = sys.argv[1:]
md = read_model_description(path)
assert md.version == version, f"{path}: version {md.version!r}, workspace {version}"
assert md.generationTool == f"robofmu {version}", f"{path}: {md.generationTool!r}"
PY
done
echo "cosim --version = Cargo.toml = every bundled FMU's version: $version (12 FMUs)"

fmpy info "$(cosim fmus --path PID)" >info.txt
grep -q "Model Name *PID" info.txt || fail "fmpy info: $(cat info.txt)"

cp "$(cosim examples --path regulation)" regulation.toml
grep -q '^plant = "Pss3Plant"$' regulation.toml || fail "the example names no bundled FMU"
cosim run regulation.toml --out out --quiet >run.txt 2>run.err || fail "cosim run: $(cat run.err)"
grep -q "1000 steps" run.txt && [[ -s out/regulation.csv ]] || fail "cosim run: $(cat run.txt)"
# The wheel carries the native loop of the platform it was built on (this one).
[[ ! -s run.err ]] || fail "cosim run said: $(cat run.err)"
cat run.txt

cosim verify "$(cosim fmus --path Pss3Plant)" "$(cosim examples --path Pss3Plant/path1)" \
    --out verify --junit verify/junit.xml
python - <<'PY'
from xml.etree import ElementTree
suite = ElementTree.parse("verify/junit.xml").getroot()
suite = suite if suite.tag == "testsuite" else suite.find("testsuite")
counts = {k: int(suite.get(k)) for k in ("tests", "failures", "errors")}
assert counts["tests"] > 0 and counts["failures"] == counts["errors"] == 0, counts
print(f"JUnit: {counts}")
PY
EOF
echo "test-wheel: the wheel $(basename "$wheel") ($(du -k "$wheel" | cut -f1) KiB) runs outside the checkout"
