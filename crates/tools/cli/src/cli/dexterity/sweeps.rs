//! Subcommands over orientations and readings: the largest LCI versus phi, and the
//! largest LCI at one orientation for every reading of the parallel layouts.

use super::options::{ReadingArgs, check_mode, mode_label, mode_or_default, parse_mode};
use super::output::{cell, file_in, write_csv};
use crate::cli::CliError;
use crate::cli::bounds::show;
use crate::cli::report::usage;
use crate::plot::{Axes, Series, line_chart};
use clap::Args;
use robofmu_analyses::dexterity::layout::{ApexSide, BaseDirection, Origin, Reading};
use robofmu_analyses::dexterity::sweep::{Region, SweepRow, max_lci, phi_sweep as sweep};
use robofmu_analyses::dexterity::workspace::{ModeChoice, XyGrid};
use robofmu_analyses::dexterity::{Manipulator, Robot, RobotKind};
use std::path::PathBuf;
use std::time::Instant;

#[derive(Args)]
pub struct SweepArgs {
    /// First orientation (deg).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    from: f64,
    /// Last orientation (deg).
    #[arg(long, default_value_t = 180.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    to: f64,
    /// Orientation step (deg, > 0; orientations x grid points^2 at most 2e8).
    #[arg(long, default_value_t = 1.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::positive)]
    step: f64,
    /// Grid points per axis over each searched square (2 to 1001).
    #[arg(long, default_value_t = 161, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<2, 1001>)]
    grid: usize,
    /// Working mode of the 1-RRR: a mode index (0, 1) or `best`; default 0.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_mode)]
    mode_1rrr: Option<ModeChoice>,
    /// Working mode of the 2-RRR: a mode index (0 to 3) or `best`; default 3.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_mode)]
    mode_2rrr: Option<ModeChoice>,
    /// Working mode of the 3-RRR: a mode index (0 to 7) or `best`; default 7.
    #[arg(long, allow_hyphen_values = true, value_parser = parse_mode)]
    mode_3rrr: Option<ModeChoice>,
    /// Output directory for the CSV and PNG files.
    #[arg(long, default_value = "dexterity-out")]
    out: PathBuf,
    #[command(flatten)]
    reading: ReadingArgs,
}

impl SweepArgs {
    /// The working mode of each manipulator, in the order of `RobotKind::ALL`.
    fn choices(&self) -> [ModeChoice; 3] {
        let given = [self.mode_1rrr, self.mode_2rrr, self.mode_3rrr];
        std::array::from_fn(|k| mode_or_default(given[k], RobotKind::ALL[k]))
    }

    /// The manipulators' working modes, for the terminal and the plot titles.
    fn modes_label(&self) -> String {
        RobotKind::ALL
            .iter()
            .zip(self.choices())
            .map(|(&kind, choice)| format!("{kind} {}", mode_label(choice, kind)))
            .collect::<Vec<_>>()
            .join(", ")
    }
}

/// Orientations from `from` to `to` (deg, inclusive) every `step`.
fn orientations(from: f64, to: f64, step: f64) -> Vec<f64> {
    let count = ((to - from) / step + 1e-9).floor() as usize + 1;
    (0..count).map(|i| from + i as f64 * step).collect()
}

/// Value of robot `k` in a sweep row.
fn value(row: &SweepRow, k: usize) -> Option<f64> {
    row.max[k].map(|m| m.value)
}

/// Orientation (deg) where the largest LCI of `robots[which]` in the working modes of
/// `choice` over its own workspace peaks, on a 1 deg sweep from 10 to 180 deg with
/// `points` per grid axis.
pub fn peak_phi(robots: &[Robot], which: usize, choice: ModeChoice, points: usize) -> Option<f64> {
    let degrees = orientations(10.0, 180.0, 1.0);
    let phis: Vec<f64> = degrees.iter().map(|d| d.to_radians()).collect();
    let rows = sweep(
        &robots[which..=which],
        &[choice],
        &phis,
        Region::Own,
        points,
    );
    rows.iter()
        .zip(&degrees)
        .filter_map(|(row, &d)| Some((value(row, 0)?, d)))
        .max_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, d)| d)
}

