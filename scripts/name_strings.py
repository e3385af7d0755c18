"""Variable names written as strings in the FMU crates (issue 34), and declarations
stated twice (issue 44): prints every string literal in fmus/*/src that equals a
declared variable name outside the declaration of that name, every name that two
declarations of one crate declare, and every declaration constant listed twice in one
list, with its file and line, and exits 1 when there is one.

The names are the checked-in descriptions': every FMI 2.0 scalar of
modelDescription/*.xml (`theta[1]`, `platformInertia[1,2]`, `der(omega[2])`) and every
FMI 3.0 variable of modelDescription/fmi3/*.xml (`theta`, `der(omega)`), of all FMUs
together, and the head of an element's name (`concat!("Kp[", ..)`). A literal is a
declaration when it is the first string literal among the
arguments of a declaring call: `Decl::real/integer/boolean(..)` or
`Decl::real_in/integer_in/boolean_in(..)` (also
`Declaration::`, or `Decl::$ty(..)` inside a macro), a constructor of a `Family`
(`CH.tunable("Kp", ..)`, `.flag`, `.input`, `.output`, `.state`, `.derivative`), or a macro or function of the
same crate whose definition makes such a call (`gain!("Kp", ..)`, `planned::<0>("q",
..)`). Everything else that names a variable refers to it through its declaration
(`KP.var()`, `THETA.item(1)`, `U.is(element)`, `STATE.name`) and is checked by the
compiler.

Usage: python3 scripts/name_strings.py [ROOT]   (default: the repository)
"""

import re
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

DECLARE = {"real", "integer", "boolean", "real_in", "integer_in", "boolean_in"}
TABLES = {"Decl", "Declaration"}
# The constructors of the layer's `Family` (`CH.tunable("Kp", ..)`): method calls with
# arguments whose first string literal is the name they declare (the roles `.input()`,
# `.output()`, `.state()` of a declaration take none).
FAMILY = {"tunable", "flag", "input", "output", "state", "derivative"}
# The clocked partitions' constructors (robofmu_fmi::core::clocks) and the structural
# parameters' (robofmu_fmi::core::structural): `new` declares too.
CLOCK_TABLES = {"InputClock", "PeriodParameter", "ClockedOutput", "StructuralParameter"}
IDENT = re.compile(r"[A-Za-z_][A-Za-z0-9_]*")


def declared_names(root: Path) -> set[str]:
    """FMI 2.0 scalar and FMI 3.0 variable names of every checked-in description."""
    names = set()
    for folder in (root / "modelDescription", root / "modelDescription" / "fmi3"):
        for f in sorted(folder.glob("*.xml")):
            variables = ET.parse(f).getroot().find("ModelVariables")
            if variables is not None:
                names.update(v.get("name") for v in variables if v.get("name"))
    return names


class Token:
    """`kind`: "str" (value: the literal's text), "ident", "num", "punct" or "char"."""

    def __init__(self, kind: str, value: str, line: int):
        self.kind, self.value, self.line = kind, value, line

    def __repr__(self):
        return f"{self.kind}:{self.value!r}@{self.line}"


def _string(text: str, i: int) -> tuple[str, int]:
    """A "..." literal opening at text[i] (the quote): its value and the index after it."""
    out, i = [], i + 1
    while text[i] != '"':
        if text[i] == "\\":
            nxt = text[i + 1]
            simple = {"n": "\n", "t": "\t", "r": "\r", "0": "\0", "\\": "\\", '"': '"', "'": "'"}
            if nxt in simple:
                out.append(simple[nxt])
                i += 2
            elif nxt == "\n":  # line continuation: the newline and the indentation go
                i += 2
                while text[i] in " \t\n\r":
                    i += 1
            elif nxt == "x":
                out.append(chr(int(text[i + 2:i + 4], 16)))
                i += 4
            elif nxt == "u":
                end = text.index("}", i)
                out.append(chr(int(text[i + 3:end], 16)))
                i = end + 1
            else:
                out.append(nxt)
                i += 2
        else:
            out.append(text[i])
            i += 1
    return "".join(out), i + 1


