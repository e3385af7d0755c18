#!/usr/bin/env bash
# The wheel as a user gets it: builds the sdist and the wheel (python -m build, after
# scripts/build-fmus.sh and scripts/setup-venv.sh), puts the wheel alone into an empty
# temporary folder and there, in a shell with nothing of this one (no checkout on a path,
# no Rust on PATH; dependencies from PyPI at the versions pinned by
# scripts/python-requirements.txt, as constraints), runs README.md's install commands
# (its block ```text wheel: a venv, pip install of the wheel, a bundled scenario,
# fmpy info) as written, then checks:
#   cosim --version                = the workspace version (Cargo.toml) = every bundled
#                                    FMU's modelDescription version (read by FMPy)
#   cosim run <a bundled example scenario copied there: it names bundled FMUs>, with the
#                                    native loop (no fallback line)
#   cosim verify <bundled Pss3Plant> <bundled reference case> --junit  (0 failures)
#   examples/robofmu.ipynb executed (nbclient), a sweep on a real Dask cluster (tests/wheel/)
# Run by scripts/test.sh (CI); about a minute and a half, most of it pip.
set -euo pipefail
cd "$(dirname "$0")/.."
root=$PWD
version=$(sed -n '/^\[workspace\.package\]/,/^\[/s/^version = "\(.*\)"$/\1/p' Cargo.toml)
[[ -n "$version" ]] || { echo "test-wheel: Cargo.toml: no [workspace.package] version" >&2; exit 1; }
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

.venv/bin/python -m build --no-isolation --outdir "$work/packages" . >"$work/build.log" 2>&1 ||
    { cat "$work/build.log" >&2; exit 1; }
wheel="$work/packages/robofmu-$version-py3-none-any.whl"
[[ -f "$wheel" ]] || { echo "test-wheel: no $wheel" >&2; ls "$work/packages" >&2; exit 1; }
# pip refuses extras in constraints: dask[distributed]==X constrains dask==X.
sed 's/\[[^]]*\]//' scripts/python-requirements.txt >"$work/constraints.txt"
# The library's scripts of docs/python-api.md (its blocks ```python wheel), run in the
# user's folder with only the wheel installed, and the third-party FMUs they couple with
# our PID (compiled here from examples/integrator/ and integrator3/, as the docs' sh
# lines do).
mkdir "$work/docs"
awk -v dir="$work/docs" '/^```python wheel$/ { n++; inside = 1; next } /^```$/ { inside = 0 }
    inside { print > (dir "/" n ".py") }' docs/python-api.md
[[ -f "$work/docs/2.py" ]] || { echo "test-wheel: docs/python-api.md: fewer than two blocks \`\`\`python wheel" >&2; exit 1; }
.venv/bin/python examples/integrator/build_fmu.py "$work/Integrator.fmu" >/dev/null
.venv/bin/python examples/integrator3/build_fmu.py "$work/Integrator3.fmu" >/dev/null
# The notebook and the Dask cluster test (tests/wheel/), run there with the wheel's venv.
mkdir "$work/tests"
cp examples/robofmu.ipynb tests/wheel/run_notebook.py tests/wheel/cluster.py "$work/tests/"

user="$work/user"
mkdir "$user"
cp "$wheel" "$user/"  # as downloaded from the release page
# The user's shell script: checks of the folder, the README's install commands (its
# block ```text wheel) as written, then the checks below the line `checks=...`.
readme=$(awk '/^```text wheel$/ { inside = 1; next } /^```$/ { inside = 0 } inside' README.md)
[[ -n "$readme" ]] || { echo "test-wheel: README.md: no block \`\`\`text wheel" >&2; exit 1; }
{
    cat <<'EOF'
fail() { echo "test-wheel: $*" >&2; exit 1; }
if command -v cargo >/dev/null || command -v rustc >/dev/null; then
    fail "Rust is on the user's PATH ($PATH)"
fi
[[ "$(ls -A)" == "$WHEEL" ]] || fail "the user's folder holds more than the wheel: $(ls -A)"
EOF
    while IFS= read -r line; do  # each README line shown, then run
        printf 'echo %q\n%s\n' "\$ $line" "$line"
    done <<<"$readme"
    sed -n '/^checks=/,$p' "$root/scripts/test-wheel.sh" | tail -n +2
} >"$work/user.sh"
base=$(.venv/bin/python -c 'import sys; print(sys._base_executable)')
# The user's environment: nothing of this shell's (no cargo, no PYTHONPATH, no checkout);
# pip takes the dependencies from PyPI at the versions pinned for CI (PIP_CONSTRAINT).
(cd "$user" && env -i HOME="$user" LANG=C.UTF-8 MPLBACKEND=Agg VERSION="$version" \
    DOCS="$work/docs" INTEGRATOR="$work/Integrator.fmu" INTEGRATOR3="$work/Integrator3.fmu" \
    TESTS="$work/tests" CHECKOUT="$root" \
    WHEEL="$(basename "$wheel")" PIP_CONSTRAINT="$work/constraints.txt" \
    PIP_DISABLE_PIP_VERSION_CHECK=1 PIP_QUIET=1 PATH="$(dirname "$base"):/usr/bin:/bin" \
    bash -euo pipefail "$work/user.sh")
echo "test-wheel: $(basename "$wheel") ($(du -k "$wheel" | cut -f1) KiB) runs outside the checkout"
exit 0

# The checks, in the user's shell after the README's commands (their venv active):
checks=
version=$VERSION
where=$(python -c 'import robofmu; print(robofmu.__file__)')
[[ "$where" == "$PWD/robofmu-env/"* ]] || fail "robofmu imported from $where, not the venv"

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

# The library with only the wheel (numpy, FMPy): docs/python-api.md's scripts.
mkdir -p results && cp "$INTEGRATOR" results/Integrator.fmu && cp "$INTEGRATOR3" results/Integrator3.fmu
for script in "$DOCS"/*.py; do
    python "$script" || fail "docs/python-api.md's block $(basename "$script" .py) failed"
done
# A missing extra: one line naming it, exit 2; then the extras.
code=0
cosim run "$(cosim examples --path regulation)" --out plots --quiet 2>extra.err || code=$?
[[ $code == 2 && $(cat extra.err) == "cosim: the plots of cosim run needs matplotlib, which robofmu leaves optional; pip install 'robofmu[plots]', or run with --no-plots" ]] ||
    fail "cosim run without matplotlib: exit $code, said: $(cat extra.err)"
pip install "$WHEEL[all]"

# examples/robofmu.ipynb executed by nbclient (its asserts check its numbers; every code
# cell ran without error, the figure cells made image/png): about 15 s.
pip install nbclient nbformat ipykernel  # the versions of scripts/python-requirements.txt
timeout 180 python "$TESTS/run_notebook.py" "$TESTS/robofmu.ipynb" ||
    fail "examples/robofmu.ipynb: exit $?"
# robofmu.run_sweep with a Client of a real cluster: `dask scheduler` and two `dask worker`
# processes of this venv, each in its own empty folder, on 127.0.0.1; the table equals the
# serial sweep's (tests/wheel/cluster.py; its processes are killed at its end): about 20 s.
timeout 300 python "$TESTS/cluster.py" "$CHECKOUT" || fail "the Dask cluster sweep: exit $?"


cp "$(cosim examples --path regulation)" my_scenario.toml
grep -q '^plant = "Pss3Plant"$' my_scenario.toml || fail "the example names no bundled FMU"
cosim run my_scenario.toml --out out --quiet >run.txt 2>run.err || fail "cosim run: $(cat run.err)"
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
