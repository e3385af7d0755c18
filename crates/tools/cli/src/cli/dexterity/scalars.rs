//! Subcommands that print numbers: the largest LCI at one orientation and the GCI.
//! Each value is printed first on its line, followed by the manipulator and the working
//! mode it refers to (`--mode all`: one line per mode and one for the best over modes).

use super::options::{
    MODE_HELP, ModeOption, ReadingArgs, Workspace, check_mode, index_of, mode_label,
    parse_mode_option,
};
use crate::cli::CliError;
use clap::Args;
use robofmu_analyses::dexterity::gci::{GciGrid, gci as global_index};
use robofmu_analyses::dexterity::sweep::max_lci_in;
use robofmu_analyses::dexterity::workspace::ModeChoice;
use robofmu_analyses::dexterity::{Manipulator, Robot, RobotKind};

/// The mode choices an optional `--mode` asks for: every mode then the best for `all`.
fn choices(mode: Option<ModeOption>, robot: &Robot) -> Result<Vec<ModeChoice>, CliError> {
    let list = match mode {
        None => vec![ModeChoice::Only(robot.kind().default_mode())],
        Some(ModeOption::Choice(c)) => vec![c],
        Some(ModeOption::All) => (0..robot.working_modes())
            .map(ModeChoice::Only)
            .chain([ModeChoice::Best])
            .collect(),
    };
    for &choice in &list {
        check_mode(robot, choice)?;
    }
    Ok(list)
}

#[derive(Args)]
pub struct MaxLciArgs {
    /// Manipulator: 1rrr, 2rrr or 3rrr.
    #[arg(long)]
    robot: RobotKind,
    /// Orientation phi of the end effector (deg).
    #[arg(long, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    phi: f64,
    /// Positions searched: the paper's square, the own or the common workspace.
    #[arg(long, value_enum, default_value = "paper")]
    workspace: Workspace,
    /// Grid points per axis (161 over the paper's 40 cm square: 0.25 cm steps; 2 to 1001).
    #[arg(long, default_value_t = 161, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<2, 1001>)]
    grid: usize,
    #[arg(long, help = MODE_HELP, allow_hyphen_values = true, value_parser = parse_mode_option)]
    mode: Option<ModeOption>,
    #[command(flatten)]
    reading: ReadingArgs,
}

/// Prints the largest LCI (4 decimals) first, then its manipulator, mode and position.
pub fn max_lci(a: &MaxLciArgs) -> Result<(), CliError> {
    let robots = a.reading.robots();
    let which = index_of(a.robot);
    for choice in choices(a.mode, &robots[which])? {
        let found = max_lci_in(
            &robots,
            which,
            a.phi.to_radians(),
            a.workspace.into(),
            a.grid,
            choice,
        )
        .ok_or_else(|| format!("{} reaches no grid point at phi = {} deg", a.robot, a.phi))?;
        let attained = match choice {
            ModeChoice::Best => format!(", attained in mode {}", found.mode),
            ModeChoice::Only(_) => String::new(),
        };
        outln!(
            "{:.4}  ({}, {}{attained}; at x = {:.2} cm, y = {:.2} cm, phi = {} deg)",
            found.value,
            a.robot,
            mode_label(choice, a.robot),
            100.0 * found.pose.x,
            100.0 * found.pose.y,
            a.phi
        );
    }
    Ok(())
}

#[derive(Args)]
pub struct GciArgs {
    /// Manipulator: 1rrr, 2rrr or 3rrr.
    #[arg(long)]
    robot: RobotKind,
    /// Midpoint-rule cells along x and along y (over the reach square), 1 to 400.
    #[arg(long, default_value_t = 100, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<1, 400>)]
    cells: usize,
    /// Midpoint-rule cells along phi, 1 to 400.
    #[arg(long, default_value_t = 85, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<1, 400>)]
    phi_cells: usize,
    /// Lower end of the orientation range (deg).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    phi_min: f64,
    /// Upper end of the orientation range (deg).
    #[arg(long, default_value_t = 180.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    phi_max: f64,
    #[arg(long, help = MODE_HELP, allow_hyphen_values = true, value_parser = parse_mode_option)]
    mode: Option<ModeOption>,
    #[command(flatten)]
    reading: ReadingArgs,
}

impl GciArgs {
    fn grid(&self) -> Result<GciGrid, CliError> {
        if self.phi_max <= self.phi_min {
            return Err(crate::cli::report::usage(format!(
                "--phi-max {} deg must be greater than --phi-min {} deg",
                self.phi_max, self.phi_min
            )));
        }
        Ok(GciGrid {
            xy_cells: self.cells,
            phi_cells: self.phi_cells,
            phi_min: self.phi_min.to_radians(),
            phi_max: self.phi_max.to_radians(),
        })
    }
}

/// Prints the GCI (4 decimals) first, then its manipulator, mode and workspace volume.
pub fn gci(a: &GciArgs) -> Result<(), CliError> {
    let robot = a.reading.robots()[index_of(a.robot)];
    let grid = a.grid()?;
    for choice in choices(a.mode, &robot)? {
        let value = global_index(&robot, &grid, choice).ok_or("empty workspace")?;
        outln!(
            "{:.4}  ({}, {}; workspace volume {:.4} m^2 rad)",
            value.value,
            a.robot,
            mode_label(choice, a.robot),
            value.volume
        );
    }
    Ok(())
}

/// Prints the GCI on the grid divided by 8, 4, 2 and 1 per axis.
pub fn gci_convergence(a: &GciArgs) -> Result<(), CliError> {
    let robot = a.reading.robots()[index_of(a.robot)];
    let finest = a.grid()?;
    for choice in choices(a.mode, &robot)? {
        outln!(
            "# GCI of {} ({}) over phi in [{}, {}] deg, midpoint rule",
            a.robot,
            mode_label(choice, a.robot),
            a.phi_min,
            a.phi_max
        );
        outln!("xy_cells  phi_cells  gci      change   volume_m2rad");
        let mut previous: Option<f64> = None;
        for divisor in [8, 4, 2, 1] {
            let grid = GciGrid {
                xy_cells: (finest.xy_cells / divisor).max(1),
                phi_cells: (finest.phi_cells / divisor).max(1),
                ..finest
            };
            let g = global_index(&robot, &grid, choice).ok_or("empty workspace")?;
            let change = previous.map_or("-".to_string(), |p| format!("{:+.5}", g.value - p));
            outln!(
                "{:8}  {:9}  {:.5}  {:>8}  {:.5}",
                grid.xy_cells,
                grid.phi_cells,
                g.value,
                change,
                g.volume
            );
            previous = Some(g.value);
        }
    }
    Ok(())
}
