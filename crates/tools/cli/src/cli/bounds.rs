//! Value parsers that bound every numeric option before anything runs: non-finite
//! numbers are refused where they make no sense, counts and sizes have a range so that
//! no argument can exhaust memory or run without end. clap names the option in the
//! message ("invalid value 'NaN' for '--tol <TOL>': a finite number ...") and the
//! binary exits with code 2.

use super::CliError;
use super::report::usage;

/// Most samples of a path or a reference (the CSV of 1e6 rows is about 200 MB).
pub const MAX_SAMPLES: f64 = 1e6;

/// A number as a person reads it: plain between 1e-4 and 1e9, else in e notation.
pub fn show(v: f64) -> String {
    if v == 0.0 || (1e-4..1e9).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn number(text: &str) -> Result<f64, String> {
    text.trim()
        .parse::<f64>()
        .map_err(|_| "not a number".to_string())
}

/// Any finite number.
pub fn finite(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err("a finite number is needed".into())
    }
}

/// A finite number > 0.
pub fn positive(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err("a finite number greater than 0 is needed".into())
    }
}

/// A finite number from `lo` to `hi`; `what` says what it is.
fn within(text: &str, lo: f64, hi: f64, what: &str) -> Result<f64, String> {
    let v = number(text)?;
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "{what} from {} to {} is needed",
            show(lo),
            show(hi)
        ))
    }
}

/// The residual tolerance of forward kinematics, m: 0 (iterate to the limit) to 1.
pub fn fk_tolerance(text: &str) -> Result<f64, String> {
    within(text, 0.0, 1.0, "a tolerance in m")
}

/// The tolerance of the closed-loop reference integration: 1e-14 to 1e-2 (below,
/// Dop853 cannot reach it in double precision and would run without end).
pub fn ode_tolerance(text: &str) -> Result<f64, String> {
    within(text, 1e-14, 1e-2, "a relative tolerance")
}

/// A closed-loop bandwidth, rad/s: above 0 and at most 1e4 (the gains grow as w^3).
pub fn bandwidth(text: &str) -> Result<f64, String> {
    let v = number(text)?;
    if v.is_finite() && v > 0.0 && v <= 1e4 {
        Ok(v)
    } else {
        Err("a bandwidth in rad/s greater than 0 and at most 1e4 is needed".into())
    }
}

/// A joint angle of an initial guess, rad: -100 to 100 (about 16 turns). Far beyond,
/// sin and cos lose their digits and the shooting method's integrator creeps on
/// without end (a guess of 1e7 rad ran for minutes).
pub fn joint_angle(text: &str) -> Result<f64, String> {
    within(text, -100.0, 100.0, "a joint angle in rad")
}

/// A spacing of the orientation grid of `pss3 workspace`, deg: 0.25 to 10.
pub fn angle_step(text: &str) -> Result<f64, String> {
    within(text, 0.25, 10.0, "a spacing in deg")
}

/// A whole number from `MIN` to `MAX`.
pub fn count<const MIN: usize, const MAX: usize>(text: &str) -> Result<usize, String> {
    match text.trim().parse::<usize>() {
        Ok(v) if (MIN..=MAX).contains(&v) => Ok(v),
        _ => Err(format!("a whole number from {MIN} to {MAX} is needed")),
    }
}

/// Refuses a sampling step that gives more than [`MAX_SAMPLES`] samples over
/// `duration` or exceeds it; `dt_option` and `duration_option` name the options.
pub fn samples(
    duration: f64,
    dt: f64,
    dt_option: &str,
    duration_option: &str,
) -> Result<(), CliError> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(usage(format!(
            "{dt_option} {} s: a step greater than 0 is needed",
            show(dt)
        )));
    }
    if !(duration.is_finite() && duration > 0.0) {
        return Err(usage(format!(
            "{duration_option} {} s: a duration greater than 0 is needed",
            show(duration)
        )));
    }
    if dt > duration {
        return Err(usage(format!(
            "{dt_option} {} s is longer than {duration_option} {} s; \
             give a step at most the duration",
            show(dt),
            show(duration)
        )));
    }
    let n = duration / dt;
    if n > MAX_SAMPLES {
        return Err(usage(format!(
            "{dt_option} {} s over {duration_option} {} s gives {n:.3e} samples; \
             at most {MAX_SAMPLES:e} are allowed (raise {dt_option})",
            show(dt),
            show(duration)
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parsers_refuse_what_makes_no_sense() {
        // Truth: the ranges written in the parsers' documentation.
        assert_eq!(finite("-2.5"), Ok(-2.5));
        assert!(finite("NaN").is_err() && finite("inf").is_err() && finite("1e400").is_err());
        assert!(positive("0").is_err() && positive("-1").is_err() && positive("1e-300").is_ok());
        assert_eq!(fk_tolerance("0"), Ok(0.0));
        assert!(fk_tolerance("NaN").is_err() && fk_tolerance("2").is_err());
        assert!(ode_tolerance("1e-15").is_err() && ode_tolerance("1e-11").is_ok());
        assert!(bandwidth("1e200").is_err() && bandwidth("30").is_ok());
        assert!(joint_angle("1e7").is_err() && joint_angle("-100").is_ok());
        assert_eq!(count::<2, 5>("5"), Ok(5));
        assert!(count::<2, 5>("6").is_err() && count::<2, 5>("-1").is_err());
        assert!(count::<2, 5>("4294967295").is_err() && count::<2, 5>("3.5").is_err());
    }

    #[test]
    fn sample_counts_are_bounded() {
        // Truth: 2 s / 1e-6 s = 2e6 samples > 1e6; 2 s / 1e-3 s = 2000.
        assert!(samples(2.0, 1e-3, "--dt", "--duration").is_ok());
        assert!(samples(2.0, 1e-6, "--dt", "--duration").is_err());
        assert!(samples(2.0, 1e-300, "--dt", "--duration").is_err());
        assert!(samples(2.0, 3.0, "--dt", "--duration").is_err());
        // A negative or zero step or duration gives no sample count at all.
        assert!(samples(1.0, -1e-3, "--dt", "--duration").is_err());
        assert!(samples(1.0, 0.0, "--dt", "--duration").is_err());
        assert!(samples(-1.0, 1e-3, "--dt", "--duration").is_err());
        assert!(samples(f64::NAN, 1e-3, "--dt", "--duration").is_err());
    }
}
