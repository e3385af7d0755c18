//! Subcommands that write maps over x, y at one orientation: LCI, load index and the
//! reachable and common workspaces (CSV and PNG).

use super::options::{ReadingArgs, check_mode, index_of, mode_label, mode_or_default, parse_mode};
use super::output::{cell, cm, file_in, write_csv};
use super::sweeps::peak_phi;
use crate::cli::CliError;
use crate::plot::{Axes, Grid, heat_map};
use clap::{Args, ValueEnum};
use robofmu_analyses::dexterity::workspace::{
    ModeChoice, XyGrid, common_map, lci_map, load_index_map, reachable_map,
};
use robofmu_analyses::dexterity::{Manipulator, Robot, RobotKind};
use std::path::{Path, PathBuf};

/// Square of positions a map covers.
#[derive(Clone, Copy, ValueEnum)]
pub enum Square {
    /// The paper's x, y in [-20, 20] cm.
    Paper,
    /// A square holding the manipulator's whole reachable workspace.
    Own,
}

#[derive(Args)]
pub struct MapArgs {
    /// Manipulator: 1rrr, 2rrr or 3rrr.
    #[arg(long)]
    robot: RobotKind,
    /// Orientation phi (deg).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    phi: f64,
    /// Square of positions mapped.
    #[arg(long, value_enum, default_value = "paper")]
    square: Square,
    /// Grid points per axis (2 to 501).
    #[arg(long, default_value_t = 81, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<2, 501>)]
    grid: usize,
    /// Output directory for the CSV and PNG files.
    #[arg(long, default_value = "dexterity-out")]
    out: PathBuf,
    #[command(flatten)]
    reading: ReadingArgs,
}

fn square_grid(robot: &Robot, square: Square, points: usize) -> XyGrid {
    match square {
        Square::Paper => XyGrid::paper(points),
        Square::Own => XyGrid::own(robot, points),
    }
}

/// One mapped quantity: CSV column and file-name suffix, plot title, values.
struct MapColumn {
    name: String,
    title: String,
    values: Vec<Option<f64>>,
}

/// Writes one CSV of x, y and one column per map, and one heat map per column.
fn write_maps(
    dir: &Path,
    stem: &str,
    grid: &XyGrid,
    columns: &[MapColumn],
    what: &str,
) -> Result<(), CliError> {
    let mut header = vec!["x_cm", "y_cm"];
    header.extend(columns.iter().map(|c| c.name.as_str()));
    let rows: Vec<Vec<String>> = (0..grid.len())
        .map(|i| {
            let (x, y) = grid.position(i);
            let mut row = vec![format!("{:.4}", cm(x)), format!("{:.4}", cm(y))];
            row.extend(columns.iter().map(|c| cell(c.values[i])));
            row
        })
        .collect();
    write_csv(&file_in(dir, &format!("{stem}.csv"))?, &header, &rows)?;
    let axis: Vec<f64> = grid.coordinates().into_iter().map(cm).collect();
    for MapColumn {
        name,
        title,
        values,
    } in columns
    {
        if values.iter().all(Option::is_none) {
            continue;
        }
        let axes = Axes {
            title,
            x_label: "x (cm)",
            y_label: "y (cm)",
        };
        let map = Grid {
            xs: axis.clone(),
            ys: axis.clone(),
            values: values.clone(),
        };
        heat_map(
            &file_in(dir, &format!("{stem}-{name}.png"))?,
            &axes,
            &map,
            what,
        )?;
    }
    Ok(())
}

/// LCI maps of every working mode and of the best over modes, each titled by its mode.
pub fn lci_maps(a: &MapArgs) -> Result<(), CliError> {
    let robot = a.reading.robots()[index_of(a.robot)];
    let grid = square_grid(&robot, a.square, a.grid);
    let phi = a.phi.to_radians();
    let column = |name: String, choice: ModeChoice| MapColumn {
        name,
        title: format!(
            "LCI of the {} at phi = {} deg, {}",
            a.robot,
            a.phi,
            mode_label(choice, a.robot)
        ),
        values: lci_map(&robot, phi, &grid, choice),
    };
    let mut columns: Vec<MapColumn> = (0..robot.working_modes())
        .map(|m| column(format!("mode{m}"), ModeChoice::Only(m)))
        .collect();
    columns.push(column("best".into(), ModeChoice::Best));
    let stem = format!("lci-{}-phi{}", a.robot, a.phi);
    write_maps(&a.out, &stem, &grid, &columns, "LCI")?;
    outln!("wrote {}/{stem}.csv and its PNG maps", a.out.display());
    Ok(())
}

