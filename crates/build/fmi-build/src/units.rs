//! Units known to the layer, with their SI base-unit exponents and display units.
//! modelDescription.xml declares exactly the units its variables use.

/// Exponents of the SI base units (kg, m, s, A, K, mol, cd) and of rad.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct BaseUnit {
    pub kg: i32,
    pub m: i32,
    pub s: i32,
    pub rad: i32,
}

/// A display unit: value_display = factor * value + offset.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DisplayUnit {
    pub name: &'static str,
    pub factor: f64,
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitDefinition {
    pub name: &'static str,
    pub base: BaseUnit,
    pub display_units: &'static [DisplayUnit],
}

/// Degrees per radian.
pub const DEG_PER_RAD: f64 = 57.29577951308232;

const fn base(kg: i32, m: i32, s: i32, rad: i32) -> BaseUnit {
    BaseUnit { kg, m, s, rad }
}

const fn def(
    name: &'static str,
    base: BaseUnit,
    display_units: &'static [DisplayUnit],
) -> UnitDefinition {
    UnitDefinition {
        name,
        base,
        display_units,
    }
}

const fn display(name: &'static str, factor: f64) -> DisplayUnit {
    DisplayUnit { name, factor }
}

/// Every unit a model may use.
pub const UNITS: &[UnitDefinition] = &[
    def("s", base(0, 0, 1, 0), &[]),
    def("rad", base(0, 0, 0, 1), &[display("deg", DEG_PER_RAD)]),
    def("rad/s", base(0, 0, -1, 1), &[display("deg/s", DEG_PER_RAD)]),
    def(
        "rad/s2",
        base(0, 0, -2, 1),
        &[display("deg/s2", DEG_PER_RAD)],
    ),
    def("m", base(0, 1, 0, 0), &[display("mm", 1000.0)]),
    def("m/s", base(0, 1, -1, 0), &[]),
    def("m/s2", base(0, 1, -2, 0), &[]),
    def("kg", base(1, 0, 0, 0), &[]),
    def("kg.m2", base(1, 2, 0, 0), &[]),
    def("N", base(1, 1, -2, 0), &[]),
    def("N.m", base(1, 2, -2, 0), &[]),
    def("m3", base(0, 3, 0, 0), &[]),
    def("J", base(1, 2, -2, 0), &[]),
    def("N/m", base(1, 0, -2, 0), &[]),
    def("N.s/m", base(1, 0, -1, 0), &[]),
    def("N.m.s/rad", base(1, 2, -1, -1), &[]),
    def("1/s", base(0, 0, -1, 0), &[]),
];

/// The definition of a unit by name.
pub fn unit(name: &str) -> Option<&'static UnitDefinition> {
    UNITS.iter().find(|u| u.name == name)
}
