"""scripts/name_strings.py: no FMU crate writes a variable name as a string outside the
declaration of that name (issue 34: dependency lists, partial derivatives and messages
refer to a variable through its declaration, which the compiler checks), and the checker
finds such a string where there is one (a crate written here, its strings known by
construction)."""

import importlib.util
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
SPEC = importlib.util.spec_from_file_location("name_strings", ROOT / "scripts" / "name_strings.py")
name_strings = importlib.util.module_from_spec(SPEC)
SPEC.loader.exec_module(name_strings)


def test_the_names_are_those_of_every_checked_in_description():
    names = name_strings.declared_names(ROOT)
    # FMI 2.0 scalars and FMI 3.0 arrays of the four FMUs, read from the XML files.
    for name in ("theta", "theta[1]", "der(omega)", "der(omega[3])", "platformInertia[1,2]",
                 "platformCom[2]", "Kp[3]", "der(integral)", "q0", "setpointAcceleration"):
        assert name in names, name
    assert len(names) > 200  # 233 distinct names in the four FMUs today


def test_no_fmu_crate_writes_a_variable_name_as_a_string():
    found = name_strings.findings(ROOT)
    assert {"pid", "planner", "pss3-plant", "computed-torque"} <= set(found)
    assert {crate: f for crate, f in found.items() if f} == {}


DESCRIPTION = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="2.0" modelName="M">
  <UnitDefinitions><Unit name="rad"/></UnitDefinitions>
  <ModelVariables>
    <ScalarVariable name="gain" valueReference="1"/>
    <ScalarVariable name="x[1]" valueReference="2"/>
    <ScalarVariable name="x[2]" valueReference="3"/>
    <ScalarVariable name="der(x[1])" valueReference="4"/>
    <ScalarVariable name="der(x[2])" valueReference="5"/>
    <ScalarVariable name="mass" valueReference="6"/>
    <ScalarVariable name="y" valueReference="7"/>
  </ModelVariables>
</fmiModelDescription>
"""

DESCRIPTION3 = """<?xml version="1.0" encoding="UTF-8"?>
<fmiModelDescription fmiVersion="3.0" modelName="M">
  <ModelVariables>
    <Float64 name="time" valueReference="0"/>
    <Float64 name="x" valueReference="2"/>
    <Float64 name="der(x)" valueReference="4"/>
  </ModelVariables>
