//! FMU bindings: each model of the library behind the generic FMI 2.0 layer. The
//! cdylib crates under fmus/ only call `export_fmi2!` on these types.

pub mod pid;
pub mod planner;
pub mod pss3_plant;

use crate::fmi2::Model;
use crate::fmi2::description::model_description;

/// What packaging needs to know about one FMU.
pub struct FmuEntry {
    pub model_name: &'static str,
    pub model_identifier: &'static str,
    /// File name of the cdylib built from `fmus/<dir>` (`target/release/<file>`).
    pub library_file: &'static str,
    pub model_description: fn() -> Result<String, String>,
    pub documentation: fn() -> Result<String, String>,
}

fn entry<M: Model>(library_file: &'static str) -> FmuEntry {
    FmuEntry {
        model_name: M::info().model_name,
        model_identifier: M::info().model_identifier,
        library_file,
        model_description: model_description::<M>,
        documentation: crate::fmi2::documentation::documentation::<M>,
    }
}

/// All FMUs of the project.
pub fn all() -> Vec<FmuEntry> {
    vec![
        entry::<planner::Planner>("librobofmu_planner_fmu.so"),
        entry::<pid::Pid>("librobofmu_pid_fmu.so"),
        entry::<pss3_plant::Pss3Plant>("librobofmu_pss3_plant_fmu.so"),
    ]
}