/// Largest LCI versus phi over the own and the common workspace, timed.
pub fn phi_sweep(a: &SweepArgs) -> Result<(), CliError> {
    check_sweep_size(a)?;
    let robots = a.reading.robots();
    let choices = a.choices();
    for (robot, &choice) in robots.iter().zip(&choices) {
        check_mode(robot, choice).map_err(|e| usage(format!("{e} (--mode-{})", robot.kind())))?;
    }
    outln!("# working modes: {}", a.modes_label());
    let degrees = orientations(a.from, a.to, a.step);
    let phis: Vec<f64> = degrees.iter().map(|d| d.to_radians()).collect();
    let mut header = vec!["phi_deg".to_string()];
    let mut columns: Vec<Vec<SweepRow>> = Vec::new();
    for (region, name) in [(Region::Own, "own"), (Region::Common, "common")] {
        let start = Instant::now();
        let rows = sweep(&robots, &choices, &phis, region, a.grid);
        outln!(
            "# {name} workspace: {} orientations x {} x {} grid in {:.2} s",
            phis.len(),
            a.grid,
            a.grid,
            start.elapsed().as_secs_f64()
        );
        for (k, kind) in RobotKind::ALL.iter().enumerate() {
            header.push(format!("{name}_{kind}"));
            let peak = rows
                .iter()
                .filter_map(|r| Some((value(r, k)?, r.phi.to_degrees())))
                .max_by(|x, y| x.0.total_cmp(&y.0));
            if let Some((v, d)) = peak {
                let mode = mode_label(choices[k], *kind);
                outln!("{name:6} {kind} ({mode}): largest LCI {v:.4} at phi = {d:.1} deg");
            }
        }
        summarise_leaders(&rows, name);
        plot_sweep(a, &rows, name)?;
        columns.push(rows);
    }
    let rows: Vec<Vec<String>> = (0..phis.len())
        .map(|i| {
            let mut row = vec![format!("{:.3}", degrees[i])];
            for c in &columns {
                row.extend((0..robots.len()).map(|k| cell(value(&c[i], k))));
            }
            row
        })
        .collect();
    let header: Vec<&str> = header.iter().map(String::as_str).collect();
    write_csv(&file_in(&a.out, "phi-sweep.csv")?, &header, &rows)?;
    outln!(
        "wrote {}/phi-sweep.csv and phi-sweep-{{own,common}}.png",
        a.out.display()
    );
    Ok(())
}

/// Most grid evaluations of one phi sweep (orientations x grid points per region;
/// the default 171 x 161^2 is 4.4e6).
const MAX_SWEEP_POINTS: f64 = 2e8;

/// Refuses an empty or reversed range and a sweep beyond [`MAX_SWEEP_POINTS`].
fn check_sweep_size(a: &SweepArgs) -> Result<(), CliError> {
    if a.to < a.from {
        return Err(usage(format!(
            "--to {} deg is below --from {} deg; give --to >= --from",
            a.to, a.from
        )));
    }
    let points = ((a.to - a.from) / a.step + 1.0) * (a.grid as f64).powi(2);
    if points > MAX_SWEEP_POINTS {
        return Err(usage(format!(
            "--from {} --to {} --step {} deg on a --grid {} is {points:.2e} grid points; \
             at most {MAX_SWEEP_POINTS:e} (raise --step or lower --grid)",
            show(a.from),
            show(a.to),
            show(a.step),
            a.grid
        )));
    }
    Ok(())
}

/// Prints which manipulator has the largest LCI below and above 90 deg, and how often.
fn summarise_leaders(rows: &[SweepRow], name: &str) {
    for (label, below) in [("phi < 90 deg", true), ("phi > 90 deg", false)] {
        let mut wins = [0usize; 3];
        for row in rows.iter().filter(|r| {
            let d = r.phi.to_degrees();
            if below { d < 90.0 } else { d > 90.0 }
        }) {
            let leader = (0..3)
                .filter_map(|k| Some((value(row, k)?, k)))
                .max_by(|x, y| x.0.total_cmp(&y.0));
            if let Some((_, k)) = leader {
                wins[k] += 1;
            }
        }
        outln!(
            "{name:6} {label}: orientations led by 1rrr {}, 2rrr {}, 3rrr {}",
            wins[0],
            wins[1],
            wins[2]
        );
    }
}

