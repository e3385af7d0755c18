//! Files written for one solution: CSV tables and PNG figures (joint paths, cost over
//! time, Newton residuals, snapshots of the arms).

use crate::plot::{Axes, PlotError, Series, line_chart};
use plotters::prelude::*;
use robofmu_analyses::dual_arm::kinematics::{
    ARM_JOINTS, JOINTS, LinkLengths, Side, joint_name, joint_points,
};
use robofmu_analyses::dual_arm::paths::Path;
use robofmu_analyses::dual_arm::shooting::NewtonStep;
use robofmu_analyses::dual_arm::trajectory::Trajectory;
use std::fmt::Write as _;
use std::path::Path as FilePath;

/// An error while writing the output files.
#[derive(Debug)]
pub enum OutputError {
    Io(std::io::Error),
    Plot(PlotError),
}

impl std::fmt::Display for OutputError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Io(e) => write!(f, "writing output: {e}"),
            Self::Plot(e) => write!(f, "{e}"),
        }
    }
}

impl std::error::Error for OutputError {}

impl From<std::io::Error> for OutputError {
    fn from(e: std::io::Error) -> Self {
        Self::Io(e)
    }
}

impl From<PlotError> for OutputError {
    fn from(e: PlotError) -> Self {
        Self::Plot(e)
    }
}

/// CSV of the trajectory: t, the eight joints (rad), the path point (m), PI(t).
pub fn trajectory_csv(trajectory: &Trajectory, path: &dyn Path) -> String {
    let mut out = String::from("t_s");
    for j in 0..JOINTS {
        let _ = write!(out, ",{}_rad", joint_name(j));
    }
    out.push_str(",x_m,y_m,PI_rad2_per_s\n");
    for ((t, theta), cost) in trajectory
        .times
        .iter()
        .zip(&trajectory.joints)
        .zip(&trajectory.cost)
    {
        let r = path.position(*t);
        let _ = write!(out, "{t:.6}");
        for v in theta {
            let _ = write!(out, ",{v:.12}");
        }
        let _ = writeln!(out, ",{:.12},{:.12},{cost:.12}", r.x, r.y);
    }
    out
}

/// CSV of the Newton iterates: iteration, residual, the guess.
pub fn newton_csv(history: &[NewtonStep], redundant: &[usize]) -> String {
    let mut out = String::from("iteration,residual");
    for &j in redundant {
        let _ = write!(out, ",{}_final_rad", joint_name(j));
    }
    out.push('\n');
    for (i, step) in history.iter().enumerate() {
        let _ = write!(out, "{i},{:.6e}", step.residual);
        for v in &step.guess {
            let _ = write!(out, ",{v:.12}");
        }
        out.push('\n');
    }
    out
}

/// Line chart of the free joints (deg) over time.
pub fn joints_png(
    file: &FilePath,
    trajectory: &Trajectory,
    free: &[usize],
    title: &str,
) -> Result<(), OutputError> {
    let names: Vec<String> = free.iter().map(|&j| joint_name(j)).collect();
    let series: Vec<Series> = free
        .iter()
        .zip(&names)
        .map(|(&j, name)| Series {
            label: name,
            points: trajectory
                .times
                .iter()
                .zip(&trajectory.joints)
                .map(|(t, theta)| (*t, theta[j].to_degrees()))
                .collect(),
        })
        .collect();
    let axes = Axes {
        title,
        x_label: "t [s]",
        y_label: "angle theta [deg]",
    };
    Ok(line_chart(file, &axes, &series)?)
}

/// Line chart of the accumulated cost PI(t).
pub fn cost_png(file: &FilePath, trajectory: &Trajectory, title: &str) -> Result<(), OutputError> {
    let series = Series {
        label: "PI(t)",
        points: trajectory
            .times
            .iter()
            .copied()
            .zip(trajectory.cost.iter().copied())
            .collect(),
    };
    let axes = Axes {
        title,
        x_label: "t [s]",
        y_label: "integral of |theta_dot|^2 [rad^2/s]",
    };
    Ok(line_chart(file, &axes, &[series])?)
}

