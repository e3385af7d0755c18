//! The sections of modelDescription.xml that FMI 2.0 and FMI 3.0 write alike:
//! `<UnitDefinitions>` (the units and display units the scalars use),
//! `<LogCategories>` and `<DefaultExperiment>`.

use crate::common::number;
use crate::units::{UNITS, UnitDefinition, unit};
use robofmu_fmi::core::logging::LogCategory;
use robofmu_fmi::core::model::DefaultExperiment as Experiment;
use robofmu_fmi::description::{Scalar, Value};
use serde::Serialize;

/// `<UnitDefinitions>`.
#[derive(Serialize)]
pub struct UnitDefinitions {
    #[serde(rename = "Unit")]
    units: Vec<Unit>,
}

#[derive(Serialize)]
struct Unit {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "BaseUnit")]
    base: BaseUnit,
    #[serde(rename = "DisplayUnit")]
    display_units: Vec<DisplayUnit>,
}

#[derive(Serialize)]
struct BaseUnit {
    #[serde(rename = "@kg", skip_serializing_if = "is_zero")]
    kg: i32,
    #[serde(rename = "@m", skip_serializing_if = "is_zero")]
    m: i32,
    #[serde(rename = "@s", skip_serializing_if = "is_zero")]
    s: i32,
    #[serde(rename = "@rad", skip_serializing_if = "is_zero")]
    rad: i32,
}

fn is_zero(v: &i32) -> bool {
    *v == 0
}

#[derive(Serialize)]
struct DisplayUnit {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "@factor")]
    factor: String,
}

impl UnitDefinitions {
    /// The units `table` uses (None: no unit), in the order of the layer's unit list,
    /// after checking that every unit and display unit is defined.
    pub fn of(table: &[Scalar]) -> Result<Option<UnitDefinitions>, String> {
        let units = used_units(table)?;
        Ok((!units.is_empty()).then(|| UnitDefinitions {
            units: units.iter().map(|u| Unit::of(u)).collect(),
        }))
    }
}

impl Unit {
    fn of(u: &UnitDefinition) -> Unit {
        Unit {
            name: u.name,
            base: BaseUnit {
                kg: u.base.kg,
                m: u.base.m,
                s: u.base.s,
                rad: u.base.rad,
            },
            display_units: u
                .display_units
                .iter()
                .map(|d| DisplayUnit {
                    name: d.name,
                    factor: number(d.factor),
                })
                .collect(),
        }
    }
}

fn used_units(table: &[Scalar]) -> Result<Vec<&'static UnitDefinition>, String> {
    let mut used: Vec<&'static UnitDefinition> = Vec::new();
    for v in table {
        if let Value::Real {
            unit: Some(name),
            display_unit,
            ..
        } = &v.value
        {
            let def = unit(name).ok_or_else(|| format!("\"{}\": unknown unit {name}", v.name))?;
            if let Some(d) = display_unit
                && !def.display_units.iter().any(|du| du.name == *d)
            {
                return Err(format!(
                    "\"{}\": {d} is not a display unit of {name}",
                    v.name
                ));
            }
            if !used.iter().any(|u| u.name == def.name) {
                used.push(def);
            }
        }
    }
    used.sort_by_key(|u| UNITS.iter().position(|k| k.name == u.name));
    Ok(used)
}

/// `<LogCategories>`.
#[derive(Serialize)]
pub struct LogCategories {
    #[serde(rename = "Category")]
    categories: Vec<Category>,
}

#[derive(Serialize)]
struct Category {
    #[serde(rename = "@name")]
    name: &'static str,
    #[serde(rename = "@description")]
    description: &'static str,
}

impl LogCategories {
    pub fn of(categories: &[LogCategory]) -> LogCategories {
        LogCategories {
            categories: categories
                .iter()
                .map(|c| Category {
                    name: c.name,
                    description: c.description,
                })
                .collect(),
        }
    }
}

/// `<DefaultExperiment>`.
#[derive(Serialize)]
pub struct DefaultExperiment {
    #[serde(rename = "@startTime")]
    start_time: String,
    #[serde(rename = "@stopTime")]
    stop_time: String,
    #[serde(rename = "@tolerance")]
    tolerance: String,
    #[serde(rename = "@stepSize")]
    step_size: String,
}

impl DefaultExperiment {
    pub fn of(e: &Experiment) -> DefaultExperiment {
        DefaultExperiment {
            start_time: number(e.start_time),
            stop_time: number(e.stop_time),
            tolerance: number(e.tolerance),
            step_size: number(e.step_size),
        }
    }
}