fn plot_sweep(a: &SweepArgs, rows: &[SweepRow], name: &str) -> Result<(), CliError> {
    let labels: Vec<String> = RobotKind::ALL
        .iter()
        .zip(a.choices())
        .map(|(&kind, choice)| format!("{kind}, {}", mode_label(choice, kind)))
        .collect();
    let series: Vec<Series> = labels
        .iter()
        .enumerate()
        .map(|(k, label)| Series {
            label,
            points: rows
                .iter()
                .filter_map(|r| Some((r.phi.to_degrees(), value(r, k)?)))
                .collect(),
        })
        .collect();
    let title = format!(
        "Largest LCI, {name} workspace, modes as labelled ({} x {} grid)",
        a.grid, a.grid
    );
    let axes = Axes {
        title: &title,
        x_label: "phi (deg)",
        y_label: "largest LCI",
    };
    line_chart(
        &file_in(&a.out, &format!("phi-sweep-{name}.png"))?,
        &axes,
        &series,
    )?;
    Ok(())
}

#[derive(Args)]
pub struct ReadingsArgs {
    /// Orientation phi (deg).
    #[arg(long, default_value_t = 10.0, allow_hyphen_values = true, value_parser = crate::cli::bounds::finite)]
    phi: f64,
    /// Grid points per axis over the paper's square (2 to 1001).
    #[arg(long, default_value_t = 161, allow_hyphen_values = true, value_parser = crate::cli::bounds::count::<2, 1001>)]
    grid: usize,
}

/// Every reading of the parallel layouts (the 2-RRR has no O3, so no base apex).
fn all_readings(kind: RobotKind) -> Vec<Reading> {
    let sides = [ApexSide::Left, ApexSide::Right];
    let origins = [Origin::FirstVertex, Origin::Centroid];
    let base_apexes: &[ApexSide] = match kind {
        RobotKind::Parallel3Rrr => &sides,
        _ => &sides[..1],
    };
    let mut readings = Vec::new();
    for base_direction in [BaseDirection::PlusX, BaseDirection::MinusX] {
        for &base_origin in &origins {
            for &base_apex in base_apexes {
                for &platform_apex in &sides {
                    for &frame in &origins {
                        readings.push(Reading {
                            base_origin,
                            base_direction,
                            base_apex,
                            platform_apex,
                            frame,
                        });
                    }
                }
            }
        }
    }
    readings
}

/// Table of the largest LCI per working mode and overall for every reading.
pub fn readings(a: &ReadingsArgs) -> Result<(), CliError> {
    let phi = a.phi.to_radians();
    let grid = XyGrid::paper(a.grid);
    outln!(
        "# largest LCI at phi = {} deg over x, y in [-20, 20] cm, {} x {} grid",
        a.phi,
        a.grid,
        a.grid
    );
    for kind in [RobotKind::Parallel2Rrr, RobotKind::Parallel3Rrr] {
        for reading in all_readings(kind) {
            let robot = Robot::with_reading(kind, reading);
            let per_mode: Vec<String> = (0..robot.working_modes())
                .map(|m| {
                    cell(
                        max_lci(&robot, phi, &grid, ModeChoice::Only(m), |_: usize| true)
                            .map(|v| v.value),
                    )
                })
                .collect();
            let best =
                max_lci(&robot, phi, &grid, ModeChoice::Best, |_: usize| true).map(|v| v.value);
            outln!(
                "{kind} base {:?} {:?} base-apex {:?} platform-apex {:?} frame {:?}: modes [{}] best over modes {}",
                reading.base_direction,
                reading.base_origin,
                reading.base_apex,
                reading.platform_apex,
                reading.frame,
                per_mode.join(" "),
                cell(best)
            );
        }
    }
    Ok(())
}