def tokens(text: str) -> list[Token]:
    """Rust tokens without comments: string literals with their value, identifiers,
    numbers, punctuation (`::` one token), char literals; lifetimes are dropped."""
    out, i, line, n = [], 0, 1, len(text)
    while i < n:
        c = text[i]
        if c == "\n":
            line += 1
            i += 1
        elif c.isspace():
            i += 1
        elif text.startswith("//", i):
            i = text.find("\n", i)
            i = n if i < 0 else i
        elif text.startswith("/*", i):
            depth, i = 1, i + 2
            while depth:
                if text.startswith("/*", i):
                    depth, i = depth + 1, i + 2
                elif text.startswith("*/", i):
                    depth, i = depth - 1, i + 2
                else:
                    line += text[i] == "\n"
                    i += 1
        elif (m := re.compile(r'(?:b|c)?r(#*)"').match(text, i)) and (
            i == 0 or not (text[i - 1].isalnum() or text[i - 1] == "_")
        ):
            close = '"' + m.group(1)
            end = text.index(close, m.end())
            value = text[m.end():end]
            out.append(Token("str", value, line))
            line += value.count("\n")
            i = end + len(close)
        elif c == '"' or (c in "bc" and text.startswith('"', i + 1)):
            start = i + (c != '"')
            value, end = _string(text, start)
            out.append(Token("str", value, line))
            line += text.count("\n", i, end)
            i = end
        elif c == "'":
            if text[i + 1] == "\\":
                end = text.index("'", i + 3)
                out.append(Token("char", text[i:end + 1], line))
                i = end + 1
            elif i + 2 < n and text[i + 2] == "'":
                out.append(Token("char", text[i:i + 3], line))
                i += 3
            else:  # a lifetime or a loop label
                m = IDENT.match(text, i + 1)
                i = m.end() if m else i + 1
        elif c.isalpha() or c == "_":
            m = IDENT.match(text, i)
            out.append(Token("ident", m.group(), line))
            i = m.end()
        elif c.isdigit():
            m = re.compile(r"[0-9][0-9A-Za-z_]*(?:\.[0-9][0-9A-Za-z_]*)?").match(text, i)
            out.append(Token("num", m.group(), line))
            i = m.end()
        elif text.startswith("::", i):
            out.append(Token("punct", "::", line))
            i += 2
        else:
            out.append(Token("punct", c, line))
            i += 1
    return out


OPEN, CLOSE = "([{", ")]}"


def matching(toks: list[Token], i: int) -> int:
    """Index of the bracket closing the one at toks[i]."""
    depth = 0
    for j in range(i, len(toks)):
        t = toks[j]
        if t.kind == "punct" and t.value in OPEN:
            depth += 1
        elif t.kind == "punct" and t.value in CLOSE:
            depth -= 1
            if depth == 0:
                return j
    return len(toks) - 1


def _is(t: Token, kind: str, value: str | None = None) -> bool:
    return t.kind == kind and (value is None or t.value == value)


