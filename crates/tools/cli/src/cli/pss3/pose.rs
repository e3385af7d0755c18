//! `pss3 ik`, `pss3 fk` and `pss3 jacobian`: single poses, printed with labelled units.

use crate::cli::CliError;
use crate::cli::args::{angles_deg, check_stroke, triple};
use crate::cli::bounds::{count, finite, fk_tolerance};
use clap::Args;
use robofmu::pss3::workspace::tilt;
use robofmu::pss3::{
    Assembly, FkOptions, Geometry, forward_kinematics, inverse_kinematics, jacobian, start_pose,
};

/// A pose given by its Euler angles.
#[derive(Args)]
pub struct IkArgs {
    /// Euler angles thx,thy,thz in deg (R = Rz(thz) Ry(thy) Rx(thx)), e.g. 0,0,130.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true,
        value_parser = finite
    )]
    angles: Vec<f64>,
}

/// Actuator displacements and the options of Newton's method.
#[derive(Args)]
pub struct FkArgs {
    /// Actuator displacements l1,l2,l3 in m, e.g. 0.05,0.08,0.1.
    #[arg(
        long,
        value_delimiter = ',',
        allow_hyphen_values = true,
        required = true,
        value_parser = finite
    )]
    l: Vec<f64>,
    /// Seed orientation thx,thy,thz in deg [default: the start pose 0,0,122.07].
    #[arg(long, value_delimiter = ',', allow_hyphen_values = true, value_parser = finite)]
    seed: Option<Vec<f64>>,
    /// Convergence tolerance on the actuator residual, m (0 to 1).
    #[arg(long, default_value_t = FkOptions::default().tolerance,
          allow_hyphen_values = true, value_parser = fk_tolerance)]
    tol: f64,
    /// Iteration limit of Newton's method (1 to 1000).
    #[arg(long, default_value_t = FkOptions::default().max_iterations,
          allow_hyphen_values = true, value_parser = count::<1, 1000>)]
    max_iter: usize,
    /// Accept displacements outside the stroke [2, 152] mm.
    #[arg(long)]
    ignore_stroke: bool,
}

pub fn run_ik(args: &IkArgs) -> Result<(), CliError> {
    let geometry = Geometry::default();
    let assembly = inverse_kinematics(&geometry, &angles_deg(&args.angles, "angles")?)?;
    print_pose(&assembly);
    Ok(())
}

pub fn run_fk(args: &FkArgs) -> Result<(), CliError> {
    let geometry = Geometry::default();
    let seed = match &args.seed {
        Some(s) => angles_deg(s, "seed")?,
        None => start_pose(),
    };
    let options = FkOptions {
        tolerance: args.tol,
        max_iterations: args.max_iter,
        check_stroke: !args.ignore_stroke,
    };
    let l = triple(&args.l, "l")?;
    if !args.ignore_stroke {
        check_stroke(&geometry, &l, "l")?;
    }
    let solution = forward_kinematics(&geometry, &l, &seed, &options)?;
    print_pose(&solution.assembly);
    outln!(
        "Newton: {} iterations, residual {:.3e} m",
        solution.iterations,
        solution.residual
    );
    Ok(())
}

pub fn run_jacobian(args: &IkArgs) -> Result<(), CliError> {
    let geometry = Geometry::default();
    let assembly = inverse_kinematics(&geometry, &angles_deg(&args.angles, "angles")?)?;
    print_pose(&assembly);
    let j = jacobian(&geometry, &assembly)?;
    outln!("Jacobian J (l_dot = J omega, omega in the base frame), m/rad:");
    for row in j.matrix.row_iter() {
        outln!("  [{:>10.6} {:>10.6} {:>10.6}]", row[0], row[1], row[2]);
    }
    outln!("det J = {:.6e} m^3, cond J = {:.4}", j.det(), j.cond());
    let p = j.leg_projection;
    outln!(
        "leg projections n_i.u_i (0 at a singularity): {:.5}, {:.5}, {:.5}",
        p[0],
        p[1],
        p[2]
    );
    Ok(())
}

fn print_pose(assembly: &Assembly) {
    let [thx, thy, thz] = assembly.euler.map(f64::to_degrees).into();
    outln!("orientation: thx = {thx:.4} deg, thy = {thy:.4} deg, thz (roll) = {thz:.4} deg");
    outln!(
        "tilt of the platform normal from Z: {:.4} deg",
        tilt(&assembly.euler).to_degrees()
    );
    let l = assembly.l;
    outln!(
        "actuators: l1 = {:.6} m, l2 = {:.6} m, l3 = {:.6} m",
        l[0],
        l[1],
        l[2]
    );
    for (i, n) in assembly.n.iter().enumerate() {
        outln!(
            "leg {} direction n{} = ({:.5}, {:.5}, {:.5})",
            i + 1,
            i + 1,
            n.x,
            n.y,
            n.z
        );
    }
}