</fmiModelDescription>
"""

# Declarations: Decl::real's first string (even on the next line), a macro that declares
# through Decl::$ty, a const fn that declares through Declaration::real, a macro that
# declares through that macro. Strings that name a variable elsewhere: the dependency
# list, the head of an element's name, the match on an element's name, the raw string,
# a second "mass", the message's argument. Not counted: comments, the unit "rad" (not a
# variable), a char literal, a format string that holds a name among other words.
SOURCE = r'''
//! Module doc naming "x" and "gain".
type Decl = Declaration<M>;
macro_rules! settable {
    ($ty:ident, $name:literal, $what:literal) => { Decl::$ty($name, $what, |m, _| m.v) };
}
macro_rules! param { ($name:literal) => { settable!(real, $name, "a parameter") }; }
const fn state(name: &'static str, what: &'static str) -> Decl {
    Declaration::real(name, what, get).array(2)
}
const GAIN: Decl = param!("gain");
const X: Decl = state("x", "position").unit("rad", None);
const DX: Decl = Decl::real(
    "der(x)", // the derivative
    "velocity",
    |m, i| m.v[i],
).derivative_of(X.name);
const MASS: Decl = settable!(integer, "mass", "in kg");
const Y: Decl = Decl::real("y", "out", |m, _| m.y).depends_on(&[Var::Named("x[2]")]);
/* block comment "y" /* nested "gain" */ still comment "x[1]" */
fn partial(e: Element) -> f64 {
    let c = 'x';
    let lifetime: &'static str = "an x and a y";
    let element = concat!("x[", "1]");
    match e.name {
        "der(x)" => 1.0,
        _ if e.name == r#"mass"# => 2.0,
        _ => fail(format!("{} is {}", "y", lifetime)),
    }
}
'''


def test_a_name_outside_its_declaration_is_found(tmp_path):
    (tmp_path / "modelDescription" / "fmi3").mkdir(parents=True)
    (tmp_path / "modelDescription" / "M.xml").write_text(DESCRIPTION)
    (tmp_path / "modelDescription" / "fmi3" / "M.xml").write_text(DESCRIPTION3)
    src = tmp_path / "fmus" / "m" / "src"
    src.mkdir(parents=True)
    (src / "lib.rs").write_text(SOURCE)
    (src / "other.rs").write_text('fn f() -> &str { "gain" }\n')
    found = name_strings.findings(tmp_path)
    assert found == {
        "m": [
            ("fmus/m/src/lib.rs", 19, "x[2]"),
            ("fmus/m/src/lib.rs", 24, "x["),
            ("fmus/m/src/lib.rs", 26, "der(x)"),
            ("fmus/m/src/lib.rs", 27, "mass"),
            ("fmus/m/src/lib.rs", 28, "y"),
            ("fmus/m/src/other.rs", 1, "gain"),
        ]
    }
    # Written through the declarations, the crate passes.
    fixed = (SOURCE.replace('Var::Named("x[2]")', "X.item(1)")
             .replace('"der(x)" =>', "_ if DX.is(e) =>")
             .replace('r#"mass"#', "MASS.name")
             .replace('"y", lifetime', "Y.name, lifetime")
             .replace('concat!("x[", "1]")', "X.item(0)"))
    (src / "lib.rs").write_text(fixed)
    (src / "other.rs").write_text("fn f() -> &'static str { GAIN.name }\n")
    assert name_strings.findings(tmp_path) == {"m": []}


def test_no_fmu_crate_declares_a_name_twice_or_lists_a_declaration_twice():
    twice = name_strings.repeats(ROOT)
    assert {"pid", "planner", "pss3-plant", "computed-torque"} <= set(twice)
    assert {crate: f for crate, f in twice.items() if f} == {}


def test_no_fmu_crate_defines_a_macro():
    # Every FMU declares its variables in the layer's vocabulary (Declaration's const
    # builders and the crate's const fns), not in a dialect of its own (issue 44).
    sources = sorted((ROOT / "fmus").glob("*/src/**/*.rs"))
    assert len(sources) >= 4
    defining = [str(f.relative_to(ROOT)) for f in sources
                if any(t.value == "macro_rules" for t in name_strings.tokens(f.read_text()))]
    assert defining == []


# Stated twice: "gain" declared by two calls (the second at line 9, through the crate's
# declaring fn), X listed twice in VARIABLES (line 11), the tuple table naming Y twice
# (line 12) and X.var() twice in a dependency list (line 13). Not counted: X.item(0)
# beside X.item(1) (two elements), the same constant in two different lists, Decl::real
# inside a helper's arguments (one declaration, not two).
REPEATED = r'''
type Decl = Declaration<M>;
const fn param(name: &'static str) -> Decl { Decl::real(name, "a parameter", |m, _| m.v) }
const fn array(d: Decl) -> Decl { d.array(2) }
const GAIN: Decl = param("gain");
const X: Decl = array(Decl::real("x", "position", |m, i| m.v[i]));
const Y: Decl = Decl::real("y", "out", |m, _| m.y).depends_on(&[X.item(0), X.item(1)]);
const Z: Decl = Decl::real("z", "out", |m, _| m.y).depends_on(&[X.var()]);
const AGAIN: Decl = param("gain");
static ALL: [Var; 2] = [GAIN.var(), X.var()];
static VARIABLES: &[Decl] = &[GAIN, X, Y, Z, X];
const ROLES: [(Decl, u8); 3] = [(Y, 1), (Z, 2), (Y, 3)];
static DEPENDS: [Var; 3] = [X.var(), GAIN.var(), X.var()];
'''


def test_a_declaration_stated_twice_is_found(tmp_path):
    src = tmp_path / "fmus" / "m" / "src"
    src.mkdir(parents=True)
    (src / "lib.rs").write_text(REPEATED)
    assert name_strings.repeats(tmp_path) == {
        "m": [
            ("fmus/m/src/lib.rs", 9, '"gain" declared twice'),
            ("fmus/m/src/lib.rs", 11, "X listed twice in one list"),
            ("fmus/m/src/lib.rs", 12, "Y listed twice in one list"),
            ("fmus/m/src/lib.rs", 13, "X.var() listed twice in one list"),
        ]
    }
    fixed = (REPEATED.replace('const AGAIN: Decl = param("gain");', "")
             .replace("Y, Z, X];", "Y, Z];").replace("(Y, 3)]", "(GAIN, 3)]")
             .replace("[X.var(), GAIN.var(), X.var()]", "[X.var(), GAIN.var(), Z.var()]"))
    (src / "lib.rs").write_text(fixed)
    assert name_strings.repeats(tmp_path) == {"m": []}


# Declared through a Family of the layer (`CH.tunable("gain", ..)`, `CH.state("x", ..)`):
# the first string of the call is the declaration. "gain" in the message is found (line
# 6); the helper `own` calls the role `.input()` (no arguments: no declaration), so its
# first string, the unit "rad", is no declaration and "rad" names no variable anyway.
FAMILY = r'''
const CH: Family<M> = Family::new(2, "Channel");
const GAIN: Decl = CH.tunable("gain", 1, &[1.0], |m, c| &mut m.v[c]);
const X: Decl = CH.state("x", 11, |m, c| &mut m.x[c]);
const fn own(d: Decl, unit: &'static str) -> Decl { d.input().unit(unit, None) }
fn f() -> String { format!("{}", "gain") }
'''


def test_a_family_constructor_declares_its_first_string(tmp_path):
    (tmp_path / "modelDescription" / "fmi3").mkdir(parents=True)
    (tmp_path / "modelDescription" / "M.xml").write_text(DESCRIPTION)
    (tmp_path / "modelDescription" / "fmi3" / "M.xml").write_text(DESCRIPTION3)
    src = tmp_path / "fmus" / "m" / "src"
    src.mkdir(parents=True)
    (src / "lib.rs").write_text(FAMILY)
    assert name_strings.findings(tmp_path) == {"m": [("fmus/m/src/lib.rs", 6, "gain")]}
    assert name_strings.repeats(tmp_path) == {"m": []}
    (src / "lib.rs").write_text(FAMILY.replace('"gain") }', "GAIN.name) }"))
    assert name_strings.findings(tmp_path) == {"m": []}
