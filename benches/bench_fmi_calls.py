"""Instructions per FMI call of each FMU binary, counted by callgrind (issue 34).

For each FMU and each directory of FMU binaries (cdylibs such as target/release, or a
copy of a baseline build), a small C driver dlopens the binary and repeats one
operation N and 2N times under `valgrind --tool=callgrind`; the difference over N is
the steady cost of one operation, without the one-time work (loading, the first
instantiation building the shared index). Operations: fmi2Instantiate +
fmi2FreeInstance, fmi3InstantiateCoSimulation + fmi3FreeInstance, fmi2GetReal of every
Real output and of one, fmi3GetFloat64 of every Float64 output and of one output
array, fmi2DoStep of 1 ms after initialization. With several directories the last
column is the last one's count over the first one's.

Which binary is which FMU is found by instantiating it with each checked-in
modelDescription/<Model>.xml's GUID (adding an FMU changes no list here). Needs a C
compiler (cc) and valgrind.

Usage: python3 benches/bench_fmi_calls.py [--repeat 1000] DIR [DIR ...]
e.g.   python3 benches/bench_fmi_calls.py baseline-build/ target/release/
"""

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET
from pathlib import Path

DESCRIPTIONS = Path(__file__).resolve().parents[1] / "modelDescription"
MODELS = sorted(path.stem for path in DESCRIPTIONS.glob("*.xml"))
SUFFIX = {"linux": ".so", "darwin": ".dylib"}.get(sys.platform, ".so")

# The driver: DRIVE LIB OP N GUID NVALUES [VR ...]; OP is probe (instantiate once:
# exit 0 when the GUID is this binary's), inst2, inst3, get2, get3 or step2.
DRIVER = r"""
#include <dlfcn.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
typedef void *(*inst2_t)(const char *, int, const char *, const char *, const void *, int, int);
typedef void (*free_t)(void *);
typedef int (*setup2_t)(void *, int, double, double, int, double);
typedef int (*call_t)(void *);
typedef int (*get2_t)(void *, const unsigned *, size_t, double *);
typedef int (*step2_t)(void *, double, double, int);
typedef void *(*inst3_t)(const char *, const char *, const char *, bool, bool, bool, bool,
                         const unsigned *, size_t, void *, void *, void *);
typedef int (*enter3_t)(void *, bool, double, double, bool, double);
typedef int (*get3_t)(void *, const unsigned *, size_t, double *, size_t);
static void logger2(void *e, const char *n, int s, const char *c, const char *m, ...) {}
static void logger3(void *e, int s, const char *c, const char *m) {}
struct callbacks2 { void *logger, *allocate, *free, *step_finished, *environment; };
static void *sym(void *h, const char *name) {
  void *f = dlsym(h, name);
  if (!f) { fprintf(stderr, "no symbol %s\n", name); exit(3); }
  return f;
}
int main(int argc, char **argv) {
  if (argc < 6) { fprintf(stderr, "usage: drive LIB OP N GUID NVALUES [VR ...]\n"); return 3; }
  void *h = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
  if (!h) { fprintf(stderr, "%s\n", dlerror()); return 3; }
  const char *op = argv[2], *guid = argv[4];
  int n = atoi(argv[3]);
  size_t nvr = (size_t)(argc - 6), nvalues = (size_t)atoi(argv[5]);
  unsigned *vr = calloc(nvr + 1, sizeof *vr);
  for (size_t i = 0; i < nvr; i++) vr[i] = (unsigned)atoi(argv[6 + i]);
  double *values = calloc(nvalues + 1, sizeof *values);
  struct callbacks2 cb = {(void *)logger2, (void *)calloc, (void *)free, NULL, NULL};
  inst2_t inst2 = sym(h, "fmi2Instantiate");
  free_t free2 = sym(h, "fmi2FreeInstance");
  inst3_t inst3 = sym(h, "fmi3InstantiateCoSimulation");
  free_t free3 = sym(h, "fmi3FreeInstance");
  int status = 0;
  if (!strcmp(op, "probe")) {
    void *c = inst2("bench", 1, guid, "", &cb, 0, 0);
    if (c) free2(c);
    return c ? 0 : 2;
  }
  if (!strcmp(op, "inst2")) {
    for (int i = 0; i < n; i++) free2(inst2("bench", 1, guid, "", &cb, 0, 0));
  } else if (!strcmp(op, "inst3")) {
    for (int i = 0; i < n; i++)
      free3(inst3("bench", guid, "", 0, 0, 0, 0, NULL, 0, NULL, (void *)logger3, NULL));
  } else if (!strcmp(op, "get2") || !strcmp(op, "step2")) {
    void *c = inst2("bench", 1, guid, "", &cb, 0, 0);
    if (!c) return 2;
    ((setup2_t)sym(h, "fmi2SetupExperiment"))(c, 0, 0, 0, 0, 0);
    ((call_t)sym(h, "fmi2EnterInitializationMode"))(c);
    ((call_t)sym(h, "fmi2ExitInitializationMode"))(c);
    get2_t get = sym(h, "fmi2GetReal");
    step2_t step = sym(h, "fmi2DoStep");
    double t = 0;
    for (int i = 0; i < n; i++) {
      if (op[0] == 'g') status |= get(c, vr, nvr, values);
      else { status |= step(c, t, 1e-3, 1); t += 1e-3; }
    }
    free2(c);
  } else if (!strcmp(op, "get3")) {
    void *c = inst3("bench", guid, "", 0, 0, 0, 0, NULL, 0, NULL, (void *)logger3, NULL);
    if (!c) return 2;
    ((enter3_t)sym(h, "fmi3EnterInitializationMode"))(c, 0, 0, 0, 0, 0);
    ((call_t)sym(h, "fmi3ExitInitializationMode"))(c);
    get3_t get = sym(h, "fmi3GetFloat64");
    for (int i = 0; i < n; i++) status |= get(c, vr, nvr, values, nvalues);
    free3(c);
  } else {
    fprintf(stderr, "unknown operation %s\n", op);
    return 3;
  }
  return status;
}
"""


