//! Parsing helpers shared by the subcommands.

use crate::cli::CliError;
use crate::cli::report::usage;
use nalgebra::Vector3;

/// Three comma-separated finite numbers as a vector, or an error naming the option.
pub fn triple(values: &[f64], option: &str) -> Result<Vector3<f64>, CliError> {
    match values {
        [x, y, z] if values.iter().all(|v| v.is_finite()) => Ok(Vector3::new(*x, *y, *z)),
        _ => Err(usage(format!(
            "--{option} takes three comma-separated finite numbers, {} given",
            values.len()
        ))),
    }
}

/// Three angles in degrees (thx, thy, thz) as radians.
pub fn angles_deg(values: &[f64], option: &str) -> Result<Vector3<f64>, CliError> {
    Ok(triple(values, option)?.map(f64::to_radians))
}