def calls(toks: list[Token]):
    """(callee, index of the opening bracket) of every call and macro invocation:
    callee "Decl::real" for a declaring call of the table (also `Decl::$ty`), the
    function's or macro's name otherwise."""
    for i, t in enumerate(toks):
        if not (t.kind == "punct" and t.value in "([{"):
            continue
        j = i - 1
        if j >= 0 and _is(toks[j], "punct", ">"):  # turbofish `f::<K>(`
            depth = 0
            while j >= 0:
                if _is(toks[j], "punct", ">"):
                    depth += 1
                elif _is(toks[j], "punct", "<"):
                    depth -= 1
                    if depth == 0:
                        break
                j -= 1
            j -= 2 if j >= 1 and _is(toks[j - 1], "punct", "::") else 1
        if j >= 1 and _is(toks[j], "punct", "!") and _is(toks[j - 1], "ident"):
            if toks[j - 1].value != "macro_rules":
                yield toks[j - 1].value, i
            continue
        if t.value != "(" or j < 0 or toks[j].kind != "ident":
            continue
        name = toks[j].value
        if j >= 2 and _is(toks[j - 1], "punct", "$"):  # `Decl::$ty(`
            name, j = "$", j - 1
        if (
            j >= 2
            and _is(toks[j - 1], "punct", "::")
            and (
                (toks[j - 2].value in TABLES and (name in DECLARE or name == "$"))
                or (toks[j - 2].value in CLOCK_TABLES and name == "new")
            )
        ):
            yield "Decl::real", i
        elif (  # a Family constructor; `.input()` without arguments is a role
            name in FAMILY
            and j >= 1
            and _is(toks[j - 1], "punct", ".")
            and i + 1 < len(toks)
            and not _is(toks[i + 1], "punct", ")")
        ):
            yield "Decl::real", i
        else:
            yield name, i


def definitions(toks: list[Token]) -> dict[str, list[tuple[int, int]]]:
    """Name -> token ranges of the bodies of the macros and functions defined."""
    out: dict[str, list[tuple[int, int]]] = {}
    for i, t in enumerate(toks[:-2]):
        if _is(t, "ident", "macro_rules") and _is(toks[i + 1], "punct", "!"):
            name, k = toks[i + 2].value, i + 3
        elif _is(t, "ident", "fn") and toks[i + 1].kind == "ident":
            name, k = toks[i + 1].value, i + 2
            depth = 0  # the body: the first `{` outside the signature's brackets
            while k < len(toks):
                v = toks[k]
                if v.kind == "punct" and v.value in "([<":
                    depth += 1
                elif v.kind == "punct" and v.value in ")]>":
                    depth -= 1
                elif depth <= 0 and v.kind == "punct" and v.value in "{;":
                    break
                k += 1
            if k >= len(toks) or toks[k].value == ";":
                continue
        else:
            continue
        if k < len(toks) and _is(toks[k], "punct") and toks[k].value in OPEN:
            out.setdefault(name, []).append((k, matching(toks, k)))
    return out


def declaring(files: dict[Path, list[Token]]) -> set[str]:
    """The callees whose first string literal is a declared name: the table's
    constructors, and the macros and functions of these files that call one."""
    bodies = []
    for toks in files.values():
        found = list(calls(toks))
        for name, ranges in definitions(toks).items():
            for start, end in ranges:
                bodies.append((name, {c for c, at in found if start < at < end}))
    known = {"Decl::real"}
    while True:
        more = {name for name, inner in bodies if inner & known} - known
        if not more:
            return known
        known |= more


def declared_at(toks: list[Token], callees: set[str]):
    """For each call of a declaring callee: the index of the string literal it declares
    (the first among its own arguments), or None."""
    for callee, at in calls(toks):
        if callee not in callees:
            continue
        end, depth, first = matching(toks, at), 0, None
        for k in range(at + 1, end):
            v = toks[k]
            if v.kind == "punct" and v.value in OPEN:
                depth += 1
            elif v.kind == "punct" and v.value in CLOSE:
                depth -= 1
            elif depth == 0 and v.kind == "str":
                first = k
                break
        yield first


def findings(root: Path = ROOT) -> dict[str, list[tuple[str, int, str]]]:
    """FMU folder -> (file, line, literal) of every variable name written as a string
    outside its declaration."""
    names = declared_names(root)
    out = {}
    for crate in sorted((root / "fmus").iterdir()):
        sources = sorted((crate / "src").rglob("*.rs"))
        if not sources:
            continue
        files = {f: tokens(f.read_text()) for f in sources}
        callees = declaring(files)
        found = []
        for f, toks in files.items():
            declarations = {k for k in declared_at(toks, callees) if k is not None}
            for k, t in enumerate(toks):
                named = t.value in names or (t.value.endswith("[") and t.value[:-1] in names)
                if t.kind == "str" and named and k not in declarations:
                    found.append((str(f.relative_to(root)), t.line, t.value))
        out[crate.name] = found
    return out