/// Line chart of log10 of the Newton residual per iteration.
pub fn newton_png(file: &FilePath, history: &[NewtonStep], title: &str) -> Result<(), OutputError> {
    let series = Series {
        label: "log10 ||e||",
        points: history
            .iter()
            .enumerate()
            .map(|(i, s)| (i as f64, s.residual.max(1e-300).log10()))
            .collect(),
    };
    let axes = Axes {
        title,
        x_label: "Newton iteration",
        y_label: "log10 of the start error ||e||",
    };
    Ok(line_chart(file, &axes, &[series])?)
}

/// Snapshots of both arms at `count` evenly spaced samples, with the path, to scale.
pub fn snapshots_png(
    file: &FilePath,
    trajectory: &Trajectory,
    lengths: &LinkLengths,
    path: &dyn Path,
    count: usize,
    title: &str,
) -> Result<(), OutputError> {
    let err = |e: &dyn std::fmt::Display| OutputError::Plot(PlotError(e.to_string()));
    let samples = trajectory.times.len();
    let picks: Vec<usize> = (0..count.max(2))
        .map(|i| i * (samples - 1) / (count.max(2) - 1))
        .collect();
    let arms: Vec<(Side, Vec<(f64, f64)>)> = picks
        .iter()
        .flat_map(|&k| {
            let theta = trajectory.joints[k];
            Side::BOTH.map(|side| {
                let o = side.offset();
                let arm: [f64; ARM_JOINTS] = [theta[o], theta[o + 1], theta[o + 2], theta[o + 3]];
                let points = joint_points(lengths.of(side), &arm);
                (side, points.iter().map(|p| (p.x, p.y)).collect())
            })
        })
        .collect();
    let curve: Vec<(f64, f64)> = trajectory
        .times
        .iter()
        .map(|t| {
            let r = path.position(*t);
            (r.x, r.y)
        })
        .collect();
    let all = arms.iter().flat_map(|(_, p)| p.iter()).chain(curve.iter());
    let (mut x0, mut x1, mut y0, mut y1) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for &(x, y) in all {
        (x0, x1, y0, y1) = (x0.min(x), x1.max(x), y0.min(y), y1.max(y));
    }
    // Equal scales on both axes: widen the narrower range to the figure's aspect.
    let (width, height) = (800u32, 800u32);
    let span = (x1 - x0).max(y1 - y0) * 1.1;
    let (cx, cy) = (0.5 * (x0 + x1), 0.5 * (y0 + y1));
    let root = BitMapBackend::new(file, (width, height)).into_drawing_area();
    root.fill(&WHITE).map_err(|e| err(&e))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 22))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .build_cartesian_2d(
            cx - span / 2.0..cx + span / 2.0,
            cy - span / 2.0..cy + span / 2.0,
        )
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc("x [m]")
        .y_desc("y [m]")
        .draw()
        .map_err(|e| err(&e))?;
    chart
        .draw_series(LineSeries::new(curve, BLACK.stroke_width(2)))
        .map_err(|e| err(&e))?
        .label("path")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    for (i, (side, points)) in arms.into_iter().enumerate() {
        let shade = 0.35 + 0.65 * (i / 2) as f64 / (picks.len().max(2) - 1) as f64;
        let color = match side {
            Side::Right => RGBColor(200, 40, 40).mix(shade),
            Side::Left => RGBColor(40, 80, 200).mix(shade),
        };
        let dots = points.clone();
        chart
            .draw_series(LineSeries::new(points, color.stroke_width(2)))
            .map_err(|e| err(&e))?;
        chart
            .draw_series(dots.into_iter().map(|p| Circle::new(p, 3, color.filled())))
            .map_err(|e| err(&e))?;
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))
}