def size(variable):
    """Number of values of an FMI 3.0 variable (its Dimension's start, else 1)."""
    dimension = variable.find("Dimension")
    return int(dimension.get("start")) if dimension is not None else 1


def operations(model):
    """The GUID and (label, op, value references, number of values) of each operation."""
    root2 = ET.parse(DESCRIPTIONS / f"{model}.xml").getroot()
    outputs2 = [int(v.get("valueReference")) for v in root2.iter("ScalarVariable")
                if v.get("causality") == "output" and v.find("Real") is not None]
    root3 = ET.parse(DESCRIPTIONS / "fmi3" / f"{model}.xml").getroot()
    outputs3 = [v for v in root3.find("ModelVariables")
                if v.tag == "Float64" and v.get("causality") == "output"]
    vrs3 = [int(v.get("valueReference")) for v in outputs3]
    n3 = sum(size(v) for v in outputs3)
    first_array = next((v for v in outputs3 if v.find("Dimension") is not None), outputs3[0])
    return root2.get("guid"), [
        ("fmi2Instantiate + fmi2FreeInstance", "inst2", [], 0),
        ("fmi3InstantiateCoSimulation + fmi3FreeInstance", "inst3", [], 0),
        (f"fmi2GetReal of every Real output ({len(outputs2)} vr)", "get2", outputs2,
         len(outputs2)),
        ("fmi2GetReal of one output", "get2", outputs2[:1], 1),
        (f"fmi3GetFloat64 of every Float64 output ({len(vrs3)} vr, {n3} values)", "get3",
         vrs3, n3),
        (f"fmi3GetFloat64 of one output array ({size(first_array)} values)", "get3",
         [int(first_array.get("valueReference"))], size(first_array)),
        ("fmi2DoStep (1 ms, after initialization)", "step2", [], 0),
    ]


def instructions(drive, out, lib, op, n, guid, nvalues, vrs, mangled=False):
    """Instructions callgrind counts for one run of the driver (function names kept
    mangled when `mangled`: one name per generic instance)."""
    demangle = ["--demangle=no"] if mangled else []
    command = ["valgrind", "--tool=callgrind", f"--callgrind-out-file={out}", *demangle,
               str(drive), str(lib), op, str(n), guid, str(nvalues)] + [str(v) for v in vrs]
    run = subprocess.run(command, capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f"{lib}: {op} failed (exit {run.returncode}): {run.stderr.strip()[-300:]}")
    for line in Path(out).read_text().splitlines():
        if line.startswith(("summary:", "totals:")):
            return int(line.split()[1])
    sys.exit(f"{out}: no instruction total")


def call_graph(path):
    """Caller -> callees of a callgrind output file (function names decompressed)."""
    names, edges, current = {}, {}, None
    entry = re.compile(r"^(c?fn)=\((\d+)\)(?: (.*))?$")
    for line in Path(path).read_text().splitlines():
        match = entry.match(line)
        if not match:
            continue
        kind, number, name = match.groups()
        if name is not None:
            names[number] = name
        if kind == "fn":
            current = names[number]
        elif current is not None:
            edges.setdefault(current, set()).add(names[number])
    return edges


