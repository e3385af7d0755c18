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

/// Every unit a model may use.
pub const UNITS: &[UnitDefinition] = &[
    UnitDefinition {
        name: "s",
        base: base(0, 0, 1, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "rad",
        base: base(0, 0, 0, 1),
        display_units: &[DisplayUnit {
            name: "deg",
            factor: DEG_PER_RAD,
        }],
    },
    UnitDefinition {
        name: "rad/s",
        base: base(0, 0, -1, 1),
        display_units: &[DisplayUnit {
            name: "deg/s",
            factor: DEG_PER_RAD,
        }],
    },
    UnitDefinition {
        name: "rad/s2",
        base: base(0, 0, -2, 1),
        display_units: &[DisplayUnit {
            name: "deg/s2",
            factor: DEG_PER_RAD,
        }],
    },
    UnitDefinition {
        name: "m",
        base: base(0, 1, 0, 0),
        display_units: &[DisplayUnit {
            name: "mm",
            factor: 1000.0,
        }],
    },
    UnitDefinition {
        name: "m/s",
        base: base(0, 1, -1, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "m/s2",
        base: base(0, 1, -2, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "kg",
        base: base(1, 0, 0, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "kg.m2",
        base: base(1, 2, 0, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "N",
        base: base(1, 1, -2, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "N.m",
        base: base(1, 2, -2, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "m3",
        base: base(0, 3, 0, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "J",
        base: base(1, 2, -2, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "N/m",
        base: base(1, 0, -2, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "N.s/m",
        base: base(1, 0, -1, 0),
        display_units: &[],
    },
    UnitDefinition {
        name: "N.m.s/rad",
        base: base(1, 2, -1, -1),
        display_units: &[],
    },
    UnitDefinition {
        name: "1/s",
        base: base(0, 0, -1, 0),
        display_units: &[],
    },
];

/// The definition of a unit by name.
pub fn unit(name: &str) -> Option<&'static UnitDefinition> {
    UNITS.iter().find(|u| u.name == name)
}
