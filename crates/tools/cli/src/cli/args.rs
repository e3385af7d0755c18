//! Parsing helpers shared by the subcommands.

use crate::cli::CliError;
use crate::cli::report::usage;
use nalgebra::Vector3;
use robofmu::pss3::Geometry;

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

/// Refuses displacements outside the stroke as a usage error; displacements that are
/// within it once divided by 1000 were most likely given in mm, and the message says so.
pub fn check_stroke(geometry: &Geometry, l: &Vector3<f64>, option: &str) -> Result<(), CliError> {
    let (low, high) = (geometry.params.stroke_min, geometry.params.stroke_max);
    let inside = |x: f64| (low..=high).contains(&x);
    let Some(leg) = l.iter().position(|&x| !inside(x)) else {
        return Ok(());
    };
    let fix = if l.iter().all(|&x| inside(x / 1000.0)) {
        let metres: Vec<String> = l.iter().map(|x| format!("{}", x / 1000.0)).collect();
        format!(
            "--{option} is in m, not mm: did you mean --{option} {}?",
            metres.join(",")
        )
    } else {
        let ignore = if option == "l" {
            " (or --ignore-stroke)"
        } else {
            ""
        };
        format!("give displacements in m within the stroke{ignore}")
    };
    Err(usage(format!(
        "--{option}: actuator {} at {} m is outside the stroke [{low}, {high}] m; {fix}",
        leg + 1,
        l[leg]
    )))
}