def declaration_constants(toks: list[Token]) -> set[str]:
    """Names of the `const` and `static` items whose type is a declaration or a table of
    them (`Decl`, `Declaration<M>`, `[Decl; 7]`, `&[Decl]`)."""
    out = set()
    for i, t in enumerate(toks[:-2]):
        if t.kind == "ident" and t.value in ("const", "static") and toks[i + 1].kind == "ident" \
                and _is(toks[i + 2], "punct", ":"):
            k = i + 3
            while k < len(toks) and not _is(toks[k], "punct", "=") and not _is(toks[k], "punct", ";"):
                if toks[k].value in TABLES:
                    out.add(toks[i + 1].value)
                k += 1
    return out


def list_elements(toks: list[Token], start: int) -> list[list[Token]]:
    """The elements of the `[..]` list opening at toks[start], split at its own commas."""
    elements: list[list[Token]] = [[]]
    depth = 0
    for k in range(start + 1, matching(toks, start)):
        v = toks[k]
        if v.kind == "punct" and v.value in OPEN:
            depth += 1
        elif v.kind == "punct" and v.value in CLOSE:
            depth -= 1
        if depth == 0 and _is(v, "punct", ","):
            elements.append([])
        else:
            elements[-1].append(v)
    return [e for e in elements if e]


def listed(element: list[Token], constants: set[str]) -> str | None:
    """What a list element names of the declarations: the element as written when it
    starts with a declaration constant (`KP`, `THETA.var()`, `THETA.item(1)`), the
    constant when the element is a tuple opening with one (`(U, Unknown::Output)`)."""
    if element[0].kind == "ident" and element[0].value in constants:
        return "".join(t.value for t in element)
    if _is(element[0], "punct", "(") and len(element) > 1 and element[1].value in constants:
        return element[1].value
    return None


def repeats(root: Path = ROOT) -> dict[str, list[tuple[str, int, str]]]:
    """FMU folder -> (file, line, what) of every declaration stated twice: a name that
    two declarations of the crate declare, a declaration constant listed twice in one
    list (a table, a dependency list, a Jacobian table)."""
    out = {}
    for crate in sorted((root / "fmus").iterdir()):
        sources = sorted((crate / "src").rglob("*.rs"))
        if not sources:
            continue
        files = {f: tokens(f.read_text()) for f in sources}
        callees = declaring(files)
        constants = set().union(*(declaration_constants(t) for t in files.values()))
        declared: dict[str, list[tuple[str, int]]] = {}
        found = []
        for f, toks in files.items():
            name = str(f.relative_to(root))
            for k in declared_at(toks, callees):
                if k is not None:
                    declared.setdefault(toks[k].value, []).append((name, toks[k].line))
            for i, t in enumerate(toks):
                if not _is(t, "punct", "["):
                    continue
                seen = set()
                for element in list_elements(toks, i):
                    what = listed(element, constants)
                    if what is not None and what in seen:
                        found.append((name, element[0].line, f"{what} listed twice in one list"))
                    seen.add(what)
        for value, places in declared.items():
            found += [(f, line, f'"{value}" declared twice') for f, line in places[1:]]
        out[crate.name] = sorted(found)
    return out


def main() -> int:
    root = Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT
    result, twice = findings(root), repeats(root)
    total = 0
    for crate, found in result.items():
        print(f"fmus/{crate}: {len(found) + len(twice[crate])}")
        for f, line, value in found:
            print(f"  {f}:{line}: \"{value}\"")
        for f, line, what in twice[crate]:
            print(f"  {f}:{line}: {what}")
        total += len(found) + len(twice[crate])
    if total:
        print(f"{total} findings: refer to a variable through its declaration (D.var(), "
              "D.item(i), D.same(), D.is(element), D.name), declare it once, list it once")
    return 1 if total else 0


if __name__ == "__main__":
    sys.exit(main())