def demangled(symbol):
    """The path of a legacy-mangled Rust symbol (`_ZN4core3fmt5write17h..E` ->
    `core::fmt::write`), the symbol itself when it is not one."""
    if not symbol.startswith("_ZN"):
        return symbol
    parts, at = [], 3
    while at < len(symbol) and symbol[at].isdigit():
        digits = re.match(r"\d+", symbol[at:]).group()
        at += len(digits)
        parts.append(symbol[at:at + int(digits)])
        at += int(digits)
    if parts and re.fullmatch(r"h[0-9a-f]{16}", parts[-1]):
        parts.pop()
    escapes = {"$LT$": "<", "$GT$": ">", "$u20$": " ", "$C$": ",", "$RF$": "&", "..": "::"}
    path = "::".join(parts)
    for escape, text in escapes.items():
        path = path.replace(escape, text)
    return path


# A model's code: a function of a crate other than the FMI layer (the FMU crate, the
# robot libraries), possibly as a trait impl `<robofmu_pid_fmu::Pid as ...>`, or a
# closure of the FMU's declarations (the getter the layer calls through its fn pointer,
# named `core::ops::function::FnOnce::call_once` in the binary).
MODEL_CODE = re.compile(r"^<?robofmu_(?!fmi::)\w+::|^core::ops::function::FnOnce::call_once$")


def hops(graph, symbol):
    """The shortest call chain from the exported `symbol` to the model's code."""
    chains, seen = [[symbol]], {symbol}
    while chains:
        chain = chains.pop(0)
        for callee in sorted(graph.get(chain[-1], ())):
            if MODEL_CODE.match(demangled(callee)):
                return chain + [callee]
            if callee not in seen:
                seen.add(callee)
                chains.append(chain + [callee])
    return None


def print_hops(drive, out, model, lib, guid, ops):
    """The call chains of fmi2GetReal and fmi3GetFloat64 of one output."""
    for symbol, op in (("fmi2GetReal", "get2"), ("fmi3GetFloat64", "get3")):
        _, _, vrs, nvalues = next(o for o in ops if o[1] == op and len(o[2]) == 1)
        instructions(drive, out, lib, op, 1, guid, nvalues, vrs, mangled=True)
        chain = hops(call_graph(out), symbol)
        if chain is None:
            print(f"{lib}: {symbol}: no call chain to the model's code found")
            continue
        shown = " -> ".join(demangled(f) for f in chain)
        print(f"{lib.parent.name}: {model} {symbol}: {len(chain) - 1} calls: {shown}")


def binary_of(drive, directory, guid):
    """The FMU binary in `directory` that accepts `guid`, or None."""
    for lib in sorted(Path(directory).glob(f"*{SUFFIX}")):
        probe = [str(drive), str(lib), "probe", "1", guid, "0"]
        if subprocess.run(probe, capture_output=True).returncode == 0:
            return lib
    return None


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeat", type=int, default=1000, help="N (default 1000)")
    parser.add_argument("--hops", action="store_true",
                        help="print the call chain from fmi2GetReal and fmi3GetFloat64 to "
                        "the model's code instead of the counts")
    parser.add_argument("dirs", nargs="+", help="directories of FMU binaries")
    args = parser.parse_args()
    for directory in args.dirs:
        if not Path(directory).is_dir():
            parser.error(f"{directory}: no such directory (give folders of FMU binaries)")
    for tool, package in (("cc", "gcc"), ("valgrind", "valgrind")):
        if shutil.which(tool) is None:
            parser.error(f"{tool} is missing: install it (Debian: apt-get install {package})")
    with tempfile.TemporaryDirectory() as tmp:
        drive = Path(tmp, "drive")
        Path(tmp, "drive.c").write_text(DRIVER)
        subprocess.run(["cc", "-O2", "-o", str(drive), str(Path(tmp, "drive.c")), "-ldl"],
                       check=True)
        out = Path(tmp, "callgrind.out")
        ratio = " | ratio" if len(args.dirs) > 1 else ""
        if not args.hops:
            print("| FMU | operation | " + " | ".join(args.dirs) + ratio + " |")
            print("|---|---|" + "---|" * (len(args.dirs) + (1 if ratio else 0)))
        for model in MODELS:
            guid, ops = operations(model)
            libs = [binary_of(drive, d, guid) for d in args.dirs]
            if None in libs:
                missing = args.dirs[libs.index(None)]
                print(f"{missing}: no binary of {model} (GUID {guid}); skipped", file=sys.stderr)
                continue
            if args.hops:
                for lib in libs:
                    print_hops(drive, out, model, lib, guid, ops)
                continue
            for label, op, vrs, nvalues in ops:
                n = args.repeat
                counts = [(instructions(drive, out, lib, op, 2 * n, guid, nvalues, vrs)
                           - instructions(drive, out, lib, op, n, guid, nvalues, vrs)) / n
                          for lib in libs]
                cells = [f"{c:,.0f}" for c in counts]
                if ratio:
                    cells.append(f"{counts[-1] / counts[0]:.3f}")
                print(f"| {model} | {label} | " + " | ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