#[derive(Args)]
pub struct LoadMapArgs {
    /// Manipulator: 1rrr, 2rrr or 3rrr.
    #[arg(long)]
    robot: RobotKind,
    /// Orientation phi (deg); default: where the largest LCI over the own workspace
    /// peaks (1 deg sweep from 10 to 180 deg on an 81-point grid).
    #[arg(long, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    phi: Option<f64>,
    /// Working mode: a mode index or `best` (largest over the modes at each pose);
    /// default: the fixed mode of docs/dexterity.md (1rrr 0, 2rrr 3, 3rrr 7).
    #[arg(long, allow_hyphen_values = true, value_parser = parse_mode)]
    mode: Option<ModeChoice>,
    /// Grid points per axis over the own workspace square (2 to 501).
    #[arg(long, default_value_t = 121, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<2, 501>)]
    grid: usize,
    /// Output directory for the CSV and PNG files.
    #[arg(long, default_value = "dexterity-out")]
    out: PathBuf,
    #[command(flatten)]
    reading: ReadingArgs,
}

/// Load-index map (1/m) at the requested or the peak-LCI orientation.
pub fn load_maps(a: &LoadMapArgs) -> Result<(), CliError> {
    let robots = a.reading.robots();
    let which = index_of(a.robot);
    let mode = mode_or_default(a.mode, a.robot);
    check_mode(&robots[which], mode)?;
    let phi_deg = match a.phi {
        Some(p) => p,
        None => peak_phi(&robots, which, mode, 81).ok_or("no reachable pose in the sweep")?,
    };
    let robot = robots[which];
    let grid = XyGrid::own(&robot, a.grid);
    let label = mode_label(mode, a.robot);
    let columns = [MapColumn {
        name: "load_index_per_m".into(),
        title: format!(
            "Load index (1/m) of the {} at phi = {phi_deg} deg, {label}",
            a.robot
        ),
        values: load_index_map(&robot, phi_deg.to_radians(), &grid, mode),
    }];
    let stem = format!("load-{}-phi{phi_deg}", a.robot);
    write_maps(&a.out, &stem, &grid, &columns, "load index (1/m)")?;
    outln!(
        "phi = {phi_deg} deg ({}, {label}); wrote {}/{stem}.csv and .png",
        a.robot,
        a.out.display()
    );
    Ok(())
}

#[derive(Args)]
pub struct WorkspaceArgs {
    /// Orientation phi (deg).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    phi: f64,
    /// Grid points per axis over a square holding every workspace (2 to 501).
    #[arg(long, default_value_t = 181, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<2, 501>)]
    grid: usize,
    /// Output directory for the CSV and PNG files.
    #[arg(long, default_value = "dexterity-out")]
    out: PathBuf,
    #[command(flatten)]
    reading: ReadingArgs,
}

/// Reachable workspaces and their intersection; prints their areas.
pub fn workspaces(a: &WorkspaceArgs) -> Result<(), CliError> {
    let robots = a.reading.robots();
    let half_width = robots.iter().map(|r| r.reach()).fold(0.0, f64::max);
    let grid = XyGrid {
        half_width,
        points: a.grid,
    };
    let phi = a.phi.to_radians();
    let mut maps: Vec<Vec<bool>> = robots
        .iter()
        .map(|r| reachable_map(r, phi, &grid))
        .collect();
    maps.push(common_map(&robots, phi, &grid));
    let cell_area = cm(grid.step()).powi(2);
    outln!(
        "# workspace areas at phi = {} deg ({} x {} grid), reachable in any working mode \
         (each mode of these manipulators reaches the same poses)",
        a.phi,
        a.grid,
        a.grid
    );
    let names: Vec<String> = RobotKind::ALL
        .iter()
        .map(|k| k.to_string())
        .chain(["common".into()])
        .collect();
    for (name, map) in names.iter().zip(&maps) {
        let area = map.iter().filter(|&&b| b).count() as f64 * cell_area;
        outln!("{name:7} {area:8.1} cm^2");
    }
    let stem = format!("workspace-phi{}", a.phi);
    let mut header = vec!["x_cm", "y_cm"];
    header.extend(names.iter().map(String::as_str));
    let rows: Vec<Vec<String>> = (0..grid.len())
        .map(|i| {
            let (x, y) = grid.position(i);
            let mut row = vec![format!("{:.4}", cm(x)), format!("{:.4}", cm(y))];
            row.extend(maps.iter().map(|m| u8::from(m[i]).to_string()));
            row
        })
        .collect();
    write_csv(&file_in(&a.out, &format!("{stem}.csv"))?, &header, &rows)?;
    let reaching: Vec<Option<f64>> = (0..grid.len())
        .map(|i| {
            let n = maps[..robots.len()].iter().filter(|m| m[i]).count();
            (n > 0).then_some(n as f64)
        })
        .collect();
    let axis: Vec<f64> = grid.coordinates().into_iter().map(cm).collect();
    let title = format!(
        "Manipulators reaching (x, y) at phi = {} deg, any mode (3: common)",
        a.phi
    );
    let axes = Axes {
        title: &title,
        x_label: "x (cm)",
        y_label: "y (cm)",
    };
    let map = Grid {
        xs: axis.clone(),
        ys: axis,
        values: reaching,
    };
    heat_map(
        &file_in(&a.out, &format!("{stem}.png"))?,
        &axes,
        &map,
        "count",
    )?;
    outln!("wrote {}/{stem}.csv and .png", a.out.display());
    Ok(())
}
